//! Static overlap contacts of circles and capsules with the terrain (penetration depth,
//! normal, contact point).

use glam::Vec2;

use super::{QueryError, check_radius, check_vec, eval, length, lipschitz, normalize};
use crate::Sdf;

/// A penetration contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Penetration depth `radius - d(center) / L` (> 0).
    pub depth: f32,
    /// Unit normal out of the terrain (normalized gradient at `center`); `+y` where the
    /// gradient is zero or not finite (medial axis, deep in a clamped region).
    pub normal: Vec2,
    /// Contact point on the terrain surface, `center - normal * d(center) / L` (exact for
    /// exact fields away from the medial axis).
    pub point: Vec2,
    /// The circle centre the contact was measured from: the given centre for circles, the
    /// deepest point found on the segment for capsules.
    pub center: Vec2,
}

/// Options of [`contact_capsule`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapsuleOptions {
    /// Maximum number of evenly spaced samples along the segment (at least 2 are always
    /// taken). Default 64.
    pub max_samples: u32,
    /// Samples per radius of segment length: the count is
    /// `ceil(length / radius * samples_per_radius) + 1`, clamped to `[2, max_samples]`.
    /// Non-finite or non-positive values are an error. Default 2 (spacing `radius / 2`).
    pub samples_per_radius: f32,
    /// Golden-section refinement steps around the best sample. Default 20.
    pub refine_steps: u32,
}

impl Default for CapsuleOptions {
    fn default() -> Self {
        CapsuleOptions {
            max_samples: 64,
            samples_per_radius: 2.0,
            refine_steps: 20,
        }
    }
}

/// The contact of a circle of `radius` at `center`: `Some` when `d(center) / L < radius`.
///
/// Errors on a non-finite `center`, a negative or non-finite `radius`, a non-finite field
/// value or Lipschitz constant.
pub fn contact_circle<F: Sdf>(
    field: &F,
    center: Vec2,
    radius: f32,
) -> Result<Option<Contact>, QueryError> {
    check_vec("center", center)?;
    check_radius(radius)?;
    let l = lipschitz(field)?;
    let estimate = eval(field, center)? / l;
    contact_at(field, center, estimate, radius)
}

/// The contact of a circle at `center` whose distance estimate is `estimate`.
fn contact_at<F: Sdf>(
    field: &F,
    center: Vec2,
    estimate: f32,
    radius: f32,
) -> Result<Option<Contact>, QueryError> {
    if estimate >= radius {
        return Ok(None);
    }
    let normal = normalize(field.sample(center).gradient).unwrap_or(Vec2::Y);
    Ok(Some(Contact {
        depth: radius - estimate,
        normal,
        point: center - normal * estimate,
        center,
    }))
}

