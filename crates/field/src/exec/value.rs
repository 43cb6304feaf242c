//! The numbers the interpreter runs on: a register of lanes as a plain value ([`Fv`],
//! distance mode) or as a dual number ([`Dv`], distance and gradient), mirroring
//! [`craterfield_core::det::math::Num`] for `f32` and `Dual` operation for operation, so each
//! lane computes the reference's bits.

use craterfield_core::simd::Lanes;

/// A lane register as a number: the generic face of [`Fv`] and [`Dv`].
pub(crate) trait Val<L: Lanes>: Copy {
    /// The value part.
    fn v(self) -> L::F;
    /// A constant (zero gradient).
    fn cst(l: L, c: f32) -> Self;
    /// Per-lane constants (zero gradient); also how masks and integers are stored.
    fn lanes(l: L, v: L::F) -> Self;
    /// The query point's x (gradient `(1, 0)`).
    fn px(l: L, x: L::F) -> Self;
    /// The query point's y (gradient `(0, 1)`).
    fn py(l: L, y: L::F) -> Self;
    /// `self + o`.
    fn add(self, l: L, o: Self) -> Self;
    /// `self - o`.
    fn sub(self, l: L, o: Self) -> Self;
    /// `self * o`.
    fn mul(self, l: L, o: Self) -> Self;
    /// `self / o`.
    fn div(self, l: L, o: Self) -> Self;
    /// `-self`.
    fn neg(self, l: L) -> Self;
    /// `|self|`.
    fn abs(self, l: L) -> Self;
    /// `sqrt(self)` (zero gradient where the value is zero).
    fn sqrt(self, l: L) -> Self;
    /// `Num::scale` by a constant.
    fn scale(self, l: L, c: f32) -> Self;
    /// `Num::offset` by a constant.
    fn offset(self, l: L, c: f32) -> Self;
    /// `Num::scale` by per-lane constants.
    fn scale_v(self, l: L, c: L::F) -> Self;
    /// `Num::offset` by per-lane constants.
    fn offset_v(self, l: L, c: L::F) -> Self;
    /// `Num::chain`: value `value`, gradient times `slope`.
    fn chain(self, l: L, value: L::F, slope: L::F) -> Self;
    /// `if m { a } else { b }` per lane.
    fn select(l: L, m: L::M, a: Self, b: Self) -> Self;
    /// `nmin`: `if self < o { self } else { o }` on values.
    #[inline(always)]
    fn min(self, l: L, o: Self) -> Self {
        Self::select(l, l.lt(self.v(), o.v()), self, o)
    }
    /// `nmax`: `if self > o { self } else { o }` on values.
    #[inline(always)]
    fn max(self, l: L, o: Self) -> Self {
        Self::select(l, l.gt(self.v(), o.v()), self, o)
    }
}

/// A plain value register.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fv<L: Lanes>(pub L::F);

