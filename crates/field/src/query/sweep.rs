//! Continuous collision of a moving circle (swept-circle time of impact).

use glam::Vec2;

use super::raycast::march;
use super::{
    QueryError, RayOptions, check_positive, check_radius, check_vec, eval, length, lipschitz,
    normalize,
};
use crate::Sdf;

/// The first contact of a moving circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepHit {
    /// Time of impact as a fraction of the motion, in `[0, 1]`: `0` for an initial overlap.
    pub toi: f32,
    /// The circle's centre at contact (marched along the normalized motion direction, so it
    /// can differ from `from + (to - from) * toi` by rounding).
    pub center: Vec2,
    /// Unit surface normal from the field's gradient at `center` (pointing out of the
    /// terrain, towards the centre); `-direction of motion` where the gradient is zero (and
    /// `+y` for a motionless circle with a zero gradient).
    pub normal: Vec2,
    /// Estimated contact point on the terrain surface: `center - normal * d(center) / L`
    /// (exact for exact fields away from the medial axis).
    pub point: Vec2,
    /// Field evaluations used.
    pub steps: u32,
}

/// Sweeps a circle of `radius` from `from` to `to` and returns its first contact with the
/// terrain.
///
/// Sphere tracing on the clearance `d(c) / L - radius` along the motion: every step is the
/// current clearance, which the circle can travel without touching anything, so there is no
/// tunnelling at any speed or through features of any thickness. The only limit is the step
/// budget: a sweep costs about `path length / minimum clearance along the path` steps
/// (capped by `opts.max_steps`, then [`QueryError::StepBudget`]). Contact is reported when the
/// clearance drops below `opts.hit_epsilon`.
///
/// * An initial overlap (or a clearance below `hit_epsilon` at `from`) gives `toi = 0`.
/// * Motions longer than `f32::MAX` (opposite extreme coordinates) are marched over their first
///   `f32::MAX` units only.
/// * `from == to` is a point test: `toi = 0` when overlapping, else `None`.
/// * Errors on non-finite `from`/`to`, a negative or non-finite `radius`, invalid options, a
///   non-finite field value, or `NoProgress` (see [`raycast`](super::raycast())).
pub fn sweep_circle<F: Sdf>(
    field: &F,
    from: Vec2,
    to: Vec2,
    radius: f32,
    opts: &RayOptions,
) -> Result<Option<SweepHit>, QueryError> {
    check_vec("from", from)?;
    check_vec("to", to)?;
    check_radius(radius)?;
    check_positive("hit_epsilon", opts.hit_epsilon)?;
    // The motion is measured at scale `1 / k`, with `k = 4` only where `to - from` or its
    // length would overflow (extreme coordinates); `k` is a power of two, so exact.
    let motion = to - from;
    let len = length(motion);
    let (motion, len, k) = if len.is_finite() {
        (motion, len, 1.0)
    } else {
        let q = to * 0.25 - from * 0.25;
        (q, length(q), 4.0)
    };
    let Some(dir) = normalize(motion).filter(|_| len > 0.0) else {
        return point_test(field, from, radius, opts);
    };
    let max_t = len * k;
    let max_t = if max_t.is_finite() { max_t } else { f32::MAX };
    let Some(h) = march(field, from, dir, max_t, radius, opts)? else {
        return Ok(None);
    };
    let toi = (h.t / k) / len;
    let toi = if toi > 1.0 { 1.0 } else { toi };
    Ok(Some(SweepHit {
        toi,
        center: h.point,
        normal: h.normal,
        point: h.point - h.normal * h.estimate,
        steps: h.steps,
    }))
}

/// The motionless case.
fn point_test<F: Sdf>(
    field: &F,
    c: Vec2,
    radius: f32,
    opts: &RayOptions,
) -> Result<Option<SweepHit>, QueryError> {
    let l = lipschitz(field)?;
    if opts.max_steps == 0 {
        return Err(QueryError::StepBudget {
            t: 0.0,
            steps: 0,
            max_t: 0.0,
        });
    }
    let estimate = eval(field, c)? / l;
    if estimate - radius >= opts.hit_epsilon {
        return Ok(None);
    }
    let normal = normalize(field.sample(c).gradient).unwrap_or(Vec2::Y);
    Ok(Some(SweepHit {
        toi: 0.0,
        center: c,
        normal,
        point: c - normal * estimate,
        steps: 1,
    }))
}

#[cfg(test)]
mod tests {
    use super::super::test_fields::*;
    use super::*;

    fn opts() -> RayOptions {
        RayOptions::default()
    }

    #[test]
    fn falling_circle_lands_on_ground() {
        let g = Ground { height: 0.0 };
        let h = sweep_circle(
            &g,
            Vec2::new(3.0, 10.0),
            Vec2::new(3.0, -10.0),
            1.0,
            &opts(),
        )
        .unwrap()
        .unwrap();
        // Contact when the centre is at height 1: 9 of 20 units.
        assert!(h.toi <= 0.45 && h.toi > 0.45 - 1e-4, "{h:?}");
        assert!(h.center.y >= 1.0 && h.center.y < 1.001, "{h:?}");
        assert_eq!(h.normal, Vec2::Y);
        assert!(h.point.y.abs() < 1e-5, "{h:?}");
    }

