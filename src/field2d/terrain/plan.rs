//! The base field's tapes for each explosion-grid cell, built on first use and kept.
//!
//! A cell's tapes are the base program specialized to the cell's rectangle (see
//! [`crate::field2d::tape::specialize`]): subtrees that cannot win anywhere in the cell are
//! dropped, which changes no bit of any result there. They depend only on the base field
//! and the cell's rectangle, both fixed for the terrain's life, so once built they never
//! go stale: events, baking and tick changes alter what is applied after the base, never
//! the base itself. Points outside the grid use the whole program.

use std::sync::{Arc, OnceLock};

use glam::Vec2;

use crate::field2d::grid::Grid;
use crate::field2d::tape::{Outputs, Program, Tape};

/// The tapes of one region.
#[derive(Debug)]
pub(crate) struct CellPlan {
    /// Distance only.
    pub value: Tape,
    /// Distance and material.
    pub material: Tape,
}

impl CellPlan {
    fn new(program: &Program, region: Option<(Vec2, Vec2)>) -> CellPlan {
        let program = match region {
            Some((min, max)) => program.specialize(min, max).fuse(),
            None => program.fuse(),
        };
        CellPlan {
            value: program.tape(Outputs::Value),
            material: program.tape(Outputs::ValueMaterial),
        }
    }
}

/// Every cell's plan, built lazily (thread-safe).
#[derive(Clone, Debug)]
pub(crate) struct Plans {
    program: Arc<Program>,
    cells: Vec<OnceLock<Arc<CellPlan>>>,
    outside: OnceLock<Arc<CellPlan>>,
    specialize: bool,
}

impl Plans {
    pub fn new(program: Arc<Program>, cells: usize) -> Plans {
        Plans {
            program,
            cells: (0..cells).map(|_| OnceLock::new()).collect(),
            outside: OnceLock::new(),
            specialize: true,
        }
    }

    /// Whether cells get specialized tapes (on by default; off gives every cell the
    /// whole program, for comparison).
    pub fn set_specialize(&mut self, on: bool) {
        if on != self.specialize {
            self.specialize = on;
            for c in &mut self.cells {
                *c = OnceLock::new();
            }
        }
    }

    /// The plan of `cell` (`None`: outside the grid).
    pub fn get(&self, grid: &Grid, cell: Option<usize>) -> &CellPlan {
        let whole = || Arc::new(CellPlan::new(&self.program, None));
        match cell.and_then(|c| self.cells.get(c).map(|slot| (c, slot))) {
            Some((c, slot)) if self.specialize => slot.get_or_init(|| {
                // Padded: the f32 cell lookup may place a point a rounding error outside
                // the cell's exact rectangle.
                let s = grid.cell_size();
                let min = grid.cell_min_f32(c);
                let pad = s / 1024.0 + (min.abs().max_element() + s) / 1_048_576.0;
                let max = min + Vec2::splat(s + pad);
                let min = min - Vec2::splat(pad);
                Arc::new(CellPlan::new(&self.program, Some((min, max))))
            }),
            _ => self.outside.get_or_init(whole),
        }
    }
}
