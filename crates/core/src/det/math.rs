//! Deterministic scalar math for the collision path.
//!
//! Everything here uses only exactly rounded IEEE-754 operations (`+ - * /`, `sqrt`,
//! comparisons, sign-bit operations and selects) in a fixed order, so every platform and every
//! backend gets the same bits (the determinism contract of `docs/ARCHITECTURE.md`).
//! `min`/`max` are defined by compare + select, never by `f32::min`, whose NaN and signed-zero handling is
//! platform-defined in SIMD instruction sets. Transcendentals are fixed polynomials.
//!
//! The [`Num`] trait lets one generic formula run on plain `f32` (distance only) and on
//! [`Dual`] numbers (distance plus analytic gradient in one pass, forward-mode
//! differentiation). The value part of a `Dual` is computed by exactly the same operations as
//! the `f32` path, so `distance(p)` and `sample(p).distance` are bit-identical.

use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::Vec2;

/// `if a < b { a } else { b }`: the project's definition of minimum.
#[inline(always)]
pub fn min(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// `if a > b { a } else { b }`: the project's definition of maximum.
#[inline(always)]
pub fn max(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

/// `min(max(x, lo), hi)`.
#[inline(always)]
pub fn clamp(x: f32, lo: f32, hi: f32) -> f32 {
    min(max(x, lo), hi)
}

/// 2π, rounded to f32.
pub const TAU: f32 = std::f32::consts::TAU;

/// `sin(2π t)` for `t` in turns, by range reduction to a quarter turn and a degree-11 odd
/// Taylor polynomial (absolute error below 1e-6 for |t| < 2^12).
pub fn sin_turns(t: f32) -> f32 {
    // r in [-0.5, 0.5]: floor is exact, the subtraction is exact for |t| < 2^22.
    let mut r = t - (t + 0.5).floor();
    if r > 0.25 {
        r = 0.5 - r;
    } else if r < -0.25 {
        r = -0.5 - r;
    }
    let x = r * TAU;
    let x2 = x * x;
    let p = -2.505_210_8e-8_f32;
    let p = p * x2 + 2.755_731_9e-6;
    let p = p * x2 - 1.984_127e-4;
    let p = p * x2 + 8.333_333e-3;
    let p = p * x2 - 1.666_666_7e-1;
    let p = p * x2 + 1.0;
    x * p
}

/// `cos(2π t)` for `t` in turns.
pub fn cos_turns(t: f32) -> f32 {
    sin_turns(t + 0.25)
}

/// `(sin, cos)` of an angle in degrees.
pub fn sin_cos_deg(degrees: f32) -> (f32, f32) {
    let t = degrees / 360.0;
    (sin_turns(t), cos_turns(t))
}

/// A number the generic distance formulas run on: `f32` or [`Dual`].
pub trait Num:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The value part.
    fn value(self) -> f32;
    /// A constant (zero derivative).
    fn constant(c: f32) -> Self;
    /// Correctly rounded square root; the derivative is zero where the value is zero.
    fn sqrt(self) -> Self;
    /// Absolute value (sign-bit clear on the value).
    fn abs(self) -> Self;
    /// Multiply by a constant.
    fn scale(self, c: f32) -> Self;
    /// Add a constant.
    fn offset(self, c: f32) -> Self;
    /// Apply a scalar function whose value at `self.value()` is `value` and whose
    /// derivative there is `slope` (chain rule for the gradient part).
    fn chain(self, value: f32, slope: f32) -> Self;
}

impl Num for f32 {
    #[inline(always)]
    fn value(self) -> f32 {
        self
    }
    #[inline(always)]
    fn constant(c: f32) -> Self {
        c
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn scale(self, c: f32) -> Self {
        self * c
    }
    #[inline(always)]
    fn offset(self, c: f32) -> Self {
        self + c
    }
    #[inline(always)]
    fn chain(self, value: f32, _slope: f32) -> Self {
        value
    }
}

/// Generic minimum by the project's definition (compare + select on the value).
#[inline(always)]
pub fn nmin<N: Num>(a: N, b: N) -> N {
    if a.value() < b.value() { a } else { b }
}

/// Generic maximum by the project's definition.
#[inline(always)]
pub fn nmax<N: Num>(a: N, b: N) -> N {
    if a.value() > b.value() { a } else { b }
}

/// Generic clamp to constant bounds.
#[inline(always)]
pub fn nclamp<N: Num>(x: N, lo: f32, hi: f32) -> N {
    nmin(nmax(x, N::constant(lo)), N::constant(hi))
}

/// A value with its gradient with respect to the query point `(x, y)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: f32,
    /// d value / dx.
    pub dx: f32,
    /// d value / dy.
    pub dy: f32,
}

impl Dual {
    /// The query point's coordinates as duals: `x` varies along x, `y` along y.
    pub fn point(p: Vec2) -> (Dual, Dual) {
        (
            Dual {
                v: p.x,
                dx: 1.0,
                dy: 0.0,
            },
            Dual {
                v: p.y,
                dx: 0.0,
                dy: 1.0,
            },
        )
    }
    /// The gradient part.
    pub fn gradient(self) -> Vec2 {
        Vec2::new(self.dx, self.dy)
    }
}

impl Add for Dual {
    type Output = Dual;
    #[inline(always)]
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            dx: self.dx + o.dx,
            dy: self.dy + o.dy,
        }
    }
}

