//! Keeping the explosion grid: listing a new event in the cells it reaches, the exact
//! pruning of those lists (cell resets and covered events), baking over-long lists into
//! bricks, and rebuilding everything after the tick moves back. The module doc of the
//! terrain proves the listing and the pruning bitwise equal to the brute force, and bounds
//! a brick's error.

use std::ops::Range;

use super::grid::{self, Brick, CellState, Listed, MaterialSource};
use super::{Terrain, TerrainError, take_revision};
use crate::event::{Event, EventKind};
use crate::sdf::Sdf;
use craterfield_core::det::quant::FIXED_ONE;

/// Exact `f64` distance between two fixed-point centres, in world units.
fn center_dist(a: &Event, b: &Event) -> f64 {
    let dx = (i64::from(a.center[0]) - i64::from(b.center[0])) as f64;
    let dy = (i64::from(a.center[1]) - i64::from(b.center[1])) as f64;
    (dx * dx + dy * dy).sqrt() / f64::from(FIXED_ONE)
}

/// Whether one of two discs can lie inside the other: their centres no farther apart than
/// their radii differ, tested exactly on the fixed-point integers. Every pair the covering
/// tests of [`Terrain::prune_new`] accept passes it (they ask for the difference to exceed
/// the distance by a guard of at least 1/32 unit, far past `f64` rounding), so it skips the
/// square root and the guards of most pairs without changing a decision.
fn may_nest(a: &Event, b: &Event) -> bool {
    let dx = (i64::from(a.center[0]) - i64::from(b.center[0])).unsigned_abs();
    let dy = (i64::from(a.center[1]) - i64::from(b.center[1])).unsigned_abs();
    let dr = (i64::from(a.radius) - i64::from(b.radius)).unsigned_abs();
    // Each leg of the centres' offset is at most its length: most pairs of a list fail on
    // a leg, without the 128-bit squares (the differences reach 2^33). One comparison of
    // the longer leg: the shorter one's was a branch that went either way.
    if dx.max(dy) > dr {
        return false;
    }
    let (dx, dy, dr) = (u128::from(dx), u128::from(dy), u128::from(dr));
    dx * dx + dy * dy <= dr * dr
}

/// The last of `list` that [`may_nest`] with `e`. A separate loop with nothing else in
/// it: the scan over a cell's whole list is most of an insert's pruning, and inside the
/// pruning's body it kept `e`'s fields on the stack.
#[inline(never)]
fn last_nesting(list: &[Listed], e: &Event) -> Option<usize> {
    list.iter().rposition(|x| may_nest(x, e))
}

pub(super) fn fixed_f64(v: i32) -> f64 {
    f64::from(v) / f64::from(FIXED_ONE)
}

/// `|cx| + |cy| + r + k` of an event, world units (for guards).
pub(super) fn event_extent(e: &Event) -> f64 {
    fixed_f64(e.center[0]).abs()
        + fixed_f64(e.center[1]).abs()
        + fixed_f64(e.radius)
        + fixed_f64(e.rim)
}

impl<F: Sdf> Terrain<F> {
    /// Rebuilds the grid by replaying every event at the current tick (which forgets the
    /// undo history: see [`grid::Grid::restart`]).
    pub(super) fn rebuild(&mut self) {
        let revisions = &mut self.next_revision;
        self.grid.restart(|| take_revision(revisions));
        self.over_cap.clear();
        self.baking = None;
        for idx in 0..self.events.len() as u32 {
            self.insert(idx);
        }
    }

    /// The cells whose lists an event joins.
    pub(super) fn cells_of(&self, e: &Event) -> Vec<usize> {
        let band = f64::from(self.options.band);
        let center = [fixed_f64(e.center[0]), fixed_f64(e.center[1])];
        let extent = event_extent(e) + band;
        let reach = fixed_f64(e.radius) + fixed_f64(e.rim) + band;
        self.grid.cells_touching(center, reach, extent)
    }

    /// The cells `e` joins, or [`TerrainError::CellFull`] at the first of them whose list
    /// is already `max_cell_events` long.
    pub(super) fn cells_with_room(&self, e: &Event) -> Result<Vec<usize>, TerrainError> {
        let max = self.options.max_cell_events;
        let cells = self.cells_of(e);
        let full = cells.iter().copied().find(|&cell| {
            self.grid
                .stored_cell(cell)
                .is_some_and(|c| c.events.len() >= max)
        });
        let Some(cell) = full else {
            return Ok(cells);
        };
        let r = self.grid.cell_rect(cell);
        let at = glam::Vec2::new(
            ((r.min[0] + r.max[0]) * 0.5) as f32,
            ((r.min[1] + r.max[1]) * 0.5) as f32,
        );
        Err(TerrainError::CellFull { at, max })
    }

