//! Which height profiles may stop searching at a cap: those whose value only reaches the
//! program's value output through min, max, negation and selects, when the caller clamps
//! that output to a band.
//!
//! Those operations commute with `clamp(·, -M, M)` (it is a lattice map), so the clamped
//! output depends on a profile's value only through `clamp(h, -M, M)`. A profile that
//! visits only the segments within a reach `C >= M` of the point returns exactly `h` when
//! `|h| <= C` (the nearest segment is among those visited) and otherwise a value of the
//! same sign and at least `C` in magnitude, so the clamped output keeps every bit, the
//! gradient included (a clamped value has none). Anything else that reads the profile
//! (an offset, a comparison that picks a material, arithmetic) could see the difference,
//! and then no profile is capped.

use super::{MatOut, Op, Program};

impl Program {
    /// Whether the program has a height profile and each one's value reaches the value
    /// output only through [`Op`]s that commute with a clamp (see the module doc), so that
    /// a caller who clamps the output may run its tapes with
    /// [`Tape::with_height_cap`](super::Tape::with_height_cap).
    pub fn heights_only_clamped(&self) -> bool {
        let n = self.ops.len();
        let mut any_height = false;
        // `tainted[i]`: some use of value `i` does not pass it to the value output through
        // the lattice (or it is the material output).
        let mut tainted = vec![false; n];
        if let MatOut::Value(m) = self.material
            && let Some(t) = tainted.get_mut(m as usize)
        {
            *t = true;
        }
        let mut used = vec![false; n];
        if let Some(u) = used.get_mut(self.value as usize) {
            *u = true;
        }
        for i in (0..n).rev() {
            let ins = &self.ops[i];
            let clean = used[i] && !tainted[i];
            if ins.op == Op::Height {
                any_height = true;
                if !clean {
                    return false;
                }
            }
            for (k, operand) in ins.operands().enumerate() {
                // Operands come before their users (SSA order); anything else is not
                // a program this can reason about.
                let j = operand as usize;
                if j >= i {
                    return false;
                }
                used[j] = true;
                if !(clean && passes_clamp(ins.op, k)) {
                    tainted[j] = true;
                }
            }
        }
        any_height
    }
}

/// Whether operand `k` of `op` reaches its result through an operation that commutes with
/// a clamp to a symmetric band.
fn passes_clamp(op: Op, k: usize) -> bool {
    match op {
        Op::Neg
        | Op::MinImm
        | Op::MaxImm
        | Op::Min
        | Op::Max
        | Op::MinNeg
        | Op::MaxNeg
        | Op::Min3
        | Op::Max3 => true,
        // The mask picks; the picked values pass as they are.
        Op::Select => k > 0,
        _ => false,
    }
}
