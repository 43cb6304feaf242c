//! Pass 3 in mode `refine`: every `BLOCK x BLOCK` pixel block of a quad is either proven
//! from the quad's four texels and the terrain's events, or evaluated exactly at every
//! pixel centre. `docs/render2d-pipeline.md` ("Refine") states the proof in full.
//!
//! For a block whose pixel centres span the rectangle `B`, with quad texels `k = 0..3`
//! (centres `C_k`, distances `d_k`, materials `m_k`, margins `mu_k`), `L` and `J` the
//! largest slope bound and border-jump allowance over the cells the quad touches
//! ([`Terrain::cell_bounds`]):
//!
//! * `R_k` is the largest distance from `C_k` to a corner of `B` (the farthest point of a
//!   rectangle from any point is a corner); `reach_k = L R_k + J + |d_k| / 1024 + upp / 1000`
//!   (the last two cover the `f16` rounding of `d_k` and the `f32` evaluations).
//! * Every pixel of `B` has its exact distance in `[lo, hi]`, `lo = max_k (d_k - reach_k)`,
//!   `hi = min_k (d_k + reach_k)`; where that decides nothing, the events of the cells `B`
//!   touches may ([`Terrain::rect_sign`]), first for the whole quad, then for the block.
//! * **Sky** when the distance is at least `upp / 2`: every pixel is its row's sky colour.
//! * **Solid** when it is at most `-(outline_px + 1/2) upp` and the material is proven, by
//!   either rule: every grid cell `B` touches has one constant material
//!   ([`Terrain::cell_material`]), and each pixel takes its cell's; or `B` and some `C_k` lie
//!   in one cell and `2 max(L, 1) R_k < mu_k` ([`Terrain::material_margin`]), and every pixel
//!   takes `m_k`. Each pixel is then fully covered with no outline. Blocks deeper than the
//!   interior depth everywhere are shaded from the planes interpolant; the others from exact
//!   samples on the GPU's corner grid (the pixel centres `(BLOCK i, BLOCK j)`), interpolated
//!   bilinearly over each grid square, the distance clamped to `hi`; the pixels of squares
//!   whose corners are creased ([`Prover::creased`]: a hard edge of the exact shade runs
//!   through them) are evaluated instead.
//! * Otherwise **uncertain**: every pixel is sampled with the terrain's batch evaluator and
//!   shaded exactly as [`crate::render_exact`] shades it.
//!
//! Sky and uncertain pixels are the exact render's, bit for bit; solid pixels have its
//! coverage and material, and differ from it only in the depth shade inside the terrain.

use std::ops::Range;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::Vec2;
use image::RgbaImage;
use serde::Serialize;

use super::blocks::{Block, Kernel, Layout, Run, Scratch, pixel_weights, split_row_groups};
use super::shade::{Shader, mix};
use super::threads::run_units;
use super::upsample::{Textures, normal};
use super::{FieldImage, LowRes, TwinError};
use crate::camera::Camera;
use crate::lattice::Lattice;
use crate::options::ShadeOptions;
use craterfield_field::Grid;
use craterfield_field::terrain::{EventDiscs, RectSign};
use craterfield_field::{MaterialId, Sample, Sdf, Terrain};

/// Side of the pixel blocks that are proven or refined, pixels.
pub const BLOCK: usize = 4;

/// Most pixels evaluated per batch call.
const BATCH: usize = 4096;

/// Pixel rows of one unit of work at least (see [`Refiner::band`]).
const UNIT_ROWS: usize = 32;

/// What the `refine` mode did for one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RefineStats {
    /// Pixel blocks classified.
    pub blocks: u64,
    /// Blocks proven all sky.
    pub sky_blocks: u64,
    /// Blocks proven solid, with their materials.
    pub solid_blocks: u64,
    /// Blocks evaluated at every pixel.
    pub refined_blocks: u64,
    /// Pixels of the image.
    pub pixels: u64,
    /// Pixels evaluated exactly.
    pub refined_pixels: u64,
    /// Field evaluations of the frame: pass 1's texels, the material margins computed for
    /// them, the corners of solid blocks shaded from exact samples, and the refined pixels.
    pub exact_evaluations: u64,
}

impl RefineStats {
    /// Refined blocks over all blocks (0 for an empty frame).
    pub fn refined_block_fraction(&self) -> f64 {
        ratio(self.refined_blocks, self.blocks)
    }

    /// Refined pixels over all pixels (0 for an empty frame).
    pub fn refined_pixel_fraction(&self) -> f64 {
        ratio(self.refined_pixels, self.pixels)
    }
}

fn ratio(a: u64, b: u64) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

/// The material proof of a solid block.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Material {
    /// One material for every pixel.
    One(MaterialId),
    /// Each pixel's grid cell has a constant material.
    PerCell,
}

/// What a block is proven to be.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Class {
    Sky {
        lo: f32,
    },
    Solid {
        hi: f32,
        material: Material,
        /// Whether the block reaches depths whose shade depends on the distance: it is then
        /// shaded from exact samples on the corner grid instead of the texels.
        shaded: bool,
    },
    Uncertain,
}

/// What the proofs read about one grid cell.
#[derive(Clone, Copy, Debug)]
struct CellInfo {
    material: Option<MaterialId>,
    lipschitz: f32,
    error: f32,
}

