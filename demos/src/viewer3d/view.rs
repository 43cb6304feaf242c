//! [`MarchView`]: the GPU raymarcher drawing the plan straight into the texture the central
//! panel shows, on eframe's own device, and the time the pass took.
//!
//! The marcher writes an `Rgba8Unorm` storage texture of sRGB-encoded bytes, which egui
//! samples as they are (see `GpuImage`). The pass's GPU time comes from timestamp queries inside the pass where the
//! device has them (`Marcher::encode_timed`), and otherwise from the wall clock, from
//! submitting the pass until the device is done.

use std::time::Instant;

use craterfield::gpu::Timestamps;
use craterfield::march3d::gpu::Marcher;
use craterfield::march3d::{Camera3d, Plan};
use egui_wgpu::RenderState;

use crate::common::GpuImage;

/// The raymarcher, its timestamps and the texture egui shows.
pub(crate) struct MarchView {
    marcher: Marcher,
    stamps: Option<Timestamps>,
    image: Option<GpuImage>,
}

/// One drawn frame of the view.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Drawn {
    /// egui's id of the texture holding the picture.
    pub(crate) texture: egui::TextureId,
    /// Milliseconds the pass took (see [`MarchView::gpu_timed`]).
    pub(crate) pass_ms: f64,
}

impl MarchView {
    /// A raymarcher on eframe's device.
    pub(crate) fn new(rs: &RenderState) -> Result<MarchView, String> {
        let marcher = Marcher::new(&rs.device, &rs.queue)
            .map_err(|e| format!("the GPU raymarcher could not start: {e}"))?;
        Ok(MarchView {
            marcher,
            stamps: Timestamps::new(&rs.device, &rs.queue, 1),
            image: None,
        })
    }

    /// Pipeline cache `(hits, misses)`.
    pub(crate) fn cache_counters(&self) -> (u64, u64) {
        self.marcher.cache_counters()
    }

    /// Whether pass times are GPU timestamps (otherwise wall clock, submit to done).
    pub(crate) fn gpu_timed(&self) -> bool {
        self.stamps.is_some()
    }

    /// Renders `plan` seen by `camera` into the `size` (pixels) texture, submits the pass
    /// and waits for it.
    pub(crate) fn draw(
        &mut self,
        rs: &RenderState,
        plan: &Plan,
        camera: &Camera3d,
        size: [u32; 2],
    ) -> Result<Drawn, String> {
        let image = GpuImage::ensure(
            &mut self.image,
            rs,
            size,
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::STORAGE_BINDING,
        );
        let mut encoder = rs
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("viewer3d march"),
            });
        let pair = self.stamps.as_ref().and_then(|s| s.pair(0));
        self.marcher
            .encode_timed(&mut encoder, plan, camera, image.target(), pair)
            .map_err(|e| e.to_string())?;
        if let Some(s) = &self.stamps {
            s.encode_resolve(&mut encoder);
        }
        let texture = image.id();
        let started = Instant::now();
        rs.queue.submit([encoder.finish()]);
        let pass_ms = match &self.stamps {
            Some(s) => s
                .read_ms(&rs.device)
                .map_err(|e| format!("reading the pass time: {e}"))?
                .first()
                .copied()
                .unwrap_or(0.0),
            None => {
                rs.device
                    .poll(wgpu::PollType::wait_indefinitely())
                    .map_err(|e| format!("the GPU stopped: {e}"))?;
                started.elapsed().as_secs_f64() * 1e3
            }
        };
        Ok(Drawn { texture, pass_ms })
    }
}
