//! Lowering the boolean operators (unions, intersections, subtractions, sharp and smooth):
//! their children, and bounds and Lipschitz facts combined from the children's.

use super::Compiler;
use crate::aabb::Aabb;
use crate::error::LevelError;
use crate::graph::{Exactness, NodeInfo, Op};
use crate::node::Node;
use craterfield_core::det::math;

impl Compiler<'_> {
    /// The boolean operator `node` lowered, or `None` when it is not one.
    pub(super) fn boolean(
        &mut self,
        node: &Node,
        path: &str,
        depth: usize,
    ) -> Result<Option<(Op, NodeInfo)>, LevelError> {
        Ok(Some(match node {
            Node::Union(nodes) | Node::Intersection(nodes) => {
                let union = matches!(node, Node::Union(_));
                let ids = self.children(nodes, path, depth)?;
                let infos: Vec<NodeInfo> = ids.iter().map(|&i| self.info_of(i)).collect();
                let bounds = if union {
                    infos.iter().fold(Aabb::EMPTY, |b, i| b.union(&i.bounds))
                } else {
                    infos
                        .iter()
                        .fold(Aabb::EVERYTHING, |b, i| b.intersection(&i.bounds))
                };
                let info = combine(&infos, bounds, 0.0);
                (
                    if union {
                        Op::Union(ids)
                    } else {
                        Op::Intersection(ids)
                    },
                    info,
                )
            }
            Node::SmoothUnion { k, nodes } | Node::SmoothIntersection { k, nodes } => {
                let union = matches!(node, Node::SmoothUnion { .. });
                let k = self.positive(path, "k", *k)?;
                let ids = self.children(nodes, path, depth)?;
                let infos: Vec<NodeInfo> = ids.iter().map(|&i| self.info_of(i)).collect();
                let bounds = if union {
                    infos
                        .iter()
                        .fold(Aabb::EMPTY, |b, i| b.union(&i.bounds))
                        .expand(k * 0.25)
                } else {
                    infos
                        .iter()
                        .fold(Aabb::EVERYTHING, |b, i| b.intersection(&i.bounds))
                };
                let mut info = combine(&infos, bounds, 0.0);
                info.exactness = Exactness::Bound;
                (
                    if union {
                        Op::SmoothUnion(k, ids)
                    } else {
                        Op::SmoothIntersection(k, ids)
                    },
                    info,
                )
            }
            Node::Subtract { base, cut } | Node::SmoothSubtract { base, cut, .. } => {
                let k = match node {
                    Node::SmoothSubtract { k, .. } => Some(self.positive(path, "k", *k)?),
                    _ => None,
                };
                let a = self.node(base, &format!("{path}.base"), depth + 1)?;
                let b = self.node(cut, &format!("{path}.cut"), depth + 1)?;
                let (ia, ib) = (self.info_of(a), self.info_of(b));
                let mut info = combine(&[ia, ib], ia.bounds, 0.0);
                info.exactness = Exactness::Bound;
                (
                    match k {
                        Some(k) => Op::SmoothSubtract(k, a, b),
                        None => Op::Subtract(a, b),
                    },
                    info,
                )
            }
            _ => return Ok(None),
        }))
    }
}

/// Info of an n-ary min/max combination.
fn combine(infos: &[NodeInfo], bounds: Aabb, extra_lipschitz: f32) -> NodeInfo {
    let exactness = if infos.len() == 1 {
        infos[0].exactness
    } else {
        Exactness::Bound
    };
    let lipschitz = infos.iter().fold(0.0f32, |m, i| math::max(m, i.lipschitz)) + extra_lipschitz;
    let cost = infos.iter().map(|i| i.cost).sum::<u64>() + infos.len() as u64;
    NodeInfo {
        exactness,
        lipschitz,
        bounds,
        cost,
    }
}
