//! Deterministic 2D value noise: integer lattice hash, smoothstep interpolation.
//!
//! The lattice hash is a polynomial in the wrapped 32-bit integers (multiply-add with odd
//! constants) followed by xor-shift mixing: integer arithmetic, so it is exact everywhere.
//! Lattice values are in [-1, 1); the interpolant uses the cubic fade `3t² - 2t³`, so the
//! noise is C1 and its gradient is bounded by [`NOISE_LIPSCHITZ`].

use craterfield_core::det::math::Num;

/// Bound on |∇ noise| for unit wavelength: per axis `max fade' * max value jump = 1.5 * 2`,
/// so `3 * sqrt(2) = 4.243`, rounded up.
pub const NOISE_LIPSCHITZ: f32 = 4.25;

/// Hash of a lattice point: a polynomial in the coordinates and seed, then mixed.
pub fn lattice_hash(ix: i32, iy: i32, seed: u32) -> u32 {
    let x = ix as u32;
    let y = iy as u32;
    let mut h = x
        .wrapping_mul(0x8da6_b343)
        .wrapping_add(y.wrapping_mul(0xd816_3841))
        .wrapping_add(seed.wrapping_mul(0xcb1a_b31f))
        .wrapping_add(0x9e37_79b9);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}

/// Lattice value in [-1, 1), exactly representable.
pub fn lattice_value(ix: i32, iy: i32, seed: u32) -> f32 {
    // 24 bits fit f32 exactly; the scale is a power of two.
    (lattice_hash(ix, iy, seed) >> 8) as f32 * (1.0 / 8_388_608.0) - 1.0
}

/// Value noise at `(x, y)` (lattice spacing 1), with its gradient when `N` is a dual number.
pub fn value_noise<N: Num>(x: N, y: N, seed: u32) -> N {
    let fx0 = x.value().floor();
    let fy0 = y.value().floor();
    // Saturating float-to-int casts: deterministic for every input, NaN included.
    let ix = fx0 as i32;
    let iy = fy0 as i32;
    let tx = x.offset(-fx0);
    let ty = y.offset(-fy0);
    let ux = fade(tx);
    let uy = fade(ty);
    let v00 = lattice_value(ix, iy, seed);
    let v10 = lattice_value(ix.wrapping_add(1), iy, seed);
    let v01 = lattice_value(ix, iy.wrapping_add(1), seed);
    let v11 = lattice_value(ix.wrapping_add(1), iy.wrapping_add(1), seed);
    let bottom = ux.scale(v10 - v00).offset(v00);
    let top = ux.scale(v11 - v01).offset(v01);
    bottom + uy * (top - bottom)
}

/// `t² (3 - 2t)`.
fn fade<N: Num>(t: N) -> N {
    t * t * (t.scale(-2.0).offset(3.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield_core::det::math::Dual;
    use glam::Vec2;

    #[test]
    fn noise_is_in_range_and_continuous_across_lattice_lines() {
        for i in 0..2000 {
            let x = i as f32 * 0.0137 - 7.0;
            let y = (i * 31 % 997) as f32 * 0.021 - 9.0;
            let n = value_noise(x, y, 7);
            assert!((-1.0..=1.0).contains(&n));
        }
        let a = value_noise(3.0 - 1e-4, 0.5, 1);
        let b = value_noise(3.0 + 1e-4, 0.5, 1);
        assert!((a - b).abs() < 1e-3);
    }

    #[test]
    fn noise_gradient_respects_the_lipschitz_bound_and_matches_differences() {
        for i in 0..3000 {
            let p = Vec2::new(
                i as f32 * 0.0731 - 50.0,
                (i * 17 % 1013) as f32 * 0.0913 - 40.0,
            );
            let (x, y) = Dual::point(p);
            let d = value_noise(x, y, 42);
            assert!(d.gradient().length() <= NOISE_LIPSCHITZ);
            let h = 1e-3;
            let fx = (value_noise(p.x + h, p.y, 42) - value_noise(p.x - h, p.y, 42)) / (2.0 * h);
            assert!((fx - d.dx).abs() < 2e-2, "at {p}: {fx} vs {}", d.dx);
        }
    }

    #[test]
    fn seeds_differ() {
        let same = (0..64)
            .filter(|&i| lattice_value(i, 0, 1) == lattice_value(i, 0, 2))
            .count();
        assert!(same < 4);
    }
}
