//! The destructible terrain: a base field minus carved circles plus filled circles, applied
//! in event order and kept in an explosion grid so that a query reads only its own cell.
//!
//! # The field
//!
//! With band `M` ([`TerrainOptions::band`]) and current tick `t`:
//!
//! * `d = clamp(base(p), -M, M)` (zero gradient where clamped; material from the base);
//! * for each event in order, with `r = radius_at(t)` ([`Event::radius_at`]; the event is
//!   skipped before its tick) and `c = |p - center| - r`:
//!   sharp carve `d = max(d, -c)`, smooth carve `d = smax(d, -c, k)`, sharp fill
//!   `d = min(d, c)`, smooth fill `d = smin(d, c, k)`, then `d = clamp(d, -M, M)`.
//!   A fill wins where `min` selects its term (`!(d < c)`), and then sets the material to its
//!   own; carves keep the material.
//! * `smin(a, b, k)`: `h = max(k - |a - b|, 0) / k`; `min(a, b) - h*h*k*0.25` if `h > 0`, else
//!   `min(a, b)` (a select, so `-0.0` survives); `smax` likewise with `max` and `+`.
//!
//! One generic routine computes this over `f32` ([`Sdf::distance`]) and over
//! [`Dual`](craterfield_core::det::math::Dual) ([`Sdf::sample`]), so both give the same distance bits.
//! Where a cell's list holds events and none of them smooth, [`Sdf::sample`] runs the
//! `f32` routine and evaluates on duals only the term whose value won (`min`, `max` and the
//! clamp each pick one operand, by value): the same bits as the dual routine, with one
//! event's gradient computed instead of every listed event's.
//!
//! # Why the grid is exact
//!
//! `d` always lies in `[-M, M]`. An event whose disc is farther than `r + k + M` from `p` is
//! exactly the identity there: a carve gives `-c < -M <= d`, so `max` selects `d` (and the
//! smooth term has `h = 0`); a fill gives `c > M >= d`. So each event is listed in every cell
//! whose rectangle lies within `r + k + M + guard` of its centre, where the guard (see
//! `grid::guard`) bounds the `f32` rounding of `|p - c|` and of the cell lookup. The grid
//! covers the bounds grown by `max_event_radius + max_rim + M + 1` on every side; points
//! outside it get `clamp(base)` only, which is what every event leaves there.
//!
//! # Exact pruning (bitwise equal to the brute force)
//!
//! Only events *settled* at the current tick (full radius now and at every later tick) take
//! part in pruning or baking; moving the tick backwards rebuilds the grid from the events.
//!
//! 1. **Cell reset.** A sharp settled carve whose disc contains the cell with margin
//!    (farthest corner `+ M + guard <= r`) has `-c > M >= d` everywhere in the cell, so it
//!    wins and the clamp gives the constant `+M` with zero gradient, whatever came before.
//!    Carves keep the material, so if the list holds no fill the material is the previous
//!    state's (the base's, a constant, or a brick's): the cell becomes `Air(source)` and its
//!    list is cleared. A sharp settled fill containing the cell likewise wins everywhere:
//!    `Solid(material)` (`-M`, zero gradient, the fill's material).
//! 2. **Covered events.** If sharp settled carves `A` and `B` satisfy
//!    `rA >= rB + |cA - cB| + guard`, then `-cA > -cB` at every point. If `A` is later, every
//!    point where `B` won has `A` win too, and where `B` lost nothing changed; if `A` is
//!    earlier, after `A` (and any carves) `d >= min(-cA, M)`, so `B` either loses strictly or
//!    hits the clamp at the same `+M`. We only drop `B` when every event between them in the
//!    cell's list is a sharp carve, so no fill or smooth term can tell the two runs apart;
//!    carves keep the material. Fills are symmetric (with `min`); there the events between
//!    must be sharp fills and all of them, `A` and `B` included, must share one material.
//! 3. **Cap.** If a list is still longer than `cell_cap`, its longest settled prefix is baked
//!    into a brick at the following tick advances, `bake_rows_per_tick` lattice rows per
//!    advance, cells in cell order (see `bake`: no insert pays for a bake, and no tick for
//!    more than its rows), or whole as the event is applied once the list reaches twice
//!    the cap; until the brick is installed queries apply the whole list, exactly. The
//!    brick is the cell's field (state + prefix, clamped) sampled
//!    exactly at an `(n+1) x (n+1)` lattice (spacing `h = cell_size / n`), values and
//!    materials. Queries in a brick cell interpolate bilinearly (gradient of the
//!    interpolant, material of the nearest lattice sample) and then apply the remaining
//!    events.
//!
//! # What is exact and what is bounded
//!
//! Every cell without a brick (state `Base`, `Air`, `Solid`) is bitwise equal to
//! [`Terrain::distance_brute_force`] and [`Terrain::sample_brute_force`], material and
//! gradient included. In a cell whose state is (or whose material comes from) a brick, the
//! distance error is at most `L * h / sqrt(2)` (plus `f32` rounding), `L = max(base
//! lipschitz, 1)`: the field before baking is `L`-Lipschitz (clamp, min, max, smin, smax of
//! `L`- and 1-Lipschitz terms), the bilinear weights are a convex combination of exact
//! samples each within `L |p - corner|`, `sum w_i |p - q_i| <= h / sqrt(2)` on a lattice
//! square, and every later event is non-expansive in `d`. Re-baking samples at the same
//! lattice points, where the interpolant is exact, so the error does not accumulate. The
//! gradient and the material of a brick cell are approximations. Each cell holds at most
//! one brick, so brick memory is bounded by the cell count times `(n+1)^2` samples.

