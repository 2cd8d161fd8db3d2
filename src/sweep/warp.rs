//! The fold warp of the partial-slip patch: a coordinate `c'` in which the fold curve F₊ of `P`
//! (`docs/solver.md`, "Kink curves") lies on a root-cell boundary, so that no quadtree leaf
//! straddles its slope jump.
//!
//! The knot `K(γ)` is F₊ in the partial-slip coordinate `c` (traced by
//! [`fold_plus_at_extrapolated`]) from [`TRACK_FROM`] up, and a quintic Hermite blend from
//! `c*` (no warp) at `γ₀ = TRACK_FROM − BLEND` to that curve, matching its value, slope and
//! curvature, so that the warp is C² in γ. Below `TRACK_FROM` the fold is born (γ ≈ 2.904)
//! with a square-root start; there the quadtree still follows it, over 0.1 in γ instead of 0.6.

use oblique_lookup::surface::{PatchKind, Warp};
use rayon::prelude::*;

use super::SweepError;
use crate::physics::history::{fold_plus_at, fold_plus_at_extrapolated};
use crate::physics::regimes::alpha_c2;

/// γ from which the knot follows F₊ exactly.
pub const TRACK_FROM: f64 = 3.0;
/// Width in γ of the blend below [`TRACK_FROM`].
pub const BLEND: f64 = 0.1;
/// Spacing of the knot grid in γ.
pub const STEP: f64 = 0.01;
/// Steps per contact time of the coarser of the two tracings (Richardson with twice as many).
pub const TRACE_STEPS: usize = 2048;

/// The fold warp for a partial-slip patch over `[gamma_lo, gamma_hi]` with `blocks_coord` root
/// cells along `c`, or `None` when the patch does not reach past [`TRACK_FROM`] (or starts
/// inside the blend, where the fold is too close to its birth to be tracked).
pub fn fold_warp(
    gamma_lo: f64,
    gamma_hi: f64,
    blocks_coord: usize,
) -> Result<Option<Warp>, SweepError> {
    let gamma_0 = TRACK_FROM - BLEND;
    if gamma_hi <= TRACK_FROM + 3.0 * STEP || gamma_lo > gamma_0 || blocks_coord < 2 {
        return Ok(None);
    }
    let n_blend = (BLEND / STEP).round() as usize;
    // Grid points from γ₀ until one at or beyond γ_hi (at least 4 tracked points).
    let n = (((gamma_hi - gamma_0) / STEP).ceil() as usize + 1).max(n_blend + 4);
    let grid: Vec<f64> = (0..n).map(|i| gamma_0 + i as f64 * STEP).collect();
    // Coarse continuation (1024 steps) for the guesses, then the Richardson pairs in parallel.
    let tracked = &grid[n_blend..];
    let mut guesses = Vec::with_capacity(tracked.len());
    // Above F₊ the predicate fails: search down from 0.7 α_c2 (F₊ is at 0.69 α_c2 at γ = 3).
    let mut guess = 0.75 * alpha_c2(tracked[0]);
    for &g in tracked {
        let a = fold_plus_at(g, guess, 1024)
            .map_err(|e| fold_error(g, &e.to_string()))?
            .ok_or_else(|| fold_error(g, "not found near the previous point"))?;
        guesses.push(a);
        guess = a;
    }
    let alphas = tracked
        .par_iter()
        .zip(guesses.par_iter())
        .map(|(&g, &a)| {
            fold_plus_at_extrapolated(g, a, TRACE_STEPS)
                .map_err(|e| fold_error(g, &e.to_string()))?
                .ok_or_else(|| fold_error(g, "not found at 2048/4096 steps"))
        })
        .collect::<Result<Vec<f64>, SweepError>>()?;
    let curve: Vec<f64> = tracked
        .iter()
        .zip(&alphas)
        .map(|(&g, &a)| PatchKind::PartialSlip.coord(g, a, f64::INFINITY))
        .collect();
    // c*: the root-cell boundary nearest to the mean of the curve.
    let mean = curve.iter().sum::<f64>() / curve.len() as f64;
    let bc = blocks_coord as f64;
    let c_star = ((mean * bc).round().clamp(1.0, bc - 1.0)) / bc;
    // Value, slope and curvature of the curve at TRACK_FROM (one-sided, second order), in units
    // of the blend's parameter t = (γ − γ₀)/BLEND.
    let (k1, k2, k3, k4) = (curve[0], curve[1], curve[2], curve[3]);
    let slope = (-3.0 * k1 + 4.0 * k2 - k3) / (2.0 * STEP) * BLEND;
    let curvature = (2.0 * k1 - 5.0 * k2 + 4.0 * k3 - k4) / (STEP * STEP) * BLEND * BLEND;
    let mut knot: Vec<f64> = (0..n_blend)
        .map(|i| {
            let t = i as f64 / n_blend as f64;
            let (t2, t3) = (t * t, t * t * t);
            let (t4, t5) = (t3 * t, t3 * t2);
            let h0 = 1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5;
            let h3 = 10.0 * t3 - 15.0 * t4 + 6.0 * t5;
            let h4 = -4.0 * t3 + 7.0 * t4 - 3.0 * t5;
            let h5 = 0.5 * t3 - t4 + 0.5 * t5;
            c_star * h0 + k1 * h3 + slope * h4 + curvature * h5
        })
        .collect();
    knot.extend(curve);
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
    Ok(Some(Warp {
        gamma_0,
        gamma_step: STEP,
        c_star,
        knot,
    }))
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
    fn the_warp_puts_the_fold_on_c_star() {
        let w = fold_warp(1.0, 3.3, 4).unwrap().expect("a warp up to 3.3");
        assert_eq!(w.c_star, 0.5);
        // On the knot grid from TRACK_FROM, the fold maps to c* to the precision of its tracing;
        // between grid points, to that of the cubic rule on the 0.01 grid.
        for g in [3.0, 3.03, 3.11, 3.2, 3.27] {
            let guess = PatchKind::PartialSlip.alpha(g, w.knot_at(g), f64::INFINITY);
            let a = fold_plus_at_extrapolated(g, guess, TRACE_STEPS)
                .unwrap()
                .unwrap();
            let c = PatchKind::PartialSlip.coord(g, a, f64::INFINITY);
            let cp = w.apply(g, c);
            assert!((cp - 0.5).abs() < 1e-6, "gamma {g}: c' = {cp}");
        }
        // Below gamma_0 nothing moves; the blend is monotone between c* and the curve.
        assert_eq!(w.apply(2.5, 0.3), 0.3);
        assert!((w.knot_at(w.gamma_0) - 0.5).abs() < 1e-12);
        assert!(fold_warp(1.0, 2.8, 4).unwrap().is_none());
    }
}
