//! The distances of the tracer's primitives over lanes (spheres, boxes, cones, tori and
//! the rest of the plan's kinds), the power-8 Mandelbulb, and the ray-sphere test of the
//! early-out.

use glam::Vec2;

use super::constants::{PrimC, PrimK};
use super::lanes::V3;
use crate::math;
use crate::plan3d::Sphere;
use crate::simd::Pack;

/// The distance of a primitive placed at `prim.centre` with its rotation.
#[inline(always)]
pub(crate) fn prim_distance<P: Pack>(p: P, prim: &PrimC, q: V3<P>, active: P::M) -> P::F {
    let mut l = q.sub_c(p, prim.centre);
    if let Some(r) = &prim.rot {
        l = l.rotate(p, r);
    }
    let zero = p.splat(0.0);
    match prim.kind {
        PrimK::Sphere { r } => p.sub(l.len(p), p.splat(r)),
        PrimK::Box { half } => {
            let b = l.abs(p).sub_c(p, half);
            p.add(b.max0(p).len(p), p.min(b.max_elem(p), zero))
        }
        PrimK::RoundBox { inner, r } => {
            let b = l.abs(p).sub_c(p, inner);
            p.sub(
                p.add(b.max0(p).len(p), p.min(b.max_elem(p), zero)),
                p.splat(r),
            )
        }
        PrimK::Capsule { a, ba, inv_baba, r } => {
            let pa = l.sub_c(p, a);
            let h = p.mul(pa.dot_c(p, ba), p.splat(inv_baba));
            let h = p.max(zero, p.min(p.splat(1.0), h));
            let v = V3::splat(p, ba).scale(p, h);
            p.sub(pa.sub(p, v).len(p), p.splat(r))
        }
        PrimK::Torus { major, minor } => {
            let rxz = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
            let a = p.sub(rxz, p.splat(major));
            p.sub(p.sqrt(p.fma(a, a, p.mul(l.y, l.y))), p.splat(minor))
        }
        PrimK::Cylinder { r, h } => {
            let rxz = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
            let dx = p.sub(rxz, p.splat(r));
            let dy = p.sub(p.abs(l.y), p.splat(h));
            let (ox, oy) = (p.max(dx, zero), p.max(dy, zero));
            p.add(
                p.min(p.max(dx, dy), zero),
                p.sqrt(p.fma(ox, ox, p.mul(oy, oy))),
            )
        }
        PrimK::CappedCone {
            h,
            r1,
            r2,
            k2,
            inv_k2k2,
        } => capped_cone(p, l, h, r1, r2, k2, inv_k2k2),
        PrimK::Octahedron { s } => octahedron(p, l, s, active),
        PrimK::Ellipsoid { inv_r, inv_r2 } => {
            let k0 = V3 {
                x: p.mul(l.x, p.splat(inv_r.x)),
                y: p.mul(l.y, p.splat(inv_r.y)),
                z: p.mul(l.z, p.splat(inv_r.z)),
            }
            .len(p);
            let k1 = V3 {
                x: p.mul(l.x, p.splat(inv_r2.x)),
                y: p.mul(l.y, p.splat(inv_r2.y)),
                z: p.mul(l.z, p.splat(inv_r2.z)),
            }
            .len(p);
            p.div(p.mul(k0, p.sub(k0, p.splat(1.0))), k1)
        }
        PrimK::PlaneY { offset } => p.sub(l.y, p.splat(offset)),
        PrimK::Plane { normal, offset } => p.sub(l.dot_c(p, normal), p.splat(offset)),
    }
}

