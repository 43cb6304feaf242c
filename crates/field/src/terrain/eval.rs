//! Point queries of a terrain: the base clamped to the band (from the cell's tape when the
//! base is a level), a cell's state and list applied in order, and the brute-force
//! reference that every grid path is tested against.

use glam::Vec2;

use super::Terrain;
use super::carve_lanes::{LANES_FROM, carve_max, carve_max_term};
use super::cell_tapes::{CellTape, CellTapes};
use super::field::{Lift, apply_event, apply_unless_top, sharp_carves};
use super::grid::{Cell, CellState, Listed, MaterialSource};
use crate::event::EventKind;
use crate::exec;
use crate::sample::{MaterialId, Sample};
use crate::sdf::{ClearRun, Sdf};
use craterfield_core::det::math::{Dual, Num, V2, max, nclamp};

/// Whether `nmax(a, b)` keeps `a`: only where `a > b` (a tie or a NaN takes `b`).
fn max_keeps(a: f32, b: f32) -> bool {
    a > b
}

/// Whether `nmin(a, b)` keeps `a`: only where `a < b`.
fn min_keeps(a: f32, b: f32) -> bool {
    a < b
}

/// [`sharp_carves`] on values (sharp carves, all settled), with the term the result came
/// from: the last operand the running maximum took, or the clamp's bound. The loop of
/// [`Terrain::pick_term`] gives the same value and term: between its steps the clamp only
/// replaces a value at or past a bound, after which the running maximum and the clamped
/// value take the same later events (ties go to the later operand in both), and a result
/// at a bound is the clamp's constant in both.
fn carves_term(d: f32, from: Term, p: V2<f32>, events: &[Listed], band: f32) -> (f32, Term) {
    if events.is_empty() {
        return (d, from);
    }
    let (mut top, mut from) = (d, from);
    for (i, e) in events.iter().enumerate() {
        let c = p.minus(e.center_f32()).length().offset(-e.radius_f32());
        if !max_keeps(top, -c) {
            (top, from) = (-c, Term::Event(i));
        }
    }
    match nclamp_term(top, band) {
        Some(bound) => (bound, Term::Flat),
        None => (top, from),
    }
}

/// The bound `nclamp(top, -band, band)` replaces `top` with, if it does: `-band` where
/// `top` is not above it, else `band` where it is not below.
fn nclamp_term(top: f32, band: f32) -> Option<f32> {
    if !max_keeps(top, -band) {
        return Some(-band);
    }
    if !min_keeps(top, band) {
        return Some(band);
    }
    None
}

/// The term a value computed on `f32` came from ([`Terrain::sample_cell`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Term {
    /// A constant of the clamp (or a constant state): gradient `+0`.
    Flat,
    /// The cell state's base or brick.
    State,
    /// The listed event at this position.
    Event(usize),
}

