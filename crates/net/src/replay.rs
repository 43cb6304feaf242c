//! Replay files: the match settings and every player's input for every tick, with
//! periodic state hashes to prove that a re-simulation reproduces the match.
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
//! validated, and every count is held to [`DecodeLimits`] before anything is allocated.

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::codec::{self, DecodeLimits, Reader, Writer};
use super::error::{DecodeError, DecodeErrorKind, EncodeError};
use craterfield_field::Event;
use craterfield_field::Level;
use craterfield_sim::Input;
use craterfield_sim::Settings;
use craterfield_sim::{SimError, World};

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

    /// Encodes the replay (see the [module documentation](self) for the layout), refusing
    /// what [`Replay::decode`] would refuse: what one side writes the other reads.
    ///
    /// Fails with [`EncodeError::Inconsistent`] where the public fields break the
    /// invariants documented on them, or the settings or an input are invalid, and with
    /// [`EncodeError::TooLarge`] past the default [`DecodeLimits`].
    pub fn encode(&self) -> Result<Vec<u8>, EncodeError> {
        self.encode_with_limits(&DecodeLimits::default())
    }

    /// Encodes the replay, refusing anything [`Replay::decode_with_limits`] would refuse
    /// with the same `limits`.
    pub fn encode_with_limits(&self, limits: &DecodeLimits) -> Result<Vec<u8>, EncodeError> {
        self.validate().map_err(inconsistent)?;
        let too_large = |what, value: u64, limit: u64| EncodeError::TooLarge { what, value, limit };
        if self.ticks() > limits.max_ticks {
            let (ticks, max) = (self.ticks(), limits.max_ticks);
            return Err(too_large("ticks", ticks.into(), max.into()));
        }
        let max_players = limits.max_players.min(FORMAT_MAX_PLAYERS);
        if self.players > max_players {
            return Err(too_large(
                "players",
                self.players.into(),
                max_players.into(),
            ));
        }
        if self.edits.len() as u64 > u64::from(limits.max_events) {
            let (n, max) = (self.edits.len() as u64, limits.max_events);
            return Err(too_large("edits", n, max.into()));
        }
        let header = Header {
            level_hash: self.level_hash,
            settings: self.settings,
            players: self.players,
            hash_interval: self.hash_interval,
            ticks: self.ticks(),
        };
        let header =
            postcard::to_stdvec(&header).map_err(|e| inconsistent(format!("header: {e}")))?;
        let mut w = Writer::default();
        w.bytes(MAGIC);
        w.u16(if self.edits.is_empty() {
            VERSION_WITHOUT_EDITS
        } else {
            VERSION
        });
        w.section(&header);
        w.section(&self.encode_inputs());
        w.section(&self.encode_hashes());
        if !self.edits.is_empty() {
            let mut edits = Writer::default();
            super::wire::write_event_list(&mut edits, &self.edits)?;
            w.section(&edits.buf);
        }
        w.checksum();
        if w.buf.len() > limits.max_bytes {
            let (len, max) = (w.buf.len() as u64, limits.max_bytes as u64);
            return Err(too_large("file length", len, max));
        }
        Ok(w.buf)
    }

    /// Decodes a replay with the default [`DecodeLimits`].
    pub fn decode(bytes: &[u8]) -> Result<Replay, DecodeError> {
        Replay::decode_with_limits(bytes, &DecodeLimits::default())
    }

    /// Decodes a replay, rejecting anything beyond `limits` before allocating for it.
    pub fn decode_with_limits(bytes: &[u8], limits: &DecodeLimits) -> Result<Replay, DecodeError> {
        codec::check_len(bytes, limits)?;
        let mut r = Reader::new(bytes, 0, "file");
        codec::expect_magic(&mut r, MAGIC)?;
        let version = check_version(&mut r)?;
        let mut header = r.section("header", limits.max_bytes)?;
        let mut inputs = r.section("inputs", limits.max_bytes)?;
        let mut hashes = r.section("hashes", limits.max_bytes)?;
        let edits = match version {
            VERSION_WITHOUT_EDITS => None,
            _ => Some(r.section("edits", limits.max_bytes)?),
        };
        codec::check_crc(bytes, r.offset())?;
        let h = decode_header(&mut header, limits)?;
        let players = usize::from(h.players);
        let inputs = decode_inputs(&mut inputs, players, h.ticks)?;
        let hashes = decode_hashes(&mut hashes, h.ticks)?;
        let edits = match edits {
            Some(mut r) => decode_edits(&mut r, h.ticks, limits)?,
            None => Vec::new(),
        };
        Ok(Replay {
            level_hash: h.level_hash,
            settings: h.settings,
            players: h.players,
            hash_interval: h.hash_interval,
            inputs,
            hashes,
            edits,
        })
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

    fn encode_inputs(&self) -> Vec<u8> {
        let mut w = Writer::default();
        let p = usize::from(self.players);
        let mut prev = vec![Input::default(); p];
        let mut rows = self.rows().peekable();
        while let Some(row) = rows.next() {
            let mut len = 1u64;
            while rows.next_if(|next| *next == row).is_some() {
                len += 1;
            }
            w.varint(len);
            write_row_change(&mut w, &prev, row);
            prev.copy_from_slice(row);
        }
        w.buf
    }

    fn encode_hashes(&self) -> Vec<u8> {
        let mut w = Writer::default();
        w.varint(self.hashes.len() as u64);
        let mut prev = 0;
        for &(tick, hash) in &self.hashes {
            w.varint(u64::from(tick - prev));
            w.u64(hash);
            prev = tick;
        }
        w.buf
    }
}

