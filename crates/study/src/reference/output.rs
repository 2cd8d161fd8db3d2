//! A computed suite as files: one CSV and one figure per test (normal tests add their force
//! history), the measured comparison where a suite publishes data, and the closed-form checks.
//!
//! CSVs start with `#` comment lines (title, source, what lies outside the elastic model, how
//! the numbers were computed, the conventions), then one header line. Every computed quantity
//! `q` is followed by `q_err`, its error bound. A value that does not exist for a case (a ratio
//! to a zero incident velocity, `P` of a pure normal impact) is an empty field.

use oblique_plot::{Figure, Legend, Panel, Series, Style};

use super::columns::{self, Quantity};
use super::eval::{self, Method, NormalOutcome, ObliqueResult, Outcome};
use super::measured::Measured;
use super::spec::{Case, Convention, NormalTest, ObliqueTest, Setup};
use super::{Check, ReferenceError, SuiteResult, TestResult};
use crate::scene::csv::num;

/// One output file.
#[derive(Debug, Clone, PartialEq)]
pub enum Content {
    /// CSV text.
    Csv(String),
    /// A figure (written as PNG).
    Figure(Figure),
}

/// A file of a suite's output: its name inside the suite's folder and its content.
pub type File = (String, Content);

const COLORS: [(u8, u8, u8); 6] = [
    (31, 90, 180),
    (230, 130, 20),
    (150, 70, 170),
    (0, 150, 150),
    (140, 90, 40),
    (40, 40, 40),
];
const GROSS_SLIP: (u8, u8, u8) = (200, 50, 40);
const RIGID: (u8, u8, u8) = (40, 150, 70);
const MEASURED: (u8, u8, u8) = (0, 0, 0);

fn cell(v: f64) -> String {
    if v.is_finite() {
        num(v)
    } else {
        String::new()
    }
}

fn comments(lines: &[String]) -> String {
    lines.iter().map(|l| format!("# {l}\n")).collect()
}

/// `(value, error)` of a quantity, empty where undefined.
fn pair_cells(v: (f64, f64)) -> [String; 2] {
    if v.0.is_finite() {
        [num(v.0), num(v.1)]
    } else {
        [String::new(), String::new()]
    }
}

fn describe_setup(s: &Setup) -> String {
    let b = s.sphere;
    let target = match s.target {
        super::spec::Target::Wall(m) if m.youngs_modulus.is_infinite() => "a rigid plane".into(),
        super::spec::Target::Wall(m) => format!(
            "a {} wall (E = {:e} Pa, nu = {})",
            m.name, m.youngs_modulus, m.poisson_ratio
        ),
        super::spec::Target::Sphere(o) => format!(
            "a {} sphere (R = {} m, E = {:e} Pa, nu = {}, rho = {} kg/m^3)",
            o.material.name,
            o.radius,
            o.material.youngs_modulus,
            o.material.poisson_ratio,
            o.material.density
        ),
    };
    let plastic = s.yield_pressure.map_or(String::new(), |y| {
        format!(
            ", limiting pressure p_y = {} Pa ({})",
            num(y.pascal),
            y.source
        )
    });
    format!(
        "{}: {} sphere R = {} m, E = {:e} Pa, nu = {}, rho = {} kg/m^3, on {target}, mu = {}{plastic}",
        s.label,
        b.material.name,
        b.radius,
        b.material.youngs_modulus,
        b.material.poisson_ratio,
        b.material.density,
        s.friction
    )
}

/// The regime column: the friction regime, `normal-impact` without slip, `unclassified` for
/// Thornton's law below the yield speed (it has no closed-form slip regimes).
fn regime_name(o: &Outcome) -> &'static str {
    match o.regime {
        Some(r) => r.name(),
        None if o.how != "normal-impact" && o.plastic.is_some() => "unclassified",
        None => "normal-impact",
    }
}

