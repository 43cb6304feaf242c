//! View culling of a level graph: which sub-graphs cannot affect the clamped field inside the
//! world rectangle an SDF pass covers, so the emitted shader can leave them out.
//!
//! # What is dropped
//!
//! The walk starts at the root with the view rectangle and the clamp band `M` (the caller
//! clamps distances to `[-M, M]`). A child `c` counts as *far* when its solid box
//! ([`NodeInfo::bounds`](craterfield_field::NodeInfo::bounds)) lies farther than
//! `M * max(L_c, 1)` (plus a blend allowance for smooth operators, below, and the child's
//! deficit `δ_c`) from the view, and its values are *box-bounded*: at any point outside its
//! box, `c(p) >= dist(p, box) - δ_c`. Then:
//!
//! * `Union`: far children are dropped (all of them: the node becomes the far constant).
//! * `Subtract`: a far cut is dropped; a far base makes the node the far constant.
//! * `Intersection`, `SmoothIntersection`: one far child makes the node the far constant.
//! * `SmoothUnion`: child `j` of `n` is dropped when far with the extra allowance
//!   `1.25 k (n - max(j, 1))`; `SmoothSubtract` drops a far cut with the allowance `1.25 k`.
//!
//! The far constant is `(1e20, 0, 0)`, material 0.
//!
//! # Why the clamped field does not change in the view
//!
//! Box-boundedness holds with `δ = 0` for every exact primitive (its value is the distance to
//! its solid, which lies in its box) and is inherited (same `δ`) by union, subtraction and
//! smooth subtraction (both are at least the base), round and onion (box grown by the
//! offset), displacements (box grown by the amplitude, and the displacement is at most the
//! amplitude), translation, rotation, material, mirror (non-empty box) and repetition (each
//! instance is guarded by its box, the cap by the box of all instances); uniform scaling by
//! `s` scales `δ` by `s`. A smooth union's box grows by `k / 4`, but each of its `n - 1`
//! blend steps may lower the running value by up to `k / 4` (three equal children already
//! lose `0.39 k`), so it adds `(n - 2) k / 4` to the largest `δ` of its children.
//! Intersections and arithmetic expressions are not box-bounded, so they are never dropped
//! themselves (their own children still can be).
//!
//! At a view point `p` a far child therefore has `c(p) > M` (its gap exceeds the margin
//! plus `δ_c`). Since clamping to `[-M, M]` commutes with `min` and `max`,
//! `clamp(min(a, c)) = clamp(a)`, `clamp(max(a, -c)) = clamp(a)` and
//! `clamp(max(a, c)) = M`: the clamped value (and with it
//! the sign) is unchanged, and a child's values only need to agree with the original after
//! clamping to the same band. The smooth minimum `s(x, c)` equals `x` exactly when
//! `x <= c - k`, and is at least `min(x, c) - k / 4` otherwise; so each blend step can only
//! move values that are above the band minus `1.25 k`, and a child blended `t` more times
//! after its own step needs `1.25 k t` of extra distance (`t = n - max(j, 1)`). Smooth
//! maxima are the mirror image. The same argument gives the band a child must keep:
//! `M + 1.25 k t` below smooth operators, `M + r` below `Round(r)`, `M + w` below
//! `Onion(w)`, `M + a` below displacements of amplitude `a`, and `M / s` below `Scale(s)`.
//! Distances from box to view are shrunk by a relative `1e-3` (the ellipse solver's
//! tolerance and rounding in the transformed boxes) before they are compared.
//!
//! So culling never changes the sign of the field in the view, and never changes the
//! clamped distance there, exact node or not.
//!
//! # Frames
//!
//! The view is carried into each child's frame: shifted below `Translate`, rotated (its
//! bounding box) below `Rotate`, scaled with the band below `Scale`, folded onto the
//! evaluated half below `Mirror`. Below `Repeat`/`RepeatFinite` and arithmetic expressions
//! nothing is culled. A node reached along several paths is planned once, with the box
//! around all its views and the largest band (a larger view or band only culls less), so the
//! emitted code keeps one copy of every shared node.

