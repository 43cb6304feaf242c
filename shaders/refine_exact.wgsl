// Mode `refine` on the GPU, the exact pass: one instance per block in the list that
// classification level 1 wrote, drawn as a quad over the block's pixels by an indirect draw;
// the fragment stage is the direct evaluation (direct.wgsl). Needs direct.wgsl's module and
// refine_common.wgsl.

@group(1) @binding(0) var<storage, read> exact_list: array<u32>;

@vertex
fn vs_exact_block(
    @builtin(vertex_index) v: u32,
    @builtin(instance_index) i: u32,
) -> @builtin(position) vec4<f32> {
    let dims = block_dims();
    let block = exact_list[i];
    let b = vec2<u32>(block % dims.x, block / dims.x);
    // Two triangles: (0,0) (1,0) (0,1) and (1,0) (1,1) (0,1).
    let corner = vec2<u32>((0x1au >> v) & 1u, (0x34u >> v) & 1u);
    let px = min((b + corner) * BLOCK, frame.image);
    let size = vec2<f32>(frame.image);
    let ndc = vec2<f32>(f32(px.x) / size.x * 2.0 - 1.0, 1.0 - f32(px.y) / size.y * 2.0);
    return vec4<f32>(ndc, 0.0, 1.0);
}
