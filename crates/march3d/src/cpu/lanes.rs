//! Vertical SoA vectors of a packet: three registers (x, y, z) of `P::WIDTH` lanes each,
//! and the few vector operations the tracer needs, all inlined into the kernel.

use glam::Vec3;

use crate::simd::Pack;

/// The widest packet any backend uses (a [`crate::simd::Pair`] of 16-lane registers).
pub(crate) const MAX_WIDTH: usize = 32;

/// `P::WIDTH` 3D vectors, one per lane.
pub(crate) struct V3<P: Pack> {
    pub x: P::F,
    pub y: P::F,
    pub z: P::F,
}

impl<P: Pack> Clone for V3<P> {
    #[inline(always)]
    fn clone(&self) -> Self {
        *self
    }
}

impl<P: Pack> Copy for V3<P> {}

impl<P: Pack> V3<P> {
    /// The same vector in every lane.
    #[inline(always)]
    pub(super) fn splat(p: P, v: Vec3) -> Self {
        V3 {
            x: p.splat(v.x),
            y: p.splat(v.y),
            z: p.splat(v.z),
        }
    }

    /// `self + o`.
    #[inline(always)]
    pub(super) fn add(self, p: P, o: Self) -> Self {
        V3 {
            x: p.add(self.x, o.x),
            y: p.add(self.y, o.y),
            z: p.add(self.z, o.z),
        }
    }

    /// `self - o`.
    #[inline(always)]
    pub(super) fn sub(self, p: P, o: Self) -> Self {
        V3 {
            x: p.sub(self.x, o.x),
            y: p.sub(self.y, o.y),
            z: p.sub(self.z, o.z),
        }
    }

    /// `self - c` for a constant `c` (zero components cost nothing).
    #[inline(always)]
    pub(super) fn sub_c(self, p: P, c: Vec3) -> Self {
        let s = |v: P::F, c: f32| if c == 0.0 { v } else { p.sub(v, p.splat(c)) };
        V3 {
            x: s(self.x, c.x),
            y: s(self.y, c.y),
            z: s(self.z, c.z),
        }
    }

    /// `self * s`.
    #[inline(always)]
    pub(super) fn scale(self, p: P, s: P::F) -> Self {
        V3 {
            x: p.mul(self.x, s),
            y: p.mul(self.y, s),
            z: p.mul(self.z, s),
        }
    }

    /// `self * s + o`.
    #[inline(always)]
    pub(super) fn mul_add(self, p: P, s: P::F, o: Self) -> Self {
        V3 {
            x: p.fma(self.x, s, o.x),
            y: p.fma(self.y, s, o.y),
            z: p.fma(self.z, s, o.z),
        }
    }

    /// The dot product.
    #[inline(always)]
    pub(super) fn dot(self, p: P, o: Self) -> P::F {
        p.fma(self.x, o.x, p.fma(self.y, o.y, p.mul(self.z, o.z)))
    }

    /// The dot product with a constant.
    #[inline(always)]
    pub(super) fn dot_c(self, p: P, c: Vec3) -> P::F {
        p.fma(
            self.x,
            p.splat(c.x),
            p.fma(self.y, p.splat(c.y), p.mul(self.z, p.splat(c.z))),
        )
    }

    /// The squared length.
    #[inline(always)]
    pub(super) fn len2(self, p: P) -> P::F {
        self.dot(p, self)
    }

    /// The length.
    #[inline(always)]
    pub(super) fn len(self, p: P) -> P::F {
        p.sqrt(self.len2(p))
    }

    /// The unit vector along `self`.
    #[inline(always)]
    pub(super) fn normalize(self, p: P) -> Self {
        let inv = p.div(p.splat(1.0), self.len(p));
        self.scale(p, inv)
    }

    /// Componentwise absolute value.
    #[inline(always)]
    pub(super) fn abs(self, p: P) -> Self {
        V3 {
            x: p.abs(self.x),
            y: p.abs(self.y),
            z: p.abs(self.z),
        }
    }

    /// Componentwise `max(self, 0)`.
    #[inline(always)]
    pub(super) fn max0(self, p: P) -> Self {
        let z = p.splat(0.0);
        V3 {
            x: p.max(self.x, z),
            y: p.max(self.y, z),
            z: p.max(self.z, z),
        }
    }

    /// The largest component.
    #[inline(always)]
    pub(super) fn max_elem(self, p: P) -> P::F {
        p.max(self.x, p.max(self.y, self.z))
    }

    /// `if m { a } else { b }` per lane.
    #[inline(always)]
    pub(super) fn select(p: P, m: P::M, a: Self, b: Self) -> Self {
        V3 {
            x: p.select(m, a.x, b.x),
            y: p.select(m, a.y, b.y),
            z: p.select(m, a.z, b.z),
        }
    }

    /// `m * self` for a row-major 3x3 matrix.
    #[inline(always)]
    pub(super) fn rotate(self, p: P, m: &[f32; 9]) -> Self {
        V3 {
            x: self.dot_row(p, &m[0..3]),
            y: self.dot_row(p, &m[3..6]),
            z: self.dot_row(p, &m[6..9]),
        }
    }

    /// `row . self`, as [`V3::rotate`] rounds it. A function, not a closure: a closure may
    /// be compiled out of line, without the backend's instruction set (the rotation's was,
    /// and each row called `_mm512_set1_ps` through memory).
    #[inline(always)]
    fn dot_row(self, p: P, row: &[f32]) -> P::F {
        p.fma(
            self.x,
            p.splat(row[0]),
            p.fma(self.y, p.splat(row[1]), p.mul(self.z, p.splat(row[2]))),
        )
    }

    /// The mirror direction of `self` about the unit normal `n`.
    #[inline(always)]
    pub(super) fn reflect(self, p: P, n: Self) -> Self {
        let k = p.mul(p.splat(-2.0), self.dot(p, n));
        n.mul_add(p, k, self)
    }
}
