// Mode `refine` on the GPU: the proof of one block from distance samples around it, with
// per-cell slope bounds. Mirrors the distance proof of src/render2d/twin/refine.rs (the
// Lipschitz cones; the event signs are refine_signs.wgsl's; the GPU does not read material
// margins, so it proves a subset of what the twin proves and evaluates the rest). Needs
// common.wgsl and refine_common.wgsl; the including module binds `proof`, the array of
// `CellProof`s (one per grid cell, then one for every point outside the grid). `CellProof`
// mirrors `GpuCellProof` in src/render2d/gpu/uniforms.rs.

struct CellProof {
    // Slope bound of the field over the cell; `known` = 0 when there is none.
    lipschitz: f32,
    // Jump allowance at the cell's borders (brick interpolation error).
    error: f32,
    // The cell's constant material, or MATERIAL_NONE.
    material: u32,
    known: u32,
    // Bounds of the cell's starting state over the cell (before its events).
    start: vec2<f32>,
    pad: vec2<u32>,
}

// Most cells one proof reads; a wider span proves nothing.
const MAX_SPAN_CELLS: i32 = 64;

// No bound (the proof then fails).
const UNBOUNDED: f32 = 1.0e30;

fn sky_at() -> f32 {
    return 0.5 * frame.upp;
}

fn solid_at() -> f32 {
    return -(max(frame.outline_px, 0.0) + 0.5) * frame.upp;
}

// Deeper than this every solid pixel of a material and row has one colour (the twin's
// `Shader::interior_depth`).
fn deep_at() -> f32 {
    let exact = max(max(frame.shade_depth_px, frame.outline_px + 0.5), 0.5);
    return -(exact * (1.0 + 1.0e-6) + 1.0e-3) * frame.upp;
}

// The cells a world rectangle touches, padded so that the f32 cell lookup of any point in
// it lands inside: (ix0, iy0, ix1, iy1), clamped to one cell past the grid each way.
fn cell_span(lo: vec2<f32>, hi: vec2<f32>) -> vec4<i32> {
    let pad = 1.0e-2 + 1.0e-6 * max(max(abs(lo.x), abs(lo.y)), max(abs(hi.x), abs(hi.y)));
    let a = floor((lo - vec2<f32>(pad) - frame.grid_origin) / frame.cell_size);
    let b = floor((hi + vec2<f32>(pad) - frame.grid_origin) / frame.cell_size);
    let dims = vec2<f32>(frame.grid_dims);
    let a2 = clamp(a, vec2<f32>(-1.0), dims);
    let b2 = clamp(b, vec2<f32>(-1.0), dims);
    return vec4<i32>(i32(a2.x), i32(a2.y), i32(b2.x), i32(b2.y));
}

fn cell_proof(ix: i32, iy: i32) -> CellProof {
    let dims = vec2<i32>(frame.grid_dims);
    if ix < 0 || iy < 0 || ix >= dims.x || iy >= dims.y {
        return proof[frame.grid_dims.x * frame.grid_dims.y];
    }
    return proof[u32(iy) * frame.grid_dims.x + u32(ix)];
}

fn span_cells(s: vec4<i32>) -> i32 {
    return (s.z - s.x + 1) * (s.w - s.y + 1);
}

// (slope bound, border-jump allowance) over the cells of a span, UNBOUNDED when any is
// unknown or the span is too wide.
fn span_bounds(s: vec4<i32>) -> vec2<f32> {
    if span_cells(s) > MAX_SPAN_CELLS {
        return vec2<f32>(UNBOUNDED, UNBOUNDED);
    }
    var lipschitz = 0.0;
    var error = 0.0;
    for (var iy = s.y; iy <= s.w; iy++) {
        for (var ix = s.x; ix <= s.z; ix++) {
            let c = cell_proof(ix, iy);
            if c.known == 0u {
                return vec2<f32>(UNBOUNDED, UNBOUNDED);
            }
            lipschitz = max(lipschitz, c.lipschitz);
            error = max(error, c.error);
        }
    }
    let borders = f32((s.z - s.x) + (s.w - s.y));
    return vec2<f32>(lipschitz, 2.0 * error * borders);
}

