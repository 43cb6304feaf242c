//! The explosion grid agrees with the brute-force field: bit for bit without bricks, within
//! the documented bound with bricks; bad events change nothing; costs stay bounded.

mod common;

use common::Rng;
use craterfield::det::math::{Dual, Num, V2};
use craterfield::field2d::{
    CellState, Event, MaterialSource, Node, Sample, Sdf, Terrain, TerrainError, TerrainOptions,
};
use glam::Vec2;
use proptest::prelude::*;

/// Ground half-plane `y < ground` (material 1) united with circles (their own materials).
#[derive(Clone, Debug)]
struct TestBase {
    ground: f32,
    circles: Vec<(Vec2, f32, u16)>,
}

impl TestBase {
    fn eval<N: Num>(&self, x: N, y: N) -> (N, u16) {
        let mut d = y.offset(-self.ground);
        let mut m = 1;
        for &(c, r, mat) in &self.circles {
            let dc = V2::new(x, y).minus(c).length().offset(-r);
            if dc.value() < d.value() {
                d = dc;
                m = mat;
            }
        }
        (d, m)
    }
}

impl Sdf for TestBase {
    fn distance(&self, p: Vec2) -> f32 {
        self.eval(p.x, p.y).0
    }
    fn sample(&self, p: Vec2) -> Sample {
        let (x, y) = Dual::point(p);
        let (d, material) = self.eval(x, y);
        Sample {
            distance: d.v,
            gradient: d.gradient(),
            material,
        }
    }
    fn lipschitz(&self) -> f32 {
        1.0
    }
}

const BOUND: f32 = 200.0;

fn opts(cap: usize, res: u32) -> TerrainOptions {
    TerrainOptions {
        cell_size: 32.0,
        band: 16.0,
        cell_cap: cap,
        // Every waiting list bakes at the next advance: these tests check exactness.
        bake_rows_per_tick: 1 << 16,
        max_cell_events: cap.max(1 << 16),
        brick_resolution: res,
        max_event_radius: 128.0,
        max_rim: 16.0,
        max_events: 10_000,
        material_count: 8,
    }
}

fn terrain(base: TestBase, o: TerrainOptions) -> Terrain<TestBase> {
    Terrain::new(base, Vec2::splat(-BOUND), Vec2::splat(BOUND), o).unwrap()
}

#[derive(Clone, Debug)]
struct Spec {
    fill: bool,
    /// Either a free centre, or a cell corner (i, j) plus a tiny offset.
    center: (Vec2, Option<(i32, i32)>),
    radius: f32,
    rim: f32,
    grow: u16,
    tick: u32,
    material: u16,
    set_tick_before: Option<u32>,
}

fn spec() -> impl Strategy<Value = Spec> {
    let center = prop_oneof![
        (-BOUND..BOUND, -BOUND..BOUND).prop_map(|(x, y)| (Vec2::new(x, y), None)),
        (-4i32..5, -4i32..5, -3i32..4, -3i32..4, 0u8..3).prop_map(|(i, j, ox, oy, edge)| {
            let off = Vec2::new(ox as f32, oy as f32) / 256.0;
            let off = match edge {
                0 => off,
                1 => Vec2::new(off.x, off.y + 13.0),
                _ => Vec2::new(off.x + 7.5, off.y),
            };
            (off, Some((i, j)))
        }),
    ];
    let radius = prop_oneof![1.0f32..40.0, 40.0f32..128.0, Just(128.0f32)];
    let rim = prop_oneof![3 => Just(0.0f32), 2 => 0.25f32..16.0];
    let grow = prop_oneof![3 => Just(0u16), 1 => 1u16..6];
    let tick = prop_oneof![2 => Just(0u32), 1 => 0u32..8];
    let set_tick = prop_oneof![4 => Just(None), 1 => (0u32..12).prop_map(Some)];
    (
        any::<bool>(),
        center,
        radius,
        rim,
        grow,
        tick,
        0u16..8,
        set_tick,
    )
        .prop_map(
            |(fill, center, radius, rim, grow, tick, material, set_tick_before)| Spec {
                fill,
                center,
                radius,
                rim,
                grow,
                tick,
                material,
                set_tick_before,
            },
        )
}

fn base() -> impl Strategy<Value = TestBase> {
    let circle = (-150.0f32..150.0, -150.0f32..150.0, 5.0f32..60.0, 2u16..6)
        .prop_map(|(x, y, r, m)| (Vec2::new(x, y), r, m));
    (-50.0f32..50.0, prop::collection::vec(circle, 0..4))
        .prop_map(|(ground, circles)| TestBase { ground, circles })
}

fn to_event(t: &Terrain<TestBase>, s: &Spec) -> Event {
    let c = match s.center.1 {
        None => s.center.0,
        Some((i, j)) => {
            // A cell corner near the middle of the grid, plus the offset.
            let g = t.grid();
            let o = g.origin();
            let cs = g.cell_size();
            let (nx, ny) = g.dims();
            let ci = (nx / 2) as i32 + i;
            let cj = (ny / 2) as i32 + j;
            Vec2::new(o.x + ci as f32 * cs, o.y + cj as f32 * cs) + s.center.0
        }
    };
    let c = c.clamp(Vec2::splat(-BOUND), Vec2::splat(BOUND));
    let e = if s.fill {
        Event::fill(c, s.radius, s.material).unwrap()
    } else {
        Event::carve(c, s.radius).unwrap()
    };
    e.with_rim(s.rim)
        .unwrap()
        .with_growth(s.grow)
        .at_tick(s.tick)
}

fn build(base: &TestBase, specs: &[Spec], final_tick: u32, o: TerrainOptions) -> Terrain<TestBase> {
    let mut t = terrain(base.clone(), o);
    for s in specs {
        if let Some(tk) = s.set_tick_before {
            t.set_tick(tk).unwrap();
        }
        let e = to_event(&t, s);
        t.apply(e).unwrap();
    }
    t.set_tick(final_tick).unwrap();
    t
}

/// Query points: random ones plus points near event centres, disc edges and cell corners.
fn query_points(t: &Terrain<TestBase>, random: &[(f32, f32)]) -> Vec<Vec2> {
    let mut pts: Vec<Vec2> = random.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
    let g = t.grid();
    for e in t.events() {
        let c = e.center_f32();
        let r = e.radius_f32();
        pts.push(c + Vec2::new(0.3, -0.2));
        pts.push(c + Vec2::new(r, 0.01));
        pts.push(c + Vec2::new(-0.7 * r, 0.7 * r));
        // Just inside the disc edge in 8 directions (where a wrongly dropped event shows).
        for k in 0..8 {
            let (sn, cs) = craterfield::det::math::sin_cos_deg(k as f32 * 45.0 + 10.0);
            pts.push(c + Vec2::new(cs, sn) * (r - 0.5));
        }
        let corner = ((c - g.origin()) / g.cell_size()).round() * g.cell_size() + g.origin();
        pts.push(corner);
        pts.push(corner - Vec2::splat(1.0 / 1024.0));
    }
    pts
}

