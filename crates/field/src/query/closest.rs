//! Closest point on the terrain surface by projection along the gradient.

use glam::Vec2;

use super::{QueryError, check_positive, check_vec, length, lipschitz, normalize};
use crate::Sdf;

/// Options of [`closest_point`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestOptions {
    /// Maximum number of projection steps (field samples: at most `max_iterations + 1`).
    /// Default 16.
    pub max_iterations: u32,
    /// Convergence tolerance on the distance estimate `|d| / L` at the projected point, in
    /// world units. Must be finite and `> 0`. Default `1e-3`.
    pub tolerance: f32,
}

impl Default for ClosestOptions {
    fn default() -> Self {
        ClosestOptions {
            max_iterations: 16,
            tolerance: 1e-3,
        }
    }
}

/// A point on the terrain surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// The surface point (`|d(point)| / L <= tolerance`).
    pub point: Vec2,
    /// Unit outward normal (normalized gradient) at `point`.
    pub normal: Vec2,
    /// Euclidean distance from the query point to `point` (unsigned; use
    /// [`inside`](super::inside) for the side).
    pub distance_from_query: f32,
}

/// Projects `p` onto the surface by Newton steps along the gradient:
/// `q -= d(q) * g / |g|^2`, at most `opts.max_iterations` times, stopping as soon as
/// `|d(q)| / L <= opts.tolerance`.
///
/// For an exact field away from the medial axis one step lands on the closest point. Returns
/// `None` when the gradient vanishes (medial axis, clamped region far from any surface), when
/// the iteration leaves the finite range, or when it has not converged within the budget.
/// Errors on a non-finite `p`, an invalid tolerance, a non-finite field value or Lipschitz
/// constant.
pub fn closest_point<F: Sdf>(
    field: &F,
    p: Vec2,
    opts: &ClosestOptions,
) -> Result<Option<SurfacePoint>, QueryError> {
    check_vec("p", p)?;
    check_positive("tolerance", opts.tolerance)?;
    let l = lipschitz(field)?;
    let mut q = p;
    let mut i = 0u32;
    loop {
        let s = field.sample(q);
        if !s.distance.is_finite() {
            return Err(QueryError::NonFiniteField {
                point: q,
                value: s.distance,
            });
        }
        let g = s.gradient;
        let gg = g.x * g.x + g.y * g.y;
        if !(gg > 0.0 && gg.is_finite()) {
            return Ok(None);
        }
        if (s.distance / l).abs() <= opts.tolerance {
            let Some(normal) = normalize(g) else {
                return Ok(None);
            };
            return Ok(Some(SurfacePoint {
                point: q,
                normal,
                distance_from_query: length(q - p),
            }));
        }
        if i >= opts.max_iterations {
            return Ok(None);
        }
        i += 1;
        let k = s.distance / gg;
        q = Vec2::new(q.x - g.x * k, q.y - g.y * k);
        if !(q.x.is_finite() && q.y.is_finite()) {
            return Ok(None);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_fields::*;
    use super::*;

    fn opts() -> ClosestOptions {
        ClosestOptions::default()
    }

    #[test]
    fn circle_matches_analytic_closest_point() {
        let c = Circle {
            center: Vec2::new(1.0, -2.0),
            radius: 3.0,
        };
        for i in 0..40 {
            let a = i as f32 * 0.37 - 7.0;
            let p = Vec2::new(1.0 + a, -2.0 + 0.6 * a - 1.3);
            let s = closest_point(&c, p, &opts()).unwrap().unwrap();
            let v = p - c.center;
            let expected = c.center + v / v.length() * 3.0;
            assert!((s.point - expected).length() < 1e-3, "{p} {s:?} {expected}");
            assert!((s.normal - v / v.length()).length() < 1e-5);
            assert!((s.distance_from_query - (v.length() - 3.0).abs()).abs() < 1e-3);
        }
    }

    #[test]
    fn box_matches_analytic_closest_point() {
        let b = Boxy {
            center: Vec2::ZERO,
            half: Vec2::new(2.0, 1.0),
        };
        let cases = [
            (Vec2::new(5.0, 0.5), Vec2::new(2.0, 0.5)),
            (Vec2::new(-0.3, -4.0), Vec2::new(-0.3, -1.0)),
            (Vec2::new(4.0, 3.0), Vec2::new(2.0, 1.0)),
            (Vec2::new(-3.0, -2.0), Vec2::new(-2.0, -1.0)),
            // Inside: the nearest side.
            (Vec2::new(1.5, 0.1), Vec2::new(2.0, 0.1)),
            (Vec2::new(0.2, -0.7), Vec2::new(0.2, -1.0)),
        ];
        for (p, expected) in cases {
            let s = closest_point(&b, p, &opts()).unwrap().unwrap();
            assert!(
                (s.point - expected).length() < 1e-3,
                "{p}: {s:?} vs {expected}"
            );
            assert!((s.distance_from_query - (p - expected).length()).abs() < 1e-3);
        }
    }

    #[test]
    fn medial_axis_is_none_without_panic() {
        let c = Circle {
            center: Vec2::new(1.0, 1.0),
            radius: 3.0,
        };
        assert_eq!(
            closest_point(&c, Vec2::new(1.0, 1.0), &opts()).unwrap(),
            None
        );
        let flat = Constant {
            value: 7.0,
            lipschitz: 1.0,
        };
        assert_eq!(closest_point(&flat, Vec2::ZERO, &opts()).unwrap(), None);
    }

    #[test]
    fn on_the_surface_is_itself() {
        let g = Ground { height: 2.0 };
        let s = closest_point(&g, Vec2::new(4.0, 2.0), &opts())
            .unwrap()
            .unwrap();
        assert_eq!(s.point, Vec2::new(4.0, 2.0));
        assert_eq!(s.distance_from_query, 0.0);
        assert_eq!(s.normal, Vec2::Y);
    }

    #[test]
    fn lipschitz_two_field_converges() {
        let c = Scaled(
            Circle {
                center: Vec2::ZERO,
                radius: 2.0,
            },
            2.0,
        );
        let s = closest_point(&c, Vec2::new(0.0, 10.0), &opts())
            .unwrap()
            .unwrap();
        assert!((s.point - Vec2::new(0.0, 2.0)).length() < 1e-3, "{s:?}");
    }

    #[test]
    fn errors_and_budget() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        let e = closest_point(&c, Vec2::new(0.0, f32::NAN), &opts()).unwrap_err();
        assert!(e.to_string().contains("`p`"), "{e}");
        let e = closest_point(
            &c,
            Vec2::X,
            &ClosestOptions {
                tolerance: -1.0,
                ..opts()
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("tolerance"), "{e}");
        // No iterations allowed and not on the surface: not converged.
        let o = ClosestOptions {
            max_iterations: 0,
            ..opts()
        };
        assert_eq!(closest_point(&c, Vec2::new(5.0, 0.0), &o).unwrap(), None);
        // Huge input: the projection overflows or converges, never panics.
        let _ = closest_point(&c, Vec2::new(3e38, -3e38), &opts());
    }

    #[test]
    fn deterministic_bits() {
        let b = Boxy {
            center: Vec2::new(0.3, 0.2),
            half: Vec2::new(2.0, 1.0),
        };
        let run = || {
            closest_point(&b, Vec2::new(4.1, 3.3), &opts())
                .unwrap()
                .unwrap()
        };
        let bits = |s: SurfacePoint| {
            [
                s.point.x,
                s.point.y,
                s.normal.x,
                s.normal.y,
                s.distance_from_query,
            ]
            .map(f32::to_bits)
        };
        assert_eq!(bits(run()), bits(run()));
    }
}
