// The destructible terrain on the GPU: the emitted base field (`base_sample`, see src/emit/)
// clamped to the band, the explosion grid's cell states and bricks, and the cell's events
// applied in order. Mirrors `Terrain::eval_cell` (src/field2d/terrain/mod.rs) on dual numbers
// vec3(value, d/dx, d/dy). `GpuEvent` and `GpuCell` mirror src/render2d/gpu/uniforms.rs.

struct GpuEvent {
    center: vec2<f32>,
    radius: f32,
    rim: f32,
    tick: u32,
    grow: u32,
    kind: u32,
    material: u32,
}

struct GpuCell {
    state: u32,
    payload: u32,
    start: u32,
    len: u32,
}

const CELL_BASE: u32 = 0u;
const CELL_AIR_BASE: u32 = 1u;
const CELL_AIR_CONSTANT: u32 = 2u;
const CELL_AIR_BRICK: u32 = 3u;
const CELL_SOLID: u32 = 4u;
const CELL_BRICK: u32 = 5u;
const EVENT_FILL: u32 = 1u;

@group(0) @binding(1) var<storage, read> events: array<GpuEvent>;
@group(0) @binding(2) var<storage, read> cells: array<GpuCell>;
@group(0) @binding(3) var<storage, read> lists: array<u32>;
// Brick `id` occupies words `2 id w .. 2 (id + 1) w` (w = (n + 1)^2): its values as f32 bits,
// then its materials. One buffer, so the pass stays within 4 storage buffers (downlevel).
@group(0) @binding(4) var<storage, read> bricks: array<u32>;

// The project's min/max: the first operand unless the second is strictly better.
fn dmin(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a.x < b.x);
}

fn dmax(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a.x > b.x);
}

fn dclamp(v: vec3<f32>, band: f32) -> vec3<f32> {
    return dmin(dmax(v, vec3<f32>(-band, 0.0, 0.0)), vec3<f32>(band, 0.0, 0.0));
}

fn dsmin(a: vec3<f32>, b: vec3<f32>, k: f32) -> vec3<f32> {
    let m = dmin(a, b);
    let diff = a - b;
    let ad = select(diff, -diff, diff.x < 0.0);
    let hk = dmax(vec3<f32>(k, 0.0, 0.0) - ad, vec3<f32>(0.0));
    let h = hk / k;
    if h.x > 0.0 {
        // (h*h) * k * 0.25 with the dual product rule.
        let hh = vec3<f32>(h.x * h.x, 2.0 * h.x * h.yz);
        return m - hh * k * 0.25;
    }
    return m;
}

// The smooth maximum is the smooth minimum of the negated operands, negated (the same
// selects, the same blend term).
fn dsmax(a: vec3<f32>, b: vec3<f32>, k: f32) -> vec3<f32> {
    return -dsmin(-a, -b, k);
}

// The base field clamped to the band, with its material.
fn base_clamped(p: vec2<f32>) -> vec4<f32> {
    let b = base_sample(p);
    let d = dclamp(b.xyz, frame.band);
    return vec4<f32>(d, b.w);
}

// Cell index of p, or -1 outside the grid (Grid::cell_index).
fn cell_of(p: vec2<f32>) -> i32 {
    let f = (p - frame.grid_origin) / frame.cell_size;
    let dims = vec2<f32>(frame.grid_dims);
    if !(f.x >= 0.0 && f.x < dims.x && f.y >= 0.0 && f.y < dims.y) {
        return -1;
    }
    let ix = min(u32(f.x), frame.grid_dims.x - 1u);
    let iy = min(u32(f.y), frame.grid_dims.y - 1u);
    return i32(iy * frame.grid_dims.x + ix);
}

fn cell_min(cell: u32) -> vec2<f32> {
    let ix = cell % frame.grid_dims.x;
    let iy = cell / frame.grid_dims.x;
    return frame.grid_origin + vec2<f32>(f32(ix), f32(iy)) * frame.cell_size;
}

