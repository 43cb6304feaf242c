//! The level compiler: a node tree (with named references) to a [`Graph`], validating every
//! value and computing each node's facts (exactness, Lipschitz bound, bounds, cost). Every
//! error names the node path of the first problem.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use glam::Vec2;

use super::{Graph, GraphLimits, NodeId, NodeInfo, Op};
use crate::error::LevelError;
use crate::node::{Node, P2};
use crate::tape::{EvalCost, Outputs};

mod booleans;
mod expressions;
mod shapes;
mod transforms;

impl Graph {
    /// Compile `root`, resolving `Ref`s against `named`, with the default limits.
    pub fn compile(root: &Node, named: &BTreeMap<String, Node>) -> Result<Graph, LevelError> {
        Graph::compile_with_limits(root, named, GraphLimits::default())
    }

    /// Compile with explicit limits.
    pub fn compile_with_limits(
        root: &Node,
        named: &BTreeMap<String, Node>,
        limits: GraphLimits,
    ) -> Result<Graph, LevelError> {
        let mut c = Compiler {
            ops: Vec::new(),
            info: Vec::new(),
            named,
            memo: BTreeMap::new(),
            stack: Vec::new(),
            limits,
        };
        let root = c.node(root, "root", 0)?;
        c.check_lipschitz("root", c.info[root.0 as usize].lipschitz)?;
        let cost = c.info[root.0 as usize].cost;
        if cost > limits.max_cost {
            return Err(LevelError::Limit {
                path: "root".into(),
                what: "evaluation cost",
                limit: limits.max_cost,
            });
        }
        let mut graph = Graph {
            ops: c.ops,
            info: c.info,
            root,
            program: OnceLock::new(),
            cost: EvalCost::default(),
        };
        graph.cost = graph.program().fuse().tape(Outputs::ValueMaterial).cost();
        if graph.cost.work > limits.max_eval_work {
            return Err(LevelError::TooCostly {
                work: graph.cost.work,
                instructions: graph.cost.instructions,
                limit: limits.max_eval_work,
            });
        }
        Ok(graph)
    }
}

struct Compiler<'a> {
    ops: Vec<Op>,
    info: Vec<NodeInfo>,
    named: &'a BTreeMap<String, Node>,
    memo: BTreeMap<String, NodeId>,
    stack: Vec<String>,
    limits: GraphLimits,
}

fn invalid(path: &str, field: &str, reason: String) -> LevelError {
    LevelError::Invalid {
        path: format!("{path}.{field}"),
        reason,
    }
}

