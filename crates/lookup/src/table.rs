//! The loaded table: its contents ([`oblique_table::read::Contents`]) and the acceleration
//! structure of the query path.

use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use oblique_table::format::{ExtraAxis, EXTRA_AXES, E_N as E_N_AXIS};
use oblique_table::read::Contents;
use oblique_table::surface::{OutOfDomain, Surface};
use oblique_table::{Check, Provenance};

use crate::fast::{Accel, Accel3};
use crate::LookupError;

/// A loaded table: the surface, its provenance and its held-out checks. Immutable,
/// `Send + Sync`; queries touch only memory.
///
/// [`Table::p`] and the other queries answer from an acceleration structure built from the
/// surface when the table is made (a fine leaf index per patch, see [`Table::index_bytes`], and
/// a copy of the node values); they return the same bits as [`Surface::eval_with`].
#[derive(Debug, Clone)]
pub struct Table {
    /// The interpolated surface.
    surface: Surface,
    /// Provenance attributes.
    provenance: Provenance,
    /// Held-out check points.
    checks: Vec<Check>,
    /// The stated error bound ([`Table::error_bound`]).
    error_bound: f64,
    /// The query path's acceleration structure (`None`: answered by `surface` directly).
    accel: Option<Accel<2>>,
    /// The same for a table with an `e_n` axis.
    accel3: Option<Accel3>,
    /// This table's identity (kept by its clones), named by what [`Table::prepare`] stores
    /// for it.
    id: u64,
}

/// Tables are equal when their contents are (whatever their identities).
impl PartialEq for Table {
    fn eq(&self, other: &Table) -> bool {
        self.surface == other.surface
            && self.provenance == other.provenance
            && self.checks == other.checks
            && self.error_bound.to_bits() == other.error_bound.to_bits()
    }
}

/// The identity of the next table made ([`Table::from_parts`]).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

impl Table {
    /// Open, validate and load a table ([`oblique_table::read::read`]). Errors name the
    /// problem: not HDF5 or truncated, not a P table, a newer schema, inconsistent shapes,
    /// non-finite values.
    pub fn open(path: impl AsRef<Path>) -> Result<Table, LookupError> {
        let c: Contents = oblique_table::read::read(path)?;
        Ok(Table::from_parts(
            c.surface,
            c.provenance,
            c.checks,
            c.error_bound,
        ))
    }

