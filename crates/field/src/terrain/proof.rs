//! What a renderer may prove about the field without evaluating every point: per cell, its
//! slope and error bounds and whether its material is one constant; per rectangle, the sign
//! its events force ([`Terrain::rect_sign`]); per point, how far the winning material is
//! from being overtaken inside the point's cell ([`Terrain::material_margin`]).
//!
//! Materials change in three ways only (see the module doc of [`super`]): the base field's
//! own material selects, the nearest-sample material of a brick, and fills of another
//! material winning their `min`. Carves keep the material.
//!
//! # The margin
//!
//! [`Terrain::material_margin`] at `p` in cell `C` returns `m >= 0` with this guarantee:
//! every point `q` of `C` with `2 L' |q - p| < m` has the material of `p`, where
//! `L' = max(L, 1)` and `L` is the cell's slope bound ([`Terrain::cell_bounds`]). It is
//! computed along the same event fold as the field:
//! the cell's starting material is constant over `C` (margin `+inf`) or not (margin `0`);
//! a fill of material `F` compared with the accumulated `(d, mat, m)` at `c = |p - o| - r`
//! switches where `d - c` changes sign, a function whose slope is at most `L' + 1 <= 2 L'`:
//!
//! * the fill wins (`c <= d`): `m' = d - c` if `mat != F`, else `max(d - c, m)`;
//! * it loses (`d < c`): `m' = min(m, c - d)` if `mat != F`, else `m`.
//!
//! Both cases follow from "the winner stays the winner within `|d - c| / 2L'`, and the
//! accumulated material stays within `m / 2L'`". The guarantee holds within the cell only:
//! another cell has another event list and starting state.

use std::cmp::Ordering;

use glam::Vec2;

use super::Terrain;
use crate::event::EventKind;
use crate::sample::MaterialId;
use crate::sdf::Sdf;
use crate::tape::MatOut;
use crate::terrain::grid::{CellState, Listed, MaterialSource};
use craterfield_core::det::math::{Num, V2};

/// What a proof may assume about the field inside one grid cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellBounds {
    /// The field is `lipschitz`-Lipschitz inside the cell (`0` where it is constant).
    pub lipschitz: f32,
    /// How far the cell's field may be from the exact field (`0` unless the cell is a
    /// brick): across a border between two cells the field may jump by the sum of their
    /// errors.
    pub error: f32,
}

/// One cell's events at one tick, read once for many [`Terrain::rect_sign_of`] questions
/// ([`Terrain::event_discs`]).
#[derive(Clone, Debug)]
pub struct EventDiscs {
    cell: usize,
    discs: Vec<Disc>,
    start: Start,
}

/// One event as the sign proof reads it: centre, radius at the tick and rim, in `f64`.
#[derive(Clone, Copy, Debug)]
struct Disc {
    center: [f64; 2],
    radius: f64,
    rim: f64,
    carve: bool,
}

/// A cell's starting state as the sign proof bounds it: one range over the whole cell, or
/// a brick whose range depends on the rectangle.
#[derive(Clone, Copy, Debug)]
enum Start {
    Range(f32, f32),
    Brick(u32),
}

/// What a cell's starting state and events force over a rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RectSign {
    /// The field is at least the `above` threshold everywhere in it.
    Above,
    /// The field is at most the `below` threshold everywhere in it.
    Below,
    /// Neither is proven.
    Unknown,
}

impl<F: Sdf> Terrain<F> {
    /// What cell `cell`'s starting state and events force over the rectangle
    /// `[min, max]` (its part inside the cell): `Above` when the field is at least `above`
    /// (`0 < above <= M`) everywhere, `Below` when at most `below` (`-M <= below < 0`).
    ///
    /// Walking the cell's list: the starting state proves `Above` when it is at least
    /// `above` over the cell (air, a base clamped or bounded there, a brick whose samples
    /// all are), `Below` likewise. A carve whose disc holds the rectangle `above` deep makes
    /// `d >= -c >= above` (`max` and `smax` only raise `d`, the clamp keeps `M >= above`); a
    /// fill at least `above + k` away keeps `d >= above` (for `smin` see the proof in
    /// `docs/render2d-pipeline.md`), any other fill clears the proof. Symmetrically for
    /// `Below` with fills holding the rectangle and carves staying away. Distances are
    /// measured in `f64` with an allowance for the `f32` rounding of `|p - o| - r`.
    ///
    /// A caller asking about many rectangles of one cell reads the events once with
    /// [`Terrain::event_discs`] and asks [`Terrain::rect_sign_of`].
    pub fn rect_sign(&self, cell: usize, min: Vec2, max: Vec2, above: f32, below: f32) -> RectSign {
        let Some(c) = self.grid.stored_cell(cell) else {
            return RectSign::Unknown;
        };
        // The same walk as `rect_sign_of`, reading the list in place: one question about a
        // cell allocates nothing.
        let discs = c.events.listed().iter().filter_map(|e| self.disc(e));
        let start = self.proof_start(cell);
        self.sign_over(discs, start, cell, min, max, above, Some(below))
    }

