//! Lowering a compiled [`Graph`] to an SSA [`Program`].
//!
//! Each graph operation becomes exactly the sequence of number operations the reference
//! walker ([`crate::eval`]) performs for it, in the same order, so the tape's
//! results are bit-identical to the reference's in both `f32` and dual mode. The builder
//! shares identical instructions and folds constant arithmetic (checked in dual arithmetic,
//! so a fold never changes a gradient's signed zero).

use std::collections::HashMap;
use std::sync::Arc;

use super::{Instr, MatOut, Op, Program};
use crate::graph::{Graph, NodeId, Op as G, Repeat};
use crate::node::Axis;
use crate::sample::MaterialId;
use craterfield_core::det::math::{Dual, Num, nmax, nmin};

/// A material while lowering: constant, or an integer SSA value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Mat {
    Const(MaterialId),
    Value(u32),
}

/// Builds SSA with common-subexpression sharing and constant folding.
#[derive(Default)]
pub(crate) struct Builder {
    pub(crate) ops: Vec<Instr>,
    pub(crate) params: Vec<u32>,
    cse: HashMap<Instr, u32>,
    param_blocks: HashMap<Vec<u32>, u32>,
    /// Parameters shared with the program being rewritten (instead of `params`).
    shared: Option<Arc<Vec<u32>>>,
    /// Skip the common-subexpression table: rewriting an already shared program finds
    /// few new duplicates, and the hashing dominates its cost.
    no_cse: bool,
}

impl Builder {
    /// A builder rewriting a program whose parameters it keeps.
    pub(crate) fn rewriting(params: Arc<Vec<u32>>) -> Builder {
        Builder {
            shared: Some(params),
            no_cse: true,
            ..Builder::default()
        }
    }

    /// Adds `op(a, b, c; imm)` or returns an existing identical value.
    pub(crate) fn push(&mut self, op: Op, a: u32, b: u32, c: u32, imm: u32) -> u32 {
        let n = op.arity();
        let key = Instr {
            op,
            dst: 0,
            a: if n > 0 { a } else { 0 },
            b: if n > 1 { b } else { 0 },
            c: if n > 2 { c } else { 0 },
            imm,
        };
        let shared = if self.no_cse {
            None
        } else {
            self.cse.get(&key).copied()
        };
        if let Some(id) = shared {
            return id;
        }
        if let Some(v) = self.fold(&key) {
            return self.constant(v);
        }
        if let Some(same) = self.trivial_select(&key) {
            return same;
        }
        let id = self.ops.len() as u32;
        self.ops.push(Instr { dst: id, ..key });
        if !self.no_cse {
            self.cse.insert(key, id);
        }
        id
    }

    /// A float constant.
    pub(crate) fn constant(&mut self, v: f32) -> u32 {
        self.push(Op::Const, 0, 0, 0, v.to_bits())
    }

    /// Stores a parameter block (shared with identical blocks) and returns its index.
    pub(crate) fn params(&mut self, block: Vec<u32>) -> u32 {
        if let Some(&at) = self.param_blocks.get(&block) {
            return at;
        }
        let at = self.params.len() as u32;
        self.params.extend_from_slice(&block);
        self.param_blocks.insert(block, at);
        at
    }

    fn const_of(&self, id: u32) -> Option<f32> {
        match self.ops.get(id as usize) {
            Some(i) if i.op == Op::Const => Some(i.imm_f32()),
            _ => None,
        }
    }

    /// The constant result of `i` if all its operands are constants and the result is a
    /// plain constant in dual arithmetic too (gradient exactly `(+0, +0)`).
    fn fold(&self, i: &Instr) -> Option<f32> {
        let c = |id: u32| self.const_of(id).map(Dual::constant);
        let imm = i.imm_f32();
        let d = match i.op {
            Op::Add => c(i.a)? + c(i.b)?,
            Op::Sub => c(i.a)? - c(i.b)?,
            Op::Mul => c(i.a)? * c(i.b)?,
            Op::Neg => -c(i.a)?,
            Op::Abs => c(i.a)?.abs(),
            Op::Sqrt => c(i.a)?.sqrt(),
            Op::Square => c(i.a)? * c(i.a)?,
            Op::Offset => c(i.a)?.offset(imm),
            Op::Scale => c(i.a)?.scale(imm),
            Op::Min => nmin(c(i.a)?, c(i.b)?),
            Op::Max => nmax(c(i.a)?, c(i.b)?),
            _ => return None,
        };
        (d.dx.to_bits() == 0 && d.dy.to_bits() == 0).then_some(d.v)
    }

