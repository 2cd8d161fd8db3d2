//! The curves against `α` or `γ`: `P` along lines of fixed `γ` and fixed `α` ([`slices`]) and
//! along fixed `γ` for several `e_n` ([`restitution`]), with their default families.

use oblique_lookup::{LookupError, Table};
use oblique_physics::regimes::{alpha_c1_dissipative, full_slip_line, no_slip_fit};
use oblique_plot::{Axis, Chart, LegendPlace, Series, Sheet, Style, Ticks};
use oblique_table::surface::{alpha_c1, alpha_c2};

use super::parts::{
    alpha_axis, caption, check_family, family_color, fmt_num, gamma_axis, isotropic_lines,
    ALPHA_LABEL, BLACK, P_LABEL,
};
use super::{alpha_at, compact, critical_gammas, linspace, FigureError, Source};

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