    /// Whether the field of cell `cell` is at least `above` (`0 < above <= M`) over the
    /// rectangle `[min, max]`: [`Terrain::rect_sign`]'s `Above`, decided without any
    /// geometry where the cell starts at least that high everywhere and lists carves
    /// only (a carve never lowers the field, and the clamp keeps it at `M >= above`).
    pub(crate) fn rect_above(&self, cell: usize, min: Vec2, max: Vec2, above: f32) -> bool {
        let Some(c) = self.grid.stored_cell(cell) else {
            return false;
        };
        let start = self.proof_start(cell);
        // A list that never held a fill (`may_fill`) holds carves only, unread.
        if let Start::Range(lo, _) = start
            && lo >= above
            && c.lists_carves_only()
        {
            return true;
        }
        if let Start::Brick(_) = start {
            // Reading a brick's samples under a ray's piece costs more than the steps it
            // could save: bricks hold surfaces, and the march crosses them anyway.
            return false;
        }
        let discs = c.events.listed().iter().filter_map(|e| self.disc(e));
        let sign = self.sign_over(discs, start, cell, min, max, above, None);
        sign == RectSign::Above
    }

    /// The events of cell `cell` at the terrain's tick as [`Terrain::rect_sign_of`] reads
    /// them, in list order (events not yet in effect left out), and its starting state.
    /// `None`: no such cell. Valid until the terrain changes.
    pub fn event_discs(&self, cell: usize) -> Option<EventDiscs> {
        let c = self.grid.stored_cell(cell)?;
        let discs = c
            .events
            .listed()
            .iter()
            .filter_map(|e| self.disc(e))
            .collect();
        Some(EventDiscs {
            cell,
            discs,
            start: self.proof_start(cell),
        })
    }

    /// [`Terrain::rect_sign`] over the events `discs` read of one cell.
    pub fn rect_sign_of(
        &self,
        discs: &EventDiscs,
        min: Vec2,
        max: Vec2,
        above: f32,
        below: f32,
    ) -> RectSign {
        let discs_in_order = discs.discs.iter().copied();
        let below = Some(below);
        self.sign_over(
            discs_in_order,
            discs.start,
            discs.cell,
            min,
            max,
            above,
            below,
        )
    }

    /// Event `e` as the sign proof reads it at the terrain's tick; `None` when it is not
    /// in effect.
    fn disc(&self, e: &Listed) -> Option<Disc> {
        let r = e.radius_at(self.tick)?;
        let o = e.center_f32();
        Some(Disc {
            center: [f64::from(o.x), f64::from(o.y)],
            radius: f64::from(r),
            rim: f64::from(e.rim_f32()),
            carve: e.kind == EventKind::Carve,
        })
    }

