//! Kink curves of `P` whose leaves the refinement's prediction cannot be trusted on, traced
//! before the build so that every leaf they cross is measured by direct simulations
//! (`nodes.probe_kinks`, `docs/table-format.md`, "The stated error bound").
//!
//! The one treated today is the fold curve F₋ of the partial-slip patch (`docs/solver.md`,
//! "Kink curves": a `−μF_N` episode late in the restitution phase vanishes as α grows; γ ≳ 2.40,
//! α ≈ 0.31–0.52). Above it `P` departs from its smooth continuation like `(α − α_F)^{3/2}`:
//! at γ = 3.3589 the slope `dP/d ln α` falls from 0.345 at F₋ by `0.9 √(α/α_F − 1)` (0.020 at
//! 5e-4 above, 0.090 at 1e-2). A cubic across such a point errs in proportion to `h^{3/2}`, not
//! `h²`, and the quarter-surplus prediction of a leaf that F₋ crosses was up to 4.2× below the
//! leaf's error in `tables/full.h5` (1.61e-5 at γ = 3.35889, α = 0.326995; `docs/accuracy.md`).

use rayon::prelude::*;

use super::SweepError;
use oblique_solver::history::fold_minus_at;
use oblique_table::surface::stencil4;

/// Lowest γ at which F₋ is traced: its predicate first holds at γ ≈ 2.398 (2048 steps); below
/// it the curve is younger than its tracing and its slope change smaller.
pub const FOLD_MINUS_FROM: f64 = 2.40;
/// Spacing of the traced points in γ.
pub const STEP: f64 = 0.01;
/// Steps per contact time of the tracing (α_F within about 1e-5 relative of the converged
/// curve, `docs/solver.md`; a leaf's node spacing next to F₋ is ≥ 1e-3 relative).
pub const TRACE_STEPS: usize = 2048;

/// A kink curve `α_K(γ)` traced on an even grid of γ, interpolated (4-point Lagrange in
/// `ln α`) between the grid points; undefined outside the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct KinkCurve {
    gamma_0: f64,
    step: f64,
    ln_alpha: Vec<f64>,
}

impl KinkCurve {
    /// `α_K(γ)`, or `None` outside `[γ₀, γ₀ + (n − 1)·step]`.
    pub fn alpha_at(&self, gamma: f64) -> Option<f64> {
        let n = self.ln_alpha.len();
        let u = (gamma - self.gamma_0) / self.step;
        if !(u >= 0.0 && u <= (n - 1) as f64) {
            return None;
        }
        let (start, w) = stencil4(u, n);
        let l = &self.ln_alpha[start..start + 4];
        Some((w[0] * l[0] + w[1] * l[1] + w[2] * l[2] + w[3] * l[3]).exp())
    }

    /// The γ range of the curve.
    pub fn gamma_range(&self) -> (f64, f64) {
        (
            self.gamma_0,
            self.gamma_0 + (self.ln_alpha.len() - 1) as f64 * self.step,
        )
    }
}

/// The piecewise-linear interpolant of `table` (`(x, y)` pairs, `x` increasing) at `x`, held
/// constant beyond the first and the last pair: the first guesses of the fold tracings.
pub(crate) fn lerp_table(table: &[(f64, f64)], x: f64) -> f64 {
    match table.iter().position(|&(t, _)| t >= x) {
        Some(0) => table[0].1,
        Some(i) => {
            let ((x0, y0), (x1, y1)) = (table[i - 1], table[i]);
            y0 + (y1 - y0) * (x - x0) / (x1 - x0)
        }
        None => table[table.len() - 1].1,
    }
}

/// `α_F` of F₋ at a few γ (`docs/solver.md`, "Kink curves"), linearly interpolated and raised by
/// 1 %: the first guess of each point's search, which must lie above F₋ (within a factor `e`)
/// or inside the narrow interval below it where the tracing predicate holds.
fn first_guess(gamma: f64) -> f64 {
    const TABLE: [(f64, f64); 9] = [
        (2.4, 0.5211),
        (2.5, 0.4821),
        (2.6, 0.4516),
        (2.7, 0.4265),
        (2.8, 0.4052),
        (2.9, 0.3870),
        (3.0, 0.3711),
        (3.2, 0.3447),
        (3.5, 0.3144),
    ];
    let a = lerp_table(&TABLE, gamma);
    1.01 * a
}

