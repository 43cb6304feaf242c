//! The 2D GPU renderer's error type, [`RenderError`]: what [`TerrainRenderer`] and
//! [`render_to_image`] return. The failures of the device itself (no adapter, a limit, a
//! validation error, a lost device, a readback, a wait past its limit) stay the GPU layer's
//! [`GpuError`], carried whole in [`RenderError::Gpu`].
//!
//! [`TerrainRenderer`]: super::TerrainRenderer
//! [`render_to_image`]: super::render_to_image

use thiserror::Error;

use crate::camera::CameraError;
use craterfield_gpu::GpuError;
use craterfield_wgsl::EmitError;

/// Why the 2D GPU renderer could not do its job.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The GPU layer failed (its message unchanged).
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The camera cannot be rendered (see [`crate::Camera::validate`]).
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    /// The level's emitted shader is past the budget a GPU compiler is handed (the
    /// emitter's error says which part and by how much); render it on the CPU instead.
    #[error(transparent)]
    ShaderTooLarge(#[from] EmitError),
    /// The device, or the renderer at this image size, cannot draw what was asked.
    #[error("the device cannot {what}")]
    Unsupported {
        /// What cannot be drawn, and the limit in the way.
        what: Unsupported,
    },
    /// A frame was recorded, or its refine statistics read, before a successful
    /// `prepare` (or the statistics of mode refine were asked of another mode).
    #[error("render called before prepare")]
    NotPrepared,
    /// The render target format is not one the renderer can draw into (or, for
    /// [`render_to_image`](super::render_to_image), not the readback format).
    #[error("unsupported render target format {0:?}")]
    TargetFormat(wgpu::TextureFormat),
}

/// What mode refine needs that the device or the image size does not give
/// ([`RenderError::Unsupported`]). Each reads after "the device cannot".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum Unsupported {
    /// The device binds fewer storage buffers per shader stage than the refine passes do.
    #[error(
        "draw mode refine with {have} storage buffers per shader stage (it needs {needed}; \
         request them when creating the device)"
    )]
    StorageBuffers {
        /// The device's `max_storage_buffers_per_shader_stage`.
        have: u32,
        /// What the refine passes bind.
        needed: u32,
    },
    /// The device runs fewer compute invocations per workgroup than the refine passes.
    #[error("draw mode refine without {needed} compute invocations per workgroup")]
    ComputeInvocations {
        /// The device's `max_compute_invocations_per_workgroup`.
        have: u32,
        /// What the refine passes run.
        needed: u32,
    },
    /// The image has more `4 x 4` pixel blocks than the refine block list can index.
    #[error("draw refine at {width}x{height}: its block list holds at most 2^{index_bits} blocks")]
    RefineBlocks {
        /// Image width, pixels.
        width: u32,
        /// Image height, pixels.
        height: u32,
        /// Bits of a block index in the list.
        index_bits: u32,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages read as they did when these were `GpuError` strings (the CLI prints
    /// them, e.g. when it falls back to the CPU twin).
    #[test]
    fn messages_read_as_before() {
        let camera = CameraError::BadZoom { value: 0.0 };
        assert_eq!(
            RenderError::from(camera).to_string(),
            format!("camera: {camera}")
        );
        let emit = EmitError::TooLarge {
            what: "inlined statements",
            size: 2,
            limit: 1,
        };
        assert_eq!(
            RenderError::from(emit.clone()).to_string(),
            emit.to_string()
        );
        let lost = GpuError::DeviceLost("gone".into());
        assert_eq!(
            RenderError::from(lost).to_string(),
            "the GPU device was lost or ran out of memory: gone"
        );
        let cases = [
            (
                Unsupported::StorageBuffers { have: 4, needed: 7 },
                "the device cannot draw mode refine with 4 storage buffers per shader stage (it \
                 needs 7; request them when creating the device)",
            ),
            (
                Unsupported::ComputeInvocations {
                    have: 32,
                    needed: 64,
                },
                "the device cannot draw mode refine without 64 compute invocations per workgroup",
            ),
            (
                Unsupported::RefineBlocks {
                    width: 70_000,
                    height: 70_000,
                    index_bits: 28,
                },
                "the device cannot draw refine at 70000x70000: its block list holds at most 2^28 \
                 blocks",
            ),
        ];
        for (what, text) in cases {
            assert_eq!(RenderError::Unsupported { what }.to_string(), text);
        }
        assert_eq!(
            RenderError::NotPrepared.to_string(),
            "render called before prepare"
        );
        assert_eq!(
            RenderError::TargetFormat(wgpu::TextureFormat::Depth32Float).to_string(),
            "unsupported render target format Depth32Float"
        );
    }
}
