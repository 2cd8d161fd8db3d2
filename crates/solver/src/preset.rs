//! Named accuracy presets: `fast`, `standard`, `reference`.
//!
//! A preset is a tolerance on the absolute error of `P(γ, α)` for the accurate scheme's
//! automatic refinement ([`super::Accuracy::Tolerance`]). The measured error and cost of each,
//! over the accuracy study's points, are in `docs/accuracy.md` (`sweep accuracy`).

use serde::Serialize;

use super::error::PhysicsError;

/// An accuracy preset of the accurate scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// Error estimate ≤ 1e-4 on `P`: the minimum four refinement levels almost everywhere,
    /// 0.05–0.5 ms per impact at the study's points. For quick looks, DEM runs whose other
    /// inputs are uncertain to 1e-3.
    Fast,
    /// Error estimate ≤ 1e-6 (the default of `sweep impact`): 0.05–5.4 ms per impact at the
    /// study's points.
    #[default]
    Standard,
    /// Error estimate ≤ 1e-8: for checking other codes and tables; 0.5–141 ms per impact at
    /// the study's points, the most at large γ.
    Reference,
}

impl Preset {
    /// Every preset, from the fastest.
    pub const ALL: [Preset; 3] = [Preset::Fast, Preset::Standard, Preset::Reference];

    /// Tolerance on the absolute error of `P` (the solver's error estimate is ≤ this).
    pub fn tolerance(self) -> f64 {
        match self {
            Preset::Fast => 1e-4,
            Preset::Standard => 1e-6,
            Preset::Reference => 1e-8,
        }
    }

    /// Name as used on the command line and in configs.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Fast => "fast",
            Preset::Standard => "standard",
            Preset::Reference => "reference",
        }
    }

    /// Parse a preset name (`fast`, `standard`, `reference`; case-insensitive).
    pub fn from_name(name: &str) -> Result<Self, PhysicsError> {
        let n = name.trim().to_ascii_lowercase();
        Self::ALL
            .into_iter()
            .find(|p| p.name() == n)
            .ok_or_else(|| PhysicsError::UnknownPreset {
                name: name.to_string(),
                allowed: "fast, standard or reference",
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_tolerances_tighten() {
        for p in Preset::ALL {
            assert_eq!(Preset::from_name(p.name()), Ok(p));
            assert_eq!(Preset::from_name(&p.name().to_uppercase()), Ok(p));
        }
        assert!(Preset::from_name("fastest").is_err());
        let tols: Vec<f64> = Preset::ALL.iter().map(|p| p.tolerance()).collect();
        assert!(tols.windows(2).all(|w| w[1] < w[0]), "{tols:?}");
        assert_eq!(Preset::default().tolerance(), 1e-6);
    }
}
