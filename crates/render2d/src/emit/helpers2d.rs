//! The WGSL library the 2D emitter calls: dual-number arithmetic and the primitive formulas,
//! each a line-for-line transcription of its CPU twin in `field2d` (`detmath`, `primitives`,
//! `noise`), so the GPU computes the same operations in the same order.
//!
//! A dual number is a `vec3<f32>`: value, d/dx, d/dy. Selects (`min`, `max`, `abs`, clamps)
//! compare values and carry the chosen operand's gradient, as the CPU `Dual` does. Only the
//! helpers an emitted module calls are included ([`used_helpers`]).

use craterfield_core::det::math::TAU;
use craterfield_field::primitives::ELLIPSE_ITERATIONS;

use craterfield_wgsl::{f32_expr, f32_literal, u32_literal};

/// One module-scope helper: its name and WGSL text.
pub(crate) struct Helper {
    pub name: &'static str,
    pub text: String,
}

/// The literal of an `f32` constant of the CPU code (always finite).
fn lit(v: f32) -> String {
    f32_literal(v).unwrap_or_else(|_| f32_expr(v))
}

/// Every helper, in the order they are written out.
pub(crate) fn all_helpers() -> Vec<Helper> {
    let mut out = vec![
        helper(
            "em_far",
            format!(
                "// Value of a sub-graph culled as far outside the view: above any band.\n\
                 const em_far: vec3<f32> = vec3<f32>({}, 0.0f, 0.0f);\n",
                lit(super::cull::FAR)
            ),
        ),
        helper(
            "em_off",
            fn_text(
                "em_off(a: vec3<f32>, c: f32) -> vec3<f32>",
                "return vec3<f32>(a.x + c, a.yz);",
            ),
        ),
        helper(
            "em_mul",
            fn_text(
                "em_mul(a: vec3<f32>, b: vec3<f32>) -> vec3<f32>",
                "return vec3<f32>(a.x * b.x, a.yz * b.x + a.x * b.yz);",
            ),
        ),
        helper(
            "em_abs",
            fn_text(
                "em_abs(a: vec3<f32>) -> vec3<f32>",
                "return vec3<f32>(abs(a.x), select(a.yz, -a.yz, a.x < 0.0));",
            ),
        ),
        helper(
            "em_sqrt",
            fn_text(
                "em_sqrt(a: vec3<f32>) -> vec3<f32>",
                "let v = sqrt(a.x);\n    \
                 if (v > 0.0) {\n        let k = 0.5 / v;\n        return vec3<f32>(v, a.yz * k);\n    }\n    \
                 // The medial-axis case: a zero gradient rather than inf or NaN.\n    \
                 return vec3<f32>(v, 0.0, 0.0);",
            ),
        ),
        helper(
            "em_min",
            fn_text(
                "em_min(a: vec3<f32>, b: vec3<f32>) -> vec3<f32>",
                "return select(b, a, a.x < b.x);",
            ),
        ),
        helper(
            "em_max",
            fn_text(
                "em_max(a: vec3<f32>, b: vec3<f32>) -> vec3<f32>",
                "return select(b, a, a.x > b.x);",
            ),
        ),
        helper(
            "em_minf",
            fn_text(
                "em_minf(a: f32, b: f32) -> f32",
                "return select(b, a, a < b);",
            ),
        ),
        helper(
            "em_maxf",
            fn_text(
                "em_maxf(a: f32, b: f32) -> f32",
                "return select(b, a, a > b);",
            ),
        ),
        helper(
            "em_len2",
            fn_text(
                "em_len2(x: vec3<f32>, y: vec3<f32>) -> vec3<f32>",
                "return em_mul(x, x) + em_mul(y, y);",
            ),
        ),
        helper(
            "em_len",
            fn_text(
                "em_len(x: vec3<f32>, y: vec3<f32>) -> vec3<f32>",
                "return em_sqrt(em_len2(x, y));",
            ),
        ),
        helper(
            "em_clamp01",
            fn_text(
                "em_clamp01(t: vec3<f32>) -> vec3<f32>",
                "return em_min(em_max(t, vec3<f32>(0.0)), vec3<f32>(1.0, 0.0, 0.0));",
            ),
        ),
        helper(
            "em_seg2",
            fn_text(
                "em_seg2(wx: vec3<f32>, wy: vec3<f32>, e: vec2<f32>, inv_e2: f32) -> vec3<f32>",
                "// Squared distance from w = p - a to the segment a .. a + e.\n    \
                 let t = em_clamp01((wx * e.x + wy * e.y) * inv_e2);\n    \
                 return em_len2(wx - t * e.x, wy - t * e.y);",
            ),
        ),
        helper(
            "em_circle",
            fn_text(
                "em_circle(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, r: f32) -> vec3<f32>",
                "return em_off(em_len(em_off(px, -c.x), em_off(py, -c.y)), -r);",
            ),
        ),
        helper(
            "em_aabox",
            fn_text(
                "em_aabox(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, h: vec2<f32>) -> vec3<f32>",
                "let qx = em_off(em_abs(em_off(px, -c.x)), -h.x);\n    \
                 let qy = em_off(em_abs(em_off(py, -c.y)), -h.y);\n    \
                 let z = vec3<f32>(0.0);\n    \
                 return em_len(em_max(qx, z), em_max(qy, z)) + em_min(em_max(qx, qy), z);",
            ),
        ),
        helper(
            "em_obox",
            fn_text(
                "em_obox(px: vec3<f32>, py: vec3<f32>, mid: vec2<f32>, dir: vec2<f32>, half: vec2<f32>) -> vec3<f32>",
                "let qx = em_off(px, -mid.x);\n    \
                 let qy = em_off(py, -mid.y);\n    \
                 return em_aabox(qx * dir.x + qy * dir.y, qy * dir.x - qx * dir.y, vec2<f32>(0.0), half);",
            ),
        ),
        helper(
            "em_capsule",
            fn_text(
                "em_capsule(px: vec3<f32>, py: vec3<f32>, a: vec2<f32>, ba: vec2<f32>, inv_ba2: f32, r: f32) -> vec3<f32>",
                "return em_off(em_sqrt(em_seg2(em_off(px, -a.x), em_off(py, -a.y), ba, inv_ba2)), -r);",
            ),
        ),
        helper("em_ellipse_q", ellipse_solver()),
        helper(
            "em_ellipse",
            fn_text(
                "em_ellipse(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, radii: vec2<f32>) -> vec3<f32>",
                "let lx = em_off(px, -c.x);\n    \
                 let ly = em_off(py, -c.y);\n    \
                 let q = em_ellipse_q(vec2<f32>(abs(lx.x), abs(ly.x)), radii);\n    \
                 let qx = select(q.x, -q.x, lx.x < 0.0);\n    \
                 let qy = select(q.y, -q.y, ly.x < 0.0);\n    \
                 // The closest point is held constant: the gradient is (p - q) / |p - q|.\n    \
                 let d = em_len(em_off(lx, -qx), em_off(ly, -qy));\n    \
                 let nx = lx.x / radii.x;\n    \
                 let ny = ly.x / radii.y;\n    \
                 return select(d, -d, nx * nx + ny * ny < 1.0);",
            ),
        ),
        helper(
            "em_ring",
            fn_text(
                "em_ring(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, r: f32, half_width: f32) -> vec3<f32>",
                "return em_off(em_abs(em_off(em_len(em_off(px, -c.x), em_off(py, -c.y)), -r)), -half_width);",
            ),
        ),
        helper(
            "em_arc",
            fn_text(
                "em_arc(px: vec3<f32>, py: vec3<f32>, c: vec2<f32>, rot: vec2<f32>, sc: vec2<f32>, tip: vec2<f32>, ra: f32, rb: f32) -> vec3<f32>",
                "let lx = em_off(px, -c.x);\n    \
                 let ly = em_off(py, -c.y);\n    \
                 let qx = em_abs(lx * rot.x + ly * rot.y);\n    \
                 let qy = ly * rot.x - lx * rot.y;\n    \
                 var d: vec3<f32>;\n    \
                 if (sc.y * qx.x > sc.x * qy.x) {\n        d = em_len(em_off(qx, -tip.x), em_off(qy, -tip.y));\n    \
                 } else {\n        d = em_abs(em_off(em_len(qx, qy), -ra));\n    }\n    \
                 return em_off(d, -rb);",
            ),
        ),
        helper(
            "em_smin",
            fn_text(
                "em_smin(a: vec3<f32>, b: vec3<f32>, k: f32, k_quarter: f32) -> vec3<f32>",
                "let m = em_min(a, b);\n    \
                 let hk = em_off(em_abs(a - b) * -1.0, k);\n    \
                 if (hk.x > 0.0) {\n        let h = hk / k;\n        return m - em_mul(h, h) * k_quarter;\n    }\n    \
                 return m;",
            ),
        ),
        helper(
            "em_smax",
            fn_text(
                "em_smax(a: vec3<f32>, b: vec3<f32>, k: f32, k_quarter: f32) -> vec3<f32>",
                "let m = em_max(a, b);\n    \
                 let hk = em_off(em_abs(a - b) * -1.0, k);\n    \
                 if (hk.x > 0.0) {\n        let h = hk / k;\n        return m + em_mul(h, h) * k_quarter;\n    }\n    \
                 return m;",
            ),
        ),
        helper(
            "em_sat_i32",
            fn_text(
                "em_sat_i32(v: f32) -> i32",
                "// Rust's saturating `as i32`: NaN gives 0, out-of-range values the nearest end.\n    \
                 if (v != v) {\n        return 0;\n    }\n    \
                 if (v >= 2147483648.0) {\n        return 2147483647;\n    }\n    \
                 return i32(max(v, -2147483648.0));",
            ),
        ),
        helper("em_lattice", lattice()),
        helper(
            "em_fade",
            fn_text(
                "em_fade(t: vec3<f32>) -> vec3<f32>",
                "return em_mul(em_mul(t, t), em_off(t * -2.0, 3.0));",
            ),
        ),
        helper(
            "em_noise",
            fn_text(
                "em_noise(x: vec3<f32>, y: vec3<f32>, seed: u32) -> vec3<f32>",
                "let fx0 = floor(x.x);\n    \
                 let fy0 = floor(y.x);\n    \
                 let ix = em_sat_i32(fx0);\n    \
                 let iy = em_sat_i32(fy0);\n    \
                 let ux = em_fade(em_off(x, -fx0));\n    \
                 let uy = em_fade(em_off(y, -fy0));\n    \
                 // i32 addition wraps at run time, like the CPU's wrapping_add.\n    \
                 let v00 = em_lattice(ix, iy, seed);\n    \
                 let v10 = em_lattice(ix + 1, iy, seed);\n    \
                 let v01 = em_lattice(ix, iy + 1, seed);\n    \
                 let v11 = em_lattice(ix + 1, iy + 1, seed);\n    \
                 let bottom = em_off(ux * (v10 - v00), v00);\n    \
                 let top = em_off(ux * (v11 - v01), v01);\n    \
                 return bottom + em_mul(uy, top - bottom);",
            ),
        ),
        helper("em_sin_turns", sin_turns()),
        helper(
            "em_wave",
            fn_text(
                "em_wave(t: vec3<f32>) -> vec3<f32>",
                &format!(
                    "// sin(2 pi t) and its derivative 2 pi cos(2 pi t), by the CPU's polynomial.\n    \
                     return vec3<f32>(em_sin_turns(t.x), t.yz * ({} * em_sin_turns(t.x + 0.25)));",
                    lit(TAU)
                ),
            ),
        ),
        helper(
            "em_hp_index",
            fn_text(
                "em_hp_index(x: f32, x0: f32, dx: f32, segments: u32) -> u32",
                "// Index of the segment whose x-range holds x, clamped to 0 .. segments - 1.\n    \
                 let f = floor((x - x0) / dx);\n    \
                 if (f > 0.0) {\n        return u32(min(f, f32(segments - 1u)));\n    }\n    \
                 return 0u;",
            ),
        ),
    ];
    out.push(helper(
        craterfield_wgsl::NONFINITE_FN,
        craterfield_wgsl::NONFINITE_HELPER.to_string(),
    ));
    out
}

