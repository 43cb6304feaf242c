//! Recording a match as it is played.

use craterfield_field::Event;
use craterfield_sim::{Input, Settings};

use super::format::inconsistent;
use super::{FORMAT_MAX_PLAYERS, Replay};
use crate::codec::DecodeLimits;
use crate::error::EncodeError;

/// Records a match as it is played, producing a [`Replay`].
///
/// ```
/// use craterfield_field::Level;
/// use craterfield_net::Recorder;
/// use craterfield_sim::{Input, Settings, World};
/// use craterfield_sim::level_hash;
///
/// let level = Level::default_level();
/// let settings = Settings::default();
/// let mut world = World::new(&level, settings, 2)?;
/// let mut rec = Recorder::new(level_hash(&level), settings, 2, 60)?;
/// for tick in 0..90 {
///     let inputs = [Input { drive: 100, ..Input::default() }, Input::default()];
///     world.step(&inputs)?;
///     rec.record(&inputs, world.tick(), world.state_hash())?;
/// }
/// let replay = rec.finish(world.tick(), world.state_hash());
/// assert_eq!(replay.ticks(), 90);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Recorder {
    replay: Replay,
    since_hash: u32,
}

impl Recorder {
    /// A recorder for `players` players that stores a state hash every `hash_interval`
    /// ticks. Errors if `players` is 0 or above [`FORMAT_MAX_PLAYERS`], or `hash_interval`
    /// is 0.
    pub fn new(
        level_hash: u64,
        settings: Settings,
        players: u8,
        hash_interval: u32,
    ) -> Result<Recorder, EncodeError> {
        if !(1..=FORMAT_MAX_PLAYERS).contains(&players) {
            return Err(EncodeError::Inconsistent {
                detail: format!("a replay holds 1 to {FORMAT_MAX_PLAYERS} players, not {players}"),
            });
        }
        if hash_interval == 0 {
            return Err(EncodeError::Inconsistent {
                detail: "the hash interval must be at least one tick".to_string(),
            });
        }
        Ok(Recorder {
            replay: Replay {
                level_hash,
                settings,
                players,
                hash_interval,
                inputs: Vec::new(),
                hashes: Vec::new(),
                edits: Vec::new(),
            },
            since_hash: 0,
        })
    }

    /// Records one tick: the inputs the world was stepped with, and its tick and state hash
    /// after the step. Invalid inputs are stored as [`Input::sanitized`] does (the
    /// simulation treats them the same way), so the replay always encodes. Errors (and
    /// records nothing) unless there is one input per player, and with
    /// [`EncodeError::TooLarge`] once the replay holds the default [`DecodeLimits`]'
    /// `max_ticks`: a longer one could not be read back.
    pub fn record(
        &mut self,
        inputs: &[Input],
        tick_after: u32,
        state_hash_after: u64,
    ) -> Result<(), EncodeError> {
        let max_ticks = DecodeLimits::default().max_ticks;
        if self.replay.ticks() >= max_ticks {
            return Err(EncodeError::TooLarge {
                what: "ticks",
                value: u64::from(max_ticks) + 1,
                limit: max_ticks.into(),
            });
        }
        if inputs.len() != usize::from(self.replay.players) {
            return Err(EncodeError::Inconsistent {
                detail: format!(
                    "{} inputs recorded for {} players",
                    inputs.len(),
                    self.replay.players
                ),
            });
        }
        self.replay
            .inputs
            .extend(inputs.iter().map(|i| i.sanitized()));
        self.since_hash += 1;
        if self.since_hash == self.replay.hash_interval {
            self.since_hash = 0;
            self.push_hash(tick_after, state_hash_after);
        }
        Ok(())
    }

    /// Records an edit: a terrain event applied with [`World::apply_event`](craterfield_sim::World::apply_event) before the
    /// step that [`Recorder::record`] records next, so `e.tick` must be
    /// [`Recorder::ticks`]. Errors, recording nothing, for an invalid event, another tick,
    /// or past the default [`DecodeLimits`]' `max_events` edits.
    pub fn record_edit(&mut self, e: Event) -> Result<(), EncodeError> {
        e.validate().map_err(|source| EncodeError::InvalidEvent {
            index: self.replay.edits.len(),
            source,
        })?;
        if e.tick != self.ticks() {
            return Err(inconsistent(format!(
                "an edit at tick {} recorded while the replay is at tick {}",
                e.tick,
                self.ticks()
            )));
        }
        let max = DecodeLimits::default().max_events;
        if self.replay.edits.len() as u64 >= u64::from(max) {
            return Err(EncodeError::TooLarge {
                what: "edits",
                value: u64::from(max) + 1,
                limit: max.into(),
            });
        }
        self.replay.edits.push(e);
        Ok(())
    }

    /// Ticks recorded so far.
    pub fn ticks(&self) -> u32 {
        self.replay.ticks()
    }

    /// The replay, with the final tick's hash stored (unless the last periodic hash was
    /// for that tick already).
    pub fn finish(mut self, final_tick: u32, final_hash: u64) -> Replay {
        self.push_hash(final_tick, final_hash);
        self.replay
    }

    fn push_hash(&mut self, tick: u32, hash: u64) {
        if self.replay.hashes.last().is_none_or(|h| h.0 < tick) {
            self.replay.hashes.push((tick, hash));
        }
    }
}
