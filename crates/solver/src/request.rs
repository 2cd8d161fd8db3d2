//! One request to the solver: the impact (`γ`, `α`, and `e_n` with its law) and how to answer
//! it (accuracy, scheme, limits, closed forms allowed or not), in place of positional
//! arguments that grow with every new parameter.
//!
//! ```
//! use oblique_solver::{Accuracy, Request};
//! // A soda-lime glass bead on glass (γ ≈ 1.75) at α = 1, e_n = 0.9 (Kelvin–Voigt law).
//! let s = Request::new(1.754, 1.0).e_n(0.9).accuracy(Accuracy::Tolerance(1e-6)).solve()?;
//! assert!(s.error_estimate <= 1e-6 && s.law.name() == "kelvin-voigt");
//! # Ok::<(), oblique_solver::PhysicsError>(())
//! ```

use oblique_physics::regimes;

use crate::error::PhysicsError;
use crate::impact::{
    check_alpha, check_gamma, simulate_elastic, Limits, Resolution, Scheme, ALPHA_NO_SLIP,
};
use crate::kelvin_voigt;
use crate::law::Law;
use crate::preset::Preset;
use crate::refine::{solve_core, solve_elastic, Accuracy, RefineEvent, Solution};

/// An impact to solve and how.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// `γ = √((m*/m_t) G*/E*)` (finite, > 0).
    pub gamma: f64,
    /// `α = (2/7)(m*/m_t) μ v_z0/|u0|` (≥ 0, `∞` for no slip).
    pub alpha: f64,
    /// Normal restitution `e_n` (1: elastic; `[0.3, 1]` for the Kelvin–Voigt law).
    pub e_n: f64,
    /// The dissipation law.
    pub law: Law,
    /// Tolerance or fixed resolution.
    pub accuracy: Accuracy,
    /// Time scheme (the Kelvin–Voigt law has the accurate one only).
    pub scheme: Scheme,
    /// Simulate even where a closed form is exact.
    pub force_simulation: bool,
    /// Work and memory limits.
    pub limits: Limits,
}

impl Request {
    /// An elastic impact at `(γ, α)`, to the default preset's tolerance (1e-6), accurate
    /// scheme, closed forms allowed, default limits.
    pub fn new(gamma: f64, alpha: f64) -> Self {
        Self {
            gamma,
            alpha,
            e_n: 1.0,
            law: Law::Elastic,
            accuracy: Accuracy::Tolerance(Preset::default().tolerance()),
            scheme: Scheme::Accurate,
            force_simulation: false,
            limits: Limits::default(),
        }
    }

    /// Normal restitution `e_n`, with the law it implies ([`Law::for_restitution`]: elastic at
    /// 1, Kelvin–Voigt below); name another law after it with [`Request::law`].
    pub fn e_n(mut self, e_n: f64) -> Self {
        self.e_n = e_n;
        self.law = Law::for_restitution(e_n);
        self
    }

    /// The dissipation law.
    pub fn law(mut self, law: Law) -> Self {
        self.law = law;
        self
    }

    /// Tolerance or fixed resolution.
    pub fn accuracy(mut self, accuracy: Accuracy) -> Self {
        self.accuracy = accuracy;
        self
    }

    /// Time scheme.
    pub fn scheme(mut self, scheme: Scheme) -> Self {
        self.scheme = scheme;
        self
    }

    /// Simulate even where a closed form is exact.
    pub fn forced(mut self, force_simulation: bool) -> Self {
        self.force_simulation = force_simulation;
        self
    }

    /// Work and memory limits.
    pub fn limits(mut self, limits: Limits) -> Self {
        self.limits = limits;
        self
    }

    /// `P` to the requested accuracy.
    pub fn solve(&self) -> Result<Solution, PhysicsError> {
        self.solve_observed(&mut |_| {})
    }