fn inconsistent(detail: impl Into<String>) -> EncodeError {
    EncodeError::Inconsistent {
        detail: detail.into(),
    }
}

/// Writes the player mask and the changed fields of `row` relative to `prev`.
fn write_row_change(w: &mut Writer, prev: &[Input], row: &[Input]) {
    let mask = (0..row.len())
        .filter(|&p| row[p] != prev[p])
        .fold(0u8, |m, p| m | 1 << p);
    w.u8(mask);
    for (old, new) in prev.iter().zip(row).filter(|(old, new)| old != new) {
        let fields = [
            (field::AIM, old.aim != new.aim),
            (field::BUTTONS, old.buttons != new.buttons),
            (field::DRIVE, old.drive != new.drive),
            (field::POWER, old.power != new.power),
            (field::WEAPON, old.weapon != new.weapon),
        ];
        let fmask = fields.iter().filter(|f| f.1).fold(0u8, |m, f| m | f.0);
        w.u8(fmask);
        let b = new.to_bytes();
        if fmask & field::AIM != 0 {
            w.bytes(&b[0..2]);
        }
        for (bit, byte) in [
            (field::BUTTONS, b[2]),
            (field::DRIVE, b[3]),
            (field::POWER, b[4]),
            (field::WEAPON, b[5]),
        ] {
            if fmask & bit != 0 {
                w.u8(byte);
            }
        }
    }
}

/// Reads the format version: [`VERSION_WITHOUT_EDITS`] or [`VERSION`].
fn check_version(r: &mut Reader<'_>) -> Result<u16, DecodeError> {
    r.enter("version", None);
    let at = r.offset();
    let found = r.u16()?;
    if found != VERSION && found != VERSION_WITHOUT_EDITS {
        return Err(r.error_at(
            at,
            DecodeErrorKind::UnsupportedVersion {
                found,
                supported: VERSION,
            },
        ));
    }
    Ok(found)
}

fn decode_header(r: &mut Reader<'_>, limits: &DecodeLimits) -> Result<Header, DecodeError> {
    let at = r.offset();
    let h: Header = r.postcard()?;
    let err = |kind| DecodeError::new("header", at, kind);
    let max_players = limits.max_players.min(FORMAT_MAX_PLAYERS);
    if h.players > max_players {
        return Err(err(too_large(
            "players",
            h.players.into(),
            max_players.into(),
        )));
    }
    if h.ticks > limits.max_ticks {
        return Err(err(too_large(
            "ticks",
            h.ticks.into(),
            limits.max_ticks.into(),
        )));
    }
    if h.players == 0 || h.hash_interval == 0 {
        let detail = format!(
            "players {} and hash interval {} must be at least 1",
            h.players, h.hash_interval
        );
        return Err(err(DecodeErrorKind::InvalidValue { detail }));
    }
    if let Err(e) = h.settings.validate() {
        return Err(err(DecodeErrorKind::InvalidValue {
            detail: format!("settings: {e}"),
        }));
    }
    Ok(h)
}

