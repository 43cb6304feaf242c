//! The plugin's simulation in a headless Bevy app: fixed ticks of scripted inputs end on
//! the state hash of a bare `World` fed the same inputs and edits; messages apply at the
//! tick boundary; a bad level asset fails with the node path; body entities are
//! interpolated between the last two ticks; `TerrainQuery` answers as the library does;
//! a recorded replay verifies.

use std::time::Duration;

use bevy::asset::LoadState;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use craterfield_bevy::craterfield::field2d::query::{RayOptions, raycast};
use craterfield_bevy::craterfield::field2d::{Event, Level, Sdf};
use craterfield_bevy::craterfield::net::verify;
use craterfield_bevy::craterfield::sim::{World as SimWorld, buttons};
use craterfield_bevy::prelude::*;
use craterfield_bevy::{CraterfieldSystems, install_match};

const PLAYERS: usize = 2;

/// The input of `player` at `tick`: driving, aiming, firing every 40 ticks.
fn scripted(player: usize, tick: u32) -> Input {
    let fire = (tick + player as u32 * 20) % 40 == 5;
    Input {
        aim: Input::aim_from_degrees(if player == 0 { 60.0 } else { 120.0 } + (tick % 30) as f32),
        buttons: if fire { buttons::FIRE } else { 0 },
        drive: if (tick / 50).is_multiple_of(2) {
            80
        } else {
            -60
        },
        power: 90 + (tick % 100) as u8,
        weapon: u8::from(tick % 120 > 100),
    }
}

/// An edit at some ticks: carves and fills near the spawns.
fn scripted_edit(tick: u32) -> Option<Event> {
    match tick % 37 {
        3 => Event::carve(Vec2::new(300.0 + tick as f32, 640.0), 30.0).ok(),
        19 => Event::fill(Vec2::new(1240.0 - tick as f32, 700.0), 20.0, 4).ok(),
        _ => None,
    }
}

/// A headless app with the plugin, one fixed tick (1/60 s) per update, keeping every
/// failure the plugin reports.
fn app() -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), CraterfieldPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_nanos(
            16_666_667,
        )))
        .init_resource::<Failures>()
        .add_systems(
            Last,
            |mut r: MessageReader<CraterfieldFailed>, mut f: ResMut<Failures>| {
                f.0.extend(r.read().map(|m| format!("{}: {}", m.what, m.error)));
            },
        );
    app
}

#[derive(Resource, Default)]
struct Failures(Vec<String>);

fn start(app: &mut App) {
    let level = Level::default_level();
    let cf = Craterfield::new(&level, Settings::default(), PLAYERS).expect("a match");
    app.world_mut().commands().queue(install_match(cf));
    app.update();
}

fn run_until_tick(app: &mut App, tick: u32) {
    for _ in 0..tick * 4 + 10 {
        if app.world().resource::<Craterfield>().world().tick() >= tick {
            return;
        }
        app.update();
    }
    panic!("the world did not reach tick {tick}");
}

/// Sets each tick's inputs and sends its edits, from the fixed schedule, before the step.
fn script(
    cf: Res<Craterfield>,
    mut inputs: ResMut<PlayerInputs>,
    mut edits: MessageWriter<TerrainEdit>,
) {
    let tick = cf.world().tick();
    inputs.0 = (0..PLAYERS).map(|p| scripted(p, tick)).collect();
    if let Some(e) = scripted_edit(tick) {
        edits.write(TerrainEdit(e));
    }
}

fn bare_world(ticks: u32) -> SimWorld {
    let mut world = SimWorld::new(&Level::default_level(), Settings::default(), PLAYERS).unwrap();
    for tick in 0..ticks {
        if let Some(mut e) = scripted_edit(tick) {
            e.tick = tick;
            world.apply_event(e).unwrap();
        }
        let inputs: Vec<Input> = (0..PLAYERS).map(|p| scripted(p, tick)).collect();
        world.step(&inputs).unwrap();
    }
    world
}

