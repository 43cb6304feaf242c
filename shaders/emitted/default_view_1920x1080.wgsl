// Emitted by craterfield from a level graph: do not edit.
// graph fingerprint 887fba6f40e99788, plan key 52ee41c30f5e3d6d.
// base_sample(p) = (distance, d/dx, d/dy, material) of the terrain graph at p.

// Value of a sub-graph culled as far outside the view: above any band.
const em_far: vec3<f32> = vec3<f32>(1e20f, 0.0f, 0.0f);

fn em_off(a: vec3<f32>, c: f32) -> vec3<f32> {
    return vec3<f32>(a.x + c, a.yz);
}

fn em_mul(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(a.x * b.x, a.yz * b.x + a.x * b.yz);
}

fn em_abs(a: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(abs(a.x), select(a.yz, -a.yz, a.x < 0.0));
}

fn em_sqrt(a: vec3<f32>) -> vec3<f32> {
    let v = sqrt(a.x);
    if (v > 0.0) {
        let k = 0.5 / v;
        return vec3<f32>(v, a.yz * k);
    }
    // The medial-axis case: a zero gradient rather than inf or NaN.
    return vec3<f32>(v, 0.0, 0.0);
}

fn em_min(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a.x < b.x);
}

fn em_max(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a.x > b.x);
}

fn em_minf(a: f32, b: f32) -> f32 {
    return select(b, a, a < b);
}

fn em_maxf(a: f32, b: f32) -> f32 {
    return select(b, a, a > b);
}

fn em_len2(x: vec3<f32>, y: vec3<f32>) -> vec3<f32> {
    return em_mul(x, x) + em_mul(y, y);
}

fn em_len(x: vec3<f32>, y: vec3<f32>) -> vec3<f32> {
    return em_sqrt(em_len2(x, y));
}

fn em_clamp01(t: vec3<f32>) -> vec3<f32> {
    return em_min(em_max(t, vec3<f32>(0.0)), vec3<f32>(1.0, 0.0, 0.0));
}

fn em_seg2(wx: vec3<f32>, wy: vec3<f32>, e: vec2<f32>, inv_e2: f32) -> vec3<f32> {
    // Squared distance from w = p - a to the segment a .. a + e.
    let t = em_clamp01((wx * e.x + wy * e.y) * inv_e2);
    return em_len2(wx - t * e.x, wy - t * e.y);
}

fn em_circle(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, r: f32) -> vec3<f32> {
    return em_off(em_len(em_off(px, -c.x), em_off(py, -c.y)), -r);
}

fn em_capsule(px: vec3<f32>, py: vec3<f32>, a: vec2<f32>, ba: vec2<f32>, inv_ba2: f32, r: f32) -> vec3<f32> {
    return em_off(em_sqrt(em_seg2(em_off(px, -a.x), em_off(py, -a.y), ba, inv_ba2)), -r);
}

fn em_ellipse_q(p: vec2<f32>, r: vec2<f32>) -> vec2<f32> {
    let a = r.x;
    let b = r.y;
    var tx = 0.70710677f;
    var ty = 0.70710677f;
    let ab = a * a - b * b;
    for (var i = 0; i < 5; i++) {
        let x = a * tx;
        let y = b * ty;
        let ex = ab * (tx * tx * tx) / a;
        let ey = -ab * (ty * ty * ty) / b;
        let rx = x - ex;
        let ry = y - ey;
        let qx = p.x - ex;
        let qy = p.y - ey;
        let rl = sqrt(rx * rx + ry * ry);
        let ql = sqrt(qx * qx + qy * qy);
        if (ql > 0.0) {
            tx = em_minf(em_maxf((qx * rl / ql + ex) / a, 0.0), 1.0);
            ty = em_minf(em_maxf((qy * rl / ql + ey) / b, 0.0), 1.0);
        }
        let t = sqrt(tx * tx + ty * ty);
        if (t > 0.0) {
            tx = tx / t;
            ty = ty / t;
        }
    }
    return vec2<f32>(a * tx, b * ty);
}

