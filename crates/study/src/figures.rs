//! The figures of `sweep plot`: what a `P(γ, α)` table holds, as pictures.
//!
//! Each function here is a pure function from a loaded [`Table`] to a [`Sheet`] (plain data:
//! grids, series, regions, points); [`oblique_plot::render_sheet`] draws it. So the plotted numbers
//! can be checked against the table without looking at pixels.
//!
//! Symbols as in `physics.md`: `γ = √((7/2) G*/E*)`, `α = μ v_z0/|v_x0 + R ω0|` (dimensionless),
//! `P = u_after/u_before` (dimensionless, `u = v_x + R ω`), `α_c1 = 2γ²/(7(2γ² − 1))`,
//! `α_c2 = 2γ²/7`. The α axis of every figure is compactified, `y = α/(1 + α)`, so that the
//! no-slip limit `α = ∞` is the top (or right) edge `y = 1`.
//!
//! | figure | file stem | shows |
//! |---|---|---|
//! | [`surface`] | `p_surface` | `P(γ, α)` as a colour map with contours, `α_c1`, `α_c2`, the isotropic band |
//! | [`slices`] | `p_slices` | `P` against `α` for fixed `γ`; `P` against `γ` for fixed `α` with seed 001's fit (29) |
//! | [`regimes`] | `regimes` | full slip / partial slip / stick in the `(γ, α)` plane |
//! | [`quality`] | `check_errors` | interpolation error at the held-out checks, over the quadtree leaves |
//! | [`restitution`] | `p_restitution` | `P` against `α` at fixed `γ` for several `e_n` beside the elastic curve (a table with an `e_n` axis; on request only) |
//!
//! What every figure shares (axes, overlays, caption) is in `figures/parts.rs`, the maps of the
//! `(γ, α)` plane in `figures/plane.rs`, the curves in `figures/curves.rs`.

mod curves;
mod parts;
mod plane;

use oblique_lookup::{LookupError, Table};
use oblique_plot::Sheet;
use thiserror::Error;

pub use curves::{
    default_alphas, default_gammas, default_restitution_gammas, default_restitutions, restitution,
    slices, SLICE_SAMPLES,
};
pub use parts::caption;
pub use plane::{leaf_outlines, quality, regimes, surface, REGIME_LABELS, SURFACE_GRID};

/// Range of `γ` of one isotropic material (`G*/E* = 2(1 − ν)/(2 − ν)`, `0 ≤ ν ≤ 1/2`), rounded as in
/// the seeds.
pub const ISOTROPIC_GAMMA: (f64, f64) = (1.52, 2.16);

/// Most values in a family (`--gammas`, `--alphas`): more curves are not readable.
pub const MAX_FAMILY: usize = 16;

/// Errors of figure building.
#[derive(Debug, Error)]
pub enum FigureError {
    /// A figure option is invalid: `name` is the option (`gammas`, `alphas`).
    #[error("invalid {name}: {message}")]
    Invalid {
        /// Option name.
        name: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The table refused a query (a table inconsistent with its own domain).
    #[error(transparent)]
    Lookup(#[from] LookupError),
}

impl FigureError {
    /// Whether the caller can fix it: an invalid figure request, or a table that cannot be read
    /// or queried.
    pub fn user_can_fix(&self) -> bool {
        match self {
            FigureError::Invalid { .. } => true,
            FigureError::Lookup(e) => e.user_can_fix(),
        }
    }
}

/// The four figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureKind {
    /// [`surface`].
    Surface,
    /// [`slices`].
    Slices,
    /// [`regimes`].
    Regimes,
    /// [`quality`].
    Quality,
    /// [`restitution`] (a table with an `e_n` axis; not among [`FigureKind::ALL`]).
    Restitution,
}

impl FigureKind {
    /// The four figures of every table, in order (`sweep plot` without `--figure`);
    /// [`FigureKind::Restitution`] is drawn on request.
    pub const ALL: [FigureKind; 4] = [
        FigureKind::Surface,
        FigureKind::Slices,
        FigureKind::Regimes,
        FigureKind::Quality,
    ];

    /// File name without extension.
    pub fn stem(self) -> &'static str {
        match self {
            FigureKind::Surface => "p_surface",
            FigureKind::Slices => "p_slices",
            FigureKind::Regimes => "regimes",
            FigureKind::Quality => "check_errors",
            FigureKind::Restitution => "p_restitution",
        }
    }