use craterfield_field::Aabb;
use craterfield_field::Axis;
use craterfield_field::{Graph, NodeId, Op};

use craterfield_wgsl::fnv::Fnv64;

/// Value of the far-outside constant: above any band, yet far from overflow when scaled.
pub(crate) const FAR: f32 = 1.0e20;

/// Bands above this are not culled against (the far constant must stay above the band).
const BAND_LIMIT: f32 = 1.0e18;

/// Relative shrink of box-to-view distances before comparing them with the margin.
const RELATIVE_SLACK: f32 = 1.0e-3;

/// Absolute shrink per unit of view coordinate magnitude (rounding of transformed views).
const COORDINATE_SLACK: f32 = 1.0e-5;

/// Extra distance per remaining smooth blend step, in units of the blend width `k`.
const BLEND_STEP: f32 = 1.25;

/// What a plan does with one node.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Fate {
    /// Not evaluated.
    Unreached,
    /// Evaluated with all its children.
    Whole,
    /// Replaced by the far-outside constant; its children are not evaluated through it.
    Far,
    /// Evaluated without the children at these positions (ascending).
    Without(Vec<u32>),
}

/// The kept/culled decisions for one view, with the key naming the shader they produce.
///
/// Made by [`TerrainEmitter::plan`](super::TerrainEmitter::plan); turned into WGSL by
/// [`TerrainEmitter::emit`](super::TerrainEmitter::emit).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CullPlan {
    /// Hash of the graph's fingerprint and every decision: equal keys give byte-identical
    /// shader text, so it keys a `gpu::PipelineCache`.
    pub key: u64,
    /// Nodes the planned shader evaluates.
    pub kept: usize,
    /// Nodes the unculled shader evaluates that this one does not.
    pub culled: usize,
    pub(crate) fingerprint: u64,
    pub(crate) fates: Vec<Fate>,
}

/// A child edge a plan leaves out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CulledChild {
    /// The node whose child is dropped.
    pub parent: NodeId,
    /// Position of the child among the parent's children.
    pub position: u32,
    /// The dropped child.
    pub child: NodeId,
}

impl CullPlan {
    /// What the plan does with `node` (`None` for an id from another graph).
    pub fn fate(&self, node: NodeId) -> Option<&Fate> {
        self.fates.get(node.0 as usize)
    }

    /// Every child edge the plan drops, parents in ascending id order.
    pub fn culled_children(&self, graph: &Graph) -> Vec<CulledChild> {
        let mut out = Vec::new();
        for (i, fate) in self.fates.iter().enumerate() {
            let Fate::Without(dropped) = fate else {
                continue;
            };
            let Some(op) = graph.ops().get(i) else {
                continue;
            };
            let children = op_children(op);
            for &position in dropped {
                if let Some(&child) = children.get(position as usize) {
                    out.push(CulledChild {
                        parent: NodeId(i as u32),
                        position,
                        child,
                    });
                }
            }
        }
        out
    }

    /// Nodes the plan replaces by the far-outside constant.
    pub fn far_nodes(&self) -> Vec<NodeId> {
        (0..self.fates.len() as u32)
            .filter(|&i| self.fates[i as usize] == Fate::Far)
            .map(NodeId)
            .collect()
    }
}

impl Fate {
    /// True when the child at `position` is left out.
    pub(crate) fn drops(&self, position: usize) -> bool {
        match self {
            Fate::Without(dropped) => dropped.contains(&(position as u32)),
            _ => false,
        }
    }
}

/// The region a node is evaluated over, in its own frame, and the band its values must keep.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Reach {
    /// No culling below here.
    Everywhere,
    /// Values must agree with the original after clamping to `[-band, band]` over `view`.
    Within { view: Aabb, band: f32 },
}

impl Reach {
    fn join(self, other: Reach) -> Reach {
        match (self, other) {
            (Reach::Within { view: a, band: ba }, Reach::Within { view: b, band: bb }) => {
                Reach::Within {
                    view: a.union(&b),
                    band: ba.max(bb),
                }
            }
            _ => Reach::Everywhere,
        }
    }

