// Pass 3: full-resolution upsample and shade (docs/render2d-pipeline.md). Needs common.wgsl
// and shade.wgsl. One entry point per interpolant; mirrors src/render2d/twin/upsample.rs.

@group(0) @binding(1) var texels: texture_2d<f32>;
@group(0) @binding(2) var pairs: texture_2d<f32>;
@group(0) @binding(3) var linear_clamp: sampler;
@group(0) @binding(4) var<uniform> palette: Palette;

fn load(c: vec2<i32>) -> vec4<f32> {
    return textureLoad(texels, clamp_texel(c), 0);
}

fn base_color(material: f32) -> vec3<f32> {
    return palette_color(material);
}

struct Lookup {
    p: vec2<f32>,
    q: vec2<f32>,
    // Top-left texel of the quad holding q, and q's offset in it.
    c: vec2<i32>,
    f: vec2<f32>,
}

fn lookup(pos: vec4<f32>) -> Lookup {
    let p = pixel_to_world(floor(pos.xy));
    let q = to_lattice(p);
    let hi = vec2<i32>(frame.lattice_dims) - vec2<i32>(2, 2);
    let c = clamp(vec2<i32>(floor(q)), vec2<i32>(0, 0), hi);
    let f = clamp(q - vec2<f32>(c), vec2<f32>(0.0), vec2<f32>(1.0));
    return Lookup(p, q, c, f);
}

// Bilinear normal over the quad, normalized; material of the nearest texel.
fn finish(l: Lookup, d: f32, y: f32) -> vec4<f32> {
    let nearest = load(vec2<i32>(floor(l.q + vec2<f32>(0.5))));
    return finish_with(l, d, y, nearest.w);
}

fn finish_with(l: Lookup, d: f32, y: f32, material: f32) -> vec4<f32> {
    return finish_quad(l, d, y, material, load(l.c), load(l.c + vec2<i32>(1, 0)),
        load(l.c + vec2<i32>(0, 1)), load(l.c + vec2<i32>(1, 1)));
}

// finish_with over quad texels the caller already loaded.
fn finish_quad(l: Lookup, d: f32, y: f32, material: f32,
    t00: vec4<f32>, t10: vec4<f32>, t01: vec4<f32>, t11: vec4<f32>) -> vec4<f32> {
    let g = mix(mix(t00.yz, t10.yz, l.f.x), mix(t01.yz, t11.yz, l.f.x), l.f.y);
    let n = select(vec2<f32>(0.0), normalize(g), dot(g, g) > 0.0);
    return shade_pixel(d / frame.upp, n, base_color(material), y);
}

fn uv_of(t: vec2<f32>) -> vec2<f32> {
    return (t + vec2<f32>(0.5)) / vec2<f32>(frame.texture_dims);
}

@fragment
fn fs_bilinear(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let l = lookup(pos);
    let d = textureSampleLevel(texels, linear_clamp, uv_of(vec2<f32>(l.c) + l.f), 0.0).x;
    return finish(l, d, floor(pos.y));
}

fn bspline_weights(t: f32) -> vec4<f32> {
    let t2 = t * t;
    let t3 = t2 * t;
    let s = 1.0 - t;
    return vec4<f32>(
        s * s * s,
        3.0 * t3 - 6.0 * t2 + 4.0,
        -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0,
        t3,
    ) / 6.0;
}

// The cubic B-spline over 4x4 texels from four bilinear taps.
@fragment
fn fs_bspline(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let l = lookup(pos);
    let wx = bspline_weights(l.f.x);
    let wy = bspline_weights(l.f.y);
    let gx = vec2<f32>(wx.x + wx.y, wx.z + wx.w);
    let gy = vec2<f32>(wy.x + wy.y, wy.z + wy.w);
    let base = vec2<f32>(l.c);
    let x0 = base.x - 1.0 + wx.y / gx.x;
    let x1 = base.x + 1.0 + wx.w / gx.y;
    let y0 = base.y - 1.0 + wy.y / gy.x;
    let y1 = base.y + 1.0 + wy.w / gy.y;
    let d = gy.x * (gx.x * textureSampleLevel(texels, linear_clamp, uv_of(vec2<f32>(x0, y0)), 0.0).x
        + gx.y * textureSampleLevel(texels, linear_clamp, uv_of(vec2<f32>(x1, y0)), 0.0).x)
        + gy.y * (gx.x * textureSampleLevel(texels, linear_clamp, uv_of(vec2<f32>(x0, y1)), 0.0).x
        + gx.y * textureSampleLevel(texels, linear_clamp, uv_of(vec2<f32>(x1, y1)), 0.0).x);
    return finish(l, d, floor(pos.y));
}

fn catmull_weights(t: f32) -> vec4<f32> {
    let t2 = t * t;
    let t3 = t2 * t;
    return vec4<f32>(
        -t3 + 2.0 * t2 - t,
        3.0 * t3 - 5.0 * t2 + 2.0,
        -3.0 * t3 + 4.0 * t2 + t,
        t3 - t2,
    ) * 0.5;
}

@fragment
fn fs_catmull_rom(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let l = lookup(pos);
    let wx = catmull_weights(l.f.x);
    let wy = catmull_weights(l.f.y);
    var d = 0.0;
    for (var j = 0; j < 4; j++) {
        var row = 0.0;
        for (var i = 0; i < 4; i++) {
            row += wx[i] * load(l.c + vec2<i32>(i - 1, j - 1)).x;
        }
        d += wy[j] * row;
    }
    return finish(l, d, floor(pos.y));
}

