//! Ray casts by sphere tracing, and the conservative march shared with swept circles.

use glam::Vec2;

use super::{QueryError, check_positive, check_scalar, check_vec, eval, lipschitz, normalize};
use crate::Sdf;

/// Options of [`raycast`] and [`sweep_circle`](super::sweep_circle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayOptions {
    /// Maximum number of field evaluations of the march (the initial point included).
    /// Exceeding it is [`QueryError::StepBudget`]. Default 1024.
    pub max_steps: u32,
    /// Hit tolerance in world units, compared with the distance estimate `d / L` (minus the
    /// radius for sweeps): the march reports a hit once the estimate drops below it.
    /// Must be finite and `> 0`. Default `1e-3`.
    pub hit_epsilon: f32,
}

impl Default for RayOptions {
    fn default() -> Self {
        RayOptions {
            max_steps: 1024,
            hit_epsilon: 1e-3,
        }
    }
}

/// A ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Distance along the (normalized) direction from the origin, in world units.
    pub t: f32,
    /// `origin + dir * t`: within `hit_epsilon * L` (in field value) of the surface, on the
    /// near side of the first crossing (or the origin, when it starts inside). Where the
    /// spacing of `f32` points along the ray exceeds `hit_epsilon` (huge coordinates), it is
    /// the last representable point before the crossing instead.
    pub point: Vec2,
    /// Unit surface normal from the field's gradient at `point`; `-dir` where the gradient is
    /// zero (medial axis, clamped region) or not finite.
    pub normal: Vec2,
    /// Field evaluations used.
    pub steps: u32,
}

/// Casts a ray from `origin` along `dir` (normalized internally) up to distance `max_t`.
///
/// Sphere tracing: from `t`, the disc of radius `d(p(t)) / L` is clear of the surface. Steps
/// are over-relaxed (1.6 times that radius, except within 32 times `hit_epsilon` of the
/// surface) and kept only where the disc at the landing point overlaps the last one, so
/// the two together clear the whole step; otherwise the march takes the plain step and
/// steps plainly from then on. No crossing is ever skipped whatever the feature
/// thickness. A hit is reported when `d / L < hit_epsilon`. Stretches
/// that the field proves clear ([`Sdf::clear_run`]: a terrain's cells of air, and the
/// base's clearance outside its grid) are crossed without evaluating it.
///
/// * An origin inside the terrain, or within `hit_epsilon` of it, is a hit at `t = 0` (whatever
///   `max_t`).
/// * Otherwise `max_t <= 0` gives `Ok(None)`, as does reaching `max_t` (or leaving the range
///   of finite `f32` points) without a hit.
/// * `Err(StepBudget)` when `opts.max_steps` evaluations did not settle it (a ray grazing a
///   surface advances by the clearance per step).
/// * `Err(NoProgress)` when `t + step == t` in `f32` (far from the origin with a tiny
///   `hit_epsilon`).
/// * Errors on non-finite `origin`, `dir`, `max_t` (use `f32::MAX` for an unbounded ray), a
///   zero `dir`, invalid options or a non-finite field value.
pub fn raycast<F: Sdf>(
    field: &F,
    origin: Vec2,
    dir: Vec2,
    max_t: f32,
    opts: &RayOptions,
) -> Result<Option<RayHit>, QueryError> {
    check_vec("origin", origin)?;
    check_vec("dir", dir)?;
    check_scalar("max_t", max_t)?;
    let dir = normalize(dir).ok_or(QueryError::ZeroDirection {
        argument: "dir",
        value: dir,
    })?;
    let hit = march(field, origin, dir, max_t, 0.0, opts)?;
    Ok(hit.map(|h| RayHit {
        t: h.t,
        point: h.point,
        normal: h.normal,
        steps: h.steps,
    }))
}

/// The result of [`march`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct MarchHit {
    pub t: f32,
    pub point: Vec2,
    pub normal: Vec2,
    /// The distance estimate `d / L` at `point`.
    pub estimate: f32,
    pub steps: u32,
}

/// Bisection steps used when rounding (or a field breaking its Lipschitz promise) lands a
/// step past the surface.
const BISECTION_STEPS: u32 = 32;

