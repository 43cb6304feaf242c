//! The level graph as data: the serde node types a level file is made of.
//!
//! A node is a primitive shape, an operator over child nodes, or a reference to a named node
//! of the level (`Ref("name")`), so levels can share sub-graphs. Coordinates are world units
//! (y up; one unit is one pixel at the default zoom), angles are degrees. Solid is where the
//! distance is negative. [`crate::graph::Graph::compile`] validates and compiles a
//! node tree into an evaluable arena.

use serde::{Deserialize, Serialize};

/// A 2D point or vector in a level file: `(x, y)`.
pub type P2 = [f32; 2];

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Axis {
    /// The x axis.
    X,
    /// The y axis.
    Y,
}

fn origin() -> P2 {
    [0.0, 0.0]
}

/// One node of a level graph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[non_exhaustive]
pub enum Node {
    // ---- primitives -------------------------------------------------------------------
    /// Disc. Exact.
    Circle {
        /// Centre.
        #[serde(default = "origin")]
        center: P2,
        /// Radius (> 0).
        radius: f32,
    },
    /// Axis-aligned box. Exact.
    Box {
        /// Centre.
        #[serde(default = "origin")]
        center: P2,
        /// Half extents (> 0).
        half_size: P2,
    },
    /// Axis-aligned box with rounded corners; `half_size` is the overall extent. Exact.
    RoundedBox {
        /// Centre.
        #[serde(default = "origin")]
        center: P2,
        /// Half extents including the rounding (> 0).
        half_size: P2,
        /// Corner radius (0 ..= min half extent).
        radius: f32,
    },
    /// Box of the given thickness around the segment `a`-`b` (square ends). Exact.
    OrientedBox {
        /// Start of the centre line.
        a: P2,
        /// End of the centre line (distinct from `a`).
        b: P2,
        /// Full thickness across the centre line (> 0).
        thickness: f32,
    },
    /// Capsule: points within `radius` of the segment `a`-`b` (a disc when `a == b`). Exact.
    Capsule {
        /// Segment start.
        a: P2,
        /// Segment end.
        b: P2,
        /// Radius (> 0).
        radius: f32,
    },
    /// Triangle, either winding. Exact.
    Triangle {
        /// First corner.
        a: P2,
        /// Second corner.
        b: P2,
        /// Third corner.
        c: P2,
    },
    /// Simple polygon (no self-intersections), either winding, 3 or more vertices. Exact.
    Polygon {
        /// Vertices in order around the boundary.
        points: Vec<P2>,
    },
    /// Axis-aligned ellipse. Exact up to float rounding: the closest boundary point is found
    /// by a fixed number of iterations (see `primitives::ellipse`).
    Ellipse {
        /// Centre.
        #[serde(default = "origin")]
        center: P2,
        /// Semi-axes along x and y (> 0).
        radii: P2,
    },
    /// Annulus of the given width around a circle. Exact.
    Ring {
        /// Centre.
        #[serde(default = "origin")]
        center: P2,
        /// Radius of the centre line (> 0).
        radius: f32,
        /// Full width (> 0).
        width: f32,
    },
    /// Circular arc with round caps, symmetric about its direction. Exact.
    Arc {
        /// Centre of the circle the arc lies on.
        #[serde(default = "origin")]
        center: P2,
        /// Radius of the centre line (> 0).
        radius: f32,
        /// Full width (> 0).
        width: f32,
        /// Half of the opening angle, degrees (0, 180].
        aperture: f32,
        /// Direction of the arc's middle, degrees counter-clockwise from +y.
        #[serde(default)]
        rotation: f32,
    },
    /// Everything on the side of the line through `point` opposite to `normal`. Exact.
    HalfPlane {
        /// A point on the boundary line.
        #[serde(default = "origin")]
        point: P2,
        /// Outward normal (any non-zero length).
        normal: P2,
    },
    /// Ground below a polyline through `(x0 + i * dx, heights[i])`, extended flat beyond both
    /// ends. Exact.
    HeightProfile {
        /// x of the first sample.
        x0: f32,
        /// Spacing between samples (> 0).
        dx: f32,
        /// Ground heights (at least 2).
        heights: Vec<f32>,
    },

