//! No-tunnelling property tests for ray casts and swept circles: random thin features, random
//! paths of any length, compared with dense sampling of the true geometry along the path.

use craterfield::field2d::query::{QueryError, RayOptions, raycast, sweep_circle};
use craterfield::field2d::{Sample, Sdf};
use glam::Vec2;
use proptest::prelude::*;

type P = [f64; 2];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn len(a: P) -> f64 {
    dot(a, a).sqrt()
}
fn p64(v: Vec2) -> P {
    [v.x as f64, v.y as f64]
}

/// A thin feature with an exact signed distance (computed in f64).
#[derive(Clone, Debug)]
enum Shape {
    /// Segment `a-b` inflated by `r`.
    Capsule { a: P, b: P, r: f64 },
    /// Box centred at `c` with unit axis `u` and half extents `h` (along `u`, across).
    Box { c: P, u: P, h: P },
}

impl Shape {
    /// Exact distance and gradient.
    fn exact(&self, p: P) -> (f64, P) {
        match *self {
            Shape::Capsule { a, b, r } => {
                let pa = sub(p, a);
                let ba = sub(b, a);
                let h = (dot(pa, ba) / dot(ba, ba)).clamp(0.0, 1.0);
                let v = [pa[0] - ba[0] * h, pa[1] - ba[1] * h];
                let l = len(v);
                let g = if l > 0.0 {
                    [v[0] / l, v[1] / l]
                } else {
                    [0.0, 0.0]
                };
                (l - r, g)
            }
            Shape::Box { c, u, h } => {
                let w = [-u[1], u[0]];
                let d = sub(p, c);
                let local = [dot(d, u), dot(d, w)];
                let q = [local[0].abs() - h[0], local[1].abs() - h[1]];
                let sx = if local[0] < 0.0 { -1.0 } else { 1.0 };
                let sy = if local[1] < 0.0 { -1.0 } else { 1.0 };
                let (dist, gl) = if q[0] > 0.0 || q[1] > 0.0 {
                    let o = [q[0].max(0.0), q[1].max(0.0)];
                    let l = len(o);
                    (l, [o[0] * sx / l, o[1] * sy / l])
                } else if q[0] > q[1] {
                    (q[0], [sx, 0.0])
                } else {
                    (q[1], [0.0, sy])
                };
                (
                    dist,
                    [gl[0] * u[0] + gl[1] * w[0], gl[0] * u[1] + gl[1] * w[1]],
                )
            }
        }
    }

    /// Bounding circle.
    fn bound(&self) -> (P, f64) {
        match *self {
            Shape::Capsule { a, b, r } => (
                [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0],
                len(sub(b, a)) / 2.0 + r,
            ),
            Shape::Box { c, h, .. } => (c, len(h)),
        }
    }

    /// Thinnest dimension.
    fn width(&self) -> f64 {
        match *self {
            Shape::Capsule { r, .. } => 2.0 * r,
            Shape::Box { h, .. } => 2.0 * h[0].min(h[1]),
        }
    }
}

/// How the scene's exact distance is turned into the field handed to the queries.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// Exact (L = 1).
    Exact,
    /// `2 * exact`, declared L = 2.
    Double,
    /// `0.5 * exact`, a bound declared L = 1.
    Half,
    /// `clamp(exact, -4, 4)`: saturated far away with a zero gradient there, L = 1.
    Clamped,
}

#[derive(Clone, Debug)]
struct Scene {
    shapes: Vec<Shape>,
    kind: Kind,
}

impl Scene {
    fn exact(&self, p: P) -> (f64, P) {
        let mut best = (f64::INFINITY, [0.0, 0.0]);
        for s in &self.shapes {
            let e = s.exact(p);
            if e.0 < best.0 {
                best = e;
            }
        }
        best
    }
}

