//! Golden hashes: the default level after a fixed sequence of 10,000 events, sampled at a
//! fixed 1,000,000-point lattice, hashes to pinned values on every backend and on every
//! platform (the test suite runs on x86_64 and, cross-compiled, on aarch64 under qemu).
//! A change of these values is a change of the simulation's bits: it breaks replays and
//! network play between versions, so it must be deliberate.

#[macro_use]
mod common;

// In a browser the same tests run under wasm-bindgen-test (`scripts/test`'s web leg), so
// the pinned bits are checked on wasm32 too.
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use common::Rng;
use craterfield::backend::Backend;
use craterfield::field2d::{Event, EventKind, Level, Sample, Sdf, Terrain};
use glam::Vec2;

/// Hash of distance, gradient and material of every sample.
const GOLDEN_SAMPLES: u64 = 0x2e5d_2964_37f7_69b9;
/// Hash of the distance-only batch path.
const GOLDEN_DISTANCES: u64 = 0xc4b6_66da_82ba_7acd;

/// The fixed event sequence, in fixed point (no float enters it).
fn events() -> Vec<Event> {
    let mut r = Rng(0xc4a7_e4f1_e1d0_0001);
    (0..10_000u32)
        .map(|i| {
            let fill = i % 6 == 5;
            Event {
                kind: if fill {
                    EventKind::Fill
                } else {
                    EventKind::Carve
                },
                center: [
                    (r.below(3840 * 256) as i32),
                    150 * 256 + (r.below(1150 * 256) as i32),
                ],
                radius: 2 * 256 + (r.below(58 * 256) as i32),
                rim: if i % 4 == 0 {
                    r.below(10 * 256) as i32
                } else {
                    0
                },
                grow_ticks: if i % 13 == 0 { 8 } else { 0 },
                tick: i / 50,
                material: if fill { (i % 5) as u16 } else { 0 },
            }
        })
        .collect()
}

fn terrain() -> Terrain<craterfield::field2d::Graph> {
    let mut t = Level::default_level().terrain().unwrap();
    for e in events() {
        // The terrain follows the events' ticks, as a game's world does: each advance bakes
        // some of the lists that went past the cap.
        t.set_tick(e.tick).unwrap();
        t.apply(e).unwrap();
    }
    // Long enough after the last event for every list past the cap to have baked.
    t.set_tick(10_000 / 50 + 400).unwrap();
    t
}

/// 1250 x 800 points over the level and its margins.
fn lattice() -> Vec<Vec2> {
    let mut pts = Vec::with_capacity(1_000_000);
    for j in 0..800 {
        for i in 0..1250 {
            pts.push(Vec2::new(
                -200.0 + i as f32 * (4240.0 / 1250.0) + 0.37,
                -200.0 + j as f32 * (2000.0 / 800.0) + 0.11,
            ));
        }
    }
    pts
}

/// FNV-1a over little-endian bytes.
fn fnv(words: impl Iterator<Item = u32>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for w in words {
        for b in w.to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

fn hash_samples(s: &[Sample]) -> u64 {
    fnv(s.iter().flat_map(|s| {
        [
            s.distance.to_bits(),
            s.gradient.x.to_bits(),
            s.gradient.y.to_bits(),
            u32::from(s.material),
        ]
    }))
}

#[test]
fn default_level_after_10k_events_hashes_to_the_golden_values() {
    let mut t = terrain();
    let stats = t.stats();
    assert!(stats.bricks > 0 && stats.max_cell_events <= 48, "{stats:?}");
    let pts = lattice();
    let mut reference: Option<Vec<Sample>> = None;
    for b in Backend::available() {
        t.set_backend(b).unwrap();
        let mut s = vec![
            Sample {
                distance: 0.0,
                gradient: Vec2::ZERO,
                material: 0
            };
            pts.len()
        ];
        t.samples(&pts, &mut s).unwrap();
        let mut d = vec![0.0; pts.len()];
        t.distances(&pts, &mut d).unwrap();
        let (hs, hd) = (hash_samples(&s), fnv(d.iter().map(|v| v.to_bits())));
        say!("{b}: samples {hs:#018x} distances {hd:#018x}");
        assert_eq!(hs, GOLDEN_SAMPLES, "{b}: sample hash {hs:#018x}");
        assert_eq!(hd, GOLDEN_DISTANCES, "{b}: distance hash {hd:#018x}");
        if reference.is_none() {
            // The single-point path agrees with the batches.
            for k in (0..pts.len()).step_by(101) {
                let one = t.sample(pts[k]);
                assert_eq!(
                    one.distance.to_bits(),
                    s[k].distance.to_bits(),
                    "at {}",
                    pts[k]
                );
                assert_eq!(one.gradient.x.to_bits(), s[k].gradient.x.to_bits());
                assert_eq!(one.gradient.y.to_bits(), s[k].gradient.y.to_bits());
                assert_eq!(one.material, s[k].material);
                assert_eq!(t.distance(pts[k]).to_bits(), d[k].to_bits());
            }
            reference = Some(s);
        }
    }
}
