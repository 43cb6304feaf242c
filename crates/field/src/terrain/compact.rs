//! Compacting the event log: forgetting the events no cell can reach any more, so a long
//! match stays destructible in bounded memory.
//!
//! An event leaves every cell list when a later carve or fill covers it, a cell reset
//! clears the list, or a bake folds it into a brick; lists never take an event back (only
//! a rebuild, which replays the whole log, does). An event that no list holds, and that no
//! pre-image of the undo journal holds either, therefore never affects a query again, so
//! dropping it and renumbering the rest changes no query's bits. Events the journal may
//! still pop (appended after the oldest journal entry) stay, so undo stays exact.
//!
//! What compaction gives up is the full history: a rebuild (moving the tick backwards)
//! and the brute-force references need every event, so after the first compaction the
//! former is refused ([`TerrainError::HistoryCompacted`]) and the latter describe only
//! the kept events. Whether and when a terrain compacted never changes a query's result,
//! so runs that compact at different moments (a re-simulation after a rollback, say) stay
//! bitwise equal.

use super::error::TerrainError;
use super::{Terrain, take_revision};
use crate::sdf::Sdf;

impl<F: Sdf> Terrain<F> {
    /// Events applied over the terrain's life: the ones in [`Terrain::events`] and the ones
    /// compaction forgot.
    pub fn events_applied(&self) -> u64 {
        self.forgotten + self.events.len() as u64
    }

    /// Whether [`Terrain::events`] still holds every event ever applied (no compaction
    /// has dropped one). Rebuilds and the brute-force references need it.
    pub fn history_complete(&self) -> bool {
        self.forgotten == 0
    }

    /// Drops the events no cell list and no journal pre-image holds (they can no longer
    /// change any query), renumbering the rest; returns how many were dropped. Queries
    /// give the same bits before and after. [`Terrain::apply`] calls it when the log
    /// reaches [`TerrainOptions::max_events`](super::TerrainOptions::max_events).
    pub fn compact_history(&mut self) -> usize {
        let keep = self.events_to_keep();
        let dropped = keep.iter().filter(|&&k| !k).count();
        if dropped == 0 {
            return 0;
        }
        let mut renumber = vec![u32::MAX; self.events.len()];
        let mut next = 0u32;
        for (slot, &k) in renumber.iter_mut().zip(&keep) {
            if k {
                *slot = next;
                next += 1;
            }
        }
        let mut kept = keep.iter();
        self.events.retain(|_| kept.next().copied().unwrap_or(true));
        // Every rewritten cell (and pre-image) takes a fresh revision: a mirror that sent
        // the old indices resends it.
        let revisions = &mut self.next_revision;
        self.grid
            .renumber_events(&renumber, || take_revision(revisions));
        self.forgotten += dropped as u64;
        dropped
    }

    /// Which events must stay: those listed by a cell or a journal pre-image, and those the
    /// journal may still pop.
    fn events_to_keep(&self) -> Vec<bool> {
        let n = self.events.len();
        let poppable = self.grid.poppable_events().min(n);
        let mut keep = vec![false; n];
        for k in keep.iter_mut().skip(n - poppable) {
            *k = true;
        }
        for list in self.grid.event_lists() {
            for &i in list {
                if let Some(k) = keep.get_mut(i as usize) {
                    *k = true;
                }
            }
        }
        keep
    }

    /// Compacts when the log is full and has grown since the last compaction by at least
    /// what that one kept, so the cost of compacting stays linear in the events applied.
    pub(super) fn compact_if_full(&mut self) {
        let threshold = self.options.max_events.max(2 * self.kept_after_compaction);
        if self.events.len() >= threshold {
            self.compact_history();
            self.kept_after_compaction = self.events.len();
        }
    }

    /// Refuses a rebuild once compaction has dropped events.
    pub(super) fn check_rebuild(&self, tick: u32) -> Result<(), TerrainError> {
        if self.history_complete() {
            Ok(())
        } else {
            Err(TerrainError::HistoryCompacted {
                tick,
                current: self.tick,
                forgotten: self.forgotten,
            })
        }
    }
}
