//! Cratered terrains for the renderer tests (native and in the browser): deterministic
//! explosions and fills dropped onto a level's surface, the same bits everywhere.

use craterfield::field2d::{Event, Graph, Level, Sdf, Terrain};
use glam::Vec2;

/// A level with a few hundred deterministic explosions and fills, so the grid has lists,
/// air and brick cells.
pub(crate) fn cratered(level: &Level, count: usize) -> Terrain<Graph> {
    let mut terrain = level.terrain().expect("terrain");
    crater(&mut terrain, level, count, 0x9e37_79b9_7f4a_7c15);
    terrain
}

/// Applies `count` deterministic explosions and fills (seeded by `seed`) to `terrain`.
pub(crate) fn crater(terrain: &mut Terrain<Graph>, level: &Level, count: usize, seed: u64) {
    let b = level.bounds();
    let mut state = seed;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let materials = level.materials().len().max(1) as u16;
    let mut applied = 0;
    let mut attempt = 0;
    while applied < count && attempt < count * 20 {
        attempt += 1;
        let x = b.min.x + next() * (b.max.x - b.min.x);
        let mut y = b.max.y;
        while y > b.min.y && terrain.distance(Vec2::new(x, y)) > 0.0 {
            y -= 8.0;
        }
        let r = 10.0 + next() * 40.0;
        let e = if attempt % 7 == 6 {
            Event::fill(
                Vec2::new(x, y + r * 0.5),
                r * 0.5,
                attempt as u16 % materials,
            )
        } else {
            Event::carve(Vec2::new(x, y), r)
        };
        if e.is_ok_and(|e| terrain.apply(e).is_ok()) {
            applied += 1;
        }
    }
}
