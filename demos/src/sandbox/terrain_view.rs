//! [`TerrainView`]: the library's `TerrainRenderer` drawing the world into a texture the
//! size of the central panel every frame, on eframe's device, with per-pass GPU times from
//! timestamp queries where the adapter has them; and the CPU twin's refine overlay on
//! request.

use std::rc::Rc;

use web_time::Instant;

use craterfield::field2d::{Graph, Terrain};
use craterfield::gpu::Timestamps;
use craterfield::render2d::gpu::{PrepareStats, TerrainRenderer};
use craterfield::render2d::twin::render_refine_overlay;
use craterfield::render2d::{Camera, RenderOptions};
use egui_wgpu::RenderState;

use crate::common::GpuImage;

/// The renderer's target. The renderer writes sRGB-encoded bytes into a plain `Rgba8Unorm`
/// target, which is what egui samples (see `GpuImage`).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// What the last frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameCost {
    /// CPU time of `prepare` and recording the passes, milliseconds.
    pub cpu_ms: f64,
    /// GPU time of passes 1, 2 and 3, milliseconds (timestamp queries).
    pub gpu_ms: Option<[f64; 3]>,
    /// What `prepare` did.
    pub prepare: PrepareStats,
}

/// The refine overlay of one view and terrain, kept until either changes.
struct Overlay {
    key: (Camera, u64),
    texture: egui::TextureHandle,
    refined_pixels: u64,
}

/// The GPU terrain renderer shown in a panel.
pub struct TerrainView {
    renderer: TerrainRenderer,
    image: Option<GpuImage>,
    timer: Option<PassTimer>,
    last: FrameCost,
    overlay: Option<Overlay>,
}

impl TerrainView {
    /// A renderer on `rs`'s device with `options`.
    pub fn new(rs: &RenderState, options: RenderOptions) -> Result<TerrainView, String> {
        let renderer = TerrainRenderer::new(&rs.device, &rs.queue, FORMAT, options)
            .map_err(|e| e.to_string())?;
        Ok(TerrainView {
            renderer,
            image: None,
            timer: Timestamps::new(&rs.device, &rs.queue, 2).map(PassTimer::new),
            last: FrameCost::default(),
            overlay: None,
        })
    }

    /// The options in use.
    pub fn options(&self) -> &RenderOptions {
        self.renderer.options()
    }

    /// Changes the options from the next frame.
    pub fn set_options(&mut self, options: RenderOptions) {
        if &options != self.renderer.options() {
            self.renderer.set_options(options);
        }
    }

    /// Whether per-pass GPU times are measured.
    pub fn has_timestamps(&self) -> bool {
        self.timer.is_some()
    }

    /// Pipeline cache `(hits, misses)`.
    pub fn cache_counters(&self) -> (u64, u64) {
        self.renderer.cache_counters()
    }

    /// The last frame's cost.
    pub fn last_cost(&self) -> FrameCost {
        self.last
    }

