#![cfg(feature = "ggrs")]
//! GGRS sync tests: every frame the session rolls the world back `check_distance` frames,
//! re-simulates them and compares the state hashes of both runs. Scripted pseudo-random
//! matches of 2, 3 and 4 players (driving, jumping, stick toggles, both weapons fired every
//! few ticks, so the terrain changes all the time) must never mismatch, and must end on the
//! state of a plain run of the same inputs without any rollback.

mod common;
use common::scripted_input;

use craterfield::field2d::Level;
use craterfield::net::rollback::{
    SessionBuilder, handle_requests, handle_requests_from, session_builder,
};
use craterfield::net::state::{decode_state, encode_state};
use craterfield::sim::{Input, Settings, World};

const FRAMES: u32 = 1200;

fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 3;
    s.dirt.cooldown_ticks = 4;
    // Shells still hurt, but nobody dies: every player keeps firing all match long.
    s.vehicle.health = 1_000_000;
    s
}

/// Runs a sync test and returns the number of explosions applied.
fn sync_test(players: usize, check_distance: usize, input_delay: usize, seed: u64) -> usize {
    let level = Level::default_level();
    let mut world = World::new(&level, settings(), players).unwrap();
    let mut session = SessionBuilder::new()
        .with_num_players(players)
        .unwrap()
        .with_max_prediction_window(check_distance + 1)
        .with_check_distance(check_distance)
        .with_input_delay(input_delay)
        .start_synctest_session()
        .unwrap();
    for frame in 0..FRAMES {
        for player in 0..players {
            session
                .add_local_input(player, scripted_input(seed, player, frame))
                .unwrap();
        }
        let requests = session.advance_frame().unwrap_or_else(|e| {
            panic!(
                "{players} players, check distance {check_distance}, frame {frame}: {e} \
                 ({} explosions so far)",
                world.terrain().events().len()
            )
        });
        handle_requests(&mut world, requests).unwrap();
    }
    assert_eq!(world.tick(), FRAMES);

    // The same inputs without GGRS: the input added on frame f acts on frame f + delay.
    let mut plain = World::new(&level, settings(), players).unwrap();
    let mut inputs = vec![Input::default(); players];
    for tick in 0..FRAMES {
        for (player, input) in inputs.iter_mut().enumerate() {
            *input = match tick.checked_sub(input_delay as u32) {
                Some(frame) => scripted_input(seed, player, frame),
                None => Input::default(),
            };
        }
        plain.step(&inputs).unwrap();
    }
    assert_eq!(
        world.state_hash(),
        plain.state_hash(),
        "{players} players, check distance {check_distance}: the rolled-back world ended \
         elsewhere than a plain run"
    );
    assert_eq!(
        world.terrain().events().len(),
        plain.terrain().events().len()
    );

    let explosions = world.terrain().events().len();
    eprintln!("{players} players, check distance {check_distance}: {explosions} explosions");
    // Not vacuous: the terrain changed every few frames all along.
    assert!(
        explosions >= FRAMES as usize / 8,
        "{players} players, check distance {check_distance}: only {explosions} explosions \
         in {FRAMES} frames"
    );
    explosions
}

#[test]
fn sync_test_two_players() {
    sync_test(2, 2, 0, 1);
    sync_test(2, 7, 0, 2);
}

#[test]
fn sync_test_three_players() {
    sync_test(3, 2, 0, 3);
    sync_test(3, 7, 0, 4);
}

#[test]
fn sync_test_four_players() {
    sync_test(4, 2, 0, 5);
    sync_test(4, 7, 0, 6);
}

#[test]
fn sync_test_with_input_delay() {
    sync_test(2, 4, 2, 7);
    sync_test(4, 7, 3, 8);
}

#[test]
fn sync_test_eight_players() {
    sync_test(8, 3, 1, 9);
}

/// The desync path: a world that diverged resyncs from a peer's encoded state, then a new
/// sync-test session starts at the resynced tick (frame 0 = that tick) and rolls back
/// and re-simulates without a mismatch, ending where the peer's plain run ends.
#[test]
fn a_resynced_world_continues_under_a_new_session() {
    let level = Level::default_level();
    let players = 2;
    let mut good = World::new(&level, settings(), players).unwrap();
    let mut diverged = World::new(&level, settings(), players).unwrap();
    for tick in 0..300 {
        let row = |seed| -> Vec<Input> {
            (0..players)
                .map(|p| scripted_input(seed, p, tick))
                .collect()
        };
        good.step(&row(21)).unwrap();
        diverged.step(&row(22)).unwrap();
    }
    assert_ne!(good.state_hash(), diverged.state_hash());
    let message = encode_state(&good.state()).unwrap();
    diverged.resync(&decode_state(&message).unwrap()).unwrap();
    let origin = diverged.tick();

    let mut session = session_builder()
        .with_num_players(players)
        .unwrap()
        .with_max_prediction_window(5)
        .with_check_distance(4)
        .start_synctest_session()
        .unwrap();
    for frame in 0..300u32 {
        for player in 0..players {
            session
                .add_local_input(player, scripted_input(23, player, origin + frame))
                .unwrap();
        }
        let requests = session.advance_frame().unwrap();
        handle_requests_from(&mut diverged, origin, requests).unwrap();
        let inputs: Vec<Input> = (0..players)
            .map(|p| scripted_input(23, p, origin + frame))
            .collect();
        good.step(&inputs).unwrap();
    }
    assert_eq!(diverged.tick(), good.tick());
    assert_eq!(diverged.state_hash(), good.state_hash());
}