fn smooth01(t: f32) -> f32 {
    return t * t * (3.0 - 2.0 * t);
}

// Plane r pulled towards `other` by pair value s: up where the gradients diverge, down where
// they converge (one step of the twin's combined_plane; zero weights skipped).
fn pull_up(r: f32, other: f32, s: f32) -> f32 {
    let a = smooth01(max(s, 0.0));
    if a > 0.0 {
        return r + a * (max(r, other) - r);
    }
    return r;
}

fn pull_down(r: f32, other: f32, s: f32) -> f32 {
    let b = smooth01(max(-s, 0.0));
    if b > 0.0 {
        return r + b * (min(r, other) - r);
    }
    return r;
}

// R_k: plane pk against the other three (o, in ascending texel order) with pair values s.
fn combined_plane(pk: f32, o: vec3<f32>, s: vec3<f32>) -> f32 {
    let up = pull_up(pull_up(pull_up(pk, o.x, s.x), o.y, s.y), o.z, s.z);
    return pull_down(pull_down(pull_down(up, o.x, s.x), o.y, s.y), o.z, s.z);
}

// Tangent-plane reconstruction: per quad texel k, its plane combined with the others' by max
// where gradients diverge and min where they converge; the results blended bilinearly.
// Straight-line code: no function-scope arrays, no loops (each would get a loop_bound counter
// from naga and defeat unrolling), and the four quad texels loaded once.
@fragment
fn fs_planes(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let l = lookup(pos);
    let t0 = load(l.c);
    let t1 = load(l.c + vec2<i32>(1, 0));
    let t2 = load(l.c + vec2<i32>(0, 1));
    let t3 = load(l.c + vec2<i32>(1, 1));
    let c0 = texel_center(l.c.x, l.c.y);
    let c1 = texel_center(l.c.x + 1, l.c.y);
    let c2 = texel_center(l.c.x, l.c.y + 1);
    let c3 = texel_center(l.c.x + 1, l.c.y + 1);
    let p = vec4<f32>(
        t0.x + dot(t0.yz, l.p - c0),
        t1.x + dot(t1.yz, l.p - c1),
        t2.x + dot(t2.yz, l.p - c2),
        t3.x + dot(t3.yz, l.p - c3),
    );
    // The material of the texel whose plane is lowest here (the union's rule, extrapolated).
    var material = 0.0;
    var lowest = 3.0e38;
    if p.x < lowest { lowest = p.x; material = t0.w; }
    if p.y < lowest { lowest = p.y; material = t1.w; }
    if p.z < lowest { lowest = p.z; material = t2.w; }
    if p.w < lowest { lowest = p.w; material = t3.w; }
    let s0 = textureLoad(pairs, l.c, 0);
    let s1 = textureLoad(pairs, l.c + vec2<i32>(1, 0), 0);
    let s2 = textureLoad(pairs, l.c + vec2<i32>(0, 1), 0);
    // Pairs: 01 right(0) s0.x, 02 down(0) s0.y, 03 diag(0) s0.z, 12 anti(0) s0.w,
    // 13 down(1) s1.y, 23 right(2) s2.x.
    let r0 = combined_plane(p.x, p.yzw, vec3<f32>(s0.x, s0.y, s0.z));
    let r1 = combined_plane(p.y, p.xzw, vec3<f32>(s0.x, s0.w, s1.y));
    let r2 = combined_plane(p.z, p.xyw, vec3<f32>(s0.y, s0.w, s2.x));
    let r3 = combined_plane(p.w, p.xyz, vec3<f32>(s0.z, s1.y, s2.x));
    let w = vec4<f32>(
        (1.0 - l.f.x) * (1.0 - l.f.y),
        l.f.x * (1.0 - l.f.y),
        (1.0 - l.f.x) * l.f.y,
        l.f.x * l.f.y,
    );
    // Summed in texel order, as before (not dot(), whose order is unspecified).
    let d = w.x * r0 + w.y * r1 + w.z * r2 + w.w * r3;
    let reach = vec4<f32>(length(l.p - c0), length(l.p - c1), length(l.p - c2), length(l.p - c3));
    let clamped = lipschitz_clamp(d, vec4<f32>(t0.x, t1.x, t2.x, t3.x),
        vec4<f32>(length(t0.yz), length(t1.yz), length(t2.yz), length(t3.yz)), reach);
    return finish_quad(l, clamped, floor(pos.y), material, t0, t1, t2, t3);
}

// The field changes by at most `slope` per world unit around the quad, so at p it lies within
// d_k +- slope |p - C_k| of every quad texel: clamp the reconstruction into that interval.
// The slope is the quad's largest gradient magnitude (the field's local rate of change, 1 for
// a distance field) with a 5% margin, at least 1 and at most the global bound. `dk`, `gk` and
// `dist` are the quad texels' distances, gradient lengths and distances |p - C_k|.
fn lipschitz_clamp(d: f32, dk: vec4<f32>, gk: vec4<f32>, dist: vec4<f32>) -> f32 {
    let local = max(max(max(max(1.0, gk.x), gk.y), gk.z), gk.w);
    let slope = min(local * 1.05, frame.slope);
    let reach = slope * dist;
    let lo = max(max(max(max(-3.0e38, dk.x - reach.x), dk.y - reach.y), dk.z - reach.z), dk.w - reach.w);
    let hi = min(min(min(min(3.0e38, dk.x + reach.x), dk.y + reach.y), dk.z + reach.z), dk.w + reach.w);
    if lo > hi {
        return 0.5 * (lo + hi);
    }
    return min(max(d, lo), hi);
}
