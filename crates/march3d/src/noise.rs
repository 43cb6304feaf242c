//! Lattice hashes, value noise and fractal (FBM) heights with their analytic gradients,
//! written once over any lane backend, exactly as the plan's "Noise" section defines them.
//!
//! The tracer evaluates the terrain through [`FbmLanes`] (per-frame constants hoisted: the
//! octave weights and the octave Jacobians are scalars shared by every lane); the scalar
//! conveniences on [`Fbm`] (height, slope bound, step scale, validation) serve the emitter
//! and the tests.

use glam::Vec2;

use super::math;
use super::simd::Pack;
use super::simd::Scalar;
use crate::plan3d::{Fbm, Hash, MAX_OCTAVES};

/// `x - floor(x)`.
#[inline(always)]
pub fn fract<P: Pack>(p: P, x: P::F) -> P::F {
    p.sub(x, p.floor(x))
}

/// The 2D lattice hash of the integer point `(qx, qy)`, in `[0, 1)`.
#[inline(always)]
pub fn hash2<P: Pack>(p: P, hash: Hash, qx: P::F, qy: P::F) -> P::F {
    match hash {
        Hash::DotFract => {
            let k = p.splat(0.1031);
            // p3 = fract((q.x, q.y, q.x) * 0.1031) = (a, b, a).
            let a = fract(p, p.mul(qx, k));
            let b = fract(p, p.mul(qy, k));
            let s = p.splat(33.33);
            // dot(p3, p3.yzx + 33.33) with p3.yzx = (b, a, a).
            let dd = p.fma(a, p.add(b, s), p.fma(b, p.add(a, s), p.mul(a, p.add(a, s))));
            let (x, y, z) = (p.add(a, dd), p.add(b, dd), p.add(a, dd));
            fract(p, p.mul(p.add(x, y), z))
        }
        Hash::Sin => {
            // Unfused on purpose: the sine's argument is in the thousands and its result
            // is scaled by 43758, so one rounding of difference between fused and unfused
            // backends would give another hash.
            let d = p.add(p.mul(qx, p.splat(127.1)), p.mul(qy, p.splat(311.7)));
            fract(p, p.mul(math::sin(p, d), p.splat(43_758.547)))
        }
    }
}

/// The 3D lattice hash of the integer point `(qx, qy, qz)`, in `[0, 1)`.
#[inline(always)]
pub fn hash3<P: Pack>(p: P, hash: Hash, qx: P::F, qy: P::F, qz: P::F) -> P::F {
    match hash {
        Hash::DotFract => {
            let k = p.splat(0.1031);
            let a = fract(p, p.mul(qx, k));
            let b = fract(p, p.mul(qy, k));
            let c = fract(p, p.mul(qz, k));
            let s = p.splat(31.32);
            // dot(p3, p3.zyx + 31.32) with p3.zyx = (c, b, a).
            let dd = p.fma(a, p.add(c, s), p.fma(b, p.add(b, s), p.mul(c, p.add(a, s))));
            let (x, y, z) = (p.add(a, dd), p.add(b, dd), p.add(c, dd));
            fract(p, p.mul(p.add(x, y), z))
        }
        Hash::Sin => {
            // Unfused on purpose (see `hash2`).
            let d = p.add(
                p.add(p.mul(qx, p.splat(127.1)), p.mul(qy, p.splat(311.7))),
                p.mul(qz, p.splat(74.7)),
            );
            fract(p, p.mul(math::sin(p, d), p.splat(43_758.547)))
        }
    }
}

/// Smoothstep weight `f*f*(3 - 2f)` and its derivative `6 f (1 - f)`.
#[inline(always)]
fn smooth<P: Pack>(p: P, f: P::F) -> (P::F, P::F) {
    let u = p.mul(p.mul(f, f), p.fnma(p.splat(2.0), f, p.splat(3.0)));
    let du = p.mul(p.mul(p.splat(6.0), f), p.sub(p.splat(1.0), f));
    (u, du)
}

/// 2D value noise at `(x, y)` in `[0, 1)` and its gradient: `(value, d/dx, d/dy)`.
#[inline(always)]
pub fn noise2<P: Pack>(p: P, hash: Hash, x: P::F, y: P::F) -> (P::F, P::F, P::F) {
    let (ix, iy) = (p.floor(x), p.floor(y));
    let (ux, dux) = smooth(p, p.sub(x, ix));
    let (uy, duy) = smooth(p, p.sub(y, iy));
    let one = p.splat(1.0);
    let (ix1, iy1) = (p.add(ix, one), p.add(iy, one));
    let a = hash2(p, hash, ix, iy);
    let b = hash2(p, hash, ix1, iy);
    let c = hash2(p, hash, ix, iy1);
    let d = hash2(p, hash, ix1, iy1);
    let ba = p.sub(b, a);
    let ca = p.sub(c, a);
    let k = p.add(p.sub(p.neg(ba), c), d); // a - b - c + d
    let v = p.fma(ba, ux, p.fma(ca, uy, p.fma(k, p.mul(ux, uy), a)));
    let gx = p.mul(dux, p.fma(k, uy, ba));
    let gy = p.mul(duy, p.fma(k, ux, ca));
    (v, gx, gy)
}

