//! Rollback netcode: the simulation as a [GGRS](ggrs) game.
//!
//! GGRS runs a match as a sequence of frames and asks the game, through
//! [`GgrsRequest`]s, to save the state of a frame, to load a saved one, and to advance by
//! one frame with a given set of inputs. The simulation maps onto that one to one:
//!
//! | GGRS | simulation |
//! |---|---|
//! | frame `f` | the world at tick `f` (a session starts on a fresh [`World`], tick 0; after a resync, at tick `origin + f`) |
//! | `Config::Input` | [`Input`], one per player and tick (a peer's invalid input acts as no input: the simulation sanitizes every input) |
//! | `Config::State` | [`Snapshot`] from [`World::snapshot`] |
//! | `SaveGameState` | [`World::snapshot`], with [`World::state_hash`] as the checksum |
//! | `LoadGameState` | [`World::restore`] |
//! | `AdvanceFrame` | [`World::step`], a disconnected player's input being [`Input::default`] |
//!
//! [`handle_requests`] fulfils a batch of requests in order, checking that the world's
//! tick is the frame GGRS names for every save and load: a skipped or reordered request is
//! an error rather than a silent desync.
//!
//! Inputs are predicted with [`ggrs::PredictRepeatLast`]: [`Input`] holds the state of
//! the controls (buttons act on the tick they go down, so a held button repeats nothing),
//! which is what repeating the last input predicts best.
//!
//! The checksum GGRS compares between peers (desync detection) and across rollbacks (the
//! sync test) is the world's 64-bit state hash: the tick, every body (vehicles with their
//! controls' state, projectiles, debris) and the terrain's event log, the same on every
//! machine.
//!
//! # Desyncs
//!
//! Peers that stop agreeing (a bug, a modified client, corrupted memory) are caught by
//! comparing state hashes: [`session_builder`] starts every session with GGRS's desync
//! detection on, comparing the checksum of every confirmed frame
//! ([`DESYNC_INTERVAL`]), and a [`DesyncMonitor`] fed the session's events keeps a
//! [`DesyncReport`] of the first divergent frame. Recovery is a full-state resync:
//!
//! 1. the peers stop the session (every peer sees the report);
//! 2. the peer the match names as the authority (say handle 0) encodes
//!    [`World::state`] of its last confirmed frame with
//!    [`encode_state`](crate::state::encode_state) and sends it;
//! 3. the other decodes it and calls [`World::resync`], which refuses a state of another
//!    match or one altered on the way, changing nothing;
//! 4. both start a new session whose frame 0 is the resynced tick, fulfilling its requests
//!    with [`handle_requests_from`] and that tick as the origin.
//!
//! GGRS loads states at most its prediction window back (`max_prediction`, 8 frames
//! unless the session builder sets another), and the world restores snapshots up to
//! [`Settings::rollback_ticks`](craterfield_sim::Settings::rollback_ticks) back (128 by
//! default); the prediction window must stay below the latter.

use std::net::SocketAddr;

use ggrs::{Frame, GgrsError, GgrsRequest, InputStatus};
use thiserror::Error;

use craterfield_sim::{Input, MAX_PLAYERS, SimError, Snapshot, World};

/// Frames between two checksum comparisons in sessions from [`session_builder`]: every
/// frame, so the first report names the first divergent frame (a checksum costs GGRS a
/// few bytes per frame).
pub const DESYNC_INTERVAL: u32 = 1;

/// A session builder with desync detection on ([`DESYNC_INTERVAL`]); everything else is
/// GGRS's default, for the caller to set (players, addresses, prediction window).
pub fn session_builder() -> SessionBuilder {
    SessionBuilder::new().with_desync_detection_mode(ggrs::DesyncDetection::On {
        interval: DESYNC_INTERVAL,
    })
}

/// A desync GGRS reported: the peers' state hashes differ at `frame`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DesyncReport {
    /// The frame whose checksums differ.
    pub frame: Frame,
    /// The earliest frame that may be the first divergent one: the frame after the
    /// previous comparison (the same as `frame` at [`DESYNC_INTERVAL`] 1).
    pub since: Frame,
    /// This peer's state hash at `frame`.
    pub local: u64,
    /// The remote peer's.
    pub remote: u64,
    /// The remote peer.
    pub addr: SocketAddr,
}