fn em_ellipse(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, radii: vec2<f32>) -> vec3<f32> {
    let lx = em_off(px, -c.x);
    let ly = em_off(py, -c.y);
    let q = em_ellipse_q(vec2<f32>(abs(lx.x), abs(ly.x)), radii);
    let qx = select(q.x, -q.x, lx.x < 0.0);
    let qy = select(q.y, -q.y, ly.x < 0.0);
    // The closest point is held constant: the gradient is (p - q) / |p - q|.
    let d = em_len(em_off(lx, -qx), em_off(ly, -qy));
    let nx = lx.x / radii.x;
    let ny = ly.x / radii.y;
    return select(d, -d, nx * nx + ny * ny < 1.0);
}

fn em_ring(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, r: f32, half_width: f32) -> vec3<f32> {
    return em_off(em_abs(em_off(em_len(em_off(px, -c.x), em_off(py, -c.y)), -r)), -half_width);
}

fn em_arc(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, rot: vec2<f32>, sc: vec2<f32>, tip: vec2<f32>, ra: f32, rb: f32) -> vec3<f32> {
    let lx = em_off(px, -c.x);
    let ly = em_off(py, -c.y);
    let qx = em_abs(lx * rot.x + ly * rot.y);
    let qy = ly * rot.x - lx * rot.y;
    var d: vec3<f32>;
    if (sc.y * qx.x > sc.x * qy.x) {
        d = em_len(em_off(qx, -tip.x), em_off(qy, -tip.y));
    } else {
        d = em_abs(em_off(em_len(qx, qy), -ra));
    }
    return em_off(d, -rb);
}

fn em_smin(a: vec3<f32>, b: vec3<f32>, k: f32, k_quarter: f32) -> vec3<f32> {
    let m = em_min(a, b);
    let hk = em_off(em_abs(a - b) * -1.0, k);
    if (hk.x > 0.0) {
        let h = hk / k;
        return m - em_mul(h, h) * k_quarter;
    }
    return m;
}

fn em_sat_i32(v: f32) -> i32 {
    // Rust's saturating `as i32`: NaN gives 0, out-of-range values the nearest end.
    if (v != v) {
        return 0;
    }
    if (v >= 2147483648.0) {
        return 2147483647;
    }
    return i32(max(v, -2147483648.0));
}

fn em_lattice(ix: i32, iy: i32, seed: u32) -> f32 {
    var h = bitcast<u32>(ix) * 0x8da6b343u + bitcast<u32>(iy) * 0xd8163841u + seed * 0xcb1ab31fu + 0x9e3779b9u;
    h = h ^ (h >> 15u);
    h = h * 0x2c1b3c6du;
    h = h ^ (h >> 12u);
    h = h * 0x297a2d39u;
    h = h ^ (h >> 15u);
    // 24 bits fit f32 exactly; the scale is a power of two.
    return f32(h >> 8u) * 1.1920929e-7f - 1.0;
}

fn em_fade(t: vec3<f32>) -> vec3<f32> {
    return em_mul(em_mul(t, t), em_off(t * -2.0, 3.0));
}

fn em_noise(x: vec3<f32>, y: vec3<f32>, seed: u32) -> vec3<f32> {
    let fx0 = floor(x.x);
    let fy0 = floor(y.x);
    let ix = em_sat_i32(fx0);
    let iy = em_sat_i32(fy0);
    let ux = em_fade(em_off(x, -fx0));
    let uy = em_fade(em_off(y, -fy0));
    // i32 addition wraps at run time, like the CPU's wrapping_add.
    let v00 = em_lattice(ix, iy, seed);
    let v10 = em_lattice(ix + 1, iy, seed);
    let v01 = em_lattice(ix, iy + 1, seed);
    let v11 = em_lattice(ix + 1, iy + 1, seed);
    let bottom = em_off(ux * (v10 - v00), v00);
    let top = em_off(ux * (v11 - v01), v01);
    return bottom + em_mul(uy, top - bottom);
}

fn em_hp_index(x: f32, x0: f32, dx: f32, segments: u32) -> u32 {
    // Index of the segment whose x-range holds x, clamped to 0 .. segments - 1.
    let f = floor((x - x0) / dx);
    if (f > 0.0) {
        return u32(min(f, f32(segments - 1u)));
    }
    return 0u;
}