/// The slope and border-jump allowance of one quad: the largest over the cells its texel
/// square touches.
#[derive(Clone, Copy, Debug)]
struct QuadBounds {
    lipschitz: f32,
    jump: f32,
}

/// Everything the proofs of one frame read.
pub(super) struct Prover<'a, F: Sdf> {
    terrain: &'a Terrain<F>,
    grid: &'a Grid,
    /// Texel material margins, computed on first use (only solid blocks in cells of
    /// several materials need them).
    lazy_margins: Vec<OnceLock<f32>>,
    lattice: Lattice,
    cells: Vec<OnceLock<CellInfo>>,
    /// Each cell's events for the sign proofs, read on first use.
    discs: Vec<OnceLock<Option<EventDiscs>>>,
    /// The bounds of points outside the grid (the clamped base, exact).
    outside: CellInfo,
    upp: f32,
    sky_at: f32,
    solid_at: f32,
    /// Deeper than this every solid pixel of a material and row has one colour.
    deep_at: f32,
    /// Shallower than this the shade depends on the normal (the lit rim).
    lit_at: f32,
    origin: [f64; 2],
    cell_size: f64,
    dims: [i64; 2],
    /// Classify nothing: every block is evaluated (the full-resolution direct renderer).
    exact_only: bool,
}

impl<'a, F: Sdf> Prover<'a, F> {
    fn new(terrain: &'a Terrain<F>, lowres: &'a LowRes, upp: f32, shade: &ShadeOptions) -> Self {
        let grid = terrain.grid();
        let (nx, ny) = grid.dims();
        Prover {
            terrain,
            grid,
            lazy_margins: (0..lowres.texels.len()).map(|_| OnceLock::new()).collect(),
            lattice: lowres.lattice,
            cells: (0..nx as usize * ny as usize)
                .map(|_| OnceLock::new())
                .collect(),
            discs: (0..nx as usize * ny as usize)
                .map(|_| OnceLock::new())
                .collect(),
            outside: CellInfo {
                material: None,
                lipschitz: terrain.lipschitz(),
                error: 0.0,
            },
            upp,
            sky_at: 0.5 * upp,
            solid_at: -(shade.outline_px.max(0.0) + 0.5) * upp,
            deep_at: -Shader::new(shade, 1).interior_depth() * upp,
            lit_at: -0.5 * shade.shade_depth_px * upp,
            origin: [f64::from(grid.origin().x), f64::from(grid.origin().y)],
            cell_size: f64::from(grid.cell_size()),
            dims: [i64::from(nx), i64::from(ny)],
            exact_only: false,
        }
    }

    /// The material margin of texel `index` (see [`Terrain::material_margin`]).
    fn margin(&self, index: usize) -> f32 {
        let Some(slot) = self.lazy_margins.get(index) else {
            return 0.0;
        };
        *slot.get_or_init(|| {
            let cols = self.lattice.cols as usize;
            let (c, r) = ((index % cols) as u32, (index / cols) as u32);
            self.terrain
                .material_margin(self.lattice.texel_center(c, r))
        })
    }

    /// Margins computed on demand so far.
    fn margins_computed(&self) -> u64 {
        self.lazy_margins
            .iter()
            .filter(|m| m.get().is_some())
            .count() as u64
    }

    /// The cell at cell coordinates `(ix, iy)`, computed once per frame; points outside the
    /// grid get [`Prover::outside`].
    fn cell(&self, ix: i64, iy: i64) -> CellInfo {
        let inside = (0..self.dims[0]).contains(&ix) && (0..self.dims[1]).contains(&iy);
        if !inside {
            return self.outside;
        }
        let index = (iy * self.dims[0] + ix) as usize;
        let Some(slot) = self.cells.get(index) else {
            return self.outside;
        };
        *slot.get_or_init(|| {
            let bounds = self.terrain.cell_bounds(index);
            CellInfo {
                material: self.terrain.cell_material(index),
                lipschitz: bounds.map_or(f32::INFINITY, |b| b.lipschitz),
                error: bounds.map_or(f32::INFINITY, |b| b.error),
            }
        })
    }

    /// The events of cell `cell` as the sign proof reads them, read once per frame.
    fn discs(&self, cell: usize) -> Option<&EventDiscs> {
        self.discs
            .get(cell)?
            .get_or_init(|| self.terrain.event_discs(cell))
            .as_ref()
    }

    /// Cell coordinate along axis `axis` of world coordinate `v` (not clamped to the grid).
    fn cell_coord(&self, v: f32, axis: usize) -> i64 {
        ((f64::from(v) - self.origin[axis]) / self.cell_size).floor() as i64
    }

    /// The cell range `[lo, hi]` touches along `axis`, padded by a rounding allowance so
    /// that the `f32` cell lookup of any point in it lands inside.
    fn cell_span(&self, lo: f32, hi: f32, axis: usize) -> (i64, i64) {
        let pad = 1.0e-2 + 1.0e-6 * lo.abs().max(hi.abs());
        (
            self.cell_coord(lo - pad, axis),
            self.cell_coord(hi + pad, axis),
        )
    }

