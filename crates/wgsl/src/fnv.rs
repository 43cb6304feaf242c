//! A stable 64-bit FNV-1a hasher for shader fingerprints and cache keys.
//!
//! `std::hash::DefaultHasher` may change its algorithm between Rust releases; keys that name
//! cached pipelines (and that tests pin) need a hash whose value is fixed by this code alone.

/// FNV-1a over bytes, 64-bit variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fnv64(u64);

impl Fnv64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    /// A hasher in its initial state.
    pub fn new() -> Fnv64 {
        Fnv64(Self::OFFSET_BASIS)
    }

    /// Mix in bytes.
    pub fn bytes(&mut self, bytes: &[u8]) -> &mut Self {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(Self::PRIME);
        }
        self
    }

    /// Mix in a `u32` (little-endian bytes).
    pub fn u32(&mut self, v: u32) -> &mut Self {
        self.bytes(&v.to_le_bytes())
    }

    /// Mix in a `u64` (little-endian bytes).
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.bytes(&v.to_le_bytes())
    }

    /// Mix in an `f32` by its bits, so `0.0` and `-0.0` differ and the value is exact.
    pub fn f32(&mut self, v: f32) -> &mut Self {
        self.u32(v.to_bits())
    }

    /// The hash so far.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

impl Default for Fnv64 {
    fn default() -> Self {
        Fnv64::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_published_fnv1a_test_vectors() {
        assert_eq!(Fnv64::new().finish(), 0xcbf2_9ce4_8422_2325);
        assert_eq!(Fnv64::new().bytes(b"a").finish(), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(
            Fnv64::new().bytes(b"foobar").finish(),
            0x8594_4171_f739_67e8
        );
    }

    #[test]
    fn float_bits_are_hashed_exactly() {
        assert_ne!(
            Fnv64::new().f32(0.0).finish(),
            Fnv64::new().f32(-0.0).finish()
        );
        assert_eq!(
            Fnv64::new().f32(1.5).finish(),
            Fnv64::new().u32(1.5f32.to_bits()).finish()
        );
    }
}
