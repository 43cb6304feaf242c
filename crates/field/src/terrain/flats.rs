//! Squares of a cell where the whole field is the band's constant, proven from the cell's
//! state and list (kept densely by the grid, `grid::CellFlats`), so that a point query
//! there answers from twenty bytes without the cell, its base tape or its list.
//!
//! A square is flat at the top (`+band`) where the cell's state is at the top over it and
//! the list can hold no fill: every carve leaves the top as it is, and both query paths
//! return the state's top without reading the list (`eval_cell`, `pick_term`). It is flat
//! at the bottom (`-band`) where the state is at the bottom over it and no listed event
//! reaches it: beyond an event's reach its term is at or past the band on the side that
//! changes nothing after the clamp. The state is at a bound over a square where the base's
//! tape is proven there (`SubClamp`, padded for the lookup's rounding), the state is air or
//! solid, or every brick sample a point of the square may interpolate is that bound (the
//! bilinear blend of equal corners is that value, bit for bit, with a zero gradient).
//! Either way the answer is the bound with a zero gradient and the state's material, which
//! a query takes from here only where the state has one material over the whole cell.
//!
//! The proofs are conservative: a square left out is answered by the full path, the same
//! bits. Computing a cell's squares costs a pass over its list (a box per event) and, for a
//! brick, one over its samples once per brick; a query pays it once after each change of
//! the cell.

use super::Terrain;
use super::grid::{ALL_SQUARES, CellState, FLAT_SIDE, Flats, Listed, MaterialSource, Rect, guard};
use super::maintain::{event_extent, fixed_f64};
use crate::sample::MaterialId;
use crate::sdf::Sdf;
use crate::tape::MatOut;

impl<F: Sdf> Terrain<F> {
    /// Where the square of `bit` (`Grid::cell_and_square`'s) of cell `cell` is flat: the
    /// band's constant there, and the material if the cell's state has one. Computes the
    /// cell's squares on its first ask after a change.
    #[inline]
    pub(super) fn flat_at(&self, cell: usize, bit: u64) -> Option<(f32, Option<MaterialId>)> {
        let flats = self.flats(cell);
        let band = self.options.band;
        if flats.top & bit != 0 {
            Some((band, flats.material))
        } else if flats.bottom & bit != 0 {
            Some((-band, flats.material))
        } else {
            None
        }
    }

    /// Cell `cell`'s flat squares, computed on the first ask after a change.
    #[inline]
    pub(super) fn flats(&self, cell: usize) -> Flats {
        match self.grid.cell_flats().get(cell) {
            Some(f) => f,
            None => self.compute_flats(cell),
        }
    }

    /// Cell `cell`'s flat squares, computed and kept.
    #[cold]
    fn compute_flats(&self, cell: usize) -> Flats {
        let flats = self.cell_flats_of(cell);
        self.grid.cell_flats().set(cell, flats);
        flats
    }

    fn cell_flats_of(&self, cell: usize) -> Flats {
        let Some(c) = self.grid.stored_cell(cell) else {
            return Flats::default();
        };
        let mut flats = self.state_flats(cell, c.state.0);
        if c.may_fill {
            flats.top = 0;
        }
        flats.bottom &= !self.reached(cell, c.events.listed());
        flats
    }

    /// The squares where cell `cell`'s state is at the top or the bottom of the band, and
    /// its one material.
    fn state_flats(&self, cell: usize, state: CellState) -> Flats {
        let band = self.options.band;
        let base = || {
            let plan = self.cell_tapes.as_ref()?.get(&self.grid, Some(cell));
            let material = match plan.material.material() {
                MatOut::Const(m) => Some(m),
                MatOut::Value(_) => None,
            };
            let (top, bottom) = match plan.clamped {
                Some(c) if c >= band => (ALL_SQUARES, 0),
                Some(_) => (0, ALL_SQUARES),
                None => plan.squares.flats(),
            };
            Some(Flats {
                top,
                bottom,
                material,
            })
        };
        let brick = |id: u32| {
            let b = self.grid.brick(id)?;
            Some(b.flats(self.grid.brick_resolution(), band))
        };
        let air = |material| Flats {
            top: ALL_SQUARES,
            bottom: 0,
            material,
        };
        let flats = match state {
            CellState::Base => base(),
            CellState::Solid(m) => Some(Flats {
                top: 0,
                bottom: ALL_SQUARES,
                material: Some(m),
            }),
            CellState::Air(MaterialSource::Constant(m)) => Some(air(Some(m))),
            CellState::Air(MaterialSource::Base) => Some(air(base().and_then(|f| f.material))),
            CellState::Air(MaterialSource::Brick(id)) => brick(id).map(|f| air(f.material)),
            CellState::Brick(id) => brick(id),
        };
        flats.unwrap_or_default()
    }

