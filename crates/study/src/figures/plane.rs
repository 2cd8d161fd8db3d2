//! The maps of the `(γ, α)` plane: the colour map of `P` ([`surface`]), the regime diagram
//! ([`regimes`]) and the held-out checks over the quadtree leaves ([`quality`]).

use oblique_lookup::Table;
use oblique_plot::{
    Chart, ColorScale, Colormap, Contours, Grid, Legend, LegendPlace, Note, Region, Scale, Scatter,
    Sheet,
};
use oblique_table::surface::{alpha_c1, alpha_c2, linear_limit, Patch};

use super::parts::{
    alpha_axis, caption, critical_curves, fmt_num, fold_curve, gamma_axis, isotropic_lines,
    ALPHA_LABEL, BLACK, P_LABEL,
};
use super::{alpha_at, compact, linspace, FigureError, Source};

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

/// Outline of every leaf of a patch in `(γ, α/(1+α))` (following the `split` masks of a tree
/// whose cells halve only some axes): bottom, right, top and left edge, the
/// edges of constant patch coordinate `c` (`c'` of a warp; curves in this plane) sampled at 64 points per patch
/// width, at least 5 per leaf.
pub fn leaf_outlines(patch: &Patch, alpha_max: f64) -> Vec<Vec<(f64, f64)>> {
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
    let (bg, bc) = (patch.blocks_gamma() as f64, patch.blocks_coord() as f64);
    for (pos, depth) in patch.leaf_boxes() {
        // The leaf's box in patch units: root cells over 2^depth along each axis.
        let (sg, sc) = (
            bg * f64::from(depth[0].min(1000) as i32).exp2(),
            bc * f64::from(depth[1].min(1000) as i32).exp2(),
        );
        let (x0, hx, c0, hc) = (pos[0] / sg, 1.0 / sg, pos[1] / sc, 1.0 / sc);
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
