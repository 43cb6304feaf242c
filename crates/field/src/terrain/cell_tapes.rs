//! The base field's tapes for each explosion-grid cell, built on first use and kept.
//!
//! A cell's tapes are the base program specialized to the cell's rectangle (see
//! [`crate::tape::specialize`]): subtrees that cannot win anywhere in the cell are
//! dropped, which changes no bit of any result there. They depend only on the base field
//! and the cell's rectangle, both fixed for the terrain's life, so once built they never
//! go stale: events, baking and tick changes alter what is applied after the base, never
//! the base itself. Points outside the grid, where no event reaches, use coarser tiles of a
//! halo around it the same way, and the whole program past the halo.
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

use crate::tape::{Outputs, Program, Tape};
use crate::terrain::grid::Grid;
use crate::terrain::limits::MAX_CELL_TAPE_BYTES;

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
        let mut h = WordHasher::default();
        for t in [&self.value, &self.material] {
            t.instrs.hash(&mut h);
            // Every 64th parameter word: regions of one program share most parameters
            // (a long height profile's all), so the words add little to tell tapes apart.
            t.params.len().hash(&mut h);
            t.params.iter().step_by(64).for_each(|w| w.hash(&mut h));
            (t.registers, t.value, t.material, t.height_cap.to_bits()).hash(&mut h);
        }
        self.clamped.map(f32::to_bits).hash(&mut h);
        (self.range.0.to_bits(), self.range.1.to_bits()).hash(&mut h);
        h.finish()
    }

    fn new(program: &Program, region: Option<(Vec2, Vec2)>, band: f32, reach: Reach) -> CellTape {
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
        let (value, material) = (
            program.tape(Outputs::Value),
            program.tape(Outputs::ValueMaterial),
        );
        let (value, material) = match reach {
            Reach::Band if program.heights_only_clamped() => {
                // Past the band by a margin for the rounding of the search's bounds
                // (the nearest segment's computed distance against its true one, and
                // `x ± cap` at coordinates up to `MAX_COORD`).
                let cap = band + band / 256.0 + 1.0 / 16.0;
                (value.with_height_cap(cap), material.with_height_cap(cap))
            }
            _ => (value, material),
        };
        CellTape {
            value,
            material,
            clamped,
            range,
        }
    }
}

/// A multiply-rotate hasher over 8-byte words for [`CellTape::key`]: the key only picks a
/// bucket (equal tapes are confirmed by [`CellTape::same_as`]), so it needs speed, not
/// resistance to chosen inputs. SipHash over a long height profile's parameters (12 KiB
/// per tape) was most of the time a cell's specialization took.
#[derive(Default)]
struct WordHasher(u64);