    // ---- boolean operators ------------------------------------------------------------
    /// Union of the children (min). A bound.
    Union(Vec<Node>),
    /// Intersection of the children (max). A bound.
    Intersection(Vec<Node>),
    /// `base` with `cut` removed (max(base, -cut)). A bound.
    Subtract {
        /// What remains.
        base: Box<Node>,
        /// What is removed.
        cut: Box<Node>,
    },
    /// Union blended over width `k` (quadratic polynomial smooth min). A bound.
    SmoothUnion {
        /// Blend width (> 0).
        k: f32,
        /// Children.
        nodes: Vec<Node>,
    },
    /// Intersection blended over width `k`. A bound.
    SmoothIntersection {
        /// Blend width (> 0).
        k: f32,
        /// Children.
        nodes: Vec<Node>,
    },
    /// Subtraction blended over width `k`. A bound.
    SmoothSubtract {
        /// Blend width (> 0).
        k: f32,
        /// What remains.
        base: Box<Node>,
        /// What is removed.
        cut: Box<Node>,
    },

    // ---- shape operators --------------------------------------------------------------
    /// Grow the child by `radius` (rounds corners). A bound.
    Round {
        /// Offset (>= 0).
        radius: f32,
        /// Child.
        node: Box<Node>,
    },
    /// Shell of the given half-width around the child's boundary. A bound.
    Onion {
        /// Half-width of the shell (> 0).
        width: f32,
        /// Child.
        node: Box<Node>,
    },

    // ---- domain operators -------------------------------------------------------------
    /// Move the child by `offset`. Keeps exactness.
    Translate {
        /// Offset.
        offset: P2,
        /// Child.
        node: Box<Node>,
    },
    /// Rotate the child about the origin, counter-clockwise. Keeps exactness.
    Rotate {
        /// Angle in degrees.
        degrees: f32,
        /// Child.
        node: Box<Node>,
    },
    /// Scale the child uniformly about the origin. Keeps exactness.
    Scale {
        /// Factor (> 0).
        factor: f32,
        /// Child.
        node: Box<Node>,
    },
    /// Mirror: the half on the positive side of the line `axis = at` is reflected onto the
    /// other side. A bound.
    Mirror {
        /// The axis whose coordinate is reflected.
        axis: Axis,
        /// Position of the mirror line.
        #[serde(default)]
        at: f32,
        /// Child.
        node: Box<Node>,
    },
    /// Infinite repetition with the given period per axis (0 = not repeated along that axis).
    /// The child's bounding box must fit in one period on each repeated axis. A bound.
    Repeat {
        /// Period per axis (>= 0, at least one > 0).
        period: P2,
        /// Child, centred on the origin cell.
        node: Box<Node>,
    },
    /// Finite repetition: copies at `i * period` for `i` in `0..count` per axis.
    RepeatFinite {
        /// Period per axis (>= 0, at least one > 0).
        period: P2,
        /// Copies per axis (>= 1; must be 1 where the period is 0).
        count: [u32; 2],
        /// Child.
        node: Box<Node>,
    },
    /// Displace the child's distance by deterministic value noise: `d + amplitude * n(p /
    /// wavelength)` with `n` in [-1, 1]. A bound whose Lipschitz constant grows accordingly.
    DisplaceNoise {
        /// Amplitude in world units (>= 0).
        amplitude: f32,
        /// Noise cell size in world units (> 0).
        wavelength: f32,
        /// Noise seed.
        #[serde(default)]
        seed: u32,
        /// Child.
        node: Box<Node>,
    },
    /// Displace the child's distance by a sine wave along a direction: `d + amplitude *
    /// sin(2π (dot(p, dir) / wavelength + phase))`. A bound.
    DisplaceWave {
        /// Amplitude in world units (>= 0).
        amplitude: f32,
        /// Wavelength in world units (> 0).
        wavelength: f32,
        /// Direction of travel, degrees counter-clockwise from +x.
        #[serde(default)]
        direction: f32,
        /// Phase in turns.
        #[serde(default)]
        phase: f32,
        /// Child.
        node: Box<Node>,
    },
    /// Paint the child with a palette material.
    Material {
        /// Index into the level's material palette.
        id: u16,
        /// Child.
        node: Box<Node>,
    },
    /// A reference to a named node of the level.
    Ref(String),