    /// The walk of [`Terrain::rect_sign`] over a cell's `discs` (in list order) and its
    /// starting state `start`; without `below` it proves `Above` or nothing, and stops as
    /// soon as that is decided.
    #[allow(clippy::too_many_arguments)]
    fn sign_over(
        &self,
        discs: impl DoubleEndedIterator<Item = Disc>,
        start: Start,
        cell: usize,
        min: Vec2,
        max: Vec2,
        above: f32,
        below: Option<f32>,
    ) -> RectSign {
        let ask_below = below.is_some();
        let below = below.unwrap_or(-self.options.band);
        let rect = [
            [f64::from(min.x), f64::from(min.y)],
            [f64::from(max.x), f64::from(max.y)],
        ];
        let slack = 1.0e-3 + 1.0e-6 * f64::from(min.abs().max(max.abs()).max_element());
        let (above64, below64) = (f64::from(above), f64::from(below));
        // Without `below`, only events within reach of `above` can decide anything.
        let widest = if ask_below {
            above64.max(-below64)
        } else {
            above64
        } + slack;
        // Backwards: the last event that forces or breaks a sign decides it, and the
        // starting state decides what no event did.
        let (mut up, mut down) = (None, None);
        for e in discs.rev() {
            if up.is_some() && (down.is_some() || !ask_below) {
                break;
            }
            let (o, r, k) = (e.center, e.radius, e.rim);
            // Most listed events stay away from a small rectangle: past `reach` an event
            // neither forces nor breaks a sign (see below), which the squared distance
            // decides without a square root. The bound is widened by a relative 1e-12 so
            // that the rounding of the squares never skips an event the roots would keep;
            // NaN compares false and takes the full test.
            let reach = (r + widest + k) * (1.0 + 1.0e-12);
            let near_squared = nearest_squared(o, rect);
            if near_squared >= reach * reach {
                continue;
            }
            let (near, far) = (near_squared.sqrt(), farthest(o, rect));
            // `Some(true)`: this event forces the sign, `Some(false)`: it breaks it.
            let (for_up, for_down) = if e.carve {
                // A carve holding the rectangle `above` deep forces `Above`; one reaching
                // within `k` of `-below` breaks `Below`.
                (
                    (far <= r - above64 - slack).then_some(true),
                    short_of(near, r - below64 + k + slack).then_some(false),
                )
            } else {
                // A fill holding it `-below` deep forces `Below`; one reaching within
                // `above + k` breaks `Above`.
                (
                    short_of(near, r + above64 + k + slack).then_some(false),
                    (far <= r + below64 - slack).then_some(true),
                )
            };
            up = up.or(for_up);
            down = down.or(for_down);
        }
        let (up, down) = match (up, down) {
            (Some(u), Some(d)) => (u, d),
            (Some(u), None) if !ask_below => (u, false),
            (u, d) => {
                let (lo, hi) = self.start_bounds(start, cell, min, max);
                (u.unwrap_or(lo >= above), d.unwrap_or(hi <= below))
            }
        };
        // Unasked, `Below` is never claimed: the walk skipped the events that break it.
        let down = down && ask_below;
        match (up, down) {
            (true, _) => RectSign::Above,
            (false, true) => RectSign::Below,
            _ => RectSign::Unknown,
        }
    }

    /// Bounds of cell `cell`'s starting state (before its events) over the whole cell, as
    /// [`Terrain::rect_sign`] reads them: the base's range over the cell (or the band), the
    /// band for air, its negation for solid, a brick's smallest and largest samples.
    /// `None`: no such cell.
    pub fn cell_start_range(&self, cell: usize) -> Option<(f32, f32)> {
        self.grid.stored_cell(cell)?;
        let min = self.grid.cell_min_f32(cell);
        let max = min + Vec2::splat(self.grid.cell_size());
        Some(self.start_range(cell, min, max))
    }

    /// Bounds of cell `cell`'s starting state over the rectangle `[min, max]` (a brick's
    /// interpolant stays within the samples of the lattice squares it covers; the base's
    /// bound is over the whole cell).
    fn start_range(&self, cell: usize, min: Vec2, max: Vec2) -> (f32, f32) {
        self.start_bounds(self.proof_start(cell), cell, min, max)
    }

    /// Cell `cell`'s starting state as the sign proof bounds it: one range over the whole
    /// cell, or a brick to read over each rectangle.
    fn proof_start(&self, cell: usize) -> Start {
        let m = self.options.band;
        let Some(c) = self.grid.stored_cell(cell) else {
            return Start::Range(-m, m);
        };
        match c.state.0 {
            CellState::Base => match &self.cell_tapes {
                Some(cell_tapes) => {
                    let (lo, hi) = cell_tapes.get(&self.grid, Some(cell)).range;
                    Start::Range(lo, hi)
                }
                None => Start::Range(-m, m),
            },
            CellState::Air(_) => Start::Range(m, m),
            CellState::Solid(_) => Start::Range(-m, -m),
            CellState::Brick(id) => Start::Brick(id),
        }
    }

    /// The low end of cell `cell`'s starting range over the whole cell (`None` for a
    /// brick, whose range depends on the rectangle).
    pub(super) fn start_low(&self, cell: usize) -> Option<f32> {
        match self.proof_start(cell) {
            Start::Range(lo, _) => Some(lo),
            Start::Brick(_) => None,
        }
    }

