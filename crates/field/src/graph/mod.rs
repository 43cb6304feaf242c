//! The compiled level graph: nodes validated, references resolved and constants precomputed
//! into a flat arena, with per-node facts (exact or bound, Lipschitz bound, bounding box).
//!
//! [`Graph::compile`] is the only way in: it checks every value (finite, positive where
//! needed, within absurd-size limits), polygon sanity, reference cycles and the size limits,
//! and reports the node path of the first problem; the compiler is `compile`. Evaluation is
//! in [`super::eval`].

mod compile;

use std::sync::{Arc, OnceLock};

use glam::Vec2;
use serde::{Deserialize, Serialize};

use super::aabb::Aabb;
use super::node::Axis;
use super::sample::MaterialId;
use super::tape::{EvalCost, Program};

/// Index of a node in a compiled [`Graph`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct NodeId(pub u32);

/// Whether a node's value is the true Euclidean distance or only a bound on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Exactness {
    /// The value is the signed Euclidean distance to the boundary.
    Exact,
    /// The sign is right and `|value| / lipschitz` is at most the true distance (so a sphere
    /// tracing step of `|value| / lipschitz` never crosses the boundary). For nodes with a
    /// Lipschitz bound of 1 that is `|value| <= distance`.
    Bound,
}

/// Facts every node reports.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodeInfo {
    /// Exact distance or a bound.
    pub exactness: Exactness,
    /// Upper bound on `|d(a) - d(b)| / |a - b|`.
    pub lipschitz: f32,
    /// Box holding the solid region (`d < 0`), infinite where the node is unbounded. Exact
    /// for primitives; for operators it is derived from the children's boxes (for smooth
    /// blends and displacements, grown by the largest amount they lower the value).
    pub bounds: Aabb,
    /// Evaluation cost estimate (primitive evaluations).
    pub cost: u64,
}

/// The default [`GraphLimits::max_eval_work`]: twice what the largest expression we test
/// against costs (prospero: 7,866 operations, 3,994 work units), and about thirty times the
/// shipped levels (at most 270).
pub const MAX_EVAL_WORK: u64 = 8_192;

/// Size limits enforced by [`Graph::compile`], so no input makes evaluation unbounded.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GraphLimits {
    /// Compiled nodes.
    pub max_nodes: usize,
    /// Nesting depth (references included).
    pub max_depth: usize,
    /// Estimated primitive evaluations per query.
    pub max_cost: u64,
    /// Vertices of one polygon or samples of one height profile.
    pub max_points: usize,
    /// Largest accepted coordinate or size magnitude.
    pub max_coordinate: f32,
    /// Largest accepted Lipschitz bound of any node. Queries step by `distance /
    /// lipschitz`: past this a raycast or a sphere trace crawls (a noise wavelength of
    /// 1e-30 gave a bound of 2.55e31, and every raycast hit at its origin).
    pub max_lipschitz: f32,
    /// Work units one evaluation of the compiled tape may cost ([`EvalCost::work`]): every
    /// query, every cell's specialization and every GPU pixel pays it, so a level past it
    /// would stall whatever loads it (an `Add` of 24,000 `Mul(X, Const)` terms, 134 KB of
    /// text, made one distance query cost 844 us).
    pub max_eval_work: u64,
}

impl Default for GraphLimits {
    fn default() -> Self {
        GraphLimits {
            max_nodes: 20_000,
            max_depth: 64,
            max_cost: 200_000,
            max_points: 65_536,
            max_coordinate: 1.0e6,
            max_lipschitz: 1.0e4,
            max_eval_work: MAX_EVAL_WORK,
        }
    }
}

