//! Whole-world state messages: a peer that diverged resyncs from another's state and then
//! steps to the same bits; states of other matches, altered states and oversized messages
//! are refused with nothing changed; no mutated message panics.

mod common;
use common::{Rng, scripted_input};

use craterfield::field2d::{Level, Sdf};
use craterfield::net::state::{
    decode_state, decode_state_with_limits, encode_state, encode_state_with_limits,
};
use craterfield::net::{DecodeErrorKind, DecodeLimits, crc32};
use craterfield::sim::{Input, Settings, SimError, World};
use glam::Vec2;

const PLAYERS: usize = 3;

fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 3;
    s.dirt.cooldown_ticks = 4;
    s.vehicle.health = 1_000_000;
    s
}

fn world() -> World {
    World::new(&Level::default_level(), settings(), PLAYERS).unwrap()
}

fn inputs(seed: u64, tick: u32) -> Vec<Input> {
    (0..PLAYERS)
        .map(|p| scripted_input(seed, p, tick))
        .collect()
}

fn play(w: &mut World, seed: u64, ticks: u32) {
    for _ in 0..ticks {
        let t = w.tick();
        w.step(&inputs(seed, t)).unwrap();
    }
}

/// The terrain's distances on a lattice over the level, as bits.
fn field_bits(w: &World) -> Vec<u32> {
    let b = Level::default_level().bounds();
    let mut out = Vec::new();
    for j in 0..40 {
        for i in 0..120 {
            let p = Vec2::new(
                b.min.x + (b.max.x - b.min.x) * (i as f32 + 0.37) / 120.0,
                b.min.y + (b.max.y - b.min.y) * (j as f32 + 0.61) / 40.0,
            );
            out.push(w.terrain().distance(p).to_bits());
        }
    }
    out
}

fn fix_crc(bytes: &mut [u8]) {
    if bytes.len() >= 4 {
        let n = bytes.len() - 4;
        let c = crc32(&bytes[..n]);
        bytes[n..].copy_from_slice(&c.to_le_bytes());
    }
}

#[test]
fn a_diverged_world_resyncs_and_then_steps_to_the_same_bits() {
    let mut a = world();
    let mut b = world();
    play(&mut a, 1, 600);
    // `b` saw other inputs: another history, other craters, other bodies.
    play(&mut b, 2, 600);
    assert_ne!(a.state_hash(), b.state_hash());
    assert!(a.terrain().stats().bakes > 0, "bricks travel too");
    let stale = b.snapshot();

    let bytes = encode_state(&a.state()).unwrap();
    let state = decode_state(&bytes).unwrap();
    let taken = a.state();
    assert!(state == taken, "the message round-trips");
    assert_eq!(state.state_hash(), a.state_hash());
    b.resync(&state).unwrap();
    assert_eq!(b.state_hash(), a.state_hash());
    assert!(
        field_bits(&b) == field_bits(&a),
        "the same terrain, to the bit"
    );
    assert_eq!(b.terrain().stats(), a.terrain().stats());
    eprintln!(
        "world state at tick {}: {} bytes ({} events, {} bricks)",
        a.tick(),
        bytes.len(),
        a.terrain().events().len(),
        a.terrain().stats().bricks
    );

    for _ in 0..300 {
        let t = a.tick();
        a.step(&inputs(3, t)).unwrap();
        b.step(&inputs(3, t)).unwrap();
        assert_eq!(a.state_hash(), b.state_hash(), "tick {t}");
    }
    assert!(field_bits(&b) == field_bits(&a));
    // The rollback history before the resync is gone: old snapshots are refused.
    let e = b.restore(&stale).unwrap_err();
    assert!(matches!(e, SimError::Restore { .. }), "{e}");
    // Snapshots taken after it work as before.
    let s = b.snapshot();
    let before = b.state_hash();
    play(&mut b, 4, 5);
    b.restore(&s).unwrap();
    assert_eq!(b.state_hash(), before);
}

#[test]
fn states_of_other_matches_and_altered_states_are_refused_whole() {
    let mut a = world();
    play(&mut a, 5, 200);
    let state = a.state();

    let level = Level::default_level();
    let mut other_players = World::new(&level, settings(), 2).unwrap();
    let mut other_settings = World::new(&level, Settings::default(), PLAYERS).unwrap();
    for w in [&mut other_players, &mut other_settings] {
        let before = w.state_hash();
        let e = w.resync(&state).unwrap_err();
        assert!(matches!(e, SimError::ForeignSnapshot { tick: 200 }), "{e}");
        assert_eq!(w.state_hash(), before);
    }

    // A state whose parts were changed after it was taken: a body moved (the hash it
    // carries no longer matches), a body out of play, a NaN.
    let mut b = world();
    play(&mut b, 6, 50);
    let before = (b.state_hash(), field_bits(&b));
    let mut json = serde_json::to_value(&state).unwrap();
    json["bodies"][0]["pos"][0] = serde_json::json!(1234.5);
    let moved: craterfield::sim::WorldState = serde_json::from_value(json.clone()).unwrap();
    let e = b.resync(&moved).unwrap_err().to_string();
    assert!(e.contains("hash"), "{e}");
    json["bodies"][0]["pos"][0] = serde_json::json!(-1.0e9);
    let away: craterfield::sim::WorldState = serde_json::from_value(json.clone()).unwrap();
    let e = b.resync(&away).unwrap_err().to_string();
    assert!(e.contains("out of play") && e.contains("body"), "{e}");
    json["bodies"][0]["pos"][0] = serde_json::json!(null);
    if let Ok(nan) = serde_json::from_value::<craterfield::sim::WorldState>(json) {
        assert!(b.resync(&nan).is_err());
    }
    assert!(
        (b.state_hash(), field_bits(&b)) == before,
        "nothing changed"
    );
}

