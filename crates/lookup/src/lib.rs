//! Interpolator for the universal tangential restitution `P(γ, α)` of oblique impacts (and
//! `P(γ, α, e_n)` of viscoelastic ones, from tables with an `e_n` axis).
//!
//! Reads a table written by `sweep run` (HDF5, schema v3 or v2, see `docs/table-format.md`), keeps it in
//! memory and evaluates `P` by the documented rule: the exact full-slip line `P = 1 − 7α` below
//! the linear limit, otherwise local Lagrange interpolation on curve-aligned patches. No HDF5 call
//! happens on the query path. This crate never depends on the simulator.
//!
//! - [`Table::open`] loads and validates a table ([`Table::embedded`]: the one built in,
//!   [`EMBEDDED_TABLE`]); [`Table::p`] / [`Table::p_with`] answer one
//!   `P(γ, α)`, [`Table::p_batch`] and [`Table::p_batch_par`] (feature `rayon`) many.
//! - [`Table::rebound`] (2-D, the plane of impact) and [`Table::rebound_3d`] (velocity and spin
//!   vectors, contact normal) answer sphere–wall and sphere–sphere impacts in SI units, with
//!   `γ` from the materials ([`Stiffness::Materials`]) or given ([`Stiffness::Gamma`]);
//!   [`rebound`] is the algebra from `P` to the post-impact state. [`Table::prepare`] (or
//!   [`Prepared::new`], without a table) checks a pair and contact once for many rebounds
//!   ([`Table::rebound_3d_prepared`], [`Table::rebound_3d_batch`],
//!   [`Table::rebound_3d_batch_par`]); for a table with an `e_n` axis it also computes the
//!   pair's `P(α)` through the table once.
//! - [`Table::curve`] precomputes `P(α)` at one fixed `γ` ([`Curve`]) for codes that meet one
//!   pair of materials many times: the same values, fewer operations per query.
//! - [`columns`]: batches as columns of one value per row or one for every row (NumPy's
//!   broadcasting), answered by the functions above: `P` ([`Table::p_columns`]) and rebounds
//!   ([`Table::rebound_columns`]) as rows of named numbers ([`columns::REBOUND_COLUMNS`],
//!   [`columns::REBOUND_3D_COLUMNS`]); what the Python module, the C ABI and `sweep query
//!   --batch` run.
//! - The C ABI is the crate `oblique-lookup-capi` (header `crates/lookup-capi/include/oblique_lookup.h`).
//!
//! Symbols (as in `physics.md`): `γ = √((7/2) G*/E*)`, `α = μ v_z0/|u0|`, `P = u_after/u_before`,
//! `α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`.

mod batch;
pub mod columns;
mod curve;
mod embedded;
mod fast;
pub mod impact;
mod line;
mod prepared;
mod table;
#[doc(hidden)]
pub mod testing;

pub use curve::Curve;
pub use embedded::{embedded_name, EMBEDDED_TABLE};
pub use impact::{Answer, Contact, Stiffness};
pub use oblique_table::format::{ExtraAxis, EXTRA_AXES, E_N};
pub use oblique_table::{Check, OutOfDomain, Provenance};
pub use prepared::Prepared;
pub use table::{axis_error, Table};

/// The rebound algebra and the bodies, from `oblique-physics` (one vocabulary with the
/// simulator).
pub use oblique_physics::rebound;

/// Errors of table loading and queries (the table format's error type).
pub use oblique_table::TableError as LookupError;
