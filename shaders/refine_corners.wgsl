// Mode `refine` on the GPU: the exact samples (distance, gradient, material) at the
// corners of the blocks classification level 0 left open. Needs common.wgsl, the emitted
// base field, field.wgsl and refine_common.wgsl.

@group(1) @binding(0) var<storage, read> blocks: array<BlockState>;
@group(1) @binding(1) var<storage, read_write> corners: array<vec4<f32>>;
@group(1) @binding(2) var<storage, read_write> work: Work;

fn is_open(bx: i32, by: i32, dims: vec2<u32>) -> bool {
    if bx < 0 || by < 0 || bx >= i32(dims.x) || by >= i32(dims.y) {
        return false;
    }
    return blocks[u32(by) * dims.x + u32(bx)].kind == CLASS_NEED;
}

@compute @workgroup_size(8, 8)
fn cs_corners(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = block_dims();
    if id.x > dims.x || id.y > dims.y {
        return;
    }
    let i = i32(id.x);
    let j = i32(id.y);
    let needed = is_open(i - 1, j - 1, dims) || is_open(i, j - 1, dims)
        || is_open(i - 1, j, dims) || is_open(i, j, dims);
    if !needed {
        return;
    }
    let p = pixel_to_world(vec2<f32>(f32(id.x * BLOCK), f32(id.y * BLOCK)));
    corners[corner_index(id.x, id.y)] = terrain_field(p);
    atomicAdd(&work.counters[COUNT_CORNERS], 1u);
}