/// The deepest contact of the capsule `segment a-b` inflated by `radius`.
///
/// Deterministic search for the minimum of `d / L` along the segment: `n` evenly spaced
/// samples (`n` from the length and radius, see [`CapsuleOptions`]), then a fixed number of
/// golden-section steps in the two intervals around the best sample (ties go to the first
/// sample). The result is the contact of the circle at the best point found. Any contact
/// deeper than half the sample spacing is always found (the estimate is 1-Lipschitz along the
/// segment); shallower contacts of features thinner than the spacing may be missed. `a == b`
/// is [`contact_circle`].
///
/// Errors on non-finite `a`/`b`, a negative or non-finite `radius`, invalid options, a
/// non-finite field value or Lipschitz constant.
pub fn contact_capsule<F: Sdf>(
    field: &F,
    a: Vec2,
    b: Vec2,
    radius: f32,
    opts: &CapsuleOptions,
) -> Result<Option<Contact>, QueryError> {
    check_vec("a", a)?;
    check_vec("b", b)?;
    check_radius(radius)?;
    let spr = opts.samples_per_radius;
    if !(spr.is_finite() && spr > 0.0) {
        return Err(QueryError::InvalidOption {
            option: "samples_per_radius",
            value: spr,
            requirement: "must be finite and > 0",
        });
    }
    let l = lipschitz(field)?;
    let ab = b - a;
    let len = length(ab);
    if len <= 0.0 {
        return contact_circle(field, a, radius);
    }
    // A point on the segment at parameter `s` in [0, 1]; the ends are exact.
    let at = |s: f32| -> Vec2 {
        if s >= 1.0 {
            b
        } else if s <= 0.0 {
            a
        } else {
            // (a + ab * s) can overflow when `ab` does; lerp by halves then.
            let p = a + ab * s;
            if p.x.is_finite() && p.y.is_finite() {
                p
            } else {
                a * (1.0 - s) + b * s
            }
        }
    };
    let est = |s: f32| -> Result<(f32, Vec2), QueryError> {
        let p = at(s);
        Ok((eval(field, p)? / l, p))
    };

    // Sample count: ceil(len / radius * spr) + 1, clamped (float to int casts saturate).
    let want = (len / radius * spr).ceil();
    let want = if want.is_finite() && want < 4_294_967_294.0 {
        want as u32 + 1
    } else {
        u32::MAX
    };
    let max = if opts.max_samples < 2 {
        2
    } else {
        opts.max_samples
    };
    let n = if want < 2 {
        2
    } else if want > max {
        max
    } else {
        want
    };
    let last = (n - 1) as f32;

    let mut best_i = 0u32;
    let (mut best, mut best_p) = est(0.0)?;
    for i in 1..n {
        let s = i as f32 / last;
        let (e, p) = est(s)?;
        if e < best {
            best = e;
            best_p = p;
            best_i = i;
        }
    }

    // Golden-section search on the bracket around the best sample.
    let lo_i = if best_i == 0 { 0 } else { best_i - 1 };
    let hi_i = if best_i + 1 >= n { n - 1 } else { best_i + 1 };
    let mut lo = lo_i as f32 / last;
    let mut hi = hi_i as f32 / last;
    const INV_PHI: f32 = 0.618_034;
    let mut x1 = hi - (hi - lo) * INV_PHI;
    let mut x2 = lo + (hi - lo) * INV_PHI;
    let (mut f1, p1) = est(x1)?;
    let (mut f2, p2) = est(x2)?;
    for (f, p) in [(f1, p1), (f2, p2)] {
        if f < best {
            (best, best_p) = (f, p);
        }
    }
    for _ in 0..opts.refine_steps {
        if f1 < f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - (hi - lo) * INV_PHI;
            let (f, p) = est(x1)?;
            f1 = f;
            if f < best {
                (best, best_p) = (f, p);
            }
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + (hi - lo) * INV_PHI;
            let (f, p) = est(x2)?;
            f2 = f;
            if f < best {
                (best, best_p) = (f, p);
            }
        }
    }
    contact_at(field, best_p, best, radius)
}

#[cfg(test)]
mod tests {
    use super::super::test_fields::*;
    use super::*;

    #[test]
    fn circle_contact_matches_analytic() {
        let c = Circle {
            center: Vec2::new(0.0, 0.0),
            radius: 5.0,
        };
        let k = contact_circle(&c, Vec2::new(0.0, 5.5), 1.0)
            .unwrap()
            .unwrap();
        assert!((k.depth - 0.5).abs() < 1e-6, "{k:?}");
        assert_eq!(k.normal, Vec2::Y);
        assert!((k.point - Vec2::new(0.0, 5.0)).length() < 1e-6);
        assert_eq!(k.center, Vec2::new(0.0, 5.5));
        assert_eq!(contact_circle(&c, Vec2::new(0.0, 6.0), 1.0).unwrap(), None);
        assert_eq!(contact_circle(&c, Vec2::new(0.0, 7.0), 1.0).unwrap(), None);
        // Centre inside: depth beyond the radius, point on the surface.
        let k = contact_circle(&c, Vec2::new(3.0, 4.0) * 0.8, 1.0)
            .unwrap()
            .unwrap();
        assert!((k.depth - 2.0).abs() < 1e-5, "{k:?}");
        assert!((k.point - Vec2::new(3.0, 4.0)).length() < 1e-5, "{k:?}");
        // Medial axis: +y fallback.
        let k = contact_circle(&c, Vec2::ZERO, 1.0).unwrap().unwrap();
        assert_eq!(k.normal, Vec2::Y);
        assert_eq!(k.depth, 6.0);
    }

    #[test]
    fn circle_contact_on_lipschitz_two_field() {
        let c = Scaled(
            Circle {
                center: Vec2::ZERO,
                radius: 5.0,
            },
            2.0,
        );
        let k = contact_circle(&c, Vec2::new(0.0, 5.5), 1.0)
            .unwrap()
            .unwrap();
        assert!((k.depth - 0.5).abs() < 1e-6, "{k:?}");
        assert!((k.point - Vec2::new(0.0, 5.0)).length() < 1e-6);
    }

