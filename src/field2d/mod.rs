//! The 2D terrain field: level graph, level format, explosion grid and collision queries.

pub mod aabb;
pub mod contour;
pub mod detmath;
pub mod error;
pub mod eval;
pub mod graph;
pub mod level;
#[cfg(feature = "mesh")]
pub mod mesh;
pub mod node;
pub mod noise;
pub mod primitives;
pub mod query;
pub mod sdf;

pub use aabb::Aabb;
pub use error::LevelError;
pub use graph::{Exactness, Graph, GraphLimits, NodeId, NodeInfo};
pub use level::{Level, LevelFile, MaterialDef, WorldBounds};
pub use node::{Axis, Node};
pub use sdf::{MaterialId, Sample, Sdf};
