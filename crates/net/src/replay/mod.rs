//! Replay files: the match settings and every player's input for every tick, with
//! periodic state hashes to prove that a re-simulation reproduces the match.
//!
//! Here the model ([`Replay`] and its invariants); the byte format below in `format`, the
//! [`Recorder`] that builds a replay as a match is played in `recorder`, and [`verify`],
//! which re-simulates one, in `verify`.
//!
//! A replay is small because the simulation is deterministic: inputs are all it needs to
//! rebuild every state, and the stored hashes catch a build whose simulation diverges.
//!
//! # Layout (format version 1)
//!
//! All offsets in bytes; `H`, `I` and `S` are the section lengths.
//!
//! | offset         | size | field                                             |
//! |----------------|------|---------------------------------------------------|
//! | 0              | 8    | magic `CRTRPLY\0` ([`MAGIC`])                     |
//! | 8              | 2    | format version, `u16 LE` ([`VERSION`])           |
//! | 10             | 4    | `H`, `u32 LE`                                      |
//! | 14             | `H`  | header section (postcard)                          |
//! | 14 + H         | 4    | `I`, `u32 LE`                                      |
//! | 18 + H         | `I`  | inputs section                                     |
//! | 18 + H + I     | 4    | `S`, `u32 LE`                                      |
//! | 22 + H + I     | `S`  | hashes section                                     |
//! | 22 + H + I + S | 4    | CRC-32 of bytes `0 .. 22 + H + I + S`, `u32 LE`    |
//!
//! Format version 2 adds a fourth section, the *edits*, before the checksum: `E`
//! (`u32 LE`) and `E` bytes, and the CRC-32 then covers bytes `0 .. 26 + H + I + S + E`.
//! A replay without edits is written as version 1, byte for byte what builds before
//! version 2 wrote; both versions are read.
//!
//! **Header**: the postcard encoding of, in order, `level_hash: u64`, `settings:`
//! [`Settings`] (its fields in declaration order, nested structs inline), `players: u8`
//! (1 to 8), `hash_interval: u32` (at least 1) and `ticks: u32` (the number of input
//! rows). Postcard writes a `u8` as itself, a `bool` as one byte 0 or 1, wider unsigned
//! integers as varints and signed ones as zigzag varints, with no field names or padding.
//! Adding, removing or reordering a field of [`Settings`] therefore changes the format and
//! must come with a new [`VERSION`].
//!
//! **Inputs**: the rows of `players` inputs, one row per tick, as runs of identical rows.
//! Each run is
//!
//! - `varint` run length (at least 1 tick; the runs add up to `ticks` exactly);
//! - `u8` player mask: bit `p` is set where player `p`'s input differs from the previous
//!   row (the row before the first is all [`Input::default`]). Only the first run may have
//!   an empty mask; bits at or above `players` must be clear;
//! - for each set bit, lowest first: a `u8` field mask (bit 0 `aim`, 1 `buttons`,
//!   2 `drive`, 3 `power`, 4 `weapon`; not empty, bits 5 to 7 clear), then the changed
//!   fields in that order: `aim` as `u16 LE`, the others one byte each (`drive` as its
//!   two's complement).
//!
//! A player who turns the aim for a second costs about 4 bytes per tick while turning and
//! nothing while holding still, so a match costs bytes per input *change*, not per tick.
//!
//! **Hashes**: `varint` count, then per entry a `varint` tick delta (from the previous
//! entry's tick; the first entry's from 0; after the first entry at least 1, so ticks
//! strictly increase and none passes `ticks`) and the state hash as `u64 LE`. The hash for
//! tick `T` is [`World::state_hash`] once [`World::tick`] is `T`; a [`Recorder`] stores one
//! every `hash_interval` ticks and one for the final tick.
//!
//! **Edits** (version 2): terrain events applied from outside the simulation (a level
//! editor's brush, a server's scripted hazards), as the event list of the destruction
//! stream (see [`crate::wire`], "Event list"). Each event's `tick` is the tick it was
//! applied at: before the step that leaves that tick, with [`World::apply_event`]. Ticks
//! never decrease and are below the replay's tick count.
//!
//! Varints are described in `super::codec`.
//!
//! # Decoding
//!
//! The framing is walked first (magic, version, the three lengths, which must account for
//! every byte), so a cut file reports `Truncated` in the section where it ends; then the
//! CRC-32 is checked; then the sections are parsed, still bounds-checking everything
//! (a valid checksum proves nothing about a hostile file). Settings and every input are
//! validated, and every count is held to [`DecodeLimits`](crate::DecodeLimits) before anything is allocated.