    /// A select between one value and itself is that value.
    fn trivial_select(&self, i: &Instr) -> Option<u32> {
        matches!(i.op, Op::Select | Op::MatSelect)
            .then_some(())
            .filter(|_| i.b == i.c)
            .map(|_| i.b)
    }

    fn unary(&mut self, op: Op, a: u32) -> u32 {
        self.push(op, a, 0, 0, 0)
    }
    fn binary(&mut self, op: Op, a: u32, b: u32) -> u32 {
        self.push(op, a, b, 0, 0)
    }
    fn imm(&mut self, op: Op, a: u32, c: f32) -> u32 {
        self.push(op, a, 0, 0, c.to_bits())
    }
    fn prim(&mut self, op: Op, p: P, block: Vec<u32>) -> u32 {
        let at = self.params(block);
        self.push(op, p.0, p.1, 0, at)
    }

    /// The material of `nmin(a, b)` (the winner's).
    fn mat_min(&mut self, a: u32, b: u32, ma: Mat, mb: Mat) -> Mat {
        if ma == mb {
            return ma;
        }
        let m = self.binary(Op::Lt, a, b);
        let (x, y) = (self.mat_value(ma), self.mat_value(mb));
        Mat::Value(self.push(Op::MatSelect, m, x, y, 0))
    }

    fn mat_value(&mut self, m: Mat) -> u32 {
        match m {
            Mat::Const(c) => self.push(Op::MatConst, 0, 0, 0, u32::from(c)),
            Mat::Value(v) => v,
        }
    }

    /// Drops instructions not reachable from the outputs and renumbers the rest.
    pub(crate) fn finish(self, value: u32, material: Mat) -> Program {
        let mut live = vec![false; self.ops.len()];
        let mut roots = vec![value];
        if let Mat::Value(m) = material {
            roots.push(m);
        }
        for r in roots {
            if let Some(l) = live.get_mut(r as usize) {
                *l = true;
            }
        }
        for i in (0..self.ops.len()).rev() {
            if live[i] {
                for o in self.ops[i].operands() {
                    live[o as usize] = true;
                }
            }
        }
        let mut remap = vec![u32::MAX; self.ops.len()];
        let mut ops = Vec::with_capacity(self.ops.len());
        for (i, ins) in self.ops.iter().enumerate() {
            if !live[i] {
                continue;
            }
            let mut ins = *ins;
            ins.map_operands(|o| remap[o as usize]);
            ins.dst = ops.len() as u32;
            remap[i] = ins.dst;
            ops.push(ins);
        }
        Program {
            ops,
            params: self.shared.unwrap_or_else(|| Arc::new(self.params)),
            value: remap[value as usize],
            material: match material {
                Mat::Const(c) => MatOut::Const(c),
                Mat::Value(v) => MatOut::Value(remap[v as usize]),
            },
        }
    }
}

/// A point: the SSA values of its x and y.
type P = (u32, u32);

fn f(v: f32) -> u32 {
    v.to_bits()
}

fn v2(v: glam::Vec2) -> [u32; 2] {
    [f(v.x), f(v.y)]
}

impl Graph {
    /// The graph lowered to an SSA tape program (built once, then shared).
    pub fn program(&self) -> Arc<Program> {
        self.program.get_or_init(|| Arc::new(lower(self))).clone()
    }
}

/// Lowers a graph.
pub(super) fn lower(graph: &Graph) -> Program {
    let mut l = Lower {
        g: graph,
        b: Builder::default(),
        memo: HashMap::new(),
    };
    let x = l.b.push(Op::X, 0, 0, 0, 0);
    let y = l.b.push(Op::Y, 0, 0, 0, 0);
    let (v, m) = l.node(graph.root, (x, y));
    l.b.finish(v, m)
}

struct Lower<'a> {
    g: &'a Graph,
    b: Builder,
    memo: HashMap<(u32, u32, u32), (u32, Mat)>,
}

