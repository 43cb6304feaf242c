//! Rolling a terrain back: the public mark/rollback API over the undo journal, and the
//! recording and undoing of one cell's pre-image.

use super::Terrain;
use super::journal::{Entry, Journal, RollbackError, TerrainMark};
use crate::sdf::Sdf;

impl<F: Sdf> Terrain<F> {
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
        Some(j.mark(self.grid.stats, self.events_applied()))
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

    /// Records `cell`'s pre-image before a change.
    pub(super) fn record_cell(&mut self, cell: usize) {
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
    pub(super) fn undo(&mut self, entry: Entry) {
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
}
