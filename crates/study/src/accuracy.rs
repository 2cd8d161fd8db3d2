//! The accuracy study: error against cost of each scheme, and of the presets.
//!
//! For a fixed set of `(γ, α)` points spanning the regimes, every scheme is run over a ladder
//! of resolutions; each result is compared with a reference computed at a much finer
//! resolution (Richardson-extrapolated accurate scheme), and each run is timed (thread CPU
//! time where available, see [`oblique_clock::thread_cpu_time`]). The CLI (`sweep accuracy`) writes the rows as CSV
//! and draws error against time per impact on log–log axes. No file I/O here.

use serde::Serialize;

use oblique_physics::regimes::{alpha_c1, alpha_c2};
use oblique_plot::{Figure, Legend, Panel, Series, Style};
use oblique_solver::impact::{base_resolution, dimensionless_normal};
use oblique_solver::{Accuracy, Law, PhysicsError, Preset, Request, Resolution, Scheme};

/// One point of the study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StudyPoint {
    /// Short label (regime and position).
    pub label: &'static str,
    /// `γ`.
    pub gamma: f64,
    /// `α` (`∞` allowed).
    pub alpha: f64,
}

/// The fixed set of points: full slip, partial slip near `α_c1` and `α_c2`, stick, `α = ∞`,
/// small and large `γ`.
pub fn study_points() -> Vec<StudyPoint> {
    let g = 1.754;
    let (c1, c2) = (alpha_c1(g), alpha_c2(g));
    let big = 3.5;
    vec![
        StudyPoint {
            label: "full slip (1.754, 0.5 a_c1)",
            gamma: g,
            alpha: 0.5 * c1,
        },
        StudyPoint {
            label: "partial, near a_c1 (1.754, 1.1 a_c1)",
            gamma: g,
            alpha: 1.1 * c1,
        },
        StudyPoint {
            label: "partial, near a_c2 (1.754, 0.95 a_c2)",
            gamma: g,
            alpha: 0.95 * c2,
        },
        StudyPoint {
            label: "stick (1.754, 1.5 a_c2)",
            gamma: g,
            alpha: 1.5 * c2,
        },
        StudyPoint {
            label: "no slip (1.754, inf)",
            gamma: g,
            alpha: f64::INFINITY,
        },
        StudyPoint {
            label: "small gamma, line end (0.5, 1.05 a_c2)",
            gamma: 0.5,
            alpha: 1.05 * alpha_c2(0.5),
        },
        StudyPoint {
            label: "small gamma, no slip (0.1, inf)",
            gamma: 0.1,
            alpha: f64::INFINITY,
        },
        StudyPoint {
            label: "large gamma, partial (3.5, mid)",
            gamma: big,
            alpha: 0.5 * (alpha_c1(big) + alpha_c2(big)),
        },
        StudyPoint {
            label: "large gamma, no slip (3.5, inf)",
            gamma: big,
            alpha: f64::INFINITY,
        },
    ]
}

/// The reference value of a point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reference {
    /// `P`.
    pub p: f64,
    /// Its error estimate (0 for a closed form).
    pub error_estimate: f64,
    /// Finest resolution simulated (zero for a closed form).
    pub resolution: Resolution,
}

/// Steps of the finest reference level (springs = steps).
pub const REFERENCE_STEPS: usize = 1 << 15;

