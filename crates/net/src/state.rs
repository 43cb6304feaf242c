//! World-state messages: a whole [`WorldState`] (bodies, counters, the terrain's grid and
//! kept events) for a peer that must continue from another's exact state, after a desync
//! or when it joins once the terrain's log was compacted.
//!
//! The frame is the one of [`super::wire`] (kind 3, [`MessageKind::State`]); the body is
//! the postcard encoding of [`WorldState`], whose arrays are flat so that decoding
//! allocates at most a few times the message's length, and whose length is held to
//! [`DecodeLimits::max_state_bytes`]. Decoding checks the frame, the checksum and the
//! encoding; what the state means (does it fit this world? do its parts match the hash
//! they carry?) is checked by [`World::resync`](craterfield_sim::World::resync), which changes
//! nothing when it refuses.

use super::codec::DecodeLimits;
use super::error::{DecodeError, EncodeError};
use super::wire::{MessageKind, frame, unframe};
use craterfield_sim::WorldState;

/// Encodes a world state as a message.
pub fn encode_state(state: &WorldState) -> Result<Vec<u8>, EncodeError> {
    encode_state_with_limits(state, &DecodeLimits::default())
}

/// Encodes a world state for a reader with `limits`: a message it would refuse as too
/// long is [`EncodeError::TooLarge`].
pub fn encode_state_with_limits(
    state: &WorldState,
    limits: &DecodeLimits,
) -> Result<Vec<u8>, EncodeError> {
    let body = postcard::to_stdvec(state).map_err(|e| EncodeError::Inconsistent {
        detail: format!("world state: {e}"),
    })?;
    let message = frame(MessageKind::State, &body)?;
    let limit = limits.max_state_bytes.min(limits.max_bytes);
    if message.len() > limit {
        return Err(EncodeError::TooLarge {
            what: "world state message length",
            value: message.len() as u64,
            limit: limit as u64,
        });
    }
    Ok(message)
}

/// Decodes a world-state message with the default [`DecodeLimits`].
pub fn decode_state(bytes: &[u8]) -> Result<WorldState, DecodeError> {
    decode_state_with_limits(bytes, &DecodeLimits::default())
}

/// Decodes a world-state message within `limits`.
pub fn decode_state_with_limits(
    bytes: &[u8],
    limits: &DecodeLimits,
) -> Result<WorldState, DecodeError> {
    let limits = DecodeLimits {
        max_bytes: limits.max_state_bytes.min(limits.max_bytes),
        ..*limits
    };
    let mut r = unframe(bytes, MessageKind::State, &limits)?;
    r.enter("world state", None);
    r.postcard()
}
