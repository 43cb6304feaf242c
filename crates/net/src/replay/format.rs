//! The replay's byte format (the layout in the module doc of [`super`]): encoding, and
//! decoding that walks the framing, checks the CRC-32 and bounds every count before
//! anything is allocated.

use craterfield_field::Event;
use craterfield_sim::Input;

use super::{
    FORMAT_MAX_PLAYERS, Header, MAGIC, MIN_HASH_ENTRY, Replay, VERSION, VERSION_WITHOUT_EDITS,
    field,
};
use crate::codec::{self, DecodeLimits, Reader, Writer};
use crate::error::{DecodeError, DecodeErrorKind, EncodeError};

impl Replay {
    /// Encodes the replay (see the [module documentation](super) for the layout), refusing
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
            crate::wire::write_event_list(&mut edits, &self.edits)?;
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

pub(super) fn inconsistent(detail: impl Into<String>) -> EncodeError {
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
    let edits = crate::wire::read_event_list(r, limits.max_events)?;
    if let Some((i, e)) = edits.iter().enumerate().find(|(_, e)| e.tick >= ticks) {
        return Err(r.malformed(format!(
            "edit {i} is at tick {}, not below the replay's {ticks} ticks",
            e.tick
        )));
    }
    Ok(edits)
}