    /// The bounds of the quad whose texel square is `quad.centers`.
    fn quad_bounds(&self, quad: &Quad) -> QuadBounds {
        let [c0, _, _, c3] = quad.centers;
        let (x0, x1) = (c0.x.min(c3.x), c0.x.max(c3.x));
        let (y0, y1) = (c0.y.min(c3.y), c0.y.max(c3.y));
        let (ix0, ix1) = self.cell_span(x0, x1, 0);
        let (iy0, iy1) = self.cell_span(y0, y1, 1);
        let (mut lipschitz, mut error) = (0.0f32, 0.0f32);
        for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                let c = self.cell(ix, iy);
                lipschitz = lipschitz.max(c.lipschitz);
                error = error.max(c.error);
            }
        }
        let borders = (ix1 - ix0) + (iy1 - iy0);
        QuadBounds {
            lipschitz,
            jump: 2.0 * error * borders as f32,
        }
    }

    /// The proof of the block with pixel-centre rectangle `rect` (`[x0, y0, x1, y1]`) in
    /// `quad`, whose bounds are `bounds`.
    fn classify(
        &self,
        quad: &Quad,
        bounds: QuadBounds,
        rect: [f32; 4],
        quad_sign: &mut QuadSign,
    ) -> Class {
        if self.exact_only || !(bounds.lipschitz.is_finite() && bounds.jump.is_finite()) {
            return Class::Uncertain;
        }
        let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
        let mut far = [0.0f32; 4];
        for (k, far_k) in far.iter_mut().enumerate() {
            *far_k = farthest_corner(quad.centers[k], rect);
            let d = quad.d[k];
            let reach = bounds.lipschitz * *far_k * (1.0 + 1.0e-5)
                + bounds.jump
                + d.abs() / 1024.0
                + self.upp / 1000.0;
            lo = lo.max(d - reach);
            hi = hi.min(d + reach);
        }
        if lo >= self.sky_at {
            return Class::Sky { lo };
        }
        let solid = matches!(
            hi.partial_cmp(&self.solid_at),
            Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
        );
        if !solid {
            let whole = *quad_sign.get_or_insert_with(|| self.event_sign(quad_sign_rect(quad)));
            let sign = match whole {
                RectSign::Unknown => self.event_sign(rect),
                proven => proven,
            };
            match sign {
                RectSign::Above => return Class::Sky { lo: self.sky_at },
                RectSign::Below => hi = self.solid_at,
                RectSign::Unknown => return Class::Uncertain,
            }
        }
        match self.material(quad, rect, far) {
            Some(material) => Class::Solid {
                hi,
                material,
                shaded: hi > self.deep_at,
            },
            None => Class::Uncertain,
        }
    }

    /// What the events of the cells `rect` touches force over it (all must agree).
    fn event_sign(&self, rect: [f32; 4]) -> RectSign {
        let [x0, y0, x1, y1] = rect;
        let (ix0, ix1) = self.cell_span(x0, x1, 0);
        let (iy0, iy1) = self.cell_span(y0, y1, 1);
        let inside = ix0 >= 0 && iy0 >= 0 && ix1 < self.dims[0] && iy1 < self.dims[1];
        let band = self.terrain.options().band;
        if !inside || self.sky_at > band || self.solid_at < -band {
            return RectSign::Unknown;
        }
        let (min, max) = (Vec2::new(x0, y0), Vec2::new(x1, y1));
        let mut agreed = None;
        for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                let cell = (iy * self.dims[0] + ix) as usize;
                let sign = match self.discs(cell) {
                    Some(discs) => {
                        self.terrain
                            .rect_sign_of(discs, min, max, self.sky_at, self.solid_at)
                    }
                    None => RectSign::Unknown,
                };
                match (sign, agreed) {
                    (RectSign::Unknown, _) => return RectSign::Unknown,
                    (s, Some(a)) if s != a => return RectSign::Unknown,
                    (s, _) => agreed = Some(s),
                }
            }
        }
        agreed.unwrap_or(RectSign::Unknown)
    }

    /// The material proof of a block (see the module doc); `far[k]` is the largest distance
    /// from texel `k` to the block.
    fn material(&self, quad: &Quad, rect: [f32; 4], far: [f32; 4]) -> Option<Material> {
        let [x0, y0, x1, y1] = rect;
        let (ix0, ix1) = self.cell_span(x0, x1, 0);
        let (iy0, iy1) = self.cell_span(y0, y1, 1);
        let mut first = None;
        let mut all_same = true;
        let mut all_constant = true;
        'cells: for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                match (self.cell(ix, iy).material, first) {
                    (None, _) => {
                        all_constant = false;
                        break 'cells;
                    }
                    (Some(m), None) => first = Some(m),
                    (Some(m), Some(f)) => all_same &= m == f,
                }
            }
        }
        if all_constant {
            return Some(match first {
                Some(m) if all_same => Material::One(m),
                _ => Material::PerCell,
            });
        }
        if ix0 != ix1 || iy0 != iy1 {
            return None;
        }
        let cell = self.cell(ix0, iy0);
        let index = (iy0 * self.dims[0] + ix0) as usize;
        // The margin's switch functions have slope at most `L + 1`.
        let slope = cell.lipschitz.max(1.0) * 2.0;
        (0..4).find_map(|k| {
            let c = quad.centers[k];
            let same_cell = self.cell_span(c.x, c.x, 0) == (ix0, ix0)
                && self.cell_span(c.y, c.y, 1) == (iy0, iy0)
                && self.grid.cell_index(c) == Some(index);
            let needed = slope * far[k] * (1.0 + 1.0e-5) + self.upp / 1000.0;
            (same_cell && needed < self.margin(quad.texels[k]))
                .then_some(Material::One(quad.materials[k]))
        })
    }

    /// The material of pixel `p` of a block proven with `material` (`None`: the cell lookup
    /// disagreed with the proof, so the pixel is evaluated instead).
    fn pixel_material(&self, material: Material, p: Vec2) -> Option<MaterialId> {
        match material {
            Material::One(m) => Some(m),
            Material::PerCell => {
                let cell = self.grid.cell_index(p)?;
                let (nx, _) = self.grid.dims();
                let (ix, iy) = (cell % nx as usize, cell / nx as usize);
                self.cell(ix as i64, iy as i64).material
            }
        }
    }
}

