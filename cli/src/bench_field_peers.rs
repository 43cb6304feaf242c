//! `craterfield bench field --peers`: craterfield against the polygon terrain a game would
//! otherwise keep, on the same level, the same explosions, points and rays, in one run
//! (`field_scene` makes the inputs, `peers_field` the polygon side; feature `peers`).
//!
//! Inserts, one explosion per tick: the insert's time, its tick's end (where lists past
//! the cap bake) and both (median, p95, p99, max, total), on the barrage and on a second
//! one placed inside the ground, beside the polygon peers. Queries, one thread, at 0,
//! 1,000 and 10,000 explosions: single-point distance, distance + gradient and inside on
//! points uniform in the level and near the ground, batch distances, and raycasts, each
//! the median of several timed passes. Then
//! the long row (`bench_field_long`): a million explosions into one terrain.

use std::time::Instant;

use craterfield::field2d::query::{RayOptions, inside, raycast, sweep_circle};
use craterfield::field2d::{Event, Graph, Sdf, Terrain};
use glam::Vec2;
use serde::Serialize;

use crate::field_scene::{self, Blast};
use crate::peers_field::{EdgeGrid, ParryPolyline, PolygonTerrain};
use crate::tails::Tails;

/// Explosions after which the queries are timed.
const CHECKPOINTS: [usize; 3] = [0, 1_000, 10_000];
const EVENT_SEED: u64 = 0x5eed_f1e1d;
const SWISS_SEED: u64 = 0x5eed_5155;
/// Radius of the circles swept along the rays.
const SWEEP_RADIUS: f32 = 2.0;

/// Per-insert times of one implementation: microseconds, and the total in milliseconds.
#[derive(Serialize)]
pub(crate) struct Inserts {
    #[serde(flatten)]
    us: Tails,
    total_ms: f64,
}

impl Inserts {
    fn of(us: Vec<f64>) -> Inserts {
        Inserts {
            total_ms: us.iter().sum::<f64>() * 1e-3,
            us: Tails::of(us),
        }
    }
}

/// Millions of queries per second of one implementation at one checkpoint.
#[derive(Serialize, Default)]
pub(crate) struct Queries {
    explosions: usize,
    implementation: String,
    distance_uniform: Option<f64>,
    distance_near: Option<f64>,
    gradient_uniform: Option<f64>,
    gradient_near: Option<f64>,
    inside_uniform: Option<f64>,
    batch_distance_uniform: Option<f64>,
    raycast: Option<f64>,
    /// Circles of radius [`SWEEP_RADIUS`] swept along the same rays.
    sweep: Option<f64>,
}

/// The whole comparison.
#[derive(Serialize)]
pub(crate) struct Comparison {
    points: usize,
    rays: usize,
    /// Milliseconds a fresh terrain's [`Terrain::prepare`] took, and its cells (every
    /// terrain here is prepared before it is used, as at a level load).
    prepare_ms: (f64, usize),
    inserts: Vec<(String, Inserts)>,
    queries: Vec<Queries>,
    /// One terrain after a million explosions (`bench_field_long`).
    long_run: crate::bench_field_long::LongRun,
    /// Per checkpoint: the share of uniform points (more than one unit from craterfield's
    /// surface) where the polygon terrain's inside/outside disagrees with craterfield's.
    sign_mismatch: Vec<(usize, f64)>,
}

/// Million operations per second of `f` over `items` (the median pass, see [`PASSES`]).
fn mops<T>(items: &[T], mut f: impl FnMut(&T) -> f32) -> f64 {
    median_rate(items.len(), || {
        let mut acc = 0.0f32;
        for item in items {
            acc += f(item);
        }
        std::hint::black_box(acc);
    })
}

/// Timed passes over each query set; the table gives the median pass. A single pass
/// takes a few milliseconds, and on a shared machine one burst of other work during it
/// moved a figure by a third between runs.
const PASSES: usize = 5;

