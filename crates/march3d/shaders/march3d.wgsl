// The hand-written half of the 3D raymarcher: camera rays, primitives, noise, the march,
// normals, shadows and both shading models of `src/march3d/plan.rs`. The emitted half
// (`emit::codegen3d`) is prepended and defines every `em_` name used here: the plan's
// constants, `em_hash2`, `em_hash3`, `em_height`, `em_map`, `em_dist`, `em_material`,
// `em_lights`, `em_bounds_shadow` and `em_ao_taps`.

// The camera and image size; `MarchFrame` in `src/march3d/gpu/uniforms.rs` (same field
// order, 64 bytes: each vec3 is padded by the scalar after it).
struct MarchFrame {
    position: vec3<f32>,
    tan_half_fov: f32,
    forward: vec3<f32>,
    width: u32,
    right: vec3<f32>,
    height: u32,
    up: vec3<f32>,
    pad: u32,
}

@group(0) @binding(0) var<uniform> frame: MarchFrame;
@group(0) @binding(1) var out_image: texture_storage_2d<rgba8unorm, write>;

// `SKY` of plan.rs: the material of the background.
const SKY: u32 = 0xffffffffu;

// A scene sample: distance and the nearest material.
struct MapHit {
    d: f32,
    m: u32,
}

// A marched ray: whether it hit, where (t along the ray) and what.
struct RayHit {
    hit: bool,
    t: f32,
    m: u32,
}

// A material's look (plan.rs `Material`).
struct Look {
    colour: vec3<f32>,
    reflectivity: f32,
}

// Diffuse and specular sums of the paper's point lights.
struct Lit {
    diffuse: f32,
    specular: f32,
}

fn frac(x: f32) -> f32 {
    return x - floor(x);
}

fn frac3(x: vec3<f32>) -> vec3<f32> {
    return x - floor(x);
}

// ---- lattice hashes (plan.rs, Noise) ----

fn hash2_dot_fract(q: vec2<f32>) -> f32 {
    var p3 = frac3(vec3<f32>(q.x, q.y, q.x) * 0.1031);
    p3 += dot(p3, p3.yzx + 33.33);
    return frac((p3.x + p3.y) * p3.z);
}

fn hash3_dot_fract(q: vec3<f32>) -> f32 {
    var p3 = frac3(q * 0.1031);
    p3 += dot(p3, p3.zyx + 31.32);
    return frac((p3.x + p3.y) * p3.z);
}

fn hash2_sin(q: vec2<f32>) -> f32 {
    return frac(sin(dot(q, vec2<f32>(127.1, 311.7))) * 43758.5453);
}

fn hash3_sin(q: vec3<f32>) -> f32 {
    return frac(sin(dot(q, vec3<f32>(127.1, 311.7, 74.7))) * 43758.5453);
}

// ---- value noise ----

// 2D value noise at `x` and its gradient: (value, d/dx, d/dy).
fn noise2(x: vec2<f32>) -> vec3<f32> {
    let i = floor(x);
    let f = x - i;
    let u = f * f * (3.0 - 2.0 * f);
    let du = 6.0 * f * (1.0 - f);
    let a = em_hash2(i);
    let b = em_hash2(i + vec2<f32>(1.0, 0.0));
    let c = em_hash2(i + vec2<f32>(0.0, 1.0));
    let d = em_hash2(i + vec2<f32>(1.0, 1.0));
    let k = a - b - c + d;
    let value = a + (b - a) * u.x + (c - a) * u.y + k * u.x * u.y;
    let grad = du * vec2<f32>((b - a) + k * u.y, (c - a) + k * u.x);
    return vec3<f32>(value, grad);
}

// 3D value noise (value only): trilinear over the eight corner hashes.
fn noise3(x: vec3<f32>) -> f32 {
    let i = floor(x);
    let f = x - i;
    let u = f * f * (3.0 - 2.0 * f);
    let h000 = em_hash3(i);
    let h100 = em_hash3(i + vec3<f32>(1.0, 0.0, 0.0));
    let h010 = em_hash3(i + vec3<f32>(0.0, 1.0, 0.0));
    let h110 = em_hash3(i + vec3<f32>(1.0, 1.0, 0.0));
    let h001 = em_hash3(i + vec3<f32>(0.0, 0.0, 1.0));
    let h101 = em_hash3(i + vec3<f32>(1.0, 0.0, 1.0));
    let h011 = em_hash3(i + vec3<f32>(0.0, 1.0, 1.0));
    let h111 = em_hash3(i + vec3<f32>(1.0, 1.0, 1.0));
    let x00 = h000 + (h100 - h000) * u.x;
    let x10 = h010 + (h110 - h010) * u.x;
    let x01 = h001 + (h101 - h001) * u.x;
    let x11 = h011 + (h111 - h011) * u.x;
    let y0 = x00 + (x10 - x00) * u.y;
    let y1 = x01 + (x11 - x01) * u.y;
    return y0 + (y1 - y0) * u.z;
}

