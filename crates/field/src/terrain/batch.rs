//! Batch queries: distances and samples for slices of points (many bodies, render tiles,
//! mesh extraction), on a SIMD backend, cell-coherent.
//!
//! Points are grouped by grid cell (a counting sort, or a comparison sort for batches much
//! smaller than the grid). A group's points in a flat square of their cell take its
//! constant, as on the point path (`super::flats`). The rest of a group runs in lane
//! blocks: the cell's specialized base tape (or its constant, baked or carved state), the
//! clamp, and the cell's events, one event at a time across all lanes. Every step mirrors
//! the single-point path of [`super::Terrain`], so each result has the same bits as
//! [`Sdf::distance`] and [`Sdf::sample`] at that point, whatever the backend, batch size
//! or order.

use glam::Vec2;

use super::Terrain;
use super::cell_tapes::{CellTape, CellTapes};
use crate::event::EventKind;
use crate::exec::batch::Block;
use crate::exec::value::clamp;
use crate::exec::{Dv, Fv, P2, Val};
use crate::sample::{MaterialId, Sample};
use crate::sdf::Sdf;
use crate::tape::check;
use crate::tape::{EvalError, MatOut};
use crate::terrain::grid::{self, CellState, FLAT_SIDE, Flats, MaterialSource, Rect};
use craterfield_core::backend::{Backend, BackendError};
use craterfield_core::simd::{self, Kernel, Lanes};

/// Cells with fewer points than this are answered on the point path (see
/// [`Terrain::batch`]).
const SPARSE: usize = 4;

/// Points of one cell (`None`: outside the grid), as a range of the sorted order.
struct Group {
    cell: Option<usize>,
    start: usize,
    end: usize,
}

/// A batch's points grouped by cell: the point indices in cell order, the groups, and
/// each point's flat square in its cell, in the same order (read beside the indices).
struct Grouped {
    order: Vec<u32>,
    groups: Vec<Group>,
    squares: Vec<u8>,
}

/// Groups point indices by cell, from each point's key and square (see [`CellKeys`]). NaN
/// points are left out (their result is fixed).
fn group(keys: &[u32], squares: &[u8], cells: usize) -> Grouped {
    let group_of = |k: usize, start: usize, end: usize| {
        (k <= cells).then(|| Group {
            cell: (k < cells).then_some(k),
            start,
            end,
        })
    };
    if cells > keys.len().saturating_mul(4) {
        // Few points on a large grid: a comparison sort, then runs of equal keys.
        let mut order: Vec<u32> = (0..keys.len() as u32).collect();
        order.sort_unstable_by_key(|&i| keys[i as usize]);
        let mut groups = Vec::new();
        let mut start = 0;
        while start < order.len() {
            let k = keys[order[start] as usize];
            let mut end = start + 1;
            while end < order.len() && keys[order[end] as usize] == k {
                end += 1;
            }
            groups.extend(group_of(k as usize, start, end));
            start = end;
        }
        let squares = order.iter().map(|&i| squares[i as usize]).collect();
        return Grouped {
            order,
            groups,
            squares,
        };
    }
    // A counting sort: the keys counted, then placed; each key's range of the order is
    // known from the counts.
    let mut counts = vec![0u32; cells + 3];
    for &k in keys {
        counts[k as usize + 1] += 1;
    }
    for i in 1..counts.len() {
        counts[i] += counts[i - 1];
    }
    let starts = counts.clone();
    let mut order = vec![0u32; keys.len()];
    // Placed beside the indices: the kernels read both in order.
    let mut sorted_squares = vec![0u8; keys.len()];
    for (i, (&k, &square)) in keys.iter().zip(squares).enumerate() {
        let at = counts[k as usize] as usize;
        order[at] = i as u32;
        sorted_squares[at] = square;
        counts[k as usize] += 1;
    }
    let groups = (0..cells + 2)
        .filter(|&k| starts[k + 1] > starts[k])
        .filter_map(|k| group_of(k, starts[k] as usize, starts[k + 1] as usize))
        .collect();
    Grouped {
        order,
        groups,
        squares: sorted_squares,
    }
}

/// A point's grouping key: its cell (`cell`, from [`Grid::cell_index`]), `cells` outside
/// the grid, `cells + 1` for NaN.
fn cell_key(p: Vec2, cell: Option<usize>, cells: usize) -> u32 {
    if p.x.is_nan() || p.y.is_nan() {
        (cells + 1) as u32
    } else {
        cell.unwrap_or(cells) as u32
    }
}

/// Every point's [`cell_key`], the cell found on lanes: `Grid::cell_index`'s arithmetic
/// (the same roundings, so the same cells), a lane register of points at a time. Looking
/// the cells up one point at a time was a fifth of a batch of uniform points. Beside it,
/// the index of the point's flat square in its cell (`Grid::cell_and_square`'s, the same
/// roundings; 0 outside the grid).
struct CellKeys<'a> {
    lookup: grid::Lookup,
    cells: usize,
    points: &'a [Vec2],
    keys: &'a mut [u32],
    squares: &'a mut [u8],
}

