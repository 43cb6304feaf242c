#![cfg(feature = "ggrs")]
//! Two OS processes play a scripted match as a GGRS peer-to-peer session over UDP on
//! 127.0.0.1, with desync detection on (the library's session builder, every frame), and
//! must end on the same confirmed state: the state of a plain run of the same inputs. Peers
//! of different settings must see a desync reported at the first frame compared.
//!
//! The test binary is its own peer: a test re-executes the binary twice, running only
//! itself, with `CRATERFIELD_GGRS_PEER` telling each child its player handle, its port,
//! the other's port, the frames to play and the script's seed. A child prints
//! `FINAL <tick> <hash>` (the state hash at tick `<tick>` once every input before it is
//! confirmed), `STATS ...`, `DESYNC ...` for every desync GGRS reports and
//! `FIRST_DESYNC <frame> <since>` for the earliest.

mod common;
use common::scripted_input;

use std::io::Read;
use std::net::UdpSocket;
use std::process::{Child, Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use craterfield::field2d::Level;
use craterfield::net::rollback::{
    DESYNC_INTERVAL, DesyncMonitor, P2PSession, Request, handle_request, session_builder,
};
use craterfield::sim::{Input, Settings, World};
use ggrs::{GgrsError, GgrsEvent, GgrsRequest, PlayerType, SessionState, UdpNonBlockingSocket};

const PEER_ENV: &str = "CRATERFIELD_GGRS_PEER";
/// Frames (ticks) of scripted play; the match is judged on the state at this tick.
const FRAMES: u32 = 600;
/// The peers run faster than real time: a frame every 2 ms.
const FPS: u32 = 500;

/// A child's part in a match.
#[derive(Clone, Copy, Debug)]
struct Peer {
    handle: usize,
    local_port: u16,
    remote_port: u16,
    frames: u32,
    seed: u64,
    /// The desync test: peer 1 plays with other settings than peer 0, and desyncs are
    /// reported rather than fatal.
    desync_test: bool,
}

impl Peer {
    fn to_env(self) -> String {
        format!(
            "{} {} {} {} {} {}",
            self.handle,
            self.local_port,
            self.remote_port,
            self.frames,
            self.seed,
            u8::from(self.desync_test)
        )
    }

    fn from_env() -> Option<Peer> {
        let text = std::env::var(PEER_ENV).ok()?;
        let f: Vec<u64> = text
            .split_whitespace()
            .map(|w| {
                w.parse()
                    .unwrap_or_else(|_| panic!("bad {PEER_ENV}: {text}"))
            })
            .collect();
        assert_eq!(f.len(), 6, "bad {PEER_ENV}: {text}");
        Some(Peer {
            handle: f[0] as usize,
            local_port: f[1] as u16,
            remote_port: f[2] as u16,
            frames: f[3] as u32,
            seed: f[4],
            desync_test: f[5] != 0,
        })
    }
}

fn settings(perturb: bool) -> Settings {
    let mut s = Settings::default();
    s.shell.cooldown_ticks = 3;
    s.dirt.cooldown_ticks = 4;
    // Shells still hurt, but nobody dies: every player keeps firing all match long.
    s.vehicle.health = 1_000_000;
    if perturb {
        s.wind[0] = -s.wind[0] - 256;
    }
    s
}

/// Under CI (shared, slow machines) every time bound is doubled.
fn time_scale() -> u32 {
    if std::env::var_os("CI").is_some() {
        2
    } else {
        1
    }
}

// ---------------------------------------------------------------------------------------
// The child: one peer.

fn bind(port: u16) -> UdpNonBlockingSocket {
    let mut last = None;
    for _ in 0..100 {
        match UdpNonBlockingSocket::bind_to_port(port) {
            Ok(socket) => return socket,
            Err(e) => last = Some(e),
        }
        thread::sleep(Duration::from_millis(20));
    }
    panic!("cannot bind UDP port {port}: {last:?}");
}

struct Outcome {
    hash: u64,
    rollbacks: u64,
    resimulated: u64,
    skipped: u64,
    desyncs: Vec<String>,
    monitor: DesyncMonitor,
}

/// Drains the session's events: returns the frames GGRS recommends skipping, records
/// desyncs, and fails on a disconnect.
fn drain_events(
    session: &mut P2PSession,
    desyncs: &mut Vec<String>,
    monitor: &mut DesyncMonitor,
    strict: bool,
) -> u32 {
    let mut skip = 0;
    for event in session.events() {
        monitor.observe(&event);
        match event {
            GgrsEvent::WaitRecommendation { skip_frames } => skip += skip_frames,
            GgrsEvent::DesyncDetected {
                frame,
                local_checksum,
                remote_checksum,
                ..
            } => {
                let line = format!("DESYNC {frame} {local_checksum:016x} {remote_checksum:016x}");
                assert!(!strict, "{line}");
                desyncs.push(line);
            }
            GgrsEvent::Disconnected { addr } => panic!("peer {addr} disconnected"),
            GgrsEvent::NetworkInterrupted { addr, .. } => {
                eprintln!("network to {addr} interrupted");
            }
            GgrsEvent::NetworkResumed { addr } => eprintln!("network to {addr} resumed"),
            GgrsEvent::Synchronizing { .. } | GgrsEvent::Synchronized { .. } => {}
        }
    }
    skip
}

fn play(peer: Peer) -> Outcome {
    let scale = time_scale();
    let strict = !peer.desync_test;
    let perturb = peer.desync_test && peer.handle == 1;
    let remote = std::net::SocketAddr::from(([127, 0, 0, 1], peer.remote_port));
    let mut session = session_builder()
        .with_num_players(2)
        .unwrap()
        .with_fps(FPS as usize)
        .unwrap()
        .with_input_delay(0)
        .with_max_prediction_window(8)
        .with_disconnect_timeout(Duration::from_secs(10 * u64::from(scale)))
        .with_disconnect_notify_delay(Duration::from_secs(2))
        .add_player(PlayerType::Local, peer.handle)
        .unwrap()
        .add_player(PlayerType::Remote(remote), 1 - peer.handle)
        .unwrap()
        .start_p2p_session(bind(peer.local_port))
        .unwrap();

    let mut desyncs = Vec::new();
    let mut monitor = DesyncMonitor::new(DESYNC_INTERVAL);
    let sync_deadline = Instant::now() + Duration::from_secs(15 * u64::from(scale));
    while session.current_state() != SessionState::Running {
        assert!(
            Instant::now() < sync_deadline,
            "peer {} never synchronized with port {}",
            peer.handle,
            peer.remote_port
        );
        session.poll_remote_clients();
        drain_events(&mut session, &mut desyncs, &mut monitor, strict);
        thread::sleep(Duration::from_millis(1));
    }

    let mut world = World::new(&Level::default_level(), settings(perturb), 2).unwrap();
    let target = peer.frames;
    let mut hash_at_target = None;
    let (mut rollbacks, mut resimulated, mut skipped) = (0u64, 0u64, 0u64);
    let mut skip = 0u32;
    let period = Duration::from_micros(1_000_000 / u64::from(FPS));
    let deadline = Instant::now() + Duration::from_secs(30 * u64::from(scale));
    let mut next_frame = Instant::now();
    loop {
        assert!(
            Instant::now() < deadline,
            "peer {}: the match did not end in time (frame {}, confirmed {})",
            peer.handle,
            session.current_frame(),
            session.confirmed_frame()
        );
        let now = Instant::now();
        if next_frame > now {
            thread::sleep(next_frame - now);
        }
        next_frame = (next_frame + period).max(Instant::now());

        skip += drain_events(&mut session, &mut desyncs, &mut monitor, strict);
        if skip > 0 {
            // GGRS recommends letting the other peer catch up.
            skip -= 1;
            skipped += 1;
            session.poll_remote_clients();
            continue;
        }

        let frame = session.current_frame() as u32;
        let input = if frame < target {
            scripted_input(peer.seed, peer.handle, frame)
        } else {
            Input::default()
        };
        session.add_local_input(peer.handle, input).unwrap();
        let requests: Vec<Request> = match session.advance_frame() {
            Ok(requests) => requests,
            Err(GgrsError::PredictionThreshold) => continue,
            Err(e) => panic!("peer {}: advance_frame: {e}", peer.handle),
        };
        let mut rolled_back = false;
        for request in requests {
            let advance = matches!(request, GgrsRequest::AdvanceFrame { .. });
            if matches!(request, GgrsRequest::LoadGameState { .. }) {
                rollbacks += 1;
                rolled_back = true;
            }
            if advance && rolled_back {
                resimulated += 1;
            }
            handle_request(&mut world, request).unwrap();
            // The last (re)simulation of the target tick is the one on confirmed inputs
            // once they all are.
            if advance && world.tick() == target {
                hash_at_target = Some(world.state_hash());
            }
        }
        // advance_frame polled the network and then rolled back for every input it
        // received: once the inputs of every tick before the target are confirmed, the
        // state at the target is final.
        if hash_at_target.is_some() && session.confirmed_frame() >= target as i32 - 1 {
            break;
        }
    }

    // Let the other peer receive (and acknowledge) everything it still needs from us.
    let linger = Instant::now() + Duration::from_secs(3 * u64::from(scale));
    let remote_handle = 1 - peer.handle;
    while Instant::now() < linger {
        session.poll_remote_clients();
        drain_events(&mut session, &mut desyncs, &mut monitor, strict);
        let acknowledged = session
            .network_stats(remote_handle)
            .is_ok_and(|stats| stats.send_queue_len == 0);
        if acknowledged {
            break;
        }
        thread::sleep(Duration::from_millis(1));
    }

    Outcome {
        hash: hash_at_target.unwrap(),
        rollbacks,
        resimulated,
        skipped,
        desyncs,
        monitor,
    }
}

fn run_child(peer: Peer) {
    let outcome = play(peer);
    // The test harness has printed `test <name> ... ` without a line break.
    println!();
    for line in &outcome.desyncs {
        println!("{line}");
    }
    if let Some(first) = outcome.monitor.first() {
        println!("FIRST_DESYNC {} {}", first.frame, first.since);
    }
    println!(
        "STATS {} {} {}",
        outcome.rollbacks, outcome.resimulated, outcome.skipped
    );
    println!("FINAL {} {:016x}", peer.frames, outcome.hash);
}

// ---------------------------------------------------------------------------------------
// The parent: two children.

/// Kills and reaps the child if the test fails before it ended.
struct ChildGuard(Option<Child>);

impl Drop for ChildGuard {
    fn drop(&mut self) {
        if let Some(child) = self.0.as_mut() {
            if let Ok(None) = child.try_wait() {
                let _ = child.kill();
            }
            let _ = child.wait();
        }
    }
}

struct Report {
    status: String,
    success: bool,
    stdout: String,
    stderr: String,
}

impl Report {
    fn lines(&self, tag: &str) -> Vec<Vec<&str>> {
        self.stdout
            .lines()
            .filter_map(|l| l.find(tag).map(|at| &l[at + tag.len()..]))
            .map(|rest| rest.split_whitespace().collect())
            .collect()
    }

    fn final_state(&self) -> (u32, u64) {
        let finals = self.lines("FINAL ");
        assert_eq!(finals.len(), 1, "{self}");
        (
            finals[0][0].parse().unwrap(),
            u64::from_str_radix(finals[0][1], 16).unwrap(),
        )
    }

    fn stats(&self) -> [u64; 3] {
        let stats = self.lines("STATS ");
        assert_eq!(stats.len(), 1, "{self}");
        let n: Vec<u64> = stats[0].iter().map(|w| w.parse().unwrap()).collect();
        [n[0], n[1], n[2]]
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "peer exited with {}\n--- stdout\n{}\n--- stderr\n{}",
            self.status, self.stdout, self.stderr
        )
    }
}

