// Mode `refine` on the GPU, the two distance-bound classification levels
// (docs/render2d-pipeline.md, "Refine on the GPU"). Needs common.wgsl, refine_common.wgsl
// and refine_proof.wgsl. Level 0 (`cs_classify`) bounds each block from the pass-1 texels
// around it; the event signs (`cs_signs`, refine_signs.wgsl) try the blocks it left open;
// `cs_open` lists the blocks still open with the corners each samples and `cs_corner_args`
// sizes the corner pass over that list; level 1 (`cs_blocks`) bounds the open blocks from
// the exact samples at their four corners (written by `cs_corners`, refine_corners.wgsl)
// and their signs, appends the blocks it cannot prove, and the shaded ones whose corners are
// creased (`creased`), to the list the exact pass evaluates, and counts every block once;
// `cs_args` sizes the exact pass's dispatch.

@group(0) @binding(1) var texels: texture_2d<f32>;
@group(0) @binding(2) var<storage, read> proof: array<CellProof>;
@group(0) @binding(3) var<storage, read_write> blocks: array<BlockState>;
@group(0) @binding(4) var<storage, read> corners: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> work: Work;
@group(0) @binding(6) var<storage, read_write> exact_list: array<u32>;

// Most texels per axis level 0 reads around one block.
const MAX_TEXELS: i32 = 4;

// The counts of one `cs_blocks` workgroup, added to `work.counters` once per workgroup: one
// global atomic per block and counter would make every invocation wait on the same words.
var<workgroup> tally: array<atomic<u32>, COUNTERS_PER_BLOCK>;

fn count_final(kind: u32) {
    atomicAdd(&tally[COUNT_BLOCKS], 1u);
    switch kind {
        case CLASS_SKY: {
            atomicAdd(&tally[COUNT_SKY], 1u);
        }
        case CLASS_DEEP, CLASS_SHADED: {
            atomicAdd(&tally[COUNT_SOLID], 1u);
        }
        default: {}
    }
}

@compute @workgroup_size(8, 8)
fn cs_classify(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = block_dims();
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let rect = block_rect(block_pixels(id.xy));
    // Texels of every quad the block touches: columns grow with x, rows with -y.
    let la = to_lattice(vec2<f32>(rect.x, rect.w));
    let lz = to_lattice(vec2<f32>(rect.z, rect.y));
    let c0 = i32(floor(la.x));
    let r0 = i32(floor(la.y));
    let c1 = min(i32(floor(lz.x)) + 1, c0 + MAX_TEXELS - 1);
    let r1 = min(i32(floor(lz.y)) + 1, r0 + MAX_TEXELS - 1);
    // Every segment from a texel to the block lies in the box of both.
    let ta = texel_center(clamp_texel(vec2<i32>(c0, r0)).x, clamp_texel(vec2<i32>(c0, r0)).y);
    let tz = texel_center(clamp_texel(vec2<i32>(c1, r1)).x, clamp_texel(vec2<i32>(c1, r1)).y);
    let box_lo = min(min(rect.xy, vec2<f32>(ta.x, tz.y)), vec2<f32>(tz.x, ta.y));
    let box_hi = max(max(rect.zw, vec2<f32>(tz.x, ta.y)), vec2<f32>(ta.x, tz.y));
    let bounds = span_bounds(cell_span(box_lo, box_hi));
    var lo = -UNBOUNDED;
    var hi = UNBOUNDED;
    if bounds.x < UNBOUNDED {
        for (var r = r0; r <= r1; r++) {
            for (var c = c0; c <= c1; c++) {
                let t = clamp_texel(vec2<i32>(c, r));
                let d = textureLoad(texels, t, 0).x;
                // f16 keeps 11 bits: |d| / 1024 covers its rounding twice over.
                let k = reach(texel_center(t.x, t.y), d, rect, bounds, 1.0 / 1024.0);
                lo = max(lo, d - k);
                hi = min(hi, d + k);
            }
        }
    }
    blocks[id.y * dims.x + id.x] = decide(lo, hi, 0u, rect, false);
}

@compute @workgroup_size(8, 8)
fn cs_blocks(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    if lane < COUNTERS_PER_BLOCK {
        atomicStore(&tally[lane], 0u);
    }
    workgroupBarrier();
    let dims = block_dims();
    if id.x < dims.x && id.y < dims.y {
        finish_block(id.xy, dims);
    }
    workgroupBarrier();
    if lane < COUNTERS_PER_BLOCK {
        let n = atomicLoad(&tally[lane]);
        if n > 0u {
            atomicAdd(&work.counters[lane], n);
        }
    }
}

