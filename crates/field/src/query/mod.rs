//! Deterministic collision queries against any [`Sdf`]: ray casts, swept circles, closest
//! points, circle and capsule contacts.
//!
//! Every query here is on the network-synced collision path, so it obeys the determinism
//! contract: only `+ - * /`, `sqrt`, comparisons, sign operations and selects, in a fixed
//! order, with fixed (or deterministically data-dependent) iteration counts. No FMA, no libm,
//! no `f32::min`/`f32::max` (see [`detmath`](craterfield_core::det::math)).
//!
//! # Fields that are bounds
//!
//! A field may be a *bound* rather than an exact distance, and may be clamped to `±M` far
//! from surfaces. The queries rely only on the Lipschitz promise of [`Sdf::lipschitz`]:
//! `|d(a) - d(b)| <= L |a - b|`. From it, `d(p) / L` is a lower bound on the true distance
//! from `p` to the surface, the *distance estimate* used throughout this module:
//!
//! * a step of `d(p) / L` along any direction never crosses the surface (sphere tracing);
//! * a circle of radius `r` centred at `p` is reported in contact when `d(p) / L < r`, with
//!   depth `r - d(p) / L`. For exact fields (`L = 1`) this is exactly `d(p) < r`; for bounds it
//!   is conservative (contacts may be reported early, never missed).
//!
//! A field reporting `L < 1` (including zero or negative values from a broken field) is
//! treated as `L = 1`, which only makes steps smaller; a non-finite `L` is an error
//! ([`QueryError::InvalidLipschitz`]).
//!
//! # Precision
//!
//! Points are `f32`. Far from the origin the spacing of representable points grows (about
//! `0.008` units at `1e5`), and no query can be more precise than that: choose tolerances
//! (`hit_epsilon`) above the coordinate resolution where queries run.

mod closest;
mod contact;
mod raycast;
mod sweep;

pub use closest::{ClosestOptions, SurfacePoint, closest_point};
pub use contact::{CapsuleOptions, Contact, contact_capsule, contact_circle};
pub use raycast::{RayHit, RayOptions, raycast};
pub use sweep::{SweepHit, sweep_circle};

use glam::Vec2;

use crate::Sdf;

/// Why a query could not give an answer.
///
/// Messages name the offending argument and value.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum QueryError {
    /// A scalar argument (or option) is NaN or infinite.
    #[error("argument `{argument}` must be finite, got {value}")]
    NonFiniteScalar {
        /// The argument's name.
        argument: &'static str,
        /// The value passed.
        value: f32,
    },
    /// A vector argument has a NaN or infinite component.
    #[error("argument `{argument}` must be finite, got {value}")]
    NonFiniteVector {
        /// The argument's name.
        argument: &'static str,
        /// The value passed.
        value: Vec2,
    },
    /// A direction argument is the zero vector.
    #[error("argument `{argument}` is a zero-length direction: {value}")]
    ZeroDirection {
        /// The argument's name.
        argument: &'static str,
        /// The value passed.
        value: Vec2,
    },
    /// A radius is negative or not finite.
    #[error("argument `radius` must be finite and >= 0, got {value}")]
    InvalidRadius {
        /// The value passed.
        value: f32,
    },
    /// An option is out of its documented range.
    #[error("option `{option}` is out of range: {value} ({requirement})")]
    InvalidOption {
        /// The option's name.
        option: &'static str,
        /// The value passed.
        value: f32,
        /// What the option must satisfy.
        requirement: &'static str,
    },
    /// The field reported a non-finite Lipschitz constant.
    #[error("the field's Lipschitz constant must be finite, got {value}")]
    InvalidLipschitz {
        /// The value the field reported.
        value: f32,
    },
    /// The field returned NaN or an infinity.
    #[error("the field returned a non-finite value {value} at point {point}")]
    NonFiniteField {
        /// Where the field was evaluated.
        point: Vec2,
        /// What it returned.
        value: f32,
    },
    /// The march used its whole step budget without reaching a hit or the end of the path
    /// (typically a path grazing a surface: steps shrink to the clearance).
    #[error("step budget exhausted after {steps} steps at t = {t} (path length {max_t})")]
    StepBudget {
        /// Distance along the path reached (world units).
        t: f32,
        /// Steps taken (field evaluations).
        steps: u32,
        /// Length of the path being marched.
        max_t: f32,
    },
    /// The path parameter stopped advancing: the step is below the `f32` resolution of `t`
    /// there (a `hit_epsilon` too small for coordinates this large).
    #[error(
        "the march stopped advancing at t = {t}, point {point}: hit_epsilon is below the f32 resolution there"
    )]
    NoProgress {
        /// Distance along the path reached (world units).
        t: f32,
        /// The point reached.
        point: Vec2,
    },
}

/// Whether `p` is inside solid terrain (`d(p) < 0`).
///
/// Errors on a non-finite `p` or a non-finite field value.
pub fn inside<F: Sdf>(field: &F, p: Vec2) -> Result<bool, QueryError> {
    check_vec("p", p)?;
    Ok(eval(field, p)? < 0.0)
}

