//! The registry of contact laws: the one list of the laws ([`laws!`], one line per law), from
//! which their names ([`Law`]), the one place a name picks its implementation of
//! [`ContactLaw`] ([`with_law!`]), their parameters as answers report them
//! ([`LawParameters`]) and as physical bodies take them ([`BodiesLaw`]) are generated; and the
//! rules that pick the law once for a request: by name, by `e_n` where none is named
//! ([`Law::for_restitution`]), and the elastic solver wherever `e_n = 1` ([`Law::answering`]).
//! A new law is its folder and one more line of the list below.

use serde::Serialize;

use crate::error::PhysicsError;
use crate::law::{BodiesNormal, ContactLaw, PARAMETER_KEYS};
use crate::{elastic, kelvin_voigt};

/// `"a"`, `"a or b"`, `"a, b or c"`: the names of a list in words, at compile time.
macro_rules! or_list {
    ($a:literal) => { $a };
    ($a:literal, $b:literal) => { concat!($a, " or ", $b) };
    ($a:literal, $($rest:literal),+) => { concat!($a, ", ", or_list!($($rest),+)) };
}

/// The laws, one line each: `Variant => implementation of ContactLaw, "name";` (with the
/// variant's doc comment). `$d` is `$`, for the macro it defines ([`with_law!`]).
macro_rules! laws {
    ($d:tt $( $(#[$doc:meta])* $variant:ident => $imp:ty, $name:literal; )+) => {
        /// A contact law, by name (`physics.md`: the elastic model and its dissipative laws).
        /// Within a law `P` depends on `(γ, α, e_n)` only; across laws it does not, so every
        /// answer names its law.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Hash)]
        #[serde(rename_all = "kebab-case")]
        pub enum Law {
            $( $(#[$doc])* $variant, )+
        }

        impl Law {
            /// Every law.
            pub const ALL: [Law; [$( Law::$variant ),+].len()] = [$( Law::$variant ),+];

            /// The names of the laws in words (`"elastic or kelvin-voigt"`), for messages.
            pub const NAMES: &'static str = or_list!($( $name ),+);

            /// Name as used on the command line, in configs and in outputs.
            pub fn name(self) -> &'static str {
                match self {
                    $( Law::$variant => $name, )+
                }
            }

            /// This law with its parameters for a checked `e_n` ([`ContactLaw::parameters`]).
            pub fn parameters(self, e_n: f64) -> Result<LawParameters, PhysicsError> {
                match self {
                    $( Law::$variant => <$imp>::parameters(e_n).map(LawParameters::$variant), )+
                }
            }
        }

        /// `$body` with `$L` the [`ContactLaw`] implementation of the law `$law`: the one place
        /// a law's name picks its implementation.
        macro_rules! with_law {
            ($d law:expr, $d L:ident => $d body:expr) => {
                match $d law {
                    $( $crate::registry::Law::$variant => {
                        type $d L = $imp;
                        $d body
                    } )+
                }
            };
        }

        /// A law with its parameters, as answers report them ([`crate::Solution::law`],
        /// [`crate::units::PhysicalOutcome::law`]): each law's own typed value.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize)]
        #[serde(rename_all = "kebab-case")]
        pub enum LawParameters {
            $( $(#[$doc])* $variant(<$imp as ContactLaw>::Parameters), )+
        }

        impl LawParameters {
            /// The law.
            pub fn law(&self) -> Law {
                match self {
                    $( LawParameters::$variant(_) => Law::$variant, )+
                }
            }

            /// The values of [`PARAMETER_KEYS`], in their order ([`ContactLaw::values`]).
            pub fn values(&self) -> [f64; PARAMETER_KEYS.len()] {
                match self {
                    $( LawParameters::$variant(p) => <$imp>::values(p), )+
                }
            }

            /// The parameters in words with their units, for a line of text (`None` for a law
            /// without parameters; [`ContactLaw::describe`]).
            pub fn describe(&self) -> Option<String> {
                match self {
                    $( LawParameters::$variant(p) => <$imp>::describe(p), )+
                }
            }
        }

        /// A law with the parameters physical bodies take in SI units
        /// ([`crate::units::PhysicalImpact::law`]; [`ContactLaw::BodiesParameters`]).
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum BodiesLaw {
            $( $(#[$doc])* $variant(<$imp as ContactLaw>::BodiesParameters), )+
        }

        impl BodiesLaw {
            /// The law.
            pub fn law(&self) -> Law {
                match self {
                    $( BodiesLaw::$variant(_) => Law::$variant, )+
                }
            }

            /// Check the parameters and find, for the bodies' normal constants, the law's
            /// dimensionless parameters and the impact's `e_n` ([`ContactLaw::of_bodies`]).
            pub fn of_bodies(&self, normal: &BodiesNormal) -> Result<(LawParameters, f64), PhysicsError> {
                match *self {
                    $( BodiesLaw::$variant(p) => <$imp>::of_bodies(p, normal)
                        .map(|(q, e_n)| (LawParameters::$variant(q), e_n)), )+
                }
            }
        }

        /// `$body` with `$L` the [`ContactLaw`] implementation of the law of the physical
        /// parameters `$bodies` ([`BodiesLaw`]) and `$p` those parameters.
        macro_rules! with_bodies_law {
            ($d bodies:expr, $d L:ident, $d p:ident => $d body:expr) => {
                match $d bodies {
                    $( $crate::registry::BodiesLaw::$variant($d p) => {
                        type $d L = $imp;
                        $d body
                    } )+
                }
            };
        }
    };
}

laws! { $
    /// Perfectly elastic springs: `e_n = 1`.
    Elastic => crate::elastic::Elastic, "elastic";
    /// Kelvin–Voigt springs, one relaxation time `τ` in both directions, non-adhesive:
    /// `e_n ∈ [0.3, 1]` (`e_n = 1` is the elastic law exactly).
    KelvinVoigt => crate::kelvin_voigt::KelvinVoigt, "kelvin-voigt";
    /// Thornton's elastic–perfectly plastic law (Thornton 1997): Hertz up to the limiting
    /// pressure `p_y`, the pressure capped at `p_y` beyond, Hertz unloading of a larger radius:
    /// `e_n ∈ [0.3, 1]` (`e_n = 1` is the elastic law exactly).
    Thornton => crate::thornton::Thornton, "thornton";
    /// Thornton's loading with the MDR's own unloading (every spring shortens by the same
    /// `d_max − d`): its limits do not jump at the switch. For comparison with Thornton's law
    /// (solver only): `e_n ∈ [0.3, 1]`.
    ThorntonMdr => crate::thornton_mdr::ThorntonMdr, "thornton-mdr";
}
pub(crate) use {with_bodies_law, with_law};

impl Law {
    /// Parse a law name (case-insensitive; [`Law::NAMES`]).
    pub fn from_name(name: &str) -> Result<Self, PhysicsError> {
        let n = name.trim().to_ascii_lowercase();
        Self::ALL
            .into_iter()
            .find(|l| l.name() == n)
            .ok_or_else(|| PhysicsError::UnknownLaw {
                name: name.to_string(),
                allowed: Law::NAMES,
            })
    }

    /// The law an `e_n` implies when none is named: elastic at 1, Kelvin–Voigt below.
    pub fn for_restitution(e_n: f64) -> Self {
        if e_n == 1.0 {
            Law::Elastic
        } else {
            Law::KelvinVoigt
        }
    }

    /// Check `e_n` for this law ([`ContactLaw::check_restitution`]): exactly 1 for the elastic
    /// law, `[0.3, 1]` for Kelvin–Voigt.
    pub fn check_restitution(self, e_n: f64) -> Result<f64, PhysicsError> {
        with_law!(self, L => L::check_restitution(e_n))
    }

    /// `P(γ, α, e_n)` where this law has it exactly without simulation (`None` elsewhere;
    /// [`ContactLaw::closed_form`]); `γ`, `α` and `e_n` checked.
    pub fn closed_form(self, gamma: f64, alpha: f64, e_n: f64) -> Option<f64> {
        with_law!(self.answering(e_n), L => L::closed_form(gamma, alpha, e_n))
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
}

impl LawParameters {
    /// The law's name ([`Law::name`]).
    pub fn name(&self) -> &'static str {
        self.law().name()
    }
}

impl BodiesLaw {
    /// Bodies of the Kelvin–Voigt law with relaxation time `τ` (s), elastic ones for `τ = 0`
    /// (any other value, NaN and negatives included, is the Kelvin–Voigt law's to check).
    pub fn of_relaxation_time(tau: f64) -> BodiesLaw {
        if tau == 0.0 {
            BodiesLaw::default()
        } else {
            BodiesLaw::KelvinVoigt(kelvin_voigt::BodiesParameters {
                relaxation_time: tau,
            })
        }
    }
}

/// The elastic law.
impl Default for Law {
    fn default() -> Self {
        Law::Elastic
    }
}

/// Elastic bodies.
impl Default for BodiesLaw {
    fn default() -> Self {
        BodiesLaw::Elastic(elastic::Parameters)
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
    use crate::thornton::Thornton;

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
        assert_eq!(BodiesLaw::of_relaxation_time(1e-6).law(), Law::KelvinVoigt);
        assert_eq!(BodiesLaw::of_relaxation_time(0.0).law(), Law::Elastic);
        assert_eq!(
            BodiesLaw::of_relaxation_time(f64::NAN).law(),
            Law::KelvinVoigt
        );
        assert!(picks::<Thornton>(Law::Thornton));
        assert_eq!(Law::Thornton.answering(0.9), Law::Thornton);
        assert_eq!(
            Law::NAMES,
            "elastic, kelvin-voigt, thornton or thornton-mdr"
        );
        assert_eq!(
            Law::from_name("plastic"),
            Err(PhysicsError::UnknownLaw {
                name: "plastic".into(),
                allowed: "elastic, kelvin-voigt, thornton or thornton-mdr",
            })
        );
    }
}
