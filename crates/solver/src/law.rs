//! The dissipation law of an impact, picked by name: `elastic` (`e_n = 1`, the model of
//! `physics.md`) or `kelvin-voigt` (every MDR spring a Kelvin–Voigt element with one relaxation
//! time in the normal and tangential direction, non-adhesive unloading; `physics.md`,
//! "Dissipative impacts"). Within a law, `P` depends on `(γ, α, e_n)` only; across laws it
//! does not, so every answer names its law.

use serde::Serialize;

use crate::error::PhysicsError;

/// Smallest normal restitution the solver takes (the Kelvin–Voigt law's range is
/// `[MIN_RESTITUTION, 1]`).
pub const MIN_RESTITUTION: f64 = 0.3;

/// Check a normal restitution: finite, in `[0.3, 1]` (`[MIN_RESTITUTION, 1]`).
pub fn check_restitution(e_n: f64) -> Result<f64, PhysicsError> {
    if (MIN_RESTITUTION..=1.0).contains(&e_n) {
        Ok(e_n)
    } else {
        Err(PhysicsError::InvalidParameter {
            name: "e_n",
            value: e_n,
            allowed: "a number in [0.3, 1] (1: elastic)",
        })
    }
}

/// The floor of the Richardson estimate as a share of the last raw difference
/// `|P_k − P_{k−1}|`: `regular` where the last two ratios of successive differences are within
/// `[0.75, 1.375] · 2^p` (clean convergence at order `p`), `irregular` elsewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floor {
    /// Share where the convergence is regular.
    pub regular: f64,
    /// Share elsewhere (and while fewer than four values exist).
    pub irregular: f64,
}

impl Floor {
    /// One share whatever the convergence.
    pub const fn fixed(share: f64) -> Self {
        Floor {
            regular: share,
            irregular: share,
        }
    }
}

/// A dissipation law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default, Hash)]
#[serde(rename_all = "kebab-case")]
pub enum Law {
    /// Perfectly elastic springs: `e_n = 1`.
    #[default]
    Elastic,
    /// Kelvin–Voigt springs, one relaxation time `τ` in both directions, non-adhesive:
    /// `e_n ∈ [0.3, 1]` (`e_n = 1` is the elastic law exactly).
    KelvinVoigt,
}

impl Law {
    /// Every law.
    pub const ALL: [Law; 2] = [Law::Elastic, Law::KelvinVoigt];

    /// Name as used on the command line, in configs and in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Law::Elastic => "elastic",
            Law::KelvinVoigt => "kelvin-voigt",
        }
    }

    /// Parse a law name (`elastic`, `kelvin-voigt`; case-insensitive).
    pub fn from_name(name: &str) -> Result<Self, PhysicsError> {
        let n = name.trim().to_ascii_lowercase();
        Self::ALL
            .into_iter()
            .find(|l| l.name() == n)
            .ok_or_else(|| PhysicsError::UnknownLaw {
                name: name.to_string(),
                allowed: "elastic or kelvin-voigt",
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

    /// Check `e_n` for this law: exactly 1 for the elastic law, `[0.3, 1]` for Kelvin–Voigt.
    pub fn check_restitution(self, e_n: f64) -> Result<f64, PhysicsError> {
        match self {
            Law::Elastic if e_n == 1.0 => Ok(e_n),
            Law::Elastic => Err(PhysicsError::InvalidParameter {
                name: "e_n",
                value: e_n,
                allowed: "1 for the elastic law (name the kelvin-voigt law for e_n < 1)",
            }),
            Law::KelvinVoigt => check_restitution(e_n),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
