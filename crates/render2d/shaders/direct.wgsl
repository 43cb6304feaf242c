// Full-resolution direct rendering: the terrain evaluated at every pixel and shaded, the
// baseline the reduced-scale pipeline is measured against. Needs common.wgsl, field.wgsl,
// the emitted base field and shade.wgsl. The normal is the field's own gradient.

@group(0) @binding(6) var<uniform> palette: Palette;

@fragment
fn fs_direct(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let px = floor(pos.xy);
    let t = terrain_field(pixel_to_world(px));
    let base = palette_color(t.w);
    let g = t.yz;
    let n = select(vec2<f32>(0.0), normalize(g), dot(g, g) > 0.0);
    return shade_pixel(t.x / frame.upp, n, base, px.y);
}
