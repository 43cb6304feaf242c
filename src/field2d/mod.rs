//! The 2D terrain field: level graph, level format, explosion grid and collision queries.

pub mod aabb;
pub mod contour;

pub mod error;
pub mod eval;
pub mod event;
pub(crate) mod exec;
pub mod graph;
pub mod grid;
pub mod import;
pub mod level;
#[cfg(feature = "mesh")]
pub mod mesh;
pub mod node;
pub mod noise;
pub mod primitives;

pub mod query;
pub mod sample;
pub mod sdf;
pub mod simd;
pub mod tape;
pub mod terrain;

pub use crate::det::quant::{FIXED_ONE, QuantError};
pub use aabb::Aabb;
pub use error::LevelError;
pub use event::{Event, EventError, EventKind};
pub use graph::{Exactness, Graph, GraphLimits, NodeId, NodeInfo};
pub use grid::{CellState, GridStats, MaterialSource};
pub use level::{Level, LevelFile, MaterialDef, WorldBounds};
pub use node::{Axis, Node};
pub use sample::{MaterialId, Sample};
pub use sdf::Sdf;
pub use terrain::{Terrain, TerrainError, TerrainOptions};