    /// One line: what the figure shows.
    pub fn describe(self) -> &'static str {
        match self {
            FigureKind::Surface => {
                "P(gamma, alpha) colour map with contours, alpha_c1, alpha_c2, isotropic band"
            }
            FigureKind::Slices => {
                "P against alpha for fixed gamma; P against gamma for fixed alpha with the seed-001 fit"
            }
            FigureKind::Regimes => "full slip / partial slip / stick in the (gamma, alpha) plane",
            FigureKind::Quality => {
                "interpolation error at the held-out checks, over the quadtree leaves"
            }
            FigureKind::Restitution => {
                "P against alpha at fixed gamma for several e_n beside the elastic curve"
            }
        }
    }
}

/// Where a figure's table came from and how the figure was made (for the caption).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// Table path as given.
    pub table: String,
    /// The command line that makes the figure.
    pub command: String,
}

/// Compactified α: `y = α/(1 + α)`, `∞ ↦ 1`.
pub fn compact(alpha: f64) -> f64 {
    if alpha.is_infinite() {
        1.0
    } else {
        alpha / (1.0 + alpha)
    }
}

/// Inverse of [`compact`]: `α = y/(1 − y)`, `∞` for `y ≥ 1`.
pub fn alpha_at(y: f64) -> f64 {
    if y >= 1.0 {
        f64::INFINITY
    } else {
        y / (1.0 - y)
    }
}

/// `n ≥ 2` equally spaced values from `a` to `b`, both ends exact.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| {
            if i == n - 1 {
                b
            } else {
                a + (b - a) * i as f64 / (n - 1) as f64
            }
        })
        .collect()
}

/// `γ` where a fixed `α` crosses `α_c2` (`γ = √(7α/2)`) and `α_c1` (`γ = √(7α/(14α − 2))`,
/// only for `α > 1/7`, and only where `γ > 1`): the kinks of `P(γ)` at fixed `α`.
pub fn critical_gammas(alpha: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if alpha.is_finite() && alpha > 0.0 {
        out.push((3.5 * alpha).sqrt());
        if alpha > 1.0 / 7.0 {
            let g = (7.0 * alpha / (14.0 * alpha - 2.0)).sqrt();
            if g > 1.0 {
                out.push(g);
            }
        }
    }
    out
}

/// Build one figure (`e_ns`: the `e_n` family of [`FigureKind::Restitution`], whose `γ` are the
/// first two of `gammas`).
pub fn build(
    kind: FigureKind,
    table: &Table,
    src: &Source,
    gammas: &[f64],
    alphas: &[f64],
    e_ns: &[f64],
) -> Result<Sheet, FigureError> {
    match kind {
        FigureKind::Surface => surface(table, src),
        FigureKind::Slices => slices(table, src, gammas, alphas),
        FigureKind::Regimes => Ok(regimes(table, src)),
        FigureKind::Quality => Ok(quality(table, src)),
        FigureKind::Restitution => restitution(table, src, gammas, e_ns),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_table::surface::{alpha_c1, alpha_c2};

    #[test]
    fn compactification_round_trips_and_puts_infinity_at_one() {
        for a in [0.0, 0.1, 0.5, 1.0, 7.0, 100.0] {
            assert!((alpha_at(compact(a)) - a).abs() <= 1e-12 * a.max(1.0));
        }
        // 1 − y loses digits as α grows: relative error about α · 1e-16.
        assert!((alpha_at(compact(1e6)) / 1e6 - 1.0).abs() < 1e-9);
        assert_eq!(compact(f64::INFINITY), 1.0);
        assert!(alpha_at(1.0).is_infinite());
    }

    #[test]
    fn critical_gammas_solve_the_critical_curves() {
        for a in [0.2, 0.3, 1.0, 3.0] {
            let g = critical_gammas(a);
            assert!((alpha_c2(g[0]) - a).abs() < 1e-12);
            if let Some(&g1) = g.get(1) {
                assert!((alpha_c1(g1) - a).abs() < 1e-12);
            }
        }
        // α_c1 ≥ 1/7 for every γ > 1 and ≤ 2/7: one crossing for 1/7 < α < 2/7, none above.
        assert_eq!(critical_gammas(0.2).len(), 2);
        assert_eq!(critical_gammas(1.0).len(), 1);
    }

    #[test]
    fn linspace_hits_both_ends_exactly() {
        let v = linspace(0.1, 3.5, 301);
        assert_eq!(v.len(), 301);
        assert_eq!(v[0], 0.1);
        assert_eq!(v[300], 3.5);
    }
}