// ---- primitives in their own frame (plan.rs `PrimKind`) ----

fn max3(q: vec3<f32>) -> f32 {
    return max(q.x, max(q.y, q.z));
}

fn sd_sphere(p: vec3<f32>, r: f32) -> f32 {
    return length(p) - r;
}

fn sd_box(p: vec3<f32>, half: vec3<f32>) -> f32 {
    let q = abs(p) - half;
    return length(max(q, vec3<f32>(0.0))) + min(max3(q), 0.0);
}

fn sd_round_box(p: vec3<f32>, half: vec3<f32>, r: f32) -> f32 {
    let q = abs(p) - half + r;
    return length(max(q, vec3<f32>(0.0))) + min(max3(q), 0.0) - r;
}

fn sd_capsule(p: vec3<f32>, a: vec3<f32>, b: vec3<f32>, r: f32) -> f32 {
    let pa = p - a;
    let ba = b - a;
    let h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
    return length(pa - ba * h) - r;
}

fn sd_torus(p: vec3<f32>, major: f32, minor: f32) -> f32 {
    let q = vec2<f32>(length(p.xz) - major, p.y);
    return length(q) - minor;
}

fn sd_cylinder(p: vec3<f32>, r: f32, h: f32) -> f32 {
    let d = abs(vec2<f32>(length(p.xz), p.y)) - vec2<f32>(r, h);
    return min(max(d.x, d.y), 0.0) + length(max(d, vec2<f32>(0.0)));
}

fn sd_capped_cone(p: vec3<f32>, h: f32, r1: f32, r2: f32) -> f32 {
    let q = vec2<f32>(length(p.xz), p.y);
    let k1 = vec2<f32>(r2, h);
    let k2 = vec2<f32>(r2 - r1, 2.0 * h);
    let rim = select(r2, r1, q.y < 0.0);
    let ca = vec2<f32>(q.x - min(q.x, rim), abs(q.y) - h);
    let cb = q - k1 + k2 * clamp(dot(k1 - q, k2) / dot(k2, k2), 0.0, 1.0);
    let s = select(1.0, -1.0, cb.x < 0.0 && ca.y < 0.0);
    return s * sqrt(min(dot(ca, ca), dot(cb, cb)));
}

fn sd_octahedron(p_in: vec3<f32>, s: f32) -> f32 {
    let p = abs(p_in);
    let m = p.x + p.y + p.z - s;
    var q: vec3<f32>;
    if (3.0 * p.x < m) {
        q = p;
    } else if (3.0 * p.y < m) {
        q = p.yzx;
    } else if (3.0 * p.z < m) {
        q = p.zxy;
    } else {
        return m * 0.57735027;
    }
    let k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3<f32>(q.x, q.y - s + k, q.z - k));
}

fn sd_ellipsoid(p: vec3<f32>, r: vec3<f32>) -> f32 {
    let k0 = length(p / r);
    let k1 = length(p / (r * r));
    return k0 * (k0 - 1.0) / k1;
}

fn sd_plane(p: vec3<f32>, normal: vec3<f32>, offset: f32) -> f32 {
    return dot(p, normal) - offset;
}

// The polynomial smooth minimum (plan.rs, `Shape::Blend`).
fn smin(a: f32, b: f32, k: f32) -> f32 {
    let h = max(k - abs(a - b), 0.0) / k;
    return min(a, b) - h * h * k * 0.25;
}

// The distance below the guard's box: 0 inside it.
fn guard_distance(p: vec3<f32>, centre: vec3<f32>, half: vec3<f32>) -> f32 {
    let q = abs(p - centre) - half;
    return length(max(q, vec3<f32>(0.0)));
}

