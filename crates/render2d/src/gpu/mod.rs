//! The wgpu terrain renderer: the reduced-scale pipeline of `docs/render2d-pipeline.md` on
//! the caller's `Device` and `Queue`.
//!
//! [`TerrainRenderer`] follows the conventions of wgpu ecosystem crates: it is built from a
//! device, a queue and the target format, [`TerrainRenderer::prepare`] uploads what changed
//! (explosion grid, camera, palette) and picks the compiled pipeline for the visible part of
//! the level, and [`TerrainRenderer::render`] records the passes into the caller's command
//! encoder, drawing into the caller's texture view (or [`TerrainRenderer::draw`] into the
//! caller's own render pass after [`TerrainRenderer::encode_prepasses`]). Errors are values
//! of its own type, [`RenderError`], which carries the GPU layer's [`GpuError`] whole.
//!
//! Module map: `culling` ([`Culling`]: the part of the level a pipeline covers), `error` ([`RenderError`]), `uniforms` (plain data shared with WGSL),
//! `grid_mirror` (incremental uploads of the explosion grid), [`shaders`] (WGSL assembly),
//! `pipelines` (layout entries and pipeline constructors), `renderer` (pipelines and
//! passes), `refine` (mode refine's proof mirror, buffers and dispatches), `refine_passes`
//! (its layouts, pipelines and bind groups), `refine_mode` (what the renderer holds of the
//! mode across frames, and the calls it makes into it), `readback` (a frame rendered to an image). The
//! device plumbing it shares with the 3D raymarcher (headless context, offscreen targets,
//! timestamps, the pipeline cache and [`GpuError`]) is [`craterfield_gpu`].

mod culling;
mod error;
pub(crate) mod grid_mirror;
pub(crate) mod pipelines;
pub(crate) mod readback;
pub(crate) mod refine;
pub(crate) mod refine_mode;
pub(crate) mod refine_passes;
pub(crate) mod renderer;
pub mod shaders;
pub(crate) mod uniforms;

use craterfield_gpu::GpuError;
pub use culling::Culling;
pub use error::{RenderError, Unsupported};
#[cfg(not(target_family = "wasm"))]
pub use readback::render_to_image;
pub use readback::{Pipeline, render_to_image_async};
pub use renderer::{PrepareStats, TerrainRenderer};

#[cfg(test)]
mod tests;