    #[test]
    fn capsule_on_ground_at_an_angle() {
        let g = Ground { height: 0.0 };
        let o = CapsuleOptions::default();
        for (a, b, r) in [
            (Vec2::new(0.0, 0.5), Vec2::new(4.0, 2.0), 1.0),
            (Vec2::new(-3.0, 3.0), Vec2::new(1.0, 0.2), 0.5),
            (Vec2::new(2.0, -0.3), Vec2::new(2.5, 8.0), 0.25),
        ] {
            let k = contact_capsule(&g, a, b, r, &o).unwrap().unwrap();
            let low = if a.y < b.y { a } else { b };
            assert!((k.depth - (r - low.y)).abs() < 1e-6, "{a} {b}: {k:?}");
            assert_eq!(k.center, low);
            assert_eq!(k.normal, Vec2::Y);
            assert!((k.point - Vec2::new(low.x, 0.0)).length() < 1e-6);
        }
        assert_eq!(
            contact_capsule(&g, Vec2::new(0.0, 1.5), Vec2::new(4.0, 2.0), 1.0, &o).unwrap(),
            None
        );
    }

    #[test]
    fn capsule_over_a_bump_finds_the_interior_minimum() {
        let c = Circle {
            center: Vec2::new(1.234, 0.0),
            radius: 1.0,
        };
        let o = CapsuleOptions::default();
        let k = contact_capsule(&c, Vec2::new(-10.0, 1.3), Vec2::new(10.0, 1.3), 0.5, &o)
            .unwrap()
            .unwrap();
        assert!((k.depth - 0.2).abs() < 1e-4, "{k:?}");
        assert!((k.center - Vec2::new(1.234, 1.3)).length() < 1e-2, "{k:?}");
        assert!((k.normal - Vec2::Y).length() < 1e-2, "{k:?}");
        // Degenerate capsule = circle.
        let p = Vec2::new(1.234, 1.3);
        assert_eq!(
            contact_capsule(&c, p, p, 0.5, &o).unwrap(),
            contact_circle(&c, p, 0.5).unwrap()
        );
    }

    #[test]
    fn capsule_errors_and_extremes() {
        let g = Ground { height: 0.0 };
        let o = CapsuleOptions::default();
        let e = contact_capsule(&g, Vec2::ZERO, Vec2::new(f32::NAN, 0.0), 1.0, &o).unwrap_err();
        assert!(e.to_string().contains("`b`"), "{e}");
        let e = contact_capsule(&g, Vec2::ZERO, Vec2::X, -1.0, &o).unwrap_err();
        assert!(
            e.to_string().contains("`radius`") && e.to_string().contains("-1"),
            "{e}"
        );
        let bad = CapsuleOptions {
            samples_per_radius: f32::NAN,
            ..o
        };
        assert!(contact_capsule(&g, Vec2::ZERO, Vec2::X, 1.0, &bad).is_err());
        // Zero radius, huge segment, zero sample budget: no panic.
        let k = contact_capsule(&g, Vec2::new(-3e38, -1.0), Vec2::new(3e38, 1.0), 0.0, &o)
            .unwrap()
            .unwrap();
        assert!(k.depth > 0.0);
        let tiny = CapsuleOptions {
            max_samples: 0,
            refine_steps: 0,
            ..o
        };
        assert!(
            contact_capsule(&g, Vec2::new(0.0, 2.0), Vec2::new(3.0, -1.0), 0.1, &tiny)
                .unwrap()
                .is_some()
        );
        let e = contact_circle(&g, Vec2::new(0.0, f32::INFINITY), 1.0).unwrap_err();
        assert!(e.to_string().contains("`center`"), "{e}");
    }

    #[test]
    fn deterministic_bits() {
        let c = Circle {
            center: Vec2::new(1.234, 0.0),
            radius: 1.0,
        };
        let run = || {
            contact_capsule(
                &c,
                Vec2::new(-3.1, 1.3),
                Vec2::new(7.7, 0.9),
                0.5,
                &CapsuleOptions::default(),
            )
            .unwrap()
            .unwrap()
        };
        let bits = |k: Contact| {
            [
                k.depth, k.normal.x, k.normal.y, k.point.x, k.point.y, k.center.x, k.center.y,
            ]
            .map(f32::to_bits)
        };
        assert_eq!(bits(run()), bits(run()));
    }
}
