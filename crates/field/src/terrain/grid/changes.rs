//! Every change to the grid's contents, and the undo journal's life.
//!
//! The grid is the journal's one owner: each method here that changes a cell, a brick slot
//! or the free list records the pre-image first and mutates after, so the terrain decides
//! *what* changes and cannot forget to make it undoable. The entries are pushed in the
//! order the terrain's changes happen, which is what makes a rollback restore the exact
//! bytes. The changes that cannot be undone entry by entry either forget the history (a
//! rebuild, a restored state) or rewrite it alike (compaction renumbering the lists).
//!
//! One pre-image undoes a whole change of a cell: [`Grid::record_and_edit_cell`] records it
//! and [`Grid::edit_recorded_cell`] and [`Grid::set_state`] make the further edits of the
//! same change without recording again (checked in debug builds).

use super::journal::{Entry, Journal, RollbackError, TerrainMark};
use super::{
    Brick, Cell, CellFlats, CellLows, CellState, CellStateSlot, Grid, GridStats, PartialBake,
};

impl Grid {
    /// Forgets what the grid keeps derived from cell `cell` (its ray bound and flat
    /// squares): the cell is about to change.
    fn forget_bounds(&mut self, cell: usize) {
        self.lows.forget(cell);
        self.flats.forget(cell);
    }

    /// Starts keeping the undo journal (nothing changes when it is kept already).
    pub(in crate::terrain) fn enable_journal(&mut self) {
        if self.journal.is_none() {
            self.journal = Some(Journal::default());
        }
    }

    /// The current position in the history, with the counters to restore and `events`
    /// (the terrain's events applied so far); `None` when journaling is off.
    pub(in crate::terrain) fn mark(&self, events: u64) -> Option<TerrainMark> {
        Some(self.journal.as_ref()?.mark(self.stats, events))
    }

    /// Entries kept (0 when journaling is off).
    pub(in crate::terrain) fn journal_len(&self) -> usize {
        self.journal.as_ref().map_or(0, Journal::len)
    }

    /// Events appended since the oldest kept entry (0 when journaling is off): an undo may
    /// pop them off the log, so compaction must keep them.
    pub(in crate::terrain) fn poppable_events(&self) -> usize {
        self.journal.as_ref().map_or(0, Journal::appended_events)
    }

    /// The journaled pre-images of cells, oldest first.
    #[cfg(test)]
    pub(in crate::terrain) fn journal_cell_images(&self) -> impl Iterator<Item = &Cell> {
        self.journal.iter().flat_map(Journal::cell_images)
    }

    /// Every list of event indices the terrain may read again: each cell's, then each
    /// journaled pre-image's (an undo puts those back). Compaction keeps what they hold.
    pub(in crate::terrain) fn event_lists(&self) -> impl Iterator<Item = &[u32]> {
        let images = self.journal.iter().flat_map(Journal::cell_images);
        self.cells.iter().chain(images).map(|c| &c.events[..])
    }

    /// Forgets the history before `mark` (older marks become too old), bounding the
    /// journal's memory.
    pub(in crate::terrain) fn forget_before(&mut self, mark: &TerrainMark) {
        if let Some(j) = &mut self.journal {
            j.forget_before(mark);
        }
    }

    /// Returns to `mark`: pops every newer entry, newest first, hands it to
    /// `undo_outside` to restore what the terrain keeps outside the grid (the event log,
    /// the tick, the over-cap set), restores the grid's part, and at the end puts back the
    /// counters of the mark. On error nothing changes.
    pub(in crate::terrain) fn rewind_to(
        &mut self,
        mark: &TerrainMark,
        mut undo_outside: impl FnMut(&Entry),
    ) -> Result<(), RollbackError> {
        self.journal
            .as_ref()
            .ok_or(RollbackError::Disabled)?
            .check(mark)?;
        while let Some(entry) = self.journal.as_mut().and_then(|j| j.pop_after(mark.pos())) {
            undo_outside(&entry);
            self.undo(entry);
        }
        self.stats = mark.stats();
        self.recorded_cell = None;
        Ok(())
    }

