//! [`Session`]: the sandbox's match. The human's vehicle and the scripted opponents step on
//! the deterministic simulation at its fixed tick; brush edits are queued and applied at the
//! next tick boundary through [`World::apply_event`], the way an authoritative server's
//! events arrive; everything is recorded on a [`Timeline`] that can be saved, loaded and
//! scrubbed.

use std::path::Path;
use web_time::Instant;

use craterfield::field2d::{Event, Level};
use craterfield::net::DecodeLimits;
use craterfield::net::replay::{self, Replay};
use craterfield::sim::{Body, Input, Settings, World, level_hash};

use super::ai::opponent_input;
use super::timeline::Timeline;

/// Players in a sandbox match: the human (player 0) and scripted opponents.
pub const PLAYERS: usize = 4;

/// Most ticks one frame may run to catch up (a slow frame does not snowball).
const MAX_CATCH_UP: u32 = 8;

/// Whether the session records what happens or plays back its timeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Inputs and edits are simulated and recorded.
    Live,
    /// The timeline is played back (or held still, paused).
    Playback {
        /// Whether ticks advance.
        playing: bool,
    },
}

/// The result of verifying a loaded replay, for the panel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verified {
    /// `replay verify` passed: ticks re-simulated and hashes compared.
    Passed {
        /// Ticks re-simulated.
        ticks: u32,
        /// Stored hashes compared.
        hashes: usize,
    },
    /// It failed, with the reason.
    Failed(String),
}

/// One sandbox match.
pub struct Session {
    level: Level,
    world: World,
    timeline: Timeline,
    mode: Mode,
    pending: Vec<Event>,
    previous: Vec<Body>,
    accumulator: f64,
    verified: Option<Verified>,
    divergence: Option<(u32, u64)>,
    tick_ms: Vec<f64>,
}

impl Session {
    /// A new live match on `level`.
    pub fn new(level: Level) -> Result<Session, String> {
        let world = World::new(&level, Settings::default(), PLAYERS)
            .map_err(|e| format!("the level cannot host a match: {e}"))?;
        let timeline = Timeline::new(&world, level_hash(&level));
        Ok(Session {
            previous: world.bodies().to_vec(),
            level,
            world,
            timeline,
            mode: Mode::Live,
            pending: Vec::new(),
            accumulator: 0.0,
            verified: None,
            divergence: None,
            tick_ms: Vec::new(),
        })
    }

    /// The level.
    pub fn level(&self) -> &Level {
        &self.level
    }

    /// The world now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The recording.
    pub fn timeline(&self) -> &Timeline {
        &self.timeline
    }

    /// Live or playback.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The verification of the last loaded replay.
    pub fn verified(&self) -> Option<&Verified> {
        self.verified.as_ref()
    }

    /// The first tick where playback's hash differed from the recording's, if any.
    pub fn divergence(&self) -> Option<(u32, u64)> {
        self.divergence
    }

    /// CPU time of recent ticks, milliseconds (cleared by [`Session::take_tick_ms`]).
    pub fn take_tick_ms(&mut self) -> Vec<f64> {
        std::mem::take(&mut self.tick_ms)
    }

    /// Edits waiting for the next tick.
    pub fn pending_edits(&self) -> usize {
        self.pending.len()
    }

    /// Queues a brush edit for the next tick of a live match. Checked now, so a bad one is
    /// refused with its reason and never half-applied.
    pub fn queue_edit(&mut self, e: Event) -> Result<(), String> {
        if self.mode != Mode::Live {
            return Err("edits go into a live match: press Go live to continue from here".into());
        }
        let e = e.at_tick(self.world.tick());
        self.world
            .terrain()
            .validate_event(&e)
            .map_err(|err| err.to_string())?;
        self.pending.push(e);
        Ok(())
    }

    /// Runs the ticks `seconds` of real time owe (live, or playing back), with `human` as
    /// player 0's input. Returns how many ran.
    pub fn update(&mut self, seconds: f64, human: Input) -> Result<u32, String> {
        let dt = f64::from(self.world.settings().dt());
        let running = matches!(self.mode, Mode::Live | Mode::Playback { playing: true });
        if !running {
            self.accumulator = 0.0;
            return Ok(0);
        }
        self.accumulator = (self.accumulator + seconds.max(0.0)).min(dt * f64::from(MAX_CATCH_UP));
        let mut ran = 0;
        while self.accumulator >= dt {
            self.accumulator -= dt;
            if !self.tick(human)? {
                break;
            }
            ran += 1;
        }
        Ok(ran)
    }

