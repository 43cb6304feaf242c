// Emitted by craterfield from a level graph: do not edit.
// graph fingerprint 45171a49ec2633b4, plan key b64c731989257ded.
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

var<private> em_poly1_v: array<vec3<f32>, 4> = array<vec3<f32>, 4>(
    vec3<f32>(-120.0f, -10.0f, 2.1367521e-5f),
    vec3<f32>(120.0f, -10.0f, 1.7361112e-5f),
    vec3<f32>(20.0f, -150.0f, 3.3783785e-5f),
    vec3<f32>(0.0f, -190.0f, 0.0005f),
);

fn em_poly1(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly1_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 3u;
    for (var i = 0u; i < 4u; i++) {
        let vi = em_poly1_v[i];
        let vj = em_poly1_v[j];
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

var<private> em_poly13_v: array<vec3<f32>, 3> = array<vec3<f32>, 3>(
    vec3<f32>(1260.0f, 1000.0f, 1.5898251e-5f),
    vec3<f32>(1300.0f, 1000.0f, 0.000625f),
    vec3<f32>(1280.0f, 1250.0f, 1.5898251e-5f),
);

fn em_poly13(px: vec3<f32>, py: vec3<f32>) -> vec3<f32> {
    let first = em_poly13_v[0];
    var d2 = em_len2(em_off(px, -first.x), em_off(py, -first.y));
    var inside = false;
    var j = 2u;
    for (var i = 0u; i < 3u; i++) {
        let vi = em_poly13_v[i];
        let vj = em_poly13_v[j];
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

fn em_rep18(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let kx = clamp(em_sat_i32(floor(px.x / 160.0f + 0.5)), -1073741824i, 1073741823i);
    let x0 = max(kx - 1, -1073741824i);
    let x1 = min(kx + 1, 1073741823i);
    var best = vec4<f32>(em_max(vec3<f32>(80.0f, 0.0, 0.0), em_len(vec3<f32>(0.0), em_max(em_max(vec3<f32>(-80.0f, 0.0, 0.0) - py, em_off(py, -80.0f)), vec3<f32>(0.0)))), 0.0);
    for (var ix = x0; ix <= x1; ix++) {
        let qx = em_off(px, -(f32(ix) * 160.0f));
        let qy = py;
        let r = em_c17(qx, qy);
        let g = em_max(r.xyz, em_off(em_abs(em_off(qx, -0.0f)), -20.0f));
        if (g.x < best.x) {
            best = vec4<f32>(g, r.w);
        }
    }
    return best;
}

fn em_c5(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d0 = em_ellipse(px, py, vec2<f32>(0.0f, 0.0f), vec2<f32>(160.0f, 40.0f));
    let d1 = em_poly1(px, py);
    let d2 = em_circle(px, py, vec2<f32>(60.0f, 30.0f), 45.0f);
    let d3 = d2 + em_noise(px * 0.025f, py * 0.025f, 11u) * 5.0f;
    let d4_0 = em_smin(d0, d1, 30.0f, 7.5f);
    let d4 = em_smin(d4_0, d3, 30.0f, 7.5f);
    let d5 = d4;
    return vec4<f32>(d5, 1.0f);
}

fn em_c7(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r7 = em_c5(px * 0.6666667f, py * 0.6666667f);
    let d7 = r7.xyz * 1.5f;
    return vec4<f32>(d7, 1.0f);
}

fn em_c9(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r9 = em_c5(px * 0.990268f + py * -0.13917312f, py * 0.990268f - px * -0.13917312f);
    let d9 = r9.xyz;
    return vec4<f32>(d9, 1.0f);
}

fn em_c17(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let d17 = em_off(em_aabox(px, py, vec2<f32>(0.0f, 0.0f), vec2<f32>(14.0f, 74.0f)), -6.0f);
    return vec4<f32>(d17, 0.0f);
}

fn em_c18(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r18 = em_rep18(px, py);
    let d18 = r18.xyz;
    return vec4<f32>(d18, 0.0f);
}

fn em_c21(px: vec3<f32>, py: vec3<f32>) -> vec4<f32> {
    let r6 = em_c5(em_off(px, -420.0f), em_off(py, -640.0f));
    let d6 = r6.xyz;
    let r8 = em_c7(em_off(px, -1280.0f), em_off(py, -780.0f));
    let d8 = r8.xyz;
    let r10 = em_c9(em_off(px, -2100.0f), em_off(py, -580.0f));
    let d10 = r10.xyz;
    let d11 = em_ring(px, py, vec2<f32>(860.0f, 1100.0f), 90.0f, 2.0f);
    let d12 = em_arc(px, py, vec2<f32>(1700.0f, 1050.0f), vec2<f32>(-0.9999999f, 0.0f), vec2<f32>(0.9396927f, -0.3420203f), vec2<f32>(112.76312f, -41.042435f), 120.0f, 1.5f);
    let d13 = em_poly13(px, py);
    let d14 = em_off(d13, -3.0f);
    let d15_0 = em_min(d11, d12);
    let d15 = em_min(d15_0, d14);
    let d16 = d15;
    let r19 = em_c18(em_off(px, -0.0f), em_off(py, -80.0f));
    let d19 = r19.xyz;
    let d20 = d19;
    let d21_0 = em_min(d6, d8);
    let d21_1 = em_min(d21_0, d10);
    let d21_2 = em_min(d21_1, d16);
    let m21_2 = select(2.0f, 1.0f, d21_1.x < d16.x);
    let d21 = em_min(d21_2, d20);
    let m21 = select(0.0f, m21_2, d21_2.x < d20.x);
    return vec4<f32>(d21, m21);
}

fn base_sample(p: vec2<f32>) -> vec4<f32> {
    return em_c21(vec3<f32>(p.x, 1.0, 0.0), vec3<f32>(p.y, 0.0, 1.0));
}
