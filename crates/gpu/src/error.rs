//! The one error type of the GPU layer, shared by the 2D renderer and the 3D raymarcher:
//! failures of the adapter, the device and its limits, validation, readbacks and waits.
//! What only one renderer can refuse (a camera, a shader past its budget, a mode the
//! device cannot draw) is that renderer's own error (`RenderError` in the 2D renderer,
//! `MarchGpuError` in the 3D one), which carries this one.

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
