//! GPU plumbing shared by the 2D terrain renderer and the 3D raymarcher: a headless device
//! for tools and tests ([`GpuContext`]), offscreen targets and readback ([`Offscreen`]),
//! timestamp queries ([`Timestamps`]), bounded waits ([`wait_for`]), the bounded pipeline cache
//! ([`PipelineCache`]) and the one error type ([`GpuError`]).
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
mod wait;

pub use cache::PipelineCache;
pub use context::{GpuContext, device_limits};
pub use error::GpuError;
pub use limits::{check_buffer, check_storage, check_texture};
pub use offscreen::{Offscreen, READBACK_FORMAT, map_read};
pub use timing::Timestamps;
pub use wait::{DEFAULT_WAIT, wait_for};
