//! A terrain's whole state as plain data: what a peer needs to continue from exactly where
//! another one is, bricks and a compacted log included, when replaying the history is not
//! possible (the log was compacted) or not wanted (a desync).
//!
//! The state is the tick, the kept events, and every cell that is not a fresh `Base` cell
//! with an empty list (its state, list and settle tick), the brick slots and the free list.
//! What is derived is rebuilt on restore (which cells are over their cap, revisions, the
//! per-cell tapes, the journal, the samples of the partial bake from where it was); none
//! of it changes a query's bits. A restored terrain
//! answers every query, and takes every later event, exactly as the one it was taken from.
//!
//! A state may come from a stranger: [`Terrain::restore_state`] checks every index, size,
//! material and value against the receiving terrain before it changes anything.

use serde::{Deserialize, Serialize};

use super::Terrain;
use super::error::TerrainError;
use super::grid::{Brick, Cell, CellState, CellStateSlot, EventList, GridStats, MaterialSource};
use crate::event::{Event, EventKind};
use crate::sample::MaterialId;
use crate::sdf::Sdf;

/// A terrain's whole state: the tick, the kept events, every cell that is not fresh and
/// the bricks. Taken by [`Terrain::state`], put back by [`Terrain::restore_state`] on a
/// terrain of the same base and options, which then answers every query and takes every
/// later event exactly as the original. What is derived (revisions, per-cell tapes, the
/// undo journal) is not part of it.
///
/// Stored as flat arrays, so that decoding one from bytes allocates at most a few times
/// the bytes' length (a list of small structs would cost tens of bytes per input byte).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TerrainState {
    tick: u32,
    forgotten: u64,
    events: Vec<Event>,
    /// The cells that are not fresh (`Base`, empty list, settle tick 0), ascending.
    cell_index: Vec<u32>,
    cell_state: Vec<CellState>,
    cell_settled: Vec<u32>,
    /// Each listed cell's list length; the lists follow one another in `lists`.
    list_len: Vec<u32>,
    lists: Vec<u32>,
    /// Each brick slot's sample count: `(n+1)^2`, or 0 for a free slot.
    brick_len: Vec<u32>,
    brick_values: Vec<f32>,
    brick_materials: Vec<MaterialId>,
    free_bricks: Vec<u32>,
    counters: GridStats,
    /// The partial bake (see `terrain::bake`): its cell, the listed events it folds in and
    /// the lattice rows baked so far. The rows are baked again on restore.
    baking: Option<(u32, u32, u32)>,
}

impl TerrainState {
    /// The terrain's tick.
    pub fn tick(&self) -> u32 {
        self.tick
    }

    /// Events applied over the terrain's life.
    pub fn events_applied(&self) -> u64 {
        self.forgotten + self.events.len() as u64
    }

    /// The listed cells, each with its state, settle tick and list.
    fn cells(&self) -> impl Iterator<Item = (u32, CellState, u32, &[u32])> {
        let mut start = 0usize;
        let lens = self.list_len.iter().map(|&n| n as usize);
        let rows = self
            .cell_index
            .iter()
            .zip(&self.cell_state)
            .zip(&self.cell_settled);
        rows.zip(lens).map(move |(((&i, &state), &settled), n)| {
            let list = self.lists.get(start..start + n).unwrap_or(&[]);
            start += n;
            (i, state, settled, list)
        })
    }

    /// The brick slots' samples, in slot order.
    fn bricks(&self) -> impl Iterator<Item = (&[f32], &[MaterialId])> {
        let mut start = 0usize;
        self.brick_len.iter().map(move |&n| {
            let range = start..start + n as usize;
            start = range.end;
            (
                self.brick_values.get(range.clone()).unwrap_or(&[]),
                self.brick_materials.get(range).unwrap_or(&[]),
            )
        })
    }
}

fn bad(detail: String) -> TerrainError {
    TerrainError::BadState { detail }
}

/// The flat arrays agree with one another: one row per listed cell, the lists and the
/// brick samples exactly as long as their lengths add up to.
fn check_shape(s: &TerrainState) -> Result<(), TerrainError> {
    let rows = s.cell_index.len();
    if s.cell_state.len() != rows || s.cell_settled.len() != rows || s.list_len.len() != rows {
        return Err(bad("the cell columns differ in length".into()));
    }
    let listed: u64 = s.list_len.iter().map(|&n| u64::from(n)).sum();
    if listed != s.lists.len() as u64 {
        return Err(bad(format!(
            "the lists hold {} entries, their lengths add up to {listed}",
            s.lists.len()
        )));
    }
    let samples: u64 = s.brick_len.iter().map(|&n| u64::from(n)).sum();
    if samples != s.brick_values.len() as u64 || samples != s.brick_materials.len() as u64 {
        return Err(bad(format!(
            "the bricks hold {} values and {} materials, their lengths add up to {samples}",
            s.brick_values.len(),
            s.brick_materials.len()
        )));
    }
    Ok(())
}

