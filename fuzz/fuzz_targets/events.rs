//! Wire messages, their checksum fixed: event batches applied one by one to a terrain
//! (a rejected event must leave it unchanged), and terrain snapshots.
#![no_main]

use craterfield::field2d::Sdf;
use craterfield::net::wire::{TerrainSnapshot, decode_events};
use craterfield_fuzz::{fix_crc, small_level};
use glam::Vec2;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    fix_crc(&mut bytes);
    let _ = TerrainSnapshot::decode(&bytes);
    let Ok(events) = decode_events(&bytes) else {
        return;
    };
    let level = small_level();
    let Ok(mut terrain) = level.terrain() else {
        return;
    };
    let probe = Vec2::new(300.0, 250.0);
    for e in events.into_iter().take(2_000) {
        let before = (terrain.events().len(), terrain.distance(probe).to_bits());
        if terrain.apply(e).is_err() {
            assert_eq!(
                (terrain.events().len(), terrain.distance(probe).to_bits()),
                before
            );
        }
    }
    for x in 0..8 {
        let _ = terrain.sample(Vec2::new(x as f32 * 128.0, 200.0));
    }
});