/// 3D value noise at `(x, y, z)` in `[0, 1)`: trilinear over the eight corner hashes with
/// smoothstep weights.
#[inline(always)]
pub fn noise3<P: Pack>(p: P, hash: Hash, x: P::F, y: P::F, z: P::F) -> P::F {
    let (ix, iy, iz) = (p.floor(x), p.floor(y), p.floor(z));
    let (ux, _) = smooth(p, p.sub(x, ix));
    let (uy, _) = smooth(p, p.sub(y, iy));
    let (uz, _) = smooth(p, p.sub(z, iz));
    let one = p.splat(1.0);
    let (jx, jy, jz) = (p.add(ix, one), p.add(iy, one), p.add(iz, one));
    let lerp = |a: P::F, b: P::F, u: P::F| p.fma(p.sub(b, a), u, a);
    let h = |x: P::F, y: P::F, z: P::F| hash3(p, hash, x, y, z);
    let x00 = lerp(h(ix, iy, iz), h(jx, iy, iz), ux);
    let x10 = lerp(h(ix, jy, iz), h(jx, jy, iz), ux);
    let x01 = lerp(h(ix, iy, jz), h(jx, iy, jz), ux);
    let x11 = lerp(h(ix, jy, jz), h(jx, jy, jz), ux);
    lerp(lerp(x00, x10, uy), lerp(x01, x11, uy), uz)
}

/// An [`Fbm`] prepared for evaluation over lanes: every lane-independent quantity (the
/// octave weights times the amplitude, the weighted transposed octave Jacobians, the
/// scaled rotation) computed once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FbmLanes {
    hash: Hash,
    base: f32,
    frequency: f32,
    /// `lacunarity * (cos, sin)` of the rotation: one octave's map `q -> lacunarity R q`.
    rot: (f32, f32),
    octaves: usize,
    /// Per octave: `amplitude * gain^o`.
    weight: [f32; MAX_OCTAVES as usize],
    /// Per octave: `amplitude * gain^o * J_o^T`, row-major 2x2.
    jac: [[f32; 4]; MAX_OCTAVES as usize],
}

impl FbmLanes {
    /// The prepared form of `fbm` (of a [valid](crate::plan3d::Plan::validate) plan; octaves beyond
    /// [`MAX_OCTAVES`] are dropped).
    pub fn new(fbm: &Fbm, hash: Hash) -> FbmLanes {
        let octaves = fbm.octaves.clamp(1, MAX_OCTAVES) as usize;
        let (s, c) = (fbm.rotation as f64).sin_cos();
        let lac = fbm.lacunarity as f64;
        let (a, b) = (lac * c, lac * s);
        let mut weight = [0.0; MAX_OCTAVES as usize];
        let mut jac = [[0.0; 4]; MAX_OCTAVES as usize];
        // J = frequency * I; per octave J <- lacunarity R J.
        let mut j = [fbm.frequency as f64, 0.0, 0.0, fbm.frequency as f64];
        let mut w = fbm.amplitude as f64;
        for o in 0..octaves {
            weight[o] = w as f32;
            // w J^T, row-major.
            jac[o] = [
                (w * j[0]) as f32,
                (w * j[2]) as f32,
                (w * j[1]) as f32,
                (w * j[3]) as f32,
            ];
            j = [
                a * j[0] - b * j[2],
                a * j[1] - b * j[3],
                b * j[0] + a * j[2],
                b * j[1] + a * j[3],
            ];
            w *= fbm.gain as f64;
        }
        FbmLanes {
            hash,
            base: fbm.base,
            frequency: fbm.frequency,
            rot: (a as f32, b as f32),
            octaves,
            weight,
            jac,
        }
    }