fn too_large(what: &'static str, value: u64, limit: u64) -> DecodeErrorKind {
    DecodeErrorKind::TooLarge { what, value, limit }
}

fn decode_inputs(
    r: &mut Reader<'_>,
    players: usize,
    ticks: u32,
) -> Result<Vec<Input>, DecodeError> {
    let mut row = [Input::default(); FORMAT_MAX_PLAYERS as usize];
    let row = &mut row[..players];
    let mut inputs = Vec::new();
    let mut done = 0u32;
    while done < ticks {
        r.enter("inputs at tick", Some(done.into()));
        let len = r.varint_u32("run length")?;
        if len == 0 || len > ticks - done {
            return Err(r.malformed(format!("run of {len} ticks at tick {done} of {ticks}")));
        }
        read_row_change(r, row, done == 0)?;
        for _ in 0..len {
            // Bounded: the header's tick count was checked against the limits.
            inputs.extend_from_slice(row);
        }
        done += len;
    }
    r.enter("inputs", None);
    r.finish()?;
    Ok(inputs)
}

/// Applies one run's changes to `row`, validating every changed input.
fn read_row_change(r: &mut Reader<'_>, row: &mut [Input], first: bool) -> Result<(), DecodeError> {
    let at = r.offset();
    let mask = r.u8()?;
    if u32::from(mask) >> row.len() != 0 {
        return Err(r.error_at(
            at,
            codec::malformed(format!(
                "player mask {mask:#010b} names players beyond {}",
                row.len()
            )),
        ));
    }
    if mask == 0 && !first {
        return Err(r.error_at(at, codec::malformed("run repeats the previous row")));
    }
    for (p, input) in row.iter_mut().enumerate() {
        if mask & (1 << p) != 0 {
            let at = r.offset();
            *input = read_input_change(r, *input)?;
            if let Err(e) = input.validate() {
                return Err(r.error_at(
                    at,
                    DecodeErrorKind::InvalidValue {
                        detail: format!("player {p}: {e}"),
                    },
                ));
            }
        }
    }
    Ok(())
}

fn read_input_change(r: &mut Reader<'_>, old: Input) -> Result<Input, DecodeError> {
    let at = r.offset();
    let fmask = r.u8()?;
    if fmask == 0 || fmask & !field::ALL != 0 {
        return Err(r.error_at(at, codec::malformed(format!("field mask {fmask:#010b}"))));
    }
    let mut b = old.to_bytes();
    if fmask & field::AIM != 0 {
        b[0..2].copy_from_slice(r.take(2)?);
    }
    for (bit, i) in [
        (field::BUTTONS, 2),
        (field::DRIVE, 3),
        (field::POWER, 4),
        (field::WEAPON, 5),
    ] {
        if fmask & bit != 0 {
            b[i] = r.u8()?;
        }
    }
    Ok(Input::from_bytes(b))
}

fn decode_hashes(r: &mut Reader<'_>, ticks: u32) -> Result<Vec<(u32, u64)>, DecodeError> {
    let at = r.offset();
    let count = r.varint_max("hash count", u64::from(ticks) + 1)?;
    r.check_fits(at, count, MIN_HASH_ENTRY)?;
    let mut hashes = Vec::new();
    let mut tick = 0u32;
    for i in 0..count {
        r.enter("hash", Some(i));
        let at = r.offset();
        let delta = r.varint_u32("hash tick delta")?;
        let next = tick.checked_add(delta).filter(|&t| t <= ticks);
        let next = match next {
            Some(t) if i == 0 || delta > 0 => t,
            _ => {
                let detail = format!(
                    "tick delta {delta} after tick {tick} (ticks increase strictly up to {ticks})"
                );
                return Err(r.error_at(at, codec::malformed(detail)));
            }
        };
        tick = next;
        hashes.push((tick, r.u64()?));
    }
    r.enter("hashes", None);
    r.finish()?;
    Ok(hashes)
}

