//! An upper bound of a tape's Lipschitz constant, read off its instructions.
//!
//! The graph derives one bound for a whole level; a tape specialized to a small region has
//! lost the subtrees that cannot win there (a noise-displaced boulder far away, a scaled
//! shape), so its own bound is often much tighter. Each value is tracked abstractly as
//!
//! * `Linear(u)`: exactly `u . p + const` (the query point's coordinates, translated,
//!   rotated or scaled), so that a primitive of `(a, b)` is bounded by the spectral norm of
//!   the linear map `p -> (a, b)` rather than by `|u_a| + |u_b|`;
//! * `Const(c)`: a known constant;
//! * `Bound(L)`: anything else, `L`-Lipschitz (`+inf` where nothing is known).
//!
//! The rules: sums add bounds, `min`/`max`/smooth `min`/`max` take the larger, scaling by
//! `c` multiplies by `|c|`, a product needs a constant factor, and every primitive is an
//! exact distance (1-Lipschitz) of its local coordinates, as the graph states. Noise, waves,
//! square roots, squares, selects and domain repetition give `+inf`: callers fall back to
//! the graph's bound there.

use glam::Vec2;

use super::{Instr, Op};

/// What is known about one value.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Abs {
    Const(f32),
    Linear(Vec2),
    Bound(f32),
}

impl Abs {
    /// The Lipschitz bound of the value.
    fn lipschitz(self) -> f32 {
        match self {
            Abs::Const(_) => 0.0,
            Abs::Linear(u) => u.length(),
            Abs::Bound(l) => l,
        }
    }

    fn gradient(self) -> Option<Vec2> {
        match self {
            Abs::Const(_) => Some(Vec2::ZERO),
            Abs::Linear(u) => Some(u),
            Abs::Bound(_) => None,
        }
    }
}

const UNKNOWN: Abs = Abs::Bound(f32::INFINITY);

/// `a + s b` for linear or constant operands, else the sum of the bounds.
fn sum(a: Abs, b: Abs, s: f32) -> Abs {
    match (a, b) {
        (Abs::Const(x), Abs::Const(y)) => Abs::Const(x + s * y),
        _ => match (a.gradient(), b.gradient()) {
            (Some(u), Some(v)) => Abs::Linear(u + s * v),
            _ => Abs::Bound(a.lipschitz() + b.lipschitz()),
        },
    }
}

fn scaled(a: Abs, c: f32) -> Abs {
    match a {
        Abs::Const(x) => Abs::Const(x * c),
        Abs::Linear(u) => Abs::Linear(u * c),
        Abs::Bound(l) => Abs::Bound(l * c.abs()),
    }
}

/// The larger bound (min, max and their smooth and fused forms).
fn larger(bounds: &[Abs]) -> Abs {
    Abs::Bound(bounds.iter().map(|b| b.lipschitz()).fold(0.0, f32::max))
}

/// The bound of an exact distance of the local coordinates `(a, b)`: the spectral norm of
/// the map `p -> (a, b)` when both are linear, else `sqrt(La^2 + Lb^2)`.
fn of_coordinates(a: Abs, b: Abs) -> Abs {
    let l = match (a.gradient(), b.gradient()) {
        (Some(u), Some(v)) => spectral_norm(u, v),
        _ => a.lipschitz().hypot(b.lipschitz()),
    };
    Abs::Bound(l * (1.0 + 1.0e-6))
}

/// Largest singular value of the matrix with rows `u` and `v`.
fn spectral_norm(u: Vec2, v: Vec2) -> f32 {
    let (a, b, c) = (u.dot(u), u.dot(v), v.dot(v));
    // Largest eigenvalue of [[a, b], [b, c]].
    let half_trace = 0.5 * (a + c);
    let disc = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    (half_trace + disc).max(0.0).sqrt()
}