/// Sphere-traces `g(t) = d(origin + dir * t) / L - radius` for `t` in `[0, max_t]`, `dir` unit.
///
/// Returns the first `t` with `g < hit_epsilon`, never past the first zero of `g`.
pub(crate) fn march<F: Sdf>(
    field: &F,
    origin: Vec2,
    dir: Vec2,
    max_t: f32,
    radius: f32,
    opts: &RayOptions,
) -> Result<Option<MarchHit>, QueryError> {
    check_positive("hit_epsilon", opts.hit_epsilon)?;
    let l = lipschitz(field)?;
    let eps = opts.hit_epsilon;
    let gap = |p: Vec2| -> Result<f32, QueryError> { Ok(eval(field, p)? / l - radius) };

    let mut t = 0.0f32;
    let mut steps = 0u32;
    // The last point known to be clear (`t` and its gap `g >= eps`), for the bisection
    // fallback and to check over-relaxed steps.
    let mut clear: Option<(f32, f32)> = None;
    let mut relaxed = false;
    // Dropped to 1 at the first step that fails: from there the march is plain sphere
    // tracing, and the failed step cost one evaluation.
    let mut relax = RELAX;
    let mut skips = Skips::new(radius, eps, l, opts.max_steps);
    loop {
        if steps >= opts.max_steps {
            return Err(QueryError::StepBudget { t, steps, max_t });
        }
        if !relaxed && let Some(next) = skips.ask(field, origin, dir, t) {
            if next >= max_t {
                return Ok(None);
            }
            // The whole skipped stretch is at least `eps` clear, its end included.
            clear = Some((next, eps));
            t = next;
            continue;
        }
        let p = origin + dir * t;
        let finite = p.x.is_finite() && p.y.is_finite();
        let g = if finite { gap(p)? } else { f32::NAN };
        steps += u32::from(finite);
        if let (true, Some((t0, g0))) = (relaxed, clear) {
            relaxed = false;
            // The step went past the clear disc at `t0`; it stands only where the disc
            // here reaches back over the rest of it, so that together they clear the whole
            // step, with `eps` and the rounding of points this far out to spare (at 1e8
            // units a point is off by several units). Otherwise take the plain step.
            let rounding = 16.0 * f32::EPSILON * (t.abs() + origin.x.abs() + origin.y.abs());
            // A NaN gap (a point past the range of `f32`) overlaps nothing.
            let overlaps = g + g0 >= (t - t0) + eps + rounding;
            if !overlaps {
                t = t0 + g0;
                relax = 1.0;
                continue;
            }
        }
        if !finite {
            // Left the range of representable points without a crossing.
            return Ok(None);
        }
        let clear_t = clear.map(|(t0, _)| t0);
        if g < eps {
            let (t, p, g) = match clear_t {
                Some(lo) if g < 0.0 => {
                    let (t, p, g, used) = bisect(&gap, origin, dir, lo, t, eps)?;
                    steps = steps.saturating_add(used);
                    (t, p, g)
                }
                _ => (t, p, g),
            };
            let normal = normalize(field.sample(p).gradient).unwrap_or(-dir);
            return Ok(Some(MarchHit {
                t,
                point: p,
                normal,
                estimate: g + radius,
                steps,
            }));
        }
        if t >= max_t {
            return Ok(None);
        }
        let next = t + g;
        if next >= max_t {
            // The disc of radius g around p(t) is clear, and it covers the rest of the path
            // (for sweeps: the moving circle stays clear of the surface).
            return Ok(None);
        }
        if next <= t {
            return Err(QueryError::NoProgress { t, point: p });
        }
        clear = Some((t, g));
        // The disc clears the plain step: a stretch the field proves clear from its end
        // is crossed at once.
        if let Some(end) = skips.ask(field, origin, dir, next) {
            if end >= max_t {
                return Ok(None);
            }
            clear = Some((end, eps));
            t = end;
            continue;
        }
        // Over-relaxed: a ray grazing a wall sees gaps that shrink slowly, and steps past
        // them by `RELAX` are checked at the next evaluation (Keinert et al. 2014). Not
        // within `RELAX_FROM` hit tolerances of the surface: a relaxed step is kept only
        // where it lands with a gap of `(RELAX - 1) g + eps`, which a ray closing in on
        // the surface there almost never has, and the failed step costs an evaluation.
        let relax = if g > RELAX_FROM * eps { relax } else { 1.0 };
        let far = (t + relax * g).min(max_t);
        relaxed = far > next;
        t = if relaxed { far } else { next };
    }
}