impl<F: Sdf> Terrain<F> {
    /// The terrain's whole state (see [`TerrainState`]).
    pub fn state(&self) -> TerrainState {
        let (bricks, free) = self.grid.brick_slots();
        let mut st = TerrainState {
            tick: self.tick,
            forgotten: self.forgotten,
            events: self.events.to_vec(),
            cell_index: Vec::new(),
            cell_state: Vec::new(),
            cell_settled: Vec::new(),
            list_len: Vec::new(),
            lists: Vec::new(),
            brick_len: bricks.iter().map(|b| b.values.len() as u32).collect(),
            brick_values: bricks
                .iter()
                .flat_map(|b| b.values.iter().copied())
                .collect(),
            brick_materials: bricks
                .iter()
                .flat_map(|b| b.materials.iter().copied())
                .collect(),
            free_bricks: free.to_vec(),
            counters: self.grid.counters(),
            baking: self.baking_progress(),
        };
        for (i, c) in self.grid.stored_cells().iter().enumerate() {
            let fresh =
                matches!(c.state.0, CellState::Base) && c.events.is_empty() && c.settled_at == 0;
            if !fresh {
                st.cell_index.push(i as u32);
                st.cell_state.push(c.state.0);
                st.cell_settled.push(c.settled_at);
                st.list_len.push(c.events.len() as u32);
                st.lists.extend_from_slice(&c.events);
            }
        }
        st
    }

    /// Continues from `state`, taken from a terrain of the same base and options: every
    /// later query and event gives the bits the original would. The undo journal starts
    /// afresh (earlier marks are refused). A state that does not fit this terrain (an
    /// index, a size, a material or a value out of range) is [`TerrainError::BadState`],
    /// naming what, and nothing changes.
    pub fn restore_state(&mut self, state: &TerrainState) -> Result<(), TerrainError> {
        self.check_state(state)?;
        let mut cells = vec![Cell::default(); self.grid.cell_count()];
        for (i, cell_state, settled, list) in state.cells() {
            if let Some(c) = cells.get_mut(i as usize) {
                c.state = CellStateSlot(cell_state);
                c.events = EventList::from_log(list, &state.events).ok_or_else(|| {
                    bad(format!(
                        "cell {i} lists an event past the log's {}",
                        state.events.len()
                    ))
                })?;
                c.may_fill = list.iter().any(|&k| {
                    (state.events.get(k as usize)).is_none_or(|e| e.kind == EventKind::Fill)
                });
                c.settled_at = settled;
            }
        }
        for c in &mut cells {
            c.revision = self.new_revision();
        }
        let bricks = state
            .bricks()
            .map(|(values, materials)| Brick {
                values: values.to_vec(),
                materials: materials.to_vec(),
                ..Brick::default()
            })
            .collect();
        let cap = self.options.cell_cap;
        self.over_cap = (cells.iter().enumerate())
            .filter(|(_, c)| c.events.len() > cap)
            .map(|(i, _)| i)
            .collect();
        self.grid
            .replace_contents(cells, bricks, state.free_bricks.clone(), state.counters);
        self.tick = state.tick;
        self.forgotten = state.forgotten;
        // Into the log's own room: a restore does not give up its reservation.
        self.events.clear();
        self.events.extend_from_slice(&state.events);
        self.kept_after_compaction = self.events.len();
        self.baking = None;
        if let Some((cell, prefix, rows)) = state.baking {
            self.resume_bake(cell as usize, prefix as usize, rows);
        }
        Ok(())
    }

    fn check_state(&self, s: &TerrainState) -> Result<(), TerrainError> {
        for (i, e) in s.events.iter().enumerate() {
            self.check_event(e)
                .map_err(|err| bad(format!("event {i}: {err}")))?;
        }
        if s.events.len() >= u32::MAX as usize {
            return Err(bad(format!("{} events", s.events.len())));
        }
        check_shape(s)?;
        let owners = self.check_cells(s)?;
        self.check_bricks(s, &owners)?;
        self.check_baking(s)
    }

