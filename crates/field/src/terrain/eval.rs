//! Point queries of a terrain: the base clamped to the band (from the cell's tape when the
//! base is a level), a cell's state and list applied in order, and the brute-force
//! reference that every grid path is tested against.

use glam::Vec2;

use super::Terrain;
use super::cell_tapes::{CellTape, CellTapes};
use super::field::{Lift, apply_event, apply_unless_top};
use super::grid::{CellState, MaterialSource};
use crate::exec;
use crate::sample::{MaterialId, Sample};
use crate::sdf::{ClearRun, Sdf};
use craterfield_core::det::math::{Dual, max, nclamp};

impl<F: Sdf> Terrain<F> {
    /// The base's tapes at `p` in `cell` (`None`: outside the grid, its halo tile).
    fn plan<'a>(&self, cell_tapes: &'a CellTapes, cell: Option<usize>, p: Vec2) -> &'a CellTape {
        match cell {
            Some(_) => cell_tapes.get(&self.grid, cell),
            None => cell_tapes.outside(p).0,
        }
    }

    /// `clamp(base(p), -M, M)`.
    pub(super) fn base_clamped<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: Option<usize>,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        if let Some(cell_tapes) = &self.cell_tapes {
            let plan = self.plan(cell_tapes, cell, p);
            if let Some(c) = plan.clamped {
                let mat = if MAT || N::MATERIAL {
                    exec::point::material(&plan.material, p)
                } else {
                    0
                };
                return (N::constant(c), mat);
            }
        }
        let (d, mat) = self.base_at::<N>(p, cell, MAT);
        (nclamp(d, -m, m), mat)
    }

    /// The base field at `p` (in `cell`): from the cell's tape when the base has a
    /// program, else from the base itself. Both give the same bits.
    pub(super) fn base_at<N: Lift>(
        &self,
        p: Vec2,
        cell: Option<usize>,
        material: bool,
    ) -> (N, MaterialId) {
        match &self.cell_tapes {
            Some(cell_tapes) => N::tape(self.plan(cell_tapes, cell, p), p, material),
            None => N::base(&self.base, p, material),
        }
    }

    /// The base's material at `p` (in `cell`), without its distance or gradient.
    fn base_material_at(&self, p: Vec2, cell: Option<usize>) -> MaterialId {
        match &self.cell_tapes {
            Some(cell_tapes) => exec::point::material(&self.plan(cell_tapes, cell, p).material, p),
            None => self.base.distance_material(p).1,
        }
    }

    /// The field at `p` in `cell` from the cell's state and the first `upto` listed events.
    pub(super) fn eval_cell<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: usize,
        upto: usize,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        let Some(c) = self.grid.stored_cell(cell) else {
            return self.base_clamped::<N, MAT>(p, None);
        };
        let pn = N::point(p);
        let (mut d, mut mat) = match c.state.0 {
            CellState::Base => self.base_clamped::<N, MAT>(p, Some(cell)),
            CellState::Air(src) => {
                let mat = if N::MATERIAL || MAT {
                    match src {
                        MaterialSource::Base => self.base_material_at(p, Some(cell)),
                        MaterialSource::Constant(m) => m,
                        MaterialSource::Brick(id) => self.grid.brick_material(id, cell, p),
                    }
                } else {
                    0
                };
                (N::constant(m), mat)
            }
            CellState::Solid(mat) => (N::constant(-m), mat),
            CellState::Brick(id) => match self.grid.interpolate(id, cell, pn, N::MATERIAL || MAT) {
                Some(x) => x,
                None => self.base_clamped::<N, MAT>(p, Some(cell)),
            },
        };
        if !c.may_fill && d.is_top(m) {
            // Only carves follow, and each leaves the top as it is (`apply_unless_top`):
            // the list need not be read.
            return (d, mat);
        }
        for e in c.events.listed().iter().take(upto) {
            (d, mat) = apply_unless_top(d, mat, pn, e, self.tick, m);
        }
        (d, mat)
    }

    pub(super) fn eval<N: Lift, const MAT: bool>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        match self.grid.cell_index(p) {
            Some(cell) => self.eval_cell::<N, MAT>(p, cell, usize::MAX),
            None => self.base_clamped::<N, MAT>(p, None),
        }
    }

    pub(super) fn eval_brute<N: Lift>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        let pn = N::point(p);
        // The reference: the base's own evaluation (the graph walker for a level).
        let band = self.options.band;
        let (d0, mat0) = N::base(&self.base, p, true);
        let (mut d, mut mat) = (nclamp(d0, -band, band), mat0);
        for e in self.events.iter() {
            (d, mat) = apply_event(d, mat, pn, e, self.tick, self.options.band);
        }
        (d, mat)
    }

    /// Reference distance: every event in order, no grid, no pruning.
    pub fn distance_brute_force(&self, p: Vec2) -> f32 {
        self.eval_brute::<f32>(p).0
    }

    /// Reference sample: every event in order, no grid, no pruning.
    pub fn sample_brute_force(&self, p: Vec2) -> Sample {
        let (d, material) = self.eval_brute::<Dual>(p);
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }
}

impl<F: Sdf> Sdf for Terrain<F> {
    fn distance(&self, p: Vec2) -> f32 {
        self.eval::<f32, false>(p).0
    }

    fn distance_material(&self, p: Vec2) -> (f32, MaterialId) {
        self.eval::<f32, true>(p)
    }

    fn sample(&self, p: Vec2) -> Sample {
        let (d, material) = self.eval::<Dual, true>(p);
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }

    fn lipschitz(&self) -> f32 {
        max(self.base.lipschitz(), 1.0)
    }

    fn clear_run(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        self.clear_run_from(p, dir, above)
    }
}