// The material every pixel of the rectangle provably has: one material, MATERIAL_PER_CELL
// (every cell it touches is constant), or MATERIAL_NONE.
fn span_material(s: vec4<i32>) -> u32 {
    let dims = vec2<i32>(frame.grid_dims);
    if s.x < 0 || s.y < 0 || s.z >= dims.x || s.w >= dims.y || span_cells(s) > MAX_SPAN_CELLS {
        return MATERIAL_NONE;
    }
    var first = MATERIAL_NONE;
    var same = true;
    for (var iy = s.y; iy <= s.w; iy++) {
        for (var ix = s.x; ix <= s.z; ix++) {
            let m = cell_proof(ix, iy).material;
            if m == MATERIAL_NONE {
                return MATERIAL_NONE;
            }
            if first == MATERIAL_NONE {
                first = m;
            }
            same = same && m == first;
        }
    }
    return select(MATERIAL_PER_CELL, first, same);
}

// A block's class from the bounds lo <= d <= hi over its pixel rectangle, what its events
// force (`signs`, SIGN_* bits) and the material proof: sky, deep solid, shaded solid (at
// the final level only: it is drawn from the corner samples) or not proven (NEED before the
// final level, EXACT at it).
fn decide(lo: f32, hi: f32, signs: u32, rect: vec4<f32>, final_level: bool) -> BlockState {
    if lo >= sky_at() || (signs & SIGN_ABOVE) != 0u {
        return BlockState(CLASS_SKY, 0u, max(lo, sky_at()), hi, signs);
    }
    var top = hi;
    if (signs & SIGN_BELOW_DEEP) != 0u {
        top = min(top, deep_at());
    } else if (signs & SIGN_BELOW_SOLID) != 0u {
        top = min(top, solid_at());
    }
    if top <= solid_at() {
        let material = span_material(cell_span(rect.xy, rect.zw));
        if material != MATERIAL_NONE {
            if top <= deep_at() {
                return BlockState(CLASS_DEEP, material, lo, top, signs);
            }
            if final_level {
                return BlockState(CLASS_SHADED, material, lo, top, signs);
            }
        }
    }
    let open = select(CLASS_NEED, CLASS_EXACT, final_level);
    return BlockState(open, MATERIAL_NONE, lo, top, signs);
}

// The material of pixel p of a block proven with `material`.
fn pixel_material(material: u32, p: vec2<f32>) -> u32 {
    if material != MATERIAL_PER_CELL {
        return material;
    }
    let f = (p - frame.grid_origin) / frame.cell_size;
    let dims = vec2<f32>(frame.grid_dims);
    if !(f.x >= 0.0 && f.x < dims.x && f.y >= 0.0 && f.y < dims.y) {
        return MATERIAL_NONE;
    }
    let ix = min(u32(f.x), frame.grid_dims.x - 1u);
    let iy = min(u32(f.y), frame.grid_dims.y - 1u);
    return proof[iy * frame.grid_dims.x + ix].material;
}

// Pixel range (x0, y0, x1, y1), inclusive, of block b.
fn block_pixels(b: vec2<u32>) -> vec4<u32> {
    let last = frame.image - vec2<u32>(1u);
    let a = b * BLOCK;
    let z = min(a + vec2<u32>(BLOCK - 1u), last);
    return vec4<u32>(a, z);
}

// World rectangle (min.xy, max.xy) of a block's pixel centres.
fn block_rect(px: vec4<u32>) -> vec4<f32> {
    let a = pixel_to_world(vec2<f32>(f32(px.x), f32(px.y)));
    let z = pixel_to_world(vec2<f32>(f32(px.z), f32(px.w)));
    return vec4<f32>(a.x, z.y, z.x, a.y);
}

// Largest distance from c to the rectangle (a corner).
fn farthest(c: vec2<f32>, r: vec4<f32>) -> f32 {
    let dx = max(abs(c.x - r.x), abs(c.x - r.z));
    let dy = max(abs(c.y - r.y), abs(c.y - r.w));
    return sqrt(dx * dx + dy * dy);
}

// How far the field can move between sample point c (value d) and the rectangle r:
// the cone, the border jumps, and the sample's own rounding (`rel` of |d|, an f16 texel
// or an f32 evaluation) and evaluation slack.
fn reach(c: vec2<f32>, d: f32, r: vec4<f32>, bounds: vec2<f32>, rel: f32) -> f32 {
    return bounds.x * farthest(c, r) * (1.0 + 1.0e-5) + bounds.y + abs(d) * rel
        + frame.upp / 1000.0;
}
