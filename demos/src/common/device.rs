//! The wgpu device both demos ask eframe for, natively and in the browser: the library's
//! renderers' limits and timestamp queries where the adapter has them.

use std::sync::Arc;

/// Device features the demos use where the adapter offers them.
fn wanted_features(adapter: &wgpu::Adapter) -> wgpu::Features {
    adapter.features() & wgpu::Features::TIMESTAMP_QUERY
}

/// How eframe (and the tests' harness) create the device: the limits the library's
/// renderers need ([`craterfield::gpu::device_limits`]) and timestamp queries when offered.
/// In a browser only WebGPU is asked for: WebGL2 has no compute shaders, which the
/// renderer's refine mode needs.
pub fn wgpu_setup() -> egui_wgpu::WgpuSetup {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    if cfg!(target_family = "wasm") {
        setup.instance_descriptor.backends = wgpu::Backends::BROWSER_WEBGPU;
    }
    setup.device_descriptor = Arc::new(|adapter| wgpu::DeviceDescriptor {
        label: Some("craterfield demo"),
        required_features: wanted_features(adapter),
        required_limits: craterfield::gpu::device_limits(&adapter.limits()),
        ..Default::default()
    });
    egui_wgpu::WgpuSetup::CreateNew(setup)
}
