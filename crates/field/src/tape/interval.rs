//! Interval arithmetic over tape values, sound for the `f32` evaluation of the tape.
//!
//! Bounds are computed with the same round-to-nearest `f32` operations the evaluator uses.
//! Round-to-nearest is monotonic, so for an operation monotonic in each argument the
//! rounded results at the interval ends bound the rounded result at every point inside:
//! no outward rounding is needed. Primitives (exact distances, 1-Lipschitz) are bounded by
//! their value at the box centre plus the box's half diagonal, widened by a margin far
//! larger than their `f32` rounding error. An interval that may contain NaN says so, and
//! nothing is decided from it.

/// A range of `f32` values, possibly with NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Lowest value.
    pub lo: f32,
    /// Highest value.
    pub hi: f32,
    /// Whether NaN may occur.
    pub nan: bool,
}

/// A mask's possible values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tri {
    /// Never set.
    False,
    /// Always set.
    True,
    /// Either.
    Maybe,
}

impl Range {
    /// Everything, NaN included.
    pub const ALL: Range = Range {
        lo: f32::NEG_INFINITY,
        hi: f32::INFINITY,
        nan: true,
    };

    /// `[lo, hi]`; NaN bounds give [`Range::ALL`].
    pub fn new(lo: f32, hi: f32) -> Range {
        if lo.is_nan() || hi.is_nan() {
            Range::ALL
        } else {
            Range { lo, hi, nan: false }
        }
    }

    /// A single value.
    pub fn point(v: f32) -> Range {
        Range::new(v, v)
    }

    fn with_nan(self, nan: bool) -> Range {
        if nan {
            Range { nan: true, ..self }
        } else {
            self
        }
    }

    fn any_nan(a: Range, b: Range) -> bool {
        a.nan || b.nan
    }

    /// `a + b`.
    pub fn sum(a: Range, b: Range) -> Range {
        Range::new(a.lo + b.lo, a.hi + b.hi).with_nan(Range::any_nan(a, b))
    }

    /// `a - b`.
    pub fn difference(a: Range, b: Range) -> Range {
        Range::new(a.lo - b.hi, a.hi - b.lo).with_nan(Range::any_nan(a, b))
    }

    /// `a * b`.
    pub fn product(a: Range, b: Range) -> Range {
        let c = [a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi];
        if c.iter().any(|v| v.is_nan()) {
            return Range::ALL;
        }
        let lo = c.iter().fold(f32::INFINITY, |m, &v| m.min(v));
        let hi = c.iter().fold(f32::NEG_INFINITY, |m, &v| m.max(v));
        Range::new(lo, hi).with_nan(Range::any_nan(a, b))
    }

    /// `a / b`.
    pub fn quotient(a: Range, b: Range) -> Range {
        if b.lo <= 0.0 && b.hi >= 0.0 {
            return Range::ALL;
        }
        let c = [a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi];
        if c.iter().any(|v| v.is_nan()) {
            return Range::ALL;
        }
        let lo = c.iter().fold(f32::INFINITY, |m, &v| m.min(v));
        let hi = c.iter().fold(f32::NEG_INFINITY, |m, &v| m.max(v));
        Range::new(lo, hi).with_nan(Range::any_nan(a, b))
    }

    /// `-a`.
    pub fn negated(a: Range) -> Range {
        Range::new(-a.hi, -a.lo).with_nan(a.nan)
    }

    /// `|a|`.
    pub fn abs(a: Range) -> Range {
        let r = if a.lo >= 0.0 {
            Range::new(a.lo, a.hi)
        } else if a.hi <= 0.0 {
            Range::new(-a.hi, -a.lo)
        } else {
            Range::new(0.0, (-a.lo).max(a.hi))
        };
        r.with_nan(a.nan)
    }

    /// `sqrt(a)` (NaN below zero).
    pub fn sqrt(a: Range) -> Range {
        let lo = if a.lo > 0.0 { a.lo.sqrt() } else { 0.0 };
        Range::new(lo, a.hi.max(0.0).sqrt()).with_nan(a.nan || a.lo < 0.0)
    }

    /// `a * a`.
    pub fn square(a: Range) -> Range {
        let (l2, h2) = (a.lo * a.lo, a.hi * a.hi);
        let r = if a.lo >= 0.0 || a.hi <= 0.0 {
            Range::new(l2.min(h2), l2.max(h2))
        } else {
            Range::new(0.0, l2.max(h2))
        };
        r.with_nan(a.nan)
    }

    /// `a * c` for a constant.
    pub fn scale(a: Range, c: f32) -> Range {
        Range::product(a, Range::point(c))
    }

    /// `a + c` for a constant.
    pub fn offset(a: Range, c: f32) -> Range {
        Range::sum(a, Range::point(c))
    }

    /// The project's `min`.
    pub fn min(a: Range, b: Range) -> Range {
        if Range::any_nan(a, b) {
            return Range::ALL;
        }
        Range::new(a.lo.min(b.lo), a.hi.min(b.hi))
    }

    /// The project's `max`.
    pub fn max(a: Range, b: Range) -> Range {
        if Range::any_nan(a, b) {
            return Range::ALL;
        }
        Range::new(a.lo.max(b.lo), a.hi.max(b.hi))
    }

