//! The plot of a scene: `e_t` (or `P` where `e_t` is undefined) and `ω` against the swept
//! quantity, with the model, the full-slip approximation, the rolling solution, measured
//! points and the regime boundaries.

use super::eval::{Evaluation, Row};
use super::spec::{CaseKind, Dissipation, Scene, SceneTarget};
use oblique_plot::{Figure, Legend, Panel, Series, Style};

const MODEL: (u8, u8, u8) = (31, 90, 180);
const CLOSED: (u8, u8, u8) = (200, 60, 40);
const ROLLING: (u8, u8, u8) = (40, 150, 70);
const MEASURED: (u8, u8, u8) = (0, 0, 0);

/// x positions where `α` crosses `α_c` between neighbouring rows (interpolated in `1/α`,
/// which is linear in `tan θ` for an angle sweep without spin).
fn crossings(rows: &[Row], alpha_c: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if !(alpha_c.is_finite() && alpha_c > 0.0) {
        return out;
    }
    for w in rows.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (ia, ib, ic) = (1.0 / a.alpha, 1.0 / b.alpha, 1.0 / alpha_c);
        if (ia - ic) * (ib - ic) < 0.0 {
            out.push(a.x + (b.x - a.x) * (ic - ia) / (ib - ia));
        }
    }
    out
}

fn series(
    label: &str,
    rows: &[Row],
    style: Style,
    color: (u8, u8, u8),
    sets_range: bool,
    f: impl Fn(&Row) -> Option<f64>,
) -> Series {
    Series {
        label: label.to_string(),
        points: rows
            .iter()
            .map(|r| (r.x, f(r).unwrap_or(f64::NAN)))
            .collect(),
        style,
        color,
        sets_range,
    }
}