impl<L: Lanes> Val<L> for Fv<L> {
    #[inline(always)]
    fn v(self) -> L::F {
        self.0
    }
    #[inline(always)]
    fn cst(l: L, c: f32) -> Self {
        Fv(l.splat(c))
    }
    #[inline(always)]
    fn lanes(_: L, v: L::F) -> Self {
        Fv(v)
    }
    #[inline(always)]
    fn px(_: L, x: L::F) -> Self {
        Fv(x)
    }
    #[inline(always)]
    fn py(_: L, y: L::F) -> Self {
        Fv(y)
    }
    #[inline(always)]
    fn add(self, l: L, o: Self) -> Self {
        Fv(l.add(self.0, o.0))
    }
    #[inline(always)]
    fn sub(self, l: L, o: Self) -> Self {
        Fv(l.sub(self.0, o.0))
    }
    #[inline(always)]
    fn mul(self, l: L, o: Self) -> Self {
        Fv(l.mul(self.0, o.0))
    }
    #[inline(always)]
    fn div(self, l: L, o: Self) -> Self {
        Fv(l.div(self.0, o.0))
    }
    #[inline(always)]
    fn neg(self, l: L) -> Self {
        Fv(l.neg(self.0))
    }
    #[inline(always)]
    fn abs(self, l: L) -> Self {
        Fv(l.abs(self.0))
    }
    #[inline(always)]
    fn sqrt(self, l: L) -> Self {
        Fv(l.sqrt(self.0))
    }
    #[inline(always)]
    fn scale(self, l: L, c: f32) -> Self {
        Fv(l.mul(self.0, l.splat(c)))
    }
    #[inline(always)]
    fn offset(self, l: L, c: f32) -> Self {
        Fv(l.add(self.0, l.splat(c)))
    }
    #[inline(always)]
    fn scale_v(self, l: L, c: L::F) -> Self {
        Fv(l.mul(self.0, c))
    }
    #[inline(always)]
    fn offset_v(self, l: L, c: L::F) -> Self {
        Fv(l.add(self.0, c))
    }
    #[inline(always)]
    fn chain(self, _: L, value: L::F, _slope: L::F) -> Self {
        Fv(value)
    }
    #[inline(always)]
    fn select(l: L, m: L::M, a: Self, b: Self) -> Self {
        Fv(l.select(m, a.0, b.0))
    }
    #[inline(always)]
    fn min(self, l: L, o: Self) -> Self {
        Fv(l.min(self.0, o.0))
    }
    #[inline(always)]
    fn max(self, l: L, o: Self) -> Self {
        Fv(l.max(self.0, o.0))
    }
}

/// A dual-number register: value and gradient `(dx, dy)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dv<L: Lanes> {
    pub v: L::F,
    pub dx: L::F,
    pub dy: L::F,
}

impl<L: Lanes> Val<L> for Dv<L> {
    #[inline(always)]
    fn v(self) -> L::F {
        self.v
    }
    #[inline(always)]
    fn cst(l: L, c: f32) -> Self {
        let z = l.splat(0.0);
        Dv {
            v: l.splat(c),
            dx: z,
            dy: z,
        }
    }
    #[inline(always)]
    fn lanes(l: L, v: L::F) -> Self {
        let z = l.splat(0.0);
        Dv { v, dx: z, dy: z }
    }
    #[inline(always)]
    fn px(l: L, x: L::F) -> Self {
        Dv {
            v: x,
            dx: l.splat(1.0),
            dy: l.splat(0.0),
        }
    }
    #[inline(always)]
    fn py(l: L, y: L::F) -> Self {
        Dv {
            v: y,
            dx: l.splat(0.0),
            dy: l.splat(1.0),
        }
    }
    #[inline(always)]
    fn add(self, l: L, o: Self) -> Self {
        Dv {
            v: l.add(self.v, o.v),
            dx: l.add(self.dx, o.dx),
            dy: l.add(self.dy, o.dy),
        }
    }
    #[inline(always)]
    fn sub(self, l: L, o: Self) -> Self {
        Dv {
            v: l.sub(self.v, o.v),
            dx: l.sub(self.dx, o.dx),
            dy: l.sub(self.dy, o.dy),
        }
    }
    #[inline(always)]
    fn mul(self, l: L, o: Self) -> Self {
        Dv {
            v: l.mul(self.v, o.v),
            dx: l.add(l.mul(self.dx, o.v), l.mul(self.v, o.dx)),
            dy: l.add(l.mul(self.dy, o.v), l.mul(self.v, o.dy)),
        }
    }
    #[inline(always)]
    fn div(self, l: L, o: Self) -> Self {
        let v = l.div(self.v, o.v);
        Dv {
            v,
            dx: l.div(l.sub(self.dx, l.mul(v, o.dx)), o.v),
            dy: l.div(l.sub(self.dy, l.mul(v, o.dy)), o.v),
        }
    }
    #[inline(always)]
    fn neg(self, l: L) -> Self {
        Dv {
            v: l.neg(self.v),
            dx: l.neg(self.dx),
            dy: l.neg(self.dy),
        }
    }
    #[inline(always)]
    fn abs(self, l: L) -> Self {
        let m = l.lt(self.v, l.splat(0.0));
        Dv {
            v: l.abs(self.v),
            dx: l.select(m, l.neg(self.dx), self.dx),
            dy: l.select(m, l.neg(self.dy), self.dy),
        }
    }
    #[inline(always)]
    fn sqrt(self, l: L) -> Self {
        let v = l.sqrt(self.v);
        let k = l.div(l.splat(0.5), v);
        let pos = l.gt(v, l.splat(0.0));
        let z = l.splat(0.0);
        Dv {
            v,
            dx: l.select(pos, l.mul(self.dx, k), z),
            dy: l.select(pos, l.mul(self.dy, k), z),
        }
    }
    #[inline(always)]
    fn scale(self, l: L, c: f32) -> Self {
        self.scale_v(l, l.splat(c))
    }
    #[inline(always)]
    fn offset(self, l: L, c: f32) -> Self {
        self.offset_v(l, l.splat(c))
    }
    #[inline(always)]
    fn scale_v(self, l: L, c: L::F) -> Self {
        Dv {
            v: l.mul(self.v, c),
            dx: l.mul(self.dx, c),
            dy: l.mul(self.dy, c),
        }
    }
    #[inline(always)]
    fn offset_v(self, l: L, c: L::F) -> Self {
        Dv {
            v: l.add(self.v, c),
            dx: self.dx,
            dy: self.dy,
        }
    }
    #[inline(always)]
    fn chain(self, l: L, value: L::F, slope: L::F) -> Self {
        Dv {
            v: value,
            dx: l.mul(self.dx, slope),
            dy: l.mul(self.dy, slope),
        }
    }
    #[inline(always)]
    fn select(l: L, m: L::M, a: Self, b: Self) -> Self {
        Dv {
            v: l.select(m, a.v, b.v),
            dx: l.select(m, a.dx, b.dx),
            dy: l.select(m, a.dy, b.dy),
        }
    }
}

