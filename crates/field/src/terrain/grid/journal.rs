//! The undo journal: what each change of a terrain overwrote, so that rolling back to a
//! mark costs what changed since the mark, never the whole terrain.
//!
//! The grid owns it and alone writes to it: each of the grid's changing methods records the
//! pre-image before it mutates, so no caller can change a cell, a brick or the tick past the
//! journal. The changes that are not undone one by one forget the history instead (a
//! rebuild, a restored state) or rewrite it alike (compaction renumbers the pre-images'
//! lists with the cells').
//!
//! The event log is append-only (compaction drops only events no cell or pre-image holds,
//! and none the journal may pop, renumbering the pre-images with the cells) and the grid's
//! cells change only when an event is inserted or a tick change bakes a list, so every
//! change is recorded as the pre-image of what it touched: a cell (its state, list and
//! over-cap flag), a brick slot, one step of the brick free list, an appended event, or the
//! previous tick, or a step of the partial bake (see
//! `terrain::bake`). Undoing the entries in reverse restores the exact bytes, bricks included,
//! so a re-simulation after a rollback produces the same bits as a run that never rolled
//! back.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};

use thiserror::Error;

use super::cell::{Brick, Cell, GridStats, PartialBake};

/// One pre-image.
#[derive(Clone, Debug)]
pub(in crate::terrain) enum Entry {
    /// A cell before a change, and whether it was over its cap then.
    Cell {
        cell: usize,
        before: Cell,
        over_cap: bool,
    },
    /// A brick slot before it was overwritten.
    Brick { id: u32, before: Brick },
    /// A brick slot was appended.
    BrickPushed,
    /// An id was pushed onto the free list.
    FreePushed,
    /// This id was popped off the free list.
    FreePopped(u32),
    /// An event was appended to the log.
    Event,
    /// The tick before a tick change.
    Tick(u32),
    /// A partial bake was started (there was none).
    BakeStarted,
    /// Rows were appended to the partial bake, which held this many samples.
    BakeRows(usize),
    /// The partial bake was installed or cancelled: what it was.
    BakeEnded(PartialBake),
}

/// A position in a terrain's history that [`crate::Terrain::rollback`] can return
/// to. Cheap to copy; taking one costs nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TerrainMark {
    /// Journal entries recorded before the mark (counted from the journal's start).
    pos: u64,
    /// Serial number of the entry just before the mark (0 when there is none), to tell a
    /// mark on this timeline from one whose future was rolled back and rewritten, or from
    /// a clone's diverged timeline.
    serial: u64,
    /// The journal the mark was taken on (clones share it: their history is the same up
    /// to where they diverge, which the serials tell).
    origin: u64,
    /// The grid's counters at the mark.
    stats: GridStats,
    /// Events applied before the mark (over the terrain's life).
    events: u64,
}

impl TerrainMark {
    /// The journal position.
    pub(super) fn pos(&self) -> u64 {
        self.pos
    }

    /// The grid's counters at the mark.
    pub(super) fn stats(&self) -> GridStats {
        self.stats
    }

    /// Events applied before the mark, over the terrain's life (what
    /// [`crate::Terrain::events_applied`] returns after rolling back to it).
    pub fn events(&self) -> u64 {
        self.events
    }
}

/// Why a rollback was refused (the terrain is unchanged).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum RollbackError {
    /// Journaling is off (see [`crate::Terrain::enable_rollback`]).
    #[error("rollback is not enabled on this terrain")]
    Disabled,
    /// The history back to the mark was already forgotten (or reset by a rebuild).
    #[error(
        "the mark is older than the kept history (mark at entry {mark}, history starts at entry {kept})"
    )]
    TooOld {
        /// The mark's journal position.
        mark: u64,
        /// The oldest position still kept.
        kept: u64,
    },
    /// The mark belongs to a future that was rolled back and replaced, to another
    /// terrain, or to a clone of this one that has since diverged.
    #[error("the mark is not on the terrain's current timeline (journal entry {mark})")]
    NotOnTimeline {
        /// The mark's journal position.
        mark: u64,
    },
}