#[test]
fn terrain_states_that_do_not_fit_are_refused_with_nothing_changed() {
    let mut a = world();
    play(&mut a, 1, 600);
    assert!(a.terrain().stats().bricks > 0, "bricks to alter");
    let good = serde_json::to_value(a.state().terrain()).unwrap();
    let level = Level::default_level();
    let mut t = level.terrain().unwrap();
    let bits = |t: &craterfield::field2d::Terrain<_>| {
        let b = level.bounds();
        (0..4000)
            .map(|k| {
                let p = Vec2::new(
                    b.min.x + (b.max.x - b.min.x) * ((k % 100) as f32 + 0.37) / 100.0,
                    b.min.y + (b.max.y - b.min.y) * ((k / 100) as f32 + 0.61) / 40.0,
                );
                t.distance(p).to_bits()
            })
            .collect::<Vec<u32>>()
    };
    let before = (bits(&t), t.stats());
    let cases: Vec<(&str, serde_json::Value, &str)> = vec![
        ("/cell_index/0", serde_json::json!(u32::MAX), "cell"),
        ("/lists/0", serde_json::json!(u32::MAX - 1), "lists events"),
        ("/brick_values/0", serde_json::json!(1.0e9), "band"),
        ("/brick_len/0", serde_json::json!(3), "brick"),
        ("/free_bricks", serde_json::json!([0, 0]), "free brick"),
        ("/events/0/radius", serde_json::json!(1 << 30), "event 0"),
        ("/list_len/0", serde_json::json!(100_000), "lists"),
        (
            "/cell_state/0",
            serde_json::json!({"Solid": 999}),
            "material 999",
        ),
        (
            "/cell_state/0",
            serde_json::json!({"Brick": 100_000}),
            "brick 100000",
        ),
    ];
    for (path, value, words) in cases {
        let mut v = good.clone();
        let Some(slot) = v.pointer_mut(path) else {
            panic!("{path} is not in the state")
        };
        *slot = value;
        let state: craterfield::field2d::TerrainState = serde_json::from_value(v).unwrap();
        let e = t.restore_state(&state).unwrap_err().to_string();
        assert!(e.contains(words), "{path}: {e:?} should mention {words:?}");
        assert!((bits(&t), t.stats()) == before, "{path}: nothing changed");
    }
    let state: craterfield::field2d::TerrainState = serde_json::from_value(good).unwrap();
    t.restore_state(&state).unwrap();
    assert!(
        bits(&t) == bits(a.terrain()),
        "the unaltered state restores"
    );
}

#[test]
fn state_messages_are_bounded_and_mutations_never_panic() {
    let mut a = world();
    play(&mut a, 9, 150);
    let bytes = encode_state(&a.state()).unwrap();
    let small = DecodeLimits {
        max_state_bytes: bytes.len() - 1,
        ..DecodeLimits::default()
    };
    let e = decode_state_with_limits(&bytes, &small).unwrap_err();
    assert!(matches!(e.kind, DecodeErrorKind::TooLarge { .. }), "{e}");
    let e = encode_state_with_limits(&a.state(), &small).unwrap_err();
    assert!(e.to_string().contains("world state"), "{e}");

    let mut rng = Rng(11);
    let mut target = world();
    play(&mut target, 10, 30);
    let (mut decoded, mut resynced) = (0, 0);
    for round in 0..400 {
        let mut m = bytes.clone();
        for _ in 0..1 + rng.next() % 4 {
            let i = (rng.next() % m.len() as u64) as usize;
            m[i] ^= 1 + (rng.next() % 255) as u8;
        }
        if round % 2 == 0 {
            fix_crc(&mut m);
        }
        let Ok(state) = decode_state(&m) else {
            continue;
        };
        decoded += 1;
        let before = target.state_hash();
        let mut trial = target.clone();
        match trial.resync(&state) {
            Ok(()) => {
                resynced += 1;
                // Whatever was accepted steps without trouble.
                play(&mut trial, 12, 5);
            }
            Err(_) => assert_eq!(trial.state_hash(), before),
        }
    }
    eprintln!("400 mutated state messages: {decoded} decoded, {resynced} accepted");
}
