//! The fold F₋ and the end-of-contact curve E₋ of Thornton's law as kink surfaces for the
//! probes of `nodes.probe_kinks` (`docs/solver.md`, "Kinks inside the slip regions"): the
//! elastic kinks continued to `e_n < 1`, which plasticity brings to lower γ (F₋ born near
//! γ 1.87 at `e_n` = 0.3, 2.37 at 1; E₋ reaching γ 1.5 at small `e_n`). `P` is smooth on neither
//! side of F₋ and changes its curvature fast on one side of E₋; a leaf either crosses errs
//! more than its surplus predicts (next to E₋ up to 2.2e-4 against a bound of 1.43e-4 in a
//! table over γ 2.2–2.4, `e_n` 0.5–0.7, target 1e-4, without these probes).

use rayon::prelude::*;

use super::{e_of_row, CurveScale, KinkSurface, SweepError, CONTINUATION_SPAN, PROBE_OFFSETS};
use oblique_solver::history::{
    end_minus_at_thornton_within, end_minus_edges_thornton, fold_minus_at_thornton,
    fold_minus_free_below_thornton, fold_minus_thornton, has_restitution_plus,
    loading_band_thornton, loading_band_top_within_thornton, restitution_plus_change_thornton,
    restitution_plus_strip_thornton, slip_history_thornton,
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
    let grid = ColumnGrid::new(
        (gamma_lo.max(free), gamma_hi),
        (e_lo, e_hi),
        THORNTON_ROWS_PER_UNIT_E,
    );
    let columns = (0..grid.n_gamma)
        .into_par_iter()
        .map(|i| column(grid.gamma(i), grid.top, grid.n_e))
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    Ok(grid.surface("F-", false, columns.concat()))
}

/// The grid of a surface traced column by column from its lowest row up (F₋ and the `+`
/// strip): columns [`THORNTON_STEP`] apart from one step below `γ_from` to one beyond `γ_hi`,
/// rows `1/rows` apart in `e_n` from `e_n` = 1 down to one below `e_lo` (at least 0.3), the
/// first traced one (`top`) one above `e_hi`.
struct ColumnGrid {
    gamma_0: f64,
    rows: f64,
    n_gamma: usize,
    n_e: usize,
    top: usize,
}

impl ColumnGrid {
    fn new((gamma_from, gamma_hi): (f64, f64), (e_lo, e_hi): (f64, f64), rows: f64) -> Self {
        let step = THORNTON_STEP;
        let gamma_0 = gamma_from - step;
        let n_gamma = ((gamma_hi - gamma_0) / step - 1e-9).ceil().max(0.0) as usize + 2;
        let min_row = ((1.0 - oblique_solver::law::MIN_RESTITUTION) * rows).round() as usize;
        let n_e = (((1.0 - e_lo) * rows - 1e-9).ceil().max(0.0) as usize + 2).min(min_row + 1);
        let top = (((1.0 - e_hi) * rows + 1e-9).floor() as usize).saturating_sub(1);
        ColumnGrid {
            gamma_0,
            rows,
            n_gamma,
            n_e,
            top,
        }
    }

    /// γ of column `i`.
    fn gamma(&self, i: usize) -> f64 {
        self.gamma_0 + i as f64 * THORNTON_STEP
    }

