//! Sheets of Thornton's law across the `e_n` axis, as kinks for the probes of
//! `nodes.probe_kinks` (`docs/solver.md`, "Kinks inside the slip regions"):
//! - the switch sheet `e_S(γ, α)`: at small `e_n` the field clipped at the switch to unloading
//!   keeps a `+` zone at the contact's edge, which ceases as `e_n` grows on a sheet nearly flat
//!   in α far from `α_c2` (γ 1.7: 0.5216 at 3 `α_c2`, 0.5208 at 20) and falling towards it
//!   (0.3916 at 1.02 `α_c2`). `P` leaves its smooth continuation below it, and a table over
//!   γ 2.2–2.4, `e_n` 0.5–0.7 (target 1e-4) erred next to it by 9.8e-5 against a bound of
//!   1.43e-4, the most next to any kink it was checked at;
//! - the end-of-contact sheet `e_E(γ, α)`: below it the contact ends in a `−μF_N` episode, above
//!   it a `+` episode takes the end (γ 1.66: 0.307 at 2 `α_c2`, 0.328 at 3, 0.322 at 10), and
//!   the curvature of `P` along `e_n` changes above it (`end_minus_sheet_edges_thornton`); in
//!   the stick patch, and from γ ≈ 1.86 in the partial-slip patch too.

use rayon::prelude::*;

use super::{lagrange_weights, local_stencil, Kink};
use crate::SweepError;
use oblique_physics::regimes::alpha_c2;
use oblique_solver::history::{end_minus_sheet_edges_thornton, switch_sheet_edges_thornton};
use oblique_table::surface::PatchKind;

/// Spacing of the traced columns in γ.
pub const SWITCH_SHEET_STEP: f64 = 0.02;
/// Nodes of a column in `s = α_c2/α`, evenly spaced from `s` = 1 (`α_c2`) to 0 (α → ∞): 0.05
/// apart, 0.05 in `ln α` next to `α_c2` where the sheet falls fastest (by 0.22 per unit of
/// `ln α` at γ 1.7), and ever wider in `ln α` where it is flat.
const S_NODES: usize = 21;
/// The α of the nodes at the ends of a column, as `α/α_c2`: just inside the patch, and the
/// stand-in for α → ∞ (`e_S` changes by 6e-3 from 5 to 200 `α_c2` at γ 1.5).
const RATIO_ENDS: (f64, f64) = (1.001, 1000.0);
/// Spacing of the scan along `e_n` that brackets the sheet at a node.
const SCAN_STEP: f64 = 0.02;
/// How far beyond a table's `e_n` range the sheet is looked for.
const REACH: f64 = 0.02;
/// Steps per contact time of the tracing (2 048 and 8 192 steps put `e_S` within 1e-4 of each
/// other at γ 1.7, `docs/solver.md`).
pub const SWITCH_SHEET_STEPS: usize = 2048;

/// Where a cell next to `e_S` is measured on each line of nodes along `e_n`, in node intervals
/// from it along `e_n`: `P` departs below it.
pub const SWITCH_PROBE_OFFSETS: [f64; 4] = [-1.0, -0.5, 0.0, 0.5];
/// The same next to a lower edge of the sheet, where `P` departs above it.
pub const SWITCH_LOWER_PROBE_OFFSETS: [f64; 4] = [-0.5, 0.0, 0.5, 1.0];
/// The same next to the end-of-contact sheet `e_E`, where `P` departs above it.
pub const END_SHEET_PROBE_OFFSETS: [f64; 4] = SWITCH_LOWER_PROBE_OFFSETS;

/// Which sheet a [`SwitchSheet`] traces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SheetKind {
    /// The switch sheet `e_S` (`switch_sheet_edges_thornton`).
    Switch,
    /// The end-of-contact sheet `e_E` (`end_minus_sheet_edges_thornton`).
    EndMinus,
}

