//! [`Timeline`]: everything a sandbox session did, tick by tick (inputs, edits, state
//! hashes), with periodic world states so that any tick can be reached again quickly. It
//! is the replay in the making: [`Timeline::to_replay`] writes it as a `.replay`, and a
//! loaded replay becomes a timeline to scrub.

use craterfield::field2d::Event;
use craterfield::net::replay::Replay;
use craterfield::sim::{Input, World, WorldState};

/// Ticks between two kept world states: seeking re-simulates at most this many ticks.
pub const STATE_INTERVAL: u32 = 120;

/// Ticks between two state hashes in a saved replay.
pub const HASH_INTERVAL: u32 = 60;

/// A match's history: the replay being recorded, with a state hash for every tick, and
/// the world states kept for seeking.
#[derive(Clone, Debug)]
pub struct Timeline {
    /// Inputs, edits and `(tick, hash)` pairs (every tick of a live session, the stored
    /// ones of a loaded replay).
    replay: Replay,
    /// `states[i]` is the world at tick `i * STATE_INTERVAL`.
    states: Vec<WorldState>,
}

impl Timeline {
    /// An empty history starting at `world` (tick 0).
    pub fn new(world: &World, level_hash: u64) -> Timeline {
        Timeline {
            replay: Replay {
                level_hash,
                settings: *world.settings(),
                players: world.players() as u8,
                hash_interval: HASH_INTERVAL,
                inputs: Vec::new(),
                hashes: vec![(world.tick(), world.state_hash())],
                edits: Vec::new(),
            },
            states: vec![world.state()],
        }
    }

    /// The history of `replay`, whose first world is `world` (at tick 0).
    pub fn from_replay(replay: &Replay, world: &World) -> Timeline {
        Timeline {
            replay: replay.clone(),
            states: vec![world.state()],
        }
    }

    /// Ticks recorded.
    pub fn ticks(&self) -> u32 {
        self.replay.ticks()
    }

    /// Edits recorded.
    pub fn edits(&self) -> &[Event] {
        &self.replay.edits
    }

    /// The known state hash of `tick`.
    pub fn hash_at(&self, tick: u32) -> Option<u64> {
        self.replay.hash_at(tick)
    }

    /// Records one live tick: the edits applied before the step, the inputs stepped with,
    /// and the world after it.
    pub fn push_tick(&mut self, edits: &[Event], row: &[Input], after: &World) {
        self.replay.edits.extend_from_slice(edits);
        self.replay.inputs.extend_from_slice(row);
        self.replay.hashes.push((after.tick(), after.state_hash()));
        self.keep_state(after);
    }

    fn keep_state(&mut self, world: &World) {
        let tick = world.tick();
        if tick.is_multiple_of(STATE_INTERVAL) && self.states.len() as u32 == tick / STATE_INTERVAL
        {
            self.states.push(world.state());
        }
    }

    /// Forgets everything after `tick` (a live session continues from there).
    pub fn truncate(&mut self, tick: u32) {
        let tick = tick.min(self.ticks());
        let r = &mut self.replay;
        r.inputs.truncate(tick as usize * usize::from(r.players));
        r.edits.truncate(r.edits.partition_point(|e| e.tick < tick));
        r.hashes.truncate(r.hashes.partition_point(|h| h.0 <= tick));
        self.states.truncate((tick / STATE_INTERVAL) as usize + 1);
    }

    /// Advances `world` one recorded tick (its edits, then its step:
    /// [`Replay::advance`]). Returns the stored hash of the new tick when it differs from
    /// the world's: a divergence.
    pub fn advance(&mut self, world: &mut World) -> Result<Option<(u32, u64)>, String> {
        self.replay.advance(world).map_err(|e| e.to_string())?;
        self.keep_state(world);
        let now = world.tick();
        Ok(self
            .hash_at(now)
            .filter(|&h| h != world.state_hash())
            .map(|h| (now, h)))
    }

    /// Puts `world` at `tick` (clamped to the recording): from the latest kept state at or
    /// before it, re-simulating the rest. Returns the first divergence met, if any.
    pub fn seek(&mut self, world: &mut World, tick: u32) -> Result<Option<(u32, u64)>, String> {
        let tick = tick.min(self.ticks());
        let slot = ((tick / STATE_INTERVAL) as usize).min(self.states.len() - 1);
        let from = slot as u32 * STATE_INTERVAL;
        let resume_here = world.tick() >= from && world.tick() <= tick;
        if !resume_here {
            world
                .resync(&self.states[slot])
                .map_err(|e| format!("restoring tick {from}: {e}"))?;
        }
        let mut diverged = None;
        while world.tick() < tick {
            let d = self.advance(world)?;
            diverged = diverged.or(d);
        }
        Ok(diverged)
    }

    /// The recording as a replay: state hashes every [`HASH_INTERVAL`] ticks and at the
    /// last tick.
    pub fn to_replay(&self) -> Replay {
        let last = self.ticks();
        let hashes = self
            .replay
            .hashes
            .iter()
            .copied()
            .filter(|&(t, _)| t > 0 && (t % HASH_INTERVAL == 0 || t == last))
            .collect();
        let r = &self.replay;
        Replay {
            level_hash: r.level_hash,
            settings: r.settings,
            players: r.players,
            hash_interval: HASH_INTERVAL,
            inputs: r.inputs.clone(),
            hashes,
            edits: r.edits.clone(),
        }
    }
}
