//! Checks of allocation sizes against the device's limits, made before asking wgpu for a
//! buffer or texture: wgpu treats a size past a limit as a validation error that panics
//! by default, and every size here may come from a caller's image size or a level.

use super::GpuError;

/// Fails unless a buffer of `bytes` fits the device's `max_buffer_size`.
pub fn check_buffer(device: &wgpu::Device, what: &'static str, bytes: u64) -> Result<(), GpuError> {
    let limit = device.limits().max_buffer_size;
    within(what, bytes, limit)
}

/// Fails unless a buffer bound as storage fits the device's binding and buffer limits.
pub fn check_storage(
    device: &wgpu::Device,
    what: &'static str,
    bytes: u64,
) -> Result<(), GpuError> {
    let limits = device.limits();
    within(
        what,
        bytes,
        limits
            .max_storage_buffer_binding_size
            .min(limits.max_buffer_size),
    )
}

/// Fails unless a 2D texture of `width x height` fits the device's largest side.
pub fn check_texture(
    device: &wgpu::Device,
    what: &'static str,
    width: u32,
    height: u32,
) -> Result<(), GpuError> {
    let limit = device.limits().max_texture_dimension_2d;
    if width == 0 || height == 0 {
        return Err(GpuError::LimitsTooLow {
            what,
            needed: 0,
            limit: limit.into(),
        });
    }
    within(what, width.max(height).into(), limit.into())
}

fn within(what: &'static str, needed: u64, limit: u64) -> Result<(), GpuError> {
    if needed > limit {
        return Err(GpuError::LimitsTooLow {
            what,
            needed,
            limit,
        });
    }
    Ok(())
}