    /// One tick: live or playback. `false` when playback reached the end.
    pub fn tick(&mut self, human: Input) -> Result<bool, String> {
        self.previous = self.world.bodies().to_vec();
        let started = Instant::now();
        let ran = match self.mode {
            Mode::Live => self.tick_live(human).map(|()| true),
            Mode::Playback { .. } => self.tick_playback(),
        };
        self.tick_ms.push(started.elapsed().as_secs_f64() * 1e3);
        ran
    }

    fn tick_live(&mut self, human: Input) -> Result<(), String> {
        let mut applied = Vec::with_capacity(self.pending.len());
        for e in self.pending.drain(..) {
            // Checked when queued, on this same tick.
            if self.world.apply_event(e).is_ok() {
                applied.push(e);
            }
        }
        let mut row = vec![human.sanitized()];
        row.extend((1..PLAYERS as u8).map(|p| opponent_input(&self.world, p)));
        self.world.step(&row).map_err(|e| e.to_string())?;
        self.timeline.push_tick(&applied, &row, &self.world);
        Ok(())
    }

    fn tick_playback(&mut self) -> Result<bool, String> {
        if self.world.tick() >= self.timeline.ticks() {
            self.mode = Mode::Playback { playing: false };
            return Ok(false);
        }
        let d = self.timeline.advance(&mut self.world)?;
        self.divergence = self.divergence.or(d);
        Ok(true)
    }

    /// Fraction of the next tick already elapsed, for drawing between ticks.
    pub fn alpha(&self) -> f32 {
        let dt = f64::from(self.world.settings().dt());
        (self.accumulator / dt).clamp(0.0, 1.0) as f32
    }

    /// Body positions interpolated between the last two ticks.
    pub fn interpolated(&self) -> Vec<(Body, glam::Vec2)> {
        let a = self.alpha();
        self.world
            .bodies()
            .iter()
            .map(|b| {
                let before = self.previous.iter().find(|p| p.id == b.id);
                let pos = before.map_or(b.pos, |p| p.pos.lerp(b.pos, a));
                (*b, pos)
            })
            .collect()
    }

    /// Stops at the current tick for scrubbing (live sessions become playback).
    pub fn pause(&mut self) {
        self.mode = Mode::Playback { playing: false };
        self.pending.clear();
    }

    /// Plays the timeline from the current tick.
    pub fn play(&mut self) {
        self.mode = Mode::Playback { playing: true };
        self.pending.clear();
    }

    /// Goes back to live play from the current tick: what was recorded after it is
    /// dropped.
    pub fn go_live(&mut self) {
        self.timeline.truncate(self.world.tick());
        self.mode = Mode::Live;
        self.divergence = None;
    }

    /// Puts the world at `tick` of the recording (pausing).
    pub fn seek(&mut self, tick: u32) -> Result<(), String> {
        self.pause();
        let d = self.timeline.seek(&mut self.world, tick)?;
        self.divergence = self.divergence.or(d);
        self.previous = self.world.bodies().to_vec();
        Ok(())
    }

    /// The recording as replay file bytes.
    pub fn replay_bytes(&self) -> Result<Vec<u8>, String> {
        self.timeline
            .to_replay()
            .encode()
            .map_err(|e| e.to_string())
    }