impl Sub for Dual {
    type Output = Dual;
    #[inline(always)]
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            dx: self.dx - o.dx,
            dy: self.dy - o.dy,
        }
    }
}

impl Mul for Dual {
    type Output = Dual;
    #[inline(always)]
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self.v * o.v,
            dx: self.dx * o.v + self.v * o.dx,
            dy: self.dy * o.v + self.v * o.dy,
        }
    }
}

impl Div for Dual {
    type Output = Dual;
    #[inline(always)]
    fn div(self, o: Dual) -> Dual {
        let v = self.v / o.v;
        // (a/b)' = (a' - (a/b) b') / b
        Dual {
            v,
            dx: (self.dx - v * o.dx) / o.v,
            dy: (self.dy - v * o.dy) / o.v,
        }
    }
}

impl Neg for Dual {
    type Output = Dual;
    #[inline(always)]
    fn neg(self) -> Dual {
        Dual {
            v: -self.v,
            dx: -self.dx,
            dy: -self.dy,
        }
    }
}

impl Num for Dual {
    #[inline(always)]
    fn value(self) -> f32 {
        self.v
    }
    #[inline(always)]
    fn constant(c: f32) -> Self {
        Dual {
            v: c,
            dx: 0.0,
            dy: 0.0,
        }
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let v = f32::sqrt(self.v);
        if v > 0.0 {
            let k = 0.5 / v;
            Dual {
                v,
                dx: self.dx * k,
                dy: self.dy * k,
            }
        } else {
            // The medial-axis / apex case: report a zero gradient rather than inf or NaN.
            Dual {
                v,
                dx: 0.0,
                dy: 0.0,
            }
        }
    }
    #[inline(always)]
    fn abs(self) -> Self {
        if self.v < 0.0 {
            Dual {
                v: f32::abs(self.v),
                dx: -self.dx,
                dy: -self.dy,
            }
        } else {
            Dual {
                v: f32::abs(self.v),
                dx: self.dx,
                dy: self.dy,
            }
        }
    }
    #[inline(always)]
    fn scale(self, c: f32) -> Self {
        Dual {
            v: self.v * c,
            dx: self.dx * c,
            dy: self.dy * c,
        }
    }
    #[inline(always)]
    fn offset(self, c: f32) -> Self {
        Dual {
            v: self.v + c,
            dx: self.dx,
            dy: self.dy,
        }
    }
    #[inline(always)]
    fn chain(self, value: f32, slope: f32) -> Self {
        Dual {
            v: value,
            dx: self.dx * slope,
            dy: self.dy * slope,
        }
    }
}

/// A 2D vector over a [`Num`].
#[derive(Clone, Copy, Debug)]
pub struct V2<N> {
    /// x component.
    pub x: N,
    /// y component.
    pub y: N,
}

