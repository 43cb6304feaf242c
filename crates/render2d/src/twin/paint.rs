//! Pass 3's fast path, one band of pixel rows at a time: the band is filled with the sky,
//! then each quad's block is left as sky, filled with the interior colour, or evaluated and
//! shaded, and within an evaluated block each row likewise. Which one is decided by
//! [`Kernel::bounds`]; the shortcuts produce exactly the colours [`Shader::shade`] would,
//! so the image equals the per-pixel path's.

use glam::Vec2;

use super::blocks::{Block, Bounds, Kernel, Layout, Run, Scratch, pixel_weights};
use super::shade::Shader;
use super::upsample::{Textures, normal};

/// Interior colours are tabulated per row for materials below this; rarer ones are shaded
/// when met.
const TABLE_MATERIALS: usize = 256;

/// Blocks with fewer pixels are evaluated without bounding them first.
const MIN_BOUNDED_PIXELS: usize = 4;

/// The colours of one image row that do not depend on the pixel.
#[derive(Default)]
struct RowColors {
    sky: [f32; 3],
    sky_rgb: [u8; 3],
    /// Deep-interior colour of palette entries `0..min(palette, TABLE_MATERIALS)`.
    interior: Vec<[u8; 3]>,
    /// Deep-interior colour of a material outside the palette.
    missing: [u8; 3],
}

/// A thread's buffers.
#[derive(Default)]
pub(super) struct PaintScratch {
    blocks: Scratch,
    rows: Vec<RowColors>,
}

/// What a block's (or row's) bounds prove about it.
enum Fill {
    Sky,
    Interior,
    Evaluate,
}

/// Everything pass 3 reads, for one frame.
pub(super) struct Painter<'a> {
    pub tex: &'a Textures<'a>,
    pub layout: &'a Layout,
    pub shader: &'a Shader,
    pub palette: &'a [[u8; 3]],
    pub upp: f32,
    pub width: usize,
}

