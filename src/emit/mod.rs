//! The shader emitter, shared by the 2D terrain renderer and the 3D raymarcher: level graphs
//! and 3D plans to WGSL text, and view culling.
//!
//! Emission is plain text generation (no GPU types), so this module builds without the `gpu`
//! feature; the renderers concatenate the emitted text with their hand-written WGSL.
//!
//! * [`wgsl`]: exact number literals and `em_`-prefixed names (generic).
//! * `fnv`: the stable hash behind fingerprints and keys (generic).
//! * [`terrain2d`]: [`TerrainEmitter`], a 2D level graph to `base_sample`.
//! * [`cull`]: which sub-graphs a view cannot see, and why that is safe.
//! * [`plan3d`]: the emitted form of a 3D world for one camera, which `march3d::compile`
//!   builds and both 3D renderers execute; [`codegen3d`] turns it into WGSL.

mod codegen2d;
pub mod codegen3d;
pub mod cull;
mod fingerprint2d;
pub(crate) mod fnv;
mod helpers2d;
pub mod plan3d;
pub mod terrain2d;
pub mod wgsl;

pub use cull::{CullPlan, CulledChild, Fate};
pub use terrain2d::{EmitError, ShaderBudget, TerrainEmitter};

/// Stable 64-bit fingerprint of a compiled level graph's content (see
/// [`TerrainEmitter::fingerprint`]), without building an emitter.
pub fn graph_fingerprint(graph: &crate::field2d::Graph) -> u64 {
    fingerprint2d::fingerprint(graph)
}
