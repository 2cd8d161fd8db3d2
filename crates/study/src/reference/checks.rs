//! Closed-form checks printed beside the computed values: Hertz's normal impact, the gross-slip
//! line, the rolling state (angular momentum about the contact point), the no-slip limit, and
//! the normal restitution of Thornton's law against its closed form.

use oblique_physics::regimes::{self, Regime};
use oblique_solver::units::PhysicalImpact;
use oblique_solver::{Accuracy, Request};

use super::eval::{Method, NormalOutcome, ObliqueResult};
use super::spec::Setup;
use super::ReferenceError;

/// One closed form against what was computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// The test (file stem) and setup it belongs to.
    pub test: String,
    /// What is checked, with its unit.
    pub name: String,
    /// The closed form.
    pub closed_form: f64,
    /// The computed value (the one of the largest `|difference| − bound`, for a sweep).
    pub computed: f64,
    /// The bound the difference must stay within (the computed value's error bound; for a fit,
    /// the fit's stated accuracy).
    pub bound: f64,
    /// `false` for a published fit that is not exact (shown for comparison).
    pub exact: bool,
}

impl Check {
    /// `computed − closed form`.
    pub fn difference(&self) -> f64 {
        self.computed - self.closed_form
    }

    /// Whether the difference is within the bound.
    pub fn holds(&self) -> bool {
        self.difference().abs() <= self.bound
    }
}

/// Relative rounding allowed where a computed value should equal a closed form exactly.
const ROUNDING: f64 = 1e-12;

/// Relative agreement of the time-resolved normal motion with Hertz's closed form beyond its
/// own convergence estimate: the contact time is found by bisection on an RK4 step (measured:
/// 4e-12 relative), and the closed form's Beta-function constant has 17 digits.
const HERTZ_ROUNDING: f64 = 1e-10;

/// Hertz's contact time, peak overlap and peak force against the time-resolved normal motion.
pub fn hertz(test: &str, outs: &[NormalOutcome]) -> Vec<Check> {
    let mut v = Vec::new();
    for o in outs {
        let t = format!("{} ({})", test, o.setup.label);
        let rows = [
            (
                "contact time t_c (s)",
                o.hertz.contact_time,
                o.simulated.contact_time,
                o.simulated_error.contact_time,
            ),
            (
                "peak overlap delta_max (m)",
                o.hertz.max_overlap,
                o.simulated.max_overlap,
                o.simulated_error.max_overlap,
            ),
            (
                "peak force F_max (N)",
                o.hertz.peak_force,
                o.simulated.peak_force,
                o.simulated_error.peak_force,
            ),
        ];
        for (name, closed, computed, err) in rows {
            v.push(Check {
                test: t.clone(),
                name: name.into(),
                closed_form: closed,
                computed,
                bound: err + HERTZ_ROUNDING * closed.abs(),
                exact: true,
            });
        }
    }
    v
}

/// Rounding allowed in the normal restitution of Thornton's exact normal motion (its three
/// phases in closed form) against Thornton's closed form `e(V_y/V)`: relative to `e_n`.
const RESTITUTION_ROUNDING: f64 = 1e-12;

/// The error bound of an `e_n` of Thornton's exact normal motion: the rounding.
pub fn restitution_rounding(e_n: f64) -> f64 {
    RESTITUTION_ROUNDING * e_n.abs()
}

/// Thornton's closed form `e(V_y/V)` (`physics.md`, "Elastic–plastic impacts") against the
/// normal restitution computed for every case of an elastic–plastic test (the exact normal
/// motion of the bodies, or the direct two-body simulation): one check per setup, the worst
/// case. `V_y` is Thornton's (1997) yield speed of the setup's `p_y`, `R*`, `E*` and `m*`.
pub fn plastic_restitution(test: &str, res: &ObliqueResult) -> Vec<Check> {
    let mut v = Vec::new();
    for (setup, outs) in &res.setups {
        let ratios = || outs.iter().filter_map(|o| o.plastic.map(|p| p.speed_ratio));
        let (lo, hi) = (
            ratios().fold(f64::INFINITY, f64::min),
            ratios().fold(0.0, f64::max),
        );
        let range = if lo == hi {
            format!("{lo:.3}")
        } else {
            format!("{lo:.3} to {hi:.3}")
        };
        let checks = outs.iter().filter_map(|o| {
            o.plastic.map(|p| Check {
                test: format!("{test} ({})", setup.label),
                name: format!(
                    "normal restitution e_n = Thornton's e(V_y/V) (V_y = {:.6} m/s; {} cases; \
                     V/V_y {range}; e_n of the normal motion)",
                    p.yield_speed,
                    outs.len(),
                ),
                closed_form: p.closed_form_e_n,
                computed: o.e_n,
                bound: restitution_rounding(p.closed_form_e_n),
                exact: true,
            })
        });
        v.extend(worst(checks));
    }
    v
}

