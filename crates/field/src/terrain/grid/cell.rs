//! What the grid stores per cell and per brick, and the counters it keeps: plain data that
//! the grid and the terrain's undo journal both read, so it lives apart from the grid's code.

use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use super::flats::{Flats, brick_flats};
use super::floors::BlockFloors;
use crate::event::EventKind;
use crate::sample::MaterialId;

/// Where an air cell takes its material from (carves keep the material that was there).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum MaterialSource {
    /// The base field's material at the query point.
    Base,
    /// A constant material.
    Constant(MaterialId),
    /// The nearest lattice sample of a brick.
    Brick(u32),
}

/// What a cell's field is before its listed events are applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum CellState {
    /// The base field, clamped to the band.
    Base,
    /// Constant `+M`, zero gradient (the whole cell was carved away with margin).
    Air(MaterialSource),
    /// Constant `-M`, zero gradient, constant material (the whole cell was filled).
    Solid(MaterialId),
    /// A baked brick, bilinearly interpolated.
    Brick(u32),
}

impl CellState {
    /// The brick this state references, if any.
    pub fn brick(self) -> Option<u32> {
        match self {
            CellState::Brick(id) | CellState::Air(MaterialSource::Brick(id)) => Some(id),
            _ => None,
        }
    }
}

/// Counters describing a grid, for diagnostics and tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct GridStats {
    /// Number of cells.
    pub cells: usize,
    /// Longest event list of any cell (the per-query event cost bound).
    pub max_cell_events: usize,
    /// Sum of all list lengths.
    pub total_cell_events: usize,
    /// Bricks currently referenced by a cell.
    pub bricks: usize,
    /// Cells whose state is a brick.
    pub brick_cells: usize,
    /// Cells whose state is air.
    pub air_cells: usize,
    /// Cells whose state is solid.
    pub solid_cells: usize,
    /// Cells whose list is longer than the cap (only while they hold unsettled events).
    pub over_cap_cells: usize,
    /// Cell resets performed since the last rebuild.
    pub resets: u64,
    /// Bakes performed since the last rebuild.
    pub bakes: u64,
    /// Covered events dropped from lists since the last rebuild.
    pub pruned: u64,
}

/// One cell: base state and the indices (ascending) of the events that can reach it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Cell {
    pub(in crate::terrain) state: CellStateSlot,
    pub(in crate::terrain) events: super::EventList,
    /// Changes whenever the cell's field may change (a number never given to any other
    /// content of any cell of this terrain), so callers can cache values by it.
    pub(in crate::terrain) revision: u64,
    /// The tick from which every listed event is settled (the field stops depending on the
    /// tick).
    pub(in crate::terrain) settled_at: u32,
    /// Whether the list may hold a fill: set when one is listed, cleared only with the
    /// list (a removal leaves it set, which costs a query its shortcut, never its bits).
    /// Without a fill, a value at the band's top stays there through the whole list.
    pub(in crate::terrain) may_fill: bool,
}

impl Cell {
    /// Whether at `tick` the list is sharp carves alone, every one settled: then it applies
    /// as one running maximum (`terrain::field::sharp_carves`).
    pub(in crate::terrain) fn folds_carves(&self, tick: u32) -> bool {
        self.events.sharp_carves_only() && tick >= self.settled_at
    }

    /// Whether the list holds carves alone, so that it can only raise the field (a list
    /// that never held a fill needs no reading).
    #[inline]
    pub(in crate::terrain) fn lists_carves_only(&self) -> bool {
        !self.may_fill
            || self.events.sharp_carves_only()
            || self
                .events
                .listed()
                .iter()
                .all(|e| e.kind == EventKind::Carve)
    }
}

/// A `CellState` with a `Default` (Base).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CellStateSlot(pub(in crate::terrain) CellState);

impl Default for CellStateSlot {
    fn default() -> Self {
        CellStateSlot(CellState::Base)
    }
}

/// A baked `(n+1) x (n+1)` lattice of distances and materials, row-major (y outer), and
/// the floors of its blocks, computed when a ray first asks for them (a function of
/// `values` alone, so whenever and on whichever thread they are computed they are the same
/// bits; a bake or a restore pays nothing for them).
#[derive(Clone, Debug, Default)]
pub(crate) struct Brick {
    pub(in crate::terrain) values: Vec<f32>,
    pub(in crate::terrain) materials: Vec<MaterialId>,
    pub(in crate::terrain) floors: OnceLock<BlockFloors>,
    /// The squares where every sample a point of them interpolates is the band's top or
    /// bottom, and the one material of all samples if there is one; computed when a query
    /// first asks, like the floors.
    pub(in crate::terrain) flats: OnceLock<Flats>,
}

impl Brick {
    /// The floors of the brick's blocks (`n` its resolution).
    pub(in crate::terrain) fn floors(&self, n: u32) -> &BlockFloors {
        self.floors.get_or_init(|| BlockFloors::of(&self.values, n))
    }

    /// The brick's flat squares (`n` its resolution, `band` the terrain's).
    pub(in crate::terrain) fn flats(&self, n: u32, band: f32) -> Flats {
        *self
            .flats
            .get_or_init(|| brick_flats(&self.values, &self.materials, n, band))
    }
}

/// A brick being baked a few lattice rows per tick: the cell, how many of its listed
/// events (a settled prefix) it folds in, and the rows baked so far (the first rows of
/// the brick's lattice). Invisible to queries until the last row is baked and the brick
/// installed.
#[derive(Clone, Debug)]
pub(crate) struct PartialBake {
    pub(in crate::terrain) cell: usize,
    pub(in crate::terrain) prefix: usize,
    pub(in crate::terrain) rows: Brick,
}