impl<F: Sdf> Prover<'_, F> {
    /// Whether a grid square with the exact samples `s` at its corners must be evaluated
    /// rather than interpolated: some corner lies in the lit rim and two corners' normals
    /// differ by more than [`CREASE`]. The interpolant is smooth, the exact shade is not
    /// where the normal jumps: at the contour where the distance reaches its clamp `-M`
    /// (past it the gradient is zero, so zoomed out, where the band is shallower than the
    /// rim, the rim stops there with a hard edge) and along creases (where the nearest
    /// surface changes, e.g. under the peak between two craters). Interpolated across, such
    /// edges become steps along the squares.
    fn creased(&self, s: &[Sample; 4]) -> bool {
        if !s.iter().any(|s| s.distance > self.lit_at) {
            return false;
        }
        let n = s.map(|s| s.gradient.normalize_or_zero());
        (0..4).any(|a| (a + 1..4).any(|b| (n[a] - n[b]).length_squared() > CREASE * CREASE))
    }
}

/// The largest difference between the unit normals (zero where the gradient is) at the
/// corners of a grid square that is interpolated: about 23 degrees, so that the lit term
/// `0.35 dot(n, light)` of an interpolated pixel is within about 7% of the base colour.
const CREASE: f32 = 0.4;

/// The distance from `c` to the farthest corner of `rect` (`[x0, y0, x1, y1]`): the corner
/// with the larger offset on each axis, whose rounded distance is also the largest of the
/// four corners' rounded distances (squares and sums round monotonically).
fn farthest_corner(c: Vec2, rect: [f32; 4]) -> f32 {
    let [x0, y0, x1, y1] = rect;
    let dx = (x0 - c.x).abs().max((x1 - c.x).abs());
    let dy = (y0 - c.y).abs().max((y1 - c.y).abs());
    (dx * dx + dy * dy).sqrt()
}

/// The event sign of a whole quad, computed once the first block needs it.
type QuadSign = Option<RectSign>;

/// The rectangle of a quad's texel square (it holds every pixel centre of the quad).
fn quad_sign_rect(quad: &Quad) -> [f32; 4] {
    let [c0, _, _, c3] = quad.centers;
    [
        c0.x.min(c3.x),
        c0.y.min(c3.y),
        c0.x.max(c3.x),
        c0.y.max(c3.y),
    ]
}

/// The four texels of one quad as the proof reads them.
struct Quad {
    centers: [Vec2; 4],
    d: [f32; 4],
    materials: [MaterialId; 4],
    /// Indices of the texels in the lattice.
    texels: [usize; 4],
}

impl Quad {
    fn new(tex: &Textures, c: u32, r: u32) -> Quad {
        let texels = tex.quad(c, r);
        let cols = tex.lattice.cols as usize;
        let at = |dc: u32, dr: u32| (r + dr) as usize * cols + (c + dc) as usize;
        let idx = [at(0, 0), at(1, 0), at(0, 1), at(1, 1)];
        Quad {
            centers: tex.quad_centers(c, r),
            d: texels.map(|t| t.d),
            materials: texels.map(|t| t.material),
            texels: idx,
        }
    }
}