/// A compiled operation with its precomputed constants: one entry of a [`Graph`]'s arena
/// ([`Graph::ops`]), indexed by [`NodeId`]. What the field evaluates and what the shader
/// emitter and fingerprints read; the constants are those the CPU evaluator uses, so an
/// emitter that prints them computes the same function. Exhaustive on purpose: a new
/// operation must fail to compile in every crate that matches on them until it is handled.
#[derive(Clone, Debug)]
#[allow(missing_docs)] // The fields are named in each variant's doc.
pub enum Op {
    /// A circle: centre `c`, radius `r`.
    Circle { c: Vec2, r: f32 },
    /// An axis-aligned box: centre `c`, half extents `h`.
    Box { c: Vec2, h: Vec2 },
    /// A box with rounded corners: centre `c`, half extents less the radius (`inner`), corner radius `r`.
    RoundedBox { c: Vec2, inner: Vec2, r: f32 },
    /// A box along a segment: midpoint `mid`, unit direction `dir`, half length and half width (`half`).
    OrientedBox { mid: Vec2, dir: Vec2, half: Vec2 },
    /// A capsule: start `a`, segment `ba` (end minus start), `1 / |ba|^2`, radius `r`.
    Capsule {
        a: Vec2,
        ba: Vec2,
        inv_ba2: f32,
        r: f32,
    },
    /// A closed polygon: vertices `pts`, and `1 / |edge|^2` per edge.
    Polygon { pts: Vec<Vec2>, inv_e2: Vec<f32> },
    /// An ellipse: centre `c`, radii.
    Ellipse { c: Vec2, radii: Vec2 },
    /// A ring: centre `c`, radius `r`, half its width.
    Ring { c: Vec2, r: f32, half_width: f32 },
    /// An arc: centre `c`, rotation (cos, sin) `rot`, aperture (sin, cos) `sc`, radius `ra`, thickness `rb`.
    Arc {
        c: Vec2,
        rot: Vec2,
        sc: Vec2,
        ra: f32,
        rb: f32,
    },
    /// The half plane below a line: unit normal `n` and offset (inside where `n . p < offset`).
    HalfPlane { n: Vec2, offset: f32 },
    /// A height profile: samples `pts` every `dx` along x, and `1 / |segment|^2` per segment.
    Height {
        pts: Vec<Vec2>,
        dx: f32,
        inv_e2: Vec<f32>,
    },
    /// The union of the children.
    Union(Vec<NodeId>),
    /// The intersection of the children.
    Intersection(Vec<NodeId>),
    /// The first child minus the second.
    Subtract(NodeId, NodeId),
    /// The smooth union (blend radius first) of the children.
    SmoothUnion(f32, Vec<NodeId>),
    /// The smooth intersection (blend radius first) of the children.
    SmoothIntersection(f32, Vec<NodeId>),
    /// The smooth difference (blend radius first) of two children.
    SmoothSubtract(f32, NodeId, NodeId),
    /// The child grown by a radius.
    Round(f32, NodeId),
    /// A shell of the given half thickness around the child's boundary.
    Onion(f32, NodeId),
    /// The child moved by an offset.
    Translate(Vec2, NodeId),
    /// The child rotated (`cos`, `sin` of the angle).
    Rotate { cos: f32, sin: f32, child: NodeId },
    /// The child scaled by `factor` (`inv` is its inverse).
    Scale {
        factor: f32,
        inv: f32,
        child: NodeId,
    },
    /// The child mirrored across the line `axis = at`.
    Mirror { axis: Axis, at: f32, child: NodeId },
    /// The child repeated on a lattice (constants in [`Repeat`]).
    Repeat(Box<Repeat>),
    /// The child displaced by value noise.
    Noise {
        amplitude: f32,
        inv_wavelength: f32,
        seed: u32,
        child: NodeId,
    },
    /// The child displaced by a sine wave of wave vector `k`.
    Wave {
        amplitude: f32,
        k: Vec2,
        phase: f32,
        child: NodeId,
    },
    /// The child, painted with a material.
    Material(MaterialId, NodeId),
    /// The x coordinate.
    X,
    /// The y coordinate.
    Y,
    /// A constant.
    Const(f32),
    /// The sum of two nodes.
    Add(NodeId, NodeId),
    /// The difference of two nodes.
    Sub(NodeId, NodeId),
    /// The product of two nodes.
    Mul(NodeId, NodeId),
    /// The negation of a node.
    Neg(NodeId),
    /// The square of a node.
    Square(NodeId),
    /// The square root of a node.
    Sqrt(NodeId),
}

/// Constants of a (finite or infinite) repetition.
#[derive(Clone, Debug)]
pub struct Repeat {
    /// Period per axis; 0 where the axis is not repeated.
    pub period: Vec2,
    /// Lowest instance index per axis.
    pub lo: [i32; 2],
    /// Highest instance index per axis.
    pub hi: [i32; 2],
    /// The child's bounding box (centre, half extents) on the repeated axes: each instance is
    /// intersected with its box so that instances left out of the 3x3 neighbourhood are
    /// provably farther than `cap`. The box's centre:
    pub guard_c: Vec2,
    /// and its half extents.
    pub guard_h: Vec2,
    /// Half the smallest repeated period: instances outside the 3x3 neighbourhood are at
    /// least this far away (see `eval`).
    pub cap: f32,
    /// Box around all instances (infinite along infinitely repeated or unbounded axes):
    /// every instance is at least as far as this box. Its lower corner:
    pub all_min: Vec2,
    /// and its upper corner.
    pub all_max: Vec2,
    /// The repeated node.
    pub child: NodeId,
}

/// A validated, compiled level graph.
#[derive(Clone, Debug)]
pub struct Graph {
    pub(crate) ops: Vec<Op>,
    pub(crate) info: Vec<NodeInfo>,
    pub(crate) root: NodeId,
    /// The lowered tape program, built on first use ([`Graph::program`], where the
    /// lowering is).
    pub(crate) program: OnceLock<Arc<Program>>,
    /// What one evaluation of the whole program costs (counted at compile time).
    pub(crate) cost: EvalCost,
}

impl Graph {
    /// The root node.
    pub fn root(&self) -> NodeId {
        self.root
    }

    /// Facts about the root node.
    pub fn root_info(&self) -> &NodeInfo {
        &self.info[self.root.0 as usize]
    }

    /// The compiled operations, indexed by [`NodeId`]: children come before their parents.
    pub fn ops(&self) -> &[Op] {
        &self.ops
    }

    /// Facts about every node, indexed like [`Graph::ops`].
    pub fn infos(&self) -> &[NodeInfo] {
        &self.info
    }

    /// Facts about a node, or `None` for an id from another graph.
    pub fn info(&self, id: NodeId) -> Option<&NodeInfo> {
        self.info.get(id.0 as usize)
    }

    /// What one evaluation of the whole (fused) tape costs. A cell's specialized tape costs
    /// at most this; points far outside the level run the whole tape.
    pub fn eval_cost(&self) -> EvalCost {
        self.cost
    }

    /// Number of compiled nodes (shared sub-graphs count once).
    pub fn node_count(&self) -> usize {
        self.ops.len()
    }

    /// All node ids, children before parents.
    pub fn node_ids(&self) -> impl Iterator<Item = NodeId> + '_ {
        (0..self.ops.len() as u32).map(NodeId)
    }
}
