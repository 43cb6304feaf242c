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
use crate::terrain::grid::{FLAT_SIDE, Grid, square_bit};
use crate::terrain::limits::MAX_CELL_TAPE_BYTES;
use crate::terrain::square_walk::Lattice;

/// The tapes of one region.
///
/// In this order, from the start of a cache line: a point query reads the clamp's fields
/// first and, where they do not answer, the value tape's; the material tape last
/// (near-surface distances at 0 explosions, best of 40 passes: 11.08-11.22 M/s laid out
/// so, 10.88-11.08 in the compiler's order).
#[derive(Debug)]
#[repr(C, align(64))]
pub(crate) struct CellTape {
    /// `Some(±band)` when the base is beyond the band everywhere in the region: the clamp
    /// then gives that constant with a zero gradient (the material still comes from the
    /// tape), so the distance needs no evaluation.
    pub clamped: Option<f32>,
    /// Where [`CellTape::clamped`] is not known for the whole cell, the squares of it
    /// where it is (none for a halo tile or the whole program).
    pub squares: SubClamp,
    /// Bounds of `clamp(base, -M, M)` over the region (`[-M, M]` when nothing is known).
    pub range: (f32, f32),
    /// Distance only.
    pub value: Tape,
    /// Distance and material.
    pub material: Tape,
}

impl CellTape {
    fn bytes(&self) -> usize {
        self.value.bytes() + self.material.bytes()
    }

    fn same_as(&self, other: &CellTape) -> bool {
        self.value.same_as(&other.value)
            && self.material.same_as(&other.material)
            && self.clamped.map(f32::to_bits) == other.clamped.map(f32::to_bits)
            && self.squares == other.squares
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
        self.squares.key().hash(&mut h);
        (self.range.0.to_bits(), self.range.1.to_bits()).hash(&mut h);
        h.finish()
    }

    /// The tapes of `program` over `region` (the whole program's for `None`).
    fn new(program: &Program, region: Option<Region>, band: f32, reach: Reach) -> CellTape {
        let mut range = (-band, band);
        let mut squares = SubClamp::default();
        let (program, clamped) = match region {
            Some(region) => {
                let (min, max) = region.padded();
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
                let p = p.fuse();
                if clamped.is_none() && reach == Reach::Band {
                    squares = SubClamp::prove(&p, region, band);
                }
                (p, clamped)
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
            squares,
            range,
        }
    }
}

/// The square a tape is specialized to: a cell, or a halo tile.
#[derive(Clone, Copy, Debug)]
struct Region {
    min: Vec2,
    size: f32,
}

impl Region {
    /// How far the square is grown for its proofs: the `f32` lookup may place a point a
    /// rounding error outside it.
    fn pad(self) -> f32 {
        self.size / 1024.0 + (self.min.abs().max_element() + self.size) / 1_048_576.0
    }

    /// The square grown by [`Region::pad`].
    fn padded(self) -> (Vec2, Vec2) {
        let pad = Vec2::splat(self.pad());
        (self.min - pad, self.min + Vec2::splat(self.size) + pad)
    }
}

/// Squares per side of a cell that [`SubClamp`] tells apart.
const SUB_SQUARES: u32 = 4;

/// The squares of a cell, in a [`SUB_SQUARES`] by [`SUB_SQUARES`] split, where the base is
/// proven beyond the band: there the clamp gives its constant with a zero gradient, as in
/// a cell whose whole tape is [`CellTape::clamped`], with no evaluation. Cells are twice
/// the band wide (by default), so much of a cell that the surface crosses lies beyond
/// the band from it.
///
/// Part of a cell's [`CellTape`], and of what makes two tapes equal: it holds the cell's
/// corner, so cells whose specialized tapes are alike no longer share them where either
/// has a square proven (levels repeat few tapes across cells the surface crosses).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SubClamp {
    /// Bit `j * SUB_SQUARES + i`: the base is at least the band over square `(i, j)`.
    above: u16,
    /// The same, at most minus the band.
    below: u16,
    /// The cell's lower-left corner, kept so that a lookup needs no division.
    min: Vec2,
    /// Squares per unit of length.
    scale: f32,
}

impl SubClamp {
    /// The proof over the squares of `cell`, by the bound of `program` (the cell's,
    /// specialized) over each square grown by the cell's pad, which covers the rounding
    /// of [`SubClamp::constant`]'s lookup as it covers the cell's.
    fn prove(program: &Program, cell: Region, band: f32) -> SubClamp {
        let (min, size, pad) = (cell.min, cell.size, cell.pad());
        let side = size / SUB_SQUARES as f32;
        let mut proof = SubClamp {
            min,
            scale: SUB_SQUARES as f32 / size,
            ..SubClamp::default()
        };
        for j in 0..SUB_SQUARES {
            for i in 0..SUB_SQUARES {
                let lo = min + Vec2::new(i as f32, j as f32) * side;
                let bound = program.bound(lo - Vec2::splat(pad), lo + Vec2::splat(side + pad));
                let bit = 1u16 << (j * SUB_SQUARES + i);
                if bound.nan {
                    continue;
                }
                if bound.lo >= band {
                    proof.above |= bit;
                } else if bound.hi <= -band {
                    proof.below |= bit;
                }
            }
        }
        proof
    }