/// Where the pixels of a refined frame go: an RGBA image or a field image.
trait Sink {
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

/// A thread's buffers.
#[derive(Default)]
struct RefineScratch {
    blocks: Scratch,
    classes: Vec<Class>,
    /// The pixel columns of each block of the current quad.
    col_blocks: Vec<Range<usize>>,
    tally: Tally,
    /// The first image row of the unit being drawn: sink rows count from it.
    base: usize,
    points: Vec<Vec2>,
    pixels: Vec<(usize, usize)>,
    samples: Vec<Sample>,
    /// Solid blocks shaded from exact corner samples, and those samples' points.
    deferred: Vec<Deferred>,
    corners: Vec<Vec2>,
    corner_samples: Vec<Sample>,
    /// The corner grid of the unit: which of `corners` each grid point is.
    grid: CornerGrid,
}

/// A solid block shaded from the exact samples on the corner grid.
struct Deferred {
    xs: Range<usize>,
    /// Rows relative to the unit's first.
    rows: Range<usize>,
    /// The first image row.
    y0: usize,
    hi: f32,
    material: Material,
}

/// The corner grid of one unit of work: the pixel centres `(BLOCK i, BLOCK j)`, the
/// corners of the `BLOCK x BLOCK` squares aligned with the image (the GPU's blocks,
/// `shaders/refine_corners.wgsl`), each sampled at most once per unit.
#[derive(Default)]
struct CornerGrid {
    /// The first grid row (`j`) of the unit.
    j0: usize,
    /// Grid points per row (`i = 0..cols`).
    cols: usize,
    /// Index in `RefineScratch::corners` per grid point, `u32::MAX` when not sampled.
    slots: Vec<u32>,
}

impl CornerGrid {
    /// An empty grid for image rows `rows` of an image `width` pixels wide.
    fn reset(&mut self, rows: Range<usize>, width: usize) {
        self.j0 = rows.start / BLOCK;
        let j1 = rows.end.saturating_sub(1) / BLOCK + 1;
        self.cols = width.saturating_sub(1) / BLOCK + 2;
        self.slots.clear();
        self.slots.resize((j1 - self.j0 + 1) * self.cols, u32::MAX);
    }

    fn slot(&self, i: usize, j: usize) -> usize {
        (j - self.j0) * self.cols + i
    }
}

/// Class counts of one unit of work, added to [`Counters`] when the unit is done.
#[derive(Clone, Copy, Default)]
struct Tally {
    blocks: u64,
    sky: u64,
    solid: u64,
    refined: u64,
    refined_pixels: u64,
}

/// Class counts, summed over threads.
#[derive(Default)]
struct Counters {
    blocks: AtomicU64,
    sky: AtomicU64,
    solid: AtomicU64,
    refined: AtomicU64,
    refined_pixels: AtomicU64,
    corners: AtomicU64,
}

/// One frame's refine pass.
struct Refiner<'a, F: Sdf> {
    prover: Prover<'a, F>,
    tex: &'a Textures<'a>,
    layout: &'a Layout,
    /// The frame's camera (the corner grid's points lie also past the image's edge).
    camera: Camera,
    counters: Counters,
}

impl<'a, F: Sdf + Sync> Refiner<'a, F> {
    /// The refine pass of one frame (`exact_only`: prove nothing, evaluate every block).
    fn new(
        terrain: &'a Terrain<F>,
        lowres: &'a LowRes,
        tex: &'a Textures<'a>,
        layout: &'a Layout,
        camera: &Camera,
        shade: &ShadeOptions,
        exact_only: bool,
    ) -> Self {
        let mut prover = Prover::new(terrain, lowres, camera.units_per_pixel, shade);
        prover.exact_only = exact_only;
        Refiner {
            prover,
            tex,
            layout,
            camera: *camera,
            counters: Counters::default(),
        }
    }

    /// Classifies and draws the consecutive quad rows `bands` (one unit of work). The exact
    /// evaluations of the whole unit go to the batch evaluator together: a quad row alone
    /// holds a few uncertain pixels per grid cell, too few to fill the SIMD lanes of one
    /// cell's pass.
    fn band<S: Sink>(
        &self,
        scratch: &mut RefineScratch,
        bands: &[Run],
        sink: &mut S,
    ) -> Result<(), TwinError> {
        scratch.points.clear();
        scratch.pixels.clear();
        scratch.deferred.clear();
        scratch.corners.clear();
        scratch.base = bands.first().map_or(0, |b| b.pixels.start);
        let end = bands.last().map_or(0, |b| b.pixels.end);
        let width = self.layout.columns.world.len();
        scratch
            .grid
            .reset(scratch.base..end.max(scratch.base), width);
        for rows in bands {
            for columns in &self.layout.columns.runs {
                let block = Block::at(columns, rows);
                self.quad(scratch, block, sink);
            }
        }
        self.draw_deferred(scratch, sink)?;
        self.flush(&mut scratch.tally);
        self.evaluate(scratch, sink)
    }