    /// Writes the recording to `path`.
    pub fn save_replay(&self, path: &Path) -> Result<(), String> {
        let bytes = self.replay_bytes()?;
        std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Reads a replay file of this level, verifies it (`replay verify`) and switches to
    /// playing it back from tick 0. A file that does not decode changes nothing.
    pub fn load_replay(&mut self, path: &Path) -> Result<(), String> {
        let limit = DecodeLimits::default().max_bytes as u64;
        let bytes = craterfield::files::read(path, limit).map_err(|e| e.to_string())?;
        self.load_replay_bytes(&bytes)
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// [`Session::load_replay`] from bytes.
    pub fn load_replay_bytes(&mut self, bytes: &[u8]) -> Result<(), String> {
        let replay = Replay::decode(bytes).map_err(|e| e.to_string())?;
        replay
            .check_level(level_hash(&self.level))
            .map_err(|e| format!("{e}; load that level first"))?;
        let world = World::new(&self.level, replay.settings, usize::from(replay.players))
            .map_err(|e| e.to_string())?;
        self.verified = Some(match replay::verify(&replay, &self.level) {
            Ok(r) => Verified::Passed {
                ticks: r.ticks,
                hashes: r.hashes_checked,
            },
            Err(e) => Verified::Failed(e.to_string()),
        });
        self.timeline = Timeline::from_replay(&replay, &world);
        self.previous = world.bodies().to_vec();
        self.world = world;
        self.mode = Mode::Playback { playing: false };
        self.pending.clear();
        self.divergence = None;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield::field2d::{DEFAULT_LEVEL_RON, Sdf};
    use glam::Vec2;

    fn live_session_with_edits(ticks: u32) -> Session {
        let mut s = Session::new(Level::default_level()).expect("session");
        let b = s.level().bounds();
        for t in 0..ticks {
            if t % 50 == 10 {
                let x = b.min.x + 300.0 + t as f32 * 5.0;
                let mut y = b.max.y;
                while s.world().terrain().distance(Vec2::new(x, y)) > 0.0 && y > b.min.y {
                    y -= 8.0;
                }
                s.queue_edit(Event::carve(Vec2::new(x, y), 30.0).expect("carve"))
                    .expect("queued");
            }
            let drive = Input {
                drive: 100,
                ..Input::default()
            };
            assert!(s.tick(drive).expect("tick"));
        }
        s
    }

    #[test]
    fn a_live_session_saves_a_replay_that_verifies_and_reloads() {
        let s = live_session_with_edits(300);
        assert_eq!(s.timeline().ticks(), 300);
        assert_eq!(s.timeline().edits().len(), 6);
        let bytes = s.replay_bytes().expect("encodes");
        let replay = Replay::decode(&bytes).expect("decodes");
        let report = replay::verify(&replay, s.level()).expect("verifies");
        assert_eq!(report.final_hash, s.world().state_hash());

        let mut loaded = Session::new(Level::default_level()).expect("session");
        loaded.load_replay_bytes(&bytes).expect("loads");
        assert!(matches!(
            loaded.verified(),
            Some(Verified::Passed { ticks: 300, .. })
        ));
        loaded.play();
        while loaded.tick(Input::default()).expect("plays") {}
        assert_eq!(loaded.world().tick(), 300);
        assert_eq!(loaded.world().state_hash(), s.world().state_hash());
        assert_eq!(loaded.divergence(), None);
    }

    #[test]
    fn seeking_reaches_each_recorded_hash_and_going_live_truncates() {
        let mut s = live_session_with_edits(400);
        let expected: Vec<u64> = (0..=400)
            .map(|t| s.timeline().hash_at(t).expect("hash"))
            .collect();
        for t in [399, 0, 121, 240, 7, 400, 238] {
            s.seek(t).expect("seek");
            assert_eq!(s.world().tick(), t);
            assert_eq!(s.world().state_hash(), expected[t as usize], "tick {t}");
        }
        assert!(
            s.queue_edit(Event::carve(Vec2::new(500.0, 500.0), 20.0).expect("carve"))
                .is_err()
        );
        s.seek(250).expect("seek");
        s.go_live();
        assert_eq!(s.timeline().ticks(), 250);
        assert_eq!(s.timeline().edits().len(), 5);
        s.tick(Input::default()).expect("tick");
        assert_eq!(s.timeline().ticks(), 251);
        let replay = Replay::decode(&s.replay_bytes().expect("encodes")).expect("decodes");
        replay::verify(&replay, s.level()).expect("the truncated and continued match verifies");
    }

    #[test]
    fn a_replay_of_another_level_or_garbage_changes_nothing() {
        let s = live_session_with_edits(60);
        let bytes = s.replay_bytes().expect("encodes");
        // The default level under another name: another level hash.
        let renamed = DEFAULT_LEVEL_RON.replacen("name: \"Default\"", "name: \"Other\"", 1);
        let other_level = Level::from_ron(&renamed).expect("level");
        assert_ne!(level_hash(&other_level), level_hash(s.level()));
        let mut other = Session::new(other_level).expect("session");
        let before = other.world().state_hash();
        let e = other.load_replay_bytes(&bytes).expect_err("another level");
        assert!(e.contains("level"), "{e}");
        assert!(other.load_replay_bytes(&bytes[..bytes.len() / 2]).is_err());
        assert!(other.load_replay_bytes(b"not a replay").is_err());
        assert_eq!(other.world().state_hash(), before);
        assert_eq!(other.mode(), Mode::Live);
    }
}
