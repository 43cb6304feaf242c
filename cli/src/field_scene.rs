//! The scene of `bench field --peers`: a 4096x1024 level a game might ship (a wavy ground,
//! three round islands, three floating boxes), a seeded barrage of explosions over it, and
//! the query points and rays, so that craterfield and the polygon peers get the same inputs.
//!
//! The solid set is the union of: below `ground(x)` (a height profile sampled every 4 units),
//! the discs of [`ISLANDS`] and the boxes of [`BOXES`]. 90% of the explosions fall near the
//! ground (`y = ground(x) + uniform(-120, 20)`), 10% around a random island; radii are
//! uniform in 20..60. A second barrage ([`swiss_blasts`]) lands anywhere inside the ground.

use std::collections::BTreeMap;

use craterfield::field2d::Node;
use craterfield::field2d::{Graph, Terrain, TerrainOptions};
use glam::Vec2;

use crate::rng::Rng;

/// The level's extent: `[0, WIDTH] x [0, HEIGHT]`.
pub(crate) const WIDTH: f32 = 4096.0;
/// See [`WIDTH`].
pub(crate) const HEIGHT: f32 = 1024.0;
/// Spacing of the ground's height samples.
pub(crate) const GROUND_STEP: f32 = 4.0;
/// Islands: centre and radius.
pub(crate) const ISLANDS: [(Vec2, f32); 3] = [
    (Vec2::new(600.0, 700.0), 80.0),
    (Vec2::new(1900.0, 820.0), 100.0),
    (Vec2::new(3300.0, 650.0), 70.0),
];
/// Floating boxes: centre and half size.
pub(crate) const BOXES: [(Vec2, Vec2); 3] = [
    (Vec2::new(1225.0, 590.0), Vec2::new(124.0, 29.0)),
    (Vec2::new(2700.0, 731.0), Vec2::new(99.0, 30.0)),
    (Vec2::new(3776.0, 910.0), Vec2::new(175.0, 29.0)),
];

/// The ground height at `x`.
pub(crate) fn ground(x: f32) -> f32 {
    300.0 + 80.0 * (x / 200.0).sin() + 30.0 * (x / 37.0).sin()
}

/// The ground's samples, `x = i * GROUND_STEP` for `i` in `0..=WIDTH / GROUND_STEP`.
pub(crate) fn ground_samples() -> Vec<Vec2> {
    let n = (WIDTH / GROUND_STEP) as usize;
    (0..=n)
        .map(|i| {
            let x = i as f32 * GROUND_STEP;
            Vec2::new(x, ground(x))
        })
        .collect()
}

/// The level as a craterfield terrain (default options), prepared as a game's level load
/// would prepare it ([`Terrain::prepare`]: every cell's tapes built now, not inside the
/// first tick that touches the cell).
pub(crate) fn terrain() -> Result<Terrain<Graph>, String> {
    let terrain = unprepared_terrain()?;
    terrain.prepare();
    Ok(terrain)
}

/// Milliseconds [`Terrain::prepare`] takes on a fresh terrain of the level, and the
/// cells it prepares.
pub(crate) fn prepare_ms() -> Result<(f64, usize), String> {
    let terrain = unprepared_terrain()?;
    let t = std::time::Instant::now();
    terrain.prepare();
    Ok((t.elapsed().as_secs_f64() * 1e3, terrain.grid().cell_count()))
}

fn unprepared_terrain() -> Result<Terrain<Graph>, String> {
    let mut parts = vec![Node::HeightProfile {
        x0: 0.0,
        dx: GROUND_STEP,
        heights: ground_samples().iter().map(|p| p.y).collect(),
    }];
    parts.extend(ISLANDS.iter().map(|&(c, r)| Node::Circle {
        center: c.into(),
        radius: r,
    }));
    parts.extend(BOXES.iter().map(|&(c, h)| Node::Box {
        center: c.into(),
        half_size: h.into(),
    }));
    let graph = Graph::compile(&Node::Union(parts), &BTreeMap::new()).map_err(|e| e.to_string())?;
    Terrain::new(
        graph,
        Vec2::ZERO,
        Vec2::new(WIDTH, HEIGHT),
        TerrainOptions::default(),
    )
    .map_err(|e| e.to_string())
}

/// One explosion of the barrage: a carved disc.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Blast {
    pub center: Vec2,
    pub radius: f32,
}

/// `count` explosions from `seed` (see the module doc), centres kept inside the level.
pub(crate) fn blasts(seed: u64, count: usize) -> Vec<Blast> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| {
            let radius = rng.range(20.0, 60.0);
            let center = if rng.unit() < 0.9 {
                let x = rng.range(0.0, WIDTH);
                Vec2::new(x, ground(x) + rng.range(-120.0, 20.0))
            } else {
                let (c, r) = ISLANDS[(rng.next_u64() % ISLANDS.len() as u64) as usize];
                let angle = rng.range(0.0, std::f32::consts::TAU);
                c + Vec2::from_angle(angle) * r * rng.range(0.5, 1.2)
            };
            Blast {
                center: center.clamp(Vec2::ZERO, Vec2::new(WIDTH, HEIGHT)),
                radius,
            }
        })
        .collect()
}

/// `count` explosions placed inside the ground ("swiss"): `x` uniform over the level, `y`
/// uniform between the bottom and the ground there, radii uniform in 20..60.
pub(crate) fn swiss_blasts(seed: u64, count: usize) -> Vec<Blast> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| {
            let radius = rng.range(20.0, 60.0);
            let x = rng.range(0.0, WIDTH);
            let y = rng.range(0.0, ground(x));
            Blast {
                center: Vec2::new(x, y),
                radius,
            }
        })
        .collect()
}

/// `count` points uniform in the level.
pub(crate) fn uniform_points(seed: u64, count: usize) -> Vec<Vec2> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| Vec2::new(rng.range(0.0, WIDTH), rng.range(0.0, HEIGHT)))
        .collect()
}

/// Up to `count` points within 16 units of the surface of `terrain` (the field's own
/// distance), drawn around the ground's band where craters are.
pub(crate) fn near_points(terrain: &Terrain<Graph>, seed: u64, count: usize) -> Vec<Vec2> {
    use craterfield::field2d::Sdf;
    let mut rng = Rng::new(seed);
    let mut out = Vec::with_capacity(count);
    for _ in 0..count * 100 {
        if out.len() == count {
            break;
        }
        let x = rng.range(0.0, WIDTH);
        let p = Vec2::new(x, ground(x) + rng.range(-200.0, 60.0));
        if terrain.distance(p).abs() < 16.0 {
            out.push(p);
        }
    }
    out
}

/// One ray: origin, unit direction and length.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Ray {
    pub origin: Vec2,
    pub dir: Vec2,
    pub length: f32,
}

/// `count` rays: origins uniform in the level, directions uniform in angle, length 2000.
pub(crate) fn rays(seed: u64, count: usize) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| Ray {
            origin: Vec2::new(rng.range(0.0, WIDTH), rng.range(0.0, HEIGHT)),
            dir: Vec2::from_angle(rng.range(0.0, std::f32::consts::TAU)),
            length: 2000.0,
        })
        .collect()
}