    #[test]
    fn fast_circle_does_not_tunnel_through_a_thin_wall() {
        let wall = Boxy {
            center: Vec2::new(50.0, 0.0),
            half: Vec2::new(0.01, 5.0),
        };
        let h = sweep_circle(&wall, Vec2::ZERO, Vec2::new(1e5, 0.0), 0.5, &opts())
            .unwrap()
            .unwrap();
        let x = h.center.x;
        assert!(x <= 49.49 && x > 49.48, "{h:?}");
        assert!((h.toi - x / 1e5).abs() < 1e-7);
        assert_eq!(h.normal, Vec2::NEG_X);
    }

    #[test]
    fn misses_and_point_tests() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 1.0,
        };
        assert_eq!(
            sweep_circle(&c, Vec2::new(-5.0, 2.1), Vec2::new(5.0, 2.1), 1.0, &opts()).unwrap(),
            None
        );
        assert!(
            sweep_circle(&c, Vec2::new(-5.0, 1.9), Vec2::new(5.0, 1.9), 1.0, &opts())
                .unwrap()
                .is_some()
        );
        // Motionless: a point test, not an error.
        let p = Vec2::new(1.5, 0.0);
        let h = sweep_circle(&c, p, p, 1.0, &opts()).unwrap().unwrap();
        assert_eq!(h.toi, 0.0);
        assert_eq!(h.center, p);
        assert_eq!(h.normal, Vec2::X);
        assert!((h.point - Vec2::X).length() < 1e-6);
        assert_eq!(sweep_circle(&c, p, p, 0.4, &opts()).unwrap(), None);
    }

    #[test]
    fn initial_overlap_is_toi_zero() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 1.0,
        };
        let h = sweep_circle(&c, Vec2::new(1.5, 0.0), Vec2::new(10.0, 0.0), 1.0, &opts())
            .unwrap()
            .unwrap();
        assert_eq!(h.toi, 0.0);
        assert_eq!(h.center, Vec2::new(1.5, 0.0));
    }

    #[test]
    fn bad_arguments_are_named() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 1.0,
        };
        let a = Vec2::new(5.0, 0.0);
        for r in [-1.0, f32::NAN, f32::INFINITY] {
            let e = sweep_circle(&c, a, a + Vec2::X, r, &opts()).unwrap_err();
            assert!(matches!(e, QueryError::InvalidRadius { .. }), "{e}");
            assert!(e.to_string().contains("`radius`"), "{e}");
        }
        let e = sweep_circle(&c, a, Vec2::new(f32::NAN, 1.0), 1.0, &opts()).unwrap_err();
        assert!(
            matches!(e, QueryError::NonFiniteVector { argument: "to", .. }),
            "{e}"
        );
        let e = sweep_circle(&c, Vec2::INFINITY, a, 1.0, &opts()).unwrap_err();
        assert!(
            matches!(
                e,
                QueryError::NonFiniteVector {
                    argument: "from",
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn huge_motion_does_not_panic() {
        let g = Ground { height: 0.0 };
        // The motion's length overflows f32.
        let o = RayOptions {
            max_steps: 100,
            ..opts()
        };
        let r = sweep_circle(&g, Vec2::new(-3e38, 5.0), Vec2::new(3e38, 5.0), 1.0, &o);
        assert!(matches!(r, Err(QueryError::StepBudget { .. })), "{r:?}");
        let h = sweep_circle(
            &g,
            Vec2::new(0.0, 3e38),
            Vec2::new(0.0, -3e38),
            1.0,
            &opts(),
        )
        .unwrap()
        .unwrap();
        // The f32 spacing of points near 3e38 is about 2e31: the contact is the last
        // representable clear centre before the crossing.
        assert!(h.center.y >= 1.0 && h.center.y <= 2.1e31, "{h:?}");
        assert!(h.toi > 0.49 && h.toi <= 0.5, "{h:?}");
        assert_eq!(h.normal, Vec2::Y);
    }

    #[test]
    fn lipschitz_two_field_contacts_at_the_true_distance() {
        let c = Scaled(
            Circle {
                center: Vec2::new(10.0, 0.0),
                radius: 2.0,
            },
            2.0,
        );
        let h = sweep_circle(&c, Vec2::ZERO, Vec2::new(20.0, 0.0), 1.0, &opts())
            .unwrap()
            .unwrap();
        assert!(h.center.x <= 7.0 && h.center.x > 7.0 - 1e-3, "{h:?}");
        assert!((h.point - Vec2::new(8.0, 0.0)).length() < 1e-3, "{h:?}");
    }

    #[test]
    fn deterministic_bits() {
        let b = Boxy {
            center: Vec2::new(10.3, 1.7),
            half: Vec2::new(0.3, 2.0),
        };
        let run = || {
            sweep_circle(&b, Vec2::new(-3.3, 0.1), Vec2::new(90.0, 7.0), 0.7, &opts())
                .unwrap()
                .unwrap()
        };
        let (a, b) = (run(), run());
        let bits = |h: SweepHit| {
            [
                h.toi, h.center.x, h.center.y, h.normal.x, h.normal.y, h.point.x, h.point.y,
            ]
            .map(f32::to_bits)
        };
        assert_eq!(bits(a), bits(b));
        assert_eq!(a.steps, b.steps);
    }
}