    /// Either `a` or `b`.
    pub fn union(a: Range, b: Range) -> Range {
        Range::new(a.lo.min(b.lo), a.hi.max(b.hi)).with_nan(Range::any_nan(a, b))
    }

    /// Whether `a < b` everywhere (`True`), nowhere (`False`) or undecided.
    pub fn lt(a: Range, b: Range) -> Tri {
        if Range::any_nan(a, b) {
            Tri::Maybe
        } else if a.hi < b.lo {
            Tri::True
        } else if a.lo >= b.hi {
            Tri::False
        } else {
            Tri::Maybe
        }
    }

    /// Whether `a > b` everywhere, nowhere or undecided.
    pub fn gt(a: Range, b: Range) -> Tri {
        if Range::any_nan(a, b) {
            Tri::Maybe
        } else if a.lo > b.hi {
            Tri::True
        } else if a.hi <= b.lo {
            Tri::False
        } else {
            Tri::Maybe
        }
    }

    /// Bound of a 1-Lipschitz function over the box `x` by `y`, from its `f32` value at
    /// the box centre `value_at(cx, cy)`. `None` for an unbounded box.
    pub fn lipschitz_box(x: Range, y: Range, value_at: impl Fn(f32, f32) -> f32) -> Range {
        if x.nan || y.nan || !(x.lo.is_finite() && x.hi.is_finite()) {
            return Range::ALL;
        }
        if !(y.lo.is_finite() && y.hi.is_finite()) {
            return Range::ALL;
        }
        let (cx, cy) = (
            ((f64::from(x.lo) + f64::from(x.hi)) * 0.5) as f32,
            ((f64::from(y.lo) + f64::from(y.hi)) * 0.5) as f32,
        );
        let v = value_at(cx, cy);
        if !v.is_finite() {
            return Range::ALL;
        }
        let (hx, hy) = (
            (f64::from(cx) - f64::from(x.lo)).max(f64::from(x.hi) - f64::from(cx)),
            (f64::from(cy) - f64::from(y.lo)).max(f64::from(y.hi) - f64::from(cy)),
        );
        let r = (hx * hx + hy * hy).sqrt();
        // Covers the f32 rounding of the primitive at both points (a few ulps of the
        // magnitudes involved) and the ellipse solver's residual (relative 1e-4) many times.
        let margin = (f64::from(v.abs()) + r + f64::from(cx.abs()) + f64::from(cy.abs())) / 1024.0
            + 1.0 / 1024.0;
        let (v, w) = (f64::from(v), r + margin);
        Range::new((v - w) as f32, (v + w) as f32)
    }
}

/// `a & b` on masks.
pub(super) fn and(a: Tri, b: Tri) -> Tri {
    match (a, b) {
        (Tri::False, _) | (_, Tri::False) => Tri::False,
        (Tri::True, Tri::True) => Tri::True,
        _ => Tri::Maybe,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random points in random intervals: the f32 result of each operation lies in the
    /// interval computed for it.
    #[test]
    fn operations_contain_their_pointwise_results() {
        let mut s = 0x1234_5678_u64;
        let mut next = || {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((s >> 40) as f32 / 16_777_216.0 - 0.5) * 200.0
        };
        for _ in 0..20_000 {
            let (a0, a1, b0, b1) = (next(), next(), next(), next());
            let a = Range::new(a0.min(a1), a0.max(a1));
            let b = Range::new(b0.min(b1), b0.max(b1));
            let t = (next() + 100.0) / 200.0;
            let u = (next() + 100.0) / 200.0;
            let x = a.lo + (a.hi - a.lo) * t;
            let y = b.lo + (b.hi - b.lo) * u;
            let x = x.clamp(a.lo, a.hi);
            let y = y.clamp(b.lo, b.hi);
            let within = |r: Range, v: f32| v.is_nan() && r.nan || (r.lo <= v && v <= r.hi);
            assert!(within(Range::sum(a, b), x + y));
            assert!(within(Range::difference(a, b), x - y));
            assert!(within(Range::product(a, b), x * y));
            assert!(within(Range::quotient(a, b), x / y));
            assert!(within(Range::square(a), x * x));
            assert!(within(Range::sqrt(a), x.sqrt()));
            assert!(within(Range::abs(a), x.abs()));
            assert!(within(Range::negated(a), -x));
            assert!(within(
                Range::min(a, b),
                craterfield_core::det::math::min(x, y)
            ));
            assert!(within(
                Range::max(a, b),
                craterfield_core::det::math::max(x, y)
            ));
        }
    }

    #[test]
    fn decisions_need_strict_separation_and_no_nan() {
        let a = Range::new(0.0, 1.0);
        let b = Range::new(1.0, 2.0);
        assert_eq!(Range::lt(a, b), Tri::Maybe);
        assert_eq!(Range::lt(a, Range::new(1.5, 2.0)), Tri::True);
        assert_eq!(Range::lt(b, a), Tri::False);
        assert_eq!(Range::lt(Range::sqrt(Range::new(-1.0, 1.0)), b), Tri::Maybe);
    }
}
