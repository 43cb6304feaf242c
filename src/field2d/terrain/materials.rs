//! What a renderer may prove about materials without evaluating every point: per cell,
//! whether the material is one constant; per point, how far the winning material is from
//! being overtaken inside the point's cell.
//!
//! Materials change in three ways only (see the module doc of [`super`]): the base field's
//! own material selects, the nearest-sample material of a brick, and fills of another
//! material winning their `min`. Carves keep the material.
//!
//! # The margin
//!
//! [`Terrain::material_margin`] at `p` in cell `C` returns `m >= 0` with this guarantee:
//! every point `q` of `C` with `2 L' |q - p| < m` has the material of `p`, where `L'` is
//! [`Terrain::proof_lipschitz`]. It is computed along the same event fold as the field:
//! the cell's starting material is constant over `C` (margin `+inf`) or not (margin `0`);
//! a fill of material `F` compared with the accumulated `(d, mat, m)` at `c = |p - o| - r`
//! switches where `d - c` changes sign, a function whose slope is at most `L' + 1 <= 2 L'`:
//!
//! * the fill wins (`c <= d`): `m' = d - c` if `mat != F`, else `max(d - c, m)`;
//! * it loses (`d < c`): `m' = min(m, c - d)` if `mat != F`, else `m`.
//!
//! Both cases follow from "the winner stays the winner within `|d - c| / 2L'`, and the
//! accumulated material stays within `m / 2L'`". The guarantee holds within the cell only:
//! another cell has another event list and starting state.

use glam::Vec2;

use super::Terrain;
use crate::field2d::detmath::{Num, V2};
use crate::field2d::event::EventKind;
use crate::field2d::grid::{CellState, MaterialSource};
use crate::field2d::sdf::{MaterialId, Sdf};
use crate::field2d::tape::MatOut;

impl<F: Sdf> Terrain<F> {
    /// The slope bound a proof over this terrain may use: the field's Lipschitz bound, times
    /// `sqrt(2)` while any cell is a brick (the gradient of a bilinear interpolant of
    /// `L`-Lipschitz samples may reach `sqrt(2) L`).
    pub fn proof_lipschitz(&self) -> f32 {
        let l = self.lipschitz();
        if self.grid.live_bricks() > 0 {
            l * std::f32::consts::SQRT_2
        } else {
            l
        }
    }

    /// The most the field may jump across one cell border (`0` without bricks): a brick
    /// cell is within [`Terrain::brick_error_bound`] of the exact field, its neighbour may
    /// be exact or another brick.
    pub fn cell_border_jump(&self) -> f32 {
        if self.grid.live_bricks() > 0 {
            2.0 * self.brick_error_bound()
        } else {
            0.0
        }
    }

    /// The material everywhere in cell `cell` after its events, when it is provably one
    /// constant: the starting state's material is constant over the cell and every listed
    /// fill has that material. `None` when it may vary (or the cell does not exist).
    pub fn cell_material(&self, cell: usize) -> Option<MaterialId> {
        let start = self.start_material(cell)?;
        let c = self.grid.cells.get(cell)?;
        let all_same = c.events.iter().all(|&i| {
            self.events
                .get(i as usize)
                .is_none_or(|e| e.kind == EventKind::Carve || e.material == start)
        });
        all_same.then_some(start)
    }

    /// Whether the material cell `cell` starts from (before its events) is one constant
    /// over the cell, and which.
    pub fn start_material(&self, cell: usize) -> Option<MaterialId> {
        let c = self.grid.cells.get(cell)?;
        match c.state.0 {
            CellState::Base | CellState::Air(MaterialSource::Base) => self.base_material(cell),
            CellState::Air(MaterialSource::Constant(m)) | CellState::Solid(m) => Some(m),
            CellState::Brick(id) | CellState::Air(MaterialSource::Brick(id)) => {
                let b = self.grid.brick(id)?;
                let first = *b.materials.first()?;
                b.materials.iter().all(|&m| m == first).then_some(first)
            }
        }
    }

    /// The base field's material over cell `cell`, when its specialized tape has a
    /// constant material there.
    fn base_material(&self, cell: usize) -> Option<MaterialId> {
        let plans = self.plans.as_ref()?;
        match plans.get(&self.grid, Some(cell)).material.material() {
            MatOut::Const(m) => Some(m),
            MatOut::Value(_) => None,
        }
    }

    /// The material margin at `p` (see the module doc): `+inf` where no other material can
    /// win anywhere in `p`'s cell, `0` where nothing is proven (outside the grid, a varying
    /// starting material, NaN).
    pub fn material_margin(&self, p: Vec2) -> f32 {
        if p.x.is_nan() || p.y.is_nan() {
            return 0.0;
        }
        let Some(cell) = self.grid.cell_index(p) else {
            return 0.0;
        };
        if self.cell_material(cell).is_some() {
            return f32::INFINITY;
        }
        let Some(start) = self.start_material(cell) else {
            return 0.0;
        };
        let Some(c) = self.grid.cells.get(cell) else {
            return 0.0;
        };
        let band = self.options.band;
        let pn = V2::new(p.x, p.y);
        let (mut d, _) = self.eval_cell::<f32, false>(p, cell, 0);
        let (mut mat, mut margin) = (start, f32::INFINITY);
        for &i in &c.events {
            let Some(e) = self.events.get(i as usize) else {
                continue;
            };
            if let (EventKind::Fill, Some(r)) = (e.kind, e.radius_at(self.tick)) {
                // `c` exactly as `apply_event` computes it, so `wins` is its decision.
                let c = pn.minus(e.center_f32()).length().offset(-r);
                let wins = !(d < c);
                margin = match (wins, mat == e.material) {
                    (true, true) => (d - c).max(margin),
                    (true, false) => d - c,
                    (false, true) => margin,
                    (false, false) => margin.min(c - d),
                };
            }
            (d, mat) = super::apply_event(d, mat, pn, e, self.tick, band);
        }
        // NaN (never expected) proves nothing.
        if margin >= 0.0 { margin } else { 0.0 }
    }
}
