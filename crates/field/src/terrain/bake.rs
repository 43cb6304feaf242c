//! Baking over-long lists into bricks at tick ends, a bounded number of lattice rows per
//! tick, so that no tick pays for a whole brick.
//!
//! A list past the cap waits in the over-cap set. Each tick advance bakes
//! [`TerrainOptions::bake_rows_per_tick`](super::TerrainOptions::bake_rows_per_tick)
//! rows: those of the partial bake under way, then of the next over-cap cell in cell order
//! whose list starts with a settled event. A partial bake folds in the settled prefix its
//! cell had when it started; its rows are invisible to queries (the cell answers exactly
//! from its list) until the last one is baked, when the brick is installed as a whole bake
//! would install it. A change of the cell other than an appended event (a reset, a pruned
//! event, a bake at twice the cap) cancels it, since its prefix is no longer the list's.
//!
//! Which rows a tick bakes depends only on the terrain's history, never on time or
//! threads, and every step is journaled and carried by [`TerrainState`](super::TerrainState),
//! so rollbacks and restored states bake the same bricks at the same ticks.

use super::Terrain;
use super::grid::{Brick, PartialBake};
use crate::sdf::Sdf;

/// Lists that may wait past the cap before a tick advance bakes more rows: each further
/// `BACKLOG` waiting lists add `bake_rows_per_tick` rows, so that a flood of explosions
/// (tens per tick) cannot pile lists up to twice the cap, where every query in them applies
/// twice the events and each insert bakes whole.
const BACKLOG: usize = 4;

impl<F: Sdf> Terrain<F> {
    /// The lattice rows an advance by `advanced` ticks bakes: `bake_rows_per_tick` per tick,
    /// once more for every [`BACKLOG`] lists waiting past the cap (a function of the lists,
    /// so of the history alone).
    pub(super) fn bake_budget(&self, advanced: usize) -> usize {
        let scale = self.over_cap.len().div_ceil(BACKLOG).max(1);
        self.options
            .bake_rows_per_tick
            .saturating_mul(advanced)
            .saturating_mul(scale)
    }

    /// Bakes `budget` lattice rows at a tick advance: the partial bake's, then new ones in
    /// cell order; a bake whose last row is baked is installed.
    pub(super) fn bake_pending(&mut self, mut budget: usize) {
        let side = self.grid.brick_resolution() as usize + 1;
        let mut next = 0;
        while budget > 0 {
            let started_here = self.baking.is_none();
            if started_here {
                let Some(cell) = self.over_cap.range(next..).next().copied() else {
                    break;
                };
                next = cell + 1;
                let prefix = self.settled_prefix(cell);
                if prefix == 0 {
                    continue;
                }
                self.grid.record_bake_started();
                // The whole lattice's room at once: growing it row by row as the ticks
                // go copied up to a brick's samples inside one tick.
                self.baking = Some(PartialBake {
                    cell,
                    prefix,
                    rows: Brick {
                        values: Vec::with_capacity(side * side),
                        materials: Vec::with_capacity(side * side),
                        ..Brick::default()
                    },
                });
            }
            let Some(mut bake) = self.baking.take() else {
                break;
            };
            let (cell, prefix) = (bake.cell, bake.prefix);
            let done = bake.rows.values.len() / side;
            let take = budget.min(side - done);
            budget -= take;
            self.grid.record_bake_rows(bake.rows.values.len());
            self.bake_rows_onto(
                cell,
                prefix,
                done as u32..(done + take) as u32,
                &mut bake.rows,
            );
            self.baking = Some(bake);
            if done + take == side {
                self.finish_bake();
                // A bake carried over from an earlier advance may be past cells that
                // wait: the search goes on from where it was.
                if started_here {
                    next = cell + 1;
                }
            }
        }
    }

    /// Installs the completed partial bake as its cell's brick.
    fn finish_bake(&mut self) {
        let Some(bake) = self.baking.take() else {
            return;
        };
        self.grid.record_bake_ended(&bake);
        let cell = bake.cell;
        self.begin_cell_change(cell);
        self.over_cap.remove(&cell);
        self.install_brick(cell, bake.prefix, bake.rows);
        self.update_over_cap(cell);
    }

    /// Cancels the partial bake if it is `cell`'s (its prefix is about to change).
    pub(super) fn cancel_bake_of(&mut self, cell: usize) {
        if self.baking.as_ref().is_some_and(|b| b.cell == cell)
            && let Some(bake) = self.baking.take()
        {
            self.grid.record_bake_ended(&bake);
        }
    }

    /// The partial bake as `(cell, prefix, rows baked)`, for a state snapshot.
    pub(super) fn baking_progress(&self) -> Option<(u32, u32, u32)> {
        let side = self.grid.brick_resolution() as usize + 1;
        self.baking.as_ref().map(|b| {
            (
                b.cell as u32,
                b.prefix as u32,
                (b.rows.values.len() / side) as u32,
            )
        })
    }

    /// Rebakes the first `rows` rows of a partial bake of `cell`'s first `prefix` events (a
    /// restored state carries where the bake was, not its samples).
    pub(super) fn resume_bake(&mut self, cell: usize, prefix: usize, rows: u32) {
        let rows = self.bake_rows(cell, prefix, 0..rows);
        self.baking = Some(PartialBake { cell, prefix, rows });
    }
}