/// Measured points against the model at the same angle.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredRow {
    /// The quantity's column.
    pub column: &'static str,
    /// Incidence angle from the normal (°).
    pub angle_deg: f64,
    /// The measured value.
    pub measured: f64,
    /// The model's value and its error bound.
    pub model: (f64, f64),
    /// Where the point is published.
    pub source: &'static str,
}

/// The model at every measured angle (the test's first setup, its speed).
pub fn measured_rows(
    test: &ObliqueTest,
    measured: &Measured,
    method: &Method,
) -> Result<Vec<MeasuredRow>, ReferenceError> {
    let Some((setup, Some(first))) = test.setups.first().map(|(s, c)| (s, c.first())) else {
        return Ok(Vec::new());
    };
    let first = first.incident.sphere;
    let speed = first.v_x.hypot(first.v_z);
    let qs = columns::quantities(test.convention, setup.sphere_sphere());
    let mut rows = Vec::new();
    for series in measured.series {
        let Some(q) = qs.iter().find(|q| q.name == series.column) else {
            continue;
        };
        for &(angle, value) in series.points {
            let t = angle.to_radians();
            let case = Case {
                x: angle,
                incident: oblique_lookup::rebound::Incident {
                    sphere: oblique_lookup::rebound::State {
                        v_x: speed * t.sin(),
                        v_z: speed * t.cos(),
                        omega: 0.0,
                    },
                    other: Default::default(),
                },
            };
            let o = eval::outcome_e(setup, &case, test.e_n, method)?;
            rows.push(MeasuredRow {
                column: series.column,
                angle_deg: angle,
                measured: value,
                model: columns::value(q, setup, &o),
                source: series.source,
            });
        }
    }
    Ok(rows)
}