    /// A reach whose numbers are all usable, or no culling at all.
    fn sane(self) -> Reach {
        match self {
            Reach::Within { view, band }
                if view.min.is_finite()
                    && view.max.is_finite()
                    && !view.is_empty()
                    && (0.0..=BAND_LIMIT).contains(&band) =>
            {
                self
            }
            _ => Reach::Everywhere,
        }
    }
}

/// The children of an operation, in evaluation order.
pub(crate) fn op_children(op: &Op) -> Vec<NodeId> {
    match op {
        Op::Union(ids)
        | Op::Intersection(ids)
        | Op::SmoothUnion(_, ids)
        | Op::SmoothIntersection(_, ids) => ids.clone(),
        Op::Subtract(a, b)
        | Op::SmoothSubtract(_, a, b)
        | Op::Add(a, b)
        | Op::Sub(a, b)
        | Op::Mul(a, b) => vec![*a, *b],
        Op::Round(_, c)
        | Op::Onion(_, c)
        | Op::Translate(_, c)
        | Op::Material(_, c)
        | Op::Neg(c)
        | Op::Square(c)
        | Op::Sqrt(c) => vec![*c],
        Op::Rotate { child, .. }
        | Op::Scale { child, .. }
        | Op::Mirror { child, .. }
        | Op::Noise { child, .. }
        | Op::Wave { child, .. } => vec![*child],
        Op::Repeat(r) => vec![r.child],
        Op::Circle { .. }
        | Op::Box { .. }
        | Op::RoundedBox { .. }
        | Op::OrientedBox { .. }
        | Op::Capsule { .. }
        | Op::Polygon { .. }
        | Op::Ellipse { .. }
        | Op::Ring { .. }
        | Op::Arc { .. }
        | Op::HalfPlane { .. }
        | Op::Height { .. }
        | Op::X
        | Op::Y
        | Op::Const(_) => Vec::new(),
    }
}

/// For every node: its deficit `δ` (its value is at least the distance to its box minus `δ`
/// outside the box), or `None` when it is not box-bounded (see the module doc for the rules).
/// Children come before parents in the arena.
pub(crate) fn box_deficits(graph: &Graph) -> Vec<Option<f32>> {
    let mut deficits: Vec<Option<f32>> = Vec::with_capacity(graph.ops().len());
    for (op, info) in graph.ops().iter().zip(graph.infos()) {
        let of = |id: &NodeId| deficits[id.0 as usize];
        let largest = |ids: &[NodeId]| {
            ids.iter()
                .try_fold(0.0f32, |m, id| of(id).map(|d| m.max(d)))
        };
        let deficit = match op {
            Op::Circle { .. }
            | Op::Box { .. }
            | Op::RoundedBox { .. }
            | Op::OrientedBox { .. }
            | Op::Capsule { .. }
            | Op::Polygon { .. }
            | Op::Ellipse { .. }
            | Op::Ring { .. }
            | Op::Arc { .. }
            | Op::HalfPlane { .. }
            | Op::Height { .. } => Some(0.0),
            Op::Union(ids) => largest(ids),
            Op::SmoothUnion(k, ids) => {
                let extra_steps = ids.len().saturating_sub(2) as f32;
                largest(ids).map(|d| d + extra_steps * k * 0.25)
            }
            Op::Intersection(ids) | Op::SmoothIntersection(_, ids) if ids.len() == 1 => of(&ids[0]),
            Op::Intersection(_) | Op::SmoothIntersection(..) => None,
            Op::Subtract(a, _) | Op::SmoothSubtract(_, a, _) => of(a),
            Op::Round(_, c) | Op::Onion(_, c) | Op::Translate(_, c) | Op::Material(_, c) => of(c),
            Op::Scale { factor, child, .. } => of(child).map(|d| d * factor),
            Op::Rotate { child, .. }
            | Op::Mirror { child, .. }
            | Op::Noise { child, .. }
            | Op::Wave { child, .. } => of(child),
            Op::Repeat(r) => of(&r.child),
            Op::X
            | Op::Y
            | Op::Const(_)
            | Op::Add(..)
            | Op::Sub(..)
            | Op::Mul(..)
            | Op::Neg(_)
            | Op::Square(_)
            | Op::Sqrt(_) => None,
        };
        deficits.push(deficit.filter(|_| !info.bounds.is_empty()));
    }
    deficits
}

