//! Computing a test: every case to `(γ, α)`, `P` with its error bound, and the state after the
//! impact; the normal tests' contact time, peak overlap and peak force.

use oblique_lookup::rebound::{Incident, Pair, State};
use oblique_lookup::Table;
use oblique_physics::regimes::{self, Regime};
use oblique_solver::hertz::{HertzClosedForm, NormalBodies};
use oblique_solver::request::dissipative_closed_form;
use oblique_solver::thornton::normal::{Loading, Motion};
use oblique_solver::units::PhysicalImpact;
use oblique_solver::{Accuracy, BodiesLaw, Law, Method as SolverMethod, Request, Resolution};
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
    /// Normal restitution of the impact (1: elastic; below, the Kelvin–Voigt law, or Thornton's
    /// law where [`Outcome::plastic`] is set: there the `e_n` of its exact normal motion, or of
    /// the direct simulation).
    pub e_n: f64,
    /// Thornton's law of the case: its limiting pressure and yield speed (`None`: elastic or
    /// Kelvin–Voigt).
    pub plastic: Option<Plastic>,
    /// How `P` was obtained: `simulated`, `closed-form`, `table`, `direct`, `normal-impact`.
    pub how: &'static str,
    /// The state after the impact.
    pub post: Post,
    /// The state after the impact by the rebound algebra at `P − p_error`, `P + p_error` and
    /// `P` (error propagation; the last differs from `post` only for a direct simulation, by
    /// its error in the normal motion and rounding).
    pub bracket: [Post; 3],
}

/// What Thornton's law gives one impact: the limiting pressure, the yield speed and the
/// closed form of its normal restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plastic {
    /// Limiting contact pressure `p_y` (Pa).
    pub yield_pressure: f64,
    /// Yield speed `V_y` (m/s): the approach speed at which the peak Hertz pressure reaches
    /// `p_y` ([`yield_speed`]).
    pub yield_speed: f64,
    /// The approach speed over the yield speed, `V/V_y`.
    pub speed_ratio: f64,
    /// Thornton's closed form `e(V_y/V)` (`physics.md`; 1 for `V ≤ V_y`), the check of `e_n`.
    pub closed_form_e_n: f64,
}

/// `1/E* = Σ (1 − ν²)/E` (Pa), `R*` (m) and `m*` (kg) of a setup.
fn effective(setup: &Setup) -> (f64, f64, f64) {
    let pair = setup.pair();
    let [a, b] = setup.materials();
    let (e_star, _) = oblique_lookup::rebound::effective_moduli(&a, &b);
    (e_star, pair.effective_radius(), pair.normal_mass())
}

/// Thornton's (1997) yield speed `V_y = √(π⁵/30 · p_y⁵ R*³/(E*⁴ m*))` (m/s) of a setup with
/// limiting pressure `p_y` (Pa): `½ m* V_y² = (2/5) k d_y^{5/2}`, `k = (4/3) E* √R*`,
/// `d_y = R* (π p_y/(2E*))²` (the Hertz approach that stops where the peak pressure reaches
/// `p_y`).
pub fn yield_speed(setup: &Setup, yield_pressure: f64) -> f64 {
    let (e_star, r, m) = effective(setup);
    let pi5 = std::f64::consts::PI.powi(5);
    (pi5 / 30.0 * yield_pressure.powi(5) * r.powi(3) / (e_star.powi(4) * m)).sqrt()
}

/// Thornton's closed form of the normal restitution of a setup with limiting pressure `p_y`
/// (Pa) at approach speed `speed` (m/s), `e(V_y/V)` ([`yield_speed`]).
pub fn thornton_restitution(setup: &Setup, yield_pressure: f64, speed: f64) -> f64 {
    oblique_solver::thornton::restitution(yield_speed(setup, yield_pressure) / speed)
}

/// The limiting pressure `p_y` (Pa) whose Thornton restitution at approach speed `speed` (m/s)
/// is `e_n ∈ (0, 1)`: [`yield_speed`] inverted at `V_y = r V`, `r` the speed ratio of `e_n`
/// (NaN for an `e_n` out of range).
pub fn yield_pressure_for_restitution(setup: &Setup, speed: f64, e_n: f64) -> f64 {
    let Ok(ratio) = oblique_solver::thornton::speed_ratio_for_restitution(e_n) else {
        return f64::NAN;
    };
    let (e_star, r, m) = effective(setup);
    let v_y = ratio * speed;
    let pi5 = std::f64::consts::PI.powi(5);
    (v_y * v_y * 30.0 / pi5 * e_star.powi(4) * m / r.powi(3)).powf(0.2)
}

