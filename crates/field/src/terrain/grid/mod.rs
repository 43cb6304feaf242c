//! The explosion grid: a regular grid of cells, each with a base state and the list of the
//! events that can reach it, plus the bricks (baked lattices) that bound a cell's list.
//!
//! This module is storage, geometry and the undo journal; what the states mean and when
//! lists are pruned or baked is decided by [`crate::terrain`]. The grid is the journal's one
//! owner: its cells, counters and journal are private, the terrain reads them through
//! accessors and changes them only through the methods of `changes`, which record each
//! pre-image before they mutate.
//!
//! Geometry predicates (disc touches cell, disc contains cell) are evaluated in `f64` with a
//! guard that covers the `f32` rounding of the query path, so they are conservative for
//! every `f32` query point that the `f32` cell lookup assigns to the cell.

use crate::sample::MaterialId;
use craterfield_core::det::math::{Num, V2, nclamp};
use glam::Vec2;
use thiserror::Error;

mod cell;
mod changes;
mod flats;
mod floors;
mod journal;
mod list;
mod lows;

pub(crate) use cell::{Brick, Cell, CellStateSlot, PartialBake};
pub use cell::{CellState, GridStats, MaterialSource};
pub(crate) use flats::{ALL_SQUARES, CellFlats, FLAT_SIDE, Flats, square_bit};
pub(crate) use floors::FloorGrid;
pub(in crate::terrain) use journal::Entry;
use journal::Journal;
pub use journal::{RollbackError, TerrainMark};
pub(crate) use list::DISC_LANES;
pub(crate) use list::{EventList, Listed};
pub(crate) use lows::CellLows;

/// Most cells a grid may have, so that memory stays bounded.
pub const MAX_CELLS: u64 = 4_000_000;

/// Largest accepted brick resolution (lattice intervals per cell side).
pub const MAX_BRICK_RESOLUTION: u32 = 256;

/// Why a grid could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum GridError {
    /// The grid would have too many cells.
    #[error("grid would have {cells} cells ({nx} x {ny}); at most {MAX_CELLS} are allowed")]
    TooManyCells {
        /// Requested total.
        cells: f64,
        /// Columns.
        nx: f64,
        /// Rows.
        ny: f64,
    },
    /// The cell size is not a positive finite number.
    #[error("grid cell size must be positive and finite, got {value}")]
    BadCellSize {
        /// The offending size.
        value: f32,
    },
    /// The brick resolution is 0 or too large.
    #[error("brick resolution must be in 1..={MAX_BRICK_RESOLUTION}, got {value}")]
    BadBrickResolution {
        /// The offending resolution.
        value: u32,
    },
}

/// The grid's geometry as [`Grid::cell_index`] uses it (see [`Grid::lookup`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lookup {
    pub(crate) origin: Vec2,
    /// `1 / cell_size` when that is exact (see `Grid::inv_pow2`).
    pub(crate) inv_pow2: Option<f32>,
    pub(crate) cell_size: f32,
    pub(crate) nx: u32,
    pub(crate) ny: u32,
}

/// An axis-aligned rectangle in `f64`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rect {
    pub(crate) min: [f64; 2],
    pub(crate) max: [f64; 2],
}

impl Rect {
    /// Largest coordinate magnitude.
    fn extent(&self) -> f64 {
        self.min[0].abs().max(self.max[0].abs()) + self.min[1].abs().max(self.max[1].abs())
    }
    /// Distance from `c` to the nearest point of the rectangle (0 inside).
    pub(crate) fn near_dist(&self, c: [f64; 2]) -> f64 {
        self.near_dist_squared(c).sqrt()
    }
    /// The square of [`Rect::near_dist`], before its root.
    fn near_dist_squared(&self, c: [f64; 2]) -> f64 {
        let dx = (self.min[0] - c[0]).max(0.0).max(c[0] - self.max[0]);
        let dy = (self.min[1] - c[1]).max(0.0).max(c[1] - self.max[1]);
        dx * dx + dy * dy
    }
    /// `self.near_dist(c) <= limit`, the same decision, with the square root taken only
    /// where the squares are too close to tell: `sqrt` rounds correctly, so a squared
    /// distance below `limit^2` by more than the rounding of the squares (`2^-50` of them
    /// here, against `2^-52`) has its root at most `limit`, and one above it by as much has
    /// its root above `limit` by more than half an ulp.
    pub(crate) fn near_dist_at_most(&self, c: [f64; 2], limit: f64) -> bool {
        let d2 = self.near_dist_squared(c);
        let l2 = limit * limit;
        const MARGIN: f64 = 1.0 / (1u64 << 50) as f64;
        // A negative, NaN, infinite or tiny limit takes the root.
        let squares_decide = limit >= 0.0 && l2.is_normal();
        if squares_decide && d2 < l2 * (1.0 - MARGIN) {
            true
        } else if squares_decide && d2 > l2 * (1.0 + MARGIN) {
            false
        } else {
            d2.sqrt() <= limit
        }
    }
    /// Distance from `c` to the farthest corner.
    pub(crate) fn far_dist(&self, c: [f64; 2]) -> f64 {
        let dx = (c[0] - self.min[0]).abs().max((c[0] - self.max[0]).abs());
        let dy = (c[1] - self.min[1]).abs().max((c[1] - self.max[1]).abs());
        (dx * dx + dy * dy).sqrt()
    }
}