var<private> em_hp0_v: array<vec3<f32>, 61> = array<vec3<f32>, 61>(
    vec3<f32>(0.0f, 610.6f, 0.00012093121f),
    vec3<f32>(64.0f, 675.2f, 0.00016313179f),
    vec3<f32>(128.0f, 630.1f, 0.00024271784f),
    vec3<f32>(192.0f, 635.0f, 0.00022943987f),
    vec3<f32>(256.0f, 618.8f, 0.00023061401f),
    vec3<f32>(320.0f, 634.3f, 0.00016481627f),
    vec3<f32>(384.0f, 678.7f, 8.819885e-5f),
    vec3<f32>(448.0f, 593.6f, 8.598276e-5f),
    vec3<f32>(512.0f, 506.8f, 8.458514e-5f),
    vec3<f32>(576.0f, 418.9f, 0.00010495726f),
    vec3<f32>(640.0f, 345.2f, 0.00013891805f),
    vec3<f32>(704.0f, 400.9f, 0.00022857715f),
    vec3<f32>(768.0f, 417.6f, 0.00024157157f),
    vec3<f32>(832.0f, 411.0f, 0.0002396105f),
    vec3<f32>(896.0f, 419.8f, 0.00018001026f),
    vec3<f32>(960.0f, 381.6f, 9.88361e-5f),
    vec3<f32>(1024.0f, 459.2f, 5.7963978e-5f),
    vec3<f32>(1088.0f, 573.9f, 0.00012614149f),
    vec3<f32>(1152.0f, 635.8f, 0.00011776221f),
    vec3<f32>(1216.0f, 702.1f, 0.00015229775f),
    vec3<f32>(1280.0f, 652.4f, 0.00015978908f),
    vec3<f32>(1344.0f, 605.9f, 0.00021226738f),
    vec3<f32>(1408.0f, 630.7f, 0.00022679385f),
    vec3<f32>(1472.0f, 613.0f, 0.00023077843f),
    vec3<f32>(1536.0f, 628.4f, 0.00013014034f),
    vec3<f32>(1600.0f, 568.5f, 4.39453e-5f),
    vec3<f32>(1664.0f, 431.9f, 0.00015299037f),
    vec3<f32>(1728.0f, 382.5f, 0.000173346f),
    vec3<f32>(1792.0f, 341.6f, 0.00019040366f),
    vec3<f32>(1856.0f, 375.6f, 0.0001067605f),
    vec3<f32>(1920.0f, 448.2f, 0.00020326482f),
    vec3<f32>(1984.0f, 419.5f, 0.00023930258f),
    vec3<f32>(2048.0f, 428.6f, 0.00022875129f),
    vec3<f32>(2112.0f, 445.2f, 0.00016602445f),
    vec3<f32>(2176.0f, 489.1f, 4.0884268e-5f),
    vec3<f32>(2240.0f, 631.8f, 0.00014526778f),
    vec3<f32>(2304.0f, 684.6f, 0.00024293957f),
    vec3<f32>(2368.0f, 689.1f, 0.00022142264f),
    vec3<f32>(2432.0f, 668.6f, 8.926588e-5f),
    vec3<f32>(2496.0f, 584.3f, 0.00023061401f),
    vec3<f32>(2560.0f, 599.8f, 0.00023725859f),
    vec3<f32>(2624.0f, 610.7f, 0.00016002658f),
    vec3<f32>(2688.0f, 564.3f, 0.00017605512f),
    vec3<f32>(2752.0f, 524.5f, 4.7805504e-5f),
    vec3<f32>(2816.0f, 394.8f, 0.000117578464f),
    vec3<f32>(2880.0f, 328.4f, 0.00019701749f),
    vec3<f32>(2944.0f, 359.7f, 0.00022340128f),
    vec3<f32>(3008.0f, 379.2f, 9.83825e-5f),
    vec3<f32>(3072.0f, 457.1f, 0.00023919785f),
    vec3<f32>(3136.0f, 466.3f, 0.00019798806f),
    vec3<f32>(3200.0f, 435.4f, 0.00012438055f),
    vec3<f32>(3264.0f, 498.2f, 0.00014750918f),
    vec3<f32>(3328.0f, 550.0f, 6.848259e-5f),
    vec3<f32>(3392.0f, 652.5f, 9.6150485e-5f),
    vec3<f32>(3456.0f, 731.9f, 0.00013956417f),
    vec3<f32>(3520.0f, 676.5f, 0.00018669778f),
    vec3<f32>(3584.0f, 641.0f, 0.00013467485f),
    vec3<f32>(3648.0f, 583.3f, 0.00018966374f),
    vec3<f32>(3712.0f, 549.0f, 0.0001755618f),
    vec3<f32>(3776.0f, 589.0f, 0.00012832624f),
    vec3<f32>(3840.0f, 528.2f, 0.0f),
);

