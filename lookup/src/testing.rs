//! Deterministic pseudo-random numbers and query points for the tests, benchmarks and examples
//! of this workspace (not part of the API: hidden from the documentation, may change).

use crate::Surface;

/// Uniform numbers in `[0, 1)` from a xorshift64 generator seeded with `seed` (nonzero): the
/// 53 high bits of each state. No external RNG, the same stream on every platform.
pub fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `n` points over a table's domain drawn from `next`: γ uniform in `[gamma_min, gamma_max]`,
/// α log-uniform in `[1e-3, 1e3]`, with 10 % α = ∞ (about a third of them on the full-slip
/// line).
pub fn domain_points_from(
    surface: &Surface,
    n: usize,
    next: &mut impl FnMut() -> f64,
) -> Vec<(f64, f64)> {
    (0..n)
        .map(|_| {
            let g = surface.gamma_min + (surface.gamma_max - surface.gamma_min) * next();
            let a = if next() < 0.1 {
                f64::INFINITY
            } else {
                10f64.powf(-3.0 + 6.0 * next())
            };
            (g, a)
        })
        .collect()
}

/// [`domain_points_from`] with a fresh [`uniform`] stream.
pub fn domain_points(surface: &Surface, n: usize, seed: u64) -> Vec<(f64, f64)> {
    domain_points_from(surface, n, &mut uniform(seed))
}