impl Sdf for Scene {
    fn distance(&self, p: Vec2) -> f32 {
        self.sample(p).distance
    }
    fn sample(&self, p: Vec2) -> Sample {
        let (d, g) = self.exact(p64(p));
        let (d, g) = match self.kind {
            Kind::Exact => (d, g),
            Kind::Double => (2.0 * d, [2.0 * g[0], 2.0 * g[1]]),
            Kind::Half => (0.5 * d, [0.5 * g[0], 0.5 * g[1]]),
            Kind::Clamped if d > 4.0 => (4.0, [0.0, 0.0]),
            Kind::Clamped if d < -4.0 => (-4.0, [0.0, 0.0]),
            Kind::Clamped => (d, g),
        };
        Sample {
            distance: d as f32,
            gradient: Vec2::new(g[0] as f32, g[1] as f32),
            material: 0,
        }
    }
    fn lipschitz(&self) -> f32 {
        match self.kind {
            Kind::Double => 2.0,
            _ => 1.0,
        }
    }
}

/// First `s` in `[0, max_s]` where dense sampling finds `exact(from + dir * s) < radius`,
/// sampling each shape's neighbourhood with a step of a tenth of its width.
fn first_crossing(scene: &Scene, from: P, dir: P, max_s: f64, radius: f64) -> Option<f64> {
    let mut first: Option<f64> = None;
    for shape in &scene.shapes {
        let (c, r) = shape.bound();
        let reach = r + radius + 0.01;
        // The interval of s where the path is within `reach` of the bounding circle's centre.
        let oc = sub(c, from);
        let mid = dot(oc, dir);
        let perp2 = dot(oc, oc) - mid * mid;
        if perp2 > reach * reach {
            continue;
        }
        let half = (reach * reach - perp2).max(0.0).sqrt();
        let s0 = (mid - half).max(0.0);
        let s1 = (mid + half).min(max_s);
        if s0 > s1 {
            continue;
        }
        let h = shape.width() / 10.0;
        let n = ((s1 - s0) / h).ceil() as usize;
        for k in 0..=n {
            let s = (s0 + k as f64 * h).min(s1);
            if first.is_some_and(|f| s >= f) {
                break;
            }
            let p = [from[0] + dir[0] * s, from[1] + dir[1] * s];
            if shape.exact(p).0 < radius {
                first = Some(s);
                break;
            }
        }
    }
    first
}

fn shape_strategy() -> impl Strategy<Value = Shape> {
    (
        any::<bool>(),
        -20.0f64..20.0,
        -20.0f64..20.0,
        0.0f64..std::f64::consts::TAU,
        0.0f64..20.0,
        0.05f64..3.0,
    )
        .prop_map(|(capsule, x, y, angle, length, width)| {
            let u = [angle.cos(), angle.sin()];
            if capsule {
                let a = [x - u[0] * length / 2.0, y - u[1] * length / 2.0];
                let b = [x + u[0] * length / 2.0, y + u[1] * length / 2.0];
                Shape::Capsule {
                    a,
                    b,
                    r: width / 2.0,
                }
            } else {
                Shape::Box {
                    c: [x, y],
                    u,
                    h: [(length + width) / 2.0, width / 2.0],
                }
            }
        })
}

fn scene_strategy() -> impl Strategy<Value = Scene> {
    (
        prop::collection::vec(shape_strategy(), 1..6),
        prop_oneof![
            Just(Kind::Exact),
            Just(Kind::Double),
            Just(Kind::Half),
            Just(Kind::Clamped)
        ],
    )
        .prop_map(|(shapes, kind)| Scene { shapes, kind })
}

/// A path: origin, unit direction, length (log-uniform from 0.1 to 1e5).
fn path_strategy() -> impl Strategy<Value = (Vec2, Vec2, f32)> {
    (
        -40.0f32..40.0,
        -40.0f32..40.0,
        0.0f64..std::f64::consts::TAU,
        -1.0f64..5.0,
    )
        .prop_map(|(x, y, angle, e)| {
            (
                Vec2::new(x, y),
                Vec2::new(angle.cos() as f32, angle.sin() as f32),
                10f64.powf(e) as f32,
            )
        })
}