/// Reference for a point: the closed form where it is exact (full slip), otherwise the accurate
/// scheme at `2^12, 2^13, 2^14, 2^15` steps (one spring per step), Richardson-extrapolated
/// (`R_k = P_k + (P_k − P_{k−1})/3`), with the estimate `max(|R_k − R_{k−1}|, 0.1 |P_k − P_{k−1}|)`
/// of the solver itself.
///
/// For `e_n < 1` the closed forms are those of the law (`law`, or Kelvin–Voigt where none is
/// named) and the levels run the continuum row (the only row of the dissipative laws).
pub fn reference(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    law: Option<Law>,
    steps: usize,
) -> Result<Reference, PhysicsError> {
    let law = law.unwrap_or_else(|| Law::for_restitution(e_n));
    let closed = law.closed_form(gamma, alpha, e_n);
    if let Some(p) = closed {
        return Ok(Reference {
            p,
            error_estimate: 0.0,
            resolution: Resolution {
                springs: 0,
                steps: 0,
            },
        });
    }
    let levels: Vec<usize> = (0..4).map(|k| steps >> (3 - k)).collect();
    let mut values = Vec::new();
    for &s in &levels {
        let springs = if e_n < 1.0 { 0 } else { s };
        values.push(
            Request::new(gamma, alpha)
                .e_n(e_n)
                .law(law)
                .simulate(Resolution { springs, steps: s })?,
        );
    }
    let rich = |k: usize| values[k] + (values[k] - values[k - 1]) / 3.0;
    let p = rich(3);
    let est = (p - rich(2)).abs().max(0.1 * (values[3] - values[2]).abs());
    Ok(Reference {
        p,
        error_estimate: est,
        resolution: Resolution {
            springs: if e_n < 1.0 { 0 } else { steps },
            steps,
        },
    })
}

/// Time per call of `f` (seconds of thread CPU time, or elapsed time where that is not
/// available): one warm-up call, then repeated until at least `min_total` seconds have passed
/// (at most 1000 calls). Returns the last value, the time per call and the number of calls.
pub fn time_per_call<T>(
    min_total: f64,
    mut f: impl FnMut() -> Result<T, PhysicsError>,
) -> Result<(T, f64, usize), PhysicsError> {
    f()?;
    let clock = || oblique_clock::Clock::ThreadCpu.now().as_secs_f64();
    let start = clock();
    let mut n = 0;
    loop {
        let v = f()?;
        n += 1;
        let spent = clock() - start;
        if spent >= min_total || n >= 1000 {
            return Ok((v, spent / n as f64, n));
        }
    }
}

/// What one row of the study measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Point label.
    pub point: &'static str,
    /// `γ`.
    pub gamma: f64,
    /// `α`.
    pub alpha: f64,
    /// `euler` or `accurate` at a fixed resolution (for `accurate`, a level of the default
    /// refinement: [`fixed_ladder`]), or `accurate-tol` (automatic refinement to `tol`, the way
    /// the solver is used).
    pub series: &'static str,
    /// Tolerance asked for (`accurate-tol` only).
    pub tol: Option<f64>,
    /// Springs of the (finest) run.
    pub springs: usize,
    /// Steps of the (finest) run.
    pub steps: usize,
    /// `P` computed.
    pub p: f64,
    /// `P − P_ref`.
    pub error: f64,
    /// The solver's own error estimate (`accurate-tol` only).
    pub error_estimate: Option<f64>,
    /// Reference error estimate (the floor below which `error` is not meaningful).
    pub reference_error: f64,
    /// CPU time per impact (s), warm trajectory cache.
    pub time_s: f64,
    /// Calls timed.
    pub calls: usize,
}

/// Settings of a study run.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Finest steps of the accurate fixed ladder ([`fixed_ladder`]).
    pub accurate_max_steps: usize,
    /// Euler ladder: steps from `euler_min_steps` to `euler_max_steps`, doubling.
    pub euler_min_steps: usize,
    /// Finest Euler steps.
    pub euler_max_steps: usize,
    /// Steps per spring of the Euler ladder (the time error dominates; see `docs/accuracy.md`).
    pub euler_ratio: usize,
    /// Tolerances of the automatic refinement.
    pub tolerances: Vec<f64>,
    /// Finest steps of the reference.
    pub reference_steps: usize,
    /// Minimum CPU time spent timing one row (s).
    pub min_time: f64,
    /// Normal restitution of every impact of the study (1: elastic; below, a dissipative law,
    /// whose only scheme is the accurate one: no Euler series then).
    pub e_n: f64,
    /// The law of the study below `e_n = 1` (`None`: Kelvin–Voigt, the default law there).
    pub law: Option<Law>,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            accurate_max_steps: 8192,
            euler_min_steps: 1 << 10,
            euler_max_steps: 1 << 17,
            euler_ratio: 256,
            tolerances: vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
            reference_steps: REFERENCE_STEPS,
            min_time: 0.05,
            e_n: 1.0,
            law: None,
        }
    }
}

