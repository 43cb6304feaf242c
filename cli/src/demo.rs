//! `craterfield demo`: the default level under a scripted barrage, rendered on the CPU
//! (full-resolution exact field) with a JSON summary of what happened and how fast; then a
//! scripted four-player match on the pristine level, recorded as a replay and pictured at
//! its last tick.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use craterfield::field2d::terrain::Terrain;
use craterfield::field2d::{Level, Sdf};
use craterfield::net::DecodeLimits;
use craterfield::render2d::RenderOptions;
use craterfield::render2d::overlay::draw_markers;
use glam::Vec2;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use crate::barrage::{self, BarrageStats};
use crate::rng::Rng;
use crate::{frame, render_frame, script};

/// Seed of the demo's barrage (`craterfield render --seed` takes it as 12648430).
const DEMO_SEED: u64 = 0xc0ffee;

/// Players of the demo match.
const MATCH_PLAYERS: u8 = 4;
/// Ticks between two state hashes stored in the demo match's replay.
const MATCH_HASH_INTERVAL: u32 = 60;
/// Seed of the demo match's scripted players.
const MATCH_SEED: u64 = 0x006d_6174_6368;

#[derive(Serialize)]
struct Summary {
    level: String,
    events: EventSummary,
    timings: Timings,
    field: FieldStats,
    image: ImageInfo,
    /// The scripted match (absent when it was skipped).
    #[serde(rename = "match", skip_serializing_if = "Option::is_none")]
    match_: Option<MatchSummary>,
}

#[derive(Serialize)]
struct MatchSummary {
    players: u8,
    ticks: u32,
    seconds: f64,
    shots: usize,
    explosions: usize,
    replay_bytes: usize,
    replay_bytes_per_min: f64,
    hashes: usize,
    /// The state hash after the last tick, as hex.
    final_hash: String,
    bodies_left: usize,
    vehicles_left: usize,
    simulate_ms: f64,
    replay: String,
    image: ImageInfo,
}

#[derive(Serialize)]
struct EventSummary {
    requested: usize,
    applied: usize,
    #[serde(flatten)]
    barrage: BarrageStats,
}

#[derive(Serialize)]
struct Timings {
    barrage_ms: f64,
    insert_us_mean: f64,
    distance_ns: f64,
    sample_ns: f64,
    raycast_us: f64,
    render_ms: f64,
}

#[derive(Serialize)]
struct FieldStats {
    solid_fraction: f64,
    lipschitz: f32,
    /// Work units of one evaluation of the level's tape, and its instructions
    /// (`Graph::eval_cost`; levels past `MAX_EVAL_WORK` are refused at load).
    eval_work: u64,
    tape_instructions: usize,
    grid_cells: usize,
    max_events_in_a_cell: usize,
    bricks: usize,
    air_cells: usize,
    solid_cells: usize,
}

#[derive(Serialize)]
struct ImageInfo {
    path: String,
    width: u32,
    height: u32,
    /// Which renderer drew it (GPU pipeline or its CPU twin).
    renderer: String,
}

