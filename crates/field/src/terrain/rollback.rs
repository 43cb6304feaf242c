//! Rolling a terrain back: the public mark/rollback API over the undo journal the grid
//! keeps, and the undoing of what the terrain holds outside the grid (the event log, the
//! tick, the over-cap set, the partial bake).

use super::Terrain;
use super::grid::{Entry, RollbackError, TerrainMark};
use crate::sdf::Sdf;

impl<F: Sdf> Terrain<F> {
    /// Starts keeping an undo journal, so that [`Terrain::mark`] and [`Terrain::rollback`]
    /// work. Each change then also stores what it overwrote (a few cells per event), until
    /// [`Terrain::forget_before`] drops it.
    pub fn enable_rollback(&mut self) {
        self.grid.enable_journal();
    }

    /// The current position in the terrain's history, if rollback is enabled.
    pub fn mark(&self) -> Option<TerrainMark> {
        self.grid.mark(self.events_applied())
    }

    /// Returns to `mark`: events applied and tick changes made since are undone, in
    /// reverse. Costs the number of changes since the mark (a few cells per event), not the
    /// size of the terrain. On error nothing changes.
    ///
    /// A rebuild (moving the tick backwards with [`Terrain::set_tick`]) forgets the history.
    pub fn rollback(&mut self, mark: &TerrainMark) -> Result<(), RollbackError> {
        let (events, tick, over_cap) = (&mut self.events, &mut self.tick, &mut self.over_cap);
        let baking = &mut self.baking;
        self.grid.rewind_to(mark, |entry| match *entry {
            Entry::Event => {
                events.pop();
            }
            Entry::Tick(t) => *tick = t,
            Entry::Cell {
                cell,
                over_cap: was_over,
                ..
            } => {
                if was_over {
                    over_cap.insert(cell);
                } else {
                    over_cap.remove(&cell);
                }
            }
            Entry::BakeStarted => *baking = None,
            Entry::BakeRows(len) => {
                if let Some(b) = baking {
                    b.rows.values.truncate(len);
                    b.rows.materials.truncate(len);
                }
            }
            Entry::BakeEnded(ref bake) => *baking = Some(bake.clone()),
            // The grid restores these itself.
            Entry::Brick { .. } | Entry::BrickPushed => {}
            Entry::FreePushed | Entry::FreePopped(_) => {}
        })
    }

    /// Forgets the history before `mark` (older marks can no longer be rolled back to),
    /// bounding the journal's memory.
    pub fn forget_before(&mut self, mark: &TerrainMark) {
        self.grid.forget_before(mark);
    }

    /// Journal entries kept (0 when rollback is off).
    pub fn journal_len(&self) -> usize {
        self.grid.journal_len()
    }
}
