//! Scripted, deterministic barrages of explosions and fills: shells fall from the sky along
//! slightly slanted paths, and each lands where a raycast meets the terrain.

use craterfield::field2d::Event;
use craterfield::field2d::query::{RayOptions, raycast};
use craterfield::field2d::terrain::Terrain;
use craterfield::field2d::{Graph, Level};
use glam::Vec2;

use crate::rng::Rng;

/// What a barrage did.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub(crate) struct BarrageStats {
    pub carves: usize,
    pub fills: usize,
    pub misses: usize,
    pub rejected: usize,
}

/// The `i`-th event of the barrage with seed `seed`, aimed by a raycast into `terrain`.
pub(crate) fn next_event(
    level: &Level,
    terrain: &Terrain<Graph>,
    rng: &mut Rng,
    tick: u32,
) -> Option<Event> {
    let b = level.bounds();
    let x = rng.range(b.min.x, b.max.x);
    let slant = rng.range(-0.35, 0.35);
    let origin = Vec2::new(x, b.max.y - 1.0);
    let dir = Vec2::new(slant, -1.0);
    let roll = rng.unit();
    let hit = raycast(
        terrain,
        origin,
        dir,
        (b.max.y - b.min.y) * 1.5,
        &RayOptions::default(),
    )
    .ok()
    .flatten()?;
    let fill_material = (level.materials().len() - 1) as u16;
    let event = if roll < 0.02 {
        Event::carve(hit.point, rng.range(40.0, 64.0))
            .and_then(|e| e.with_rim(rng.range(6.0, 16.0)))
    } else if roll < 0.82 {
        let e = Event::carve(hit.point, rng.range(5.0, 20.0));
        if rng.unit() < 0.3 {
            e.and_then(|e| e.with_rim(rng.range(2.0, 10.0)))
        } else {
            e
        }
    } else {
        // Dirt shells pile up where they land.
        let r = rng.range(6.0, 16.0);
        Event::fill(hit.point + hit.normal * (r * 0.4), r, fill_material)
    };
    event.ok().map(|e| e.at_tick(tick))
}

/// Shells per seed of [`fire_seeded`]: each run of this many takes the next seed.
const SHELLS_PER_SEED: usize = 100;

/// Ticks [`fire_seeded`] lets pass after the last shell: every growing blast at full size.
const SETTLE_TICKS: u32 = 120;

/// The barrage `craterfield render --events N --seed S` fires, and the demo and
/// `bench render2d` with their own seeds: `count` shells in runs of 100 seeded `seed`,
/// `seed + 1`, ..., then 120 ticks for the blasts to settle. `progress` hears how many
/// shells each run fired.
pub(crate) fn fire_seeded(
    level: &Level,
    terrain: &mut Terrain<Graph>,
    count: usize,
    seed: u64,
    mut progress: impl FnMut(usize),
) -> BarrageStats {
    let mut stats = BarrageStats::default();
    for run in 0..count.div_ceil(SHELLS_PER_SEED) {
        let n = (count - run * SHELLS_PER_SEED).min(SHELLS_PER_SEED);
        let s = fire(level, terrain, n, seed.wrapping_add(run as u64));
        stats.carves += s.carves;
        stats.fills += s.fills;
        stats.misses += s.misses;
        stats.rejected += s.rejected;
        progress(n);
    }
    // Moving the tick forwards never fails (only a rebuild can).
    let _ = terrain.set_tick(terrain.tick().saturating_add(SETTLE_TICKS));
    stats
}

/// Fire `count` shells into `terrain`, one per tick from its current tick on (each aimed at
/// the terrain as it is then).
pub(crate) fn fire(
    level: &Level,
    terrain: &mut Terrain<Graph>,
    count: usize,
    seed: u64,
) -> BarrageStats {
    let mut rng = Rng::new(seed);
    let mut stats = BarrageStats::default();
    for _ in 0..count {
        let tick = terrain.tick().saturating_add(1);
        let _ = terrain.set_tick(tick); // forwards: never fails
        let Some(event) = next_event(level, terrain, &mut rng, tick) else {
            stats.misses += 1;
            continue;
        };
        let is_fill = matches!(event.kind, craterfield::field2d::EventKind::Fill);
        match terrain.apply(event) {
            Ok(()) if is_fill => stats.fills += 1,
            Ok(()) => stats.carves += 1,
            Err(_) => stats.rejected += 1,
        }
    }
    stats
}
