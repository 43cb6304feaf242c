//! Scalar evaluation of a compiled [`Graph`]: the reference every faster backend must match
//! bit for bit.
//!
//! One generic walk over the arena runs on `f32` (distance) or on [`Dual`] (distance and
//! analytic gradient in the same pass); the value part is computed by the same operations in
//! both cases, so `sample(p).distance` is bit-identical to `distance(p)`.

use glam::Vec2;

use super::graph::{Graph, NodeId, Op, Repeat};
use super::node::Axis;
use super::noise::value_noise;
use super::primitives as prim;
use super::sample::{MaterialId, Sample};
use super::sdf::Sdf;
use craterfield_core::det::math::{Dual, Num, V2, nmax};

impl Graph {
    /// Distance of one node of the graph (for tests and tools; [`Sdf::distance`] is the root).
    pub fn node_distance(&self, id: NodeId, p: Vec2) -> f32 {
        if id.0 as usize >= self.ops.len() {
            return f32::NAN;
        }
        self.eval::<f32>(id, V2::new(p.x, p.y)).0
    }

    /// Distance, gradient and material of one node.
    pub fn node_sample(&self, id: NodeId, p: Vec2) -> Sample {
        if id.0 as usize >= self.ops.len() {
            return Sample {
                distance: f32::NAN,
                gradient: Vec2::ZERO,
                material: 0,
            };
        }
        let (x, y) = Dual::point(p);
        let (d, material) = self.eval::<Dual>(id, V2::new(x, y));
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }

    fn eval<N: Num>(&self, id: NodeId, p: V2<N>) -> (N, MaterialId) {
        let leaf = |d: N| (d, 0);
        match &self.ops[id.0 as usize] {
            Op::Circle { c, r } => leaf(prim::circle(p, *c, *r)),
            Op::Box { c, h } => leaf(prim::aabox(p, *c, *h)),
            Op::RoundedBox { c, inner, r } => leaf(prim::aabox(p, *c, *inner).offset(-r)),
            Op::OrientedBox { mid, dir, half } => leaf(prim::oriented_box(p, *mid, *dir, *half)),
            Op::Capsule { a, ba, inv_ba2, r } => leaf(prim::capsule(p, *a, *ba, *inv_ba2, *r)),
            Op::Polygon { pts, inv_e2 } => leaf(prim::polygon(p, pts, inv_e2)),
            Op::Ellipse { c, radii } => leaf(prim::ellipse(p, *c, *radii)),
            Op::Ring { c, r, half_width } => leaf(prim::ring(p, *c, *r, *half_width)),
            Op::Arc { c, rot, sc, ra, rb } => leaf(prim::arc(p, *c, *rot, *sc, *ra, *rb)),
            Op::HalfPlane { n, offset } => leaf(prim::half_plane(p, *n, *offset)),
            Op::Height { pts, dx, inv_e2 } => leaf(prim::height_profile(p, pts, *dx, inv_e2)),
            Op::Union(ids) => self.fold(ids, p, |acc, next| {
                if acc.0.value() < next.0.value() {
                    acc
                } else {
                    next
                }
            }),
            Op::Intersection(ids) => self.fold(ids, p, |acc, next| (nmax(acc.0, next.0), acc.1)),
            Op::Subtract(a, b) => {
                let (da, m) = self.eval(*a, p);
                let (db, _) = self.eval(*b, p);
                (nmax(da, -db), m)
            }
            Op::SmoothUnion(k, ids) => self.fold(ids, p, |acc, next| {
                let m = if acc.0.value() < next.0.value() {
                    acc.1
                } else {
                    next.1
                };
                (prim::smooth_min(acc.0, next.0, *k), m)
            }),
            Op::SmoothIntersection(k, ids) => self.fold(ids, p, |acc, next| {
                (prim::smooth_max(acc.0, next.0, *k), acc.1)
            }),
            Op::SmoothSubtract(k, a, b) => {
                let (da, m) = self.eval(*a, p);
                let (db, _) = self.eval(*b, p);
                (prim::smooth_max(da, -db, *k), m)
            }
            Op::Round(r, c) => {
                let (d, m) = self.eval(*c, p);
                (d.offset(-r), m)
            }
            Op::Onion(w, c) => {
                let (d, m) = self.eval(*c, p);
                (d.abs().offset(-w), m)
            }
            Op::Translate(t, c) => self.eval(*c, p.minus(*t)),
            Op::Rotate { cos, sin, child } => {
                self.eval(*child, prim::rotate_inverse(p, *cos, *sin))
            }
            Op::Scale { factor, inv, child } => {
                let (d, m) = self.eval(*child, p.scale(*inv));
                (d.scale(*factor), m)
            }
            Op::Mirror { axis, at, child } => {
                let q = match axis {
                    Axis::X => V2::new(p.x.offset(-at).abs().offset(*at), p.y),
                    Axis::Y => V2::new(p.x, p.y.offset(-at).abs().offset(*at)),
                };
                self.eval(*child, q)
            }
            Op::Repeat(r) => self.repeat(r, p),
            Op::Noise {
                amplitude,
                inv_wavelength,
                seed,
                child,
            } => {
                let (d, m) = self.eval(*child, p);
                let n = value_noise(
                    p.x.scale(*inv_wavelength),
                    p.y.scale(*inv_wavelength),
                    *seed,
                );
                (d + n.scale(*amplitude), m)
            }
            Op::Wave {
                amplitude,
                k,
                phase,
                child,
            } => {
                let (d, m) = self.eval(*child, p);
                let t = p.dot_c(*k).offset(*phase);
                let tv = t.value();
                let s = t.chain(
                    craterfield_core::det::math::sin_turns(tv),
                    craterfield_core::det::math::TAU * craterfield_core::det::math::cos_turns(tv),
                );
                (d + s.scale(*amplitude), m)
            }
            Op::Material(mat, c) => (self.eval(*c, p).0, *mat),
            // Arithmetic: the material is the first operand's.
            Op::X => (p.x, 0),
            Op::Y => (p.y, 0),
            Op::Const(c) => (N::constant(*c), 0),
            Op::Add(a, b) => self.binary(*a, *b, p, |x, y| x + y),
            Op::Sub(a, b) => self.binary(*a, *b, p, |x, y| x - y),
            Op::Mul(a, b) => self.binary(*a, *b, p, |x, y| x * y),
            Op::Neg(a) => {
                let (d, m) = self.eval(*a, p);
                (-d, m)
            }
            Op::Square(a) => {
                let (d, m) = self.eval(*a, p);
                (d * d, m)
            }
            Op::Sqrt(a) => {
                let (d, m) = self.eval(*a, p);
                (d.sqrt(), m)
            }
        }
    }