mod bake;
mod batch;
mod brick_walk;
mod carve_lanes;
mod cell_tapes;
mod compact;
mod error;
mod eval;
mod event_log;
mod field;
mod flats;
pub(crate) mod grid;
mod limits;
mod maintain;
mod options;
mod proof;
mod ray;
mod rollback;
mod square_walk;
mod state;

use std::collections::BTreeSet;

use glam::Vec2;

use super::event::{Event, EventKind};
use super::sdf::Sdf;
use cell_tapes::CellTapes;
use craterfield_core::backend::Backend;
pub use error::TerrainError;
use event_log::EventLog;
use grid::{Cell, PartialBake};
pub use grid::{
    CellState, CellView, Grid, GridError, GridStats, MAX_BRICK_RESOLUTION, MAX_CELLS,
    MaterialSource, RollbackError, TerrainMark,
};
pub use limits::{MAX_BRICK_BYTES, MAX_CELL_TAPE_BYTES, MAX_COORD};
pub use options::TerrainOptions;
pub use proof::{CellBounds, EventDiscs, RectSign};
pub use state::TerrainState;

/// A base field with carves and fills applied, queried through an explosion grid.
#[derive(Clone, Debug)]
pub struct Terrain<F: Sdf> {
    base: F,
    options: TerrainOptions,
    bounds: (Vec2, Vec2),
    tick: u32,
    events: EventLog,
    grid: Grid,
    /// Cells whose list exceeds the cap (they wait for a bake, or unsettled events block it).
    over_cap: BTreeSet<usize>,
    /// The brick being baked at tick ends, a few rows per tick (see `bake`).
    baking: Option<PartialBake>,
    /// The base's per-cell tapes, when the base is a tape program (a level graph).
    cell_tapes: Option<CellTapes>,
    /// The backend of batch queries.
    backend: Backend,
    /// The next cell revision to hand out (never reused, not rolled back).
    next_revision: u64,
    /// Events compaction dropped from the log (not rolled back: they were unreachable).
    forgotten: u64,
    /// Events the log kept after the last compaction (when the next one is due).
    kept_after_compaction: usize,
}