/// One edge of a sheet ([`SheetKind`]) over a γ range ([`switch_sheet_surfaces`],
/// [`end_minus_sheet_surface`]): the edge on a grid of γ (spacing [`SWITCH_SHEET_STEP`]) and
/// α (columns of 21 nodes: `s = α_c2/α` evenly spaced in the stick patch, `α/α_c2` from
/// [`PARTIAL_RATIO_FROM`] in the partial-slip patch), interpolated along γ on each node of the
/// columns, then across them (Lagrange, up to 4 points each, fewer at the edge of the located
/// nodes); a [`Kink`] across the `e_n` axis of its patch.
#[derive(Debug, Clone, PartialEq)]
pub struct SwitchSheet {
    gamma_0: f64,
    step: f64,
    n_gamma: usize,
    /// The edge at node `(i, j)` (γ = `gamma_0 + i step`, `α/α_c2` = [`node_ratio`] of `j`)
    /// at `i S_NODES + j`; NaN where no such edge lies in the range looked at.
    values: Vec<f64>,
    /// Whether this is the lower edge of a band (the zone exists above it), else the upper.
    lower: bool,
    /// The sheet.
    kind: SheetKind,
    /// The patch whose α the columns cover ([`node_ratio`]).
    patch: PatchKind,
}

impl SwitchSheet {
    fn node(&self, i: usize, j: usize) -> f64 {
        self.values[i * S_NODES + j]
    }

    /// The value at node `j` of `s` interpolated along γ (position `u` in grid steps).
    fn along_gamma(&self, u: f64, j: usize) -> Option<f64> {
        let (start, k) = local_stencil(u, self.n_gamma, |i| self.node(i, j).is_finite())?;
        let w = lagrange_weights(u, start, k);
        Some((0..k).map(|m| w[m] * self.node(start + m, j)).sum())
    }

    /// The sheet's `e_n` at `(γ, α)`: for `α ≥ α_c2` (α = ∞ included) in the stick patch,
    /// `PARTIAL_RATIO_FROM α_c2 ≤ α ≤ α_c2` in the partial-slip patch; `None` outside the traced
    /// grid or where the nodes around it do not all hold the sheet.
    pub fn e_at(&self, gamma: f64, alpha: f64) -> Option<f64> {
        let u = (gamma - self.gamma_0) / self.step;
        if !(u >= 0.0 && u <= (self.n_gamma - 1) as f64) || alpha.is_nan() {
            return None;
        }
        let x = node_position(self.patch, alpha / alpha_c2(gamma))?;
        let cell = (x as usize).min(S_NODES - 2);
        let first = cell.saturating_sub(1);
        let rows: Vec<Option<f64>> = (first..(cell + 3).min(S_NODES))
            .map(|j| self.along_gamma(u, j))
            .collect();
        let row = |j: usize| {
            j.checked_sub(first)
                .and_then(|r| rows.get(r).copied().flatten())
        };
        let (start, k) = local_stencil(x, S_NODES, |j| row(j).is_some())?;
        let w = lagrange_weights(x, start, k);
        Some(
            (0..k)
                .map(|m| w[m] * row(start + m).unwrap_or(f64::NAN))
                .sum(),
        )
    }

    /// The located nodes: `(γ, α/α_c2, e_S)`.
    pub fn points(&self) -> Vec<(f64, f64, f64)> {
        (0..self.values.len())
            .filter(|&n| self.values[n].is_finite())
            .map(|n| {
                let (i, j) = (n / S_NODES, n % S_NODES);
                (
                    self.gamma_0 + i as f64 * self.step,
                    node_ratio(self.patch, j),
                    self.values[n],
                )
            })
            .collect()
    }

    /// How many nodes hold the sheet.
    pub fn traced_nodes(&self) -> usize {
        self.values.iter().filter(|e| e.is_finite()).count()
    }
}

