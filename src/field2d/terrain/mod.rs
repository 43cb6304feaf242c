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
//! [`Dual`] ([`Sdf::sample`]), so both give the same distance bits.
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
//!    into a brick: the cell's field (state + prefix, clamped) sampled exactly at an
//!    `(n+1) x (n+1)` lattice (spacing `h = cell_size / n`), values and materials. Queries in
//!    a brick cell interpolate bilinearly (gradient of the interpolant, material of the
//!    nearest lattice sample) and then apply the remaining events.
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

mod batch;
pub(crate) mod grid;
pub(crate) mod journal;
mod proof;
pub use proof::{CellBounds, EventDiscs, RectSign};
mod cell_tapes;

use std::collections::BTreeSet;

use glam::Vec2;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use self::grid::Brick;
use super::event::{Event, EventError, EventKind};
use super::exec;
use super::sample::{MaterialId, Sample};
use super::sdf::Sdf;
use super::simd::Backend;
use crate::det::math::{Dual, Num, V2, max, nclamp, nmax, nmin};
use crate::det::quant::FIXED_ONE;
use cell_tapes::{CellTape, CellTapes};
pub use grid::{
    CellState, CellView, Grid, GridError, GridStats, MAX_BRICK_RESOLUTION, MAX_CELLS,
    MaterialSource,
};
use journal::{Entry, Journal};
pub use journal::{RollbackError, TerrainMark};

/// Largest accepted world coordinate magnitude (bounds, and so event centres).
pub const MAX_COORD: f32 = 65536.0;

/// Most memory the bricks of one terrain may ever take (every cell baked): the grid size
/// and brick resolution are checked against it up front, so memory stays bounded whatever
/// the events.
pub const MAX_BRICK_BYTES: u64 = 1 << 30;

/// Tuning and limits of a [`Terrain`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TerrainOptions {
    /// Side of a grid cell, world units.
    pub cell_size: f32,
    /// The band `M`: distances are clamped to `[-M, M]`.
    pub band: f32,
    /// Longest event list a cell keeps before baking a brick.
    pub cell_cap: usize,
    /// Brick lattice intervals per cell side.
    pub brick_resolution: u32,
    /// Largest accepted event radius, world units.
    pub max_event_radius: f32,
    /// Largest accepted rim (blend width), world units.
    pub max_rim: f32,
    /// Most events a terrain accepts.
    pub max_events: usize,
    /// Fills must use a material below this.
    pub material_count: u16,
}

impl Default for TerrainOptions {
    fn default() -> Self {
        TerrainOptions {
            cell_size: 64.0,
            band: 32.0,
            cell_cap: 48,
            brick_resolution: 32,
            max_event_radius: 512.0,
            max_rim: 64.0,
            max_events: 1_000_000,
            material_count: 256,
        }
    }
}