impl<N: Num> V2<N> {
    /// A vector from components.
    #[inline(always)]
    pub fn new(x: N, y: N) -> Self {
        V2 { x, y }
    }
    /// `self - c` for a constant `c`.
    #[inline(always)]
    pub fn minus(self, c: Vec2) -> Self {
        V2 {
            x: self.x.offset(-c.x),
            y: self.y.offset(-c.y),
        }
    }
    /// `x*x + y*y`, in that order.
    #[inline(always)]
    pub fn length_squared(self) -> N {
        self.x * self.x + self.y * self.y
    }
    /// Euclidean length.
    #[inline(always)]
    pub fn length(self) -> N {
        self.length_squared().sqrt()
    }
    /// Dot product with a constant vector: `x*c.x + y*c.y`.
    #[inline(always)]
    pub fn dot_c(self, c: Vec2) -> N {
        self.x.scale(c.x) + self.y.scale(c.y)
    }
    /// Scale by a constant.
    #[inline(always)]
    pub fn scale(self, c: f32) -> Self {
        V2 {
            x: self.x.scale(c),
            y: self.y.scale(c),
        }
    }
    /// Value part.
    #[inline(always)]
    pub fn value(self) -> Vec2 {
        Vec2::new(self.x.value(), self.y.value())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_match_std_closely() {
        let mut worst = 0.0f32;
        for i in -20000..20000 {
            let t = i as f32 * 0.000_37;
            let exact = (t as f64 * std::f64::consts::TAU).sin() as f32;
            worst = worst.max((sin_turns(t) - exact).abs());
            let exact_c = (t as f64 * std::f64::consts::TAU).cos() as f32;
            worst = worst.max((cos_turns(t) - exact_c).abs());
        }
        assert!(worst < 2e-6, "worst error {worst}");
    }

    #[test]
    fn sin_cos_exact_at_quarter_turns() {
        assert_eq!(sin_turns(0.0), 0.0);
        // Never above 1, so unit vectors built from it never grow.
        for i in 0..=1000 {
            assert!(sin_turns(0.24 + i as f32 * 2e-5).abs() <= 1.0);
        }
        assert!((sin_turns(0.25) - 1.0).abs() < 1e-6);
        assert!((cos_turns(0.5) + 1.0).abs() < 1e-6);
    }

    #[test]
    fn min_max_follow_the_contract_on_nan_and_zero() {
        assert!(min(f32::NAN, 1.0) == 1.0);
        assert!(min(1.0, f32::NAN).is_nan());
        assert!(max(f32::NAN, 1.0) == 1.0);
        assert_eq!(min(-0.0, 0.0).to_bits(), 0.0f32.to_bits());
        assert_eq!(min(0.0, -0.0).to_bits(), (-0.0f32).to_bits());
    }

    #[test]
    fn dual_value_is_bit_identical_to_f32_path() {
        let f = |x: f32, y: f32| V2::new(x, y).length().offset(-3.0) * (x + 1.5) / (y - 7.25);
        let g = |x: Dual, y: Dual| {
            V2::new(x, y).length().offset(-3.0) * (x.offset(1.5)) / (y.offset(-7.25))
        };
        for i in 0..500 {
            let p = Vec2::new(i as f32 * 0.731 - 100.0, (i * 7 % 113) as f32 * 1.37 - 50.0);
            let (dx, dy) = Dual::point(p);
            assert_eq!(f(p.x, p.y).to_bits(), g(dx, dy).v.to_bits());
        }
    }

    #[test]
    fn dual_gradient_matches_finite_differences() {
        let g = |x: Dual, y: Dual| (V2::new(x, y).length() * x) / (y.offset(10.0));
        let p = Vec2::new(1.7, -2.3);
        let (dx, dy) = Dual::point(p);
        let d = g(dx, dy);
        let h = 1e-3f64;
        let f64f = |x: f64, y: f64| ((x * x + y * y).sqrt() * x) / (y + 10.0);
        let fx = (f64f(p.x as f64 + h, p.y as f64) - f64f(p.x as f64 - h, p.y as f64)) / (2.0 * h);
        let fy = (f64f(p.x as f64, p.y as f64 + h) - f64f(p.x as f64, p.y as f64 - h)) / (2.0 * h);
        assert!((d.dx as f64 - fx).abs() < 1e-4);
        assert!((d.dy as f64 - fy).abs() < 1e-4);
    }

    #[test]
    fn sqrt_of_zero_has_zero_gradient() {
        let d = Dual {
            v: 0.0,
            dx: 1.0,
            dy: 1.0,
        }
        .sqrt();
        assert_eq!(
            d,
            Dual {
                v: 0.0,
                dx: 0.0,
                dy: 0.0
            }
        );
    }
}
