//! The fold F₋ of Thornton's law as a kink surface for the probes of `nodes.probe_kinks`
//! (`docs/solver.md`, "Kinks inside the slip regions"): the elastic F₋ continued to `e_n < 1`,
//! which plasticity brings to lower γ (born near γ 1.87 at `e_n` = 0.3, 2.37 at 1). `P` is
//! smooth on neither side of it, and a leaf it crosses errs more than its surplus predicts.

use rayon::prelude::*;

use super::{e_of_row, CurveScale, KinkSurface, SweepError, CONTINUATION_SPAN, PROBE_OFFSETS};
use oblique_solver::history::{
    fold_minus_at_thornton, fold_minus_free_below_thornton, fold_minus_thornton,
};
use oblique_table::surface::PatchKind;

/// Spacing in γ of the traced F₋ of Thornton's law (`α_F` changes by under 2 % a step).
pub const THORNTON_STEP: f64 = 0.02;
/// Rows of its surface per unit of `e_n` (0.01 apart; `α_F` changes by under 1 % a row).
pub const THORNTON_ROWS_PER_UNIT_E: f64 = 100.0;
/// Steps per contact time of the tracing (`α_F` within about 1.2e-6 of its converged value).
pub const THORNTON_TRACE_STEPS: usize = 2048;

/// F₋ of Thornton's law as a surface `α_F(γ, e_n)` over `gammas` × `e_range`, for the probes
/// of a table of this law: on a grid of γ spacing [`THORNTON_STEP`] from one step below
/// `max(γ_lo, γ_free)` (`γ_free` = [`fold_minus_free_below_thornton`]`(e_lo)`: no F₋ below
/// it) to one step beyond `γ_hi`, and rows `e_n = 1, 0.99, …` from one row above `e_hi` down
/// to one row below `e_lo` (or 0.3). Each column is traced from its lowest row up (F₋ is born
/// at lower γ the lower `e_n`): the first node by the full search ([`fold_minus_thornton`]),
/// the next ones by continuation from the rows below ([`fold_minus_at_thornton`], accepted
/// within `CONTINUATION_SPAN` of the extrapolated guess), up to the first row where it is not
/// found (F₋ ends there); the columns in parallel. `None` when the range holds no F₋.
pub fn thornton_fold_minus_surface(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<Option<KinkSurface>, SweepError> {
    let free = fold_minus_free_below_thornton(e_lo);
    if gamma_hi < free {
        return Ok(None);
    }
    let step = THORNTON_STEP;
    let rows = THORNTON_ROWS_PER_UNIT_E;
    let gamma_0 = gamma_lo.max(free) - step;
    let n_gamma = ((gamma_hi - gamma_0) / step - 1e-9).ceil().max(0.0) as usize + 2;
    let min_row = ((1.0 - oblique_solver::law::MIN_RESTITUTION) * rows).round() as usize;
    let n_e = (((1.0 - e_lo) * rows - 1e-9).ceil().max(0.0) as usize + 2).min(min_row + 1);
    let top = (((1.0 - e_hi) * rows + 1e-9).floor() as usize).saturating_sub(1);
    let columns = (0..n_gamma)
        .into_par_iter()
        .map(|i| column(gamma_0 + i as f64 * step, top, n_e))
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    let values = columns.concat();
    if values.iter().all(|v| !v.is_finite()) {
        return Ok(None);
    }
    Ok(Some(KinkSurface {
        name: "F-",
        patch: PatchKind::PartialSlip,
        scale: CurveScale::Ln,
        gamma_0,
        step,
        rows_per_unit: rows,
        n_gamma,
        n_e,
        offsets: &PROBE_OFFSETS,
        extrapolate: false,
        knotted: false,
        values,
    }))
}

/// One column of [`thornton_fold_minus_surface`]: `ln α_F` at `γ` on rows `top..n_e`, from the
/// lowest row up; NaN below the first row where F₋ is found (none: the whole column) and from
/// the first row above it where it is not.
fn column(gamma: f64, top: usize, n_e: usize) -> Result<Vec<f64>, SweepError> {
    let mut out = vec![f64::NAN; n_e];
    let mut found: Vec<f64> = Vec::new();
    for l in (top..n_e).rev() {
        let e_n = e_of_row(l, THORNTON_ROWS_PER_UNIT_E);
        let fail = |what: String| SweepError::Kink {
            curve: "F-",
            gamma,
            what: format!("at e_n = {e_n}: {what}"),
        };
        let k = found.len();
        let guess = match k {
            0 => None,
            1 => Some(found[0]),
            2 => Some(2.0 * found[1] - found[0]),
            _ => Some(3.0 * found[k - 1] - 3.0 * found[k - 2] + found[k - 3]),
        };
        let a = match guess {
            None => fold_minus_thornton(gamma, e_n, THORNTON_TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?,
            Some(g) => fold_minus_at_thornton(gamma, e_n, g.exp(), THORNTON_TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?
                .filter(|a| (a.ln() - g).abs() <= CONTINUATION_SPAN),
        };
        match a {
            Some(a) => {
                out[l] = a.ln();
                found.push(a.ln());
            }
            // Not at the lowest row: none at higher e_n either (F₋ is born at lower γ the
            // lower e_n); above the rows where it was found: it has ended.
            None => break,
        }
    }
    Ok(out)
}
