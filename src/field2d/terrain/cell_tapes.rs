//! The base field's tapes for each explosion-grid cell, built on first use and kept.
//!
//! A cell's tapes are the base program specialized to the cell's rectangle (see
//! [`crate::field2d::tape::specialize`]): subtrees that cannot win anywhere in the cell are
//! dropped, which changes no bit of any result there. They depend only on the base field
//! and the cell's rectangle, both fixed for the terrain's life, so once built they never
//! go stale: events, baking and tick changes alter what is applied after the base, never
//! the base itself. Points outside the grid use the whole program.
//!
//! Memory is bounded by [`MAX_CELL_TAPE_BYTES`]: a cell whose tapes come out the same as
//! another's (or as the whole program's) shares them, and once the distinct tapes reach
//! the budget further cells use the whole program. Either way a cell's results are the
//! same bits, so what is shared or specialized never depends on the order of queries in a
//! way anyone can see but the time taken.

use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use glam::Vec2;

use crate::field2d::tape::{Outputs, Program, Tape};
use crate::field2d::terrain::grid::Grid;
use crate::field2d::terrain::limits::MAX_CELL_TAPE_BYTES;

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
    fn bytes(&self) -> usize {
        self.value.bytes() + self.material.bytes()
    }

    fn same_as(&self, other: &CellTape) -> bool {
        self.value.same_as(&other.value)
            && self.material.same_as(&other.material)
            && self.clamped.map(f32::to_bits) == other.clamped.map(f32::to_bits)
            && (self.range.0.to_bits(), self.range.1.to_bits())
                == (other.range.0.to_bits(), other.range.1.to_bits())
    }

    /// A hash of what [`CellTape::same_as`] compares.
    fn key(&self) -> u64 {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for t in [&self.value, &self.material] {
            t.instrs.hash(&mut h);
            t.params.hash(&mut h);
            (t.registers, t.value, t.material).hash(&mut h);
        }
        self.clamped.map(f32::to_bits).hash(&mut h);
        (self.range.0.to_bits(), self.range.1.to_bits()).hash(&mut h);
        h.finish()
    }

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

/// The distinct tapes built so far, by content, and their bytes.
#[derive(Debug, Default)]
struct Interned {
    table: Mutex<HashMap<u64, Vec<Arc<CellTape>>>>,
    bytes: AtomicUsize,
}

impl Interned {
    /// The stored tape equal to `tape`, or `tape` stored; `None` when it is new and the
    /// budget is spent.
    fn share(&self, tape: CellTape) -> Option<Arc<CellTape>> {
        let mut table = self.table.lock().unwrap_or_else(|e| e.into_inner());
        let bucket = table.entry(tape.key()).or_default();
        if let Some(same) = bucket.iter().find(|t| t.same_as(&tape)) {
            return Some(same.clone());
        }
        let bytes = tape.bytes();
        if self.bytes.load(Ordering::Relaxed) + bytes > MAX_CELL_TAPE_BYTES {
            return None;
        }
        self.bytes.fetch_add(bytes, Ordering::Relaxed);
        let tape = Arc::new(tape);
        bucket.push(tape.clone());
        Some(tape)
    }
}

/// Every cell's plan, built lazily (thread-safe).
#[derive(Clone, Debug)]
pub(crate) struct CellTapes {
    program: Arc<Program>,
    cells: Vec<OnceLock<Arc<CellTape>>>,
    outside: OnceLock<Arc<CellTape>>,
    /// Shared by clones: equal tapes are interchangeable whichever terrain built them.
    interned: Arc<Interned>,
    specialize: bool,
    band: f32,
}

impl CellTapes {
    pub(super) fn new(program: Arc<Program>, cells: usize, band: f32) -> CellTapes {
        CellTapes {
            program,
            cells: (0..cells).map(|_| OnceLock::new()).collect(),
            outside: OnceLock::new(),
            interned: Arc::default(),
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

    /// The whole program's tapes (outside the grid, and past the budget).
    fn whole(&self) -> &Arc<CellTape> {
        self.outside
            .get_or_init(|| Arc::new(CellTape::new(&self.program, None, self.band)))
    }

    /// Bytes of the distinct specialized tapes kept.
    pub(super) fn bytes(&self) -> usize {
        self.interned.bytes.load(Ordering::Relaxed)
    }

    /// The plan of `cell` (`None`: outside the grid).
    pub(super) fn get(&self, grid: &Grid, cell: Option<usize>) -> &CellTape {
        match cell.and_then(|c| self.cells.get(c).map(|slot| (c, slot))) {
            Some((c, slot)) if self.specialize => slot.get_or_init(|| {
                // Padded: the f32 cell lookup may place a point a rounding error outside
                // the cell's exact rectangle.
                let s = grid.cell_size();
                let min = grid.cell_min_f32(c);
                let pad = s / 1024.0 + (min.abs().max_element() + s) / 1_048_576.0;
                let max = min + Vec2::splat(s + pad);
                let min = min - Vec2::splat(pad);
                let whole = self.whole();
                if self.bytes() >= MAX_CELL_TAPE_BYTES {
                    return whole.clone();
                }
                let tape = CellTape::new(&self.program, Some((min, max)), self.band);
                if tape.same_as(whole) {
                    return whole.clone();
                }
                self.interned.share(tape).unwrap_or_else(|| whole.clone())
            }),
            _ => self.whole(),
        }
    }
}
