//! The fold edge of the partial-slip patch: a coordinate `c'` in which the fold curve F₊ of `P`
//! (`docs/solver.md`, "Kink curves" and "The fold edge") lies on the root-cell boundary
//! `c' = c_star`, graded below it so that `P` is smooth on both sides.
//!
//! F₊ is born at γ* ≈ 2.904 inside the slip region with a square-root start. The warp applies
//! from a lattice position `start` along γ: the first multiple of `2^-START_DEPTH` root rows at
//! or above [`FOLD_FROM`]. Below it the quadtree follows the young fold (its slope jump is
//! below 0.07 there); no leaf straddles `start` (the sweep splits any cell that does), so the
//! warp may jump there. The knot `K(γ)` is F₊ in the partial-slip coordinate `c`, traced by
//! [`fold_plus_at_extrapolated`] on a grid of [`STEP`] in γ.
//!
//! Measured (`configs/full.toml`: target 2e-5, tol 5e-6, 2 idle cores): 1 238 partial-slip
//! leaves and a held-out maximum of 8.5e-6 over 1 500 checks in 46.7 s, where the unwarped
//! build of the same target goes past 150 000 nodes (`docs/benchmarks.md`, "Table builds").

use oblique_table::surface::{PatchKind, Warp};
use rayon::prelude::*;

use super::SweepError;
use oblique_physics::regimes::alpha_c2;
use oblique_solver::history::{fold_plus_at, fold_plus_at_extrapolated};

/// Lowest γ of the warp: just above the birth of the fold proper (γ* ≈ 2.904,
/// `docs/solver.md`), where it can be traced.
pub const FOLD_FROM: f64 = 2.906;
/// `start` is a multiple of `2^-START_DEPTH` root rows (cells deeper than this are not forced).
pub const START_DEPTH: u32 = 4;
/// Spacing of the knot grid in γ.
pub const STEP: f64 = 0.0025;
/// Steps per contact time of the coarser of the two tracings (Richardson with twice as many).
pub const TRACE_STEPS: usize = 2048;
/// The sequential continuation that supplies first guesses visits every this-many grid points.
const GUESS_EVERY: usize = 5;

/// `α_F/α_c2` of F₊ at a few γ (`docs/solver.md`), linearly interpolated: the first guess of
/// the continuation, which must land between 0.76 α_c2 and F₊ (where the tracing predicate
/// holds).
fn first_guess(gamma: f64) -> f64 {
    const TABLE: [(f64, f64); 9] = [
        (2.906, 0.887),
        (2.91, 0.876),
        (2.92, 0.853),
        (2.95, 0.776),
        (3.0, 0.685),
        (3.1, 0.5535),
        (3.2, 0.4591),
        (3.3, 0.3872),
        (3.5, 0.2856),
    ];
    let ratio = crate::kink::lerp_table(&TABLE, gamma);
    // Slightly below the fold: the continuation steps up from there.
    0.98 * ratio * alpha_c2(gamma)
}

/// The lattice position (root-row units) where the warp of a patch over `[gamma_lo,
/// gamma_hi]` with `blocks_gamma` root rows starts, and γ there; `None` when the patch does not
/// reach far enough past [`FOLD_FROM`] (at least four knot intervals).
pub fn start_row(gamma_lo: f64, gamma_hi: f64, blocks_gamma: usize) -> Option<(f64, f64)> {
    let bg = blocks_gamma as f64;
    let v = (FOLD_FROM - gamma_lo) / (gamma_hi - gamma_lo) * bg;
    let scale = f64::from(1u32 << START_DEPTH);
    let start = (v.max(0.0) * scale).ceil() / scale;
    let from = gamma_lo + (gamma_hi - gamma_lo) * start / bg;
    (start > 0.0 && start < bg && from + 4.0 * STEP <= gamma_hi).then_some((start, from))
}