const OPTS: RayOptions = RayOptions {
    max_steps: 1_000_000,
    hit_epsilon: 1e-3,
};
const TOL: f64 = 1e-3;

/// Checks a query answer (`t` of the hit and the point tested) against dense sampling.
fn check(
    scene: &Scene,
    from: Vec2,
    dir: Vec2,
    max_s: f32,
    radius: f32,
    hit: Option<(f64, Vec2)>,
) -> Result<(), TestCaseError> {
    let first = first_crossing(scene, p64(from), p64(dir), max_s as f64, radius as f64);
    match hit {
        None => prop_assert!(
            first.is_none(),
            "no hit reported, but dense sampling crosses at s = {first:?}"
        ),
        Some((t, point)) => {
            if let Some(f) = first {
                prop_assert!(
                    t <= f + TOL,
                    "hit at t = {t} after the first crossing at s = {f}"
                );
            }
            // The field clearance at the hit is below hit_epsilon...
            let est = scene.distance(point) as f64 / scene.lipschitz() as f64 - radius as f64;
            prop_assert!(
                est < OPTS.hit_epsilon as f64 + 1e-5,
                "clearance {est} at the hit {point}"
            );
            // ...and, unless it starts overlapping, the hit is on the near side of the surface.
            if t > 0.0 {
                let truth = scene.exact(p64(point)).0 - radius as f64;
                prop_assert!(truth >= -TOL, "hit {point} is {truth} past the surface");
                prop_assert!(est >= -TOL, "field clearance {est} at the hit {point}");
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn raycast_never_tunnels(scene in scene_strategy(), (origin, dir, max_t) in path_strategy()) {
        let hit = raycast(&scene, origin, dir, max_t, &OPTS).map_err(|e| TestCaseError::fail(e.to_string()))?;
        if let Some(h) = hit {
            prop_assert!(h.t >= 0.0 && h.t <= max_t);
            prop_assert!((h.normal.length() - 1.0).abs() < 1e-5);
        }
        check(&scene, origin, dir, max_t, 0.0, hit.map(|h| (h.t as f64, h.point)))?;
    }

    #[test]
    fn sweep_never_tunnels(
        scene in scene_strategy(),
        (from, dir, length) in path_strategy(),
        radius in prop_oneof![Just(0.0f32), 0.0f32..2.0],
    ) {
        let to = from + dir * length;
        let hit = sweep_circle(&scene, from, to, radius, &OPTS).map_err(|e| TestCaseError::fail(e.to_string()))?;
        // The reference path uses the motion as the query sees it.
        let motion = to - from;
        let real_len = motion.length();
        let u = motion / real_len;
        let mapped = hit.map(|h| {
            let t = dot(sub(p64(h.center), p64(from)), p64(u));
            (t, h.center)
        });
        if let Some(h) = hit {
            prop_assert!((0.0..=1.0).contains(&h.toi), "{h:?}");
            prop_assert!((h.toi as f64 * real_len as f64 - mapped.unwrap().0).abs() < 1e-3 + 1e-6 * real_len as f64, "{h:?}");
            prop_assert!((h.normal.length() - 1.0).abs() < 1e-5);
        }
        check(&scene, from, u, real_len, radius, mapped)?;
    }

    #[test]
    fn raycast_against_a_convex_polygon_bound(
        offsets in prop::collection::vec(0.5f64..10.0, 3..7),
        jitter in prop::collection::vec(-0.4f64..0.4, 7),
        (origin, dir, max_t) in path_strategy(),
    ) {
        let k = offsets.len();
        let planes: Vec<(P, f64)> = offsets.iter().enumerate().map(|(i, &c)| {
            let a = (i as f64 + jitter[i]) / k as f64 * std::f64::consts::TAU;
            ([a.cos(), a.sin()], c)
        }).collect();
        let poly = Polygon { planes };
        let hit = raycast(&poly, origin, dir, max_t, &OPTS).map_err(|e| TestCaseError::fail(e.to_string()))?;
        // Dense sampling of the sign (exact for a bound) over the part of the ray near the polygon.
        let (o, d) = (p64(origin), p64(dir));
        let mid = -dot(o, d);
        let reach = 60.0f64;
        let perp2 = dot(o, o) - mid * mid;
        let mut first = None;
        if perp2 < reach * reach {
            let half = (reach * reach - perp2).sqrt();
            let (s0, s1) = ((mid - half).max(0.0), (mid + half).min(max_t as f64));
            let mut s = s0;
            while s <= s1 {
                if poly.value([o[0] + d[0] * s, o[1] + d[1] * s]) < 0.0 {
                    first = Some(s);
                    break;
                }
                s += 0.01;
            }
        }
        match hit {
            None => prop_assert!(first.is_none(), "missed a crossing at {first:?}"),
            Some(h) => {
                if let Some(f) = first {
                    prop_assert!((h.t as f64) <= f + TOL, "hit {} after crossing {f}", h.t);
                }
                let v = poly.distance(h.point);
                prop_assert!(v < OPTS.hit_epsilon, "{v}");
                if h.t > 0.0 {
                    prop_assert!(v as f64 >= -TOL, "{v}");
                }
            }
        }
    }
}

/// A convex polygon as the max of half-planes `n . p - c`: exact sign, a distance bound
/// (underestimates outside near vertices), L = 1.
struct Polygon {
    planes: Vec<(P, f64)>,
}

impl Polygon {
    fn sample64(&self, p: P) -> (f64, P) {
        let mut best = (f64::NEG_INFINITY, [0.0, 0.0]);
        for &(n, c) in &self.planes {
            let v = dot(n, p) - c;
            if v > best.0 {
                best = (v, n);
            }
        }
        best
    }
    fn value(&self, p: P) -> f64 {
        self.sample64(p).0
    }
}

impl Sdf for Polygon {
    fn distance(&self, p: Vec2) -> f32 {
        self.value(p64(p)) as f32
    }
    fn sample(&self, p: Vec2) -> Sample {
        let (d, g) = self.sample64(p64(p));
        Sample {
            distance: d as f32,
            gradient: Vec2::new(g[0] as f32, g[1] as f32),
            material: 0,
        }
    }
    fn lipschitz(&self) -> f32 {
        1.0
    }
}

/// A very fast sweep (1e5 units in one motion) still stops at a 0.05-wide wall.
#[test]
fn fast_sweep_stops_at_a_thin_wall() {
    let scene = Scene {
        shapes: vec![Shape::Box {
            c: [30.0, 0.0],
            u: [0.0, 1.0],
            h: [10.0, 0.025],
        }],
        kind: Kind::Exact,
    };
    let from = Vec2::new(0.0, 1.0);
    let h = sweep_circle(
        &scene,
        from,
        Vec2::new(1e5, 1.0),
        0.25,
        &RayOptions::default(),
    )
    .unwrap()
    .unwrap();
    assert!(h.center.x <= 29.725 && h.center.x > 29.72, "{h:?}");
    let r = raycast(&scene, from, Vec2::X, 1e5, &RayOptions::default())
        .unwrap()
        .unwrap();
    assert!(r.t <= 29.975 && r.t > 29.97, "{r:?}");
}

/// A grazing ray along a wall with a small budget fails loudly, naming the budget.
#[test]
fn grazing_ray_reports_the_step_budget() {
    let scene = Scene {
        shapes: vec![Shape::Box {
            c: [50.0, 0.0],
            u: [1.0, 0.0],
            h: [50.0, 1.0],
        }],
        kind: Kind::Exact,
    };
    let small = RayOptions {
        max_steps: 64,
        hit_epsilon: 1e-3,
    };
    let e = raycast(&scene, Vec2::new(0.0, 1.002), Vec2::X, 200.0, &small).unwrap_err();
    assert!(matches!(e, QueryError::StepBudget { steps: 64, .. }), "{e}");
    assert!(e.to_string().contains("step budget"), "{e}");
}

/// The same query twice gives the same bits.
#[test]
fn queries_are_bit_deterministic() {
    let scene = Scene {
        shapes: vec![
            Shape::Capsule {
                a: [3.0, -2.0],
                b: [7.0, 5.0],
                r: 0.2,
            },
            Shape::Box {
                c: [12.0, 1.0],
                u: [0.6, 0.8],
                h: [2.0, 0.1],
            },
        ],
        kind: Kind::Clamped,
    };
    let run = || {
        let r = raycast(
            &scene,
            Vec2::new(-1.0, 0.3),
            Vec2::new(1.0, 0.05),
            100.0,
            &RayOptions::default(),
        )
        .unwrap()
        .unwrap();
        let s = sweep_circle(
            &scene,
            Vec2::new(-1.0, 0.3),
            Vec2::new(40.0, 2.0),
            0.4,
            &RayOptions::default(),
        )
        .unwrap()
        .unwrap();
        [
            r.t, r.point.x, r.point.y, r.normal.x, r.normal.y, s.toi, s.center.x, s.center.y,
            s.normal.x, s.normal.y,
        ]
        .map(f32::to_bits)
    };
    assert_eq!(run(), run());
}

/// A cratered terrain: a wavy ground, two islands and a floating box, carved by explosions
/// and patched by a few fills, so that rays cross air, untouched base, crater and brick cells.
fn cratered_terrain(
    seed: u64,
    events: usize,
) -> craterfield::field2d::Terrain<craterfield::field2d::Graph> {
    cratered_terrain_with(seed, events, 10)
}

/// [`cratered_terrain`] with one fill every `fill_every` events (`0`: carves only).
fn cratered_terrain_with(
    seed: u64,
    events: usize,
    fill_every: usize,
) -> craterfield::field2d::Terrain<craterfield::field2d::Graph> {
    use craterfield::field2d::{Event, Graph, Node, Terrain, TerrainOptions};
    let heights = (0..=256)
        .map(|i| 200.0 + 40.0 * (i as f32 / 12.0).sin())
        .collect();
    let root = Node::Union(vec![
        Node::HeightProfile {
            x0: 0.0,
            dx: 4.0,
            heights,
        },
        Node::Circle {
            center: [300.0, 380.0],
            radius: 40.0,
        },
        Node::Circle {
            center: [760.0, 420.0],
            radius: 25.0,
        },
        Node::Box {
            center: [520.0, 330.0],
            half_size: [60.0, 8.0],
        },
    ]);
    let graph = Graph::compile(&root, &Default::default()).expect("the scene compiles");
    let options = TerrainOptions {
        cell_cap: 8,
        ..TerrainOptions::default()
    };
    let mut terrain =
        Terrain::new(graph, Vec2::ZERO, Vec2::new(1024.0, 512.0), options).expect("a terrain");
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    for k in 0..events {
        let center = Vec2::new(next() * 1024.0, 120.0 + next() * 340.0);
        let radius = 8.0 + next() * 40.0;
        let event = if fill_every > 0 && k % fill_every == fill_every - 1 {
            Event::fill(center, radius * 0.5, 0)
        } else {
            Event::carve(center, radius)
        };
        terrain
            .apply(event.expect("a valid event"))
            .expect("applied");
    }
    terrain
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Rays over a cratered terrain (air, untouched base, crater and brick cells, and the
    /// base alone outside the grid) stop at the first crossing: dense sampling of the
    /// terrain's own field finds none before the hit (nor any, when there is no hit). Two
    /// of the terrains list carves alone, whose bricks rays cross by the floors of their
    /// blocks and by the walk over their lattices.
    #[test]
    fn raycasts_over_a_cratered_terrain_never_tunnel(
        seed in 0u64..4,
        // Inside the level, around it in the grid, and outside the grid (which reaches
        // 609 units past the level).
        origin in (-900.0f32..1900.0, -900.0f32..1400.0),
        angle in 0.0f32..std::f32::consts::TAU,
        length in 1.0f32..2500.0,
    ) {
        thread_local! {
            static TERRAINS: Vec<craterfield::field2d::Terrain<craterfield::field2d::Graph>> =
                (0..4).map(|s| cratered_terrain_with(s, 400, if s < 2 { 10 } else { 0 })).collect();
        }
        TERRAINS.with(|terrains| {
            let terrain = &terrains[seed as usize];
            let (origin, dir) = (Vec2::new(origin.0, origin.1), Vec2::from_angle(angle));
            let hit = raycast(terrain, origin, dir, length, &OPTS).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let end = hit.map_or(length, |h| h.t);
            let step = 0.05f32;
            let mut s = 0.0f32;
            while s + 0.01 < end {
                let d = terrain.distance(origin + dir * s);
                prop_assert!(d > 0.0, "the field is {d} at s = {s}, before the reported end {end}");
                s += step;
            }
            Ok(())
        })?;
    }
}

/// Uniform numbers in `[0, 1)` from `seed` (a 64-bit LCG's top bits).
fn uniform_stream(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// The terrain's clear runs ([`Sdf::clear_run`]) keep their promise: dense sampling along
/// every run finds the field at or above the threshold, inside the grid (air, base,
/// crater and brick cells, with fills listed and without) and outside it (the base's halo
/// and beyond). And they are long enough to matter.
#[test]
fn clear_runs_of_a_cratered_terrain_hold() {
    clear_runs_hold(&cratered_terrain(1, 400));
    clear_runs_hold(&cratered_terrain_with(2, 400, 0));
    // Few carves: most cells the surface crosses keep their base, with short carve lists
    // that the sign proof reads.
    clear_runs_hold(&cratered_terrain_with(3, 30, 0));
}

/// Clear runs from points outside the grid, where the base's halo tiles prove the sky a
/// tile at a time and the walk crosses up to four of them: dense sampling along every run
/// finds the field at or above the threshold (the ground runs on past the level on both
/// sides, so many rays reach it), and many runs cross more than one tile.
#[test]
fn clear_runs_through_the_halo_hold() {
    let terrain = cratered_terrain_with(2, 400, 0);
    let grid = terrain.grid();
    let mut next = uniform_stream(0x4a10_7115);
    let (mut runs, mut past_a_tile) = (0usize, 0usize);
    for k in 0..800 {
        // Left or right of the grid (which reaches 609 units past the level) and within
        // the halo (8,192 units past the grid), around the ground's height.
        let x = 700.0 + next() * 8200.0;
        let x = if k % 2 == 0 { -x } else { 1024.0 + x };
        let p = Vec2::new(x, -1500.0 + next() * 4000.0);
        assert!(grid.cell_index(p).is_none(), "{p} is outside the grid");
        let dir = Vec2::from_angle(next() * std::f32::consts::TAU);
        let above = [1e-3, 0.5, 4.0, 31.0][k % 4];
        let run = terrain.clear_run(p, dir, above);
        assert!(run.clear >= 0.0 && run.retry_after >= 0.0, "{run:?}");
        runs += usize::from(run.clear > 0.0);
        past_a_tile += usize::from(run.clear > 512.0);
        let mut s = 0.0f32;
        while run.clear > 0.0 && s <= run.clear {
            let d = terrain.distance(p + dir * s);
            // The rounding of `p + dir * s` moves the point by less than 1e-2 units here.
            assert!(
                d >= above - 1e-2,
                "run {run:?} from {p} along {dir} above {above}: the field is {d} at s = {s}"
            );
            s += 0.5;
        }
    }
    assert!(runs > 400, "only {runs} of 800 runs proved anything");
    assert!(
        past_a_tile > 100,
        "only {past_a_tile} runs reached past one tile's side"
    );
}

/// [`clear_runs_of_a_cratered_terrain_hold`] on one terrain.
fn clear_runs_hold(terrain: &craterfield::field2d::Terrain<craterfield::field2d::Graph>) {
    let mut next = uniform_stream(0x0c1e_a125);
    let (mut runs, mut proven) = (0usize, 0.0f64);
    for k in 0..3000 {
        let p = Vec2::new(-900.0 + next() * 2800.0, -900.0 + next() * 2300.0);
        let dir = Vec2::from_angle(next() * std::f32::consts::TAU);
        let above = [1e-3, 0.5, 4.0, 31.0][k % 4];
        let run = terrain.clear_run(p, dir, above);
        assert!(run.clear >= 0.0 && run.retry_after >= 0.0, "{run:?}");
        runs += usize::from(run.clear > 0.0);
        proven += f64::from(run.clear);
        // A run of zero claims nothing.
        let mut s = if run.clear > 0.0 {
            0.0f32
        } else {
            f32::INFINITY
        };
        while s <= run.clear {
            let q = p + dir * s;
            let d = terrain.distance(q);
            // The rounding of `p + dir * s` moves `q` by less than 1e-3 units.
            assert!(
                d >= above - 1e-3,
                "run {run:?} from {p} along {dir} above {above}: the field is {d} at s = {s}"
            );
            s += 0.25;
        }
    }
    assert!(runs > 1000, "only {runs} of 3000 runs proved anything");
    assert!(proven > 200_000.0, "only {proven} units proven in all");
}

/// Clear runs from points in brick cells: dense sampling finds the field at or above the
/// threshold over every run (no crossing skipped, the caller's roundings included), with
/// fills listed after the bakes and without. Without fills, the bricks' block floors and
/// the closed-form walk over their lattice squares carry runs into the bricks, many of
/// them to the surface itself, where the field reaches the threshold (the others end at
/// the brick's own surface under a later carve, which the walk does not read; with the
/// floors alone, 1 run in 695 ended at the surface).
#[test]
fn clear_runs_in_brick_cells_hold_and_reach_the_surface() {
    let (inside, _) = brick_runs(&cratered_terrain(3, 400));
    assert!(
        inside >= 300,
        "only {inside} runs ended inside their brick cell"
    );
    let (inside, at_surface) = brick_runs(&cratered_terrain_with(3, 400, 0));
    assert!(
        inside >= 150,
        "only {inside} runs ended inside their brick cell"
    );
    assert!(
        at_surface * 10 >= inside * 3,
        "{at_surface} of {inside} runs that ended inside their brick reached its surface"
    );
}

/// Clear runs from random points of `terrain`'s brick cells along random directions, each
/// checked by dense sampling: how many ended inside their cell, and how many of those
/// ended within 0.05 units of where the field falls to within 0.05 of the threshold.
fn brick_runs(terrain: &craterfield::field2d::Terrain<craterfield::field2d::Graph>) -> (u32, u32) {
    use craterfield::field2d::CellState;
    let grid = terrain.grid();
    let bricks: Vec<usize> = (0..grid.cell_count())
        .filter(|&i| matches!(grid.cell(i).map(|c| c.state()), Some(CellState::Brick(_))))
        .collect();
    assert!(bricks.len() >= 20, "only {} brick cells", bricks.len());
    let (nx, size) = (grid.dims().0 as usize, grid.cell_size());
    let mut next = uniform_stream(0x0b1c_7e57);
    let (mut inside, mut at_surface) = (0u32, 0u32);
    for k in 0..6000 {
        let cell = bricks[(next() * bricks.len() as f32) as usize % bricks.len()];
        let corner = grid.origin() + Vec2::new((cell % nx) as f32, (cell / nx) as f32) * size;
        let p = corner + Vec2::new(next(), next()) * size;
        let dir = Vec2::from_angle(next() * std::f32::consts::TAU);
        let above = [1e-3, 0.25, 3.0][k % 3];
        if terrain.distance(p) < above {
            continue;
        }
        let run = terrain.clear_run(p, dir, above);
        let mut s = 0.0f32;
        loop {
            let d = terrain.distance(p + dir * s);
            assert!(
                d >= above,
                "run {run:?} from {p} along {dir} above {above}: the field is {d} at s = {s}"
            );
            // Past the cell the other proofs answer (`clear_runs_of_a_cratered_terrain_hold`).
            if s >= run.clear || grid.cell_index(p + dir * s) != Some(cell) {
                break;
            }
            s = (s + 0.01).min(run.clear);
        }
        if grid.cell_index(p + dir * (run.clear + 0.05)) == Some(cell) {
            inside += 1;
            let reached = (0..=10).any(|i| {
                let q = p + dir * (run.clear + 0.005 * i as f32);
                terrain.distance(q) < above + 0.05
            });
            at_surface += u32::from(reached);
        }
    }
    (inside, at_surface)
}

/// Counts the evaluations a march makes, and proves clear runs only when asked to.
struct Counting<'a, F> {
    field: &'a F,
    skips: bool,
    evaluations: std::cell::Cell<u64>,
}

impl<F: Sdf> Sdf for Counting<'_, F> {
    fn distance(&self, p: Vec2) -> f32 {
        self.evaluations.set(self.evaluations.get() + 1);
        self.field.distance(p)
    }
    fn sample(&self, p: Vec2) -> Sample {
        self.evaluations.set(self.evaluations.get() + 1);
        self.field.sample(p)
    }
    fn lipschitz(&self) -> f32 {
        self.field.lipschitz()
    }
    fn clear_run(&self, p: Vec2, dir: Vec2, above: f32) -> craterfield::field2d::ClearRun {
        if self.skips {
            self.field.clear_run(p, dir, above)
        } else {
            craterfield::field2d::ClearRun::NOTHING
        }
    }
}

/// Skipping the stretches the terrain proves clear gives the same answers (the same hit or
/// miss, the same crossing up to the hit tolerance) for rays and swept circles, with far
/// fewer field evaluations.
#[test]
fn skipping_clear_runs_keeps_every_answer_and_saves_evaluations() {
    let terrain = cratered_terrain(2, 400);
    let with = |skips| Counting {
        field: &terrain,
        skips,
        evaluations: std::cell::Cell::new(0),
    };
    let (plain, skipping) = (with(false), with(true));
    let mut next = uniform_stream(0x5eed_0017);
    let (mut compared, mut differ) = (0u32, 0u32);
    for k in 0..2000 {
        let origin = Vec2::new(-300.0 + next() * 1600.0, -300.0 + next() * 1100.0);
        let dir = Vec2::from_angle(next() * std::f32::consts::TAU);
        let length = 50.0 + next() * 2000.0;
        let (a, b) = if k % 4 == 3 {
            let radius = 1.0 + next() * 6.0;
            let to = origin + dir * length;
            let cast = |f: &Counting<_>| {
                sweep_circle(f, origin, to, radius, &OPTS)
                    .unwrap()
                    .map(|h| h.toi * length)
            };
            (cast(&plain), cast(&skipping))
        } else {
            let cast =
                |f: &Counting<_>| raycast(f, origin, dir, length, &OPTS).unwrap().map(|h| h.t);
            (cast(&plain), cast(&skipping))
        };
        compared += 1;
        let same = match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => (a - b).abs() < 0.05,
            _ => false,
        };
        differ += u32::from(!same);
    }
    // Grazing paths may meet a surface within the hit tolerance at a point one march
    // samples and the other steps over; nothing else may differ.
    assert!(
        differ * 200 <= compared,
        "{differ} of {compared} answers differ"
    );
    let (e0, e1) = (plain.evaluations.get(), skipping.evaluations.get());
    assert!(
        e1 * 10 < e0 * 6,
        "{e1} evaluations with skips, {e0} without"
    );
}