/// Two UDP ports free on 127.0.0.1 a moment ago (the children retry if one was taken).
fn free_ports() -> [u16; 2] {
    let a = UdpSocket::bind("127.0.0.1:0").unwrap();
    let b = UdpSocket::bind("127.0.0.1:0").unwrap();
    [
        a.local_addr().unwrap().port(),
        b.local_addr().unwrap().port(),
    ]
}

fn pipe_reader(pipe: Option<impl Read + Send + 'static>) -> thread::JoinHandle<String> {
    thread::spawn(move || {
        let mut text = String::new();
        if let Some(mut pipe) = pipe {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            text = String::from_utf8_lossy(&bytes).into_owned();
        }
        text
    })
}

/// Runs this test's binary twice as the two peers of a match; returns their reports.
fn run_match(test_name: &str, frames: u32, seed: u64, desync_test: bool) -> [Report; 2] {
    let ports = free_ports();
    let exe = std::env::current_exe().unwrap();
    let mut guards = Vec::new();
    let mut readers = Vec::new();
    for handle in 0..2 {
        let peer = Peer {
            handle,
            local_port: ports[handle],
            remote_port: ports[1 - handle],
            frames,
            seed,
            desync_test,
        };
        let mut child = Command::new(&exe)
            .args(["--exact", test_name, "--nocapture", "--test-threads=1"])
            .env(PEER_ENV, peer.to_env())
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        readers.push((
            pipe_reader(child.stdout.take()),
            pipe_reader(child.stderr.take()),
        ));
        guards.push(ChildGuard(Some(child)));
    }

    let deadline = Instant::now() + Duration::from_secs(60 * u64::from(time_scale()));
    let mut statuses = [None, None];
    while statuses.iter().any(Option::is_none) {
        for (guard, status) in guards.iter_mut().zip(&mut statuses) {
            if status.is_none() {
                *status = guard.0.as_mut().unwrap().try_wait().unwrap();
            }
        }
        if Instant::now() > deadline {
            // Dropping the guards kills and reaps both children.
            drop(guards);
            let out: Vec<String> = readers
                .into_iter()
                .map(|(o, e)| format!("{}\n{}", o.join().unwrap(), e.join().unwrap()))
                .collect();
            panic!("the peers did not finish in time:\n{}", out.join("\n---\n"));
        }
        thread::sleep(Duration::from_millis(10));
    }
    let mut reports = readers.into_iter().zip(statuses).map(|((o, e), status)| {
        let status = status.unwrap();
        Report {
            status: status.to_string(),
            success: status.success(),
            stdout: o.join().unwrap(),
            stderr: e.join().unwrap(),
        }
    });
    [reports.next().unwrap(), reports.next().unwrap()]
}

