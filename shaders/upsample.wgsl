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
    let t00 = load(l.c);
    let t10 = load(l.c + vec2<i32>(1, 0));
    let t01 = load(l.c + vec2<i32>(0, 1));
    let t11 = load(l.c + vec2<i32>(1, 1));
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

// Tangent-plane reconstruction: per quad texel k, its plane combined with the others' by max
// where gradients diverge and min where they converge; the results blended bilinearly.
@fragment
fn fs_planes(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let l = lookup(pos);
    var offs = array<vec2<i32>, 4>(vec2<i32>(0, 0), vec2<i32>(1, 0), vec2<i32>(0, 1), vec2<i32>(1, 1));
    var planes: array<f32, 4>;
    // The material of the texel whose plane is lowest here (the union's rule, extrapolated).
    var material = 0.0;
    var lowest = 3.0e38;
    for (var k = 0; k < 4; k++) {
        let c = l.c + offs[k];
        let t = load(c);
        planes[k] = t.x + dot(t.yz, l.p - texel_center(c.x, c.y));
        if planes[k] < lowest {
            lowest = planes[k];
            material = t.w;
        }
    }
    let s0 = textureLoad(pairs, l.c, 0);
    let s1 = textureLoad(pairs, l.c + vec2<i32>(1, 0), 0);
    let s2 = textureLoad(pairs, l.c + vec2<i32>(0, 1), 0);
    // s[k][m], symmetric: 01 right(0), 02 down(0), 03 diag(0), 12 anti(0), 13 down(1), 23 right(2).
    var s = array<vec4<f32>, 4>(
        vec4<f32>(0.0, s0.x, s0.y, s0.z),
        vec4<f32>(s0.x, 0.0, s0.w, s1.y),
        vec4<f32>(s0.y, s0.w, 0.0, s2.x),
        vec4<f32>(s0.z, s1.y, s2.x, 0.0),
    );
    let w = vec4<f32>(
        (1.0 - l.f.x) * (1.0 - l.f.y),
        l.f.x * (1.0 - l.f.y),
        (1.0 - l.f.x) * l.f.y,
        l.f.x * l.f.y,
    );
    var d = 0.0;
    for (var k = 0; k < 4; k++) {
        var r = planes[k];
        for (var m = 0; m < 4; m++) {
            let a = smooth01(max(s[k][m], 0.0));
            if m != k && a > 0.0 {
                r += a * (max(r, planes[m]) - r);
            }
        }
        for (var m = 0; m < 4; m++) {
            let b = smooth01(max(-s[k][m], 0.0));
            if m != k && b > 0.0 {
                r += b * (min(r, planes[m]) - r);
            }
        }
        d += w[k] * r;
    }
    return finish_with(l, lipschitz_clamp(d, l.p, l.c), floor(pos.y), material);
}

// The field changes by at most `slope` per world unit around the quad, so at p it lies within
// d_k +- slope |p - C_k| of every quad texel: clamp the reconstruction into that interval.
// The slope is the quad's largest gradient magnitude (the field's local rate of change, 1 for
// a distance field) with a 5% margin, at least 1 and at most the global bound.
fn lipschitz_clamp(d: f32, p: vec2<f32>, c: vec2<i32>) -> f32 {
    var local = 1.0;
    for (var k = 0; k < 4; k++) {
        local = max(local, length(load(c + vec2<i32>(k & 1, k >> 1u)).yz));
    }
    let slope = min(local * 1.05, frame.slope);
    var lo = -3.0e38;
    var hi = 3.0e38;
    for (var k = 0; k < 4; k++) {
        let t = c + vec2<i32>(k & 1, k >> 1u);
        let reach = slope * length(p - texel_center(t.x, t.y));
        let dk = load(t).x;
        lo = max(lo, dk - reach);
        hi = min(hi, dk + reach);
    }
    if lo > hi {
        return 0.5 * (lo + hi);
    }
    return min(max(d, lo), hi);
}