/// The normal restitution of Thornton's exact normal motion of the setup's bodies (its three
/// phases in closed form, [`Motion`]) at approach speed `speed` (m/s): an independent
/// computation of what [`thornton_restitution`] states.
pub fn thornton_motion_restitution(setup: &Setup, yield_pressure: f64, speed: f64) -> f64 {
    let (e_star, r, m) = effective(setup);
    let loading = Loading {
        stiffness: 4.0 / 3.0 * e_star * r.sqrt(),
        yield_indentation: oblique_solver::thornton::yield_indentation(yield_pressure, r, e_star),
    };
    Motion::new(loading, 1.0 / m, speed).restitution()
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
    let pair = setup.pair();
    let [a, b] = setup.materials();
    let gamma = pair.gamma_from_materials(&a, &b)?;
    let inc = &case.incident;
    let alpha = pair.alpha(inc, setup.friction)?;
    let u0 = pair.slip_velocity(inc);
    // Thornton's law: e_n of the exact normal motion at this approach speed, and the closed
    // form beside it (the check).
    let plastic = setup.yield_pressure.map(|y| {
        let speed = pair.approach_speed(inc);
        let yield_speed = yield_speed(setup, y.pascal);
        Plastic {
            yield_pressure: y.pascal,
            yield_speed,
            speed_ratio: speed / yield_speed,
            closed_form_e_n: oblique_solver::thornton::restitution(yield_speed / speed),
        }
    });
    let e_n = match (plastic, setup.yield_pressure) {
        (Some(_), Some(y)) => {
            thornton_motion_restitution(setup, y.pascal, pair.approach_speed(inc))
        }
        _ => e_n,
    };
    let law = if plastic.is_some() {
        Law::Thornton
    } else {
        Law::for_restitution(e_n)
    };
    let algebra = |pair: &Pair, inc: &Incident, p: f64| algebra(pair, inc, p, e_n);
    let (post, p_error, how, e_n) = match method {
        Method::Direct { tol } => {
            let law = match setup.yield_pressure {
                Some(y) => BodiesLaw::Thornton(oblique_solver::thornton::BodiesParameters {
                    yield_pressure: y.pascal,
                }),
                None => BodiesLaw::of_relaxation_time(relaxation_time(setup, inc, e_n)?),
            };
            let imp = PhysicalImpact {
                pair,
                materials: [a, b],
                incident: *inc,
                friction: setup.friction,
                law,
            };
            let out = imp.solve(*tol)?;
            let post = Post {
                sphere: out.sphere,
                other: out.other,
                p: out.p.unwrap_or(f64::NAN),
            };
            (post, out.error_estimate, "direct", out.e_n)
        }
        _ if u0 == 0.0 => (algebra(&pair, inc, f64::NAN)?, 0.0, "normal-impact", e_n),
        Method::Slice { tol } => {
            let mut r = Request::new(gamma, alpha).accuracy(Accuracy::Tolerance(*tol));
            if e_n != 1.0 {
                r = r.e_n(e_n).law(law);
            }
            let s = r.solve()?;
            let (err, how) = match s.method {
                SolverMethod::ClosedForm => (0.0, "closed-form"),
                SolverMethod::Simulated => (s.error_estimate, "simulated"),
            };
            (algebra(&pair, inc, s.p)?, err, how, e_n)
        }
        // A dissipative case that the table cannot answer (a table without its e_n, or any
        // table for Thornton's law): it is simulated (its `method` column says so), never
        // answered at e_n = 1.
        Method::Table(t)
            if e_n != 1.0
                && (law == Law::Thornton
                    || !t
                        .restitution()
                        .is_some_and(|(lo, hi)| (lo..=hi).contains(&e_n))) =>
        {
            let s = Request::new(gamma, alpha)
                .e_n(e_n)
                .law(law)
                .accuracy(Accuracy::Tolerance(1e-8))
                .solve()?;
            let (err, how) = match s.method {
                SolverMethod::ClosedForm => (0.0, "closed-form"),
                SolverMethod::Simulated => (s.error_estimate, "simulated"),
            };
            (algebra(&pair, inc, s.p)?, err, how, e_n)
        }
        Method::Table(t) if e_n != 1.0 => {
            let p = t.p_e(gamma, alpha, e_n)?;
            let (err, how) = match dissipative_closed_form(gamma, alpha, e_n) {
                Some(_) => (0.0, "closed-form"),
                None => (t.error_bound(), "table"),
            };
            (algebra(&pair, inc, p)?, err, how, e_n)
        }
        Method::Table(t) => {
            let p = t.p(gamma, alpha)?;
            let (err, how) = match regimes::closed_form(gamma, alpha) {
                Some(_) => (0.0, "closed-form"),
                None => (t.error_bound(), "table"),
            };
            (algebra(&pair, inc, p)?, err, how, e_n)
        }
    };
    let algebra = |pair: &Pair, inc: &Incident, p: f64| self::algebra(pair, inc, p, e_n);
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
        // Thornton's law has no closed-form slip regimes (its limits jump at the switch to
        // unloading): its cases are not classified below the yield speed.
        regime: (u0 != 0.0 && (plastic.is_none() || e_n == 1.0)).then(|| {
            if e_n == 1.0 {
                Regime::of(gamma, alpha)
            } else {
                Regime::of_dissipative(gamma, alpha, e_n)
            }
        }),
        e_n,
        plastic,
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
