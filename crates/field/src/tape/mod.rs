//! The tape compiler: a level [`Graph`](super::Graph) lowered to a flat SSA program, then
//! optimized and register-allocated into an instruction [`Tape`] that the interpreter
//! (`field2d::exec`) runs on every backend.
//!
//! # Pipeline
//!
//! 1. `lower`: the graph becomes SSA, operation for operation what the reference walker
//!    ([`super::eval`]) computes, so that every backend can match it bit for bit, in
//!    distance (`f32`) and in distance-and-gradient (dual number) mode. Primitives stay
//!    coarse instructions (a circle is one instruction, a polygon one loop); arithmetic,
//!    transforms and booleans are fine-grained. Building deduplicates identical
//!    instructions (common subexpressions) and folds constant arithmetic where the folded
//!    constant is the same dual number, signed zeros included.
//! 2. `specialize`: for a region, interval arithmetic decides which side of each
//!    `min`/`max`/select always wins there; the other side is dropped. Results are
//!    bit-identical with and without it.
//! 3. `fuse`: adjacent instruction patterns that dominate real tapes become
//!    superinstructions.
//! 4. `regalloc`: dead instructions are dropped, constants become immediates where the
//!    instruction has an immediate form, and values get registers by a linear scan that
//!    reuses a register as soon as its value's last use has passed.

mod cost;
mod error;
mod fuse;
mod image;
mod interval;
mod lipschitz;
mod lower;
mod reach;
mod regalloc;
mod specialize;

use std::sync::Arc;

pub use cost::EvalCost;
pub use error::EvalError;
pub(crate) use error::check;
pub use fuse::FuseOptions;
pub use image::{ImageOptions, inside_image};

use super::sample::MaterialId;

/// An instruction code. Operands `a`, `b`, `c` are values (SSA ids in a [`Program`],
/// registers in a [`Tape`]); `imm` is a constant's bits or an index into the parameters.
///
/// Value kinds: float values (a dual number in gradient mode), masks and integers. Float
/// instructions follow the dual-number arithmetic of [`craterfield_core::det::math::Dual`] exactly, so
/// the gradient's bits match the reference too (`a + C` and `a.offset(c)` differ there:
/// `dx + 0.0` turns `-0.0` into `+0.0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u8)]
pub enum Op {
    /// The query point's x (gradient `(1, 0)`).
    X,
    /// The query point's y (gradient `(0, 1)`).
    Y,
    /// Constant `imm` (f32 bits), zero gradient.
    Const,
    /// `a + b`.
    Add,
    /// `a - b`.
    Sub,
    /// `a * b`.
    Mul,
    /// `-a`.
    Neg,
    /// `|a|`.
    Abs,
    /// `sqrt(a)` (zero gradient where the value is zero).
    Sqrt,
    /// `a * a`.
    Square,
    /// `a.offset(imm)`: adds to the value, keeps the gradient.
    Offset,
    /// `a.scale(imm)`: multiplies value and gradient.
    Scale,
    /// `if a < b { a } else { b }`.
    Min,
    /// `if a > b { a } else { b }`.
    Max,
    /// `a.offset(-b.value)`: translation by a per-lane constant `b`.
    ShiftSub,
    /// `a + C` with `C = imm` (dual: `dx + 0`).
    AddImm,
    /// `a - C`.
    SubImm,
    /// `C - a`.
    RSubImm,
    /// `a * C`.
    MulImm,
    /// `if a < C { a } else { C }`.
    MinImm,
    /// `if a > C { a } else { C }`.
    MaxImm,
    /// Polynomial smooth minimum of width `imm` (`primitives::smooth_min`).
    SmoothMin,
    /// Polynomial smooth maximum of width `imm` (`primitives::smooth_max`).
    SmoothMax,
    /// Primitives of `(x, y) = (a, b)` with constants at `params[imm..]`.
    Circle,
    /// Axis-aligned box.
    Box,
    /// Oriented box.
    OrientedBox,
    /// Capsule.
    Capsule,
    /// Polygon.
    Polygon,
    /// Ellipse.
    Ellipse,
    /// Ring.
    Ring,
    /// Arc.
    Arc,
    /// Half-plane.
    HalfPlane,
    /// Height profile.
    Height,
    /// Value noise of `(a, b)` with seed `imm`.
    Noise,
    /// `sin(2π a)` by the deterministic polynomial, with its chain-rule gradient.
    Wave,
    /// Integer: the nearest repetition instance of coordinate `a` (`params[imm..]`:
    /// period, lowest and highest instance).
    RepeatIndex,
    /// Float: `(a + dk) as f32 * period` for integer `a` (`params[imm..]`: dk, period).
    RepeatOffset,
    /// Mask: `lo <= a + dk <= hi` for integer `a` (`params[imm..]`: dk, lo, hi).
    RepeatActive,
    /// Mask: `a < b` on values.
    Lt,
    /// Mask: `a & b`.
    And,
    /// Float: `if a { b } else { c }` for mask `a`.
    Select,
    /// Material (integer) `imm`.
    MatConst,
    /// Material: `if a { b } else { c }` for mask `a`.
    MatSelect,
    /// Fused: `sqrt(a * a + b * b)`.
    Hypot,
    /// Fused: `max(a, -b)`.
    MaxNeg,
    /// Fused: `min(a, -b)`.
    MinNeg,
    /// Fused: `max(max(a, b), c)`.
    Max3,
    /// Fused: `min(min(a, b), c)`.
    Min3,
    /// Fused: `max(a, b - C)`.
    MaxSubImm,
    /// Fused: `max(a, C - b)`.
    MaxRSubImm,
    /// Fused: `max(a, b + C)`.
    MaxAddImm,
    /// Fused: `max(a, b - c)`.
    MaxSub,
    /// Fused: `min(a, b - C)`.
    MinSubImm,
    /// Fused: `min(a, C - b)`.
    MinRSubImm,
    /// Fused: `min(a, b + C)`.
    MinAddImm,
    /// Fused: `min(a, b - c)`.
    MinSub,
}

