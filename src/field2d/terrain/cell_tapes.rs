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

use crate::field2d::tape::{Outputs, Program, Tape};
use crate::field2d::terrain::grid::Grid;

/// The tapes of one region.
#[derive(Debug)]
pub(crate) struct CellTape {
    /// Distance only.
    pub value: Tape,
    /// Distance and material.
    pub material: Tape,
    /// `Some(±band)` when the base is beyond the band everywhere in the region: the clamp
    /// then gives that constant with a zero gradient (the material still comes from the
    /// tape), so the distance needs no evaluation.
    pub clamped: Option<f32>,
    /// Bounds of `clamp(base, -M, M)` over the region (`[-M, M]` when nothing is known).
    pub range: (f32, f32),
}

impl CellTape {
    fn new(program: &Program, region: Option<(Vec2, Vec2)>, band: f32) -> CellTape {
        let mut range = (-band, band);
        let (program, clamped) = match region {
            Some((min, max)) => {
                let (p, bound) = program.specialize_with_bound(min, max);
                if !bound.nan {
                    range = (bound.lo.clamp(-band, band), bound.hi.clamp(-band, band));
                }
                // `nmin(nmax(d, -M), M)` is the constant `M` when `d >= M`, and `-M` when
                // `d <= -M`, whatever the gradient of `d`.
                let clamped = if bound.nan {
                    None
                } else if bound.lo >= band {
                    Some(band)
                } else if bound.hi <= -band {
                    Some(-band)
                } else {
                    None
                };
                (p.fuse(), clamped)
            }
            None => (program.fuse(), None),
        };
        CellTape {
            value: program.tape(Outputs::Value),
            material: program.tape(Outputs::ValueMaterial),
            clamped,
            range,
        }
    }
}

/// Every cell's plan, built lazily (thread-safe).
#[derive(Clone, Debug)]
pub(crate) struct CellTapes {
    program: Arc<Program>,
    cells: Vec<OnceLock<Arc<CellTape>>>,
    outside: OnceLock<Arc<CellTape>>,
    specialize: bool,
    band: f32,
}

impl CellTapes {
    pub(super) fn new(program: Arc<Program>, cells: usize, band: f32) -> CellTapes {
        CellTapes {
            program,
            cells: (0..cells).map(|_| OnceLock::new()).collect(),
            outside: OnceLock::new(),
            specialize: true,
            band,
        }
    }

    /// Whether cells get specialized tapes (on by default; off gives every cell the
    /// whole program, for comparison).
    pub(super) fn set_specialize(&mut self, on: bool) {
        if on != self.specialize {
            self.specialize = on;
            for c in &mut self.cells {
                *c = OnceLock::new();
            }
        }
    }

    /// The plan of `cell` (`None`: outside the grid).
    pub(super) fn get(&self, grid: &Grid, cell: Option<usize>) -> &CellTape {
        let whole = || Arc::new(CellTape::new(&self.program, None, self.band));
        match cell.and_then(|c| self.cells.get(c).map(|slot| (c, slot))) {
            Some((c, slot)) if self.specialize => slot.get_or_init(|| {
                // Padded: the f32 cell lookup may place a point a rounding error outside
                // the cell's exact rectangle.
                let s = grid.cell_size();
                let min = grid.cell_min_f32(c);
                let pad = s / 1024.0 + (min.abs().max_element() + s) / 1_048_576.0;
                let max = min + Vec2::splat(s + pad);
                let min = min - Vec2::splat(pad);
                Arc::new(CellTape::new(&self.program, Some((min, max)), self.band))
            }),
            _ => self.outside.get_or_init(whole),
        }
    }
}
