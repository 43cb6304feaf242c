//! Rendering a terrain frame into an offscreen texture and reading it back as an image: for
//! the CLI, golden-image tests and GPU-vs-CPU comparisons. Readbacks stall the pipeline;
//! games render into their own targets instead.

use image::RgbaImage;

use super::RenderError;
use super::renderer::TerrainRenderer;
use craterfield_gpu::{Offscreen, READBACK_FORMAT};

/// Which pipeline draws the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pipeline {
    /// The reduced-scale pipeline with the renderer's options.
    Reduced,
    /// Full-resolution direct evaluation.
    Direct,
}

/// Renders the prepared frame of `renderer` (whose target format must be
/// [`READBACK_FORMAT`]) with `pipeline` and reads it back. Native targets only: in a
/// browser, await [`render_to_image_async`].
#[cfg(not(target_family = "wasm"))]
pub fn render_to_image(
    renderer: &TerrainRenderer,
    width: u32,
    height: u32,
    pipeline: Pipeline,
) -> Result<RgbaImage, RenderError> {
    let target = submit_to_offscreen(renderer, width, height, pipeline)?;
    Ok(target.read(renderer.device())?)
}

/// [`render_to_image`] for every target, awaiting the readback.
pub async fn render_to_image_async(
    renderer: &TerrainRenderer,
    width: u32,
    height: u32,
    pipeline: Pipeline,
) -> Result<RgbaImage, RenderError> {
    let target = submit_to_offscreen(renderer, width, height, pipeline)?;
    Ok(target.read_async(renderer.device()).await?)
}

/// Renders the prepared frame into a new offscreen target and submits its copy to the
/// readback buffer.
fn submit_to_offscreen(
    renderer: &TerrainRenderer,
    width: u32,
    height: u32,
    pipeline: Pipeline,
) -> Result<Offscreen, RenderError> {
    if renderer.target_format() != READBACK_FORMAT {
        return Err(RenderError::TargetFormat(renderer.target_format()));
    }
    let device = renderer.device();
    let target = Offscreen::new(device, width, height)?;
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("craterfield readback"),
    });
    match pipeline {
        Pipeline::Reduced => renderer.render(&mut encoder, target.view())?,
        Pipeline::Direct => renderer.render_direct(&mut encoder, target.view(), None)?,
    }
    target.encode_copy(&mut encoder);
    renderer.queue().submit([encoder.finish()]);
    Ok(target)
}