    /// The proven squares as those of the finer [`FLAT_SIDE`] split (`above`, `below`):
    /// each of ours holds 2 x 2 of them, and its padded proof covers theirs.
    pub(crate) fn flats(self) -> (u64, u64) {
        const FINE: u32 = FLAT_SIDE / SUB_SQUARES;
        let spread = |bits: u16| {
            let mut out = 0u64;
            for j in 0..FLAT_SIDE {
                for i in 0..FLAT_SIDE {
                    if bits & (1 << ((j / FINE) * SUB_SQUARES + i / FINE)) != 0 {
                        out |= square_bit(i, j);
                    }
                }
            }
            out
        };
        (spread(self.above), spread(self.below))
    }

    /// How many squares are proven.
    #[cfg(test)]
    pub(crate) fn proven(self) -> u32 {
        (self.above | self.below).count_ones()
    }

    /// What [`CellTape::key`] hashes of the proof: equal proofs, equal keys.
    fn key(self) -> (u16, u16, u32, u32, u32) {
        let (x, y) = (self.min.x.to_bits(), self.min.y.to_bits());
        (self.above, self.below, x, y, self.scale.to_bits())
    }

    /// The clamp's constant (`band` or `-band`) at `p` (in the cell, up to the rounding
    /// that the proof's padding covers), if its square is proven.
    pub(crate) fn constant(self, p: Vec2, band: f32) -> Option<f32> {
        let last = Vec2::splat((SUB_SQUARES - 1) as f32);
        let local = ((p - self.min) * self.scale).clamp(Vec2::ZERO, last);
        // In [0, SUB_SQUARES - 1] (NaN casts to 0, and is refused below): the casts floor.
        let bit = 1u16 << (local.y as u32 * SUB_SQUARES + local.x as u32);
        // One branch, on the bit: a point near the surface, in no proven square, takes
        // it the same way every time wherever it is.
        if (self.above | self.below) & bit == 0 || !p.is_finite() {
            return None;
        }
        Some(if self.above & bit != 0 { band } else { -band })
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

    /// Tile `(ix, iy)`'s index and lower-left corner (both inside the halo).
    fn tile_at(&self, ix: u32, iy: u32) -> (usize, Vec2) {
        let min = Vec2::new(
            self.origin.x + ix as f32 * self.tile,
            self.origin.y + iy as f32 * self.tile,
        );
        (iy as usize * self.nx as usize + ix as usize, min)
    }

    /// The tile holding `p` as `(column, row)`, if the halo reaches `p`.
    fn tile_of(&self, p: Vec2) -> Option<(u32, u32)> {
        let f = (p - self.origin) / self.tile;
        if !(f.x >= 0.0 && f.x < self.nx as f32 && f.y >= 0.0 && f.y < self.ny as f32) {
            return None;
        }
        Some(((f.x as u32).min(self.nx - 1), (f.y as u32).min(self.ny - 1)))
    }

    /// The halo's tiles as a lattice of squares.
    fn lattice(&self) -> Lattice {
        Lattice {
            origin: self.origin,
            size: self.tile,
            nx: self.nx,
            ny: self.ny,
        }
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
                let (min, size) = (grid.cell_min_f32(c), grid.cell_size());
                self.specialized(min, size, Reach::Band)
            }),
            _ => self.whole(),
        }
    }

    /// The plan for `p` outside the grid: its halo tile's, or the whole program's past the
    /// halo.
    pub(super) fn outside(&self, p: Vec2) -> &CellTape {
        match self.halo.tile_of(p) {
            Some((ix, iy)) if self.specialize => self.halo_tile(ix, iy),
            _ => self.whole(),
        }
    }

    /// The halo's tiles as a lattice, and the tile holding `p` as `(column, row)`;
    /// `None` past the halo, or where cells are not specialized (every tile is then the
    /// whole program, which proves nothing a tile could).
    #[inline]
    pub(super) fn halo_tile_of(&self, p: Vec2) -> Option<(Lattice, (u32, u32))> {
        let tile = self.halo.tile_of(p).filter(|_| self.specialize)?;
        Some((self.halo.lattice(), tile))
    }

    /// Whether the base is bounded at or above `above` over the whole of halo tile
    /// `(ix, iy)` (inside the halo).
    #[inline]
    pub(super) fn halo_tile_proven(&self, ix: u32, iy: u32, above: f32) -> bool {
        // NaN compares false: an unbounded tile proves nothing.
        self.halo_tile(ix, iy).range.0 >= above
    }

    /// Halo tile `(ix, iy)`'s plan (inside the halo), specialized on its first use.
    #[inline]
    fn halo_tile(&self, ix: u32, iy: u32) -> &CellTape {
        let halo = &self.halo;
        let (i, min) = halo.tile_at(ix, iy);
        halo.tiles[i].get_or_init(|| self.specialized(min, halo.tile, Reach::Full))
    }

    /// The program specialized to the square of side `size` at `min` (shared with any
    /// equal tape; the whole program's past the budget).
    fn specialized(&self, min: Vec2, size: f32, reach: Reach) -> Arc<CellTape> {
        let whole = self.whole();
        if self.bytes() >= MAX_CELL_TAPE_BYTES {
            return whole.clone();
        }
        let region = Region { min, size };
        let tape = CellTape::new(&self.program, Some(region), self.band, reach);
        if tape.same_as(whole) {
            return whole.clone();
        }
        self.interned.share(tape).unwrap_or_else(|| whole.clone())
    }
}