// Bilinear interpolation of a brick with the interpolant's gradient, and the material of the
// nearest lattice sample (Grid::interpolate).
fn brick_sample(id: u32, cell: u32, p: vec2<f32>) -> vec4<f32> {
    let n = frame.brick_res;
    let nf = f32(n);
    let h = frame.brick_spacing;
    let m = cell_min(cell);
    let raw = (p - m) / h;
    let uv = clamp(raw, vec2<f32>(0.0), vec2<f32>(nf));
    let du = select(0.0, 1.0 / h, raw.x > 0.0 && raw.x < nf);
    let dv = select(0.0, 1.0 / h, raw.y > 0.0 && raw.y < nf);
    let i = min(u32(uv.x), n - 1u);
    let j = min(u32(uv.y), n - 1u);
    let f = uv - vec2<f32>(f32(i), f32(j));
    let row = n + 1u;
    let words = row * row;
    let base = id * 2u * words;
    let v00 = bitcast<f32>(bricks[base + j * row + i]);
    let v10 = bitcast<f32>(bricks[base + j * row + i + 1u]);
    let v01 = bitcast<f32>(bricks[base + (j + 1u) * row + i]);
    let v11 = bitcast<f32>(bricks[base + (j + 1u) * row + i + 1u]);
    let bottom = f.x * (v10 - v00) + v00;
    let top = f.x * (v11 - v01) + v01;
    let d = (top - bottom) * f.y + bottom;
    let ddx = ((v10 - v00) + f.y * ((v11 - v01) - (v10 - v00))) * du;
    let ddy = (top - bottom) * dv;
    let mi = min(u32(uv.x + 0.5), n);
    let mj = min(u32(uv.y + 0.5), n);
    let mat = bricks[base + words + mj * row + mi];
    return vec4<f32>(d, ddx, ddy, f32(mat));
}

// Radius of an event at the current tick; 0 when it has no effect yet (Event::radius_at).
fn event_radius(e: GpuEvent) -> f32 {
    if frame.tick < e.tick {
        return 0.0;
    }
    let elapsed = frame.tick - e.tick;
    if e.grow == 0u || elapsed >= e.grow {
        return e.radius;
    }
    return e.radius * (f32(elapsed + 1u) / f32(e.grow));
}

fn apply_event(acc: vec4<f32>, p: vec2<f32>, e: GpuEvent) -> vec4<f32> {
    let r = event_radius(e);
    if !(r > 0.0) {
        return acc;
    }
    let w = p - e.center;
    let len = length(w);
    let g = select(vec2<f32>(0.0), w / len, len > 0.0);
    let c = vec3<f32>(len - r, g);
    let d = acc.xyz;
    if e.kind == EVENT_FILL {
        let wins = !(d.x < c.x);
        var v = dmin(d, c);
        if e.rim > 0.0 {
            v = dsmin(d, c, e.rim);
        }
        return vec4<f32>(dclamp(v, frame.band), select(acc.w, f32(e.material), wins));
    }
    var v = dmax(d, -c);
    if e.rim > 0.0 {
        v = dsmax(d, -c, e.rim);
    }
    return vec4<f32>(dclamp(v, frame.band), acc.w);
}

// Distance, gradient and material of the terrain at p.
fn terrain_field(p: vec2<f32>) -> vec4<f32> {
    let ci = cell_of(p);
    if ci < 0 {
        return base_clamped(p);
    }
    let cell = cells[u32(ci)];
    let band = frame.band;
    var acc: vec4<f32>;
    switch cell.state {
        case CELL_AIR_BASE: {
            acc = vec4<f32>(band, 0.0, 0.0, base_sample(p).w);
        }
        case CELL_AIR_CONSTANT: {
            acc = vec4<f32>(band, 0.0, 0.0, f32(cell.payload));
        }
        case CELL_AIR_BRICK: {
            acc = vec4<f32>(band, 0.0, 0.0, brick_sample(cell.payload, u32(ci), p).w);
        }
        case CELL_SOLID: {
            acc = vec4<f32>(-band, 0.0, 0.0, f32(cell.payload));
        }
        case CELL_BRICK: {
            acc = brick_sample(cell.payload, u32(ci), p);
        }
        default: {
            acc = base_clamped(p);
        }
    }
    for (var k = cell.start; k < cell.start + cell.len; k++) {
        acc = apply_event(acc, p, events[lists[k]]);
    }
    return acc;
}
