//! Evaluating a scene: every case to `(γ, α)`, `P`, and the rebound.

use std::time::Instant;

use oblique_lookup::rebound::{effective_moduli, Incident, Rebound};
use oblique_lookup::Table;
use rayon::prelude::*;

use super::measured::{self, MeasuredPoint};
use super::spec::{CaseKind, Dissipation, Scene, SceneTarget};
use super::SceneError;
use oblique_physics::regimes::{self, Regime};
use oblique_solver::request::dissipative_closed_form;
use oblique_solver::thornton::{self, Thornton};
use oblique_solver::units::PhysicalImpact;
use oblique_solver::{Accuracy, BodiesLaw, ContactLaw, Law, Method, Request};

/// Where `P` comes from.
#[derive(Debug, Clone, Copy)]
pub enum PSource<'a> {
    /// Simulate each case that has no closed form, at the scene's tolerance. Only the scene's
    /// points are computed, never a surface.
    Simulate,
    /// Interpolate in a table (the full-slip line stays exact).
    Table(&'a Table),
}

/// How a row's `P` was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowMethod {
    /// `u0 = 0`: a pure normal impact, nothing tangential happens (`P` undefined).
    NormalImpact,
    /// Exact closed form (full-slip line, `γ = 1` plateau); nothing simulated.
    ClosedForm,
    /// Simulated at the scene's tolerance.
    Simulated,
    /// Interpolated in the table.
    Table,
}

impl RowMethod {
    /// Name used in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            RowMethod::NormalImpact => "normal-impact",
            RowMethod::ClosedForm => "closed-form",
            RowMethod::Simulated => "simulated",
            RowMethod::Table => "table",
        }
    }
}

/// One evaluated case.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Swept value (degrees, m/s or rad/s as the scene's `cases.kind`).
    pub x: f64,
    /// Incidence angle from the normal (degrees): the swept angle for `angles` scenes, otherwise
    /// that of the relative centre velocity.
    pub angle_deg: f64,
    /// Incident state of both bodies.
    pub incident: Incident,
    /// `α = (2/7)(m*/m_t) μ v_z0/|u0|` (`∞` for `u0 = 0` or `μ = ∞`).
    pub alpha: f64,
    /// Normal restitution `e_n` of the case (1 for elastic bodies; from the impact speed when
    /// the scene gives a relaxation time or a limiting pressure).
    pub e_n: f64,
    /// The contact law of the case ([`Dissipation::law`]): `P` is that law's `P(γ, α, e_n)`.
    pub law: Law,
    /// `P` (NaN for a pure normal impact).
    pub p: f64,
    /// Error bound of `P`: the solver's estimate, the table's stated bound
    /// ([`Table::error_bound`]), or 0 for closed forms.
    pub p_error: f64,
    /// How `P` was obtained.
    pub method: RowMethod,
    /// Friction regime (`None` for a pure normal impact).
    pub regime: Option<Regime>,
    /// The rebound with the model's `P`.
    pub model: Rebound,
    /// The seed's closed-form approximation: full slip throughout, `P = 1 − 7α`
    /// (`e_t = 1 − μ(1 + e_n) v_z0/v_x0` for a solid sphere on a wall without spin;
    /// `P = 1 − (7/2)(1 + e_n)α` with the case's `e_n < 1`); `None` when `α = ∞`.
    pub closed_form: Option<Rebound>,
    /// The classical rolling solution: the contact point stops, `P = 0`.
    pub rolling: Rebound,
    /// Measured point at this `x`, if any.
    pub measured: Option<MeasuredPoint>,
    /// `false` for rows added only to compare with a measured point.
    pub in_scene: bool,
}

/// RMS difference model − measurement.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rms {
    /// RMS of `e_t` and the number of points, if any `e_t` was measured.
    pub e_t: Option<(f64, usize)>,
    /// RMS of `ω` (rad/s) and the number of points, if any `ω` was measured.
    pub omega: Option<(f64, usize)>,
}