/// The march's questions to the field about stretches it may skip ([`Sdf::clear_run`]):
/// asked where the last answer said asking again may prove more, at most `max_steps` times.
struct Skips {
    /// The field value that keeps the gap at least `eps`, with room for the rounding of
    /// `d / L - radius`; `NaN` when no threshold is meaningful.
    above: f32,
    /// The march asks again once `t` reaches this.
    ask_at: f32,
    /// The last `t` asked at: an answer that proves nothing is not asked again there.
    asked: f32,
    left: u32,
}

impl Skips {
    fn new(radius: f32, eps: f32, l: f32, max_steps: u32) -> Skips {
        let above = (radius + eps) * l * (1.0 + 1.0 / 65536.0);
        Skips {
            above: if above.is_finite() { above } else { f32::NAN },
            ask_at: 0.0,
            asked: f32::NAN,
            left: max_steps,
        }
    }

    /// The end of the stretch from `t` that the field proves clear, if it proves one.
    fn ask<F: Sdf>(&mut self, field: &F, origin: Vec2, dir: Vec2, t: f32) -> Option<f32> {
        // `ask_at` may be infinite (never again); `t` is finite here.
        let due = t >= self.ask_at && t != self.asked;
        if !due || self.left == 0 || self.above.is_nan() {
            return None;
        }
        self.left -= 1;
        self.asked = t;
        let run = field.clear_run(origin + dir * t, dir, self.above);
        let next = t + run.clear;
        // A stretch too short to move `t` proves nothing the march can use.
        let end = if run.clear > 0.0 && next > t { next } else { t };
        self.ask_at = end + run.retry_after.max(0.0);
        (end > t).then_some(end)
    }
}

/// Over-relaxation of the march's steps: each is `RELAX` times the clear gap, kept when
/// the gap where it lands overlaps the last one. Fewer evaluations for grazing rays; the
/// first step that fails costs one evaluation, and the march steps plainly after it.
const RELAX: f32 = 1.6;

/// Gaps up to this many hit tolerances take plain steps (see [`march`]): measured on rays
/// ending at cratered terrain, 8, 32 and 128 save the same evaluations (8.33 -> 7.95 per
/// ray that hits), 32 is in the middle.
const RELAX_FROM: f32 = 32.0;

/// Bisects `[lo, hi]` (`g(lo) >= 0 > g(hi)`) for a point with `0 <= g < eps`, keeping the
/// clear end. Returns `(t, point, g, evaluations)`.
fn bisect(
    gap: &impl Fn(Vec2) -> Result<f32, QueryError>,
    origin: Vec2,
    dir: Vec2,
    mut lo: f32,
    mut hi: f32,
    eps: f32,
) -> Result<(f32, Vec2, f32, u32), QueryError> {
    let mut p_lo = origin + dir * lo;
    let mut g_lo = gap(p_lo)?;
    let mut used = 1;
    for _ in 0..BISECTION_STEPS {
        if g_lo < eps {
            break;
        }
        let mid = lo + (hi - lo) * 0.5;
        if !(mid > lo && mid < hi) {
            break;
        }
        let p = origin + dir * mid;
        let g = gap(p)?;
        used += 1;
        if g < 0.0 {
            hi = mid;
        } else {
            lo = mid;
            p_lo = p;
            g_lo = g;
        }
    }
    Ok((lo, p_lo, g_lo, used))
}

#[cfg(test)]
mod tests {
    use super::super::test_fields::*;
    use super::*;

    fn opts() -> RayOptions {
        RayOptions::default()
    }

    #[test]
    fn hits_a_circle_head_on() {
        let c = Circle {
            center: Vec2::new(10.0, 0.0),
            radius: 2.0,
        };
        let h = raycast(&c, Vec2::ZERO, Vec2::new(5.0, 0.0), 100.0, &opts())
            .unwrap()
            .unwrap();
        assert!(h.t <= 8.0 && h.t > 8.0 - 1e-3, "{h:?}");
        assert!((h.normal - Vec2::NEG_X).length() < 1e-5, "{h:?}");
        assert_eq!(h.point, Vec2::ZERO + Vec2::X * h.t);
        let d = c.distance(h.point);
        assert!((0.0..1e-3).contains(&d), "{d}");
    }

