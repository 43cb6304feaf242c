//! `craterfield bench sim`: release-mode cost of the simulation on the default level after
//! 10,000 explosions, measured in this run on one thread:
//!
//! - milliseconds per tick with 100, 1,000 and 10,000 bodies (four scripted players who
//!   drive and fire, the rest debris dropped into the air above the terrain);
//! - snapshot and restore times (the restore goes back 8 ticks, as a rollback session
//!   typically does) in a world of 1,000 bodies, medians over many repetitions;
//! - replay bytes per minute of a scripted four-player match;
//! - wire bytes per terrain event, for the events that match produced;
//! - with `--peers` (feature `peers`), rapier2d beside the world on the same bodies and
//!   terrain (`peers_sim`), both idle players and no explosions, same ticks, same run.

use std::process::ExitCode;
use std::time::Instant;

use craterfield::field2d::Level;
use craterfield::field2d::Sdf;
use craterfield::field2d::{Event, EventKind};
use craterfield::net::wire::bytes_per_event;
use craterfield::net::{DecodeLimits, encode_events_with_limits};
use craterfield::sim::{EVENT_CENTER_STEP, Input, Settings, World};
use glam::Vec2;
use serde::Serialize;

use crate::barrage;
use crate::rng::Rng;
use crate::script::{self, Script};
use crate::tails::Tails;

/// Players in every measured world.
const PLAYERS: u8 = 4;
/// How far back a restore goes.
const ROLLBACK_DISTANCE: u32 = 8;
/// Fewest match events for the match to be the wire figure's source.
const MIN_MATCH_EVENTS: usize = 100;

/// What to measure (the command's arguments).
#[derive(clap::Args)]
pub(crate) struct Options {
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Body counts of the rows (vehicles included), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "100,1000,10000")]
    pub bodies: Vec<usize>,
    /// Timed ticks per row.
    #[arg(long, default_value_t = 120)]
    pub ticks: u32,
    /// Untimed ticks before the timed ones.
    #[arg(long, default_value_t = 60)]
    pub warmup: u32,
    /// Explosions applied to the terrain first.
    #[arg(long, default_value_t = 10_000)]
    pub explosions: usize,
    /// Bodies in the snapshot and restore world.
    #[arg(long, default_value_t = 1000)]
    pub snapshot_bodies: usize,
    /// Snapshot and restore repetitions (medians are reported).
    #[arg(long, default_value_t = 300)]
    pub reps: usize,
    /// Length in seconds of the scripted match measured for replay and wire sizes.
    #[arg(long, default_value_t = 60)]
    pub match_seconds: u32,
    /// Also step rapier2d on the same bodies and terrain (needs the feature `peers`).
    #[arg(long)]
    pub peers: bool,
    /// Bodies of the `--peers` comparison.
    #[arg(long, default_value_t = 1000)]
    pub peer_bodies: usize,
}

#[derive(Serialize)]
struct Row {
    bodies: usize,
    /// Mean over the timed ticks.
    ms_per_tick: f64,
    ms_per_tick_median: f64,
    ms_per_tick_p95: f64,
    ms_per_tick_p99: f64,
    ms_per_tick_max: f64,
    /// Bodies alive after the timed ticks.
    bodies_at_end: usize,
}

#[derive(Serialize)]
struct Report {
    rows: Vec<Row>,
    snapshot_ms: f64,
    restore_ms: f64,
    replay_bytes_per_min: f64,
    bytes_per_event: f64,
    /// Which events `bytes_per_event` encodes.
    bytes_per_event_source: String,
    /// The barrage's events with sim-like shapes (the weapons' radii, no rim) and centres
    /// snapped to 1/4 unit, in one message.
    barrage_bytes_per_event: f64,
    explosions: usize,
    /// The field evaluator backend the world uses.
    backend: String,
    threads: usize,
    ticks: u32,
    warmup: u32,
    snapshot_bodies: usize,
    restore_distance_ticks: u32,
    reps: usize,
    match_seconds: f64,
    match_replay_bytes: usize,
    match_events: usize,
    release: bool,
    /// `--peers`: rapier2d on the same bodies and terrain.
    #[cfg(feature = "peers")]
    peers: Option<PhysicsComparison>,
}