use serde::{Deserialize, Serialize};

use craterfield_field::Event;
use craterfield_sim::{Input, Settings, World};

mod error;
mod format;
mod recorder;
mod verify;

pub use error::VerifyError;
pub use recorder::Recorder;
pub use verify::{VerifyReport, verify};

/// The first eight bytes of every replay file.
pub const MAGIC: &[u8; 8] = b"CRTRPLY\0";

/// The newest format version this build writes and reads (with edits).
pub const VERSION: u16 = 2;

/// The format version of replays without edits, which this build writes for them and
/// still reads.
pub const VERSION_WITHOUT_EDITS: u16 = 1;

/// Most players a replay can hold (the player mask of a run is one byte).
pub const FORMAT_MAX_PLAYERS: u8 = 8;

const _: () = assert!(craterfield_sim::MAX_PLAYERS <= FORMAT_MAX_PLAYERS as usize);

/// Bytes in the smallest hash entry (a one-byte tick delta and the eight-byte hash).
const MIN_HASH_ENTRY: usize = 9;

/// Bit of each field in a run's field mask, in encoding order.
mod field {
    pub(super) const AIM: u8 = 1 << 0;
    pub(super) const BUTTONS: u8 = 1 << 1;
    pub(super) const DRIVE: u8 = 1 << 2;
    pub(super) const POWER: u8 = 1 << 3;
    pub(super) const WEAPON: u8 = 1 << 4;
    pub(super) const ALL: u8 = AIM | BUTTONS | DRIVE | POWER | WEAPON;
}

/// A recorded match: everything needed to re-simulate it and check the result.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Replay {
    /// [`craterfield_sim::level_hash`] of the level it was played on.
    pub level_hash: u64,
    /// The match settings.
    pub settings: Settings,
    /// Number of players (1 to [`FORMAT_MAX_PLAYERS`]).
    pub players: u8,
    /// Ticks between two stored hashes (at least 1).
    pub hash_interval: u32,
    /// `ticks * players` inputs, row-major: tick `t`'s row is
    /// `inputs[t * players .. (t + 1) * players]`. Every input is valid.
    pub inputs: Vec<Input>,
    /// `(tick, state hash)` pairs, ticks strictly increasing and at most [`Replay::ticks`].
    pub hashes: Vec<(u32, u64)>,
    /// Terrain events applied from outside the simulation, in order: each before the step
    /// that leaves tick `event.tick`. Ticks never decrease and are below
    /// [`Replay::ticks`]; every event is valid.
    pub edits: Vec<Event>,
}

/// The header section, as postcard encodes it.
#[derive(Serialize, Deserialize)]
struct Header {
    level_hash: u64,
    settings: Settings,
    players: u8,
    hash_interval: u32,
    ticks: u32,
}

impl Replay {
    /// Number of ticks (input rows).
    pub fn ticks(&self) -> u32 {
        // Encoding checks that this fits; a decoded replay has at most `max_ticks`.
        (self.inputs.len() / usize::from(self.players.max(1))) as u32
    }

    /// The inputs of tick `tick`, one per player.
    ///
    /// # Panics
    ///
    /// If `tick >= self.ticks()`.
    pub fn row(&self, tick: u32) -> &[Input] {
        let p = usize::from(self.players);
        let start = tick as usize * p;
        &self.inputs[start..start + p]
    }

