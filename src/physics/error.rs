//! Errors of the physics core.

use thiserror::Error;

/// Errors returned by the physics core. Messages name the parameter and the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PhysicsError {
    /// A parameter is outside its allowed range (or NaN).
    #[error("invalid {name} = {value}: must be {allowed}")]
    InvalidParameter {
        /// Parameter name as the user knows it (CLI flag or field).
        name: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// The requested tolerance needs more resolution than the configured limit allows.
    #[error(
        "tolerance {tol:e} not reached: best error estimate {achieved:e} at {springs} springs x \
         {steps} steps (limit {max_steps} steps); loosen --tol or raise the limit"
    )]
    ToleranceUnreachable {
        /// Requested tolerance.
        tol: f64,
        /// Best error estimate reached.
        achieved: f64,
        /// Springs at the last level.
        springs: usize,
        /// Steps at the last level.
        steps: usize,
        /// Maximum number of steps allowed.
        max_steps: usize,
    },
}

/// Check `value` is finite and `> 0`.
pub fn positive(name: &'static str, value: f64) -> Result<f64, PhysicsError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(PhysicsError::InvalidParameter {
            name,
            value,
            allowed: "a finite number > 0",
        })
    }
}
