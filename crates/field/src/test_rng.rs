//! A seeded generator for the crate's own tests: xorshift64, no dependency, the same
//! numbers on every machine.

/// Numbers uniform in `[0, 1)`, 53 bits each, from a nonzero `seed`.
pub(crate) fn unit_f64(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}
