//! Superinstructions: adjacent instruction patterns that dominate real tapes, fused into one
//! instruction that computes the same dual arithmetic in the same order (so no bit
//! changes) with one decode and no intermediate registers.
//!
//! The patterns, chosen from the instruction histograms of the prospero expression and the
//! example levels (`craterfield bench eval` reports what each saves):
//!
//! * `sqrt(a*a + b*b)` (`Square`, `Square`, `Add`, `Sqrt`) becomes `Hypot(a, b)`: every
//!   circle and rounded corner of an expression;
//! * `max(a, -b)` and `min(a, -b)` (`Neg` then `Max`/`Min`) become `MaxNeg`/`MinNeg`:
//!   subtraction (`max(base, -cut)`) and its mirror.
//!
//! An intermediate is folded only when nothing else reads it.

use super::lower::Builder;
use super::lower::Mat;
use super::{Instr, MatOut, Op, Program};

impl Program {
    /// This program with the superinstructions of the module doc.
    pub fn fuse(&self) -> Program {
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
        let single = |id: u32, op: Op| {
            let i = &self.ops[id as usize];
            (i.op == op && uses[id as usize] == 1).then_some(i)
        };
        let mut b = Builder::rewriting(self.params.clone());
        let mut new = vec![0u32; self.ops.len()];
        for (k, ins) in self.ops.iter().enumerate() {
            let fused = match ins.op {
                Op::Sqrt => single(ins.a, Op::Add).and_then(|add| {
                    let (sa, sb) = (single(add.a, Op::Square)?, single(add.b, Op::Square)?);
                    Some((Op::Hypot, sa.a, sb.a))
                }),
                Op::Max | Op::Min => single(ins.b, Op::Neg).map(|neg| {
                    let op = if ins.op == Op::Max {
                        Op::MaxNeg
                    } else {
                        Op::MinNeg
                    };
                    (op, ins.a, neg.a)
                }),
                _ => None,
            };
            let i: Instr = match fused {
                Some((op, a, c)) => Instr {
                    op,
                    a,
                    b: c,
                    c: 0,
                    imm: 0,
                    ..*ins
                },
                None => *ins,
            };
            let mut i = i;
            i.map_operands(|o| new[o as usize]);
            new[k] = b.push(i.op, i.a, i.b, i.c, i.imm);
        }
        let material = match self.material {
            MatOut::Const(c) => Mat::Const(c),
            MatOut::Value(m) => Mat::Value(new[m as usize]),
        };
        b.finish(new[self.value as usize], material)
    }
}
