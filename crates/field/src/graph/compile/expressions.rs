//! Lowering arithmetic expressions (`X`, `Y`, constants, `+ - *`, negation, square and
//! square root): a field written as a formula, with the Lipschitz bound its form allows.

use super::Compiler;
use crate::aabb::Aabb;
use crate::error::LevelError;
use crate::graph::{Exactness, NodeId, NodeInfo, Op};
use crate::node::Node;

impl Compiler<'_> {
    /// The expression `node` lowered, or `None` when it is not an expression.
    pub(super) fn expression(
        &mut self,
        node: &Node,
        path: &str,
        depth: usize,
    ) -> Result<Option<(Op, NodeInfo)>, LevelError> {
        Ok(Some(match node {
            Node::X => (Op::X, expression_info(1.0, 1)),
            Node::Y => (Op::Y, expression_info(1.0, 1)),
            Node::Const(c) => {
                // Constants of expressions are not coordinates: only finiteness is required.
                if !c.is_finite() {
                    return Err(LevelError::Invalid {
                        path: path.into(),
                        reason: format!("must be a finite number, got {c}"),
                    });
                }
                (Op::Const(*c), expression_info(0.0, 1))
            }
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                let ia = self.node(a, &format!("{path}[0]"), depth + 1)?;
                let ib = self.node(b, &format!("{path}[1]"), depth + 1)?;
                let (fa, fb) = (self.info_of(ia), self.info_of(ib));
                let lipschitz = match node {
                    Node::Mul(..) => mul_lipschitz(&self.ops, ia, fa, ib, fb),
                    _ => fa.lipschitz + fb.lipschitz,
                };
                let op = match node {
                    Node::Add(..) => Op::Add(ia, ib),
                    Node::Sub(..) => Op::Sub(ia, ib),
                    _ => Op::Mul(ia, ib),
                };
                (op, expression_info(lipschitz, fa.cost + fb.cost + 1))
            }
            Node::Neg(a) | Node::Square(a) | Node::Sqrt(a) => {
                let ia = self.node(a, &format!("{path}[0]"), depth + 1)?;
                let fa = self.info_of(ia);
                let (op, lipschitz) = match node {
                    Node::Neg(_) => (Op::Neg(ia), fa.lipschitz),
                    Node::Square(_) => (Op::Square(ia), square_lipschitz(fa)),
                    _ => (Op::Sqrt(ia), sqrt_lipschitz(&self.ops, &self.info, ia)),
                };
                (op, expression_info(lipschitz, fa.cost + 1))
            }
            _ => return Ok(None),
        }))
    }
}

/// Facts of an arithmetic expression node: a bound whose box is the whole plane.
fn expression_info(lipschitz: f32, cost: u64) -> NodeInfo {
    NodeInfo {
        exactness: Exactness::Bound,
        lipschitz,
        bounds: Aabb::EVERYTHING,
        cost,
    }
}

/// `|grad (a b)| <= |c| L` when one factor is the constant `c`; unbounded otherwise.
fn mul_lipschitz(ops: &[Op], ia: NodeId, fa: NodeInfo, ib: NodeId, fb: NodeInfo) -> f32 {
    let constant = |id: NodeId| match ops.get(id.0 as usize) {
        Some(Op::Const(c)) => Some(c.abs()),
        _ => None,
    };
    match (constant(ia), constant(ib)) {
        (Some(c), _) => c * fb.lipschitz,
        (_, Some(c)) => c * fa.lipschitz,
        _ if fa.lipschitz == 0.0 && fb.lipschitz == 0.0 => 0.0,
        _ => f32::INFINITY,
    }
}

/// A square has no global Lipschitz bound unless its argument is constant.
fn square_lipschitz(fa: NodeInfo) -> f32 {
    if fa.lipschitz == 0.0 {
        0.0
    } else {
        f32::INFINITY
    }
}

/// `sqrt(a² + b²)` is the norm of `(a, b)`: by Cauchy-Schwarz its gradient is at most
/// `sqrt(La² + Lb²)`. Any other square root has no global bound (its slope is unbounded
/// near zero) unless its argument is constant.
fn sqrt_lipschitz(ops: &[Op], info: &[NodeInfo], ia: NodeId) -> f32 {
    let at = |id: NodeId| ops.get(id.0 as usize);
    let lip = |id: NodeId| {
        info.get(id.0 as usize)
            .map_or(f32::INFINITY, |i| i.lipschitz)
    };
    if lip(ia) == 0.0 {
        return 0.0;
    }
    // (No let-chains: the deterministic core also builds with older cross toolchains.)
    match at(ia) {
        Some(Op::Add(s, t)) => match (at(*s), at(*t)) {
            (Some(Op::Square(a)), Some(Op::Square(b))) => {
                let (la, lb) = (lip(*a), lip(*b));
                (la * la + lb * lb).sqrt() * 1.000_001
            }
            _ => f32::INFINITY,
        },
        _ => f32::INFINITY,
    }
}
