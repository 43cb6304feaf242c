#![cfg(feature = "ggrs")]
//! The world under bevy_ggrs: a `SyncTest` session resimulates every frame `check
//! distance` frames back (2 to 7) from the world's snapshots and compares the state hashes;
//! with players firing every few frames the terrain changes under every rollback. The
//! match must end where a bare `World` fed the same inputs ends, with no mismatch reported.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_ggrs::{LocalInputs, LocalPlayers, ReadInputs, SyncTestMismatch};
use craterfield_bevy::craterfield::field2d::Level;
use craterfield_bevy::craterfield::net::rollback::{GgrsConfig, SessionBuilder};
use craterfield_bevy::craterfield::sim::{World as SimWorld, buttons};
use craterfield_bevy::prelude::*;
use craterfield_bevy::{Session, install_match};

const PLAYERS: usize = 3;
const FRAMES: u32 = 240;

fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 3;
    s.dirt.cooldown_ticks = 4;
    // Nobody dies: every player keeps firing all match long.
    s.vehicle.health = 1_000_000;
    s
}

/// Player `player`'s input on frame `frame`: each fires every 6 frames, staggered, so
/// some player fires every other frame; aim sweeps, power varies, they drive.
fn scripted(player: usize, frame: u32) -> Input {
    let fire = (frame + player as u32 * 2).is_multiple_of(6);
    Input {
        aim: Input::aim_from_degrees(200.0 + ((frame * 7 + player as u32 * 40) % 140) as f32),
        buttons: if fire { buttons::FIRE } else { 0 },
        drive: if (frame / 40 + player as u32).is_multiple_of(2) {
            90
        } else {
            -90
        },
        power: 60 + ((frame * 13) % 150) as u8,
        weapon: u8::from(frame % 18 == 12),
    }
}

/// Frames whose inputs were read (ReadInputs runs once per advanced frame).
#[derive(Resource, Default)]
struct FramesRead(u32);

fn read_inputs(mut commands: Commands, local: Res<LocalPlayers>, mut frames: ResMut<FramesRead>) {
    let mut map = HashMap::default();
    for &handle in &local.0 {
        map.insert(handle, scripted(handle, frames.0));
    }
    frames.0 += 1;
    commands.insert_resource(LocalInputs::<GgrsConfig>(map));
}

/// Runs a sync test; returns the mismatches GGRS reported and the app.
fn run_sync_test(
    check_distance: usize,
    extra: impl FnOnce(&mut App),
) -> (Vec<(i32, Vec<i32>)>, App) {
    let level = Level::default_level();
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin::default(),
        CraterfieldPlugin,
        CraterfieldRollbackPlugin,
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_nanos(
        16_666_667,
    )))
    .init_resource::<FramesRead>()
    .add_systems(ReadInputs, read_inputs);
    let mismatches = Arc::new(Mutex::new(Vec::new()));
    let seen = mismatches.clone();
    app.add_observer(move |m: On<SyncTestMismatch>| {
        seen.lock()
            .unwrap()
            .push((m.current_frame, m.mismatched_frames.clone()));
    });
    let cf = Craterfield::new(&level, settings(), PLAYERS).unwrap();
    app.world_mut().commands().queue(install_match(cf));
    extra(&mut app);
    let session = SessionBuilder::new()
        .with_num_players(PLAYERS)
        .unwrap()
        .with_max_prediction_window(check_distance + 1)
        .with_check_distance(check_distance)
        .start_synctest_session()
        .unwrap();
    app.insert_resource(Session::SyncTest(session));
    for _ in 0..FRAMES * 3 {
        if app.world().resource::<FramesRead>().0 >= FRAMES {
            break;
        }
        app.update();
    }
    let found = mismatches.lock().unwrap().clone();
    (found, app)
}

fn sync_test(check_distance: usize) {
    let level = Level::default_level();
    let (mismatches, app) = run_sync_test(check_distance, |_| {});
    let cf = app.world().resource::<Craterfield>();
    assert_eq!(cf.world().tick(), FRAMES, "check distance {check_distance}");
    let explosions = cf.world().terrain().events().len();
    assert!(explosions > 40, "only {explosions} explosions");
    assert!(
        mismatches.is_empty(),
        "check distance {check_distance}: the sync test found mismatches {mismatches:?}"
    );
    // A bare world fed the same inputs.
    let mut bare = SimWorld::new(&level, settings(), PLAYERS).unwrap();
    for frame in 0..FRAMES {
        let inputs: Vec<Input> = (0..PLAYERS).map(|p| scripted(p, frame)).collect();
        bare.step(&inputs).unwrap();
    }
    assert_eq!(
        cf.state_hash(),
        bare.state_hash(),
        "check distance {check_distance}: the rolled-back world ended elsewhere than a bare run"
    );
    eprintln!(
        "check distance {check_distance}: {FRAMES} frames, {explosions} explosions, hash {:#018x}",
        cf.state_hash()
    );
}

#[test]
fn sync_test_check_distances_2_to_7() {
    for d in 2..=7 {
        sync_test(d);
    }
}

/// Not rolled back: counts every time the rollback schedule runs.
#[derive(Resource, Default)]
struct Runs(u32);

/// A change to the world from state GGRS does not roll back: the resimulated frames
/// differ from the first run, and the sync test must say so (the test can fail).
#[test]
fn state_outside_the_rollback_is_caught() {
    let (mismatches, _) = run_sync_test(3, |app| {
        app.init_resource::<Runs>().add_systems(
            bevy_ggrs::GgrsSchedule,
            (|mut cf: ResMut<Craterfield>, mut runs: ResMut<Runs>| {
                runs.0 += 1;
                if runs.0.is_multiple_of(5) {
                    let at = Vec2::new(300.0 + runs.0 as f32, 600.0);
                    let e = craterfield_bevy::craterfield::field2d::Event::carve(at, 8.0).unwrap();
                    cf.apply_edit(e).unwrap();
                }
            })
            .before(craterfield_bevy::CraterfieldSystems::Step),
        );
    });
    assert!(!mismatches.is_empty(), "the sync test missed a desync");
}