/// Why a terrain could not be built or an event not applied.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// A bound is NaN, infinite or beyond [`MAX_COORD`].
    #[error("terrain bound {name} = {value} must be finite with magnitude <= {MAX_COORD}")]
    BadBound {
        /// Which bound (`min.x`, ...).
        name: &'static str,
        /// The offending value.
        value: f32,
    },
    /// `bounds_min` is not below `bounds_max` on some axis.
    #[error("terrain bounds are empty: min {min} must be below max {max} on both axes")]
    EmptyBounds {
        /// Lower corner.
        min: Vec2,
        /// Upper corner.
        max: Vec2,
    },
    /// An option is out of its accepted range.
    #[error("terrain option {name} = {value} is invalid: {reason}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value, formatted.
        value: String,
        /// What is required.
        reason: &'static str,
    },
    /// The grid could not be built.
    #[error("terrain grid: {0}")]
    Grid(#[from] GridError),
    /// The event is malformed.
    #[error("invalid event: {0}")]
    Event(#[from] EventError),
    /// The event radius exceeds `max_event_radius`.
    #[error("event radius {radius} exceeds max_event_radius {max}")]
    RadiusTooLarge {
        /// The radius.
        radius: f32,
        /// The limit.
        max: f32,
    },
    /// The event rim exceeds `max_rim`.
    #[error("event rim {rim} exceeds max_rim {max}")]
    RimTooLarge {
        /// The rim.
        rim: f32,
        /// The limit.
        max: f32,
    },
    /// The event centre lies outside the terrain bounds.
    #[error("event center {center} lies outside the terrain bounds {min} .. {max}")]
    CenterOutOfBounds {
        /// The centre.
        center: Vec2,
        /// Lower bound.
        min: Vec2,
        /// Upper bound.
        max: Vec2,
    },
    /// A fill uses a material beyond `material_count`.
    #[error("fill material {material} is out of range (material_count is {count})")]
    BadMaterial {
        /// The material.
        material: MaterialId,
        /// The number of materials.
        count: u16,
    },
    /// The terrain already holds `max_events` events.
    #[error("too many events: the terrain already holds max_events = {max}")]
    TooManyEvents {
        /// The limit.
        max: usize,
    },
}

/// A base field with carves and fills applied, queried through an explosion grid.
#[derive(Clone, Debug)]
pub struct Terrain<F: Sdf> {
    base: F,
    options: TerrainOptions,
    bounds: (Vec2, Vec2),
    tick: u32,
    events: Vec<Event>,
    grid: Grid,
    /// Cells whose list exceeds the cap because unsettled events block baking.
    over_cap: BTreeSet<usize>,
    /// The base's per-cell tapes, when the base is a tape program (a level graph).
    cell_tapes: Option<CellTapes>,
    /// The backend of batch queries.
    backend: Backend,
    /// The next cell revision to hand out (never reused, not rolled back).
    next_revision: u64,
}

/// The numbers the field runs on: `f32` for distances, [`Dual`] for samples.
trait Lift: Num {
    /// Whether this path reports materials (the `f32` path does not need them).
    const MATERIAL: bool;
    fn point(p: Vec2) -> V2<Self>;
    /// The base field at `p`; `material` asks the `f32` path to report the material too.
    fn base<F: Sdf>(f: &F, p: Vec2, material: bool) -> (Self, MaterialId);
    /// The same from the base's tapes for the region holding `p`.
    fn tape(plan: &CellTape, p: Vec2, material: bool) -> (Self, MaterialId);
}

impl Lift for f32 {
    const MATERIAL: bool = false;
    fn point(p: Vec2) -> V2<f32> {
        V2::new(p.x, p.y)
    }
    fn base<F: Sdf>(f: &F, p: Vec2, material: bool) -> (f32, MaterialId) {
        if material {
            f.distance_material(p)
        } else {
            (f.distance(p), 0)
        }
    }
    fn tape(plan: &CellTape, p: Vec2, material: bool) -> (f32, MaterialId) {
        if material {
            exec::point::value(&plan.material, p)
        } else {
            (exec::point::value(&plan.value, p).0, 0)
        }
    }
}

impl Lift for Dual {
    const MATERIAL: bool = true;
    fn point(p: Vec2) -> V2<Dual> {
        let (x, y) = Dual::point(p);
        V2::new(x, y)
    }
    fn base<F: Sdf>(f: &F, p: Vec2, _material: bool) -> (Dual, MaterialId) {
        let s = f.sample(p);
        (
            Dual {
                v: s.distance,
                dx: s.gradient.x,
                dy: s.gradient.y,
            },
            s.material,
        )
    }
    fn tape(plan: &CellTape, p: Vec2, _material: bool) -> (Dual, MaterialId) {
        exec::point::dual(&plan.material, p)
    }
}

/// Smooth minimum (see the module doc); the select keeps `min`'s bits where `h == 0`.
fn smin<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmin(a, b);
    let h = nmax(N::constant(k) - (a - b).abs(), N::constant(0.0)) / N::constant(k);
    if h.value() > 0.0 {
        m - (h * h).scale(k).scale(0.25)
    } else {
        m
    }
}

