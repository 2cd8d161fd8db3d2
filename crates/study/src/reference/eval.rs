//! Computing a test: every case to `(γ, α)`, `P` with its error bound, and the state after the
//! impact; the normal tests' contact time, peak overlap and peak force.

use oblique_lookup::rebound::{Incident, Pair, State};
use oblique_lookup::Table;
use oblique_physics::regimes::{self, Regime};
use oblique_solver::hertz::{HertzClosedForm, NormalBodies};
use oblique_solver::request::dissipative_closed_form;
use oblique_solver::units::PhysicalImpact;
use oblique_solver::{Accuracy, BodiesLaw, Method as SolverMethod, Request, Resolution};
use rayon::prelude::*;

use super::spec::{Case, NormalTest, ObliqueTest, Setup};
use super::ReferenceError;

/// How `P` (and, with [`Method::Direct`], the whole rebound) is computed.
#[derive(Debug, Clone, Copy)]
pub enum Method<'a> {
    /// The universal mapping to `(γ, α)` and a dimensionless simulation of that one point at
    /// this tolerance (closed forms exact).
    Slice {
        /// Target absolute error of `P`.
        tol: f64,
    },
    /// The universal mapping and a table lookup (error: the table's stated bound).
    Table(&'a Table),
    /// Direct two-body simulation in SI units ([`PhysicalImpact::solve`]) at this tolerance:
    /// no mapping.
    Direct {
        /// Target absolute error of `P`.
        tol: f64,
    },
}

impl Method<'_> {
    /// In words, for captions and summaries.
    pub fn describe(&self) -> String {
        match self {
            Method::Slice { tol } => {
                format!("P(gamma, alpha) simulated per case at tol {tol:e} (closed forms exact)")
            }
            Method::Table(t) => format!(
                "P(gamma, alpha) from the table (stated error bound {:.2e})",
                t.error_bound()
            ),
            Method::Direct { tol } => {
                format!("direct two-body simulation in SI units at tol {tol:e}")
            }
        }
    }
}

/// The state after one impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Post {
    /// Sphere 1 after the impact.
    pub sphere: State,
    /// Sphere 2 after the impact (`None` for a wall).
    pub other: Option<State>,
    /// `P` (NaN when `u0 = 0`).
    pub p: f64,
}

/// One evaluated case of an oblique test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// The case.
    pub case: Case,
    /// `γ` of the setup.
    pub gamma: f64,
    /// `α = (2/7)(m*/m_t) μ v_z0/|u0|` (`∞` when `u0 = 0`).
    pub alpha: f64,
    /// Error bound of `P` (0 for closed forms and pure normal impacts).
    pub p_error: f64,
    /// Friction regime (`None`: `u0 = 0`, a pure normal impact).
    pub regime: Option<Regime>,
    /// Normal restitution of the impact (1: elastic; below, the Kelvin–Voigt law).
    pub e_n: f64,
    /// How `P` was obtained: `simulated`, `closed-form`, `table`, `direct`, `normal-impact`.
    pub how: &'static str,
    /// The state after the impact.
    pub post: Post,
    /// The state after the impact by the rebound algebra at `P − p_error`, `P + p_error` and
    /// `P` (error propagation; the last differs from `post` only for a direct simulation, by
    /// its error in the normal motion and rounding).
    pub bracket: [Post; 3],
}

/// An evaluated oblique test: per setup, its outcomes.
#[derive(Debug, Clone, PartialEq)]
pub struct ObliqueResult {
    /// Per setup (as in the test), the outcomes of its cases in order.
    pub setups: Vec<(Setup, Vec<Outcome>)>,
}

fn algebra(pair: &Pair, inc: &Incident, p: f64, e_n: f64) -> Result<Post, ReferenceError> {
    let r = pair.rebound_dissipative(inc, p, e_n)?;
    Ok(Post {
        sphere: r.sphere,
        other: r.other,
        p: r.p,
    })
}

/// Evaluate one case.
pub fn outcome(setup: &Setup, case: &Case, method: &Method) -> Result<Outcome, ReferenceError> {
    outcome_e(setup, case, 1.0, method)
}

/// The relaxation time `τ` (s) of the Kelvin–Voigt law that gives normal restitution `e_n` to
/// this setup's impact `inc` (0 for `e_n = 1`).
pub fn relaxation_time(setup: &Setup, inc: &Incident, e_n: f64) -> Result<f64, ReferenceError> {
    if e_n == 1.0 {
        return Ok(0.0);
    }
    let pair = setup.pair();
    let [a, b] = setup.materials();
    let (e_star, _) = oblique_lookup::rebound::effective_moduli(&a, &b);
    let stiffness = 4.0 / 3.0 * e_star * pair.effective_radius().sqrt();
    let hat = oblique_solver::kelvin_voigt::tau_for_restitution(e_n)?;
    let unit = oblique_solver::kelvin_voigt::dimensionless_tau(
        1.0,
        pair.normal_mass(),
        stiffness,
        pair.approach_speed(inc),
    );
    Ok(hat / unit)
}

