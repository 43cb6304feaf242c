//! Draws a terrain frame through the GPU pipeline when wgpu finds an adapter, and through
//! the CPU twin of the same pipeline otherwise, saying which.

use craterfield::field2d::{Graph, Terrain};
use craterfield::gpu::GpuContext;
use craterfield::gpu::READBACK_FORMAT;
use craterfield::render2d::gpu::{Pipeline, render_to_image};
use craterfield::render2d::gpu::{RenderError, TerrainRenderer};
use craterfield::render2d::twin::render_twin;
use craterfield::render2d::{Camera, RenderOptions};
use image::RgbaImage;

/// A rendered frame and the renderer that drew it.
pub(crate) struct Frame {
    pub image: RgbaImage,
    /// `GPU (adapter)` or `CPU twin (why)`.
    pub renderer: String,
}

/// Renders on the GPU, falling back to the CPU twin when no adapter (or a GPU error).
pub(crate) fn render(
    terrain: &Terrain<Graph>,
    palette: &[[u8; 3]],
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Frame, String> {
    let gpu = GpuContext::new()
        .map_err(RenderError::from)
        .and_then(|ctx| {
            let mut r =
                TerrainRenderer::new(&ctx.device, &ctx.queue, READBACK_FORMAT, options.clone())?;
            r.prepare(terrain, palette, camera)?;
            let image = render_to_image(&r, camera.width, camera.height, Pipeline::Reduced)?;
            Ok((image, ctx.describe()))
        });
    match gpu {
        Ok((image, adapter)) => Ok(Frame {
            image,
            renderer: format!("GPU pipeline on {adapter}"),
        }),
        Err(why) => {
            let image =
                render_twin(terrain, palette, camera, options, 0).map_err(|e| e.to_string())?;
            Ok(Frame {
                image,
                renderer: format!("CPU twin of the pipeline (GPU unavailable: {why})"),
            })
        }
    }
}
