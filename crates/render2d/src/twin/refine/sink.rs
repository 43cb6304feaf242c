//! Where the pixels of a `refine` frame go: the [`Sink`] trait, the shaded RGBA image
//! ([`ImageSink`], with the sky filled beforehand by [`fill_sky`]) and the per-pixel
//! field image ([`FieldSink`]).

use std::ops::Range;

use glam::Vec2;

use crate::twin::shade::Shader;
use craterfield_field::{MaterialId, Sample};

/// Where the pixels of a refined frame go: an RGBA image or a field image.
pub(super) trait Sink {
    /// Whether proven sky and deep solid pixels need their interpolated distance and normal
    /// ([`Sink::proven`]; field images do). Without, sky is filled beforehand and deep
    /// solid pixels go to [`Sink::deep`].
    const VALUES: bool;
    /// Pixels `xs` of row `yi`, proven solid of `material` and deeper than the interior
    /// depth (only called where `VALUES` is false).
    fn deep(&mut self, xs: Range<usize>, yi: usize, material: MaterialId);
    /// A proven pixel: its distance (world units), normal and material.
    fn proven(&mut self, x: usize, yi: usize, d: f32, n: Vec2, material: MaterialId);
    /// A pixel evaluated exactly.
    fn exact(&mut self, x: usize, yi: usize, s: &Sample);
}

/// The shaded image of a `refine` frame.
pub(super) struct ImageSink<'a> {
    pub(super) bytes: &'a mut [u8],
    pub(super) width: usize,
    pub(super) y0: usize,
    pub(super) shader: &'a Shader,
    pub(super) palette: &'a [[u8; 3]],
    pub(super) upp: f32,
    /// Tint refined pixels (the overlay of [`crate::twin::render_refine_overlay`]).
    pub(super) tint: bool,
    /// A distance past the interior depth (world units): the shade of proven deep pixels.
    pub(super) deep_at: f32,
    /// The last deep colour computed: its band row, material and colour.
    pub(super) deep_color: Option<(usize, MaterialId, [u8; 3])>,
}

impl ImageSink<'_> {
    fn put(&mut self, x: usize, yi: usize, rgb: [u8; 3]) {
        let i = (yi * self.width + x) * 4;
        self.bytes[i..i + 4].copy_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
    }

    fn shade(&self, yi: usize, d: f32, n: Vec2, material: MaterialId) -> [u8; 3] {
        let base = self.palette.get(usize::from(material)).copied();
        let sky = self.shader.sky((self.y0 + yi) as u32);
        self.shader.shade(d / self.upp, n, base, sky)
    }
}

impl Sink for ImageSink<'_> {
    const VALUES: bool = false;

    fn deep(&mut self, xs: Range<usize>, yi: usize, material: MaterialId) {
        let rgb = match self.deep_color {
            Some((row, m, rgb)) if row == yi && m == material => rgb,
            _ => {
                // Past the interior depth the colour depends on the row and material only.
                let rgb = self.shade(yi, self.deep_at, Vec2::ZERO, material);
                self.deep_color = Some((yi, material, rgb));
                rgb
            }
        };
        let row = yi * self.width;
        for px in self.bytes[(row + xs.start) * 4..(row + xs.end) * 4].chunks_exact_mut(4) {
            px.copy_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
        }
    }

    fn proven(&mut self, x: usize, yi: usize, d: f32, n: Vec2, material: MaterialId) {
        let rgb = self.shade(yi, d, n, material);
        self.put(x, yi, rgb);
    }

    fn exact(&mut self, x: usize, yi: usize, s: &Sample) {
        let d_px = s.distance / self.upp;
        let n = if self.shader.needs_normal(d_px) {
            s.gradient.normalize_or_zero()
        } else {
            Vec2::ZERO
        };
        let mut rgb = self.shade(yi, s.distance, n, s.material);
        if self.tint {
            rgb = [rgb[0] / 2 + 128, rgb[1] / 2, rgb[2] / 2];
        }
        self.put(x, yi, rgb);
    }
}

/// The per-pixel field of a `refine` frame.
pub(super) struct FieldSink<'a> {
    pub(super) d: &'a mut [f32],
    pub(super) n: &'a mut [Vec2],
    pub(super) m: &'a mut [MaterialId],
    pub(super) width: usize,
    pub(super) upp: f32,
}

impl Sink for FieldSink<'_> {
    const VALUES: bool = true;

    fn deep(&mut self, _: Range<usize>, _: usize, _: MaterialId) {
        unreachable!("field images take the interpolated values of deep pixels")
    }

    fn proven(&mut self, x: usize, yi: usize, d: f32, n: Vec2, material: MaterialId) {
        let i = yi * self.width + x;
        (self.d[i], self.n[i], self.m[i]) = (d / self.upp, n, material);
    }

    fn exact(&mut self, x: usize, yi: usize, s: &Sample) {
        let i = yi * self.width + x;
        self.d[i] = s.distance / self.upp;
        self.n[i] = s.gradient.normalize_or_zero();
        self.m[i] = s.material;
    }
}

/// Fills every row of a band with its sky colour.
pub(super) fn fill_sky(shader: &Shader, bytes: &mut [u8], width: usize, y0: usize) {
    let row_bytes = width * 4;
    for (i, row) in bytes.chunks_exact_mut(row_bytes).enumerate() {
        let [r, g, b] = shader.sky_rgb((y0 + i) as u32);
        row[..4].copy_from_slice(&[r, g, b, 255]);
        // Doubling copies: memcpy speed.
        let mut filled = 4;
        while filled < row_bytes {
            let n = filled.min(row_bytes - filled);
            row.copy_within(..n, filled);
            filled += n;
        }
    }
}
