//! Determinism of the simulation: the same inputs give the same per-tick state hashes on
//! every run, evaluator backend and thread count, and after any pattern of rollbacks; a
//! golden hash of a scripted 600-tick match is pinned (and checked on aarch64 too).

#[macro_use]
mod common;

// In a browser the same tests run under wasm-bindgen-test (`scripts/test`'s web leg), so
// the pinned bits are checked on wasm32 too.
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);
use common::Rng;

use std::collections::VecDeque;

use craterfield::backend::Backend;
use craterfield::field2d::{Level, Sdf};
use craterfield::sim::{Input, Settings, SimError, Snapshot, World, buttons};
use glam::Vec2;

/// Scripted inputs: throttle held for a while, fire, jump and stick presses, aim sweeps.
fn script(seed: u64, players: usize, ticks: usize) -> Vec<Vec<Input>> {
    let mut rng = Rng(seed);
    let mut held = vec![Input::default(); players];
    let mut out = Vec::with_capacity(ticks);
    for _ in 0..ticks {
        let mut row = Vec::with_capacity(players);
        for h in held.iter_mut() {
            if rng.below(30) == 0 {
                h.drive = rng.below(255) as i8;
                if h.drive == i8::MIN {
                    h.drive = 0;
                }
            }
            if rng.below(10) == 0 {
                h.aim = rng.next() as u16;
                h.power = 80 + rng.below(176) as u8;
                h.weapon = u8::from(rng.below(5) == 0);
            }
            let mut b = 0;
            if rng.below(8) == 0 {
                b |= buttons::FIRE;
            }
            if rng.below(90) == 0 {
                b |= buttons::JUMP;
            }
            if rng.below(150) == 0 {
                b |= buttons::STICK;
            }
            h.buttons = b;
            row.push(*h);
        }
        out.push(row);
    }
    out
}

fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 8;
    s.dirt.cooldown_ticks = 8;
    // Players shoot the ground under themselves; keep them alive to keep them shooting.
    s.vehicle.health = 1_000_000;
    s
}

/// A match with `players` vehicles and a heap of debris dropped over the level.
fn world(players: usize, debris: usize) -> World {
    let level = Level::default_level();
    let mut w = World::new(&level, settings(), players).unwrap();
    let mut rng = Rng(42);
    while w.bodies().len() < players + debris {
        let at = Vec2::new(
            100.0 + rng.below(3600) as f32,
            700.0 + rng.below(700) as f32,
        );
        let radius = 2.0 + rng.below(5) as f32;
        // In the air only.
        if w.terrain().distance(at) > radius + 1.0 {
            w.add_debris(at, radius).unwrap();
        }
    }
    w
}

fn run(w: &mut World, inputs: &[Vec<Input>]) -> Vec<u64> {
    inputs
        .iter()
        .map(|row| {
            w.step(row).unwrap();
            w.state_hash()
        })
        .collect()
}

#[test]
fn same_inputs_same_hashes_on_every_backend_and_thread_count() {
    let inputs = script(1, 3, 300);
    let mut base = world(3, 700);
    base.set_backend(Backend::Scalar).unwrap();
    let reference = run(&mut base, &inputs);
    assert!(base.terrain().events().len() > 20, "explosions happened");
    for backend in Backend::available() {
        for threads in [1, 2, 3] {
            let mut w = world(3, 700);
            w.set_backend(backend).unwrap();
            w.set_threads(threads);
            let hashes = run(&mut w, &inputs);
            let first = hashes.iter().zip(&reference).position(|(a, b)| a != b);
            assert_eq!(
                first,
                None,
                "{} with {threads} threads diverged",
                backend.name()
            );
        }
    }
}

/// A 600-tick, 4-player scripted match with 200 debris bodies: the final state hash and a
/// hash of every tick's hash. Pinned: a change here means every replay and every peer of an
/// older build disagrees.
#[test]
fn golden_match_hash() {
    let inputs = script(600, 4, 600);
    let mut w = world(4, 200);
    let hashes = run(&mut w, &inputs);
    let mut all = craterfield::sim::StateHasher::new(0);
    for h in &hashes {
        all.word(*h);
    }
    let events = w.terrain().events().len();
    let bodies = w.bodies().len();
    say!(
        "golden match: final {:#018x}, all ticks {:#018x}, {events} events, {bodies} bodies",
        hashes[599],
        all.finish()
    );
    assert!(events > 50, "{events} events");
    assert_eq!(hashes[599], GOLDEN_FINAL, "final state hash");
    assert_eq!(all.finish(), GOLDEN_ALL, "hash of the per-tick hashes");
}

// Re-pinned when the state hash began to cover the match's setup (level, settings and
// player count): the same 152 events and 212 bodies as before, one more word per hash.
const GOLDEN_FINAL: u64 = 0x0ab2_ee29_b2c6_65ab;
const GOLDEN_ALL: u64 = 0xd1f3_195a_5e6c_e38c;

