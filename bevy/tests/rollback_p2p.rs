#![cfg(feature = "ggrs")]
//! Two OS processes, each a headless Bevy app with the plugin and its rollback plugin, play
//! a scripted match as a GGRS peer-to-peer session over UDP on 127.0.0.1 (the library's
//! session builder: desync detection on, every frame). Both must end on the same confirmed
//! state, the state of a bare `World` fed the same inputs, with no desync reported.
//!
//! The test binary is its own peer: the test re-executes it twice, running only itself,
//! with `CRATERFIELD_BEVY_PEER` telling each child its handle and ports. A child prints
//! `FINAL <tick> <hash>` once every input before that tick is confirmed, `DESYNC ...` for
//! every desync GGRS reports, and `STATS <updates> <frames>`.

use std::net::UdpSocket;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_ggrs::ggrs::{GgrsEvent, PlayerType, UdpNonBlockingSocket};
use bevy_ggrs::{ConfirmedFrameCount, LocalInputs, LocalPlayers, ReadInputs, RollbackFrameCount};
use craterfield_bevy::craterfield::field2d::Level;
use craterfield_bevy::craterfield::net::rollback::{GgrsConfig, session_builder};
use craterfield_bevy::craterfield::sim::{World as SimWorld, buttons};
use craterfield_bevy::prelude::*;
use craterfield_bevy::{Session, install_match};

const PEER_ENV: &str = "CRATERFIELD_BEVY_PEER";
const TEST_NAME: &str = "two_processes_play_one_match_on_loopback";
const FRAMES: u32 = 300;

fn settings() -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 5;
    s.vehicle.health = 1_000_000;
    s
}

/// Player `player`'s input on frame `frame`: firing every 9 frames, aim and drive varying.
fn scripted(player: usize, frame: u32) -> Input {
    let fire = (frame + player as u32 * 4).is_multiple_of(9);
    Input {
        aim: Input::aim_from_degrees(210.0 + ((frame * 11 + player as u32 * 50) % 120) as f32),
        buttons: if fire { buttons::FIRE } else { 0 },
        drive: if (frame / 30 + player as u32).is_multiple_of(2) {
            100
        } else {
            -100
        },
        power: 70 + ((frame * 7) % 160) as u8,
        weapon: u8::from(frame % 27 == 13),
    }
}

/// The state hash after each tick (a resimulated tick overwrites its mispredicted hash).
#[derive(Resource, Default)]
struct Hashes(HashMap<u32, u64>);

fn read_inputs(mut commands: Commands, local: Res<LocalPlayers>, frame: Res<RollbackFrameCount>) {
    let frame = u32::try_from(frame.0).unwrap_or(0);
    let inputs = local.0.iter().map(|&h| (h, scripted(h, frame))).collect();
    commands.insert_resource(LocalInputs::<GgrsConfig>(inputs));
}

fn keep_hashes(mut ticked: MessageReader<Ticked>, mut hashes: ResMut<Hashes>) {
    for t in ticked.read() {
        hashes.0.insert(t.tick, t.state_hash);
    }
}

fn report_desyncs(session: Option<ResMut<Session>>) {
    if let Some(mut session) = session
        && let bevy_ggrs::Session::P2P(s) = session.as_mut()
    {
        for event in s.events() {
            if let GgrsEvent::DesyncDetected {
                frame,
                local_checksum,
                remote_checksum,
                ..
            } = event
            {
                println!(
                    "DESYNC frame {frame} local {local_checksum:#x} remote {remote_checksum:#x}"
                );
            }
        }
    }
}

fn peer(handle: usize, local_port: u16, remote_port: u16) {
    let socket = (0..100)
        .find_map(|_| {
            UdpNonBlockingSocket::bind_to_port(local_port)
                .inspect_err(|_| std::thread::sleep(Duration::from_millis(20)))
                .ok()
        })
        .expect("a UDP port");
    let remote = std::net::SocketAddr::from(([127, 0, 0, 1], remote_port));
    let session = session_builder()
        .with_num_players(2)
        .unwrap()
        .with_input_delay(0)
        .with_max_prediction_window(8)
        .with_disconnect_timeout(Duration::from_secs(20))
        .add_player(PlayerType::Local, handle)
        .unwrap()
        .add_player(PlayerType::Remote(remote), 1 - handle)
        .unwrap()
        .start_p2p_session(socket)
        .unwrap();
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
    .init_resource::<Hashes>()
    .add_systems(ReadInputs, read_inputs)
    .add_systems(Update, (keep_hashes, report_desyncs));
    let cf = Craterfield::new(&Level::default_level(), settings(), 2).unwrap();
    app.world_mut().commands().queue(install_match(cf));
    app.insert_resource(Session::P2P(session));
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut updates = 0u64;
    while Instant::now() < deadline {
        app.update();
        updates += 1;
        let confirmed = app
            .world()
            .get_resource::<ConfirmedFrameCount>()
            .map_or(-1, |c| c.0);
        if confirmed >= FRAMES as i32 {
            break;
        }
        // Real time for the packets to cross; the game clock is the manual one.
        std::thread::sleep(Duration::from_millis(2));
    }
    let hash = app.world().resource::<Hashes>().0.get(&FRAMES).copied();
    let frames = app.world().resource::<Craterfield>().world().tick();
    // On a line of its own: libtest has printed the test's name without a newline.
    println!("\nSTATS {updates} {frames}");
    match hash {
        Some(h) => println!("FINAL {FRAMES} {h}"),
        None => println!("NO_FINAL after {updates} updates at tick {frames}"),
    }
    // Let the other peer confirm too before this one stops answering.
    let linger = Instant::now() + Duration::from_millis(500);
    while Instant::now() < linger {
        app.update();
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn free_port() -> u16 {
    UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

#[test]
fn two_processes_play_one_match_on_loopback() {
    if let Ok(config) = std::env::var(PEER_ENV) {
        let n: Vec<u16> = config.split(' ').map(|s| s.parse().unwrap()).collect();
        peer(usize::from(n[0]), n[1], n[2]);
        return;
    }
    let ports = [free_port(), free_port()];
    let exe = std::env::current_exe().unwrap();
    let children: Vec<_> = (0..2)
        .map(|h| {
            Command::new(&exe)
                .args(["--exact", TEST_NAME, "--nocapture", "--test-threads", "1"])
                .env(PEER_ENV, format!("{h} {} {}", ports[h], ports[1 - h]))
                .stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .unwrap()
        })
        .collect();
    let outputs: Vec<String> = children
        .into_iter()
        .map(|c| String::from_utf8_lossy(&c.wait_with_output().unwrap().stdout).into_owned())
        .collect();
    let mut bare = SimWorld::new(&Level::default_level(), settings(), 2).unwrap();
    for frame in 0..FRAMES {
        bare.step(&[scripted(0, frame), scripted(1, frame)])
            .unwrap();
    }
    let expected = format!("FINAL {FRAMES} {}", bare.state_hash());
    for (h, out) in outputs.iter().enumerate() {
        let lines: Vec<&str> = out
            .lines()
            .filter(|l| {
                ["FINAL", "NO_FINAL", "DESYNC", "STATS"]
                    .iter()
                    .any(|p| l.starts_with(p))
            })
            .collect();
        eprintln!("peer {h}: {}", lines.join(" | "));
        assert!(!out.contains("DESYNC"), "peer {h} saw a desync:\n{out}");
        assert!(
            out.lines().any(|l| l == expected),
            "peer {h} did not end on the bare world's state ({expected}):\n{out}"
        );
    }
    assert!(
        bare.terrain().events().len() > 20,
        "the match has explosions"
    );
}
