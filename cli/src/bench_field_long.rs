//! The long row of `craterfield bench field --peers`: one terrain takes a million explosions
//! of the same generator as the comparison (a match far longer than any game plays), one
//! per tick, timing every insert with its tick's end (bakes included), then single-point distances one at a time, and the process's memory.
//!
//! A million events fill the terrain's default `max_events` log exactly; a longer match
//! compacts its history on the insert that goes past it (see `Terrain::compact_history`).

use std::time::Instant;

use craterfield::field2d::Sdf;
use glam::Vec2;
use serde::Serialize;

use crate::field_scene;
use crate::tails::{Tails, nearest_rank};

/// Explosions of the long row.
pub(crate) const LONG_RUN: usize = 1_000_000;
const LONG_SEED: u64 = 0x10_0000_5eed;

/// Times of one kind (inserts in microseconds, queries in nanoseconds): how many, the
/// median and tails, and p99.9, from one sort.
#[derive(Serialize)]
pub(crate) struct Spread {
    count: usize,
    #[serde(flatten)]
    tails: Tails,
    p999: f64,
}

impl Spread {
    fn of(mut times: Vec<f64>) -> Spread {
        times.sort_by(f64::total_cmp);
        Spread {
            count: times.len(),
            tails: Tails::of_sorted(&times),
            p999: nearest_rank(&times, 0.999),
        }
    }
}

/// What the long row measured.
#[derive(Serialize)]
pub(crate) struct LongRun {
    explosions: usize,
    /// Microseconds per explosion of the insert, of its tick's end (the bakes), and of
    /// both, each with its mean.
    insert_us: Spread,
    tick_end_us: Spread,
    both_us: Spread,
    means_us: [f64; 3],
    total_s: f64,
    /// Events the terrain keeps (the rest were compacted away) of those it applied, bricks,
    /// and the most events a cell lists.
    events_kept: usize,
    events_applied: u64,
    bricks: usize,
    max_cell_events: usize,
    /// Per-query nanoseconds.
    distance_uniform: Spread,
    distance_near: Spread,
    /// The median cost of the two clock reads around each timed query, included in the
    /// query times above.
    clock_ns: f64,
    /// Resident memory of the whole process before the terrain was built and after, and
    /// its peak over the process's life (Linux only).
    rss_before_mib: Option<f64>,
    rss_after_mib: Option<f64>,
    peak_rss_mib: Option<f64>,
}

/// Runs the long row with `points` query points per set.
pub(crate) fn run(points: usize) -> Result<LongRun, String> {
    let blasts = field_scene::blasts(LONG_SEED, LONG_RUN);
    let rss_before = process_memory_mib("VmRSS:");
    let mut terrain = field_scene::terrain()?;
    let mut us = [(); 3].map(|()| Vec::with_capacity(LONG_RUN));
    let start = Instant::now();
    for (k, b) in blasts.iter().enumerate() {
        let (insert, tick_end) = crate::bench_field_peers::carve_timed(&mut terrain, b)
            .map_err(|e| format!("explosion {k} of the long row: {e}"))?;
        us[0].push(insert);
        us[1].push(tick_end);
        us[2].push(insert + tick_end);
    }
    let total_s = start.elapsed().as_secs_f64();
    drop(blasts);

    let uniform = field_scene::uniform_points(21, points);
    let near = field_scene::near_points(&terrain, 22, points);
    // Untimed: the first query of a cell builds its specialized tape.
    std::hint::black_box(uniform.iter().map(|&p| terrain.distance(p)).sum::<f32>());
    std::hint::black_box(near.iter().map(|&p| terrain.distance(p)).sum::<f32>());
    let stats = terrain.stats();
    Ok(LongRun {
        explosions: LONG_RUN,
        means_us: [0, 1, 2].map(|k| us[k].iter().sum::<f64>() / us[k].len().max(1) as f64),
        insert_us: Spread::of(std::mem::take(&mut us[0])),
        tick_end_us: Spread::of(std::mem::take(&mut us[1])),
        both_us: Spread::of(std::mem::take(&mut us[2])),
        total_s,
        events_kept: terrain.events().len(),
        events_applied: terrain.events_applied(),
        bricks: stats.bricks,
        max_cell_events: stats.max_cell_events,
        distance_uniform: Spread::of(each_timed(&uniform, |p| terrain.distance(p))),
        distance_near: Spread::of(each_timed(&near, |p| terrain.distance(p))),
        clock_ns: Tails::of(each_timed(&uniform, |p| p.x)).median,
        rss_before_mib: rss_before,
        rss_after_mib: process_memory_mib("VmRSS:"),
        peak_rss_mib: process_memory_mib("VmHWM:"),
    })
}

/// Nanoseconds of `f` at each point, timed one call at a time.
fn each_timed(points: &[Vec2], f: impl Fn(Vec2) -> f32) -> Vec<f64> {
    points
        .iter()
        .map(|&p| {
            let t = Instant::now();
            std::hint::black_box(f(std::hint::black_box(p)));
            t.elapsed().as_secs_f64() * 1e9
        })
        .collect()
}

/// A memory line (`VmRSS:`, `VmHWM:`) of `/proc/self/status` in MiB, where there is one.
fn process_memory_mib(key: &str) -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    let kib: f64 = line[key.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib / 1024.0)
}

fn mib(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.0} MiB"))
}

/// Prints the long row.
pub(crate) fn print(r: &LongRun) {
    println!(
        "long run: {} explosions (same generator, another seed) into one terrain, craterfield alone",
        r.explosions
    );
    println!(
        "{:<28} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "", "mean", "median", "p95", "p99", "p99.9", "max"
    );
    let rows = [
        ("insert us", &r.insert_us),
        ("tick end us", &r.tick_end_us),
        ("both us", &r.both_us),
    ];
    for ((name, t), mean) in rows.into_iter().zip(r.means_us) {
        println!(
            "{name:<28} {mean:>10.2} {:>10.2} {:>10.2} {:>10.2} {:>10.2} {:>10.1}",
            t.tails.median, t.tails.p95, t.tails.p99, t.p999, t.tails.max
        );
    }
    for (name, q) in [
        ("distance ns, uniform", &r.distance_uniform),
        ("distance ns, near", &r.distance_near),
    ] {
        println!(
            "{:<28} {:>10} {:>10.0} {:>10.0} {:>10.0} {:>10.0} {:>10.0}",
            format!("{name} ({})", q.count),
            "-",
            q.tails.median,
            q.tails.p95,
            q.tails.p99,
            q.p999,
            q.tails.max
        );
    }
    println!(
        "inserts took {:.1} s in all; the terrain keeps {} of the {} events it applied, {} bricks, at most {} events in a cell; query times include {:.0} ns of clock reads",
        r.total_s, r.events_kept, r.events_applied, r.bricks, r.max_cell_events, r.clock_ns
    );
    println!(
        "process memory: {} resident before the terrain, {} after, {} at peak",
        mib(r.rss_before_mib),
        mib(r.rss_after_mib),
        mib(r.peak_rss_mib)
    );
}