impl Op {
    /// Every instruction code.
    pub const ALL: [Op; 56] = [
        Op::X,
        Op::Y,
        Op::Const,
        Op::Add,
        Op::Sub,
        Op::Mul,
        Op::Neg,
        Op::Abs,
        Op::Sqrt,
        Op::Square,
        Op::Offset,
        Op::Scale,
        Op::Min,
        Op::Max,
        Op::ShiftSub,
        Op::AddImm,
        Op::SubImm,
        Op::RSubImm,
        Op::MulImm,
        Op::MinImm,
        Op::MaxImm,
        Op::SmoothMin,
        Op::SmoothMax,
        Op::Circle,
        Op::Box,
        Op::OrientedBox,
        Op::Capsule,
        Op::Polygon,
        Op::Ellipse,
        Op::Ring,
        Op::Arc,
        Op::HalfPlane,
        Op::Height,
        Op::Noise,
        Op::Wave,
        Op::RepeatIndex,
        Op::RepeatOffset,
        Op::RepeatActive,
        Op::Lt,
        Op::And,
        Op::Select,
        Op::MatConst,
        Op::MatSelect,
        Op::Hypot,
        Op::MaxNeg,
        Op::MinNeg,
        Op::Max3,
        Op::Min3,
        Op::MaxSubImm,
        Op::MaxRSubImm,
        Op::MaxAddImm,
        Op::MaxSub,
        Op::MinSubImm,
        Op::MinRSubImm,
        Op::MinAddImm,
        Op::MinSub,
    ];
}

/// What kind of value an instruction produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A float (dual) value.
    Float,
    /// A mask.
    Mask,
    /// An integer (repetition index, material).
    Int,
}

impl Op {
    /// The kind of the result.
    pub fn kind(self) -> Kind {
        match self {
            Op::RepeatIndex | Op::MatConst | Op::MatSelect => Kind::Int,
            Op::RepeatActive | Op::Lt | Op::And => Kind::Mask,
            _ => Kind::Float,
        }
    }

    /// How many of `a`, `b`, `c` are operands.
    pub fn arity(self) -> usize {
        match self {
            Op::X | Op::Y | Op::Const | Op::MatConst => 0,
            Op::Neg
            | Op::Abs
            | Op::Sqrt
            | Op::Square
            | Op::Offset
            | Op::Scale
            | Op::AddImm
            | Op::SubImm
            | Op::RSubImm
            | Op::MulImm
            | Op::MinImm
            | Op::MaxImm
            | Op::Wave
            | Op::RepeatIndex
            | Op::RepeatOffset
            | Op::RepeatActive => 1,
            Op::Select | Op::MatSelect | Op::Max3 | Op::Min3 | Op::MaxSub | Op::MinSub => 3,
            _ => 2,
        }
    }

    /// Whether `imm` is an index into the parameters.
    pub fn has_params(self) -> bool {
        matches!(
            self,
            Op::Circle
                | Op::Box
                | Op::OrientedBox
                | Op::Capsule
                | Op::Polygon
                | Op::Ellipse
                | Op::Ring
                | Op::Arc
                | Op::HalfPlane
                | Op::Height
                | Op::RepeatIndex
                | Op::RepeatOffset
                | Op::RepeatActive
        )
    }
}