impl Painter<'_> {
    /// Paints image rows `rows.pixels` (all in quad row `rows.cell`) into `bytes`, RGBA.
    pub(super) fn paint(&self, scratch: &mut PaintScratch, rows: &Run, bytes: &mut [u8]) {
        self.row_colors(scratch, rows);
        self.fill_sky(scratch, bytes);
        for columns in &self.layout.columns.runs {
            let block = Block::at(columns, rows);
            let kernel = Kernel::new(self.tex, block);
            let small = kernel.block.xs.len() * kernel.block.ys.len() < MIN_BOUNDED_PIXELS;
            // Bounding a tiny block costs more than evaluating it.
            let bounds = (!small).then(|| kernel.bounds(self.layout));
            match bounds.map_or(Fill::Evaluate, |b| {
                self.fill(b.lo - b.margin, b.hi + b.margin)
            }) {
                Fill::Sky => {}
                Fill::Interior => {
                    for yi in 0..kernel.block.ys.len() {
                        self.paint_interior(scratch, &kernel, yi, bytes);
                    }
                }
                Fill::Evaluate => self.paint_evaluated(scratch, &kernel, bounds, bytes),
            }
        }
    }

    /// Tabulates the sky and interior colours of the band's rows.
    fn row_colors(&self, scratch: &mut PaintScratch, rows: &Run) {
        let depth = -self.shader.interior_depth();
        let tabulated = &self.palette[..self.palette.len().min(TABLE_MATERIALS)];
        scratch
            .rows
            .resize_with(rows.pixels.len(), RowColors::default);
        for (colors, y) in scratch.rows.iter_mut().zip(rows.pixels.clone()) {
            let sky = self.shader.sky(y as u32);
            let deep = |base| self.shader.shade(depth, Vec2::ZERO, base, sky);
            colors.sky = sky;
            colors.sky_rgb = self.shader.sky_rgb(y as u32);
            colors.interior.clear();
            colors
                .interior
                .extend(tabulated.iter().map(|&c| deep(Some(c))));
            colors.missing = deep(None);
        }
    }

    /// Which fill pixels whose distances lie in `lo..=hi` (world units) provably take.
    fn fill(&self, lo: f32, hi: f32) -> Fill {
        // Rounding is monotone: every pixel's `d / upp` lies between these.
        let (lo_px, hi_px) = (lo / self.upp, hi / self.upp);
        if lo_px >= 0.5 {
            Fill::Sky
        } else if hi_px <= -self.shader.interior_depth() {
            Fill::Interior
        } else {
            Fill::Evaluate
        }
    }

    /// The RGBA pixels of row `y` (band-relative `yi`), columns `xs`.
    fn pixels<'b>(&self, bytes: &'b mut [u8], yi: usize, block: &Block) -> &'b mut [u8] {
        let start = (yi * self.width + block.xs.start) * 4;
        &mut bytes[start..start + block.xs.len() * 4]
    }

    /// Fills every row of the band with its sky colour (doubling copies: memcpy speed).
    fn fill_sky(&self, scratch: &PaintScratch, bytes: &mut [u8]) {
        let row_bytes = self.width * 4;
        for (row, colors) in bytes.chunks_exact_mut(row_bytes).zip(&scratch.rows) {
            row[..4].copy_from_slice(&rgba(colors.sky_rgb));
            let mut filled = 4;
            while filled < row_bytes {
                let n = filled.min(row_bytes - filled);
                row.copy_within(..n, filled);
                filled += n;
            }
        }
    }

    /// Paints band row `yi` of `block` with deep-interior colours.
    fn paint_interior(&self, scratch: &PaintScratch, kernel: &Kernel, yi: usize, bytes: &mut [u8]) {
        let block = &kernel.block;
        let y = block.ys.start + yi;
        let colors = &scratch.rows[yi];
        let pixels = self.pixels(bytes, yi, block).chunks_exact_mut(4);
        for (px, x) in pixels.zip(block.xs.clone()) {
            px.copy_from_slice(&rgba(
                self.interior(colors, kernel.material(self.layout, x, y)),
            ));
        }
    }

    /// Paints a block row by row: rows proven sky stay sky, rows proven deep get the
    /// interior colours, the others are evaluated and shaded pixel by pixel.
    fn paint_evaluated(
        &self,
        scratch: &mut PaintScratch,
        kernel: &Kernel,
        bounds: Option<Bounds>,
        bytes: &mut [u8],
    ) {
        let block = &kernel.block;
        let n = block.xs.len();
        let deep = -self.shader.interior_depth();
        kernel.prepare(self.tex, self.layout, &mut scratch.blocks);
        for (yi, y) in block.ys.clone().enumerate() {
            if let Some(b) = bounds {
                let (lo, hi) = kernel.row_bounds(self.layout, y, &scratch.blocks);
                match self.fill(lo - b.margin, hi + b.margin) {
                    Fill::Sky => continue,
                    Fill::Interior => {
                        self.paint_interior(scratch, kernel, yi, bytes);
                        continue;
                    }
                    Fill::Evaluate => {}
                }
            }
            kernel.row(self.layout, y, &mut scratch.blocks);
            let colors = &scratch.rows[yi];
            let dist = &scratch.blocks.dist[..n];
            let pixels = self.pixels(bytes, yi, block).chunks_exact_mut(4);
            for ((px, &d), x) in pixels.zip(dist).zip(block.xs.clone()) {
                let d_px = d / self.upp;
                let rgb = if d_px >= 0.5 {
                    colors.sky_rgb
                } else if d_px <= deep {
                    self.interior(colors, kernel.material(self.layout, x, y))
                } else {
                    self.surface(kernel, d_px, x, y, colors.sky)
                };
                px.copy_from_slice(&rgba(rgb));
            }
        }
    }

    /// A pixel near the surface: the full formula.
    fn surface(&self, kernel: &Kernel, d_px: f32, x: usize, y: usize, sky: [f32; 3]) -> [u8; 3] {
        let n = if self.shader.needs_normal(d_px) {
            normal(&kernel.quad, pixel_weights(self.layout, x, y))
        } else {
            Vec2::ZERO
        };
        let base = self
            .palette
            .get(usize::from(kernel.material(self.layout, x, y)))
            .copied();
        self.shader.shade(d_px, n, base, sky)
    }

    /// The deep-interior colour of `material` in the row of `colors`.
    fn interior(&self, colors: &RowColors, material: u16) -> [u8; 3] {
        let m = usize::from(material);
        match self.palette.get(m) {
            None => colors.missing,
            Some(&base) => colors.interior.get(m).copied().unwrap_or_else(|| {
                let depth = -self.shader.interior_depth();
                self.shader.shade(depth, Vec2::ZERO, Some(base), colors.sky)
            }),
        }
    }
}

fn rgba(rgb: [u8; 3]) -> [u8; 4] {
    [rgb[0], rgb[1], rgb[2], 255]
}