impl Kernel for CellKeys<'_> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let g = self.lookup;
        // Cell counts are below 2^24 (`MAX_CELLS`): every index is exact in f32.
        let (nx, ny) = (l.splat(g.nx as f32), l.splat(g.ny as f32));
        let (last_x, last_y) = (l.splat((g.nx - 1) as f32), l.splat((g.ny - 1) as f32));
        let zero = l.splat(0.0);
        let (outside, nan) = (
            l.splat_i(self.cells as i32),
            l.splat_i(self.cells as i32 + 1),
        );
        let (side, last_square) = (l.splat(FLAT_SIDE as f32), l.splat((FLAT_SIDE - 1) as f32));
        let w = L::WIDTH;
        let (mut xs, mut ys, mut ks, mut ss) = ([0.0f32; 16], [0.0f32; 16], [0i32; 16], [0i32; 16]);
        let squares = self.squares.chunks_mut(w);
        for ((pts, out), sq) in self
            .points
            .chunks(w)
            .zip(self.keys.chunks_mut(w))
            .zip(squares)
        {
            for (k, p) in pts.iter().enumerate() {
                (xs[k], ys[k]) = (p.x, p.y);
            }
            let (x, y) = (l.load(&xs), l.load(&ys));
            let (fx, fy) = (
                in_cells(l, &g, x, g.origin.x),
                in_cells(l, &g, y, g.origin.y),
            );
            let inside = l.and(
                l.and(l.ge(fx, zero), l.lt(fx, nx)),
                l.and(l.ge(fy, zero), l.lt(fy, ny)),
            );
            // Non-negative inside: the floor is the cast's truncation.
            let ix = l.min(l.floor(fx), last_x);
            let iy = l.min(l.floor(fy), last_y);
            let cell = l.to_i32(l.add(l.mul(iy, nx), ix));
            let is_number = l.and(l.le(x, x), l.le(y, y));
            let key = l.select_i(is_number, l.select_i(inside, cell, outside), nan);
            l.store_i(key, &mut ks);
            for (o, &k) in out.iter_mut().zip(&ks) {
                *o = k as u32;
            }
            // In [0, 1) up to rounding: the floor is the cast's truncation, the minimum
            // keeps the last square.
            let sx = l.min(l.floor(l.mul(l.sub(fx, ix), side)), last_square);
            let sy = l.min(l.floor(l.mul(l.sub(fy, iy), side)), last_square);
            let square = l.to_i32(l.add(l.mul(sy, side), sx));
            l.store_i(l.select_i(inside, square, l.splat_i(0)), &mut ss);
            for (o, &k) in sq.iter_mut().zip(&ss) {
                *o = k as u8;
            }
        }
    }
}

/// `(v - o) / cell_size` as `Grid::cell_index` rounds it.
#[inline(always)]
fn in_cells<L: Lanes>(l: L, g: &grid::Lookup, v: L::F, o: f32) -> L::F {
    match g.inv_pow2 {
        Some(inv) => l.mul(l.sub(v, l.splat(o)), l.splat(inv)),
        None => l.div(l.sub(v, l.splat(o)), l.splat(g.cell_size)),
    }
}

/// What a lane block starts from before the cell's events.
enum Start<'a> {
    Base(&'a CellTape),
    Constant(f32, Option<MaterialId>),
    AirFromBase(&'a CellTape),
    AirFromBrick(u32),
    Brick(u32),
}

impl Start<'_> {
    /// Whether every lane starts at exactly the band's top `+M`.
    fn is_top(&self, band: f32) -> bool {
        match self {
            Start::Base(plan) => plan.clamped == Some(band),
            Start::Constant(v, _) => *v == band,
            Start::AirFromBase(_) | Start::AirFromBrick(_) => true,
            Start::Brick(_) => false,
        }
    }
}

impl<F: Sdf> Terrain<F> {
    /// The backend of the batch queries and of brick baking (by default [`Backend::best`]).
    pub fn backend(&self) -> Backend {
        self.backend
    }

    /// Chooses the backend of the batch queries and of brick baking; results do not depend
    /// on it (bricks included), only the time they take.
    pub fn set_backend(&mut self, backend: Backend) -> Result<(), BackendError> {
        self.backend = backend.check()?;
        Ok(())
    }

    /// Whether each grid cell evaluates the base through a tape specialized to the cell
    /// (on by default). Results do not depend on it; it exists to measure what it saves.
    pub fn set_specialize(&mut self, on: bool) {
        if let Some(cell_tapes) = &mut self.cell_tapes {
            cell_tapes.set_specialize(on);
        }
    }

    /// Distances at `points` into `out`, bit-identical to [`Sdf::distance`] at each point.
    pub fn distances(&self, points: &[Vec2], out: &mut [f32]) -> Result<(), EvalError> {
        let Some((cell_tapes, grouped)) = self.batch(points, out, |p| self.distance(p))? else {
            return Ok(());
        };
        let t = self;
        simd::run(
            self.backend,
            Distances {
                t,
                cell_tapes,
                points,
                grouped: &grouped,
                out,
            },
        )?;
        Ok(())
    }

    /// Samples at `points` into `out`, bit-identical to [`Sdf::sample`] at each point.
    pub fn samples(&self, points: &[Vec2], out: &mut [Sample]) -> Result<(), EvalError> {
        let Some((cell_tapes, grouped)) = self.batch(points, out, |p| self.sample(p))? else {
            return Ok(());
        };
        let t = self;
        simd::run(
            self.backend,
            Samples {
                t,
                cell_tapes,
                points,
                grouped: &grouped,
                out,
            },
        )?;
        Ok(())
    }

    /// The values and materials of `cell`'s field from its state and its first `upto`
    /// events at `points` (a brick's lattice), on the lanes of the terrain's backend:
    /// bit-identical to the point path (`eval_cell` on values with materials), which it
    /// replaces where the base has tapes. `false` (nothing written) where it has none.
    pub(super) fn bake_lattice(
        &self,
        cell: usize,
        upto: usize,
        points: &[Vec2],
        values: &mut [f32],
        materials: &mut [MaterialId],
    ) -> bool {
        debug_assert!(values.len() == points.len() && materials.len() == points.len());
        let Some(cell_tapes) = &self.cell_tapes else {
            return false;
        };
        // A brick state whose brick is missing falls back to the base on the point path;
        // the lanes would not (it cannot happen: the grid keeps every brick it lists).
        let brick = match self.grid.stored_cell(cell).map(|c| c.state.0) {
            Some(CellState::Brick(id) | CellState::Air(MaterialSource::Brick(id))) => Some(id),
            _ => None,
        };
        if brick.is_some_and(|id| self.grid.brick(id).is_none()) {
            return false;
        }
        let bake = Bake {
            t: self,
            cell_tapes,
            cell,
            upto,
            points,
            values,
            materials,
        };
        // The backend was checked when it was set, so this does not fail.
        simd::run(self.backend, bake).is_ok()
    }

