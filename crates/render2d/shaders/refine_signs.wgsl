// Mode `refine` on the GPU, the event-sign proof (docs/render2d-pipeline.md, "Refine on the
// GPU"): for every block level 0 left open, what the events of the cells it touches force
// over it, as `Terrain::rect_sign` proves it (src/field2d/terrain/proof.rs), read from the
// same event lists the field is evaluated from. One walk per cell answers three questions:
// is the field at least sky_at(), at most deep_at(), at most solid_at() over the block? The
// first two decide the block here (sky, deep solid: neither needs corner samples); the
// third is kept in the block for level 1 (`cs_blocks`, refine_classify.wgsl). Needs
// common.wgsl, the emitted base field, field.wgsl, refine_common.wgsl and refine_proof.wgsl.

@group(1) @binding(0) var<storage, read> proof: array<CellProof>;
@group(1) @binding(1) var<storage, read_write> blocks: array<BlockState>;

// One question's state along the backwards walk: no event decided it yet, the last
// deciding event forces the bound, or the last deciding event breaks it.
const UNDECIDED: u32 = 0u;
const FORCED: u32 = 1u;
const BROKEN: u32 = 2u;

// The thresholds of the three questions: the field at least `above`, at most `solid`, at
// most `deep` (above > 0 > solid > deep).
struct Thresholds {
    above: f32,
    solid: f32,
    deep: f32,
}

// The smallest and largest samples of brick `id` (in cell `cell`) on the lattice squares
// rectangle r touches, the lookup clamped to the brick as `brick_sample` clamps it
// (`Terrain::brick_range`); one extra square each way covers the rounding of the lookup.
fn brick_range(id: u32, cell: u32, r: vec4<f32>) -> vec2<f32> {
    let n = i32(frame.brick_res);
    let origin = cell_min(cell);
    let h = frame.brick_spacing;
    let a = clamp(vec2<i32>(floor((r.xy - origin) / h)) - vec2<i32>(1), vec2<i32>(0), vec2<i32>(n));
    let b = clamp(vec2<i32>(ceil((r.zw - origin) / h)) + vec2<i32>(1), vec2<i32>(0), vec2<i32>(n));
    let row = u32(n) + 1u;
    let first = id * 2u * row * row;
    var lo = UNBOUNDED;
    var hi = -UNBOUNDED;
    for (var j = a.y; j <= b.y; j++) {
        for (var i = a.x; i <= b.x; i++) {
            let v = bitcast<f32>(bricks[first + u32(j) * row + u32(i)]);
            lo = min(lo, v);
            hi = max(hi, v);
        }
    }
    return vec2<f32>(lo, hi);
}

// Bounds of cell `cell`'s starting state over rectangle r (`Terrain::start_range`).
fn start_range(cell: u32, c: GpuCell, r: vec4<f32>) -> vec2<f32> {
    let band = frame.band;
    switch c.state {
        case CELL_AIR_BASE, CELL_AIR_CONSTANT, CELL_AIR_BRICK: {
            return vec2<f32>(band, band);
        }
        case CELL_SOLID: {
            return vec2<f32>(-band, -band);
        }
        case CELL_BRICK: {
            let b = brick_range(c.payload, cell, r);
            // NaN samples (never expected) prove nothing.
            if b.x <= b.y {
                return b;
            }
            return vec2<f32>(-band, band);
        }
        default: {
            return proof[cell].start;
        }
    }
}

// What one event of radius `radius` (> 0) says over rectangle r: a carve holding r `t`
// deep forces "at least t"; one reaching within `rim` of `-t` breaks "at most t". A fill
// reaching within `t + rim` breaks "at least t"; one holding r `-t` deep forces "at most
// t". `slack` covers the f32 rounding of |p - o| - r in `apply_event`.
fn event_verdicts(e: GpuEvent, radius: f32, r: vec4<f32>, t: Thresholds, slack: f32) -> vec3<u32> {
    let near = length(max(max(r.xy - e.center, e.center - r.zw), vec2<f32>(0.0)));
    let far = length(max(abs(e.center - r.xy), abs(e.center - r.zw)));
    let forced = vec3<bool>(false, far <= radius + t.solid - slack, far <= radius + t.deep - slack);
    if e.kind == EVENT_FILL {
        let breaks_above = !(near >= radius + t.above + e.rim + slack);
        return vec3<u32>(
            select(UNDECIDED, BROKEN, breaks_above),
            select(UNDECIDED, FORCED, forced.y),
            select(UNDECIDED, FORCED, forced.z),
        );
    }
    let holds = far <= radius - t.above - slack;
    let breaks_solid = !(near >= radius - t.solid + e.rim + slack);
    let breaks_deep = !(near >= radius - t.deep + e.rim + slack);
    return vec3<u32>(
        select(UNDECIDED, FORCED, holds),
        select(UNDECIDED, BROKEN, breaks_solid),
        select(UNDECIDED, BROKEN, breaks_deep),
    );
}