/// Watches a session's events for desyncs and keeps the first one (see the
/// [module documentation](self)).
#[derive(Clone, Debug, Default)]
pub struct DesyncMonitor {
    first: Option<DesyncReport>,
    count: u64,
    interval: u32,
}

impl DesyncMonitor {
    /// A monitor for a session that compares checksums every `interval` frames.
    pub fn new(interval: u32) -> DesyncMonitor {
        DesyncMonitor {
            first: None,
            count: 0,
            interval: interval.max(1),
        }
    }

    /// Looks at one session event; returns its report when it is a desync.
    pub fn observe(&mut self, event: &ggrs::GgrsEvent<GgrsConfig>) -> Option<DesyncReport> {
        let ggrs::GgrsEvent::DesyncDetected {
            frame,
            local_checksum,
            remote_checksum,
            addr,
        } = *event
        else {
            return None;
        };
        let report = DesyncReport {
            frame,
            since: (frame - self.interval as i32 + 1).max(0),
            local: local_checksum as u64,
            remote: remote_checksum as u64,
            addr,
        };
        self.count += 1;
        if self.first.is_none_or(|f| frame < f.frame) {
            self.first = Some(report);
        }
        Some(report)
    }

    /// The earliest divergent frame reported so far.
    pub fn first(&self) -> Option<DesyncReport> {
        self.first
    }

    /// Desyncs reported so far.
    pub fn count(&self) -> u64 {
        self.count
    }
}

/// The GGRS parameters of a match: the simulation's [`Input`] and [`Snapshot`], peers
/// addressed by UDP socket address.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct GgrsConfig;

impl ggrs::Config for GgrsConfig {
    type Input = Input;
    type InputPredictor = ggrs::PredictRepeatLast;
    type State = Snapshot;
    type Address = SocketAddr;
}

/// A GGRS request for the simulation.
pub type Request = GgrsRequest<GgrsConfig>;

/// A peer-to-peer GGRS session of the simulation.
pub type P2PSession = ggrs::P2PSession<GgrsConfig>;

/// A GGRS sync-test session of the simulation (rolls back every frame and compares
/// checksums: a local determinism check).
pub type SyncTestSession = ggrs::SyncTestSession<GgrsConfig>;

/// A GGRS session builder for the simulation.
pub type SessionBuilder = ggrs::SessionBuilder<GgrsConfig>;

/// Why a GGRS request could not be fulfilled (or, for [`SessionError::Ggrs`], why a
/// session call failed).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SessionError {
    /// GGRS asked to load a frame whose cell holds no state.
    #[error("GGRS asked to load frame {frame}, but no state was saved for it")]
    EmptyState {
        /// The frame GGRS named.
        frame: Frame,
    },
    /// The world (for a save) or the saved snapshot (for a load) is not at the tick GGRS
    /// names: a request was skipped, reordered or fulfilled on another world, or the
    /// session did not start on a fresh world.
    #[error("GGRS request for frame {frame}, but the state is at tick {tick}")]
    FrameMismatch {
        /// The frame GGRS named.
        frame: Frame,
        /// The world's tick.
        tick: u32,
    },
    /// GGRS passed inputs for more players than a match can have.
    #[error("GGRS passed inputs for {count} players (at most {MAX_PLAYERS})")]
    TooManyPlayers {
        /// The number of inputs.
        count: usize,
    },
    /// The simulation rejected a step or a restore.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A GGRS session call failed.
    #[error("GGRS: {0}")]
    Ggrs(#[from] GgrsError),
}

/// The checksum GGRS stores with a saved state: the world's state hash.
pub fn checksum(world: &World) -> u128 {
    u128::from(world.state_hash())
}

fn check_frame(world: &World, origin: u32, frame: Frame) -> Result<(), SessionError> {
    if i64::from(world.tick()) == i64::from(origin) + i64::from(frame) {
        Ok(())
    } else {
        Err(SessionError::FrameMismatch {
            frame,
            tick: world.tick(),
        })
    }
}