/// The fold warp for a partial-slip patch over `[gamma_lo, gamma_hi]` with `blocks_gamma` ×
/// `blocks_coord` root cells, or `None` when the patch does not reach past [`FOLD_FROM`] (see
/// [`start_row`]) or has a single root column along `c`.
pub fn fold_warp(
    gamma_lo: f64,
    gamma_hi: f64,
    blocks_gamma: usize,
    blocks_coord: usize,
) -> Result<Option<Warp>, SweepError> {
    let Some((start, gamma_0)) = start_row(gamma_lo, gamma_hi, blocks_gamma) else {
        return Ok(None);
    };
    if blocks_coord < 2 {
        return Ok(None);
    }
    // Grid points from γ₀ until one at or beyond γ_hi.
    let n = (((gamma_hi - gamma_0) / STEP).ceil() as usize + 1).max(4);
    let grid: Vec<f64> = (0..n).map(|i| gamma_0 + i as f64 * STEP).collect();
    // Coarse continuation (1024 steps) on every GUESS_EVERY-th grid point (and the last), the
    // guesses between interpolated in ln α; then the Richardson pairs in parallel, each
    // searching from its guess.
    let coarse: Vec<usize> = (0..n)
        .filter(|&i| i % GUESS_EVERY == 0 || i == n - 1)
        .collect();
    let mut found = Vec::with_capacity(coarse.len());
    let mut guess = first_guess(grid[0]);
    for &i in &coarse {
        let g = grid[i];
        let a = fold_plus_at(g, guess, 1024)
            .map_err(|e| fold_error(g, &e.to_string()))?
            .ok_or_else(|| fold_error(g, "not found near the previous point"))?;
        found.push(a.ln());
        guess = a;
    }
    let guesses: Vec<f64> = (0..n)
        .map(|i| {
            let k = coarse.partition_point(|&j| j <= i) - 1;
            if coarse[k] == i {
                return found[k].exp();
            }
            let (i0, i1) = (coarse[k], coarse[k + 1]);
            let t = (i - i0) as f64 / (i1 - i0) as f64;
            (found[k] + t * (found[k + 1] - found[k])).exp()
        })
        .collect();
    let alphas = grid
        .par_iter()
        .zip(guesses.par_iter())
        .map(|(&g, &a)| {
            fold_plus_at_extrapolated(g, a, TRACE_STEPS)
                .map_err(|e| fold_error(g, &e.to_string()))?
                .ok_or_else(|| fold_error(g, "not found at 2048/4096 steps"))
        })
        .collect::<Result<Vec<f64>, SweepError>>()?;
    let knot: Vec<f64> = grid
        .iter()
        .zip(&alphas)
        .map(|(&g, &a)| PatchKind::PartialSlip.coord(g, a, f64::INFINITY))
        .collect();
    // c*: the root-cell boundary nearest to the mean of the curve.
    let mean = knot.iter().sum::<f64>() / knot.len() as f64;
    let bc = blocks_coord as f64;
    let c_star = ((mean * bc).round().clamp(1.0, bc - 1.0)) / bc;
    if let Some((i, &k)) = knot
        .iter()
        .enumerate()
        .find(|(_, &k)| !(k > 0.02 && k < 0.98))
    {
        return Err(fold_error(
            grid[i],
            &format!("its patch coordinate {k} is too close to the patch edge for a warp"),
        ));
    }
    Warp::new(start, gamma_0, STEP, c_star, knot)
        .map(Some)
        .map_err(|m| fold_error(gamma_0, &format!("the warp is invalid: {m}")))
}

fn fold_error(gamma: f64, what: &str) -> SweepError {
    SweepError::Fold {
        gamma,
        what: what.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_start_is_the_first_dyadic_row_above_the_birth() {
        // full.toml's partial-slip patch: [1, 3.5], 5 root rows of 0.5.
        let (s, g) = start_row(1.0, 3.5, 5).expect("reaches past the fold");
        assert_eq!(s, 3.8125);
        assert_eq!(g, 1.0 + 2.5 * s / 5.0);
        assert!((FOLD_FROM..FOLD_FROM + 0.5 / 16.0).contains(&g), "{g}");
        assert!(start_row(1.0, 2.9, 4).is_none());
        // One root row of 0.08 and 0.09: the start is 15/16 or 13/16 of it; from 2.91 the
        // patch is too short for four knot intervals, from 2.908125 it is not.
        assert!(
            start_row(2.835, 2.915, 1).is_none(),
            "too short for four knot intervals"
        );
        assert!(start_row(2.835, 2.925, 1).is_some());
    }

    #[test]
    fn the_warp_puts_the_fold_on_c_star() {
        let w = fold_warp(1.0, 3.3, 5, 4)
            .unwrap()
            .expect("a warp up to 3.3");
        assert_eq!(w.c_star(), 0.5);
        // Midway between the knot grid points (0.0025 apart), the fold maps to c* to the precision of
        // the cubic rule for the knot and of the grading (c' − c* ∝ √(K − c_F) below it).
        let mut worst = 0.0_f64;
        for g in [2.935, 2.985, 3.005, 3.035, 3.115, 3.205, 3.275] {
            let guess = PatchKind::PartialSlip.alpha(g, w.knot_at(g), f64::INFINITY);
            let a = fold_plus_at_extrapolated(g, guess, TRACE_STEPS)
                .unwrap()
                .unwrap();
            let c = PatchKind::PartialSlip.coord(g, a, f64::INFINITY);
            let k = w.knot_at(g);
            worst = f64::max(worst, (c - k).abs());
        }
        assert!(worst < 5e-6, "worst |c_F - K| {worst}");
        assert!((w.apply(3.1, w.knot_at(3.1)) - 0.5).abs() < 1e-15);
    }
}