    fn binary<N: Num>(
        &self,
        a: NodeId,
        b: NodeId,
        p: V2<N>,
        f: impl Fn(N, N) -> N,
    ) -> (N, MaterialId) {
        let (da, m) = self.eval(a, p);
        let (db, _) = self.eval(b, p);
        (f(da, db), m)
    }

    fn fold<N: Num>(
        &self,
        ids: &[NodeId],
        p: V2<N>,
        f: impl Fn((N, MaterialId), (N, MaterialId)) -> (N, MaterialId),
    ) -> (N, MaterialId) {
        let mut it = ids.iter();
        let Some(first) = it.next() else {
            return (N::constant(f32::INFINITY), 0);
        };
        let mut acc = self.eval(*first, p);
        for id in it {
            acc = f(acc, self.eval(*id, p));
        }
        acc
    }

    /// Repetition: the union over all instances, each intersected with its copy of the
    /// child's bounding box, then capped by `max(half the smallest period, distance to the box
    /// around all instances)`. Instances outside the 3x3 neighbourhood of the nearest one are
    /// at least that far away, so leaving them out changes nothing: the result is one
    /// continuous, Lipschitz function (not a per-cell patchwork) and a valid bound.
    fn repeat<N: Num>(&self, r: &Repeat, p: V2<N>) -> (N, MaterialId) {
        let pv = p.value();
        let range = |axis: usize, v: f32| -> (i32, i32) {
            let period = r.period[axis];
            if period == 0.0 {
                return (0, 0);
            }
            // Saturating cast; NaN becomes 0.
            let k = ((v / period + 0.5).floor() as i32).clamp(r.lo[axis], r.hi[axis]);
            ((k - 1).max(r.lo[axis]), (k + 1).min(r.hi[axis]))
        };
        let (x0, x1) = range(0, pv.x);
        let (y0, y1) = range(1, pv.y);
        let mut best = (
            nmax(
                N::constant(r.cap),
                outside_distance(p, r.all_min, r.all_max),
            ),
            0,
        );
        for iy in y0..=y1 {
            for ix in x0..=x1 {
                let offset = Vec2::new(ix as f32 * r.period.x, iy as f32 * r.period.y);
                let q = p.minus(offset);
                let (d, m) = self.eval(r.child, q);
                let g = nmax(d, self.repeat_guard(r, q));
                if g.value() < best.0.value() {
                    best = (g, m);
                }
            }
        }
        best
    }

    /// Exact distance to the child's box along the repeated axes.
    fn repeat_guard<N: Num>(&self, r: &Repeat, q: V2<N>) -> N {
        match (r.period.x > 0.0, r.period.y > 0.0) {
            (true, true) => prim::aabox(q, r.guard_c, r.guard_h),
            (true, false) => q.x.offset(-r.guard_c.x).abs().offset(-r.guard_h.x),
            _ => q.y.offset(-r.guard_c.y).abs().offset(-r.guard_h.y),
        }
    }
}

/// Distance from `p` to a box with possibly infinite sides, 0 inside.
fn outside_distance<N: Num>(p: V2<N>, min: Vec2, max: Vec2) -> N {
    let axis = |v: N, lo: f32, hi: f32| -> N {
        let zero = N::constant(0.0);
        let below = if lo.is_finite() {
            N::constant(lo) - v
        } else {
            zero
        };
        let above = if hi.is_finite() { v.offset(-hi) } else { zero };
        nmax(nmax(below, above), zero)
    };
    V2::new(axis(p.x, min.x, max.x), axis(p.y, min.y, max.y)).length()
}

impl Sdf for Graph {
    fn distance(&self, p: Vec2) -> f32 {
        self.eval::<f32>(self.root, V2::new(p.x, p.y)).0
    }

    fn sample(&self, p: Vec2) -> Sample {
        self.node_sample(self.root, p)
    }

    fn distance_material(&self, p: Vec2) -> (f32, MaterialId) {
        self.eval::<f32>(self.root, V2::new(p.x, p.y))
    }

    fn lipschitz(&self) -> f32 {
        self.root_info().lipschitz
    }

    fn program(&self) -> Option<std::sync::Arc<crate::tape::Program>> {
        Some(Graph::program(self))
    }
}
