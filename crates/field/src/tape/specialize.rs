//! Region specialization: a program rewritten for the points of one box, keeping only what
//! can affect its results there, bit for bit.
//!
//! One forward pass bounds every value over the box ([`super::interval`]). Where the bounds
//! decide a comparison everywhere in the box, the instruction is replaced by the side that
//! always wins, exactly as evaluation would pick it:
//!
//! * `min(a, b)` is `a` when `a < b` everywhere, `b` when `a >= b` everywhere (ties go to
//!   `b`, as in evaluation); `max` likewise;
//! * a smooth min or max whose operands stay at least its width apart is the plain one;
//! * a mask decided everywhere (`a < b`, a repetition instance's activity) decides the
//!   selects and material selects that use it.
//!
//! The rebuilt program shares identical instructions and drops what no output reads.
//! Nothing is decided from an interval that may hold NaN.

use glam::Vec2;

use super::interval::{Range, Tri, and};
use super::lower::{Builder, Mat};
use super::{Instr, MatOut, Op, Program};
use crate::primitives as prim;
use craterfield_core::det::math;

/// The bound of each value, as the pass computes it.
#[derive(Clone, Copy, Debug)]
enum Bound {
    Float(Range),
    Mask(Tri),
    Int(i64, i64),
}

impl Bound {
    fn range(self) -> Range {
        match self {
            Bound::Float(r) => r,
            _ => Range::ALL,
        }
    }
    fn tri(self) -> Tri {
        match self {
            Bound::Mask(t) => t,
            _ => Tri::Maybe,
        }
    }
}

impl Program {
    /// This program specialized to the box `[min, max]` (see the module doc): for every
    /// point of the box it computes the same bits as `self`, in distance and dual mode.
    pub fn specialize(&self, min: Vec2, max: Vec2) -> Program {
        self.specialize_with_bound(min, max).0
    }

    /// [`Program::specialize`] and the bound of the value over the box, in one pass.
    pub fn specialize_with_bound(&self, min: Vec2, max: Vec2) -> (Program, Range) {
        let mut s = Specializer::new(self, min, max, true);
        for (i, ins) in self.ops.iter().enumerate() {
            s.step(i, ins);
        }
        let value = s.new[self.value as usize];
        let material = match self.material {
            MatOut::Const(c) => Mat::Const(c),
            MatOut::Value(m) => s.mat(s.new[m as usize]),
        };
        let bound = s.bound[self.value as usize].range();
        (s.b.finish(value, material), bound)
    }

    /// The bound of the program's value over the box `[min, max]`.
    pub fn bound(&self, min: Vec2, max: Vec2) -> Range {
        let mut s = Specializer::new(self, min, max, false);
        for (i, ins) in self.ops.iter().enumerate() {
            s.step(i, ins);
        }
        s.bound[self.value as usize].range()
    }
}

struct Specializer<'a> {
    p: &'a Program,
    /// Whether to rebuild the program (or only bound it).
    rebuild: bool,
    b: Builder,
    /// New id of each old value (`u32::MAX` for a mask decided everywhere).
    new: Vec<u32>,
    bound: Vec<Bound>,
    region: (Range, Range),
}

