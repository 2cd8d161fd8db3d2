//! The elastic law's models behind the traits of [`crate::model`]: the Hertz normal motion
//! ([`NormalTrajectory`], tabulated on the contact's time grid) and the two tangential rows,
//! the MDR continuum row ([`ContinuumRow`], exact in space) and the seed's row of springs
//! ([`SpringRow`]). They answer the traits' law-specific questions (reach, force at first
//! touch, viscous share) with the traits' elastic defaults.

use crate::continuum::ContinuumRow;
use crate::hertz::NormalTrajectory;
use crate::model::{grid_accessors, NormalModel, TangentialModel};
use crate::springs::{SpringRow, StepMotion, StepResult};

impl TangentialModel for ContinuumRow {
    const LOCATES_GROSS_SLIP: bool = true;
    #[inline(always)]
    fn at_limit(&self) -> (bool, bool) {
        ContinuumRow::at_limit(self)
    }
    #[inline(always)]
    fn stuck(&self) -> bool {
        ContinuumRow::stuck(self)
    }
    #[inline(always)]
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        ContinuumRow::step_accurate(self, m, d1, c)
    }
}

impl TangentialModel for SpringRow {
    #[inline(always)]
    fn at_limit(&self) -> (bool, bool) {
        SpringRow::at_limit(self)
    }
    #[inline(always)]
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        SpringRow::step_accurate(self, m, d1, c)
    }
}

/// Hertz, elastic: `d̈ = −k (1/m1 + 1/m2) d^{3/2}`, tabulated on the contact's grid.
impl NormalModel for NormalTrajectory {
    grid_accessors!();
    #[inline(always)]
    fn acceleration(&self, d: f64, _rate: f64) -> f64 {
        -self.accel_factor * d * d.max(0.0).sqrt()
    }
    #[inline(always)]
    fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        NormalTrajectory::within_step(self, n, t)
    }
}