    /// The partial-slip surface `name` of `ln α` on this grid (`values` column by column),
    /// `None` where no node holds it.
    fn surface(
        &self,
        name: &'static str,
        extrapolate: bool,
        values: Vec<f64>,
    ) -> Option<KinkSurface> {
        values.iter().any(|v| v.is_finite()).then_some(KinkSurface {
            name,
            patch: PatchKind::PartialSlip,
            scale: CurveScale::Ln,
            gamma_0: self.gamma_0,
            step: THORNTON_STEP,
            rows_per_unit: self.rows,
            n_gamma: self.n_gamma,
            n_e: self.n_e,
            offsets: &PROBE_OFFSETS,
            extrapolate,
            knotted: false,
            values,
        })
    }
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
        let guess = (!found.is_empty()).then(|| extrapolated(&found));
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

/// Spacing of the grid of Thornton's E₋ in γ and in `e_n` (as the Kelvin–Voigt surface's,
/// [`super::END_SURFACE_STEP`]).
pub const THORNTON_END_STEP: f64 = 0.02;

/// The end-of-contact curve E₋ of Thornton's law as a surface `α_E(γ, e_n)` over `gammas` ×
/// `e_range`, for the probes of both patches ([`super::end_minus_in_patch`] keeps each patch's
/// side): the lowest of its curves (`oblique_solver::history::end_minus_edges_thornton`; at
/// small `e_n` a second one lies higher in the stick patch, not traced), on a grid of
/// [`THORNTON_END_STEP`] in γ (multiples of it, one point beyond each end of `gammas`, γ ≥ 1)
/// and in `e_n` (rows `e_n = 1, 0.98, …` from one above `e_range.1` to one below `e_range.0`,
/// at least 0.3), stored as `1/α_E`. Each row is located at the middle column by the full
/// scan (α from 0.8 · 2/7 to 60, 250 intervals) and traced from there towards both ends by
/// continuation (`end_minus_at_thornton_within` to `END_TRACE_LN_ALPHA`, the guess
/// extrapolated linearly in `1/α_E`), the rows in parallel; a row stops where E₋ is lost or
/// α_E passes 60 (it leaves for α → ∞ as γ falls: 41 at γ 1.5, `e_n` = 0.7). `None` when no
/// grid point holds it.
pub fn thornton_end_minus_surface(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<Option<KinkSurface>, SweepError> {
    let h = THORNTON_END_STEP;
    let rows_per_unit = 1.0 / h;
    let i_lo = ((gamma_lo / h - 1e-9).floor() as i64 - 1).max((1.0 / h).round() as i64);
    let i_hi = (gamma_hi / h + 1e-9).ceil() as i64 + 1;
    if i_hi < i_lo + 1 {
        return Ok(None);
    }
    let min_row = ((1.0 - oblique_solver::law::MIN_RESTITUTION) * rows_per_unit).round() as usize;
    let n_e = (((1.0 - e_lo) * rows_per_unit - 1e-9).ceil().max(0.0) as usize + 2).min(min_row + 1);
    let top = (((1.0 - e_hi) * rows_per_unit + 1e-9).floor() as usize).saturating_sub(1);
    let i_start = (i_lo + i_hi) / 2;
    let n_gamma = (i_hi - i_lo + 1) as usize;
    let rows = (0..n_e)
        .into_par_iter()
        .map(|l| {
            if l < top {
                Ok(vec![f64::NAN; n_gamma])
            } else {
                end_minus_row(l, (i_lo, i_hi), i_start)
            }
        })
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    let values: Vec<f64> = (0..n_gamma)
        .flat_map(|i| rows.iter().map(move |r| r[i]))
        .collect();
    if values.iter().all(|v| !v.is_finite()) {
        return Ok(None);
    }
    Ok(Some(KinkSurface {
        name: "E-",
        patch: PatchKind::PartialSlip,
        scale: CurveScale::Reciprocal,
        gamma_0: i_lo as f64 * h,
        step: h,
        rows_per_unit,
        n_gamma,
        n_e,
        offsets: &super::END_PROBE_OFFSETS,
        extrapolate: true,
        knotted: false,
        values,
    }))
}

/// Row `l` of [`thornton_end_minus_surface`] over the columns `i_lo..=i_hi` (γ = `i` h), as
/// `1/α_E` (NaN where not found), from column `i_start` outwards.
fn end_minus_row(l: usize, (i_lo, i_hi): (i64, i64), i_start: i64) -> Result<Vec<f64>, SweepError> {
    let h = THORNTON_END_STEP;
    let n = (i_hi - i_lo + 1) as usize;
    let e_n = e_of_row(l, 1.0 / h);
    let mut inv = vec![f64::NAN; n];
    let fail = |g: f64, what: String| SweepError::Kink {
        curve: "E-",
        gamma: g,
        what: format!("at e_n = {e_n}: {what}"),
    };
    let g_start = i_start as f64 * h;
    let edges = end_minus_edges_thornton(
        g_start,
        e_n,
        (0.8 * 2.0 / 7.0, super::end_minus::ALPHA_STOP),
        250,
        THORNTON_TRACE_STEPS,
    )
    .map_err(|e| fail(g_start, e.to_string()))?;
    let Some(&first) = edges.first() else {
        return Ok(inv);
    };
    let s = (i_start - i_lo) as usize;
    inv[s] = 1.0 / first;
    super::end_minus::continue_row(&mut inv, s, |i, guess| {
        let g = (i_lo + i as i64) as f64 * h;
        Ok(end_minus_at_thornton_within(
            g,
            e_n,
            guess,
            THORNTON_TRACE_STEPS,
            super::end_minus::END_TRACE_LN_ALPHA,
        )
        .map_err(|e| fail(g, e.to_string()))?
        .filter(|a| (a / guess).ln().abs() <= super::end_minus::SPAN)
        .filter(|&a| a <= super::end_minus::ALPHA_STOP)
        .map(|a| 1.0 / a))
    })?;
    Ok(inv)
}

/// The two edges of the strip of Thornton's law where a `+μF_N` episode of the restitution
/// exists (`oblique_solver::history::restitution_plus_strip_thornton`; `docs/solver.md`):
/// `[F+lo, F+hi]`, each a surface `α(γ, e_n)` over both patches (split by
/// [`super::end_minus_in_patch`] as E₋; the strip rises with `e_n` from the partial-slip patch
/// into the stick patch), on a grid of γ spacing [`THORNTON_STEP`] from one step below
/// `max(γ_lo, PLUS_STRIP_FROM)` to one beyond `γ_hi` and rows `1/PLUS_STRIP_ROWS_PER_UNIT_E`
/// apart in `e_n` from one below `e_lo` to one above `e_hi`, at [`THORNTON_TRACE_STEPS`].
/// Each column is traced from its lowest row up, as the strip is born at small `e_n` and ends
/// as `e_n` grows (γ 2.3: from below 0.3 to 0.575): the first row by the full search, the next
/// by continuation ([`strip_at`]) once two rows give a slope (the full search again where that
/// finds nothing), up to the first row where it is not found. `None` for both where no node
/// holds the strip.
///
/// Between its nodes the surfaces are within 5e-4 (relative) of the edges located there up to
/// 0.02 in `e_n` below the strip's end; closer to the end, where the edges rise ever faster in
/// `e_n` and fall in γ, up to 3.6e-3 (γ 2.31, `e_n` 0.56: `α_hi` 1.8310 against 1.8380).
/// The lower edge converges late in the steps (1.6263 at 2 048 and 4 096 steps, 1.62651 from
/// 8 192 at γ 2.3, `e_n` 0.55: 1.3e-4 relative, a tenth of the node spacing of the cells
/// next to it); the probes measure a cell at several offsets around each edge.
pub fn thornton_plus_strip_surfaces(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<[Option<KinkSurface>; 2], SweepError> {
    if gamma_hi < PLUS_STRIP_FROM {
        return Ok([None, None]);
    }
    let grid = ColumnGrid::new(
        (gamma_lo.max(PLUS_STRIP_FROM), gamma_hi),
        (e_lo, e_hi),
        PLUS_STRIP_ROWS_PER_UNIT_E,
    );
    let columns = (0..grid.n_gamma)
        .into_par_iter()
        .map(|i| strip_column(grid.gamma(i), grid.top, grid.n_e))
        .collect::<Result<Vec<[Vec<f64>; 2]>, SweepError>>()?;
    let surface = |edge: usize, name: &'static str| {
        grid.surface(
            name,
            true,
            columns.iter().flat_map(|c| c[edge].clone()).collect(),
        )
    };
    Ok([surface(0, "F+lo"), surface(1, "F+hi")])
}

/// Rows of the strip's surfaces per unit of `e_n` (0.005 apart): the strip rises ever faster
/// with `e_n` towards its end (γ 2.3: `α_lo` 1.2284 at `e_n` 0.5, 1.6263 at 0.55, none from
/// 0.575), and rows 0.01 apart put `α_lo` 2.2e-3 off at γ 2.3071, `e_n` 0.5462.
pub const PLUS_STRIP_ROWS_PER_UNIT_E: f64 = 200.0;

/// Lowest γ at which [`thornton_plus_strip_surfaces`] looks for the strip. It is born near
/// γ 1.95 at `e_n` = 0.3 (the smallest), narrow: 0.7496–0.7531 `α_c2` at γ 1.955, 0.7403–0.7447
/// at 1.96, 0.7224–0.7285 at 1.97 (`thornfold -- --strip 1.955,1.96,1.965,1.97 0.3 2048`),
/// only its upper edge a visible kink there (`thornscan -- 1.955 0.3 0.72 0.8 320 2048`), and
/// none shows at 1.945 or 1.93 (the same scan). The full search steps up by 1 % and misses a
/// strip narrower than that (at γ 1.965 it finds none), so the columns next to the birth may
/// hold no nodes.
pub const PLUS_STRIP_FROM: f64 = 1.9;

/// How far (in `ln α`) the continuation of [`strip_at`] looks beyond an extrapolated edge before
/// it widens the bracket, and the widest it goes (the strip's edges move by up to 8 % a row of
/// 0.005 in `e_n` where it rises through α_c2).
const STRIP_SPAN: (f64, f64) = (0.03, 0.25);

/// One column of [`thornton_plus_strip_surfaces`]: `ln α` of both edges at `γ` on rows
/// `top..n_e`, from the lowest row up; NaN below the first row where the strip is found (none:
/// the whole column) and from the first row above it where it is not.
fn strip_column(gamma: f64, top: usize, n_e: usize) -> Result<[Vec<f64>; 2], SweepError> {
    let mut out = [vec![f64::NAN; n_e], vec![f64::NAN; n_e]];
    let mut found: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for l in (top..n_e).rev() {
        let e_n = e_of_row(l, PLUS_STRIP_ROWS_PER_UNIT_E);
        let fail = |what: String| SweepError::Kink {
            curve: "F+",
            gamma,
            what: format!("at e_n = {e_n}: {what}"),
        };
        // By continuation once two rows give a slope; the full search where that finds
        // nothing (the strip may have moved further than the bracket widens).
        let followed = if found[0].len() >= 2 {
            let guess = [extrapolated(&found[0]), extrapolated(&found[1])];
            strip_at(gamma, e_n, guess).map_err(|e| fail(e.to_string()))?
        } else {
            None
        };
        let strip = match followed {
            Some(s) => Some(s),
            None => restitution_plus_strip_thornton(gamma, e_n, THORNTON_TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?,
        };
        match strip {
            Some((lo, hi)) => {
                for (k, a) in [lo, hi].into_iter().enumerate() {
                    out[k][l] = a.ln();
                    found[k].push(a.ln());
                }
            }
            // Not at the lowest row: none at higher e_n either (the strip rises from small
            // e_n); above the rows where it was found: it has ended.
            None => break,
        }
    }
    Ok(out)
}

/// The next value of a sequence of equally spaced values, extrapolated by a polynomial through
/// its last (up to) three.
fn extrapolated(v: &[f64]) -> f64 {
    let n = v.len();
    match n {
        0 => f64::NAN,
        1 => v[0],
        2 => 2.0 * v[1] - v[0],
        _ => 3.0 * v[n - 1] - 3.0 * v[n - 2] + v[n - 3],
    }
}

/// The strip at `(γ, e_n)` by continuation from the extrapolated edges `guess` (`ln α`): where
/// the predicate holds between them, each edge is bracketed on its side (the bracket widened
/// from [`STRIP_SPAN`]`.0` while the predicate still holds at its outer end, up to
/// [`STRIP_SPAN`]`.1`, never below `(2/7)(1 + 10⁻³)`) and located by
/// `restitution_plus_change_thornton`. `None` where the predicate fails between the guesses
/// or an edge is not bracketed: the strip has ended (or moved too far to follow).
fn strip_at(
    gamma: f64,
    e_n: f64,
    [lo, hi]: [f64; 2],
) -> Result<Option<(f64, f64)>, oblique_solver::PhysicsError> {
    let holds = |ln_a: f64| -> Result<bool, oblique_solver::PhysicsError> {
        Ok(has_restitution_plus(&slip_history_thornton(
            gamma,
            ln_a.exp(),
            e_n,
            THORNTON_TRACE_STEPS,
        )?))
    };
    let mid = 0.5 * (lo + hi);
    if !holds(mid)? {
        return Ok(None);
    }
    let floor = (2.0f64 / 7.0 * (1.0 + 1e-3)).ln();
    let outer = |edge: f64, down: bool| -> Result<Option<f64>, oblique_solver::PhysicsError> {
        let mut span = STRIP_SPAN.0;
        while span <= STRIP_SPAN.1 {
            let x = if down {
                (edge - span).max(floor)
            } else {
                edge + span
            };
            if !holds(x)? {
                return Ok(Some(x));
            }
            if down && x <= floor {
                return Ok(None);
            }
            span *= 2.0;
        }
        Ok(None)
    };
    let (Some(below), Some(above)) = (outer(lo.min(mid), true)?, outer(hi.max(mid), false)?) else {
        return Ok(None);
    };
    let change = |(a, b): (f64, f64)| {
        restitution_plus_change_thornton(gamma, e_n, (a.exp(), b.exp()), THORNTON_TRACE_STEPS)
    };
    match (change((below, mid))?, change((mid, above))?) {
        (Some(l), Some(h)) => Ok(Some((l, h))),
        _ => Ok(None),
    }
}

/// Steps per contact time on which [`thornton_loading_band_surface`] locates the upper edge of
/// the loading band: it moves by 4e-6 relative from 1 024 to 8 192 steps (γ = 1.7, `e_n` = 0.9;
/// 1.2e-5 at γ = 2.5, `e_n` = 0.5: `thornband -- --locate 2.5 0.5 1024` and `8192`).
pub const BAND_TRACE_STEPS: usize = 1024;

/// The upper edge of Thornton's loading band (`loading_band_thornton`: the band of α where a
/// zone at the `+μq` limit opens and closes while the contact loads; `docs/solver.md`, "Kinks
/// inside the slip regions") as the kink surface `L-hi` of `ln α` over `gammas` × `e_range`, for
/// the probes of both patches: columns [`THORNTON_STEP`] apart in γ from one below `γ_lo` to one
/// beyond `γ_hi` and rows `1/`[`PLUS_STRIP_ROWS_PER_UNIT_E`] apart in `e_n` from one below
/// `e_lo` to one above `e_hi`, at [`BAND_TRACE_STEPS`]. The band rises through `α_c2` as `e_n`
/// falls (its upper edge at γ = 1.6428, `e_n` = 0.8759 lies at 0.9926 `α_c2`, where a table
/// over γ 1.6–1.8, `e_n` 0.8–1 without these probes erred by 1.65e-4 against its bound
/// 1.43e-4), and `P` changes its slope there; its lower edge is no visible kink and is not
/// traced. Each column is traced from its lowest row up, where the band is widest: the first
/// row by the band's search, the next ones by continuation ([`band_top_at`]), up to the first
/// row where no band is found (next to `e_n` = 1 it is narrower than the search's scan: 0.2 %
/// of α at γ = 1.7, `e_n` = 0.999). `None` where no node holds it.
pub fn thornton_loading_band_surface(
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> Result<Option<KinkSurface>, SweepError> {
    let grid = ColumnGrid::new(gammas, e_range, PLUS_STRIP_ROWS_PER_UNIT_E);
    let columns = (0..grid.n_gamma)
        .into_par_iter()
        .map(|i| band_column(grid.gamma(i), grid.top, grid.n_e))
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    Ok(grid.surface("L-hi", true, columns.concat()))
}

/// One column of [`thornton_loading_band_surface`]: `ln α` of the band's upper edge at `γ` on
/// rows `top..n_e`, from the lowest row up; NaN from the first row where the band is not found.
fn band_column(gamma: f64, top: usize, n_e: usize) -> Result<Vec<f64>, SweepError> {
    let mut out = vec![f64::NAN; n_e];
    let mut found: Vec<f64> = Vec::new();
    // The band's width in ln α where it was last searched whole.
    let mut width = f64::NAN;
    for l in (top..n_e).rev() {
        let e_n = e_of_row(l, PLUS_STRIP_ROWS_PER_UNIT_E);
        let fail = |what: String| SweepError::Kink {
            curve: "L-hi",
            gamma,
            what: format!("at e_n = {e_n}: {what}"),
        };
        let followed = if found.is_empty() {
            None
        } else {
            band_top_at(gamma, e_n, extrapolated(&found), width).map_err(|e| fail(e.to_string()))?
        };
        let top_edge = match followed {
            Some(a) => Some(a),
            None => loading_band_thornton(gamma, e_n, BAND_TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?
                .map(|(lo, hi)| {
                    width = (hi / lo).ln();
                    hi
                }),
        };
        let Some(a) = top_edge else { break };
        out[l] = a.ln();
        found.push(a.ln());
    }
    Ok(out)
}

/// The band's upper edge at `(γ, e_n)` by continuation from its extrapolated `ln α` `guess`: the
/// bracket `guess ± δ`, `δ` 1 % or a third of the band's last known width `width` (`ln α`), if
/// the predicate holds at its lower end and fails at its upper one, bisected there
/// (`loading_band_top_within_thornton`); `None` where it does not bracket the edge (the band
/// moved further or narrowed: the caller searches it whole).
fn band_top_at(
    gamma: f64,
    e_n: f64,
    guess: f64,
    width: f64,
) -> Result<Option<f64>, oblique_solver::PhysicsError> {
    let delta = if width.is_finite() {
        0.01f64.min(width / 3.0)
    } else {
        0.01
    };
    loading_band_top_within_thornton(
        gamma,
        e_n,
        ((guess - delta).exp(), (guess + delta).exp()),
        BAND_TRACE_STEPS,
    )
}