    /// The partial bake names a cell over the cap, a prefix of settled events of its list
    /// and fewer rows than a brick has.
    fn check_baking(&self, s: &TerrainState) -> Result<(), TerrainError> {
        let Some((at, prefix, rows)) = s.baking else {
            return Ok(());
        };
        let list = s.cells().find(|c| c.0 == at).map_or(&[][..], |c| c.3);
        if list.len() <= self.options.cell_cap {
            return Err(bad(format!(
                "the partial bake's cell {at} lists {} events, not more than the cap {}",
                list.len(),
                self.options.cell_cap
            )));
        }
        let settled = list.get(..prefix as usize).is_some_and(|p| {
            p.iter().all(|&i| {
                s.events
                    .get(i as usize)
                    .is_some_and(|e| e.is_settled(s.tick))
            })
        });
        if prefix == 0 || !settled {
            return Err(bad(format!(
                "the partial bake of cell {at} folds in {prefix} events, not a settled prefix of its {}",
                list.len()
            )));
        }
        let side = self.grid.brick_resolution() + 1;
        if rows >= side {
            return Err(bad(format!(
                "the partial bake of cell {at} has {rows} rows of {side}"
            )));
        }
        Ok(())
    }

    /// Cells: in range, ascending, lists ascending within the log and the per-cell limit,
    /// materials known. Returns which cell owns each brick slot.
    fn check_cells(&self, s: &TerrainState) -> Result<Vec<Option<u32>>, TerrainError> {
        let count = self.grid.cell_count();
        let mut owners = vec![None; s.brick_len.len()];
        let mut previous: Option<u32> = None;
        for (at, state, _, list) in s.cells() {
            if at as usize >= count || previous.is_some_and(|p| p >= at) {
                return Err(bad(format!(
                    "cell {at} is out of order or past the grid's {count} cells"
                )));
            }
            previous = Some(at);
            if list.len() > self.options.max_cell_events {
                return Err(bad(format!(
                    "cell {at} lists {} events (max_cell_events is {})",
                    list.len(),
                    self.options.max_cell_events
                )));
            }
            let ascending = list.windows(2).all(|w| w[0] < w[1]);
            let in_log = list.last().is_none_or(|&i| (i as usize) < s.events.len());
            if !(ascending && in_log) {
                return Err(bad(format!(
                    "cell {at} lists events that are not ascending indices into the {} kept",
                    s.events.len()
                )));
            }
            self.check_cell_state(at, state, &mut owners)?;
        }
        Ok(owners)
    }

    fn check_cell_state(
        &self,
        at: u32,
        state: CellState,
        owners: &mut [Option<u32>],
    ) -> Result<(), TerrainError> {
        let material = match state {
            CellState::Solid(m) | CellState::Air(MaterialSource::Constant(m)) => Some(m),
            _ => None,
        };
        if let Some(m) = material.filter(|&m| m >= self.options.material_count) {
            return Err(bad(format!(
                "cell {at} has material {m} (the level has {})",
                self.options.material_count
            )));
        }
        if let Some(id) = state.brick() {
            match owners.get_mut(id as usize) {
                Some(owner @ None) => *owner = Some(at),
                Some(Some(other)) => {
                    return Err(bad(format!("cells {other} and {at} share brick {id}")));
                }
                None => {
                    return Err(bad(format!(
                        "cell {at} names brick {id} of {}",
                        owners.len()
                    )));
                }
            }
        }
        Ok(())
    }

    /// Bricks: every slot owned by one cell (full, finite, in the band, known materials)
    /// or on the free list once (empty).
    fn check_bricks(&self, s: &TerrainState, owners: &[Option<u32>]) -> Result<(), TerrainError> {
        if s.brick_len.len() > self.grid.cell_count() {
            return Err(bad(format!(
                "{} brick slots for {} cells",
                s.brick_len.len(),
                self.grid.cell_count()
            )));
        }
        let mut free = vec![false; s.brick_len.len()];
        for &id in &s.free_bricks {
            match free.get_mut(id as usize) {
                Some(slot @ false) if owners.get(id as usize) == Some(&None) => *slot = true,
                _ => {
                    return Err(bad(format!(
                        "free brick {id} is out of range, listed twice or in use"
                    )));
                }
            }
        }
        let side = self.grid.brick_resolution() as usize + 1;
        let band = self.options.band;
        for (id, &n) in s.brick_len.iter().enumerate() {
            let used = owners.get(id).is_some_and(Option::is_some);
            if !used && !free.get(id).copied().unwrap_or(false) {
                return Err(bad(format!("brick {id} is neither used nor free")));
            }
            let len = if used { side * side } else { 0 };
            if n as usize != len {
                return Err(bad(format!("brick {id} holds {n} samples, not {len}")));
            }
        }
        if let Some(v) = s.brick_values.iter().find(|v| v.is_nan() || v.abs() > band) {
            return Err(bad(format!("a brick holds {v}, outside the band {band}")));
        }
        let count = self.options.material_count;
        if let Some(m) = s.brick_materials.iter().find(|&&m| m >= count) {
            return Err(bad(format!("a brick holds material {m} of {count}")));
        }
        Ok(())
    }
}