fn assert_same(a: Sample, b: Sample, p: Vec2) {
    assert_eq!(
        a.distance.to_bits(),
        b.distance.to_bits(),
        "distance at {p}: {a:?} vs {b:?}"
    );
    assert_eq!(
        a.gradient.x.to_bits(),
        b.gradient.x.to_bits(),
        "gradient.x at {p}: {a:?} vs {b:?}"
    );
    assert_eq!(
        a.gradient.y.to_bits(),
        b.gradient.y.to_bits(),
        "gradient.y at {p}: {a:?} vs {b:?}"
    );
    assert_eq!(a.material, b.material, "material at {p}: {a:?} vs {b:?}");
}

fn uses_brick(t: &Terrain<TestBase>, p: Vec2) -> bool {
    matches!(
        t.cell_state(p),
        Some(CellState::Brick(_)) | Some(CellState::Air(MaterialSource::Brick(_)))
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn grid_without_bricks_is_bit_identical_to_brute_force(
        b in base(),
        specs in prop::collection::vec(spec(), 0..40),
        final_tick in 0u32..12,
        random in prop::collection::vec((-420.0f32..420.0, -420.0f32..420.0), 48),
    ) {
        let t = build(&b, &specs, final_tick, opts(1_000_000, 8));
        prop_assert_eq!(t.stats().bricks, 0);
        for p in query_points(&t, &random) {
            let s = t.sample(p);
            prop_assert_eq!(s.distance.to_bits(), t.distance(p).to_bits());
            prop_assert_eq!(t.distance(p).to_bits(), t.distance_brute_force(p).to_bits(), "at {}", p);
            assert_same(s, t.sample_brute_force(p), p);
        }
    }

    #[test]
    fn grid_with_bricks_is_within_the_documented_bound(
        b in base(),
        specs in prop::collection::vec(spec(), 0..40),
        final_tick in 0u32..12,
        random in prop::collection::vec((-420.0f32..420.0, -420.0f32..420.0), 48),
    ) {
        let t = build(&b, &specs, final_tick, opts(2, 8));
        let bound = t.brick_error_bound() + 1e-4;
        prop_assert!((bound - (4.0 / 2f32.sqrt() + 1e-4)).abs() < 1e-5);
        for p in query_points(&t, &random) {
            let d = t.distance(p);
            prop_assert_eq!(t.sample(p).distance.to_bits(), d.to_bits());
            let exact = t.distance_brute_force(p);
            if uses_brick(&t, p) {
                prop_assert!((d - exact).abs() <= bound, "at {}: grid {} brute {} bound {}", p, d, exact, bound);
            } else {
                assert_same(t.sample(p), t.sample_brute_force(p), p);
            }
        }
    }
}

fn hills() -> TestBase {
    TestBase {
        ground: 0.0,
        circles: vec![
            (Vec2::new(-40.0, 10.0), 50.0, 2),
            (Vec2::new(80.0, -20.0), 35.0, 3),
        ],
    }
}

#[test]
fn ten_thousand_explosions_keep_query_cost_bounded() {
    let o = TerrainOptions {
        brick_resolution: 8,
        ..TerrainOptions::default()
    };
    let mut t = Terrain::new(hills(), Vec2::splat(-1000.0), Vec2::splat(1000.0), o).unwrap();
    let mut rng = Rng(7);
    for _ in 0..10_000 {
        let c = Vec2::new(rng.range(-150.0, 150.0), rng.range(-150.0, 150.0));
        let e = Event::carve(c, rng.range(8.0, 200.0)).unwrap();
        t.apply(e).unwrap();
    }
    // Without a tick, lists wait past the cap, but below twice the cap.
    let s = t.stats();
    assert!(s.max_cell_events < 2 * o.cell_cap, "{s:?}");
    // Advancing bakes them back within the cap.
    let mut advances = 0;
    while t.stats().over_cap_cells > 0 && advances < 100 {
        t.set_tick(t.tick() + 1).unwrap();
        advances += 1;
    }
    let s = t.stats();
    assert!(s.max_cell_events <= o.cell_cap, "{s:?}");
    assert_eq!(s.over_cap_cells, 0);
    assert!(s.bricks > 0 || s.resets > 0, "{s:?}");
    assert!(s.resets > 0 && s.bakes > 0, "{s:?}");
    let bound = t.brick_error_bound() + 1e-4;
    for _ in 0..200 {
        let p = Vec2::new(rng.range(-400.0, 400.0), rng.range(-400.0, 400.0));
        assert!(t.cell_event_count(p) <= o.cell_cap);
        let d = t.distance(p);
        let exact = t.distance_brute_force(p);
        assert!((d - exact).abs() <= bound, "at {p}: {d} vs {exact}");
        if !uses_brick(&t, p) {
            assert_eq!(d.to_bits(), exact.to_bits(), "at {p}");
        }
    }
}

/// Events that cannot be baked yet (growing ones, ones that start later, and every event
/// queued behind them) fill a cell's list only up to `max_cell_events`: the next is
/// refused and changes nothing, the cells stay as cheap as the limit, and once the
/// blockers settle the cell bakes and accepts events again.
#[test]
fn unbakeable_events_cannot_grow_a_cell_past_its_limit() {
    let o = TerrainOptions {
        cell_cap: 8,
        max_cell_events: 40,
        ..TerrainOptions::default()
    };
    let at = Vec2::new(10.0, 10.0);
    for blocker in ["growing", "future", "queued behind growing"] {
        let mut t = Terrain::new(hills(), Vec2::splat(-1000.0), Vec2::splat(1000.0), o).unwrap();
        let mut accepted = 0;
        let mut refused = None;
        for k in 0..200u32 {
            let e = Event::carve(at + Vec2::new((k % 7) as f32, (k % 5) as f32), 6.0).unwrap();
            let e = match blocker {
                "growing" => e.with_growth(65_535),
                "future" => e.at_tick(1_000_000),
                _ if k == 0 => e.with_growth(100),
                _ => e,
            };
            let before = (t.events().len(), t.distance(at).to_bits(), t.stats());
            match t.apply(e) {
                Ok(()) => accepted += 1,
                Err(err) => {
                    assert!(
                        matches!(err, TerrainError::CellFull { max: 40, .. }),
                        "{err}"
                    );
                    assert_eq!(
                        (t.events().len(), t.distance(at).to_bits(), t.stats()),
                        before
                    );
                    refused = Some(err);
                }
            }
        }
        assert!(refused.is_some(), "{blocker}: nothing refused");
        assert_eq!(accepted, 40, "{blocker}");
        assert!(
            t.stats().max_cell_events <= 40,
            "{blocker}: {:?}",
            t.stats()
        );
        if blocker == "queued behind growing" {
            // Once the growing event settles the list bakes and takes events again.
            t.set_tick(200).unwrap();
            assert!(t.stats().max_cell_events <= o.cell_cap, "{:?}", t.stats());
            t.apply(Event::carve(at, 6.0).unwrap()).unwrap();
        }
    }
}

/// No insert pays for a bake until a list reaches twice the cap: lists past the cap wait
/// for the tick to advance, which bakes `bake_rows_per_tick` lattice rows per tick advanced
/// (here a third of a brick's 9 rows, as many again for every 4 waiting lists).
/// Meanwhile the waiting cells answer exactly (bitwise the brute force), and the same
/// events at the same ticks give the same bits.
#[test]
fn bakes_wait_for_the_tick_and_pending_cells_stay_exact() {
    let o = TerrainOptions {
        cell_cap: 8,
        bake_rows_per_tick: 3,
        ..opts(8, 8)
    };
    let run = || {
        let mut t = terrain(hills(), o);
        let mut bakes_on_insert = Vec::new();
        for k in 0..15u32 {
            let at = Vec2::new(-30.0 + 4.0 * k as f32, 5.0 * (k % 3) as f32);
            let before = t.stats().bakes;
            t.apply(Event::carve(at, 40.0).unwrap()).unwrap();
            bakes_on_insert.push(t.stats().bakes - before);
        }
        (t, bakes_on_insert)
    };
    let (mut t, bakes_on_insert) = run();
    // Lists of at most 15 (< 2 x 8) never bake on insert.
    assert!(
        bakes_on_insert.iter().all(|&b| b == 0),
        "{bakes_on_insert:?}"
    );
    let s = t.stats();
    assert!(s.over_cap_cells > 2 && s.max_cell_events > 8, "{s:?}");
    let lattice: Vec<Vec2> = (0..4000)
        .map(|i| {
            Vec2::new(
                -190.0 + (i % 80) as f32 * 4.75,
                -190.0 + (i / 80) as f32 * 7.6,
            )
        })
        .collect();
    for &p in &lattice {
        assert_same(t.sample(p), t.sample_brute_force(p), p);
    }
    // Each advance bakes its rows (a third of a brick, once more for every 4 waiting
    // lists), until nothing waits.
    let mut advances = 0;
    let (first, mut rows) = (t.stats().bakes, 0);
    while t.stats().over_cap_cells > 0 {
        rows += 3 * t.stats().over_cap_cells.div_ceil(4) as u64;
        t.set_tick(t.tick() + 1).unwrap();
        let bakes = t.stats().bakes - first;
        assert!(bakes * 9 <= rows, "{bakes} bricks of 9 rows in {rows} rows");
        advances += 1;
        assert!(advances < 100, "{:?}", t.stats());
        for &p in lattice.iter().step_by(7) {
            if t.cell_state(p).is_some_and(|s| s.brick().is_none()) {
                assert_same(t.sample(p), t.sample_brute_force(p), p);
            }
        }
    }
    assert!(advances > 1, "{advances}");
    assert!(t.stats().max_cell_events <= 8, "{:?}", t.stats());
    // A list that reaches twice the cap bakes as its event is applied.
    let before = t.stats().bakes;
    for _ in 0..16 {
        t.apply(Event::carve(Vec2::new(3.0, 4.0), 30.0).unwrap())
            .unwrap();
    }
    assert!(t.stats().bakes > before, "{:?}", t.stats());
    assert!(t.stats().max_cell_events < 16, "{:?}", t.stats());
    // The same events at the same ticks: the same bits.
    let (mut again, _) = run();
    let mut first = run().0;
    for k in 1..=advances {
        again.set_tick(k).unwrap();
        first.set_tick(k).unwrap();
    }
    for &p in &lattice {
        assert_eq!(
            again.distance(p).to_bits(),
            first.distance(p).to_bits(),
            "{p}"
        );
    }
}

/// Options whose bricks (9 x 9 samples) bake `rows` lattice rows per tick advance.
fn slow_bake_opts(rows: usize) -> TerrainOptions {
    TerrainOptions {
        cell_cap: 8,
        bake_rows_per_tick: rows,
        ..opts(8, 8)
    }
}

/// A terrain with rollback on whose lists run past the cap of 8.
fn over_cap_terrain(rows: usize) -> Terrain<TestBase> {
    let mut t = terrain(hills(), slow_bake_opts(rows));
    t.enable_rollback();
    for k in 0..15u32 {
        let at = Vec2::new(-30.0 + 4.0 * k as f32, 5.0 * (k % 3) as f32);
        t.apply(Event::carve(at, 40.0).unwrap()).unwrap();
    }
    t
}

/// Applies `n` carves of stream `seed`, one per tick advance.
fn carve_and_advance(t: &mut Terrain<TestBase>, seed: u64, n: usize) {
    let mut rng = Rng(seed);
    for _ in 0..n {
        let at = Vec2::new(rng.range(-60.0, 60.0), rng.range(-20.0, 20.0));
        let r = rng.range(10.0, 40.0);
        t.apply(Event::carve(at, r).unwrap()).unwrap();
        t.set_tick(t.tick() + 1).unwrap();
    }
}

fn distance_bits<F: Sdf>(t: &Terrain<F>) -> Vec<u32> {
    (0..6400)
        .map(|i| {
            let p = Vec2::new(
                -190.0 + (i % 80) as f32 * 4.75,
                -190.0 + (i / 80) as f32 * 4.75,
            );
            t.distance(p).to_bits()
        })
        .collect()
}

/// The partial bake of `t`'s state, as the state's JSON has it.
fn partial_bake(t: &Terrain<TestBase>) -> serde_json::Value {
    serde_json::to_value(t.state()).unwrap()["baking"].clone()
}

/// A bake spread over several advances installs, once its last row is baked, the brick a
/// bake in one advance installs: the same samples, the same field.
#[test]
fn a_bake_spread_over_ticks_installs_the_brick_a_whole_bake_would() {
    let mut slow = over_cap_terrain(2);
    let mut whole = over_cap_terrain(1 << 16);
    whole.set_tick(1).unwrap();
    assert_eq!(whole.stats().over_cap_cells, 0, "{:?}", whole.stats());
    let mut advances = 0;
    while slow.stats().over_cap_cells > 0 {
        slow.set_tick(slow.tick() + 1).unwrap();
        advances += 1;
        assert!(advances < 100, "{:?}", slow.stats());
    }
    assert!(advances >= 5, "9 rows at 2 a tick: {advances}");
    assert!(whole.stats().bakes > 1, "{:?}", whole.stats());
    assert_eq!(slow.stats().bakes, whole.stats().bakes);
    assert!(bricks(&slow) == bricks(&whole), "the same bricks");
    assert!(
        distance_bits(&slow) == distance_bits(&whole),
        "the same field"
    );
}

/// A partial bake continues exactly after a rollback to a mark taken while it was under
/// way (the timeline rolled back had finished it and started others), and after its state
/// was restored into a fresh terrain: every later tick gives the bits of a run that did
/// neither.
#[test]
fn rollbacks_and_restored_states_continue_a_partial_bake_exactly() {
    let mut reference = over_cap_terrain(3);
    reference.set_tick(1).unwrap();
    assert!(!partial_bake(&reference).is_null(), "a bake is under way");
    let mut rolled = reference.clone();
    let mark = rolled.mark().unwrap();
    carve_and_advance(&mut rolled, 7, 12);
    assert!(rolled.stats().bakes > 0, "{:?}", rolled.stats());
    rolled.rollback(&mark).unwrap();
    assert!(
        rolled.state() == reference.state(),
        "the rollback restores the bake"
    );
    let mut restored = terrain(hills(), slow_bake_opts(3));
    restored.restore_state(&reference.state()).unwrap();
    assert!(
        restored.state() == reference.state(),
        "the restore keeps the bake"
    );
    for t in [&mut reference, &mut rolled, &mut restored] {
        carve_and_advance(t, 8, 12);
    }
    assert!(reference.stats().bakes > 1, "{:?}", reference.stats());
    assert!(rolled.state() == reference.state(), "after the rollback");
    assert!(restored.state() == reference.state(), "after the restore");
    assert!(distance_bits(&rolled) == distance_bits(&reference));
    assert!(distance_bits(&restored) == distance_bits(&reference));
}

/// A state whose partial bake does not fit its cells (a cell not over the cap, a prefix
/// that is not a settled prefix of the list, as many rows as a brick has) is refused,
/// naming it, and nothing changes.
#[test]
fn states_with_a_bad_partial_bake_are_refused() {
    let mut t = over_cap_terrain(3);
    t.set_tick(1).unwrap();
    let good = serde_json::to_value(t.state()).unwrap();
    let bake = good["baking"].as_array().unwrap().clone();
    let (cell, prefix) = (bake[0].as_u64().unwrap(), bake[1].as_u64().unwrap());
    let quiet = (0..t.grid().cell_count() as u64)
        .find(|&c| t.grid().cell(c as usize).unwrap().events().is_empty())
        .unwrap();
    let cases = [
        (serde_json::json!([quiet, 1, 0]), "cap"),
        (serde_json::json!([cell, 0, 0]), "settled prefix"),
        (serde_json::json!([cell, 10_000, 0]), "settled prefix"),
        (serde_json::json!([cell, prefix, 9]), "9 rows of 9"),
        (serde_json::json!([u32::MAX, 1, 0]), "cap"),
    ];
    let mut fresh = terrain(hills(), slow_bake_opts(3));
    let before = (distance_bits(&fresh), fresh.stats());
    for (value, words) in cases {
        let mut v = good.clone();
        v["baking"] = value.clone();
        let state: craterfield::field2d::TerrainState = serde_json::from_value(v).unwrap();
        let e = fresh.restore_state(&state).unwrap_err().to_string();
        assert!(e.contains(words), "{value}: {e:?} should mention {words:?}");
        assert!((distance_bits(&fresh), fresh.stats()) == before, "{value}");
    }
}

#[test]
fn bad_events_are_rejected_and_change_nothing() {
    let o = TerrainOptions {
        material_count: 4,
        ..TerrainOptions::default()
    };
    let mut t = Terrain::new(hills(), Vec2::splat(-500.0), Vec2::splat(500.0), o).unwrap();
    t.apply(Event::carve(Vec2::new(0.0, 0.0), 30.0).unwrap())
        .unwrap();
    t.apply(
        Event::fill(Vec2::new(50.0, 10.0), 20.0, 3)
            .unwrap()
            .with_rim(4.0)
            .unwrap(),
    )
    .unwrap();
    let probes: Vec<Vec2> = (0..40)
        .map(|i| Vec2::new(i as f32 * 7.3 - 140.0, (i % 7) as f32 * 9.1 - 30.0))
        .collect();
    let before: Vec<(u32, Sample)> = probes
        .iter()
        .map(|&p| (t.distance(p).to_bits(), t.sample(p)))
        .collect();
    let stats_before = t.stats();

    let msg = Event::carve(Vec2::new(f32::NAN, 0.0), 5.0)
        .unwrap_err()
        .to_string();
    assert!(msg.contains("NaN") && msg.contains("center.x"), "{msg}");
    let msg = Event::carve(Vec2::ZERO, f32::NAN).unwrap_err().to_string();
    assert!(msg.contains("NaN") && msg.contains("radius"), "{msg}");
    let msg = Event::carve(Vec2::ZERO, -5.0).unwrap_err().to_string();
    assert!(msg.contains("radius") && msg.contains("-5"), "{msg}");
    let msg = Event::carve(Vec2::ZERO, 0.0).unwrap_err().to_string();
    assert!(msg.contains("radius"), "{msg}");

    let base_event = Event::carve(Vec2::ZERO, 5.0).unwrap();
    let cases: Vec<(Event, &[&str])> = vec![
        (
            Event {
                radius: -256,
                ..base_event
            },
            &["radius", "-1"],
        ),
        (
            Event {
                radius: 0,
                ..base_event
            },
            &["radius", "0"],
        ),
        (
            Event::carve(Vec2::ZERO, 600.0).unwrap(),
            &["radius", "600", "512"],
        ),
        (base_event.with_rim(100.0).unwrap(), &["rim", "100", "64"]),
        (
            Event::carve(Vec2::new(501.0, 0.0), 5.0).unwrap(),
            &["center", "501"],
        ),
        (Event::fill(Vec2::ZERO, 5.0, 4).unwrap(), &["material", "4"]),
        (
            Event {
                center: [i32::MAX, 0],
                ..base_event
            },
            &["center.x", "2147483647"],
        ),
    ];
    for (e, words) in cases {
        let msg = t.apply(e).unwrap_err().to_string();
        for w in words {
            assert!(msg.contains(w), "{msg:?} should mention {w:?}");
        }
    }
    let after: Vec<(u32, Sample)> = probes
        .iter()
        .map(|&p| (t.distance(p).to_bits(), t.sample(p)))
        .collect();
    assert_eq!(before, after, "refused events change nothing");
    assert_eq!(t.stats(), stats_before);
    assert_eq!(t.events().len(), 2);
    // A fresh terrain given only the valid events has the same bits.
    let mut u = Terrain::new(hills(), Vec2::splat(-500.0), Vec2::splat(500.0), o).unwrap();
    u.apply(Event::carve(Vec2::new(0.0, 0.0), 30.0).unwrap())
        .unwrap();
    u.apply(
        Event::fill(Vec2::new(50.0, 10.0), 20.0, 3)
            .unwrap()
            .with_rim(4.0)
            .unwrap(),
    )
    .unwrap();
    assert_eq!(u.stats(), stats_before);
    let again: Vec<(u32, Sample)> = probes
        .iter()
        .map(|&p| (u.distance(p).to_bits(), u.sample(p)))
        .collect();
    assert_eq!(before, again);
}

#[test]
fn bad_terrain_options_are_rejected() {
    let b = hills();
    let e = Terrain::new(
        b.clone(),
        Vec2::new(f32::NAN, 0.0),
        Vec2::ONE,
        TerrainOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("NaN"), "{e}");
    let e = Terrain::new(b.clone(), Vec2::ONE, Vec2::ZERO, TerrainOptions::default()).unwrap_err();
    assert!(e.to_string().contains("empty"), "{e}");
    let e = Terrain::new(
        b.clone(),
        Vec2::ZERO,
        Vec2::splat(1e6),
        TerrainOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("1000000"), "{e}");
    let o = TerrainOptions {
        cell_size: 1.0,
        ..TerrainOptions::default()
    };
    let e = Terrain::new(b.clone(), Vec2::splat(-60000.0), Vec2::splat(60000.0), o).unwrap_err();
    assert!(e.to_string().contains("cells"), "{e}");
    let o = TerrainOptions {
        band: -1.0,
        ..TerrainOptions::default()
    };
    let e = Terrain::new(b.clone(), Vec2::ZERO, Vec2::ONE, o).unwrap_err();
    assert!(
        e.to_string().contains("band") && e.to_string().contains("-1"),
        "{e}"
    );
    let o = TerrainOptions {
        cell_cap: 0,
        ..TerrainOptions::default()
    };
    assert!(
        Terrain::new(b, Vec2::ZERO, Vec2::ONE, o)
            .unwrap_err()
            .to_string()
            .contains("cell_cap")
    );
}

#[test]
fn gradients_match_finite_differences_away_from_kinks() {
    let mut t = terrain(hills(), opts(1_000_000, 8));
    let mut rng = Rng(3);
    for i in 0..30 {
        let c = Vec2::new(rng.range(-150.0, 150.0), rng.range(-60.0, 60.0));
        let e = if i % 3 == 0 {
            Event::fill(c, rng.range(5.0, 30.0), 5).unwrap()
        } else {
            Event::carve(c, rng.range(5.0, 50.0)).unwrap()
        };
        let e = if i % 2 == 0 {
            e.with_rim(rng.range(1.0, 12.0)).unwrap()
        } else {
            e
        };
        t.apply(e).unwrap();
    }
    let h = 1.0 / 64.0;
    let mut checked = 0;
    for _ in 0..2000 {
        let p = Vec2::new(rng.range(-200.0, 200.0), rng.range(-80.0, 80.0));
        let s = t.sample(p);
        let len = s.gradient.length();
        if !(0.5..=1.01).contains(&len) || s.distance.abs() > 15.0 {
            continue;
        }
        // Smooth here: the analytic gradient barely changes over the stencil.
        let smooth = [Vec2::X, Vec2::NEG_X, Vec2::Y, Vec2::NEG_Y]
            .iter()
            .all(|&dir| (t.sample(p + dir * h).gradient - s.gradient).length() < 0.01);
        if !smooth {
            continue;
        }
        let fx = (t.distance(p + Vec2::X * h) - t.distance(p - Vec2::X * h)) / (2.0 * h);
        let fy = (t.distance(p + Vec2::Y * h) - t.distance(p - Vec2::Y * h)) / (2.0 * h);
        assert!(
            (fx - s.gradient.x).abs() < 0.02,
            "at {p}: fd {fx} vs {}",
            s.gradient.x
        );
        assert!(
            (fy - s.gradient.y).abs() < 0.02,
            "at {p}: fd {fy} vs {}",
            s.gradient.y
        );
        checked += 1;
    }
    assert!(checked > 200, "only {checked} smooth points checked");
}

#[test]
fn same_events_give_same_bits_and_pruning_matches_brute_force() {
    let mut rng = Rng(11);
    let mut events = Vec::new();
    for i in 0..300 {
        let c = Vec2::new(rng.range(-100.0, 100.0), rng.range(-100.0, 100.0));
        let r = rng.range(4.0, 128.0);
        let e = if i % 4 == 0 {
            Event::fill(c, r * 0.5, (i % 7) as u16).unwrap()
        } else {
            Event::carve(c, r).unwrap()
        };
        events.push(e);
    }
    let run = || {
        let mut t = terrain(hills(), opts(1_000_000, 8));
        for &e in &events {
            t.apply(e).unwrap();
        }
        t
    };
    let (a, b) = (run(), run());
    assert_eq!(a.stats(), b.stats());
    let s = a.stats();
    assert!(
        s.resets > 0 && s.pruned > 0,
        "pruning should have happened: {s:?}"
    );
    for _ in 0..500 {
        let p = Vec2::new(rng.range(-300.0, 300.0), rng.range(-300.0, 300.0));
        assert_eq!(a.distance(p).to_bits(), b.distance(p).to_bits());
        assert_same(a.sample(p), b.sample(p), p);
        assert_same(a.sample(p), a.sample_brute_force(p), p);
    }
}

#[test]
fn growth_and_tick_rewind_match_brute_force() {
    let mut t = terrain(hills(), opts(2, 8));
    let mut rng = Rng(5);
    for i in 0..60u32 {
        let c = Vec2::new(rng.range(-100.0, 100.0), rng.range(-100.0, 100.0));
        let e = Event::carve(c, rng.range(10.0, 100.0))
            .unwrap()
            .with_growth((i % 4) as u16)
            .at_tick(i / 6);
        t.apply(e).unwrap();
    }
    for tick in [0u32, 3, 12, 5, 20, 1] {
        t.set_tick(tick).unwrap();
        assert_eq!(t.tick(), tick);
        let s = t.stats();
        if tick >= 12 {
            // Every event is settled: every list is within the cap.
            assert_eq!(s.over_cap_cells, 0, "tick {tick}: {s:?}");
            assert!(s.max_cell_events <= 2, "tick {tick}: {s:?}");
        }
        let bound = t.brick_error_bound() + 1e-4;
        for _ in 0..100 {
            let p = Vec2::new(rng.range(-200.0, 200.0), rng.range(-200.0, 200.0));
            let (d, exact) = (t.distance(p), t.distance_brute_force(p));
            if uses_brick(&t, p) {
                assert!(
                    (d - exact).abs() <= bound,
                    "tick {tick} at {p}: {d} vs {exact}"
                );
            } else {
                assert_eq!(d.to_bits(), exact.to_bits(), "tick {tick} at {p}");
            }
        }
    }
}

#[test]
fn nan_and_far_queries_do_not_panic() {
    let mut t = terrain(hills(), opts(2, 8));
    t.apply(Event::carve(Vec2::ZERO, 50.0).unwrap()).unwrap();
    assert!(t.distance(Vec2::new(f32::NAN, 0.0)).is_nan());
    assert!(t.sample(Vec2::new(0.0, f32::NAN)).distance.is_nan());
    for p in [
        Vec2::splat(f32::INFINITY),
        Vec2::new(f32::NEG_INFINITY, 3.0),
        Vec2::splat(1e30),
        Vec2::splat(-1e30),
    ] {
        assert_eq!(t.distance(p).to_bits(), t.distance_brute_force(p).to_bits());
        let _ = t.sample(p);
        assert_eq!(t.cell_event_count(p), 0);
    }
    assert_eq!(t.lipschitz(), 1.0);
}

/// Nested sharp discs (mostly one kind and material, so runs of covered events form), queried
/// densely along every disc edge: a wrongly dropped event shows up there.
fn nested_specs() -> impl Strategy<Value = Vec<(bool, Vec2, f32, u16)>> {
    prop::collection::vec(
        (
            prop::bool::weighted(0.2),
            -20.0f32..20.0,
            -20.0f32..20.0,
            10.0f32..70.0,
            prop::bool::weighted(0.2),
        ),
        1..30,
    )
    .prop_map(|v| {
        v.into_iter()
            .map(|(flip, x, y, r, other_mat)| {
                (flip, Vec2::new(x, y), r, if other_mat { 2 } else { 1 })
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn covered_event_pruning_is_exact(fills in any::<bool>(), specs in nested_specs()) {
        let mut t = terrain(hills(), opts(1_000_000, 8));
        for &(flip, c, r, m) in &specs {
            let e = if fills != flip { Event::fill(c, r, m).unwrap() } else { Event::carve(c, r).unwrap() };
            t.apply(e).unwrap();
        }
        for e in t.events().to_vec() {
            for k in 0..32 {
                let (sn, cs) = craterfield::det::math::sin_cos_deg(k as f32 * 11.25 + 3.0);
                for dr in [-1.5f32, -0.5, -0.1, 0.1, 0.7] {
                    let p = e.center_f32() + Vec2::new(cs, sn) * (e.radius_f32() + dr);
                    assert_same(t.sample(p), t.sample_brute_force(p), p);
                    prop_assert_eq!(t.distance(p).to_bits(), t.distance_brute_force(p).to_bits());
                }
            }
        }
    }
}

#[test]
fn covered_events_are_pruned() {
    let mut t = terrain(hills(), opts(1_000_000, 8));
    for i in 0..20 {
        t.apply(Event::carve(Vec2::new(i as f32 * 0.5, 0.0), 20.0 + i as f32).unwrap())
            .unwrap();
    }
    let s = t.stats();
    assert!(s.pruned > 0, "{s:?}");
    // Each newer disc covers the previous one: every cell lists at most one of them.
    assert!(s.max_cell_events <= 1, "{s:?}");
}

#[test]
fn brick_memory_is_bounded_up_front() {
    use craterfield::field2d::{Graph, Node, Terrain, TerrainOptions};
    let base = Graph::compile(
        &Node::Circle {
            center: [0.0, 0.0],
            radius: 10.0,
        },
        &Default::default(),
    )
    .unwrap();
    let opts = TerrainOptions {
        cell_size: 16.0,
        brick_resolution: 64,
        ..TerrainOptions::default()
    };
    let result = Terrain::new(
        base,
        glam::Vec2::splat(-8000.0),
        glam::Vec2::splat(8000.0),
        opts,
    );
    let Err(err) = result else {
        panic!("a grid whose bricks could take tens of GiB must be refused");
    };
    let msg = err.to_string();
    assert!(
        msg.contains("brick_resolution") && msg.contains("1 GiB"),
        "{msg}"
    );
}

/// A level graph seen only through its point queries (no tape program): the terrain over it
/// evaluates and bakes point by point with the graph walker.
struct Walked<'a>(&'a craterfield::field2d::Graph);

impl Sdf for Walked<'_> {
    fn distance(&self, p: Vec2) -> f32 {
        self.0.distance(p)
    }
    fn sample(&self, p: Vec2) -> Sample {
        self.0.sample(p)
    }
    fn distance_material(&self, p: Vec2) -> (f32, u16) {
        self.0.distance_material(p)
    }
    fn lipschitz(&self) -> f32 {
        self.0.lipschitz()
    }
}

/// Every brick of `terrain`, cell by cell: its values' bits and its materials.
fn bricks<F: Sdf>(terrain: &Terrain<F>) -> Vec<(usize, Vec<u32>, Vec<u16>)> {
    let grid = terrain.grid();
    grid.cells()
        .enumerate()
        .filter_map(|(i, c)| match c.state() {
            CellState::Brick(id) => grid
                .brick_samples(id)
                .map(|(v, m)| (i, v.iter().map(|x| x.to_bits()).collect(), m.to_vec())),
            _ => None,
        })
        .collect()
}

/// Bricks are baked on the SIMD lanes where the base has tapes: on every backend they hold
/// the bits the point path (the graph walker, one lattice point at a time) bakes.
#[test]
fn bricks_are_the_same_bits_on_every_backend_and_on_the_point_path() {
    let level = craterfield::field2d::Level::default_level();
    let b = level.bounds();
    let options = TerrainOptions {
        cell_cap: 6,
        ..level.terrain_options()
    };
    let mut rng = Rng(0xbac0);
    let events: Vec<Event> = (0..1500)
        .map(|i| {
            let c = Vec2::new(
                b.min.x + rng.unit() * (b.max.x - b.min.x),
                b.min.y + rng.unit() * (b.max.y - b.min.y) * 0.6,
            );
            let r = 10.0 + rng.unit() * 50.0;
            if i % 7 == 6 {
                Event::fill(c, r * 0.5, 1).expect("a fill")
            } else {
                Event::carve(c, r).expect("a carve")
            }
        })
        .collect();
    let walked = Walked(level.graph());
    let mut reference = Terrain::new(&walked, b.min, b.max, options).expect("a terrain");
    for e in &events {
        reference.apply(*e).expect("applied");
    }
    let expected = bricks(&reference);
    assert!(expected.len() > 20, "only {} bricks", expected.len());
    for backend in craterfield::backend::Backend::available() {
        let mut t = Terrain::new(level.graph().clone(), b.min, b.max, options).expect("a terrain");
        t.set_backend(backend).expect("available");
        for e in &events {
            t.apply(*e).expect("applied");
        }
        assert!(bricks(&t) == expected, "{backend} baked other bits");
    }
}

/// Cells whose specialized tapes come out alike share one copy: a long expression with no
/// branch to drop costs one tape however many cells are queried, where each cell kept its
/// own (590 KB a cell for such a level). A level with branches keeps its distinct tapes,
/// within the budget, and every result is the same bits as with no specialization.
#[test]
fn cell_tapes_are_shared_and_bounded() {
    use craterfield::field2d::Level;
    use craterfield::field2d::terrain::MAX_CELL_TAPE_BYTES;
    let terms: Vec<String> = (0..3000)
        .map(|i| format!("Mul(X, Const({}.0))", i % 7 + 1))
        .collect();
    // A balanced tree of sums (a chain would pass the parser's nesting limit).
    let mut sum = terms;
    while sum.len() > 1 {
        sum = sum
            .chunks(2)
            .map(|c| match c {
                [a, b] => format!("Add({a}, {b})"),
                [a] => a.clone(),
                _ => unreachable!(),
            })
            .collect();
    }
    let sum = &sum[0];
    // Keep the distance scale sane: x times a large constant, minus y.
    let root = format!("Sub(Y, Mul(Const(0.0001), {sum}))");
    let text = format!(
        "Level(name: \"sum\", bounds: (min: (0.0, 0.0), max: (2048.0, 1024.0)),\n\
         materials: [(name: \"soil\", color: (1, 2, 3))], root: {root})"
    );
    let level = Level::from_ron(&text).unwrap();
    let terrain = level.terrain().unwrap();
    let mut rng = Rng(5);
    for _ in 0..2000 {
        let p = Vec2::new(rng.range(0.0, 2048.0), rng.range(0.0, 1024.0));
        terrain.distance(p);
    }
    // 512 cells queried, each tape set about 300 KB alone: shared, they take a fraction
    // of one.
    let bytes = terrain.cell_tape_bytes();
    assert!(bytes < 1 << 20, "{bytes} bytes of cell tapes");

    let level = Level::default_level();
    let mut plain = level.terrain().unwrap();
    plain.set_specialize(false);
    let terrain = level.terrain().unwrap();
    let b = level.bounds();
    for _ in 0..4000 {
        let p = Vec2::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y));
        assert_eq!(
            terrain.distance(p).to_bits(),
            plain.distance(p).to_bits(),
            "{p}"
        );
    }
    let bytes = terrain.cell_tape_bytes();
    assert!(bytes > 0 && bytes <= MAX_CELL_TAPE_BYTES, "{bytes}");
}

/// `Terrain::prepare` builds every cell's tapes up front (bytes are counted before any
/// query), does nothing more when called again, and changes no bit: a prepared terrain and
/// one whose cells specialize on first use answer every query, and bake every brick, alike.
#[test]
fn prepare_builds_every_cell_tape_and_changes_no_bit() {
    use craterfield::field2d::Level;
    let level = Level::default_level();
    let b = level.bounds();
    // A short cap, so that lists bake.
    let o = TerrainOptions {
        cell_cap: 6,
        ..level.terrain_options()
    };
    let new = || Terrain::new(level.graph().clone(), b.min, b.max, o).unwrap();
    let prepared = new();
    assert_eq!(prepared.cell_tape_bytes(), 0, "nothing is built before use");
    prepared.prepare();
    let bytes = prepared.cell_tape_bytes();
    assert!(bytes > 0, "prepare built no tape");
    prepared.prepare();
    assert_eq!(
        prepared.cell_tape_bytes(),
        bytes,
        "a second prepare built more"
    );

    let mut prepared = prepared;
    let mut lazy = new();
    let mut rng = Rng(0x9e9a);
    // Concentrated on the hills' surface, so that lists pass the cap and bake.
    let mid = Vec2::new(400.0, 620.0);
    for tick in 1..=160u32 {
        let c = mid + Vec2::new(rng.range(-150.0, 150.0), rng.range(-150.0, 150.0));
        let e = Event::carve(c, rng.range(8.0, 60.0)).unwrap();
        for t in [&mut prepared, &mut lazy] {
            t.apply(e).unwrap();
            t.set_tick(tick).unwrap();
        }
    }
    assert!(prepared.stats().bricks > 0, "the events baked no brick");
    let pts: Vec<Vec2> = (0..4000)
        .map(|i| {
            if i % 2 == 0 {
                Vec2::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y))
            } else {
                mid + Vec2::new(rng.range(-220.0, 220.0), rng.range(-220.0, 220.0))
            }
        })
        .collect();
    for &p in &pts {
        assert_same(prepared.sample(p), lazy.sample(p), p);
    }
    let (mut a, mut c) = (vec![0.0; pts.len()], vec![0.0; pts.len()]);
    prepared.distances(&pts, &mut a).unwrap();
    lazy.distances(&pts, &mut c).unwrap();
    for (k, p) in pts.iter().enumerate() {
        assert_eq!(a[k].to_bits(), c[k].to_bits(), "batch at {p}");
    }
}

