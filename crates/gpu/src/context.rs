//! A headless device for tools and tests: the first adapter wgpu finds (a GPU, or a software
//! driver such as Mesa's lavapipe), with default limits lowered to what the adapter offers.
//! Games pass their own device to the renderer and never need this.

use super::GpuError;

/// A device, its queue and what the adapter says about itself.
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, driver and type.
    pub info: wgpu::AdapterInfo,
    /// Whether the device was created with `TIMESTAMP_QUERY`.
    pub timestamps: bool,
}

impl GpuContext {
    /// Requests the default adapter and a device on it, with timestamp queries when offered.
    /// wgpu's environment variables choose the backends (`WGPU_BACKEND=vulkan,gl`, ...).
    /// Native targets only: in a browser, await [`Self::new_async`].
    #[cfg(not(target_family = "wasm"))]
    pub fn new() -> Result<GpuContext, GpuError> {
        pollster::block_on(GpuContext::new_async())
    }

    /// [`Self::new`] for every target (in a browser, the page's WebGPU adapter).
    pub async fn new_async() -> Result<GpuContext, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions::default())
            .await
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let required_features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("craterfield"),
            required_features,
            required_limits: device_limits(&adapter.limits()),
            ..wgpu::DeviceDescriptor::default()
        };
        let (device, queue) = adapter
            .request_device(&descriptor)
            .await
            .map_err(|e| GpuError::RequestDevice(e.to_string()))?;
        Ok(GpuContext {
            device,
            queue,
            info: adapter.get_info(),
            timestamps,
        })
    }

    /// `name (backend, device type)`, for messages.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {:?})",
            self.info.name, self.info.backend, self.info.device_type
        )
    }
}

/// The limits to request for craterfield's renderers on an adapter that offers `adapter`:
/// downlevel limits raised to the adapter's texture sizes, and to the storage buffers per
/// stage that the 2D renderer's refine passes bind (up to 8, where the adapter has them).
/// A game creating its own device can request these (or more).
pub fn device_limits(adapter: &wgpu::Limits) -> wgpu::Limits {
    let base = wgpu::Limits::downlevel_defaults().using_resolution(adapter.clone());
    wgpu::Limits {
        max_storage_buffers_per_shader_stage: adapter
            .max_storage_buffers_per_shader_stage
            .clamp(base.max_storage_buffers_per_shader_stage, 8),
        ..base
    }
}
