//! Rebound queries answered from a table: `γ` from the materials (or given), `α` from `μ` and
//! the incident state, `P(γ, α)` from the surface, the post-impact state from [`crate::rebound`].
//! SI units; conventions as in [`crate::rebound`].

use crate::rebound::{Elastic, Incident, Incident3, Pair, Rebound, Rebound3};
use crate::{LookupError, Prepared, Table};
use oblique_table::surface::OutOfDomain;

/// What fixes the material group `γ` of a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stiffness {
    /// `γ` itself, the group that enters `P`: `γ² = (m*/m_t) G*/E*` for this pair
    /// (`√((7/2) G*/E*)` for one solid sphere on a wall). Finite, `> 0`.
    Gamma(f64),
    /// The elastic constants of sphere 1 and of the other body (wall or sphere 2); `γ` follows
    /// from `E*`, `G*` ([`crate::rebound::effective_moduli`]) and the pair's `m*/m_t`.
    Materials(Elastic, Elastic),
}

/// Contact properties of an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Elastic group.
    pub stiffness: Stiffness,
    /// Coulomb friction coefficient `μ ≥ 0` (`∞` for no slip).
    pub friction: f64,
    /// What a `γ` outside the table's domain does (default: an error).
    pub outside: OutOfDomain,
    /// Normal restitution `e_n` of the impact (1 for an elastic one): the table must answer it
    /// (an elastic table `e_n = 1` only, one with an `e_n` axis its range), and the normal
    /// relative velocity reverses to `e_n` times its value.
    pub restitution: f64,
}

impl Contact {
    /// A contact with `γ` given directly, refusing points outside the table's domain.
    pub fn with_gamma(gamma: f64, friction: f64) -> Contact {
        Contact {
            stiffness: Stiffness::Gamma(gamma),
            friction,
            outside: OutOfDomain::Error,
            restitution: 1.0,
        }
    }

    /// A contact between two materials, refusing points outside the table's domain.
    pub fn with_materials(sphere: Elastic, other: Elastic, friction: f64) -> Contact {
        Contact {
            stiffness: Stiffness::Materials(sphere, other),
            friction,
            outside: OutOfDomain::Error,
            restitution: 1.0,
        }
    }

    /// The same contact with normal restitution `e_n` ([`Contact::restitution`]).
    pub fn with_restitution(self, e_n: f64) -> Contact {
        Contact {
            restitution: e_n,
            ..self
        }
    }

    /// `γ` of this contact for `pair` (dimensionless).
    pub fn gamma(&self, pair: &Pair) -> Result<f64, LookupError> {
        match self.stiffness {
            Stiffness::Gamma(g) => {
                if g.is_finite() && g > 0.0 {
                    Ok(g)
                } else {
                    Err(LookupError::Query {
                        name: "gamma",
                        value: g,
                        allowed: "a finite number > 0".into(),
                    })
                }
            }
            Stiffness::Materials(a, b) => Ok(pair.gamma_from_materials(&a, &b)?),
        }
    }
}

/// `γ`, `α` and `P` of one impact, with the post-impact state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Answer<R> {
    /// The material group `γ` used (dimensionless).
    pub gamma: f64,
    /// The friction group `α = (2/7)(m*/m_t) μ v_z0/|u0|` (`∞` when `u0 = 0`).
    pub alpha: f64,
    /// The post-impact state ([`Rebound`] or [`Rebound3`]); its `p` is `P(γ, α)` (NaN when
    /// `u0 = 0`: then `P` is not looked up, but an `e_n` the table does not answer is refused
    /// all the same, [`Table::check_restitution`]).
    pub rebound: R,
}

impl Table {
    fn p_for(
        &self,
        pair: &Pair,
        s: &Incident,
        gamma: f64,
        alpha: f64,
        contact: &Contact,
    ) -> Result<f64, LookupError> {
        if pair.slip_velocity(s) == 0.0 {
            // u0 = 0: a pure normal impact, P is not needed; an e_n the table does not answer
            // is refused all the same, as on every other path and in every binding.
            self.check_restitution(contact.restitution)?;
            return Ok(f64::NAN);
        }
        self.p_e_with(gamma, alpha, contact.restitution, contact.outside)
    }

    /// A 2-D impact in its plane (sphere–wall when `pair.other` is `None`, else
    /// sphere–sphere): `γ`, `α`, `P` from the table, then [`Pair::rebound`].
    pub fn rebound(
        &self,
        pair: &Pair,
        contact: &Contact,
        s: &Incident,
    ) -> Result<Answer<Rebound>, LookupError> {
        let gamma = contact.gamma(pair)?;
        let alpha = pair.alpha(s, contact.friction)?;
        let p = self.p_for(pair, s, gamma, alpha, contact)?;
        Ok(Answer {
            gamma,
            alpha,
            rebound: pair.rebound_dissipative(s, p, contact.restitution)?,
        })
    }

    /// A 3-D impact (velocity and spin vectors, contact normal): reduced to its plane of impact
    /// ([`Pair::plane`]), answered there, and applied back ([`Pair::rebound_3d`]). Components
    /// the model has no force for (spin about the normal, velocity and spin across the plane)
    /// are returned unchanged.
    ///
    /// Checks `pair` and `contact` and computes `γ` on every call; for many impacts of one
    /// pair, [`Prepared::new`] once and [`Table::rebound_3d_prepared`] are faster (the same
    /// answer).
    pub fn rebound_3d(
        &self,
        pair: &Pair,
        contact: &Contact,
        s: &Incident3,
    ) -> Result<Answer<Rebound3>, LookupError> {
        match Prepared::new(pair, contact) {
            Ok(k) => self.rebound_3d_prepared(&k, s),
            // The step-by-step path reports the first invalid input in its order.
            Err(_) => self.rebound_3d_steps(pair, contact, s),
        }
    }

    /// [`Table::rebound_3d`] step by step: [`Pair::plane`], `α`, `P`, then
    /// [`Pair::rebound_3d`]'s algebra.
    pub(crate) fn rebound_3d_steps(
        &self,
        pair: &Pair,
        contact: &Contact,
        s: &Incident3,
    ) -> Result<Answer<Rebound3>, LookupError> {
        let gamma = contact.gamma(pair)?;
        let plane = pair.plane(s)?;
        let alpha = pair.alpha(&plane.incident, contact.friction)?;
        let p = self.p_for(pair, &plane.incident, gamma, alpha, contact)?;
        Ok(Answer {
            gamma,
            alpha,
            rebound: pair.rebound_in_plane_dissipative(s, &plane, p, contact.restitution)?,
        })
    }
}