pub(crate) fn run(
    out: &Path,
    events: usize,
    width: u32,
    level: Option<&Path>,
    match_ticks: u32,
) -> Result<ExitCode, String> {
    // The match is recorded as a replay, which must stay readable: refused before any work.
    let max_ticks = DecodeLimits::default().max_ticks;
    if match_ticks > max_ticks {
        return Err(format!(
            "--match-ticks {match_ticks}: a replay holds at most {max_ticks} ticks (4 hours at 60 Hz)"
        ));
    }
    if events > MAX_BARRAGE {
        return Err(format!(
            "--events {events}: the barrage takes at most {MAX_BARRAGE} events"
        ));
    }
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let level = match level {
        Some(path) => Level::load(path).map_err(|e| e.to_string())?,
        None => Level::default_level(),
    };
    let mut terrain = level.terrain().map_err(|e| e.to_string())?;

    let bar = ProgressBar::new(events as u64).with_style(
        ProgressStyle::with_template("{msg:>10} [{bar:40}] {pos}/{len}")
            .map_err(|e| e.to_string())?
            .progress_chars("=> "),
    );
    bar.set_message("barrage");
    let t = Instant::now();
    // `craterfield render --events N --seed 12648430` draws this terrain again.
    let stats = barrage::fire_seeded(&level, &mut terrain, events, DEMO_SEED, |n| {
        bar.inc(n as u64)
    });
    let barrage_ms = t.elapsed().as_secs_f64() * 1e3;
    bar.finish_and_clear();
    let applied = terrain.events_applied() as usize;

    let timings_q = time_queries(&terrain, &level);
    bar.set_message("render");
    let camera = frame::camera(&level, width)?;
    let palette: Vec<[u8; 3]> = level.materials().iter().map(|m| m.color).collect();
    let t = Instant::now();
    let drawn = render_frame::render(&terrain, &palette, &camera, &RenderOptions::default())?;
    let mut img = drawn.image;
    let render_ms = t.elapsed().as_secs_f64() * 1e3;
    let spawns: Vec<Vec2> = level.spawns().collect();
    draw_markers(&mut img, &camera, &spawns, 10.0, [250, 240, 90]);
    let png = out.join("terrain.png");
    img.save(&png)
        .map_err(|e| format!("cannot write {}: {e}", png.display()))?;

    bar.set_message("match");
    let (match_summary, match_note) = match play_match(&level, out, width, match_ticks)? {
        Ok(Some(m)) => (Some(m), None),
        Ok(None) => (None, Some("skipped (--match-ticks 0)".to_string())),
        Err(why) => (None, Some(format!("skipped: {why}"))),
    };
    bar.finish_and_clear();

    let grid = terrain.stats();
    let summary = Summary {
        level: level.name().to_string(),
        events: EventSummary {
            requested: events,
            applied,
            barrage: stats,
        },
        timings: Timings {
            barrage_ms,
            insert_us_mean: barrage_ms * 1e3 / applied.max(1) as f64,
            distance_ns: timings_q.0,
            sample_ns: timings_q.1,
            raycast_us: timings_q.2,
            render_ms,
        },
        field: FieldStats {
            solid_fraction: solid_fraction(&terrain, &level),
            lipschitz: terrain.lipschitz(),
            eval_work: level.graph().eval_cost().work,
            tape_instructions: level.graph().eval_cost().instructions,
            grid_cells: grid.cells,
            max_events_in_a_cell: grid.max_cell_events,
            bricks: grid.bricks,
            air_cells: grid.air_cells,
            solid_cells: grid.solid_cells,
        },
        image: ImageInfo {
            path: png.display().to_string(),
            width: camera.width,
            height: camera.height,
            renderer: drawn.renderer.clone(),
        },
        match_: match_summary,
    };
    let json = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    let json_path = out.join("summary.json");
    std::fs::write(&json_path, json + "\n")
        .map_err(|e| format!("cannot write {}: {e}", json_path.display()))?;

    println!(
        "craterfield demo: level \"{}\" (cost {} work units per evaluation, {} tape instructions; limit {})",
        summary.level,
        summary.field.eval_work,
        summary.field.tape_instructions,
        craterfield::field2d::MAX_EVAL_WORK
    );
    println!(
        "  {} events applied ({} craters, {} fills; {} shells missed, {} rejected) in {:.0} ms",
        applied, stats.carves, stats.fills, stats.misses, stats.rejected, barrage_ms
    );
    println!(
        "  queries: distance {:.0} ns, distance+gradient {:.0} ns, raycast {:.1} us",
        summary.timings.distance_ns, summary.timings.sample_ns, summary.timings.raycast_us
    );
    println!(
        "  grid: {} cells, at most {} events in a cell, {} baked bricks; solid fraction {:.3}",
        grid.cells, grid.max_cell_events, grid.bricks, summary.field.solid_fraction
    );
    println!(
        "  wrote {} ({}x{}, rendered in {:.0} ms by the {}) and {}",
        png.display(),
        camera.width,
        camera.height,
        render_ms,
        drawn.renderer,
        json_path.display()
    );
    match (&summary.match_, match_note) {
        (Some(m), _) => println!(
            "  match: {} players, {} ticks ({:.1} s), {} shots, {} explosions, replay {} bytes ({:.0} bytes/minute), final hash {}; wrote {} and {}",
            m.players,
            m.ticks,
            m.seconds,
            m.shots,
            m.explosions,
            m.replay_bytes,
            m.replay_bytes_per_min,
            m.final_hash,
            m.replay,
            m.image.path
        ),
        (None, note) => println!("  match: {}", note.unwrap_or_default()),
    }
    Ok(ExitCode::SUCCESS)
}