// One power-8 Mandelbulb step without trigonometry: `w^8 + c` of the spherical form
// `r^8 (sin b sin a, cos b, sin b cos a)`, `b = 8 acos(w.y / r)`, `a = 8 atan2(w.x, w.z)`.
// The same operations as the CPU tracer's (cpu/prims.rs `bulb8_plus`, which derives the
// polynomials): `k2 = rho^-7` from the reciprocal square root enters each product last,
// and sums after products are fused. On (or, where rho^7 underflows, within 8 rho r^7 of)
// the axis, x and z are 0: not 0 * inf, which is NaN; far out `k2` is 0 too.
const RHO2_MIN: f32 = 1.4551915e-11; // 2^-36
const RHO2_MAX: f32 = 34359738368.0; // 2^35

fn bulb8_plus(w: vec3<f32>, c: vec3<f32>) -> vec3<f32> {
    let x = w.x;
    let y = w.y;
    let z = w.z;
    let x2 = x * x;
    let y2 = y * y;
    let z2 = z * z;
    let x4 = x2 * x2;
    let y4 = y2 * y2;
    let z4 = z2 * z2;
    let x2z2 = x2 * z2;
    let x4z4 = x4 + z4;
    let rho2 = x2 + z2;
    let r = inverseSqrt(min(rho2, RHO2_MAX));
    let r2 = r * r;
    let r7 = (r2 * r2) * (r2 * r);
    let k2 = select(0.0, r7, rho2 >= RHO2_MIN && rho2 <= RHO2_MAX);
    let k1 = x4z4 + (y4 + fma(-6.0 * y2, rho2, x2z2 + x2z2));
    let k4 = rho2 - y2;
    let k14 = k1 * k4;
    let ax = x4 + fma(-6.0, x2z2, z4);
    let tx = ((x * y) * (z * (x2 - z2))) * ((64.0 * ax) * k14);
    // -az = (70 x^4 + z^4) z^4 + x^8 - 28 x^2 z^2 (x^4 + z^4).
    let neg_az = fma(-(28.0 * x2z2), x4z4, fma(fma(70.0, x4, z4), z4, x4 * x4));
    let tz = (-8.0 * y) * (neg_az * k14);
    let ty = fma((-16.0 * y2) * rho2, k4 * k4, c.y);
    return vec3<f32>(fma(tx, k2, c.x), fma(k1, k1, ty), fma(tz, k2, c.z));
}

fn sd_mandelbulb(p: vec3<f32>, centre: vec3<f32>, iterations: u32, bailout: f32, derivative: f32) -> f32 {
    let c = p - centre;
    var w = c;
    var m = dot(w, w);
    var dz = derivative;
    for (var i = 0u; i < iterations; i++) {
        dz = fma(8.0, m * m * m * sqrt(m) * dz, 1.0);
        w = bulb8_plus(w, c);
        m = dot(w, w);
        if (m > bailout) {
            break;
        }
    }
    return 0.25 * log(m) * sqrt(m) / dz;
}

// ---- camera and march (plan.rs, Marching) ----

fn camera_ray(i: u32, j: u32) -> vec3<f32> {
    let w = f32(frame.width);
    let h = f32(frame.height);
    let aspect = w / h;
    let x = (2.0 * (f32(i) + 0.5) / w - 1.0) * aspect * frame.tan_half_fov;
    let y = (1.0 - 2.0 * (f32(j) + 0.5) / h) * frame.tan_half_fov;
    return normalize(frame.forward + frame.right * x + frame.up * y);
}

// The scene at `p` in the march: the material only when the plan tracks it.
fn march_sample(p: vec3<f32>) -> MapHit {
    if (em_material_ids) {
        return em_map(p);
    }
    return MapHit(em_dist(p), SKY);
}