fn helper(name: &'static str, text: String) -> Helper {
    Helper { name, text }
}

fn fn_text(signature: &str, body: &str) -> String {
    format!("fn {signature} {{\n    {body}\n}}\n")
}

/// `primitives::ellipse_closest_first_quadrant`, operation for operation.
fn ellipse_solver() -> String {
    let s = lit(std::f32::consts::FRAC_1_SQRT_2);
    fn_text(
        "em_ellipse_q(p: vec2<f32>, r: vec2<f32>) -> vec2<f32>",
        &format!(
            "let a = r.x;\n    \
             let b = r.y;\n    \
             var tx = {s};\n    \
             var ty = {s};\n    \
             let ab = a * a - b * b;\n    \
             for (var i = 0; i < {ELLIPSE_ITERATIONS}; i++) {{\n        \
             let x = a * tx;\n        \
             let y = b * ty;\n        \
             let ex = ab * (tx * tx * tx) / a;\n        \
             let ey = -ab * (ty * ty * ty) / b;\n        \
             let rx = x - ex;\n        \
             let ry = y - ey;\n        \
             let qx = p.x - ex;\n        \
             let qy = p.y - ey;\n        \
             let rl = sqrt(rx * rx + ry * ry);\n        \
             let ql = sqrt(qx * qx + qy * qy);\n        \
             if (ql > 0.0) {{\n            \
             tx = em_minf(em_maxf((qx * rl / ql + ex) / a, 0.0), 1.0);\n            \
             ty = em_minf(em_maxf((qy * rl / ql + ey) / b, 0.0), 1.0);\n        \
             }}\n        \
             let t = sqrt(tx * tx + ty * ty);\n        \
             if (t > 0.0) {{\n            \
             tx = tx / t;\n            \
             ty = ty / t;\n        \
             }}\n    \
             }}\n    \
             return vec2<f32>(a * tx, b * ty);"
        ),
    )
}