impl Settings {
    /// A smaller study for tests and a quick look (coarser ladders, reference at 2^13 steps).
    pub fn quick() -> Self {
        Self {
            accurate_max_steps: 1024,
            euler_min_steps: 1 << 10,
            euler_max_steps: 1 << 13,
            euler_ratio: 256,
            tolerances: vec![1e-3, 1e-4, 1e-5],
            reference_steps: 1 << 13,
            min_time: 0.005,
            e_n: 1.0,
            law: None,
        }
    }
}

/// The fixed resolutions of the `accurate` series at `γ`: the levels the default refinement
/// (`Request::new(γ, α).accuracy(Accuracy::Tolerance(tol)).forced(…).solve()`) runs, from
/// [`base_resolution`] up to `max_steps` steps, doubling. Those are the continuum row
/// (`springs = 0`, exact in space) with the steps graded towards separation, so each row is
/// one level of the shipped solver, not the spring row that the study measured up to commit
/// `cd6398b` (`springs = max(steps, 64)`).
pub fn fixed_ladder(gamma: f64, max_steps: usize) -> Vec<Resolution> {
    let base = base_resolution(gamma, Scheme::Accurate);
    (0..)
        .map(|k| base.doubled(k))
        .take_while(|res| res.steps <= max_steps)
        .collect()
}

/// Run the study at one point: the reference, then every ladder.
pub fn study_point(pt: &StudyPoint, set: &Settings) -> Result<(Reference, Vec<Row>), PhysicsError> {
    let reference = reference(pt.gamma, pt.alpha, set.e_n, set.law, set.reference_steps)?;
    let mut request = Request::new(pt.gamma, pt.alpha).e_n(set.e_n);
    if let Some(law) = set.law {
        request = request.law(law);
    }
    let mut rows = Vec::new();
    let row = |series, tol, res: Resolution, p: f64, est, time_s, calls| Row {
        point: pt.label,
        gamma: pt.gamma,
        alpha: pt.alpha,
        series,
        tol,
        springs: res.springs,
        steps: res.steps,
        p,
        error: p - reference.p,
        error_estimate: est,
        reference_error: reference.error_estimate,
        time_s,
        calls,
    };
    // Accurate scheme at fixed resolutions: the levels of the default refinement.
    for res in fixed_ladder(pt.gamma, set.accurate_max_steps) {
        dimensionless_normal(res.steps);
        let (p, t, n) = time_per_call(set.min_time, || request.simulate(res))?;
        rows.push(row("accurate", None, res, p, None, t, n));
    }
    // Automatic refinement (the solver as used): every level from the base, Richardson value.
    for &tol in &set.tolerances {
        let (sol, t, n) = time_per_call(set.min_time, || {
            request
                .accuracy(Accuracy::Tolerance(tol))
                .forced(true)
                .solve()
        })?;
        rows.push(row(
            "accurate-tol",
            Some(tol),
            sol.resolution,
            sol.p,
            Some(sol.error_estimate),
            t,
            n,
        ));
    }
    // Euler at fixed resolutions, springs = steps / ratio (at least 8); elastic only.
    let mut steps = if set.e_n < 1.0 {
        usize::MAX
    } else {
        set.euler_min_steps
    };
    while steps <= set.euler_max_steps {
        let res = Resolution {
            springs: (steps / set.euler_ratio).max(8),
            steps,
        };
        let (p, t, n) = time_per_call(set.min_time, || {
            Request::new(pt.gamma, pt.alpha)
                .scheme(Scheme::Euler)
                .simulate(res)
        })?;
        rows.push(row("euler", None, res, p, None, t, n));
        steps *= 2;
    }
    Ok((reference, rows))
}