/// Number of nodes reachable from the root (what the unculled shader evaluates).
pub(crate) fn reachable_count(graph: &Graph) -> usize {
    let mut seen = vec![false; graph.ops().len()];
    let mut stack = vec![graph.root()];
    let mut count = 0;
    while let Some(id) = stack.pop() {
        let i = id.0 as usize;
        if seen[i] {
            continue;
        }
        seen[i] = true;
        count += 1;
        stack.extend(op_children(&graph.ops()[i]));
    }
    count
}

/// Euclidean distance between two boxes (0 when they overlap; infinite sides allowed).
pub fn box_gap(a: &Aabb, b: &Aabb) -> f32 {
    let gap = |lo_a: f32, hi_a: f32, lo_b: f32, hi_b: f32| (lo_b - hi_a).max(lo_a - hi_b).max(0.0);
    let gx = gap(a.min.x, a.max.x, b.min.x, b.max.x);
    let gy = gap(a.min.y, a.max.y, b.min.y, b.max.y);
    if gx == 0.0 || gy == 0.0 {
        // Also keeps an infinite gap on one axis from becoming NaN through inf * 0.
        gx.max(gy)
    } else {
        (gx * gx + gy * gy).sqrt()
    }
}

/// Everything [`plan`] needs to know about the graph besides the graph.
pub(crate) struct GraphFacts<'a> {
    pub graph: &'a Graph,
    pub deficits: &'a [Option<f32>],
    pub fingerprint: u64,
    pub reachable: usize,
}

/// Plan the shader for `view` (world rectangle, `None` for no culling) and clamp band `band`.
pub(crate) fn plan(facts: &GraphFacts, view: Option<Aabb>, band: f32) -> CullPlan {
    let graph = facts.graph;
    let n = graph.ops().len();
    let mut reach: Vec<Option<Reach>> = vec![None; n];
    let mut fates = vec![Fate::Unreached; n];
    let start = view.map_or(Reach::Everywhere, |view| Reach::Within { view, band });
    reach[graph.root().0 as usize] = Some(start.sane());
    // Parents come after their children in the arena, so walking backwards visits every
    // parent before any of its children: a node's reach is complete when it is visited.
    for i in (0..n).rev() {
        let Some(here) = reach[i] else { continue };
        let op = &graph.ops()[i];
        let fate = decide(facts, op, here);
        let children = op_children(op);
        if fate != Fate::Far {
            for (j, &child) in children.iter().enumerate() {
                if fate.drops(j) {
                    continue;
                }
                let next = child_reach(op, j, children.len(), here).sane();
                let slot = &mut reach[child.0 as usize];
                *slot = Some(slot.map_or(next, |r| r.join(next)));
            }
        }
        fates[i] = fate;
    }
    let kept = fates.iter().filter(|f| **f != Fate::Unreached).count();
    CullPlan {
        key: plan_key(facts.fingerprint, &fates),
        kept,
        culled: facts.reachable.saturating_sub(kept),
        fingerprint: facts.fingerprint,
        fates,
    }
}

fn plan_key(fingerprint: u64, fates: &[Fate]) -> u64 {
    let mut h = Fnv64::new();
    h.u64(fingerprint);
    for fate in fates {
        match fate {
            Fate::Unreached => h.u32(0),
            Fate::Whole => h.u32(1),
            Fate::Far => h.u32(2),
            Fate::Without(dropped) => {
                h.u32(3).u32(dropped.len() as u32);
                for &j in dropped {
                    h.u32(j);
                }
                &mut h
            }
        };
    }
    h.finish()
}