/// A wavy ground as a height profile (`dx` 4) united with a disc and a box, as a level
/// without materials writes it; `wrap` puts something around the profile.
fn profile_graph(wrap: impl Fn(Node) -> Node) -> craterfield::field2d::Graph {
    let heights: Vec<f32> = (0..=256)
        .map(|i| 300.0 + 60.0 * (i as f32 * 0.09).sin() + 25.0 * (i as f32 * 0.31).cos())
        .collect();
    let ground = Node::HeightProfile {
        x0: 0.0,
        dx: 4.0,
        heights,
    };
    let root = Node::Union(vec![
        wrap(ground),
        Node::Circle {
            center: [300.0, 520.0],
            radius: 40.0,
        },
        Node::Box {
            center: [700.0, 480.0],
            half_size: [50.0, 20.0],
        },
    ]);
    craterfield::field2d::Graph::compile(&root, &Default::default()).unwrap()
}

/// Which programs may cap their height profiles' search at the band: a profile read
/// through unions only may; one offset, or painted so that a comparison picks a material,
/// may not.
#[test]
fn only_profiles_read_through_unions_are_capped() {
    let program = |g: &craterfield::field2d::Graph| g.program();
    assert!(program(&profile_graph(|n| n)).heights_only_clamped());
    let round = |n| Node::Round {
        radius: 3.0,
        node: Box::new(n),
    };
    assert!(!program(&profile_graph(round)).heights_only_clamped());
    let painted = |n| Node::Material {
        id: 1,
        node: Box::new(n),
    };
    assert!(!program(&profile_graph(painted)).heights_only_clamped());
    let circle = Node::Circle {
        center: [0.0, 0.0],
        radius: 5.0,
    };
    let g = craterfield::field2d::Graph::compile(&circle, &Default::default()).unwrap();
    assert!(!program(&g).heights_only_clamped(), "no profile to cap");
}

