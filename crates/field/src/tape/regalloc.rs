//! From SSA to a register-allocated [`Tape`]: dead-code elimination for the outputs asked
//! for, constant operands turned into immediates, and a linear-scan register allocation.
//!
//! Immediate forms keep the exact dual arithmetic of the general instruction with a
//! constant operand (`a + C` is `AddImm`, not `Offset`). `min`/`max` with the constant
//! first are not symmetric (ties and NaN pick the second operand), so only the
//! constant-second form has an immediate; anything else keeps the constant in a register.

use super::{Instr, MatOut, Op, Outputs, Program, Tape};

/// Which immediate form `op(a, b)` takes when `a` (`first`) or `b` is the constant.
fn immediate_form(op: Op, constant_first: bool) -> Option<Op> {
    Some(match (op, constant_first) {
        (Op::Add, _) => Op::AddImm,
        (Op::Mul, _) => Op::MulImm,
        (Op::Sub, false) => Op::SubImm,
        (Op::Sub, true) => Op::RSubImm,
        (Op::Min, false) => Op::MinImm,
        (Op::Max, false) => Op::MaxImm,
        _ => return None,
    })
}

/// Rewrites binary instructions with one constant operand into immediate forms.
fn use_immediates(ops: &mut [Instr]) {
    let constant = |ops: &[Instr], id: u32| {
        let i = ops[id as usize];
        (i.op == Op::Const).then_some(i.imm)
    };
    for k in 0..ops.len() {
        let i = ops[k];
        if i.op.arity() != 2 || immediate_form(i.op, false).is_none() {
            continue;
        }
        let (ca, cb) = (constant(ops, i.a), constant(ops, i.b));
        let rewritten = match (ca, cb) {
            (_, Some(c)) => immediate_form(i.op, false).map(|op| (op, i.a, c)),
            (Some(c), None) => immediate_form(i.op, true).map(|op| (op, i.b, c)),
            (None, None) => None,
        };
        if let Some((op, a, imm)) = rewritten {
            ops[k] = Instr {
                op,
                a,
                b: 0,
                c: 0,
                imm,
                ..i
            };
        }
    }
}

/// Allocates registers for `program`, computing `outputs`.
pub(super) fn allocate(program: &Program, outputs: Outputs) -> Tape {
    let mut ops = program.ops.clone();
    use_immediates(&mut ops);
    let mut roots = vec![program.value];
    let material = match (outputs, program.material) {
        (Outputs::ValueMaterial, MatOut::Value(m)) => {
            roots.push(m);
            Some(m)
        }
        _ => None,
    };
    // Liveness: the last instruction reading each value (roots live to the end).
    let n = ops.len();
    let mut live = vec![false; n];
    let mut last_use = vec![0usize; n];
    for &r in &roots {
        live[r as usize] = true;
        last_use[r as usize] = usize::MAX;
    }
    for k in (0..n).rev() {
        if !live[k] {
            continue;
        }
        for o in ops[k].operands() {
            let o = o as usize;
            live[o] = true;
            if last_use[o] < k {
                last_use[o] = k;
            }
        }
    }
    let mut reg_of = vec![u32::MAX; n];
    let mut free: Vec<u32> = Vec::new();
    let mut registers = 0u32;
    let mut instrs = Vec::with_capacity(n);
    for k in 0..n {
        if !live[k] {
            continue;
        }
        let mut ins = ops[k];
        ins.map_operands(|o| reg_of[o as usize]);
        // Operands whose last use this is give their registers back before the result
        // takes one: the interpreter reads every operand before writing.
        let mut released: Vec<u32> = Vec::new();
        for o in ops[k].operands() {
            if last_use[o as usize] == k && !released.contains(&o) {
                released.push(o);
                free.push(reg_of[o as usize]);
            }
        }
        let dst = free.pop().unwrap_or_else(|| {
            registers += 1;
            registers - 1
        });
        reg_of[k] = dst;
        ins.dst = dst;
        instrs.push(ins);
    }
    Tape {
        instrs,
        params: program.params.clone(),
        registers: registers.max(1) as usize,
        value: reg_of[program.value as usize],
        material: match (material, program.material) {
            (Some(m), _) => MatOut::Value(reg_of[m as usize]),
            (None, MatOut::Const(c)) => MatOut::Const(c),
            (None, MatOut::Value(_)) => MatOut::Const(0),
        },
        height_cap: f32::INFINITY,
    }
}

impl Program {
    /// The register-allocated tape of this program for `outputs`.
    pub fn tape(&self, outputs: Outputs) -> Tape {
        allocate(self, outputs)
    }
}
