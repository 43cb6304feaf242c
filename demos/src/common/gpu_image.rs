//! [`GpuImage`]: a texture the library's renderers draw into, registered with egui's wgpu
//! renderer so a panel shows it as an image. It follows the panel's size in pixels.
//!
//! egui's wgpu renderer keeps its own textures as `Rgba8Unorm` holding sRGB-encoded bytes
//! and blends in that gamma space, so it must sample ours the same way: through an
//! `Rgba8Unorm` view, which hands the shader the stored bytes as they are. (An sRGB view
//! would decode them to linear values, and egui would show the picture too dark.)

use egui_wgpu::RenderState;

/// A render target shown by egui.
pub struct GpuImage {
    texture: wgpu::Texture,
    /// The view the renderer draws into (the texture's own format).
    target: wgpu::TextureView,
    id: egui::TextureId,
}

impl GpuImage {
    /// Keeps `slot` a `size` texture of `format` (`Rgba8Unorm`, or `Rgba8UnormSrgb` for a
    /// renderer that writes linear values), usable as `usage` plus sampling and copies, and
    /// registered with egui.
    pub fn ensure<'a>(
        slot: &'a mut Option<GpuImage>,
        rs: &RenderState,
        size: [u32; 2],
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> &'a GpuImage {
        let fits = slot.as_ref().is_some_and(|img| {
            img.texture.width() == size[0]
                && img.texture.height() == size[1]
                && img.texture.format() == format
        });
        if !fits {
            if let Some(old) = slot.take() {
                rs.renderer.write().free_texture(&old.id);
            }
            *slot = Some(GpuImage::new(rs, size, format, usage));
        }
        slot.as_ref().expect("the image was just made")
    }

    fn new(
        rs: &RenderState,
        size: [u32; 2],
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> GpuImage {
        const SHOWN: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
        let view_formats: &[wgpu::TextureFormat] = if format == SHOWN { &[] } else { &[SHOWN] };
        let texture = rs.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("craterfield demo image"),
            size: wgpu::Extent3d {
                width: size[0].max(1),
                height: size[1].max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: usage | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats,
        });
        let target = texture.create_view(&wgpu::TextureViewDescriptor::default());
        // Only sampled: egui's view needs no storage or render use.
        let shown = texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(SHOWN),
            usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
            ..Default::default()
        });
        let id = rs.renderer.write().register_native_texture(
            &rs.device,
            &shown,
            wgpu::FilterMode::Nearest,
        );
        GpuImage {
            texture,
            target,
            id,
        }
    }

    /// The view to render into.
    pub fn target(&self) -> &wgpu::TextureView {
        &self.target
    }

    /// The texture.
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// egui's id of the texture, for `egui::Image`.
    pub fn id(&self) -> egui::TextureId {
        self.id
    }

    /// Size in pixels.
    pub fn size(&self) -> [u32; 2] {
        [self.texture.width(), self.texture.height()]
    }
}
