//! Wire messages of the destruction stream: batches of terrain events for clients of an
//! authoritative server, and terrain snapshots for late joiners.
//!
//! Both carry [`Event`]s compactly. Events made by the simulation repeat a few shapes
//! (a weapon's radius, rim and material) and sit on a coarse grid (centres snapped to
//! 1/4 world unit, 64 in fixed point), so a message lists its distinct shapes once and
//! stores each centre in units of the largest power of two that divides every centre
//! coordinate (its *quantum*), relative to the smallest coordinates. A simulation event
//! then costs about six bytes (see [`bytes_per_event`]).
//!
//! # Message layout (version 1)
//!
//! | offset | size | field |
//! |--------|------|-------|
//! | 0      | 1    | kind ([`MessageKind`]: 1 event batch, 2 terrain snapshot, 3 world state) |
//! | 1      | 1    | format version ([`VERSION`]) |
//! | 2      | 4    | body length `L`, `u32 LE` |
//! | 6      | `L`  | body |
//! | 6 + L  | 4    | CRC-32 of bytes `0 .. 6 + L`, `u32 LE` |
//!
//! The first [`HEADER_LEN`] bytes tell a stream reader the whole length
//! ([`message_len`]).
//!
//! **Event batch body**: an *event list*.
//!
//! **Snapshot body**: the level hash (`u64 LE`), the terrain's tick (`varint`), then an
//! event list of every event the terrain holds.
//!
//! **Event list** (varints and zigzag as in `super::codec`):
//!
//! - `varint` event count `N`; if `N` is 0 nothing follows;
//! - `u8` quantum shift `q` (0 to 24): every centre coordinate is a multiple of `2^q`;
//! - `zigzag` origin x and `zigzag` origin y, in quanta (the smallest coordinates);
//! - `varint` shape count `S` (1 to `N`), then `S` shapes, each: `u8` kind (0 carve,
//!   1 fill), `varint` radius, `varint` rim, `varint` grow ticks, `varint` material
//!   (fixed-point lengths as in [`Event`]);
//! - `N` events, each: `varint` tick delta (from the previous event's tick; the first
//!   event's from 0, so ticks never decrease), `varint` shape index (below `S`), `varint`
//!   x and `varint` y offsets from the origin, in quanta. The centre is
//!   `(origin + offset) << q`.
//!
//! Every decoded event passes [`Event::validate`]; counts are held to [`DecodeLimits`]
//! and to the bytes left (a shape takes at least 5 bytes, an event 4) before allocating.

use std::collections::HashMap;

use super::codec::{self, DecodeLimits, Reader, Writer};
use super::error::{DecodeError, DecodeErrorKind, EncodeError};
use craterfield_core::det::quant::FIXED_MAX;
use craterfield_field::{Event, EventKind};
use craterfield_field::{Sdf, Terrain};

/// The message format version this build writes and reads.
pub const VERSION: u8 = 1;

/// Bytes before the body: kind, version and body length.
pub const HEADER_LEN: usize = 6;

/// Bytes after the body: the CRC-32.
pub const CHECKSUM_LEN: usize = 4;

/// Largest quantum shift: coordinates are below `2^24`.
const MAX_SHIFT: u8 = 24;
/// Largest coordinate offset or origin magnitude in quanta (the fixed-point span is below
/// `2^25`), so shifting back stays far inside `i64`.
const MAX_QUANTA: u64 = 1 << 25;
const MIN_SHAPE_BYTES: usize = 5;
const MIN_EVENT_BYTES: usize = 4;

/// What a message carries (its first byte).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum MessageKind {
    /// A batch of new events ([`encode_events`]).
    Events = 1,
    /// A terrain snapshot ([`TerrainSnapshot`]).
    Snapshot = 2,
    /// A whole world's state, for a resync ([`crate::state`]).
    State = 3,
}

impl MessageKind {
    fn from_u8(b: u8) -> Option<MessageKind> {
        match b {
            1 => Some(MessageKind::Events),
            2 => Some(MessageKind::Snapshot),
            3 => Some(MessageKind::State),
            _ => None,
        }
    }
}

/// A terrain's whole destruction history, for a client joining late.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TerrainSnapshot {
    /// [`craterfield_sim::level_hash`] of the level the events apply to.
    pub level_hash: u64,
    /// The terrain's tick ([`Terrain::tick`]).
    pub tick: u32,
    /// Every event, in the order they were applied (ticks non-decreasing).
    pub events: Vec<Event>,
}