/// The guard added to geometric tests so they hold for every `f32` evaluation: it bounds the
/// rounding of `|p - c| - r` in `f32` (relative error a few `2^-24` of the magnitudes
/// involved) and the rounding of the `f32` cell lookup, with a wide margin.
/// `event_extent` is `|cx| + |cy| + r + k + M` of the event(s) involved.
pub(crate) fn guard(event_extent: f64, rect: &Rect) -> f64 {
    1.0 / 64.0 + (event_extent + rect.extent()) * (1.0 / 65536.0)
}

/// One cell as a reader sees it (a mirror of the grid, such as the GPU renderer's, or a
/// tool): its state, the events that can reach it and its revision. The grid's storage stays
/// private to the terrain, which alone changes it.
#[derive(Clone, Copy, Debug)]
pub struct CellView<'g> {
    cell: &'g Cell,
}

impl<'g> CellView<'g> {
    /// The cell's field before its listed events are applied.
    pub fn state(&self) -> CellState {
        self.cell.state.0
    }

    /// Indices into the terrain's event log, ascending, of the events that can reach it.
    pub fn events(&self) -> &'g [u32] {
        &self.cell.events
    }

    /// Changes whenever the cell's field may change, and is never given to other content of
    /// any cell of the terrain: a mirror that remembers the revision it sent knows whether
    /// the cell changed since, without comparing contents.
    pub fn revision(&self) -> u64 {
        self.cell.revision
    }
}

/// The grid: geometry, cells and bricks.
#[derive(Clone, Debug)]
pub struct Grid {
    origin: Vec2,
    cell_size: f32,
    /// `1 / cell_size` when the cell size is a power of two (the reciprocal is exact).
    inv_pow2: Option<f32>,
    nx: u32,
    ny: u32,
    resolution: u32,
    cells: Vec<Cell>,
    /// Each cell's lower bound for ray walks, forgotten by every edit of the cell.
    lows: CellLows,
    /// Each cell's squares flat at the band, forgotten with `lows`.
    flats: CellFlats,
    bricks: Vec<Brick>,
    free_bricks: Vec<u32>,
    stats: GridStats,
    /// The undo journal, when rollback is enabled.
    journal: Option<Journal>,
    /// The cell whose change last recorded a pre-image: the one cell the change's further
    /// edits may touch (checked in debug builds; see `changes`).
    recorded_cell: Option<usize>,
}