    /// What both batch queries do first: check the lengths, answer every point one at a
    /// time when the base has no tapes (`None`), else answer the NaN points (whose result
    /// is fixed) and group the rest by cell. Cells with fewer than [`SPARSE`] points are
    /// answered one point at a time too (the same bits): a block of lanes applies a busy
    /// cell's whole event list for every lane, used or not, which for one scattered
    /// point (a body's probe) cost several times the point path.
    fn batch<T>(
        &self,
        points: &[Vec2],
        out: &mut [T],
        single: impl Fn(Vec2) -> T,
    ) -> Result<Option<(&CellTapes, Grouped)>, EvalError> {
        check(points.len(), out.len())?;
        let Some(cell_tapes) = &self.cell_tapes else {
            for (o, &p) in out.iter_mut().zip(points) {
                *o = single(p);
            }
            return Ok(None);
        };
        for (o, &p) in out.iter_mut().zip(points) {
            if p.x.is_nan() || p.y.is_nan() {
                *o = single(p);
            }
        }
        let mut grouped = self.group(points);
        let order = &grouped.order;
        grouped.groups.retain(|g| {
            let sparse = g.end - g.start < SPARSE;
            if sparse {
                for &i in &order[g.start..g.end] {
                    out[i as usize] = single(points[i as usize]);
                }
            }
            !sparse
        });
        Ok(Some((cell_tapes, grouped)))
    }

    fn group(&self, points: &[Vec2]) -> Grouped {
        let cells = self.grid.cell_count();
        let mut keys = vec![0u32; points.len()];
        let mut squares = vec![0u8; points.len()];
        let kernel = CellKeys {
            lookup: self.grid.lookup(),
            cells,
            points,
            keys: &mut keys,
            squares: &mut squares,
        };
        if simd::run(self.backend, kernel).is_err() {
            // The backend was checked when it was set; this is the same lookup, per point.
            for ((k, s), &p) in keys.iter_mut().zip(&mut squares).zip(points) {
                let found = self.grid.cell_and_square(p);
                *k = cell_key(p, found.map(|(c, _)| c), cells);
                *s = found.map_or(0, |(_, bit)| bit.trailing_zeros() as u8);
            }
        }
        group(&keys, &squares, cells)
    }

    /// How a group's lanes start (state and base).
    fn start<'p>(
        &'p self,
        cell_tapes: &'p CellTapes,
        cell: Option<usize>,
        material: bool,
    ) -> Start<'p> {
        let m = self.options.band;
        let state = cell
            .and_then(|c| self.grid.stored_cell(c))
            .map_or(CellState::Base, |c| c.state.0);
        match state {
            CellState::Base => Start::Base(cell_tapes.get(&self.grid, cell)),
            CellState::Solid(mat) => Start::Constant(-m, Some(mat)),
            CellState::Air(src) if material => match src {
                MaterialSource::Base => Start::AirFromBase(cell_tapes.get(&self.grid, cell)),
                MaterialSource::Constant(mat) => Start::Constant(m, Some(mat)),
                MaterialSource::Brick(id) => Start::AirFromBrick(id),
            },
            CellState::Air(_) => Start::Constant(m, None),
            CellState::Brick(id) => Start::Brick(id),
        }
    }

    /// Whether `cell`'s list never held a fill since it was last cleared (see
    /// `Cell::may_fill`): it holds carves only.
    fn lists_carves_only(&self, cell: Option<usize>) -> bool {
        cell.and_then(|c| self.grid.stored_cell(c))
            .is_none_or(|c| !c.may_fill)
    }

    /// The cell's events in order with their constants at the current tick (events not
    /// yet started are left out: they change nothing).
    fn prepared_events(&self, cell: Option<usize>, out: &mut Vec<Prepared>) {
        self.prepared_prefix(cell, usize::MAX, out);
    }

    /// [`Terrain::prepared_events`] of the first `upto` listed events only.
    fn prepared_prefix(&self, cell: Option<usize>, upto: usize, out: &mut Vec<Prepared>) {
        out.clear();
        let list = cell.and_then(|c| self.grid.stored_cell(c));
        // Once, not by doubling: a bake starts from an empty vector, and growing it was a
        // twentieth of a barrage's instructions.
        out.reserve(list.map_or(0, |c| c.events.len().min(upto)));
        for e in list
            .into_iter()
            .flat_map(|c| c.events.listed().iter().take(upto))
        {
            if let Some(r) = e.radius_at(self.tick) {
                out.push(Prepared {
                    kind: e.kind,
                    center: e.center_f32(),
                    radius: r,
                    rim: e.rim_f32(),
                    material: e.material,
                });
            }
        }
    }
}

/// The events of `events` that can change anything at `pts`: the grid's own reach test
/// (the one that lists an event in a cell, see `Terrain::insert`) applied to the points'
/// bounding box instead of the whole cell. An event beyond it leaves every lane's bits as
/// they are (the field is clamped to the band), so leaving it out changes nothing, and
/// scattered points (bodies, projectiles) skip most of a busy cell's list.
fn events_reaching(events: &[Prepared], pts: &[Vec2], band: f32, out: &mut Vec<Prepared>) {
    out.clear();
    let Some(first) = pts.first() else {
        return;
    };
    let mut rect = Rect {
        min: [f64::from(first.x), f64::from(first.y)],
        max: [f64::from(first.x), f64::from(first.y)],
    };
    for p in pts {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        rect.min = [rect.min[0].min(x), rect.min[1].min(y)];
        rect.max = [rect.max[0].max(x), rect.max[1].max(y)];
    }
    let band = f64::from(band);
    out.extend(events.iter().copied().filter(|e| {
        let center = [f64::from(e.center.x), f64::from(e.center.y)];
        let (r, k) = (f64::from(e.radius), f64::from(e.rim));
        let extent = center[0].abs() + center[1].abs() + r + k + band;
        rect.near_dist(center) <= r + k + band + 2.0 * grid::guard(extent, &rect)
    }));
}

/// The events to apply to one block of group `g`: all of the cell's for a group of several
/// blocks (points spread over the cell, where the test would rarely drop one), else those
/// reaching the block's points.
fn reaching_block<'e>(
    events: &'e [Prepared],
    pts: &[Vec2],
    group_len: usize,
    step: usize,
    band: f32,
    reaching: &'e mut Vec<Prepared>,
) -> &'e [Prepared] {
    if group_len > step {
        return events;
    }
    events_reaching(events, pts, band, reaching);
    reaching
}

