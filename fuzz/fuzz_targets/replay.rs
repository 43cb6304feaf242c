//! Replay files, their checksum fixed so mutations reach the decoder: decode, then
//! re-simulate on a small level with a tick budget (replays of other levels stop at the
//! level check, so the level hash is set to the small level's half of the time).
#![no_main]

use craterfield::net::{Replay, verify};
use craterfield::sim::level_hash;
use craterfield_fuzz::{fix_crc, small_level};
use libfuzzer_sys::fuzz_target;

/// Ticks simulated at most per input (the decoder bounds the file; this bounds the time).
const MAX_TICKS: u32 = 240;

fuzz_target!(|data: &[u8]| {
    let mut bytes = data.to_vec();
    fix_crc(&mut bytes);
    let Ok(mut replay) = Replay::decode(&bytes) else {
        return;
    };
    if replay.ticks() > MAX_TICKS {
        return;
    }
    let level = small_level();
    if data.len() % 2 == 0 {
        replay.level_hash = level_hash(&level);
    }
    let _ = verify(&replay, &level);
    // What decodes encodes again, to the same replay.
    if let Ok(again) = replay.encode() {
        assert_eq!(Replay::decode(&again).ok().as_ref(), Some(&replay));
    }
});