impl Grid {
    /// Columns and rows of a grid covering `[min, max]` (rounded outwards to whole cells),
    /// checked against the limits without allocating anything.
    pub(crate) fn dims_for(
        min: Vec2,
        max: Vec2,
        cell_size: f32,
        resolution: u32,
    ) -> Result<(u32, u32), GridError> {
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(GridError::BadCellSize { value: cell_size });
        }
        if resolution == 0 || resolution > MAX_BRICK_RESOLUTION {
            return Err(GridError::BadBrickResolution { value: resolution });
        }
        let s = f64::from(cell_size);
        let nx = ((f64::from(max.x) - f64::from(min.x)) / s).ceil().max(1.0);
        let ny = ((f64::from(max.y) - f64::from(min.y)) / s).ceil().max(1.0);
        let cells = nx * ny;
        if cells.is_nan() || cells > MAX_CELLS as f64 {
            return Err(GridError::TooManyCells { cells, nx, ny });
        }
        Ok((nx as u32, ny as u32))
    }

    /// A grid of `Base` cells covering `[min, max]` (rounded outwards to whole cells).
    pub(crate) fn new(
        min: Vec2,
        max: Vec2,
        cell_size: f32,
        resolution: u32,
    ) -> Result<Grid, GridError> {
        let (nx, ny) = Grid::dims_for(min, max, cell_size, resolution)?;
        let inv = 1.0 / cell_size;
        let exact =
            cell_size.to_bits() & 0x007f_ffff == 0 && inv.is_normal() && inv * cell_size == 1.0;
        Ok(Grid {
            origin: min,
            cell_size,
            inv_pow2: exact.then_some(inv),
            nx,
            ny,
            resolution,
            cells: vec![Cell::default(); nx as usize * ny as usize],
            lows: CellLows::new(nx as usize * ny as usize),
            flats: CellFlats::new(nx as usize * ny as usize),
            bricks: Vec::new(),
            free_bricks: Vec::new(),
            stats: GridStats::default(),
            journal: None,
            recorded_cell: None,
        })
    }

    /// Columns and rows.
    pub fn dims(&self) -> (u32, u32) {
        (self.nx, self.ny)
    }

    /// Lower-left corner of the grid.
    pub fn origin(&self) -> Vec2 {
        self.origin
    }

    /// Side length of a cell.
    pub fn cell_size(&self) -> f32 {
        self.cell_size
    }

    /// The cell holding `p`, or `None` outside the grid (and for NaN).
    #[inline]
    pub fn cell_index(&self, p: Vec2) -> Option<usize> {
        let (_, (ix, iy)) = self.cell_quotients(p)?;
        Some(iy as usize * self.nx as usize + ix as usize)
    }

    /// `p`'s coordinates in cells from the origin, and the column and row of its cell;
    /// `None` outside the grid (and for NaN).
    #[inline]
    fn cell_quotients(&self, p: Vec2) -> Option<((f32, f32), (u32, u32))> {
        let (fx, fy) = match self.inv_pow2 {
            // Dividing by a power of two and multiplying by its (exact) reciprocal round
            // the same exact quotient: the same bits, without a division.
            Some(inv) => ((p.x - self.origin.x) * inv, (p.y - self.origin.y) * inv),
            None => (
                (p.x - self.origin.x) / self.cell_size,
                (p.y - self.origin.y) / self.cell_size,
            ),
        };
        if !(fx >= 0.0 && fx < self.nx as f32 && fy >= 0.0 && fy < self.ny as f32) {
            return None;
        }
        // Non-negative and below nx, ny (exact in f32, both < 2^24): the casts floor.
        let ix = (fx as u32).min(self.nx - 1);
        let iy = (fy as u32).min(self.ny - 1);
        Some(((fx, fy), (ix, iy)))
    }

    /// [`Grid::cell_index`], and the bit of the square of the cell's [`FLAT_SIDE`] split
    /// that holds `p` (from the same quotients: the square's real bounds hold `p` up to
    /// their rounding, which every proof of a square's flatness pads).
    #[inline]
    pub(crate) fn cell_and_square(&self, p: Vec2) -> Option<(usize, u64)> {
        let ((fx, fy), (ix, iy)) = self.cell_quotients(p)?;
        // In [0, 1] up to rounding (exact where the cell size is a power of two): the
        // casts floor, the minimum keeps the last square.
        let side = FLAT_SIDE as f32;
        let sx = (((fx - ix as f32) * side) as u32).min(FLAT_SIDE - 1);
        let sy = (((fy - iy as f32) * side) as u32).min(FLAT_SIDE - 1);
        let cell = iy as usize * self.nx as usize + ix as usize;
        Some((cell, square_bit(sx, sy)))
    }

    /// What [`Grid::cell_index`] computes with, for the same lookup on lanes.
    pub(crate) fn lookup(&self) -> Lookup {
        Lookup {
            origin: self.origin,
            inv_pow2: self.inv_pow2,
            cell_size: self.cell_size,
            nx: self.nx,
            ny: self.ny,
        }
    }

    /// Column and row of cell `i`.
    fn coords(&self, i: usize) -> (u32, u32) {
        let nx = self.nx as usize;
        ((i % nx) as u32, (i / nx) as u32)
    }

    /// Lower-left corner of cell `i` in `f32`, as the brick lattice uses it.
    pub(crate) fn cell_min_f32(&self, i: usize) -> Vec2 {
        let (ix, iy) = self.coords(i);
        Vec2::new(
            self.origin.x + ix as f32 * self.cell_size,
            self.origin.y + iy as f32 * self.cell_size,
        )
    }

    /// The rectangle of cell `i` in `f64`.
    pub(crate) fn cell_rect(&self, i: usize) -> Rect {
        let (ix, iy) = self.coords(i);
        self.rect_at(ix, iy)
    }

    /// The rectangle of the cell in column `ix`, row `iy`.
    fn rect_at(&self, ix: u32, iy: u32) -> Rect {
        let s = f64::from(self.cell_size);
        let x0 = f64::from(self.origin.x) + f64::from(ix) * s;
        let y0 = f64::from(self.origin.y) + f64::from(iy) * s;
        Rect {
            min: [x0, y0],
            max: [x0 + s, y0 + s],
        }
    }

    /// Cells whose rectangle is within `reach` (plus the guard) of `center`, in ascending
    /// index order.
    pub(crate) fn cells_touching(
        &self,
        center: [f64; 2],
        reach: f64,
        event_extent: f64,
    ) -> Vec<usize> {
        let s = f64::from(self.cell_size);
        let pad = reach + 1.0 + (event_extent + 4.0 * s) / 1024.0;
        let lo = |c: f64, o: f32| ((c - pad - f64::from(o)) / s).floor();
        let hi = |c: f64, o: f32| ((c + pad - f64::from(o)) / s).floor();
        let x0 = lo(center[0], self.origin.x).max(0.0);
        let y0 = lo(center[1], self.origin.y).max(0.0);
        let x1 = hi(center[0], self.origin.x).min(f64::from(self.nx) - 1.0);
        let y1 = hi(center[1], self.origin.y).min(f64::from(self.ny) - 1.0);
        if !(x0 <= x1 && y0 <= y1) {
            return Vec::new();
        }
        let mut out = Vec::with_capacity(((x1 - x0 + 1.0) * (y1 - y0 + 1.0)) as usize);
        for iy in (y0 as u32)..=(y1 as u32) {
            for ix in (x0 as u32)..=(x1 as u32) {
                // From the column and row, not the index: that would divide per cell.
                let rect = self.rect_at(ix, iy);
                if rect.near_dist_at_most(center, reach + 2.0 * guard(event_extent, &rect)) {
                    out.push(iy as usize * self.nx as usize + ix as usize);
                }
            }
        }
        out
    }

    /// Lattice intervals per cell side.
    pub fn brick_resolution(&self) -> u32 {
        self.resolution
    }

    /// Lattice spacing `h = cell_size / n`.
    pub fn brick_spacing(&self) -> f32 {
        self.cell_size / self.resolution as f32
    }

    /// The brick lattice points of rows `rows` of cell `cell`, row by row: point `(i, j)`
    /// is `m + (i h, j h)` in `f32`, `m` the cell's corner and `h` the spacing.
    pub(crate) fn lattice_rows(&self, cell: usize, rows: std::ops::Range<u32>) -> Vec<Vec2> {
        let m = self.cell_min_f32(cell);
        let h = self.brick_spacing();
        let side = self.resolution + 1;
        let mut points = Vec::with_capacity(rows.len() * side as usize);
        for j in rows {
            let y = m.y + j as f32 * h;
            points.extend((0..side).map(|i| Vec2::new(m.x + i as f32 * h, y)));
        }
        points
    }

    /// Every brick slot (freed ones are empty) and the free list, for a state snapshot.
    pub(in crate::terrain) fn brick_slots(&self) -> (&[Brick], &[u32]) {
        (&self.bricks, &self.free_bricks)
    }

    /// Bilinear interpolation of brick `id` at `p` in cell `cell` (its value and gradient),
    /// and, when asked for `material`, the material of the nearest lattice sample (else
    /// 0: a distance query reads no material, which spares it a cache miss). `None` for a
    /// missing brick.
    #[inline]
    pub(crate) fn interpolate<N: Num>(
        &self,
        id: u32,
        cell: usize,
        p: V2<N>,
        material: bool,
    ) -> Option<(N, MaterialId)> {
        let b = self.bricks.get(id as usize)?;
        let n = self.resolution;
        let nf = n as f32;
        let m = self.cell_min_f32(cell);
        let h = N::constant(self.brick_spacing());
        let u = nclamp(p.x.offset(-m.x) / h, 0.0, nf);
        let v = nclamp(p.y.offset(-m.y) / h, 0.0, nf);
        // u, v in [0, n] (NaN clamps to 0): the casts floor and stay in range.
        let i = (u.value() as u32).min(n - 1);
        let j = (v.value() as u32).min(n - 1);
        let fu = u.offset(-(i as f32));
        let fv = v.offset(-(j as f32));
        let row = (n + 1) as usize;
        let at = |i: u32, j: u32| j as usize * row + i as usize;
        let val = |i: u32, j: u32| b.values.get(at(i, j)).copied().unwrap_or(0.0);
        let (v00, v10, v01, v11) = (val(i, j), val(i + 1, j), val(i, j + 1), val(i + 1, j + 1));
        let bottom = fu.scale(v10 - v00).offset(v00);
        let top = fu.scale(v11 - v01).offset(v01);
        let d = (top - bottom) * fv + bottom;
        if !material {
            return Some((d, 0));
        }
        let mi = ((u.value() + 0.5) as u32).min(n);
        let mj = ((v.value() + 0.5) as u32).min(n);
        let mat = b.materials.get(at(mi, mj)).copied().unwrap_or(0);
        Some((d, mat))
    }

    /// The material of the nearest lattice sample of brick `id` at `p` in cell `cell`.
    pub(crate) fn brick_material(&self, id: u32, cell: usize, p: Vec2) -> MaterialId {
        self.interpolate::<f32>(id, cell, V2::new(p.x, p.y), true)
            .map(|(_, m)| m)
            .unwrap_or(0)
    }

    /// The number of cells (`nx * ny`, row-major).
    pub fn cell_count(&self) -> usize {
        self.cells.len()
    }

    /// Cell `i` as stored, for the terrain's own reads (`None` past the end).
    pub(in crate::terrain) fn stored_cell(&self, i: usize) -> Option<&Cell> {
        self.cells.get(i)
    }

    /// The cells' flat squares, as far as computed.
    pub(in crate::terrain) fn cell_flats(&self) -> &CellFlats {
        &self.flats
    }

    /// The cells' lower bounds for ray walks, as far as computed.
    pub(in crate::terrain) fn cell_lows(&self) -> &CellLows {
        &self.lows
    }

    /// Every cell as stored, row-major, for the terrain's own reads.
    pub(in crate::terrain) fn stored_cells(&self) -> &[Cell] {
        &self.cells
    }

    /// The counters the grid keeps itself (resets, bakes, pruned events); the terrain
    /// derives the others.
    pub(in crate::terrain) fn counters(&self) -> GridStats {
        self.stats
    }

    /// Cell `i`, or `None` past the end.
    pub fn cell(&self, i: usize) -> Option<CellView<'_>> {
        self.cells.get(i).map(|cell| CellView { cell })
    }

    /// Every cell, row-major.
    pub fn cells(&self) -> impl ExactSizeIterator<Item = CellView<'_>> {
        self.cells.iter().map(|cell| CellView { cell })
    }

    /// The cells whose revision differs from the one a mirror last saw (`seen[i]` for cell
    /// `i`; a cell without an entry counts as changed): the changes since the mirror's copy.
    pub fn changed_since<'a>(&'a self, seen: &'a [u64]) -> impl Iterator<Item = usize> + 'a {
        self.cells
            .iter()
            .enumerate()
            .filter(move |(i, c)| seen.get(*i) != Some(&c.revision))
            .map(|(i, _)| i)
    }

    /// Brick `id`'s lattice, row-major (y outer), `(resolution + 1)^2` distances and as many
    /// materials; `None` for an id no cell references.
    pub fn brick_samples(&self, id: u32) -> Option<(&[f32], &[MaterialId])> {
        self.brick(id)
            .map(|b| (b.values.as_slice(), b.materials.as_slice()))
    }

    /// Brick `id`, if it exists.
    pub(crate) fn brick(&self, id: u32) -> Option<&Brick> {
        self.bricks.get(id as usize)
    }

    /// Number of live bricks.
    pub(crate) fn live_bricks(&self) -> usize {
        self.bricks.len() - self.free_bricks.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The squared test decides as the root does, on limits at the distance itself, one
    /// ulp either side, and the edge values, over random rectangles and points.
    #[test]
    fn near_dist_at_most_is_the_roots_decision() {
        let mut unit = crate::test_rng::unit_f64(0x9e37_79b9_7f4a_7c15);
        for _ in 0..20_000 {
            let (x0, y0) = (unit() * 4096.0 - 512.0, unit() * 1024.0 - 128.0);
            let rect = Rect {
                min: [x0, y0],
                max: [x0 + 64.0, y0 + 64.0],
            };
            let c = [unit() * 4096.0 - 512.0, unit() * 1024.0 - 128.0];
            let d = rect.near_dist(c);
            let ulp = |x: f64, up: bool| {
                let b = x.to_bits();
                f64::from_bits(if up == (x >= 0.0) {
                    b + 1
                } else {
                    b.saturating_sub(1)
                })
            };
            let limits = [
                d,
                ulp(d, true),
                ulp(d, false),
                d * (1.0 + 1e-15),
                d * (1.0 - 1e-15),
                unit() * 200.0,
                0.0,
                -1.0,
                f64::NAN,
                f64::INFINITY,
                1e-160,
            ];
            for limit in limits {
                assert_eq!(
                    rect.near_dist_at_most(c, limit),
                    d <= limit,
                    "{rect:?} {c:?} limit {limit:e}"
                );
            }
        }
    }

    #[test]
    fn cell_lookup_never_goes_out_of_range() {
        let g = Grid::new(Vec2::new(-10.0, -10.0), Vec2::new(10.0, 30.0), 4.0, 4).unwrap();
        assert_eq!(g.dims(), (5, 10));
        assert_eq!(g.cell_index(Vec2::new(-10.0, -10.0)), Some(0));
        assert_eq!(g.cell_index(Vec2::new(9.999, 29.999)), Some(49));
        for p in [
            Vec2::new(10.0, 0.0),
            Vec2::new(-10.001, 0.0),
            Vec2::new(f32::NAN, 0.0),
            Vec2::new(0.0, f32::INFINITY),
            Vec2::new(f32::NEG_INFINITY, 0.0),
        ] {
            assert_eq!(g.cell_index(p), None, "{p}");
        }
    }

    #[test]
    fn rejects_huge_grids_and_bad_sizes() {
        let e = Grid::new(Vec2::splat(-1e5), Vec2::splat(1e5), 1.0, 4).unwrap_err();
        assert!(e.to_string().contains("cells"), "{e}");
        assert!(
            Grid::new(Vec2::ZERO, Vec2::ONE, f32::NAN, 4)
                .unwrap_err()
                .to_string()
                .contains("NaN")
        );
        assert!(Grid::new(Vec2::ZERO, Vec2::ONE, 1.0, 0).is_err());
    }

    #[test]
    fn touching_cells_are_conservative() {
        let g = Grid::new(Vec2::ZERO, Vec2::splat(64.0), 8.0, 4).unwrap();
        let hit = g.cells_touching([32.0, 32.0], 4.0, 100.0);
        // The disc of radius 4 at a corner shared by four cells touches all four.
        assert_eq!(hit.len(), 4);
        let hit = g.cells_touching([-100.0, 32.0], 4.0, 100.0);
        assert!(hit.is_empty());
    }

    /// `sum_i w_i |p - q_i|` over the unit square peaks at the centre, at `1/sqrt(2)`: the
    /// bilinear error bound `L h / sqrt(2)` relies on it.
    #[test]
    fn bilinear_distance_weight_bound() {
        let mut worst = 0.0f64;
        for a in 0..=100 {
            for b in 0..=100 {
                let (x, y) = (a as f64 / 100.0, b as f64 / 100.0);
                let s = (1.0 - x) * (1.0 - y) * (x * x + y * y).sqrt()
                    + x * (1.0 - y) * ((1.0 - x).powi(2) + y * y).sqrt()
                    + (1.0 - x) * y * (x * x + (1.0 - y).powi(2)).sqrt()
                    + x * y * ((1.0 - x).powi(2) + (1.0 - y).powi(2)).sqrt();
                worst = worst.max(s);
            }
        }
        assert!(worst <= std::f64::consts::FRAC_1_SQRT_2 + 1e-12, "{worst}");
    }
}
