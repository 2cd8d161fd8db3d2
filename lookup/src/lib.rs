//! Interpolator for the universal tangential restitution `P(γ, α)` of oblique elastic impacts.
//!
//! Reads a table written by `sweep run` (HDF5, schema v2, see `docs/table-format.md`), keeps it in
//! memory and evaluates `P` by the documented rule: the exact full-slip line `P = 1 − 7α` below
//! the linear limit, otherwise local Lagrange interpolation on curve-aligned patches. No HDF5 call
//! happens on the query path. This crate never depends on the simulator.
//!
//! Symbols (as in `physics.md`): `γ = √((7/2) G*/E*)`, `α = μ v_z0/|u0|`, `P = u_after/u_before`,
//! `α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`.

pub mod format;
mod read;
pub mod rebound;
pub mod surface;

pub use read::{Check, Provenance, Table};
pub use surface::{Patch, PatchKind, Surface};

use thiserror::Error;

/// Errors of table loading and queries.
#[derive(Debug, Error)]
pub enum LookupError {
    /// The file could not be opened or read as HDF5.
    #[error("cannot read table {path}: {message}")]
    Io {
        /// File path.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// The file is HDF5 but not a valid table of a schema this crate reads.
    #[error("invalid table {path}: {message}")]
    Invalid {
        /// File path.
        path: String,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// A query argument is outside the allowed range.
    #[error("invalid {name} = {value}: must be {allowed}")]
    Query {
        /// Argument name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        allowed: String,
    },
}