    /// The bounds of starting state `start` of cell `cell` over the rectangle `[min, max]`.
    fn start_bounds(&self, start: Start, cell: usize, min: Vec2, max: Vec2) -> (f32, f32) {
        let m = self.options.band;
        match start {
            Start::Range(lo, hi) => (lo, hi),
            Start::Brick(id) => self.brick_range(cell, id, min, max).unwrap_or((-m, m)),
        }
    }

    /// Slope and error bounds of the field in cell `cell` (`None`: no such cell).
    ///
    /// The base's bound is the smaller of the graph's ([`Sdf::lipschitz`]) and the cell's
    /// specialized tape's ([`crate::tape::Tape::lipschitz_bound`]); `0` where
    /// the base is clamped over the whole cell. Events are 1-Lipschitz and `min`, `max`,
    /// their smooth forms and the clamp keep the larger bound. A brick interpolates
    /// bilinearly samples of a field whose lattice difference quotients are at most `L`
    /// (re-baking samples the previous interpolant at its own lattice points), so its
    /// gradient is at most `sqrt(2) L` and its error at most `L h / sqrt(2)`
    /// ([`Terrain::brick_error_bound`] with the cell's `L`).
    pub fn cell_bounds(&self, cell: usize) -> Option<CellBounds> {
        let c = self.grid.stored_cell(cell)?;
        let events = if c.events.is_empty() { 0.0 } else { 1.0 };
        let base = self.base_cell_lipschitz(cell);
        let exact = base.max(1.0);
        Some(match c.state.0 {
            CellState::Base => CellBounds {
                lipschitz: base.max(events),
                error: 0.0,
            },
            CellState::Air(_) | CellState::Solid(_) => CellBounds {
                lipschitz: events,
                error: 0.0,
            },
            CellState::Brick(_) => CellBounds {
                lipschitz: exact * std::f32::consts::SQRT_2,
                error: exact * self.grid.brick_spacing() * std::f32::consts::FRAC_1_SQRT_2,
            },
        })
    }

    /// The base field's slope bound over cell `cell` (see [`Terrain::cell_bounds`]).
    fn base_cell_lipschitz(&self, cell: usize) -> f32 {
        let global = self.lipschitz();
        let Some(cell_tapes) = &self.cell_tapes else {
            return global;
        };
        let plan = cell_tapes.get(&self.grid, Some(cell));
        if plan.clamped.is_some() {
            return 0.0;
        }
        global.min(plan.value.lipschitz_bound())
    }

    /// The material everywhere in cell `cell` after its events, when it is provably one
    /// constant: the starting state's material is constant over the cell and every listed
    /// fill has that material. `None` when it may vary (or the cell does not exist).
    pub fn cell_material(&self, cell: usize) -> Option<MaterialId> {
        let start = self.start_material(cell)?;
        let c = self.grid.stored_cell(cell)?;
        let all_same =
            (c.events.listed().iter()).all(|e| e.kind == EventKind::Carve || e.material == start);
        all_same.then_some(start)
    }

    /// Whether the material cell `cell` starts from (before its events) is one constant
    /// over the cell, and which.
    pub fn start_material(&self, cell: usize) -> Option<MaterialId> {
        let c = self.grid.stored_cell(cell)?;
        match c.state.0 {
            CellState::Base | CellState::Air(MaterialSource::Base) => self.base_material(cell),
            CellState::Air(MaterialSource::Constant(m)) | CellState::Solid(m) => Some(m),
            CellState::Brick(id) | CellState::Air(MaterialSource::Brick(id)) => {
                let b = self.grid.brick(id)?;
                let first = *b.materials.first()?;
                b.materials.iter().all(|&m| m == first).then_some(first)
            }
        }
    }

    /// The base field's material over cell `cell`, when its specialized tape has a
    /// constant material there.
    fn base_material(&self, cell: usize) -> Option<MaterialId> {
        let cell_tapes = self.cell_tapes.as_ref()?;
        match cell_tapes.get(&self.grid, Some(cell)).material.material() {
            MatOut::Const(m) => Some(m),
            MatOut::Value(_) => None,
        }
    }