#[test]
fn fixed_ticks_end_on_the_hash_of_a_bare_world() {
    const TICKS: u32 = 240;
    let mut app = app();
    app.add_systems(
        FixedUpdate,
        script
            .run_if(resource_exists::<Craterfield>)
            .before(CraterfieldSystems::Step),
    );
    start(&mut app);
    run_until_tick(&mut app, TICKS);
    let cf = app.world().resource::<Craterfield>();
    let bare = bare_world(TICKS);
    assert_eq!(cf.world().tick(), TICKS);
    assert!(
        cf.world().terrain().events().len() > 10,
        "the script carves, fills and fires: {} events",
        cf.world().terrain().events().len()
    );
    assert_eq!(
        cf.state_hash(),
        bare.state_hash(),
        "the plugin's world and a bare world fed the same inputs and edits differ"
    );
    // The fixed tick ran at the settings' rate.
    let step = app.world().resource::<Time<Fixed>>().timestep();
    assert_eq!(step, Duration::from_secs_f64(1.0 / 60.0));
}

#[test]
fn edits_sent_from_update_apply_at_the_next_tick_boundary() {
    let mut app = app();
    start(&mut app);
    run_until_tick(&mut app, 10);
    let before = app
        .world()
        .resource::<Craterfield>()
        .world()
        .terrain()
        .events()
        .len();
    let tick_before = app.world().resource::<Craterfield>().world().tick();
    let crater = Event::carve(Vec2::new(300.0, 600.0), 50.0).unwrap();
    app.world_mut().write_message(TerrainEdit(crater));
    // Not applied until a fixed tick runs.
    assert_eq!(
        app.world()
            .resource::<Craterfield>()
            .world()
            .terrain()
            .events()
            .len(),
        before
    );
    run_until_tick(&mut app, tick_before + 1);
    let cf = app.world().resource::<Craterfield>();
    let events = cf.world().terrain().events();
    assert_eq!(events.len(), before + 1, "the edit applied once");
    let applied = events.last().unwrap();
    assert_eq!(
        applied.tick, tick_before,
        "stamped with the tick boundary it applied at"
    );
    assert!(
        cf.world().terrain().distance(Vec2::new(300.0, 600.0)) > 0.0,
        "carved"
    );
    // And it is never applied again.
    run_until_tick(&mut app, tick_before + 5);
    assert_eq!(
        app.world()
            .resource::<Craterfield>()
            .world()
            .terrain()
            .events()
            .len(),
        before + 1
    );
}

#[test]
fn a_failed_edit_is_reported_and_changes_nothing() {
    let mut app = app();
    start(&mut app);
    run_until_tick(&mut app, 2);
    let tick = app.world().resource::<Craterfield>().world().tick();
    // A valid event (it encodes) with a radius over the terrain's limit: refused whole.
    let huge = Event::carve(Vec2::new(300.0, 600.0), 5000.0).unwrap();
    app.world_mut().write_message(TerrainEdit(huge));
    run_until_tick(&mut app, tick + 1);
    let failed = app.world().resource::<Failures>().0.clone();
    assert_eq!(failed.len(), 1, "{failed:?}");
    assert!(
        failed[0].contains("terrain edit") && failed[0].contains("radius"),
        "{failed:?}"
    );
    let cf = app.world().resource::<Craterfield>();
    assert!(cf.world().terrain().events().is_empty(), "half-applied");
    // The step of that tick still ran, as without the edit.
    assert_eq!(cf.world().tick(), tick + 1);
    let mut bare = SimWorld::new(&Level::default_level(), Settings::default(), PLAYERS).unwrap();
    for _ in 0..=tick {
        bare.step(&[Input::default(); PLAYERS]).unwrap();
    }
    assert_eq!(cf.state_hash(), bare.state_hash());
}