#[test]
fn random_rollbacks_then_resimulation_equal_a_straight_run() {
    let inputs = script(7, 4, 700);
    let mut straight = world(4, 100);
    let reference = run(&mut straight, &inputs);
    for seed in 0..3u64 {
        let mut rng = Rng(seed);
        let mut w = world(4, 100);
        let mut snaps: VecDeque<Snapshot> = VecDeque::new();
        snaps.push_back(w.snapshot());
        let mut rollbacks = 0;
        while (w.tick() as usize) < inputs.len() {
            let t = w.tick() as usize;
            w.step(&inputs[t]).unwrap();
            assert_eq!(
                w.state_hash(),
                reference[t],
                "seed {seed}: tick {} after {rollbacks} rollbacks",
                t + 1
            );
            snaps.push_back(w.snapshot());
            while snaps.len() > 120 {
                snaps.pop_front();
            }
            // Mostly short rollbacks (as GGRS does), sometimes deep ones.
            let depth = match rng.below(150) {
                0 => 100,
                1..=10 => 8,
                _ => 0,
            };
            if depth > 0 {
                let back = 1 + rng.below(depth.min(snaps.len() as u64 - 1)) as usize;
                let target = snaps.len() - 1 - back;
                w.restore(&snaps[target]).unwrap();
                snaps.truncate(target + 1);
                rollbacks += 1;
            }
        }
        assert!(rollbacks > 30, "{rollbacks} rollbacks");
        assert_eq!(w.state_hash(), straight.state_hash());
    }
}

#[test]
fn snapshots_beyond_the_rollback_window_are_refused_unchanged() {
    let inputs = script(3, 2, 400);
    let mut w = world(2, 0);
    let old = w.snapshot();
    run(&mut w, &inputs[..200]);
    let recent = w.snapshot();
    run(&mut w, &inputs[200..]);
    let before = w.state_hash();
    let journal = w.terrain().journal_len();
    let err = w.restore(&old).unwrap_err();
    assert!(matches!(err, SimError::Restore { tick: 0, .. }), "{err}");
    assert!(
        err.to_string().contains("older than the kept history"),
        "{err}"
    );
    assert_eq!(w.state_hash(), before);
    assert_eq!(w.terrain().journal_len(), journal);
    // 200 ticks back is beyond the default window of 128 too.
    assert!(w.restore(&recent).is_err());
    assert!(
        w.step(&[Input::default()]).is_err(),
        "input count is checked"
    );
}

/// Restoring must only accept a snapshot of this world's own timeline: every other source
/// is refused, and the world is unchanged and keeps stepping.
#[test]
fn snapshots_of_other_worlds_are_refused_unchanged() {
    let level = Level::default_level();
    let caverns = Level::from_ron(include_str!("../levels/caverns.ron")).unwrap();
    let inputs = script(5, 2, 60);
    let mut w = world(2, 0);
    run(&mut w, &inputs[..30]);
    let shared = w.snapshot();
    let mut clone = w.clone();
    run(&mut w, &inputs[30..40]);

    let stepped = |mut other: World, players: usize| {
        let row = vec![Input::default(); players];
        for _ in 0..5 {
            other.step(&row).unwrap();
        }
        other.snapshot()
    };
    let mut more_wind = settings();
    more_wind.wind[0] += 1;
    let mut foreign: Vec<(&str, Snapshot, bool)> = vec![
        // Another player count, level, or any setting: another setup.
        ("4 players", stepped(world(4, 0), 4), true),
        ("1 player", stepped(world(1, 0), 1), true),
        (
            "another level",
            stepped(World::new(&caverns, settings(), 2).unwrap(), 2),
            true,
        ),
        (
            "another setting",
            stepped(World::new(&level, more_wind, 2).unwrap(), 2),
            true,
        ),
        // The same setup, but another world's timeline.
        ("another world", stepped(world(2, 0), 2), false),
    ];
    // A clone that went its own way after the clone was made.
    clone
        .step(
            &[Input {
                drive: 90,
                ..Input::default()
            }; 2],
        )
        .unwrap();
    clone
        .apply_event(craterfield::field2d::Event::carve(Vec2::new(1800.0, 900.0), 30.0).unwrap())
        .unwrap();
    foreign.push(("a diverged clone", clone.snapshot(), false));

    let before = (w.tick(), w.state_hash(), w.bodies().len());
    for (what, snap, other_setup) in &foreign {
        let err = w.restore(snap).unwrap_err();
        match err {
            SimError::ForeignSnapshot { .. } => assert!(other_setup, "{what}: {err}"),
            SimError::Restore { .. } => assert!(!other_setup, "{what}: {err}"),
            _ => panic!("{what}: {err}"),
        }
        assert_eq!(
            (w.tick(), w.state_hash(), w.bodies().len()),
            before,
            "{what}"
        );
    }
    // The shared history before the clone is still this world's own: it restores, and
    // re-simulating gives the same hashes as the first time.
    let hashes = run(&mut w, &inputs[40..60]);
    w.restore(&shared).unwrap();
    run(&mut w, &inputs[30..40]);
    assert_eq!(run(&mut w, &inputs[40..60]), hashes);
}
