//! The registry of contact laws: the one place a [`Law`] name picks its implementation of
//! [`ContactLaw`] ([`with_law!`]), and the rules that pick the law once for a request: by name,
//! by `e_n` where none is named ([`Law::for_restitution`]), and the elastic solver wherever
//! `e_n = 1` ([`Law::answering`]). A new law is one more arm of [`with_law!`] (and its name in
//! [`Law`]).

use crate::error::PhysicsError;
use crate::law::{ContactLaw, Law};

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