impl<F: Sdf> Terrain<F> {
    /// A terrain over `base` for events centred in `[bounds_min, bounds_max]`.
    pub fn new(
        base: F,
        bounds_min: Vec2,
        bounds_max: Vec2,
        options: TerrainOptions,
    ) -> Result<Self, TerrainError> {
        let (min, max) = options.check(bounds_min, bounds_max)?;
        let grid = Grid::new(min, max, options.cell_size, options.brick_resolution)?;
        let cell_tapes = base
            .program()
            .map(|program| CellTapes::new(program, &grid, options.band));
        Ok(Terrain {
            base,
            options,
            bounds: (bounds_min, bounds_max),
            tick: 0,
            events: EventLog::with_room(options.max_events),
            grid,
            over_cap: BTreeSet::new(),
            baking: None,
            cell_tapes,
            backend: Backend::best(),
            next_revision: 1,
            forgotten: 0,
            kept_after_compaction: 0,
        })
    }

    /// Specializes the base's program to every grid cell now, as a level load would,
    /// instead of at each cell's first use. A cell's first query, bake or explosion
    /// otherwise pays for it (10 to 45 us on a height-profile level of 1,025 points,
    /// measured by `bench field --peers`), inside whatever tick first touches the cell.
    /// Changes no result; does nothing when the base is not a tape program.
    pub fn prepare(&self) {
        if let Some(tapes) = &self.cell_tapes {
            tapes.build_all(&self.grid);
        }
    }

    /// The base field.
    pub fn base(&self) -> &F {
        &self.base
    }

    /// The options the terrain was built with.
    pub fn options(&self) -> &TerrainOptions {
        &self.options
    }

