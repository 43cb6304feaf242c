// Mode `refine` on the GPU, the exact pass: dispatched indirectly over the list of blocks
// classification level 1 could not prove, EXACT_BLOCKS_PER_GROUP blocks per workgroup, one
// invocation per pixel. Each pixel is evaluated and shaded exactly as the direct pass does
// it (direct.wgsl), and its colour stored by list slot for the draw (refine_draw.wgsl).
// Needs common.wgsl, the emitted base field, field.wgsl, shade.wgsl and refine_common.wgsl.

// `Work` (refine_common.wgsl) read without atomics.
struct WorkCounts {
    dispatch: array<u32, 3>,
    exact_blocks: u32,
    counters: array<u32, 8>,
    corner_dispatch: array<u32, 3>,
    open_blocks: u32,
}

@group(0) @binding(6) var<uniform> palette: Palette;
@group(1) @binding(0) var<storage, read> exact_list: array<u32>;
@group(1) @binding(1) var<storage, read> work: WorkCounts;
// Two words per pixel, BLOCK * BLOCK pixels per list slot, row-major within the block: the
// colour as 8-bit unorm (what an 8-bit target stores, so the draw writes the same bytes as
// the direct pass), or for sRGB targets as two pack2x16float words (the linear value).
@group(1) @binding(2) var<storage, read_write> exact_colors: array<vec2<u32>>;

fn pack_color(c: vec4<f32>) -> vec2<u32> {
    if frame.srgb_target != 0u {
        return vec2<u32>(pack2x16float(c.rg), pack2x16float(c.ba));
    }
    return vec2<u32>(pack4x8unorm(c), 0u);
}

@compute @workgroup_size(64)
fn cs_exact(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let per_block = BLOCK * BLOCK;
    let slot = (group.y * groups.x + group.x) * EXACT_BLOCKS_PER_GROUP + lane / per_block;
    if slot >= work.exact_blocks {
        return;
    }
    let dims = block_dims();
    let block = exact_list[slot];
    let local = lane % per_block;
    let px = vec2<u32>(block % dims.x, block / dims.x) * BLOCK
        + vec2<u32>(local % BLOCK, local / BLOCK);
    if px.x >= frame.image.x || px.y >= frame.image.y {
        return;
    }
    let pf = vec2<f32>(px);
    let t = terrain_field(pixel_to_world(pf));
    let g = t.yz;
    let n = select(vec2<f32>(0.0), normalize(g), dot(g, g) > 0.0);
    let c = shade_pixel(t.x / frame.upp, n, palette_color(t.w), pf.y);
    exact_colors[slot * per_block + local] = pack_color(c);
}
