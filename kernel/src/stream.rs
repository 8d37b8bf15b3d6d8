//! A seeded stream of uniform numbers, the same on every platform and version (SplitMix64, no
//! dependency): the random arms of the tests and benchmarks, and the states the base-parameter
//! reduction samples.

/// SplitMix64 from a seed: the same numbers on every platform.
pub struct Stream(pub u64);

impl Stream {
    /// The next number, uniform in `[0, 1)`.
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number, uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// One of `options`, uniformly.
    pub fn pick<T: Copy>(&mut self, options: &[T]) -> T {
        let i = (self.next_f64() * options.len() as f64) as usize;
        options[i.min(options.len() - 1)]
    }
}