/// RMS of model − measured per column: `(column, rms, n)`.
pub fn rms(rows: &[MeasuredRow]) -> Vec<(&'static str, f64, usize)> {
    let mut out: Vec<(&'static str, f64, usize)> = Vec::new();
    for r in rows {
        let d2 = (r.model.0 - r.measured).powi(2);
        match out.iter_mut().find(|(c, _, _)| *c == r.column) {
            Some(e) => {
                e.1 += d2;
                e.2 += 1;
            }
            None => out.push((r.column, d2, 1)),
        }
    }
    for e in &mut out {
        e.1 = (e.1 / e.2 as f64).sqrt();
    }
    out
}

fn oblique_csv(test: &ObliqueTest, res: &ObliqueResult, method: &str) -> String {
    let sphere_sphere = res.setups.iter().any(|(s, _)| s.sphere_sphere());
    let qs = columns::quantities(test.convention, sphere_sphere);
    let mut head = vec![
        test.title.to_string(),
        format!("source: {}", test.source),
        format!("model: {}", test.elastic_note),
        format!("computed: {method}"),
    ];
    for (s, _) in &res.setups {
        head.push(describe_setup(s));
    }
    head.push(match test.convention {
        Convention::Mfix => "conventions (MFIX's): angles in degrees from the normal; \
            rebound_angle_deg = atan(|v'_t|/v'_n) of the centre, e_t = |v'_t|/|v_t|, \
            omega_abs_rad_s = |omega'|; NAME_err is the error bound of NAME"
            .into(),
        _ => "conventions: angles in degrees from the normal; omega signed so that sphere 1's \
            contact point moves at v_x + R omega (physics.md); NAME_err is the error bound of \
            NAME"
            .into(),
    });
    let plastic = test.plastic();
    if plastic {
        head.push(
            "elastic-plastic columns: e_n of the exact normal motion (its error bound e_n_err: \
             the rounding, checked against Thornton's closed form in closed_form_checks.csv), \
             p_y_pa the limiting pressure (Pa), v_y_m_s the yield speed V_y = \
             sqrt(pi^5/30 p_y^5 R*^3/(E*^4 m*)) (Thornton 1997), v_over_v_y = V/V_y with V \
             the normal approach speed (inputs and closed forms of them: exact to the \
             rounding); regime = unclassified: Thornton's law has no closed-form slip regimes"
                .into(),
        );
    }
    let mut text = comments(&head);
    let mut header = vec![
        "material".to_string(),
        test.x_name.to_string(),
        "gamma".into(),
        "alpha".into(),
        "regime".into(),
        "method".into(),
    ];
    for q in &qs {
        header.push(q.name.into());
        header.push(format!("{}_err", q.name));
    }
    if plastic {
        header.extend([
            "e_n".into(),
            "e_n_err".into(),
            "p_y_pa".into(),
            "v_y_m_s".into(),
            "v_over_v_y".into(),
        ]);
    }
    header.extend(["v_x0_m_s".into(), "v_z0_m_s".into(), "omega0_rad_s".into()]);
    if sphere_sphere {
        header.extend([
            "v_x0_2_m_s".into(),
            "v_z0_2_m_s".into(),
            "omega0_2_rad_s".into(),
        ]);
    }
    text.push_str(&header.join(","));
    text.push('\n');
    for (setup, outs) in &res.setups {
        for o in outs {
            let mut row = vec![
                setup.label.to_string(),
                num(o.case.x),
                num(o.gamma),
                num(o.alpha),
                regime_name(o).to_string(),
                o.how.to_string(),
            ];
            for q in &qs {
                row.extend(pair_cells(columns::value(q, setup, o)));
            }
            if plastic {
                let p = o.plastic;
                row.extend([
                    num(o.e_n),
                    num(super::checks::restitution_rounding(o.e_n)),
                    p.map_or(String::new(), |p| num(p.yield_pressure)),
                    p.map_or(String::new(), |p| num(p.yield_speed)),
                    p.map_or(String::new(), |p| num(p.speed_ratio)),
                ]);
            }
            let (a, b) = (o.case.incident.sphere, o.case.incident.other);
            row.extend([num(a.v_x), num(a.v_z), num(a.omega)]);
            if sphere_sphere {
                row.extend([num(b.v_x), num(b.v_z), num(b.omega)]);
            }
            text.push_str(&row.join(","));
            text.push('\n');
        }
    }
    text
}

fn measured_csv(test: &ObliqueTest, m: &Measured, rows: &[MeasuredRow]) -> String {
    let mut text = comments(&[
        format!("{}: measured points against the model", test.title),
        format!("experiment: {}", m.experiment),
        format!(
            "model: the test's first setup ({}) at each measured angle",
            test.setups.first().map_or("", |(s, _)| s.label)
        ),
    ]);
    text.push_str("quantity,angle_deg,measured,model,model_err,model_minus_measured,source\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{},{},{},{},{}\n",
            r.column,
            num(r.angle_deg),
            num(r.measured),
            cell(r.model.0),
            cell(r.model.1),
            cell(r.model.0 - r.measured),
            r.source
        ));
    }
    text
}