    /// The rows, one per tick.
    pub fn rows(&self) -> impl Iterator<Item = &[Input]> + '_ {
        self.inputs.chunks_exact(usize::from(self.players.max(1)))
    }

    /// The edits applied at tick `tick` (before its step), in order.
    pub fn edits_at(&self, tick: u32) -> &[Event] {
        let start = self.edits.partition_point(|e| e.tick < tick);
        let end = self.edits.partition_point(|e| e.tick <= tick);
        &self.edits[start..end]
    }

    /// Advances `world` by one recorded tick: applies the edits of [`World::tick`], then
    /// steps with that tick's inputs. Fails, changing nothing, when the world is at or past
    /// the end of the replay; a world built from another level or settings simply
    /// diverges (compare [`World::state_hash`] with [`Replay::hash_at`]).
    pub fn advance(&self, world: &mut World) -> Result<(), VerifyError> {
        let tick = world.tick();
        if tick >= self.ticks() {
            return Err(VerifyError::Inconsistent {
                detail: format!(
                    "the world is at tick {tick}, past the replay's last input row ({} ticks)",
                    self.ticks()
                ),
            });
        }
        for &e in self.edits_at(tick) {
            world.apply_event(e)?;
        }
        world.step(self.row(tick))?;
        Ok(())
    }

    /// The stored hash for `tick`, if there is one.
    pub fn hash_at(&self, tick: u32) -> Option<u64> {
        let i = self.hashes.binary_search_by_key(&tick, |h| h.0).ok()?;
        Some(self.hashes[i].1)
    }

    /// Fails with [`VerifyError::LevelMismatch`] unless the replay was recorded on a level
    /// with hash `level_hash`.
    pub fn check_level(&self, level_hash: u64) -> Result<(), VerifyError> {
        if self.level_hash != level_hash {
            return Err(VerifyError::LevelMismatch {
                expected: self.level_hash,
                found: level_hash,
            });
        }
        Ok(())
    }

    /// Checks the invariants documented on the public fields (players in range, whole
    /// rows of valid inputs, valid settings, stored hash ticks increasing up to the last
    /// tick). [`Replay::encode`] and [`verify`] refuse a replay that breaks them; the error
    /// says which.
    pub fn validate(&self) -> Result<(), String> {
        if self.players == 0 || self.players > FORMAT_MAX_PLAYERS {
            return Err(format!(
                "{} players (1 to {FORMAT_MAX_PLAYERS} allowed)",
                self.players
            ));
        }
        let p = usize::from(self.players);
        let ticks = self.inputs.len() / p;
        if ticks * p != self.inputs.len() || ticks > u32::MAX as usize {
            let n = self.inputs.len();
            return Err(format!("{n} inputs for {p} players: not whole rows"));
        }
        if self.hash_interval == 0 {
            return Err("hash interval 0".to_string());
        }
        self.settings
            .validate()
            .map_err(|e| format!("settings: {e}"))?;
        if let Some((i, e)) = self
            .inputs
            .iter()
            .enumerate()
            .find_map(|(i, x)| x.validate().err().map(|e| (i, e)))
        {
            return Err(format!("tick {} player {}: {e}", i / p, i % p));
        }
        let ticks = self.ticks();
        let increasing = self.hashes.windows(2).all(|w| w[0].0 < w[1].0);
        if !increasing || self.hashes.last().is_some_and(|h| h.0 > ticks) {
            return Err(format!("hash ticks must increase strictly up to {ticks}"));
        }
        self.validate_edits()
    }

    fn validate_edits(&self) -> Result<(), String> {
        let mut previous = 0;
        for (i, e) in self.edits.iter().enumerate() {
            e.validate().map_err(|err| format!("edit {i}: {err}"))?;
            if e.tick < previous || e.tick >= self.ticks() {
                return Err(format!(
                    "edit {i} at tick {}: edit ticks must not decrease and must be below {}",
                    e.tick,
                    self.ticks()
                ));
            }
            previous = e.tick;
        }
        Ok(())
    }
}
