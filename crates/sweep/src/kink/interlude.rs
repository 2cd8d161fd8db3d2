//! The sheet I₊ of the Kelvin–Voigt law, `e_n = e_I(γ, α)`: where a `+` interlude is born in
//! the restitution (`oblique_solver::history::has_plus_interlude_e`; `docs/solver.md`, "Kink
//! curves"). Above it `P` departs from its smooth continuation like `(e_n − e_I)^{3/2}`, a fold
//! across the `e_n` axis: at γ = 2.3529, α = 0.6824 (`e_I` = 0.98143) the second difference of
//! `P` along `e_n` drops from 4.2 to −6.9 within 4e-4 of it. It spans the partial-slip patch
//! from γ ≈ 2.32 (`e_I` ≈ 0.995, α ≈ 0.6) to the end of the traced range (γ = 2.62:
//! `e_I` = 0.949 at α = 0.41, 0.907 at 0.58, 0.956 at α_c2), U-shaped in α: steep where it
//! begins (α_L, next to F₋ and E₋), rising slowly towards α_c2. A table whose leaves it
//! crossed unmeasured erred by 3.1× their prediction (8.26e-6 at γ = 2.3529, α = 0.6824,
//! `e_n` = 0.980, above the stated 8.10e-6).

use rayon::prelude::*;

use super::Kink;
use crate::SweepError;
use oblique_physics::regimes::alpha_c2;
use oblique_solver::history::plus_interlude_edge_e_within;
use oblique_table::surface::{PatchKind, Point};

/// Spacing of the traced rows in γ: `e_I` at a fixed distance from the sheet's start α_L
/// (in `ln α`) is within 4e-5 of the linear rule between rows (`d²e_I/dγ²` ≈ 0.8).
pub const SHEET_STEP: f64 = 0.02;
/// Lowest γ of the rows: the sheet is not found below γ ≈ 2.32.
const SHEET_FROM: f64 = 2.30;
/// Highest γ of the rows: beyond it the sheet reaches `e_n` below [`E_LOW`] and into the stick
/// patch (where the interlude's signature changes), which this tracing does not follow.
pub const SHEET_TO: f64 = 2.62;
/// Lowest α of a row: the sheet begins above α ≈ 0.41 up to γ = 2.62.
const ALPHA_FROM: f64 = 0.38;
/// Spacing of a row's first pass in `ln α`.
const LN_ALPHA_STEP: f64 = 0.02;
/// A row's samples are bisected in `ln α` where neighbours differ by more than this in `e_I`
/// (or one of them lacks it), down to [`LN_ALPHA_MIN`]: the sheet rises steeply at α_L.
const E_JUMP: f64 = 0.002;
const LN_ALPHA_MIN: f64 = 1e-4;
/// The `e_n` bracket of each location (the interlude holds at its top).
const E_LOW: f64 = 0.8;
/// Below this `e_n` the sheet is not found up to γ = [`SHEET_TO`] (its lowest point there is
/// 0.8616, at γ = 2.62 and α ≈ 0.58): a table whose `e_n` range ends below it is not traced.
const SHEET_E_MIN: f64 = 0.85;
const E_TOP: f64 = 0.999;
/// Steps per contact time of the tracing: 2048 and 4096 steps put `e_I` within 1e-5 of each
/// other (γ = 2.5, α = 0.9: 0.9445958 and 0.9446023).
pub const SHEET_STEPS: usize = 2048;

/// How closely each point of the sheet is located in `e_n`: 10 times below the error of
/// [`SHEET_STEPS`] steps, and far below the probes' spacing (half a node interval along `e_n`,
/// at least 1e-4).
const SHEET_E_TOL: f64 = 1e-6;

/// Where a cell next to I₊ is measured on each line of nodes along `e_n`, in node intervals
/// from it along `e_n`: the fold departs above it.
pub const SHEET_PROBE_OFFSETS: [f64; 4] = [-0.5, 0.0, 0.5, 1.0];

/// One traced row of the sheet at a γ: samples `(ln α, e_I)` in increasing α, contiguous from
/// the sheet's start α_L.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Row {
    pub(super) samples: Vec<(f64, f64)>,
}

impl Row {
    /// `ln α_L`, the first sample.
    fn start(&self) -> Option<f64> {
        self.samples.first().map(|s| s.0)
    }

    /// `e_I` at `ln α` by the linear rule between samples; `None` outside them.
    fn at(&self, x: f64) -> Option<f64> {
        let s = &self.samples;
        let (first, last) = (s.first()?, s.last()?);
        if !(x >= first.0 && x <= last.0) {
            return None;
        }
        let j = s.partition_point(|p| p.0 <= x).clamp(1, s.len() - 1);
        let (a, b) = (s[j - 1], s[j]);
        if b.0 == a.0 {
            return Some(a.1);
        }
        let t = (x - a.0) / (b.0 - a.0);
        Some(a.1 + t * (b.1 - a.1))
    }
}

/// The sheet I₊ of the Kelvin–Voigt law over a γ range, traced row by row
/// ([`interlude_sheet`]); a [`Kink`] across the `e_n` axis of the partial-slip patch.
#[derive(Debug, Clone, PartialEq)]
pub struct InterludeSheet {
    gamma_0: f64,
    step: f64,
    rows: Vec<Row>,
}

