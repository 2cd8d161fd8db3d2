//! The end-of-contact surface E₋ of the Kelvin–Voigt law, `α_E(γ, e_n)`: where the last
//! `−μF_N` episode of an impact leaves the separation as α grows, for a table with an `e_n`
//! axis. At `e_n = 1` it is the elastic curve ([`super::end_minus_curve`]); with damping it
//! moves little above γ ≈ 1.8 (α_E = 0.8699, 0.8170, 0.9873, 1.6320 at γ = 2.0 and
//! `e_n` = 1, 0.8, 0.5, 0.3) and leaves for α → ∞ at a γ that depends on `e_n` (α_E = 20.87,
//! 9.77, 62.2 at γ = 1.74 and `e_n` = 1, 0.75, 0.5; not found at 0.48). Beyond F₋'s birth
//! (γ ≈ 2.40) the change at `e_n = 1` is F₋'s own (the `−μF_N` episode at the separation
//! turns into F₋'s interior one); below `e_n` ≈ 0.99 E₋ goes on (α_E ≈ 0.49 at γ = 2.45,
//! `e_n` = 0.99), next to F₋ where F₋ exists.

use rayon::prelude::*;

use super::{CurveScale, KinkSurface, TRACE_STEPS};
use crate::SweepError;
use oblique_physics::regimes::alpha_c2;
use oblique_solver::history::end_minus_at_e_within;
use oblique_table::surface::PatchKind;

/// Spacing of the surface's grid in γ and in `e_n` (rows `e_n = 1, 0.98, …`). `α_E` varies
/// slowly with both: the 4-point rule between the grid points is within 1e-4 (relative) of
/// direct location where α_E ≤ 10 (`the_end_of_contact_surface_matches_direct_location`).
pub const END_SURFACE_STEP: f64 = 0.02;

/// Where a cell next to E₋ is measured on each row, in node intervals from it: four of the seven
/// [`super::PROBE_OFFSETS`]. `P` keeps its slope across E₋ (a curvature change, not F₋'s
/// `(α − α_F)^{3/2}`), so a cubic's error across it varies over the whole stencil, not within
/// one interval of it. With damping the curvature grows without bound just above it (the second
/// difference along α at γ 2.40077, `e_n` 0.9106: −22.7 at E₋, −3.1 at 0.109 above), a tail
/// that reaches leaves E₋ does not cross; those are not probed (`docs/accuracy.md`).
pub const END_PROBE_OFFSETS: [f64; 4] = [-0.7, 0.0, 0.7, 1.4];

/// How closely (in `ln α`) each point of the surface is located: 100 times below the error of
/// [`TRACE_STEPS`] steps (about 1e-5 relative), and far below the probes' spacing (a node
/// interval, at least 1e-4 of α); 14 bisections from the continuation's first bracket where
/// the public [`oblique_solver::history::end_minus_at_e`] takes 24 to reach 1e-10.
pub const END_TRACE_LN_ALPHA: f64 = 1e-7;

/// The γ at which every row's tracing starts (or the grid's first column above it), where E₋
/// exists at every `e_n` in [0.3, 1] with α_E of order one (0.82–1.63 at γ = 2.0, 0.43–1.38
/// at 2.6).
const START_GAMMA: f64 = 2.0;

/// First guess of α_E at the start: within a factor `e` of it at every `e_n` for γ 2.0–2.62.
const START_GUESS: f64 = 1.0;

/// Lowest γ of the grid: E₋ is not found below γ ≈ 1.72 at any `e_n`.
const SURFACE_FROM: f64 = 1.70;

/// Highest γ of the grid: beyond γ ≈ 2.6 the predicate has more than one upper edge at some
/// `e_n` (at γ = 3.0, `e_n` = 0.9 it holds on α 0.16–0.32 and again above 1.82), which this
/// tracing does not follow.
const SURFACE_TO: f64 = 2.62;

/// α beyond which a row's tracing towards small γ stops (α_E → ∞ there; `P` is flat in α,
/// `dP/d ln α` ≈ 0.009 at α = 20 and γ = 1.74).
pub(super) const ALPHA_STOP: f64 = 60.0;

/// How far (in `ln α`) a point located by continuation may lie from its extrapolated guess
/// (neighbouring points differ by at most 25 % where α_E ≤ [`ALPHA_STOP`]; the linear
/// extrapolation of `1/α_E` by far less).
pub(super) const SPAN: f64 = 0.3;

