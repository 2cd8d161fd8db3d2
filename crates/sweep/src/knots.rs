//! The knots of the partial-slip coordinate of a table of Thornton's law (`nodes.knots`):
//! its kinks inside the slip regions (`docs/solver.md`, "Kinks inside the slip regions")
//! traced on a grid of `(γ, e_n)` and sent to fixed cell edges (`docs/table-format.md`, "The
//! knots"), so that no leaf straddles them.
//!
//! | knot | kink | `c'` | grading |
//! |---|---|---|---|
//! | `α_c1(γ, e_n)` | the Kelvin–Voigt end of the full-slip line, where the coordinate changes its map (`c = 1/2`); the law's own edge `α₁` lies within a few per cent of it | 1/2 | none |
//! | `α_R(γ, e_n)` | the re-slip fold: `P` departs like `(α/α_R − 1)^{3/2}` above it | 5/8 | above |
//! | `2/7` | the end of the first gross-slip episode at the switch: a jump of curvature | 3/4 | none |
//! | `α_S(γ, e_n)` | the switch fold: `P` departs like `(1 − α/α_S)^{3/2}` below it | 7/8 | below |
//!
//! As `e_n → 1` the folds merge towards `α = 2/7` (`α_S` − 2/7 falls like `√(1 − e_n)`), so
//! the knots apply up to [`E_N_MAX`] only.

use rayon::prelude::*;

use super::SweepError;
use oblique_solver::history::{reslip_fold_thornton, switch_fold_thornton};
use oblique_table::surface::{Knots, PartialMap, PatchKind};

/// Highest `e_n` the knots apply at (rounded down to a sixteenth of a root cell).
pub const E_N_MAX: f64 = 0.98;
/// Largest grid spacing along γ of the traced kinks.
pub const GAMMA_STEP: f64 = 0.025;
/// Largest grid spacing along `e_n` of the traced kinks.
pub const E_N_STEP: f64 = 0.01;
/// Steps per contact time of the tracing (the folds within about 1e-6 of their converged
/// values, `docs/solver.md`).
pub const STEPS: usize = 2048;
/// Where the knots are sent: `α_c1`, `α_R`, `2/7`, `α_S`.
pub const C_STAR: [f64; 4] = [0.5, 0.625, 0.75, 0.875];
/// Their grading ([`oblique_table::surface::Grade`] values): none, above, none, below.
pub const GRADE: [u8; 4] = [0, 2, 0, 1];
/// Names of the knots in messages.
const NAMES: [&str; 4] = ["alpha_c1", "alpha_R", "2/7", "alpha_S"];

/// `n ≥ 4` equal steps of at most `step` over `[lo, hi]`: `(first, step, n)`.
fn grid(lo: f64, hi: f64, step: f64) -> (f64, f64, usize) {
    let n = (((hi - lo) / step).ceil() as usize + 1).max(4);
    (lo, (hi - lo) / (n - 1) as f64, n)
}

/// The knots of the partial-slip patch over `γ ∈ gammas` (`bg` root cells) and `e_n ∈ e_range`
/// (`be` root cells), with the partial-slip coordinate of Thornton's law
/// ([`PartialMap::Slip`]); `None` when the `e_n` range starts above [`E_N_MAX`]. `Err` names
/// the kink and the point where it is missing or out of order.
pub fn thornton_knots(
    gammas: (f64, f64),
    bg: usize,
    e_range: (f64, f64),
    be: usize,
) -> Result<Option<Knots>, SweepError> {
    let (e_lo, e_hi) = e_range;
    // The region along e_n: root-cell units, down to a multiple of 1/16.
    let top = if e_hi <= E_N_MAX {
        be as f64
    } else {
        ((E_N_MAX - e_lo) / (e_hi - e_lo) * be as f64 * 16.0).floor() / 16.0
    };
    if top <= 0.0 {
        return Ok(None);
    }
    let e_top = e_lo + (e_hi - e_lo) * top / be as f64;
    let (g0, gs, ng) = grid(gammas.0, gammas.1, GAMMA_STEP);
    let (e0, es, ne) = grid(e_lo, e_top, E_N_STEP);
    let points: Vec<(f64, f64)> = (0..ng)
        .flat_map(|i| {
            (0..ne).map(move |l| {
                let g = if i + 1 == ng {
                    gammas.1
                } else {
                    g0 + gs * i as f64
                };
                let e = if l + 1 == ne {
                    e_top
                } else {
                    e0 + es * l as f64
                };
                (g, e)
            })
        })
        .collect();
    let traced: Vec<[f64; 4]> = points
        .par_iter()
        .map(|&(g, e)| knots_at(g, e))
        .collect::<Result<_, _>>()?;
    // `knot[j, i, l]`, j the knot.
    let mut knot = vec![0.0; 4 * ng * ne];
    for (p, k) in traced.iter().enumerate() {
        for (j, &v) in k.iter().enumerate() {
            knot[j * ng * ne + p] = v;
        }
    }
    let knots = Knots::new(
        g0,
        gs,
        e0,
        es,
        [0.0, bg as f64, 0.0, top],
        C_STAR.to_vec(),
        GRADE.to_vec(),
        [4, ng, ne],
        knot,
    )
    .map_err(|what| SweepError::Knots {
        knot: "all",
        gamma: gammas.0,
        e_n: e_lo,
        what,
    })?;
    Ok(Some(knots))
}

/// The coordinates `c` of the four kinks at `(γ, e_n)`, checked to lie in order inside `(0, 1)`.
fn knots_at(gamma: f64, e_n: f64) -> Result<[f64; 4], SweepError> {
    let fail = |j: usize, what: String| SweepError::Knots {
        knot: NAMES[j],
        gamma,
        e_n,
        what,
    };
    let missing = |j: usize| fail(j, "no such kink here".into());
    // `α_c1` is `c = 1/2` of the coordinate, where its map changes (linear in α below,
    // graded above): a knot that stays there keeps that change on a cell edge.
    let a1 = oblique_physics::regimes::alpha_c1_dissipative(gamma, e_n);
    let ar = reslip_fold_thornton(gamma, e_n, STEPS)
        .map_err(|e| fail(1, e.to_string()))?
        .ok_or_else(|| missing(1))?;
    let as_ = switch_fold_thornton(gamma, e_n, STEPS)
        .map_err(|e| fail(3, e.to_string()))?
        .ok_or_else(|| missing(3))?;
    let alphas = [a1, ar, 2.0 / 7.0, as_];
    let mut out = [0.0; 4];
    let mut below = 0.0;
    for (j, &a) in alphas.iter().enumerate() {
        let c = PatchKind::PartialSlip.coord_at(PartialMap::Slip, gamma, a, e_n, f64::INFINITY);
        if !(c > below && c < 1.0) {
            return Err(fail(
                j,
                format!(
                    "at alpha = {a} (c = {c}): the kinks must lie in the order alpha_c1 < alpha_R \
                     < 2/7 < alpha_S < alpha_c2"
                ),
            ));
        }
        below = c;
        out[j] = if j == 0 { 0.5 } else { c };
    }
    Ok(out)
}