    /// The bounds event centres must lie in: `(min, max)`.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        self.bounds
    }

    /// The events the log holds, in the order they were applied: every event applied so
    /// far while [`Terrain::history_complete`], else the ones compaction kept (see
    /// [`Terrain::compact_history`]). Cell lists index into it.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// The current tick (growing events and events with a later tick depend on it).
    pub fn tick(&self) -> u32 {
        self.tick
    }

    /// The explosion grid (read-only, for diagnostics).
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Checks `e` against the options and bounds without changing anything.
    pub fn validate_event(&self, e: &Event) -> Result<(), TerrainError> {
        self.check_event(e)?;
        self.cells_with_room(e).map(drop)
    }

    /// The checks of an event on its own: valid, within the options' sizes and the bounds,
    /// of a known material.
    fn check_event(&self, e: &Event) -> Result<(), TerrainError> {
        e.validate()?;
        let o = &self.options;
        let r = e.radius_f32();
        if r > o.max_event_radius {
            return Err(TerrainError::RadiusTooLarge {
                radius: r,
                max: o.max_event_radius,
            });
        }
        let k = e.rim_f32();
        if k > o.max_rim {
            return Err(TerrainError::RimTooLarge {
                rim: k,
                max: o.max_rim,
            });
        }
        let c = e.center_f32();
        let (lo, hi) = self.bounds;
        if !(c.x >= lo.x && c.x <= hi.x && c.y >= lo.y && c.y <= hi.y) {
            return Err(TerrainError::CenterOutOfBounds {
                center: c,
                min: lo,
                max: hi,
            });
        }
        if e.kind == EventKind::Fill && e.material >= o.material_count {
            return Err(TerrainError::BadMaterial {
                material: e.material,
                count: o.material_count,
            });
        }
        Ok(())
    }

    /// Applies an event. On error nothing changes. When the log is full
    /// ([`TerrainOptions::max_events`]) it is compacted first, which changes no query.
    pub fn apply(&mut self, e: Event) -> Result<(), TerrainError> {
        self.check_event(&e)?;
        // Found once: compacting the log renumbers events but moves no cell.
        let cells = self.cells_with_room(&e)?;
        self.compact_if_full();
        if self.events.len() >= u32::MAX as usize {
            return Err(TerrainError::LogFull {
                kept: self.events.len(),
            });
        }
        let idx = self.events.len() as u32;
        self.events.push(e);
        self.grid.record_event();
        self.insert_into(idx, e, &cells);
        Ok(())
    }

    /// Sets the current tick. Moving forwards bakes lists that wait past the cap
    /// ([`TerrainOptions::bake_rows_per_tick`] lattice rows per tick advanced); moving backwards
    /// rebuilds the grid from the events (cost of a replay), which needs the whole
    /// history: once compaction has dropped events it is
    /// [`TerrainError::HistoryCompacted`] and nothing changes (roll back to a
    /// [`TerrainMark`] instead).
    pub fn set_tick(&mut self, tick: u32) -> Result<(), TerrainError> {
        if tick < self.tick {
            self.check_rebuild(tick)?;
            self.tick = tick;
            self.rebuild();
        } else if tick > self.tick {
            self.grid.record_tick(self.tick);
            let advanced = (tick - self.tick) as usize;
            self.tick = tick;
            self.bake_pending(self.bake_budget(advanced));
        }
        Ok(())
    }

    /// A revision number never handed out before.
    fn new_revision(&mut self) -> u64 {
        take_revision(&mut self.next_revision)
    }

    /// Starts a change of `cell`: the grid journals its pre-image (with whether it is over
    /// its cap now) and the cell takes a fresh revision. Returns the cell for the change's
    /// first edit; the later ones go through [`Grid::edit_recorded_cell`].
    fn begin_cell_change(&mut self, cell: usize) -> Option<&mut Cell> {
        let revision = self.new_revision();
        let over_cap = self.over_cap.contains(&cell);
        let c = self.grid.record_and_edit_cell(cell, over_cap)?;
        c.revision = revision;
        Some(c)
    }

    /// A number that changes whenever the field at `p` may change, or `None` while it
    /// depends on the tick (growing or not yet started events reach `p`'s cell). Equal
    /// stamps at the same point mean bit-identical results, so callers can cache samples
    /// of points that do not move (bodies at rest) by it.
    pub fn region_stamp(&self, p: Vec2) -> Option<u64> {
        // Outside the grid no event reaches: the field there never changes.
        let Some(cell) = self.grid.cell_index(p) else {
            return Some(0);
        };
        let c = self.grid.stored_cell(cell)?;
        (self.tick >= c.settled_at).then_some(c.revision)
    }

    /// Number of events a query at `p` applies (its cell's list length; 0 outside the grid).
    pub fn cell_event_count(&self, p: Vec2) -> usize {
        self.grid
            .cell_index(p)
            .and_then(|i| self.grid.stored_cell(i))
            .map_or(0, |c| c.events.len())
    }

    /// The state of the cell holding `p` (`None` outside the grid).
    pub fn cell_state(&self, p: Vec2) -> Option<CellState> {
        self.grid
            .cell_index(p)
            .and_then(|i| self.grid.stored_cell(i))
            .map(|c| c.state.0)
    }

    /// The documented distance error bound of brick cells, `L * h / sqrt(2)`.
    pub fn brick_error_bound(&self) -> f32 {
        self.lipschitz() * self.grid.brick_spacing() * std::f32::consts::FRAC_1_SQRT_2
    }

    /// Bytes of the distinct specialized tapes the cells keep (at most
    /// [`MAX_CELL_TAPE_BYTES`]; cells that specialize alike count once).
    pub fn cell_tape_bytes(&self) -> usize {
        self.cell_tapes.as_ref().map_or(0, CellTapes::bytes)
    }

    /// Grid counters.
    pub fn stats(&self) -> GridStats {
        let mut s = self.grid.counters();
        s.cells = self.grid.cell_count();
        s.bricks = self.grid.live_bricks();
        s.over_cap_cells = self.over_cap.len();
        for c in self.grid.stored_cells() {
            s.max_cell_events = s.max_cell_events.max(c.events.len());
            s.total_cell_events += c.events.len();
            match c.state.0 {
                CellState::Base => {}
                CellState::Air(_) => s.air_cells += 1,
                CellState::Solid(_) => s.solid_cells += 1,
                CellState::Brick(_) => s.brick_cells += 1,
            }
        }
        s
    }
}

/// Hands out the next revision of `counter`: a number it never handed out before.
fn take_revision(counter: &mut u64) -> u64 {
    *counter += 1;
    *counter
}