/// Build the figure of an evaluated scene. `command` is the command line that produced it (for
/// the caption).
pub fn figure(scene: &Scene, ev: &Evaluation, command: &str) -> Figure {
    let rows = &ev.rows;
    let use_e_t = rows.iter().any(|r| r.model.e_t.is_finite());
    let wall = matches!(scene.target, SceneTarget::Wall { .. });
    let (top_label, top): (&str, fn(&Row) -> f64) = if use_e_t {
        (
            if wall {
                "tangential restitution e_t = v_x/v_x0"
            } else {
                "e_t of the relative centre velocity"
            },
            |r| r.model.e_t,
        )
    } else {
        ("P = u_after/u_before", |r| r.p)
    };
    let top_closed: fn(&Row) -> Option<f64> = if use_e_t {
        |r| r.closed_form.map(|c| c.e_t)
    } else {
        |r| r.closed_form.map(|c| c.p)
    };
    let top_rolling: fn(&Row) -> Option<f64> = if use_e_t {
        |r| Some(r.rolling.e_t)
    } else {
        |_| Some(0.0)
    };
    let simple = wall
        && scene.cases.kind != CaseKind::Spin
        && scene.cases.omega0 == 0.0
        && (scene.sphere.kappa - 0.4).abs() < 1e-12;
    let closed_label = if ev.dissipative {
        "full slip throughout: P = 1 − (7/2)(1 + e_n)α"
    } else if simple && use_e_t {
        "full slip: e_t = 1 − 2μ v_z0/v_x0 (seed eq. 35)"
    } else {
        "full slip throughout: P = 1 − 7α"
    };
    let model_label = "MDR model";
    let rolling_label = "rolling: P = 0";
    let mut vlines = Vec::new();
    if ev.gamma > 1.0 {
        vlines.extend(
            crossings(rows, ev.alpha_c1)
                .into_iter()
                .map(|x| (x, "α_c1".to_string())),
        );
    }
    vlines.extend(
        crossings(rows, ev.alpha_c2)
            .into_iter()
            .map(|x| (x, "α_c2".to_string())),
    );
    let measured_label = scene
        .measured
        .as_ref()
        .map(|m| format!("measured ({})", shorten(&m.source, 40)))
        .unwrap_or_default();
    let mut top_panel = Panel {
        y_label: top_label.to_string(),
        series: vec![
            series(model_label, rows, Style::LineMarkers, MODEL, true, |r| {
                Some(top(r))
            }),
            series(
                rolling_label,
                rows,
                Style::Dotted,
                ROLLING,
                false,
                top_rolling,
            ),
            series(closed_label, rows, Style::Dashed, CLOSED, false, top_closed),
        ],
        vlines: vlines.clone(),
        y_range: None,
        legend: Legend::LowerRight,
    };
    let mut omega_panel = Panel {
        y_label: if wall {
            "spin after the impact ω (rad/s)"
        } else {
            "spin of sphere 1 after the impact ω (rad/s)"
        }
        .to_string(),
        series: vec![
            series(model_label, rows, Style::LineMarkers, MODEL, true, |r| {
                Some(r.model.sphere.omega)
            }),
            series(rolling_label, rows, Style::Dotted, ROLLING, false, |r| {
                Some(r.rolling.sphere.omega)
            }),
            series(closed_label, rows, Style::Dashed, CLOSED, false, |r| {
                r.closed_form.map(|c| c.sphere.omega)
            }),
        ],
        vlines,
        y_range: None,
        legend: Legend::LowerRight,
    };
    if scene.measured.is_some() {
        let meas = |f: fn(&super::MeasuredPoint) -> Option<f64>| {
            series(
                &measured_label,
                rows,
                Style::Markers,
                MEASURED,
                true,
                move |r| r.measured.as_ref().and_then(f),
            )
        };
        if use_e_t {
            top_panel.series.push(meas(|m| m.e_t));
        }
        omega_panel.series.push(meas(|m| m.omega));
    }
    let target = match &scene.target {
        SceneTarget::Wall { material } => format!("{} wall", material.describe()),
        SceneTarget::Sphere { body, material, .. } => format!(
            "{} sphere R = {} mm",
            material.describe(),
            fmt_g(body.radius * 1e3)
        ),
    };
    let title = format!(
        "{}: γ = {:.4}, μ = {}",
        scene.name, ev.gamma, scene.friction
    );
    let subtitle = format!(
        "{} sphere R = {} mm on {}",
        scene.sphere_material.describe(),
        fmt_g(scene.sphere.radius * 1e3),
        target
    );
    let mut caption = vec![
        format!(
            "scene file: {}    command: {}",
            scene.path.display(),
            command
        ),
        format!(
            "P: {}; {}; α_c1 = {:.4}, α_c2 = {:.4}",
            ev.source,
            match scene.cases.kind {
                CaseKind::Angles => format!(
                    "|v0| = {} m/s, ω0 = {} rad/s",
                    scene.cases.speed, scene.cases.omega0
                ),
                CaseKind::TangentialSpeed => format!(
                    "v_z0 = {} m/s, ω0 = {} rad/s",
                    scene.cases.speed, scene.cases.omega0
                ),
                CaseKind::Spin => format!(
                    "v_z0 = {} m/s, v_x0 = {} m/s",
                    scene.cases.speed, scene.cases.tangential_speed
                ),
            },
            ev.alpha_c1,
            ev.alpha_c2
        ),
    ];
    if let Some(line) = dissipation_caption(scene, ev) {
        caption.push(line);
    }
    if let Some(m) = &scene.measured {
        caption.push(format!("measured data: {}", shorten(&m.source, 150)));
    }
    Figure {
        title,
        subtitle,
        x_label: scene.cases.kind.x_label().to_string(),
        panels: vec![top_panel, omega_panel],
        caption,
        size: (1000, 1100),
    }
}

fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        format!("{}…", s.chars().take(n).collect::<String>())
    }
}

/// A short number: up to 4 significant digits, no trailing zeros.
fn fmt_g(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// The caption line of a dissipative scene: its `e_n` (range) and the law.
fn dissipation_caption(scene: &Scene, ev: &Evaluation) -> Option<String> {
    let (lo, hi) = ev.e_n_range()?;
    match scene.dissipation {
        Dissipation::Elastic => None,
        Dissipation::Restitution(e) => Some(format!("normal restitution e_n = {e} (Kelvin–Voigt law)")),
        Dissipation::YieldPressure(p) => Some(format!(
            "Thornton limiting pressure p_y = {p:e} Pa: e_n = {lo:.4} .. {hi:.4} from each case's impact speed"
        )),
        Dissipation::RelaxationTime(tau) => Some(format!(
            "Kelvin–Voigt relaxation time τ = {tau:e} s: e_n = {lo:.4} .. {hi:.4} from each case's impact speed"
        )),
    }
}