/// [`outcome`] at normal restitution `e_n` (Kelvin–Voigt law; 1: elastic, the same bits as
/// [`outcome`]).
pub fn outcome_e(
    setup: &Setup,
    case: &Case,
    e_n: f64,
    method: &Method,
) -> Result<Outcome, ReferenceError> {
    let algebra = |pair: &Pair, inc: &Incident, p: f64| algebra(pair, inc, p, e_n);
    let pair = setup.pair();
    let [a, b] = setup.materials();
    let gamma = pair.gamma_from_materials(&a, &b)?;
    let inc = &case.incident;
    let alpha = pair.alpha(inc, setup.friction)?;
    let u0 = pair.slip_velocity(inc);
    let (post, p_error, how) = match method {
        Method::Direct { tol } => {
            let imp = PhysicalImpact {
                pair,
                materials: [a, b],
                incident: *inc,
                friction: setup.friction,
                law: BodiesLaw::of_relaxation_time(relaxation_time(setup, inc, e_n)?),
            };
            let out = imp.solve(*tol)?;
            let post = Post {
                sphere: out.sphere,
                other: out.other,
                p: out.p.unwrap_or(f64::NAN),
            };
            (post, out.error_estimate, "direct")
        }
        _ if u0 == 0.0 => (algebra(&pair, inc, f64::NAN)?, 0.0, "normal-impact"),
        Method::Slice { tol } => {
            let mut r = Request::new(gamma, alpha).accuracy(Accuracy::Tolerance(*tol));
            if e_n != 1.0 {
                r = r.e_n(e_n);
            }
            let s = r.solve()?;
            let (err, how) = match s.method {
                SolverMethod::ClosedForm => (0.0, "closed-form"),
                SolverMethod::Simulated => (s.error_estimate, "simulated"),
            };
            (algebra(&pair, inc, s.p)?, err, how)
        }
        // A damped test and a table without its e_n: that case is simulated (its `method`
        // column says so), never answered at e_n = 1.
        Method::Table(t)
            if e_n != 1.0
                && !t
                    .restitution()
                    .is_some_and(|(lo, hi)| (lo..=hi).contains(&e_n)) =>
        {
            let s = Request::new(gamma, alpha)
                .e_n(e_n)
                .accuracy(Accuracy::Tolerance(1e-8))
                .solve()?;
            let (err, how) = match s.method {
                SolverMethod::ClosedForm => (0.0, "closed-form"),
                SolverMethod::Simulated => (s.error_estimate, "simulated"),
            };
            (algebra(&pair, inc, s.p)?, err, how)
        }
        Method::Table(t) if e_n != 1.0 => {
            let p = t.p_e(gamma, alpha, e_n)?;
            let (err, how) = match dissipative_closed_form(gamma, alpha, e_n) {
                Some(_) => (0.0, "closed-form"),
                None => (t.error_bound(), "table"),
            };
            (algebra(&pair, inc, p)?, err, how)
        }
        Method::Table(t) => {
            let p = t.p(gamma, alpha)?;
            let (err, how) = match regimes::closed_form(gamma, alpha) {
                Some(_) => (0.0, "closed-form"),
                None => (t.error_bound(), "table"),
            };
            (algebra(&pair, inc, p)?, err, how)
        }
    };
    let how = if u0 == 0.0 { "normal-impact" } else { how };
    let bracket = if u0 == 0.0 {
        [post, post, algebra(&pair, inc, f64::NAN)?]
    } else {
        [
            algebra(&pair, inc, post.p - p_error)?,
            algebra(&pair, inc, post.p + p_error)?,
            algebra(&pair, inc, post.p)?,
        ]
    };
    Ok(Outcome {
        case: *case,
        gamma,
        alpha,
        p_error,
        regime: (u0 != 0.0).then(|| {
            if e_n == 1.0 {
                Regime::of(gamma, alpha)
            } else {
                Regime::of_dissipative(gamma, alpha, e_n)
            }
        }),
        e_n,
        how,
        post,
        bracket,
    })
}

/// Evaluate every case of an oblique test (in parallel on the current rayon pool).
pub fn oblique(test: &ObliqueTest, method: &Method) -> Result<ObliqueResult, ReferenceError> {
    let setups = test
        .setups
        .iter()
        .map(|(setup, cases)| {
            let outs = cases
                .par_iter()
                .map(|c| outcome_e(setup, c, test.e_n, method))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((*setup, outs))
        })
        .collect::<Result<Vec<_>, ReferenceError>>()?;
    Ok(ObliqueResult { setups })
}

