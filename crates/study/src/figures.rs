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

use oblique_lookup::{LookupError, Table};
use oblique_table::surface::{alpha_c1, alpha_c2, linear_limit, Patch};
use thiserror::Error;

use oblique_physics::regimes::{alpha_c1_dissipative, full_slip_line, no_slip_fit};
use oblique_plot::{
    Axis, Chart, ColorScale, Colormap, Contours, Grid, Legend, LegendPlace, Note, Region, Scale,
    Scatter, Series, Sheet, Style, Ticks,
};
use oblique_solver::history::fold_plus_curve;

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

const BLACK: (u8, u8, u8) = (0, 0, 0);
const BAND: (u8, u8, u8) = (0, 110, 0);
const ALPHA_TICKS: [f64; 8] = [0.0, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, f64::INFINITY];

fn fmt_num(v: f64) -> String {
    if v.is_infinite() {
        "∞".into()
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// The compactified α axis, `[0, α/(1+α) of alpha_max]`, ticks at round α and `∞`.
fn alpha_axis(alpha_max: f64, label: &str) -> Axis {
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

const ALPHA_LABEL: &str = "α = μ v_z0 / |v_x0 + R ω0|   (scale α/(1 + α); ∞: no slip)";
const GAMMA_LABEL: &str = "γ = √((7/2) G*/E*)";
const P_LABEL: &str = "P = u_after / u_before";

fn gamma_axis(table: &Table) -> Axis {
    Axis {
        label: GAMMA_LABEL.into(),
        range: (table.surface().gamma_min(), table.surface().gamma_max()),
        ticks: Ticks::Auto,
    }
}

/// `α_c2` over the whole domain and `α_c1` where `γ > 1`, as curves `(γ, α/(1+α))`.
fn critical_curves(table: &Table) -> Vec<Series> {
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
fn fold_curve(table: &Table) -> Option<Series> {
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
fn isotropic_lines(table: &Table, y: (f64, f64)) -> Vec<Series> {
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

/// Grid size of the colour map of [`surface`] (γ nodes, α nodes).
pub const SURFACE_GRID: (usize, usize) = (301, 241);

/// Figure 1: `P(γ, α)` over the table's domain as a colour map (`γ` across, `α/(1+α)` up, so
/// `α = ∞` is the top edge) with contours every 0.2 (bold: `P = 0`, rolling), the critical
/// curves `α_c1(γ)` and `α_c2(γ)` and the isotropic band `1.52 < γ < 2.16`. The seed's Figs. 2
/// and 3 in one picture.
///
/// The map is `charts[0].map`: node `(i, j)` is `P(xs[i], alpha_at(ys[j]))` by [`Table::p`].
pub fn surface(table: &Table, src: &Source) -> Result<Sheet, FigureError> {
    let s = &table.surface();
    let top = compact(s.alpha_max());
    let xs = linspace(s.gamma_min(), s.gamma_max(), SURFACE_GRID.0);
    let ys = linspace(0.0, top, SURFACE_GRID.1);
    let mut values = Vec::with_capacity(xs.len() * ys.len());
    for &g in &xs {
        for &y in &ys {
            values.push(table.p(g, alpha_at(y))?);
        }
    }
    let mut series = critical_curves(table);
    series.extend(isotropic_lines(table, (0.0, top)));
    let levels: Vec<f64> = (-4..=4)
        .filter(|&k| k != 0)
        .map(|k| k as f64 * 0.2)
        .collect();
    let mut notes = Vec::new();
    if s.gamma_max() > 1.2 {
        let g = 0.5 * (s.gamma_max() + s.gamma_min().max(1.0));
        notes.push(Note {
            text: "full slip: P = 1 − 7α".into(),
            at: (g, 0.5 * compact(alpha_c1(g).min(alpha_c2(g)))),
            color: BLACK,
            size: 14,
            boxed: true,
        });
    }
    let chart = Chart {
        title: String::new(),
        x: gamma_axis(table),
        y: alpha_axis(s.alpha_max(), ALPHA_LABEL),
        regions: Vec::new(),
        map: Some(Grid { xs, ys, values }),
        contours: Some(Contours {
            levels,
            bold: vec![0.0],
            color: (40, 40, 40),
        }),
        outlines: Vec::new(),
        series,
        scatter: None,
        color_scale: Some(ColorScale {
            label: P_LABEL.into(),
            colormap: Colormap::Diverging,
            scale: Scale::Linear,
            range: (-1.0, 1.0),
            bands: 40,
            ticks: [-1.0, -0.5, 0.0, 0.5, 1.0]
                .into_iter()
                .map(|v| (v, fmt_num(v).replace('-', "−")))
                .collect(),
        }),
        notes,
        legend: LegendPlace::Inside(Legend::UpperLeft),
    };
    Ok(Sheet {
        title: "P(γ, α): tangential restitution of the contact point".into(),
        subtitle: "colour: P in bands of 0.05; contours every 0.2, bold P = 0 (rolling); top edge α = ∞ (no slip)".into(),
        charts: vec![chart],
        caption: caption(table, src),
        size: (1200, 860),
    })
}

/// Default family of `γ` for [`slices`]: round values in the table's domain (the isotropic
/// band's ends among them), or six equally spaced values if fewer than four fall inside.
pub fn default_gammas(table: &Table) -> Vec<f64> {
    let s = &table.surface();
    let inside: Vec<f64> = [0.5, 0.8, 1.0, 1.2, 1.52, 1.84, 2.16, 2.5, 3.0, 3.5]
        .into_iter()
        .filter(|&g| g >= s.gamma_min() && g <= s.gamma_max())
        .collect();
    if inside.len() >= 4 {
        inside
    } else {
        linspace(s.gamma_min(), s.gamma_max(), 6)
    }
}

/// Default family of `α` for [`slices`]: values from the seed's Fig. 4b, and `∞`, up to the
/// table's `alpha_max`.
pub fn default_alphas(table: &Table) -> Vec<f64> {
    [0.3, 0.5, 0.7, 1.0, 2.0, 4.0, 12.0, f64::INFINITY]
        .into_iter()
        .filter(|&a| a <= table.surface().alpha_max())
        .collect()
}

fn check_family(
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
fn family_color(k: usize, n: usize) -> (u8, u8, u8) {
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

/// Samples of `α/(1+α)` for curves against `α`.
pub const SLICE_SAMPLES: usize = 401;

/// Figure 2: (a) `P` against `α` (compactified) for each `γ` in `gammas` (seed 000 Fig. 4a), with
/// the full-slip line `1 − 7α` and dots at `α_c1` (γ > 1) and `α_c2` of each curve; (b) `P`
/// against `γ` for each `α` in `alphas` (seed 000 Fig. 4b), `α = ∞` allowed, with seed 001's fit
/// (29) of the no-slip limit.
///
/// Data layout: `charts[0].series[k]` (k < gammas.len()) is the curve of `gammas[k]`, points
/// `(y, P(γ, alpha_at(y)))`; `charts[1].series[k]` (k < alphas.len()) is the curve of
/// `alphas[k]`, points `(γ, P(γ, α))`; both from [`Table::p`].
pub fn slices(
    table: &Table,
    src: &Source,
    gammas: &[f64],
    alphas: &[f64],
) -> Result<Sheet, FigureError> {
    let s = &table.surface();
    let allowed = format!(
        "a gamma in the table's domain [{}, {}]",
        s.gamma_min(),
        s.gamma_max()
    );
    check_family(
        "gammas",
        gammas,
        |g| g >= s.gamma_min() && g <= s.gamma_max(),
        &allowed,
    )?;
    let allowed = format!(
        "an alpha in [0, {}] (the table's alpha_max; inf allowed if it is inf)",
        s.alpha_max()
    );
    check_family(
        "alphas",
        alphas,
        |a| a >= 0.0 && a <= s.alpha_max(),
        &allowed,
    )?;
    let top = compact(s.alpha_max());
    let p_axis = Axis {
        label: P_LABEL.into(),
        range: (-1.05, 1.05),
        ticks: Ticks::Auto,
    };

    // (a) P against α.
    let base = linspace(0.0, top, SLICE_SAMPLES);
    let mut curves = Vec::new();
    let mut dots = Vec::new();
    for (k, &g) in gammas.iter().enumerate() {
        let crit: Vec<f64> = if g > 1.0 {
            vec![alpha_c1(g), alpha_c2(g)]
        } else {
            vec![alpha_c2(g)]
        };
        let crit: Vec<f64> = crit.into_iter().filter(|&a| a <= s.alpha_max()).collect();
        let mut ys: Vec<f64> = base.clone();
        ys.extend(crit.iter().map(|&a| compact(a)));
        ys.sort_by(f64::total_cmp);
        ys.dedup();
        let points = ys
            .iter()
            .map(|&y| Ok((y, table.p(g, alpha_at(y))?)))
            .collect::<Result<Vec<_>, LookupError>>()?;
        let color = family_color(k, gammas.len());
        curves.push(Series {
            label: format!("γ = {}", fmt_num(g)),
            points,
            style: Style::Line,
            color,
            sets_range: true,
        });
        dots.push(Series {
            label: String::new(),
            points: crit
                .iter()
                .map(|&a| Ok((compact(a), table.p(g, a)?)))
                .collect::<Result<Vec<_>, LookupError>>()?,
            style: Style::Markers,
            color,
            sets_range: false,
        });
    }
    let mut series_a = curves;
    series_a.extend(dots);
    series_a.push(Series {
        label: "full slip: P = 1 − 7α".into(),
        points: base.iter().map(|&y| (y, 1.0 - 7.0 * alpha_at(y))).collect(),
        style: Style::Dashed,
        color: BLACK,
        sets_range: false,
    });
    series_a.push(Series {
        label: "dots: α_c1 (γ > 1), α_c2".into(),
        points: Vec::new(),
        style: Style::Markers,
        color: (90, 90, 90),
        sets_range: false,
    });
    let chart_a = Chart {
        title: "(a) P against α for fixed γ".into(),
        x: alpha_axis(s.alpha_max(), ALPHA_LABEL),
        y: p_axis.clone(),
        regions: Vec::new(),
        map: None,
        contours: None,
        outlines: Vec::new(),
        series: series_a,
        scatter: None,
        color_scale: None,
        notes: Vec::new(),
        legend: LegendPlace::Right,
    };

    // (b) P against γ.
    let mut series_b = Vec::new();
    for (k, &a) in alphas.iter().enumerate() {
        let mut gs = linspace(s.gamma_min(), s.gamma_max(), 341);
        gs.extend(
            critical_gammas(a)
                .into_iter()
                .chain([1.0])
                .filter(|&g| g > s.gamma_min() && g < s.gamma_max()),
        );
        gs.sort_by(f64::total_cmp);
        gs.dedup();
        let points = gs
            .iter()
            .map(|&g| Ok((g, table.p(g, a)?)))
            .collect::<Result<Vec<_>, LookupError>>()?;
        series_b.push(Series {
            label: if a.is_infinite() {
                "α = ∞ (no slip)".into()
            } else {
                format!("α = {}", fmt_num(a))
            },
            points,
            style: Style::Line,
            color: family_color(k, alphas.len()),
            sets_range: true,
        });
    }
    series_b.push(Series {
        label: "seed 001 fit (29) of P(γ, ∞)".into(),
        points: linspace(s.gamma_min(), s.gamma_max(), 341)
            .into_iter()
            .map(|g| (g, no_slip_fit(g)))
            .collect(),
        style: Style::Dashed,
        color: BLACK,
        sets_range: false,
    });
    series_b.extend(isotropic_lines(table, (-1.05, 1.05)));
    let chart_b = Chart {
        title: "(b) P against γ for fixed α".into(),
        x: gamma_axis(table),
        y: p_axis,
        regions: Vec::new(),
        map: None,
        contours: None,
        outlines: Vec::new(),
        series: series_b,
        scatter: None,
        color_scale: None,
        notes: Vec::new(),
        legend: LegendPlace::Right,
    };
    Ok(Sheet {
        title: "P(γ, α) along lines of fixed γ and fixed α".into(),
        subtitle: "fit (29): −1 + 2 exp(−0.195γ) cos²(1.685(γ − 0.061)), Lyashenko & Popov 2015 (a fit, off by ≈ 0.01 in places)".into(),
        charts: vec![chart_a, chart_b],
        caption: caption(table, src),
        size: (1200, 1250),
    })
}

/// Labels of the three regimes in [`regimes`], in the order of its regions.
pub const REGIME_LABELS: [&str; 3] = [
    "full slip: P = 1 − 7α exactly",
    "partial slip (γ > 1): α_c1 < α < α_c2",
    "stick during compression: α ≥ α_c2",
];

/// Figure 3: the regime diagram over the table's domain: full slip (`α ≤ α_c1` for `γ > 1`,
/// `α ≤ α_c2` for `γ ≤ 1`), partial slip (`γ > 1`, `α_c1 < α < α_c2`), stick (`α ≥ α_c2`), as
/// filled polygons in `(γ, α/(1+α))` with the labels [`REGIME_LABELS`]; the boundaries are
/// sampled on 401 values of `γ` (and `γ = 1`). Where the domain reaches γ ≈ 2.9, the fold curve
/// F₊ inside the partial-slip region is drawn too ([`fold_curve`]).
pub fn regimes(table: &Table, src: &Source) -> Sheet {
    let s = &table.surface();
    let top = compact(s.alpha_max());
    let mut gs = linspace(s.gamma_min(), s.gamma_max(), 401);
    if s.gamma_min() < 1.0 && s.gamma_max() > 1.0 {
        gs.push(1.0);
        gs.sort_by(f64::total_cmp);
        gs.dedup();
    }
    let y_of = |a: f64| compact(a.min(s.alpha_max()));
    // Full slip: below the linear limit.
    let mut full: Vec<(f64, f64)> = gs.iter().map(|&g| (g, y_of(linear_limit(g)))).collect();
    full.push((s.gamma_max(), 0.0));
    full.push((s.gamma_min(), 0.0));
    // Stick: above α_c2.
    let mut stick: Vec<(f64, f64)> = gs.iter().map(|&g| (g, y_of(alpha_c2(g)))).collect();
    stick.push((s.gamma_max(), top));
    stick.push((s.gamma_min(), top));
    let mut regions = vec![Region {
        label: REGIME_LABELS[0].into(),
        polygon: full,
        color: (198, 219, 239),
    }];
    let high: Vec<f64> = gs.iter().copied().filter(|&g| g >= 1.0).collect();
    if high.len() >= 2 {
        let mut partial: Vec<(f64, f64)> = high.iter().map(|&g| (g, y_of(alpha_c1(g)))).collect();
        partial.extend(high.iter().rev().map(|&g| (g, y_of(alpha_c2(g)))));
        regions.push(Region {
            label: REGIME_LABELS[1].into(),
            polygon: partial,
            color: (253, 208, 162),
        });
    }
    regions.push(Region {
        label: REGIME_LABELS[2].into(),
        polygon: stick,
        color: (199, 233, 192),
    });
    let mut series = critical_curves(table);
    series.extend(fold_curve(table));
    series.extend(isotropic_lines(table, (0.0, top)));
    let mut notes = Vec::new();
    let note = |text: &str, at: (f64, f64)| Note {
        text: text.into(),
        at,
        color: (20, 20, 20),
        size: 16,
        boxed: false,
    };
    let gm = 0.5 * (s.gamma_min() + s.gamma_max());
    notes.push(note("I  stick", (gm, 0.5 * (top + y_of(alpha_c2(gm))))));
    if s.gamma_max() > 1.3 {
        let g = s.gamma_min().max(1.0) + 0.75 * (s.gamma_max() - s.gamma_min().max(1.0));
        let mid = 0.5 * (y_of(alpha_c1(g)) + y_of(alpha_c2(g)));
        notes.push(note("II  partial slip", (g, mid)));
        notes.push(note("III  full slip", (g, 0.5 * y_of(alpha_c1(g)))));
    }
    if s.gamma_min() < 1.0 && s.gamma_max() > 1.0 {
        notes.push(Note {
            text: "γ = 1: α_c1 = α_c2 = 2/7".into(),
            at: (1.0, y_of(2.0 / 7.0) + 0.04),
            color: (20, 20, 20),
            size: 13,
            boxed: true,
        });
    }
    let chart = Chart {
        title: String::new(),
        x: gamma_axis(table),
        y: alpha_axis(s.alpha_max(), ALPHA_LABEL),
        regions,
        map: None,
        contours: None,
        outlines: Vec::new(),
        series,
        scatter: None,
        color_scale: None,
        notes,
        legend: LegendPlace::Right,
    };
    Sheet {
        title: "Friction regimes of an oblique impact".into(),
        subtitle: "γ < 1: the line P = 1 − 7α holds up to α_c2 (α_c1 marks nothing there); regime names as in seed 000, Fig. 3".into(),
        charts: vec![chart],
        caption: caption(table, src),
        size: (1200, 800),
    }
}

/// Outline of every leaf of a patch in `(γ, α/(1+α))`: bottom, right, top and left edge, the
/// edges of constant patch coordinate `c` (`c'` of a warp; curves in this plane) sampled at 64 points per patch
/// width, at least 5 per leaf.
pub fn leaf_outlines(patch: &Patch, alpha_max: f64) -> Vec<Vec<(f64, f64)>> {
    let roots = patch.blocks_gamma() * patch.blocks_coord();
    let mut stack: Vec<(usize, f64, f64, f64, f64)> = (0..roots)
        .map(|i| {
            let (a, b) = (i / patch.blocks_coord(), i % patch.blocks_coord());
            let (hx, hc) = (
                1.0 / patch.blocks_gamma() as f64,
                1.0 / patch.blocks_coord() as f64,
            );
            (i, a as f64 * hx, b as f64 * hc, hx, hc)
        })
        .collect();
    let mut out = Vec::new();
    let gamma = |x: f64| patch.gamma_lo() + (patch.gamma_hi() - patch.gamma_lo()) * x;
    // The quadtree is over the warped c' from the warp's start on (schema 3).
    let point = |x: f64, c: f64, warped: bool| {
        let g = gamma(x);
        let c = match &patch.warp() {
            Some(w) if warped => w.invert(g, c),
            _ => c,
        };
        (g, compact(patch.kind().alpha(g, c, alpha_max)))
    };
    let bg = patch.blocks_gamma() as f64;
    while let Some((cell, x0, c0, hx, hc)) = stack.pop() {
        let Some(&t) = patch.tree().get(cell) else {
            continue;
        };
        if t >= 0 {
            let t = t as usize;
            for qg in 0..2 {
                for qc in 0..2 {
                    stack.push((
                        t + 2 * qg + qc,
                        x0 + 0.5 * hx * qg as f64,
                        c0 + 0.5 * hc * qc as f64,
                        0.5 * hx,
                        0.5 * hc,
                    ));
                }
            }
            continue;
        }
        // The leaf's first row in root-row units (exact up to the rounding of 1/blocks).
        let warped = patch
            .warp()
            .as_ref()
            .is_some_and(|w| x0 * bg >= w.start() - 1e-9);
        let xs = linspace(x0, x0 + hx, ((64.0 * hx).ceil() as usize).max(4) + 1);
        let mut line: Vec<(f64, f64)> = xs.iter().map(|&x| point(x, c0, warped)).collect();
        line.extend(xs.iter().rev().map(|&x| point(x, c0 + hc, warped)));
        line.push(point(x0, c0, warped));
        out.push(line);
    }
    out
}

/// Figure 4: the table's own quality. Every held-out check (a point simulated at `check_tol`,
/// never used for interpolation) is a dot at `(γ, α/(1+α))` coloured by its stored interpolation
/// error `|P_interpolated − P_simulated|` on a log scale, over the outlines of the quadtree leaves
/// (smaller where `P` needed more nodes), with `α_c1` and `α_c2`.
///
/// Data layout: `charts[0].scatter.points[k] = (γ, α/(1+α), error)` of `table.checks[k]`;
/// `charts[0].outlines` has one closed outline per leaf.
pub fn quality(table: &Table, src: &Source) -> Sheet {
    let s = &table.surface();
    let top = compact(s.alpha_max());
    let errors: Vec<f64> = table
        .checks()
        .iter()
        .map(|c| c.interpolation_error)
        .collect();
    let positive = errors.iter().copied().filter(|&e| e > 0.0 && e.is_finite());
    let lo = positive.clone().fold(f64::INFINITY, f64::min);
    let hi = positive
        .fold(0.0, f64::max)
        .max(table.provenance().target_error);
    let (dlo, dhi) = if lo.is_finite() && hi > 0.0 {
        (lo.log10().floor(), hi.log10().ceil())
    } else {
        (-8.0, -4.0)
    };
    let dhi = if dhi > dlo { dhi } else { dlo + 1.0 };
    let ticks = (dlo as i32..=dhi as i32)
        .map(|d| (10f64.powi(d), format!("1e{d}").replace('-', "−")))
        .collect();
    let outlines: Vec<Vec<(f64, f64)>> = s
        .patches()
        .map(|(_, p)| p)
        .flat_map(|p| leaf_outlines(p, s.alpha_max()))
        .collect();
    let leaves = outlines.len();
    let mut series = critical_curves(table);
    series.extend(isotropic_lines(table, (0.0, top)));
    let (n, max, rms) = {
        let n = errors.len();
        let max = errors.iter().copied().fold(0.0, f64::max);
        let rms = if n > 0 {
            (errors.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt()
        } else {
            0.0
        };
        (n, max, rms)
    };
    let chart = Chart {
        title: String::new(),
        x: gamma_axis(table),
        y: alpha_axis(s.alpha_max(), ALPHA_LABEL),
        regions: Vec::new(),
        map: None,
        contours: None,
        outlines,
        series,
        scatter: Some(Scatter {
            label: format!("held-out check ({n}), colour: its error"),
            points: table
                .checks()
                .iter()
                .map(|c| (c.gamma, compact(c.alpha), c.interpolation_error))
                .collect(),
            radius: 4,
        }),
        color_scale: Some(ColorScale {
            label: "|P_interpolated − P_simulated|".into(),
            colormap: Colormap::Sequential,
            scale: Scale::Log10,
            range: (10f64.powf(dlo), 10f64.powf(dhi)),
            // Two colour classes per decade.
            bands: 2 * (dhi - dlo) as usize,
            ticks,
        }),
        notes: Vec::new(),
        legend: LegendPlace::Inside(Legend::UpperLeft),
    };
    Sheet {
        title: "Interpolation error of the table at its held-out checks".into(),
        subtitle: format!(
            "max {max:.1e}, rms {rms:.1e} over {n} points (target_error {:.0e}, check_tol {:.0e}); grey: the {leaves} quadtree leaves",
            table.provenance().target_error, table.provenance().check_tol
        ),
        charts: vec![chart],
        caption: caption(table, src),
        size: (1200, 860),
    }
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

/// Default `γ` of [`restitution`]: 1.52 and 1.84 (inside the isotropic band) where the table
/// covers them, else the middle of its domain.
pub fn default_restitution_gammas(table: &Table) -> Vec<f64> {
    let s = table.surface();
    let inside: Vec<f64> = [1.52, 1.84]
        .into_iter()
        .filter(|&g| g >= s.gamma_min() && g <= s.gamma_max())
        .collect();
    if inside.is_empty() {
        vec![0.5 * (s.gamma_min() + s.gamma_max())]
    } else {
        inside
    }
}

/// Default `e_n` family of [`restitution`]: 0.5, 0.7, 0.9 and 1 where the table's `e_n` range
/// covers them (empty for an elastic table).
pub fn default_restitutions(table: &Table) -> Vec<f64> {
    match table.restitution() {
        None => Vec::new(),
        Some((lo, hi)) => [0.5, 0.7, 0.9, 1.0]
            .into_iter()
            .filter(|&e| e >= lo && e <= hi)
            .collect(),
    }
}

/// Figure 5 (a table with an `e_n` axis): for each `γ` in `gammas` (at most two; one chart
/// each), `P` against `α` (compactified) for each `e_n` in `e_ns` (Kelvin–Voigt law), with
/// `e_n = 1` drawn as the elastic curve (black), the full-slip line `1 − (7/2)(1 + e_n)α` of
/// each `e_n` (dashed) and a dot at each `α_c1(e_n)` (γ > 1).
///
/// Data layout: `charts[j].series[k]` (k < e_ns.len()) is the curve of `e_ns[k]` at
/// `gammas[j]`, points `(y, P(γ, alpha_at(y), e_n))` from [`Table::p_e`].
pub fn restitution(
    table: &Table,
    src: &Source,
    gammas: &[f64],
    e_ns: &[f64],
) -> Result<Sheet, FigureError> {
    let Some((e_lo, e_hi)) = table.restitution() else {
        return Err(FigureError::Invalid {
            name: "figure",
            message: format!(
                "restitution needs a table with an e_n axis; {} is elastic (it answers e_n = 1 \
                 only): give one such as tables/dissipative-demo.h5",
                src.table
            ),
        });
    };
    let s = table.surface();
    let allowed = format!(
        "a gamma in the table's domain [{}, {}] (at most two for this figure)",
        s.gamma_min(),
        s.gamma_max()
    );
    check_family(
        "gammas",
        gammas,
        |g| g >= s.gamma_min() && g <= s.gamma_max(),
        &allowed,
    )?;
    if gammas.len() > 2 {
        return Err(FigureError::Invalid {
            name: "gammas",
            message: format!("{} values: {allowed}", gammas.len()),
        });
    }
    let allowed = format!("an e_n in the table's range [{e_lo}, {e_hi}]");
    check_family("e-n", e_ns, |e| e >= e_lo && e <= e_hi, &allowed)?;
    let top = compact(s.alpha_max());
    let base = linspace(0.0, top, SLICE_SAMPLES);
    let mut charts = Vec::new();
    for (j, &g) in gammas.iter().enumerate() {
        let mut curves = Vec::new();
        let mut extras = Vec::new();
        let damped = e_ns.iter().filter(|&&e| e < 1.0).count();
        let mut k_damped = 0;
        for &e in e_ns {
            let crit: Vec<f64> = if g > 1.0 {
                vec![alpha_c1_dissipative(g, e)]
            } else {
                Vec::new()
            };
            let mut ys = base.clone();
            ys.extend(crit.iter().map(|&a| compact(a)));
            ys.sort_by(f64::total_cmp);
            ys.dedup();
            let points = ys
                .iter()
                .map(|&y| Ok((y, table.p_e(g, alpha_at(y), e)?)))
                .collect::<Result<Vec<_>, LookupError>>()?;
            let (label, color) = if e == 1.0 {
                ("elastic (e_n = 1)".to_string(), BLACK)
            } else {
                k_damped += 1;
                (
                    format!("e_n = {}", fmt_num(e)),
                    family_color(k_damped - 1, damped),
                )
            };
            curves.push(Series {
                label,
                points,
                style: Style::Line,
                color,
                sets_range: true,
            });
            let lim = crit.first().copied().unwrap_or(0.0);
            extras.push(Series {
                label: String::new(),
                points: base
                    .iter()
                    .filter(|&&y| y <= compact(if lim > 0.0 { 1.5 * lim } else { 0.3 }))
                    .map(|&y| (y, full_slip_line(alpha_at(y), e)))
                    .collect(),
                style: Style::Dashed,
                color,
                sets_range: false,
            });
            extras.push(Series {
                label: String::new(),
                points: crit
                    .iter()
                    .map(|&a| Ok((compact(a), table.p_e(g, a, e)?)))
                    .collect::<Result<Vec<_>, LookupError>>()?,
                style: Style::Markers,
                color,
                sets_range: false,
            });
        }
        let mut series = curves;
        series.extend(extras);
        series.push(Series {
            label: "dashed: full slip P = 1 − (7/2)(1 + e_n)α; dots: α_c1(e_n)".into(),
            points: Vec::new(),
            style: Style::Dashed,
            color: (90, 90, 90),
            sets_range: false,
        });
        charts.push(Chart {
            title: format!(
                "({}) P against α at γ = {}",
                ["a", "b"][j.min(1)],
                fmt_num(g)
            ),
            x: alpha_axis(s.alpha_max(), ALPHA_LABEL),
            y: Axis {
                label: P_LABEL.into(),
                range: (-1.05, 1.05),
                ticks: Ticks::Auto,
            },
            regions: Vec::new(),
            map: None,
            contours: None,
            outlines: Vec::new(),
            series,
            scatter: None,
            color_scale: None,
            notes: Vec::new(),
            legend: LegendPlace::Right,
        });
    }
    let size = (1200, if charts.len() > 1 { 1250 } else { 700 });
    Ok(Sheet {
        title: "P(γ, α, e_n): dissipative impacts beside the elastic curve".into(),
        subtitle: format!(
            "Kelvin–Voigt law (one relaxation time, physics.md \"Dissipative impacts\"); table e_n range [{e_lo}, {e_hi}]; DEM codes damp by other laws"
        ),
        charts,
        caption: caption(table, src),
        size,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