/// Smooth maximum (see the module doc).
fn smax<N: Num>(a: N, b: N, k: f32) -> N {
    let m = nmax(a, b);
    let h = nmax(N::constant(k) - (a - b).abs(), N::constant(0.0)) / N::constant(k);
    if h.value() > 0.0 {
        m + (h * h).scale(k).scale(0.25)
    } else {
        m
    }
}

/// Applies one event at `p` (the field definition's loop body).
#[inline]
fn apply_event<N: Num>(
    d: N,
    mat: MaterialId,
    p: V2<N>,
    e: &Event,
    tick: u32,
    band: f32,
) -> (N, MaterialId) {
    let Some(r) = e.radius_at(tick) else {
        return (d, mat);
    };
    let c = p.minus(e.center_f32()).length().offset(-r);
    let k = e.rim_f32();
    match e.kind {
        EventKind::Carve => {
            let v = if k > 0.0 { smax(d, -c, k) } else { nmax(d, -c) };
            (nclamp(v, -band, band), mat)
        }
        EventKind::Fill => {
            // The fill wins where `nmin(d, c)` selects `c`.
            let keeps_d = d.value() < c.value();
            let wins = !keeps_d;
            let v = if k > 0.0 { smin(d, c, k) } else { nmin(d, c) };
            (nclamp(v, -band, band), if wins { e.material } else { mat })
        }
    }
}

/// Exact `f64` distance between two fixed-point centres, in world units.
fn center_dist(a: &Event, b: &Event) -> f64 {
    let dx = (i64::from(a.center[0]) - i64::from(b.center[0])) as f64;
    let dy = (i64::from(a.center[1]) - i64::from(b.center[1])) as f64;
    (dx * dx + dy * dy).sqrt() / f64::from(FIXED_ONE)
}

fn fixed_f64(v: i32) -> f64 {
    f64::from(v) / f64::from(FIXED_ONE)
}

/// `|cx| + |cy| + r + k` of an event, world units (for guards).
fn event_extent(e: &Event) -> f64 {
    fixed_f64(e.center[0]).abs()
        + fixed_f64(e.center[1]).abs()
        + fixed_f64(e.radius)
        + fixed_f64(e.rim)
}

fn check_positive(name: &'static str, value: f32, limit: f32) -> Result<(), TerrainError> {
    if value.is_finite() && value > 0.0 && value <= limit {
        Ok(())
    } else {
        Err(TerrainError::BadOption {
            name,
            value: value.to_string(),
            reason: "must be positive, finite and <= 65536",
        })
    }
}

