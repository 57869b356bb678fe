//! Small deterministic generators for the cut's unit tests: the same
//! sequences on every machine, without a dependency.

/// Knuth's MMIX linear congruential generator, its top 53 bits.
pub(super) fn lcg(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        s >> 11
    }
}

/// Marsaglia's xorshift64 (shifts 13, 7, 17), as a double in `[-1, 1)`.
pub(super) fn xorshift_unit(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}
