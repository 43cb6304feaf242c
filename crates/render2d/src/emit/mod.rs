//! The 2D terrain emitter: level graphs to WGSL text, and view culling.
//!
//! Emission is plain text generation (no GPU types), so this module builds without the `gpu`
//! and `raster` features; the renderer concatenates the emitted text with its hand-written
//! WGSL. The literals, names, hash and budget it shares with the 3D plan's code generator are
//! in `craterfield-wgsl`.
//!
//! * [`terrain2d`]: [`TerrainEmitter`], a 2D level graph to `base_sample`.
//! * [`cull`]: which sub-graphs a view cannot see, and why that is safe.

mod codegen2d;
pub mod cull;
mod fingerprint2d;
mod helpers2d;
pub mod terrain2d;

pub use craterfield_wgsl::{EmitError, ShaderBudget};
pub use cull::{CullPlan, CulledChild, Fate};
pub use terrain2d::TerrainEmitter;

/// Stable 64-bit fingerprint of a compiled level graph's content (see
/// [`TerrainEmitter::fingerprint`]), without building an emitter.
pub fn graph_fingerprint(graph: &craterfield_field::Graph) -> u64 {
    fingerprint2d::fingerprint(graph)
}
