//! What a ray may skip ([`Sdf::clear_run`] for a terrain): inside the grid, the run of
//! cells along the ray whose starting state and events prove the field above the
//! threshold; outside it, where no event reaches, whole halo tiles whose base is bounded
//! above the threshold, else the clearance of the unclamped base, up to the grid's edge.
//!
//! A cell proves its piece of the ray by the sign proof of [`Terrain::rect_sign`], asked
//! about `Above` only, over the whole piece; a brick, which that proof cannot clear (it
//! holds a surface), proves it instead, where its list holds carves alone (each only
//! raises the field), by the floors of its 8x8 blocks and, where a block falls short, by
//! the walk over its lattice squares in closed form (`super::brick_walk`), which ends the
//! run at the surface. (Floors of a base cell's squares, from interval bounds of its
//! tape, measured slower: rays at 0 and 1,000 explosions asked more often for the steps
//! they saved.)
//!
//! A ray cast through a terrain spends most of its sphere-tracing steps crossing air that
//! the clamp to the band holds at `+M`, `M / L` per step; a few proofs per cell replace
//! them, and the march's steps are left for the last stretch before the surface.

use glam::{DVec2, Vec2};

use super::Terrain;
use super::brick_walk::{BrickRun, WalkRay, walk};
use super::cell_tapes::CellTapes;
use super::grid::{Brick, CellState, FloorGrid};
use super::square_walk::{Lattice, SquareWalk};
use crate::sdf::{ClearRun, Sdf};

/// The rounding allowance of the ray's points, on each side of a cell's piece of the ray:
/// the caller computes its points from its own origin, not from `p`.
fn point_slack(p: DVec2) -> f64 {
    1.0e-3 + 1.0e-6 * p.abs().max_element()
}

/// The largest `f32` at most `v` (`v >= 0`, finite).
fn f32_at_most(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        f32::from_bits(f.to_bits() - 1).max(0.0)
    } else {
        f
    }
}

impl<F: Sdf> Terrain<F> {
    /// [`Sdf::clear_run`]: cells proven above `above` inside the grid, the base's clearance
    /// outside it.
    pub(super) fn clear_run_from(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        let band = self.options.band;
        let meaningful = above > 0.0 && above <= band;
        if !(meaningful && p.is_finite() && dir.is_finite()) {
            return ClearRun::NOTHING;
        }
        match self.grid.cell_index(p) {
            Some(cell) => self.clear_cells(cell, p, dir, above),
            None => self.clear_outside(p, dir, above),
        }
    }

    /// Walks the grid's cells from `cell` (holding `p`) along `dir`, cell by cell as the
    /// ray crosses them, while each cell proves its piece of the ray above `above`.
    fn clear_cells(&self, cell: usize, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        let (nx, ny) = self.grid.dims();
        let (p64, d64) = (p.as_dvec2(), dir.as_dvec2());
        let slack = point_slack(p64);
        let (l, band) = (self.lipschitz(), self.options.band);
        let ray = Piece {
            p: p64,
            d: d64,
            slack,
            above,
            walk: WalkRay::new(d64, above, slack, l, band),
        };
        let lattice = Lattice {
            origin: self.grid.origin(),
            size: self.grid.cell_size(),
            nx,
            ny,
        };
        let mut walk = SquareWalk::new(lattice, (cell as u32 % nx, cell as u32 / nx), p64, d64);
        let mut s = 0.0f64;
        loop {
            let (ix, iy) = walk.square();
            let index = iy as usize * nx as usize + ix as usize;
            let exit = walk.exit().max(s);
            let cleared = self.cell_low(index) >= above;
            if !cleared && let Some((from, to)) = self.unproven_piece(index, &ray, s, exit) {
                return ClearRun {
                    clear: f32_at_most(from),
                    retry_after: (to - from) as f32,
                };
            }
            s = exit;
            if !walk.step() || !s.is_finite() {
                // Left the grid: the base alone from here, asked at the next point.
                return ClearRun {
                    clear: f32_at_most(s),
                    retry_after: 0.0,
                };
            }
        }
    }

    /// A lower bound of cell `cell`'s field over the whole cell: its starting range's low
    /// end where the list holds carves alone (which only raise the field), else `-inf`.
    /// A piece of a ray in a cell at least `above` is proven as [`Terrain::rect_above`]
    /// proves it first, without reading the cell: kept in the grid's dense `CellLows`.
    #[inline]
    fn cell_low(&self, cell: usize) -> f32 {
        let lows = self.grid.cell_lows();
        if let Some(low) = lows.get(cell) {
            return low;
        }
        let low = self.uncached_low(cell);
        lows.set(cell, low);
        low
    }