impl InterludeSheet {
    /// `e_I(γ, α)`: on each of the two rows around γ at the same distance in `ln α` from the
    /// sheet's start α_L (interpolated linearly in γ between them), then linearly across the
    /// rows; `None` outside the traced rows or where either row lacks the sheet there.
    pub fn e_at(&self, gamma: f64, alpha: f64) -> Option<f64> {
        let x = (gamma - self.gamma_0) / self.step;
        let n = self.rows.len();
        if n < 2 || !(x >= 0.0 && x <= (n - 1) as f64) || alpha.is_nan() || alpha <= 0.0 {
            return None;
        }
        let i = (x as usize).min(n - 2);
        let t = x - i as f64;
        let (r0, r1) = (&self.rows[i], &self.rows[i + 1]);
        let (l0, l1) = (r0.start()?, r1.start()?);
        let s = alpha.ln() - ((1.0 - t) * l0 + t * l1);
        let (e0, e1) = (r0.at(l0 + s)?, r1.at(l1 + s)?);
        Some((1.0 - t) * e0 + t * e1)
    }

    /// How many points were located.
    pub fn traced_points(&self) -> usize {
        self.rows.iter().map(|r| r.samples.len()).sum()
    }

    /// Every traced point `(γ, α, e_I)`.
    pub fn points(&self) -> Vec<(f64, f64, f64)> {
        self.rows
            .iter()
            .enumerate()
            .flat_map(|(i, r)| {
                let g = self.gamma_0 + i as f64 * self.step;
                r.samples.iter().map(move |&(x, e)| (g, x.exp(), e))
            })
            .collect()
    }
}

/// `n` points next to the sheet I₊ (`sheet`, from [`interlude_sheet`]): γ uniform over the
/// part of `gammas` its rows cover, `α` uniform in `ln α` from the rows' lowest start α_L to
/// α_c2(γ) (drawn again where the sheet is undefined), `e_n = e_I(γ, α) + s·10^u`, `s = ±1`,
/// `u` uniform in `[−4, −1.5]` (1e-4 to 0.03 in `e_n`: a leaf's node interval along `e_n` is
/// 2e-3 to 4e-3 there), drawn again outside `e_range`. The same `seed` gives the same points
/// (`sweep verify --near-sheet`). Fewer than `n` (none) when `1000 n` draws do not find them.
pub fn near_interlude_points(
    sheet: &InterludeSheet,
    (gamma_min, gamma_max): (f64, f64),
    (e_min, e_max): (f64, f64),
    n: usize,
    seed: u64,
) -> Vec<Point> {
    let top = sheet.gamma_0 + sheet.step * (sheet.rows.len().max(1) - 1) as f64;
    let (g_lo, g_hi) = (gamma_min.max(sheet.gamma_0), gamma_max.min(top));
    let Some(l_lo) = sheet
        .rows
        .iter()
        .filter_map(Row::start)
        .min_by(f64::total_cmp)
    else {
        return Vec::new();
    };
    if g_lo > g_hi {
        return Vec::new();
    }
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    for _ in 0..n.saturating_mul(1000) {
        if out.len() == n {
            break;
        }
        let gamma = (g_lo + (g_hi - g_lo) * rng.uniform()).min(g_hi);
        let l_hi = alpha_c2(gamma).ln();
        let alpha = (l_lo + (l_hi - l_lo) * rng.uniform()).exp();
        let r = 10f64.powf(-4.0 + 2.5 * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        if let Some(e_k) = sheet.e_at(gamma, alpha) {
            let e_n = e_k + sign * r;
            if e_n >= e_min && e_n <= e_max {
                out.push(Point::new(gamma, alpha, e_n));
            }
        }
    }
    out
}

impl Kink for InterludeSheet {
    fn name(&self) -> &'static str {
        "I+"
    }

    fn patch(&self) -> PatchKind {
        PatchKind::PartialSlip
    }

    fn alpha(&self, _gamma: f64, _e_n: f64) -> Option<f64> {
        None
    }

    fn e_n_at(&self, gamma: f64, alpha: f64) -> Option<f64> {
        self.e_at(gamma, alpha)
    }

    fn across_e_n(&self) -> bool {
        true
    }

    fn offsets(&self) -> &'static [f64] {
        &SHEET_PROBE_OFFSETS
    }
}

/// How far outside a table's `e_n` range the sheet still counts as reaching it.
const REACH: f64 = 0.01;