    /// Draws `terrain` seen by `camera` and returns the texture egui shows.
    pub fn draw(
        &mut self,
        rs: &RenderState,
        terrain: &Terrain<Graph>,
        palette: &[[u8; 3]],
        camera: &Camera,
    ) -> Result<egui::TextureId, String> {
        let started = Instant::now();
        let size = [camera.width, camera.height];
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let image = GpuImage::ensure(&mut self.image, rs, size, FORMAT, usage);
        let prepare = self
            .renderer
            .prepare(terrain, palette, camera)
            .map_err(|e| e.to_string())?;
        let mut encoder = rs
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("sandbox terrain"),
            });
        let timer = self.timer.as_ref().filter(|t| t.ready());
        match timer.and_then(|t| t.stamps.pair(0)) {
            Some((set, index)) => {
                self.renderer
                    .render_timed_passes(&mut encoder, image.target(), set, index)
            }
            None => self.renderer.render(&mut encoder, image.target()),
        }
        .map_err(|e| e.to_string())?;
        if let Some(t) = timer {
            t.stamps.encode_resolve(&mut encoder);
        }
        rs.queue.submit([encoder.finish()]);
        let cpu_ms = started.elapsed().as_secs_f64() * 1e3;
        let id = image.id();
        let gpu_ms = match timer {
            Some(t) => t.read(&rs.device)?,
            None => None,
        };
        self.last = FrameCost {
            cpu_ms,
            gpu_ms,
            prepare,
        };
        Ok(id)
    }

    /// The CPU twin's mode-refine picture of the same view with every exactly evaluated
    /// pixel tinted red (recomputed only when the view or the terrain's events changed), and how
    /// many pixels that is.
    pub fn refine_overlay(
        &mut self,
        ctx: &egui::Context,
        terrain: &Terrain<Graph>,
        palette: &[[u8; 3]],
        camera: &Camera,
    ) -> Result<(egui::TextureId, u64), String> {
        // Keyed by the events, not the tick: a growing crater's last frames may lag, where
        // recomputing every tick would cost a CPU frame each.
        let key = (*camera, terrain.events_applied());
        if let Some(o) = self.overlay.as_ref().filter(|o| o.key == key) {
            return Ok((o.texture.id(), o.refined_pixels));
        }
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let (rgba, stats) =
            render_refine_overlay(terrain, palette, camera, self.options(), threads)
                .map_err(|e| e.to_string())?;
        let image = egui::ColorImage::from_rgba_unmultiplied(
            [rgba.width() as usize, rgba.height() as usize],
            rgba.as_raw(),
        );
        let texture = ctx.load_texture("refine overlay", image, egui::TextureOptions::NEAREST);
        let id = texture.id();
        self.overlay = Some(Overlay {
            key,
            texture,
            refined_pixels: stats.refined_pixels,
        });
        Ok((id, stats.refined_pixels))
    }
}

/// Pass 1, 2 and 3 durations from the four marks of `render_timed_passes`.
fn pass_times(marks: &[f64]) -> [f64; 3] {
    let at = |i: usize| marks.get(i).copied().unwrap_or(0.0);
    [at(1) - at(0), at(2) - at(1), at(3) - at(2)]
}

/// The timestamp queries of the three passes. Natively a frame's times are read back as soon
/// as it is submitted. A browser's readback can only be awaited: there the times of a frame
/// arrive during a later one, and frames drawn while a read is in flight go untimed.
struct PassTimer {
    stamps: Rc<Timestamps>,
    #[cfg(target_family = "wasm")]
    arrived: Rc<std::cell::Cell<Option<Option<[f64; 3]>>>>,
    #[cfg(target_family = "wasm")]
    reading: Rc<std::cell::Cell<bool>>,
}

impl PassTimer {
    fn new(stamps: Timestamps) -> PassTimer {
        PassTimer {
            stamps: Rc::new(stamps),
            #[cfg(target_family = "wasm")]
            arrived: Rc::default(),
            #[cfg(target_family = "wasm")]
            reading: Rc::default(),
        }
    }

    /// Whether this frame can be timed (its buffers are not being read).
    fn ready(&self) -> bool {
        #[cfg(target_family = "wasm")]
        {
            !self.reading.get()
        }
        #[cfg(not(target_family = "wasm"))]
        {
            true
        }
    }

    /// The pass times of the frame just submitted (natively), or of the latest frame whose
    /// times have arrived (in a browser, where this frame's read starts now).
    #[cfg(not(target_family = "wasm"))]
    fn read(&self, device: &wgpu::Device) -> Result<Option<[f64; 3]>, String> {
        let marks = self
            .stamps
            .read_marks_ms(device)
            .map_err(|e| e.to_string())?;
        Ok(Some(pass_times(&marks)))
    }

    #[cfg(target_family = "wasm")]
    fn read(&self, device: &wgpu::Device) -> Result<Option<[f64; 3]>, String> {
        self.reading.set(true);
        let (stamps, device) = (self.stamps.clone(), device.clone());
        let (arrived, reading) = (self.arrived.clone(), self.reading.clone());
        wasm_bindgen_futures::spawn_local(async move {
            let marks = stamps.read_marks_ms_async(&device).await;
            arrived.set(Some(marks.ok().map(|m| pass_times(&m))));
            reading.set(false);
        });
        Ok(self.arrived.take().flatten())
    }
}
