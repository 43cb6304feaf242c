//! The one error type of the GPU layer, shared by the 2D renderer and the 3D raymarcher.

use thiserror::Error;

/// Why a GPU renderer could not do its job.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum GpuError {
    /// No adapter was found (no GPU and no software driver).
    #[error("no GPU adapter found: {0}")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("could not create a GPU device: {0}")]
    RequestDevice(String),
    /// A buffer or texture would exceed the device's limits (or is empty).
    #[error("{what}: {needed} needed, outside the device's limit of 1..={limit}")]
    LimitsTooLow {
        /// What was being allocated, with its unit (`readback buffer (bytes)`).
        what: &'static str,
        /// Bytes, or pixels per side, needed.
        needed: u64,
        /// The device's limit.
        limit: u64,
    },
    /// An emitted shader is past the budget a GPU compiler is handed (the emitter's
    /// message says which part and by how much).
    #[error("{0}")]
    ShaderTooLarge(String),
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
    /// The camera or view cannot be rendered (the reason names the bad value).
    #[error("camera: {0}")]
    Camera(String),
    /// `render` was called before a successful `prepare`.
    #[error("render called before prepare")]
    NotPrepared,
    /// The render target format is not one the renderer can draw into.
    #[error("unsupported render target format {0:?}")]
    TargetFormat(wgpu::TextureFormat),
    /// Reading back pixels failed.
    #[error("reading the frame back failed: {0}")]
    Readback(String),
    /// The GPU did not finish submitted work within the wait's limit ([`super::wait_for`]);
    /// the work may still be running.
    #[error("the GPU did not finish the {what} within {limit:?}")]
    Timeout {
        /// What was waited for.
        what: &'static str,
        /// The limit.
        limit: std::time::Duration,
    },
}
