//! What one evaluation of a program costs, counted from its instructions before anything
//! runs, so that a level whose queries would crawl is refused when it is loaded rather than
//! discovered when a game stalls on it.
//!
//! The unit is one simple instruction (an add, a `min`, a circle). Instructions that loop
//! over data count what the loop can visit at worst: a polygon tests every edge, and a
//! height profile's nearest-segment search can visit every segment (a point far above the
//! ground reaches all of them). Value noise hashes four lattice corners and blends them.

use super::{Op, Tape};

/// The cost of one evaluation of a program at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EvalCost {
    /// Instructions of the tape (after fusion and register allocation, which turns
    /// constants into immediates: what the interpreter dispatches).
    pub instructions: usize,
    /// Work units: one per instruction, plus every polygon edge and height-profile
    /// segment an evaluation may visit, plus the lattice work of each noise instruction.
    pub work: u64,
}

/// Extra work of one value-noise instruction beyond its dispatch: four lattice hashes and
/// the smoothstep blend of the corners (measured at about eight simple instructions).
const NOISE_WORK: u64 = 8;

impl Tape {
    /// What one evaluation of this tape costs.
    pub fn cost(&self) -> EvalCost {
        let work = self
            .instrs
            .iter()
            .map(|i| 1 + self.loop_work(i.op, i.imm))
            .fold(0u64, u64::saturating_add);
        EvalCost {
            instructions: self.instrs.len(),
            work,
        }
    }

    /// The work of an instruction beyond its own dispatch.
    fn loop_work(&self, op: Op, imm: u32) -> u64 {
        let count = || self.params.get(imm as usize).copied().unwrap_or(0) as u64;
        match op {
            Op::Polygon => count(),
            Op::Height => count().saturating_sub(1),
            Op::Noise => NOISE_WORK,
            _ => 0,
        }
    }
}