/// F₋ over the part of `[gamma_lo, gamma_hi]` at or above [`FOLD_MINUS_FROM`], on a grid of
/// [`STEP`] from there to the first point at or beyond `gamma_hi` (each point located to
/// ≈1e-10 in `ln α` at [`TRACE_STEPS`] steps, in parallel); `None` when the range ends less than
/// three steps above [`FOLD_MINUS_FROM`].
pub fn fold_minus_curve(gamma_lo: f64, gamma_hi: f64) -> Result<Option<KinkCurve>, SweepError> {
    let gamma_0 = gamma_lo.max(FOLD_MINUS_FROM);
    if gamma_hi < gamma_0 + 3.0 * STEP {
        return Ok(None);
    }
    let n = ((gamma_hi - gamma_0) / STEP).ceil() as usize + 1;
    let ln_alpha = (0..n)
        .into_par_iter()
        .map(|i| {
            let g = gamma_0 + i as f64 * STEP;
            let fail = |what: String| SweepError::Kink {
                curve: "F-",
                gamma: g,
                what,
            };
            fold_minus_at(g, first_guess(g), TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?
                .map(f64::ln)
                .ok_or_else(|| fail("not found near its tabulated position".into()))
        })
        .collect::<Result<Vec<f64>, SweepError>>()?;
    Ok(Some(KinkCurve {
        gamma_0,
        step: STEP,
        ln_alpha,
    }))
}

/// Where a leaf next to a kink is measured, in node intervals from the kink along the patch
/// coordinate, on every node row along γ: the cubic's error is largest within
/// about one interval of the kink, on either side (across F₋, measured against direct
/// simulations: at γ = 3.3589 in a leaf of depth 6, 1.6e-5 at 0.35 intervals below it; at
/// γ = 3.276 in a leaf of depth 7, 4.6e-6 at 0.8 above; under 2e-7 beyond 1.5 intervals).
pub const PROBE_OFFSETS: [f64; 7] = [-0.7, -0.35, 0.0, 0.35, 0.7, 1.05, 1.4];

/// `n` points next to the fold curve F₋ (`curve`, from [`fold_minus_curve`]): `γ` uniform over
/// the curve's range within `[gamma_min, gamma_max]`, `α = α_F(γ)(1 + s·r)` with `s = ±1` and
/// `r = 10^u`, `u` uniform in `[−4, −2]` (the finest leaves next to F₋ are about 1e-3 wide in
/// `α/α_F`), `e_n = 1`. The same `seed` gives the same points (`sweep verify --near-fold`).
pub fn near_fold_minus_points(
    curve: &KinkCurve,
    gamma_min: f64,
    gamma_max: f64,
    n: usize,
    seed: u64,
) -> Vec<oblique_table::surface::Point> {
    let (c_lo, c_hi) = curve.gamma_range();
    let (lo, hi) = (gamma_min.max(c_lo), gamma_max.min(c_hi));
    // An empty range (or a NaN edge) gives no points.
    if lo > hi || lo.is_nan() || hi.is_nan() {
        return Vec::new();
    }
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let gamma = (lo + (hi - lo) * rng.uniform()).min(hi);
        let r = 10f64.powf(-4.0 + 2.0 * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        if let Some(alpha_f) = curve.alpha_at(gamma) {
            out.push(oblique_table::surface::Point::new(
                gamma,
                alpha_f * (1.0 + sign * r),
                1.0,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_traced_fold_minus_matches_its_continuation() {
        // The tabulated positions of docs/solver.md and the sequential continuation (kinkmap):
        // 0.344692 at γ = 3.2, 0.500226 at 2.45.
        let curve = fold_minus_curve(2.3, 3.25).unwrap().expect("a curve");
        assert_eq!(curve.gamma_range().0, FOLD_MINUS_FROM);
        assert!(curve.gamma_range().1 >= 3.25);
        for (g, want) in [(3.2, 0.344692), (2.45, 0.500226)] {
            let a = curve.alpha_at(g).unwrap();
            assert!((a / want - 1.0).abs() < 1e-5, "{a} at {g}");
        }
        // Between grid points: the 4-point rule against a located point.
        let g = 2.8137;
        let direct = fold_minus_at(g, 0.41, TRACE_STEPS).unwrap().unwrap();
        let a = curve.alpha_at(g).unwrap();
        assert!((a / direct - 1.0).abs() < 1e-6, "{a} vs {direct}");
        assert_eq!(curve.alpha_at(2.39), None);
        assert_eq!(curve.alpha_at(3.4), None);
        assert!(fold_minus_curve(1.0, 2.42).unwrap().is_none());
        // Points next to it: within 1e-2 (relative) of the curve, both sides, over the range
        // asked for; the same seed, the same points.
        let pts = near_fold_minus_points(&curve, 2.3, 3.0, 200, 5);
        assert_eq!(pts.len(), 200);
        assert_eq!(pts, near_fold_minus_points(&curve, 2.3, 3.0, 200, 5));
        let d: Vec<f64> = pts
            .iter()
            .map(|p| p.alpha / curve.alpha_at(p.gamma).unwrap() - 1.0)
            .collect();
        assert!(pts
            .iter()
            .all(|p| (2.4..=3.0).contains(&p.gamma) && p.e_n == 1.0));
        assert!(d
            .iter()
            .all(|d| (1e-4 - 1e-15..=1e-2 + 1e-15).contains(&d.abs())));
        assert!(d.iter().any(|&d| d < 0.0) && d.iter().any(|&d| d > 0.0));
        assert!(near_fold_minus_points(&curve, 1.0, 2.0, 10, 5).is_empty());
    }
}