/// E₋ of the Kelvin–Voigt law as a surface `α_E(γ, e_n)` over `gammas` × `e_range` for the
/// probes of `patch` (it crosses both patches: the stick patch above α_c2, the partial-slip
/// patch below; [`end_minus_in_patch`] keeps each patch's side), on a grid of
/// [`END_SURFACE_STEP`] in γ (multiples of it, one point beyond each end of `gammas`, within
/// [`SURFACE_FROM`]–[`SURFACE_TO`]) and in `e_n` (from 1 down to one row below `e_range.0`, at
/// least 0.3), stored as `1/α_E`. Each row is traced from [`START_GAMMA`] (or the grid's first
/// column above it) towards both ends by continuation ([`end_minus_at_e_within`] to
/// [`END_TRACE_LN_ALPHA`], [`TRACE_STEPS`] steps, the guess extrapolated linearly in
/// `1/α_E`), the rows in parallel; a row stops where E₋ is lost or α_E passes
/// [`ALPHA_STOP`]. `None` when no grid point holds it.
pub fn end_minus_surface(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, _e_hi): (f64, f64),
    patch: PatchKind,
) -> Result<Option<KinkSurface>, SweepError> {
    let h = END_SURFACE_STEP;
    let rows_per_unit = 1.0 / h;
    let i_lo = ((gamma_lo / h - 1e-9).floor() as i64 - 1).max((SURFACE_FROM / h).round() as i64);
    let i_hi = ((gamma_hi / h + 1e-9).ceil() as i64 + 1).min((SURFACE_TO / h).round() as i64);
    if i_hi < i_lo + 1 {
        return Ok(None);
    }
    // Each row starts at START_GAMMA, or at the grid's first column where that lies below it
    // (the guess holds up to γ = 2.62); the columns traced are the grid's and those between it
    // and the start.
    let i_start = start_column(i_lo);
    let (t_lo, t_hi) = (i_lo.min(i_start), i_hi.max(i_start));
    // The rows of the stored widest grid where they hold these columns with this start, else
    // traced ([`super::stored`]: the same bits).
    let n_e =
        (((1.0 - e_lo) * rows_per_unit - 1e-9).ceil().max(0.0) as usize + 2).min(min_row() + 1);
    let stored = super::stored::end_minus();
    let rows = (0..n_e)
        .into_par_iter()
        .map(
            |l| match stored.and_then(|g| g.row(l, (t_lo, t_hi), i_start)) {
                Some(row) => Ok(row),
                None => trace_row(l, (t_lo, t_hi), i_start),
            },
        )
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    // Keep the grid's columns, node (i, l) at i n_e + l.
    let n_gamma = (i_hi - i_lo + 1) as usize;
    let off = (i_lo - t_lo) as usize;
    let values: Vec<f64> = (0..n_gamma)
        .flat_map(|i| rows.iter().map(move |r| r[off + i]))
        .collect();
    if values.iter().all(|v| !v.is_finite()) {
        return Ok(None);
    }
    Ok(Some(KinkSurface {
        name: "E-",
        patch,
        scale: CurveScale::Reciprocal,
        gamma_0: i_lo as f64 * h,
        step: h,
        rows_per_unit,
        n_gamma,
        n_e,
        offsets: &END_PROBE_OFFSETS,
        extrapolate: true,
        knotted: false,
        values,
    }))
}

/// The last row of the grid: `e_n` = [`oblique_solver::law::MIN_RESTITUTION`].
fn min_row() -> usize {
    ((1.0 - oblique_solver::law::MIN_RESTITUTION) / END_SURFACE_STEP).round() as usize
}

