//! The GPU raymarcher: a plan's emitted WGSL (`march3d::codegen3d`) as a compute pass on the
//! caller's wgpu device, writing an `rgba8unorm` storage texture.
//!
//! [`Marcher`] compiles one pipeline per plan key (an LRU [`PipelineCache`](craterfield_gpu::PipelineCache)
//! with hit/miss counters), records the pass into the caller's encoder and view
//! ([`Marcher::encode`]), or renders and reads back pixels ([`Marcher::render_to_rgba`],
//! [`Marcher::render_timed`]). Module map: `uniforms` (the camera uniform shared with
//! WGSL), `marcher` (pipelines, targets and passes).
//!
//! Two limits keep a render from stalling without a word. A plan's module past the
//! marcher's [`ShaderBudget`](craterfield_wgsl::ShaderBudget) (default
//! [`MARCH3D_BUDGET`](crate::codegen3d::MARCH3D_BUDGET)) is refused with
//! [`MarchGpuError::TooLarge`] before the driver compiles it ([`march_wgsl_within`] checks a
//! plan without a device). Each wait for submitted work ends after the marcher's wait limit
//! with [`GpuError::Timeout`].

mod marcher;
mod uniforms;

use thiserror::Error;

use crate::plan3d::PlanError;
use craterfield_gpu::GpuError;

pub use marcher::{Marcher, march_wgsl_within};
pub use uniforms::MarchFrame;

/// Why the GPU raymarcher could not render.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum MarchGpuError {
    /// The plan cannot be turned into WGSL.
    #[error("plan: {0}")]
    Plan(#[from] PlanError),
    /// The image size is zero, above the device's texture limit, or holds more than
    /// [`crate::cpu::MAX_PIXELS`] pixels.
    #[error(
        "image size {width}x{height} is not within 1..={limit} per side and {} pixels",
        crate::cpu::MAX_PIXELS
    )]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// The device's largest 2D texture side.
        limit: u32,
    },
    /// The camera has a non-finite vector or a field of view that is not positive.
    #[error("camera is not finite or its field of view is not positive")]
    Camera,
    /// The caller's target is not an `Rgba8Unorm` 2D texture with `STORAGE_BINDING` usage.
    #[error(
        "target texture must be Rgba8Unorm with STORAGE_BINDING usage, got {format:?} {usage:?}"
    )]
    Target {
        /// The target's format.
        format: wgpu::TextureFormat,
        /// The target's usages.
        usage: wgpu::TextureUsages,
    },
    /// The device rejected the emitted shader or its pipeline.
    #[error("GPU validation failed for plan {key:#018x}: {message}")]
    Validation {
        /// The plan's key.
        key: u64,
        /// The driver's message.
        message: String,
    },
    /// The plan's emitted shader is past the marcher's
    /// [`ShaderBudget`](craterfield_wgsl::ShaderBudget) (by default
    /// [`MARCH3D_BUDGET`](crate::codegen3d::MARCH3D_BUDGET)). It was refused before
    /// the driver saw it: a compiler handed such a module can spend minutes on it.
    #[error(
        "plan {key:#018x}: the shader would be too large for a GPU compiler: {size} {what}, past the budget of {limit} (render it with the CPU tracer)"
    )]
    TooLarge {
        /// The plan's key.
        key: u64,
        /// `inlined statements` or `text bytes`.
        what: &'static str,
        /// What the plan's module needs.
        size: u64,
        /// The budget.
        limit: u64,
    },
    /// Reading back pixels or timestamps failed, or the device was lost.
    #[error(transparent)]
    Gpu(#[from] GpuError),
}