impl TerrainSnapshot {
    /// The snapshot of `terrain`, which was built from the level with hash `level_hash`.
    ///
    /// A history is only whole until the terrain compacts its log
    /// ([`Terrain::compact_history`]); after that it is [`EncodeError::HistoryCompacted`],
    /// and a late joiner needs the grid itself ([`crate::state`]).
    pub fn of_terrain<F: Sdf>(
        level_hash: u64,
        terrain: &Terrain<F>,
    ) -> Result<TerrainSnapshot, EncodeError> {
        if !terrain.history_complete() {
            return Err(EncodeError::HistoryCompacted {
                kept: terrain.events().len() as u64,
                applied: terrain.events_applied(),
            });
        }
        Ok(TerrainSnapshot {
            level_hash,
            tick: terrain.tick(),
            events: terrain.events().to_vec(),
        })
    }

    /// Encodes the snapshot as a message (see the [module documentation](self)); fails
    /// if it holds more events than [`TerrainSnapshot::decode`] accepts.
    pub fn encode(&self) -> Result<Vec<u8>, EncodeError> {
        self.encode_with_limits(&DecodeLimits::default())
    }

    /// Encodes the snapshot for a reader with `limits`.
    pub fn encode_with_limits(&self, limits: &DecodeLimits) -> Result<Vec<u8>, EncodeError> {
        let limit = limits.max_events;
        if self.events.len() as u64 > u64::from(limit) {
            return Err(EncodeError::TooLarge {
                what: "events in a snapshot",
                value: self.events.len() as u64,
                limit: limit.into(),
            });
        }
        let mut body = Writer::default();
        body.u64(self.level_hash);
        body.varint(self.tick.into());
        write_event_list(&mut body, &self.events)?;
        frame(MessageKind::Snapshot, &body.buf)
    }

    /// Decodes a snapshot message with the default [`DecodeLimits`].
    pub fn decode(bytes: &[u8]) -> Result<TerrainSnapshot, DecodeError> {
        TerrainSnapshot::decode_with_limits(bytes, &DecodeLimits::default())
    }

    /// Decodes a snapshot message within `limits`.
    pub fn decode_with_limits(
        bytes: &[u8],
        limits: &DecodeLimits,
    ) -> Result<TerrainSnapshot, DecodeError> {
        let mut r = unframe(bytes, MessageKind::Snapshot, limits)?;
        r.enter("snapshot", None);
        let level_hash = r.u64()?;
        let tick = r.varint_u32("snapshot tick")?;
        let events = read_event_list(&mut r, limits.max_events)?;
        Ok(TerrainSnapshot {
            level_hash,
            tick,
            events,
        })
    }
}

/// Encodes a batch of events as a message (see the [module documentation](self)).
///
/// Fails if an event is invalid, the ticks decrease, or the batch holds more events than
/// [`decode_events`] accepts ([`DecodeLimits::max_batch_events`]).
pub fn encode_events(events: &[Event]) -> Result<Vec<u8>, EncodeError> {
    encode_events_with_limits(events, &DecodeLimits::default())
}

/// Encodes a batch of events for a reader with `limits`.
pub fn encode_events_with_limits(
    events: &[Event],
    limits: &DecodeLimits,
) -> Result<Vec<u8>, EncodeError> {
    if events.len() as u64 > u64::from(limits.max_batch_events) {
        return Err(EncodeError::TooLarge {
            what: "events in a batch",
            value: events.len() as u64,
            limit: limits.max_batch_events.into(),
        });
    }
    let mut body = Writer::default();
    write_event_list(&mut body, events)?;
    frame(MessageKind::Events, &body.buf)
}

/// Decodes an event batch message with the default [`DecodeLimits`].
pub fn decode_events(bytes: &[u8]) -> Result<Vec<Event>, DecodeError> {
    decode_events_with_limits(bytes, &DecodeLimits::default())
}

/// Decodes an event batch message within `limits`.
pub fn decode_events_with_limits(
    bytes: &[u8],
    limits: &DecodeLimits,
) -> Result<Vec<Event>, DecodeError> {
    let mut r = unframe(bytes, MessageKind::Events, limits)?;
    read_event_list(&mut r, limits.max_batch_events)
}

