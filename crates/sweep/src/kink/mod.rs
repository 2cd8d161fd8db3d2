//! Kink curves of `P` whose leaves the refinement's prediction cannot be trusted on, traced
//! before the build so that every leaf they cross is measured by direct simulations
//! (`nodes.probe_kinks`, `docs/table-format.md`, "The stated error bound").
//!
//! The one treated today is the fold F₋ of the partial-slip patch (`docs/solver.md`, "Kink
//! curves": a `−μF_N` episode late in the restitution phase vanishes as α grows; γ ≳ 2.40,
//! α ≈ 0.31–0.52). Above it `P` departs from its smooth continuation like `(α − α_F)^{3/2}`:
//! at γ = 3.3589 the slope `dP/d ln α` falls from 0.345 at F₋ by `0.9 √(α/α_F − 1)` (0.020 at
//! 5e-4 above, 0.090 at 1e-2). A cubic across such a point errs in proportion to `h^{3/2}`, not
//! `h²`, and the quarter-surplus prediction of a leaf that F₋ crosses was up to 4.2× below the
//! leaf's error in `tables/full.h5` (1.61e-5 at γ = 3.35889, α = 0.326995; `docs/accuracy.md`).
//!
//! An elastic table traces it as a curve `α_F(γ)` ([`fold_minus_curve`]); a Kelvin–Voigt table
//! as a surface `α_F(γ, e_n)` ([`fold_minus_surface`]), which ends where damping removes the
//! fold (`e_n` ≈ 0.99 at γ = 2.4, 0.94 at 2.6, 0.87 at 3.5). Both are a [`Kink`]: the probes
//! of a cell ask any kink for its α on the cell's node rows, so another kink is one more entry
//! of [`trace`].
//!
//! The second is the end-of-contact curve E₋ of an elastic table ([`end_minus_curve`]): the
//! last `−μF_N` episode leaves the separation as α grows. It runs from α → ∞ at γ ≈ 1.732
//! down the stick patch, across α_c2 at γ ≈ 1.907 and through the partial-slip patch to F₋'s
//! birth (γ = 2.40). `P` keeps its slope there, but the leaves it crosses err more than their
//! surplus predicts: `tables/full.h5` built without its probes erred by 1.04e-5 at γ = 2.2796,
//! α = 0.59139 (0.24 % below E₋; stated bound 7.98e-6), and by 8.1e-6 at γ = 1.872 in a stick
//! leaf whose prediction was 3.2e-6.

mod end_minus;
mod interlude;
pub mod stored;
mod switch_sheet;
mod thornton;

pub use switch_sheet::{
    end_minus_sheet_surface, switch_sheet_surfaces, SheetKind, SwitchSheet,
    END_SHEET_PROBE_OFFSETS, PARTIAL_RATIO_FROM, PARTIAL_SHEET_FROM, SWITCH_LOWER_PROBE_OFFSETS,
    SWITCH_PROBE_OFFSETS, SWITCH_SHEET_STEP, SWITCH_SHEET_STEPS,
};

pub use interlude::{
    interlude_sheet, near_interlude_points, InterludeSheet, SHEET_PROBE_OFFSETS, SHEET_STEP,
    SHEET_TO,
};

pub use thornton::{
    thornton_end_minus_surface, thornton_fold_minus_surface, thornton_loading_band_surface,
    thornton_plus_strip_surfaces, BAND_TRACE_STEPS, PLUS_STRIP_FROM, THORNTON_END_STEP,
    THORNTON_ROWS_PER_UNIT_E, THORNTON_STEP, THORNTON_TRACE_STEPS,
};

pub use end_minus::{
    end_minus_in_patch, end_minus_surface, EndMinusSides, END_PROBE_OFFSETS, END_SURFACE_STEP,
};

use rayon::prelude::*;

use super::SweepError;
use oblique_solver::history::{
    end_minus_edges_thornton, end_minus_sheet_edges_thornton, fold_minus_at, fold_minus_at_e,
    fold_minus_free_below, fold_minus_free_below_thornton, fold_minus_thornton,
    loading_band_thornton, loading_fold_thornton, reslip_fold_thornton,
    restitution_minus_somewhere_e, restitution_plus_change_thornton,
    restitution_plus_strip_thornton, switch_fold_thornton, switch_sheet_edges_thornton,
};
use oblique_solver::Law;
use oblique_table::surface::{stencil4, PatchKind, Point};

/// A kink of `P` that the probes of `nodes.probe_kinks` measure the leaves next to: where it
/// lies in one patch, as `α_K(γ, e_n)`. The probe code asks nothing else, so a new kink (of
/// another law, or in another patch) implements this and joins [`trace`].
pub trait Kink: std::fmt::Debug + Send + Sync {
    /// Its name in messages (`F-`).
    fn name(&self) -> &'static str;
    /// The patch whose coordinate the probes are placed along.
    fn patch(&self) -> PatchKind;
    /// `α_K` at `(γ, e_n)`; `None` where the kink does not exist or was not traced (no probes
    /// there).
    fn alpha(&self, gamma: f64, e_n: f64) -> Option<f64>;
    /// Where a cell next to it is measured on each row, in node intervals from it along the
    /// coordinate ([`PROBE_OFFSETS`] unless the kink says otherwise), or along `e_n` for a kink
    /// across that axis.
    fn offsets(&self) -> &'static [f64] {
        &PROBE_OFFSETS
    }
    /// For a kink across the `e_n` axis (a sheet `e_n = e_K(γ, α)`, [`InterludeSheet`]): `e_K`
    /// at `(γ, α)`, `None` where it does not exist or was not traced. The probes then lie on
    /// the cell's lines along `e_n` ([`Kink::alpha`] answers `None`). `None` for a kink along
    /// the coordinate (the default).
    fn e_n_at(&self, _gamma: f64, _alpha: f64) -> Option<f64> {
        None
    }
    /// Whether the kink lies across the `e_n` axis ([`Kink::e_n_at`]).
    fn across_e_n(&self) -> bool {
        false
    }
    /// Whether the knots put this kink on a cell edge where they apply (`nodes.knots`: F₋ of
    /// the Kelvin–Voigt law), so that its probes are not needed there.
    fn knotted(&self) -> bool {
        false
    }
}

/// Whether `nodes.probe_kinks` has kinks to trace for tables of `law`: F₋ and E₋ of every law
/// (of Thornton's law [`thornton_fold_minus_surface`] and [`thornton_end_minus_surface`], and
/// the edges of its `+` strip, [`thornton_plus_strip_surfaces`], and the upper and lower
/// edges of its switch sheet, [`switch_sheet_surfaces`]; its other kinks in the slip regions,
/// `docs/solver.md`, are knots or not followed).
pub fn probes_implemented(law: Law) -> bool {
    matches!(law, Law::Elastic | Law::KelvinVoigt | Law::Thornton)
}

/// What [`trace`] traced once for a whole build, shared by its patches: the end-of-contact
/// curve E₋ (elastic) and surface (Kelvin–Voigt) cross both the stick and the partial-slip
/// patch.
#[derive(Debug, Default)]
pub struct Traced {
    /// The Kelvin–Voigt E₋ and the γ and `e_n` ranges it was traced for.
    end_minus: Option<(TracedOver, Option<KinkSurface>)>,
    /// The elastic E₋ and the γ range it was traced for.
    end_minus_curve: Option<((f64, f64), Option<KinkCurve>)>,
    /// Thornton's E₋ and the γ and `e_n` ranges it was traced for.
    end_minus_thornton: Option<(TracedOver, Option<KinkSurface>)>,
    /// The edges of Thornton's `+` strip and the γ and `e_n` ranges they were traced for.
    plus_strip_thornton: Option<(TracedOver, [Option<KinkSurface>; 2])>,
    /// The upper edge of Thornton's loading band and the γ and `e_n` ranges it was traced for.
    loading_band_thornton: Option<(TracedOver, Option<KinkSurface>)>,
}

impl Traced {
    /// The elastic E₋ over `gammas` for the patch `kind`, traced on the first call for these
    /// γ ([`end_minus_curve`]; the curve does not depend on the patch, only its label).
    fn end_minus_curve(
        &mut self,
        kind: PatchKind,
        gammas: (f64, f64),
    ) -> Result<Option<KinkCurve>, SweepError> {
        let curve = match &self.end_minus_curve {
            Some((over, c)) if *over == gammas => c.clone(),
            _ => {
                let c = end_minus_curve(kind, gammas.0, gammas.1)?;
                self.end_minus_curve = Some((gammas, c.clone()));
                c
            }
        };
        Ok(curve.map(|c| KinkCurve { patch: kind, ..c }))
    }
}