impl Lower<'_> {
    fn node(&mut self, id: NodeId, p: P) -> (u32, Mat) {
        if let Some(&r) = self.memo.get(&(id.0, p.0, p.1)) {
            return r;
        }
        let r = self.node_uncached(id, p);
        self.memo.insert((id.0, p.0, p.1), r);
        r
    }

    fn leaf(&mut self, op: Op, p: P, block: Vec<u32>) -> (u32, Mat) {
        (self.b.prim(op, p, block), Mat::Const(0))
    }

    fn node_uncached(&mut self, id: NodeId, p: P) -> (u32, Mat) {
        let b = &mut self.b;
        match &self.g.ops[id.0 as usize] {
            G::Circle { c, r } => self.leaf(Op::Circle, p, vec![f(c.x), f(c.y), f(*r)]),
            G::Box { c, h } => self.leaf(Op::Box, p, [v2(*c), v2(*h)].concat()),
            G::RoundedBox { c, inner, r } => {
                let d = b.prim(Op::Box, p, [v2(*c), v2(*inner)].concat());
                (b.imm(Op::Offset, d, -r), Mat::Const(0))
            }
            G::OrientedBox { mid, dir, half } => {
                self.leaf(Op::OrientedBox, p, [v2(*mid), v2(*dir), v2(*half)].concat())
            }
            G::Capsule { a, ba, inv_ba2, r } => self.leaf(
                Op::Capsule,
                p,
                [v2(*a), v2(*ba), [f(*inv_ba2), f(*r)]].concat(),
            ),
            G::Polygon { pts, inv_e2 } => {
                let mut block = vec![pts.len() as u32];
                block.extend(pts.iter().flat_map(|q| v2(*q)));
                block.extend(inv_e2.iter().map(|v| f(*v)));
                self.leaf(Op::Polygon, p, block)
            }
            G::Ellipse { c, radii } => self.leaf(Op::Ellipse, p, [v2(*c), v2(*radii)].concat()),
            G::Ring { c, r, half_width } => {
                self.leaf(Op::Ring, p, vec![f(c.x), f(c.y), f(*r), f(*half_width)])
            }
            G::Arc { c, rot, sc, ra, rb } => self.leaf(
                Op::Arc,
                p,
                [v2(*c), v2(*rot), v2(*sc), [f(*ra), f(*rb)]].concat(),
            ),
            G::HalfPlane { n, offset } => {
                self.leaf(Op::HalfPlane, p, vec![f(n.x), f(n.y), f(*offset)])
            }
            G::Height { pts, dx, inv_e2 } => {
                let mut block = vec![pts.len() as u32, f(*dx)];
                block.extend(pts.iter().flat_map(|q| v2(*q)));
                block.extend(inv_e2.iter().map(|v| f(*v)));
                self.leaf(Op::Height, p, block)
            }
            G::Union(ids) => self.fold(ids, p, |l, acc, next| {
                let v = l.b.binary(Op::Min, acc.0, next.0);
                (v, l.b.mat_min(acc.0, next.0, acc.1, next.1))
            }),
            G::Intersection(ids) => self.fold(ids, p, |l, acc, next| {
                (l.b.binary(Op::Max, acc.0, next.0), acc.1)
            }),
            G::Subtract(a, c) => {
                let (da, m) = self.node(*a, p);
                let (dc, _) = self.node(*c, p);
                let neg = self.b.unary(Op::Neg, dc);
                (self.b.binary(Op::Max, da, neg), m)
            }
            G::SmoothUnion(k, ids) => {
                let k = *k;
                self.fold(ids, p, |l, acc, next| {
                    let m = l.b.mat_min(acc.0, next.0, acc.1, next.1);
                    (l.b.push(Op::SmoothMin, acc.0, next.0, 0, f(k)), m)
                })
            }
            G::SmoothIntersection(k, ids) => {
                let k = *k;
                self.fold(ids, p, |l, acc, next| {
                    (l.b.push(Op::SmoothMax, acc.0, next.0, 0, f(k)), acc.1)
                })
            }
            G::SmoothSubtract(k, a, c) => {
                let k = *k;
                let (da, m) = self.node(*a, p);
                let (dc, _) = self.node(*c, p);
                let neg = self.b.unary(Op::Neg, dc);
                (self.b.push(Op::SmoothMax, da, neg, 0, f(k)), m)
            }
            G::Round(r, c) => {
                let (d, m) = self.node(*c, p);
                (self.b.imm(Op::Offset, d, -r), m)
            }
            G::Onion(w, c) => {
                let (d, m) = self.node(*c, p);
                let a = self.b.unary(Op::Abs, d);
                (self.b.imm(Op::Offset, a, -w), m)
            }
            G::Translate(t, c) => {
                let q = (b.imm(Op::Offset, p.0, -t.x), b.imm(Op::Offset, p.1, -t.y));
                self.node(*c, q)
            }
            G::Rotate { cos, sin, child } => {
                let (cos, sin) = (*cos, *sin);
                let xc = b.imm(Op::Scale, p.0, cos);
                let ys = b.imm(Op::Scale, p.1, sin);
                let yc = b.imm(Op::Scale, p.1, cos);
                let xs = b.imm(Op::Scale, p.0, sin);
                let q = (b.binary(Op::Add, xc, ys), b.binary(Op::Sub, yc, xs));
                self.node(*child, q)
            }
            G::Scale { factor, inv, child } => {
                let factor = *factor;
                let q = (b.imm(Op::Scale, p.0, *inv), b.imm(Op::Scale, p.1, *inv));
                let (d, m) = self.node(*child, q);
                (self.b.imm(Op::Scale, d, factor), m)
            }
            G::Mirror { axis, at, child } => {
                let fold = |b: &mut Builder, v: u32| {
                    let o = b.imm(Op::Offset, v, -at);
                    let a = b.unary(Op::Abs, o);
                    b.imm(Op::Offset, a, *at)
                };
                let q = match axis {
                    Axis::X => (fold(b, p.0), p.1),
                    Axis::Y => (p.0, fold(b, p.1)),
                };
                self.node(*child, q)
            }
            G::Repeat(r) => self.repeat(r, p),
            G::Noise {
                amplitude,
                inv_wavelength,
                seed,
                child,
            } => {
                let (amplitude, inv, seed) = (*amplitude, *inv_wavelength, *seed);
                let (d, m) = self.node(*child, p);
                let b = &mut self.b;
                let xs = b.imm(Op::Scale, p.0, inv);
                let ys = b.imm(Op::Scale, p.1, inv);
                let n = b.push(Op::Noise, xs, ys, 0, seed);
                let n = b.imm(Op::Scale, n, amplitude);
                (b.binary(Op::Add, d, n), m)
            }
            G::Wave {
                amplitude,
                k,
                phase,
                child,
            } => {
                let (amplitude, k, phase) = (*amplitude, *k, *phase);
                let (d, m) = self.node(*child, p);
                let b = &mut self.b;
                let xk = b.imm(Op::Scale, p.0, k.x);
                let yk = b.imm(Op::Scale, p.1, k.y);
                let t = b.binary(Op::Add, xk, yk);
                let t = b.imm(Op::Offset, t, phase);
                let s = b.unary(Op::Wave, t);
                let s = b.imm(Op::Scale, s, amplitude);
                (b.binary(Op::Add, d, s), m)
            }
            G::Material(mat, c) => (self.node(*c, p).0, Mat::Const(*mat)),
            G::X => (p.0, Mat::Const(0)),
            G::Y => (p.1, Mat::Const(0)),
            G::Const(c) => (b.constant(*c), Mat::Const(0)),
            G::Add(a, c) => self.arith(Op::Add, *a, *c, p),
            G::Sub(a, c) => self.arith(Op::Sub, *a, *c, p),
            G::Mul(a, c) => self.arith(Op::Mul, *a, *c, p),
            G::Neg(a) | G::Square(a) | G::Sqrt(a) => {
                let op = match &self.g.ops[id.0 as usize] {
                    G::Neg(_) => Op::Neg,
                    G::Square(_) => Op::Square,
                    _ => Op::Sqrt,
                };
                let (d, m) = self.node(*a, p);
                (self.b.unary(op, d), m)
            }
        }
    }

    fn arith(&mut self, op: Op, a: NodeId, c: NodeId, p: P) -> (u32, Mat) {
        let (da, m) = self.node(a, p);
        let (dc, _) = self.node(c, p);
        (self.b.binary(op, da, dc), m)
    }

    fn fold(
        &mut self,
        ids: &[NodeId],
        p: P,
        f: impl Fn(&mut Self, (u32, Mat), (u32, Mat)) -> (u32, Mat),
    ) -> (u32, Mat) {
        let Some((first, rest)) = ids.split_first() else {
            return (self.b.constant(f32::INFINITY), Mat::Const(0));
        };
        let mut acc = self.node(*first, p);
        for id in rest {
            let next = self.node(*id, p);
            acc = f(self, acc, next);
        }
        acc
    }

    /// Repetition, as `Graph::repeat` evaluates it: the cap and the box around all
    /// instances, then the up to 3x3 instances around the nearest one, each guarded by its
    /// box, folded in order with the winner's material. Per-lane instance ranges become
    /// masks: an instance outside a lane's range takes no part there.
    fn repeat(&mut self, r: &Repeat, p: P) -> (u32, Mat) {
        let b = &mut self.b;
        let axes = [(p.0, 0usize), (p.1, 1usize)];
        let mut index = [None, None];
        for (coord, axis) in axes {
            if r.period[axis] > 0.0 {
                let block = vec![f(r.period[axis]), r.lo[axis] as u32, r.hi[axis] as u32];
                let at = b.params(block);
                index[axis] = Some(b.push(Op::RepeatIndex, coord, 0, 0, at));
            }
        }
        let outside = outside_distance(b, p, r.all_min, r.all_max);
        let cap = b.constant(r.cap);
        let mut best = b.binary(Op::Max, cap, outside);
        let mut best_m = Mat::Const(0);
        let offsets =
            |k: Option<u32>| -> &'static [i32] { if k.is_some() { &[-1, 0, 1] } else { &[0] } };
        for &dy in offsets(index[1]) {
            for &dx in offsets(index[0]) {
                let (qx, ax) = self.instance_axis(r, p.0, index[0], dx, 0);
                let (qy, ay) = self.instance_axis(r, p.1, index[1], dy, 1);
                let (d, m) = self.node(r.child, (qx, qy));
                let b = &mut self.b;
                let guard = repeat_guard(b, r, (qx, qy));
                let g = b.binary(Op::Max, d, guard);
                let lt = b.binary(Op::Lt, g, best);
                let take = match (ax, ay) {
                    (Some(x), Some(y)) => {
                        let both = b.binary(Op::And, x, y);
                        b.binary(Op::And, both, lt)
                    }
                    (Some(a), None) | (None, Some(a)) => b.binary(Op::And, a, lt),
                    (None, None) => lt,
                };
                best = b.push(Op::Select, take, g, best, 0);
                best_m = if m == best_m {
                    m
                } else {
                    let (x, y) = (b.mat_value(m), b.mat_value(best_m));
                    Mat::Value(b.push(Op::MatSelect, take, x, y, 0))
                };
            }
        }
        (best, best_m)
    }

    /// The instance coordinate `coord - (k + dk) * period` and its activity mask, or the
    /// coordinate itself on an axis that is not repeated (the reference subtracts `0.0`
    /// there, which changes no bit).
    fn instance_axis(
        &mut self,
        r: &Repeat,
        coord: u32,
        k: Option<u32>,
        dk: i32,
        axis: usize,
    ) -> (u32, Option<u32>) {
        let Some(k) = k else {
            return (coord, None);
        };
        let b = &mut self.b;
        let at = b.params(vec![dk as u32, f(r.period[axis])]);
        let off = b.push(Op::RepeatOffset, k, 0, 0, at);
        let at = b.params(vec![dk as u32, r.lo[axis] as u32, r.hi[axis] as u32]);
        let active = b.push(Op::RepeatActive, k, 0, 0, at);
        (b.binary(Op::ShiftSub, coord, off), Some(active))
    }
}