fn em_hp0(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let x = px.x;
    let y = py.x;
    // At or left of the first sample (and for NaN) the ground is the first height.
    var ground = 610.6f;
    if (x >= 3840.0f) {
        ground = 528.2f;
    } else if (x > 0.0f) {
        let s = em_hp_index(x, 0.0f, 64.0f, 60u);
        let a = em_hp0_v[s];
        let b = em_hp0_v[s + 1u];
        ground = a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x));
    }
    let reach = abs(y - ground);
    // The largest finite f32 stands in for the CPU's infinity: every segment is nearer.
    var d2 = vec3<f32>(3.4028234663852886e38f, 0.0, 0.0);
    if (x < 0.0f) {
        let dy = em_off(py, -610.6f);
        d2 = em_mul(dy, dy);
    }
    if (x > 3840.0f) {
        let dy = em_off(py, -528.2f);
        d2 = em_min(d2, em_mul(dy, dy));
    }
    let lo0 = em_hp_index(x - reach, 0.0f, 64.0f, 60u);
    let lo = select(lo0 - 1u, 0u, lo0 == 0u);
    let hi = min(em_hp_index(x + reach, 0.0f, 64.0f, 60u) + 1u, 59u);
    for (var s = lo; s <= hi; s++) {
        let a = em_hp0_v[s];
        let b = em_hp0_v[s + 1u];
        d2 = em_min(d2, em_seg2(em_off(px, -a.x), em_off(py, -a.y), b.xy - a.xy, a.z));
    }
    let d = em_sqrt(d2);
    return select(d, -d, y < ground);
}

fn em_c42(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d0 = em_hp0(px, py);
    let d1 = d0;
    let d8 = em_arc(px, py, vec2<f32>(640.0f, 345.0f), vec2<f32>(0.9999999f, 0.0f), vec2<f32>(0.96592575f, 0.25881916f), vec2<f32>(164.20738f, 43.999256f), 170.0f, 8.0f);
    let d9 = d8;
    let d14 = em_min(d1, d9);
    let m14 = select(1.0f, 0.0f, d1.x < d9.x);
    let d15 = em_capsule(px, py, vec2<f32>(900.0f, 250.0f), vec2<f32>(550.0f, 80.0f), 3.2372936e-6f, 42.0f);
    let d16 = em_capsule(px, py, vec2<f32>(1450.0f, 330.0f), vec2<f32>(200.0f, -130.0f), 1.7574692e-5f, 36.0f);
    let d21 = em_ring(px, py, vec2<f32>(200.0f, 330.0f), 110.0f, 14.0f);
    let d22_0 = em_min(d15, d16);
    let d22 = em_min(d22_0, d21);
    let d23 = em_max(d14, -d22);
    let d24 = em_ellipse(px, py, vec2<f32>(1050.0f, 1120.0f), vec2<f32>(170.0f, 55.0f));
    let d25 = em_circle(px, py, vec2<f32>(1110.0f, 1160.0f), 55.0f);
    let d26 = em_ellipse(px, py, vec2<f32>(980.0f, 1090.0f), vec2<f32>(90.0f, 40.0f));
    let d27_0 = em_smin(d24, d25, 50.0f, 12.5f);
    let d27 = em_smin(d27_0, d26, 50.0f, 12.5f);
    let d28 = d27 + em_noise(px * 0.016666668f, py * 0.016666668f, 3u) * 6.0f;
    let d35 = d28;
    let d36 = d35;
    let d40 = em_far;
    let d41 = d40;
    let d42_0 = em_min(d23, d36);
    let m42_0 = select(2.0f, m14, d23.x < d36.x);
    let d42 = em_min(d42_0, d41);
    let m42 = select(3.0f, m42_0, d42_0.x < d41.x);
    return vec4<f32>(d42, m42);
}

fn base_sample(p: vec2<f32>) -> vec4<f32> {
    return em_c42(vec3<f32>(p.x, 1.0, 0.0), vec3<f32>(p.y, 0.0, 1.0));
}