/// Flat squares a cell needs before its group is split (of 64): below it, most points
/// of a group take the lanes anyway, and the split's pass costs more than it saves.
const FLAT_SQUARES_WORTH_SORTING: u32 = 8;

/// Whether a group in a cell with `flats` is split into points in flat squares and the
/// others ([`unflat_members`]).
fn worth_sorting(flats: Flats) -> bool {
    (flats.top | flats.bottom).count_ones() >= FLAT_SQUARES_WORTH_SORTING
}

/// Writes the answer of a flat square (`top` or `bottom`) for the members of a group
/// (point indices, with their squares beside them) in a flat square of `flats`, and
/// returns the others, in order (the front of `unflat`). Branch-free, since a point's
/// square is flat about at random: the flat points are gathered (`flat`, with whether
/// they are at the bottom) and written after, so that a point the lanes answer is
/// written once. The scratch vectors only grow, so a group pays no clearing.
fn unflat_members<'s, T: Copy>(
    members: &[u32],
    squares: &[u8],
    flats: Flats,
    (top, bottom): (T, T),
    out: &mut [T],
    (unflat, flat): (&'s mut Vec<u32>, &mut Vec<(u32, bool)>),
) -> &'s [u32] {
    let n = members.len();
    if unflat.len() < n {
        unflat.resize(n, 0);
        flat.resize(n, (0, false));
    }
    let any = flats.top | flats.bottom;
    let (mut kept, mut found) = (0, 0);
    for (&i, &square) in members.iter().zip(squares) {
        let bit = 1u64 << (square & 63);
        let is_flat = any & bit != 0;
        unflat[kept] = i;
        kept += usize::from(!is_flat);
        flat[found] = (i, flats.bottom & bit != 0);
        found += usize::from(is_flat);
    }
    for &(i, at_bottom) in &flat[..found] {
        out[i as usize] = if at_bottom { bottom } else { top };
    }
    &unflat[..kept]
}

/// Gathers the points of one block of a group.
fn gather(points: &[Vec2], idx: &[u32], buf: &mut Vec<Vec2>) {
    buf.clear();
    buf.extend(idx.iter().map(|&i| points[i as usize]));
}

struct Distances<'a, F: Sdf> {
    t: &'a Terrain<F>,
    cell_tapes: &'a CellTapes,
    points: &'a [Vec2],
    grouped: &'a Grouped,
    out: &'a mut [f32],
}

impl<F: Sdf> Kernel for Distances<'_, F> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let t = self.t;
        let band = t.options.band;
        let mut block: Option<Block<L, Fv<L>, NB>> = None;
        let mut pts = Vec::new();
        let mut lanes = [0.0f32; 16];
        let mut events = Vec::new();
        let mut reaching = Vec::new();
        let (mut unflat, mut flat) = (Vec::new(), Vec::new());
        let step = NB * L::WIDTH;
        let (order, squares) = (&self.grouped.order, &self.grouped.squares);
        for g in &self.grouped.groups {
            let start = t.start(self.cell_tapes, g.cell, false);
            if start.is_top(band) && t.lists_carves_only(g.cell) {
                // Carves leave the band's top as it is: the list need not be read.
                for &i in &order[g.start..g.end] {
                    self.out[i as usize] = band;
                }
                continue;
            }
            let mut members = &order[g.start..g.end];
            if let Some(cell) = g.cell {
                // Points in a flat square take its constant, as the point path answers
                // them; the lanes work the others.
                let flats = t.flats(cell);
                if worth_sorting(flats) {
                    let squares = &squares[g.start..g.end];
                    let answers = (band, -band);
                    let scratch = (&mut unflat, &mut flat);
                    members = unflat_members(members, squares, flats, answers, self.out, scratch);
                }
                if members.is_empty() {
                    continue;
                }
            }
            t.prepared_events(g.cell, &mut events);
            if events.is_empty() {
                // A constant cell: no point is needed.
                let constant = match &start {
                    Start::Base(plan) => plan.clamped,
                    Start::Constant(v, _) => Some(*v),
                    Start::AirFromBase(_) | Start::AirFromBrick(_) => Some(band),
                    Start::Brick(_) => None,
                };
                if let Some(c) = constant {
                    for &i in members {
                        self.out[i as usize] = c;
                    }
                    continue;
                }
            }
            for idx in members.chunks(step) {
                gather(self.points, idx, &mut pts);
                let mut ps = [P2::new(Fv::cst(l, 0.0), Fv::cst(l, 0.0)); NB];
                for (r, p) in ps.iter_mut().enumerate() {
                    *p = lane_point(l, &pts, r);
                }
                let mut ds = [Fv::cst(l, band); NB];
                match &start {
                    Start::Base(plan) if plan.clamped.is_some() => {
                        ds = [Fv::cst(l, plan.clamped.unwrap_or(band)); NB];
                    }
                    Start::Base(plan) => {
                        let b = block.get_or_insert_with(|| Block::new(l, &plan.value));
                        b.run(l, &plan.value, &pts);
                        for (r, d) in ds.iter_mut().enumerate() {
                            *d = clamp(l, b.get(plan.value.value, r), -band, band);
                        }
                    }
                    Start::Constant(v, _) => ds = [Fv::cst(l, *v); NB],
                    Start::AirFromBase(_) | Start::AirFromBrick(_) => {}
                    Start::Brick(id) => {
                        for (d, p) in ds.iter_mut().zip(&ps) {
                            *d = brick(l, t, *id, g.cell, *p, false).0;
                        }
                    }
                }
                let mut mats = [l.splat_i(0); NB];
                let events =
                    reaching_block(&events, &pts, members.len(), step, band, &mut reaching);
                apply_values(l, events, &mut ds, &mut mats, &ps, band, NB);
                for (r, d) in ds.iter().enumerate() {
                    l.store(d.0, &mut lanes);
                    for (k, &i) in idx.iter().enumerate().skip(r * L::WIDTH).take(L::WIDTH) {
                        self.out[i as usize] = lanes[k - r * L::WIDTH];
                    }
                }
            }
        }
    }
}

