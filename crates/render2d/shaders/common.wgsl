// Shared by every 2D render pass: the per-frame uniforms and the full-screen triangle.
// `Frame` mirrors `FrameUniform` in src/render2d/gpu/uniforms.rs (same field order, 144 bytes).

struct Frame {
    center: vec2<f32>,
    upp: f32,
    // Bound on the field's change per world unit (the planes' Lipschitz clamp).
    slope: f32,
    image: vec2<u32>,
    lattice_dims: vec2<u32>,
    lattice_origin: vec2<i32>,
    h: f32,
    band: f32,
    grid_origin: vec2<f32>,
    cell_size: f32,
    brick_spacing: f32,
    grid_dims: vec2<u32>,
    brick_res: u32,
    tick: u32,
    sky_top: vec4<f32>,
    sky_bottom: vec4<f32>,
    light: vec2<f32>,
    outline_px: f32,
    shade_depth_px: f32,
    palette_len: u32,
    srgb_target: u32,
    // Size of the reduced-scale textures (at least the lattice's).
    texture_dims: vec2<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;

// One triangle covering the viewport; the fragment stages work from @builtin(position).
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

// World position of texel (c, r)'s centre (see src/render2d/lattice.rs).
fn texel_center(c: i32, r: i32) -> vec2<f32> {
    return vec2<f32>(
        f32(frame.lattice_origin.x + c) * frame.h,
        f32(frame.lattice_origin.y - r) * frame.h,
    );
}

// World position of output pixel (x, y)'s centre (Camera::pixel_to_world).
fn pixel_to_world(px: vec2<f32>) -> vec2<f32> {
    let half = vec2<f32>(f32(frame.image.x), f32(frame.image.y)) * 0.5;
    let offset = vec2<f32>(px.x + 0.5 - half.x, half.y - (px.y + 0.5));
    return frame.center + offset * frame.upp;
}

// Lattice coordinates of a world point: texel (c, r) sits at (c, r).
fn to_lattice(p: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(
        p.x / frame.h - f32(frame.lattice_origin.x),
        f32(frame.lattice_origin.y) - p.y / frame.h,
    );
}

fn clamp_texel(c: vec2<i32>) -> vec2<i32> {
    let hi = vec2<i32>(frame.lattice_dims) - vec2<i32>(1, 1);
    return clamp(c, vec2<i32>(0, 0), hi);
}