#[test]
fn a_bad_level_asset_fails_with_the_node_path() {
    let dir = std::env::temp_dir().join(format!("craterfield-bevy-assets-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("levels")).unwrap();
    let bad = r#"Level(
    name: "bad",
    bounds: (min: (0.0, 0.0), max: (1024.0, 512.0)),
    materials: [(name: "soil", color: (1, 2, 3))],
    spawns: [(10.0, 10.0)],
    root: Union([Circle(radius: 1.0), Ring(radius: 5.0, width: -1.0)]),
)"#;
    std::fs::write(dir.join("levels/bad.ron"), bad).unwrap();
    std::fs::write(
        dir.join("levels/good.ron"),
        craterfield_bevy::craterfield::field2d::DEFAULT_LEVEL_RON,
    )
    .unwrap();
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        AssetPlugin {
            file_path: dir.to_string_lossy().into_owned(),
            ..default()
        },
        CraterfieldPlugin,
    ));
    let server = app.world().resource::<AssetServer>().clone();
    let bad: Handle<LevelAsset> = server.load("levels/bad.ron");
    let good: Handle<LevelAsset> = server.load("levels/good.ron");
    let mut failure = None;
    for _ in 0..2000 {
        app.update();
        if let Some(LoadState::Failed(e)) = server.get_load_state(&bad) {
            failure = Some(e.to_string());
        }
        if failure.is_some()
            && app
                .world()
                .resource::<Assets<LevelAsset>>()
                .get(&good)
                .is_some()
        {
            break;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    let failure = failure.expect("the bad level never failed to load");
    assert!(
        failure.contains("root.Union[1].Ring.width") && failure.contains("positive"),
        "the load error names the node path and the reason: {failure}"
    );
    let good = app
        .world()
        .resource::<Assets<LevelAsset>>()
        .get(&good)
        .expect("the good level loaded");
    assert_eq!(good.level.name(), "Default");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn start_match_waits_for_the_level_and_sets_the_tick_rate() {
    let mut app = app();
    let level = Level::default_level();
    let handle = app
        .world_mut()
        .resource_mut::<Assets<LevelAsset>>()
        .add(LevelAsset { level });
    let settings = Settings {
        tick_hz: 30,
        ..Settings::default()
    };
    app.insert_resource(StartMatch {
        level: handle,
        settings,
        players: 3,
        record: true,
    });
    app.update();
    app.update();
    let cf = app.world().resource::<Craterfield>();
    assert_eq!(cf.world().players(), 3);
    assert!(cf.is_recording());
    assert!(app.world().get_resource::<StartMatch>().is_none());
    let step = app.world().resource::<Time<Fixed>>().timestep();
    assert_eq!(step, Duration::from_secs_f64(1.0 / 30.0));
    assert_eq!(app.world().resource::<PlayerInputs>().0.len(), 3);
}

#[test]
fn body_entities_are_interpolated_between_the_last_two_ticks() {
    let mut app = App::new();
    // Half a tick per update: every other frame lands between two ticks.
    app.add_plugins((MinimalPlugins, AssetPlugin::default(), CraterfieldPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_nanos(
            8_333_333,
        )));
    app.add_systems(
        FixedUpdate,
        (|mut inputs: ResMut<PlayerInputs>| {
            inputs.0 = vec![
                Input {
                    drive: 127,
                    ..Input::default()
                };
                PLAYERS
            ];
        })
        .before(CraterfieldSystems::Step),
    );
    start(&mut app);
    let mut between = 0;
    let mut previous: Option<Vec<(u32, Vec2)>> = None;
    for _ in 0..120 {
        app.update();
        let alpha = app.world().resource::<Time<Fixed>>().overstep_fraction();
        let cf = app.world().resource::<Craterfield>();
        let current: Vec<(u32, Vec2)> = cf.world().bodies().iter().map(|b| (b.id, b.pos)).collect();
        let mut q = app.world_mut().query::<(&CraterfieldBody, &Transform)>();
        let shown: Vec<(u32, Vec2)> = q
            .iter(app.world())
            .map(|(b, t)| (b.id, t.translation.truncate()))
            .collect();
        assert_eq!(shown.len(), current.len(), "one entity per body");
        let cf = app.world().resource::<Craterfield>();
        for (id, at) in shown {
            let (expected, _) = cf.interpolated_pose(id, alpha).unwrap();
            assert!(
                (at - expected).length() < 1e-3,
                "body {id} at {at}, pose {expected}"
            );
            let now = current.iter().find(|c| c.0 == id).unwrap().1;
            if let Some(prev) = previous.as_ref().and_then(|p| p.iter().find(|c| c.0 == id)) {
                // On the segment from the pose before the last tick to the last tick's.
                let (a, b) = (cf.interpolated_pose(id, 0.0).unwrap().0, now);
                let ab = b - a;
                let t = if ab.length_squared() > 0.0 {
                    (at - a).dot(ab) / ab.length_squared()
                } else {
                    0.0
                };
                assert!((-1e-4..=1.0 + 1e-4).contains(&t), "body {id}: t {t}");
                assert!(
                    (a + ab * t - at).length() < 1e-2,
                    "body {id} off its segment"
                );
                if t > 0.05 && t < 0.95 && prev.1 != now {
                    between += 1;
                }
            }
        }
        previous = Some(current);
    }
    assert!(
        between > 20,
        "only {between} poses were strictly between two ticks"
    );
}

#[test]
fn terrain_query_answers_as_the_library() {
    let mut app = app();
    start(&mut app);
    let crater = Event::carve(Vec2::new(1240.0, 700.0), 60.0).unwrap();
    app.world_mut().write_message(TerrainEdit(crater));
    run_until_tick(&mut app, 3);
    let answers = app
        .world_mut()
        .run_system_once(|q: TerrainQuery| {
            (
                q.raycast(Vec2::new(1240.0, 1500.0), Vec2::NEG_Y, 2000.0),
                q.distance(Vec2::new(1240.0, 700.0)),
                q.sample(Vec2::new(300.0, 400.0)),
                q.contact_circle(Vec2::new(300.0, 400.0), 5.0),
                q.sweep_circle(Vec2::new(1000.0, 1500.0), Vec2::new(1000.0, 0.0), 8.0),
                q.distance(Vec2::new(f32::NAN, 0.0)),
            )
        })
        .unwrap();
    let cf = app.world().resource::<Craterfield>();
    let terrain = cf.world().terrain();
    let hit = raycast(
        terrain,
        Vec2::new(1240.0, 1500.0),
        Vec2::NEG_Y,
        2000.0,
        &RayOptions::default(),
    )
    .unwrap();
    assert_eq!(answers.0.unwrap(), hit);
    assert!(hit.is_some());
    assert_eq!(
        answers.1.unwrap(),
        terrain.distance(Vec2::new(1240.0, 700.0))
    );
    assert!(answers.1.unwrap() > 0.0);
    assert_eq!(answers.2.unwrap(), terrain.sample(Vec2::new(300.0, 400.0)));
    assert!(answers.3.unwrap().is_some(), "deep in the ground");
    assert!(answers.4.unwrap().is_some());
    assert!(answers.5.unwrap_err().to_string().contains("not finite"));
    // Without a match: an error, not a panic.
    let mut empty = App::new();
    empty.add_plugins((MinimalPlugins, AssetPlugin::default(), CraterfieldPlugin));
    let none = empty
        .world_mut()
        .run_system_once(|q: TerrainQuery| q.distance(Vec2::ZERO))
        .unwrap();
    assert!(none.unwrap_err().to_string().contains("no match"));
}

#[test]
fn a_recorded_replay_verifies() {
    let mut app = app();
    app.add_systems(
        FixedUpdate,
        script
            .run_if(resource_exists::<Craterfield>)
            .before(CraterfieldSystems::Step),
    );
    let level = Level::default_level();
    let mut cf = Craterfield::new(&level, Settings::default(), PLAYERS).unwrap();
    cf.start_recording().unwrap();
    app.world_mut().commands().queue(install_match(cf));
    app.update();
    run_until_tick(&mut app, 150);
    let replay = app
        .world_mut()
        .resource_mut::<Craterfield>()
        .finish_recording()
        .unwrap();
    assert!(!replay.edits.is_empty());
    let report = verify(&replay, &level).expect("the replay verifies");
    assert_eq!(report.ticks, 150);
    assert!(report.hashes_checked >= 3);
    // A detonation cannot be recorded: refused, not silently left out of the replay.
    let mut cf = Craterfield::new(&level, Settings::default(), PLAYERS).unwrap();
    cf.start_recording().unwrap();
    let mut app = self::app();
    app.world_mut().commands().queue(install_match(cf));
    app.update();
    app.world_mut().write_message(Detonate {
        at: Vec2::new(300.0, 600.0),
        weapon: 0,
    });
    run_until_tick(&mut app, 3);
    let failed = app.world().resource::<Failures>().0.clone();
    assert_eq!(failed.len(), 1, "{failed:?}");
    assert!(failed[0].contains("replay"), "{failed:?}");
}

use bevy::ecs::system::RunSystemOnce;