/// F₋ of a table of `law` with an `e_n` axis as a surface over `gammas` × `e_range`
/// ([`fold_minus_surface`] for the Kelvin–Voigt law, [`thornton_fold_minus_surface`] for
/// Thornton's), `None` for a law whose F₋ is not traced as a surface (`sweep verify
/// --near-fold`).
pub fn fold_minus_surface_of(
    law: Law,
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> Option<Result<Option<KinkSurface>, SweepError>> {
    match law {
        Law::KelvinVoigt => Some(fold_minus_surface(gammas, e_range)),
        Law::Thornton => Some(thornton_fold_minus_surface(gammas, e_range)),
        _ => None,
    }
}

/// Whether tables of `law` with an `e_n` axis have the kinks of [`end_minus_surface`] and
/// [`interlude_sheet`] (the Kelvin–Voigt law's end-of-contact surface and sheet I₊).
pub fn has_damped_surfaces(law: Law) -> bool {
    law == Law::KelvinVoigt
}

/// The γ and `e_n` ranges a kink was traced over.
type TracedOver = ((f64, f64), (f64, f64));

/// The edges of Thornton's `+` strip over `gammas` × `e_range` ([`thornton_plus_strip_surfaces`]),
/// traced on the first call for that range: the knots of the partial-slip patch and the probes
/// of both patches share them.
pub(crate) fn plus_strip(
    traced: &mut Traced,
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> Result<[Option<KinkSurface>; 2], SweepError> {
    traced_once(&mut traced.plus_strip_thornton, (gammas, e_range), || {
        thornton_plus_strip_surfaces(gammas, e_range)
    })
}

/// What `slot` holds if it was traced over `over`, else `trace()`, kept in `slot` for the
/// other patch of the same build.
fn traced_once<T: Clone>(
    slot: &mut Option<(TracedOver, T)>,
    over: TracedOver,
    trace: impl FnOnce() -> Result<T, SweepError>,
) -> Result<T, SweepError> {
    if let Some((o, t)) = slot {
        if *o == over {
            return Ok(t.clone());
        }
    }
    let t = trace()?;
    *slot = Some((over, t.clone()));
    Ok(t)
}

/// The kinks of `law` in the patch `kind` that the probes measure, traced over γ in `gammas`
/// (and `e_n` in `e_range` for a table with an `e_n` axis): F₋ of the partial-slip patch as a
/// curve (elastic, [`fold_minus_curve`]) or as a surface (Kelvin–Voigt,
/// [`fold_minus_surface`]); the end-of-contact curve E₋ in both patches as a curve (elastic,
/// [`end_minus_curve`]) or as a surface (Kelvin–Voigt, [`end_minus_surface`], split by
/// [`end_minus_in_patch`]), each traced once per `traced` for both patches; the sheet I₊ of the
/// Kelvin–Voigt partial-slip patch across the `e_n` axis ([`interlude_sheet`]); F₋ of
/// Thornton's partial-slip patch ([`thornton_fold_minus_surface`]) and its E₋ in both patches
/// ([`thornton_end_minus_surface`], split by [`end_minus_in_patch`], traced once per `traced`),
/// the two edges of its `+` strip in both patches ([`thornton_plus_strip_surfaces`], the same
/// way) and the upper and lower edges of the switch sheet `e_S` across the `e_n` axis of its
/// stick patch ([`switch_sheet_surfaces`]); none where the range holds no such kink or the
/// law has none traced. `tracing` is told the name of each kink before it is traced (a
/// surface can take minutes over a wide range).
pub fn trace(
    law: Law,
    kind: PatchKind,
    gammas: (f64, f64),
    e_range: Option<(f64, f64)>,
    traced: &mut Traced,
    tracing: &dyn Fn(&str),
) -> Result<Vec<Box<dyn Kink>>, SweepError> {
    let mut out: Vec<Box<dyn Kink>> = Vec::new();
    match (law, kind, e_range) {
        (Law::Elastic, PatchKind::PartialSlip, None) => {
            tracing("F-");
            if let Some(c) = fold_minus_curve(gammas.0, gammas.1)? {
                out.push(Box::new(c));
            }
            tracing("E-");
            if let Some(c) = traced.end_minus_curve(kind, gammas)? {
                out.push(Box::new(c));
            }
        }
        (Law::Elastic, PatchKind::Stick, None) => {
            tracing("E-");
            if let Some(c) = traced.end_minus_curve(kind, gammas)? {
                out.push(Box::new(c));
            }
        }
        (Law::KelvinVoigt, _, Some(e_range)) => {
            if kind == PatchKind::PartialSlip {
                tracing("F-");
                if let Some(s) = fold_minus_surface(gammas, e_range)? {
                    out.push(Box::new(s));
                }
            }
            tracing("E-");
            let full = traced_once(&mut traced.end_minus, (gammas, e_range), || {
                end_minus_surface(gammas, e_range, kind)
            })?;
            if let Some(full) = full {
                out.push(Box::new(end_minus_in_patch(&full, kind)));
            }
            if kind == PatchKind::PartialSlip {
                tracing("I+");
                if let Some(s) = interlude_sheet(gammas, e_range)? {
                    out.push(Box::new(s));
                }
            }
        }
        (Law::Thornton, _, Some(e_range)) => {
            if kind == PatchKind::PartialSlip {
                tracing("F-");
                if let Some(s) = thornton_fold_minus_surface(gammas, e_range)? {
                    out.push(Box::new(s));
                }
            }
            tracing("E-");
            let full = traced_once(&mut traced.end_minus_thornton, (gammas, e_range), || {
                thornton_end_minus_surface(gammas, e_range)
            })?;
            if let Some(full) = full {
                out.push(Box::new(end_minus_in_patch(&full, kind)));
            }
            tracing("the edges of the + strip");
            let strip = plus_strip(traced, gammas, e_range)?;
            for edge in strip.into_iter().flatten() {
                out.push(Box::new(end_minus_in_patch(&edge, kind)));
            }
            tracing("the upper edge of the loading band");
            let band = traced_once(&mut traced.loading_band_thornton, (gammas, e_range), || {
                thornton_loading_band_surface(gammas, e_range)
            })?;
            if let Some(edge) = band {
                out.push(Box::new(end_minus_in_patch(&edge, kind)));
            }
            if kind == PatchKind::Stick {
                tracing("the edges of the switch sheet e_S");
                for s in switch_sheet_surfaces(gammas, e_range)?
                    .into_iter()
                    .flatten()
                {
                    out.push(Box::new(s));
                }
            }
            tracing("the end-of-contact sheet e_E");
            if let Some(s) = end_minus_sheet_surface(kind, gammas, e_range)? {
                out.push(Box::new(s));
            }
        }
        _ => {}
    }
    Ok(out)
}

/// Lowest γ at which F₋ is traced: its predicate first holds at γ ≈ 2.398 (2048 steps); below
/// it the curve is younger than its tracing and its slope change smaller.
pub const FOLD_MINUS_FROM: f64 = 2.40;
/// Spacing of the traced points in γ.
pub const STEP: f64 = 0.01;
/// Steps per contact time of the tracing (α_F within about 1e-5 relative of the converged
/// curve, `docs/solver.md`; a leaf's node spacing next to F₋ is ≥ 1e-3 relative).
pub const TRACE_STEPS: usize = 2048;

/// How a [`KinkCurve`] stores `α_K` at its grid points: the quantity that is smooth in γ, which
/// the 4-point rule interpolates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveScale {
    /// `ln α_K` (F₋).
    Ln,
    /// `1/α_K`, nearly linear in γ where E₋ leaves for α → ∞ (0.0479, 0.1069, 0.1647 at
    /// γ = 1.74, 1.75, 1.76).
    Reciprocal,
}

/// A kink curve `α_K(γ)` traced on an even grid of γ, interpolated (4-point Lagrange in the
/// curve's [`CurveScale`]) between the grid points; undefined outside the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct KinkCurve {
    name: &'static str,
    patch: PatchKind,
    scale: CurveScale,
    gamma_0: f64,
    step: f64,
    values: Vec<f64>,
}

impl KinkCurve {
    /// `α_K(γ)`, or `None` outside `[γ₀, γ₀ + (n − 1)·step]`.
    pub fn alpha_at(&self, gamma: f64) -> Option<f64> {
        let n = self.values.len();
        let u = (gamma - self.gamma_0) / self.step;
        if !(u >= 0.0 && u <= (n - 1) as f64) {
            return None;
        }
        let (start, w) = stencil4(u, n);
        let l = &self.values[start..start + 4];
        let v = w[0] * l[0] + w[1] * l[1] + w[2] * l[2] + w[3] * l[3];
        self.scale.alpha(v)
    }

    /// The γ range of the curve.
    pub fn gamma_range(&self) -> (f64, f64) {
        (
            self.gamma_0,
            self.gamma_0 + (self.values.len() - 1) as f64 * self.step,
        )
    }
}

impl Kink for KinkCurve {
    fn name(&self) -> &'static str {
        self.name
    }

    fn patch(&self) -> PatchKind {
        self.patch
    }

    /// [`KinkCurve::alpha_at`] at `e_n = 1`, the only restitution of an elastic table.
    fn alpha(&self, gamma: f64, e_n: f64) -> Option<f64> {
        if e_n == 1.0 {
            self.alpha_at(gamma)
        } else {
            None
        }
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
        name: "F-",
        patch: PatchKind::PartialSlip,
        scale: CurveScale::Ln,
        gamma_0,
        step: STEP,
        values: ln_alpha,
    }))
}

/// Where the end-of-contact curve E₋ is traced up to: F₋'s first traced point. Beyond it the
/// `−μF_N` episode at the separation turns into F₋'s interior one, whose probes take over.
pub const END_MINUS_TO: f64 = FOLD_MINUS_FROM;

/// Lowest γ at which E₋ is searched: it leaves for α → ∞ at γ ≈ 1.732 (`1/α_E` falls by
/// about 0.059 per 0.01 of γ towards it); points of the grid below where it is found are
/// dropped, so that the curve starts at the first grid point that holds it (γ = 1.74, α_E =
/// 20.87, where `dP/d ln α` is 0.009 and the leaves' errors small).
pub const END_MINUS_FROM: f64 = 1.73;

/// `1/α_E` of E₋ at a few γ (`kinkmap`, 2048 steps), linearly interpolated (extrapolated below
/// the first): the first guess of each point's search, which must lie below E₋ or above it
/// within a factor `e`.
fn end_minus_guess(gamma: f64) -> f64 {
    const TABLE: [(f64, f64); 10] = [
        (1.74, 0.04790),
        (1.75, 0.10689),
        (1.80, 0.38698),
        (1.85, 0.65216),
        (1.90, 0.90843),
        (1.95, 1.05102),
        (2.00, 1.14955),
        (2.10, 1.34468),
        (2.20, 1.54040),
        (2.40, 1.94918),
    ];
    let first = TABLE[0];
    let inv = if gamma < first.0 {
        first.1 + (gamma - first.0) * (TABLE[1].1 - first.1) / (TABLE[1].0 - first.0)
    } else {
        lerp_table(&TABLE, gamma)
    };
    // Where the extrapolation reaches nothing (below γ ≈ 1.732) look at a large α: E₋ lies
    // above it if it exists, and the search finds nothing within a factor `e`.
    1.0 / inv.max(1e-3)
}

