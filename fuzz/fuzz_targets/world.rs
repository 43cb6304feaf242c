//! Sequences of `World` calls read from the input, across two worlds: new (fuzzed player
//! counts and settings), step with inputs, snapshot, restore (its own, the other world's,
//! old ones), detonate, apply events, add debris. Nothing may panic; a refused restore
//! changes nothing.
#![no_main]

use craterfield::field2d::Event;
use craterfield::sim::{Input, Settings, Snapshot, World};
use craterfield_fuzz::small_level;
use glam::Vec2;
use libfuzzer_sys::fuzz_target;

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> Option<u8> {
        let (&b, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(b)
    }
    fn f32(&mut self, scale: f32) -> Option<f32> {
        Some(f32::from(self.u8()?) / 255.0 * scale)
    }
}

fn settings(b: &mut Bytes<'_>) -> Option<Settings> {
    let mut s = Settings::default();
    s.gravity = i32::from(b.u8()?) * 256 * 4;
    s.shell.cooldown_ticks = u16::from(b.u8()?);
    s.max_bodies = u32::from(b.u8()?) * 4;
    s.rollback_ticks = u32::from(b.u8()?);
    Some(s)
}

fuzz_target!(|data: &[u8]| {
    let mut b = Bytes(data);
    let level = small_level();
    let mut worlds = Vec::new();
    for _ in 0..2 {
        let (Some(s), Some(p)) = (settings(&mut b), b.u8()) else {
            return;
        };
        match World::new(&level, s, usize::from(p % 6)) {
            Ok(w) => worlds.push(w),
            Err(_) => return,
        }
    }
    let mut snaps: Vec<Snapshot> = Vec::new();
    for _ in 0..400 {
        let Some(op) = b.u8() else {
            break;
        };
        let w = usize::from(op >> 7);
        match op % 8 {
            0..=2 => {
                let players = worlds[w].players();
                let mut row = Vec::new();
                for _ in 0..players {
                    let Some(bytes) = (0..6).map(|_| b.u8()).collect::<Option<Vec<u8>>>() else {
                        return;
                    };
                    row.push(
                        Input::from_bytes([
                            bytes[0], bytes[1], bytes[2], bytes[3], bytes[4], bytes[5],
                        ])
                        .sanitized(),
                    );
                }
                let _ = worlds[w].step(&row);
            }
            3 => snaps.push(worlds[w].snapshot()),
            4 => {
                let Some(k) = b.u8() else { return };
                if let Some(s) = snaps.get(usize::from(k) % snaps.len().max(1)) {
                    let before = (worlds[w].tick(), worlds[w].state_hash());
                    if worlds[w].restore(s).is_err() {
                        assert_eq!((worlds[w].tick(), worlds[w].state_hash()), before);
                    }
                }
            }
            5 => {
                let (Some(x), Some(y), Some(weapon)) = (b.f32(1100.0), b.f32(600.0), b.u8()) else {
                    return;
                };
                let _ = worlds[w].detonate(Vec2::new(x - 40.0, y - 40.0), weapon % 3);
            }
            6 => {
                let (Some(x), Some(y), Some(r)) = (b.f32(1024.0), b.f32(512.0), b.f32(600.0))
                else {
                    return;
                };
                if let Ok(e) = Event::carve(Vec2::new(x, y), r) {
                    let _ = worlds[w].apply_event(e.with_growth(u16::from(op)));
                }
            }
            _ => {
                let (Some(x), Some(y), Some(r)) = (b.f32(1024.0), b.f32(512.0), b.f32(40.0)) else {
                    return;
                };
                let _ = worlds[w].add_debris(Vec2::new(x, y), r);
            }
        }
        let _ = worlds[w].state_hash();
    }
});