    /// A table from its parts (as [`Table::open`] loads them), with the acceleration structure
    /// of the query path built for `surface`; `error_bound` is what [`Table::error_bound`]
    /// returns ([`oblique_table::bound::surface_bound`] of the leaves' predicted errors).
    pub fn from_parts(
        surface: Surface,
        provenance: Provenance,
        checks: Vec<Check>,
        error_bound: f64,
    ) -> Table {
        let accel = Accel::<2>::new(&surface);
        let accel3 = Accel3::new(&surface);
        Table {
            surface,
            provenance,
            checks,
            error_bound,
            accel,
            accel3,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// This table's identity: equal for a table and its clones, different for every other
    /// table made.
    pub(crate) fn id(&self) -> u64 {
        self.id
    }

    /// The acceleration structure, if the table has one.
    pub(crate) fn accel(&self) -> Option<&Accel<2>> {
        self.accel.as_ref()
    }

    /// The interpolated surface (the model of `oblique_table`, read-only).
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// Where the table came from.
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// The held-out check points.
    pub fn checks(&self) -> &[Check] {
        &self.checks
    }

    /// Bytes of the acceleration structure's leaf indexes (0 when the table is answered by the
    /// quadtree descent of [`Surface::eval_with`], as for stencils other than 4 points).
    pub fn index_bytes(&self) -> usize {
        self.accel.as_ref().map_or(0, Accel::<2>::index_bytes)
            + self.accel3.as_ref().map_or(0, Accel3::index_bytes)
    }

    /// `P(γ, α)` (dimensionless), refusing points outside the table's domain; see
    /// [`Surface::eval_with`].
    #[inline]
    pub fn p(&self, gamma: f64, alpha: f64) -> Result<f64, LookupError> {
        self.p_with(gamma, alpha, OutOfDomain::Error)
    }

    /// `P(γ, α)` with the caller's choice for points outside the domain
    /// ([`OutOfDomain::Clamp`] answers at the nearest point of the domain); see
    /// [`Surface::eval_with`].
    #[inline]
    pub fn p_with(&self, gamma: f64, alpha: f64, outside: OutOfDomain) -> Result<f64, LookupError> {
        match (&self.accel, &self.accel3) {
            (Some(a), _) => a.eval_with(&self.surface, gamma, alpha, outside),
            (None, Some(a)) => a.eval(&self.surface, gamma, alpha, 1.0, outside),
            (None, None) => self.p_by_descent(gamma, alpha, outside),
        }
    }

    /// `P(γ, α, e_n)` (dimensionless) at normal restitution `e_n`, refusing points outside
    /// the table's domain; see [`Surface::eval_point`]. An elastic table answers `e_n = 1`
    /// only; a table with an `e_n` axis (schema 4) answers inside its range
    /// ([`Surface::restitution`]), never outside it.
    #[inline]
    pub fn p_e(&self, gamma: f64, alpha: f64, e_n: f64) -> Result<f64, LookupError> {
        self.p_e_with(gamma, alpha, e_n, OutOfDomain::Error)
    }

    /// [`Table::p_e`] with the caller's choice for `γ` and `α` outside the domain
    /// ([`OutOfDomain::Clamp`]; `e_n` is never clamped).
    #[inline]
    pub fn p_e_with(
        &self,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        match (&self.accel, &self.accel3) {
            // An elastic table's structure answers e_n = 1 (the others are refused).
            (Some(a), _) if e_n == 1.0 => a.eval_with(&self.surface, gamma, alpha, outside),
            (_, Some(a)) => a.eval(&self.surface, gamma, alpha, e_n, outside),
            _ => self.surface.eval_point(gamma, alpha, e_n, outside),
        }
    }

    /// The names of the axes of a query's point, in order: `gamma`, `alpha`, then the table's
    /// extra axes ([`oblique_table::format::EXTRA_AXES`] order; `e_n` for a table with a
    /// normal-restitution axis). The table of one pair takes a `γ` too (its own).
    pub fn axes(&self) -> Vec<&'static str> {
        ["gamma", "alpha"]
            .into_iter()
            .chain(self.extra_axes().into_iter().map(|a| a.name))
            .collect()
    }

    /// The table's axes beyond `γ` and `α`, in [`oblique_table::format::EXTRA_AXES`] order
    /// (empty for an elastic table); their ranges are [`Table::axis_range`].
    pub fn extra_axes(&self) -> Vec<&'static ExtraAxis> {
        EXTRA_AXES
            .iter()
            .filter(|a| self.axis_range(a.name).is_some())
            .collect()
    }

    /// The range `[lo, hi]` of the table's extra axis `name` (`None`: the table has no such
    /// axis).
    pub fn axis_range(&self, name: &str) -> Option<(f64, f64)> {
        match name {
            n if n == E_N_AXIS.name => self.surface.restitution(),
            _ => None,
        }
    }

    /// `P` (dimensionless) at `point`, one value per axis of [`Table::axes`] in that order
    /// (`[γ, α]`, or `[γ, α, e_n]` for a table with an `e_n` axis), refusing points outside the
    /// table's domain. The same bits as [`Table::p`] and [`Table::p_e`] at the same point.
    #[inline]
    pub fn p_at(&self, point: &[f64]) -> Result<f64, LookupError> {
        self.p_at_with(point, OutOfDomain::Error)
    }

