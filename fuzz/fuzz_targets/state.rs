//! World-state messages, their checksum fixed: the terrain state restored on its own (past
//! the digest a mutation breaks, so the terrain's checks are reached), then the whole state
//! resynced into a world of the seeds' match. A refusal must leave everything unchanged;
//! whatever is accepted must answer queries and step.
#![no_main]

use craterfield::field2d::Sdf;
use craterfield::net::state::decode_state;
use craterfield::sim::{Input, Settings, World, buttons};
use craterfield_fuzz::{fix_crc, small_level};
use glam::Vec2;
use libfuzzer_sys::fuzz_target;

/// The settings of the committed seeds' match.
fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 1;
    s.dirt.cooldown_ticks = 1;
    s.vehicle.health = 1_000_000;
    s
}

fn probes(t: &impl Sdf) -> Vec<u32> {
    (0..32)
        .map(|i| t.distance(Vec2::new(i as f32 * 33.0, 100.0 + (i % 5) as f32 * 60.0)))
        .map(f32::to_bits)
        .collect()
}

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    fix_crc(&mut bytes);
    let Ok(state) = decode_state(&bytes) else {
        return;
    };
    let level = small_level();
    let Ok(mut terrain) = level.terrain() else {
        return;
    };
    let before = probes(&terrain);
    match terrain.restore_state(state.terrain()) {
        Ok(()) => {
            let _ = probes(&terrain);
            let _ = terrain.set_tick(terrain.tick().saturating_add(3));
        }
        Err(_) => assert!(probes(&terrain) == before),
    }
    let Ok(mut world) = World::new(&level, settings(), 2) else {
        return;
    };
    let hash = world.state_hash();
    match world.resync(&state) {
        Ok(()) => {
            let fire = Input {
                buttons: buttons::FIRE,
                ..Input::default()
            };
            for _ in 0..3 {
                let _ = world.step(&[fire, Input::default()]);
            }
        }
        Err(_) => assert_eq!(world.state_hash(), hash),
    }
});
