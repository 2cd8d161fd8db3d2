//! Errors of the physics core.

use thiserror::Error;

use crate::resolution::Resolution;

/// Errors returned by the physics core. Messages name the parameter and the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PhysicsError {
    /// A parameter is outside its allowed range (or NaN).
    #[error("invalid {name} = {value:?}: must be {allowed}")]
    InvalidParameter {
        /// Parameter name as the user knows it (CLI flag or field).
        name: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// A choice the contact law of the request does not take: the `euler` scheme or a
    /// discrete row of springs for a Kelvin–Voigt impact (`e_n < 1`).
    #[error("{name} = {value} is not available {case}: {allowed}")]
    NotForLaw {
        /// Parameter name as the user knows it.
        name: &'static str,
        /// The value given, as the user wrote it (`euler`, `64`).
        value: String,
        /// The case it is not available in (`for e_n < 1`).
        case: &'static str,
        /// What the law takes instead, in words.
        allowed: &'static str,
    },
    /// A body, material or incident state outside its range (the rebound algebra's check).
    #[error(transparent)]
    Input(#[from] oblique_physics::InvalidInput),
    /// The requested tolerance needs more resolution than the configured limit allows.
    #[error(
        "tolerance {tol:e} not reached: {} at {res} (limit {max_steps} steps); loosen the \
         tolerance or raise the limit",
        unreached(*achieved, *zone_steps),
        res = Resolution { springs: *springs, steps: *steps }
    )]
    ToleranceUnreachable {
        /// Requested tolerance.
        tol: f64,
        /// Best error estimate reached.
        achieved: f64,
        /// Springs at the last level (0: the continuum row).
        springs: usize,
        /// Steps at the last level.
        steps: usize,
        /// Maximum number of steps allowed.
        max_steps: usize,
        /// Where the estimate was within `tol` but the level did not resolve the approach to
        /// gross slip ([`crate::zones::Level::resolved`]): the steps that zone spanned; `∞`
        /// otherwise.
        zone_steps: f64,
    },
    /// The tolerance cannot be reached within the limits even in the most favourable case
    /// (found before anything is simulated).
    #[error(
        "tolerance {tol:e} at gamma = {gamma} is out of reach for the {scheme} scheme: it needs \
         about {res} ({work:.1e} spring-steps, {memory_mb:.0} MB), {beyond}; loosen \
         the tolerance{hint}",
        res = Resolution { springs: *springs, steps: *steps },
        beyond = exceeded(
            (*steps as f64, *max_steps as f64, "steps"),
            (*work, *max_work, "spring-steps"),
            (*memory_mb, *max_memory_mb, "MB"),
        ),
        hint = if *scheme == "euler" { " or use the accurate scheme" } else { "" }
    )]
    Infeasible {
        /// Requested tolerance.
        tol: f64,
        /// γ of the request.
        gamma: f64,
        /// Scheme name.
        scheme: &'static str,
        /// Springs the most favourable prediction needs (0: the continuum row).
        springs: usize,
        /// Steps the most favourable prediction needs.
        steps: usize,
        /// Spring-steps of that run.
        work: f64,
        /// Memory of that run (MB).
        memory_mb: f64,
        /// Step limit.
        max_steps: usize,
        /// Work limit (spring-steps).
        max_work: f64,
        /// Memory limit (MB).
        max_memory_mb: f64,
    },
    /// An unknown preset name.
    #[error("unknown preset `{name}`: must be {allowed}")]
    UnknownPreset {
        /// The name given.
        name: String,
        /// The allowed names.
        allowed: &'static str,
    },
    /// An unknown dissipation law.
    #[error("unknown law `{name}`: must be {allowed}")]
    UnknownLaw {
        /// The name given.
        name: String,
        /// The allowed names.
        allowed: &'static str,
    },
    /// A fixed resolution beyond the work or memory limit (refused before it runs).
    #[error(
        "resolution {res} is too large: {work:.1e} spring-steps and {memory_mb:.0} MB, limits \
         {max_work:.1e} spring-steps and {max_memory_mb:.0} MB; use fewer springs or steps",
        res = Resolution { springs: *springs, steps: *steps }
    )]
    TooLarge {
        /// Springs requested (0: the continuum row).
        springs: usize,
        /// Steps requested.
        steps: usize,
        /// Spring-steps of the run.
        work: f64,
        /// Memory of the run (MB).
        memory_mb: f64,
        /// Work limit (spring-steps).
        max_work: f64,
        /// Memory limit (MB).
        max_memory_mb: f64,
    },
    /// A curve or point searched for at a fixed resolution was not found.
    #[error("{what} not found{at} at {steps} steps; use more steps or a gamma range where it exists", at = if gamma.is_nan() { String::new() } else { format!(" at gamma = {gamma}") })]
    NotFound {
        /// What was searched for.
        what: &'static str,
        /// γ of the search (NaN: a search over γ).
        gamma: f64,
        /// Steps per contact time.
        steps: usize,
    },
}