    /// Restores a grid-level pre-image (the kinds the grid does not hold are left to the
    /// caller of [`Grid::rewind_to`]).
    fn undo(&mut self, e: Entry) {
        match e {
            Entry::Cell { cell, before, .. } => {
                if let Some(c) = self.cells.get_mut(cell) {
                    *c = before;
                    self.forget_bounds(cell);
                }
            }
            Entry::Brick { id, before } => {
                if let Some(slot) = self.bricks.get_mut(id as usize) {
                    *slot = before;
                }
            }
            Entry::BrickPushed => {
                self.bricks.pop();
            }
            Entry::FreePushed => {
                self.free_bricks.pop();
            }
            Entry::FreePopped(id) => self.free_bricks.push(id),
            Entry::Event
            | Entry::Tick(_)
            | Entry::BakeStarted
            | Entry::BakeRows(_)
            | Entry::BakeEnded(_) => {}
        }
    }

    /// Records a pre-image when journaling.
    fn record(&mut self, e: Entry) {
        if let Some(j) = &mut self.journal {
            j.push(e);
        }
    }

    /// Records that the terrain appended an event to its log (an undo pops it).
    pub(in crate::terrain) fn record_event(&mut self) {
        self.record(Entry::Event);
    }

    /// Records that the terrain started a partial bake (an undo drops it).
    pub(in crate::terrain) fn record_bake_started(&mut self) {
        self.record(Entry::BakeStarted);
    }

    /// Records that the partial bake, holding `len` samples, takes more rows (an undo
    /// truncates it back).
    pub(in crate::terrain) fn record_bake_rows(&mut self, len: usize) {
        self.record(Entry::BakeRows(len));
    }

    /// Records the partial bake the terrain installs or cancels (an undo puts it back).
    pub(in crate::terrain) fn record_bake_ended(&mut self, bake: &PartialBake) {
        if self.journal.is_some() {
            self.record(Entry::BakeEnded(bake.clone()));
        }
    }

    /// Records the tick `before` the terrain moves it forwards (an undo puts it back).
    pub(in crate::terrain) fn record_tick(&mut self, before: u32) {
        self.record(Entry::Tick(before));
    }

    /// Starts a change of `cell`: records its pre-image, with whether the terrain counts it
    /// over its cap then, and hands the cell out. `None`, and nothing recorded, past the
    /// end. The change's further edits go through [`Grid::edit_recorded_cell`] and
    /// [`Grid::set_state`]: this one image undoes them all.
    pub(in crate::terrain) fn record_and_edit_cell(
        &mut self,
        cell: usize,
        over_cap: bool,
    ) -> Option<&mut Cell> {
        self.recorded_cell = Some(cell);
        self.forget_bounds(cell);
        let c = self.cells.get_mut(cell)?;
        if let Some(j) = &mut self.journal {
            let before = c.clone();
            j.push(Entry::Cell {
                cell,
                before,
                over_cap,
            });
        }
        Some(c)
    }

    /// `cell` again, for a further edit of the change [`Grid::record_and_edit_cell`]
    /// started: its pre-image already undoes this edit, so nothing is recorded.
    pub(in crate::terrain) fn edit_recorded_cell(&mut self, cell: usize) -> Option<&mut Cell> {
        self.debug_check_recorded(cell);
        self.forget_bounds(cell);
        self.cells.get_mut(cell)
    }

    /// Debug builds: `cell` is the one whose change recorded a pre-image, so an edit of it
    /// can be undone.
    fn debug_check_recorded(&self, cell: usize) {
        debug_assert_eq!(
            self.recorded_cell,
            Some(cell),
            "cell {cell} edited without its pre-image in the journal"
        );
    }

    /// Sets the state of `cell`, within the change [`Grid::record_and_edit_cell`] started,
    /// freeing (and journaling) a brick it no longer references.
    pub(in crate::terrain) fn set_state(&mut self, cell: usize, state: CellState) {
        self.debug_check_recorded(cell);
        self.forget_bounds(cell);
        let Some(c) = self.cells.get_mut(cell) else {
            return;
        };
        let old = c.state.0.brick();
        c.state = CellStateSlot(state);
        let dropped = old.filter(|&id| state.brick() != Some(id));
        if let Some(id) = dropped.filter(|&id| (id as usize) < self.bricks.len()) {
            self.replace_brick(id, Brick::default());
            self.free_bricks.push(id);
            self.record(Entry::FreePushed);
        }
    }

