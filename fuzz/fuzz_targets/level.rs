//! Level files: parse, validate, compile; if the level loads, its evaluation cost is within
//! the budget, and its terrain is built and queried (distance, sample, raycast) at points
//! taken from the input's tail.
#![no_main]

use craterfield::field2d::query::{RayOptions, raycast};
use craterfield::field2d::{Level, MAX_EVAL_WORK, Sdf};
use glam::Vec2;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(level) = Level::from_ron(text) else {
        return;
    };
    // An accepted level is one whose every query costs at most the budget.
    let cost = level.graph().eval_cost();
    assert!(cost.work <= MAX_EVAL_WORK, "accepted at {cost:?}");
    let Ok(terrain) = level.terrain() else {
        return;
    };
    let b = level.bounds();
    let size = b.max - b.min;
    for (k, chunk) in data.chunks(2).take(16).enumerate() {
        let t = Vec2::new(
            f32::from(chunk[0]) / 255.0,
            f32::from(*chunk.last().unwrap_or(&0)) / 255.0,
        );
        let p = b.min + size * t;
        let _ = terrain.distance(p);
        let _ = terrain.sample(p);
        let angle = k as f32 * 0.7;
        let _ = raycast(
            &terrain,
            p,
            Vec2::new(angle.cos(), angle.sin()),
            size.max_element(),
            &RayOptions::default(),
        );
    }
});