impl Kink for SwitchSheet {
    fn name(&self) -> &'static str {
        match (self.kind, self.lower) {
            (SheetKind::Switch, false) => "e_S",
            (SheetKind::Switch, true) => "e_S lower",
            (SheetKind::EndMinus, _) => "e_E",
        }
    }

    fn patch(&self) -> PatchKind {
        self.patch
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
        match (self.kind, self.lower) {
            (SheetKind::Switch, false) => &SWITCH_PROBE_OFFSETS,
            (SheetKind::Switch, true) => &SWITCH_LOWER_PROBE_OFFSETS,
            (SheetKind::EndMinus, _) => &END_SHEET_PROBE_OFFSETS,
        }
    }
}

/// The upper and the lower edge of the switch sheet of Thornton's stick patch over `gammas` ×
/// `e_range` ([`SwitchSheet`]): columns of γ multiples of [`SWITCH_SHEET_STEP`] from one below
/// `γ_lo` (at least 1) to one beyond `γ_hi`, at each node the edges within [`REACH`] of the
/// `e_n` range ([`edges_at`]), the nodes in parallel. Each `None` where no node holds it.
pub fn switch_sheet_surfaces(
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> Result<[Option<SwitchSheet>; 2], SweepError> {
    sheet_surfaces(SheetKind::Switch, PatchKind::Stick, gammas, e_range)
}

/// The end-of-contact sheet `e_E` of Thornton's stick patch over `gammas` × `e_range`, traced
/// as [`switch_sheet_surfaces`] traces the upper edge of `e_S` (`end_minus_sheet_edges_thornton`,
/// the highest edge below which the contact ends in a `−μF_N` episode); `None` where no node
/// holds it. The lower edges of that predicate, where the episode appears as `e_n` grows, are
/// the surface E₋ that the search along α traces (`thornton_end_minus_surface`; in the range
/// of `configs/thornton-demo.toml` they are all there is).
///
/// In the partial-slip patch (`patch`) the columns cover `α/α_c2` from
/// [`PARTIAL_RATIO_FROM`] to `α_c2`, and only a γ range that reaches [`PARTIAL_SHEET_FROM`] is
/// traced (the sheet reaches `α_c2` from γ ≈ 1.86; γ 2.2: `e_n` 0.377 at 0.6 `α_c2`, 0.470 at
/// 0.95).
pub fn end_minus_sheet_surface(
    patch: PatchKind,
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> Result<Option<SwitchSheet>, SweepError> {
    if patch == PatchKind::PartialSlip && gammas.1 < PARTIAL_SHEET_FROM {
        return Ok(None);
    }
    let [upper, _] = sheet_surfaces(SheetKind::EndMinus, patch, gammas, e_range)?;
    Ok(upper)
}

/// Lowest γ up to which a range must reach for [`end_minus_sheet_surface`] to trace the sheet
/// in the partial-slip patch.
pub const PARTIAL_SHEET_FROM: f64 = 1.84;

/// Lowest `α/α_c2` of the columns of a sheet in the partial-slip patch.
pub const PARTIAL_RATIO_FROM: f64 = 0.4;

/// The upper and the lower edge of the sheet `kind` in `patch` ([`switch_sheet_surfaces`]).
fn sheet_surfaces(
    kind: SheetKind,
    patch: PatchKind,
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<[Option<SwitchSheet>; 2], SweepError> {
    let h = SWITCH_SHEET_STEP;
    let i_lo = ((gamma_lo / h - 1e-9).floor() as i64 - 1).max((1.0 / h).round() as i64);
    let i_hi = (gamma_hi / h + 1e-9).ceil() as i64 + 1;
    let range = (
        (e_lo - REACH).max(oblique_solver::law::MIN_RESTITUTION),
        (e_hi + REACH).min(E_TOP),
    );
    if i_hi < i_lo + 1 || range.0 >= range.1 {
        return Ok([None, None]);
    }
    let n_gamma = (i_hi - i_lo + 1) as usize;
    let edges = (0..n_gamma * S_NODES)
        .into_par_iter()
        .map(|n| {
            let gamma = (i_lo + (n / S_NODES) as i64) as f64 * h;
            let alpha = node_ratio(patch, n % S_NODES) * alpha_c2(gamma);
            edges_at(kind, gamma, alpha, range).map_err(|e| SweepError::Kink {
                curve: match kind {
                    SheetKind::Switch => "e_S",
                    SheetKind::EndMinus => "e_E",
                },
                gamma,
                what: format!("at alpha = {alpha}: {e}"),
            })
        })
        .collect::<Result<Vec<[f64; 2]>, SweepError>>()?;
    let sheet = |k: usize| {
        let sheet = SwitchSheet {
            gamma_0: i_lo as f64 * h,
            step: h,
            n_gamma,
            values: edges.iter().map(|e| e[k]).collect(),
            lower: k == 1,
            kind,
            patch,
        };
        (sheet.traced_nodes() > 0).then_some(sheet)
    };
    Ok([sheet(0), sheet(1)])
}

/// `α/α_c2` of node `j` of a column: in the stick patch `1/s` with `s = 1 − j/(S_NODES − 1)`,
/// within [`RATIO_ENDS`]; in the partial-slip patch evenly spaced from [`PARTIAL_RATIO_FROM`]
/// to `1/RATIO_ENDS.0` (just inside the patch).
fn node_ratio(patch: PatchKind, j: usize) -> f64 {
    let f = j as f64 / (S_NODES - 1) as f64;
    match patch {
        PatchKind::PartialSlip => {
            PARTIAL_RATIO_FROM + (1.0 / RATIO_ENDS.0 - PARTIAL_RATIO_FROM) * f
        }
        _ => (1.0 / (1.0 - f)).clamp(RATIO_ENDS.0, RATIO_ENDS.1),
    }
}

/// The position of `α/α_c2 = ratio` among the nodes of a column of `patch` (node `j` at `j`),
/// `None` outside the patch's side of `α_c2` (or below [`PARTIAL_RATIO_FROM`]).
fn node_position(patch: PatchKind, ratio: f64) -> Option<f64> {
    let n = (S_NODES - 1) as f64;
    match patch {
        PatchKind::PartialSlip => (PARTIAL_RATIO_FROM..=1.0)
            .contains(&ratio)
            .then(|| (ratio - PARTIAL_RATIO_FROM) / (1.0 / RATIO_ENDS.0 - PARTIAL_RATIO_FROM) * n),
        _ => {
            let s = 1.0 / ratio;
            (0.0..=1.0).contains(&s).then_some((1.0 - s) * n)
        }
    }
}

/// Highest `e_n` the sheet is looked for at (`e_n` = 1 is the elastic law, whose limits do not
/// jump).
const E_TOP: f64 = 0.999;

/// The highest upper edge and the highest lower edge of the sheet `kind` in `range` (NaN where
/// there is none): the edges where its predicate (the switch zone, the `−` episode at the end)
/// starts or stops holding as `e_n` grows, bracketed by a scan of [`SCAN_STEP`] and bisected
/// to 1e-9 (`switch_sheet_edges_thornton`, `end_minus_sheet_edges_thornton`). The upper edge
/// of `e_S` is the one the scan from the top found first before lower edges were traced, to
/// the bit.
fn edges_at(
    kind: SheetKind,
    gamma: f64,
    alpha: f64,
    range: (f64, f64),
) -> Result<[f64; 2], oblique_solver::PhysicsError> {
    let find = match kind {
        SheetKind::Switch => switch_sheet_edges_thornton,
        SheetKind::EndMinus => end_minus_sheet_edges_thornton,
    };
    let edges = find(gamma, alpha, range, SCAN_STEP, SWITCH_SHEET_STEPS)?;
    let highest = |lower: bool| {
        edges
            .iter()
            .rev()
            .find(|&&(_, above)| above == lower)
            .map_or(f64::NAN, |&(e, _)| e)
    };
    Ok([highest(false), highest(true)])
}
