// Pass 2: reconstruction on the reduced-scale lattice (docs/render2d-pipeline.md). Needs
// common.wgsl. `fs_divergence` writes padded texels; `fs_pairs` writes the four pair values
// of the tangent-plane reconstruction. Mirrors src/render2d/twin/reconstruct.rs.

@group(0) @binding(1) var texels: texture_2d<f32>;

fn texel_at(c: vec2<i32>) -> vec4<f32> {
    return textureLoad(texels, clamp_texel(c), 0);
}

@fragment
fn fs_divergence(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let c = vec2<i32>(floor(pos.xy));
    let t = texel_at(c);
    let gxx = (texel_at(c + vec2<i32>(1, 0)).y - texel_at(c - vec2<i32>(1, 0)).y) * 0.5;
    // Row r - 1 is world-up.
    let gyy = (texel_at(c - vec2<i32>(0, 1)).z - texel_at(c + vec2<i32>(0, 1)).z) * 0.5;
    let k = clamp(sign(gxx) * gxx * gxx + sign(gyy) * gyy * gyy, 0.0, 1.0);
    return vec4<f32>(t.x - k * frame.h, t.yzw);
}

fn inside_lattice(c: vec2<i32>) -> bool {
    let dims = vec2<i32>(frame.lattice_dims);
    return all(c >= vec2<i32>(0, 0)) && all(c < dims);
}

// Pair value of texels a and b: positive where the gradients diverge, negative where they
// converge, 0 where either gradient is degenerate or a texel is off the lattice.
fn pair_value(a: vec2<i32>, b: vec2<i32>) -> f32 {
    if !(inside_lattice(a) && inside_lattice(b)) {
        return 0.0;
    }
    let ga = textureLoad(texels, a, 0).yz;
    let gb = textureLoad(texels, b, 0).yz;
    if length(ga) < 0.5 || length(gb) < 0.5 {
        return 0.0;
    }
    // Lattice offset b - a in world directions over h (rows go down, world y up).
    let step = vec2<f32>(f32(b.x - a.x), f32(a.y - b.y));
    let div = dot(gb - ga, step);
    return clamp(div / 0.5, -1.0, 1.0);
}

@fragment
fn fs_pairs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let c = vec2<i32>(floor(pos.xy));
    let right = pair_value(c, c + vec2<i32>(1, 0));
    let down = pair_value(c, c + vec2<i32>(0, 1));
    let diag = pair_value(c, c + vec2<i32>(1, 1));
    let anti = pair_value(c + vec2<i32>(1, 0), c + vec2<i32>(0, 1));
    return vec4<f32>(right, down, diag, anti);
}