    /// Lists logged event `idx` in every cell it can reach, then prunes those cells.
    pub(super) fn insert(&mut self, idx: u32) {
        if let Some(e) = self.events.get(idx as usize).copied() {
            let cells = self.cells_of(&e);
            self.insert_into(idx, e, &cells);
        }
    }

    /// [`Terrain::insert`] of logged event `idx` (`e`) into `cells`, its
    /// [`Terrain::cells_of`].
    pub(super) fn insert_into(&mut self, idx: u32, e: Event, cells: &[usize]) {
        let settled_at = e.tick.saturating_add(u32::from(e.grow_ticks));
        for &cell in cells {
            if let Some(c) = self.begin_cell_change(cell) {
                c.events.push(idx, e);
                c.may_fill |= e.kind == EventKind::Fill;
                c.settled_at = c.settled_at.max(settled_at);
            }
            self.prune_new(cell, idx, &e);
            self.compact_or_defer(cell);
        }
    }

    /// After an insert into `cell`: a list past the cap waits for the next tick advance
    /// (no insert pays for a bake), unless it has reached the longest a list may grow
    /// between advances, twice the cap (or `max_cell_events`).
    fn compact_or_defer(&mut self, cell: usize) {
        let o = &self.options;
        let most = o.cell_cap.saturating_mul(2).min(o.max_cell_events);
        let len = self.grid.stored_cell(cell).map_or(0, |c| c.events.len());
        if len <= o.cell_cap {
            self.over_cap.remove(&cell);
        } else if len >= most {
            self.compact(cell);
        } else {
            self.over_cap.insert(cell);
        }
    }

