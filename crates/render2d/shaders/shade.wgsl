// The shading formula of docs/render2d-pipeline.md, shared by the upsample pass and the
// full-resolution direct pass. Mirrors the CPU twin's shade function
// (src/render2d/twin/shade.rs). Colours are in 0..255.

// The level's material colours (0..255); `PaletteUniform` in src/render2d/gpu/uniforms.rs.
// Each module that includes this file binds a `palette: Palette` uniform.
struct Palette {
    colors: array<vec4<f32>, 256>,
}

// A material's colour, magenta for materials the palette lacks.
fn palette_color(material: f32) -> vec3<f32> {
    let m = u32(max(material, 0.0) + 0.5);
    if m < min(frame.palette_len, 256u) {
        return palette.colors[m].rgb;
    }
    return vec3<f32>(255.0, 0.0, 255.0);
}

fn sky_color(y: f32) -> vec3<f32> {
    let t = clamp(y / f32(frame.image.y), 0.0, 1.0);
    return mix(frame.sky_top.rgb, frame.sky_bottom.rgb, t);
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let lo = c / 12.92;
    let hi = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(hi, lo, c <= vec3<f32>(0.04045));
}

// The final colour of a pixel with distance d_px (pixels), unit normal n (or zero) and base
// colour, as the render target stores it.
fn shade_pixel(d_px: f32, n: vec2<f32>, base: vec3<f32>, y: f32) -> vec4<f32> {
    let sky = sky_color(y);
    let coverage = clamp(0.5 - d_px, 0.0, 1.0);
    let depth = clamp(-d_px / frame.shade_depth_px, 0.0, 1.0);
    var color = base * (1.0 - 0.4 * depth);
    if d_px > -frame.shade_depth_px * 0.5 {
        let l = frame.light;
        let light = select(vec2<f32>(0.0, 1.0), normalize(l), dot(l, l) > 0.0);
        let lit = dot(n, light);
        let rim = clamp(1.0 + d_px / (frame.shade_depth_px * 0.5), 0.0, 1.0);
        color = color * (1.0 + 0.35 * lit * rim);
    }
    let outline = clamp(d_px + frame.outline_px + 0.5, 0.0, 1.0) * coverage;
    color = mix(color, base * 0.35, outline);
    return finish_color(mix(sky, color, coverage));
}

// A 0..255 colour as the render target stores it. For 8-bit targets the channel is rounded
// here, half away from zero as the CPU twin rounds (`to_u8` in src/render2d/twin/shade.rs),
// and handed over as the exact level k / 255: how a driver converts a float to unorm8 is
// its own (an NVIDIA driver rounded a tie k + 1/2 down where lavapipe and the twin round it
// up, one level off in whole rows of sky), but every conforming one maps k / 255 to k.
fn finish_color(c: vec3<f32>) -> vec4<f32> {
    let clamped = clamp(c, vec3<f32>(0.0), vec3<f32>(255.0));
    if frame.srgb_target != 0u {
        return vec4<f32>(srgb_to_linear(clamped / 255.0), 1.0);
    }
    return vec4<f32>(floor(clamped + vec3<f32>(0.5)) / 255.0, 1.0);
}

// What shade_pixel gives wherever coverage is 0 (mix(sky, c, 0) is sky).
fn sky_pixel(y: f32) -> vec4<f32> {
    return finish_color(sky_color(y));
}