/// A scene's result.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// `γ = √((m*/m_t) G*/E*)`.
    pub gamma: f64,
    /// `E*` (Pa).
    pub e_star: f64,
    /// `G*` (Pa).
    pub g_star: f64,
    /// Normal reduced mass `m*` (kg).
    pub normal_mass: f64,
    /// Tangential reduced mass `m_t` (kg).
    pub tangential_mass: f64,
    /// Effective radius `R*` (m).
    pub effective_radius: f64,
    /// `α_c1(γ)` (meaningful for `γ > 1`), at the scene's `e_n` when it gives a constant one.
    pub alpha_c1: f64,
    /// `α_c2(γ)`.
    pub alpha_c2: f64,
    /// The cases, sorted by `x` (scene cases and measured-only points).
    pub rows: Vec<Row>,
    /// Whether the scene names a dissipation (`e_n`, `relaxation_time` or `yield_pressure`):
    /// the CSV then has the `e_n` and `law` columns.
    pub dissipative: bool,
    /// Where `P` came from, in words.
    pub source: String,
    /// Wall time of the evaluation (s).
    pub elapsed_s: f64,
    /// RMS against the measured data, when the scene names some.
    pub rms: Option<Rms>,
}

impl Evaluation {
    /// Number of rows (of the scene's own cases) obtained by `method`.
    pub fn count(&self, method: RowMethod) -> usize {
        self.rows
            .iter()
            .filter(|r| r.in_scene && r.method == method)
            .count()
    }

    /// Number of rows (of the scene's own cases) in `regime`.
    pub fn count_regime(&self, regime: Regime) -> usize {
        self.rows
            .iter()
            .filter(|r| r.in_scene && r.regime == Some(regime))
            .count()
    }

    /// Smallest and largest finite `α` of the scene's cases (`None` if there is none).
    pub fn alpha_range(&self) -> Option<(f64, f64)> {
        self.rows
            .iter()
            .filter(|r| r.in_scene && r.alpha.is_finite())
            .map(|r| r.alpha)
            .fold(None, |acc, a| match acc {
                None => Some((a, a)),
                Some((lo, hi)) => Some((lo.min(a), hi.max(a))),
            })
    }

    /// Smallest and largest `e_n` of the scene's cases (`None` if there is none).
    pub fn e_n_range(&self) -> Option<(f64, f64)> {
        self.rows
            .iter()
            .filter(|r| r.in_scene)
            .map(|r| r.e_n)
            .fold(None, |acc, e| match acc {
                None => Some((e, e)),
                Some((lo, hi)) => Some((lo.min(e), hi.max(e))),
            })
    }

    /// Largest error bound of `P` over the rows.
    pub fn max_p_error(&self) -> f64 {
        self.rows.iter().map(|r| r.p_error).fold(0.0, f64::max)
    }
}

fn rebound(scene: &Scene, x: f64, inc: &Incident, p: f64, e_n: f64) -> Result<Rebound, SceneError> {
    scene
        .pair()
        .rebound_dissipative(inc, p, e_n)
        .map_err(|source| SceneError::Lookup {
            x_name: scene.cases.kind.x_column(),
            x,
            source: source.into(),
        })
}

