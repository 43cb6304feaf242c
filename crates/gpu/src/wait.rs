//! Bounded waits for submitted GPU work: every wait of the renderers and of readback ends,
//! with [`GpuError::Timeout`] past its limit, instead of blocking on a device that never
//! finishes (an asynchronous driver, a hung device).

use std::time::Duration;

#[cfg(not(target_family = "wasm"))]
use super::GpuError;

/// How long a wait lasts by default: ten minutes. That is far longer than a frame takes on a
/// working device (Mesa's lavapipe, the GPU running on two CPU cores, renders the 3D forest
/// at 256x144 in about 2 s); reaching it means a hung device, or a software driver on an
/// image near the 64 Mi pixel limit.
pub const DEFAULT_WAIT: Duration = Duration::from_secs(600);

/// Waits until submission `index` has finished (every submission when `None`), for at most
/// `limit`; `what` names the work in the error. Native targets only: a browser's WebGPU
/// cannot be waited for, only awaited (its mappings, see `map_read_async`).
#[cfg(not(target_family = "wasm"))]
pub fn wait_for(
    device: &wgpu::Device,
    index: Option<wgpu::SubmissionIndex>,
    limit: Duration,
    what: &'static str,
) -> Result<(), GpuError> {
    match device.poll(wgpu::PollType::Wait {
        submission_index: index,
        timeout: Some(limit),
    }) {
        Ok(_) => Ok(()),
        Err(wgpu::PollError::Timeout) => Err(GpuError::Timeout { what, limit }),
        Err(e) => Err(GpuError::DeviceLost(e.to_string())),
    }
}