/// Most events `--events` asks for (a terrain's default event budget).
const MAX_BARRAGE: usize = 1_000_000;

/// Plays, records and pictures the scripted match. `Ok(Err(..))`: the match could not be
/// played (a level without spawn points, say); `Err`: the files could not be written.
fn play_match(
    level: &Level,
    out: &Path,
    width: u32,
    ticks: u32,
) -> Result<Result<Option<MatchSummary>, String>, String> {
    if ticks == 0 {
        return Ok(Ok(None));
    }
    let settings = craterfield::sim::Settings::default();
    let t = Instant::now();
    let played = match script::play(
        level,
        settings,
        MATCH_PLAYERS,
        ticks,
        MATCH_SEED,
        MATCH_HASH_INTERVAL,
    ) {
        Ok(p) => p,
        Err(why) => return Ok(Err(why)),
    };
    let simulate_ms = t.elapsed().as_secs_f64() * 1e3;
    let bytes = played.replay.encode().map_err(|e| e.to_string())?;
    let replay_path = out.join("match.replay");
    std::fs::write(&replay_path, &bytes)
        .map_err(|e| format!("cannot write {}: {e}", replay_path.display()))?;
    let img = frame::render(level, &played.world, width)?;
    let png = out.join("match.png");
    img.save(&png)
        .map_err(|e| format!("cannot write {}: {e}", png.display()))?;
    let seconds = f64::from(ticks) / f64::from(settings.tick_hz);
    let (vehicles_left, _, _) = frame::census(&played.world);
    Ok(Ok(Some(MatchSummary {
        players: MATCH_PLAYERS,
        ticks: played.replay.ticks(),
        seconds,
        shots: played.shots,
        explosions: played.events().len(),
        replay_bytes: bytes.len(),
        replay_bytes_per_min: bytes.len() as f64 * 60.0 / seconds,
        hashes: played.replay.hashes.len(),
        final_hash: format!("{:#018x}", played.world.state_hash()),
        bodies_left: played.world.bodies().len(),
        vehicles_left,
        simulate_ms,
        replay: replay_path.display().to_string(),
        image: ImageInfo {
            path: png.display().to_string(),
            width: img.width(),
            height: img.height(),
            renderer: "CPU exact renderer (match picture with bodies)".to_string(),
        },
    })))
}

/// Mean nanoseconds per distance and per distance+gradient query, and microseconds per
/// raycast, over random points of the world.
fn time_queries(terrain: &Terrain<craterfield::field2d::Graph>, level: &Level) -> (f64, f64, f64) {
    let b = level.bounds();
    let mut rng = Rng::new(7);
    let points: Vec<Vec2> = (0..100_000)
        .map(|_| Vec2::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y)))
        .collect();
    let t = Instant::now();
    let acc: f32 = points.iter().map(|&p| terrain.distance(p)).sum();
    let distance_ns = t.elapsed().as_secs_f64() * 1e9 / points.len() as f64;
    let t = Instant::now();
    let acc2: f32 = points.iter().map(|&p| terrain.sample(p).gradient.x).sum();
    let sample_ns = t.elapsed().as_secs_f64() * 1e9 / points.len() as f64;
    std::hint::black_box((acc, acc2));
    let rays = 2_000;
    let t = Instant::now();
    let mut hits = 0;
    for &origin in &points[..rays] {
        let dir = Vec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let opts = craterfield::field2d::query::RayOptions::default();
        if let Ok(Some(_)) =
            craterfield::field2d::query::raycast(terrain, origin, dir, 2000.0, &opts)
        {
            hits += 1;
        }
    }
    std::hint::black_box(hits);
    let raycast_us = t.elapsed().as_secs_f64() * 1e6 / rays as f64;
    (distance_ns, sample_ns, raycast_us)
}

/// Fraction of the world rectangle that is solid, on a 256 x 128 sample lattice.
fn solid_fraction(terrain: &Terrain<craterfield::field2d::Graph>, level: &Level) -> f64 {
    let b = level.bounds();
    let (nx, ny) = (256, 128);
    let mut solid = 0usize;
    for j in 0..ny {
        for i in 0..nx {
            let p = b.min
                + (b.max - b.min)
                    * Vec2::new((i as f32 + 0.5) / nx as f32, (j as f32 + 0.5) / ny as f32);
            if terrain.distance(p) < 0.0 {
                solid += 1;
            }
        }
    }
    solid as f64 / (nx * ny) as f64
}
