//! Offscreen targets and buffer readback: a frame rendered into a texture and copied back
//! to the CPU as an image, for tools, tests and GPU-vs-CPU comparisons.

use image::RgbaImage;

use super::GpuError;
use super::wait::{DEFAULT_WAIT, wait_for};

/// Format of readback targets (bytes map one to one onto image pixels).
pub const READBACK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// An offscreen `Rgba8Unorm` target of a fixed size with a buffer to copy it into.
pub struct Offscreen {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    buffer: wgpu::Buffer,
    width: u32,
    height: u32,
    padded_row: u32,
}

impl Offscreen {
    /// A render target of `width x height` pixels on `device`.
    pub fn new(device: &wgpu::Device, width: u32, height: u32) -> Result<Offscreen, GpuError> {
        Offscreen::with_usage(
            device,
            width,
            height,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        )
    }

    /// A target a compute pass writes as a storage texture.
    pub fn storage(device: &wgpu::Device, width: u32, height: u32) -> Result<Offscreen, GpuError> {
        Offscreen::with_usage(device, width, height, wgpu::TextureUsages::STORAGE_BINDING)
    }

    /// The size in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    fn with_usage(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        usage: wgpu::TextureUsages,
    ) -> Result<Offscreen, GpuError> {
        super::check_texture(device, "render target (pixels per side)", width, height)?;
        let padded_row = (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer_bytes = u64::from(padded_row) * u64::from(height);
        super::check_buffer(device, "readback buffer (bytes)", buffer_bytes)?;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("craterfield offscreen"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: READBACK_FORMAT,
            usage: usage | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("craterfield readback"),
            size: buffer_bytes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Ok(Offscreen {
            texture,
            view,
            buffer,
            width,
            height,
            padded_row,
        })
    }

    /// The view to render into.
    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Records the copy of the texture into the readback buffer.
    pub fn encode_copy(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.copy_texture_to_buffer(
            self.texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
    }

    /// Maps the buffer (after the copy was submitted) and returns the pixels.
    pub fn read(&self, device: &wgpu::Device) -> Result<RgbaImage, GpuError> {
        let (width, row) = (self.width as usize * 4, self.padded_row as usize);
        let pixels = map_read(device, &self.buffer, |data| {
            data.chunks(row)
                .flat_map(|line| &line[..width])
                .copied()
                .collect::<Vec<u8>>()
        })?;
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| GpuError::Readback("pixel count does not match the size".into()))
    }
}

/// Maps a `MAP_READ` `buffer` for reading (after the commands filling it were submitted),
/// waits for the device (at most [`DEFAULT_WAIT`]), hands the bytes to `read` and unmaps.
pub fn map_read<T>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, GpuError> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    wait_for(device, None, DEFAULT_WAIT, "readback")?;
    // The wait has run the mapping callback: `try_recv`, so a missing callback is an error
    // rather than a block.
    rx.try_recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let out = {
        let data = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        read(&data)
    };
    buffer.unmap();
    Ok(out)
}