/// Time and error of a scheme at a target error, per point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reach {
    /// Point label.
    pub point: &'static str,
    /// Target error.
    pub target: f64,
    /// Accurate scheme, automatic refinement: time of the largest `tol ≤ target` whose true
    /// error is ≤ target (what asking for `tol = target` costs, when that delivers it).
    pub accurate_tol_time: Option<f64>,
    /// Accurate scheme, fixed ladder: time of the cheapest run with true error ≤ target.
    pub accurate_fixed_time: Option<f64>,
    /// Euler: fitted first-order constant `C` in `|error| ≈ C / steps` (finest two runs).
    pub euler_constant: f64,
    /// Euler: measured time of the cheapest run with true error ≤ target, if any.
    pub euler_measured_time: Option<f64>,
    /// Euler: time extrapolated along its ladder (`steps = C/target`, springs ∝ steps, so the
    /// time grows as `steps²`).
    pub euler_time: f64,
    /// Euler: lower bound, the finest run's spring count kept (time ∝ steps only; favourable
    /// to Euler, since its spatial error then stays).
    pub euler_time_lower: f64,
}

/// Where each scheme reaches `target` at one point (from that point's rows).
pub fn reach(rows: &[Row], target: f64) -> Option<Reach> {
    let first = rows.first()?;
    let ok = |r: &&Row| r.error.abs() <= target;
    let min_time = |series: &str| {
        rows.iter()
            .filter(|r| r.series == series)
            .filter(ok)
            .map(|r| r.time_s)
            .reduce(f64::min)
    };
    let euler: Vec<&Row> = rows.iter().filter(|r| r.series == "euler").collect();
    let n = euler.len();
    if n < 2 {
        return None;
    }
    let (a, b) = (euler[n - 2], euler[n - 1]);
    let constant = 0.5 * (a.error.abs() * a.steps as f64 + b.error.abs() * b.steps as f64);
    let needed = constant / target;
    let scale = needed / b.steps as f64;
    let measured = min_time("euler");
    let (euler_time, euler_time_lower) = match measured {
        Some(t) => (t, t),
        None => (b.time_s * scale * scale, b.time_s * scale),
    };
    let accurate_tol_time = rows
        .iter()
        .filter(|r| r.series == "accurate-tol" && r.tol.is_some_and(|t| t <= target))
        .filter(ok)
        .max_by(|a, b| a.tol.unwrap_or(0.0).total_cmp(&b.tol.unwrap_or(0.0)))
        .map(|r| r.time_s);
    Some(Reach {
        point: first.point,
        target,
        accurate_tol_time,
        accurate_fixed_time: min_time("accurate"),
        euler_constant: constant,
        euler_measured_time: measured,
        euler_time,
        euler_time_lower,
    })
}

/// CSV of the rows (header line first).
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "point,gamma,alpha,series,tol,springs,steps,P,error,abs_error,error_estimate,reference_error,cpu_s_per_impact,calls\n",
    );
    let opt = |v: Option<f64>| v.map(|x| format!("{x:e}")).unwrap_or_default();
    for r in rows {
        out.push_str(&format!(
            "\"{}\",{},{},{},{},{},{},{:.15},{:e},{:e},{},{:e},{:e},{}\n",
            r.point,
            r.gamma,
            if r.alpha.is_finite() {
                r.alpha.to_string()
            } else {
                "inf".into()
            },
            r.series,
            opt(r.tol),
            r.springs,
            r.steps,
            r.p,
            r.error,
            r.error.abs(),
            opt(r.error_estimate),
            r.reference_error,
            r.time_s,
            r.calls
        ));
    }
    out
}

const COLORS: [(u8, u8, u8); 9] = [
    (31, 90, 180),
    (200, 60, 40),
    (40, 150, 70),
    (150, 60, 170),
    (230, 140, 20),
    (20, 160, 170),
    (120, 120, 120),
    (170, 30, 100),
    (90, 70, 30),
];