    /// The height at `(x, z)` and its gradient `(dh/dx, dh/dz)`.
    #[inline(always)]
    pub fn height<P: Pack>(&self, p: P, x: P::F, z: P::F) -> (P::F, P::F, P::F) {
        let f = p.splat(self.frequency);
        let (mut qx, mut qz) = (p.mul(x, f), p.mul(z, f));
        let mut h = p.splat(self.base);
        let (mut gx, mut gz) = (p.splat(0.0), p.splat(0.0));
        let (ra, rb) = (p.splat(self.rot.0), p.splat(self.rot.1));
        for o in 0..self.octaves {
            let (v, nx, nz) = noise2(p, self.hash, qx, qz);
            let jt = &self.jac[o];
            h = p.fma(p.splat(self.weight[o]), v, h);
            gx = p.fma(p.splat(jt[0]), nx, p.fma(p.splat(jt[1]), nz, gx));
            gz = p.fma(p.splat(jt[2]), nx, p.fma(p.splat(jt[3]), nz, gz));
            if o + 1 < self.octaves {
                let nqx = p.fnma(rb, qz, p.mul(ra, qx));
                let nqz = p.fma(rb, qx, p.mul(ra, qz));
                (qx, qz) = (nqx, nqz);
            }
        }
        (h, gx, gz)
    }

    /// The height only (the gradient's multiply-adds are left out).
    #[inline(always)]
    pub fn height_only<P: Pack>(&self, p: P, x: P::F, z: P::F) -> P::F {
        let f = p.splat(self.frequency);
        let (mut qx, mut qz) = (p.mul(x, f), p.mul(z, f));
        let mut h = p.splat(self.base);
        let (ra, rb) = (p.splat(self.rot.0), p.splat(self.rot.1));
        for o in 0..self.octaves {
            let (v, _, _) = noise2(p, self.hash, qx, qz);
            h = p.fma(p.splat(self.weight[o]), v, h);
            if o + 1 < self.octaves {
                let nqx = p.fnma(rb, qz, p.mul(ra, qx));
                let nqz = p.fma(rb, qx, p.mul(ra, qz));
                (qx, qz) = (nqx, nqz);
            }
        }
        h
    }
}

impl Fbm {
    /// The height at `(x, z)` and its gradient `(dh/dx, dh/dz)` (scalar lanes).
    pub fn height(&self, hash: Hash, x: f32, z: f32) -> (f32, Vec2) {
        let (h, gx, gz) = FbmLanes::new(self, hash).height(Scalar, x, z);
        (h, Vec2::new(gx, gz))
    }

    /// An upper bound of the height over the plane: each octave's noise lies in `[0, 1)`,
    /// so `h < base + |amplitude| * sum_o |gain|^o`.
    pub fn top(&self) -> f32 {
        let sum: f64 = (0..self.octaves.min(MAX_OCTAVES))
            .map(|o| (self.gain.abs() as f64).powi(o as i32))
            .sum();
        (self.base as f64 + self.amplitude.abs() as f64 * sum) as f32
    }

    /// An upper bound of `|grad h|` over the plane.
    ///
    /// Derivation: in one cell of the 2D value noise,
    /// `dn/dx = du(f.x) * ((b - a) (1 - u.y) + (d - c) u.y)`: a convex combination of two
    /// hash differences, each in (-1, 1), times `du = 6 f (1 - f) <= 1.5`; so each partial
    /// is at most 1.5 and `|grad n| <= 1.5 sqrt(2)`. Octave `o` is `n(J_o (x, z))` with
    /// `J_o = frequency * lacunarity^o * R^o`, whose operator norm is
    /// `frequency * lacunarity^o` (R is a rotation), weighted by `amplitude * gain^o`.
    /// Summing the octaves' bounds:
    /// `|amplitude| * sum_o |gain|^o * frequency * lacunarity^o * 1.5 sqrt(2)`.
    pub fn slope_bound(&self) -> f32 {
        let per = (self.gain.abs() as f64) * (self.lacunarity as f64);
        let sum: f64 = (0..self.octaves.min(MAX_OCTAVES))
            .map(|o| per.powi(o as i32))
            .sum();
        (self.amplitude.abs() as f64 * self.frequency as f64 * 1.5 * 2f64.sqrt() * sum) as f32
    }