/// One instruction: `dst = op(a, b, c; imm)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Instr {
    /// The operation.
    pub op: Op,
    /// Destination register (in a [`Tape`]; the instruction's index in a [`Program`]).
    pub dst: u32,
    /// First operand.
    pub a: u32,
    /// Second operand.
    pub b: u32,
    /// Third operand.
    pub c: u32,
    /// Immediate: constant bits, a seed, a material or a parameter index.
    pub imm: u32,
}

impl Instr {
    /// The operands in use.
    pub fn operands(&self) -> impl Iterator<Item = u32> {
        [self.a, self.b, self.c].into_iter().take(self.op.arity())
    }

    /// Rewrites each operand in use.
    pub fn map_operands(&mut self, mut f: impl FnMut(u32) -> u32) {
        let n = self.op.arity();
        for (i, slot) in [&mut self.a, &mut self.b, &mut self.c]
            .into_iter()
            .enumerate()
        {
            if i < n {
                *slot = f(*slot);
            }
        }
    }

    /// The immediate as a float.
    pub fn imm_f32(&self) -> f32 {
        f32::from_bits(self.imm)
    }
}

/// The material at the output: a constant or the value of an integer instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MatOut {
    /// The same material everywhere.
    Const(MaterialId),
    /// Computed (an SSA id in a program, a register in a tape).
    Value(u32),
}

/// A lowered graph in SSA form: instruction `i` defines value `i`; operands refer to
/// earlier instructions.
#[derive(Clone, Debug)]
pub struct Program {
    pub(crate) ops: Vec<Instr>,
    pub(crate) params: Arc<Vec<u32>>,
    pub(crate) value: u32,
    pub(crate) material: MatOut,
}

impl Program {
    /// Number of instructions.
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// Whether there are no instructions (never, for a lowered graph).
    pub fn is_empty(&self) -> bool {
        self.ops.is_empty()
    }

    /// The instructions.
    pub fn instrs(&self) -> &[Instr] {
        &self.ops
    }

    /// Counts of each operation, most frequent first (for tooling and fusion choices).
    pub fn histogram(&self) -> Vec<(Op, usize)> {
        let mut counts = std::collections::BTreeMap::new();
        for i in &self.ops {
            *counts.entry(i.op).or_insert(0usize) += 1;
        }
        let mut v: Vec<(Op, usize)> = counts.into_iter().collect();
        v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        v
    }
}

/// Which outputs a tape computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Outputs {
    /// The value only (material instructions are dropped).
    Value,
    /// The value and the material.
    ValueMaterial,
}

/// A register-allocated instruction tape, ready for the evaluators.
#[derive(Clone, Debug)]
pub struct Tape {
    pub(crate) instrs: Vec<Instr>,
    pub(crate) params: Arc<Vec<u32>>,
    pub(crate) registers: usize,
    pub(crate) value: u32,
    pub(crate) material: MatOut,
    /// How far a height profile searches for its nearest segment at most
    /// (`f32::INFINITY`: as far as the point's vertical gap to the ground; see
    /// [`Tape::with_height_cap`]).
    pub(crate) height_cap: f32,
}

impl Tape {
    /// This tape with its height profiles searching no farther than `cap`, for a caller
    /// that clamps the value output to `[-m, m]` with `m <= cap` and whose program
    /// [`Program::heights_only_clamped`]: the clamped value, gradient and material keep
    /// every bit, and a profile stops visiting segments beyond the band. A point far
    /// below the ground otherwise visits every segment within its depth.
    pub fn with_height_cap(mut self, cap: f32) -> Tape {
        self.height_cap = cap;
        self
    }

    /// Bytes of its instructions and parameters.
    pub fn bytes(&self) -> usize {
        self.instrs.len() * std::mem::size_of::<Instr>() + self.params.len() * 4
    }

    /// Whether `other` computes the same thing the same way (instruction for instruction).
    pub(crate) fn same_as(&self, other: &Tape) -> bool {
        self.instrs == other.instrs
            && self.params == other.params
            && self.registers == other.registers
            && self.value == other.value
            && self.material == other.material
            && self.height_cap.to_bits() == other.height_cap.to_bits()
    }

    /// Number of instructions.
    pub fn len(&self) -> usize {
        self.instrs.len()
    }

    /// Whether there are no instructions (a constant tape still loads its constant).
    pub fn is_empty(&self) -> bool {
        self.instrs.is_empty()
    }

    /// Registers the tape needs.
    pub fn registers(&self) -> usize {
        self.registers
    }

    /// The instructions.
    pub fn instrs(&self) -> &[Instr] {
        &self.instrs
    }

    /// The material output.
    pub fn material(&self) -> MatOut {
        self.material
    }
}