struct Samples<'a, F: Sdf> {
    t: &'a Terrain<F>,
    cell_tapes: &'a CellTapes,
    points: &'a [Vec2],
    grouped: &'a Grouped,
    out: &'a mut [Sample],
}

impl<F: Sdf> Kernel for Samples<'_, F> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let t = self.t;
        let band = t.options.band;
        let mut block: Option<Block<L, Dv<L>, NB>> = None;
        let mut pts = Vec::new();
        let (mut v, mut gx, mut gy) = ([0.0f32; 16], [0.0f32; 16], [0.0f32; 16]);
        let mut mat_lanes = [0i32; 16];
        let mut events = Vec::new();
        let mut reaching = Vec::new();
        let (mut unflat, mut flat) = (Vec::new(), Vec::new());
        let step = NB * L::WIDTH;
        let (order, squares) = (&self.grouped.order, &self.grouped.squares);
        for g in &self.grouped.groups {
            let mut members = &order[g.start..g.end];
            if let Some(cell) = g.cell {
                // As the point path: a flat square answers where the state has one
                // material, with a zero gradient.
                let flats = t.flats(cell);
                if let (Some(material), true) = (flats.material, worth_sorting(flats)) {
                    let answer = |distance| Sample {
                        distance,
                        gradient: Vec2::ZERO,
                        material,
                    };
                    let answers = (answer(band), answer(-band));
                    let squares = &squares[g.start..g.end];
                    let scratch = (&mut unflat, &mut flat);
                    members = unflat_members(members, squares, flats, answers, self.out, scratch);
                }
                if members.is_empty() {
                    continue;
                }
            }
            let start = t.start(self.cell_tapes, g.cell, true);
            t.prepared_events(g.cell, &mut events);
            if let Some(s) = constant_sample(&start, events.is_empty(), band) {
                for &i in members {
                    self.out[i as usize] = s;
                }
                continue;
            }
            for idx in members.chunks(step) {
                gather(self.points, idx, &mut pts);
                let mut ps = [P2::new(Dv::cst(l, 0.0), Dv::cst(l, 0.0)); NB];
                for (r, p) in ps.iter_mut().enumerate() {
                    *p = lane_point(l, &pts, r);
                }
                let (mut ds, mut mats) =
                    start_with_materials(l, t, &start, g.cell, &mut block, &pts, &ps, NB);
                let events =
                    reaching_block(&events, &pts, members.len(), step, band, &mut reaching);
                if !apply_sharp_carves(l, events, &mut ds, &ps, band, NB) {
                    for e in events {
                        for r in 0..NB {
                            (ds[r], mats[r]) = apply_event(l, ds[r], mats[r], ps[r], e, band);
                        }
                    }
                }
                for r in 0..NB {
                    let d = ds[r];
                    l.store(d.v, &mut v);
                    l.store(d.dx, &mut gx);
                    l.store(d.dy, &mut gy);
                    l.store_i(mats[r], &mut mat_lanes);
                    for (k, &i) in idx.iter().enumerate().skip(r * L::WIDTH).take(L::WIDTH) {
                        let k = k - r * L::WIDTH;
                        self.out[i as usize] = Sample {
                            distance: v[k],
                            gradient: Vec2::new(gx[k], gy[k]),
                            material: mat_lanes[k] as MaterialId,
                        };
                    }
                }
            }
        }
    }
}

/// The lanes' starting values and materials for the points `pts` (`ps` as lane registers)
/// of one block of `cell`: the cell's state, before its events. Samples and bakes share it.
/// Only the first `used` lane registers are worked (the rest keep the band's top).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn start_with_materials<L: Lanes, V: Val<L>, F: Sdf, const NB: usize>(
    l: L,
    t: &Terrain<F>,
    start: &Start<'_>,
    cell: Option<usize>,
    block: &mut Option<Block<L, V, NB>>,
    pts: &[Vec2],
    ps: &[P2<V>; NB],
    used: usize,
) -> ([V; NB], [L::I; NB]) {
    let used = used.min(NB);
    let band = t.options.band;
    if let Some((d, m)) = constant_start(start, band) {
        // No tape to run: the base beyond the band (or air over it) and one material.
        return ([V::cst(l, d); NB], [l.splat_i(i32::from(m)); NB]);
    }
    let mut ds = [V::cst(l, band); NB];
    let mut mats = [l.splat_i(0); NB];
    match start {
        Start::Base(plan) | Start::AirFromBase(plan) => {
            let tape = &plan.material;
            let b = block.get_or_insert_with(|| Block::new(l, tape));
            b.run_used(l, tape, pts, used);
            let base = matches!(start, Start::Base(_));
            let mut tape_mats = [0 as MaterialId; 16];
            for r in 0..used {
                b.materials(l, tape, r, &mut tape_mats);
                mats[r] = l.load_i(&tape_mats.map(i32::from));
                if base {
                    ds[r] = match plan.clamped {
                        Some(c) => V::cst(l, c),
                        None => clamp(l, b.get(tape.value, r), -band, band),
                    };
                }
            }
        }
        // Answered by `constant_start` above.
        Start::Constant(..) => {}
        Start::AirFromBrick(id) | Start::Brick(id) => {
            let baked = matches!(start, Start::Brick(_));
            for r in 0..used {
                let (d, m) = brick(l, t, *id, cell, ps[r], true);
                if baked {
                    ds[r] = d;
                }
                mats[r] = m;
            }
        }
    }
    (ds, mats)
}

/// A brick's lattice: see [`Terrain::bake_lattice`].
struct Bake<'a, F: Sdf> {
    t: &'a Terrain<F>,
    cell_tapes: &'a CellTapes,
    cell: usize,
    upto: usize,
    points: &'a [Vec2],
    values: &'a mut [f32],
    materials: &'a mut [MaterialId],
}