/// The worst of a sweep: the check whose `|difference| − bound` is largest.
fn worst(checks: impl Iterator<Item = Check>) -> Option<Check> {
    checks.max_by(|a, b| {
        (a.difference().abs() - a.bound).total_cmp(&(b.difference().abs() - b.bound))
    })
}

/// The gross-slip line `P = 1 − 7α` over the cases in full slip, simulated (never taken from
/// the closed form): one check per setup that has such cases.
pub fn gross_slip(
    test: &str,
    res: &ObliqueResult,
    method: &Method,
) -> Result<Vec<Check>, ReferenceError> {
    let mut v = Vec::new();
    for (setup, outs) in &res.setups {
        let mut checks = Vec::new();
        for o in outs {
            if o.regime != Some(Regime::FullSlip) {
                continue;
            }
            let (p, err) = match method {
                Method::Direct { .. } => (o.post.p, o.p_error),
                Method::Slice { tol } => {
                    let mut r = Request::new(o.gamma, o.alpha)
                        .accuracy(Accuracy::Tolerance(*tol))
                        .forced(true);
                    if o.e_n != 1.0 {
                        r = r.e_n(o.e_n);
                    }
                    let s = r.solve()?;
                    (s.p, s.error_estimate)
                }
                Method::Table(_) => {
                    let mut r = Request::new(o.gamma, o.alpha)
                        .accuracy(Accuracy::Tolerance(1e-8))
                        .forced(true);
                    if o.e_n != 1.0 {
                        r = r.e_n(o.e_n);
                    }
                    let s = r.solve()?;
                    (s.p, s.error_estimate)
                }
            };
            checks.push(Check {
                test: format!("{test} ({})", setup.label),
                name: format!(
                    "gross-slip line P = 1 - {} alpha ({} full-slip cases, simulated)",
                    if o.e_n == 1.0 {
                        "7".to_string()
                    } else {
                        format!("3.5(1 + e_n) alpha = 1 - {}", 3.5 * (1.0 + o.e_n))
                    },
                    outs.iter()
                        .filter(|o| o.regime == Some(Regime::FullSlip))
                        .count()
                ),
                closed_form: if o.e_n == 1.0 {
                    1.0 - 7.0 * o.alpha
                } else {
                    oblique_physics::regimes::full_slip_line(o.alpha, o.e_n)
                },
                computed: p,
                bound: err + ROUNDING,
                exact: true,
            });
        }
        v.extend(worst(checks.into_iter()));
    }
    Ok(v)
}