/// Contact time, peak overlap and peak force of a normal impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalValues {
    /// Contact time `t_c` (s).
    pub contact_time: f64,
    /// Peak overlap `δ_max` (m).
    pub max_overlap: f64,
    /// Peak normal force `F_max` (N).
    pub peak_force: f64,
}

/// A normal impact: closed form and time-resolved simulation, with the force history.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalOutcome {
    /// The setup.
    pub setup: Setup,
    /// Approach speed `v_z0` (m/s).
    pub approach_speed: f64,
    /// Effective modulus `E*` (Pa), radius `R*` (m), normal mass `m*` (kg).
    pub effective: (f64, f64, f64),
    /// Hertz's closed form.
    pub hertz: NormalValues,
    /// The time-resolved normal motion (the direct simulation with [`Method::Direct`]).
    pub simulated: NormalValues,
    /// Its error: the change from half the steps.
    pub simulated_error: NormalValues,
    /// Force history `(t (s), δ (m), F (N), error of F (N))` at the simulation's nodes.
    pub history: Vec<(f64, f64, f64, f64)>,
}

/// Steps per contact time of the normal-motion integration.
const NORMAL_STEPS: usize = 4096;
/// Points of the published force history.
const HISTORY_POINTS: usize = 128;

/// Evaluate a normal test.
pub fn normal(test: &NormalTest, method: &Method) -> Result<Vec<NormalOutcome>, ReferenceError> {
    test.setups
        .iter()
        .map(|(setup, inc)| {
            let pair = setup.pair();
            let [a, b] = setup.materials();
            pair.gamma_from_materials(&a, &b)?;
            let (e_star, _) = oblique_lookup::rebound::effective_moduli(&a, &b);
            let r = pair.effective_radius();
            let m = pair.normal_mass();
            let v = pair.approach_speed(inc);
            let stiffness = 4.0 / 3.0 * e_star * r.sqrt();
            let hertz = HertzClosedForm {
                mass: m,
                stiffness,
                approach_speed: v,
            };
            let bodies = NormalBodies {
                inv_mass1: 1.0 / pair.sphere.mass,
                inv_mass2: pair.other.map_or(0.0, |o| 1.0 / o.mass),
                stiffness,
                approach_speed: v,
            };
            let fine = bodies.trajectory(NORMAL_STEPS);
            let coarse = bodies.trajectory(NORMAL_STEPS / 2);
            let values = |t: &oblique_solver::hertz::NormalTrajectory| NormalValues {
                contact_time: t.contact_time,
                max_overlap: t.max_indentation,
                peak_force: t.peak_force,
            };
            // The simulated values and their error: the finest run against the one with half
            // the steps (the time-resolved normal motion, or the direct two-body simulation).
            let (f, c) = if let Method::Direct { .. } = method {
                let imp = PhysicalImpact {
                    pair,
                    materials: [a, b],
                    incident: *inc,
                    friction: setup.friction,
                    law: Default::default(),
                };
                let run = |steps| -> Result<NormalValues, ReferenceError> {
                    let out = imp.simulate(Resolution { springs: 0, steps })?;
                    Ok(NormalValues {
                        contact_time: out.contact_time,
                        max_overlap: out.max_indentation,
                        peak_force: out.peak_force,
                    })
                };
                (run(NORMAL_STEPS)?, run(NORMAL_STEPS / 2)?)
            } else {
                (values(&fine), values(&coarse))
            };
            let simulated = f;
            let force = |d: f64| stiffness * d * d.sqrt();
            let every = NORMAL_STEPS / HISTORY_POINTS;
            let history = (0..=HISTORY_POINTS)
                .map(|i| {
                    let j = i * every;
                    let d = fine.indentation[j];
                    let dc = coarse.indentation[j / 2];
                    let t = j as f64 * fine.dt;
                    (t, d, force(d), (force(d) - force(dc)).abs())
                })
                .collect();
            Ok(NormalOutcome {
                setup: *setup,
                approach_speed: v,
                effective: (e_star, r, m),
                hertz: NormalValues {
                    contact_time: hertz.contact_time(),
                    max_overlap: hertz.max_indentation(),
                    peak_force: hertz.peak_force(),
                },
                simulated,
                simulated_error: NormalValues {
                    contact_time: (f.contact_time - c.contact_time).abs(),
                    max_overlap: (f.max_overlap - c.max_overlap).abs(),
                    peak_force: (f.peak_force - c.peak_force).abs(),
                },
                history,
            })
        })
        .collect()
}