    /// The squares of cell `cell` within the reach of any of `listed`: for each event, the
    /// squares its reach's bounding box (grown by the guard that decides which cells list
    /// it) touches.
    fn reached(&self, cell: usize, listed: &[Listed]) -> u64 {
        if listed.is_empty() {
            return 0;
        }
        let rect = self.grid.cell_rect(cell);
        let side = f64::from(self.grid.cell_size()) / f64::from(FLAT_SIDE);
        let band = f64::from(self.options.band);
        let mut reached = 0u64;
        for l in listed {
            let e = l.event();
            let center = [fixed_f64(e.center[0]), fixed_f64(e.center[1])];
            let reach = fixed_f64(e.radius) + fixed_f64(e.rim) + band;
            // One more unit than the cells' test, for the squares' own rounding.
            let pad = reach + 2.0 * guard(event_extent(e) + band, &rect) + 1.0;
            reached |= box_squares(&rect, side, center, pad);
        }
        reached
    }
}

/// The squares of the cell `rect` (of `side` each) that the box `center ± pad` touches.
fn box_squares(rect: &Rect, side: f64, center: [f64; 2], pad: f64) -> u64 {
    let last = f64::from(FLAT_SIDE - 1);
    let span = |axis: usize| {
        let lo = ((center[axis] - pad - rect.min[axis]) / side).floor();
        let hi = ((center[axis] + pad - rect.min[axis]) / side).floor();
        // NaN or a box past the cell on either side touches nothing.
        (lo <= last && hi >= 0.0).then(|| (lo.max(0.0) as u32, hi.min(last) as u32))
    };
    let (Some((x0, x1)), Some((y0, y1))) = (span(0), span(1)) else {
        return 0;
    };
    let row = (u64::MAX >> (63 - x1)) & (u64::MAX << x0) & 0xff;
    (y0..=y1).fold(0, |m, j| m | row << (j * FLAT_SIDE))
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use crate::sdf::Sdf;
    use crate::terrain::Terrain;
    use crate::terrain::eval::tests::{cratered, random_points, short_lists};
    use crate::{Event, Graph};
    use craterfield_core::det::math::Dual;

    /// Carves alone over the whole default level (so lists keep the top of the band),
    /// with ticks advancing and lists short enough to bake bricks.
    fn barrage(seed: u64) -> Terrain<Graph> {
        let mut t = short_lists();
        let mut unit = crate::test_rng::unit_f64(seed);
        let (min, max) = t.bounds;
        for k in 0..1500 {
            let c = min + Vec2::new(unit() as f32, unit() as f32) * (max - min);
            let e = Event::carve(c, 4.0 + unit() as f32 * 60.0).unwrap();
            t.apply(e.at_tick(t.tick())).unwrap();
            if k % 2 == 0 {
                t.set_tick(t.tick() + 1).unwrap();
            }
        }
        t
    }

    /// Random points over the whole level, and points on the edges between squares, where
    /// the lookup's rounding decides.
    fn points<F: Sdf>(t: &Terrain<F>, seed: u64) -> Vec<Vec2> {
        let mut unit = crate::test_rng::unit_f64(seed);
        let (min, max) = t.bounds;
        let size = max - min;
        let mut points = random_points(&mut unit, 40_000, min.into(), size.into());
        let side = t.grid().cell_size() / super::FLAT_SIDE as f32;
        let origin = t.grid().origin();
        let (first, squares) = ((min - origin) / side, size / side);
        for _ in 0..20_000 {
            let at = (first + Vec2::new(unit() as f32, unit() as f32) * squares).floor();
            let on = origin + at * side;
            let along = unit() as f32 * side;
            let step = if unit() < 0.5 { Vec2::X } else { Vec2::Y };
            points.push(on + step * along);
        }
        points
    }

    /// Checks every point in a flat square against its cell's full path: the distance,
    /// the material where the square gives one, and the sample (a zero gradient), bit for
    /// bit. Returns how many points were in flat squares, and how many with a material.
    fn check<F: Sdf>(t: &Terrain<F>, points: &[Vec2]) -> (usize, usize) {
        let (mut flat, mut with_material) = (0, 0);
        for &p in points {
            let Some((cell, square)) = t.grid.cell_and_square(p) else {
                continue;
            };
            assert_eq!(t.grid.cell_index(p), Some(cell), "{p}");
            let Some((d, material)) = t.flat_at(cell, square) else {
                continue;
            };
            flat += 1;
            let (full, full_material) = t.eval_cell::<f32, true>(p, cell, usize::MAX);
            assert_eq!(d.to_bits(), full.to_bits(), "distance at {p}");
            let dual = t
                .sample_cell(p, cell)
                .unwrap_or_else(|| t.eval_cell::<Dual, true>(p, cell, usize::MAX));
            let bits = |x: Dual| (x.v.to_bits(), x.dx.to_bits(), x.dy.to_bits());
            assert_eq!(bits(dual.0), (d.to_bits(), 0, 0), "sample at {p}");
            if let Some(m) = material {
                with_material += 1;
                assert_eq!((m, m), (full_material, dual.1), "material at {p}");
            }
        }
        (flat, with_material)
    }

    /// A flat square answers what its cell's full path answers, on cratered terrains with
    /// fills, resets, growing and smooth events and bricks, and on a barrage of carves;
    /// and flat squares hold a good share of the points.
    #[test]
    fn flat_squares_answer_as_their_cells_do() {
        let terrains = [
            cratered(0xf1a7, false),
            cratered(0x5100, true),
            barrage(0xba7),
        ];
        for (k, t) in terrains.iter().enumerate() {
            let points = points(t, 0x33 + k as u64);
            let (flat, with_material) = check(t, &points);
            let n = points.len();
            assert!(flat * 4 > n, "{flat} of {n} points in flat squares");
            assert!(
                with_material * 8 > n,
                "{with_material} of {n} with the material"
            );
        }
    }

    /// Squares are recomputed after their cells change, by events dropped right on points
    /// of flat squares (a fill on the top, a carve on the bottom, so the field there
    /// changes) and the bakes they cause, and after a rollback to before those.
    #[test]
    fn flat_squares_follow_changes_and_rollbacks() {
        let mut t = barrage(0xc4a6);
        t.enable_rollback();
        let points = points(&t, 0x9e);
        check(&t, &points);
        let flat: Vec<(Vec2, f32)> = points
            .iter()
            .filter_map(|&p| {
                let (cell, square) = t.grid.cell_and_square(p)?;
                t.flat_at(cell, square).map(|(d, _)| (p, d))
            })
            .step_by(97)
            .collect();
        assert!(flat.len() > 100, "{} flat points", flat.len());
        let mark = t.mark().expect("rollback is enabled");
        for (k, &(p, d)) in flat.iter().enumerate() {
            let e = if d > 0.0 {
                Event::fill(p, 10.0, k as u16 % 3)
            } else {
                Event::carve(p, 10.0)
            };
            t.apply(e.unwrap().at_tick(t.tick())).unwrap();
            if k % 2 == 0 {
                t.set_tick(t.tick() + 1).unwrap();
            }
        }
        let at: Vec<Vec2> = flat.iter().map(|&(p, _)| p).collect();
        for &p in &at {
            assert!(
                t.distance(p).abs() < 32.0,
                "the event at {p} changed the field there"
            );
        }
        check(&t, &at);
        check(&t, &points);
        t.rollback(&mark).unwrap();
        let (again, _) = check(&t, &at);
        assert_eq!(again, at.len(), "the rolled-back squares are flat again");
        check(&t, &points);
    }
}