#[inline(always)]
fn capped_cone<P: Pack>(p: P, l: V3<P>, h: f32, r1: f32, r2: f32, k2: Vec2, inv_k2k2: f32) -> P::F {
    let zero = p.splat(0.0);
    let qx = p.sqrt(p.fma(l.x, l.x, p.mul(l.z, l.z)));
    let qy = l.y;
    let rim = p.select(p.lt(qy, zero), p.splat(r1), p.splat(r2));
    let cax = p.sub(qx, p.min(qx, rim));
    let cay = p.sub(p.abs(qy), p.splat(h));
    // k1 - q = (r2 - qx, h - qy).
    let (kqx, kqy) = (p.sub(p.splat(r2), qx), p.sub(p.splat(h), qy));
    let t = p.mul(
        p.fma(kqx, p.splat(k2.x), p.mul(kqy, p.splat(k2.y))),
        p.splat(inv_k2k2),
    );
    let t = p.max(zero, p.min(p.splat(1.0), t));
    let cbx = p.fma(p.splat(k2.x), t, p.neg(kqx));
    let cby = p.fma(p.splat(k2.y), t, p.neg(kqy));
    let inside = p.and(p.lt(cbx, zero), p.lt(cay, zero));
    let dd = p.min(
        p.fma(cax, cax, p.mul(cay, cay)),
        p.fma(cbx, cbx, p.mul(cby, cby)),
    );
    let d = p.sqrt(dd);
    p.select(inside, p.neg(d), d)
}

/// The exact octahedron; the cheap plane bound `m / sqrt(3)` when no active lane lies in
/// one of the corner regions that need the full formula.
#[inline(always)]
fn octahedron<P: Pack>(p: P, l: V3<P>, s: f32, active: P::M) -> P::F {
    let a = l.abs(p);
    let m = p.sub(p.add(a.x, p.add(a.y, a.z)), p.splat(s));
    let plane = p.mul(m, p.splat(0.577_350_27));
    let three = p.splat(3.0);
    let c1 = p.lt(p.mul(three, a.x), m);
    let c2 = p.lt(p.mul(three, a.y), m);
    let c3 = p.lt(p.mul(three, a.z), m);
    let corner = p.or(c1, p.or(c2, c3));
    if !p.any(p.and(active, corner)) {
        return plane;
    }
    // q = p, p.yzx or p.zxy for the first region that holds.
    let qx = p.select(c1, a.x, p.select(c2, a.y, a.z));
    let qy = p.select(c1, a.y, p.select(c2, a.z, a.x));
    let qz = p.select(c1, a.z, p.select(c2, a.x, a.y));
    let sv = p.splat(s);
    let k = p.mul(p.splat(0.5), p.add(p.sub(qz, qy), sv));
    let k = p.max(p.splat(0.0), p.min(sv, k));
    let d = V3 {
        x: qx,
        y: p.add(p.sub(qy, sv), k),
        z: p.sub(qz, k),
    }
    .len(p);
    p.select(corner, d, plane)
}

/// The power-8 Mandelbulb's distance estimate at `c = p - centre`.
#[inline(always)]
pub(crate) fn mandelbulb<P: Pack>(
    p: P,
    c: V3<P>,
    (iterations, bailout, derivative): (u32, f32, f32),
    active: P::M,
) -> P::F {
    let mut w = c;
    let mut m = w.len2(p);
    let mut dz = p.splat(derivative);
    let mut live = active;
    let bail = p.splat(bailout);
    for _ in 0..iterations {
        // dz = 8 m^3.5 dz + 1, with m^3.5 = m^3 sqrt(m). The power step below uses no
        // square root or division, so this one square root has the divider to itself, and
        // it is off the chain from one w to the next.
        let m3 = p.mul(p.mul(m, m), m);
        let k = p.mul(p.mul(m3, p.sqrt(m)), dz);
        let ndz = p.fma(p.splat(8.0), k, p.splat(1.0));
        // A lane that has escaped keeps its m and dz, which are all the estimate reads; its
        // w runs on (to infinity and NaN, which cost nothing) rather than pay three selects.
        w = bulb8_plus(p, w, c);
        let nm = w.len2(p);
        dz = p.select(live, ndz, dz);
        m = p.select(live, nm, m);
        live = p.and_not(live, p.gt(nm, bail));
        if !p.any(live) {
            break;
        }
    }
    let num = p.mul(p.splat(0.25), p.mul(math::log(p, m), p.sqrt(m)));
    p.div(num, dz)
}

