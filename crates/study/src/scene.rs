//! Scenes: a user's materials and impact conditions in, their rebound curves out.
//!
//! A scene file (TOML, [`Scene`]) names two bodies (sphere–wall or sphere–sphere), the friction
//! coefficient and a sweep of impact conditions ([`Cases`]). [`evaluate`] maps every case to
//! `(γ, α)`, gets `P` from a table (`oblique_lookup::Table`) or by simulating only that point
//! (closed forms are never simulated), and turns `P` into the rebound with
//! [`oblique_lookup::rebound`]. Alongside the model it computes the seed's closed-form
//! approximation `e_t = 1 − μ(1 + e_n) v_z0/v_x0` (the full-slip line `P = 1 − 7α` used
//! everywhere) and the classical rolling solution (`P = 0`), and, when the scene names measured
//! data, the RMS difference to it. [`csv`] writes the result table, [`figure`] builds its plot.
//!
//! Nothing here prints; the `sweep scene` command is a thin front end.

pub mod csv;
mod eval;
pub mod figure;
mod format;
/// The material catalogue (it lives in `oblique-physics`, where Python reads it too).
pub use oblique_physics::materials;
pub mod measured;
mod spec;

pub use eval::{evaluate, Evaluation, PSource, Rms, Row, RowMethod};
pub use measured::MeasuredPoint;
pub use spec::{
    CaseKind, Cases, Dissipation, MaterialUse, MeasuredRef, Scene, SceneTarget, Values,
    DEFAULT_TOL, MAX_CASES,
};

use thiserror::Error;

/// Errors of scene loading and evaluation. Messages name the file, the key and the allowed range.
#[derive(Debug, Error)]
pub enum SceneError {
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// File path.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// The scene file is not valid TOML for a scene (syntax, unknown key, wrong type).
    #[error("scene {path}: {message}")]
    Parse {
        /// Scene file.
        path: String,
        /// The parser's message (with line, column and key).
        message: String,
    },
    /// A value is outside its allowed range.
    #[error("scene {path}: invalid {key} = {value}: must be {allowed}")]
    Invalid {
        /// Scene file.
        path: String,
        /// Dotted key, e.g. `sphere.radius`.
        key: String,
        /// The value given.
        value: String,
        /// The allowed range, in words.
        allowed: String,
    },
    /// The measured-data CSV is malformed.
    #[error("measured data {path}, line {line}: {message}")]
    Measured {
        /// CSV path.
        path: String,
        /// Line number (1-based).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A case could not be evaluated by the solver.
    #[error("case {x_name} = {x}: {source}")]
    Physics {
        /// Swept quantity.
        x_name: &'static str,
        /// Its value.
        x: f64,
        /// Solver error.
        source: oblique_solver::PhysicsError,
    },
    /// The table has no `e_n` axis covering a case's `e_n`.
    #[error(
        "case {x_name} = {x}: the table {what}; the case has e_n = {e_n} (simulate it: run \
         without --table, or give a table of its law with an e_n axis covering it)"
    )]
    Restitution {
        /// Swept quantity.
        x_name: &'static str,
        /// Its value.
        x: f64,
        /// The case's `e_n`.
        e_n: f64,
        /// What the table covers, in words.
        what: String,
    },
    /// A case could not be looked up in the table (outside its domain, …) or mapped to a
    /// rebound.
    #[error("case {x_name} = {x}: {source}")]
    Lookup {
        /// Swept quantity.
        x_name: &'static str,
        /// Its value.
        x: f64,
        /// Lookup error.
        source: oblique_lookup::LookupError,
    },
}

impl SceneError {
    /// Whether the error is the user's input (a missing, unreadable or bad scene or data file)
    /// rather than a failure of the physics or the lookup.
    pub fn user_can_fix(&self) -> bool {
        matches!(
            self,
            SceneError::Io { .. }
                | SceneError::Parse { .. }
                | SceneError::Invalid { .. }
                | SceneError::Measured { .. }
                | SceneError::Restitution { .. }
        )
    }
}
