//! GPU plumbing shared by the 2D terrain renderer and the 3D raymarcher: a headless device
//! for tools and tests ([`GpuContext`]), offscreen targets and readback ([`Offscreen`]),
//! timestamp queries ([`Timestamps`]), bounded waits ([`wait_for`]), pipeline validation
//! that never blocks a browser ([`validated`]), the bounded pipeline cache
//! ([`PipelineCache`]) and the one error type ([`GpuError`]).
//!
//! In a browser (WebAssembly on WebGPU) nothing may block: the page's event loop answers
//! mappings and error scopes. Every blocking call (`GpuContext::new`, `Offscreen::read`,
//! `map_read`, `Timestamps::read_ms`) is native only; each has an `_async` twin that
//! works on every target.
//!
//! Nothing here knows about terrain or scenes: `craterfield-render2d` and
//! `craterfield-march3d` build on it, and it depends on no other craterfield crate.

#![forbid(unsafe_code)]

mod cache;
mod context;
mod error;
mod limits;
mod offscreen;
mod timing;
mod validation;
mod wait;

pub use cache::PipelineCache;
pub use context::{GpuContext, device_limits};
pub use error::GpuError;
pub use limits::{check_buffer, check_storage, check_texture};
#[cfg(not(target_family = "wasm"))]
pub use offscreen::map_read;
pub use offscreen::{Offscreen, READBACK_FORMAT, map_read_async};
pub use timing::Timestamps;
pub use validation::{pending_errors, settle, validated, validated_async};
pub use wait::DEFAULT_WAIT;
#[cfg(not(target_family = "wasm"))]
pub use wait::wait_for;
