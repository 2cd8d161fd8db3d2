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

use crate::error::PhysicsError;
use crate::impact::{Limits, Resolution, Scheme};
use crate::law::ContactLaw;
use crate::preset::Preset;
use crate::refine::{solve_core, Accuracy, RefineEvent, Solution};
use crate::registry::with_law;
use crate::registry::Law;
use crate::zones::Level;

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
    /// The registry picks the law once ([`Law::answering`]): `e_n = 1` is answered by the
    /// elastic law whatever the law named (the same operations, the same bits); below it, the
    /// named law. That law checks the request and finds its parameters
    /// ([`ContactLaw::prepare`]: the Kelvin–Voigt law the relaxation time `τ̂` that gives `e_n`,
    /// [`crate::kelvin_voigt::tau_for_restitution`]), answers in closed form where that is exact
    /// ([`ContactLaw::closed_form`]) and otherwise has its simulation refined to the accuracy
    /// asked, with its own floor of the estimate ([`ContactLaw::FLOOR`]).
    pub fn solve_observed(
        &self,
        observer: &mut dyn FnMut(RefineEvent),
    ) -> Result<Solution, PhysicsError> {
        let e_n = self.law.check_restitution(self.e_n)?;
        with_law!(self.law.answering(e_n), L => self.solve_with::<L>(e_n, observer, None))
    }

    /// [`Request::solve`] that keeps the levels of its automatic refinement in `kept` and takes
    /// those `kept` already holds instead of simulating them again: a request solved once at
    /// one tolerance and again at a smaller one continues from the levels of the first solve.
    /// Each level's value depends on its resolution alone, so the answer has the bits of a
    /// refinement from scratch. `kept` belongs to this request: levels kept for another one
    /// (another γ, α, `e_n`, law, scheme or limits) are dropped first. A fixed resolution keeps
    /// nothing.
    pub fn solve_continuing(&self, kept: &mut KeptLevels) -> Result<Solution, PhysicsError> {
        let e_n = self.law.check_restitution(self.e_n)?;
        let owner = self.owner();
        if kept.owner != Some(owner) {
            *kept = KeptLevels {
                owner: Some(owner),
                levels: Vec::new(),
            };
        }
        let memo = matches!(self.accuracy, Accuracy::Tolerance(_)).then_some(&mut kept.levels);
        with_law!(self.law.answering(e_n), L => self.solve_with::<L>(e_n, &mut |_| {}, memo))
    }

    /// What identifies the levels of this request's refinement ([`KeptLevels`]).
    fn owner(&self) -> Owner {
        Owner {
            point: [
                self.gamma.to_bits(),
                self.alpha.to_bits(),
                self.e_n.to_bits(),
            ],
            law: self.law,
            scheme: self.scheme,
            limits: self.limits,
        }
    }

    /// `P` at a fixed resolution, simulated (no closed form, no estimate), by the law the
    /// registry picks ([`Request::solve_observed`]).
    pub fn simulate(&self, res: Resolution) -> Result<f64, PhysicsError> {
        let e_n = self.law.check_restitution(self.e_n)?;
        with_law!(self.law.answering(e_n), L => {
            let (gamma, alpha, parameters) = L::prepare(self.gamma, self.alpha, e_n, self.scheme)?;
            Ok(L::simulate(gamma, alpha, parameters, res, self.scheme)?.p)
        })
    }

    /// [`Request::solve_observed`] by the law `L` at a checked `e_n`; the answer reports the law
    /// named, with its parameters for `e_n` ([`Law::parameters`]).
    fn solve_with<L: ContactLaw>(
        &self,
        e_n: f64,
        observer: &mut dyn FnMut(RefineEvent),
        mut memo: Option<&mut Vec<Level>>,
    ) -> Result<Solution, PhysicsError> {
        let (gamma, alpha, parameters) = L::prepare(self.gamma, self.alpha, e_n, self.scheme)?;
        let closed = L::closed_form(gamma, alpha, e_n);
        let law = self.law.parameters(e_n)?;
        let mut runs = 0;
        solve_core(
            (
                gamma,
                self.accuracy,
                self.scheme,
                self.force_simulation,
                self.limits,
            ),
            (law, e_n),
            if alpha.is_finite() {
                L::FLOOR
            } else {
                L::FLOOR.without_scatter()
            },
            closed,
            |res| {
                // The refinement runs its levels in order, once each: level `k` is the
                // `k`-th run.
                let Some(kept) = memo.as_deref_mut() else {
                    return L::simulate(gamma, alpha, parameters, res, self.scheme);
                };
                let level = match kept.get(runs) {
                    Some(&level) => level,
                    None => {
                        let level = L::simulate(gamma, alpha, parameters, res, self.scheme)?;
                        kept.push(level);
                        level
                    }
                };
                runs += 1;
                Ok(level)
            },
            observer,
        )
    }
}