    #[test]
    fn misses_and_short_rays_give_none() {
        let c = Circle {
            center: Vec2::new(10.0, 0.0),
            radius: 2.0,
        };
        assert_eq!(
            raycast(&c, Vec2::ZERO, Vec2::Y, 100.0, &opts()).unwrap(),
            None
        );
        assert_eq!(
            raycast(&c, Vec2::ZERO, Vec2::X, 7.5, &opts()).unwrap(),
            None
        );
        assert_eq!(
            raycast(&c, Vec2::ZERO, Vec2::X, 0.0, &opts()).unwrap(),
            None
        );
        assert_eq!(
            raycast(&c, Vec2::ZERO, Vec2::X, -5.0, &opts()).unwrap(),
            None
        );
    }

    #[test]
    fn starting_inside_is_a_hit_at_zero() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        for max_t in [100.0, 0.0, -1.0] {
            let h = raycast(&c, Vec2::new(0.0, 1.0), Vec2::X, max_t, &opts())
                .unwrap()
                .unwrap();
            assert_eq!(h.t, 0.0);
            assert_eq!(h.point, Vec2::new(0.0, 1.0));
            assert_eq!(h.normal, Vec2::Y);
            assert_eq!(h.steps, 1);
        }
        // Deep inside a zero-gradient region: the normal falls back to -dir.
        let h = raycast(&c, Vec2::ZERO, Vec2::X, 1.0, &opts())
            .unwrap()
            .unwrap();
        assert_eq!(h.normal, Vec2::NEG_X);
    }

    #[test]
    fn bad_arguments_are_named() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        let o = Vec2::new(5.0, 0.0);
        let e = raycast(&c, o, Vec2::ZERO, 10.0, &opts()).unwrap_err();
        assert!(matches!(
            e,
            QueryError::ZeroDirection {
                argument: "dir",
                ..
            }
        ));
        assert!(
            e.to_string().contains("`dir`") && e.to_string().contains("zero"),
            "{e}"
        );
        let e = raycast(&c, Vec2::new(f32::NAN, 0.0), Vec2::X, 10.0, &opts()).unwrap_err();
        assert!(
            matches!(
                e,
                QueryError::NonFiniteVector {
                    argument: "origin",
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains("`origin`") && e.to_string().contains("NaN"),
            "{e}"
        );
        let e = raycast(&c, o, Vec2::new(0.0, f32::INFINITY), 10.0, &opts()).unwrap_err();
        assert!(
            matches!(
                e,
                QueryError::NonFiniteVector {
                    argument: "dir",
                    ..
                }
            ),
            "{e}"
        );
        let e = raycast(&c, o, Vec2::X, f32::NAN, &opts()).unwrap_err();
        assert!(
            matches!(
                e,
                QueryError::NonFiniteScalar {
                    argument: "max_t",
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("`max_t`"), "{e}");
        let bad = RayOptions {
            hit_epsilon: 0.0,
            ..opts()
        };
        let e = raycast(&c, o, Vec2::X, 10.0, &bad).unwrap_err();
        assert!(e.to_string().contains("hit_epsilon"), "{e}");
        let nan = Constant {
            value: f32::NAN,
            lipschitz: 1.0,
        };
        let e = raycast(&nan, o, Vec2::X, 10.0, &opts()).unwrap_err();
        assert!(
            matches!(e, QueryError::NonFiniteField { point, .. } if point == o),
            "{e}"
        );
    }

    #[test]
    fn grazing_ray_exhausts_a_small_budget() {
        let ground = Ground { height: 0.0 };
        let small = RayOptions {
            max_steps: 50,
            ..opts()
        };
        let e = raycast(&ground, Vec2::new(0.0, 0.002), Vec2::X, 1000.0, &small).unwrap_err();
        match e {
            QueryError::StepBudget { t, steps, max_t } => {
                assert_eq!(steps, 50);
                assert!(t > 0.09 && t < 0.1, "{t}");
                assert_eq!(max_t, 1000.0);
            }
            other => panic!("{other}"),
        }
        assert!(e.to_string().contains("50 steps"), "{e}");
        // Enough budget for the whole path: no hit.
        let big = RayOptions {
            max_steps: 600,
            ..opts()
        };
        assert_eq!(
            raycast(&ground, Vec2::new(0.0, 0.002), Vec2::X, 1.0, &big).unwrap(),
            None
        );
    }

    #[test]
    fn zero_budget_is_an_immediate_step_budget_error() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        let o = RayOptions {
            max_steps: 0,
            ..opts()
        };
        let e = raycast(&c, Vec2::new(5.0, 0.0), Vec2::X, 10.0, &o).unwrap_err();
        assert!(matches!(e, QueryError::StepBudget { steps: 0, .. }));
    }

    #[test]
    fn lipschitz_two_field_hits_at_the_same_place() {
        let c = Scaled(
            Circle {
                center: Vec2::new(10.0, 0.0),
                radius: 2.0,
            },
            2.0,
        );
        let h = raycast(&c, Vec2::ZERO, Vec2::X, 100.0, &opts())
            .unwrap()
            .unwrap();
        assert!(h.t <= 8.0 && h.t > 8.0 - 1e-3, "{h:?}");
        assert!(c.distance(h.point) < 2e-3);
    }

    #[test]
    fn broken_lipschitz_is_handled() {
        let c = Constant {
            value: 5.0,
            lipschitz: 0.0,
        };
        assert_eq!(
            raycast(&c, Vec2::ZERO, Vec2::X, 100.0, &opts()).unwrap(),
            None
        );
        let c = Constant {
            value: 5.0,
            lipschitz: f32::NAN,
        };
        let e = raycast(&c, Vec2::ZERO, Vec2::X, 100.0, &opts()).unwrap_err();
        assert!(matches!(e, QueryError::InvalidLipschitz { .. }));
    }

    #[test]
    fn huge_values_do_not_panic() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        let r = raycast(
            &c,
            Vec2::new(3e38, 3e38),
            Vec2::new(-1.0, -1.0),
            f32::MAX,
            &opts(),
        );
        // The field overflows to infinity there: an error naming the point, no panic.
        assert!(matches!(r, Err(QueryError::NonFiniteField { .. })), "{r:?}");
        // Marching away from the ground: steps double until they pass max_t.
        let g = Ground { height: 0.0 };
        let r = raycast(
            &g,
            Vec2::new(3.0, 1.0),
            Vec2::new(1e-30, 1e30),
            f32::MAX,
            &opts(),
        )
        .unwrap();
        assert_eq!(r, None);
        let g = Ground { height: 0.0 };
        let h = raycast(
            &g,
            Vec2::new(0.0, 1e30),
            Vec2::new(0.0, -1e-40),
            f32::MAX,
            &opts(),
        )
        .unwrap()
        .unwrap();
        assert!(h.point.y < 1e-3 && h.point.y >= 0.0, "{h:?}");
    }

    #[test]
    fn far_grazing_ray_reports_no_progress() {
        // Passing 0.002 above a circle 1e8 units away: the step is far below ulp(t).
        let c = Circle {
            center: Vec2::new(1e8, 0.0),
            radius: 1.0,
        };
        let e = raycast(&c, Vec2::new(0.0, 1.002), Vec2::X, f32::MAX, &opts()).unwrap_err();
        assert!(matches!(e, QueryError::NoProgress { .. }), "{e}");
    }

    #[test]
    fn deterministic_bits() {
        let c = Circle {
            center: Vec2::new(10.3, 1.7),
            radius: 2.1,
        };
        let run = || {
            raycast(
                &c,
                Vec2::new(-3.3, 0.1),
                Vec2::new(0.9, 0.13),
                100.0,
                &opts(),
            )
            .unwrap()
            .unwrap()
        };
        let (a, b) = (run(), run());
        for (x, y) in [
            (a.t, b.t),
            (a.point.x, b.point.x),
            (a.point.y, b.point.y),
            (a.normal.x, b.normal.x),
            (a.normal.y, b.normal.y),
        ] {
            assert_eq!(x.to_bits(), y.to_bits());
        }
        assert_eq!(a.steps, b.steps);
    }
}