/// The decision for one node evaluated over `here`.
fn decide(facts: &GraphFacts, op: &Op, here: Reach) -> Fate {
    let Reach::Within { view, band } = here else {
        return Fate::Whole;
    };
    let far = |child: NodeId, extra: f32| is_far(facts, child, &view, band, extra);
    match op {
        Op::Union(ids) => drop_far(ids.iter().map(|&c| far(c, 0.0))),
        Op::SmoothUnion(k, ids) => drop_far(
            ids.iter()
                .enumerate()
                .map(|(j, &c)| far(c, blend_allowance(*k, j, ids.len()))),
        ),
        Op::Intersection(ids) | Op::SmoothIntersection(_, ids) => {
            if ids.iter().any(|&c| far(c, 0.0)) {
                Fate::Far
            } else {
                Fate::Whole
            }
        }
        Op::Subtract(a, b) | Op::SmoothSubtract(_, a, b) => {
            let allowance = match op {
                Op::SmoothSubtract(k, ..) => BLEND_STEP * k,
                _ => 0.0,
            };
            if far(*a, 0.0) {
                Fate::Far
            } else if far(*b, allowance) {
                Fate::Without(vec![1])
            } else {
                Fate::Whole
            }
        }
        _ => Fate::Whole,
    }
}

/// Fate of an n-ary union from which the far children are dropped.
fn drop_far(far: impl Iterator<Item = bool>) -> Fate {
    let flags: Vec<bool> = far.collect();
    let dropped: Vec<u32> = (0..flags.len() as u32)
        .filter(|&j| flags[j as usize])
        .collect();
    if dropped.is_empty() {
        Fate::Whole
    } else if dropped.len() == flags.len() {
        Fate::Far
    } else {
        Fate::Without(dropped)
    }
}

/// Extra distance child `j` of an `n`-ary smooth operator of width `k` must keep: the
/// blend steps it goes through after (and including) its own, minus the first.
fn blend_allowance(k: f32, j: usize, n: usize) -> f32 {
    BLEND_STEP * k * n.saturating_sub(j.max(1)) as f32
}

/// True when `child` is box-bounded and its box lies beyond its margin (and deficit) from
/// `view`.
fn is_far(facts: &GraphFacts, child: NodeId, view: &Aabb, band: f32, extra: f32) -> bool {
    let i = child.0 as usize;
    let Some(deficit) = facts.deficits[i] else {
        return false;
    };
    let info = &facts.graph.infos()[i];
    let margin = band * info.lipschitz.max(1.0) + extra;
    let magnitude = view.min.abs().max(view.max.abs()).max_element();
    let gap = box_gap(view, &info.bounds) * (1.0 - RELATIVE_SLACK)
        - COORDINATE_SLACK * magnitude
        - deficit;
    gap > margin
}

/// The reach of child `j` (of `n`) of `op`, evaluated over `here`.
fn child_reach(op: &Op, j: usize, n: usize, here: Reach) -> Reach {
    let Reach::Within { view, band } = here else {
        return Reach::Everywhere;
    };
    let widen = |extra: f32| Reach::Within {
        view,
        band: band + extra,
    };
    let moved = |view: Aabb, band: f32| Reach::Within { view, band };
    match op {
        Op::Union(_) | Op::Intersection(_) | Op::Subtract(..) | Op::Material(..) => here,
        Op::SmoothUnion(k, _) | Op::SmoothIntersection(k, _) => widen(blend_allowance(*k, j, n)),
        Op::SmoothSubtract(k, ..) => widen(BLEND_STEP * k),
        Op::Round(r, _) => widen(*r),
        Op::Onion(w, _) => widen(*w),
        Op::Noise { amplitude, .. } | Op::Wave { amplitude, .. } => widen(*amplitude),
        Op::Translate(t, _) => moved(view.translate(-*t), band),
        Op::Rotate { cos, sin, .. } => moved(view.rotate(*cos, -*sin), band),
        Op::Scale { inv, .. } => moved(view.scale(*inv), band * inv),
        Op::Mirror { axis, at, .. } => moved(mirror_view(view, *axis, *at), band),
        _ => Reach::Everywhere,
    }
}