// What cell `cell`'s starting state and events force over rectangle r, as SIGN_* bits
// ("at least above" excludes the others, as `RectSign::Above` does). Walked backwards: the
// last event that forces or breaks a bound decides it, and the starting state decides what
// no event did.
fn cell_signs(cell: u32, r: vec4<f32>, t: Thresholds) -> u32 {
    let c = cells[cell];
    let slack = 1.0e-3 + 4.0e-6 * max(max(abs(r.x), abs(r.y)), max(abs(r.z), abs(r.w)));
    var state = vec3<u32>(UNDECIDED);
    for (var k = c.start + c.len; k > c.start && any(state == vec3<u32>(UNDECIDED)); k--) {
        let e = events[lists[k - 1u]];
        let radius = event_radius(e);
        // Past `reach` an event neither forces nor breaks any of the three bounds: most
        // listed events stay that far from a block, and the squared distance tells it
        // without a square root. The relative 1e-5 keeps every event whose `length` in
        // `event_verdicts` could still fall short of `reach`.
        let reach = (radius + max(t.above, -t.deep) + e.rim + slack) * (1.0 + 1.0e-5);
        let gap = max(max(r.xy - e.center, e.center - r.zw), vec2<f32>(0.0));
        if radius > 0.0 && !(dot(gap, gap) >= reach * reach) {
            let v = event_verdicts(e, radius, r, t, slack);
            state = select(state, v, state == vec3<u32>(UNDECIDED));
        }
    }
    if any(state == vec3<u32>(UNDECIDED)) {
        let s = start_range(cell, c, r);
        let from_start = vec3<u32>(
            select(BROKEN, FORCED, s.x >= t.above),
            select(BROKEN, FORCED, s.y <= t.solid),
            select(BROKEN, FORCED, s.y <= t.deep),
        );
        state = select(state, from_start, state == vec3<u32>(UNDECIDED));
    }
    if state.x == FORCED {
        return SIGN_ABOVE;
    }
    return select(0u, SIGN_BELOW_SOLID, state.y == FORCED)
        | select(0u, SIGN_BELOW_DEEP, state.z == FORCED);
}

// What the events of every cell rectangle r touches force over it (a bit holds when it
// holds in every cell); nothing outside the grid, over too many cells, or with a threshold
// past the band.
fn block_signs(r: vec4<f32>) -> u32 {
    let t = Thresholds(sky_at(), solid_at(), deep_at());
    if t.above > frame.band || t.solid < -frame.band {
        return 0u;
    }
    let s = cell_span(r.xy, r.zw);
    let dims = vec2<i32>(frame.grid_dims);
    if s.x < 0 || s.y < 0 || s.z >= dims.x || s.w >= dims.y || span_cells(s) > MAX_SPAN_CELLS {
        return 0u;
    }
    // "At most deep" past the band is never forced by the clamp's argument.
    var agreed = select(SIGN_ABOVE | SIGN_BELOW_SOLID | SIGN_BELOW_DEEP,
        SIGN_ABOVE | SIGN_BELOW_SOLID, t.deep < -frame.band);
    for (var iy = s.y; iy <= s.w && agreed != 0u; iy++) {
        for (var ix = s.x; ix <= s.z && agreed != 0u; ix++) {
            agreed &= cell_signs(u32(iy) * frame.grid_dims.x + u32(ix), r, t);
        }
    }
    return agreed;
}

@compute @workgroup_size(8, 8)
fn cs_signs(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = block_dims();
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let index = id.y * dims.x + id.x;
    let state = blocks[index];
    if state.kind != CLASS_NEED {
        return;
    }
    let rect = block_rect(block_pixels(id.xy));
    blocks[index] = decide(state.lo, state.hi, block_signs(rect), rect, false);
}