impl PhysicsError {
    /// Whether the caller can fix the cause by changing an input: a parameter outside its range,
    /// an unknown preset, a resolution or tolerance beyond the work limit, a missing file. The
    /// remaining variant (a tolerance the refinement did not reach) is a limit of the solver.
    pub fn user_can_fix(&self) -> bool {
        !matches!(self, PhysicsError::ToleranceUnreachable { .. })
    }
}

impl PhysicsError {
    /// Fill in the `γ` of an [`PhysicsError::Infeasible`] raised where it was not known.
    pub fn with_gamma(mut self, g: f64) -> Self {
        if let PhysicsError::Infeasible { gamma, .. } = &mut self {
            if gamma.is_nan() {
                *gamma = g;
            }
        }
        self
    }
}

/// The limits a predicted run exceeds, in words: only those it exceeds (each `(needed, limit,
/// unit)`), or all of them where rounding hides which.
fn exceeded(steps: (f64, f64, &str), work: (f64, f64, &str), memory: (f64, f64, &str)) -> String {
    let over: Vec<String> = [steps, work, memory]
        .into_iter()
        .filter(|(need, limit, _)| need > limit)
        .map(|(_, limit, unit)| {
            if unit == "steps" {
                format!("the limit of {limit} {unit}")
            } else if unit == "MB" {
                format!("the limit of {limit:.0} {unit}")
            } else {
                format!("the limit of {limit:.1e} {unit}")
            }
        })
        .collect();
    if over.is_empty() {
        format!(
            "beyond the limits ({} steps, {:.1e} spring-steps, {:.0} MB)",
            steps.1, work.1, memory.1
        )
    } else {
        format!("beyond {}", over.join(" and "))
    }
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

/// The first words of [`PhysicsError::ToleranceUnreachable`]: the best estimate, or why an
/// estimate within the tolerance was not accepted.
fn unreached(achieved: f64, zone_steps: f64) -> String {
    if zone_steps.is_finite() {
        format!(
            "the estimate {achieved:e} is within it, but the zone where the stuck part of the \
             contact shrinks to nothing before gross slip spans {zone_steps:.1} steps, fewer than \
             the {} its estimate needs,",
            crate::zones::ZONE_STEPS
        )
    } else {
        format!("best error estimate {achieved:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_continuum_row() {
        let unreachable = |springs| PhysicsError::ToleranceUnreachable {
            tol: 1e-9,
            achieved: 3e-8,
            springs,
            steps: 4096,
            max_steps: 1 << 20,
            zone_steps: f64::INFINITY,
        };
        let infeasible = |springs| PhysicsError::Infeasible {
            tol: 1e-12,
            gamma: 2.0,
            scheme: "accurate",
            springs,
            steps: 1 << 22,
            work: 1e12,
            memory_mb: 800.0,
            max_steps: 1 << 20,
            max_work: 1.7e10,
            max_memory_mb: 2147.0,
        };
        let too_large = |springs| PhysicsError::TooLarge {
            springs,
            steps: 1 << 22,
            work: 1e12,
            memory_mb: 800.0,
            max_work: 1.7e10,
            max_memory_mb: 2147.0,
        };
        for (continuum, springs) in [
            (unreachable(0), unreachable(1024)),
            (infeasible(0), infeasible(1024)),
            (too_large(0), too_large(1024)),
        ] {
            let (continuum, springs) = (continuum.to_string(), springs.to_string());
            assert!(continuum.contains(" continuum row x "), "{continuum}");
            assert!(!continuum.contains("springs x"), "{continuum}");
            assert!(springs.contains(" 1024 springs x "), "{springs}");
        }
        assert!(unreachable(0)
            .to_string()
            .contains("at continuum row x 4096 steps (limit 1048576 steps)"));
        assert!(infeasible(0)
            .to_string()
            .contains("needs about continuum row x 4194304 steps ("));
        // Only the limits the run exceeds: steps and work, not memory (800 of 2147 MB).
        let e = infeasible(0).to_string();
        assert!(
            e.contains("beyond the limit of 1048576 steps and the limit of 1.7e10 spring-steps;"),
            "{e}"
        );
        assert!(!e.contains("2147"), "{e}");
        assert!(too_large(0)
            .to_string()
            .starts_with("resolution continuum row x 4194304 steps is too large"));
    }
}