/// Row `l` of the E₋ grid (`e_n = 1 − l` [`END_SURFACE_STEP`]) over the columns
/// `t_lo..=t_hi` (γ = `i` [`END_SURFACE_STEP`]), stored as `1/α_E` (NaN where not found),
/// traced from column `i_start` towards both ends by continuation: the row of
/// [`end_minus_surface`]. A column's value depends on the columns between it and the start
/// only (and, below the start, on the start's neighbour above it), so that the rows of a wider
/// range hold those of a narrower one bit for bit ([`super::stored`]).
pub(super) fn trace_row(
    l: usize,
    (t_lo, t_hi): (i64, i64),
    i_start: i64,
) -> Result<Vec<f64>, SweepError> {
    let h = END_SURFACE_STEP;
    let n_t = (t_hi - t_lo + 1) as usize;
    let e_n = super::e_of_row(l, 1.0 / h);
    let mut inv = vec![f64::NAN; n_t];
    let locate =
        |i: usize, guess: f64, span: f64| -> Result<Option<f64>, SweepError> {
            let g = (t_lo + i as i64) as f64 * h;
            let found = end_minus_at_e_within(g, e_n, guess, TRACE_STEPS, END_TRACE_LN_ALPHA)
                .map_err(|e| SweepError::Kink {
                    curve: "E-",
                    gamma: g,
                    what: format!("at e_n = {e_n}: {e}"),
                })?;
            Ok(found
                .filter(|a| (a / guess).ln().abs() <= span && *a <= ALPHA_STOP)
                .map(|a| 1.0 / a))
        };
    let s = (i_start - t_lo) as usize;
    let Some(first) = locate(s, START_GUESS, 1.0)? else {
        return Ok(inv);
    };
    inv[s] = first;
    continue_row(&mut inv, s, |i, guess| locate(i, guess, SPAN))?;
    Ok(inv)
}

/// A row of `1/α_E` located at `s` (`inv[s]`), continued outwards from it, up in γ and then
/// down: each next column's guess extrapolated linearly from the two points behind it (the
/// start's other neighbour on the way down), else the last point, in `1/α` (at most α =
/// [`ALPHA_STOP`]); `locate(i, guess)` answers column `i`'s `1/α_E`, and a way stops where it
/// answers `None`.
pub(super) fn continue_row(
    inv: &mut [f64],
    s: usize,
    locate: impl Fn(usize, f64) -> Result<Option<f64>, SweepError>,
) -> Result<(), SweepError> {
    let n = inv.len();
    for dir in [1i64, -1] {
        let mut i = s as i64 + dir;
        while i >= 0 && (i as usize) < n {
            let prev = inv[(i - dir) as usize];
            let guess_inv = match usize::try_from(i - 2 * dir).ok().and_then(|j| inv.get(j)) {
                Some(&p2) if p2.is_finite() => 2.0 * prev - p2,
                _ => prev,
            };
            let guess = 1.0 / guess_inv.max(1.0 / ALPHA_STOP);
            match locate(i as usize, guess)? {
                Some(v) => inv[i as usize] = v,
                None => break,
            }
            i += dir;
        }
    }
    Ok(())
}

/// The columns and the start of the widest E₋ grid ([`end_minus_surface`] over
/// [`SURFACE_FROM`]–[`SURFACE_TO`]) and its number of rows (`e_n` from 1 down to
/// [`oblique_solver::law::MIN_RESTITUTION`]).
pub(super) fn widest_grid() -> ((i64, i64), i64, usize) {
    let h = END_SURFACE_STEP;
    let (t_lo, t_hi) = (
        (SURFACE_FROM / h).round() as i64,
        (SURFACE_TO / h).round() as i64,
    );
    ((t_lo, t_hi), start_column(t_lo), min_row() + 1)
}

/// The column every row is traced from: [`START_GAMMA`]'s, or the grid's first column `i_lo`
/// where that lies above it.
fn start_column(i_lo: i64) -> i64 {
    ((START_GAMMA / END_SURFACE_STEP).round() as i64).max(i_lo)
}

/// The part of an [`end_minus_surface`] in the patch `kind`: the nodes with α_E ≥ α_c2(γ) for
/// the stick patch, α_E ≤ α_c2(γ) for the partial-slip patch. E₋ bends where it crosses α_c2
/// (α_E = 1.0914, 1.0363, 1.0116 at γ = 1.90, 1.91, 1.92 and `e_n` = 0.99, α_c2 = 1.0423 at
/// 1.91): a stencil across the bend errs by up to 0.8 %, so each side is interpolated from its
/// own nodes and extrapolated up to one grid step beyond them. The same for any surface that
/// crosses α_c2 (Thornton's E₋ and the edges of its `+` strip, stored as `ln α`).
pub fn end_minus_in_patch(surface: &KinkSurface, kind: PatchKind) -> KinkSurface {
    let mut out = surface.clone();
    out.patch = kind;
    for i in 0..out.n_gamma {
        let c2 = alpha_c2(out.gamma_0 + i as f64 * out.step);
        let (inv_c2, ln_c2) = (1.0 / c2, c2.ln());
        for l in 0..out.n_e {
            let v = &mut out.values[i * out.n_e + l];
            let stick = match out.scale {
                CurveScale::Reciprocal => *v <= inv_c2,
                CurveScale::Ln => *v >= ln_c2,
            };
            if stick != (kind == PatchKind::Stick) {
                *v = f64::NAN;
            }
        }
    }
    out
}