/// `Err` unless both components of `v` are finite.
pub(crate) fn check_vec(argument: &'static str, v: Vec2) -> Result<(), QueryError> {
    if v.x.is_finite() && v.y.is_finite() {
        Ok(())
    } else {
        Err(QueryError::NonFiniteVector { argument, value: v })
    }
}

/// `Err` unless `v` is finite.
pub(crate) fn check_scalar(argument: &'static str, v: f32) -> Result<(), QueryError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(QueryError::NonFiniteScalar { argument, value: v })
    }
}

/// `Err` unless `radius` is finite and `>= 0`.
pub(crate) fn check_radius(radius: f32) -> Result<(), QueryError> {
    if radius.is_finite() && radius >= 0.0 {
        Ok(())
    } else {
        Err(QueryError::InvalidRadius { value: radius })
    }
}

/// `Err` unless `v` is finite and `> 0`.
pub(crate) fn check_positive(option: &'static str, v: f32) -> Result<(), QueryError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(QueryError::InvalidOption {
            option,
            value: v,
            requirement: "must be finite and > 0",
        })
    }
}

/// The Lipschitz constant the queries use: the field's, raised to at least 1.
pub(crate) fn lipschitz<F: Sdf>(field: &F) -> Result<f32, QueryError> {
    let l = field.lipschitz();
    if !l.is_finite() {
        return Err(QueryError::InvalidLipschitz { value: l });
    }
    Ok(if l >= 1.0 { l } else { 1.0 })
}

/// The field's distance at `p`, or `Err` if it is not finite.
pub(crate) fn eval<F: Sdf>(field: &F, p: Vec2) -> Result<f32, QueryError> {
    let d = field.distance(p);
    if d.is_finite() {
        Ok(d)
    } else {
        Err(QueryError::NonFiniteField { point: p, value: d })
    }
}

/// `v` scaled to unit length, or `None` for a zero or non-finite vector.
///
/// Scales by the largest component first so that huge and subnormal vectors neither
/// overflow nor underflow. Plain operations only, in a fixed order.
pub(crate) fn normalize(v: Vec2) -> Option<Vec2> {
    if !(v.x.is_finite() && v.y.is_finite()) {
        return None;
    }
    let m = craterfield_core::det::math::max(v.x.abs(), v.y.abs());
    if m <= 0.0 {
        return None;
    }
    let s = Vec2::new(v.x / m, v.y / m);
    let len = (s.x * s.x + s.y * s.y).sqrt();
    Some(Vec2::new(s.x / len, s.y / len))
}

/// Length of `v` without overflow for finite `v` (`inf` only if the length itself overflows).
pub(crate) fn length(v: Vec2) -> f32 {
    let m = craterfield_core::det::math::max(v.x.abs(), v.y.abs());
    if m <= 0.0 {
        return 0.0;
    }
    let s = Vec2::new(v.x / m, v.y / m);
    (s.x * s.x + s.y * s.y).sqrt() * m
}

#[cfg(test)]
pub(crate) mod test_fields {
    //! Analytic test fields with exact distances and gradients.

    use glam::Vec2;

    use crate::{Sample, Sdf};

    /// A disc: negative inside.
    pub(crate) struct Circle {
        pub center: Vec2,
        pub radius: f32,
    }

    impl Sdf for Circle {
        fn distance(&self, p: Vec2) -> f32 {
            (p - self.center).length() - self.radius
        }
        fn sample(&self, p: Vec2) -> Sample {
            let v = p - self.center;
            let len = v.length();
            let gradient = if len > 0.0 { v / len } else { Vec2::ZERO };
            Sample {
                distance: len - self.radius,
                gradient,
                material: 0,
            }
        }
        fn lipschitz(&self) -> f32 {
            1.0
        }
    }

    /// Solid below the line `y = height` (ground).
    pub(crate) struct Ground {
        pub height: f32,
    }

    impl Sdf for Ground {
        fn distance(&self, p: Vec2) -> f32 {
            p.y - self.height
        }
        fn sample(&self, p: Vec2) -> Sample {
            Sample {
                distance: p.y - self.height,
                gradient: Vec2::Y,
                material: 0,
            }
        }
        fn lipschitz(&self) -> f32 {
            1.0
        }
    }

    /// An axis-aligned box with exact distance and gradient.
    pub(crate) struct Boxy {
        pub center: Vec2,
        pub half: Vec2,
    }