    /// Classifies the blocks of one quad, draws the proven ones and queues the others.
    fn quad<S: Sink>(&self, scratch: &mut RefineScratch, block: Block, sink: &mut S) {
        let layout = self.layout;
        let quad = Quad::new(self.tex, block.c, block.r);
        let bounds = self.prover.quad_bounds(&quad);
        let (xs, ys) = (block.xs.clone(), block.ys.clone());
        let mut col_blocks = std::mem::take(&mut scratch.col_blocks);
        col_blocks.clear();
        col_blocks.extend(chunks(xs.clone()));
        scratch.classes.clear();
        // A quad of one block proves its signs over the block alone: the quad-wide sign
        // would walk the same events over nearly the same rectangle first.
        let single = col_blocks.len() == 1 && ys.len() <= BLOCK;
        let mut quad_sign = single.then_some(RectSign::Unknown);
        for by in chunks(ys.clone()) {
            let (ya, yb) = (layout.rows.world[by.start], layout.rows.world[by.end - 1]);
            for bx in &col_blocks {
                let (x0, x1) = (
                    layout.columns.world[bx.start],
                    layout.columns.world[bx.end - 1],
                );
                let rect = [x0, ya.min(yb), x1, ya.max(yb)];
                scratch
                    .classes
                    .push(self.prover.classify(&quad, bounds, rect, &mut quad_sign));
            }
        }
        Self::count(&mut scratch.tally, &scratch.classes, &col_blocks, ys.len());
        let interpolated = |c: &Class| match c {
            Class::Sky { .. } => S::VALUES,
            Class::Solid { shaded, .. } => !shaded && S::VALUES,
            Class::Uncertain => false,
        };
        let kernel = Kernel::new(self.tex, block);
        if scratch.classes.iter().any(interpolated) {
            kernel.prepare(self.tex, layout, &mut scratch.blocks);
        }
        let per_row = col_blocks.len();
        let classes = std::mem::take(&mut scratch.classes);
        for (local, y) in ys.clone().enumerate() {
            let row = (local / BLOCK) * per_row..(local / BLOCK + 1) * per_row;
            // The sink's row: rows count from the first of the unit.
            let yi = y - scratch.base;
            if classes[row.clone()].iter().any(interpolated) {
                kernel.row(layout, y, &mut scratch.blocks);
            }
            for (bx, &class) in col_blocks.iter().zip(&classes[row]) {
                // Sky of an image is already filled, and shaded solid blocks are drawn
                // later from their corners: no pixel of theirs to visit here.
                let visit = match class {
                    Class::Sky { .. } => S::VALUES,
                    Class::Solid { shaded, .. } => !shaded,
                    Class::Uncertain => true,
                };
                if !visit {
                    continue;
                }
                if let Class::Solid {
                    material: Material::One(m),
                    ..
                } = class
                    && !S::VALUES
                {
                    sink.deep(bx.clone(), yi, m);
                    continue;
                }
                for x in bx.clone() {
                    let i = x - xs.start;
                    let p = Vec2::new(layout.columns.world[x], layout.rows.world[y]);
                    match class {
                        Class::Sky { lo } if S::VALUES => {
                            let d = scratch.blocks.dist[i].max(lo);
                            let n = normal(&kernel.quad, pixel_weights(layout, x, y));
                            sink.proven(x, yi, d, n, kernel.material(layout, x, y));
                        }
                        Class::Sky { .. } => {}
                        Class::Solid { shaded: true, .. } => {}
                        Class::Solid { material, .. } if !S::VALUES => {
                            match self.prover.pixel_material(material, p) {
                                Some(m) => sink.deep(x..x + 1, yi, m),
                                None => queue(scratch, p, x, yi),
                            }
                        }
                        Class::Solid { hi, material, .. } => {
                            match self.prover.pixel_material(material, p) {
                                Some(m) => {
                                    let d = scratch.blocks.dist[i].min(hi);
                                    let n = normal(&kernel.quad, pixel_weights(layout, x, y));
                                    sink.proven(x, yi, d, n, m);
                                }
                                None => queue(scratch, p, x, yi),
                            }
                        }
                        Class::Uncertain => queue(scratch, p, x, yi),
                    }
                }
            }
        }
        self.defer(scratch, &classes, &col_blocks, &ys);
        scratch.classes = classes;
        scratch.col_blocks = col_blocks;
    }

    /// Queues the shaded solid blocks of a quad and the corner points they are drawn from.
    fn defer(
        &self,
        scratch: &mut RefineScratch,
        classes: &[Class],
        col_blocks: &[Range<usize>],
        ys: &Range<usize>,
    ) {
        for (i, class) in classes.iter().enumerate() {
            let &Class::Solid {
                hi,
                material,
                shaded: true,
            } = class
            else {
                continue;
            };
            let xs = col_blocks[i % col_blocks.len()].clone();
            let start = ys.start + (i / col_blocks.len()) * BLOCK;
            let rows_abs = start..(start + BLOCK).min(ys.end);
            // The corners of every grid square the block's pixels fall in.
            for j in rows_abs.start / BLOCK..=(rows_abs.end - 1) / BLOCK + 1 {
                for i in xs.start / BLOCK..=(xs.end - 1) / BLOCK + 1 {
                    let slot = scratch.grid.slot(i, j);
                    if scratch.grid.slots[slot] == u32::MAX {
                        scratch.grid.slots[slot] = scratch.corners.len() as u32;
                        // The pixel centre (BLOCK i, BLOCK j), also past the image's edge.
                        let (x, y) = ((i * BLOCK) as u32, (j * BLOCK) as u32);
                        scratch.corners.push(self.camera.pixel_to_world(x, y));
                    }
                }
            }
            scratch.deferred.push(Deferred {
                xs,
                rows: rows_abs.start - scratch.base..rows_abs.end - scratch.base,
                y0: rows_abs.start,
                hi,
                material,
            });
        }
    }