    #[cold]
    fn uncached_low(&self, cell: usize) -> f32 {
        match self.grid.stored_cell(cell) {
            Some(c) if c.lists_carves_only() => self.start_low(cell).unwrap_or(f32::NEG_INFINITY),
            _ => f32::NEG_INFINITY,
        }
    }

    /// Whether cell `cell` proves the ray's piece `[s, exit]` at least the threshold:
    /// `None` when it does, else the first stretch `(start, end)` it does not.
    ///
    /// A brick whose list can only raise the field (carves alone) proves it block by
    /// block of its floors, and lattice square by square where a block falls short; other
    /// cells prove the piece as a whole ([`Terrain::rect_above`]).
    fn unproven_piece(&self, cell: usize, ray: &Piece, s: f64, exit: f64) -> Option<(f64, f64)> {
        let Some(brick) = self.ray_brick(cell) else {
            let (a, b) = (ray.p + ray.d * s, ray.p + ray.d * exit);
            let (min, max) = (a.min(b) - ray.slack, a.max(b) + ray.slack);
            let proven = self.rect_above(cell, min.as_vec2(), max.as_vec2(), ray.above);
            return (!proven).then_some((s, exit));
        };
        let corner = self.grid.cell_min_f32(cell);
        let (n, h) = (self.grid.brick_resolution(), self.grid.brick_spacing());
        let floors = brick.floors(n).over(corner, h);
        let (corner, h) = (corner.as_dvec2(), f64::from(h));
        // Where a block's floor falls short, its lattice squares along the ray.
        let lattice = walk(&ray.walk, &brick.values, n, corner, h, ray.p, ray.d);
        let squares = |t0, t1| match lattice.run(t0..t1) {
            BrickRun::Through => None,
            BrickRun::StopsAt { clear, retry_at } => Some((clear, retry_at)),
        };
        Self::unproven_block(floors, ray, s, exit, squares)
    }

    /// Cell `cell`'s brick, where its list can only raise the field (carves alone).
    fn ray_brick(&self, cell: usize) -> Option<&Brick> {
        let c = self.grid.stored_cell(cell)?;
        let CellState::Brick(id) = c.state.0 else {
            return None;
        };
        self.grid.brick(id).filter(|_| c.lists_carves_only())
    }

    /// Walks the ray's piece `[s, exit]` in a cell square by square of `floors`: `None`
    /// when they prove the field at least the threshold on every square's piece, else
    /// the first piece `(start, end)` they do not. Each piece is tested on the squares
    /// its rectangle, grown by the slack and 1/256 of a square (far more than the
    /// rounding of the square lookups of a brick's interpolation and of this walk),
    /// reaches into; where they fall short, `also` proves the piece `[t0, t1]` another
    /// way, as far as it can (`None`: all of it; else the stretch it does not).
    fn unproven_block(
        floors: FloorGrid,
        ray: &Piece,
        s: f64,
        exit: f64,
        mut also: impl FnMut(f64, f64) -> Option<(f64, f64)>,
    ) -> Option<(f64, f64)> {
        let corner = floors.corner.as_dvec2();
        let block = floors.block;
        let per_block = 1.0 / block;
        let last = f64::from(floors.side - 1);
        let margin = ray.slack + block / 256.0;
        // Clamped first, so that the cast floors.
        let index = |v: f64, o: f64| ((v - o) * per_block).clamp(0.0, last) as u32;
        let floored = |a: DVec2, b: DVec2| {
            let (min, max) = (a.min(b) - margin, a.max(b) + margin);
            let is = (index(min.x, corner.x), index(max.x, corner.x));
            let js = (index(min.y, corner.y), index(max.y, corner.y));
            floors.at_least(is, js, ray.above)
        };
        // The whole piece at once first: a ray through a brick's air above its surface
        // reaches few rows of squares.
        if floored(ray.p + ray.d * s, ray.p + ray.d * exit) {
            return None;
        }
        let mut a = ray.p + ray.d * s;
        // Where the ray crosses the next square side on each axis, and the distance
        // between such crossings. Any split of `[s, exit]` is sound (each piece is proven
        // on its own rectangle); this one follows the squares.
        let crossing = |v: f64, o: f64, d: f64| -> (f64, f64) {
            if d == 0.0 {
                return (f64::INFINITY, f64::INFINITY);
            }
            let k = f64::from(index(v, o)) + if d > 0.0 { 1.0 } else { 0.0 };
            ((o + k * block - v) / d + s, block / d.abs())
        };
        let (mut tx, dtx) = crossing(a.x, corner.x, ray.d.x);
        let (mut ty, dty) = crossing(a.y, corner.y, ray.d.y);
        let mut t0 = s;
        // Each piece but the last ends at a square's side; the guard only stops a
        // rounding loop.
        for _ in 0..2 * floors.side + 2 {
            let t1 = tx.min(ty).min(exit).max(t0);
            let b = ray.p + ray.d * t1;
            if !floored(a, b)
                && let Some(unproven) = also(t0, t1)
            {
                return Some(unproven);
            }
            if t1 >= exit {
                return None;
            }
            if tx <= ty {
                tx += dtx;
            } else {
                ty += dty;
            }
            (t0, a) = (t1, b);
        }
        Some((t0, exit))
    }

