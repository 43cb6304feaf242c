//! The shader emitter, shared by the 2D terrain renderer and the 3D raymarcher: level graphs
//! to WGSL text, view culling, and a cache of what the text compiles to.
//!
//! Emission is plain text generation (no GPU types), so this module builds without the `gpu`
//! feature; the renderers concatenate the emitted text with their hand-written WGSL.
//!
//! * [`wgsl`]: exact number literals and `em_`-prefixed names (generic).
//! * [`fnv`]: the stable hash behind fingerprints and keys (generic).
//! * [`cache`]: bounded LRU cache of pipelines by key (generic).
//! * [`terrain2d`]: [`TerrainEmitter`], a 2D level graph to `base_sample`.
//! * [`cull`]: which sub-graphs a view cannot see, and why that is safe.
//! * [`world3d`]: a 3D scene and a camera to a [`Plan`](crate::march3d::Plan): culling,
//!   LOD, step tiers, baking and the shader-side switches.

pub mod cache;
mod codegen2d;
pub mod codegen3d;
pub mod cull;
mod fingerprint2d;
pub mod fnv;
mod helpers2d;
mod objects3d;
pub mod terrain2d;
pub mod wgsl;
pub mod world3d;

pub use cache::ShaderCache;
pub use cull::{CullPlan, CulledChild, Fate};
pub use terrain2d::TerrainEmitter;

/// Stable 64-bit fingerprint of a compiled level graph's content (see
/// [`TerrainEmitter::fingerprint`]), without building an emitter.
pub fn graph_fingerprint(graph: &crate::field2d::Graph) -> u64 {
    fingerprint2d::fingerprint(graph)
}