/// The rolling state (contact point at rest, `P = 0`) in closed form, `J = m_t u0`, against the
/// one the computed rebound implies through the conservation of angular momentum about the
/// contact point: `v̄_x = v'_x − m_t V'_st/m`, `ω̄ = ω' − m_t V'_st R/I` (sphere 1).
pub fn rolling(test: &str, res: &ObliqueResult) -> Vec<Check> {
    let mut v = Vec::new();
    for (setup, outs) in &res.setups {
        let pair = setup.pair();
        let s = pair.sphere;
        let inv_mt = 1.0 / s.mass
            + s.radius * s.radius / (s.kappa * s.mass * s.radius * s.radius)
            + pair.other.map_or(0.0, |o| {
                1.0 / o.mass + o.radius * o.radius / (o.kappa * o.mass * o.radius * o.radius)
            });
        let m_t = 1.0 / inv_mt;
        let inertia = s.kappa * s.mass * s.radius * s.radius;
        let mut vx = Vec::new();
        let mut om = Vec::new();
        for o in outs {
            let inc = &o.case.incident;
            let u0 = pair.slip_velocity(inc);
            if u0 == 0.0 {
                continue;
            }
            let after = oblique_lookup::rebound::Incident {
                sphere: o.post.sphere,
                other: o.post.other.unwrap_or_default(),
            };
            let u1 = pair.slip_velocity(&after);
            let j = m_t * u0;
            let closed_v = inc.sphere.v_x - j / s.mass;
            let closed_w = inc.sphere.omega - j * s.radius / inertia;
            let comp_v = o.post.sphere.v_x - m_t * u1 / s.mass;
            let comp_w = o.post.sphere.omega - m_t * u1 * s.radius / inertia;
            let scale_v = inc.sphere.v_x.abs() + u0.abs();
            let scale_w = inc.sphere.omega.abs() + u0.abs() / s.radius;
            vx.push(Check {
                test: format!("{test} ({})", setup.label),
                name: "rolling state v_x (m/s), from the rebound".into(),
                closed_form: closed_v,
                computed: comp_v,
                bound: 1e-9 * scale_v,
                exact: true,
            });
            om.push(Check {
                test: format!("{test} ({})", setup.label),
                name: "rolling state omega (rad/s), from the rebound".into(),
                closed_form: closed_w,
                computed: comp_w,
                bound: 1e-9 * scale_w,
                exact: true,
            });
        }
        v.extend(worst(vx.into_iter()));
        v.extend(worst(om.into_iter()));
    }
    v
}

/// The no-slip limit `P(γ, ∞)` of each setup against seed 001's fit (29) (a fit, about 0.01
/// off in places), and the exact value `P(1, ∞) = −1`.
pub fn no_slip(
    suite: &str,
    setups: &[Setup],
    method: &Method,
) -> Result<Vec<Check>, ReferenceError> {
    let tol = match method {
        Method::Slice { tol } | Method::Direct { tol } => *tol,
        Method::Table(_) => 1e-8,
    };
    let mut v = Vec::new();
    let mut seen: Vec<f64> = Vec::new();
    for setup in setups {
        let pair = setup.pair();
        let [a, b] = setup.materials();
        let gamma = pair.gamma_from_materials(&a, &b)?;
        if seen.iter().any(|g| (g - gamma).abs() < 1e-12) {
            continue;
        }
        seen.push(gamma);
        let (p, err) = match method {
            Method::Direct { .. } => {
                // The same bodies with infinite friction, an oblique approach at 45°.
                let mut imp = PhysicalImpact {
                    pair,
                    materials: [a, b],
                    incident: Default::default(),
                    friction: f64::INFINITY,
                    law: Default::default(),
                };
                imp.incident.sphere = oblique_lookup::rebound::State {
                    v_x: 1.0,
                    v_z: 1.0,
                    omega: 0.0,
                };
                let out = imp.solve(tol)?;
                (out.p.unwrap_or(f64::NAN), out.error_estimate)
            }
            _ => {
                let s = Request::new(gamma, f64::INFINITY)
                    .accuracy(Accuracy::Tolerance(tol))
                    .forced(true)
                    .solve()?;
                (s.p, s.error_estimate)
            }
        };
        v.push(Check {
            test: format!("{suite} ({}, gamma = {gamma:.6})", setup.label),
            name: "no-slip limit P(gamma, inf) against seed 001's fit (29)".into(),
            closed_form: regimes::no_slip_fit(gamma),
            computed: p,
            bound: 0.015 + err,
            exact: false,
        });
    }
    let s = Request::new(1.0, f64::INFINITY)
        .accuracy(Accuracy::Tolerance(tol))
        .forced(true)
        .solve()?;
    v.push(Check {
        test: format!("{suite} (gamma = 1)"),
        name: "no-slip limit P(1, inf) = -1 (exact), simulated".into(),
        closed_form: -1.0,
        computed: s.p,
        bound: s.error_estimate + ROUNDING,
        exact: true,
    });
    Ok(v)
}