fn march(o: vec3<f32>, dir: vec3<f32>) -> RayHit {
    var t = 0.0;
    // Over-relaxation state: the previous point and its distance.
    var omega = em_relax;
    var t_prev = 0.0;
    var d_prev = 0.0;
    for (var k = 0u; k < em_max_steps; k++) {
        let p = o + t * dir;
        let s = march_sample(p);
        // The spheres of radius |d| around the two points do not overlap (the CPU tracer's
        // test: the radii are the unscaled distances, the gap the scaled step taken): the
        // long step may have skipped a surface. Back to the previous point, plain steps.
        if (omega > 1.0 && k > 0u && abs(s.d) + d_prev < omega * d_prev * em_step_factor) {
            omega = 1.0;
            t = t_prev + d_prev * em_step_factor;
            continue;
        }
        if (s.d < em_hit + em_hit_per_t * t) {
            var m = s.m;
            if (!em_material_ids) {
                m = em_map(p).m;
            }
            return RayHit(true, t, m);
        }
        if (length(p) > em_escape || t > em_far) {
            break;
        }
        t_prev = t;
        d_prev = s.d;
        t += omega * s.d * em_step_factor;
    }
    return RayHit(false, t, SKY);
}

// ---- normals ----

fn forward_normal(p: vec3<f32>) -> vec3<f32> {
    let d = em_dist(p);
    let e = em_normal_eps;
    return normalize(vec3<f32>(
        em_dist(p + vec3<f32>(e, 0.0, 0.0)) - d,
        em_dist(p + vec3<f32>(0.0, e, 0.0)) - d,
        em_dist(p + vec3<f32>(0.0, 0.0, e)) - d,
    ));
}

fn central_normal(p: vec3<f32>) -> vec3<f32> {
    let e = em_normal_eps;
    let ex = vec3<f32>(e, 0.0, 0.0);
    let ey = vec3<f32>(0.0, e, 0.0);
    let ez = vec3<f32>(0.0, 0.0, e);
    return normalize(vec3<f32>(
        em_dist(p + ex) - em_dist(p - ex),
        em_dist(p + ey) - em_dist(p - ey),
        em_dist(p + ez) - em_dist(p - ez),
    ));
}

fn surface_normal(p: vec3<f32>, m: u32) -> vec3<f32> {
    if (em_has_terrain && m == em_terrain_material) {
        if (em_analytic_normal) {
            let g = em_height(p.xz);
            return normalize(vec3<f32>(-g.y, 1.0, -g.z));
        }
        return central_normal(p);
    }
    return forward_normal(p);
}

// ---- shadows ----

// The soft shadow from `p` (normal `n`) towards unit `l` up to `limit`: 0 in shadow, 1 lit.
fn soft_shadow(p: vec3<f32>, n: vec3<f32>, l: vec3<f32>, limit: f32, k: f32, steps: u32) -> f32 {
    let q = p + n * em_ray_offset;
    // `s` runs `em_ray_offset` ahead of the distance travelled from `q`, as in the
    // reference renderer.
    var s = em_ray_offset;
    var x = q;
    var res = 1.0;
    var prev = 1e20;
    for (var i = 0u; i < steps; i++) {
        let h = em_dist(x);
        if (h < em_hit) {
            return 0.0;
        }
        // The closest approach between this sphere and the previous one.
        let y = h * h / (2.0 * prev);
        let d = sqrt(max(h * h - y * y, 0.0));
        if (s - y > 0.0) {
            res = min(res, k * d / (s - y));
        }
        prev = h;
        s += h;
        x += l * h;
        if (s > limit || length(x) > em_escape) {
            break;
        }
    }
    return res;
}

// The terrain-and-bounds shadow: 0 when a terrain sample along the sun ray lies below the
// ground or the ray meets a node's bounding sphere, else 1.
fn terrain_bounds_shadow(p: vec3<f32>, n: vec3<f32>) -> f32 {
    let o = p + n * em_ray_offset;
    if (em_has_terrain) {
        var reach = 1.0;
        for (var i = 0u; i < em_shadow_steps; i++) {
            let x = o + em_sun * (em_shadow_spacing * reach);
            if (x.y < em_height(x.xz).x) {
                return 0.0;
            }
            reach = 2.0 * reach + 1.0;
        }
    }
    if (em_bounds_shadow(o)) {
        return 0.0;
    }
    return 1.0;
}

// ---- shading ----

fn gamma_encode(c: vec3<f32>, gamma: f32) -> vec3<f32> {
    let x = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    // pow(0, g) is left undefined by some drivers: black stays black.
    return select(pow(x, vec3<f32>(gamma)), vec3<f32>(0.0), x <= vec3<f32>(0.0));
}

// The paper's local colour of a hit (before reflections), fog included.
fn paper_local(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>, t: f32, look: Look) -> vec3<f32> {
    let lit = em_lights(p, n, dir);
    let c = look.colour * (em_ambient + lit.diffuse) + vec3<f32>(em_specular * lit.specular);
    return c * exp(-em_fog * t * t * t);
}

