//! `craterfield bench field`: release-mode throughput of single-point queries (the terrain's
//! `Sdf` interface: the scalar backend on the query's cell tape, then the cell's events) on
//! the default level with 0, 1,000 and 10,000 explosions, measured in this run.

use std::collections::BTreeMap;
use std::process::ExitCode;
use std::time::Instant;

use craterfield::field2d::query::{RayOptions, raycast};
use craterfield::field2d::terrain::Terrain;
use craterfield::field2d::{Graph, Level, Sdf};
use glam::Vec2;
use serde::Serialize;

use crate::barrage;
use crate::rng::Rng;

const EVENT_COUNTS: [usize; 3] = [0, 1_000, 10_000];

#[derive(Serialize)]
struct Report {
    /// Distance + gradient queries per second (one thread).
    queries_per_s: BTreeMap<String, f64>,
    /// Raycasts per second (one thread).
    raycasts_per_s: BTreeMap<String, f64>,
    /// Median time of one explosion insert while building the 10,000-event terrain.
    insert_us_median: f64,
    /// Distance-only queries per second.
    distance_queries_per_s: BTreeMap<String, f64>,
    /// Most events any grid cell holds (the per-query cost bound).
    max_cell_events: BTreeMap<String, usize>,
    /// Cells baked into bricks because they went over the cap.
    bricks: BTreeMap<String, usize>,
    points: usize,
    rays: usize,
    /// `--peers`: craterfield against polygon terrain on a game-like level.
    #[cfg(feature = "peers")]
    #[serde(skip_serializing_if = "Option::is_none")]
    peers: Option<crate::bench_field_peers::Comparison>,
}

pub(crate) fn field(json: bool, points: usize, peers: bool) -> Result<ExitCode, String> {
    if peers && !cfg!(feature = "peers") {
        return Err("--peers needs the polygon peers: build with `--features peers`".into());
    }
    let level = Level::default_level();
    let points = points.clamp(1_000, 50_000_000);
    let rays = (points / 20).max(100);
    let mut report = Report {
        queries_per_s: BTreeMap::new(),
        raycasts_per_s: BTreeMap::new(),
        insert_us_median: 0.0,
        distance_queries_per_s: BTreeMap::new(),
        max_cell_events: BTreeMap::new(),
        bricks: BTreeMap::new(),
        points,
        rays,
        #[cfg(feature = "peers")]
        peers: None,
    };
    let b = level.bounds();
    let mut rng = Rng::new(99);
    let query_points: Vec<Vec2> = (0..points)
        .map(|_| Vec2::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y)))
        .collect();
    let ray_dirs: Vec<Vec2> = (0..rays)
        .map(|_| Vec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 0.3)))
        .collect();

    for &count in &EVENT_COUNTS {
        let (terrain, insert_us) = build(&level, count)?;
        if count == 10_000 {
            report.insert_us_median = median(insert_us);
        }
        let key = count.to_string();
        let stats = terrain.stats();
        report
            .max_cell_events
            .insert(key.clone(), stats.max_cell_events);
        report.bricks.insert(key.clone(), stats.bricks);

        let t = Instant::now();
        let mut acc = 0.0f32;
        for &p in &query_points {
            acc += terrain.sample(p).gradient.y;
        }
        report
            .queries_per_s
            .insert(key.clone(), points as f64 / t.elapsed().as_secs_f64());

        let t = Instant::now();
        for &p in &query_points {
            acc += terrain.distance(p);
        }
        report
            .distance_queries_per_s
            .insert(key.clone(), points as f64 / t.elapsed().as_secs_f64());
        std::hint::black_box(acc);

        let opts = RayOptions::default();
        let t = Instant::now();
        let mut hits = 0usize;
        for (p, d) in query_points.iter().zip(&ray_dirs) {
            if let Ok(Some(_)) = raycast(&terrain, *p, *d, 4000.0, &opts) {
                hits += 1;
            }
        }
        report
            .raycasts_per_s
            .insert(key, rays as f64 / t.elapsed().as_secs_f64());
        std::hint::black_box(hits);
    }

    #[cfg(feature = "peers")]
    if peers {
        report.peers = Some(crate::bench_field_peers::compare(points, rays)?);
    }
    if json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        println!(
            "craterfield bench field: default level, single-point queries (cell tapes, scalar), one thread"
        );
        println!(
            "{:>10} {:>16} {:>16} {:>14} {:>10} {:>7}",
            "explosions", "dist+grad q/s", "distance q/s", "raycasts/s", "max/cell", "bricks"
        );
        for &count in &EVENT_COUNTS {
            let k = count.to_string();
            println!(
                "{:>10} {:>16.0} {:>16.0} {:>14.0} {:>10} {:>7}",
                count,
                report.queries_per_s[&k],
                report.distance_queries_per_s[&k],
                report.raycasts_per_s[&k],
                report.max_cell_events[&k],
                report.bricks[&k]
            );
        }
        println!(
            "explosion insert, median while building 10,000: {:.2} us",
            report.insert_us_median
        );
        #[cfg(feature = "peers")]
        if let Some(c) = &report.peers {
            println!();
            crate::bench_field_peers::print(c);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The default level with `count` barrage events; returns the per-insert times (us).
pub(crate) fn build(level: &Level, count: usize) -> Result<(Terrain<Graph>, Vec<f64>), String> {
    let mut terrain = level.terrain().map_err(|e| e.to_string())?;
    let mut rng = Rng::new(2024);
    let mut times = Vec::with_capacity(count);
    let mut tick = 0u32;
    while times.len() < count {
        tick += 1;
        terrain.set_tick(tick).map_err(|e| e.to_string())?;
        let Some(event) = barrage::next_event(level, &terrain, &mut rng, tick) else {
            continue;
        };
        let t = Instant::now();
        let applied = terrain.apply(event).is_ok();
        let us = t.elapsed().as_secs_f64() * 1e6;
        if applied {
            times.push(us);
        }
        if tick as usize > count * 4 + 1000 {
            return Err(format!(
                "could not place {count} explosions (placed {})",
                times.len()
            ));
        }
    }
    Ok((terrain, times))
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}
