//! The resolution of one simulation ([`Resolution`]): springs on the half-row and time steps
//! per contact time. A type of its own, shared by the loop, the sub-models and the errors.

use serde::Serialize;

/// Spatial and temporal resolution of one simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Resolution {
    /// Springs on the half-row `[0, a_max]`; `0` selects the continuum limit of the row
    /// ([`crate::continuum::ContinuumRow`], exact in space: the default of the accurate
    /// scheme's automatic refinement). The Euler scheme needs at least 2.
    pub springs: usize,
    /// Time steps per contact time.
    pub steps: usize,
}

/// `"N springs x M steps"`, or `"continuum row x M steps"` for the continuum row
/// (`springs = 0`); the wording of the error messages.
impl std::fmt::Display for Resolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.springs == 0 {
            write!(f, "continuum row x {} steps", self.steps)
        } else {
            write!(f, "{} springs x {} steps", self.springs, self.steps)
        }
    }
}

impl Resolution {
    /// Both counts multiplied by `2^k`.
    pub fn doubled(self, k: u32) -> Self {
        Self {
            springs: self.springs << k,
            steps: self.steps << k,
        }
    }
}
