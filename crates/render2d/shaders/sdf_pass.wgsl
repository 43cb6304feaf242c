// Pass 1: the terrain sampled at every texel centre of the reduced-scale lattice, packed as
// (distance, gradient.x, gradient.y, material) into an Rgba16Float target. Needs common.wgsl,
// field.wgsl and the emitted base field.

@fragment
fn fs_sdf(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let c = vec2<i32>(floor(pos.xy));
    return terrain_field(texel_center(c.x, c.y));
}