impl<F: Sdf> Kernel for Bake<'_, F> {
    type Output = ();
    #[inline(always)]
    fn run<L: Lanes, const NB: usize>(self, l: L) {
        let t = self.t;
        let band = t.options.band;
        let cell = Some(self.cell);
        let start = t.start(self.cell_tapes, cell, true);
        let mut events = Vec::new();
        t.prepared_prefix(cell, self.upto, &mut events);
        let mut block: Option<Block<L, Fv<L>, NB>> = None;
        let (mut v, mut mat_lanes) = ([0.0f32; 16], [0i32; 16]);
        let step = NB * L::WIDTH;
        for (chunk, pts) in self.points.chunks(step).enumerate() {
            // A short block (a bake of a row or two) works only its registers with points.
            let used = pts.len().div_ceil(L::WIDTH).min(NB);
            let mut ps = [P2::new(Fv::cst(l, 0.0), Fv::cst(l, 0.0)); NB];
            for (r, p) in ps.iter_mut().enumerate().take(used) {
                *p = lane_point(l, pts, r);
            }
            let (mut ds, mut mats) =
                start_with_materials(l, t, &start, cell, &mut block, pts, &ps, used);
            if !bake_sharp_carves(l, &events, &mut ds, &ps, band, used) {
                apply_values(l, &events, &mut ds, &mut mats, &ps, band, used);
            }
            for r in 0..used {
                l.store(ds[r].0, &mut v);
                l.store_i(mats[r], &mut mat_lanes);
                let first = chunk * step + r * L::WIDTH;
                for k in 0..L::WIDTH {
                    if let (Some(value), Some(material)) = (
                        self.values.get_mut(first + k),
                        self.materials.get_mut(first + k),
                    ) {
                        *value = v[k];
                        *material = mat_lanes[k] as MaterialId;
                    }
                }
            }
        }
    }
}

/// The sample of every point of a cell that is constant there (no events, a constant
/// state or a clamped base whose material is the same everywhere).
fn constant_sample(start: &Start<'_>, no_events: bool, band: f32) -> Option<Sample> {
    if !no_events {
        return None;
    }
    let (distance, material) = constant_start(start, band)?;
    Some(Sample {
        distance,
        gradient: Vec2::ZERO,
        material,
    })
}

/// The value (with a zero gradient) and material a state gives everywhere in its cell,
/// where it is constant there: a constant state, or a base clamped over the whole cell (or
/// the air over it) whose material is the same everywhere: no lane needs the base's tape,
/// which a bake in the ground beyond the band otherwise ran for that one material.
fn constant_start(start: &Start<'_>, band: f32) -> Option<(f32, MaterialId)> {
    match start {
        Start::Constant(v, m) => Some((*v, m.unwrap_or(0))),
        Start::Base(plan) => match (plan.clamped, plan.material.material()) {
            (Some(c), MatOut::Const(m)) => Some((c, m)),
            _ => None,
        },
        Start::AirFromBase(plan) => match plan.material.material() {
            MatOut::Const(m) => Some((band, m)),
            MatOut::Value(_) => None,
        },
        Start::AirFromBrick(_) | Start::Brick(_) => None,
    }
}

/// Lane register `r` of the gathered points as a point of numbers (padding repeats the
/// last point).
#[inline(always)]
fn lane_point<L: Lanes, V: Val<L>>(l: L, pts: &[Vec2], r: usize) -> P2<V> {
    let (mut x, mut y) = ([0.0f32; 16], [0.0f32; 16]);
    let last = pts.len().saturating_sub(1);
    for k in 0..L::WIDTH {
        let p = pts
            .get(r * L::WIDTH + k)
            .or(pts.get(last))
            .copied()
            .unwrap_or(Vec2::ZERO);
        x[k] = p.x;
        y[k] = p.y;
    }
    P2::new(V::px(l, l.load(&x)), V::py(l, l.load(&y)))
}

/// `terrain::field::smin` (`max = false`) and `terrain::field::smax` (`max = true`).
#[inline(always)]
fn smooth<L: Lanes, V: Val<L>>(l: L, a: V, b: V, k: f32, max: bool) -> V {
    let m = if max { a.max(l, b) } else { a.min(l, b) };
    let h = V::cst(l, k)
        .sub(l, a.sub(l, b).abs(l))
        .max(l, V::cst(l, 0.0))
        .div(l, V::cst(l, k));
    let t = h.mul(l, h).scale(l, k).scale(l, 0.25);
    let blended = if max { m.add(l, t) } else { m.sub(l, t) };
    V::select(l, l.gt(h.v(), l.splat(0.0)), blended, m)
}

/// An event's constants at the current tick.
#[derive(Clone, Copy)]
struct Prepared {
    kind: EventKind,
    center: Vec2,
    radius: f32,
    rim: f32,
    material: MaterialId,
}

impl Prepared {
    #[inline(always)]
    fn is_sharp_carve(&self) -> bool {
        self.kind == EventKind::Carve && self.rim <= 0.0
    }

    /// The signed distance from `p` to the event's disc (`terrain::field::apply_event`'s).
    #[inline(always)]
    fn disc_distance<L: Lanes, V: Val<L>>(&self, l: L, p: P2<V>) -> V {
        p.minus(l, self.center).length(l).offset(l, -self.radius)
    }
}

/// Whether `events` fold as one running maximum of sharp carves (none of another kind,
/// and at least one).
#[inline(always)]
fn all_sharp_carves(events: &[Prepared]) -> bool {
    !events.is_empty() && events.iter().all(Prepared::is_sharp_carve)
}

/// `events` in order on registers of values (no gradients), skipping a carve for a
/// register whose every lane is exactly `+M`: a carve only raises the value and the clamp
/// brings it back to `M`, with the material kept, so it changes no bit there. Most of a
/// crater cell's lattice is carved-out air, where the later carves of its list would
/// otherwise each cost a square root per lane.
#[inline(always)]
fn apply_values<L: Lanes, const NB: usize>(
    l: L,
    events: &[Prepared],
    ds: &mut [Fv<L>; NB],
    mats: &mut [L::I; NB],
    ps: &[P2<Fv<L>>; NB],
    band: f32,
    used: usize,
) {
    let top = l.splat(band);
    let all_at_top = |d: L::F| !l.any(l.not(l.and(l.ge(d, top), l.le(d, top))));
    for e in events {
        let carve = e.kind == EventKind::Carve;
        for r in 0..used.min(NB) {
            if carve && all_at_top(ds[r].0) {
                continue;
            }
            (ds[r], mats[r]) = apply_event(l, ds[r], mats[r], ps[r], e, band);
        }
    }
}