/// The log–log figure: error against CPU time per impact; top panel the fixed ladders
/// (accurate solid with markers, Euler dashed, one colour per point), bottom panel the
/// automatic refinement at each tolerance. Errors below the reference's own estimate are drawn
/// at that floor.
pub fn figure(points: &[StudyPoint], rows: &[Row], set: &Settings, command: &str) -> Figure {
    let pts = |series: &str, label: &str| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.series == series && r.point == label)
            .map(|r| (r.time_s, r.error.abs().max(r.reference_error).max(1e-13)))
            .collect()
    };
    let mut top = Vec::new();
    let mut bottom = Vec::new();
    for (i, pt) in points.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        top.push(Series {
            label: pt.label.to_string(),
            points: pts("accurate", pt.label),
            style: Style::LineMarkers,
            color,
            sets_range: true,
        });
        top.push(Series {
            label: String::new(),
            points: pts("euler", pt.label),
            style: Style::Dashed,
            color,
            sets_range: true,
        });
        bottom.push(Series {
            label: pt.label.to_string(),
            points: pts("accurate-tol", pt.label),
            style: Style::LineMarkers,
            color,
            sets_range: true,
        });
    }
    Figure {
        title: "Error of P against CPU time per impact".into(),
        subtitle: "solid: accurate scheme (default); dashed: euler (seed scheme), same colour = same (γ, α)"
            .into(),
        x_label: "CPU time per impact (s)".into(),
        panels: vec![
            Panel {
                y_label: "|P − P_ref|, fixed resolutions".into(),
                series: top,
                legend: Legend::UpperRight,
                ..Panel::default()
            },
            Panel {
                y_label: format!(
                    "|P − P_ref|, refinement to tol {:.0e} … {:.0e}",
                    set.tolerances.first().copied().unwrap_or(f64::NAN),
                    set.tolerances.last().copied().unwrap_or(f64::NAN)
                ),
                series: bottom,
                legend: Legend::UpperRight,
                ..Panel::default()
            },
        ],
        caption: vec![
            format!("command: {command}"),
            format!(
                "reference: accurate scheme to {} steps, Richardson; errors below its estimate are drawn at that floor",
                set.reference_steps
            ),
        ],
        size: (1100, 1400),
    }
}

/// Measured error and cost of one preset over the study's points.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PresetSummary {
    /// The preset.
    pub preset: Preset,
    /// Its tolerance.
    pub tol: f64,
    /// Largest true error over the points.
    pub max_error: f64,
    /// Largest error estimate over the points.
    pub max_estimate: f64,
    /// Median CPU time per impact (s).
    pub median_time: f64,
    /// Largest CPU time per impact (s).
    pub max_time: f64,
}