/// The kind of the message starting with `bytes` (only its first byte is read).
pub fn message_kind(bytes: &[u8]) -> Result<MessageKind, DecodeError> {
    let mut r = Reader::new(bytes, 0, "message");
    let b = r.u8()?;
    MessageKind::from_u8(b)
        .ok_or_else(|| r.error_at(0, codec::malformed(format!("unknown message kind {b}"))))
}

/// The total length of the message whose first [`HEADER_LEN`] bytes are `header`: how
/// many bytes a stream reader must collect. Checks the kind, the version and the limit.
pub fn message_len(header: &[u8], limits: &DecodeLimits) -> Result<usize, DecodeError> {
    let mut r = Reader::new(header, 0, "message");
    message_kind(header)?;
    r.u8()?;
    check_version(&mut r)?;
    let max = limits.max_bytes.saturating_sub(HEADER_LEN + CHECKSUM_LEN);
    let at = r.offset();
    let body = r.u32()? as usize;
    if body > max {
        return Err(r.error_at(
            at,
            DecodeErrorKind::TooLarge {
                what: "body length",
                value: body as u64,
                limit: max as u64,
            },
        ));
    }
    Ok(HEADER_LEN + body + CHECKSUM_LEN)
}

/// Average bytes per event of a message holding `events` events (the whole message,
/// header and checksum included).
pub fn bytes_per_event(message: &[u8], events: usize) -> f64 {
    message.len() as f64 / events.max(1) as f64
}

pub(super) fn frame(kind: MessageKind, body: &[u8]) -> Result<Vec<u8>, EncodeError> {
    if u32::try_from(body.len()).is_err() {
        return Err(EncodeError::TooLarge {
            what: "message body length",
            value: body.len() as u64,
            limit: u32::MAX.into(),
        });
    }
    let mut w = Writer::default();
    w.u8(kind as u8);
    w.u8(VERSION);
    w.section(body);
    w.checksum();
    Ok(w.buf)
}

fn check_version(r: &mut Reader<'_>) -> Result<(), DecodeError> {
    let at = r.offset();
    let found = r.u8()?;
    if found != VERSION {
        return Err(r.error_at(
            at,
            DecodeErrorKind::UnsupportedVersion {
                found: found.into(),
                supported: VERSION.into(),
            },
        ));
    }
    Ok(())
}

/// Checks the framing and the checksum; returns a reader over the body.
pub(super) fn unframe<'a>(
    bytes: &'a [u8],
    kind: MessageKind,
    limits: &DecodeLimits,
) -> Result<Reader<'a>, DecodeError> {
    codec::check_len(bytes, limits)?;
    let mut r = Reader::new(bytes, 0, "message");
    let found = r.u8()?;
    if found != kind as u8 {
        return Err(r.error_at(
            0,
            DecodeErrorKind::UnexpectedKind {
                found,
                expected: kind as u8,
            },
        ));
    }
    check_version(&mut r)?;
    let body = r.section("body", limits.max_bytes)?;
    codec::check_crc(bytes, r.offset())?;
    Ok(body)
}

/// The part of an event a message's shape dictionary holds.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct Shape {
    kind: EventKind,
    radius: i32,
    rim: i32,
    grow_ticks: u16,
    material: u16,
}

impl Shape {
    fn of(e: &Event) -> Shape {
        Shape {
            kind: e.kind,
            radius: e.radius,
            rim: e.rim,
            grow_ticks: e.grow_ticks,
            material: e.material,
        }
    }

    fn event(self, center: [i32; 2], tick: u32) -> Event {
        Event {
            kind: self.kind,
            center,
            radius: self.radius,
            rim: self.rim,
            grow_ticks: self.grow_ticks,
            tick,
            material: self.material,
        }
    }
}

fn check_events(events: &[Event]) -> Result<(), EncodeError> {
    let mut previous = 0;
    for (index, e) in events.iter().enumerate() {
        e.validate()
            .map_err(|source| EncodeError::InvalidEvent { index, source })?;
        if e.tick < previous {
            return Err(EncodeError::TicksDecrease {
                index,
                tick: e.tick,
                previous,
            });
        }
        previous = e.tick;
    }
    Ok(())
}