fn normal_csv(test: &NormalTest, outs: &[NormalOutcome], method: &str) -> String {
    let mut head = vec![
        test.title.to_string(),
        format!("source: {}", test.source),
        format!("model: {}", test.elastic_note),
        format!(
            "computed: Hertz's closed form (exact for the model), and the time-resolved normal \
             motion ({}); NAME_err is the change of the simulated value from half the time steps",
            if method.starts_with("direct") {
                "direct simulation"
            } else {
                "RK4 on 4096 steps per contact"
            }
        ),
    ];
    for o in outs {
        head.push(describe_setup(&o.setup));
    }
    let mut text = comments(&head);
    text.push_str(
        "material,v_rel_m_s,e_star_pa,r_star_m,m_star_kg,\
         contact_time_s,max_overlap_m,peak_force_n,\
         contact_time_sim_s,contact_time_sim_err,max_overlap_sim_m,max_overlap_sim_err,\
         peak_force_sim_n,peak_force_sim_err\n",
    );
    for o in outs {
        let cells = [
            o.setup.label.to_string(),
            num(o.approach_speed),
            num(o.effective.0),
            num(o.effective.1),
            num(o.effective.2),
            num(o.hertz.contact_time),
            num(o.hertz.max_overlap),
            num(o.hertz.peak_force),
            num(o.simulated.contact_time),
            num(o.simulated_error.contact_time),
            num(o.simulated.max_overlap),
            num(o.simulated_error.max_overlap),
            num(o.simulated.peak_force),
            num(o.simulated_error.peak_force),
        ];
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    text
}

fn history_csv(test: &NormalTest, outs: &[NormalOutcome]) -> String {
    let mut text = comments(&[
        format!("{}: force history", test.title),
        "time-resolved Hertz normal motion (RK4, 4096 steps per contact, every 32nd node); \
         force_err_n is the change from half the steps"
            .into(),
    ]);
    text.push_str("material,time_s,overlap_m,force_n,force_err_n\n");
    for o in outs {
        for &(t, d, f, e) in &o.history {
            text.push_str(&format!(
                "{},{},{},{},{}\n",
                o.setup.label,
                num(t),
                num(d),
                num(f),
                num(e)
            ));
        }
    }
    text
}

/// Every test's bodies, materials and friction, one line per setup (SI units; `target` is
/// `wall` or `sphere`; a rigid wall has `E2_pa = inf`; `p_y_pa` is the limiting pressure of an
/// elastic–plastic test, empty otherwise).
fn setups_csv(res: &SuiteResult) -> String {
    let mut text = comments(&[
        "the bodies of every test: solid spheres (I = 0.4 m R^2); SI units".into(),
        "target = wall: a fixed half-space of E2_pa, nu2 (inf: rigid); target = sphere: a free \
         sphere of R2_m, rho2, E2_pa, nu2"
            .into(),
        "p_y_pa: the limiting contact pressure of Thornton's elastic-perfectly plastic law \
         (empty: elastic or Kelvin-Voigt)"
            .into(),
    ]);
    text.push_str(
        "test,material,R1_m,rho1_kg_m3,E1_pa,nu1,target,R2_m,rho2_kg_m3,E2_pa,nu2,mu,p_y_pa\n",
    );
    let mut line = |id: &str, s: &Setup| {
        let m1 = s.sphere.material;
        let (kind, r2, m2) = match s.target {
            super::spec::Target::Wall(m) => ("wall", f64::NAN, m),
            super::spec::Target::Sphere(b) => ("sphere", b.radius, b.material),
        };
        text.push_str(&format!(
            "{id},{},{},{},{},{},{kind},{},{},{},{},{},{}\n",
            s.label,
            num(s.sphere.radius),
            num(m1.density),
            num(m1.youngs_modulus),
            num(m1.poisson_ratio),
            cell(r2),
            cell(m2.density),
            num(m2.youngs_modulus),
            num(m2.poisson_ratio),
            num(s.friction),
            s.yield_pressure.map_or(String::new(), |y| num(y.pascal))
        ));
    };
    for t in &res.tests {
        match t {
            TestResult::Normal(test, outs) => outs.iter().for_each(|o| line(test.id, &o.setup)),
            TestResult::Oblique(test, r) => r.setups.iter().for_each(|(s, _)| line(test.id, s)),
        }
    }
    text
}

fn checks_csv(checks: &[Check]) -> String {
    let mut text = comments(&[
        "closed-form checks: each closed form beside the computed value".into(),
        "exact = false: a published fit, shown for comparison (bound: its accuracy)".into(),
    ]);
    text.push_str("test,check,closed_form,computed,difference,bound,exact,holds\n");
    for c in checks {
        text.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            c.test,
            c.name,
            num(c.closed_form),
            num(c.computed),
            num(c.difference()),
            num(c.bound),
            c.exact,
            c.holds()
        ));
    }
    text
}