impl<F: Sdf> Terrain<F> {
    /// The base's tapes at `p` in `cell` (`None`: outside the grid, its halo tile).
    fn plan<'a>(&self, cell_tapes: &'a CellTapes, cell: Option<usize>, p: Vec2) -> &'a CellTape {
        match cell {
            Some(_) => cell_tapes.get(&self.grid, cell),
            None => cell_tapes.outside(p),
        }
    }

    /// `clamp(base(p), -M, M)`.
    pub(super) fn base_clamped<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: Option<usize>,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        let Some(cell_tapes) = &self.cell_tapes else {
            let (d, mat) = N::base(&self.base, p, MAT);
            return (nclamp(d, -m, m), mat);
        };
        let plan = self.plan(cell_tapes, cell, p);
        if let Some(c) = plan.clamped.or_else(|| plan.squares.constant(p, m)) {
            let mat = if MAT || N::MATERIAL {
                exec::point::material(&plan.material, p)
            } else {
                0
            };
            return (N::constant(c), mat);
        }
        let (d, mat) = N::tape(plan, p, MAT);
        (nclamp(d, -m, m), mat)
    }

    /// The base field at `p` (in `cell`): from the cell's tape when the base has a
    /// program, else from the base itself. Both give the same bits.
    pub(super) fn base_at<N: Lift>(
        &self,
        p: Vec2,
        cell: Option<usize>,
        material: bool,
    ) -> (N, MaterialId) {
        match &self.cell_tapes {
            Some(cell_tapes) => N::tape(self.plan(cell_tapes, cell, p), p, material),
            None => N::base(&self.base, p, material),
        }
    }

    /// The base's material at `p` (in `cell`), without its distance or gradient.
    fn base_material_at(&self, p: Vec2, cell: Option<usize>) -> MaterialId {
        match &self.cell_tapes {
            Some(cell_tapes) => exec::point::material(&self.plan(cell_tapes, cell, p).material, p),
            None => self.base.distance_material(p).1,
        }
    }

    /// The field at `p` in `cell` from the cell's state and the first `upto` listed events.
    pub(super) fn eval_cell<N: Lift, const MAT: bool>(
        &self,
        p: Vec2,
        cell: usize,
        upto: usize,
    ) -> (N, MaterialId) {
        let m = self.options.band;
        let Some(c) = self.grid.stored_cell(cell) else {
            return self.base_clamped::<N, MAT>(p, None);
        };
        let pn = N::point(p);
        let (mut d, mut mat) = match c.state.0 {
            CellState::Base => self.base_clamped::<N, MAT>(p, Some(cell)),
            CellState::Air(src) => {
                let mat = if N::MATERIAL || MAT {
                    match src {
                        MaterialSource::Base => self.base_material_at(p, Some(cell)),
                        MaterialSource::Constant(m) => m,
                        MaterialSource::Brick(id) => self.grid.brick_material(id, cell, p),
                    }
                } else {
                    0
                };
                (N::constant(m), mat)
            }
            CellState::Solid(mat) => (N::constant(-m), mat),
            CellState::Brick(id) => match self.grid.interpolate(id, cell, pn, N::MATERIAL || MAT) {
                Some(x) => x,
                None => self.base_clamped::<N, MAT>(p, Some(cell)),
            },
        };
        if !c.may_fill && d.is_top(m) {
            // Only carves follow, and each leaves the top as it is (`apply_unless_top`):
            // the list need not be read.
            return (d, mat);
        }
        let listed = c.events.listed();
        if c.folds_carves(self.tick) {
            // Carves leave the material as it is.
            if N::VALUE
                && upto >= listed.len()
                && listed.len() >= LANES_FROM
                && let Some(top) = carve_max(self.backend, p.x, p.y, &c.events, d.value())
            {
                return (N::constant(nclamp(top, -m, m)), mat);
            }
            let upto = upto.min(listed.len());
            return (sharp_carves(d, pn, &listed[..upto], m), mat);
        }
        for e in listed.iter().take(upto) {
            (d, mat) = apply_unless_top(d, mat, pn, e, self.tick, m);
        }
        (d, mat)
    }

    /// [`Sdf::sample`]: in a flat square of a grid cell whose state has one material, the
    /// square's constant ([`Terrain::flat_at`]); elsewhere in a grid cell, on values with
    /// the gradient of the winning term alone ([`Terrain::sample_cell`]); outside the grid,
    /// and in a cell whose list blends, on duals throughout.
    fn sample_at(&self, p: Vec2) -> (Dual, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return self.eval::<Dual, true>(p);
        }
        // `eval` on duals, with the cell looked up once.
        match self.grid.cell_and_square(p) {
            Some((cell, square)) => {
                if let Some((d, Some(mat))) = self.flat_at(cell, square) {
                    return (Dual::constant(d), mat);
                }
                (self.sample_cell(p, cell))
                    .unwrap_or_else(|| self.eval_cell::<Dual, true>(p, cell, usize::MAX))
            }
            None => self.base_clamped::<Dual, true>(p, None),
        }
    }

    /// The sample at `p` in `cell` computed on `f32` values, with the gradient taken at the
    /// end from the term the value came from; `None` where a smooth event would blend, where
    /// the list is empty (nothing to save) and without cell tapes, for the dual path.
    ///
    /// Without smooth terms every step of the field picks one of its operands (`max`,
    /// `min` and the clamp select; they do not blend), and on duals it picks by the
    /// values alone, which are the `f32` path's bits. So the dual result is the picked
    /// term's dual: the state's (its base or brick, evaluated on duals before the list),
    /// an event's `-c` or `c` (evaluated on duals as [`apply_event`] evaluates it), or a
    /// constant of the clamp, whose gradient is `+0`. Every listed event's square root,
    /// division and gradient arithmetic is thus done once, for the winner, instead of on
    /// duals for every event.
    pub(super) fn sample_cell(&self, p: Vec2, cell: usize) -> Option<(Dual, MaterialId)> {
        let c = self.grid.stored_cell(cell)?;
        if c.events.is_empty() {
            // The state alone: on values first, it would be evaluated twice.
            return None;
        }
        let (d, mat, from, state) = self.pick_term(p, cell, c)?;
        let dual = match from {
            Term::Flat => <Dual as Num>::constant(d),
            Term::State => state,
            Term::Event(i) => {
                let e = c.events.listed().get(i)?;
                let r = e.radius_at(self.tick)?;
                let cv = <Dual as Lift>::point(p)
                    .minus(e.center_f32())
                    .length()
                    .offset(-r);
                if e.kind == EventKind::Carve { -cv } else { cv }
            }
        };
        debug_assert_eq!(dual.v.to_bits(), d.to_bits(), "the picked term's value");
        Some((dual, mat))
    }

    /// The value pass of [`Terrain::sample_cell`]: the field's value and material at `p`
    /// in cell `c` (index `cell`), the term the value came from, and the state's dual
    /// ([`Terrain::state_term`]).
    fn pick_term(&self, p: Vec2, cell: usize, c: &Cell) -> Option<(f32, MaterialId, Term, Dual)> {
        let m = self.options.band;
        let (state, mut mat, mut from) = self.state_term(p, cell)?;
        let mut d = state.v;
        if !c.may_fill && d == m && from == Term::Flat {
            // Only carves follow, and none changes the top (as in `eval_cell`).
            return Some((d, mat, from, state));
        }
        let pv = V2::new(p.x, p.y);
        if c.folds_carves(self.tick) {
            let listed = c.events.listed();
            if listed.len() >= LANES_FROM
                && let Some((top, k)) = carve_max_term(self.backend, p.x, p.y, &c.events, d)
            {
                let from = k.map_or(from, Term::Event);
                return Some(match nclamp_term(top, m) {
                    Some(bound) => (bound, mat, Term::Flat, state),
                    None => (top, mat, from, state),
                });
            }
            let (d, from) = carves_term(d, from, pv, listed, m);
            return Some((d, mat, from, state));
        }
        for (i, e) in c.events.listed().iter().enumerate() {
            let carve = e.kind == EventKind::Carve;
            if carve && d == m && from == Term::Flat {
                // The dual path's `is_top`. At a state's own `+M`, whose gradient may not
                // be `+0`, the carve is applied: it ends at the clamp's `+M`, which is
                // what the dual path gives there either way.
                continue;
            }
            let Some(r) = e.radius_at(self.tick) else {
                continue;
            };
            if e.rim_f32() > 0.0 {
                return None;
            }
            let cv = pv.minus(e.center_f32()).length().offset(-r);
            if carve && !max_keeps(d, -cv) {
                (d, from) = (-cv, Term::Event(i));
            } else if !carve && !min_keeps(d, cv) {
                (d, mat, from) = (cv, e.material, Term::Event(i));
            }
            // `nclamp`: each bound replaces a value not strictly inside it.
            if !max_keeps(d, -m) {
                (d, from) = (-m, Term::Flat);
            }
            if !min_keeps(d, m) {
                (d, from) = (m, Term::Flat);
            }
        }
        Some((d, mat, from, state))
    }

    /// A cell state's dual and material at `p` ([`Terrain::eval_cell`] before any
    /// event, on duals), and its term: `Flat` where the gradient is `+0` in both
    /// components (air, solid, the clamp's bounds, a brick's air), which is then bit for
    /// bit the constant a `Flat` term gives, so the top of the band skips the carves as
    /// on the distance path; `None` without cell tapes (the dual path evaluates the base).
    ///
    /// On duals at once rather than on values and again after the list when the state
    /// wins: the dual's value is the `f32` path's bits, and a brick's samples (a cache
    /// miss) are read once.
    fn state_term(&self, p: Vec2, cell: usize) -> Option<(Dual, MaterialId, Term)> {
        self.cell_tapes.as_ref()?;
        let (dual, mat) = self.eval_cell::<Dual, true>(p, cell, 0);
        let flat = dual.dx.to_bits() == 0 && dual.dy.to_bits() == 0;
        Some((dual, mat, if flat { Term::Flat } else { Term::State }))
    }

    /// The field at `p` on `N`, with the material where `MAT` or `N` wants it: from a flat
    /// square of its cell where one answers ([`Terrain::flat_at`]), else the cell's state
    /// and list, or the base outside the grid.
    pub(super) fn eval<N: Lift, const MAT: bool>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        match self.grid.cell_and_square(p) {
            Some((cell, square)) => {
                // A flat square answers the distance alone, and with the material where
                // the cell's state has one.
                match self.flat_at(cell, square) {
                    Some((d, _)) if !(MAT || N::MATERIAL) => return (N::constant(d), 0),
                    Some((d, Some(mat))) => return (N::constant(d), mat),
                    _ => {}
                }
                self.eval_cell::<N, MAT>(p, cell, usize::MAX)
            }
            None => self.base_clamped::<N, MAT>(p, None),
        }
    }

    pub(super) fn eval_brute<N: Lift>(&self, p: Vec2) -> (N, MaterialId) {
        if p.x.is_nan() || p.y.is_nan() {
            return (N::constant(f32::NAN), 0);
        }
        let pn = N::point(p);
        // The reference: the base's own evaluation (the graph walker for a level).
        let band = self.options.band;
        let (d0, mat0) = N::base(&self.base, p, true);
        let (mut d, mut mat) = (nclamp(d0, -band, band), mat0);
        for e in self.events.iter() {
            (d, mat) = apply_event(d, mat, pn, e, self.tick, self.options.band);
        }
        (d, mat)
    }

    /// Reference distance: every event in order, no grid, no pruning.
    pub fn distance_brute_force(&self, p: Vec2) -> f32 {
        self.eval_brute::<f32>(p).0
    }

    /// Reference sample: every event in order, no grid, no pruning.
    pub fn sample_brute_force(&self, p: Vec2) -> Sample {
        let (d, material) = self.eval_brute::<Dual>(p);
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }
}

