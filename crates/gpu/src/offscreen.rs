//! Offscreen targets and buffer readback: a frame rendered into a texture and copied back
//! to the CPU as an image, for tools, tests and GPU-vs-CPU comparisons.

use std::sync::{Arc, Mutex};
use std::task::{Poll, Waker};

use image::RgbaImage;

use super::GpuError;
#[cfg(not(target_family = "wasm"))]
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

    /// Maps the buffer (after the copy was submitted) and returns the pixels. Native
    /// targets only: a browser answers the mapping from its event loop, so it uses
    /// [`Self::read_async`].
    #[cfg(not(target_family = "wasm"))]
    pub fn read(&self, device: &wgpu::Device) -> Result<RgbaImage, GpuError> {
        let pixels = map_read(device, &self.buffer, |data| self.unpad(data))?;
        self.image(pixels)
    }

    /// [`Self::read`] for every target, awaiting the mapping.
    pub async fn read_async(&self, device: &wgpu::Device) -> Result<RgbaImage, GpuError> {
        let pixels = map_read_async(device, &self.buffer, |data| self.unpad(data)).await?;
        self.image(pixels)
    }

    /// The rows of the mapped buffer without their padding.
    fn unpad(&self, data: &[u8]) -> Vec<u8> {
        let (width, row) = (self.width as usize * 4, self.padded_row as usize);
        data.chunks(row)
            .flat_map(|line| &line[..width])
            .copied()
            .collect()
    }

    fn image(&self, pixels: Vec<u8>) -> Result<RgbaImage, GpuError> {
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| GpuError::Readback("pixel count does not match the size".into()))
    }
}

/// Maps a `MAP_READ` `buffer` for reading (after the commands filling it were submitted),
/// waits for the device (at most [`DEFAULT_WAIT`]), hands the bytes to `read` and unmaps.
/// Native targets only (see [`map_read_async`]).
#[cfg(not(target_family = "wasm"))]
pub fn map_read<T>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, GpuError> {
    // Never blocks past the wait: natively the future is ready once the device is.
    pollster::block_on(map_read_async(device, buffer, read))
}

/// [`map_read`] for every target: on a native device it waits as `map_read` does (at most
/// [`DEFAULT_WAIT`]); in a browser it awaits the mapping, which the page's event loop
/// completes.
pub async fn map_read_async<T>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> T,
) -> Result<T, GpuError> {
    let slice = buffer.slice(..);
    let slot = Arc::new(Mutex::new(MapSlot::default()));
    let filled = slot.clone();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let mut s = filled.lock().unwrap_or_else(|e| e.into_inner());
        s.result = Some(r);
        if let Some(waker) = s.waker.take() {
            waker.wake();
        }
    });
    #[cfg(not(target_family = "wasm"))]
    wait_for(device, None, DEFAULT_WAIT, "readback")?;
    #[cfg(target_family = "wasm")]
    let _ = device;
    let mapped = std::future::poll_fn(|cx| {
        let mut s = slot.lock().unwrap_or_else(|e| e.into_inner());
        match s.result.take() {
            Some(r) => Poll::Ready(r.map_err(|e| GpuError::Readback(e.to_string()))),
            // The wait has run the mapping's callback: a missing result is an error rather
            // than a future that never ends.
            None if cfg!(not(target_family = "wasm")) => Poll::Ready(Err(GpuError::Readback(
                "the device finished without completing the mapping".into(),
            ))),
            None => {
                s.waker = Some(cx.waker().clone());
                Poll::Pending
            }
        }
    })
    .await;
    mapped?;
    let out = {
        let data = slice.get_mapped_range().into_view()?;
        read(&data)
    };
    buffer.unmap();
    Ok(out)
}

/// A mapped range as wgpu 29 and 30 give it: wgpu 30 returns a `Result`, wgpu 29 the view
/// itself. The library builds against both, so that a game on either (Bevy 0.19's renderer is on
/// wgpu 29) shares its device with the renderers.
trait MappedRange {
    fn into_view(self) -> Result<wgpu::BufferView, GpuError>;
}

impl MappedRange for wgpu::BufferView {
    fn into_view(self) -> Result<wgpu::BufferView, GpuError> {
        Ok(self)
    }
}

impl<E: std::fmt::Display> MappedRange for Result<wgpu::BufferView, E> {
    fn into_view(self) -> Result<wgpu::BufferView, GpuError> {
        self.map_err(|e| GpuError::Readback(e.to_string()))
    }
}

/// Where a mapping's callback leaves its result for the future awaiting it.
#[derive(Default)]
struct MapSlot {
    result: Option<Result<(), wgpu::BufferAsyncError>>,
    waker: Option<Waker>,
}