/// Cells whose height profile stops its search at the band answer every query, gradient
/// and material included, and bake every brick, with the bits of the uncapped whole
/// program: points deep under the ground (whose search would cover hundreds of units) and
/// high above it, before and after explosions, one point at a time and in batches.
#[test]
fn capped_height_profiles_keep_every_bit() {
    let (min, max) = (Vec2::new(0.0, 0.0), Vec2::new(1024.0, 1024.0));
    let o = TerrainOptions {
        cell_cap: 8,
        ..TerrainOptions::default()
    };
    let mut capped = Terrain::new(profile_graph(|n| n), min, max, o).unwrap();
    let mut plain = Terrain::new(profile_graph(|n| n), min, max, o).unwrap();
    plain.set_specialize(false);
    let mut rng = Rng(0xca9);
    let pts: Vec<Vec2> = (0..6000)
        .map(|i| match i % 3 {
            0 => Vec2::new(rng.range(0.0, 1024.0), rng.range(0.0, 1024.0)),
            // Near the ground, where the cap must not drop the nearest segment.
            1 => Vec2::new(rng.range(0.0, 1024.0), rng.range(200.0, 420.0)),
            _ => Vec2::new(rng.range(-40.0, 1064.0), rng.range(-40.0, 1064.0)),
        })
        .collect();
    let compare = |a: &Terrain<craterfield::field2d::Graph>,
                   b: &Terrain<craterfield::field2d::Graph>| {
        for &p in &pts {
            assert_same(a.sample(p), b.sample(p), p);
            assert_eq!(a.distance(p).to_bits(), b.distance(p).to_bits(), "{p}");
        }
        let (mut x, mut y) = (vec![0.0; pts.len()], vec![0.0; pts.len()]);
        a.distances(&pts, &mut x).unwrap();
        b.distances(&pts, &mut y).unwrap();
        for (k, p) in pts.iter().enumerate() {
            assert_eq!(x[k].to_bits(), y[k].to_bits(), "batch at {p}");
        }
    };
    compare(&capped, &plain);
    for tick in 1..=300u32 {
        let c = Vec2::new(rng.range(0.0, 1024.0), rng.range(150.0, 450.0));
        let e = if tick % 5 == 0 {
            Event::fill(c, rng.range(8.0, 30.0), 0).unwrap()
        } else {
            Event::carve(c, rng.range(8.0, 50.0)).unwrap()
        };
        for t in [&mut capped, &mut plain] {
            t.apply(e).unwrap();
            t.set_tick(tick).unwrap();
        }
    }
    assert!(capped.stats().bricks > 0, "the events baked no brick");
    compare(&capped, &plain);
}