/// A point of lane values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct P2<V> {
    pub x: V,
    pub y: V,
}

impl<V> P2<V> {
    #[inline(always)]
    pub(crate) fn new(x: V, y: V) -> Self {
        P2 { x, y }
    }
}

/// `V2` of `detmath`, on lanes.
impl<V: Copy> P2<V> {
    /// `self - c` for a constant `c` (offset by `-c`).
    #[inline(always)]
    pub(crate) fn minus<L: Lanes>(self, l: L, c: glam::Vec2) -> Self
    where
        V: Val<L>,
    {
        P2::new(self.x.offset(l, -c.x), self.y.offset(l, -c.y))
    }
    /// `x*x + y*y`.
    #[inline(always)]
    pub(crate) fn length_squared<L: Lanes>(self, l: L) -> V
    where
        V: Val<L>,
    {
        self.x.mul(l, self.x).add(l, self.y.mul(l, self.y))
    }
    /// Euclidean length.
    #[inline(always)]
    pub(crate) fn length<L: Lanes>(self, l: L) -> V
    where
        V: Val<L>,
    {
        self.length_squared(l).sqrt(l)
    }
    /// `x*c.x + y*c.y` with scales.
    #[inline(always)]
    pub(crate) fn dot_c<L: Lanes>(self, l: L, c: glam::Vec2) -> V
    where
        V: Val<L>,
    {
        self.x.scale(l, c.x).add(l, self.y.scale(l, c.y))
    }
}

/// `nclamp`: `nmin(nmax(x, lo), hi)` with constant bounds.
#[inline(always)]
pub(crate) fn clamp<L: Lanes, V: Val<L>>(l: L, x: V, lo: f32, hi: f32) -> V {
    x.max(l, V::cst(l, lo)).min(l, V::cst(l, hi))
}