// One light's diffuse and specular terms at `p` (called by the emitted `em_lights`).
fn point_light(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>, position: vec3<f32>, emission: f32) -> Lit {
    let to_light = position - p;
    let r = length(to_light);
    let l = to_light / r;
    let intensity = emission / r;
    var shadow = 1.0;
    if (em_paper_shadows) {
        shadow = soft_shadow(p, n, l, 3.0e38, em_shadow_k, em_max_steps);
    }
    let diffuse = max(dot(n, l), 0.0);
    let rv = max(dot(reflect(-l, n), -dir), 0.0);
    let spec = select(pow(rv, em_shininess), 0.0, rv <= 0.0);
    return Lit(diffuse * shadow * intensity, spec * shadow * intensity);
}

// The paper's model: the primary hit and up to `em_bounces` mirror bounces, each weighted
// by the product of the reflectivities (times the reflection scale) before it.
fn paper_shade(origin: vec3<f32>, primary: vec3<f32>) -> vec3<f32> {
    var colour = vec3<f32>(0.0);
    var weight = 1.0;
    var o = origin;
    var dir = primary;
    for (var bounce = 0u; bounce <= em_bounces; bounce++) {
        let r = march(o, dir);
        if (!r.hit) {
            break;
        }
        let p = o + r.t * dir;
        let n = surface_normal(p, r.m);
        let look = em_material(r.m);
        colour += weight * paper_local(p, n, dir, r.t, look);
        weight *= look.reflectivity * em_reflection_scale;
        if (weight <= 0.0) {
            break;
        }
        o = p + n * em_ray_offset;
        dir = reflect(dir, n);
    }
    return gamma_encode(colour, em_gamma);
}

fn world_shade(origin: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    var r = march(origin, dir);
    var p = origin + r.t * dir;
    // A ray that stopped without a hit while pointing below the horizon or ending below the
    // terrain's top can only be looking at the ground: it lands on the height field under
    // its end point instead of drawing sky through the hills.
    if (!r.hit && em_has_terrain && (dir.y < 0.0 || p.y < em_terrain_top)) {
        p = vec3<f32>(p.x, em_height(p.xz).x, p.z);
        r = RayHit(true, length(p - origin), em_terrain_material);
    }
    if (!r.hit) {
        return gamma_encode(mix(em_sky0, em_sky1, clamp(dir.y, 0.0, 1.0)), em_gamma);
    }
    let n = surface_normal(p, r.m);
    let look = em_material(r.m);
    let diff = max(dot(n, em_sun), 0.0);
    var sh = 1.0;
    if (em_full_shadow) {
        sh = soft_shadow(p, n, em_sun, em_far, em_shadow_k, em_shadow_steps);
    } else {
        sh = terrain_bounds_shadow(p, n);
    }
    let taps = em_ao_taps(p, n, r.t, r.m);
    var ao = 0.0;
    var sca = 1.0;
    for (var i = 0u; i < taps; i++) {
        let h = 0.01 + 0.12 * f32(i) / f32(max(taps - 1u, 1u));
        ao += (h - em_dist(p + h * n)) * sca;
        sca *= 0.95;
    }
    let occ = clamp(1.0 - 3.0 * ao, 0.0, 1.0);
    let ambient = 0.6 * mix(em_sky0, em_sky1, 0.5 + 0.5 * n.y) * occ;
    let c = look.colour * (em_sun_colour * diff * sh + ambient);
    let fogged = mix(c, em_sky0, 1.0 - exp(-em_fog * r.t));
    return gamma_encode(fogged, em_gamma);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if (gid.x >= frame.width || gid.y >= frame.height) {
        return;
    }
    let dir = camera_ray(gid.x, gid.y);
    var colour: vec3<f32>;
    if (em_paper) {
        // The reference renderer truncates to bytes; k / 255 reaches the target as k.
        colour = floor(clamp(paper_shade(frame.position, dir), vec3<f32>(0.0), vec3<f32>(1.0)) * 255.0) / 255.0;
    } else {
        colour = world_shade(frame.position, dir);
    }
    textureStore(out_image, vec2<i32>(gid.xy), vec4<f32>(colour, 1.0));
}