impl<'a> Specializer<'a> {
    fn new(p: &'a Program, min: Vec2, max: Vec2, rebuild: bool) -> Specializer<'a> {
        Specializer {
            p,
            rebuild,
            b: Builder::rewriting(p.params.clone()),
            new: vec![u32::MAX; p.ops.len()],
            bound: vec![Bound::Float(Range::ALL); p.ops.len()],
            region: (Range::new(min.x, max.x), Range::new(min.y, max.y)),
        }
    }

    fn mat(&mut self, id: u32) -> Mat {
        match self.b.ops.get(id as usize) {
            Some(i) if i.op == Op::MatConst => Mat::Const(i.imm as u16),
            _ => Mat::Value(id),
        }
    }

    /// Records that old value `i` is new value `id` with bound `bound`.
    fn set(&mut self, i: usize, id: u32, bound: Bound) {
        self.new[i] = id;
        self.bound[i] = bound;
    }

    /// Old value `i` is old value `j`.
    fn alias(&mut self, i: usize, j: u32) {
        self.new[i] = self.new[j as usize];
        self.bound[i] = self.bound[j as usize];
    }

    fn step(&mut self, i: usize, ins: &Instr) {
        let r = |k: u32| self.bound[k as usize].range();
        let (ra, rb) = (r(ins.a), r(ins.b));
        let imm = ins.imm_f32();
        let decided_min = |a: Range, b: Range| Range::lt(a, b);
        match ins.op {
            Op::Min | Op::MinNeg => {
                let rb = if ins.op == Op::MinNeg {
                    Range::negated(rb)
                } else {
                    rb
                };
                match decided_min(ra, rb) {
                    Tri::True => return self.alias(i, ins.a),
                    Tri::False if ins.op == Op::Min => return self.alias(i, ins.b),
                    _ => {}
                }
            }
            Op::Max | Op::MaxNeg => {
                let rb = if ins.op == Op::MaxNeg {
                    Range::negated(rb)
                } else {
                    rb
                };
                match Range::gt(ra, rb) {
                    Tri::True => return self.alias(i, ins.a),
                    Tri::False if ins.op == Op::Max => return self.alias(i, ins.b),
                    _ => {}
                }
            }
            Op::SmoothMin | Op::SmoothMax => {
                // hk = k - |a - b| <= 0 everywhere: the result is the plain min / max.
                let hk = Range::offset(
                    Range::scale(Range::abs(Range::difference(ra, rb)), -1.0),
                    imm,
                );
                if !hk.nan && hk.hi <= 0.0 {
                    let op = if ins.op == Op::SmoothMin {
                        Op::Min
                    } else {
                        Op::Max
                    };
                    let plain = Instr { op, imm: 0, ..*ins };
                    return self.step(i, &plain);
                }
            }
            Op::Select | Op::MatSelect => match self.bound[ins.a as usize].tri() {
                Tri::True => return self.alias(i, ins.b),
                Tri::False => return self.alias(i, ins.c),
                Tri::Maybe => {}
            },
            Op::And => {
                let t = and(
                    self.bound[ins.a as usize].tri(),
                    self.bound[ins.b as usize].tri(),
                );
                match (
                    t,
                    self.bound[ins.a as usize].tri(),
                    self.bound[ins.b as usize].tri(),
                ) {
                    (Tri::Maybe, Tri::True, _) => return self.alias(i, ins.b),
                    (Tri::Maybe, _, Tri::True) => return self.alias(i, ins.a),
                    (Tri::Maybe, _, _) => {}
                    (t, _, _) => return self.set(i, u32::MAX, Bound::Mask(t)),
                }
            }
            _ => {}
        }
        let bound = self.bound_of(ins);
        if matches!(bound, Bound::Mask(Tri::True | Tri::False)) {
            // A decided mask: its users resolve it; it is never materialized.
            return self.set(i, u32::MAX, bound);
        }
        if !self.rebuild {
            return self.set(i, 0, bound);
        }
        let mut n = *ins;
        n.map_operands(|o| self.new[o as usize]);
        let id = self.b.push(n.op, n.a, n.b, n.c, n.imm);
        self.set(i, id, bound);
    }

    /// The bound of an instruction that was not replaced.
    fn bound_of(&self, ins: &Instr) -> Bound {
        let r = |k: u32| self.bound[k as usize].range();
        let (ra, rb) = (r(ins.a), r(ins.b));
        let imm = ins.imm_f32();
        let params = &self.p.params;
        let pf = |k: usize| f32::from_bits(params.get(ins.imm as usize + k).copied().unwrap_or(0));
        let pu = |k: usize| params.get(ins.imm as usize + k).copied().unwrap_or(0);
        let pv = |k: usize| Vec2::new(pf(k), pf(k + 1));
        let prim_at = |f: &dyn Fn(Vec2) -> f32| {
            Bound::Float(Range::lipschitz_box(ra, rb, |x, y| f(Vec2::new(x, y))))
        };
        let pt = |x: f32, y: f32| math::V2::new(x, y);
        Bound::Float(match ins.op {
            Op::X => self.region.0,
            Op::Y => self.region.1,
            Op::Const => Range::point(imm),
            Op::Add => Range::sum(ra, rb),
            Op::Sub => Range::difference(ra, rb),
            Op::Mul => Range::product(ra, rb),
            Op::Neg => Range::negated(ra),
            Op::Abs => Range::abs(ra),
            Op::Sqrt => Range::sqrt(ra),
            Op::Square => Range::square(ra),
            Op::Offset => Range::offset(ra, imm),
            Op::Scale => Range::scale(ra, imm),
            Op::Min => Range::min(ra, rb),
            Op::Max => Range::max(ra, rb),
            Op::MinNeg => Range::min(ra, Range::negated(rb)),
            Op::Max3 => Range::max(Range::max(ra, rb), r(ins.c)),
            Op::Min3 => Range::min(Range::min(ra, rb), r(ins.c)),
            Op::MaxSubImm => Range::max(ra, Range::offset(rb, -imm)),
            Op::MaxRSubImm => Range::max(ra, Range::difference(Range::point(imm), rb)),
            Op::MaxAddImm => Range::max(ra, Range::offset(rb, imm)),
            Op::MaxSub => Range::max(ra, Range::difference(rb, r(ins.c))),
            Op::MinSubImm => Range::min(ra, Range::offset(rb, -imm)),
            Op::MinRSubImm => Range::min(ra, Range::difference(Range::point(imm), rb)),
            Op::MinAddImm => Range::min(ra, Range::offset(rb, imm)),
            Op::MinSub => Range::min(ra, Range::difference(rb, r(ins.c))),
            Op::MaxNeg => Range::max(ra, Range::negated(rb)),
            Op::ShiftSub => Range::difference(ra, rb),
            Op::AddImm => Range::offset(ra, imm),
            Op::SubImm => Range::offset(ra, -imm),
            Op::RSubImm => Range::difference(Range::point(imm), ra),
            Op::MulImm => Range::scale(ra, imm),
            Op::MinImm => Range::min(ra, Range::point(imm)),
            Op::MaxImm => Range::max(ra, Range::point(imm)),
            Op::Hypot => Range::sqrt(Range::sum(Range::square(ra), Range::square(rb))),
            Op::SmoothMin => {
                let m = Range::min(ra, rb);
                Range::new(m.lo - imm * 0.25, m.hi).with_nan_of(m)
            }
            Op::SmoothMax => {
                let m = Range::max(ra, rb);
                Range::new(m.lo, m.hi + imm * 0.25).with_nan_of(m)
            }
            Op::Circle => return prim_at(&|p| prim::circle(pt(p.x, p.y), pv(0), pf(2))),
            Op::Box => return prim_at(&|p| prim::aabox(pt(p.x, p.y), pv(0), pv(2))),
            Op::OrientedBox => {
                return prim_at(&|p| prim::oriented_box(pt(p.x, p.y), pv(0), pv(2), pv(4)));
            }
            Op::Capsule => {
                return prim_at(&|p| prim::capsule(pt(p.x, p.y), pv(0), pv(2), pf(4), pf(5)));
            }
            Op::Ellipse => return prim_at(&|p| prim::ellipse(pt(p.x, p.y), pv(0), pv(2))),
            Op::Ring => return prim_at(&|p| prim::ring(pt(p.x, p.y), pv(0), pf(2), pf(3))),
            Op::Arc => {
                return prim_at(&|p| prim::arc(pt(p.x, p.y), pv(0), pv(2), pv(4), pf(6), pf(7)));
            }
            Op::HalfPlane => {
                return prim_at(&|p| prim::half_plane(pt(p.x, p.y), pv(0), pf(2)));
            }
            Op::Polygon => {
                let n = pu(0) as usize;
                let pts: Vec<Vec2> = (0..n).map(|k| pv(1 + 2 * k)).collect();
                let inv: Vec<f32> = (0..n).map(|k| pf(1 + 2 * n + k)).collect();
                return prim_at(&|p| prim::polygon(pt(p.x, p.y), &pts, &inv));
            }
            Op::Height => {
                let words = params.get(ins.imm as usize..).unwrap_or(&[]);
                return prim_at(&|p| crate::exec::prims::height_profile_at(words, p));
            }
            // Lattice values are in [-1, 1) and the fade weights in [0, 1]; the sine
            // polynomial stays within 1 (tested); a little room for rounding.
            Op::Noise | Op::Wave => Range::new(-1.000_1, 1.000_1),
            Op::RepeatIndex => return self.repeat_index(ra, pf(0), pu(1) as i32, pu(2) as i32),
            Op::RepeatOffset => {
                let Bound::Int(lo, hi) = self.bound[ins.a as usize] else {
                    return Bound::Float(Range::ALL);
                };
                let (dk, period) = (i64::from(pu(0) as i32), pf(1));
                let f = |k: i64| ((k + dk) as i32) as f32 * period;
                Range::new(f(lo), f(hi))
            }
            Op::RepeatActive => {
                let Bound::Int(lo, hi) = self.bound[ins.a as usize] else {
                    return Bound::Mask(Tri::Maybe);
                };
                let dk = i64::from(pu(0) as i32);
                let (l, h) = (i64::from(pu(1) as i32), i64::from(pu(2) as i32));
                let (a, b) = (lo + dk, hi + dk);
                return Bound::Mask(if a >= l && b <= h {
                    Tri::True
                } else if b < l || a > h {
                    Tri::False
                } else {
                    Tri::Maybe
                });
            }
            Op::Lt => return Bound::Mask(Range::lt(ra, rb)),
            Op::And => {
                return Bound::Mask(and(
                    self.bound[ins.a as usize].tri(),
                    self.bound[ins.b as usize].tri(),
                ));
            }
            Op::Select => Range::union(r(ins.b), r(ins.c)),
            Op::MatConst | Op::MatSelect => return Bound::Int(0, i64::from(u16::MAX)),
        })
    }

    /// The instance index is monotonic in the coordinate: bounded by its ends.
    fn repeat_index(&self, r: Range, period: f32, lo: i32, hi: i32) -> Bound {
        if r.nan || r.lo.is_nan() || r.hi.is_nan() {
            return Bound::Int(i64::from(lo), i64::from(hi));
        }
        let k = |v: f32| ((v / period + 0.5).floor() as i32).clamp(lo, hi);
        Bound::Int(i64::from(k(r.lo)), i64::from(k(r.hi)))
    }
}

impl Range {
    fn with_nan_of(self, other: Range) -> Range {
        if other.nan { Range::ALL } else { self }
    }
}