/// `bench sim --peers`: the world and rapier2d stepping the same bodies on the same
/// terrain, idle players, no explosions, the same ticks; milliseconds per tick.
#[cfg(feature = "peers")]
#[derive(Serialize)]
struct PhysicsComparison {
    bodies: usize,
    craterfield: Tails,
    craterfield_mean: f64,
    rapier2d: Tails,
    rapier2d_mean: f64,
    /// Polyline edges of rapier2d's terrain.
    rapier2d_segments: usize,
    /// Contour spacing the polylines were extracted at, world units.
    contour_spacing: f32,
    /// Bodies rapier2d had put to sleep after the timed ticks.
    rapier2d_sleeping: usize,
    /// Bodies in play at the end (both remove those that fell out of the world).
    craterfield_in_play: usize,
    rapier2d_in_play: usize,
    /// Of the balls in play at the end, those whose centre is deeper in the terrain than
    /// their radius: each side's, as a check that both simulated the same scene.
    craterfield_sunk: usize,
    rapier2d_sunk: usize,
}

pub(crate) fn sim(opts: Options) -> Result<ExitCode, String> {
    if opts.peers && !cfg!(feature = "peers") {
        return Err("--peers needs rapier2d: build with `--features peers`".into());
    }
    let level = Level::default_level();
    let largest = opts.bodies.iter().copied().max().unwrap_or(0);
    let mut settings = Settings::default();
    settings.max_bodies = settings
        .max_bodies
        .max((largest.max(opts.snapshot_bodies) + 1000).min(1_000_000) as u32);
    let ticks = opts.ticks.max(1);
    let reps = opts.reps.max(1);

    let base = barrage_world(&level, settings, opts.explosions)?;

    let mut rows = Vec::new();
    for &n in &opts.bodies {
        let mut world = populated(&base, n, 11 + n as u64)?;
        let mut script = Script::new(5, usize::from(PLAYERS));
        for _ in 0..opts.warmup {
            step(&mut world, &mut script)?;
        }
        let mut times = Vec::with_capacity(ticks as usize);
        for _ in 0..ticks {
            let row = script.next_row(&world);
            let t = Instant::now();
            world.step(&row).map_err(|e| e.to_string())?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let tails = Tails::of(times.clone());
        rows.push(Row {
            bodies: n,
            ms_per_tick: times.iter().sum::<f64>() / times.len() as f64,
            ms_per_tick_median: tails.median,
            ms_per_tick_p95: tails.p95,
            ms_per_tick_p99: tails.p99,
            ms_per_tick_max: tails.max,
            bodies_at_end: world.bodies().len(),
        });
    }

    let (snapshot_ms, restore_ms) = snapshot_restore(&base, &opts, reps)?;

    let match_ticks = opts.match_seconds.max(1) * u32::from(settings.tick_hz);
    let played = script::play(&level, Settings::default(), PLAYERS, match_ticks, 77, 60)?;
    let replay_bytes = played.replay.encode().map_err(|e| e.to_string())?.len();
    let match_seconds = f64::from(match_ticks) / f64::from(settings.tick_hz);
    let match_events = played.events().to_vec();

    let barrage_events = sim_like(base.terrain().events(), &settings);
    // One message of every event, to measure the format (a real stream sends small batches).
    let unbounded = DecodeLimits {
        max_batch_events: u32::MAX,
        ..DecodeLimits::default()
    };
    let encode_events = |events: &[_]| encode_events_with_limits(events, &unbounded);
    let barrage_message = encode_events(&barrage_events).map_err(|e| e.to_string())?;
    let barrage_bpe = bytes_per_event(&barrage_message, barrage_events.len());
    let (bytes_per_event_, source) = if match_events.len() >= MIN_MATCH_EVENTS {
        let message = encode_events(&match_events).map_err(|e| e.to_string())?;
        (
            bytes_per_event(&message, match_events.len()),
            format!(
                "the {} events of the scripted {match_seconds:.0} s match, one message",
                match_events.len()
            ),
        )
    } else {
        (
            barrage_bpe,
            format!(
                "the {} barrage events with the weapons' shapes, centres snapped to 1/4 unit, one message (the match made only {})",
                barrage_events.len(),
                match_events.len()
            ),
        )
    };

    let report = Report {
        rows,
        snapshot_ms,
        restore_ms,
        replay_bytes_per_min: replay_bytes as f64 * 60.0 / match_seconds,
        bytes_per_event: bytes_per_event_,
        bytes_per_event_source: source,
        barrage_bytes_per_event: barrage_bpe,
        explosions: base.terrain().events_applied() as usize,
        backend: base.terrain().backend().to_string(),
        threads: 1,
        ticks,
        warmup: opts.warmup,
        snapshot_bodies: opts.snapshot_bodies,
        restore_distance_ticks: ROLLBACK_DISTANCE,
        reps,
        match_seconds,
        match_replay_bytes: replay_bytes,
        match_events: match_events.len(),
        release: !cfg!(debug_assertions),
        #[cfg(feature = "peers")]
        peers: if opts.peers {
            Some(physics_peers(&base, &opts)?)
        } else {
            None
        },
    };
    if opts.json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        print_table(&report);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(r: &Report) {
    println!(
        "craterfield bench sim: default level after {} explosions, {} players firing, one thread, {} backend{}",
        r.explosions,
        PLAYERS,
        r.backend,
        if r.release {
            ""
        } else {
            " (debug build: not representative)"
        }
    );
    println!(
        "{:>8} {:>10} {:>10} {:>10} {:>10} {:>10} {:>8}",
        "bodies", "ms/tick", "median", "p95", "p99", "max", "at end"
    );
    for row in &r.rows {
        println!(
            "{:>8} {:>10.3} {:>10.3} {:>10.3} {:>10.3} {:>10.3} {:>8}",
            row.bodies,
            row.ms_per_tick,
            row.ms_per_tick_median,
            row.ms_per_tick_p95,
            row.ms_per_tick_p99,
            row.ms_per_tick_max,
            row.bodies_at_end
        );
    }
    println!(
        "({} timed ticks per row after {} warm-up ticks; bodies = 4 vehicles + debris + projectiles in flight)",
        r.ticks, r.warmup
    );
    if let Some(row) = r.rows.iter().find(|row| row.bodies == 1000) {
        println!(
            "target 1,000 bodies under 1 ms per tick on one core: {} ({:.3} ms)",
            if row.ms_per_tick < 1.0 {
                "met"
            } else {
                "NOT met"
            },
            row.ms_per_tick
        );
    }
    println!(
        "snapshot {:.4} ms, restore {:.4} ms ({} bodies, restoring the snapshot of {} ticks earlier; medians of {})",
        r.snapshot_ms, r.restore_ms, r.snapshot_bodies, r.restore_distance_ticks, r.reps
    );
    println!(
        "replay: {:.0} bytes per minute ({} bytes for a scripted {:.0} s match of {} players)",
        r.replay_bytes_per_min, r.match_replay_bytes, r.match_seconds, PLAYERS
    );
    println!(
        "wire: {:.2} bytes per event ({}); target <= 8: {}",
        r.bytes_per_event,
        r.bytes_per_event_source,
        if r.bytes_per_event <= 8.0 {
            "met"
        } else {
            "NOT met"
        }
    );
    println!(
        "wire: {:.2} bytes per event for the barrage's events with the weapons' shapes, centres snapped to 1/4 unit",
        r.barrage_bytes_per_event
    );
    #[cfg(feature = "peers")]
    if let Some(c) = &r.peers {
        print_peers(c, r.ticks, r.warmup);
    }
}

#[cfg(feature = "peers")]
fn print_peers(c: &PhysicsComparison, ticks: u32, warmup: u32) {
    println!();
    println!(
        "physics peers: the same {} bodies on the same terrain, idle players, no explosions, {ticks} timed ticks after {warmup}, one thread",
        c.bodies
    );
    println!(
        "{:<44} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "ms per tick", "mean", "median", "p95", "p99", "max"
    );
    let row = |name: &str, mean: f64, t: &Tails| {
        println!(
            "{name:<44} {mean:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3}",
            t.median, t.p95, t.p99, t.max
        );
    };
    row(
        "craterfield World::step",
        c.craterfield_mean,
        &c.craterfield,
    );
    row(
        &format!("rapier2d 0.36 ({} polyline edges)", c.rapier2d_segments),
        c.rapier2d_mean,
        &c.rapier2d,
    );
    println!(
        "(rapier2d: terrain from extract_contours at {} units; {} of {} bodies asleep at the end; median ratio craterfield/rapier2d {:.2})",
        c.contour_spacing,
        c.rapier2d_sleeping,
        c.bodies,
        c.craterfield.median / c.rapier2d.median
    );
    println!(
        "bodies in play at the end: craterfield {}, rapier2d {}; balls sunk into the terrain: craterfield {}, rapier2d {}",
        c.craterfield_in_play, c.rapier2d_in_play, c.craterfield_sunk, c.rapier2d_sunk
    );
}

/// The world and rapier2d from the same populated world, each stepped `warmup` untimed
/// and `ticks` timed ticks with idle players.
#[cfg(feature = "peers")]
fn physics_peers(base: &World, opts: &Options) -> Result<PhysicsComparison, String> {
    use crate::peers_sim::{CONTOUR, RapierPeer};
    let mut world = populated(base, opts.peer_bodies, 31)?;
    let mut peer = RapierPeer::new(&world)?;
    let idle = vec![Input::default(); usize::from(PLAYERS)];
    let ticks = opts.ticks.max(1);
    let mut ours = Vec::with_capacity(ticks as usize);
    for i in 0..opts.warmup + ticks {
        let t = Instant::now();
        world.step(&idle).map_err(|e| e.to_string())?;
        if i >= opts.warmup {
            ours.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    let mut theirs = Vec::with_capacity(ticks as usize);
    for i in 0..opts.warmup + ticks {
        let t = Instant::now();
        peer.step();
        if i >= opts.warmup {
            theirs.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    let sunk = |discs: &[(Vec2, f32)]| {
        discs
            .iter()
            .filter(|&&(at, r)| !(at.is_finite() && base.terrain().distance(at) >= -r))
            .count()
    };
    let ours_discs: Vec<(Vec2, f32)> = world
        .bodies()
        .iter()
        .filter(|b| b.half_length == 0.0)
        .map(|b| (b.pos, b.radius))
        .collect();
    let theirs_discs = peer.discs();
    Ok(PhysicsComparison {
        craterfield_sunk: sunk(&ours_discs),
        rapier2d_sunk: sunk(&theirs_discs),
        craterfield_in_play: world.bodies().len(),
        rapier2d_in_play: peer.bodies_in_play(),
        bodies: peer.bodies,
        craterfield_mean: mean(&ours),
        craterfield: Tails::of(ours),
        rapier2d_mean: mean(&theirs),
        rapier2d: Tails::of(theirs),
        rapier2d_segments: peer.segments,
        contour_spacing: CONTOUR.spacing,
        rapier2d_sleeping: peer.sleeping(),
    })
}

#[cfg(feature = "peers")]
fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// A world of four players on the default level with `count` barrage explosions applied
/// through the world (so its event journal and hash include them), all at tick 0; then
/// stepped idle past the rollback window, so the vehicles have landed and the undo
/// journal of the setup is dropped before anything is timed.
fn barrage_world(level: &Level, settings: Settings, count: usize) -> Result<World, String> {
    let mut world = World::new(level, settings, usize::from(PLAYERS)).map_err(|e| e.to_string())?;
    world.set_threads(1);
    let mut rng = Rng::new(2024);
    let mut applied = 0;
    let mut tries = 0;
    while applied < count {
        tries += 1;
        if tries > count * 4 + 1000 {
            return Err(format!(
                "could not place {count} explosions (placed {applied})"
            ));
        }
        let Some(event) = barrage::next_event(level, world.terrain(), &mut rng, 0) else {
            continue;
        };
        if world.apply_event(event).is_ok() {
            applied += 1;
        }
    }
    let idle = vec![Input::default(); usize::from(PLAYERS)];
    for _ in 0..=settings.rollback_ticks {
        world.step(&idle).map_err(|e| e.to_string())?;
    }
    Ok(world)
}

/// A copy of `base` with debris added until it holds `bodies` bodies: discs of radius 2
/// to 5 at random points of the world that are in the air (clear of the terrain).
fn populated(base: &World, bodies: usize, seed: u64) -> Result<World, String> {
    let mut world = base.clone();
    let (lo, hi) = world.terrain().bounds();
    let mut rng = Rng::new(seed);
    let mut tries = 0usize;
    while world.bodies().len() < bodies {
        tries += 1;
        if tries > bodies * 100 + 1000 {
            return Err(format!(
                "could not place {bodies} bodies in the air (placed {})",
                world.bodies().len()
            ));
        }
        let radius = rng.range(2.0, 5.0);
        let at = Vec2::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y));
        if world.terrain().distance(at) > radius + 1.0 {
            world.add_debris(at, radius).map_err(|e| e.to_string())?;
        }
    }
    Ok(world)
}

fn step(world: &mut World, script: &mut Script) -> Result<(), String> {
    let row = script.next_row(world);
    world.step(&row).map_err(|e| e.to_string())
}

/// Median snapshot time, and median time to restore the snapshot of
/// [`ROLLBACK_DISTANCE`] ticks earlier, in milliseconds.
fn snapshot_restore(base: &World, opts: &Options, reps: usize) -> Result<(f64, f64), String> {
    let mut world = populated(base, opts.snapshot_bodies, 99)?;
    let mut script = Script::new(6, usize::from(PLAYERS));
    for _ in 0..opts.warmup {
        step(&mut world, &mut script)?;
    }
    let mut snaps = Vec::with_capacity(reps);
    let mut restores = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t = Instant::now();
        let snapshot = world.snapshot();
        snaps.push(t.elapsed().as_secs_f64() * 1e3);
        for _ in 0..ROLLBACK_DISTANCE {
            step(&mut world, &mut script)?;
        }
        let t = Instant::now();
        world.restore(&snapshot).map_err(|e| e.to_string())?;
        restores.push(t.elapsed().as_secs_f64() * 1e3);
        // Move on a tick, so the next repetition rolls back over different ticks.
        step(&mut world, &mut script)?;
    }
    Ok((median(&mut snaps), median(&mut restores)))
}

/// The events as the simulation would have made them: the weapons' radii and materials,
/// no rim or growth, centres snapped to [`EVENT_CENTER_STEP`], one event per tick.
fn sim_like(events: &[Event], settings: &Settings) -> Vec<Event> {
    let snap =
        |v: i32| (v + EVENT_CENTER_STEP / 2).div_euclid(EVENT_CENTER_STEP) * EVENT_CENTER_STEP;
    events
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let w = match e.kind {
                EventKind::Carve => &settings.shell,
                EventKind::Fill => &settings.dirt,
            };
            Event {
                kind: e.kind,
                center: e.center.map(snap),
                radius: w.crater_radius,
                rim: 0,
                grow_ticks: 0,
                tick: i as u32 + 1,
                material: if w.fills { w.material } else { 0 },
            }
        })
        .collect()
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}