/// The sheet I₊ for a partial-slip patch over `gammas` and `e_range`: rows every
/// [`SHEET_STEP`] in γ (multiples of it, one beyond each end of `gammas`, within
/// [`SHEET_FROM`]–[`SHEET_TO`]), each located on a grid of [`LN_ALPHA_STEP`] in `ln α` from
/// [`ALPHA_FROM`] to α_c2(γ) ([`plus_interlude_edge_e_within`] to [`SHEET_E_TOL`],
/// [`SHEET_STEPS`] steps, bracket [`E_LOW`]–[`E_TOP`]) and bisected where it rises steeply,
/// the rows in parallel; a row keeps its first contiguous run of located points. `None` when
/// no located point lies within [`REACH`] of the `e_n` range, or the γ range lies outside the
/// rows.
pub fn interlude_sheet(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<Option<InterludeSheet>, SweepError> {
    let h = SHEET_STEP;
    let i_lo = ((gamma_lo / h - 1e-9).floor() as i64 - 1).max((SHEET_FROM / h).round() as i64);
    let i_hi = ((gamma_hi / h + 1e-9).ceil() as i64 + 1).min((SHEET_TO / h).round() as i64);
    if i_hi < i_lo + 1 || e_lo >= E_TOP || e_hi + REACH < SHEET_E_MIN {
        return Ok(None);
    }
    // The stored rows where they exist, else traced ([`super::stored`]: the same bits).
    let rows = (i_lo..=i_hi)
        .into_par_iter()
        .map(|i| match super::stored::interlude_row(i) {
            Some(samples) => Ok(Row {
                samples: samples.to_vec(),
            }),
            None => trace_row(i as f64 * h),
        })
        .collect::<Result<Vec<Row>, SweepError>>()?;
    let sheet = InterludeSheet {
        gamma_0: i_lo as f64 * h,
        step: h,
        rows,
    };
    let reaches = sheet
        .points()
        .iter()
        .any(|&(_, _, e)| e >= e_lo - REACH && e <= e_hi + REACH);
    Ok(reaches.then_some(sheet))
}

/// The indices `i` (γ = `i` [`SHEET_STEP`]) of every row [`interlude_sheet`] can trace.
pub(super) fn row_indices() -> (i64, i64) {
    (
        (SHEET_FROM / SHEET_STEP).round() as i64,
        (SHEET_TO / SHEET_STEP).round() as i64,
    )
}

/// One row of [`interlude_sheet`] at `gamma`: its samples `(ln α, e_I)`, the same whatever
/// the range of the sheet ([`super::stored`]).
pub(super) fn trace_row(gamma: f64) -> Result<Row, SweepError> {
    // The whole bracket at every point: next to the sheet's start the predicate changes more
    // than once along `e_n`, and a narrower bracket about a neighbour's value can find
    // another change (up to 7e-4 away at γ 2.44–2.62).
    let locate = |x: f64| -> Result<Option<f64>, SweepError> {
        plus_interlude_edge_e_within(gamma, x.exp(), (E_LOW, E_TOP), SHEET_STEPS, SHEET_E_TOL)
            .map_err(|e| SweepError::Kink {
                curve: "I+",
                gamma,
                what: format!("at alpha = {}: {e}", x.exp()),
            })
    };
    let (x0, x1) = (ALPHA_FROM.ln(), alpha_c2(gamma).ln());
    let n = ((x1 - x0) / LN_ALPHA_STEP).ceil().max(1.0) as usize;
    let mut pts: Vec<(f64, Option<f64>)> = Vec::with_capacity(n + 1);
    for j in 0..=n {
        let x = if j == n {
            x1
        } else {
            x0 + j as f64 * LN_ALPHA_STEP
        };
        pts.push((x, locate(x)?));
    }
    // Bisect where the sheet begins, ends or rises steeply.
    let mut j = 0;
    while j + 1 < pts.len() {
        let ((xa, ea), (xb, eb)) = (pts[j], pts[j + 1]);
        let steep = match (ea, eb) {
            (Some(a), Some(b)) => (a - b).abs() > E_JUMP,
            (None, None) => false,
            _ => true,
        };
        if steep && xb - xa > LN_ALPHA_MIN {
            let xm = 0.5 * (xa + xb);
            pts.insert(j + 1, (xm, locate(xm)?));
        } else {
            j += 1;
        }
    }
    let samples = pts
        .iter()
        .skip_while(|p| p.1.is_none())
        .map_while(|&(x, e)| e.map(|e| (x, e)))
        .collect();
    Ok(Row { samples })
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_solver::history::plus_interlude_edge_e;

    /// The traced sheet against direct location between its rows and samples: within 2e-4 in
    /// `e_n` where it is gradual, and defined from its start α_L on.
    #[test]
    fn the_interlude_sheet_matches_direct_location() {
        let sheet = interlude_sheet((2.44, 2.52), (0.3, 1.0))
            .expect("traced")
            .expect("the sheet lies there");
        for (g, a) in [
            (2.45, 0.6),
            (2.47, 0.9),
            (2.49, 1.3),
            (2.51, 0.55),
            (2.5, 0.48),
        ] {
            let got = sheet.e_at(g, a).expect("inside the sheet");
            let direct = plus_interlude_edge_e(g, a, (E_LOW, E_TOP), SHEET_STEPS)
                .expect("located")
                .expect("there");
            let tol = if a < 0.5 { 2e-3 } else { 2e-4 };
            assert!(
                (got - direct).abs() < tol,
                "γ {g}, α {a}: {got} against {direct}"
            );
        }
        // Below its start, none.
        assert!(sheet.e_at(2.47, 0.40).is_none());
    }
}