impl WordHasher {
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl Hasher for WordHasher {
    fn write(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for w in &mut words {
            let mut b = [0u8; 8];
            b.copy_from_slice(w);
            self.add(u64::from_le_bytes(b));
        }
        for &b in words.remainder() {
            self.add(u64::from(b));
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// How far a region's height profiles search for their nearest segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Reach {
    /// As far as the point's gap to the ground: the unclamped value (the halo's tiles and
    /// the whole program, whose values clear runs read past the band).
    Full,
    /// Past the band by a margin, where the program allows it
    /// ([`Program::heights_only_clamped`]): a grid cell, whose base is only ever read
    /// clamped.
    Band,
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

/// Cells of the grid per side of one halo tile.
const HALO_TILE_CELLS: u32 = 8;
/// Halo tiles on each side of the grid: with 64-unit cells the halo reaches 8,192 units
/// past the grid's edge, farther than a ray cast from inside a level usually goes.
const HALO_DEPTH: u32 = 16;

/// Coarse tiles around the grid for points outside it, where no event reaches: the base
/// specialized to a tile makes a query there as cheap as in a cell, and a tile where the
/// base is clamped needs no evaluation at all. Points past the halo use the whole program.
#[derive(Clone, Debug)]
struct Halo {
    origin: Vec2,
    tile: f32,
    nx: u32,
    ny: u32,
    tiles: Vec<OnceLock<Arc<CellTape>>>,
}

impl Halo {
    fn new(grid: &Grid) -> Halo {
        let (nx, ny) = grid.dims();
        let tile = grid.cell_size() * HALO_TILE_CELLS as f32;
        let across = |n: u32| n.div_ceil(HALO_TILE_CELLS) + 2 * HALO_DEPTH;
        let (nx, ny) = (across(nx), across(ny));
        Halo {
            origin: grid.origin() - Vec2::splat(tile * HALO_DEPTH as f32),
            tile,
            nx,
            ny,
            tiles: (0..nx as usize * ny as usize)
                .map(|_| OnceLock::new())
                .collect(),
        }
    }

    /// The tile holding `p` and its lower-left corner, if the halo reaches `p`.
    fn tile_of(&self, p: Vec2) -> Option<(usize, Vec2)> {
        let f = (p - self.origin) / self.tile;
        if !(f.x >= 0.0 && f.x < self.nx as f32 && f.y >= 0.0 && f.y < self.ny as f32) {
            return None;
        }
        let (ix, iy) = ((f.x as u32).min(self.nx - 1), (f.y as u32).min(self.ny - 1));
        let min = Vec2::new(
            self.origin.x + ix as f32 * self.tile,
            self.origin.y + iy as f32 * self.tile,
        );
        Some((iy as usize * self.nx as usize + ix as usize, min))
    }
}

/// Every cell's plan, built lazily (thread-safe).
#[derive(Clone, Debug)]
pub(crate) struct CellTapes {
    program: Arc<Program>,
    cells: Vec<OnceLock<Arc<CellTape>>>,
    halo: Halo,
    outside: OnceLock<Arc<CellTape>>,
    /// Shared by clones: equal tapes are interchangeable whichever terrain built them.
    interned: Arc<Interned>,
    specialize: bool,
    band: f32,
}

impl CellTapes {
    pub(super) fn new(program: Arc<Program>, grid: &Grid, band: f32) -> CellTapes {
        CellTapes {
            program,
            cells: (0..grid.cell_count()).map(|_| OnceLock::new()).collect(),
            halo: Halo::new(grid),
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
            for c in self.cells.iter_mut().chain(&mut self.halo.tiles) {
                *c = OnceLock::new();
            }
        }
    }

    /// Builds every cell's tapes now that is not built yet (each is otherwise built on
    /// its cell's first use).
    pub(super) fn build_all(&self, grid: &Grid) {
        for cell in 0..self.cells.len() {
            self.get(grid, Some(cell));
        }
    }

    /// The whole program's tapes (outside the grid, and past the budget).
    fn whole(&self) -> &Arc<CellTape> {
        self.outside
            .get_or_init(|| Arc::new(CellTape::new(&self.program, None, self.band, Reach::Full)))
    }

    /// Bytes of the distinct specialized tapes kept.
    pub(super) fn bytes(&self) -> usize {
        self.interned.bytes.load(Ordering::Relaxed)
    }

    /// The plan of `cell` (`None`: outside the grid, the whole program).
    pub(super) fn get(&self, grid: &Grid, cell: Option<usize>) -> &CellTape {
        match cell.and_then(|c| self.cells.get(c).map(|slot| (c, slot))) {
            Some((c, slot)) if self.specialize => slot.get_or_init(|| {
                self.specialized(grid.cell_min_f32(c), grid.cell_size(), Reach::Band)
            }),
            _ => self.whole(),
        }
    }

    /// The plan for `p` outside the grid: its halo tile's, with the tile's rectangle, or
    /// the whole program's past the halo.
    pub(super) fn outside(&self, p: Vec2) -> (&CellTape, Option<(Vec2, Vec2)>) {
        match self.halo.tile_of(p) {
            Some((i, min)) if self.specialize => {
                let size = self.halo.tile;
                let plan =
                    self.halo.tiles[i].get_or_init(|| self.specialized(min, size, Reach::Full));
                (plan, Some((min, min + Vec2::splat(size))))
            }
            _ => (self.whole(), None),
        }
    }

    /// The program specialized to the square of side `size` at `min` (shared with any
    /// equal tape; the whole program's past the budget).
    fn specialized(&self, min: Vec2, size: f32, reach: Reach) -> Arc<CellTape> {
        // Padded: the f32 lookup may place a point a rounding error outside the square.
        let pad = size / 1024.0 + (min.abs().max_element() + size) / 1_048_576.0;
        let max = min + Vec2::splat(size + pad);
        let min = min - Vec2::splat(pad);
        let whole = self.whole();
        if self.bytes() >= MAX_CELL_TAPE_BYTES {
            return whole.clone();
        }
        let tape = CellTape::new(&self.program, Some((min, max)), self.band, reach);
        if tape.same_as(whole) {
            return whole.clone();
        }
        self.interned.share(tape).unwrap_or_else(|| whole.clone())
    }
}