impl TerrainOptions {
    /// Checks these options for a world `[bounds_min, bounds_max]` without allocating: the
    /// values' ranges, the grid's cell count and the most memory its bricks could take.
    /// Returns the rectangle the explosion grid covers (the bounds grown by the farthest
    /// reach of an event).
    pub fn check(&self, bounds_min: Vec2, bounds_max: Vec2) -> Result<(Vec2, Vec2), TerrainError> {
        for (name, value) in [
            ("min.x", bounds_min.x),
            ("min.y", bounds_min.y),
            ("max.x", bounds_max.x),
            ("max.y", bounds_max.y),
        ] {
            if !(value.is_finite() && value.abs() <= MAX_COORD) {
                return Err(TerrainError::BadBound { name, value });
            }
        }
        if !(bounds_min.x < bounds_max.x && bounds_min.y < bounds_max.y) {
            return Err(TerrainError::EmptyBounds {
                min: bounds_min,
                max: bounds_max,
            });
        }
        check_positive("cell_size", self.cell_size, MAX_COORD)?;
        check_positive("band", self.band, MAX_COORD)?;
        check_positive("max_event_radius", self.max_event_radius, MAX_COORD)?;
        if !(self.max_rim.is_finite() && self.max_rim >= 0.0 && self.max_rim <= MAX_COORD) {
            return Err(TerrainError::BadOption {
                name: "max_rim",
                value: self.max_rim.to_string(),
                reason: "must be finite, >= 0 and <= 65536",
            });
        }
        if self.cell_cap == 0 {
            return Err(TerrainError::BadOption {
                name: "cell_cap",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        if self.max_events == 0 || self.max_events > u32::MAX as usize {
            return Err(TerrainError::BadOption {
                name: "max_events",
                value: self.max_events.to_string(),
                reason: "must be in 1..=4294967295",
            });
        }
        if self.material_count == 0 {
            return Err(TerrainError::BadOption {
                name: "material_count",
                value: "0".into(),
                reason: "must be at least 1",
            });
        }
        let grow = self.max_event_radius + self.max_rim + self.band + 1.0;
        let (min, max) = (
            bounds_min - Vec2::splat(grow),
            bounds_max + Vec2::splat(grow),
        );
        let (nx, ny) = Grid::dims_for(min, max, self.cell_size, self.brick_resolution)?;
        let side = self.brick_resolution as u64 + 1;
        // f32 value + u16 material per lattice point.
        let worst = nx as u64 * ny as u64 * side * side * 6;
        if worst > MAX_BRICK_BYTES {
            return Err(TerrainError::BadOption {
                name: "brick_resolution",
                value: format!(
                    "{} ({nx}x{ny} cells could take {worst} bytes of bricks)",
                    self.brick_resolution
                ),
                reason: "cells x (resolution + 1)^2 x 6 bytes must stay within 1 GiB: lower the resolution or raise cell_size",
            });
        }
        Ok((min, max))
    }
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
            .map(|program| CellTapes::new(program, grid.cells.len(), options.band));
        Ok(Terrain {
            base,
            options,
            bounds: (bounds_min, bounds_max),
            tick: 0,
            events: Vec::new(),
            grid,
            over_cap: BTreeSet::new(),
            cell_tapes,
            backend: Backend::best(),
            next_revision: 1,
        })
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

    /// The events applied so far, in order.
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
        e.validate()?;
        let o = &self.options;
        if self.events.len() >= o.max_events {
            return Err(TerrainError::TooManyEvents { max: o.max_events });
        }
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

    /// Applies an event. On error nothing changes.
    pub fn apply(&mut self, e: Event) -> Result<(), TerrainError> {
        self.validate_event(&e)?;
        let idx = self.events.len() as u32;
        self.events.push(e);
        self.grid.record(Entry::Event);
        self.insert(idx);
        Ok(())
    }

    /// Sets the current tick. Moving forwards bakes lists that were waiting for growing
    /// events to settle; moving backwards rebuilds the grid from the events (cost of a replay).
    pub fn set_tick(&mut self, tick: u32) {
        if tick < self.tick {
            self.tick = tick;
            self.rebuild();
        } else if tick > self.tick {
            self.grid.record(Entry::Tick(self.tick));
            self.tick = tick;
            let pending: Vec<usize> = self.over_cap.iter().copied().collect();
            for cell in pending {
                self.record_cell(cell);
                let revision = self.new_revision();
                if let Some(c) = self.grid.cells.get_mut(cell) {
                    c.revision = revision;
                }
                self.over_cap.remove(&cell);
                self.compact(cell);
            }
        }
    }

    /// Starts keeping an undo journal, so that [`Terrain::mark`] and [`Terrain::rollback`]
    /// work. Each change then also stores what it overwrote (a few cells per event), until
    /// [`Terrain::forget_before`] drops it.
    pub fn enable_rollback(&mut self) {
        if self.grid.journal.is_none() {
            self.grid.journal = Some(Journal::default());
        }
    }

    /// The current position in the terrain's history, if rollback is enabled.
    pub fn mark(&self) -> Option<TerrainMark> {
        let j = self.grid.journal.as_ref()?;
        Some(j.mark(self.grid.stats, self.events.len() as u32))
    }

    /// Returns to `mark`: events applied and tick changes made since are undone, in
    /// reverse. Costs the number of changes since the mark (a few cells per event), not the
    /// size of the terrain. On error nothing changes.
    ///
    /// A rebuild (moving the tick backwards with [`Terrain::set_tick`]) forgets the history.
    pub fn rollback(&mut self, mark: &TerrainMark) -> Result<(), RollbackError> {
        let journal = self.grid.journal.as_mut().ok_or(RollbackError::Disabled)?;
        journal.check(mark)?;
        while let Some(entry) = self
            .grid
            .journal
            .as_mut()
            .and_then(|j| j.pop_after(mark.pos()))
        {
            self.undo(entry);
        }
        self.grid.stats = mark.stats();
        Ok(())
    }

    /// Forgets the history before `mark` (older marks can no longer be rolled back to),
    /// bounding the journal's memory.
    pub fn forget_before(&mut self, mark: &TerrainMark) {
        if let Some(j) = &mut self.grid.journal {
            j.forget_before(mark);
        }
    }

    /// Journal entries kept (0 when rollback is off).
    pub fn journal_len(&self) -> usize {
        self.grid.journal.as_ref().map_or(0, Journal::len)
    }

    /// A revision number never handed out before.
    fn new_revision(&mut self) -> u64 {
        self.next_revision += 1;
        self.next_revision
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
        let c = self.grid.cells.get(cell)?;
        (self.tick >= c.settled_at).then_some(c.revision)
    }

    /// Records `cell`'s pre-image before a change.
    fn record_cell(&mut self, cell: usize) {
        if self.grid.journal.is_none() {
            return;
        }
        if let Some(c) = self.grid.cells.get(cell) {
            let entry = Entry::Cell {
                cell,
                before: c.clone(),
                over_cap: self.over_cap.contains(&cell),
            };
            self.grid.record(entry);
        }
    }

    /// Restores one pre-image.
    fn undo(&mut self, entry: Entry) {
        match entry {
            Entry::Event => {
                self.events.pop();
            }
            Entry::Tick(t) => self.tick = t,
            Entry::Cell { cell, over_cap, .. } => {
                if over_cap {
                    self.over_cap.insert(cell);
                } else {
                    self.over_cap.remove(&cell);
                }
                self.grid.undo(entry);
            }
            other => self.grid.undo(other),
        }
    }

    /// Rebuilds the grid by replaying every event at the current tick.
    fn rebuild(&mut self) {
        self.grid.clear();
        for i in 0..self.grid.cells.len() {
            let revision = self.new_revision();
            if let Some(c) = self.grid.cells.get_mut(i) {
                c.revision = revision;
            }
        }
        if let Some(j) = &mut self.grid.journal {
            j.reset();
        }
        self.over_cap.clear();
        for idx in 0..self.events.len() as u32 {
            self.insert(idx);
        }
    }

    /// Lists event `idx` in every cell it can reach, then prunes those cells.
    fn insert(&mut self, idx: u32) {
        let Some(e) = self.events.get(idx as usize).copied() else {
            return;
        };
        let band = f64::from(self.options.band);
        let center = [fixed_f64(e.center[0]), fixed_f64(e.center[1])];
        let extent = event_extent(&e) + band;
        let reach = fixed_f64(e.radius) + fixed_f64(e.rim) + band;
        let settled_at = e.tick.saturating_add(u32::from(e.grow_ticks));
        for cell in self.grid.cells_touching(center, reach, extent) {
            self.record_cell(cell);
            let revision = self.new_revision();
            if let Some(c) = self.grid.cells.get_mut(cell) {
                c.events.push(idx);
                c.revision = revision;
                c.settled_at = c.settled_at.max(settled_at);
            }
            self.prune_new(cell, idx, &e);
            self.compact(cell);
        }
    }

    /// Cell reset and covered-event pruning for the event `idx` just appended to `cell`.
    fn prune_new(&mut self, cell: usize, idx: u32, e: &Event) {
        if !(e.is_sharp() && e.is_settled(self.tick)) {
            return;
        }
        let band = f64::from(self.options.band);
        let rect = self.grid.cell_rect(cell);
        let center = [fixed_f64(e.center[0]), fixed_f64(e.center[1])];
        let g = 2.0 * grid::guard(event_extent(e) + band, &rect);
        let Some(c) = self.grid.cells.get(cell) else {
            return;
        };
        // 1. Cell reset.
        if rect.far_dist(center) + band + g <= fixed_f64(e.radius) {
            let new_state = match e.kind {
                EventKind::Fill => Some(CellState::Solid(e.material)),
                EventKind::Carve => {
                    let has_fill = c.events.iter().any(|&i| {
                        self.events
                            .get(i as usize)
                            .is_none_or(|x| x.kind == EventKind::Fill)
                    });
                    if has_fill {
                        None
                    } else {
                        Some(CellState::Air(match c.state.0 {
                            CellState::Base => MaterialSource::Base,
                            CellState::Air(src) => src,
                            CellState::Solid(m) => MaterialSource::Constant(m),
                            CellState::Brick(id) => MaterialSource::Brick(id),
                        }))
                    }
                }
            };
            if let Some(state) = new_state {
                self.grid.set_state(cell, state);
                if let Some(c) = self.grid.cells.get_mut(cell) {
                    c.events.clear();
                }
                self.over_cap.remove(&cell);
                self.grid.stats.resets += 1;
                return;
            }
        }
        // 2. Covered events, within the run of sharp same-kind same-material events that
        //    ends with the new one.
        let list = &c.events;
        let Some(&last) = list.last() else { return };
        if last != idx {
            return;
        }
        let mut drop_new = false;
        let mut drop: Vec<usize> = Vec::new();
        for pos in (0..list.len().saturating_sub(1)).rev() {
            let Some(x) = list.get(pos).and_then(|&i| self.events.get(i as usize)) else {
                break;
            };
            let same_run = x.kind == e.kind
                && x.is_sharp()
                && (e.kind == EventKind::Carve || x.material == e.material);
            if !same_run {
                break;
            }
            if !x.is_settled(self.tick) {
                continue;
            }
            let dist = center_dist(x, e);
            let g = 2.0 * grid::guard(event_extent(x) + event_extent(e) + band, &rect);
            let (rx, re) = (fixed_f64(x.radius), fixed_f64(e.radius));
            if re >= rx + dist + g {
                drop.push(pos);
            } else if rx >= re + dist + g {
                drop_new = true;
                break;
            }
        }
        let Some(c) = self.grid.cells.get_mut(cell) else {
            return;
        };
        let mut pruned = drop.len() as u64;
        if drop_new {
            c.events.pop();
            pruned += 1;
        }
        // `drop` is in descending position order, so removals don't shift later ones.
        for pos in drop {
            if pos < c.events.len() {
                c.events.remove(pos);
            }
        }
        self.grid.stats.pruned += pruned;
    }

    /// Bakes the longest settled prefix of an over-long list into a brick.
    fn compact(&mut self, cell: usize) {
        let cap = self.options.cell_cap;
        let Some(c) = self.grid.cells.get(cell) else {
            return;
        };
        if c.events.len() <= cap {
            self.over_cap.remove(&cell);
            return;
        }
        let prefix = c
            .events
            .iter()
            .take_while(|&&i| {
                self.events
                    .get(i as usize)
                    .is_some_and(|e| e.is_settled(self.tick))
            })
            .count();
        if prefix > 0 {
            let n = self.grid.brick_resolution();
            let count = ((n + 1) * (n + 1)) as usize;
            let mut brick = Brick {
                values: Vec::with_capacity(count),
                materials: Vec::with_capacity(count),
            };
            for j in 0..=n {
                for i in 0..=n {
                    let q = self.grid.lattice_point(cell, i, j);
                    let (d, m) = self.eval_cell::<Dual, true>(q, cell, prefix);
                    brick.values.push(d.v);
                    brick.materials.push(m);
                }
            }
            let id = self.grid.store_brick(cell, brick);
            self.grid.set_state(cell, CellState::Brick(id));
            if let Some(c) = self.grid.cells.get_mut(cell) {
                c.events.drain(..prefix.min(c.events.len()));
            }
            self.grid.stats.bakes += 1;
        }
        if self
            .grid
            .cells
            .get(cell)
            .is_some_and(|c| c.events.len() > cap)
        {
            self.over_cap.insert(cell);
        } else {
            self.over_cap.remove(&cell);
        }
    }

    /// `clamp(base(p), -M, M)`.
    fn base_clamped<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: Option<usize>,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        if let Some(cell_tapes) = &self.cell_tapes {
            let plan = cell_tapes.get(&self.grid, cell);
            if let Some(c) = plan.clamped {
                let mat = if MAT || N::MATERIAL {
                    N::tape(plan, p, true).1
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
    fn base_at<N: Lift>(&self, p: Vec2, cell: Option<usize>, material: bool) -> (N, MaterialId) {
        match &self.cell_tapes {
            Some(cell_tapes) => N::tape(cell_tapes.get(&self.grid, cell), p, material),
            None => N::base(&self.base, p, material),
        }
    }

    /// The field at `p` in `cell` from the cell's state and the first `upto` listed events.
    fn eval_cell<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: usize,
        upto: usize,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        let Some(c) = self.grid.cells.get(cell) else {
            return self.base_clamped::<N, MAT>(p, None);
        };
        let pn = N::point(p);
        let (mut d, mut mat) = match c.state.0 {
            CellState::Base => self.base_clamped::<N, MAT>(p, Some(cell)),
            CellState::Air(src) => {
                let mat = if N::MATERIAL || MAT {
                    match src {
                        MaterialSource::Base => self.base_at::<N>(p, Some(cell), true).1,
                        MaterialSource::Constant(m) => m,
                        MaterialSource::Brick(id) => self.grid.brick_material(id, cell, p),
                    }
                } else {
                    0
                };
                (N::constant(m), mat)
            }
            CellState::Solid(mat) => (N::constant(-m), mat),
            CellState::Brick(id) => match self.grid.interpolate(id, cell, pn) {
                Some(x) => x,
                None => self.base_clamped::<N, MAT>(p, Some(cell)),
            },
        };
        for &i in c.events.iter().take(upto) {
            if let Some(e) = self.events.get(i as usize) {
                (d, mat) = apply_event(d, mat, pn, e, self.tick, m);
            }
        }
        (d, mat)
    }

    fn eval<N: Lift, const MAT: bool>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        match self.grid.cell_index(p) {
            Some(cell) => self.eval_cell::<N, MAT>(p, cell, usize::MAX),
            None => self.base_clamped::<N, MAT>(p, None),
        }
    }

    fn eval_brute<N: Lift>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        let pn = N::point(p);
        // The reference: the base's own evaluation (the graph walker for a level).
        let band = self.options.band;
        let (d0, mat0) = N::base(&self.base, p, true);
        let (mut d, mut mat) = (nclamp(d0, -band, band), mat0);
        for e in &self.events {
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

    /// Number of events a query at `p` applies (its cell's list length; 0 outside the grid).
    pub fn cell_event_count(&self, p: Vec2) -> usize {
        self.grid
            .cell_index(p)
            .and_then(|i| self.grid.cells.get(i))
            .map_or(0, |c| c.events.len())
    }

    /// The state of the cell holding `p` (`None` outside the grid).
    pub fn cell_state(&self, p: Vec2) -> Option<CellState> {
        self.grid
            .cell_index(p)
            .and_then(|i| self.grid.cells.get(i))
            .map(|c| c.state.0)
    }

    /// The documented distance error bound of brick cells, `L * h / sqrt(2)`.
    pub fn brick_error_bound(&self) -> f32 {
        self.lipschitz() * self.grid.brick_spacing() * std::f32::consts::FRAC_1_SQRT_2
    }

    /// Grid counters.
    pub fn stats(&self) -> GridStats {
        let mut s = self.grid.stats;
        s.cells = self.grid.cells.len();
        s.bricks = self.grid.live_bricks();
        s.over_cap_cells = self.over_cap.len();
        for c in &self.grid.cells {
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
}