/// Summarise the `accurate-tol` rows at each preset's tolerance (rows must include them).
pub fn preset_summaries(rows: &[Row]) -> Vec<PresetSummary> {
    Preset::ALL
        .into_iter()
        .filter_map(|preset| {
            let tol = preset.tolerance();
            let sel: Vec<&Row> = rows
                .iter()
                .filter(|r| r.series == "accurate-tol" && r.tol == Some(tol))
                .collect();
            if sel.is_empty() {
                return None;
            }
            let mut times: Vec<f64> = sel.iter().map(|r| r.time_s).collect();
            times.sort_by(f64::total_cmp);
            Some(PresetSummary {
                preset,
                tol,
                max_error: sel.iter().map(|r| r.error.abs()).fold(0.0, f64::max),
                max_estimate: sel
                    .iter()
                    .filter_map(|r| r.error_estimate)
                    .fold(0.0, f64::max),
                median_time: times[times.len() / 2],
                max_time: times[times.len() - 1],
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `accurate` series is the shipped solver's ladder: continuum row, and the level at
    /// which the default refinement stops is one of its rows.
    #[test]
    fn fixed_ladder_is_the_default_refinement() {
        for gamma in [0.1, 1.754, 3.5] {
            let ladder = fixed_ladder(gamma, 8192);
            assert!(ladder.len() >= 5, "{gamma}: {ladder:?}");
            assert!(ladder.iter().all(|r| r.springs == 0), "{ladder:?}");
            assert!(ladder.windows(2).all(|w| w[1].steps == 2 * w[0].steps));
            assert_eq!(ladder[0], base_resolution(gamma, Scheme::Accurate));
            assert_eq!(ladder.last().map(|r| r.steps), Some(8192));
            let alpha = 1.5 * alpha_c2(gamma);
            let sol = Request::new(gamma, alpha)
                .accuracy(Accuracy::Tolerance(1e-5))
                .forced(true)
                .solve()
                .expect("solve");
            assert!(ladder.contains(&sol.resolution), "{gamma}: {sol:?}");
        }
    }

    /// A small study at one point: every series is there, the accurate rows converge at second
    /// order against the reference, the refinement delivers its tolerance, and `reach` finds
    /// where each scheme meets 1e-4.
    #[test]
    fn small_study_at_the_stick_point() {
        let pt = study_points()[3];
        let set = Settings {
            accurate_max_steps: 512,
            euler_min_steps: 1 << 10,
            euler_max_steps: 1 << 11,
            euler_ratio: 256,
            tolerances: vec![1e-4],
            reference_steps: 1 << 11,
            min_time: 0.0,
            e_n: 1.0,
            law: None,
        };
        let (reference, rows) = study_point(&pt, &set).expect("study");
        assert!(reference.error_estimate < 1e-6, "{reference:?}");
        let fixed: Vec<&Row> = rows.iter().filter(|r| r.series == "accurate").collect();
        assert_eq!(fixed.len(), fixed_ladder(pt.gamma, 512).len());
        assert!(fixed.iter().all(|r| r.springs == 0 && r.time_s >= 0.0));
        let (coarse, fine) = (fixed[fixed.len() - 2], fixed[fixed.len() - 1]);
        assert!(
            fine.error.abs() < coarse.error.abs() / 2.5,
            "{coarse:?} {fine:?}"
        );
        let tol = rows.iter().find(|r| r.series == "accurate-tol").unwrap();
        assert!(tol.error.abs() <= 1e-4, "{tol:?}");
        assert_eq!(rows.iter().filter(|r| r.series == "euler").count(), 2);
        let reach = reach(&rows, 1e-4).expect("reach");
        assert!(reach.accurate_tol_time.is_some() && reach.accurate_fixed_time.is_some());
        assert!(
            reach.euler_constant > 0.0 && reach.euler_time > 0.0,
            "{reach:?}"
        );
    }

    /// The study of a dissipative law: its own reference, no Euler series, the refinement
    /// within its tolerance of the reference.
    #[test]
    fn small_dissipative_study() {
        let pt = study_points()[2];
        let set = Settings {
            accurate_max_steps: 512,
            tolerances: vec![1e-4, 1e-5],
            reference_steps: 1 << 12,
            min_time: 0.0,
            e_n: 0.8,
            ..Settings::quick()
        };
        let (reference, rows) = study_point(&pt, &set).expect("study");
        let elastic = oblique_solver::Request::new(pt.gamma, pt.alpha)
            .solve()
            .unwrap();
        assert!((reference.p - elastic.p).abs() > 0.01, "{reference:?}");
        assert!(rows.iter().all(|r| r.series != "euler"));
        for r in rows.iter().filter(|r| r.series == "accurate-tol") {
            assert!(r.error.abs() <= r.tol.unwrap(), "{r:?}");
        }
        // Thornton's law at the same e_n: its own reference (another P), its tolerances kept.
        let set = Settings {
            law: Some(Law::Thornton),
            ..set
        };
        let (thornton, rows) = study_point(&pt, &set).expect("study");
        assert!((thornton.p - reference.p).abs() > 1e-3, "{thornton:?}");
        for r in rows.iter().filter(|r| r.series == "accurate-tol") {
            assert!(r.error.abs() <= r.tol.unwrap(), "{r:?}");
        }
    }
}