/// Fulfils one GGRS request on `world`.
///
/// * `SaveGameState`: stores a [`Snapshot`] and the [`checksum`] in the cell.
/// * `LoadGameState`: restores the cell's snapshot.
/// * `AdvanceFrame`: steps the world once with the given inputs; a disconnected player's
///   input is [`Input::default`] whatever GGRS passed.
///
/// Saves check that the world is at the tick GGRS names, loads that the snapshot is. A
/// request that fails changes nothing.
pub fn handle_request(world: &mut World, request: Request) -> Result<(), SessionError> {
    handle_request_from(world, 0, request)
}

/// [`handle_request`] for a session whose frame 0 is the world's tick `origin` (a session
/// started after a [`World::resync`]).
pub fn handle_request_from(
    world: &mut World,
    origin: u32,
    request: Request,
) -> Result<(), SessionError> {
    match request {
        GgrsRequest::SaveGameState { cell, frame } => {
            check_frame(world, origin, frame)?;
            cell.save(frame, Some(world.snapshot()), Some(checksum(world)));
        }
        GgrsRequest::LoadGameState { cell, frame } => {
            let snapshot = cell.data().ok_or(SessionError::EmptyState { frame })?;
            // Checked before restoring: a refused load leaves the world as it was.
            if i64::from(snapshot.tick()) != i64::from(origin) + i64::from(frame) {
                return Err(SessionError::FrameMismatch {
                    frame,
                    tick: snapshot.tick(),
                });
            }
            world.restore(&snapshot)?;
        }
        GgrsRequest::AdvanceFrame { inputs } => {
            if inputs.len() > MAX_PLAYERS {
                return Err(SessionError::TooManyPlayers {
                    count: inputs.len(),
                });
            }
            let mut step = [Input::default(); MAX_PLAYERS];
            for (slot, &(input, status)) in step.iter_mut().zip(&inputs) {
                *slot = match status {
                    InputStatus::Disconnected => Input::default(),
                    InputStatus::Confirmed | InputStatus::Predicted => input,
                };
            }
            world.step(&step[..inputs.len()])?;
        }
    }
    Ok(())
}

/// Fulfils GGRS requests on `world`, in order (as GGRS requires), stopping at the first
/// that fails. See [`handle_request`].
pub fn handle_requests(world: &mut World, requests: Vec<Request>) -> Result<(), SessionError> {
    handle_requests_from(world, 0, requests)
}