impl Compiler<'_> {
    fn push(&mut self, op: Op, info: NodeInfo, path: &str) -> Result<NodeId, LevelError> {
        if self.ops.len() >= self.limits.max_nodes {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "node count",
                limit: self.limits.max_nodes as u64,
            });
        }
        if info.cost > self.limits.max_cost {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "evaluation cost",
                limit: self.limits.max_cost,
            });
        }
        self.ops.push(op);
        self.info.push(info);
        Ok(NodeId(self.ops.len() as u32 - 1))
    }

    fn info_of(&self, id: NodeId) -> NodeInfo {
        self.info[id.0 as usize]
    }

    fn num(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        if !v.is_finite() {
            return Err(invalid(
                path,
                field,
                format!("must be a finite number, got {v}"),
            ));
        }
        if v.abs() > self.limits.max_coordinate {
            return Err(invalid(
                path,
                field,
                format!(
                    "{v} is absurdly large (limit ±{})",
                    self.limits.max_coordinate
                ),
            ));
        }
        Ok(v)
    }

    fn positive(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        let v = self.num(path, field, v)?;
        if v <= 0.0 {
            return Err(invalid(path, field, format!("must be positive, got {v}")));
        }
        Ok(v)
    }

    fn non_negative(&self, path: &str, field: &str, v: f32) -> Result<f32, LevelError> {
        let v = self.num(path, field, v)?;
        if v < 0.0 {
            return Err(invalid(
                path,
                field,
                format!("must not be negative, got {v}"),
            ));
        }
        Ok(v)
    }

    fn point(&self, path: &str, field: &str, v: P2) -> Result<Vec2, LevelError> {
        Ok(Vec2::new(
            self.num(path, &format!("{field}.x"), v[0])?,
            self.num(path, &format!("{field}.y"), v[1])?,
        ))
    }

    fn node(&mut self, node: &Node, path: &str, depth: usize) -> Result<NodeId, LevelError> {
        if depth > self.limits.max_depth {
            return Err(LevelError::Limit {
                path: path.into(),
                what: "nesting depth",
                limit: self.limits.max_depth as u64,
            });
        }
        if let Node::Ref(name) = node {
            return self.reference(name, path, depth);
        }
        let path = format!("{path}.{}", node.kind());
        let lowered = match self.shape(node, &path)? {
            Some(lowered) => Some(lowered),
            None => match self.boolean(node, &path, depth)? {
                Some(lowered) => Some(lowered),
                None => match self.transform(node, &path, depth)? {
                    Some(lowered) => Some(lowered),
                    None => self.expression(node, &path, depth)?,
                },
            },
        };
        // Every kind but `Ref` (resolved above) has a lowering.
        let Some((op, info)) = lowered else {
            return Err(LevelError::Invalid {
                path,
                reason: format!("`{}` nodes cannot be compiled", node.kind()),
            });
        };
        // A displacement's bound comes from its parameters alone: checked where they are
        // written. Other nodes are checked once, at the root: an expression's inner terms
        // may have any slope that a later factor scales down.
        if matches!(node, Node::DisplaceNoise { .. } | Node::DisplaceWave { .. }) {
            self.check_lipschitz(&path, info.lipschitz)?;
        }
        self.push(op, info, &path)
    }

    /// The bound every query steps by: NaN or past the limit makes queries meaningless,
    /// whichever parameter (a tiny wavelength, a huge factor) caused it. An infinite bound
    /// is an expression's "unknown": the terrain bounds its cells by interval arithmetic.
    fn check_lipschitz(&self, path: &str, lipschitz: f32) -> Result<(), LevelError> {
        if lipschitz.is_nan() || (lipschitz.is_finite() && lipschitz > self.limits.max_lipschitz) {
            return Err(LevelError::Invalid {
                path: path.into(),
                reason: format!(
                    "its Lipschitz bound {lipschitz:e} is past the limit of {:e}: queries could not step through it (a wavelength too small for its amplitude, or a factor too large)",
                    self.limits.max_lipschitz
                ),
            });
        }
        Ok(())
    }

    fn reference(&mut self, name: &str, path: &str, depth: usize) -> Result<NodeId, LevelError> {
        if let Some(&id) = self.memo.get(name) {
            return Ok(id);
        }
        if let Some(pos) = self.stack.iter().position(|n| n == name) {
            let mut cycle: Vec<&str> = self.stack[pos..].iter().map(String::as_str).collect();
            cycle.push(name);
            return Err(LevelError::Cycle {
                path: path.into(),
                cycle: cycle.join(" -> "),
            });
        }
        let Some(target) = self.named.get(name) else {
            let known: Vec<&str> = self.named.keys().map(String::as_str).collect();
            return Err(LevelError::UnknownRef {
                path: path.into(),
                name: name.into(),
                known: known.join(", "),
            });
        };
        self.stack.push(name.to_string());
        let id = self.node(target, &format!("nodes[\"{name}\"]"), depth + 1);
        self.stack.pop();
        let id = id?;
        self.memo.insert(name.to_string(), id);
        Ok(id)
    }

    fn child(
        &mut self,
        child: &Node,
        path: &str,
        depth: usize,
    ) -> Result<(NodeId, NodeInfo), LevelError> {
        let id = self.node(child, &format!("{path}.node"), depth + 1)?;
        Ok((id, self.info_of(id)))
    }

    fn children(
        &mut self,
        nodes: &[Node],
        path: &str,
        depth: usize,
    ) -> Result<Vec<NodeId>, LevelError> {
        if nodes.is_empty() {
            return Err(LevelError::Invalid {
                path: path.into(),
                reason: "needs at least one child".into(),
            });
        }
        nodes
            .iter()
            .enumerate()
            .map(|(i, n)| self.node(n, &format!("{path}[{i}]"), depth + 1))
            .collect()
    }
}