/// [`apply_values`] where every event is a sharp carve (`false`, nothing done, where one
/// is not): `terrain::field::sharp_carves` on lanes, a running maximum clamped once (the
/// same bits, as that function shows). A register whose every lane is at or past the top
/// ends at `+M` whatever follows, so it skips the rest. Batch samples take it, on duals
/// (which skipped no carve at the top before: 10% more samples a second after 10,000
/// explosions), and bakes its twin [`bake_sharp_carves`] (a whole list at the cap: their
/// tick ends took 4% less); batch distances do not (the lists left after a bake are
/// short, and their blocks, which already skip carves at the top, measured 5% slower
/// with it).
#[inline(always)]
fn apply_sharp_carves<L: Lanes, V: Val<L>, const NB: usize>(
    l: L,
    events: &[Prepared],
    ds: &mut [V; NB],
    ps: &[P2<V>; NB],
    band: f32,
    used: usize,
) -> bool {
    if !all_sharp_carves(events) {
        return false;
    }
    let top = l.splat(band);
    let past_top = |d: L::F| !l.any(l.not(l.ge(d, top)));
    let used = used.min(NB);
    for e in events {
        for (d, p) in ds.iter_mut().zip(ps).take(used) {
            if !past_top(d.v()) {
                *d = d.max(l, e.disc_distance(l, *p).neg(l));
            }
        }
    }
    for d in ds.iter_mut().take(used) {
        *d = clamp(l, *d, -band, band);
    }
    true
}

/// [`apply_sharp_carves`] for a bake, on values: a register at a time through the whole
/// list, its running maximum held in a machine register (the events outermost, it was
/// loaded and stored for every event), looking whether it reached the top every
/// [`TOP_CHECK_EVERY`] events (where it stops once there does not matter). The same bits:
/// each register still takes the events in order. Bakes ran 18% fewer instructions
/// (AVX2, the barrage's tick ends); batch samples, on duals, measured no faster this way
/// and keep the events outermost.
#[inline(always)]
fn bake_sharp_carves<L: Lanes, const NB: usize>(
    l: L,
    events: &[Prepared],
    ds: &mut [Fv<L>; NB],
    ps: &[P2<Fv<L>>; NB],
    band: f32,
    used: usize,
) -> bool {
    if !all_sharp_carves(events) {
        return false;
    }
    let top = l.splat(band);
    let past_top = |d: L::F| !l.any(l.not(l.ge(d, top)));
    for (d, p) in ds.iter_mut().zip(ps).take(used.min(NB)) {
        let mut m = *d;
        for run in events.chunks(TOP_CHECK_EVERY) {
            if past_top(m.v()) {
                break;
            }
            for e in run {
                m = m.max(l, e.disc_distance(l, *p).neg(l));
            }
        }
        *d = clamp(l, m, -band, band);
    }
    true
}

/// How many sharp carves [`bake_sharp_carves`] folds into a register between two looks at
/// whether it reached the band's top.
const TOP_CHECK_EVERY: usize = 8;

/// `terrain::field::apply_event` on lanes.
#[inline(always)]
fn apply_event<L: Lanes, V: Val<L>>(
    l: L,
    d: V,
    mat: L::I,
    p: P2<V>,
    e: &Prepared,
    band: f32,
) -> (V, L::I) {
    let c = e.disc_distance(l, p);
    let k = e.rim;
    match e.kind {
        EventKind::Carve => {
            let nc = c.neg(l);
            let v = if k > 0.0 {
                smooth(l, d, nc, k, true)
            } else {
                d.max(l, nc)
            };
            (clamp(l, v, -band, band), mat)
        }
        EventKind::Fill => {
            let wins = l.not(l.lt(d.v(), c.v()));
            let v = if k > 0.0 {
                smooth(l, d, c, k, false)
            } else {
                d.min(l, c)
            };
            let mat = l.select_i(wins, l.splat_i(i32::from(e.material)), mat);
            (clamp(l, v, -band, band), mat)
        }
    }
}

/// `(x as u32).min(top)` for `x` in `[0, 2^31)` (a lattice coordinate).
#[inline(always)]
fn index_at_most<L: Lanes>(l: L, x: L::F, top: i32) -> L::I {
    let i = l.to_i32(x);
    let top = l.splat_i(top);
    l.select_i(l.gt_i(i, top), top, i)
}