    impl Sdf for Boxy {
        fn distance(&self, p: Vec2) -> f32 {
            self.sample(p).distance
        }
        fn sample(&self, p: Vec2) -> Sample {
            let v = p - self.center;
            let q = v.abs() - self.half;
            let sx = if v.x < 0.0 { -1.0 } else { 1.0 };
            let sy = if v.y < 0.0 { -1.0 } else { 1.0 };
            if q.x > 0.0 || q.y > 0.0 {
                let o = Vec2::new(
                    if q.x > 0.0 { q.x } else { 0.0 },
                    if q.y > 0.0 { q.y } else { 0.0 },
                );
                let len = o.length();
                let g = Vec2::new(o.x * sx, o.y * sy) / len;
                Sample {
                    distance: len,
                    gradient: g,
                    material: 0,
                }
            } else if q.x > q.y {
                Sample {
                    distance: q.x,
                    gradient: Vec2::new(sx, 0.0),
                    material: 0,
                }
            } else {
                Sample {
                    distance: q.y,
                    gradient: Vec2::new(0.0, sy),
                    material: 0,
                }
            }
        }
        fn lipschitz(&self) -> f32 {
            1.0
        }
    }

    /// Another field scaled by `k >= 1`, declaring Lipschitz `k`.
    pub(crate) struct Scaled<F>(pub F, pub f32);

    impl<F: Sdf> Sdf for Scaled<F> {
        fn distance(&self, p: Vec2) -> f32 {
            self.0.distance(p) * self.1
        }
        fn sample(&self, p: Vec2) -> Sample {
            let s = self.0.sample(p);
            Sample {
                distance: s.distance * self.1,
                gradient: s.gradient * self.1,
                material: s.material,
            }
        }
        fn lipschitz(&self) -> f32 {
            self.0.lipschitz() * self.1
        }
    }

    /// A field returning a constant (possibly NaN) value and a configurable Lipschitz constant.
    pub(crate) struct Constant {
        pub value: f32,
        pub lipschitz: f32,
    }

    impl Sdf for Constant {
        fn distance(&self, _p: Vec2) -> f32 {
            self.value
        }
        fn sample(&self, _p: Vec2) -> Sample {
            Sample {
                distance: self.value,
                gradient: Vec2::ZERO,
                material: 0,
            }
        }
        fn lipschitz(&self) -> f32 {
            self.lipschitz
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_fields::*;
    use super::*;

    #[test]
    fn inside_reports_sign_and_errors() {
        let c = Circle {
            center: Vec2::ZERO,
            radius: 2.0,
        };
        assert!(inside(&c, Vec2::new(1.0, 0.0)).unwrap());
        assert!(!inside(&c, Vec2::new(3.0, 0.0)).unwrap());
        assert!(!inside(&c, Vec2::new(2.0, 0.0)).unwrap());
        let e = inside(&c, Vec2::new(f32::NAN, 0.0)).unwrap_err();
        assert!(matches!(
            e,
            QueryError::NonFiniteVector { argument: "p", .. }
        ));
        assert!(e.to_string().contains("`p`"), "{e}");
        let nan = Constant {
            value: f32::NAN,
            lipschitz: 1.0,
        };
        let e = inside(&nan, Vec2::new(1.0, 2.0)).unwrap_err();
        assert!(matches!(e, QueryError::NonFiniteField { .. }));
        assert!(e.to_string().contains("[1, 2]"), "{e}");
    }

    #[test]
    fn normalize_handles_extremes() {
        assert_eq!(normalize(Vec2::ZERO), None);
        assert_eq!(normalize(Vec2::new(f32::NAN, 1.0)), None);
        assert_eq!(normalize(Vec2::new(f32::INFINITY, 1.0)), None);
        let n = normalize(Vec2::new(3e38, 3e38)).unwrap();
        assert!((n.length() - 1.0).abs() < 1e-6);
        let n = normalize(Vec2::new(1e-45, 0.0)).unwrap();
        assert_eq!(n, Vec2::X);
        assert_eq!(normalize(Vec2::new(0.0, -5.0)).unwrap(), Vec2::NEG_Y);
        assert!((length(Vec2::new(2e38, 2e38)) - 2.828_427e38).abs() < 1e32);
        assert_eq!(length(Vec2::new(3e38, 3e38)), f32::INFINITY);
        assert_eq!(length(Vec2::new(3.0, 4.0)), 5.0);
    }

    #[test]
    fn lipschitz_below_one_is_one_and_non_finite_is_an_error() {
        assert_eq!(
            lipschitz(&Constant {
                value: 1.0,
                lipschitz: 0.0
            })
            .unwrap(),
            1.0
        );
        assert_eq!(
            lipschitz(&Constant {
                value: 1.0,
                lipschitz: -3.0
            })
            .unwrap(),
            1.0
        );
        assert_eq!(
            lipschitz(&Constant {
                value: 1.0,
                lipschitz: 2.5
            })
            .unwrap(),
            2.5
        );
        let e = lipschitz(&Constant {
            value: 1.0,
            lipschitz: f32::NAN,
        })
        .unwrap_err();
        assert!(matches!(e, QueryError::InvalidLipschitz { .. }));
        assert!(
            lipschitz(&Constant {
                value: 1.0,
                lipschitz: f32::INFINITY
            })
            .is_err()
        );
    }
}
