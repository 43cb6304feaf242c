//! Errors of the replay and wire codecs.
//!
//! A [`DecodeError`] always says where the problem is (the section, such as `header`,
//! `inputs` or `event 17`, and the byte offset from the start of the input) and what it is
//! (a [`DecodeErrorKind`]). Decoders never panic on any input; every failure is one of these.

use std::borrow::Cow;

use thiserror::Error;

use craterfield_field::EventError;

/// A file or message was rejected.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("{section} at byte {offset}: {kind}")]
#[non_exhaustive]
pub struct DecodeError {
    /// The part of the input being read: `file`, `magic`, `version`, `header`, `inputs`,
    /// `hashes`, `checksum`, `message`, `body`, `shape 3`, `event 17`, ...
    pub section: Cow<'static, str>,
    /// Byte offset from the start of the input where the problem was found.
    pub offset: usize,
    /// What is wrong.
    pub kind: DecodeErrorKind,
}

impl DecodeError {
    /// An error in `section` at byte `offset`.
    pub fn new(
        section: impl Into<Cow<'static, str>>,
        offset: usize,
        kind: DecodeErrorKind,
    ) -> Self {
        DecodeError {
            section: section.into(),
            offset,
            kind,
        }
    }
}

/// What was wrong with a file or message (see [`DecodeError`] for where).
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum DecodeErrorKind {
    /// The input ended before a field or section it announces.
    #[error("truncated: {needed} more bytes needed, {available} available")]
    Truncated {
        /// Bytes the field or section needs.
        needed: usize,
        /// Bytes left in the input (or in the enclosing section).
        available: usize,
    },
    /// The input does not start with the expected magic bytes (it is not this kind of file).
    #[error("bad magic: expected {expected:02x?}, found {found:02x?}")]
    BadMagic {
        /// The magic of the format.
        expected: &'static [u8],
        /// What the input starts with (at most as many bytes as the magic).
        found: Vec<u8>,
    },
    /// The format version is not one this build reads.
    #[error("unsupported format version {found} (this build reads version {supported})")]
    UnsupportedVersion {
        /// The version in the input.
        found: u16,
        /// The version this build reads.
        supported: u16,
    },
    /// The stored CRC-32 does not match the contents (the data was damaged).
    #[error("checksum mismatch: stored {stored:#010x}, computed {computed:#010x}")]
    ChecksumMismatch {
        /// The CRC-32 stored in the input.
        stored: u32,
        /// The CRC-32 of the bytes it covers.
        computed: u32,
    },
    /// A count or length exceeds a decoding limit (checked before anything is allocated).
    #[error("{what} = {value} exceeds the limit of {limit}")]
    TooLarge {
        /// What was counted (`file length`, `ticks`, `event count`, ...).
        what: &'static str,
        /// The announced value.
        value: u64,
        /// The limit (from [`crate::DecodeLimits`] or from the format).
        limit: u64,
    },
    /// The bytes do not follow the format's structure.
    #[error("malformed: {detail}")]
    Malformed {
        /// What is wrong.
        detail: String,
    },
    /// A well-formed value is not acceptable (settings out of range, reserved input bits,
    /// an invalid event, ...).
    #[error("invalid value: {detail}")]
    InvalidValue {
        /// The value and the validator's message.
        detail: String,
    },
    /// Bytes remain after the last field of the input or of a section.
    #[error("{count} trailing bytes")]
    TrailingBytes {
        /// How many bytes are left over.
        count: usize,
    },
    /// A message of another kind than expected (see [`crate::wire::MessageKind`]).
    #[error("message kind {found} where kind {expected} was expected")]
    UnexpectedKind {
        /// The kind byte found.
        found: u8,
        /// The kind byte expected.
        expected: u8,
    },
}

/// Why a value could not be encoded.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum EncodeError {
    /// An event does not pass [`craterfield_field::Event::validate`].
    #[error("event {index} is invalid: {source}")]
    InvalidEvent {
        /// Its index in the input.
        index: usize,
        /// The validator's error.
        source: EventError,
    },
    /// Events must be in non-decreasing tick order.
    #[error("event {index} has tick {tick}, before the previous event's tick {previous}")]
    TicksDecrease {
        /// The index of the out-of-order event.
        index: usize,
        /// Its tick.
        tick: u32,
        /// The previous event's tick.
        previous: u32,
    },
    /// The value breaks an invariant of its type (see the type's documentation).
    #[error("cannot encode: {detail}")]
    Inconsistent {
        /// Which invariant.
        detail: String,
    },
    /// The terrain's history is no longer whole: compaction dropped events no cell
    /// reaches, so replaying the kept ones would not give its grid.
    #[error(
        "the terrain keeps {kept} of the {applied} events it applied (its log was compacted): send its state instead of its history"
    )]
    HistoryCompacted {
        /// Events the log keeps.
        kept: u64,
        /// Events applied over the terrain's life.
        applied: u64,
    },
    /// The value exceeds what the format can represent.
    #[error("{what} = {value} exceeds the format's limit of {limit}")]
    TooLarge {
        /// What was counted.
        what: &'static str,
        /// The value.
        value: u64,
        /// The limit.
        limit: u64,
    },
}
