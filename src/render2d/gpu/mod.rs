//! The wgpu terrain renderer: the reduced-scale pipeline of `docs/render2d-pipeline.md` on
//! the caller's `Device` and `Queue`.
//!
//! [`TerrainRenderer`] follows the conventions of wgpu ecosystem crates: it is built from a
//! device, a queue and the target format, [`TerrainRenderer::prepare`] uploads what changed
//! (explosion grid, camera, palette) and picks the compiled pipeline for the visible part of
//! the level, and [`TerrainRenderer::render`] records the passes into the caller's command
//! encoder, drawing into the caller's texture view (or [`TerrainRenderer::draw`] into the
//! caller's own render pass after [`TerrainRenderer::encode_prepasses`]). Errors are values.
//!
//! Module map: [`uniforms`] (plain data shared with WGSL), [`grid_mirror`] (incremental
//! uploads of the explosion grid), [`shaders`] (WGSL assembly), [`renderer`] (pipelines and
//! passes), [`context`] (a headless device for tools and tests), [`readback`] (render to an
//! image), [`timing`] (GPU timestamps for benchmarks).

pub mod context;
pub mod grid_mirror;
pub mod readback;
pub mod renderer;
pub mod shaders;
pub mod timing;
pub mod uniforms;

use thiserror::Error;

use crate::render2d::lattice::LatticeError;

pub use context::GpuContext;
pub use renderer::{PrepareStats, TerrainRenderer};

/// Why the GPU renderer could not do its job.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter was found (no GPU and no software driver).
    #[error("no GPU adapter found: {0}")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("could not create a GPU device: {0}")]
    RequestDevice(String),
    /// A buffer or texture would exceed the device's limits.
    #[error("{what} need {needed} bytes, above the device limit of {limit}")]
    LimitsTooLow {
        /// What was being allocated.
        what: &'static str,
        /// Bytes needed.
        needed: u64,
        /// The device's limit.
        limit: u64,
    },
    /// The device lacks a texture format capability the renderer needs.
    #[error("the device cannot {0}")]
    Unsupported(String),
    /// A shader or pipeline failed validation on the device.
    #[error("GPU validation failed for {what}: {message}")]
    Validation {
        /// The object being created.
        what: String,
        /// The driver's message.
        message: String,
    },
    /// The device was lost or out of memory.
    #[error("the GPU device was lost or ran out of memory: {0}")]
    DeviceLost(String),
    /// The camera cannot be rendered.
    #[error("camera: {0}")]
    Lattice(#[from] LatticeError),
    /// `render` was called before a successful `prepare`.
    #[error("render called before prepare")]
    NotPrepared,
    /// The render target format is not one the renderer can draw into.
    #[error("unsupported render target format {0:?}")]
    TargetFormat(wgpu::TextureFormat),
    /// Reading back pixels failed.
    #[error("reading the frame back failed: {0}")]
    Readback(String),
}