/// The quantum shift: trailing zero bits shared by every centre coordinate.
fn quantum_shift(events: &[Event]) -> u8 {
    // Two's complement keeps the trailing zeros of negative coordinates.
    let bits = events
        .iter()
        .fold(0u32, |acc, e| acc | e.center[0] as u32 | e.center[1] as u32);
    if bits == 0 {
        0
    } else {
        (bits.trailing_zeros() as u8).min(MAX_SHIFT)
    }
}

pub(super) fn write_event_list(w: &mut Writer, events: &[Event]) -> Result<(), EncodeError> {
    check_events(events)?;
    w.varint(events.len() as u64);
    if events.is_empty() {
        return Ok(());
    }
    let q = quantum_shift(events);
    let min = |axis: usize| {
        events
            .iter()
            .map(|e| e.center[axis] >> q)
            .min()
            .unwrap_or(0)
    };
    let origin = [min(0), min(1)];
    w.u8(q);
    w.zigzag(origin[0].into());
    w.zigzag(origin[1].into());
    let (shapes, index) = dictionary(events);
    w.varint(shapes.len() as u64);
    for s in &shapes {
        write_shape(w, s);
    }
    let mut tick = 0;
    for (e, &i) in events.iter().zip(&index) {
        w.varint(u64::from(e.tick - tick));
        w.varint(i as u64);
        // Non-negative: the origin is the minimum; exact: q divides every coordinate.
        w.varint(((e.center[0] >> q) - origin[0]) as u64);
        w.varint(((e.center[1] >> q) - origin[1]) as u64);
        tick = e.tick;
    }
    Ok(())
}

/// The distinct shapes in order of first appearance, and each event's shape index.
fn dictionary(events: &[Event]) -> (Vec<Shape>, Vec<usize>) {
    let mut shapes = Vec::new();
    let mut lookup = HashMap::new();
    let index = events
        .iter()
        .map(|e| {
            let s = Shape::of(e);
            *lookup.entry(s).or_insert_with(|| {
                shapes.push(s);
                shapes.len() - 1
            })
        })
        .collect();
    (shapes, index)
}

fn write_shape(w: &mut Writer, s: &Shape) {
    w.u8(match s.kind {
        EventKind::Carve => 0,
        EventKind::Fill => 1,
    });
    // Non-negative: the events were validated.
    w.varint(s.radius as u64);
    w.varint(s.rim as u64);
    w.varint(s.grow_ticks.into());
    w.varint(s.material.into());
}

pub(super) fn read_event_list(
    r: &mut Reader<'_>,
    max_events: u32,
) -> Result<Vec<Event>, DecodeError> {
    r.enter("event list", None);
    let at = r.offset();
    let count = r.varint_max("event count", max_events.into())?;
    let mut events = Vec::new();
    if count > 0 {
        let (q, origin) = read_grid(r)?;
        let shapes = read_shapes(r, count)?;
        r.enter("event list", None);
        r.check_fits(at, count, MIN_EVENT_BYTES)?;
        let mut tick = 0u32;
        for i in 0..count {
            r.enter("event", Some(i));
            let e = read_event(r, &shapes, q, origin, tick)?;
            tick = e.tick;
            events.push(e);
        }
    }
    r.enter("event list", None);
    r.finish()?;
    Ok(events)
}

/// The quantum shift and the origin (in quanta).
fn read_grid(r: &mut Reader<'_>) -> Result<(u8, [i64; 2]), DecodeError> {
    let at = r.offset();
    let q = r.u8()?;
    if q > MAX_SHIFT {
        return Err(r.error_at(
            at,
            codec::malformed(format!("quantum shift {q} above {MAX_SHIFT}")),
        ));
    }
    let mut origin = [0i64; 2];
    for o in &mut origin {
        let at = r.offset();
        *o = r.zigzag()?;
        if o.unsigned_abs() > MAX_QUANTA {
            return Err(r.error_at(
                at,
                codec::malformed(format!("origin {o} quanta is out of range")),
            ));
        }
    }
    Ok((q, origin))
}