/// [`handle_requests`] for a session whose frame 0 is the world's tick `origin`.
pub fn handle_requests_from(
    world: &mut World,
    origin: u32,
    requests: Vec<Request>,
) -> Result<(), SessionError> {
    for request in requests {
        handle_request_from(world, origin, request)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield_field::Level;
    use craterfield_sim::Settings;
    use craterfield_sim::buttons;
    use ggrs::GameStateCell;

    fn world(players: usize) -> World {
        World::new(&Level::default_level(), Settings::default(), players).unwrap()
    }

    fn advance(inputs: &[(Input, InputStatus)]) -> Request {
        GgrsRequest::AdvanceFrame {
            inputs: inputs.to_vec(),
        }
    }

    #[test]
    fn save_advance_load_returns_to_the_saved_state() {
        let mut w = world(2);
        let fire = Input {
            aim: Input::aim_from_degrees(60.0),
            buttons: buttons::FIRE,
            drive: 40,
            power: 200,
            weapon: 0,
        };
        let cell = GameStateCell::<Snapshot>::default();
        handle_requests(
            &mut w,
            vec![
                advance(&[(Input::default(), InputStatus::Confirmed); 2]),
                GgrsRequest::SaveGameState {
                    cell: cell.clone(),
                    frame: 1,
                },
            ],
        )
        .unwrap();
        let saved = (w.tick(), w.state_hash());
        for _ in 0..5 {
            handle_request(
                &mut w,
                advance(&[
                    (fire, InputStatus::Predicted),
                    (Input::default(), InputStatus::Confirmed),
                ]),
            )
            .unwrap();
        }
        assert_eq!(w.tick(), 6);
        handle_request(
            &mut w,
            GgrsRequest::LoadGameState {
                cell: cell.clone(),
                frame: 1,
            },
        )
        .unwrap();
        assert_eq!((w.tick(), w.state_hash()), saved);
        assert_eq!(cell.load().map(|_| ()), Some(()));
    }

    #[test]
    fn disconnected_players_do_nothing() {
        let fire = Input {
            aim: Input::aim_from_degrees(45.0),
            buttons: buttons::FIRE,
            drive: 100,
            power: 255,
            weapon: 1,
        };
        let mut a = world(2);
        let mut b = world(2);
        for _ in 0..20 {
            handle_request(
                &mut a,
                advance(&[
                    (fire, InputStatus::Confirmed),
                    (fire, InputStatus::Disconnected),
                ]),
            )
            .unwrap();
            b.step(&[fire, Input::default()]).unwrap();
        }
        assert_eq!(a.state_hash(), b.state_hash());
    }

    #[test]
    fn the_monitor_keeps_the_earliest_desync() {
        let addr: SocketAddr = "127.0.0.1:7000".parse().unwrap();
        let desync = |frame| ggrs::GgrsEvent::DesyncDetected {
            frame,
            local_checksum: 0xaa,
            remote_checksum: 0xbb,
            addr,
        };
        let mut m = DesyncMonitor::new(10);
        assert_eq!(m.observe(&ggrs::GgrsEvent::NetworkResumed { addr }), None);
        assert_eq!(m.first(), None);
        let later = m.observe(&desync(40)).unwrap();
        assert_eq!((later.frame, later.since), (40, 31));
        m.observe(&desync(20));
        m.observe(&desync(30));
        let first = m.first().unwrap();
        assert_eq!(
            (first.frame, first.since, first.local, first.remote),
            (20, 11, 0xaa, 0xbb)
        );
        assert_eq!(m.count(), 3);
        // At the default interval the report names the divergent frame itself.
        let mut every = DesyncMonitor::new(DESYNC_INTERVAL);
        assert_eq!(every.observe(&desync(7)).map(|r| r.since), Some(7));
    }

    #[test]
    fn sessions_resynced_at_a_tick_count_frames_from_it() {
        let mut w = world(2);
        for _ in 0..5 {
            w.step(&[Input::default(); 2]).unwrap();
        }
        let cell = GameStateCell::<Snapshot>::default();
        let save = |frame| GgrsRequest::SaveGameState {
            cell: cell.clone(),
            frame,
        };
        // Frame 0 of a session started at tick 5 is tick 5, not tick 0.
        assert!(handle_request(&mut w, save(0)).is_err());
        handle_request_from(&mut w, 5, save(0)).unwrap();
        handle_request_from(
            &mut w,
            5,
            advance(&[(Input::default(), InputStatus::Confirmed); 2]),
        )
        .unwrap();
        handle_request_from(
            &mut w,
            5,
            GgrsRequest::LoadGameState {
                cell: cell.clone(),
                frame: 0,
            },
        )
        .unwrap();
        assert_eq!(w.tick(), 5);
    }

    #[test]
    fn bad_requests_are_errors() {
        let mut w = world(2);
        let cell = GameStateCell::<Snapshot>::default();
        let err = handle_request(
            &mut w,
            GgrsRequest::SaveGameState {
                cell: cell.clone(),
                frame: 3,
            },
        )
        .unwrap_err();
        assert!(matches!(
            err,
            SessionError::FrameMismatch { frame: 3, tick: 0 }
        ));
        // GGRS stamps a cell's frame when it is saved; a fresh cell holds nothing.
        let err =
            handle_request(&mut w, GgrsRequest::LoadGameState { cell, frame: 0 }).unwrap_err();
        assert!(matches!(err, SessionError::EmptyState { frame: 0 }));
        // A load whose snapshot is not of the frame GGRS names changes nothing.
        let cell = GameStateCell::<Snapshot>::default();
        handle_request(
            &mut w,
            GgrsRequest::SaveGameState {
                cell: cell.clone(),
                frame: 0,
            },
        )
        .unwrap();
        w.step(&[Input::default(); 2]).unwrap();
        let before = (w.tick(), w.state_hash());
        let err =
            handle_request(&mut w, GgrsRequest::LoadGameState { cell, frame: 1 }).unwrap_err();
        assert!(matches!(
            err,
            SessionError::FrameMismatch { frame: 1, tick: 0 }
        ));
        assert_eq!((w.tick(), w.state_hash()), before);
        let err = handle_request(
            &mut w,
            advance(&[(Input::default(), InputStatus::Confirmed); MAX_PLAYERS + 1]),
        )
        .unwrap_err();
        assert!(err.to_string().contains("players"), "{err}");
    }
}