/// `noise::lattice_value`: u32 `*` and `+` wrap in WGSL at run time, so the hash is exact.
fn lattice() -> String {
    let [m1, m2, m3, add, mix1, mix2] = [
        0x8da6_b343u32,
        0xd816_3841,
        0xcb1a_b31f,
        0x9e37_79b9,
        0x2c1b_3c6d,
        0x297a_2d39,
    ]
    .map(u32_literal);
    fn_text(
        "em_lattice(ix: i32, iy: i32, seed: u32) -> f32",
        &format!(
            "var h = bitcast<u32>(ix) * {m1} + bitcast<u32>(iy) * {m2} + seed * {m3} + {add};\n    \
             h = h ^ (h >> 15u);\n    \
             h = h * {mix1};\n    \
             h = h ^ (h >> 12u);\n    \
             h = h * {mix2};\n    \
             h = h ^ (h >> 15u);\n    \
             // 24 bits fit f32 exactly; the scale is a power of two.\n    \
             return f32(h >> 8u) * {} - 1.0;",
            lit(1.0 / 8_388_608.0)
        ),
    )
}

/// `detmath::sin_turns`: range reduction to a quarter turn, then the same odd polynomial.
fn sin_turns() -> String {
    let c: [f32; 5] = [
        2.755_731_9e-6,
        -1.984_127e-4,
        8.333_333e-3,
        -1.666_666_7e-1,
        1.0,
    ];
    let mut poly = format!("var s = {};\n", lit(-2.505_210_8e-8));
    for coefficient in c {
        poly.push_str(&format!("    s = s * x2 + {};\n", lit(coefficient)));
    }
    fn_text(
        "em_sin_turns(t: f32) -> f32",
        &format!(
            "var r = t - floor(t + 0.5);\n    \
             if (r > 0.25) {{\n        r = 0.5 - r;\n    }} else if (r < -0.25) {{\n        r = -0.5 - r;\n    }}\n    \
             let x = r * {};\n    \
             let x2 = x * x;\n    \
             {poly}    \
             return x * s;",
            lit(TAU)
        ),
    )
}

/// The helpers `text` needs, with what they need in turn, in library order.
pub(crate) fn used_helpers(text: &str) -> String {
    let library = all_helpers();
    let mut used = vec![false; library.len()];
    let mut frontier = vec![text.to_string()];
    while let Some(chunk) = frontier.pop() {
        for (i, h) in library.iter().enumerate() {
            let called = chunk.contains(&format!("{}(", h.name));
            let referenced = h.name == "em_far" && chunk.contains("em_far");
            if !used[i] && (called || referenced) {
                used[i] = true;
                frontier.push(h.text.clone());
            }
        }
    }
    library
        .iter()
        .zip(used)
        .filter(|(_, u)| *u)
        .map(|(h, _)| h.text.as_str())
        .collect::<Vec<_>>()
        .join("\n")
}