/// An upper bound of the Lipschitz constant of the value `out` computed by `instrs` over
/// `registers` registers (a [`super::Tape`]'s, or a [`super::Program`]'s with one register
/// per instruction); `+inf` when an instruction has no rule.
pub(super) fn lipschitz_bound(instrs: &[Instr], registers: usize, out: u32) -> f32 {
    let mut regs = vec![UNKNOWN; registers];
    for i in instrs {
        let get = |r: u32| regs.get(r as usize).copied().unwrap_or(UNKNOWN);
        let (a, b, c) = (get(i.a), get(i.b), get(i.c));
        let imm = i.imm_f32();
        let v = match i.op {
            Op::X => Abs::Linear(Vec2::X),
            Op::Y => Abs::Linear(Vec2::Y),
            Op::Const => Abs::Const(imm),
            Op::Add => sum(a, b, 1.0),
            Op::Sub => sum(a, b, -1.0),
            Op::Mul => match (a, b) {
                (Abs::Const(x), _) => scaled(b, x),
                (_, Abs::Const(y)) => scaled(a, y),
                _ => UNKNOWN,
            },
            Op::Neg => scaled(a, -1.0),
            Op::RSubImm => match a {
                Abs::Const(x) => Abs::Const(imm - x),
                other => scaled(other, -1.0),
            },
            Op::Abs => Abs::Bound(a.lipschitz()),
            Op::Offset | Op::AddImm => match a {
                Abs::Const(x) => Abs::Const(x + imm),
                other => other,
            },
            Op::SubImm => match a {
                Abs::Const(x) => Abs::Const(x - imm),
                other => other,
            },
            Op::Scale | Op::MulImm => scaled(a, imm),
            Op::Min | Op::Max | Op::SmoothMin | Op::SmoothMax => larger(&[a, b]),
            Op::MinImm | Op::MaxImm => larger(&[a]),
            Op::MaxNeg | Op::MinNeg | Op::MaxSubImm | Op::MaxRSubImm | Op::MaxAddImm => {
                larger(&[a, b])
            }
            Op::MinSubImm | Op::MinRSubImm | Op::MinAddImm => larger(&[a, b]),
            Op::Max3 | Op::Min3 => larger(&[a, b, c]),
            Op::MaxSub | Op::MinSub => Abs::Bound(a.lipschitz().max(sum(b, c, -1.0).lipschitz())),
            Op::Hypot => of_coordinates(a, b),
            Op::Circle
            | Op::Box
            | Op::OrientedBox
            | Op::Capsule
            | Op::Polygon
            | Op::Ellipse
            | Op::Ring
            | Op::Arc
            | Op::HalfPlane
            | Op::Height => of_coordinates(a, b),
            Op::Sqrt
            | Op::Square
            | Op::ShiftSub
            | Op::Noise
            | Op::Wave
            | Op::RepeatOffset
            | Op::Select => UNKNOWN,
            // Masks, integers and materials are not distances.
            Op::RepeatIndex
            | Op::RepeatActive
            | Op::Lt
            | Op::And
            | Op::MatConst
            | Op::MatSelect => UNKNOWN,
        };
        if let Some(slot) = regs.get_mut(i.dst as usize) {
            *slot = v;
        }
    }
    let l = regs
        .get(out as usize)
        .copied()
        .unwrap_or(UNKNOWN)
        .lipschitz();
    if l.is_nan() { f32::INFINITY } else { l }
}

impl super::Tape {
    /// An upper bound of the Lipschitz constant of the tape's value (see
    /// `lipschitz_bound`); `+inf` where the tape holds an instruction without a rule.
    pub fn lipschitz_bound(&self) -> f32 {
        lipschitz_bound(&self.instrs, self.registers, self.value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn instr(op: Op, dst: u32, a: u32, b: u32, imm: f32) -> Instr {
        Instr {
            op,
            dst,
            a,
            b,
            c: 0,
            imm: imm.to_bits(),
        }
    }

    #[test]
    fn rotated_and_scaled_coordinates_keep_their_norm() {
        let (c, s) = (0.6f32, 0.8f32);
        // a = c x + s y, b = -s x + c y (a rotation), then a circle of (a, b).
        let t = [
            instr(Op::X, 0, 0, 0, 0.0),
            instr(Op::Y, 1, 0, 0, 0.0),
            instr(Op::MulImm, 2, 0, 0, c),
            instr(Op::MulImm, 3, 1, 0, s),
            instr(Op::Add, 4, 2, 3, 0.0),
            instr(Op::MulImm, 5, 0, 0, -s),
            instr(Op::MulImm, 6, 1, 0, c),
            instr(Op::Add, 7, 5, 6, 0.0),
            instr(Op::Circle, 8, 4, 7, 0.0),
            // Scaled down by 2 and back up: still 1.
            instr(Op::MulImm, 9, 8, 0, 2.0),
        ];
        let l = lipschitz_bound(&t, 10, 8);
        assert!((l - 1.0).abs() < 1e-5, "{l}");
        assert!((lipschitz_bound(&t, 10, 9) - 2.0).abs() < 1e-5);
    }

    #[test]
    fn unknown_instructions_give_infinity_and_sums_add() {
        let t = [
            instr(Op::X, 0, 0, 0, 0.0),
            instr(Op::Y, 1, 0, 0, 0.0),
            instr(Op::Noise, 2, 0, 1, 0.0),
            instr(Op::Circle, 3, 0, 1, 0.0),
            instr(Op::Min, 4, 3, 2, 0.0),
            instr(Op::Box, 5, 0, 1, 0.0),
            instr(Op::Add, 6, 3, 5, 0.0),
        ];
        assert_eq!(lipschitz_bound(&t, 7, 4), f32::INFINITY);
        assert!((lipschitz_bound(&t, 7, 6) - 2.0).abs() < 1e-5);
        assert_eq!(spectral_norm(Vec2::X, Vec2::Y), 1.0);
    }
}