/// The edits section: an event list whose ticks stay below the replay's tick count.
fn decode_edits(
    r: &mut Reader<'_>,
    ticks: u32,
    limits: &DecodeLimits,
) -> Result<Vec<Event>, DecodeError> {
    let edits = super::wire::read_event_list(r, limits.max_events)?;
    if let Some((i, e)) = edits.iter().enumerate().find(|(_, e)| e.tick >= ticks) {
        return Err(r.malformed(format!(
            "edit {i} is at tick {}, not below the replay's {ticks} ticks",
            e.tick
        )));
    }
    Ok(edits)
}

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

    /// Records an edit: a terrain event applied with [`World::apply_event`] before the
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

/// What [`verify`] checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VerifyReport {
    /// Ticks simulated.
    pub ticks: u32,
    /// Stored hashes compared (all of them, when verification succeeds).
    pub hashes_checked: usize,
    /// The state hash after the last tick.
    pub final_hash: u64,
}

/// Why a replay did not verify.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum VerifyError {
    /// The replay was recorded on another level.
    #[error("the replay was recorded on level {expected:#018x}, not on this level ({found:#018x})")]
    LevelMismatch {
        /// The level hash stored in the replay.
        expected: u64,
        /// The hash of the level given.
        found: u64,
    },
    /// The replay breaks an invariant of [`Replay`] (see [`Replay::validate`]).
    #[error("the replay is inconsistent: {detail}")]
    Inconsistent {
        /// Which invariant, and where.
        detail: String,
    },
    /// The simulation rejected the replay's settings, players or inputs.
    #[error("simulation error: {0}")]
    Sim(#[from] SimError),
    /// The re-simulation's state hash differs from the stored one.
    #[error("diverged at tick {tick}: stored hash {expected:#018x}, simulated {found:#018x}")]
    Diverged {
        /// The tick of the first mismatching hash.
        tick: u32,
        /// The stored hash.
        expected: u64,
        /// The re-simulation's hash.
        found: u64,
    },
    /// A stored hash is for a tick the re-simulation never stopped at (it ended earlier,
    /// or its tick counter skipped it).
    #[error(
        "the stored hash for tick {tick} was never compared: the simulation never reached that tick"
    )]
    HashNotReached {
        /// The tick of the stored hash.
        tick: u32,
    },
}

/// Re-simulates `replay` on `level` and compares every stored hash.
///
/// Checks the level hash first, then builds the world from the replay's settings, advances
/// it once per input row ([`Replay::advance`]: the tick's edits, then its step) and
/// compares the stored hash of every tick the world reaches (including its starting tick).
/// Stops at the first mismatch.
pub fn verify(replay: &Replay, level: &Level) -> Result<VerifyReport, VerifyError> {
    replay
        .validate()
        .map_err(|detail| VerifyError::Inconsistent { detail })?;
    replay.check_level(craterfield_sim::level_hash(level))?;
    let mut world = World::new(level, replay.settings, usize::from(replay.players))?;
    let mut pending = replay.hashes.iter().peekable();
    let mut checked = 0;
    checked += check_hashes(&mut pending, world.tick(), world.state_hash())?;
    for _ in 0..replay.ticks() {
        replay.advance(&mut world)?;
        checked += check_hashes(&mut pending, world.tick(), world.state_hash())?;
    }
    if let Some(&&(tick, _)) = pending.peek() {
        return Err(VerifyError::HashNotReached { tick });
    }
    Ok(VerifyReport {
        ticks: replay.ticks(),
        hashes_checked: checked,
        final_hash: world.state_hash(),
    })
}

/// Compares the stored hashes up to `tick` against `hash`; a stored tick that was skipped
/// over is an error. Returns how many were compared.
fn check_hashes<'a>(
    pending: &mut std::iter::Peekable<impl Iterator<Item = &'a (u32, u64)>>,
    tick: u32,
    hash: u64,
) -> Result<usize, VerifyError> {
    let mut checked = 0;
    while let Some(&&(t, expected)) = pending.peek() {
        if t > tick {
            break;
        }
        if t < tick {
            return Err(VerifyError::HashNotReached { tick: t });
        }
        if expected != hash {
            return Err(VerifyError::Diverged {
                tick,
                expected,
                found: hash,
            });
        }
        pending.next();
        checked += 1;
    }
    Ok(checked)
}
