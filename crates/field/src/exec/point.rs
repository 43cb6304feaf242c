//! Single-point evaluation of a tape on the scalar backend, with a register file on the
//! stack for small tapes and a per-thread one for the rest, so a query allocates nothing.

use std::cell::RefCell;

use glam::Vec2;

use super::{Dv, Fv, run_tape};
use crate::sample::MaterialId;
use crate::tape::{MatOut, Tape};
use craterfield_core::det::math::Dual;
use craterfield_core::simd::Scalar;

thread_local! {
    static PLAIN: RefCell<Vec<[Fv<Scalar>; 1]>> = const { RefCell::new(Vec::new()) };
    static DUAL: RefCell<Vec<[Dv<Scalar>; 1]>> = const { RefCell::new(Vec::new()) };
}

fn material_of(tape: &Tape, bits: f32) -> MaterialId {
    match tape.material {
        MatOut::Const(m) => m,
        MatOut::Value(_) => bits.to_bits() as MaterialId,
    }
}

/// Tapes with at most this many registers run on a register file on the stack: a query
/// then skips the thread-local's lookup and borrow (most cell tapes are a few ops).
const STACK_REGISTERS: usize = 32;

/// The value (and the material, if the tape computes it) at `p`.
pub(crate) fn value(tape: &Tape, p: Vec2) -> (f32, MaterialId) {
    if tape.registers <= STACK_REGISTERS {
        let mut regs = [[Fv(0.0)]; STACK_REGISTERS];
        return value_on(tape, p, &mut regs[..tape.registers]);
    }
    PLAIN.with(|regs| {
        let mut regs = regs.borrow_mut();
        if regs.len() < tape.registers {
            regs.resize(tape.registers, [Fv(0.0)]);
        }
        value_on(tape, p, &mut regs)
    })
}

#[inline(always)]
fn value_on(tape: &Tape, p: Vec2, regs: &mut [[Fv<Scalar>; 1]]) -> (f32, MaterialId) {
    run_tape(Scalar, tape, regs, &[p.x], &[p.y], 1);
    let v = regs[tape.value as usize][0].0;
    let m = match tape.material {
        MatOut::Value(r) => material_of(tape, regs[r as usize][0].0),
        MatOut::Const(m) => m,
    };
    (v, m)
}

/// The material at `p` alone: read off the tape where it is one constant, else from the
/// value path (whose selections are the dual path's, so the material is the same).
pub(crate) fn material(tape: &Tape, p: Vec2) -> MaterialId {
    match tape.material {
        MatOut::Const(m) => m,
        MatOut::Value(_) => value(tape, p).1,
    }
}

/// The value with its gradient, and the material, at `p`.
pub(crate) fn dual(tape: &Tape, p: Vec2) -> (Dual, MaterialId) {
    let zero = Dv {
        v: 0.0,
        dx: 0.0,
        dy: 0.0,
    };
    if tape.registers <= STACK_REGISTERS {
        let mut regs = [[zero]; STACK_REGISTERS];
        return dual_on(tape, p, &mut regs[..tape.registers]);
    }
    DUAL.with(|regs| {
        let mut regs = regs.borrow_mut();
        if regs.len() < tape.registers {
            regs.resize(tape.registers, [zero]);
        }
        dual_on(tape, p, &mut regs)
    })
}

#[inline(always)]
fn dual_on(tape: &Tape, p: Vec2, regs: &mut [[Dv<Scalar>; 1]]) -> (Dual, MaterialId) {
    run_tape(Scalar, tape, regs, &[p.x], &[p.y], 1);
    let d = regs[tape.value as usize][0];
    let m = match tape.material {
        MatOut::Value(r) => material_of(tape, regs[r as usize][0].v),
        MatOut::Const(m) => m,
    };
    (
        Dual {
            v: d.v,
            dx: d.dx,
            dy: d.dy,
        },
        m,
    )
}