    /// `1 / sqrt(1 + slope_bound^2)`: multiplies the vertical distance `p.y - h` into a
    /// bound of the distance to the surface `y = h(x, z)`.
    pub fn step_scale(&self) -> f32 {
        let s = self.slope_bound() as f64;
        (1.0 / (1.0 + s * s).sqrt()) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fbm(octaves: u32) -> Fbm {
        Fbm {
            base: -1.0,
            amplitude: 2.0,
            frequency: 0.15,
            lacunarity: 2.0,
            gain: 0.5,
            octaves,
            rotation: 0.6,
        }
    }

    #[test]
    fn hashes_lie_in_the_unit_interval() {
        for hash in [Hash::DotFract, Hash::Sin] {
            for i in -60..60 {
                for j in -60..60 {
                    let (x, y) = (i as f32 * 7.0, j as f32 * 13.0);
                    let h2 = hash2(Scalar, hash, x, y);
                    let h3 = hash3(Scalar, hash, x, y, (i + j) as f32);
                    assert!((0.0..1.0).contains(&h2), "{hash:?} {x} {y}: {h2}");
                    assert!((0.0..1.0).contains(&h3), "{hash:?} {x} {y}: {h3}");
                }
            }
        }
    }

    #[test]
    fn hashes_spread_over_the_interval() {
        // A lattice hash that maps everything to a few values would make flat noise.
        let mut bins = [0u32; 10];
        for i in 0..100 {
            for j in 0..100 {
                let h = hash2(Scalar, Hash::DotFract, i as f32, j as f32);
                bins[(h * 10.0) as usize] += 1;
            }
        }
        assert!(bins.iter().all(|&b| b > 700 && b < 1300), "{bins:?}");
    }

    #[test]
    fn value_noise_interpolates_the_lattice_hashes() {
        for hash in [Hash::DotFract, Hash::Sin] {
            let (v, _, _) = noise2(Scalar, hash, 3.0, -5.0);
            assert_eq!(v, hash2(Scalar, hash, 3.0, -5.0));
            let v3 = noise3(Scalar, hash, 3.0, -5.0, 2.0);
            assert_eq!(v3, hash3(Scalar, hash, 3.0, -5.0, 2.0));
        }
    }

    #[test]
    fn fbm_gradient_matches_finite_differences() {
        for hash in [Hash::DotFract, Hash::Sin] {
            let f = fbm(5);
            let e = 1e-2f64;
            for k in 0..200 {
                let x = -20.0 + k as f32 * 0.37;
                let z = 11.0 - k as f32 * 0.23;
                let (_, g) = f.height(hash, x, z);
                let h = |x: f32, z: f32| f.height(hash, x, z).0 as f64;
                let fx = (h(x + e as f32, z) - h(x - e as f32, z)) / (2.0 * e);
                let fz = (h(x, z + e as f32) - h(x, z - e as f32)) / (2.0 * e);
                let tol = 0.02 * f.slope_bound() as f64;
                assert!((g.x as f64 - fx).abs() < tol, "{x} {z}: {} vs {fx}", g.x);
                assert!((g.y as f64 - fz).abs() < tol, "{x} {z}: {} vs {fz}", g.y);
            }
        }
    }

    #[test]
    fn height_only_equals_the_height_of_height() {
        let f = FbmLanes::new(&fbm(6), Hash::DotFract);
        for k in 0..100 {
            let (x, z) = (k as f32 * 0.71, k as f32 * -0.13);
            assert_eq!(f.height_only(Scalar, x, z), f.height(Scalar, x, z).0);
        }
    }

    /// The largest sampled `|grad h|` over a dense grid.
    fn sampled_max_slope(f: &Fbm) -> f32 {
        let mut best = 0.0f32;
        let step = 0.05 / f.frequency;
        for i in 0..600 {
            for j in 0..600 {
                let (_, g) = f.height(Hash::DotFract, i as f32 * step, j as f32 * step);
                best = best.max(g.length());
            }
        }
        best
    }

    #[test]
    fn top_bounds_the_sampled_heights() {
        for octaves in [1, 4, 6] {
            let f = fbm(octaves);
            let lanes = FbmLanes::new(&f, Hash::DotFract);
            let top = f.top();
            let mut highest = f32::NEG_INFINITY;
            for k in 0..20_000 {
                let (x, z) = ((k % 200) as f32 * 0.37, (k / 200) as f32 * 0.53);
                highest = highest.max(lanes.height_only(Scalar, x, z));
            }
            assert!(highest <= top, "{octaves} octaves: {highest} > {top}");
        }
    }

    #[test]
    fn slope_bound_bounds_the_sampled_slope_and_is_not_loose() {
        for octaves in [1, 2] {
            let f = fbm(octaves);
            let (bound, seen) = (f.slope_bound(), sampled_max_slope(&f));
            assert!(
                seen <= bound,
                "{octaves} octaves: seen {seen} > bound {bound}"
            );
            assert!(
                seen * 2.0 >= bound,
                "{octaves} octaves: seen {seen}, bound {bound}"
            );
        }
        // More octaves: still a bound (their peaks rarely line up, so it is looser).
        let f = fbm(6);
        assert!(sampled_max_slope(&f) <= f.slope_bound());
    }

    #[test]
    fn step_scale_is_the_lipschitz_factor() {
        let f = fbm(4);
        let s = f.slope_bound();
        // amplitude * frequency * 1.5 sqrt 2 * (1 + 1 + 1 + 1) with gain * lacunarity = 1.
        let expect = 2.0 * 0.15 * 1.5 * 2f32.sqrt() * 4.0;
        assert!((s - expect).abs() < 1e-5, "{s} vs {expect}");
        assert!((f.step_scale() - 1.0 / (1.0 + s * s).sqrt()).abs() < 1e-6);
        assert!(f.step_scale() > 0.0 && f.step_scale() < 1.0);
    }
}
