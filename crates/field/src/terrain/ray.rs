//! What a ray may skip ([`Sdf::clear_run`] for a terrain): inside the grid, the run of
//! cells along the ray whose starting state and events prove the field above the
//! threshold (the sign proof of [`Terrain::rect_sign`], asked about `Above` only, over
//! each cell's piece of the ray; brick cells are not asked); outside it, where no event
//! reaches, whole halo tiles whose base is bounded above the threshold, else the
//! clearance of the unclamped base, up to the grid's edge.
//!
//! A ray cast through a terrain spends most of its sphere-tracing steps crossing air that
//! the clamp to the band holds at `+M`, `M / L` per step; one proof per cell replaces them.

use glam::{DVec2, Vec2};

use super::Terrain;
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
        let size = self.grid.cell_size();
        let (mut ix, mut iy) = (cell as u32 % nx, cell as u32 / nx);
        let (p64, d64) = (p.as_dvec2(), dir.as_dvec2());
        let slack = point_slack(p64);
        // Distance along the ray to the far side of column (or row) `i`, whose sides are
        // where the cell lookup puts them, in `f32`.
        let edge = |i: u32, o: f32, p: f64, d: f64| -> f64 {
            let side = |k: u32| f64::from(o + k as f32 * size);
            axis_exit(p, d, side(i), side(i + 1))
        };
        let origin = self.grid.origin();
        let mut s = 0.0f64;
        loop {
            let index = iy as usize * nx as usize + ix as usize;
            let exit_x = edge(ix, origin.x, p64.x, d64.x);
            let exit_y = edge(iy, origin.y, p64.y, d64.y);
            let exit = exit_x.min(exit_y).max(s);
            let (a, b) = (p64 + d64 * s, p64 + d64 * exit);
            let min = (a.min(b) - DVec2::splat(slack)).as_vec2();
            let max = (a.max(b) + DVec2::splat(slack)).as_vec2();
            if !self.rect_above(index, min, max, above) {
                return ClearRun {
                    clear: f32_at_most(s),
                    retry_after: (exit - s) as f32,
                };
            }
            s = exit;
            let step = |i: &mut u32, d: f64, n: u32| -> bool {
                if d > 0.0 && *i + 1 < n {
                    *i += 1;
                    true
                } else if d < 0.0 && *i > 0 {
                    *i -= 1;
                    true
                } else {
                    false
                }
            };
            let inside = if exit_x <= exit_y {
                step(&mut ix, d64.x, nx)
            } else {
                step(&mut iy, d64.y, ny)
            };
            if !inside || !s.is_finite() {
                // Left the grid: the base alone from here, asked at the next point.
                return ClearRun {
                    clear: f32_at_most(s),
                    retry_after: 0.0,
                };
            }
        }
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
        let tile = self.cell_tapes.as_ref().map(|t| t.outside(p));
        let clear = match tile {
            Some((plan, Some((min, max)))) if plan.range.0 >= above => {
                // Back by the slack: the caller's next point lands inside the tile's
                // rectangle, or in the next tile, which answers for itself.
                square_exit(p64, d64, min.as_dvec2(), max.as_dvec2()) - slack
            }
            _ => {
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
        let clear = match self.grid_entry(p64, d64) {
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

/// Distance along `d` from `p` (inside the rectangle `[min, max]`) to its far side.
fn square_exit(p: DVec2, d: DVec2, min: DVec2, max: DVec2) -> f64 {
    let x = axis_exit(p.x, d.x, min.x, max.x);
    x.min(axis_exit(p.y, d.y, min.y, max.y)).max(0.0)
}

/// Distance along one axis's direction `d` from `p` to the side of `[lo, hi]` it moves
/// towards (infinite when it does not move).
fn axis_exit(p: f64, d: f64, lo: f64, hi: f64) -> f64 {
    if d > 0.0 {
        (hi - p) / d
    } else if d < 0.0 {
        (lo - p) / d
    } else {
        f64::INFINITY
    }
}