/// The state hash at tick `frames` of the scripted match played without any network.
fn plain_hash(frames: u32, seed: u64) -> u64 {
    let mut world = World::new(&Level::default_level(), settings(false), 2).unwrap();
    for frame in 0..frames {
        let inputs = [
            scripted_input(seed, 0, frame),
            scripted_input(seed, 1, frame),
        ];
        world.step(&inputs).unwrap();
    }
    assert!(
        world.terrain().events().len() >= frames as usize / 10,
        "the scripted match is too quiet: {} explosions",
        world.terrain().events().len()
    );
    world.state_hash()
}

#[test]
fn two_processes_agree_over_udp() {
    if let Some(peer) = Peer::from_env() {
        run_child(peer);
        return;
    }
    let seed = 0x00c0_ffee;
    let reports = run_match("two_processes_agree_over_udp", FRAMES, seed, false);
    for report in &reports {
        assert!(report.success, "{report}");
        assert!(report.lines("DESYNC ").is_empty(), "{report}");
    }
    let (a, b) = (reports[0].final_state(), reports[1].final_state());
    assert_eq!(a.0, FRAMES);
    assert_eq!(
        a, b,
        "the peers ended apart:\n{}\n{}",
        reports[0], reports[1]
    );
    assert_eq!(
        a.1,
        plain_hash(FRAMES, seed),
        "the peers agree, but not with a plain run of the same inputs"
    );
    let [ra, sa, ka] = reports[0].stats();
    let [rb, sb, kb] = reports[1].stats();
    eprintln!("rollbacks {ra} + {rb}, frames resimulated {sa} + {sb}, frames skipped {ka} + {kb}");
    // Not vacuous: the remote inputs change every frame, so the peers mispredicted them.
    assert!(ra + rb > 0, "no rollback happened");
}

#[test]
fn desync_between_processes_is_detected() {
    if let Some(peer) = Peer::from_env() {
        run_child(peer);
        return;
    }
    // One peer plays with another wind: GGRS must see the checksums differ.
    let reports = run_match("desync_between_processes_is_detected", 200, 0xbad, true);
    for report in &reports {
        assert!(report.success, "{report}");
    }
    let desyncs = reports[0].lines("DESYNC ").len() + reports[1].lines("DESYNC ").len();
    assert!(
        desyncs > 0,
        "no desync detected:\n{}\n{}",
        reports[0],
        reports[1]
    );
    eprintln!("desyncs reported: {desyncs}");
    // The setups differ (the state hash covers the settings), so the very first frame
    // compared is the first divergent one, and the report names it.
    for report in &reports {
        let first = report.lines("FIRST_DESYNC ");
        if let Some(f) = first.first() {
            assert_eq!(f, &["1", "1"], "{report}");
        }
    }
    assert!(
        reports.iter().any(|r| !r.lines("FIRST_DESYNC ").is_empty()),
        "no first desync reported"
    );
    assert_ne!(reports[0].final_state(), reports[1].final_state());
}
