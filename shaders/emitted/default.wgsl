// Emitted by craterfield from a level graph: do not edit.
// graph fingerprint 887fba6f40e99788, plan key 5db06a73f312c36e.
// base_sample(p) = (distance, d/dx, d/dy, material) of the terrain graph at p.

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

fn em_aabox(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, h: vec2<f32>) -> vec3<f32> {
    let qx = em_off(em_abs(em_off(px, -c.x)), -h.x);
    let qy = em_off(em_abs(em_off(py, -c.y)), -h.y);
    let z = vec3<f32>(0.0);
    return em_len(em_max(qx, z), em_max(qy, z)) + em_min(em_max(qx, qy), z);
}

fn em_obox(px: vec3<f32>, py: vec3<f32>, mid: vec2<f32>, dir: vec2<f32>, half: vec2<f32>) -> vec3<f32> {
    let qx = em_off(px, -mid.x);
    let qy = em_off(py, -mid.y);
    return em_aabox(qx * dir.x + qy * dir.y, qy * dir.x - qx * dir.y, vec2<f32>(0.0), half);
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

fn em_sin_turns(t: f32) -> f32 {
    var r = t - floor(t + 0.5);
    if (r > 0.25) {
        r = 0.5 - r;
    } else if (r < -0.25) {
        r = -0.5 - r;
    }
    let x = r * 6.2831855f;
    let x2 = x * x;
    var s = -2.5052108e-8f;
    s = s * x2 + 2.7557319e-6f;
    s = s * x2 + -0.0001984127f;
    s = s * x2 + 0.008333333f;
    s = s * x2 + -0.16666667f;
    s = s * x2 + 1.0f;
    return x * s;
}

fn em_wave(t: vec3<f32>) -> vec3<f32> {
    // sin(2 pi t) and its derivative 2 pi cos(2 pi t), by the CPU's polynomial.
    return vec3<f32>(em_sin_turns(t.x), t.yz * (6.2831855f * em_sin_turns(t.x + 0.25)));
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

var<private> em_poly2_v: array<vec3<f32>, 6> = array<vec3<f32>, 6>(
    vec3<f32>(2540.0f, 560.0f, 3.8844002e-5f),
    vec3<f32>(2540.0f, 622.0f, 0.0002601457f),
    vec3<f32>(2700.0f, 612.0f, 3.8910504e-5f),
    vec3<f32>(2830.0f, 596.0f, 5.8288646e-5f),
    vec3<f32>(2850.0f, 572.0f, 0.0010245901f),
    vec3<f32>(2700.0f, 548.0f, 4.3335065e-5f),
);

fn em_poly2(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly2_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 5u;
    for (var i = 0u; i < 6u; i++) {
        let vi = em_poly2_v[i];
        let vj = em_poly2_v[j];
        let e = vj.xy - vi.xy;
        let wx = em_off(px, -vi.x);
        let wy = em_off(py, -vi.y);
        d2 = em_min(d2, em_seg2(wx, wy, e, vi.z));
        // Crossing parity, so the winding does not matter.
        let c1 = py.x >= vi.y;
        let c2 = py.x < vj.y;
        let c3 = e.x * wy.x > e.y * wx.x;
        if ((c1 && c2 && c3) || (!c1 && !c2 && !c3)) {
            inside = !inside;
        }
        j = i;
    }
    let d = em_sqrt(d2);
    return select(d, -d, inside);
}

var<private> em_poly3_v: array<vec3<f32>, 3> = array<vec3<f32>, 3>(
    vec3<f32>(-1.25f, 16.0f, 0.00024404752f),
    vec3<f32>(1.25f, 16.0f, 0.16f),
    vec3<f32>(0.0f, -48.0f, 0.00024404752f),
);

fn em_poly3(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly3_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 2u;
    for (var i = 0u; i < 3u; i++) {
        let vi = em_poly3_v[i];
        let vj = em_poly3_v[j];
        let e = vj.xy - vi.xy;
        let wx = em_off(px, -vi.x);
        let wy = em_off(py, -vi.y);
        d2 = em_min(d2, em_seg2(wx, wy, e, vi.z));
        // Crossing parity, so the winding does not matter.
        let c1 = py.x >= vi.y;
        let c2 = py.x < vj.y;
        let c3 = e.x * wy.x > e.y * wx.x;
        if ((c1 && c2 && c3) || (!c1 && !c2 && !c3)) {
            inside = !inside;
        }
        j = i;
    }
    let d = em_sqrt(d2);
    return select(d, -d, inside);
}

fn em_rep4(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let kx = clamp(em_sat_i32(floor(px.x / 24.0f + 0.5)), 0i, 7i);
    let x0 = max(kx - 1, 0i);
    let x1 = min(kx + 1, 7i);
    var best = vec4<f32>(em_max(vec3<f32>(12.0f, 0.0, 0.0), em_len(em_max(em_max(vec3<f32>(-1.25f, 0.0, 0.0) - px, em_off(px, -169.25f)), vec3<f32>(0.0)), em_max(em_max(vec3<f32>(-48.0f, 0.0, 0.0) - py, em_off(py, -16.0f)), vec3<f32>(0.0)))), 0.0);
    for (var ix = x0; ix <= x1; ix++) {
        let qx = em_off(px, -(f32(ix) * 24.0f));
        let qy = py;
        let r = em_c3(qx, qy);
        let g = em_max(r.xyz, em_off(em_abs(em_off(qx, -0.0f)), -1.25f));
        if (g.x < best.x) {
            best = vec4<f32>(g, r.w);
        }
    }
    return best;
}

var<private> em_poly29_v: array<vec3<f32>, 5> = array<vec3<f32>, 5>(
    vec3<f32>(1750.0f, 1180.0f, 0.00025f),
    vec3<f32>(1990.0f, 1190.0f, 1.7331022e-5f),
    vec3<f32>(2040.0f, 1230.0f, 0.00024390244f),
    vec3<f32>(1900.0f, 1262.0f, 4.84872e-5f),
    vec3<f32>(1770.0f, 1240.0f, 5.752416e-5f),
);

fn em_poly29(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly29_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 4u;
    for (var i = 0u; i < 5u; i++) {
        let vi = em_poly29_v[i];
        let vj = em_poly29_v[j];
        let e = vj.xy - vi.xy;
        let wx = em_off(px, -vi.x);
        let wy = em_off(py, -vi.y);
        d2 = em_min(d2, em_seg2(wx, wy, e, vi.z));
        // Crossing parity, so the winding does not matter.
        let c1 = py.x >= vi.y;
        let c2 = py.x < vj.y;
        let c3 = e.x * wy.x > e.y * wx.x;
        if ((c1 && c2 && c3) || (!c1 && !c2 && !c3)) {
            inside = !inside;
        }
        j = i;
    }
    let d = em_sqrt(d2);
    return select(d, -d, inside);
}

var<private> em_poly31_v: array<vec3<f32>, 3> = array<vec3<f32>, 3>(
    vec3<f32>(-1.5f, -4.0f, 0.00062412233f),
    vec3<f32>(1.5f, -4.0f, 0.11111111f),
    vec3<f32>(0.0f, 36.0f, 0.00062412233f),
);

fn em_poly31(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly31_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 2u;
    for (var i = 0u; i < 3u; i++) {
        let vi = em_poly31_v[i];
        let vj = em_poly31_v[j];
        let e = vj.xy - vi.xy;
        let wx = em_off(px, -vi.x);
        let wy = em_off(py, -vi.y);
        d2 = em_min(d2, em_seg2(wx, wy, e, vi.z));
        // Crossing parity, so the winding does not matter.
        let c1 = py.x >= vi.y;
        let c2 = py.x < vj.y;
        let c3 = e.x * wy.x > e.y * wx.x;
        if ((c1 && c2 && c3) || (!c1 && !c2 && !c3)) {
            inside = !inside;
        }
        j = i;
    }
    let d = em_sqrt(d2);
    return select(d, -d, inside);
}

fn em_rep32(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let kx = clamp(em_sat_i32(floor(px.x / 20.0f + 0.5)), 0i, 8i);
    let x0 = max(kx - 1, 0i);
    let x1 = min(kx + 1, 8i);
    var best = vec4<f32>(em_max(vec3<f32>(10.0f, 0.0, 0.0), em_len(em_max(em_max(vec3<f32>(-1.5f, 0.0, 0.0) - px, em_off(px, -161.5f)), vec3<f32>(0.0)), em_max(em_max(vec3<f32>(-4.0f, 0.0, 0.0) - py, em_off(py, -36.0f)), vec3<f32>(0.0)))), 0.0);
    for (var ix = x0; ix <= x1; ix++) {
        let qx = em_off(px, -(f32(ix) * 20.0f));
        let qy = py;
        let r = em_c31(qx, qy);
        let g = em_max(r.xyz, em_off(em_abs(em_off(qx, -0.0f)), -1.5f));
        if (g.x < best.x) {
            best = vec4<f32>(g, r.w);
        }
    }
    return best;
}

fn em_c3(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d3 = em_poly3(px, py);
    return vec4<f32>(d3, 0.0f);
}

fn em_c4(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r4 = em_rep4(px, py);
    let d4 = r4.xyz;
    return vec4<f32>(d4, 0.0f);
}

fn em_c31(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d31 = em_poly31(px, py);
    return vec4<f32>(d31, 0.0f);
}

fn em_c32(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r32 = em_rep32(px, py);
    let d32 = r32.xyz;
    return vec4<f32>(d32, 0.0f);
}

fn em_c42(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d0 = em_hp0(px, py);
    let d1 = d0;
    let d2 = em_poly2(px, py);
    let r5 = em_c4(em_off(px, -2640.0f), em_off(py, -560.0f));
    let d5 = r5.xyz;
    let d6 = em_min(d2, d5);
    let d7 = d6;
    let d8 = em_arc(px, py, vec2<f32>(640.0f, 345.0f), vec2<f32>(0.9999999f, 0.0f), vec2<f32>(0.96592575f, 0.25881916f), vec2<f32>(164.20738f, 43.999256f), 170.0f, 8.0f);
    let d9 = d8;
    let d10 = em_circle(px, py, vec2<f32>(3560.0f, 700.0f), 120.0f);
    let d11 = d10 + em_wave(em_off(px * 0.013531646f + py * 0.0078125f, 0.0f)) * 4.0f;
    let d12 = d11 + em_noise(px * 0.0125f, py * 0.0125f, 7u) * 6.0f;
    let d13 = d12;
    let d14_0 = em_min(d1, d7);
    let m14_0 = select(1.0f, 0.0f, d1.x < d7.x);
    let d14_1 = em_min(d14_0, d9);
    let m14_1 = select(1.0f, m14_0, d14_0.x < d9.x);
    let d14 = em_min(d14_1, d13);
    let m14 = select(1.0f, m14_1, d14_1.x < d13.x);
    let d15 = em_capsule(px, py, vec2<f32>(900.0f, 250.0f), vec2<f32>(550.0f, 80.0f), 3.2372936e-6f, 42.0f);
    let d16 = em_capsule(px, py, vec2<f32>(1450.0f, 330.0f), vec2<f32>(200.0f, -130.0f), 1.7574692e-5f, 36.0f);
    let d17 = em_ellipse(px, py, vec2<f32>(2350.0f, 380.0f), vec2<f32>(200.0f, 95.0f));
    let d18 = em_circle(px, py, vec2<f32>(2200.0f, 330.0f), 70.0f);
    let d19 = em_smin(d17, d18, 40.0f, 10.0f);
    let d20 = em_circle(px, py, vec2<f32>(3400.0f, 420.0f), 60.0f);
    let d21 = em_ring(px, py, vec2<f32>(200.0f, 330.0f), 110.0f, 14.0f);
    let d22_0 = em_min(d15, d16);
    let d22_1 = em_min(d22_0, d19);
    let d22_2 = em_min(d22_1, d20);
    let d22 = em_min(d22_2, d21);
    let d23 = em_max(d14, -d22);
    let d24 = em_ellipse(px, py, vec2<f32>(1050.0f, 1120.0f), vec2<f32>(170.0f, 55.0f));
    let d25 = em_circle(px, py, vec2<f32>(1110.0f, 1160.0f), 55.0f);
    let d26 = em_ellipse(px, py, vec2<f32>(980.0f, 1090.0f), vec2<f32>(90.0f, 40.0f));
    let d27_0 = em_smin(d24, d25, 50.0f, 12.5f);
    let d27 = em_smin(d27_0, d26, 50.0f, 12.5f);
    let d28 = d27 + em_noise(px * 0.016666668f, py * 0.016666668f, 3u) * 6.0f;
    let d29 = em_poly29(px, py);
    let d30 = em_off(em_aabox(px, py, vec2<f32>(2700.0f, 1050.0f), vec2<f32>(98.0f, 18.0f)), -12.0f);
    let r33 = em_c32(em_off(px, -2620.0f), em_off(py, -1072.0f));
    let d33 = r33.xyz;
    let d34 = em_ring(px, py, vec2<f32>(3350.0f, 1180.0f), 80.0f, 1.5f);
    let d35_0 = em_min(d28, d29);
    let d35_1 = em_min(d35_0, d30);
    let d35_2 = em_min(d35_1, d33);
    let d35 = em_min(d35_2, d34);
    let d36 = d35;
    let d37 = em_obox(px, py, vec2<f32>(1485.0f, 1172.5f), vec2<f32>(0.993331f, 0.11529735f), vec2<f32>(281.87985f, 1.0f));
    let d38 = em_obox(px, py, vec2<f32>(2315.0f, 1140.0f), vec2<f32>(0.9670745f, -0.2544933f), vec2<f32>(294.70325f, 0.75f));
    let d39 = em_obox(px, py, vec2<f32>(3070.0f, 545.0f), vec2<f32>(0.9852118f, -0.17134118f), vec2<f32>(233.45235f, 1.5f));
    let d40_0 = em_min(d37, d38);
    let d40 = em_min(d40_0, d39);
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