// Level 1 of one block (see the module comment), counted into `tally`.
fn finish_block(id: vec2<u32>, dims: vec2<u32>) {
    let index = id.y * dims.x + id.x;
    let open = blocks[index];
    if open.kind != CLASS_NEED {
        count_final(open.kind);
        return;
    }
    let px = block_pixels(id.xy);
    let rect = block_rect(px);
    let far_corner = pixel_to_world(vec2<f32>(f32((id.x + 1u) * BLOCK), f32((id.y + 1u) * BLOCK)));
    let box_lo = vec2<f32>(rect.x, far_corner.y);
    let box_hi = vec2<f32>(far_corner.x, rect.w);
    let bounds = span_bounds(cell_span(box_lo, box_hi));
    var lo = open.lo;
    var hi = open.hi;
    if bounds.x < UNBOUNDED {
        for (var k = 0u; k < 4u; k++) {
            let i = id.x + (k & 1u);
            let j = id.y + (k >> 1u);
            let at = pixel_to_world(vec2<f32>(f32(i * BLOCK), f32(j * BLOCK)));
            let d = corners[corner_index(i, j)].x;
            let r = reach(at, d, rect, bounds, 1.0e-5);
            lo = max(lo, d - r);
            hi = min(hi, d + r);
        }
    }
    var state = decide(lo, hi, open.signs, rect, true);
    // Where the shade has a hard edge the draw's interpolant would smear it over the block.
    if state.kind == CLASS_SHADED
        && creased(
            corners[corner_index(id.x, id.y)],
            corners[corner_index(id.x + 1u, id.y)],
            corners[corner_index(id.x, id.y + 1u)],
            corners[corner_index(id.x + 1u, id.y + 1u)],
        ) {
        state = BlockState(CLASS_EXACT, MATERIAL_NONE, state.lo, state.hi, state.signs);
    }
    if state.kind == CLASS_EXACT {
        let slot = atomicAdd(&work.exact_blocks, 1u);
        exact_list[slot] = index;
        // The draw finds the block's exact colours by its list slot.
        state.material = slot;
        atomicAdd(&tally[COUNT_EXACT_BLOCKS], 1u);
        let pixels = (px.z - px.x + 1u) * (px.w - px.y + 1u);
        atomicAdd(&tally[COUNT_EXACT_PIXELS], pixels);
    }
    blocks[index] = state;
    count_final(state.kind);
}

// The largest difference between the unit normals at the corners of a shaded block
// (about 23 degrees; the twin's `CREASE`).
const CREASE: f32 = 0.4;

fn unit_or_zero(g: vec2<f32>) -> vec2<f32> {
    return select(vec2<f32>(0.0), normalize(g), dot(g, g) > 0.0);
}

// Whether a block with the exact corner samples a..d (distance, gradient) must be evaluated
// rather than drawn from their interpolant (the twin's `Prover::creased`): some corner lies
// in the lit rim and two corners' normals (zero where the gradient is) differ by more than
// CREASE, as at the contour where the distance reaches its clamp -M (the gradient is zero
// past it) and along creases where the nearest surface changes.
fn creased(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>) -> bool {
    let lit_at = -0.5 * frame.shade_depth_px * frame.upp;
    if max(max(a.x, b.x), max(c.x, d.x)) <= lit_at {
        return false;
    }
    let na = unit_or_zero(a.yz);
    let nb = unit_or_zero(b.yz);
    let nc = unit_or_zero(c.yz);
    let nd = unit_or_zero(d.yz);
    let m = CREASE * CREASE;
    let e = na - nb;
    let f = na - nc;
    let g = na - nd;
    let h = nb - nc;
    let i = nb - nd;
    let j = nc - nd;
    return dot(e, e) > m || dot(f, f) > m || dot(g, g) > m || dot(h, h) > m || dot(i, i) > m
        || dot(j, j) > m;
}

// The exact pass's workgroup counts, as a 2D grid when one dimension cannot hold them.
@compute @workgroup_size(1)
fn cs_args() {
    work.dispatch = group_grid(atomicLoad(&work.exact_blocks), EXACT_BLOCKS_PER_GROUP);
}

fn is_open(bx: i32, by: i32, dims: vec2<u32>) -> bool {
    if bx < 0 || by < 0 || bx >= i32(dims.x) || by >= i32(dims.y) {
        return false;
    }
    return blocks[u32(by) * dims.x + u32(bx)].kind == CLASS_NEED;
}

// The corners block (x, y) samples for level 1: a corner goes to the first open block of
// its four in the order (i, j), (i - 1, j), (i, j - 1), (i - 1, j - 1), so each is sampled
// once.
fn owned_corners(x: i32, y: i32, dims: vec2<u32>) -> u32 {
    let right = is_open(x + 1, y, dims);
    let below = is_open(x, y + 1, dims) || is_open(x - 1, y + 1, dims);
    let diagonal = is_open(x + 1, y + 1, dims) || is_open(x, y + 1, dims) || right;
    return 1u | select(2u, 0u, right) | select(4u, 0u, below) | select(8u, 0u, diagonal);
}

// Lists the blocks left open after the event signs, with the corners each samples, so that
// `cs_corners` evaluates the field only where level 1 needs it, every invocation busy.
@compute @workgroup_size(8, 8)
fn cs_open(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = block_dims();
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let index = id.y * dims.x + id.x;
    if blocks[index].kind != CLASS_NEED {
        return;
    }
    let mask = owned_corners(i32(id.x), i32(id.y), dims);
    let slot = atomicAdd(&work.open_blocks, 1u);
    exact_list[slot + 1u] = index | (mask << OPEN_INDEX_BITS);
    atomicAdd(&work.counters[COUNT_CORNERS], countOneBits(mask));
}

// The corner pass's workgroup counts; the list's count goes to its word 0.
@compute @workgroup_size(1)
fn cs_corner_args() {
    let open = atomicLoad(&work.open_blocks);
    work.corner_dispatch = group_grid(open, OPEN_BLOCKS_PER_GROUP);
    exact_list[0] = open;
}
