//! Full-resolution exact rendering on the CPU: the field is evaluated at every pixel centre,
//! thresholded at zero with a one-pixel anti-aliasing ramp, and shaded by material, depth and
//! the surface normal.
//!
//! This is the reference image (not a fast path): tiles whose centre distance proves them
//! all-sky are filled without per-pixel work, others evaluate every pixel, on all cores.

use glam::Vec2;
use image::RgbaImage;

use super::camera::{Camera, CameraError};
use super::options::ShadeOptions;
use super::twin::Shader;
use craterfield_field::Sdf;

/// Options of the exact renderer.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExactRenderOptions {
    /// Colours and shading, the same as the reduced-scale pipeline's.
    pub shade: ShadeOptions,
    /// Worker threads (0 = all cores).
    pub threads: usize,
}

const TILE: u32 = 8;

/// Render `field` through `camera`, colouring material `i` with `palette[i]` (unknown
/// materials are drawn magenta so they stand out). Fails, before allocating the image,
/// where [`Camera::validate`] does.
pub fn render_exact<F: Sdf + Sync>(
    field: &F,
    palette: &[[u8; 3]],
    camera: &Camera,
    opts: &ExactRenderOptions,
) -> Result<RgbaImage, CameraError> {
    camera.validate()?;
    let (w, h) = (camera.width, camera.height);
    let mut img = RgbaImage::new(w, h);
    let tiles_y = h.div_ceil(TILE);
    let threads = craterfield_core::threads::resolve(opts.threads);
    let row_bytes = (w * 4) as usize;
    let band_bytes = row_bytes * TILE as usize;
    let bands: Vec<(u32, &mut [u8])> = img
        .chunks_mut(band_bytes)
        .enumerate()
        .map(|(i, b)| (i as u32, b))
        .collect();
    let per_thread = (tiles_y as usize).div_ceil(threads).max(1);
    let mut groups: Vec<Vec<(u32, &mut [u8])>> = Vec::new();
    let mut bands = bands.into_iter().peekable();
    while bands.peek().is_some() {
        groups.push(bands.by_ref().take(per_thread).collect());
    }
    let painter = Painter {
        field,
        palette,
        camera,
        shader: Shader::new(&opts.shade, camera.height),
    };
    if threads == 1 {
        for (band, bytes) in groups.into_iter().flatten() {
            painter.band(band, bytes);
        }
        return Ok(img);
    }
    std::thread::scope(|s| {
        for group in groups {
            let painter = &painter;
            s.spawn(move || {
                for (band, bytes) in group {
                    painter.band(band, bytes);
                }
            });
        }
    });
    Ok(img)
}

struct Painter<'a, F> {
    field: &'a F,
    palette: &'a [[u8; 3]],
    camera: &'a Camera,
    shader: Shader,
}

impl<F: Sdf> Painter<'_, F> {
    fn band(&self, band: u32, bytes: &mut [u8]) {
        let w = self.camera.width;
        let y0 = band * TILE;
        let rows = (bytes.len() / (w as usize * 4)) as u32;
        let upp = self.camera.units_per_pixel;
        let lipschitz = self.field.lipschitz().max(1.0);
        for tx in 0..w.div_ceil(TILE) {
            let x0 = tx * TILE;
            let cx = (x0 + TILE / 2).min(w - 1);
            let cy = (y0 + TILE / 2).min(y0 + rows - 1);
            let d_center = self.field.distance(self.camera.pixel_to_world(cx, cy)) / upp;
            // Every pixel of the tile is within this many pixels of the centre.
            let reach = TILE as f32 * std::f32::consts::SQRT_2 * lipschitz;
            let all_sky = d_center - reach > 1.0;
            for y in y0..y0 + rows {
                for x in x0..(x0 + TILE).min(w) {
                    let rgb = if all_sky {
                        self.shader.sky_rgb(y)
                    } else {
                        self.pixel(x, y)
                    };
                    let i = (((y - y0) * w + x) * 4) as usize;
                    bytes[i..i + 4].copy_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
                }
            }
        }
    }

    /// The exact field at the pixel, shaded by the pipeline's formula (the gradient is
    /// only evaluated where the colour depends on it).
    fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let p = self.camera.pixel_to_world(x, y);
        let (d, material) = self.field.distance_material(p);
        let d_px = d / self.camera.units_per_pixel;
        let normal = if self.shader.needs_normal(d_px) {
            self.field.sample(p).gradient.normalize_or_zero()
        } else {
            Vec2::ZERO
        };
        let base = self.palette.get(usize::from(material)).copied();
        self.shader.shade(d_px, normal, base, self.shader.sky(y))
    }
}