    /// Samples the deferred blocks' grid corners and draws each pixel by bilinear
    /// interpolation of the exact distances and gradients at the corners of its grid square
    /// (the distance clamped to the proof's bound), as the GPU draws its shaded blocks
    /// (`shaders/refine_draw.wgsl`). Pixels of creased squares ([`Prover::creased`]) and
    /// pixels whose material lookup disagrees are queued for exact evaluation.
    fn draw_deferred<S: Sink>(
        &self,
        scratch: &mut RefineScratch,
        sink: &mut S,
    ) -> Result<(), TwinError> {
        let empty = Sample {
            distance: 0.0,
            gradient: Vec2::ZERO,
            material: 0,
        };
        scratch.corner_samples.clear();
        scratch.corner_samples.resize(scratch.corners.len(), empty);
        for (points, out) in scratch
            .corners
            .chunks(BATCH)
            .zip(scratch.corner_samples.chunks_mut(BATCH))
        {
            self.prover.terrain.samples(points, out)?;
        }
        self.counters
            .corners
            .fetch_add(scratch.corners.len() as u64, Ordering::Relaxed);
        let deferred = std::mem::take(&mut scratch.deferred);
        let grid = std::mem::take(&mut scratch.grid);
        let samples = std::mem::take(&mut scratch.corner_samples);
        let sample = |i: usize, j: usize| samples[grid.slots[grid.slot(i, j)] as usize];
        for b in &deferred {
            let mut creased = 0;
            for (yi, y) in b.rows.clone().zip(b.y0..) {
                let (j, ty) = (y / BLOCK, (y % BLOCK) as f32 / BLOCK as f32);
                // The grid square of the previous pixel, its corner samples and verdict.
                let mut square: Option<(usize, [Sample; 4], bool)> = None;
                for x in b.xs.clone() {
                    let (i, tx) = (x / BLOCK, (x % BLOCK) as f32 / BLOCK as f32);
                    let (s, exact) = match square {
                        Some((at, s, exact)) if at == i => (s, exact),
                        _ => {
                            let s = [
                                sample(i, j),
                                sample(i + 1, j),
                                sample(i, j + 1),
                                sample(i + 1, j + 1),
                            ];
                            let exact = self.prover.creased(&s);
                            square = Some((i, s, exact));
                            (s, exact)
                        }
                    };
                    let p = Vec2::new(self.layout.columns.world[x], self.layout.rows.world[y]);
                    if exact {
                        creased += 1;
                        queue(scratch, p, x, yi);
                        continue;
                    }
                    let v = |s: &Sample| [s.distance, s.gradient.x, s.gradient.y];
                    let (v00, v10, v01, v11) = (v(&s[0]), v(&s[1]), v(&s[2]), v(&s[3]));
                    let [d, gx, gy] = std::array::from_fn(|c| {
                        mix(mix(v00[c], v10[c], tx), mix(v01[c], v11[c], tx), ty)
                    });
                    let g = Vec2::new(gx, gy);
                    match self.prover.pixel_material(b.material, p) {
                        Some(m) => sink.proven(x, yi, d.min(b.hi), g.normalize_or_zero(), m),
                        None => queue(scratch, p, x, yi),
                    }
                }
            }
            if creased > 0 {
                // Evaluated (in part) after all: counted as refined.
                let t = &mut scratch.tally;
                t.solid -= 1;
                t.refined += 1;
                t.refined_pixels += creased;
            }
        }
        scratch.corner_samples = samples;
        scratch.grid = grid;
        scratch.deferred = deferred;
        scratch.deferred.clear();
        scratch.corners.clear();
        Ok(())
    }

    /// Tallies the classes of one quad's blocks into the thread's counts.
    fn count(tally: &mut Tally, classes: &[Class], col_blocks: &[Range<usize>], rows: usize) {
        for (i, class) in classes.iter().enumerate() {
            let (bx, by) = (i % col_blocks.len(), i / col_blocks.len());
            match class {
                Class::Sky { .. } => tally.sky += 1,
                Class::Solid { .. } => tally.solid += 1,
                Class::Uncertain => {
                    let block_rows = (rows - by * BLOCK).min(BLOCK);
                    tally.refined_pixels += (col_blocks[bx].len() * block_rows) as u64;
                    tally.refined += 1;
                }
            }
        }
        tally.blocks += classes.len() as u64;
    }

    /// Adds a unit's tally to the frame's counters (once per unit: per-block atomics
    /// would bounce one cache line between the threads).
    fn flush(&self, tally: &mut Tally) {
        let c = &self.counters;
        let t = std::mem::take(tally);
        for (counter, n) in [
            (&c.blocks, t.blocks),
            (&c.sky, t.sky),
            (&c.solid, t.solid),
            (&c.refined, t.refined),
            (&c.refined_pixels, t.refined_pixels),
        ] {
            counter.fetch_add(n, Ordering::Relaxed);
        }
    }

    /// Samples the queued pixels exactly and hands them to the sink.
    fn evaluate<S: Sink>(
        &self,
        scratch: &mut RefineScratch,
        sink: &mut S,
    ) -> Result<(), TwinError> {
        let empty = Sample {
            distance: 0.0,
            gradient: Vec2::ZERO,
            material: 0,
        };
        for (points, pixels) in scratch
            .points
            .chunks(BATCH)
            .zip(scratch.pixels.chunks(BATCH))
        {
            scratch.samples.clear();
            scratch.samples.resize(points.len(), empty);
            self.prover.terrain.samples(points, &mut scratch.samples)?;
            for (&(x, yi), s) in pixels.iter().zip(&scratch.samples) {
                sink.exact(x, yi, s);
            }
        }
        Ok(())
    }