/// Below this `rho^2 = 2^-36`, `rho^7` is under the smallest normal f32 (`2^-126`).
const RHO2_MIN: f32 = 1.0 / (1u64 << 36) as f32;
/// Above this `rho^2 = 2^35`, `rho^-7` is near or under the smallest normal.
const RHO2_MAX: f32 = (1u64 << 35) as f32;

/// `w^8 + c`, with `w^8` in the spherical power-8 form `r^8 (sin b sin a, cos b, sin b cos
/// a)`, `b = 8 acos(w.y / r)`, `a = 8 atan2(w.x, w.z)`, as polynomials in `x, y, z`
/// (Quilez's closed form) with `rho = |w.xz|`: `k1 = x^4 + y^4 + z^4 - 6 y^2 rho^2 + 2 x^2
/// z^2`, `k2 = rho^-7`, `k4 = x^2 - y^2 + z^2`, and
/// `x' = 64 x y z (x^2 - z^2) k4 (x^4 - 6 x^2 z^2 + z^4) k1 k2`,
/// `y' = -16 y^2 rho^2 k4^2 + k1^2`,
/// `z' = -8 y k4 (x^8 - 28 x^2 z^2 (x^4 + z^4) + 70 x^4 z^4 + z^8) k1 k2`.
///
/// The step is the fractal's inner loop, so it is written for the shortest chain from one
/// `w` to the next and the fewest operations: `k2` comes from the reciprocal square root
/// and enters each product last (everything else is ready while it is computed), and
/// multiply-adds fuse where a sum follows a product. That rounds differently from the
/// reference renderer's order of operations; the pictures stay within its FLIP bound
/// (`tests/march3d_views`). The GPU marcher's `bulb8_plus` (`shaders/march3d.wgsl`) has
/// the same operations.
#[inline(always)]
pub(crate) fn bulb8_plus<P: Pack>(p: P, w: V3<P>, c: V3<P>) -> V3<P> {
    let (x, y, z) = (w.x, w.y, w.z);
    let (x2, y2, z2) = (p.mul(x, x), p.mul(y, y), p.mul(z, z));
    let (x4, y4, z4) = (p.mul(x2, x2), p.mul(y2, y2), p.mul(z2, z2));
    let x2z2 = p.mul(x2, z2);
    let x4z4 = p.add(x4, z4);
    let rho2 = p.add(x2, z2);
    // k2 = (1/rho)^7. Outside [RHO2_MIN, RHO2_MAX] it is 0: on the axis (rho = 0) a =
    // atan2(0, 0) = 0 and sin b = 0, so x' and z' are 0, not 0 * inf, and within 8 rho r^7
    // of it rho^7 underflows (rho < 4e-6); far out rho^-7 underflows. The clamp keeps the
    // lanes that are not used normal: a subnormal product costs a microcode assist.
    let r = p.rsqrt(p.min(rho2, p.splat(RHO2_MAX)));
    let r2 = p.mul(r, r);
    let r7 = p.mul(p.mul(r2, r2), p.mul(r2, r));
    let normal = p.and(p.ge(rho2, p.splat(RHO2_MIN)), p.le(rho2, p.splat(RHO2_MAX)));
    let k2 = p.select(normal, r7, p.splat(0.0));
    let k1 = p.add(
        x4z4,
        p.add(y4, p.fma(p.mul(p.splat(-6.0), y2), rho2, p.add(x2z2, x2z2))),
    );
    let k4 = p.sub(rho2, y2);
    let k14 = p.mul(k1, k4);
    let ax = p.add(x4, p.fma(p.splat(-6.0), x2z2, z4));
    let tx = p.mul(
        p.mul(p.mul(x, y), p.mul(z, p.sub(x2, z2))),
        p.mul(p.mul(p.splat(64.0), ax), k14),
    );
    // -az = (70 x^4 + z^4) z^4 + x^8 - 28 x^2 z^2 (x^4 + z^4).
    let neg_az = p.fnma(
        p.mul(p.splat(28.0), x2z2),
        x4z4,
        p.fma(p.fma(p.splat(70.0), x4, z4), z4, p.mul(x4, x4)),
    );
    let tz = p.mul(p.mul(p.splat(-8.0), y), p.mul(neg_az, k14));
    let ty = p.fma(p.mul(p.mul(p.splat(-16.0), y2), rho2), p.mul(k4, k4), c.y);
    V3 {
        x: p.fma(tx, k2, c.x),
        y: p.fma(k1, k1, ty),
        z: p.fma(tz, k2, c.z),
    }
}

