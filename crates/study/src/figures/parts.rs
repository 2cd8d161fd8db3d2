//! What every figure of a table shares: the axes (the compactified α axis with its ticks, the
//! γ axis), the overlays of the `(γ, α)` plane (the critical curves `α_c1`, `α_c2`, the fold
//! curve F₊, the isotropic band), the colours of a family of curves, the check of a requested
//! family and the caption.

use oblique_lookup::Table;
use oblique_plot::{Axis, Colormap, Series, Style, Ticks};
use oblique_solver::history::fold_plus_curve;
use oblique_table::surface::{alpha_c1, alpha_c2};

use super::{compact, linspace, FigureError, Source, ISOTROPIC_GAMMA, MAX_FAMILY};

pub(super) const BLACK: (u8, u8, u8) = (0, 0, 0);
const BAND: (u8, u8, u8) = (0, 110, 0);
const ALPHA_TICKS: [f64; 8] = [0.0, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, f64::INFINITY];

pub(super) fn fmt_num(v: f64) -> String {
    if v.is_infinite() {
        "∞".into()
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// The compactified α axis, `[0, α/(1+α) of alpha_max]`, ticks at round α and `∞`.
pub(super) fn alpha_axis(alpha_max: f64, label: &str) -> Axis {
    let mut ticks: Vec<(f64, String)> = ALPHA_TICKS
        .iter()
        .filter(|&&a| a <= alpha_max)
        .map(|&a| (compact(a), fmt_num(a)))
        .collect();
    if alpha_max.is_finite() && !ALPHA_TICKS.contains(&alpha_max) {
        ticks.push((compact(alpha_max), fmt_num(alpha_max)));
    }
    Axis {
        label: label.to_string(),
        range: (0.0, compact(alpha_max)),
        ticks: Ticks::Fixed(ticks),
    }
}

pub(super) const ALPHA_LABEL: &str = "α = μ v_z0 / |v_x0 + R ω0|   (scale α/(1 + α); ∞: no slip)";
const GAMMA_LABEL: &str = "γ = √((7/2) G*/E*)";
pub(super) const P_LABEL: &str = "P = u_after / u_before";

pub(super) fn gamma_axis(table: &Table) -> Axis {
    Axis {
        label: GAMMA_LABEL.into(),
        range: (table.surface().gamma_min(), table.surface().gamma_max()),
        ticks: Ticks::Auto,
    }
}

/// `α_c2` over the whole domain and `α_c1` where `γ > 1`, as curves `(γ, α/(1+α))`.
pub(super) fn critical_curves(table: &Table) -> Vec<Series> {
    let s = &table.surface();
    let mut out = vec![Series {
        label: "α_c2 = 2γ²/7".into(),
        points: linspace(s.gamma_min(), s.gamma_max(), 400)
            .into_iter()
            .filter(|&g| alpha_c2(g) <= s.alpha_max())
            .map(|g| (g, compact(alpha_c2(g))))
            .collect(),
        style: Style::Line,
        color: BLACK,
        sets_range: false,
    }];
    if s.gamma_max() > 1.0 {
        out.push(Series {
            label: "α_c1 = 2γ²/(7(2γ² − 1)), γ > 1".into(),
            points: linspace(s.gamma_min().max(1.0), s.gamma_max(), 400)
                .into_iter()
                .filter(|&g| alpha_c1(g) <= s.alpha_max())
                .map(|g| (g, compact(alpha_c1(g))))
                .collect(),
            style: Style::Dashed,
            color: BLACK,
            sets_range: false,
        });
    }
    out
}

/// Largest γ up to which the regime diagram traces the fold curve F₊ (the continuation of
/// [`fold_plus_curve`] is tested to 3.5).
const FOLD_GAMMA_MAX: f64 = 3.6;

/// The fold curve F₊ of `P` (`docs/solver.md`, "Kink curves"), where the table's γ range
/// reaches it: 40 points traced at 2048 steps (about 3 s, the only simulation behind a figure).
/// Points of the curve's threshold edge just above its birth, where `P` has no kink (slope
/// jump below 0.01), are left out. `None` below the birth or if the tracing fails.
pub(super) fn fold_curve(table: &Table) -> Option<Series> {
    let s = &table.surface();
    let top = s.gamma_max().min(FOLD_GAMMA_MAX);
    let curve = fold_plus_curve(top, 40, 2048).ok()?;
    let points: Vec<(f64, f64)> = curve
        .points
        .iter()
        .filter(|p| {
            p.slope_jump.abs() > 0.01 && p.gamma >= s.gamma_min() && p.alpha <= s.alpha_max()
        })
        .map(|p| (p.gamma, compact(p.alpha)))
        .collect();
    (points.len() >= 2).then(|| Series {
        label: "fold F₊: P(α) has a kink (sweep kinks)".into(),
        points,
        style: Style::Line,
        color: (200, 30, 30),
        sets_range: false,
    })
}

/// The isotropic band `1.52 < γ < 2.16` as two vertical dotted lines (where inside the domain).
pub(super) fn isotropic_lines(table: &Table, y: (f64, f64)) -> Vec<Series> {
    let s = &table.surface();
    let mut first = true;
    [ISOTROPIC_GAMMA.0, ISOTROPIC_GAMMA.1]
        .into_iter()
        .filter(|&g| g > s.gamma_min() && g < s.gamma_max())
        .map(|g| {
            let label = if first {
                format!(
                    "one isotropic material: {} < γ < {}",
                    ISOTROPIC_GAMMA.0, ISOTROPIC_GAMMA.1
                )
            } else {
                String::new()
            };
            first = false;
            Series {
                label,
                points: vec![(g, y.0), (g, y.1)],
                style: Style::Dotted,
                color: BAND,
                sets_range: false,
            }
        })
        .collect()
}

/// Caption lines: the table's provenance and the command.
pub fn caption(table: &Table, src: &Source) -> Vec<String> {
    let pv = &table.provenance();
    let s = &table.surface();
    let commit: String = pv.git_commit.chars().take(10).collect();
    let max_err = table
        .checks()
        .iter()
        .map(|c| c.interpolation_error)
        .fold(0.0, f64::max);
    vec![
        format!(
            "table {} (schema v{}): γ {}–{}, α ≤ {}; built {} by engine {} (commit {}); node tol {:.0e}; held-out max error {:.1e} ({} points)",
            src.table,
            pv.schema_version,
            fmt_num(s.gamma_min()),
            fmt_num(s.gamma_max()),
            fmt_num(s.alpha_max()),
            pv.created,
            pv.engine_version,
            commit,
            pv.node_tol,
            max_err,
            table.checks().len()
        ),
        format!("figure: {}", src.command),
    ]
}

pub(super) fn check_family(
    name: &'static str,
    values: &[f64],
    ok: impl Fn(f64) -> bool,
    allowed: &str,
) -> Result<(), FigureError> {
    if values.is_empty() || values.len() > MAX_FAMILY {
        return Err(FigureError::Invalid {
            name,
            message: format!(
                "{} values given: give 1 to {MAX_FAMILY} (comma-separated)",
                values.len()
            ),
        });
    }
    if let Some(v) = values.iter().find(|&&v| !ok(v)) {
        return Err(FigureError::Invalid {
            name,
            message: format!("{v} is not {allowed}"),
        });
    }
    Ok(())
}

/// Ten distinct colours (Tableau 10), for families of up to ten curves.
const QUALITATIVE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

/// Colour `k` of `n` curves: distinct colours up to ten curves, else along the sequential map
/// (its palest end left out so every curve shows on white).
pub(super) fn family_color(k: usize, n: usize) -> (u8, u8, u8) {
    if n <= QUALITATIVE.len() {
        return QUALITATIVE[k];
    }
    let t = if n > 1 {
        k as f64 / (n - 1) as f64
    } else {
        0.0
    };
    Colormap::Sequential.at(0.85 * t)
}