/// Cells in the air skip their lists where no fill was ever listed (the value stays at
/// the band's top through carves), on the point path and in batches: cells with fills,
/// fills later covered by carves, and the same terrain restored from its state and rolled
/// back all keep the brute force's bits.
#[test]
fn air_cells_skip_carve_only_lists_and_keep_every_bit() {
    let mut t = terrain(hills(), opts(1 << 10, 8));
    t.enable_rollback();
    let mut rng = Rng(0x0a1e);
    let mark = {
        // Carves high in the air, then a fill there and carves over it.
        for _ in 0..40 {
            let c = Vec2::new(rng.range(-180.0, 180.0), rng.range(70.0, 190.0));
            t.apply(Event::carve(c, rng.range(5.0, 40.0)).unwrap())
                .unwrap();
        }
        let mark = t.mark().unwrap();
        t.apply(Event::fill(Vec2::new(0.0, 140.0), 30.0, 5).unwrap())
            .unwrap();
        for _ in 0..10 {
            let c = Vec2::new(rng.range(-60.0, 60.0), rng.range(100.0, 180.0));
            t.apply(Event::carve(c, rng.range(5.0, 20.0)).unwrap())
                .unwrap();
        }
        mark
    };
    let mut restored = terrain(hills(), opts(1 << 10, 8));
    restored.restore_state(&t.state()).unwrap();
    let mut rolled = t.clone();
    rolled.rollback(&mark).unwrap();
    for (name, terrain) in [
        ("applied", &t),
        ("restored", &restored),
        ("rolled back", &rolled),
    ] {
        let points: Vec<Vec2> = (0..120 * 120)
            .map(|k| {
                Vec2::new(
                    -198.0 + (k % 120) as f32 * 3.3,
                    30.0 + (k / 120) as f32 * 1.4,
                )
            })
            .collect();
        let mut batch = vec![0.0; points.len()];
        terrain.distances(&points, &mut batch).unwrap();
        let mut checked = 0;
        for (&p, &c) in points.iter().zip(&batch) {
            let (a, b) = (terrain.distance(p), terrain.distance_brute_force(p));
            assert_eq!(a.to_bits(), b.to_bits(), "{name}: {a} against {b} at {p}");
            assert_eq!(
                c.to_bits(),
                b.to_bits(),
                "{name}, batch: {c} against {b} at {p}"
            );
            checked += usize::from(a < 16.0);
        }
        assert!(checked > 500, "{name}: only {checked} points below the top");
    }
}