fn evaluate_row(
    scene: &Scene,
    gamma: f64,
    source: PSource,
    table_error: f64,
    x: f64,
    measured: Option<MeasuredPoint>,
    in_scene: bool,
) -> Result<Row, SceneError> {
    let pair = scene.pair();
    let x_name = scene.cases.kind.x_column();
    let inc = scene.incident(x);
    let alpha = pair
        .alpha(&inc, scene.friction)
        .map_err(|source| SceneError::Lookup {
            x_name,
            x,
            source: source.into(),
        })?;
    let e_n =
        restitution(scene, &inc).map_err(|source| SceneError::Physics { x_name, x, source })?;
    let law = scene.dissipation.law(e_n);
    let u0 = pair.slip_velocity(&inc);
    let (p, p_error, method) = if u0 == 0.0 {
        (f64::NAN, 0.0, RowMethod::NormalImpact)
    } else {
        match source {
            PSource::Simulate if e_n != 1.0 => {
                let sol = Request::new(gamma, alpha)
                    .e_n(e_n)
                    .law(law)
                    .accuracy(Accuracy::Tolerance(scene.tol))
                    .solve()
                    .map_err(|source| SceneError::Physics { x_name, x, source })?;
                let method = match sol.method {
                    Method::ClosedForm => RowMethod::ClosedForm,
                    Method::Simulated => RowMethod::Simulated,
                };
                (sol.p, sol.error_estimate, method)
            }
            PSource::Table(table) if e_n != 1.0 => {
                let what = match table.restitution() {
                    None => Some("is elastic (no e_n axis: it answers e_n = 1 only)".to_string()),
                    Some((lo, hi)) if !(lo..=hi).contains(&e_n) => {
                        Some(format!("covers e_n in [{lo}, {hi}] only"))
                    }
                    Some(_) if table.provenance().law != law.name() => Some(format!(
                        "answers the {} law, the case's bodies are of the {} law",
                        table.provenance().law,
                        law.name()
                    )),
                    Some(_) => None,
                };
                if let Some(what) = what {
                    return Err(SceneError::Restitution {
                        x_name,
                        x,
                        e_n,
                        what,
                    });
                }
                let p = table
                    .p_e(gamma, alpha, e_n)
                    .map_err(|source| SceneError::Lookup { x_name, x, source })?;
                // Exact only where the table itself answers the closed form (a table of
                // Thornton's law interpolates full slip too).
                if table.surface().has_line() && exact(law, gamma, alpha, e_n) {
                    (p, 0.0, RowMethod::ClosedForm)
                } else {
                    (p, table_error, RowMethod::Table)
                }
            }
            PSource::Simulate => {
                let sol = Request::new(gamma, alpha)
                    .accuracy(Accuracy::Tolerance(scene.tol))
                    .solve()
                    .map_err(|source| SceneError::Physics { x_name, x, source })?;
                let method = match sol.method {
                    Method::ClosedForm => RowMethod::ClosedForm,
                    Method::Simulated => RowMethod::Simulated,
                };
                (sol.p, sol.error_estimate, method)
            }
            PSource::Table(table) => {
                let p = table.p(gamma, alpha).map_err(|source| SceneError::Lookup {
                    x_name,
                    x,
                    source,
                })?;
                if table.surface().has_line() && regimes::closed_form(gamma, alpha).is_some() {
                    (p, 0.0, RowMethod::ClosedForm)
                } else {
                    (p, table_error, RowMethod::Table)
                }
            }
        }
    };
    let model = rebound(scene, x, &inc, p, e_n)?;
    let closed_form = if alpha.is_finite() {
        let line = if e_n == 1.0 {
            1.0 - 7.0 * alpha
        } else {
            regimes::full_slip_line(alpha, e_n)
        };
        Some(rebound(scene, x, &inc, line, e_n)?)
    } else {
        None
    };
    let rolling = rebound(scene, x, &inc, 0.0, e_n)?;
    let angle_deg = match scene.cases.kind {
        CaseKind::Angles => x,
        _ => model.incidence_angle.to_degrees(),
    };
    Ok(Row {
        x,
        angle_deg,
        incident: inc,
        alpha,
        e_n,
        law,
        p: model.p,
        p_error,
        method,
        regime: (u0 != 0.0).then(|| {
            if e_n == 1.0 {
                Regime::of(gamma, alpha)
            } else {
                Regime::of_dissipative(gamma, alpha, e_n)
            }
        }),
        model,
        closed_form,
        rolling,
        measured,
        in_scene,
    })
}

/// Whether `P(γ, α, e_n)` of the dissipative law `law` is exact in closed form there (the
/// law's own closed forms: Thornton's at `α = 0` only, as its limits jump at the switch to
/// unloading; the Kelvin–Voigt full-slip line and `γ = 1` plateau otherwise).
fn exact(law: Law, gamma: f64, alpha: f64, e_n: f64) -> bool {
    match law {
        Law::Thornton => Thornton::closed_form(gamma, alpha, e_n).is_some(),
        _ => dissipative_closed_form(gamma, alpha, e_n).is_some(),
    }
}