/// α_E(γ, e_n) of an [`end_minus_surface`] from the side of α_c2 it lies on: the traced
/// surface says which, the side's own part ([`end_minus_in_patch`]) answers, so that no stencil
/// reaches across the bend.
#[derive(Debug, Clone)]
pub struct EndMinusSides {
    full: KinkSurface,
    stick: KinkSurface,
    partial: KinkSurface,
}

impl EndMinusSides {
    /// The two sides of `surface`.
    pub fn new(surface: &KinkSurface) -> Self {
        EndMinusSides {
            full: surface.clone(),
            stick: end_minus_in_patch(surface, PatchKind::Stick),
            partial: end_minus_in_patch(surface, PatchKind::PartialSlip),
        }
    }

    /// α_E at `(γ, e_n)`, `None` where the side's part is undefined.
    pub fn alpha_at(&self, gamma: f64, e_n: f64) -> Option<f64> {
        let a = self.full.alpha_at(gamma, e_n)?;
        if a >= alpha_c2(gamma) {
            self.stick.alpha_at(gamma, e_n)
        } else {
            self.partial.alpha_at(gamma, e_n)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_solver::history::end_minus_at_e;

    #[test]
    fn the_end_of_contact_surface_matches_direct_location() {
        let full = end_minus_surface((1.74, 2.5), (0.3, 1.0), PatchKind::Stick)
            .unwrap()
            .unwrap();
        let sides = EndMinusSides::new(&full);
        let s = |g: f64, e: f64| sides.alpha_at(g, e);
        // At grid points: the traced values (kinkmap / endscan_e, 2048 steps).
        for (g, e, a) in [
            (2.0, 1.0, 0.869908),
            (2.0, 0.8, 0.817007),
            (2.0, 0.5, 0.987312),
            (2.0, 0.3, 1.631979),
            (1.8, 0.6, 2.520372),
            (2.3, 0.4, 1.078174),
            (2.4, 0.7, 0.483600),
        ] {
            let got = s(g, e).unwrap_or_else(|| panic!("{g} {e}: none"));
            assert!((got / a - 1.0).abs() < 2e-6, "{g} {e}: {got} against {a}");
        }
        // Between the grid points, against direct location from a nearby guess: within 2e-4
        // where E₋ is smooth; within 3e-3 next to its bends (where it crosses α_c2, at γ ≈ 1.91
        // for e_n near 1, and next to F₋'s birth, γ ≈ 2.4 and e_n ≥ 0.97).
        for (g, e, tol) in [
            (1.75, 0.99, 2e-4),
            (1.76, 0.71, 2e-4),
            (1.77, 0.91, 2e-4),
            (1.85, 0.45, 2e-4),
            (1.89, 0.97, 2e-4),
            (1.93, 0.77, 2e-4),
            (1.95, 0.6, 2e-4),
            (2.11, 0.33, 2e-4),
            (2.27, 0.63, 2e-4),
            (2.49, 0.51, 4e-4),
            (2.45, 0.95, 5e-4),
            (1.91, 0.99, 3e-3),
            (2.39, 0.99, 3e-3),
            (2.41, 0.97, 3e-3),
        ] {
            let got = s(g, e).unwrap_or_else(|| panic!("{g} {e}: none"));
            let direct = end_minus_at_e(g, e, got, TRACE_STEPS).unwrap().unwrap();
            assert!(
                (got / direct - 1.0).abs() < tol,
                "{g} {e}: {got} against {direct}"
            );
        }
        // Nowhere below γ ≈ 1.72.
        assert!(full.alpha_at(1.70, 0.99).is_none());
    }
}