    /// The material margin `m` at `p`: every point `q` of `p`'s cell with
    /// `2 max(L, 1) |q - p| < m` has `p`'s material (`L` from [`Terrain::cell_bounds`]).
    /// Along the event fold, from `+inf` where the cell's starting material is constant: a
    /// fill of another material that wins sets it to `d - c`, one that loses lowers it to
    /// `c - d`, one of the same material that wins raises it to `max(d - c, m)`.
    /// `+inf` where no other material can
    /// win anywhere in `p`'s cell, `0` where nothing is proven (outside the grid, a varying
    /// starting material, NaN).
    pub fn material_margin(&self, p: Vec2) -> f32 {
        if p.x.is_nan() || p.y.is_nan() {
            return 0.0;
        }
        let Some(cell) = self.grid.cell_index(p) else {
            return 0.0;
        };
        if self.cell_material(cell).is_some() {
            return f32::INFINITY;
        }
        let Some(start) = self.start_material(cell) else {
            return 0.0;
        };
        let Some(c) = self.grid.stored_cell(cell) else {
            return 0.0;
        };
        let band = self.options.band;
        let pn = V2::new(p.x, p.y);
        let (mut d, _) = self.eval_cell::<f32, false>(p, cell, 0);
        let (mut mat, mut margin) = (start, f32::INFINITY);
        for e in c.events.listed() {
            if let (EventKind::Fill, Some(r)) = (e.kind, e.radius_at(self.tick)) {
                // `c` exactly as `apply_event` computes it, so `wins` is its decision.
                let c = pn.minus(e.center_f32()).length().offset(-r);
                // `!(d < c)`, as `apply_event` decides it (NaN included).
                let wins = d.partial_cmp(&c) != Some(Ordering::Less);
                margin = match (wins, mat == e.material) {
                    (true, true) => (d - c).max(margin),
                    (true, false) => d - c,
                    (false, true) => margin,
                    (false, false) => margin.min(c - d),
                };
            }
            (d, mat) = super::field::apply_event(d, mat, pn, e, self.tick, band);
        }
        // NaN (never expected) proves nothing.
        if margin >= 0.0 { margin } else { 0.0 }
    }
}

impl<F: Sdf> Terrain<F> {
    /// The smallest and largest samples of brick `id` (in cell `cell`) on the lattice
    /// squares the rectangle `[min, max]` touches, its lookup clamped to the brick as the
    /// interpolation clamps it.
    fn brick_range(&self, cell: usize, id: u32, min: Vec2, max: Vec2) -> Option<(f32, f32)> {
        let b = self.grid.brick(id)?;
        let n = self.grid.brick_resolution() as i64;
        let h = f64::from(self.grid.brick_spacing());
        let origin = self.grid.cell_min_f32(cell);
        let lattice = |v: f32, o: f32| (f64::from(v) - f64::from(o)) / h;
        // One extra square each way covers the rounding of the lookup.
        let span = |lo: f64, hi: f64| {
            let a = (lo.floor() as i64 - 1).clamp(0, n);
            let b = (hi.ceil() as i64 + 1).clamp(0, n);
            (a, b)
        };
        let (i0, i1) = span(lattice(min.x, origin.x), lattice(max.x, origin.x));
        let (j0, j1) = span(lattice(min.y, origin.y), lattice(max.y, origin.y));
        let row = (n + 1) as usize;
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let v = *b.values.get(j as usize * row + i as usize)?;
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        (lo <= hi).then_some((lo, hi))
    }
}

/// Squared distance from `o` to the nearest point of `rect`.
fn nearest_squared(o: [f64; 2], rect: [[f64; 2]; 2]) -> f64 {
    let dx = (rect[0][0] - o[0]).max(o[0] - rect[1][0]).max(0.0);
    let dy = (rect[0][1] - o[1]).max(o[1] - rect[1][1]).max(0.0);
    dx * dx + dy * dy
}

/// Distance from `o` to the farthest point of `rect` (a corner).
fn farthest(o: [f64; 2], rect: [[f64; 2]; 2]) -> f64 {
    let dx = (o[0] - rect[0][0]).abs().max((o[0] - rect[1][0]).abs());
    let dy = (o[1] - rect[0][1]).abs().max((o[1] - rect[1][1]).abs());
    (dx * dx + dy * dy).sqrt()
}

/// `!(v >= bound)`: `v` is below `bound`, or not comparable with it (NaN proves nothing).
fn short_of(v: f64, bound: f64) -> bool {
    !matches!(
        v.partial_cmp(&bound),
        Some(Ordering::Greater | Ordering::Equal)
    )
}