    // ---- arithmetic expressions ---------------------------------------------------------
    // Plain arithmetic on the query point, so that external implicit expressions (for
    // example the SSA text format read by `crate::import`) can be terrains. Their
    // Lipschitz bound is derived by rules (see `graph`) and may be infinite; their bounding
    // box is the whole plane. `min`/`max` are `Union`/`Intersection`.
    /// The query point's x coordinate.
    X,
    /// The query point's y coordinate.
    Y,
    /// A constant.
    Const(f32),
    /// `a + b`.
    Add(Box<Node>, Box<Node>),
    /// `a - b`.
    Sub(Box<Node>, Box<Node>),
    /// `a * b`.
    Mul(Box<Node>, Box<Node>),
    /// `-a`.
    Neg(Box<Node>),
    /// `a * a`.
    Square(Box<Node>),
    /// `sqrt(a)` (NaN below zero, as IEEE-754 defines it).
    Sqrt(Box<Node>),
}

impl Node {
    /// The variant's name, as written in level files (used in error paths).
    pub fn kind(&self) -> &'static str {
        match self {
            Node::Circle { .. } => "Circle",
            Node::Box { .. } => "Box",
            Node::RoundedBox { .. } => "RoundedBox",
            Node::OrientedBox { .. } => "OrientedBox",
            Node::Capsule { .. } => "Capsule",
            Node::Triangle { .. } => "Triangle",
            Node::Polygon { .. } => "Polygon",
            Node::Ellipse { .. } => "Ellipse",
            Node::Ring { .. } => "Ring",
            Node::Arc { .. } => "Arc",
            Node::HalfPlane { .. } => "HalfPlane",
            Node::HeightProfile { .. } => "HeightProfile",
            Node::Union(_) => "Union",
            Node::Intersection(_) => "Intersection",
            Node::Subtract { .. } => "Subtract",
            Node::SmoothUnion { .. } => "SmoothUnion",
            Node::SmoothIntersection { .. } => "SmoothIntersection",
            Node::SmoothSubtract { .. } => "SmoothSubtract",
            Node::Round { .. } => "Round",
            Node::Onion { .. } => "Onion",
            Node::Translate { .. } => "Translate",
            Node::Rotate { .. } => "Rotate",
            Node::Scale { .. } => "Scale",
            Node::Mirror { .. } => "Mirror",
            Node::Repeat { .. } => "Repeat",
            Node::RepeatFinite { .. } => "RepeatFinite",
            Node::DisplaceNoise { .. } => "DisplaceNoise",
            Node::DisplaceWave { .. } => "DisplaceWave",
            Node::Material { .. } => "Material",
            Node::Ref(_) => "Ref",
            Node::X => "X",
            Node::Y => "Y",
            Node::Const(_) => "Const",
            Node::Add(..) => "Add",
            Node::Sub(..) => "Sub",
            Node::Mul(..) => "Mul",
            Node::Neg(_) => "Neg",
            Node::Square(_) => "Square",
            Node::Sqrt(_) => "Sqrt",
        }
    }
}

impl Node {
    /// Direct children with the path suffix that names each (`[2]`, `.base`, `.node`).
    pub fn children(&self) -> Vec<(String, &Node)> {
        match self {
            Node::Union(v) | Node::Intersection(v) => v
                .iter()
                .enumerate()
                .map(|(i, n)| (format!("[{i}]"), n))
                .collect(),
            Node::SmoothUnion { nodes, .. } | Node::SmoothIntersection { nodes, .. } => nodes
                .iter()
                .enumerate()
                .map(|(i, n)| (format!("[{i}]"), n))
                .collect(),
            Node::Subtract { base, cut } | Node::SmoothSubtract { base, cut, .. } => {
                vec![
                    (".base".into(), base.as_ref()),
                    (".cut".into(), cut.as_ref()),
                ]
            }
            Node::Round { node, .. }
            | Node::Onion { node, .. }
            | Node::Translate { node, .. }
            | Node::Rotate { node, .. }
            | Node::Scale { node, .. }
            | Node::Mirror { node, .. }
            | Node::Repeat { node, .. }
            | Node::RepeatFinite { node, .. }
            | Node::DisplaceNoise { node, .. }
            | Node::DisplaceWave { node, .. }
            | Node::Material { node, .. } => vec![(".node".into(), node.as_ref())],
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => {
                vec![("[0]".into(), a.as_ref()), ("[1]".into(), b.as_ref())]
            }
            Node::Neg(a) | Node::Square(a) | Node::Sqrt(a) => vec![("[0]".into(), a.as_ref())],
            _ => Vec::new(),
        }
    }
}
