//! Superinstructions: adjacent instruction patterns that dominate real tapes, fused into one
//! instruction that computes the same dual arithmetic in the same order (so no bit
//! changes) with one decode and no intermediate registers.
//!
//! The patterns, chosen from the instruction pair counts of the prospero expression (the
//! consumer and its single-use producer; `craterfield bench eval` reports what fusing
//! saves):
//!
//! * `sqrt(a*a + b*b)` becomes `Hypot(a, b)`: every circle of an expression. The squares
//!   may have other readers (they then stay); recomputing a product is cheaper than the
//!   instructions saved;
//! * `max(a, b)` / `min(a, b)` whose `b` is a negation, a subtraction, or an addition or
//!   subtraction of a constant: one instruction for both;
//! * `max(max(a, b), c)` / `min(min(a, b), c)`: chains of unions and intersections, two
//!   links at a time.
//!
//! An intermediate is folded only when nothing else reads it (except squares, see above).
//! Fusion runs after region specialization, which decides on the plain instructions.

use super::lower::Builder;
use super::lower::Mat;
use super::{Instr, MatOut, Op, Program};

/// Which patterns to fuse (all by default; switches exist to measure each one).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FuseOptions {
    /// `sqrt(a*a + b*b)` into `Hypot`.
    pub hypot: bool,
    /// `max`/`min` of a negation, a subtraction or an affine term.
    pub affine: bool,
    /// Two links of a `max`/`min` chain into one.
    pub chains: bool,
}

impl Default for FuseOptions {
    fn default() -> Self {
        FuseOptions {
            hypot: true,
            affine: true,
            chains: true,
        }
    }
}

impl FuseOptions {
    /// No fusion at all.
    pub const NONE: FuseOptions = FuseOptions {
        hypot: false,
        affine: false,
        chains: false,
    };
}

impl Program {
    /// This program with the superinstructions of the module doc.
    pub fn fuse(&self) -> Program {
        self.fuse_with(FuseOptions::default())
    }

    /// This program with the chosen superinstructions.
    pub fn fuse_with(&self, o: FuseOptions) -> Program {
        let mut uses = vec![0u32; self.ops.len()];
        for i in &self.ops {
            for o in i.operands() {
                uses[o as usize] += 1;
            }
        }
        uses[self.value as usize] += 1;
        if let MatOut::Value(m) = self.material {
            uses[m as usize] += 1;
        }
        let mut b = Builder::rewriting(self.params.clone());
        let mut new = vec![0u32; self.ops.len()];
        for (k, ins) in self.ops.iter().enumerate() {
            let fused = self.fused(ins, &uses, &b, &new, o);
            let mut i = fused.unwrap_or(*ins);
            if fused.is_none() {
                i.map_operands(|o| new[o as usize]);
            }
            new[k] = b.push(i.op, i.a, i.b, i.c, i.imm);
        }
        let material = match self.material {
            MatOut::Const(c) => Mat::Const(c),
            MatOut::Value(m) => Mat::Value(new[m as usize]),
        };
        b.finish(new[self.value as usize], material)
    }

    /// The superinstruction replacing `ins`, with operands already renamed, if any.
    fn fused(
        &self,
        ins: &Instr,
        uses: &[u32],
        b: &Builder,
        new: &[u32],
        o: FuseOptions,
    ) -> Option<Instr> {
        let at = |id: u32| &self.ops[id as usize];
        let single = |id: u32, op: Op| (at(id).op == op && uses[id as usize] == 1).then(|| at(id));
        let constant = |id: u32| (at(id).op == Op::Const).then(|| at(id).imm);
        let n = |id: u32| new[id as usize];
        let make = |op: Op, a: u32, bb: u32, c: u32, imm: u32| Instr {
            op,
            dst: 0,
            a,
            b: bb,
            c,
            imm,
        };
        match ins.op {
            Op::Sqrt if o.hypot => {
                let add = single(ins.a, Op::Add)?;
                let (sa, sb) = (at(add.a), at(add.b));
                (sa.op == Op::Square && sb.op == Op::Square)
                    .then(|| make(Op::Hypot, n(sa.a), n(sb.a), 0, 0))
            }
            Op::Max | Op::Min => {
                let max = ins.op == Op::Max;
                let pick = |mx: Op, mn: Op| if max { mx } else { mn };
                let y = at(ins.b);
                if o.affine && uses[ins.b as usize] == 1 {
                    let affine = match y.op {
                        Op::Neg => Some(make(pick(Op::MaxNeg, Op::MinNeg), n(ins.a), n(y.a), 0, 0)),
                        Op::Sub => Some(match (constant(y.a), constant(y.b)) {
                            (_, Some(c)) => {
                                make(pick(Op::MaxSubImm, Op::MinSubImm), n(ins.a), n(y.a), 0, c)
                            }
                            (Some(c), None) => {
                                make(pick(Op::MaxRSubImm, Op::MinRSubImm), n(ins.a), n(y.b), 0, c)
                            }
                            (None, None) => {
                                make(pick(Op::MaxSub, Op::MinSub), n(ins.a), n(y.a), n(y.b), 0)
                            }
                        }),
                        Op::Add => match (constant(y.a), constant(y.b)) {
                            (_, Some(c)) => Some(make(
                                pick(Op::MaxAddImm, Op::MinAddImm),
                                n(ins.a),
                                n(y.a),
                                0,
                                c,
                            )),
                            (Some(c), None) => Some(make(
                                pick(Op::MaxAddImm, Op::MinAddImm),
                                n(ins.a),
                                n(y.b),
                                0,
                                c,
                            )),
                            (None, None) => None,
                        },
                        _ => None,
                    };
                    if affine.is_some() {
                        return affine;
                    }
                }
                // A chain link whose left operand is a plain link read only here: the
                // inner instruction, as rebuilt, must still be the plain operation.
                let inner = b.ops.get(n(ins.a) as usize)?;
                (o.chains && uses[ins.a as usize] == 1 && inner.op == ins.op)
                    .then(|| make(pick(Op::Max3, Op::Min3), inner.a, inner.b, n(ins.b), 0))
            }
            _ => None,
        }
    }
}
