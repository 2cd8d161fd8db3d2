//! The registry of contact laws: the one place a [`Law`] name picks its implementation of
//! [`ContactLaw`] ([`with_law!`]), and the rules that pick the law once for a request: by name,
//! by `e_n` where none is named ([`Law::for_restitution`]), and the elastic solver wherever
//! `e_n = 1` ([`Law::answering`]). A new law is one more arm of [`with_law!`] (and its name in
//! [`Law`]).

use serde::Serialize;

use crate::error::PhysicsError;
use crate::law::{ContactLaw, Law};
use crate::{elastic, kelvin_voigt};

/// `$body` with `$L` the [`ContactLaw`] implementation of the law `$law`: the one place a
/// law's name picks its implementation.
macro_rules! with_law {
    ($law:expr, $L:ident => $body:expr) => {
        match $law {
            $crate::law::Law::Elastic => {
                type $L = $crate::elastic::Elastic;
                $body
            }
            $crate::law::Law::KelvinVoigt => {
                type $L = $crate::kelvin_voigt::KelvinVoigt;
                $body
            }
        }
    };
}
pub(crate) use with_law;

impl Law {
    /// Check `e_n` for this law ([`ContactLaw::check_restitution`]): exactly 1 for the elastic
    /// law, `[0.3, 1]` for Kelvin–Voigt.
    pub fn check_restitution(self, e_n: f64) -> Result<f64, PhysicsError> {
        with_law!(self, L => L::check_restitution(e_n))
    }

    /// This law with its parameters for a checked `e_n` ([`ContactLaw::parameters`]).
    pub fn parameters(self, e_n: f64) -> Result<LawParameters, PhysicsError> {
        with_law!(self, L => L::parameters(e_n).map(LawParameters::from))
    }

    /// The law whose solver answers a request for this law at a checked `e_n`: the elastic law
    /// at `e_n = 1` whatever the name (every law here is the elastic one there: the same
    /// operations, the same bits), this law below.
    pub fn answering(self, e_n: f64) -> Law {
        if e_n == 1.0 {
            Law::Elastic
        } else {
            self
        }
    }

    /// The law of physical bodies with relaxation time `τ` (s, checked ≥ 0): Kelvin–Voigt for
    /// `τ > 0`, elastic for `τ = 0`.
    pub fn of_relaxation_time(tau: f64) -> Law {
        if tau > 0.0 {
            Law::KelvinVoigt
        } else {
            Law::Elastic
        }
    }
}

/// A law with its parameters, as answers report them ([`crate::Solution::law`],
/// [`crate::units::PhysicalOutcome::law`]): each law's own typed value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LawParameters {
    /// The elastic law (no parameters).
    Elastic(elastic::Parameters),
    /// The Kelvin–Voigt law with its relaxation time `τ̂`.
    KelvinVoigt(kelvin_voigt::Parameters),
}

impl From<elastic::Parameters> for LawParameters {
    fn from(p: elastic::Parameters) -> Self {
        LawParameters::Elastic(p)
    }
}

impl From<kelvin_voigt::Parameters> for LawParameters {
    fn from(p: kelvin_voigt::Parameters) -> Self {
        LawParameters::KelvinVoigt(p)
    }
}

/// The keys under which outputs report the laws' parameters, one layout for every law so that
/// answers of different laws share their columns (the JSON of `sweep impact`, the columns of
/// Python's `impact`, the dict of its `simulate`): `tau`, the dimensionless relaxation time
/// `τ̂` (0 for the elastic law, which is the Kelvin–Voigt law at `τ̂ = 0`).
pub const PARAMETER_KEYS: [&str; 1] = ["tau"];

impl LawParameters {
    /// The law.
    pub fn law(&self) -> Law {
        match self {
            LawParameters::Elastic(_) => Law::Elastic,
            LawParameters::KelvinVoigt(_) => Law::KelvinVoigt,
        }
    }

    /// The law's name ([`Law::name`]).
    pub fn name(&self) -> &'static str {
        self.law().name()
    }

    /// The values of [`PARAMETER_KEYS`], in their order.
    pub fn values(&self) -> [f64; PARAMETER_KEYS.len()] {
        match self {
            LawParameters::Elastic(_) => [0.0],
            LawParameters::KelvinVoigt(p) => [p.tau],
        }
    }

    /// The parameters in words with their units, for a line of text (`None` for the elastic
    /// law, which has none).
    pub fn describe(&self) -> Option<String> {
        match self {
            LawParameters::Elastic(_) => None,
            LawParameters::KelvinVoigt(p) => Some(p.to_string()),
        }
    }

    /// The parameters of physical bodies with relaxation time `τ` (s) whose dimensionless
    /// relaxation time is `τ̂`: the law of [`Law::of_relaxation_time`] with `τ̂`.
    pub fn of_bodies(relaxation_time: f64, tau_hat: f64) -> Self {
        match Law::of_relaxation_time(relaxation_time) {
            Law::Elastic => elastic::Parameters.into(),
            Law::KelvinVoigt => kelvin_voigt::Parameters { tau: tau_hat }.into(),
        }
    }
}

/// Whether `L` is the implementation [`with_law!`] picks for `law` (a check of the registry).
#[cfg(test)]
fn picks<L: ContactLaw + 'static>(law: Law) -> bool {
    with_law!(law, M => std::any::TypeId::of::<M>() == std::any::TypeId::of::<L>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elastic::Elastic;
    use crate::kelvin_voigt::KelvinVoigt;

    #[test]
    fn names_round_trip_and_the_elastic_law_takes_only_one() {
        for l in Law::ALL {
            assert_eq!(Law::from_name(l.name()), Ok(l));
            assert_eq!(Law::from_name(&l.name().to_uppercase()), Ok(l));
        }
        assert!(Law::from_name("viscous").is_err());
        assert!(Law::Elastic.check_restitution(0.9).is_err());
        assert_eq!(Law::Elastic.check_restitution(1.0), Ok(1.0));
        for bad in [0.29, 1.01, f64::NAN, f64::INFINITY, -0.5] {
            assert!(Law::KelvinVoigt.check_restitution(bad).is_err(), "{bad}");
        }
        assert_eq!(Law::for_restitution(0.9), Law::KelvinVoigt);
        assert_eq!(Law::for_restitution(1.0), Law::Elastic);
    }

    #[test]
    fn the_registry_picks_each_law_once_and_the_elastic_solver_at_e_n_1() {
        assert!(picks::<Elastic>(Law::Elastic));
        assert!(picks::<KelvinVoigt>(Law::KelvinVoigt));
        assert!(!picks::<Elastic>(Law::KelvinVoigt));
        for law in Law::ALL {
            assert_eq!(law.answering(1.0), Law::Elastic, "{law:?}");
        }
        assert_eq!(Law::KelvinVoigt.answering(0.9), Law::KelvinVoigt);
        assert_eq!(Law::of_relaxation_time(1e-6), Law::KelvinVoigt);
        assert_eq!(Law::of_relaxation_time(0.0), Law::Elastic);
        assert_eq!(
            Law::from_name("plastic"),
            Err(PhysicsError::UnknownLaw {
                name: "plastic".into(),
                allowed: "elastic or kelvin-voigt",
            })
        );
    }
}