fn read_shapes(r: &mut Reader<'_>, events: u64) -> Result<Vec<Shape>, DecodeError> {
    let at = r.offset();
    let count = r.varint_max("shape count", events)?;
    if count == 0 {
        return Err(r.error_at(at, codec::malformed("no shapes for a non-empty event list")));
    }
    r.check_fits(at, count, MIN_SHAPE_BYTES)?;
    let mut shapes = Vec::new();
    for i in 0..count {
        r.enter("shape", Some(i));
        shapes.push(read_shape(r)?);
    }
    Ok(shapes)
}

fn read_shape(r: &mut Reader<'_>) -> Result<Shape, DecodeError> {
    let at = r.offset();
    let kind = match r.u8()? {
        0 => EventKind::Carve,
        1 => EventKind::Fill,
        k => {
            return Err(r.error_at(
                at,
                DecodeErrorKind::InvalidValue {
                    detail: format!("event kind {k} (0 = carve, 1 = fill)"),
                },
            ));
        }
    };
    let fixed = FIXED_MAX as u64;
    let shape = Shape {
        kind,
        radius: r.varint_max("radius", fixed)? as i32,
        rim: r.varint_max("rim", fixed)? as i32,
        grow_ticks: r.varint_max("grow ticks", u16::MAX.into())? as u16,
        material: r.varint_max("material", u16::MAX.into())? as u16,
    };
    if let Err(e) = shape.event([0, 0], 0).validate() {
        return Err(r.error_at(
            at,
            DecodeErrorKind::InvalidValue {
                detail: e.to_string(),
            },
        ));
    }
    Ok(shape)
}

fn read_event(
    r: &mut Reader<'_>,
    shapes: &[Shape],
    q: u8,
    origin: [i64; 2],
    tick: u32,
) -> Result<Event, DecodeError> {
    let at = r.offset();
    let delta = r.varint_u32("tick delta")?;
    let Some(tick) = tick.checked_add(delta) else {
        return Err(r.error_at(
            at,
            codec::malformed(format!("tick {tick} + {delta} overflows")),
        ));
    };
    let shape = r.varint_max("shape index", shapes.len() as u64 - 1)? as usize;
    let mut center = [0i32; 2];
    for (axis, c) in center.iter_mut().enumerate() {
        let off = r.varint_max("centre offset", MAX_QUANTA)? as i64;
        // |origin| and the offset are at most 2^25 and q at most 24: no i64 overflow.
        let fixed = (origin[axis] + off) << q;
        *c = i32::try_from(fixed).unwrap_or(i32::MAX);
    }
    let e = shapes[shape].event(center, tick);
    if let Err(err) = e.validate() {
        return Err(r.error_at(
            at,
            DecodeErrorKind::InvalidValue {
                detail: err.to_string(),
            },
        ));
    }
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn carve(x: i32, y: i32, tick: u32) -> Event {
        Event {
            kind: EventKind::Carve,
            center: [x, y],
            radius: 40 * 256,
            rim: 0,
            grow_ticks: 0,
            tick,
            material: 0,
        }
    }

    #[test]
    fn quantum_and_origin_cover_negative_coordinates() {
        let events = [carve(-128, 64, 3), carve(192, -640, 3), carve(0, 0, 9)];
        assert_eq!(quantum_shift(&events), 6);
        let bytes = encode_events(&events).unwrap();
        assert_eq!(decode_events(&bytes).unwrap(), events);
        assert_eq!(message_kind(&bytes).unwrap(), MessageKind::Events);
        assert_eq!(
            message_len(&bytes[..HEADER_LEN], &DecodeLimits::default()).unwrap(),
            bytes.len()
        );
    }

    #[test]
    fn encoder_rejects_invalid_and_unordered_events() {
        let bad = Event {
            radius: 0,
            ..carve(0, 0, 0)
        };
        assert!(matches!(
            encode_events(&[bad]),
            Err(EncodeError::InvalidEvent { index: 0, .. })
        ));
        let unordered = [carve(0, 0, 5), carve(0, 0, 4)];
        assert!(matches!(
            encode_events(&unordered),
            Err(EncodeError::TicksDecrease { index: 1, .. })
        ));
    }

    #[test]
    fn extreme_coordinates_round_trip() {
        let events = [
            carve(-FIXED_MAX, FIXED_MAX, 0),
            carve(FIXED_MAX, -FIXED_MAX, u32::MAX),
        ];
        let bytes = encode_events(&events).unwrap();
        assert_eq!(decode_events(&bytes).unwrap(), events);
    }
}