    fn stats(&self, texels: u64, margins: u64, pixels: u64) -> RefineStats {
        let c = &self.counters;
        let get = |a: &AtomicU64| a.load(Ordering::Relaxed);
        let refined_pixels = get(&c.refined_pixels);
        RefineStats {
            blocks: get(&c.blocks),
            sky_blocks: get(&c.sky),
            solid_blocks: get(&c.solid),
            refined_blocks: get(&c.refined),
            pixels,
            refined_pixels,
            exact_evaluations: texels + margins + refined_pixels + get(&c.corners),
        }
    }
}

fn queue(scratch: &mut RefineScratch, p: Vec2, x: usize, yi: usize) {
    scratch.points.push(p);
    scratch.pixels.push((x, yi));
}

/// `range` cut into runs of at most [`BLOCK`].
fn chunks(range: Range<usize>) -> impl Iterator<Item = Range<usize>> {
    range
        .clone()
        .step_by(BLOCK)
        .map(move |s| s..(s + BLOCK).min(range.end))
}

/// The shaded image of a `refine` frame.
struct ImageSink<'a> {
    bytes: &'a mut [u8],
    width: usize,
    y0: usize,
    shader: &'a Shader,
    palette: &'a [[u8; 3]],
    upp: f32,
    /// Tint refined pixels (the overlay of [`super::render_refine_overlay`]).
    tint: bool,
    /// A distance past the interior depth (world units): the shade of proven deep pixels.
    deep_at: f32,
    /// The last deep colour computed: its band row, material and colour.
    deep_color: Option<(usize, MaterialId, [u8; 3])>,
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
struct FieldSink<'a> {
    d: &'a mut [f32],
    n: &'a mut [Vec2],
    m: &'a mut [MaterialId],
    width: usize,
    upp: f32,
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

/// Pass 3 of mode `refine` into an RGBA image (see the module doc). `lowres` holds the
/// planes pair values.
#[allow(clippy::too_many_arguments)]
pub(super) fn render_refined<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    lowres: &LowRes,
    tex: &Textures,
    layout: &Layout,
    palette: &[[u8; 3]],
    camera: &Camera,
    shade: &ShadeOptions,
    threads: usize,
    exact_only: bool,
    tint: bool,
) -> Result<(RgbaImage, RefineStats), TwinError> {
    let refiner = Refiner::new(terrain, lowres, tex, layout, camera, shade, exact_only);
    let shader = Shader::new(shade, camera.height);
    let width = camera.width as usize;
    let mut image = RgbaImage::new(camera.width, camera.height);
    let units = split_row_groups(&layout.rows.runs, &mut image, width * 4, UNIT_ROWS);
    run_units(
        units,
        threads,
        RefineScratch::default,
        |scratch, (rows, bytes)| {
            let y0 = rows.first().map_or(0, |r| r.pixels.start);
            fill_sky(&shader, bytes, width, y0);
            let mut sink = ImageSink {
                bytes,
                width,
                y0,
                shader: &shader,
                palette,
                upp: camera.units_per_pixel,
                tint,
                deep_at: refiner.prover.deep_at,
                deep_color: None,
            };
            refiner.band(scratch, rows, &mut sink)
        },
    )?;
    let pixels = u64::from(camera.width) * u64::from(camera.height);
    let margin_evals = refiner.prover.margins_computed();
    let stats = refiner.stats(lowres.texels.len() as u64, margin_evals, pixels);
    Ok((image, stats))
}

/// Pass 3 of mode `refine` into a field image (see [`render_refined`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn field_refined<F: Sdf + Sync>(
    terrain: &Terrain<F>,
    lowres: &LowRes,
    tex: &Textures,
    layout: &Layout,
    camera: &Camera,
    shade: &ShadeOptions,
    threads: usize,
    exact_only: bool,
) -> Result<FieldImage, TwinError> {
    let refiner = Refiner::new(terrain, lowres, tex, layout, camera, shade, exact_only);
    let width = camera.width as usize;
    let pixels = width * camera.height as usize;
    let mut field = FieldImage {
        width: camera.width,
        height: camera.height,
        distance_px: vec![0.0; pixels],
        normal: vec![Vec2::ZERO; pixels],
        material: vec![0; pixels],
    };
    let runs = &layout.rows.runs;
    let units: Vec<_> = split_row_groups(runs, &mut field.distance_px, width, UNIT_ROWS)
        .into_iter()
        .zip(split_row_groups(runs, &mut field.normal, width, UNIT_ROWS))
        .zip(split_row_groups(
            runs,
            &mut field.material,
            width,
            UNIT_ROWS,
        ))
        .map(|(((rows, d), (_, n)), (_, m))| (rows, d, n, m))
        .collect();
    run_units(
        units,
        threads,
        RefineScratch::default,
        |scratch, (rows, d, n, m)| {
            let mut sink = FieldSink {
                d,
                n,
                m,
                width,
                upp: camera.units_per_pixel,
            };
            refiner.band(scratch, rows, &mut sink)
        },
    )?;
    Ok(field)
}

/// Fills every row of a band with its sky colour.
fn fill_sky(shader: &Shader, bytes: &mut [u8], width: usize, y0: usize) {
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