    /// [`Table::p_at`] with the caller's choice for `γ` and `α` outside the domain
    /// ([`OutOfDomain::Clamp`]; an extra axis is never clamped). A point of another length
    /// than [`Table::axes`] is [`LookupError::Point`].
    #[inline]
    pub fn p_at_with(&self, point: &[f64], outside: OutOfDomain) -> Result<f64, LookupError> {
        match (point, self.surface.restitution()) {
            (&[g, a], None) => self.p_with(g, a, outside),
            (&[g, a, e], Some(_)) => self.p_e_with(g, a, e, outside),
            _ => Err(self.point_error(point.len())),
        }
    }

    /// `P` (dimensionless) at `γ`, `α` and the values `extra` of extra axes, each named by its
    /// axis ([`oblique_table::format::EXTRA_AXES`]: `("e_n", 0.8)`), as the bindings' keyword
    /// arguments take them: an axis not named is at its fixed value (`e_n = 1`), and a table
    /// without the axis answers that value only ([`Table::p_e_with`] with the same bits). A
    /// name of no extra axis, or one named twice, is [`LookupError::Axis`].
    pub fn p_axes_with(
        &self,
        gamma: f64,
        alpha: f64,
        extra: &[(&str, f64)],
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        let mut e_n = None;
        for &(name, value) in extra {
            match name {
                n if n == E_N_AXIS.name && e_n.is_none() => e_n = Some(value),
                _ => return Err(axis_error(name)),
            }
        }
        self.p_e_with(gamma, alpha, e_n.unwrap_or(E_N_AXIS.fixed), outside)
    }

    /// [`LookupError::Point`] for a point of `len` values.
    #[cold]
    pub fn point_error(&self, len: usize) -> LookupError {
        let axes = self.axes();
        LookupError::Point {
            len,
            expected: axes.len(),
            axes: axes.join(", "),
        }
    }

    /// `Ok` for a normal restitution `e_n` this table answers: in its `e_n` range, or `1`
    /// for an elastic table; otherwise the error every query with that `e_n` returns (the
    /// field `e_n` and the range). Rebounds check it even where `P` is not needed (`u0 = 0`).
    pub fn check_restitution(&self, e_n: f64) -> Result<(), LookupError> {
        self.surface.check_e_n(e_n)
    }

    /// The `e_n` range of a table with a normal-restitution axis (`None`: an elastic table,
    /// which answers `e_n = 1` only).
    pub fn restitution(&self) -> Option<(f64, f64)> {
        self.surface.restitution()
    }

    /// [`Surface::eval_with`] out of line, for tables without an acceleration structure.
    #[inline(never)]
    fn p_by_descent(
        &self,
        gamma: f64,
        alpha: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        self.surface.eval_with(gamma, alpha, outside)
    }

    /// The error bound this table states for any `P` it answers (absolute, dimensionless):
    /// the largest, over all leaves, of the leaf's predicted interpolation error plus
    /// `Λ_k² ≈ 2.66` (cubic stencil) times the largest solver error estimate of its nodes
    /// ([`oblique_table::bound`]; `docs/table-format.md`, "The stated error bound"). Derived from the
    /// file's `leaf_predicted_error` and `error_estimate` datasets, so it is the same for every
    /// table written by `sweep run`; NaN for a file without `leaf_predicted_error` (it states
    /// no bound).
    pub fn error_bound(&self) -> f64 {
        self.error_bound
    }

    /// The first held-out check whose measured error exceeds the stated bound, if any (a
    /// table whose own checks contradict its bound; `sweep run` refuses to write one).
    pub fn contradicting_check(&self) -> Option<&Check> {
        oblique_table::bound::contradicting_check(&self.checks, self.error_bound)
    }
}

/// [`LookupError::Axis`] for `name`, not an extra axis (or named twice).
#[cold]
pub fn axis_error(name: &str) -> LookupError {
    LookupError::Axis {
        name: name.to_string(),
        allowed: EXTRA_AXES
            .iter()
            .map(|a| a.name)
            .collect::<Vec<_>>()
            .join(", "),
    }
}