/// Millions of items per second of the median of [`PASSES`] runs of `pass` over `n` items.
fn median_rate(n: usize, mut pass: impl FnMut()) -> f64 {
    let mut rates: Vec<f64> = (0..PASSES)
        .map(|_| {
            let t = Instant::now();
            pass();
            n as f64 / t.elapsed().as_secs_f64() * 1e-6
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates[PASSES / 2]
}

/// One explosion in its own tick, as a game's world applies it: the insert, then the
/// tick's end, where lists past the cap are baked (`TerrainOptions::bake_rows_per_tick`
/// lattice rows). Returns both times, microseconds.
pub(crate) fn carve_timed(terrain: &mut Terrain<Graph>, b: &Blast) -> Result<(f64, f64), String> {
    let event = Event::carve(b.center, b.radius).map_err(|e| e.to_string())?;
    let t = Instant::now();
    terrain.apply(event).map_err(|e| e.to_string())?;
    let insert = t.elapsed().as_secs_f64() * 1e6;
    let next = terrain.tick() + 1;
    let t = Instant::now();
    terrain.set_tick(next).map_err(|e| e.to_string())?;
    Ok((insert, t.elapsed().as_secs_f64() * 1e6))
}

/// The insert rows of one barrage: craterfield's inserts, its tick ends, both per
/// explosion, and the chunked polygon peer (and the whole-level one, when asked).
fn insert_rows(
    label: &str,
    blasts: &[Blast],
    whole_too: bool,
) -> Result<Vec<(String, Inserts)>, String> {
    let mut terrain = field_scene::terrain()?;
    let mut chunked = PolygonTerrain::new(true);
    let (mut insert, mut tick_end, mut both, mut chunk_us) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for b in blasts {
        let (i, e) = carve_timed(&mut terrain, b)?;
        insert.push(i);
        tick_end.push(e);
        both.push(i + e);
        let t = Instant::now();
        chunked.carve(b.center, b.radius);
        chunk_us.push(t.elapsed().as_secs_f64() * 1e6);
    }
    let mut rows = vec![
        (format!("{label}craterfield insert"), Inserts::of(insert)),
        (
            format!("{label}craterfield tick end"),
            Inserts::of(tick_end),
        ),
        (format!("{label}craterfield both"), Inserts::of(both)),
        (
            format!("{label}i_overlay, 256-unit chunks"),
            Inserts::of(chunk_us),
        ),
    ];
    if whole_too {
        let mut whole = PolygonTerrain::new(false);
        let mut us = Vec::new();
        for b in blasts {
            let t = Instant::now();
            whole.carve(b.center, b.radius);
            us.push(t.elapsed().as_secs_f64() * 1e6);
        }
        rows.push((format!("{label}i_overlay, whole level"), Inserts::of(us)));
    }
    Ok(rows)
}

struct Inputs {
    uniform: Vec<Vec2>,
    /// Points near the surface at the checkpoint being timed.
    near: Vec<Vec2>,
    rays: Vec<field_scene::Ray>,
}

fn craterfield_queries(
    terrain: &Terrain<Graph>,
    explosions: usize,
    inputs: &Inputs,
) -> Result<Queries, String> {
    let opts = RayOptions::default();
    let mut out = vec![0.0f32; inputs.uniform.len()];
    // Untimed: the first query of a cell builds its specialized tape.
    terrain
        .distances(&inputs.uniform, &mut out)
        .map_err(|e| e.to_string())?;
    let mut failed = None;
    let batch = median_rate(inputs.uniform.len(), || {
        if let Err(e) = terrain.distances(&inputs.uniform, &mut out) {
            failed = Some(e.to_string());
        }
    });
    if let Some(e) = failed {
        return Err(e);
    }
    Ok(Queries {
        explosions,
        implementation: "craterfield".into(),
        distance_uniform: Some(mops(&inputs.uniform, |&p| terrain.distance(p))),
        distance_near: Some(mops(&inputs.near, |&p| terrain.distance(p))),
        gradient_uniform: Some(mops(&inputs.uniform, |&p| terrain.sample(p).gradient.x)),
        gradient_near: Some(mops(&inputs.near, |&p| terrain.sample(p).gradient.x)),
        inside_uniform: Some(mops(&inputs.uniform, |&p| {
            f32::from(u8::from(inside(terrain, p).unwrap_or(false)))
        })),
        batch_distance_uniform: Some(batch),
        raycast: Some(mops(&inputs.rays, |r| {
            raycast(terrain, r.origin, r.dir, r.length, &opts)
                .ok()
                .flatten()
                .map_or(0.0, |h| h.t)
        })),
        sweep: Some(mops(&inputs.rays, |r| {
            let to = r.origin + r.dir * r.length;
            sweep_circle(terrain, r.origin, to, SWEEP_RADIUS, &opts)
                .ok()
                .flatten()
                .map_or(0.0, |h| h.toi)
        })),
    })
}

/// The share of `points` more than one unit from `terrain`'s surface where `grid` puts the
/// other side: checks that both sides hold the same terrain.
fn sign_mismatch(terrain: &Terrain<Graph>, grid: &EdgeGrid, points: &[Vec2]) -> f64 {
    let (mut compared, mut differ) = (0usize, 0usize);
    for &p in points {
        let d = terrain.distance(p);
        if d.abs() > 1.0 {
            compared += 1;
            differ += usize::from((d < 0.0) != (grid.distance(p) < 0.0));
        }
    }
    differ as f64 / compared.max(1) as f64
}

fn peer_queries(
    terrain: &Terrain<Graph>,
    polygons: &PolygonTerrain,
    explosions: usize,
    inputs: &Inputs,
    mismatches: &mut Vec<(usize, f64)>,
) -> [Queries; 2] {
    let edges = polygons.edges();
    let grid = EdgeGrid::new(edges.clone());
    let parry = ParryPolyline::new(&edges);
    mismatches.push((explosions, sign_mismatch(terrain, &grid, &inputs.uniform)));
    [
        Queries {
            explosions,
            implementation: "edge grid".into(),
            distance_uniform: Some(mops(&inputs.uniform, |&p| grid.distance(p))),
            distance_near: Some(mops(&inputs.near, |&p| grid.distance(p))),
            gradient_uniform: Some(mops(&inputs.uniform, |&p| grid.sample(p).1.x)),
            gradient_near: Some(mops(&inputs.near, |&p| grid.sample(p).1.x)),
            inside_uniform: Some(mops(&inputs.uniform, |&p| {
                f32::from(u8::from(grid.distance(p) < 0.0))
            })),
            ..Queries::default()
        },
        Queries {
            explosions,
            implementation: "parry2d Polyline".into(),
            distance_uniform: Some(mops(&inputs.uniform, |&p| parry.distance(p))),
            distance_near: Some(mops(&inputs.near, |&p| parry.distance(p))),
            raycast: Some(mops(&inputs.rays, |r| {
                parry.raycast(r.origin, r.dir, r.length).unwrap_or(0.0)
            })),
            sweep: Some(mops(&inputs.rays, |r| {
                parry
                    .sweep(r.origin, r.dir, r.length, SWEEP_RADIUS)
                    .unwrap_or(0.0)
            })),
            ..Queries::default()
        },
    ]
}

/// Runs the comparison with `points` query points and `rays` rays per checkpoint.
pub(crate) fn compare(points: usize, rays: usize) -> Result<Comparison, String> {
    let blasts = field_scene::blasts(EVENT_SEED, *CHECKPOINTS.last().unwrap_or(&0));
    let mut terrain = field_scene::terrain()?;
    let mut inputs = Inputs {
        uniform: field_scene::uniform_points(11, points),
        near: Vec::new(),
        rays: field_scene::rays(13, rays),
    };
    let mut whole = PolygonTerrain::new(false);
    let mut queries = Vec::new();
    let mut mismatches = Vec::new();
    for (k, b) in blasts.iter().enumerate() {
        if CHECKPOINTS.contains(&k) {
            eprintln!("  queries after {k} explosions");
            inputs.near = field_scene::near_points(&terrain, 12, points);
            queries.push(craterfield_queries(&terrain, k, &inputs)?);
            queries.extend(peer_queries(&terrain, &whole, k, &inputs, &mut mismatches));
        }
        carve_timed(&mut terrain, b)?;
        whole.carve(b.center, b.radius);
    }
    let last = blasts.len();
    eprintln!("  queries after {last} explosions");
    inputs.near = field_scene::near_points(&terrain, 12, points);
    queries.push(craterfield_queries(&terrain, last, &inputs)?);
    queries.extend(peer_queries(
        &terrain,
        &whole,
        last,
        &inputs,
        &mut mismatches,
    ));
    // The timed inserts, each barrage on fresh terrains, with the queries' memory given
    // back first; then the long row.
    drop((terrain, whole));
    eprintln!("  inserts");
    let mut inserts = insert_rows("", &blasts, true)?;
    let swiss = field_scene::swiss_blasts(SWISS_SEED, blasts.len());
    inserts.extend(insert_rows("swiss: ", &swiss, false)?);
    eprintln!(
        "  long run: {} explosions",
        crate::bench_field_long::LONG_RUN
    );
    let long_run = crate::bench_field_long::run(points)?;
    Ok(Comparison {
        points,
        rays,
        prepare_ms: field_scene::prepare_ms()?,
        inserts,
        queries,
        long_run,
        sign_mismatch: mismatches,
    })
}

fn cell(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.2}"))
}

/// Prints the comparison as tables.
pub(crate) fn print(c: &Comparison) {
    println!(
        "bench field --peers: 4096x1024 level, {} explosions (r 20..60), one thread; polygon peers on the same inputs",
        CHECKPOINTS.last().unwrap_or(&0)
    );
    println!(
        "{:<36} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "inserts (one explosion per tick)", "median us", "p95 us", "p99 us", "max us", "total ms"
    );
    for (name, i) in &c.inserts {
        println!(
            "{name:<36} {:>10.2} {:>10.2} {:>10.2} {:>10.1} {:>10.1}",
            i.us.median, i.us.p95, i.us.p99, i.us.max, i.total_ms
        );
    }
    println!(
        "(tick end: the tick's bake work on lists past the cap, {} lattice rows of a brick's 33 (TerrainOptions::bake_rows_per_tick); both: insert + tick end; swiss: the explosions placed anywhere inside the ground)",
        craterfield::field2d::TerrainOptions::default().bake_rows_per_tick
    );
    println!(
        "(every terrain prepared at load: Terrain::prepare built the {} cells' tapes in {:.1} ms)",
        c.prepare_ms.1, c.prepare_ms.0
    );
    println!(
        "queries, M/s, the median of {PASSES} timed passes ({} points uniform in the level or within 16 units of the surface, {} rays of length 2000, and circles of radius 2 swept along them)",
        c.points, c.rays
    );
    println!(
        "{:>10} {:<18} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "explosions",
        "implementation",
        "dist uni",
        "dist near",
        "grad uni",
        "grad near",
        "inside",
        "batch",
        "raycast",
        "sweep r2"
    );
    for q in &c.queries {
        println!(
            "{:>10} {:<18} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
            q.explosions,
            q.implementation,
            cell(q.distance_uniform),
            cell(q.distance_near),
            cell(q.gradient_uniform),
            cell(q.gradient_near),
            cell(q.inside_uniform),
            cell(q.batch_distance_uniform),
            cell(q.raycast),
            cell(q.sweep)
        );
    }
    println!(
        "parry2d's distance is unsigned (a polyline has no inside); the edge grid clamps at 64 units, craterfield at its band (32)"
    );
    for (explosions, share) in &c.sign_mismatch {
        println!(
            "same terrain on both sides after {explosions} explosions: inside/outside differs at {:.3}% of the uniform points more than 1 unit from the surface (32-gon explosions, 1/16-unit coordinates)",
            share * 100.0
        );
    }
    crate::bench_field_long::print(&c.long_run);
}