fn series(label: String, points: Vec<(f64, f64)>, style: Style, color: (u8, u8, u8)) -> Series {
    Series {
        label,
        points,
        style,
        color,
        sets_range: !matches!(style, Style::Dashed | Style::Dotted),
    }
}

/// The figure's x of an outcome: the convention's plotting variable, or the swept value.
fn figure_x(conv: Convention, setup: &Setup, o: &Outcome) -> f64 {
    match columns::figure_x(conv) {
        Some(xq) => columns::value(&xq, setup, o).0,
        None => o.case.x,
    }
}

fn curve(
    q: &Quantity,
    conv: Convention,
    setup: &Setup,
    outs: &[Outcome],
    p: impl Fn(&Outcome) -> Option<f64>,
) -> Vec<(f64, f64)> {
    outs.iter()
        .map(|o| {
            let y = match p(o) {
                Some(p) => columns::at_p(q, setup, o, p),
                None => columns::value(q, setup, o).0,
            };
            (figure_x(conv, setup, o), y)
        })
        .collect()
}

fn oblique_figure(
    test: &ObliqueTest,
    res: &ObliqueResult,
    measured: &[MeasuredRow],
    command: &str,
    method: &str,
) -> Figure {
    let sphere_sphere = res.setups.iter().any(|(s, _)| s.sphere_sphere());
    let qs = columns::quantities(test.convention, sphere_sphere);
    let n = columns::plotted(test.convention);
    let x_is_angle = test.x_name == "angle_deg";
    let panels = qs
        .iter()
        .take(n)
        .enumerate()
        .map(|(k, q)| {
            let mut s = Vec::new();
            for (i, (setup, outs)) in res.setups.iter().enumerate() {
                s.push(series(
                    setup.label.to_string(),
                    curve(q, test.convention, setup, outs, |_| None),
                    Style::LineMarkers,
                    COLORS[i % COLORS.len()],
                ));
            }
            if let (true, Some((setup, outs))) = (
                test.convention != Convention::ChungOoiNoSlip,
                res.setups.first(),
            ) {
                // The full-slip line at the test's e_n (1 − 7α when elastic).
                let line = |o: &Outcome| {
                    if o.e_n == 1.0 {
                        1.0 - 7.0 * o.alpha
                    } else {
                        oblique_physics::regimes::full_slip_line(o.alpha, o.e_n)
                    }
                };
                let gross = |o: &Outcome| o.alpha.is_finite().then(|| line(o));
                let (gross_label, rigid_label) = if test.e_n == 1.0 && !test.plastic() {
                    (
                        "gross slip, P = 1 − 7α".to_string(),
                        "rigid body, P = max(1 − 7α, 0)".to_string(),
                    )
                } else {
                    (
                        "gross slip, P = 1 − 3.5(1 + e_n)α".to_string(),
                        "rigid body, P = max(1 − 3.5(1 + e_n)α, 0)".to_string(),
                    )
                };
                s.push(series(
                    gross_label,
                    curve(q, test.convention, setup, outs, gross),
                    Style::Dashed,
                    GROSS_SLIP,
                ));
                s.push(series(
                    rigid_label,
                    curve(q, test.convention, setup, outs, |o| {
                        o.alpha.is_finite().then(|| line(o).max(0.0))
                    }),
                    Style::Dotted,
                    RIGID,
                ));
            }
            let pts: Vec<(f64, f64)> = measured
                .iter()
                .filter(|r| r.column == q.name && x_is_angle)
                .map(|r| (r.angle_deg, r.measured))
                .collect();
            if !pts.is_empty() {
                s.push(series(
                    "measured (Kharaz et al. 2001)".into(),
                    pts,
                    Style::Markers,
                    MEASURED,
                ));
            }
            Panel {
                y_label: q.label.to_string(),
                series: s,
                vlines: Vec::new(),
                y_range: None,
                legend: match (test.convention, k) {
                    (Convention::Thornton, 0) => Legend::UpperLeft,
                    (Convention::Thornton, _) => Legend::UpperRight,
                    _ => Legend::LowerRight,
                },
            }
        })
        .collect();
    let caption = vec![
        format!("model: {}", test.elastic_note),
        format!("computed: {method}"),
        format!("$ {command}"),
    ];
    Figure {
        title: test.title.to_string(),
        subtitle: test.source.split(';').next().unwrap_or("").to_string(),
        x_label: columns::figure_x(test.convention)
            .map_or(test.x_label, |q| q.label)
            .to_string(),
        panels,
        caption,
        size: (900, 300 + 260 * n as u32),
    }
}

