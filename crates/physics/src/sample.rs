//! Deterministic pseudo-random numbers for sampling the `(γ, α)` plane: the held-out check points
//! of a table build, `sweep verify`'s sample, and the random points of tests, benchmarks and
//! probes. One generator (SplitMix64), no external crate, the same stream for a seed on every
//! platform.

/// SplitMix64 (Steele, Lea & Flood 2014): the state advances by the golden-ratio increment and
/// each output is the state mixed by two multiply–xorshift rounds.
#[derive(Debug, Clone)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next number in `[0, 1)` (the 53 high bits of the next output).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The stream of [`SplitMix`] seeded with `seed`, as a closure.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut rng = SplitMix(seed);
    move || rng.uniform()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stream_is_uniform_in_the_unit_interval_and_repeatable() {
        let mut a = uniform(1);
        let v: Vec<f64> = (0..100_000).map(|_| a()).collect();
        assert!(v.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
        let below = v.iter().filter(|&&x| x < 0.25).count() as f64 / v.len() as f64;
        assert!((below - 0.25).abs() < 0.005, "P(x < 1/4) = {below}");
        let mut b = SplitMix(1);
        assert!(v.iter().take(10).all(|&x| x == b.uniform()));
        // SplitMix64 of seed 0: the first output is 0xE220A8397B1DCDAF (the reference
        // implementation's published value).
        let mut z = SplitMix(0);
        assert_eq!(
            z.uniform(),
            (0xE220_A839_7B1D_CDAFu64 >> 11) as f64 / (1u64 << 53) as f64
        );
    }
}
