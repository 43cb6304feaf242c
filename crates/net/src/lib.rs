//! Replays and wire messages: the match and the destruction stream as bytes.
//!
//! - [`replay`]: replay files (settings, every input, periodic state hashes) that
//!   re-simulate a match bit for bit, with [`replay::verify`] to prove it;
//! - [`wire`]: messages of terrain events and terrain snapshots, for clients of an
//!   authoritative server and for late joiners;
//! - [`state`]: whole-world state messages, for a peer that resyncs after a desync;
//! - `codec`: the shared byte-level rules, and why the structured parts use postcard;
//! - `error`: what decoding and encoding report.
//!
//! Every format starts with a magic or kind byte and a version and ends with a CRC-32 of
//! the rest, and every decoder treats its input as hostile: it never panics, checks every
//! count against [`DecodeLimits`] and the remaining bytes before allocating, validates
//! every value (settings, inputs, events), and reports a [`DecodeError`] that names the
//! section and the byte offset.

#![forbid(unsafe_code)]

mod codec;
mod error;
pub mod replay;
#[cfg(feature = "ggrs")]
pub mod rollback;
pub mod state;
pub mod wire;

pub use codec::{DecodeLimits, crc32};
pub use error::{DecodeError, DecodeErrorKind, EncodeError};
pub use replay::{Recorder, Replay, VerifyError, VerifyReport, verify};
pub use state::{decode_state, encode_state};
pub use wire::{
    MessageKind, TerrainSnapshot, decode_events, encode_events, encode_events_with_limits,
};
