//! The 2D terrain field: level graph, level format, explosion grid and collision queries.

#![forbid(unsafe_code)]

pub(crate) mod aabb;
pub mod contour;

pub(crate) mod error;
pub mod eval;
pub(crate) mod event;
pub(crate) mod exec;
pub mod graph;
pub mod import;
pub(crate) mod level;
#[cfg(feature = "mesh")]
pub mod mesh;
pub(crate) mod node;
pub mod noise;
pub mod primitives;

pub mod query;
pub(crate) mod sample;
pub(crate) mod sdf;
pub use craterfield_core::simd;
pub mod tape;
pub mod terrain;
#[cfg(test)]
pub(crate) mod test_rng;

pub use aabb::Aabb;
pub use craterfield_core::det::quant::{FIXED_ONE, QuantError};
pub use error::LevelError;
pub use event::{Event, EventError, EventKind};
pub use graph::{Exactness, Graph, GraphLimits, MAX_EVAL_WORK, NodeId, NodeInfo, Op, Repeat};
pub use level::{DEFAULT_LEVEL_RON, Level, LevelFile, MAX_LEVEL_BYTES, MaterialDef, WorldBounds};
pub use node::{Axis, Node, P2};
pub use sample::{MaterialId, Sample};
pub use sdf::{ClearRun, Sdf};
pub use terrain::{
    CellState, CellView, Grid, GridStats, MaterialSource, Terrain, TerrainError, TerrainOptions,
    TerrainState,
};