/// The points `Mirror` evaluates its child at for query points in `view`: the coordinate
/// becomes `|v - at| + at` (the same float operations, which are monotone on each side).
fn mirror_view(view: Aabb, axis: Axis, at: f32) -> Aabb {
    let i = match axis {
        Axis::X => 0,
        Axis::Y => 1,
    };
    let fold = |v: f32| (v - at).abs() + at;
    let (lo, hi) = (view.min[i], view.max[i]);
    let (new_lo, new_hi) = if lo >= at {
        (fold(lo), fold(hi))
    } else if hi <= at {
        (fold(hi), fold(lo))
    } else {
        (at, fold(lo).max(fold(hi)))
    };
    let mut out = view;
    out.min[i] = new_lo;
    out.max[i] = new_hi;
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn box_gap_measures_euclidean_distance() {
        let a = Aabb::new(Vec2::ZERO, Vec2::splat(10.0));
        let b = Aabb::new(Vec2::new(13.0, 14.0), Vec2::splat(20.0));
        assert_eq!(box_gap(&a, &b), 5.0);
        assert_eq!(box_gap(&b, &a), 5.0);
        let overlapping = Aabb::new(Vec2::splat(5.0), Vec2::splat(6.0));
        assert_eq!(box_gap(&a, &overlapping), 0.0);
        let strip = Aabb::new(
            Vec2::new(30.0, f32::NEG_INFINITY),
            Vec2::new(31.0, f32::INFINITY),
        );
        assert_eq!(box_gap(&a, &strip), 20.0);
    }

    #[test]
    fn mirror_view_folds_onto_the_evaluated_side() {
        let v = Aabb::new(Vec2::new(-4.0, 0.0), Vec2::new(2.0, 1.0));
        let m = mirror_view(v, Axis::X, 0.0);
        assert_eq!((m.min.x, m.max.x), (0.0, 4.0));
        let left = Aabb::new(Vec2::new(-9.0, 0.0), Vec2::new(-3.0, 1.0));
        let m = mirror_view(left, Axis::X, 0.0);
        assert_eq!((m.min.x, m.max.x), (3.0, 9.0));
        let right = Aabb::new(Vec2::new(0.0, 3.0), Vec2::new(1.0, 5.0));
        assert_eq!(mirror_view(right, Axis::Y, 1.0), right);
    }

    #[test]
    fn a_smooth_union_of_three_dips_below_its_box_by_at_most_its_deficit() {
        use craterfield_field::Node;
        let circle = Node::Circle {
            center: [0.0, 0.0],
            radius: 10.0,
        };
        let k = 40.0;
        let pair = Node::SmoothUnion {
            k,
            nodes: vec![circle.clone(), circle.clone()],
        };
        let triple = Node::SmoothUnion {
            k,
            nodes: vec![circle.clone(), circle.clone(), circle],
        };
        let named = Default::default();
        let pair = Graph::compile(&pair, &named).expect("valid pair");
        assert_eq!(box_deficits(&pair)[pair.root().0 as usize], Some(0.0));
        let graph = Graph::compile(&triple, &named).expect("valid triple");
        let deficit = box_deficits(&graph)[graph.root().0 as usize];
        assert_eq!(deficit, Some(k * 0.25));
        let bounds = graph.root_info().bounds;
        let p = Vec2::new(bounds.max.x + 30.0, 0.0);
        let gap = box_gap(&Aabb::new(p, p), &bounds);
        let value = graph.node_distance(graph.root(), p);
        // Blending three equal values lowers them by more than the box grew.
        assert!(value < gap, "value {value}, gap {gap}");
        assert!(value >= gap - k * 0.25, "value {value}, gap {gap}");
    }

    #[test]
    fn blend_allowance_counts_the_remaining_steps() {
        assert_eq!(blend_allowance(8.0, 0, 1), 0.0);
        assert_eq!(blend_allowance(8.0, 0, 3), 20.0);
        assert_eq!(blend_allowance(8.0, 1, 3), 20.0);
        assert_eq!(blend_allowance(8.0, 2, 3), 10.0);
    }
}