/// The normal restitution of the case with incident state `inc`: 1 for elastic bodies, the
/// scene's `e_n`, or that of its relaxation time or limiting pressure at this impact's speed.
fn restitution(scene: &Scene, inc: &Incident) -> Result<f64, oblique_solver::PhysicsError> {
    let bodies = match scene.dissipation {
        Dissipation::Elastic => return Ok(1.0),
        Dissipation::Restitution(e) => return Ok(e),
        Dissipation::RelaxationTime(tau) => BodiesLaw::of_relaxation_time(tau),
        Dissipation::YieldPressure(p) => {
            BodiesLaw::Thornton(thornton::BodiesParameters { yield_pressure: p })
        }
    };
    let sphere = (scene.sphere, scene.sphere_material.elastic);
    let impact = match &scene.target {
        SceneTarget::Wall { material } => {
            PhysicalImpact::sphere_on_wall(sphere, material.elastic, inc.sphere, scene.friction)
        }
        SceneTarget::Sphere { body, material, .. } => PhysicalImpact::sphere_on_sphere(
            sphere,
            inc.sphere,
            (*body, material.elastic),
            inc.other,
            scene.friction,
        ),
    };
    Ok(impact.with_law(bodies).restitution()?.1)
}

fn rms(values: impl Iterator<Item = (f64, f64)>) -> Option<(f64, usize)> {
    let (sum, n) = values
        .filter(|(m, d)| m.is_finite() && d.is_finite())
        .fold((0.0, 0usize), |(s, n), (m, d)| (s + (m - d).powi(2), n + 1));
    (n > 0).then(|| ((sum / n as f64).sqrt(), n))
}

/// Evaluate every case of a scene (plus the measured points' positions, when it names measured
/// data). Cases are independent and run in parallel on the current rayon pool.
pub fn evaluate(scene: &Scene, source: PSource) -> Result<Evaluation, SceneError> {
    let start = Instant::now();
    let pair = scene.pair();
    let mat_a = scene.sphere_material.elastic;
    let mat_b = scene.target_material().elastic;
    let gamma = pair
        .gamma_from_materials(&mat_a, &mat_b)
        .map_err(|source| SceneError::Lookup {
            x_name: scene.cases.kind.x_column(),
            x: f64::NAN,
            source: source.into(),
        })?;
    let (e_star, g_star) = effective_moduli(&mat_a, &mat_b);
    let measured = match &scene.measured {
        Some(m) => measured::load(&m.file, scene.cases.kind)?,
        None => Vec::new(),
    };
    // Rows: the scene's cases, with measured points attached where x matches, plus one row per
    // measured point elsewhere.
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0);
    let mut jobs: Vec<(f64, Option<MeasuredPoint>, bool)> = scene
        .cases
        .values
        .iter()
        .map(|&x| (x, None, true))
        .collect();
    for m in &measured {
        match jobs
            .iter_mut()
            .find(|(x, mp, _)| mp.is_none() && same(*x, m.x))
        {
            Some(job) => job.1 = Some(*m),
            None => jobs.push((m.x, Some(*m), false)),
        }
    }
    jobs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let table_error = match source {
        PSource::Table(t) => t.error_bound(),
        PSource::Simulate => 0.0,
    };
    let rows = jobs
        .into_par_iter()
        .map(|(x, m, in_scene)| evaluate_row(scene, gamma, source, table_error, x, m, in_scene))
        .collect::<Vec<_>>()
        // The first failing case in x order, whichever thread met it first.
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?;
    let rms = scene.measured.as_ref().map(|_| Rms {
        e_t: rms(rows
            .iter()
            .filter_map(|r| r.measured.and_then(|m| m.e_t).map(|d| (r.model.e_t, d)))),
        omega: rms(rows.iter().filter_map(|r| {
            r.measured
                .and_then(|m| m.omega)
                .map(|d| (r.model.sphere.omega, d))
        })),
    });
    let source = match source {
        PSource::Simulate => format!("simulated at tol {:e} (closed forms exact)", scene.tol),
        PSource::Table(t) => format!(
            "table lookup (certified error {:.1e}; built {})",
            table_error,
            t.provenance().created
        ),
    };
    Ok(Evaluation {
        gamma,
        e_star,
        g_star,
        normal_mass: pair.normal_mass(),
        tangential_mass: pair.tangential_mass(),
        effective_radius: pair.effective_radius(),
        alpha_c1: match scene.dissipation {
            Dissipation::Restitution(e) if e != 1.0 => regimes::alpha_c1_dissipative(gamma, e),
            _ => regimes::alpha_c1(gamma),
        },
        alpha_c2: regimes::alpha_c2(gamma),
        rows,
        dissipative: scene.dissipation.is_named(),
        source,
        elapsed_s: start.elapsed().as_secs_f64(),
        rms,
    })
}
