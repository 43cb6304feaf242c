//! What the proofs read, each looked up at most once per frame: a quad's four texels, and
//! per grid cell its slope bound, border error, constant material and events, and per
//! texel its material margin.

use std::sync::OnceLock;

use glam::Vec2;

use crate::lattice::Lattice;
use crate::twin::LowRes;
use crate::twin::upsample::Textures;
use craterfield_field::Grid;
use craterfield_field::terrain::EventDiscs;
use craterfield_field::{MaterialId, Sdf, Terrain};

/// The four texels of one quad as the proof reads them.
pub(super) struct Quad {
    pub(super) centers: [Vec2; 4],
    pub(super) d: [f32; 4],
    pub(super) materials: [MaterialId; 4],
    /// Indices of the texels in the lattice.
    pub(super) texels: [usize; 4],
}

impl Quad {
    pub(super) fn new(tex: &Textures, c: u32, r: u32) -> Quad {
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

/// What the proofs read about one grid cell.
#[derive(Clone, Copy, Debug)]
pub(super) struct CellInfo {
    pub(super) material: Option<MaterialId>,
    pub(super) lipschitz: f32,
    error: f32,
}

/// The slope and border-jump allowance of one quad: the largest over the cells its texel
/// square touches.
#[derive(Clone, Copy, Debug)]
pub(super) struct QuadBounds {
    pub(super) lipschitz: f32,
    pub(super) jump: f32,
}

/// The terrain's grid cells and texel margins as one frame's proofs read them.
pub(super) struct Cells<'a, F: Sdf> {
    pub(super) terrain: &'a Terrain<F>,
    pub(super) grid: &'a Grid,
    /// Texel material margins, computed on first use (only solid blocks in cells of
    /// several materials need them).
    lazy_margins: Vec<OnceLock<f32>>,
    lattice: Lattice,
    cells: Vec<OnceLock<CellInfo>>,
    /// Each cell's events for the sign proofs, read on first use.
    discs: Vec<OnceLock<Option<EventDiscs>>>,
    /// The bounds of points outside the grid (the clamped base, exact).
    outside: CellInfo,
    origin: [f64; 2],
    cell_size: f64,
    /// Cells per row and per column.
    pub(super) dims: [i64; 2],
}

impl<'a, F: Sdf> Cells<'a, F> {
    pub(super) fn new(terrain: &'a Terrain<F>, lowres: &'a LowRes) -> Self {
        let grid = terrain.grid();
        let (nx, ny) = grid.dims();
        Cells {
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
            origin: [f64::from(grid.origin().x), f64::from(grid.origin().y)],
            cell_size: f64::from(grid.cell_size()),
            dims: [i64::from(nx), i64::from(ny)],
        }
    }

    /// The material margin of texel `index` (see [`Terrain::material_margin`]).
    pub(super) fn margin(&self, index: usize) -> f32 {
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
    pub(super) fn margins_computed(&self) -> u64 {
        self.lazy_margins
            .iter()
            .filter(|m| m.get().is_some())
            .count() as u64
    }

    /// The index of the cell at cell coordinates `(ix, iy)` (inside the grid).
    pub(super) fn index(&self, ix: i64, iy: i64) -> usize {
        (iy * self.dims[0] + ix) as usize
    }

    /// The cell at cell coordinates `(ix, iy)`, computed once per frame; points outside the
    /// grid get [`Cells::outside`].
    pub(super) fn cell(&self, ix: i64, iy: i64) -> CellInfo {
        let inside = (0..self.dims[0]).contains(&ix) && (0..self.dims[1]).contains(&iy);
        if !inside {
            return self.outside;
        }
        let index = self.index(ix, iy);
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

    /// The constant material of the grid cell holding `p`, if it has one.
    pub(super) fn material_at(&self, p: Vec2) -> Option<MaterialId> {
        let cell = self.grid.cell_index(p)?;
        let (nx, _) = self.grid.dims();
        let (ix, iy) = (cell % nx as usize, cell / nx as usize);
        self.cell(ix as i64, iy as i64).material
    }

    /// The events of cell `cell` as the sign proof reads them, read once per frame.
    pub(super) fn discs(&self, cell: usize) -> Option<&EventDiscs> {
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
    pub(super) fn cell_span(&self, lo: f32, hi: f32, axis: usize) -> (i64, i64) {
        let pad = 1.0e-2 + 1.0e-6 * lo.abs().max(hi.abs());
        (
            self.cell_coord(lo - pad, axis),
            self.cell_coord(hi + pad, axis),
        )
    }

    /// The bounds of the quad whose texel square is `quad.centers`.
    pub(super) fn quad_bounds(&self, quad: &Quad) -> QuadBounds {
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
}