    /// Stores a baked brick for `cell`, reusing the cell's current brick slot or a free one;
    /// returns its id. Brick count never exceeds the cell count.
    pub(in crate::terrain) fn store_brick(&mut self, cell: usize, brick: Brick) -> u32 {
        let current = self.cells.get(cell).and_then(|c| c.state.0.brick());
        let slot = current
            .filter(|&id| (id as usize) < self.bricks.len())
            .or_else(|| {
                let freed = self.free_bricks.pop()?;
                self.record(Entry::FreePopped(freed));
                Some(freed).filter(|&id| (id as usize) < self.bricks.len())
            });
        match slot {
            Some(id) => {
                self.replace_brick(id, brick);
                id
            }
            None => {
                self.bricks.push(brick);
                self.record(Entry::BrickPushed);
                (self.bricks.len() - 1) as u32
            }
        }
    }

    /// Overwrites brick slot `id`, journaling what it held.
    fn replace_brick(&mut self, id: u32, brick: Brick) {
        if let Some(slot) = self.bricks.get_mut(id as usize) {
            let before = std::mem::replace(slot, brick);
            if let Some(j) = &mut self.journal {
                j.push(Entry::Brick { id, before });
            }
        }
    }

    /// Counts a cell reset. The counters are not journaled entry by entry: a mark keeps
    /// them whole and a rollback puts them back.
    pub(in crate::terrain) fn count_reset(&mut self) {
        self.stats.resets += 1;
    }

    /// Counts `n` covered events dropped from a list (restored whole, like every counter).
    pub(in crate::terrain) fn count_pruned(&mut self, n: u64) {
        self.stats.pruned += n;
    }

    /// Counts a bake (restored whole, like every counter).
    pub(in crate::terrain) fn count_bake(&mut self) {
        self.stats.bakes += 1;
    }

    /// Makes every cell a fresh `Base` cell with an empty list and a revision from
    /// `fresh_revision` (asked in cell order), drops the bricks and the counters, and
    /// forgets the journal: a rebuild replays every event from here, so no mark from
    /// before it can be returned to.
    pub(in crate::terrain) fn restart(&mut self, mut fresh_revision: impl FnMut() -> u64) {
        for c in &mut self.cells {
            *c = Cell::default();
            c.revision = fresh_revision();
        }
        self.lows.forget_all();
        self.flats.forget_all();
        self.bricks.clear();
        self.free_bricks.clear();
        self.stats = GridStats::default();
        self.forget_all();
    }

    /// Replaces every cell, brick slot, the free list and the counters at once (a state
    /// snapshot the terrain has checked), and forgets the journal: the restored state
    /// starts a new history.
    pub(in crate::terrain) fn replace_contents(
        &mut self,
        cells: Vec<Cell>,
        bricks: Vec<Brick>,
        free_bricks: Vec<u32>,
        stats: GridStats,
    ) {
        self.lows = CellLows::new(cells.len());
        self.flats = CellFlats::new(cells.len());
        self.cells = cells;
        self.bricks = bricks;
        self.free_bricks = free_bricks;
        self.stats = stats;
        self.forget_all();
    }

    /// Forgets the whole history (the journal stays on): no earlier mark can be returned to.
    fn forget_all(&mut self) {
        if let Some(j) = &mut self.journal {
            j.reset();
        }
        self.recorded_cell = None;
    }

    /// Rewrites every event index of the cells' lists and of the journaled pre-images'
    /// through `renumber` (compaction dropped events). Each cell whose list changes, and
    /// every pre-image, takes a revision from `fresh_revision` (asked in cell order, then
    /// journal order), so a mirror that holds the old indices resends the cell. Nothing is
    /// recorded: the pre-images are rewritten alike, so an undo restores renumbered lists.
    pub(in crate::terrain) fn renumber_events(
        &mut self,
        renumber: &[u32],
        mut fresh_revision: impl FnMut() -> u64,
    ) {
        for c in &mut self.cells {
            let changed = c
                .events
                .iter()
                .any(|&i| renumber.get(i as usize) != Some(&i));
            if changed {
                c.revision = fresh_revision();
                c.events.renumber(renumber);
            }
        }
        for image in self.journal.iter_mut().flat_map(Journal::cell_images_mut) {
            image.events.renumber(renumber);
            image.revision = fresh_revision();
        }
    }
}
