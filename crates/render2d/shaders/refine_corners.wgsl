// Mode `refine` on the GPU: the exact samples (distance, gradient, material) at the
// corners of the blocks the classification left open, dispatched indirectly over the list
// `cs_open` wrote (refine_classify.wgsl): four invocations per listed block, one per corner,
// each sampling its corner if the list gives it to this block. Needs common.wgsl, the
// emitted base field, field.wgsl and refine_common.wgsl.

@group(1) @binding(0) var<storage, read> open_list: array<u32>;
@group(1) @binding(1) var<storage, read_write> corners: array<vec4<f32>>;

@compute @workgroup_size(64)
fn cs_corners(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let slot = (group.y * groups.x + group.x) * OPEN_BLOCKS_PER_GROUP + lane / 4u;
    if slot >= open_list[0] {
        return;
    }
    let entry = open_list[slot + 1u];
    let k = lane % 4u;
    if ((entry >> (OPEN_INDEX_BITS + k)) & 1u) == 0u {
        return;
    }
    let dims = block_dims();
    let index = entry & ((1u << OPEN_INDEX_BITS) - 1u);
    let c = block_corner(vec2<u32>(index % dims.x, index / dims.x), k);
    let p = pixel_to_world(vec2<f32>(f32(c.x * BLOCK), f32(c.y * BLOCK)));
    corners[corner_index(c.x, c.y)] = terrain_field(p);
}