/// `eval::outside_distance` as instructions.
fn outside_distance(b: &mut Builder, p: P, min: glam::Vec2, max: glam::Vec2) -> u32 {
    let zero = b.constant(0.0);
    let mut axis = |v: u32, lo: f32, hi: f32| -> u32 {
        let below = if lo.is_finite() {
            let c = b.constant(lo);
            b.binary(Op::Sub, c, v)
        } else {
            zero
        };
        let above = if hi.is_finite() {
            b.imm(Op::Offset, v, -hi)
        } else {
            zero
        };
        let m = b.binary(Op::Max, below, above);
        b.binary(Op::Max, m, zero)
    };
    let ax = axis(p.0, min.x, max.x);
    let ay = axis(p.1, min.y, max.y);
    length(b, ax, ay)
}

/// `V2::length`: `sqrt(x*x + y*y)`.
fn length(b: &mut Builder, x: u32, y: u32) -> u32 {
    let xx = b.binary(Op::Mul, x, x);
    let yy = b.binary(Op::Mul, y, y);
    let s = b.binary(Op::Add, xx, yy);
    b.unary(Op::Sqrt, s)
}

/// `Graph::repeat_guard` as instructions.
fn repeat_guard(b: &mut Builder, r: &Repeat, q: P) -> u32 {
    let one_axis = |b: &mut Builder, v: u32, c: f32, h: f32| {
        let o = b.imm(Op::Offset, v, -c);
        let a = b.unary(Op::Abs, o);
        b.imm(Op::Offset, a, -h)
    };
    match (r.period.x > 0.0, r.period.y > 0.0) {
        (true, true) => b.prim(Op::Box, q, [v2(r.guard_c), v2(r.guard_h)].concat()),
        (true, false) => one_axis(b, q.0, r.guard_c.x, r.guard_h.x),
        _ => one_axis(b, q.1, r.guard_c.y, r.guard_h.y),
    }
}