    /// Outside the grid the field is the base clamped to the band, and no event reaches
    /// within `M + 1` of the grid's edge: the unclamped base's clearance `(d - above) / L`
    /// holds up to where the ray enters the grid.
    ///
    /// Where the base's tape for `p`'s halo tile bounds it at or above `above` over the
    /// whole tile, the run reaches the tile's far side instead, with no evaluation.
    fn clear_outside(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        let (p64, d64) = (p.as_dvec2(), dir.as_dvec2());
        let slack = point_slack(p64);
        let entry = self.grid_entry(p64, d64);
        let tiles = self
            .cell_tapes
            .as_ref()
            .and_then(|tapes| proven_tiles(tapes, p, d64, above, entry.unwrap_or(f64::INFINITY)));
        let clear = match tiles {
            // Back by the slack: the caller's next point lands inside the last tile's
            // rectangle, or in the next tile, which answers for itself.
            Some(run) => run - slack,
            None => {
                let l = self.lipschitz();
                let (d, _) = self.base_at::<f32>(p, None, false);
                let reach = f64::from(d - above) / f64::from(l);
                if reach.is_nan() || reach <= 0.0 {
                    // At the surface (or NaN): the caller's own steps decide here.
                    return ClearRun {
                        clear: 0.0,
                        retry_after: self.options.band / l,
                    };
                }
                // Short of the rounding of the caller's points.
                reach * (1.0 - 1.0e-6) - slack
            }
        };
        let clear = match entry {
            Some(enter) => clear.min(enter),
            None => clear,
        };
        ClearRun {
            clear: f32_at_most(clear.max(0.0)),
            retry_after: 0.0,
        }
    }

    /// Where the ray from `p` (outside the grid) along `d` enters the grid's rectangle,
    /// if it does.
    fn grid_entry(&self, p: DVec2, d: DVec2) -> Option<f64> {
        let (nx, ny) = self.grid.dims();
        let lo = self.grid.origin().as_dvec2();
        let size = f64::from(self.grid.cell_size());
        let hi = lo + DVec2::new(f64::from(nx), f64::from(ny)) * size;
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for (p, d, lo, hi) in [(p.x, d.x, lo.x, hi.x), (p.y, d.y, lo.y, hi.y)] {
            if d == 0.0 {
                if p < lo || p > hi {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo - p) / d, (hi - p) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 <= t1).then_some(t0)
    }
}

/// Most halo tiles one [`proven_tiles`] walks: a run costs a few tiles' checks however
/// far the sky goes (the halo is 16 tiles deep), and a ray longer than four tiles (2,048
/// units with 64-unit cells) asks again.
const TILES_PER_RUN: u32 = 4;

/// How far the ray `p + d t` (`p` outside the grid, `t` up to `limit`) runs through halo
/// tiles whose base is bounded at or above `above` over the whole tile: from `p`'s tile
/// through each next tile the ray enters, to the far side of the last such tile (or
/// `limit`), at most [`TILES_PER_RUN`] tiles. `None` where `p`'s own tile proves nothing,
/// or `p` is past the halo. The walk puts the tiles' sides where the halo's lookup does
/// (up to the rounding the caller's slack covers), so the tiles walked cover the ray up
/// to the distance returned.
fn proven_tiles(tapes: &CellTapes, p: Vec2, d: DVec2, above: f32, limit: f64) -> Option<f64> {
    let (lattice, first) = tapes.halo_tile_of(p)?;
    let mut walk = SquareWalk::new(lattice, first, p.as_dvec2(), d);
    let mut run = None;
    for _ in 0..TILES_PER_RUN {
        let (ix, iy) = walk.square();
        if !tapes.halo_tile_proven(ix, iy, above) {
            return run;
        }
        let exit = walk.exit().max(run.unwrap_or(0.0));
        run = Some(exit);
        if exit >= limit {
            return Some(limit);
        }
        if !walk.step() {
            return run;
        }
    }
    run
}

/// A ray's line (`p + d t`, in `f64`), the rounding allowance of its points and the
/// threshold its pieces are proven against.
struct Piece {
    p: DVec2,
    d: DVec2,
    slack: f64,
    above: f32,
    /// What a brick's lattice walk needs of the ray.
    walk: WalkRay,
}