fn normal_figure(test: &NormalTest, outs: &[NormalOutcome], command: &str) -> Figure {
    let force = outs
        .iter()
        .enumerate()
        .map(|(i, o)| {
            series(
                format!(
                    "{}: t_c = {:.4} µs, F_max = {:.4} kN",
                    o.setup.label,
                    o.hertz.contact_time * 1e6,
                    o.hertz.peak_force * 1e-3
                ),
                o.history.iter().map(|h| (h.0 * 1e6, h.2 * 1e-3)).collect(),
                Style::Line,
                COLORS[i % COLORS.len()],
            )
        })
        .collect();
    let overlap = outs
        .iter()
        .enumerate()
        .map(|(i, o)| {
            series(
                format!(
                    "{}: δ_max = {:.4} µm",
                    o.setup.label,
                    o.hertz.max_overlap * 1e6
                ),
                o.history.iter().map(|h| (h.0 * 1e6, h.1 * 1e6)).collect(),
                Style::Line,
                COLORS[i % COLORS.len()],
            )
        })
        .collect();
    Figure {
        title: test.title.to_string(),
        subtitle: test.elastic_note.to_string(),
        x_label: "time t (µs)".into(),
        panels: vec![
            Panel {
                y_label: "normal force F (kN)".into(),
                series: force,
                vlines: Vec::new(),
                y_range: None,
                legend: Legend::LowerRight,
            },
            Panel {
                y_label: "overlap δ (µm)".into(),
                series: overlap,
                vlines: Vec::new(),
                y_range: None,
                legend: Legend::LowerRight,
            },
        ],
        caption: vec![format!("$ {command}")],
        size: (900, 820),
    }
}

/// The files of a computed suite (names relative to the suite's folder). `command` is the
/// command line, for the figures' captions.
pub fn files(res: &SuiteResult, command: &str) -> Vec<File> {
    let measured = &res.measured;
    let mut out = Vec::new();
    for t in &res.tests {
        match t {
            TestResult::Normal(test, outs) => {
                out.push((
                    format!("{}.csv", test.id),
                    Content::Csv(normal_csv(test, outs, &res.method)),
                ));
                out.push((
                    format!("{}_force_history.csv", test.id),
                    Content::Csv(history_csv(test, outs)),
                ));
                out.push((
                    format!("{}.png", test.id),
                    Content::Figure(normal_figure(test, outs, command)),
                ));
            }
            TestResult::Oblique(test, r) => {
                let rows = measured
                    .iter()
                    .find(|(id, _)| *id == test.id)
                    .map(|(_, r)| r.as_slice())
                    .unwrap_or(&[]);
                out.push((
                    format!("{}.csv", test.id),
                    Content::Csv(oblique_csv(test, r, &res.method)),
                ));
                if let (Some(m), false) = (test.measured, rows.is_empty()) {
                    out.push((
                        format!("{}_measured.csv", test.id),
                        Content::Csv(measured_csv(test, m, rows)),
                    ));
                }
                out.push((
                    format!("{}.png", test.id),
                    Content::Figure(oblique_figure(test, r, rows, command, &res.method)),
                ));
            }
        }
    }
    out.push(("setups.csv".into(), Content::Csv(setups_csv(res))));
    out.push((
        "closed_form_checks.csv".into(),
        Content::Csv(checks_csv(&res.checks)),
    ));
    out
}