    /// [`Request::solve`], reporting each level of the automatic refinement to `observer`.
    ///
    /// `e_n = 1` is answered by the elastic solver whatever the law (the same operations, the
    /// same bits). Below it, the Kelvin–Voigt law finds the relaxation time `τ̂` that gives
    /// `e_n` ([`kelvin_voigt::tau_for_restitution`]) and refines its simulation like the
    /// elastic one; closed forms where they are exact ([`dissipative_closed_form`]).
    pub fn solve_observed(
        &self,
        observer: &mut dyn FnMut(RefineEvent),
    ) -> Result<Solution, PhysicsError> {
        let e_n = self.law.check_restitution(self.e_n)?;
        if e_n == 1.0 {
            let mut s = solve_elastic(
                self.gamma,
                self.alpha,
                self.accuracy,
                self.scheme,
                self.force_simulation,
                self.limits,
                observer,
            )?;
            s.law = self.law;
            return Ok(s);
        }
        let (gamma, alpha, tau) = self.dissipative(e_n)?;
        let closed = dissipative_closed_form(gamma, alpha, e_n);
        let mut s = solve_core(
            (
                gamma,
                self.accuracy,
                self.scheme,
                self.force_simulation,
                self.limits,
            ),
            kelvin_voigt::RAW_FLOOR,
            closed,
            |res| self.simulate_with(gamma, alpha, tau, res),
            observer,
        )?;
        s.law = self.law;
        s.e_n = e_n;
        s.tau = tau;
        Ok(s)
    }

    /// `P` at a fixed resolution, simulated (no closed form, no estimate).
    pub fn simulate(&self, res: Resolution) -> Result<f64, PhysicsError> {
        let e_n = self.law.check_restitution(self.e_n)?;
        if e_n == 1.0 {
            return simulate_elastic(self.gamma, self.alpha, res, self.scheme);
        }
        let (gamma, alpha, tau) = self.dissipative(e_n)?;
        self.simulate_with(gamma, alpha, tau, res)
    }

    /// The checked `(γ, α)` of a Kelvin–Voigt request (`e_n < 1`, checked) and the relaxation
    /// time `τ̂` of its `e_n`; the scheme must be the accurate one.
    fn dissipative(&self, e_n: f64) -> Result<(f64, f64, f64), PhysicsError> {
        let gamma = check_gamma(self.gamma)?;
        let alpha = check_alpha(self.alpha)?;
        if self.scheme != Scheme::Accurate {
            return Err(PhysicsError::NotForLaw {
                name: "scheme",
                value: self.scheme.name().to_string(),
                case: "for e_n < 1",
                allowed: "the Kelvin-Voigt law is solved with the accurate scheme only (euler is \
                          for elastic impacts)",
            });
        }
        Ok((gamma, alpha, kelvin_voigt::tau_for_restitution(e_n)?))
    }

    fn simulate_with(
        &self,
        gamma: f64,
        alpha: f64,
        tau: f64,
        res: Resolution,
    ) -> Result<f64, PhysicsError> {
        let res = res.validate()?;
        if res.springs != 0 {
            return Err(PhysicsError::NotForLaw {
                name: "springs",
                value: res.springs.to_string(),
                case: "for e_n < 1",
                allowed: "the Kelvin-Voigt law is solved on the continuum row only (springs 0)",
            });
        }
        let shear = 2.0 / 7.0 * gamma * gamma;
        let limit = if alpha > ALPHA_NO_SLIP {
            f64::INFINITY
        } else {
            alpha / shear
        };
        Ok(kelvin_voigt::dimensionless_p(shear, limit, tau, res))
    }
}

/// `P(γ, α, e_n)` where it is exact without simulation: the full-slip line
/// `1 − (7/2)(1 + e_n) α` for `α ≤` [`regimes::linear_limit_dissipative`] (`α_c1(e_n)` for
/// `γ > 1`, `α_c2` for `γ ≤ 1`; `physics.md`), and the `γ = 1` plateau `P = −e_n` for
/// `α ≥ 2/7` (measured: within 2e-7 at 4096 steps for e_n = 0.7, α = 1.01–3 × 2/7; at γ = 1
/// the stuck tangential motion is the normal motion, damping included).
pub fn dissipative_closed_form(gamma: f64, alpha: f64, e_n: f64) -> Option<f64> {
    if alpha <= regimes::linear_limit_dissipative(gamma, e_n) {
        Some(regimes::full_slip_line(alpha, e_n))
    } else if gamma == 1.0 && alpha >= 2.0 / 7.0 {
        Some(-e_n)
    } else {
        None
    }
}