/// Serial numbers and journal origins, unique in the process: a mark from another
/// terrain, or from a clone that diverged, never matches by accident. They never reach the
/// terrain's state or any hash, so determinism does not depend on them.
static NEXT_SERIAL: AtomicU64 = AtomicU64::new(1);

fn next_serial() -> u64 {
    NEXT_SERIAL.fetch_add(1, Ordering::Relaxed)
}

/// The journal: entries with serial numbers, the oldest ones forgettable.
#[derive(Clone, Debug)]
pub(super) struct Journal {
    entries: VecDeque<(u64, Entry)>,
    /// Entries forgotten from the front: the position of `entries[0]`.
    start: u64,
    /// Serial number of the last forgotten entry (0 when none was): what a mark at
    /// `start` must name.
    start_serial: u64,
    /// Which journal this is (see [`NEXT_SERIAL`]).
    origin: u64,
}

impl Default for Journal {
    fn default() -> Self {
        Journal {
            entries: VecDeque::new(),
            start: 0,
            start_serial: 0,
            origin: next_serial(),
        }
    }
}

impl Journal {
    /// Records an entry.
    pub(super) fn push(&mut self, e: Entry) {
        self.entries.push_back((next_serial(), e));
    }

    /// Position after the last entry.
    fn end(&self) -> u64 {
        self.start + self.entries.len() as u64
    }

    /// A mark at the current end.
    pub(super) fn mark(&self, stats: GridStats, events: u64) -> TerrainMark {
        TerrainMark {
            pos: self.end(),
            serial: self.entries.back().map_or(self.start_serial, |e| e.0),
            origin: self.origin,
            stats,
            events,
        }
    }

    /// Whether `m` can be returned to.
    pub(super) fn check(&self, m: &TerrainMark) -> Result<(), RollbackError> {
        if m.origin != self.origin {
            return Err(RollbackError::NotOnTimeline { mark: m.pos });
        }
        if m.pos < self.start {
            return Err(RollbackError::TooOld {
                mark: m.pos,
                kept: self.start,
            });
        }
        if m.pos > self.end() {
            return Err(RollbackError::NotOnTimeline { mark: m.pos });
        }
        let before = match m.pos - self.start {
            0 => self.start_serial,
            n => self.entries.get((n - 1) as usize).map_or(0, |e| e.0),
        };
        if before != m.serial {
            return Err(RollbackError::NotOnTimeline { mark: m.pos });
        }
        Ok(())
    }

    /// Takes the newest entry if it is after `pos`.
    pub(super) fn pop_after(&mut self, pos: u64) -> Option<Entry> {
        if self.end() > pos {
            self.entries.pop_back().map(|e| e.1)
        } else {
            None
        }
    }

    /// Forgets the entries before `m` (marks older than it become [`RollbackError::TooOld`]).
    pub(super) fn forget_before(&mut self, m: &TerrainMark) {
        while self.start < m.pos {
            let Some((serial, _)) = self.entries.pop_front() else {
                break;
            };
            self.start_serial = serial;
            self.start += 1;
        }
    }

    /// Forgets everything (after a rebuild, which rewrites the whole grid).
    pub(super) fn reset(&mut self) {
        self.start = self.end();
        // A fresh serial: no mark from before the rebuild names it.
        self.start_serial = next_serial();
        self.entries.clear();
    }

    /// Entries kept.
    pub(super) fn len(&self) -> usize {
        self.entries.len()
    }

    /// Events appended since the oldest kept entry: the ones an undo may pop.
    pub(super) fn appended_events(&self) -> usize {
        self.entries
            .iter()
            .filter(|(_, e)| matches!(e, Entry::Event))
            .count()
    }

    /// The cell pre-images kept.
    pub(super) fn cell_images(&self) -> impl Iterator<Item = &Cell> {
        self.entries.iter().filter_map(|(_, e)| match e {
            Entry::Cell { before, .. } => Some(before),
            _ => None,
        })
    }

    /// The cell pre-images kept, to rewrite their lists when the log is compacted.
    pub(super) fn cell_images_mut(&mut self) -> impl Iterator<Item = &mut Cell> {
        self.entries.iter_mut().filter_map(|(_, e)| match e {
            Entry::Cell { before, .. } => Some(before),
            _ => None,
        })
    }
}