impl<F: Sdf> Sdf for Terrain<F> {
    fn distance(&self, p: Vec2) -> f32 {
        self.eval::<f32, false>(p).0
    }

    fn distance_material(&self, p: Vec2) -> (f32, MaterialId) {
        self.eval::<f32, true>(p)
    }

    fn sample(&self, p: Vec2) -> Sample {
        let (d, material) = self.sample_at(p);
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }

    fn lipschitz(&self) -> f32 {
        max(self.base.lipschitz(), 1.0)
    }

    fn clear_run(&self, p: Vec2, dir: Vec2, above: f32) -> ClearRun {
        self.clear_run_from(p, dir, above)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use glam::Vec2;

    use super::Term;
    use crate::sdf::Sdf;
    use crate::terrain::{CellState, Terrain};
    use crate::{Event, Graph, Level};
    use craterfield_core::backend::Backend;
    use craterfield_core::det::math::Dual;

    /// The default level with lists short enough, and bricks coarse enough, that a few
    /// hundred events bake many bricks.
    pub(in crate::terrain) fn short_lists() -> Terrain<Graph> {
        let level = Level::default_level();
        let b = level.bounds();
        let mut o = level.terrain_options();
        o.cell_cap = 8;
        o.brick_resolution = 8;
        Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap()
    }

    /// Random events on the default level: carves and fills, some wide enough to reset
    /// cells, a tenth smooth, a tenth growing, with ticks advancing, lists short enough
    /// to bake bricks.
    pub(in crate::terrain) fn cratered(seed: u64, smooth: bool) -> Terrain<Graph> {
        let mut t = short_lists();
        let mut unit = crate::test_rng::unit_f64(seed);
        for k in 0..700u32 {
            let c = Vec2::new(
                1100.0 + unit() as f32 * 500.0,
                350.0 + unit() as f32 * 400.0,
            );
            // One in twenty wide enough to cover a cell: resets to air or solid.
            let wide = unit() < 0.05;
            let r = if wide { 100.0 } else { 4.0 } + unit() as f32 * 60.0;
            let mut e = if unit() < 0.2 {
                Event::fill(c, r, (k % 3) as u16).unwrap()
            } else {
                Event::carve(c, r).unwrap()
            };
            if smooth && unit() < 0.1 {
                e = e.with_rim(unit() as f32 * 6.0).unwrap();
            }
            if unit() < 0.1 {
                e = e.with_growth(1 + k as u16 % 5);
            }
            t.apply(e.at_tick(t.tick())).unwrap();
            if k % 3 == 0 {
                t.set_tick(t.tick() + 1).unwrap();
            }
        }
        t
    }

    /// `n` points uniform in the rectangle at `min` of side lengths `size`.
    pub(in crate::terrain) fn random_points(
        unit: &mut impl FnMut() -> f64,
        n: usize,
        min: (f32, f32),
        size: (f32, f32),
    ) -> Vec<Vec2> {
        (0..n)
            .map(|_| {
                let x = min.0 + unit() as f32 * size.0;
                Vec2::new(x, min.1 + unit() as f32 * size.1)
            })
            .collect()
    }

    /// The sample on values with the winner's gradient has every bit of the sample on
    /// duals (value, gradient, material), in every kind of cell, where each kind of term
    /// wins, at random points, at lattice points and on cell edges, bricks with a flat
    /// gradient included; and the fast path answered most of them.
    #[test]
    fn samples_on_values_are_the_dual_samples() {
        for (seed, smooth) in [(0x5a17_u64, false), (0xd0a1, true)] {
            let t = cratered(seed, smooth);
            let mut unit = crate::test_rng::unit_f64(seed ^ 0x77);
            let size = t.grid().cell_size();
            let h = t.grid().brick_spacing();
            let mut points = random_points(&mut unit, 40_000, (1000.0, 300.0), (700.0, 500.0));
            let origin = t.grid().origin();
            for i in 0..200 {
                let q = Vec2::new(
                    1000.0 + unit() as f32 * 700.0,
                    300.0 + unit() as f32 * 500.0,
                );
                let snap = |v: f32, o: f32, s: f32| o + ((v - o) / s).round() * s;
                let lattice = Vec2::new(snap(q.x, origin.x, h), snap(q.y, origin.y, h));
                let edge = Vec2::new(snap(q.x, origin.x, size), q.y + i as f32 * 0.01);
                points.extend([lattice, edge, edge.with_y(snap(q.y, origin.y, size))]);
            }
            // Every lattice point of every brick cell with a list: where a brick's
            // interpolation is `+M` with a slope, which is not the band's flat top.
            let n = t.options.brick_resolution;
            for (cell, c) in t.grid.stored_cells().iter().enumerate() {
                if matches!(c.state.0, CellState::Brick(_)) && !c.events.is_empty() {
                    let m = t.grid.cell_min_f32(cell);
                    let lattice = (0..=n).flat_map(|j| (0..=n).map(move |i| (i, j)));
                    points.extend(lattice.map(|(i, j)| m + Vec2::new(i as f32, j as f32) * h));
                }
            }
            let (mut fast, mut winners) = (0, [0usize; 3]);
            let (mut states, mut flat_bricks, mut sloped_tops) = ([0usize; 4], 0, 0);
            for &p in &points {
                let expected = t.eval::<Dual, true>(p);
                let got = t.sample_at(p);
                let bits = |(d, m): (Dual, u16)| (d.v.to_bits(), d.dx.to_bits(), d.dy.to_bits(), m);
                assert_eq!(bits(got), bits(expected), "at {p:?} (seed {seed:#x})");
                let Some(cell) = t.grid.cell_index(p) else {
                    continue;
                };
                if t.sample_cell(p, cell).is_some() {
                    fast += 1;
                    let state = t.grid.stored_cell(cell).unwrap().state.0;
                    states[match state {
                        CellState::Base => 0,
                        CellState::Air(_) => 1,
                        CellState::Solid(_) => 2,
                        CellState::Brick(_) => 3,
                    }] += 1;
                    let c = t.grid.stored_cell(cell).unwrap();
                    match (state, t.state_term(p, cell)) {
                        (CellState::Brick(_), Some((_, _, Term::Flat))) => flat_bricks += 1,
                        (CellState::Brick(_), Some((d, _, _))) if d.v == t.options.band => {
                            sloped_tops += 1
                        }
                        _ => {}
                    }
                    let (_, _, from, _) = t.pick_term(p, cell, c).unwrap();
                    winners[match from {
                        Term::Flat => 0,
                        Term::State => 1,
                        Term::Event(_) => 2,
                    }] += 1;
                }
            }
            assert!(
                fast > points.len() / 2,
                "{fast} of {} on values",
                points.len()
            );
            assert!(winners.iter().all(|&n| n > 100), "winners {winners:?}");
            assert!(states.iter().all(|&n| n > 100), "states {states:?}");
            // Bricks whose gradient is flat where the point is (air inside a brick).
            assert!(flat_bricks > 100, "{flat_bricks} flat brick samples");
            assert!(
                sloped_tops > 100,
                "{sloped_tops} brick samples at +M with a slope"
            );
        }
    }

    /// Lists of sharp carves long enough for the lanes (`terrain::carve_lanes`) answer
    /// distances and samples with every bit of the scalar chain, on every backend this
    /// machine runs, at random points and on the carves' rims; the chain is the
    /// brute-force reference's bits where the cell is its base.
    #[test]
    fn long_carve_lists_answer_as_the_reference_on_every_backend() {
        let level = Level::default_level();
        let b = level.bounds();
        let mut t =
            Terrain::new(level.graph().clone(), b.min, b.max, level.terrain_options()).unwrap();
        let mut unit = crate::test_rng::unit_f64(0x1a7e5);
        let mut rims = Vec::new();
        for _ in 0..1500 {
            let c = Vec2::new(
                1100.0 + unit() as f32 * 400.0,
                400.0 + unit() as f32 * 300.0,
            );
            let r = 3.0 + unit() as f32 * 20.0;
            t.apply(Event::carve(c, r).unwrap().at_tick(t.tick()))
                .unwrap();
            rims.push(c + Vec2::new(r, 0.0));
        }
        let long = |p: Vec2| {
            (t.grid
                .cell_index(p)
                .and_then(|cell| t.grid.stored_cell(cell)))
            .is_some_and(|c| c.folds_carves(t.tick) && c.events.len() >= super::LANES_FROM)
        };
        let mut points = random_points(&mut unit, 4000, (1050.0, 350.0), (500.0, 400.0));
        points.extend(rims);
        let on_long = points.iter().filter(|&&p| long(p)).count();
        assert!(on_long > 2000, "{on_long} points in long carve lists");
        // The reference: the chain, which the scalar backend runs (in a brick cell the
        // brute force has no brick to read, so it is the reference only elsewhere).
        let bits = |s: crate::Sample| {
            (
                s.distance.to_bits(),
                s.gradient.x.to_bits(),
                s.gradient.y.to_bits(),
                s.material,
            )
        };
        t.set_backend(Backend::Scalar).unwrap();
        let reference: Vec<_> = points
            .iter()
            .map(|&p| (t.distance(p).to_bits(), bits(t.sample(p))))
            .collect();
        for (&p, (d, s)) in points.iter().zip(&reference) {
            if t.cell_state(p) == Some(CellState::Base) {
                assert_eq!(*d, t.distance_brute_force(p).to_bits(), "at {p}");
                assert_eq!(*s, bits(t.sample_brute_force(p)), "at {p}");
            }
        }
        for backend in Backend::available() {
            t.set_backend(backend).unwrap();
            for (&p, (d, s)) in points.iter().zip(&reference) {
                assert_eq!(t.distance(p).to_bits(), *d, "{backend:?} at {p}");
                assert_eq!(bits(t.sample(p)), *s, "{backend:?} at {p}");
            }
        }
    }

    /// The squares of a cell that its tape proves beyond the band answer the clamp's
    /// constant with no evaluation: the same bits as the brute-force reference (distance,
    /// gradient, material) on a lattice over every cell that has proven squares, square
    /// edges included, and one rounding step to either side of each lattice point, on the
    /// untouched level and on a cratered one (events over the squares); batches too.
    #[test]
    fn clamped_squares_answer_as_the_base_does() {
        let untouched = Level::default_level().terrain().unwrap();
        for t in [untouched, cratered(0x5eed, false)] {
            let tapes = t.cell_tapes.as_ref().unwrap();
            let band = t.options.band;
            let (mut squares, mut answered) = (0, 0);
            let mut lattice = Vec::new();
            for cell in 0..t.grid.cell_count() {
                let plan = tapes.get(&t.grid, Some(cell));
                // Only a cell whose state is its base reads the base (a brick cell
                // answers from its samples, which the reference does not have).
                let base = t
                    .grid
                    .stored_cell(cell)
                    .is_none_or(|c| c.state.0 == CellState::Base);
                if plan.squares.proven() == 0 || !base {
                    continue;
                }
                squares += plan.squares.proven();
                let (min, size) = (t.grid.cell_min_f32(cell), t.grid.cell_size());
                for j in 0..=16 {
                    for i in 0..=16 {
                        let p = min + Vec2::new(i as f32, j as f32) * (size / 16.0);
                        for q in [p, p.map(f32::next_up), p.map(f32::next_down)] {
                            if t.grid.cell_index(q) != Some(cell) {
                                continue;
                            }
                            answered += u32::from(plan.squares.constant(q, band).is_some());
                            lattice.push(q);
                            let d = t.distance(q);
                            assert_eq!(d.to_bits(), t.distance_brute_force(q).to_bits(), "{q:?}");
                            let (s, r) = (t.sample(q), t.sample_brute_force(q));
                            let bits = |s: crate::Sample| {
                                let g = s.gradient;
                                (
                                    s.distance.to_bits(),
                                    g.x.to_bits(),
                                    g.y.to_bits(),
                                    s.material,
                                )
                            };
                            assert_eq!(bits(s), bits(r), "at {q:?}");
                        }
                    }
                }
            }
            // Batches answer from the flat squares where the point path does and run the
            // tape and clamp on lanes elsewhere: the same bits as the single points'.
            let mut batch = vec![0.0; lattice.len()];
            t.distances(&lattice, &mut batch).unwrap();
            for (p, d) in lattice.iter().zip(&batch) {
                assert_eq!(d.to_bits(), t.distance(*p).to_bits(), "batch at {p:?}");
            }
            assert!(
                squares > 1000 && answered > 50_000,
                "{squares} squares, {answered} points"
            );
        }
    }
}
