//! [`Timeline`]: everything a sandbox session did, tick by tick (inputs, edits, state
//! hashes), with periodic world states so that any tick can be reached again quickly. It
//! is the replay in the making: [`Timeline::to_replay`] writes it as a `.replay`, and a
//! loaded replay becomes a timeline to scrub.

use craterfield::field2d::Event;
use craterfield::net::replay::Replay;
use craterfield::sim::{Input, World, WorldState};

/// Ticks between two kept world states at first: seeking re-simulates at most this many
/// ticks until the session outgrows [`MAX_STATES`].
pub const STATE_INTERVAL: u32 = 120;

/// Most world states a timeline keeps. Past it every other one is dropped and the interval
/// doubles, so memory stays bounded over a long session (each state carries the terrain's
/// event history) while seeking re-simulates at most one interval.
pub const MAX_STATES: usize = 256;

/// Ticks between two state hashes in a saved replay.
pub const HASH_INTERVAL: u32 = 60;

/// A match's history: the replay being recorded, with a state hash for every tick, and
/// the world states kept for seeking.
#[derive(Clone, Debug)]
pub struct Timeline {
    /// Inputs, edits and `(tick, hash)` pairs (every tick of a live session, the stored
    /// ones of a loaded replay).
    replay: Replay,
    /// `states[i]` is the world at tick `i * interval`.
    states: Vec<WorldState>,
    /// Ticks between two kept states: [`STATE_INTERVAL`], doubled each time the states
    /// outgrow `max_states`.
    interval: u32,
    max_states: usize,
}

impl Timeline {
    /// An empty history starting at `world` (tick 0).
    pub fn new(world: &World, level_hash: u64) -> Timeline {
        Timeline::with_max_states(world, level_hash, MAX_STATES)
    }

    /// [`Timeline::new`] keeping at most `max_states` (at least 2) world states.
    pub fn with_max_states(world: &World, level_hash: u64, max_states: usize) -> Timeline {
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
            interval: STATE_INTERVAL,
            max_states: max_states.max(2),
        }
    }

    /// The history of `replay`, whose first world is `world` (at tick 0).
    pub fn from_replay(replay: &Replay, world: &World) -> Timeline {
        Timeline {
            replay: replay.clone(),
            states: vec![world.state()],
            interval: STATE_INTERVAL,
            max_states: MAX_STATES,
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

    /// World states kept for seeking, and the ticks between them.
    pub fn kept_states(&self) -> (usize, u32) {
        (self.states.len(), self.interval)
    }

    fn keep_state(&mut self, world: &World) {
        let tick = world.tick();
        let next = self.states.len() as u64 * u64::from(self.interval);
        if u64::from(tick) != next {
            return;
        }
        self.states.push(world.state());
        if self.states.len() > self.max_states {
            // Keep the states at even multiples of the interval, then double it.
            let mut i = 0;
            self.states.retain(|_| {
                i += 1;
                i % 2 == 1
            });
            self.interval = self.interval.saturating_mul(2);
        }
    }

    /// Forgets everything after `tick` (a live session continues from there).
    pub fn truncate(&mut self, tick: u32) {
        let tick = tick.min(self.ticks());
        let r = &mut self.replay;
        r.inputs.truncate(tick as usize * usize::from(r.players));
        r.edits.truncate(r.edits.partition_point(|e| e.tick < tick));
        r.hashes.truncate(r.hashes.partition_point(|h| h.0 <= tick));
        self.states.truncate((tick / self.interval) as usize + 1);
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
        let slot = ((tick / self.interval) as usize).min(self.states.len() - 1);
        let from = slot as u32 * self.interval;
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

#[cfg(test)]
mod tests {
    use super::*;
    use craterfield::field2d::Level;
    use craterfield::sim::{Settings, level_hash};

    #[test]
    fn a_long_session_keeps_few_states_and_still_seeks_exactly() {
        let level = Level::default_level();
        let mut world = World::new(&level, Settings::default(), 2).expect("world");
        let mut timeline = Timeline::with_max_states(&world, level_hash(&level), 4);
        let row = [
            Input {
                drive: 60,
                ..Input::default()
            },
            Input::default(),
        ];
        let ticks = 20 * STATE_INTERVAL + 7;
        for _ in 0..ticks {
            world.step(&row).expect("step");
            timeline.push_tick(&[], &row, &world);
        }
        let (kept, interval) = timeline.kept_states();
        assert!(kept <= 4, "{kept} states kept");
        assert_eq!(
            interval,
            8 * STATE_INTERVAL,
            "the interval doubled three times"
        );
        let mut replayed = World::new(&level, Settings::default(), 2).expect("world");
        for t in [
            ticks,
            5,
            2 * interval + 1,
            interval - 1,
            2 * interval,
            0,
            1000,
        ] {
            let diverged = timeline.seek(&mut replayed, t).expect("seek");
            assert_eq!(diverged, None);
            assert_eq!(replayed.tick(), t);
            assert_eq!(Some(replayed.state_hash()), timeline.hash_at(t), "tick {t}");
        }
        // Going back and continuing keeps the states consistent with the interval.
        timeline.truncate(interval + 3);
        assert_eq!(timeline.kept_states().0, 2);
    }
}