/// Whether `o + s * dir` for some `s > 0` meets the sphere (the terrain-and-bounds shadow's
/// ray test): `oc = centre - o, b = dot(oc, dir), c = dot(oc, oc) - r^2`, `b > 0 && b*b > c`.
#[inline(always)]
pub(crate) fn ray_meets_sphere<P: Pack>(p: P, o: V3<P>, dir: V3<P>, s: &Sphere) -> P::M {
    let oc = V3::splat(p, s.centre).sub(p, o);
    let b = oc.dot(p, dir);
    let c = p.sub(oc.len2(p), p.splat(s.radius * s.radius));
    p.and(p.gt(b, p.splat(0.0)), p.gt(p.mul(b, b), c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::PackKernel;
    /// The bulb's bounding radius in the emitter (`compile::objects`).
    const BULB_RADIUS: f32 = 1.25;
    use crate::simd::Scalar;

    /// The trigonometric form of the power-8 step, in f64.
    fn bulb8_trig(w: [f64; 3]) -> [f64; 3] {
        let r = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let b = 8.0 * (w[1] / r).acos();
        let a = 8.0 * w[0].atan2(w[2]);
        let r8 = r.powi(8);
        [r8 * b.sin() * a.sin(), r8 * b.cos(), r8 * b.sin() * a.cos()]
    }

    /// The trig-free form of [`bulb8_plus`] (the same complex squarings), in f64.
    fn bulb8_f64(w: [f64; 3]) -> [f64; 3] {
        let rho2 = w[0] * w[0] + w[2] * w[2];
        let rho = rho2.sqrt();
        // On the axis any unit direction will do, as in the lane version.
        let (xn, zn) = (w[0] / rho.max(1e-300), w[2] / rho.max(1e-300));
        let sq = |(c, s): (f64, f64)| (c * c - s * s, 2.0 * s * c);
        let (ca, sa) = sq(sq((zn * zn - xn * xn, 2.0 * xn * zn)));
        let (cb, sb) = sq(sq((w[1] * w[1] - rho2, 2.0 * w[1] * rho)));
        [sb * sa, cb, sb * ca]
    }

    fn points() -> impl Iterator<Item = [f64; 3]> {
        (0..2000).map(|i| {
            let f = i as f64;
            [
                (f * 0.731).sin() * 1.3,
                (f * 0.377).cos() * 1.1,
                (f * 1.913).sin() * 0.9,
            ]
        })
    }

    #[test]
    fn trig_free_bulb_step_equals_the_trigonometric_form() {
        for w in points() {
            let (a, b) = (bulb8_trig(w), bulb8_f64(w));
            let r8 = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).powi(4);
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-9 * r8.max(1.0),
                    "{w:?}: {a:?} {b:?}"
                );
            }
        }
    }

    #[test]
    fn lane_bulb_step_follows_the_f64_form() {
        for w in points() {
            let b = bulb8_f64(w);
            let v = bulb8_plus(
                Scalar,
                V3 {
                    x: w[0] as f32,
                    y: w[1] as f32,
                    z: w[2] as f32,
                },
                V3::splat(Scalar, glam::Vec3::ZERO),
            );
            let r8 = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).powi(4);
            for (got, want) in [v.x, v.y, v.z].into_iter().zip(b) {
                assert!(
                    (got as f64 - want).abs() <= 1e-5 * r8.max(1.0),
                    "{w:?}: {got} vs {want}"
                );
            }
        }
    }

    /// The distance estimate of [`mandelbulb`] in f64, with the derivative's `m^3.5` from a
    /// square root; `None` where an orbit comes within 1% of the bailout (where the two
    /// precisions may stop at different iterations).
    fn bulb_distance_f64(c: [f64; 3], iterations: u32) -> Option<f64> {
        let len2 = |w: [f64; 3]| w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
        let (mut w, mut dz) = (c, 1.5);
        let mut m = len2(w);
        for _ in 0..iterations {
            dz = 8.0 * m.powf(3.5) * dz + 1.0;
            let b = bulb8_f64(w);
            w = [b[0] + c[0], b[1] + c[1], b[2] + c[2]];
            m = len2(w);
            if (m / 256.0 - 1.0).abs() < 0.01 {
                return None;
            }
            if m > 256.0 {
                break;
            }
        }
        Some(0.25 * m.ln() * m.sqrt() / dz)
    }

    /// [`mandelbulb`] on a backend, at points as f32, with a derivative seed.
    struct Distances<'a>(&'a [[f32; 3]], f32);

    impl PackKernel for Distances<'_> {
        type Output = Vec<f32>;
        fn run<P: Pack>(self, p: P) -> Vec<f32> {
            let mut out = Vec::new();
            for chunk in self.0.chunks(P::WIDTH) {
                let mut lanes = [[1.0f32; crate::cpu::lanes::MAX_WIDTH]; 3];
                for (l, q) in chunk.iter().enumerate() {
                    (0..3).for_each(|k| lanes[k][l] = q[k]);
                }
                let c = V3 {
                    x: p.load(&lanes[0]),
                    y: p.load(&lanes[1]),
                    z: p.load(&lanes[2]),
                };
                let d = mandelbulb(p, c, (4, 256.0, self.1), p.all_set());
                let mut v = [0.0f32; crate::cpu::lanes::MAX_WIDTH];
                p.store(d, &mut v);
                out.extend_from_slice(&v[..chunk.len()]);
            }
            out
        }
    }

    #[test]
    fn distance_estimate_follows_the_f64_form_on_every_backend() {
        let mut checked = 0;
        let points: Vec<[f32; 3]> = points()
            .map(|w| w.map(|v| v as f32))
            .chain([[1e-20, 0.3, 0.0], [0.0, 0.9, 0.0], [0.2, 0.0, 1e-19]])
            .collect();
        for backend in crate::simd::TRACER_BACKENDS {
            let Ok(got) = crate::simd::run(backend, Distances(&points, 1.5)) else {
                continue;
            };
            for (q, &g) in points.iter().zip(&got) {
                let Some(want) = bulb_distance_f64(q.map(f64::from), 4) else {
                    continue;
                };
                let err = (f64::from(g) - want).abs() / want.abs().max(1e-3);
                assert!(err < 1e-3, "{backend} at {q:?}: {g} vs {want}");
                checked += 1;
            }
        }
        assert!(checked > 1500, "only {checked} points compared");
    }

    #[test]
    fn far_bound_is_below_the_estimate_on_every_backend() {
        use crate::cpu::constants::FarBound;
        // Directions over the sphere, at distances from the bound's radius outwards.
        let mut points = Vec::new();
        for i in 0..400 {
            let (u, v) = (i as f32 * 0.618_034 % 1.0, (i as f32 + 0.5) / 400.0);
            let (phi, z) = (u * std::f32::consts::TAU, 2.0 * v - 1.0);
            let s = (1.0 - z * z).sqrt();
            let dir = glam::Vec3::new(s * phi.cos(), z, s * phi.sin());
            for r in [
                2.0, 2.001, 2.5, 3.0, 4.0, 6.0, 9.5, 16.0, 40.0, 150.0, 1000.0,
            ] {
                points.push((dir * r).to_array());
            }
        }
        for derivative in [0.25, 1.0, 1.5, 6.0] {
            let far = FarBound::mandelbulb(glam::Vec3::ZERO, 4, 256.0, derivative).unwrap();
            for backend in crate::simd::TRACER_BACKENDS {
                let Ok(got) = crate::simd::run(backend, Distances(&points, derivative)) else {
                    continue;
                };
                for (q, &d) in points.iter().zip(&got) {
                    let r = glam::Vec3::from_array(*q).length();
                    let bound = far
                        .lines
                        .iter()
                        .map(|&(slope, offset)| slope * r + offset)
                        .fold(f32::NEG_INFINITY, f32::max);
                    assert!(
                        r * r < far.radius2 || d > bound,
                        "{backend}, derivative {derivative}, at {q:?}: estimate {d} under {bound}"
                    );
                }
            }
        }
        // Parameters the bound does not hold for have none.
        assert!(FarBound::mandelbulb(glam::Vec3::ZERO, 4, 1e6, 1.5).is_none());
        assert!(FarBound::mandelbulb(glam::Vec3::ZERO, 4, 256.0, 0.0).is_none());
    }

    /// [`bulb8_plus`] on a backend, at points as f32, with `c = 0`.
    struct Steps<'a>(&'a [[f32; 3]]);

    impl PackKernel for Steps<'_> {
        type Output = Vec<[f32; 3]>;
        fn run<P: Pack>(self, p: P) -> Vec<[f32; 3]> {
            self.0
                .iter()
                .map(|w| {
                    let v = bulb8_plus(
                        p,
                        V3::splat(p, glam::Vec3::from_array(*w)),
                        V3::splat(p, glam::Vec3::ZERO),
                    );
                    let mut out = [[0.0f32; crate::cpu::lanes::MAX_WIDTH]; 3];
                    for (k, lane) in [v.x, v.y, v.z].into_iter().enumerate() {
                        p.store(lane, &mut out[k]);
                    }
                    [out[0][0], out[1][0], out[2][0]]
                })
                .collect()
        }
    }

    #[test]
    fn bulb_step_on_and_near_the_axis_is_finite_on_every_backend() {
        // On the axis, where rho^7 underflows, and just past that: the estimate of
        // 1/rho there is infinite or huge, and x' and z' must still be (near) 0.
        let points = [[0.0, 0.5, 0.0], [1e-7, 0.5, -1e-7], [-4e-6, 0.7, 2e-6]];
        for backend in crate::simd::TRACER_BACKENDS {
            let Ok(got) = crate::simd::run(backend, Steps(&points)) else {
                continue;
            };
            for (w, v) in points.iter().zip(&got) {
                let want = bulb8_f64(w.map(f64::from));
                for (g, e) in v.iter().zip(want) {
                    assert!(
                        g.is_finite() && (f64::from(*g) - e).abs() <= 1e-6,
                        "{backend} at {w:?}: {v:?} vs {want:?}"
                    );
                }
            }
            assert_eq!(got[0], [0.0, 0.5f32.powi(8), 0.0], "{backend} on the axis");
            assert_eq!([got[1][0], got[1][2]], [0.0, 0.0], "{backend} next to it");
        }
    }

    #[test]
    fn bulb_distance_is_positive_outside_its_bound() {
        // The bounding sphere must contain the whole surface, for every iteration count.
        for iterations in 1..=8 {
            for (i, w) in points().enumerate() {
                let n = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
                let r = BULB_RADIUS as f64 * (1.0 + (i % 7) as f64 * 0.05);
                let c = V3 {
                    x: (w[0] / n * r) as f32,
                    y: (w[1] / n * r) as f32,
                    z: (w[2] / n * r) as f32,
                };
                let d = mandelbulb(Scalar, c, (iterations, 256.0, 1.5), true);
                assert!(d > 0.01, "{iterations} iterations at {r}: {d}");
            }
        }
    }
}