/// The levels of one request's automatic refinement ([`Request::solve_continuing`]): each
/// level's `P` and how finely it resolved its zones, in the order they ran (16 bytes a level).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KeptLevels {
    owner: Option<Owner>,
    levels: Vec<Level>,
}

impl KeptLevels {
    /// Nothing kept yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of levels kept.
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// Whether no level is kept.
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }
}

/// The request whose levels are kept: its point (bits), law, scheme and limits.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Owner {
    point: [u64; 3],
    law: Law,
    scheme: Scheme,
    limits: Limits,
}

/// `P(γ, α, e_n)` of the Kelvin–Voigt law where it is exact without simulation (its
/// [`ContactLaw::closed_form`]).
pub use crate::kelvin_voigt::dissipative_closed_form;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kelvin_voigt;
    use crate::registry::LawParameters;

    #[test]
    fn at_e_n_1_the_kelvin_voigt_name_takes_the_elastic_law_to_the_bit() {
        for (gamma, alpha) in [(1.754, 1.0), (0.7, 0.9), (3.2, f64::INFINITY), (2.0, 0.05)] {
            let elastic = Request::new(gamma, alpha);
            let named = elastic.e_n(1.0).law(Law::KelvinVoigt);
            let (a, b) = (elastic.solve().unwrap(), named.solve().unwrap());
            assert_eq!(a.p.to_bits(), b.p.to_bits(), "γ {gamma}, α {alpha}");
            assert_eq!(a.error_estimate.to_bits(), b.error_estimate.to_bits());
            assert_eq!((a.resolution, a.method), (b.resolution, b.method));
            assert_eq!((a.law.law(), b.law.law()), (Law::Elastic, Law::KelvinVoigt));
            assert_eq!((b.e_n, b.law.values()), (1.0, [0.0, 0.0]));
            let res = Resolution {
                springs: 0,
                steps: 256,
            };
            assert_eq!(
                elastic.simulate(res).unwrap().to_bits(),
                named.simulate(res).unwrap().to_bits()
            );
            // The Euler scheme too: at e_n = 1 no Kelvin–Voigt check applies.
            let euler = Resolution {
                springs: 64,
                steps: 256,
            };
            assert_eq!(
                elastic
                    .scheme(Scheme::Euler)
                    .simulate(euler)
                    .unwrap()
                    .to_bits(),
                named
                    .scheme(Scheme::Euler)
                    .simulate(euler)
                    .unwrap()
                    .to_bits()
            );
        }
    }

    #[test]
    fn below_1_the_named_law_answers_and_the_elastic_law_refuses() {
        let r = Request::new(1.754, 1.0).e_n(0.9);
        assert_eq!(r.law, Law::KelvinVoigt);
        let s = r.solve().unwrap();
        let tau = kelvin_voigt::tau_for_restitution(0.9).unwrap();
        assert_eq!(
            s.law,
            LawParameters::KelvinVoigt(kelvin_voigt::Parameters { tau })
        );
        assert!(matches!(
            r.law(Law::Elastic).solve(),
            Err(PhysicsError::InvalidParameter { name: "e_n", .. })
        ));
        assert!(matches!(
            r.scheme(Scheme::Euler).solve(),
            Err(PhysicsError::NotForLaw { name: "scheme", .. })
        ));
    }
}