/// The end-of-contact curve E₋ ([`oblique_solver::history::has_end_minus`]) of the patch `kind`
/// over the part of `[gamma_lo, gamma_hi]` within [[`END_MINUS_FROM`], [`END_MINUS_TO`]]
/// (widened by two grid steps on either side, where they exist, for the 4-point rule): a grid of
/// [`STEP`] from the first point at or below the range's start, each point located to ≈1e-10
/// in `ln α` at [`TRACE_STEPS`] steps (in parallel), stored as `1/α_E`; leading points where
/// E₋ does not exist yet are dropped. `None` when fewer than four points remain.
pub fn end_minus_curve(
    kind: PatchKind,
    gamma_lo: f64,
    gamma_hi: f64,
) -> Result<Option<KinkCurve>, SweepError> {
    let lo = (gamma_lo - 2.0 * STEP).max(END_MINUS_FROM);
    let hi = (gamma_hi + 2.0 * STEP).min(END_MINUS_TO);
    if hi < lo + 3.0 * STEP {
        return Ok(None);
    }
    let i0 = (lo / STEP - 1e-9).floor() as i64;
    let i1 = (hi / STEP + 1e-9).floor() as i64;
    let found = (i0..=i1)
        .into_par_iter()
        .map(|i| {
            let g = i as f64 * STEP;
            let fail = |what: String| SweepError::Kink {
                curve: "E-",
                gamma: g,
                what,
            };
            let a = oblique_solver::history::end_minus_at(g, end_minus_guess(g), TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?;
            Ok((g, a))
        })
        .collect::<Result<Vec<(f64, Option<f64>)>, SweepError>>()?;
    let Some(first) = found.iter().position(|(_, a)| a.is_some()) else {
        return Ok(None);
    };
    let values = found[first..]
        .iter()
        .map(|&(g, a)| {
            a.map(|a| 1.0 / a).ok_or_else(|| SweepError::Kink {
                curve: "E-",
                gamma: g,
                what: "not found near its tabulated position".into(),
            })
        })
        .collect::<Result<Vec<f64>, SweepError>>()?;
    if values.len() < 4 {
        return Ok(None);
    }
    Ok(Some(KinkCurve {
        name: "E-",
        patch: kind,
        scale: CurveScale::Reciprocal,
        gamma_0: found[first].0,
        step: STEP,
        values,
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
) -> Vec<Point> {
    near_kink_points(curve, (gamma_min, gamma_max), (-4.0, -2.0), n, seed)
}

/// `n` points next to the end-of-contact curve E₋ (`curve`, from [`end_minus_curve`]): as
/// [`near_fold_minus_points`] places them, with `r = 10^u`, `u` uniform in `[−4, −1]` (the
/// leaves it crossed erred most at 0.2–2 % from it). The same `seed` gives the same points
/// (`sweep verify --near-end`).
pub fn near_end_minus_points(
    curve: &KinkCurve,
    gamma_min: f64,
    gamma_max: f64,
    n: usize,
    seed: u64,
) -> Vec<Point> {
    near_kink_points(curve, (gamma_min, gamma_max), (-4.0, -1.0), n, seed)
}

/// `n` points at `α = α_K(γ)(1 + s·10^u)`, `γ` uniform over the curve's range within
/// `[gamma_min, gamma_max]`, `s = ±1`, `u` uniform in `[u_lo, u_hi]`, `e_n = 1`.
fn near_kink_points(
    curve: &KinkCurve,
    (gamma_min, gamma_max): (f64, f64),
    (u_lo, u_hi): (f64, f64),
    n: usize,
    seed: u64,
) -> Vec<Point> {
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
        let r = 10f64.powf(u_lo + (u_hi - u_lo) * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        if let Some(alpha_k) = curve.alpha_at(gamma) {
            out.push(Point::new(gamma, alpha_k * (1.0 + sign * r), 1.0));
        }
    }
    out
}

/// Rows of a kink surface per unit of `e_n`: rows at `e_n = 1 − l/200` (0.005 apart).
pub const ROWS_PER_UNIT_E: f64 = 200.0;

/// The relative change of `α_F` per row of [`ROWS_PER_UNIT_E`] at the top of a column
/// (`d ln α_F / d e_n` ≈ 1.3–2.4 over γ 2.5–3.5, `docs/solver.md`): the first guess one row
/// below `e_n = 1`, before two rows give a slope.
const FIRST_ROW_SLOPE: f64 = 0.0075;

/// How far (in `ln α`) a point located by continuation may lie from its extrapolated guess
/// (a neighbouring row's `α_F` differs by under 1.2 %, the extrapolation by under 1e-4).
const CONTINUATION_SPAN: f64 = 0.03;

/// A kink surface `α_K(γ, e_n)` traced on a grid of γ (spacing `step`) and `e_n`
/// (`rows_per_unit` rows per unit, from `e_n = 1` down), stored in its [`CurveScale`] and
/// interpolated in that scale along γ in each row, then across the rows (Lagrange, up to 4
/// points each, fewer at the edge of the traced nodes). Undefined where the kink was not found
/// on the two nodes on either side of the point along either axis: within one grid step of
/// where it ends, and outside the grid.
#[derive(Debug, Clone, PartialEq)]
pub struct KinkSurface {
    name: &'static str,
    patch: PatchKind,
    scale: CurveScale,
    gamma_0: f64,
    step: f64,
    rows_per_unit: f64,
    n_gamma: usize,
    n_e: usize,
    /// Where the probes measure a cell next to it ([`Kink::offsets`]).
    offsets: &'static [f64],
    /// Whether a point up to one grid step beyond the last node of a row (or column of rows)
    /// is extrapolated from the nodes on its side ([`one_sided_stencil`]): E₋ bends where it
    /// crosses α_c2, and each patch keeps the nodes on its own side.
    extrapolate: bool,
    /// Whether the knots put it on a cell edge where they apply ([`Kink::knotted`]: F₋ of the
    /// Kelvin–Voigt law).
    knotted: bool,
    /// `α_K` of node `(i, l)` in `scale` (γ = `gamma_0 + i step`, `e_n = 1 − l/rows_per_unit`)
    /// at `i n_e + l`; NaN where the kink was not found.
    values: Vec<f64>,
}

impl CurveScale {
    /// `α` from its stored value (`None` for a reciprocal at or below 0).
    fn alpha(self, v: f64) -> Option<f64> {
        match self {
            CurveScale::Ln => v.is_finite().then(|| v.exp()),
            CurveScale::Reciprocal => (v > 0.0).then(|| 1.0 / v),
        }
    }
}

/// `e_n` of row `l` of a kink surface with `rows_per_unit` rows per unit of `e_n` (exact at
/// `e_n` = 1, 0.99, …, 0.3 for 100 or 200 rows).
fn e_of_row(l: usize, rows_per_unit: f64) -> f64 {
    (rows_per_unit - l as f64) / rows_per_unit
}

/// The Lagrange stencil on up to four consecutive nodes among `0..n` (node `i` at `x = i`)
/// for which `ok` holds, around `x`: `(start, k)` with `2 ≤ k ≤ 4`, centred as
/// [`stencil4`] centres it where the nodes allow. `None` when the two nodes of the interval
/// holding `x` are not both `ok` (or `x` lies outside `[0, n − 1]`).
fn local_stencil(x: f64, n: usize, ok: impl Fn(usize) -> bool) -> Option<(usize, usize)> {
    if n < 2 || !(x >= 0.0 && x <= (n - 1) as f64) {
        return None;
    }
    let cell = (x as usize).min(n - 2);
    if !(ok(cell) && ok(cell + 1)) {
        return None;
    }
    let mut lo = cell;
    while lo > 0 && cell - lo < 2 && ok(lo - 1) {
        lo -= 1;
    }
    let mut hi = cell + 1;
    while hi + 1 < n && hi - cell < 3 && ok(hi + 1) {
        hi += 1;
    }
    let k = (hi - lo + 1).min(4);
    let start = cell.saturating_sub(1).clamp(lo, hi + 1 - k);
    Some((start, k))
}

/// Where [`local_stencil`] finds nothing because `x` lies within one node beyond the end of a
/// run of `ok` nodes: up to four consecutive `ok` nodes of that run ending next to `x`
/// (at least two), for extrapolation.
fn one_sided_stencil(x: f64, n: usize, ok: impl Fn(usize) -> bool) -> Option<(usize, usize)> {
    if n < 2 || !(x >= 0.0 && x <= (n - 1) as f64) {
        return None;
    }
    let cell = (x as usize).min(n - 2);
    let run = |last: usize, down: bool| -> Option<(usize, usize)> {
        let mut k = 1;
        while k < 4 {
            let next = if down {
                last.checked_sub(k)
            } else {
                Some(last + k).filter(|&j| j < n)
            };
            match next {
                Some(j) if ok(j) => k += 1,
                _ => break,
            }
        }
        (k >= 2).then_some((if down { last + 1 - k } else { last }, k))
    };
    match (ok(cell), ok(cell + 1)) {
        (true, false) => run(cell, true),
        (false, true) => run(cell + 1, false),
        _ => None,
    }
}

/// The Lagrange weights of nodes `start .. start + k` at `x`.
fn lagrange_weights(x: f64, start: usize, k: usize) -> [f64; 4] {
    let mut w = [0.0; 4];
    for (j, wj) in w.iter_mut().enumerate().take(k) {
        let mut prod = 1.0;
        for m in 0..k {
            if m != j {
                prod *= (x - (start + m) as f64) / (j as f64 - m as f64);
            }
        }
        *wj = prod;
    }
    w
}

impl KinkSurface {
    /// The stored value of node `(i, l)` (NaN where not found).
    fn node(&self, i: usize, l: usize) -> f64 {
        self.values[i * self.n_e + l]
    }

    /// `e_n` of row `l`.
    fn e_of_row(&self, l: usize) -> f64 {
        e_of_row(l, self.rows_per_unit)
    }

    /// The stored value interpolated along γ (position `u` in grid steps) in row `l`.
    fn along_gamma(&self, u: f64, l: usize) -> Option<f64> {
        let ok = |i: usize| self.node(i, l).is_finite();
        let (start, k) = local_stencil(u, self.n_gamma, ok).or_else(|| {
            self.extrapolate
                .then(|| one_sided_stencil(u, self.n_gamma, ok))?
        })?;
        let w = lagrange_weights(u, start, k);
        Some((0..k).map(|j| w[j] * self.node(start + j, l)).sum())
    }

    /// `α_K(γ, e_n)`, or `None` where it is undefined (see [`KinkSurface`]).
    pub fn alpha_at(&self, gamma: f64, e_n: f64) -> Option<f64> {
        let u = (gamma - self.gamma_0) / self.step;
        let x = (1.0 - e_n) * self.rows_per_unit;
        if !(u >= 0.0 && u <= (self.n_gamma - 1) as f64) {
            return None;
        }
        // The rows that can take part (within two of the interval holding `x`), each
        // interpolated along γ once.
        let cell = (x.max(0.0) as usize).min(self.n_e.saturating_sub(2));
        let first = cell.saturating_sub(2);
        let rows: Vec<Option<f64>> = (first..(cell + 4).min(self.n_e))
            .map(|l| self.along_gamma(u, l))
            .collect();
        let row = |l: usize| {
            l.checked_sub(first)
                .and_then(|r| rows.get(r).copied().flatten())
        };
        let ok = |l: usize| row(l).is_some();
        let (start, k) = local_stencil(x, self.n_e, ok).or_else(|| {
            self.extrapolate
                .then(|| one_sided_stencil(x, self.n_e, ok))?
        })?;
        let w = lagrange_weights(x, start, k);
        let v: f64 = (0..k)
            .map(|j| w[j] * row(start + j).unwrap_or(f64::NAN))
            .sum();
        self.scale.alpha(v)
    }

    /// The γ of the grid's first and last columns that hold the kink, or `None` if none does.
    pub fn gamma_range(&self) -> Option<(f64, f64)> {
        let has = |i: usize| (0..self.n_e).any(|l| self.node(i, l).is_finite());
        let lo = (0..self.n_gamma).find(|&i| has(i))?;
        let hi = (0..self.n_gamma).rev().find(|&i| has(i))?;
        Some((
            self.gamma_0 + lo as f64 * self.step,
            self.gamma_0 + hi as f64 * self.step,
        ))
    }

    /// The `e_n` of the grid's lowest and highest rows that hold the kink, or `None`.
    pub fn e_n_range(&self) -> Option<(f64, f64)> {
        let has = |l: usize| (0..self.n_gamma).any(|i| self.node(i, l).is_finite());
        let lo = (0..self.n_e).rev().find(|&l| has(l))?;
        let hi = (0..self.n_e).find(|&l| has(l))?;
        Some((self.e_of_row(lo), self.e_of_row(hi)))
    }

    /// The traced nodes that hold the kink: `(γ, e_n, v)`, `v` the stored value of `α_K` in
    /// the surface's [`CurveScale`] (`ln α_K` for F₋).
    pub fn nodes(&self) -> Vec<(f64, f64, f64)> {
        (0..self.n_gamma)
            .flat_map(|i| (0..self.n_e).map(move |l| (i, l)))
            .filter(|&(i, l)| self.node(i, l).is_finite())
            .map(|(i, l)| {
                let g = self.gamma_0 + i as f64 * self.step;
                (g, self.e_of_row(l), self.node(i, l))
            })
            .collect()
    }

    /// How many nodes hold the kink (each one located by a fold search).
    pub fn traced_nodes(&self) -> usize {
        self.values.iter().filter(|a| a.is_finite()).count()
    }
}

impl Kink for KinkSurface {
    fn name(&self) -> &'static str {
        self.name
    }

    fn patch(&self) -> PatchKind {
        self.patch
    }

    fn alpha(&self, gamma: f64, e_n: f64) -> Option<f64> {
        self.alpha_at(gamma, e_n)
    }

    fn offsets(&self) -> &'static [f64] {
        self.offsets
    }

    fn knotted(&self) -> bool {
        self.knotted
    }
}

/// One column of [`fold_minus_surface`]: `ln α_F` at `γ` on rows `0..n_e`, from `e_n = 1`
/// down, each row continued from the rows above (extrapolated), NaN from the first row where
/// F₋ is not found (damping ends it; it does not come back at lower `e_n`).
fn fold_minus_column(gamma: f64, n_e: usize) -> Result<Vec<f64>, SweepError> {
    let mut out = vec![f64::NAN; n_e];
    for l in 0..n_e {
        let e_n = e_of_row(l, ROWS_PER_UNIT_E);
        let fail = |what: String| SweepError::Kink {
            curve: "F-",
            gamma,
            what: format!("at e_n = {e_n}: {what}"),
        };
        let guess = match l {
            0 => first_guess(gamma),
            1 => (out[0] - FIRST_ROW_SLOPE).exp(),
            2 => (2.0 * out[1] - out[0]).exp(),
            _ => (3.0 * out[l - 1] - 3.0 * out[l - 2] + out[l - 3]).exp(),
        };
        let found = if l == 0 {
            // The first guess lies 1 % above the elastic curve; near F₋'s birth its predicate
            // holds only on a narrow interval below it, which the search finds.
            match fold_minus_at(gamma, guess, TRACE_STEPS).map_err(|e| fail(e.to_string()))? {
                Some(a) => Some(a),
                None => match restitution_minus_somewhere_e(gamma, 1.0, (0.25, 0.8), TRACE_STEPS)
                    .map_err(|e| fail(e.to_string()))?
                {
                    Some(a) => {
                        fold_minus_at(gamma, a, TRACE_STEPS).map_err(|e| fail(e.to_string()))?
                    }
                    None => None,
                },
            }
        } else {
            // Accepted within `CONTINUATION_SPAN` of the guess: a search that missed the
            // predicate's interval (at the end of F₋ it narrows) and found another change is no
            // point of this column.
            fold_minus_at_e(gamma, e_n, guess, TRACE_STEPS)
                .map_err(|e| fail(e.to_string()))?
                .filter(|a| (a / guess).ln().abs() <= CONTINUATION_SPAN)
        };
        match found {
            Some(a) => out[l] = a.ln(),
            None => break,
        }
    }
    Ok(out)
}

/// F₋ of the Kelvin–Voigt law as a surface `α_F(γ, e_n)` over `gammas` × `e_range`, for the
/// probes of a table with an `e_n` axis: on a grid of γ spacing [`STEP`] from one step below
/// `max(γ_lo, γ_free)` to one step beyond `γ_hi` (`γ_free` =
/// [`fold_minus_free_below`]`(e_max)`: no F₋ below it) and rows `e_n = 1, 0.99, …` down to
/// one row below `e_min` (or 0.3), each column traced from `e_n = 1` down by continuation
/// ([`fold_minus_at_e`], [`TRACE_STEPS`] steps, ≈1e-10 in `ln α`), the columns in parallel.
/// `None` when γ_hi lies below γ_free (no F₋ in the range). A column's top node (`e_n = 1`) is
/// searched as [`fold_minus_curve`] searches its points, then anywhere in α ∈ [0.25, 0.8] where
/// that finds nothing (near F₋'s birth).
pub fn fold_minus_surface(
    (gamma_lo, gamma_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> Result<Option<KinkSurface>, SweepError> {
    let free = fold_minus_free_below(e_hi.min(1.0));
    if gamma_hi < free {
        return Ok(None);
    }
    let gamma_0 = gamma_lo.max(free) - STEP;
    let n_gamma = ((gamma_hi - gamma_0) / STEP - 1e-9).ceil().max(0.0) as usize + 2;
    let min_row = ((1.0 - oblique_solver::law::MIN_RESTITUTION) * ROWS_PER_UNIT_E).round() as usize;
    let n_e =
        (((1.0 - e_lo) * ROWS_PER_UNIT_E - 1e-9).ceil().max(0.0) as usize + 2).min(min_row + 1);
    // No column below the elastic birth has F₋ at any e_n.
    let born = fold_minus_free_below(1.0);
    let columns = (0..n_gamma)
        .into_par_iter()
        .map(|i| {
            let g = gamma_0 + i as f64 * STEP;
            if g < born {
                Ok(vec![f64::NAN; n_e])
            } else {
                fold_minus_column(g, n_e)
            }
        })
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    Ok(Some(KinkSurface {
        name: "F-",
        patch: PatchKind::PartialSlip,
        scale: CurveScale::Ln,
        gamma_0,
        step: STEP,
        rows_per_unit: ROWS_PER_UNIT_E,
        n_gamma,
        n_e,
        offsets: &PROBE_OFFSETS,
        extrapolate: false,
        knotted: true,
        values: columns.concat(),
    }))
}

/// `n` points next to the fold surface F₋ (`surface`, from [`fold_minus_surface`]): `(γ, e_n)`
/// uniform over the part of `[gamma_min, gamma_max] × e_range` where the surface is defined
/// (drawn over the box of its traced nodes, drawn again where it is undefined), and
/// `α = α_F(γ, e_n)(1 + s·r)` as [`near_fold_minus_points`] places them. Fewer than `n` (none)
/// when `1000 n` draws do not find them. The same `seed` gives the same points (`sweep verify
/// --near-fold` on a table with an `e_n` axis).
pub fn near_fold_minus_points_e(
    surface: &KinkSurface,
    gammas: (f64, f64),
    e_range: (f64, f64),
    n: usize,
    seed: u64,
) -> Vec<Point> {
    near_surface_points(
        surface,
        |g, e| surface.alpha_at(g, e),
        (gammas, e_range),
        (n, seed),
        (-4.0, -2.0),
    )
}

/// `n` points next to the end-of-contact surface E₋ (`surface`, from [`end_minus_surface`]):
/// `(γ, e_n)` drawn as [`near_fold_minus_points_e`] draws them, `α = α_E(γ, e_n)(1 + s·r)` with
/// `r = 10^u`, `u` uniform in `[−4, −1]` (as [`near_end_minus_points`]), `α_E` from the side
/// of α_c2 it lies on ([`EndMinusSides`]). The same `seed` gives the same points (`sweep
/// verify --near-end` on a table with an `e_n` axis).
pub fn near_end_minus_points_e(
    surface: &KinkSurface,
    gammas: (f64, f64),
    e_range: (f64, f64),
    n: usize,
    seed: u64,
) -> Vec<Point> {
    let sides = EndMinusSides::new(surface);
    near_surface_points(
        surface,
        |g, e| sides.alpha_at(g, e),
        (gammas, e_range),
        (n, seed),
        (-4.0, -1.0),
    )
}

/// `n` points next to a kink surface whose `α_K` is `alpha`: `(γ, e_n)` uniform over the part
/// of `gammas × e_range` within the box of `surface`'s traced nodes (drawn again where `alpha`
/// is undefined), `α = α_K(1 + s·10^u)`, `s = ±1`, `u` uniform in `u_range`. Fewer than `n`
/// (none) when `1000 n` draws do not find them.
fn near_surface_points(
    surface: &KinkSurface,
    alpha: impl Fn(f64, f64) -> Option<f64>,
    ((gamma_min, gamma_max), (e_min, e_max)): TracedOver,
    (n, seed): (usize, u64),
    (u_lo, u_hi): (f64, f64),
) -> Vec<Point> {
    let (Some((g_lo, g_hi)), Some((e_lo, e_hi))) = (surface.gamma_range(), surface.e_n_range())
    else {
        return Vec::new();
    };
    let (g_lo, g_hi) = (gamma_min.max(g_lo), gamma_max.min(g_hi));
    let (e_lo, e_hi) = (e_min.max(e_lo), e_max.min(e_hi));
    if !(g_lo <= g_hi && e_lo <= e_hi) {
        return Vec::new();
    }
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    for _ in 0..n.saturating_mul(1000) {
        if out.len() == n {
            break;
        }
        let gamma = (g_lo + (g_hi - g_lo) * rng.uniform()).min(g_hi);
        let e_n = (e_lo + (e_hi - e_lo) * rng.uniform()).min(e_hi);
        let r = 10f64.powf(u_lo + (u_hi - u_lo) * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        if let Some(alpha_k) = alpha(gamma, e_n) {
            out.push(Point::new(gamma, alpha_k * (1.0 + sign * r), e_n));
        }
    }
    out
}

/// The kinks of Thornton's law that [`near_thornton_fold_points`] draws next to, in turn: four
/// folds along α, the switch sheet `e_S` across `e_n`, the fold F₋, the end-of-contact curves
/// E₋ and the two edges of the strip of a `+μF_N` episode of the restitution (F+lo, F+hi)
/// along α.
pub const THORNTON_FOLDS: [&str; 9] = [
    "alpha_R", "2/7", "alpha_S", "alpha_L", "e_S", "F-", "E-", "F+lo", "F+hi",
];

/// Steps per contact time on which [`near_thornton_fold_points`] places the edges of the
/// strip, bracketed on [`THORNTON_FOLD_STEPS`] (its lower edge moves by 1e-4 relative between
/// 4 096 and 8 192 steps, by 1e-7 from there).
const PLUS_STRIP_STEPS: usize = 8192;

/// How far up in α (multiples of `α_c2`) and on how fine a grid (log intervals)
/// [`near_thornton_fold_points`] looks for the end-of-contact curves E₋: from `0.8 · 2/7`
/// (below the lowest, about 0.42 at γ 1.75, `e_n` 0.3) to 100 `α_c2` (17 `α_c2` at γ 1.75,
/// `e_n` 0.3; E₋ rises without bound as γ falls to 1.732 at `e_n` = 1).
const END_MINUS_SCAN: (f64, usize) = (100.0, 250);

/// Steps per contact time on which [`near_thornton_fold_points`] locates the folds (as the
/// knots do, `nodes.knots`).
const THORNTON_FOLD_STEPS: usize = 2048;

/// The scan along `e_n` with which [`near_thornton_fold_points`] brackets the edges of the
/// switch sheet (`switch_sheet_edges_thornton`): the narrowest gap between two bands of the zone
/// found over γ 1.05–2.6, 1.2–10 `α_c2` is 0.06 (`thornfold -- --band`).
const SHEET_SCAN: f64 = 0.01;

/// `n` points next to the kinks of Thornton's law inside `gammas × e_range`, each with the index
/// of its kink in [`THORNTON_FOLDS`], point `i` next to kink `i mod 9` (`docs/solver.md`, "Kinks
/// inside the slip regions"):
/// - the re-slip fold `α_R`, the line `α = 2/7`, the switch fold `α_S` and the loading fold
///   `α_L`: `(γ, e_n)` uniform (`e_n` at most `1 − 1e-4`, where the folds still exist), the fold
///   located there on 2 048 steps, `α = α_K (1 + s·10^u)`, `s = ±1`, `u` uniform in `[−4, −2]`;
/// - the switch sheet `e_S(γ, α)` of the stick patch: γ uniform, `α/α_c2` log-uniform in
///   `[1.2, 10]`, the edges of the sheet located inside the table's `e_n` range (an upper or a
///   lower edge of a band of `e_n` where the zone exists, scanned in steps of [`SHEET_SCAN`]),
///   `e_n = e_S + s·10^u` next to the edge nearest the `e_n` drawn;
/// - the fold F₋, the end-of-contact curves E₋ and the edges of the strip of a `+μF_N`
///   episode of the restitution as the folds along α (E₋: one of the curves found up to 100
///   `α_c2`, each as likely; the strip's edges bracketed on 2 048 steps, placed on 8 192).
///
/// A draw whose kink does not exist there (`α_R` next to γ = 1, `α_L` where it has merged, the
/// sheet above `e_n` ≈ 0.52 at γ 1.7, F₋ below γ ≈ 1.9), whose `α` lies beyond `alpha_max` or whose `e_n` leaves the range
/// is drawn again, up to 20 rounds, and a kink none of whose draws of a round exists is not
/// drawn again (fewer points then). The draws are made in order from `seed` and located in
/// parallel: the same `seed` gives the same points (`sweep verify --near-folds`). `Err`: a
/// solve's error.
pub fn near_thornton_fold_points(
    gammas: (f64, f64),
    e_range: (f64, f64),
    alpha_max: f64,
    n: usize,
    seed: u64,
) -> Result<Vec<(usize, Point)>, oblique_solver::PhysicsError> {
    let kinds = THORNTON_FOLDS.len();
    let (e_lo, e_hi) = (e_range.0, e_range.1.min(1.0 - 1e-4));
    // The pick: the sheet's α (e_S) or which E₋ (E-).
    let draw = |rng: &mut _| draw_with_pick(rng, gammas, (e_lo, e_hi));
    draw_rounds(n, kinds, seed, draw, |i, &(gamma, e_n, r, pick)| {
        let c2 = oblique_physics::regimes::alpha_c2(gamma);
        let point = if i % kinds == 4 {
            let alpha = 1.2 * (10.0f64 / 1.2).powf(pick) * c2;
            // The edge of the sheet nearest the drawn e_n (upper or lower edge of a
            // band of the zone).
            let edges = switch_sheet_edges_thornton(
                gamma,
                alpha,
                (e_lo, e_hi),
                SHEET_SCAN,
                THORNTON_FOLD_STEPS,
            )?;
            next_to_nearest(edges.iter().map(|&(e_s, _)| e_s), e_n, r, (e_lo, e_hi))
                .filter(|_| alpha <= alpha_max)
                .map(|e| Point::new(gamma, alpha, e))
        } else {
            let fold = match i % kinds {
                0 => reslip_fold_thornton(gamma, e_n, THORNTON_FOLD_STEPS),
                1 => Ok(Some(2.0 / 7.0)),
                2 => switch_fold_thornton(gamma, e_n, THORNTON_FOLD_STEPS),
                3 => loading_fold_thornton(gamma, e_n, THORNTON_FOLD_STEPS),
                // None below its birth (the search would scan up to α_c2 for it).
                5 if gamma < fold_minus_free_below_thornton(e_n) => Ok(None),
                5 => fold_minus_thornton(gamma, e_n, THORNTON_FOLD_STEPS),
                7 | 8 => match restitution_plus_strip_thornton(gamma, e_n, THORNTON_FOLD_STEPS)? {
                    Some((lo, hi)) => {
                        let edge = if i % kinds == 7 { lo } else { hi };
                        restitution_plus_change_thornton(
                            gamma,
                            e_n,
                            (edge * (1.0 - 2e-3), edge * (1.0 + 2e-3)),
                            PLUS_STRIP_STEPS,
                        )
                    }
                    None => Ok(None),
                },
                _ => {
                    let (up, n) = END_MINUS_SCAN;
                    let lo = 0.8 * 2.0 / 7.0;
                    let hi = (up * c2).min(alpha_max).max(2.0 * lo);
                    let edges =
                        end_minus_edges_thornton(gamma, e_n, (lo, hi), n, THORNTON_FOLD_STEPS)?;
                    let k =
                        ((pick * edges.len() as f64) as usize).min(edges.len().saturating_sub(1));
                    Ok(edges.get(k).copied())
                }
            }?;
            fold.map(|a| a * (1.0 + r))
                .filter(|&a| a <= alpha_max)
                .map(|a| Point::new(gamma, a, e_n))
        };
        Ok(point)
    })
}

/// One draw of the points next to Thornton's kinks: γ uniform over `gammas`, `e_n` uniform
/// over `e_range`, and the signed relative offset `s·10^u`, `s = ±1`, `u` uniform in
/// `[−4, −2]`, in that order from `rng`.
fn draw_next_to(
    rng: &mut oblique_physics::sample::SplitMix,
    (g_lo, g_hi): (f64, f64),
    (e_lo, e_hi): (f64, f64),
) -> (f64, f64, f64) {
    let gamma = (g_lo + (g_hi - g_lo) * rng.uniform()).min(g_hi);
    let e_n = (e_lo + (e_hi - e_lo) * rng.uniform()).min(e_hi);
    let r = 10f64.powf(-4.0 + 2.0 * rng.uniform());
    let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
    (gamma, e_n, sign * r)
}

/// [`draw_next_to`], then one more uniform number from `rng` (a pick among the kink's places:
/// the α of a sheet, which E₋).
fn draw_with_pick(
    rng: &mut oblique_physics::sample::SplitMix,
    gammas: (f64, f64),
    e_range: (f64, f64),
) -> (f64, f64, f64, f64) {
    let (gamma, e_n, r) = draw_next_to(rng, gammas, e_range);
    (gamma, e_n, r, rng.uniform())
}

/// `n` points drawn in rounds, point `i` next to kind `i mod kinds`: each round draws the open
/// slots in order from `seed` (`draw`) and locates them in parallel (`locate`, `None` where
/// the kind does not exist there), up to 20 rounds; a kind none of whose draws of a round
/// exists is not drawn again. Each point with its kind.
fn draw_rounds<D: Sync>(
    n: usize,
    kinds: usize,
    seed: u64,
    mut draw: impl FnMut(&mut oblique_physics::sample::SplitMix) -> D,
    locate: impl Fn(usize, &D) -> Result<Option<Point>, oblique_solver::PhysicsError> + Sync,
) -> Result<Vec<(usize, Point)>, oblique_solver::PhysicsError> {
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut slots: Vec<Option<Point>> = vec![None; n];
    let mut gone = vec![false; kinds];
    for _ in 0..20 {
        let open: Vec<usize> = (0..n)
            .filter(|&i| slots[i].is_none() && !gone[i % kinds])
            .collect();
        if open.is_empty() {
            break;
        }
        let draws: Vec<(usize, D)> = open.iter().map(|&i| (i, draw(&mut rng))).collect();
        let found: Vec<(usize, Option<Point>)> = draws
            .par_iter()
            .map(|(i, d)| Ok((*i, locate(*i, d)?)))
            .collect::<Result<_, oblique_solver::PhysicsError>>()?;
        let mut any = vec![false; kinds];
        for (i, point) in found {
            any[i % kinds] |= point.is_some();
            slots[i] = point;
        }
        for (k, g) in gone.iter_mut().enumerate() {
            *g |= !any[k] && open.iter().any(|&i| i % kinds == k);
        }
    }
    Ok(slots
        .into_iter()
        .enumerate()
        .filter_map(|(i, p)| p.map(|p| (i % kinds, p)))
        .collect())
}

/// The edges of Thornton's loading band that [`near_loading_band_points`] draws next to, in
/// turn.
pub const LOADING_BAND_EDGES: [&str; 2] = ["L-lo", "L-hi"];

/// `n` points next to the edges of Thornton's loading band inside `gammas × e_range` (the α
/// where a zone at the `+μq` limit opens and closes while the contact loads, `loading_band_thornton`),
/// each with the index of its edge in [`LOADING_BAND_EDGES`], point `i` next to edge `i mod 2`:
/// `(γ, e_n)` uniform (`e_n` at most `1 − 1e-4`), the band located there on 2 048 steps (a
/// full search, 0.1–0.4 s), `α = α_edge (1 + s·10^u)`, `s = ±1`, `u` uniform in `[−4, −2]`. A
/// draw where no band is found (next to `e_n` = 1 it is narrower than the search's scan) or
/// whose `α` lies beyond `alpha_max` is drawn again, up to 20 rounds (an edge found nowhere in
/// a round is not drawn again). The same `seed` gives the same points (`sweep verify
/// --near-band`). `Err`: a solve's error.
pub fn near_loading_band_points(
    gammas: (f64, f64),
    e_range: (f64, f64),
    alpha_max: f64,
    n: usize,
    seed: u64,
) -> Result<Vec<(usize, Point)>, oblique_solver::PhysicsError> {
    let e_range = (e_range.0, e_range.1.min(1.0 - 1e-4));
    let draw = |rng: &mut oblique_physics::sample::SplitMix| draw_next_to(rng, gammas, e_range);
    draw_rounds(n, 2, seed, draw, |i, &(gamma, e_n, r)| {
        let band = loading_band_thornton(gamma, e_n, THORNTON_FOLD_STEPS)?;
        Ok(band
            .map(|(lo, hi)| if i % 2 == 0 { lo } else { hi } * (1.0 + r))
            .filter(|&a| a <= alpha_max)
            .map(|a| Point::new(gamma, a, e_n)))
    })
}

/// The kink [`near_end_sheet_points`] draws next to.
pub const END_SHEET_EDGES: [&str; 1] = ["e_E"];

/// The range of `α/α_c2` (log-uniform) of [`near_end_sheet_points`]: the sheet is nearly flat
/// in α far from `α_c2`; it falls below `e_n` 0.3 under about 2 `α_c2` at γ 1.66 and reaches
/// `α_c2` from γ ≈ 1.86, below which it goes on into the partial-slip patch (γ 2.2: 0.377 at
/// 0.6 `α_c2`, 0.470 at 0.95).
const END_SHEET_RATIOS: (f64, f64) = (0.5, 30.0);

/// `n` points next to the end-of-contact sheet `e_E(γ, α)` of Thornton's stick patch inside
/// `gammas × e_range` (where the contact stops ending in a `−μF_N` episode as `e_n` grows,
/// the upper edges of `end_minus_sheet_edges_thornton`; its lower edges are E₋, which
/// `--near-folds` draws next to), each with the index 0 of [`END_SHEET_EDGES`]: γ
/// uniform, `e_n` uniform (at most `1 − 1e-4`), the signed offset `s·10^u` (`s = ±1`, `u`
/// uniform in `[−4, −2]`) and `α/α_c2` log-uniform in [`END_SHEET_RATIOS`], in that order; the
/// edges of the sheet at `(γ, α)` located inside the range (scanned in steps of
/// [`SHEET_SCAN`] on 2 048 steps, 0.1–0.5 s), `e_n = e_E + s·10^u` next to the edge nearest
/// the `e_n` drawn. A draw where no such edge lies in the range, or whose `α` or `e_n` leaves the
/// table, is drawn again, up to 20 rounds. The same `seed` gives the same points (`sweep
/// verify --near-end-sheet`). `Err`: a solve's error.
pub fn near_end_sheet_points(
    gammas: (f64, f64),
    e_range: (f64, f64),
    alpha_max: f64,
    n: usize,
    seed: u64,
) -> Result<Vec<(usize, Point)>, oblique_solver::PhysicsError> {
    let (e_lo, e_hi) = (e_range.0, e_range.1.min(1.0 - 1e-4));
    // The pick: α/α_c2.
    let draw = |rng: &mut _| draw_with_pick(rng, gammas, (e_lo, e_hi));
    let (r_lo, r_hi) = END_SHEET_RATIOS;
    draw_rounds(n, 1, seed, draw, |_, &(gamma, e_n, r, pick)| {
        let alpha = r_lo * (r_hi / r_lo).powf(pick) * oblique_physics::regimes::alpha_c2(gamma);
        if alpha > alpha_max {
            return Ok(None);
        }
        let edges = end_minus_sheet_edges_thornton(
            gamma,
            alpha,
            (e_lo, e_hi),
            SHEET_SCAN,
            THORNTON_FOLD_STEPS,
        )?;
        let upper = edges.iter().filter(|&&(_, above)| !above).map(|&(e, _)| e);
        Ok(next_to_nearest(upper, e_n, r, (e_lo, e_hi)).map(|e| Point::new(gamma, alpha, e)))
    })
}

/// `e + r` for the edge `e` among `edges` nearest `e_n`, where that lies in `[e_lo, e_hi]`
/// (the samplers next to the sheets across `e_n`).
fn next_to_nearest(
    edges: impl Iterator<Item = f64>,
    e_n: f64,
    r: f64,
    (e_lo, e_hi): (f64, f64),
) -> Option<f64> {
    edges
        .min_by(|a, b| (a - e_n).abs().total_cmp(&(b - e_n).abs()))
        .map(|e| e + r)
        .filter(|&e| e >= e_lo && e <= e_hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_solver::history::switch_sheet_thornton;

    /// The kinks [`trace`] traces for `law` in the patch `kind` over `gammas` (and `e_range`),
    /// traced afresh.
    fn traced(
        law: Law,
        kind: PatchKind,
        gammas: (f64, f64),
        e_range: Option<(f64, f64)>,
    ) -> Vec<Box<dyn Kink>> {
        trace(law, kind, gammas, e_range, &mut Traced::default(), &|_| {}).expect("traced")
    }

    /// Over a range that holds seven of the kinks, each gets its share of the points, next to it:
    /// the folds within 1e-2 (relative) in α, the switch sheet within 1e-2 in `e_n`; the same
    /// seed draws the same points.
    #[test]
    fn thornton_fold_points_lie_next_to_each_kink() {
        let (gammas, e_range) = ((1.95, 2.05), (0.45, 0.65));
        let pts =
            near_thornton_fold_points(gammas, e_range, f64::INFINITY, 14, 3).expect("located");
        // The strip of the restitution's `+` episode lies below e_n 0.4 at γ 2: its two kinds
        // (points 7 and 8) are left out.
        let kinds: Vec<usize> = pts.iter().map(|p| p.0).collect();
        assert_eq!(kinds, [0, 1, 2, 3, 4, 5, 6, 0, 1, 2, 3, 4]);
        for &(k, p) in &pts {
            let steps = THORNTON_FOLD_STEPS;
            let near = |a: f64| {
                let r = (p.alpha / a - 1.0).abs();
                (1e-4 * 0.999..=1e-2 * 1.001).contains(&r)
            };
            let fold = match k {
                0 => reslip_fold_thornton(p.gamma, p.e_n, steps).unwrap(),
                1 => Some(2.0 / 7.0),
                2 => switch_fold_thornton(p.gamma, p.e_n, steps).unwrap(),
                3 => loading_fold_thornton(p.gamma, p.e_n, steps).unwrap(),
                5 => fold_minus_thornton(p.gamma, p.e_n, steps).unwrap(),
                _ => None,
            };
            match (k, fold) {
                (_, Some(a)) => assert!(near(a), "{k}: {p:?} {a}"),
                (4, None) => {
                    assert!(p.alpha > 1.2 * oblique_physics::regimes::alpha_c2(p.gamma));
                    let edges =
                        switch_sheet_edges_thornton(p.gamma, p.alpha, e_range, SHEET_SCAN, steps)
                            .unwrap();
                    let near_edge = |&(e_s, _): &(f64, bool)| {
                        (1e-4 * 0.999..=1e-2 * 1.001).contains(&(p.e_n - e_s).abs())
                    };
                    assert!(edges.iter().any(near_edge), "{p:?} {edges:?}");
                }
                (6, None) => {
                    let edges =
                        end_minus_edges_thornton(p.gamma, p.e_n, (0.2, 100.0), 300, steps).unwrap();
                    assert!(edges.iter().any(|&a| near(a)), "{p:?} {edges:?}");
                }
                _ => panic!("{k}: {p:?} has no kink"),
            }
        }
        let again =
            near_thornton_fold_points(gammas, e_range, f64::INFINITY, 14, 3).expect("located");
        assert_eq!(format!("{pts:?}"), format!("{again:?}"));
    }

    /// Where the switch sheet's zone exists in a band of `e_n` whose lower edge alone lies in
    /// the range (γ 2.28–2.32, `e_n` 0.32–0.45: from 0.35 at 2 `α_c2` to 0.40 at 10), the points
    /// of the sheet lie next to that lower edge, the zone present above it.
    #[test]
    fn thornton_fold_points_lie_next_to_the_lower_edge_of_the_sheet() {
        let e_range = (0.32, 0.45);
        let pts = near_thornton_fold_points((2.28, 2.32), e_range, f64::INFINITY, 14, 9)
            .expect("located");
        let sheet: Vec<Point> = pts.iter().filter(|p| p.0 == 4).map(|p| p.1).collect();
        assert_eq!(sheet.len(), 2, "{pts:?}");
        for p in sheet {
            let edges = switch_sheet_edges_thornton(
                p.gamma,
                p.alpha,
                e_range,
                SHEET_SCAN,
                THORNTON_FOLD_STEPS,
            )
            .unwrap();
            assert!(
                edges.iter().all(|&(_, above)| above),
                "{p:?}: only lower edges here, {edges:?}"
            );
            assert!(
                edges
                    .iter()
                    .any(|&(e, _)| (1e-4 * 0.999..=1e-2 * 1.001).contains(&(p.e_n - e).abs())),
                "{p:?} {edges:?}"
            );
        }
    }

    /// Where the strip of a `+μF_N` episode of the restitution lies (γ 2.25–2.35, e_n 0.3–0.4:
    /// 0.38–0.57 `α_c2`), points are drawn next to both its edges, placed on 8 192 steps.
    #[test]
    fn thornton_fold_points_lie_next_to_the_strip_edges() {
        let pts = near_thornton_fold_points((2.25, 2.35), (0.3, 0.4), f64::INFINITY, 18, 5)
            .expect("located");
        let strip: Vec<&(usize, Point)> = pts.iter().filter(|p| p.0 >= 7).collect();
        assert_eq!(strip.len(), 4, "{pts:?}");
        for &&(k, p) in &strip {
            let (lo, hi) = restitution_plus_strip_thornton(p.gamma, p.e_n, PLUS_STRIP_STEPS)
                .unwrap()
                .expect("the strip");
            let edge = if k == 7 { lo } else { hi };
            let r = (p.alpha / edge - 1.0).abs();
            assert!(
                (1e-4 * 0.99..=1e-2 * 1.001).contains(&r),
                "{k}: {p:?} {edge}"
            );
        }
    }

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

    #[test]
    fn the_fold_minus_surface_matches_direct_tracing_between_its_nodes() {
        // γ 2.44–2.56, e_n 0.95–1: F₋ ends at e_n ≈ 0.977 at γ = 2.45, 0.957 at 2.55
        // (`fmedge`), so the grid's edge crosses the range.
        let s = fold_minus_surface((2.44, 2.56), (0.95, 1.0))
            .unwrap()
            .expect("a surface");
        let (g_lo, g_hi) = s.gamma_range().unwrap();
        assert!(g_lo <= 2.44 && g_hi >= 2.56, "{g_lo} {g_hi}");
        let (e_lo, e_hi) = s.e_n_range().unwrap();
        assert_eq!(e_hi, 1.0);
        assert!((0.95..0.965).contains(&e_lo), "{e_lo}");
        // Between the nodes (γ off the 0.01 grid, e_n off the 0.005 rows), against F₋ located
        // directly from the interpolated value (measured: within 1.6e-6; the located α_F
        // itself moves by about 1e-6 with the step times at 2048 steps); at e_n = 1 the
        // elastic curve's.
        let curve = fold_minus_curve(2.4, 2.6).unwrap().unwrap();
        for (g, e_n, tol) in [
            (2.4537, 1.0, 5e-6),
            (2.5311, 1.0, 5e-6),
            (2.4537, 0.9921, 5e-6),
            (2.5013, 0.9837, 5e-6),
            (2.5488, 0.9712, 5e-6),
            // Near the end of F₋ (≈ 0.963 at γ = 2.5), fewer rows across e_n.
            (2.5052, 0.9723, 2e-5),
        ] {
            let a = s.alpha_at(g, e_n).unwrap_or_else(|| panic!("{g} {e_n}"));
            let direct = fold_minus_at_e(g, e_n, a, TRACE_STEPS)
                .unwrap()
                .expect("F- there");
            assert!((a / direct - 1.0).abs() < tol, "{g} {e_n}: {a} vs {direct}");
            if e_n == 1.0 {
                let c = curve.alpha_at(g).unwrap();
                assert!((a / c - 1.0).abs() < 1e-5, "{g}: {a} vs {c}");
            }
        }
        // Undefined where F₋ does not exist (γ = 2.45 below e_n ≈ 0.977; γ < 2.37), and
        // outside the grid.
        assert_eq!(s.alpha_at(2.45, 0.96), None);
        assert!(fold_minus_at_e(2.45, 0.96, 0.48, TRACE_STEPS)
            .unwrap()
            .is_none());
        assert_eq!(s.alpha_at(2.36, 1.0), None);
        assert_eq!(s.alpha_at(2.7, 1.0), None);
        assert_eq!(s.alpha_at(2.5, 1.01), None);
        // No surface where the range holds no F₋ (e_n ≤ 0.8 below γ = 3.6).
        assert!(fold_minus_surface((2.0, 2.36), (0.5, 1.0))
            .unwrap()
            .is_none());
        assert!(fold_minus_surface((2.4, 3.0), (0.3, 0.8))
            .unwrap()
            .is_none());
        // Points next to it: within 1e-4 to 1e-2 (relative) of the surface, on both sides,
        // (γ, e_n) in the range asked for; the same seed, the same points.
        let pts = near_fold_minus_points_e(&s, (2.45, 2.55), (0.96, 1.0), 200, 7);
        assert_eq!(pts.len(), 200);
        assert_eq!(
            pts,
            near_fold_minus_points_e(&s, (2.45, 2.55), (0.96, 1.0), 200, 7)
        );
        let d: Vec<f64> = pts
            .iter()
            .map(|p| p.alpha / s.alpha_at(p.gamma, p.e_n).unwrap() - 1.0)
            .collect();
        assert!(pts
            .iter()
            .all(|p| (2.45..=2.55).contains(&p.gamma) && (0.96..=1.0).contains(&p.e_n)));
        assert!(d
            .iter()
            .all(|d| (1e-4 - 1e-15..=1e-2 + 1e-15).contains(&d.abs())));
        assert!(d.iter().any(|&d| d < 0.0) && d.iter().any(|&d| d > 0.0));
        // Over the range where F₋ lives: both ends of e_n are drawn.
        assert!(pts.iter().any(|p| p.e_n < 0.97) && pts.iter().any(|p| p.e_n > 0.99));
        assert!(near_fold_minus_points_e(&s, (2.45, 2.55), (0.9, 0.94), 10, 7).is_empty());
    }

    #[test]
    fn the_traced_end_of_contact_curve_matches_direct_location() {
        // Over both patches: it starts at the first grid point that holds it (γ = 1.74) and
        // ends at F₋'s first traced point.
        let curve = end_minus_curve(PatchKind::Stick, 1.5, 2.6)
            .unwrap()
            .expect("a curve");
        let (lo, hi) = curve.gamma_range();
        assert!(
            (lo - 1.74).abs() < 1e-12 && (hi - END_MINUS_TO).abs() < 1e-12,
            "{lo} {hi}"
        );
        assert_eq!((curve.name(), curve.patch()), ("E-", PatchKind::Stick));
        // Between grid points (the 4-point rule in 1/α), against E₋ located there; near its
        // start α grows like 1/(γ − 1.732).
        for (g, guess, tol) in [
            (1.7437, 15.0, 1e-3),
            (1.7813, 3.5, 2e-5),
            (1.8711, 1.3, 1e-6),
            (2.2796, 0.59, 1e-6),
        ] {
            let direct = oblique_solver::history::end_minus_at(g, guess, TRACE_STEPS)
                .unwrap()
                .expect("E- there");
            let a = curve.alpha_at(g).unwrap();
            assert!((a / direct - 1.0).abs() < tol, "{g}: {a} vs {direct}");
        }
        assert_eq!(curve.alpha_at(1.735), None);
        assert_eq!(curve.alpha_at(2.41), None);
        // Only where the range reaches it.
        assert!(end_minus_curve(PatchKind::Stick, 0.5, 1.6)
            .unwrap()
            .is_none());
        assert!(end_minus_curve(PatchKind::PartialSlip, 2.6, 3.5)
            .unwrap()
            .is_none());
    }

    /// Thornton's switch sheet for the probes: `e_S(γ, α)` across the `e_n` axis of the stick
    /// patch, matching the sheet located between its nodes, α = ∞ included (nearly flat
    /// there), nothing below `α_c2`, and nothing for a range the sheet does not reach.
    #[test]
    fn thornton_switch_sheet_is_traced_across_e_n() {
        let [s, _] = switch_sheet_surfaces((1.68, 1.72), (0.45, 0.55)).unwrap();
        let s = s.expect("a sheet");
        assert_eq!(
            (s.name(), s.patch(), s.across_e_n(), s.alpha(1.7, 0.5)),
            ("e_S", PatchKind::Stick, true, None)
        );
        let c2 = |g: f64| oblique_physics::regimes::alpha_c2(g);
        for (g, r) in [(1.71, 2.2), (1.6933, 1.37), (1.7, 7.5)] {
            let direct = switch_sheet_thornton(g, r * c2(g), (0.35, 0.6), SWITCH_SHEET_STEPS)
                .unwrap()
                .expect("e_S there");
            let e = s.e_n_at(g, r * c2(g)).expect("traced there");
            assert!((e - direct).abs() < 1e-4, "{g} {r}: {e} vs {direct}");
        }
        let at_infinity = s.e_at(1.7, f64::INFINITY).expect("alpha = inf");
        assert!((0.45..0.55).contains(&at_infinity), "{at_infinity}");
        assert_eq!(s.e_at(1.7, 0.5 * c2(1.7)), None);
        let [upper, _] = switch_sheet_surfaces((1.68, 1.72), (0.8, 0.9)).unwrap();
        assert!(upper.is_none());
    }

    /// Thornton's end-of-contact sheet for the probes: `e_E(γ, α)` across the `e_n` axis of the
    /// stick patch, probed on the side above it, matching the edge located between its nodes
    /// within 5e-4 (the 4-point rule across the fold of the sheet where the loading fold `α_L`
    /// crosses it, γ 1.66: about 4.65 `α_c2`, flat above and falling below, errs by 2.7e-4 at
    /// 6 `α_c2` and 1.5e-3 at 4.5);
    /// `trace` hands it to the stick patch.
    #[test]
    fn thornton_end_of_contact_sheet_is_traced_across_e_n() {
        let (gammas, e_range) = ((1.65, 1.67), (0.31, 0.34));
        let s = end_minus_sheet_surface(PatchKind::Stick, gammas, e_range)
            .unwrap()
            .expect("a sheet");
        assert_eq!(
            (s.name(), s.patch(), s.across_e_n(), s.offsets()),
            ("e_E", PatchKind::Stick, true, &END_SHEET_PROBE_OFFSETS[..])
        );
        let c2 = |g: f64| oblique_physics::regimes::alpha_c2(g);
        for (g, r) in [(1.655, 3.0), (1.66, 6.0), (1.665, 12.0)] {
            let edges =
                end_minus_sheet_edges_thornton(g, r * c2(g), (0.3, 0.36), 0.01, SWITCH_SHEET_STEPS)
                    .unwrap();
            assert_eq!(edges.len(), 1, "{edges:?}");
            let e = s.e_n_at(g, r * c2(g)).expect("traced there");
            assert!((e - edges[0].0).abs() < 5e-4, "{g} {r}: {e} vs {edges:?}");
        }
        let stick = traced(Law::Thornton, PatchKind::Stick, gammas, Some(e_range));
        assert!(stick.iter().any(|k| k.name() == "e_E"));
    }

    /// From γ ≈ 1.86 the end-of-contact sheet goes on into the partial-slip patch: traced there
    /// over `α/α_c2` from 0.4 up, matching the edge located directly; not traced for a range
    /// below γ 1.84.
    #[test]
    fn thornton_end_of_contact_sheet_is_traced_in_the_partial_slip_patch() {
        let s = end_minus_sheet_surface(PatchKind::PartialSlip, (2.2, 2.2), (0.35, 0.5))
            .unwrap()
            .expect("a sheet");
        assert_eq!((s.name(), s.patch()), ("e_E", PatchKind::PartialSlip));
        let c2 = oblique_physics::regimes::alpha_c2(2.2);
        for r in [0.6, 0.8, 0.95] {
            let edges =
                end_minus_sheet_edges_thornton(2.2, r * c2, (0.33, 0.52), 0.01, SWITCH_SHEET_STEPS)
                    .unwrap();
            let direct = edges.iter().find(|e| !e.1).expect("an upper edge").0;
            let e = s.e_n_at(2.2, r * c2).expect("traced there");
            assert!((e - direct).abs() < 5e-4, "{r}: {e} vs {edges:?}");
        }
        assert_eq!(s.e_at(2.2, 1.5 * c2), None);
        assert_eq!(s.e_at(2.2, 0.3 * c2), None);
        assert!(
            end_minus_sheet_surface(PatchKind::PartialSlip, (1.6, 1.8), (0.3, 0.4))
                .unwrap()
                .is_none()
        );
    }

    /// Where the switch sheet's zone exists in a band of `e_n` (γ 2.26–2.34, `e_n` 0.31–0.41),
    /// its lower edge is traced as a second sheet, probed on the side above it, and matches the
    /// edge located directly within 5e-4 (2.7e-4 at γ 2.31, 9 `α_c2`).
    #[test]
    fn thornton_switch_sheet_lower_edge_is_traced_as_a_second_sheet() {
        // Five columns of γ (2.26–2.34), `e_n` scanned over 0.3–0.43.
        let [upper, lower] = switch_sheet_surfaces((2.3, 2.3), (0.31, 0.41)).unwrap();
        // The upper edges near the range are those of the lower band (far from α_c2, below
        // the range, within the reach of the tracing), the top band's beyond it.
        let upper = upper.expect("the lower band's upper edge");
        assert!(
            upper.points().iter().all(|&(_, r, e)| e < 0.32 && r > 2.0),
            "{upper:?}"
        );
        let lower = lower.expect("a lower edge");
        assert_eq!(
            (lower.name(), lower.offsets(), lower.across_e_n()),
            ("e_S lower", &SWITCH_LOWER_PROBE_OFFSETS[..], true)
        );
        let c2 = |g: f64| oblique_physics::regimes::alpha_c2(g);
        for (g, r) in [(2.29, 2.0), (2.3, 5.0), (2.31, 9.0)] {
            let edges =
                switch_sheet_edges_thornton(g, r * c2(g), (0.33, 0.42), 0.01, SWITCH_SHEET_STEPS)
                    .unwrap();
            let direct = edges
                .iter()
                .rev()
                .find(|e| e.1)
                .expect("a lower edge there")
                .0;
            let e = lower.e_n_at(g, r * c2(g)).expect("traced there");
            assert!((e - direct).abs() < 5e-4, "{g} {r}: {e} vs {direct}");
        }
        // Where the band reaches below the range (γ 1.7: the zone from 0.3 up to about 0.52),
        // no lower edge.
        let [upper, lower] = switch_sheet_surfaces((1.7, 1.7), (0.45, 0.55)).unwrap();
        assert!(upper.is_some() && lower.is_none());
    }

    /// The edges of Thornton's `+` strip for the probes: two surfaces that match the edges
    /// located between their nodes (to 5e-4 relative up to 0.02 in `e_n` below the strip's
    /// end; closer to it, where the edges rise ever faster, up to 3.6e-3 at γ 2.31, `e_n` 0.56),
    /// split at α_c2 as the strip rises into the stick patch, and undefined beyond where it ends
    /// (γ 2.3: near `e_n` 0.575).
    #[test]
    fn thornton_plus_strip_edges_are_traced_as_surfaces() {
        let [lo, hi] = thornton_plus_strip_surfaces((2.28, 2.32), (0.52, 0.56)).unwrap();
        let (lo, hi) = (lo.expect("F+lo"), hi.expect("F+hi"));
        assert_eq!((lo.name, hi.name, lo.knotted), ("F+lo", "F+hi", false));
        for (g, e) in [(2.2913, 0.5237), (2.3071, 0.5462), (2.2856, 0.535)] {
            let (a_lo, a_hi) = restitution_plus_strip_thornton(g, e, THORNTON_TRACE_STEPS)
                .unwrap()
                .expect("the strip there");
            for (s, direct) in [(&lo, a_lo), (&hi, a_hi)] {
                let a = s.alpha_at(g, e).expect("traced there");
                assert!((a / direct - 1.0).abs() < 5e-4, "{g} {e}: {a} vs {direct}");
            }
        }
        assert!(lo.alpha_at(2.3, 0.6).is_none() && hi.alpha_at(2.3, 0.6).is_none());
        // At γ 2.3 the strip lies below α_c2 = 1.511 at e_n 0.52 and above it at 0.555.
        let c2 = oblique_physics::regimes::alpha_c2(2.3);
        let [partial, stick] =
            [PatchKind::PartialSlip, PatchKind::Stick].map(|kind| end_minus_in_patch(&lo, kind));
        assert!(partial.alpha_at(2.3, 0.52).is_some_and(|a| a < c2));
        assert!(stick.alpha_at(2.3, 0.52).is_none());
        assert!(stick.alpha_at(2.3, 0.555).is_some_and(|a| a > c2));
        assert!(partial.alpha_at(2.3, 0.555).is_none());
        // None below the lowest γ it is looked for at.
        let none = thornton_plus_strip_surfaces((1.0, PLUS_STRIP_FROM - 0.1), (0.3, 0.4)).unwrap();
        assert!(none.iter().all(Option::is_none));
    }

    /// The upper edge of Thornton's loading band for the probes: a surface that matches the edge
    /// located between its nodes (within 1e-3 of α, where it moves by 2 % a row), split between
    /// the patches where it crosses α_c2, not knotted.
    #[test]
    fn thornton_loading_band_is_traced_in_both_patches() {
        let hi = thornton_loading_band_surface((1.62, 1.66), (0.84, 0.89))
            .unwrap()
            .expect("L-hi");
        assert_eq!((hi.name, hi.knotted), ("L-hi", false));
        for (g, e) in [
            (1.6428193451026516, 0.8758696542440176),
            (1.6317, 0.8433),
            (1.655, 0.8871),
        ] {
            let (_, direct) = loading_band_thornton(g, e, 8192).unwrap().expect("a band");
            let a = hi.alpha_at(g, e).expect("traced there");
            assert!((a / direct - 1.0).abs() < 1e-3, "{g} {e}: {a} vs {direct}");
        }
        // The upper edge lies below α_c2 at e_n 0.8759 (0.9926 α_c2 at γ 1.6428, where a table
        // without these probes erred beyond its bound) and above it at 0.84.
        let g = 1.6428193451026516;
        let c2 = oblique_physics::regimes::alpha_c2(g);
        let [partial, stick] =
            [PatchKind::PartialSlip, PatchKind::Stick].map(|kind| end_minus_in_patch(&hi, kind));
        assert!(partial
            .alpha_at(g, 0.8759)
            .is_some_and(|a| a < c2 && a > 0.99 * c2));
        assert!(stick.alpha_at(g, 0.8759).is_none());
        assert!(stick.alpha_at(g, 0.84).is_some_and(|a| a > c2));
        assert!(partial.alpha_at(g, 0.84).is_none());
    }

    /// Thornton's F₋ and E₋ for the probes: surfaces in the partial-slip patch that match the
    /// kinks located between their nodes, not knotted; F₋ ends where it does along `e_n`.
    #[test]
    fn thornton_fold_minus_is_traced_as_a_surface() {
        let k = traced(
            Law::Thornton,
            PatchKind::PartialSlip,
            (2.28, 2.34),
            Some((0.55, 0.65)),
        );
        // F₋, E₋ (below it here, α_E ≈ 0.44–0.50), the edges of the `+` strip (its part
        // below α_c2: at γ 2.34 it crosses α_c2 between `e_n` 0.55 and 0.57), the upper edge
        // of the loading band and the end-of-contact sheet (`e_n` 0.53–0.60 next to α_c2).
        let names: Vec<_> = k.iter().map(|k| k.name()).collect();
        assert_eq!(names, ["F-", "E-", "F+lo", "F+hi", "L-hi", "e_E"]);
        let f = &k[0];
        assert_eq!(
            (f.name(), f.patch(), f.knotted()),
            ("F-", PatchKind::PartialSlip, false)
        );
        assert_eq!((k[1].name(), k[1].patch()), ("E-", PatchKind::PartialSlip));
        for (g, e) in [(2.2913, 0.5847), (2.3387, 0.6412)] {
            let direct = oblique_solver::history::end_minus_edges_thornton(
                g,
                e,
                (0.3, 1.0),
                60,
                THORNTON_TRACE_STEPS,
            )
            .unwrap();
            let a = k[1].alpha(g, e).expect("E- traced there");
            assert!(
                (a / direct[0] - 1.0).abs() < 1e-4,
                "{g} {e}: {a} vs {direct:?}"
            );
        }
        for (g, e) in [(2.3013, 0.6047), (2.287, 0.5561), (2.3391, 0.6472)] {
            let direct = fold_minus_thornton(g, e, THORNTON_TRACE_STEPS)
                .unwrap()
                .expect("F- there");
            let a = f.alpha(g, e).expect("traced there");
            assert!((a / direct - 1.0).abs() < 2e-6, "{g} {e}: {a} vs {direct}");
        }
        // At γ 2.3 F₋ ends between e_n 0.9 and 0.95 (at 2.33 near 0.97): undefined beyond.
        let s = thornton_fold_minus_surface((2.29, 2.31), (0.85, 1.0))
            .unwrap()
            .expect("a surface");
        let (lo, hi) = s.e_n_range().expect("rows");
        assert!(lo <= 0.85 && (0.9..0.98).contains(&hi), "{lo} {hi}");
        assert!(s.alpha_at(2.3, 0.9).is_some());
        assert!(s.alpha_at(2.3, 0.95).is_none());
    }

    #[test]
    fn kinks_are_traced_for_the_laws_that_have_them() {
        assert!(probes_implemented(Law::Elastic) && probes_implemented(Law::KelvinVoigt));
        assert!(probes_implemented(Law::Thornton));
        // Nothing for the stick patch of an elastic table above E₋'s end; for Thornton's
        // partial-slip patch below F₋'s birth and E₋'s reach (γ 1–1.2, e_n 0.95–1) only the
        // upper edge of the loading band where it lies below α_c2 (0.9818 α_c2 at γ 1.15,
        // e_n 0.97).
        let k = traced(Law::Elastic, PatchKind::Stick, (2.4, 2.6), None);
        assert!(k.is_empty());
        let k = traced(
            Law::Thornton,
            PatchKind::PartialSlip,
            (1.0, 1.2),
            Some((0.95, 1.0)),
        );
        let names: Vec<_> = k.iter().map(|k| k.name()).collect();
        assert_eq!(names, ["L-hi"]);
        let c2 = oblique_physics::regimes::alpha_c2(1.15);
        let a = k[0].alpha(1.15, 0.97).expect("below alpha_c2 there");
        assert!((a / c2 - 0.98185).abs() < 1e-3, "{}", a / c2);
        // Its stick patch there: the band's edge where it lies above α_c2, and the switch
        // sheet, at a few nodes next to α_c2 near γ 1 (up to 1.06 and 1.053 α_c2, e_S
        // 0.93–0.98), too few for a stencil.
        let k = traced(
            Law::Thornton,
            PatchKind::Stick,
            (1.0, 1.2),
            Some((0.95, 1.0)),
        );
        assert!(k.iter().all(|k| ["e_S", "L-hi"].contains(&k.name())));
        let [sheet, _] = switch_sheet_surfaces((1.0, 1.2), (0.95, 1.0)).unwrap();
        for (g, r, _) in sheet.iter().flat_map(|s| s.points()) {
            assert!(g <= 1.06 + 1e-9 && r < 1.06, "{g} {r}");
        }
        assert!(k.iter().all(|k| k
            .e_n_at(1.1, 2.0 * oblique_physics::regimes::alpha_c2(1.1))
            .is_none()));
        // Below F₋'s end with damping, E₋ alone, in the partial-slip patch (α_E ≈ 0.46–0.7 at
        // γ 2.5, below α_c2 = 1.79); traced once for both patches.
        let mut traced = Traced::default();
        let e = Some((0.5, 0.8));
        let k = trace(
            Law::KelvinVoigt,
            PatchKind::PartialSlip,
            (2.4, 2.6),
            e,
            &mut traced,
            &|_| {},
        );
        let k = k.unwrap();
        let names: Vec<_> = k.iter().map(|k| (k.name(), k.patch())).collect();
        assert_eq!(names, [("E-", PatchKind::PartialSlip)]);
        assert!((0.4..0.8).contains(&k[0].alpha(2.5, 0.7).unwrap()));
        let stick = trace(
            Law::KelvinVoigt,
            PatchKind::Stick,
            (2.4, 2.6),
            e,
            &mut traced,
            &|_| {},
        )
        .unwrap();
        assert_eq!(stick[0].alpha(2.5, 0.7), None);
        let elastic = trace(
            Law::Elastic,
            PatchKind::PartialSlip,
            (2.4, 2.45),
            None,
            &mut traced,
            &|_| {},
        )
        .unwrap();
        assert_eq!(elastic.len(), 1);
        assert_eq!(
            (elastic[0].name(), elastic[0].patch()),
            ("F-", PatchKind::PartialSlip)
        );
        let a = elastic[0].alpha(2.42, 1.0).unwrap();
        assert!((a / 0.5123275 - 1.0).abs() < 1e-6, "{a}");
        assert_eq!(elastic[0].alpha(2.42, 0.99), None);
        // E₋ in both patches of an elastic table below F₋'s birth.
        for kind in [PatchKind::Stick, PatchKind::PartialSlip] {
            let k = trace(Law::Elastic, kind, (1.85, 2.0), None, &mut traced, &|_| {}).unwrap();
            let names: Vec<_> = k.iter().map(|k| (k.name(), k.patch())).collect();
            assert_eq!(names, [("E-", kind)]);
        }
    }
}
