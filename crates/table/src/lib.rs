//! The `P(γ, α)` table format, and its only owner: the names of the HDF5 objects and the schema
//! version ([`format`]), the file's seal, the model of the interpolated surface ([`surface`]:
//! patches, quadtrees, the warp), the interpolation rule of `docs/table-format.md`
//! ([`Surface::eval_with`]), the stated error bound ([`bound`]), the reader ([`read`]) and the
//! writer ([`write`]). Faster evaluators of the same rule live in `oblique-lookup`, pinned to
//! this one by tests.
//!
//! Symbols (as in `physics.md`): `γ = √((7/2) G*/E*)`, `α = μ v_z0/|u0|`, `P = u_after/u_before`,
//! `α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`.

pub mod bound;
pub mod export;
pub mod format;
pub mod indexed;
pub mod leaf;
pub mod line;
pub mod nodes;
pub mod read;
pub mod surface;
pub mod write;

pub use read::{Check, Contents, Provenance};
pub use surface::{
    Axis, AxisName, OutOfDomain, PartialMap, Patch, PatchData, PatchKind, Point, Region, Surface,
    Warp,
};

use thiserror::Error;

/// Errors of table loading and queries.
#[derive(Debug, Error)]
pub enum TableError {
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
        source: Box<TableError>,
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
    /// A value named by an axis that is no extra axis of a table, or named twice.
    #[error("unknown or repeated axis '{name}': the axes beyond gamma and alpha are {allowed}")]
    Axis {
        /// The name given.
        name: String,
        /// The names of the extra axes, separated by commas.
        allowed: String,
    },
    /// A point whose number of values is not the number of the table's axes.
    #[error("a point of this table has {expected} values ({axes}), not {len}")]
    Point {
        /// The number of values given.
        len: usize,
        /// The number of the table's axes.
        expected: usize,
        /// The table's axes in query order, separated by commas (`gamma, alpha, e_n`).
        axes: String,
    },
}

impl TableError {
    /// Whether the caller can fix it: a file that cannot be read or is not a valid table, a
    /// query argument outside its range (the batch's failing query included); not a
    /// programming error such as slices of different lengths.
    pub fn user_can_fix(&self) -> bool {
        !matches!(self, TableError::Length { .. })
    }
}

/// A physical input of a rebound outside its range is a query error of the lookup.
impl From<oblique_physics::InvalidInput> for TableError {
    fn from(e: oblique_physics::InvalidInput) -> Self {
        TableError::Query {
            name: e.name,
            value: e.value,
            allowed: e.allowed,
        }
    }
}
