//! Interpolator for the universal tangential restitution `P(γ, α)` of oblique elastic impacts.
//!
//! Reads a table written by `sweep run` (HDF5, schema v3 or v2, see `docs/table-format.md`), keeps it in
//! memory and evaluates `P` by the documented rule: the exact full-slip line `P = 1 − 7α` below
//! the linear limit, otherwise local Lagrange interpolation on curve-aligned patches. No HDF5 call
//! happens on the query path. This crate never depends on the simulator.
//!
//! - [`Table::open`] loads and validates a table; [`Table::p`] / [`Table::p_with`] answer one
//!   `P(γ, α)`, [`Table::p_batch`] and [`Table::p_batch_par`] (feature `rayon`) many.
//! - [`Table::rebound`] (2-D, the plane of impact) and [`Table::rebound_3d`] (velocity and spin
//!   vectors, contact normal) answer sphere–wall and sphere–sphere impacts in SI units, with
//!   `γ` from the materials ([`Stiffness::Materials`]) or given ([`Stiffness::Gamma`]);
//!   [`rebound`] is the algebra from `P` to the post-impact state. [`Prepared`] checks a pair
//!   and contact once for many rebounds ([`Table::rebound_3d_prepared`],
//!   [`Table::rebound_3d_batch`], [`Table::rebound_3d_batch_par`]).
//! - [`Table::curve`] precomputes `P(α)` at one fixed `γ` ([`Curve`]) for codes that meet one
//!   pair of materials many times: the same values, fewer operations per query.
//! - [`capi`] is the C ABI of the `cdylib` (header `lookup/include/oblique_lookup.h`).
//!
//! Symbols (as in `physics.md`): `γ = √((7/2) G*/E*)`, `α = μ v_z0/|u0|`, `P = u_after/u_before`,
//! `α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`.

mod batch;
pub mod bound;
pub mod capi;
mod curve;
mod fast;
pub mod format;
pub mod impact;
mod prepared;
mod read;
pub mod rebound;
pub mod surface;
#[doc(hidden)]
pub mod testing;

pub use curve::Curve;
pub use impact::{Answer, Contact, Stiffness};
pub use prepared::Prepared;
pub use read::{Check, Provenance, Table};
pub use surface::{OutOfDomain, Patch, PatchKind, Surface, Warp};

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
    #[error("invalid {name} = {value:?}: must be {allowed}")]
    Query {
        /// Argument name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range.
        allowed: String,
    },
    /// One query of a batch is invalid.
    #[error("query {index} (0-based) of the batch: {source}")]
    Batch {
        /// Index of the first invalid query.
        index: usize,
        /// Why it is invalid.
        source: Box<LookupError>,
    },
    /// The slices of a batch differ in length.
    #[error("batch slice '{name}' has length {len}, expected {expected} (the length of the first input slice: gamma, or incidents)")]
    Length {
        /// Name of the slice.
        name: &'static str,
        /// Its length.
        len: usize,
        /// The length of the first input slice (`gamma`, or `incidents`).
        expected: usize,
    },
}