    /// Cell reset and covered-event pruning for the event `idx` just appended to `cell`.
    pub(super) fn prune_new(&mut self, cell: usize, idx: u32, e: &Event) {
        if !(e.is_sharp() && e.is_settled(self.tick)) {
            return;
        }
        let band = f64::from(self.options.band);
        let rect = self.grid.cell_rect(cell);
        let center = [fixed_f64(e.center[0]), fixed_f64(e.center[1])];
        let g = 2.0 * grid::guard(event_extent(e) + band, &rect);
        let Some(c) = self.grid.stored_cell(cell) else {
            return;
        };
        // 1. Cell reset.
        if rect.far_dist(center) + band + g <= fixed_f64(e.radius) {
            let new_state = match e.kind {
                EventKind::Fill => Some(CellState::Solid(e.material)),
                EventKind::Carve => {
                    let has_fill = (c.events.listed().iter()).any(|x| x.kind == EventKind::Fill);
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
                self.cancel_bake_of(cell);
                self.grid.set_state(cell, state);
                if let Some(c) = self.grid.edit_recorded_cell(cell) {
                    c.events.clear();
                    c.may_fill = false;
                }
                self.over_cap.remove(&cell);
                self.grid.count_reset();
                return;
            }
        }
        // 2. Covered events, within the run of sharp same-kind same-material events that
        //    ends with the new one.
        let Some(&last) = c.events.last() else { return };
        if last != idx {
            return;
        }
        let list = c.events.listed();
        let earlier = list.len().saturating_sub(1);
        // A list of settled sharp carves alone, which a sharp carve joins, is one run
        // throughout, and every event in it is settled: only the nesting test is left.
        let run_start = if e.kind == EventKind::Carve && c.folds_carves(self.tick) {
            0
        } else {
            let in_run = |x: &Listed| {
                x.kind == e.kind
                    && x.is_sharp()
                    && (e.kind == EventKind::Carve || x.material == e.material)
            };
            list[..earlier]
                .iter()
                .rposition(|x| !in_run(x))
                .map_or(0, |p| p + 1)
        };
        let mut drop_new = false;
        let mut drop: Vec<usize> = Vec::new();
        let mut end = earlier;
        while let Some(pos) = last_nesting(&list[run_start..end], e).map(|p| run_start + p) {
            end = pos;
            let x = &list[pos];
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
        if !drop.is_empty() {
            // The list before the new event changes: a bake of its prefix is stale.
            self.cancel_bake_of(cell);
        }
        let Some(c) = self.grid.edit_recorded_cell(cell) else {
            return;
        };
        let mut pruned = drop.len() as u64;
        if drop_new {
            c.events.pop();
            pruned += 1;
        }
        // `drop` is in descending position order, so removals don't shift later ones.
        for pos in drop {
            c.events.remove(pos);
        }
        self.grid.count_pruned(pruned);
    }

    /// Rows `rows` of the brick of `cell`'s state and its first `prefix` events: its field
    /// at those rows of the `(n+1) x (n+1)` lattice, on the SIMD lanes where the base has
    /// tapes (the same bits as the point path, which does it otherwise).
    pub(super) fn bake_rows(&self, cell: usize, prefix: usize, rows: Range<u32>) -> Brick {
        let mut brick = Brick::default();
        self.bake_rows_onto(cell, prefix, rows, &mut brick);
        brick
    }

    /// [`Terrain::bake_rows`] appended to `brick`'s samples (a partial bake's, which has
    /// room for them: a tick's rows need no buffers of their own).
    pub(super) fn bake_rows_onto(
        &self,
        cell: usize,
        prefix: usize,
        rows: Range<u32>,
        brick: &mut Brick,
    ) {
        let points = self.grid.lattice_rows(cell, rows);
        let start = brick.values.len();
        brick.values.resize(start + points.len(), 0.0);
        brick.materials.resize(start + points.len(), 0);
        let (values, materials) = (&mut brick.values[start..], &mut brick.materials[start..]);
        if !self.bake_lattice(cell, prefix, &points, values, materials) {
            for (k, &q) in points.iter().enumerate() {
                (values[k], materials[k]) = self.eval_cell::<f32, true>(q, cell, prefix);
            }
        }
    }

    /// How many listed events of `cell`, from the first, have settled (what a bake may
    /// fold into a brick).
    pub(super) fn settled_prefix(&self, cell: usize) -> usize {
        let Some(c) = self.grid.stored_cell(cell) else {
            return 0;
        };
        (c.events.listed().iter())
            .take_while(|e| e.is_settled(self.tick))
            .count()
    }

    /// Makes `brick` (of `cell`'s state and its first `prefix` events) the cell's state
    /// and drops those events from its list, within a change of the cell already begun.
    pub(super) fn install_brick(&mut self, cell: usize, prefix: usize, brick: Brick) {
        let id = self.grid.store_brick(cell, brick);
        self.grid.set_state(cell, CellState::Brick(id));
        if let Some(c) = self.grid.edit_recorded_cell(cell) {
            c.events.drop_prefix(prefix);
        }
        self.grid.count_bake();
    }

    /// Keeps `cell` in the over-cap set exactly while its list is longer than the cap.
    pub(super) fn update_over_cap(&mut self, cell: usize) {
        let cap = self.options.cell_cap;
        if self
            .grid
            .stored_cell(cell)
            .is_some_and(|c| c.events.len() > cap)
        {
            self.over_cap.insert(cell);
        } else {
            self.over_cap.remove(&cell);
        }
    }

    /// Bakes the longest settled prefix of an over-long list into a brick, at once (a list
    /// that reached twice the cap), within a change of the cell already begun.
    pub(super) fn compact(&mut self, cell: usize) {
        self.cancel_bake_of(cell);
        let cap = self.options.cell_cap;
        if self
            .grid
            .stored_cell(cell)
            .is_none_or(|c| c.events.len() <= cap)
        {
            self.over_cap.remove(&cell);
            return;
        }
        let prefix = self.settled_prefix(cell);
        if prefix > 0 {
            let side = self.grid.brick_resolution() + 1;
            let brick = self.bake_rows(cell, prefix, 0..side);
            self.install_brick(cell, prefix, brick);
        }
        self.update_over_cap(cell);
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::last_nesting;
    use crate::terrain::Terrain;
    use crate::terrain::grid::EventList;
    use crate::{Event, EventKind, Graph, Level};
    use craterfield_core::det::quant::FIXED_MAX;

    /// The scan for the pruning's candidates finds, in every prefix of a list, the last
    /// event whose disc and the new one's can nest (centres no farther apart than the radii
    /// differ, exactly): on lists of neighbours, on discs that touch from inside at the
    /// fixed point's extremes, and with legs equal to the radii's difference.
    #[test]
    fn the_scan_finds_the_last_pair_that_can_nest() {
        let mut unit = crate::test_rng::unit_f64(0x5ca7);
        let mut next = move |n: i64| (unit() * n as f64) as i64;
        let event = |x: i64, y: i64, r: i64| Event {
            kind: EventKind::Carve,
            center: [x as i32, y as i32],
            radius: r as i32,
            rim: 0,
            grow_ticks: 0,
            tick: 0,
            material: 0,
        };
        let reference = |list: &[Event], e: &Event| {
            list.iter().rposition(|x| {
                let d = |a: i32, b: i32| i128::from(a) - i128::from(b);
                let (dx, dy) = (d(x.center[0], e.center[0]), d(x.center[1], e.center[1]));
                let dr = d(x.radius, e.radius);
                dx * dx + dy * dy <= dr * dr
            })
        };
        let max = i64::from(FIXED_MAX);
        let (mut found, mut checked) = (0, 0);
        for round in 0..400 {
            // Near discs of a cell's neighbourhood, or anywhere in the fixed point's range.
            let (spread, origin) = if round % 4 == 3 {
                (max, -max / 2)
            } else {
                (40_000, 0)
            };
            let e = event(
                origin + next(spread),
                origin + next(spread),
                1 + next(20_000),
            );
            let log: Vec<Event> = (0..1 + next(60))
                .map(|_| match next(4) {
                    // Inside `e` or around it, the legs up to the radii's difference.
                    0 => {
                        let r = 1 + next(40_000);
                        let dr = (r - i64::from(e.radius)).abs();
                        let (dx, dy) = (next(dr + 2) - dr / 2, next(dr + 2) - dr / 2);
                        let x = (i64::from(e.center[0]) + dx).clamp(-max, max);
                        let y = (i64::from(e.center[1]) + dy).clamp(-max, max);
                        event(x, y, r)
                    }
                    // Touching from inside along an axis: a leg equal to the difference.
                    1 => {
                        let dr = next(10_000);
                        let x = (i64::from(e.center[0]) + dr).min(max);
                        event(x, i64::from(e.center[1]), i64::from(e.radius) + dr)
                    }
                    _ => event(
                        origin + next(spread),
                        origin + next(spread),
                        1 + next(20_000),
                    ),
                })
                .collect();
            let indices: Vec<u32> = (0..log.len() as u32).collect();
            let list = EventList::from_log(&indices, &log).unwrap();
            for end in 0..=log.len() {
                let want = reference(&log[..end], &e);
                assert_eq!(
                    last_nesting(&list.listed()[..end], &e),
                    want,
                    "round {round} end {end}"
                );
                found += usize::from(want.is_some());
                checked += 1;
            }
        }
        assert!(
            found > checked / 4,
            "{found} of {checked} prefixes hold a pair that can nest"
        );
    }

    /// Every list, of every cell and of every journaled pre-image, holds copies equal to
    /// the log's events at its indices.
    fn assert_copies_match_the_log(t: &Terrain<Graph>, when: &str) {
        let images = t.grid.journal_cell_images();
        for (k, c) in t.grid.stored_cells().iter().chain(images).enumerate() {
            let named: Vec<Event> = c.events.iter().map(|&i| t.events[i as usize]).collect();
            let copies: Vec<Event> = c.events.listed().iter().map(|l| *l.event()).collect();
            assert_eq!(copies, named, "list {k} {when}");
        }
    }

    /// Inserts (carves and fills, sharp and smooth, growing), covered-event pruning, cell
    /// resets, bakes, compaction, rollback, rebuilds and restores all keep each list's
    /// copies equal to its indices' events.
    #[test]
    fn listed_copies_stay_equal_to_the_log() {
        let level = Level::default_level();
        let b = level.bounds();
        let mut o = level.terrain_options();
        o.cell_cap = 6;
        o.brick_resolution = 8;
        o.max_events = 48;
        let mut t = Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
        t.enable_rollback();
        let mut state = 0x11_57u64;
        let mut unit = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 40) as f32) / (1u64 << 24) as f32
        };
        let mut mark = t.mark();
        for k in 0..600u32 {
            let c = Vec2::new(1200.0 + unit() * 300.0, 450.0 + unit() * 250.0);
            let r = 4.0 + unit() * 60.0;
            let mut e = if unit() < 0.25 {
                Event::fill(c, r, (k % 3) as u16).unwrap()
            } else {
                Event::carve(c, r).unwrap()
            };
            if unit() < 0.1 {
                e = e.with_rim(unit() * 6.0).unwrap();
            }
            if unit() < 0.1 {
                e = e.with_growth(1 + k as u16 % 5);
            }
            t.apply(e.at_tick(t.tick())).unwrap();
            if k % 3 == 0 {
                t.set_tick(t.tick() + 1).unwrap();
            }
            if k % 50 == 25 {
                // A short rollback window, as a world keeps, so compaction may drop events.
                mark = t.mark();
                if let Some(m) = &mark {
                    t.forget_before(m);
                }
            }
            if k % 50 == 40
                && let Some(m) = &mark
            {
                t.rollback(m).unwrap();
                assert_copies_match_the_log(&t, &format!("after a rollback at {k}"));
            }
            assert_copies_match_the_log(&t, &format!("after event {k}"));
        }
        assert!(
            t.events_applied() > t.events.len() as u64,
            "the log compacted"
        );
        assert!(t.grid.live_bricks() > 0, "cells baked");
        let saved = t.state();
        let mut restored = Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
        restored.restore_state(&saved).unwrap();
        assert_copies_match_the_log(&restored, "after a restore");
    }
}
