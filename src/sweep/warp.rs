//! The fold warp of the partial-slip patch: a coordinate `c'` in which the fold curve F₊ of `P`
//! (`docs/solver.md`, "Kink curves") lies on a root-cell boundary, so that no quadtree leaf
//! straddles its slope jump.
//!
//! The knot `K(γ)` is F₊ in the partial-slip coordinate `c` (traced by
//! [`fold_plus_at_extrapolated`]) from [`TRACK_FROM`] up, and a quintic Hermite blend from
//! `c*` (no warp) at `γ₀ = TRACK_FROM − BLEND` to that curve, matching its value, slope and
//! curvature, so that the warp is C² in γ. Below `TRACK_FROM` the fold is born (γ ≈ 2.904)
//! with a square-root start; there the quadtree still follows it, over 0.05 in γ instead of 0.6.
//!
//! Measured (`configs/full.toml` with `fold_warp = true`, 2 cores): at target 1e-4 no leaf
//! deeper than 5 above γ = 2.95 (the unwarped table has 160 depth-6 leaves along F₊), but the
//! birth region 2.9–2.95 still goes to depth 7, so the table is no smaller (899 leaves in the
//! partial-slip patch against 887) and its held-out error is 5.7e-5 against 3.0e-5 (a leaf
//! beside the fold now holds the steep side of P that the deep leaves resolved before); the
//! tracing adds about 8 s. At target 2.5e-5, tol 2.5e-6 the build finishes (2 555 leaves,
//! 248 s, held-out 2.1e-5, limited by the stick patch near α_c2), where the unwarped build went
//! past 150 000 nodes.

use oblique_lookup::surface::{PatchKind, Warp};
use rayon::prelude::*;

use super::SweepError;
use crate::physics::history::{fold_plus_at, fold_plus_at_extrapolated};
use crate::physics::regimes::alpha_c2;

/// γ from which the knot follows F₊ exactly.
pub const TRACK_FROM: f64 = 2.95;
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
    // Above F₊ the predicate fails up to α_c2: search down from 0.9 α_c2 (F₊ is at 0.85 α_c2
    // at γ = 2.92; below it, down to about 0.76 α_c2, the predicate holds).
    let mut guess = 0.9 * alpha_c2(tracked[0]);
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
    let slope = (-11.0 * k1 + 18.0 * k2 - 9.0 * k3 + 2.0 * k4) / (6.0 * STEP) * BLEND;
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
        // Between the knot grid points (0.01 apart) from one interval above TRACK_FROM, the fold
        // maps to c* to the precision of the cubic rule (measured: 3e-6 at 2.965, 1e-6 at 2.985,
        // below 1e-6 further up). In the first interval above TRACK_FROM the blend's junction
        // costs 1.3e-4 (at 2.955): the quadtree refines there, as it does below TRACK_FROM.
        let mut worst = 0.0_f64;
        for g in [2.965, 2.985, 3.005, 3.035, 3.115, 3.205, 3.275] {
            let guess = PatchKind::PartialSlip.alpha(g, w.knot_at(g), f64::INFINITY);
            let a = fold_plus_at_extrapolated(g, guess, TRACE_STEPS)
                .unwrap()
                .unwrap();
            let c = PatchKind::PartialSlip.coord(g, a, f64::INFINITY);
            let cp = w.apply(g, c);
            eprintln!("gamma {g}: c' - c* = {:.2e}", cp - 0.5);
            worst = f64::max(worst, (cp - 0.5).abs());
        }
        assert!(worst < 5e-6, "worst {worst}");
        {}
        // Below gamma_0 nothing moves; the blend is monotone between c* and the curve.
        assert_eq!(w.apply(2.5, 0.3), 0.3);
        assert!((w.knot_at(w.gamma_0) - 0.5).abs() < 1e-12);
        assert!(fold_warp(1.0, 2.8, 4).unwrap().is_none());
    }
}
