//! Helpers of the bounded fuzz tests (tests/reliability/mbdyn_fuzz.rs, tests/reliability/reader_fuzz.rs): the time
//! budget and seed from the environment, and a seeded xorshift generator.

use std::time::Duration;

/// Time given to each generator (`default` unless `ROMDYN_FUZZ_SECONDS` says otherwise).
pub fn budget(default: Duration) -> Duration {
    std::env::var("ROMDYN_FUZZ_SECONDS").ok().and_then(|s| s.parse::<f64>().ok()).map_or(default, Duration::from_secs_f64)
}

/// Extra seed from `ROMDYN_FUZZ_SEED` (0 by default).
pub fn seed_offset() -> u64 {
    std::env::var("ROMDYN_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(0)
}

/// xorshift64.
pub struct Rng(pub u64);

impl Rng {
    /// A generator for `seed`, varied by `ROMDYN_FUZZ_SEED`.
    pub fn seeded(seed: u64) -> Self {
        Rng(seed ^ seed_offset().wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    pub fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}