/// `Grid::interpolate` on lanes: the brick's bilinear value (and nearest material).
#[inline(always)]
fn brick<L: Lanes, V: Val<L>, F: Sdf>(
    l: L,
    t: &Terrain<F>,
    id: u32,
    cell: Option<usize>,
    p: P2<V>,
    material: bool,
) -> (V, L::I) {
    let grid = &t.grid;
    let (Some(b), Some(cell)) = (grid.brick(id), cell) else {
        return (V::cst(l, f32::NAN), l.splat_i(0));
    };
    let n = grid.brick_resolution();
    let nf = n as f32;
    let m = grid.cell_min_f32(cell);
    let h = V::cst(l, grid.brick_spacing());
    let u = clamp(l, p.x.offset(l, -m.x).div(l, h), 0.0, nf);
    let v = clamp(l, p.y.offset(l, -m.y).div(l, h), 0.0, nf);
    let (i, j) = (
        index_at_most(l, u.v(), n as i32 - 1),
        index_at_most(l, v.v(), n as i32 - 1),
    );
    let fu = u.offset_v(l, l.neg(l.to_f32(i)));
    let fv = v.offset_v(l, l.neg(l.to_f32(j)));
    let (mut ii, mut jj) = ([0i32; 16], [0i32; 16]);
    l.store_i(i, &mut ii);
    l.store_i(j, &mut jj);
    let row = (n + 1) as usize;
    // A bake's registers mostly hold a run of one lattice row (on 8 lanes, three
    // registers in four of a 33-sample row's): the corners are then two runs of two brick
    // rows, read whole (the same samples the lanes would read one by one).
    let runs = lattice_run::<L>(&ii, &jj, row).and_then(|at| {
        let low = b.values.get(at..at + L::WIDTH + 1)?;
        let high = b.values.get(at + row..at + row + L::WIDTH + 1)?;
        Some((low, high))
    });
    let (v00, v10, v01, v11) = match runs {
        Some((low, high)) => (
            l.load(low),
            l.load(&low[1..]),
            l.load(high),
            l.load(&high[1..]),
        ),
        None => {
            let val = |i: i32, j: i32| {
                b.values
                    .get(j as usize * row + i as usize)
                    .copied()
                    .unwrap_or(0.0)
            };
            let (mut v00, mut v10, mut v01, mut v11) = ([0.0; 16], [0.0; 16], [0.0; 16], [0.0; 16]);
            for k in 0..L::WIDTH {
                let (i, j) = (ii[k], jj[k]);
                (v00[k], v10[k], v01[k], v11[k]) =
                    (val(i, j), val(i + 1, j), val(i, j + 1), val(i + 1, j + 1));
            }
            (l.load(&v00), l.load(&v10), l.load(&v01), l.load(&v11))
        }
    };
    let bottom = fu.scale_v(l, l.sub(v10, v00)).offset_v(l, v00);
    let top = fu.scale_v(l, l.sub(v11, v01)).offset_v(l, v01);
    let d = top.sub(l, bottom).mul(l, fv).add(l, bottom);
    if !material {
        return (d, l.splat_i(0));
    }
    let (mi, mj) = (
        index_at_most(l, l.add(u.v(), l.splat(0.5)), n as i32),
        index_at_most(l, l.add(v.v(), l.splat(0.5)), n as i32),
    );
    l.store_i(mi, &mut ii);
    l.store_i(mj, &mut jj);
    let mut mats = [0i32; 16];
    match lattice_run::<L>(&ii, &jj, row).and_then(|at| b.materials.get(at..at + L::WIDTH)) {
        Some(run) => {
            for (m, &s) in mats.iter_mut().zip(run) {
                *m = i32::from(s);
            }
        }
        None => {
            for k in 0..L::WIDTH {
                let at = jj[k] as usize * row + ii[k] as usize;
                mats[k] = i32::from(b.materials.get(at).copied().unwrap_or(0));
            }
        }
    }
    (d, l.load_i(&mats))
}

/// Where the lanes' lattice indices `(ii, jj)` are consecutive columns of one row (a
/// register of a bake's lattice points not split across rows), the index of the first
/// lane's sample in a brick of rows `row` long.
#[inline(always)]
fn lattice_run<L: Lanes>(ii: &[i32; 16], jj: &[i32; 16], row: usize) -> Option<usize> {
    let (i0, j0) = (ii[0], jj[0]);
    let run = (1..L::WIDTH).all(|k| ii[k] == i0 + k as i32 && jj[k] == j0);
    (run && i0 >= 0 && j0 >= 0).then(|| j0 as usize * row + i0 as usize)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::grid::Grid;

    /// On every backend the lanes find each point the cell `Grid::cell_index` finds and the
    /// flat square `Grid::cell_and_square` finds: on cell and square sides and one ulp
    /// either side, at the grid's edges, outside, and for NaN and infinities, with a
    /// power-of-two cell size (multiplied by its inverse) and another (divided).
    #[test]
    fn lane_keys_are_the_point_lookups() {
        let mut unit_f64 = crate::test_rng::unit_f64(0x2545_f491_4f6c_dd1d);
        let mut unit = || unit_f64() as f32;
        for (size, origin) in [
            (64.0, Vec2::new(-100.0, 3.5)),
            (48.3, Vec2::new(7.25, -60.0)),
        ] {
            let grid =
                Grid::new(origin, origin + Vec2::new(4000.0, 1000.0), size, 8).expect("a grid");
            let (nx, ny) = grid.dims();
            let mut points = vec![
                Vec2::new(f32::NAN, 0.0),
                Vec2::new(0.0, f32::NAN),
                Vec2::new(f32::INFINITY, 10.0),
                Vec2::new(10.0, f32::NEG_INFINITY),
                Vec2::new(-1e30, 1e30),
                origin,
            ];
            // Cell sides and the flat squares' sides between them, and a unit beside each.
            let eighths = |n: u32| (0..=n * 8).map(|k| k as f32 / 8.0);
            for i in eighths(nx) {
                for j in [0.0, (ny / 2) as f32 + 0.375, ny as f32] {
                    let edge = origin + Vec2::new(i, j) * size;
                    for d in [-1i32, 0, 1] {
                        let nudge = |v: f32| f32::from_bits((v.to_bits() as i32 + d) as u32);
                        points.push(Vec2::new(nudge(edge.x), edge.y));
                        points.push(Vec2::new(edge.x, nudge(edge.y)));
                    }
                }
            }
            for _ in 0..5000 {
                points.push(origin + Vec2::new(unit() * 4200.0 - 100.0, unit() * 1200.0 - 100.0));
            }
            let cells = grid.cell_count();
            let expected: Vec<(u32, u8)> = (points.iter())
                .map(|&p| {
                    let found = grid.cell_and_square(p);
                    let square = found.map_or(0, |(_, bit)| bit.trailing_zeros() as u8);
                    (cell_key(p, grid.cell_index(p), cells), square)
                })
                .collect();
            let squares_seen: std::collections::HashSet<u8> =
                expected.iter().map(|&(_, s)| s).collect();
            assert_eq!(squares_seen.len(), 64, "every square of a cell is tried");
            for backend in Backend::available() {
                let mut keys = vec![u32::MAX; points.len()];
                let mut squares = vec![u8::MAX; points.len()];
                let kernel = CellKeys {
                    lookup: grid.lookup(),
                    cells,
                    points: &points,
                    keys: &mut keys,
                    squares: &mut squares,
                };
                simd::run(backend, kernel).expect("an available backend");
                let got = keys.iter().zip(&squares).map(|(&k, &s)| (k, s));
                for (k, (got, want)) in got.zip(&expected).enumerate() {
                    assert_eq!(got, *want, "{backend}: point {:?} (size {size})", points[k]);
                }
            }
        }
    }
}
