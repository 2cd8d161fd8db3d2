//! Rebounds as columns: the bodies and contacts ([`PairColumns`]), the incident states in the
//! plane of impact ([`PlaneColumns`]) or in space ([`SpaceColumns`]), and the layout of an
//! answer's row ([`REBOUND_COLUMNS`], [`REBOUND_3D_COLUMNS`]). SI units; conventions as in
//! [`crate::rebound`].

use super::{batch_error, broadcast, fill_rows, Column, ColumnError};
use crate::rebound::{Body, Elastic, Incident, Incident3, Motion3, Pair, Rebound, Rebound3, State};
use crate::{Answer, Contact, LookupError, Prepared, Stiffness, Table};
use oblique_table::surface::OutOfDomain;

/// Rows of one pair and contact from which a 3-D batch prepares the pair for the table
/// ([`Table::prepare`]): below, its 2-9 µs would cost more than the 15 ns per row it saves.
const PREPARE_FOR_TABLE_ROWS: usize = 1024;

/// Mass `m` (kg), radius `R` (m) and inertia factor `κ` of a sphere, as columns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyColumns<'a> {
    /// Mass `m` (kg).
    pub mass: Column<'a>,
    /// Radius `R` (m).
    pub radius: Column<'a>,
    /// Inertia factor `κ` in `I = κ m R²`.
    pub kappa: Column<'a>,
}

impl BodyColumns<'_> {
    fn at(&self, i: usize) -> Body {
        Body {
            mass: self.mass.at(i),
            radius: self.radius.at(i),
            kappa: self.kappa.at(i),
        }
    }

    fn columns(&self) -> [Column<'_>; 3] {
        [self.mass, self.radius, self.kappa]
    }
}

/// Young's modulus `E` (Pa) and Poisson's ratio `ν` of a material, as columns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticColumns<'a> {
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: Column<'a>,
    /// Poisson's ratio `ν`.
    pub poisson_ratio: Column<'a>,
}

impl ElasticColumns<'_> {
    fn at(&self, i: usize) -> Elastic {
        Elastic {
            youngs_modulus: self.youngs_modulus.at(i),
            poisson_ratio: self.poisson_ratio.at(i),
        }
    }
}

/// What fixes `γ` of every row ([`Stiffness`] as columns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StiffnessColumns<'a> {
    /// `γ` itself (dimensionless).
    Gamma(Column<'a>),
    /// The materials of sphere 1 and of the other body (wall or sphere 2).
    Materials(ElasticColumns<'a>, ElasticColumns<'a>),
}

impl StiffnessColumns<'_> {
    fn at(&self, i: usize) -> Stiffness {
        match self {
            StiffnessColumns::Gamma(g) => Stiffness::Gamma(g.at(i)),
            StiffnessColumns::Materials(a, b) => Stiffness::Materials(a.at(i), b.at(i)),
        }
    }

    fn columns(&self) -> Vec<Column<'_>> {
        match self {
            StiffnessColumns::Gamma(g) => vec![*g],
            StiffnessColumns::Materials(a, b) => vec![
                a.youngs_modulus,
                a.poisson_ratio,
                b.youngs_modulus,
                b.poisson_ratio,
            ],
        }
    }
}

/// The bodies of every row and their contact ([`Pair`] and [`Contact`] as columns).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairColumns<'a> {
    /// Sphere 1.
    pub sphere: BodyColumns<'a>,
    /// Sphere 2, or `None` for a fixed wall.
    pub other: Option<BodyColumns<'a>>,
    /// What fixes `γ`.
    pub stiffness: StiffnessColumns<'a>,
    /// Coulomb friction coefficient `μ ≥ 0` (`∞` for no slip).
    pub friction: Column<'a>,
    /// Normal restitution `e_n` (1: elastic).
    pub restitution: Column<'a>,
    /// What a `γ` or `α` outside the table's domain does.
    pub outside: OutOfDomain,
}

impl PairColumns<'_> {
    /// The bodies of row `i`.
    ///
    /// # Panics
    /// When `i` is not a row of every column (a [`ReboundColumns`] checks them).
    pub fn pair(&self, i: usize) -> Pair {
        Pair {
            sphere: self.sphere.at(i),
            other: self.other.as_ref().map(|b| b.at(i)),
        }
    }

    /// The contact of row `i`.
    ///
    /// # Panics
    /// As [`PairColumns::pair`].
    pub fn contact(&self, i: usize) -> Contact {
        Contact {
            stiffness: self.stiffness.at(i),
            friction: self.friction.at(i),
            outside: self.outside,
            restitution: self.restitution.at(i),
        }
    }

    /// Every column.
    pub fn columns(&self) -> Vec<Column<'_>> {
        let mut c = self.sphere.columns().to_vec();
        if let Some(o) = &self.other {
            c.extend(o.columns());
        }
        c.extend(self.stiffness.columns());
        c.extend([self.friction, self.restitution]);
        c
    }

    /// Whether every row has the same pair and contact.
    pub fn is_shared(&self) -> bool {
        self.columns().iter().all(Column::is_shared)
    }
}

/// The incident states of a 2-D batch, in the plane of impact (`x` the tangent, `z` the normal
/// from sphere 1 into the other body; [`Incident`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneColumns<'a> {
    /// Tangential velocity `v_x` of sphere 1 (m/s).
    pub v_x: Column<'a>,
    /// Normal velocity `v_z` of sphere 1 (m/s).
    pub v_z: Column<'a>,
    /// Spin `ω` of sphere 1 (rad/s).
    pub omega: Column<'a>,
    /// `v_x` of sphere 2 (m/s; 0 for a wall).
    pub other_v_x: Column<'a>,
    /// `v_z` of sphere 2 (m/s; 0 for a wall).
    pub other_v_z: Column<'a>,
    /// `ω` of sphere 2 (rad/s; 0 for a wall).
    pub other_omega: Column<'a>,
}

impl PlaneColumns<'_> {
    /// The incident state of row `i`.
    ///
    /// # Panics
    /// When `i` is not a row of every column.
    pub fn incident(&self, i: usize) -> Incident {
        Incident {
            sphere: State {
                v_x: self.v_x.at(i),
                v_z: self.v_z.at(i),
                omega: self.omega.at(i),
            },
            other: State {
                v_x: self.other_v_x.at(i),
                v_z: self.other_v_z.at(i),
                omega: self.other_omega.at(i),
            },
        }
    }
}

/// The incident states of a 3-D batch ([`Incident3`]): vectors of 3 values per row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpaceColumns<'a> {
    /// Velocity of sphere 1 (m/s).
    pub velocity: Column<'a>,
    /// Angular velocity of sphere 1 (rad/s).
    pub spin: Column<'a>,
    /// Velocity of sphere 2 (m/s; zero for a wall).
    pub other_velocity: Column<'a>,
    /// Angular velocity of sphere 2 (rad/s; zero for a wall).
    pub other_spin: Column<'a>,
    /// Contact normal from sphere 1 into the other body (any non-zero length).
    pub normal: Column<'a>,
}

impl SpaceColumns<'_> {
    /// The incident state of row `i`.
    ///
    /// # Panics
    /// When `i` is not a row of every column.
    pub fn incident(&self, i: usize) -> Incident3 {
        Incident3 {
            sphere: Motion3 {
                velocity: self.velocity.vec3(i),
                spin: self.spin.vec3(i),
            },
            other: Motion3 {
                velocity: self.other_velocity.vec3(i),
                spin: self.other_spin.vec3(i),
            },
            normal: self.normal.vec3(i),
        }
    }
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::PlaneColumns<'_> {}
    impl Sealed for super::SpaceColumns<'_> {}
}

/// The incident states of a rebound batch: [`PlaneColumns`] (2-D) or [`SpaceColumns`] (3-D),
/// each with the layout of its answer's row.
pub trait Motions: sealed::Sealed + Sync {
    /// The names of the numbers of an answer's row, in order.
    const COLUMNS: &'static [&'static str];

    /// Every column.
    fn columns(&self) -> Vec<Column<'_>>;

    /// The pair prepared once for every row (only where the answer is the same bits).
    #[doc(hidden)]
    fn prepare(
        _table: &Table,
        _pairs: &PairColumns<'_>,
        _rows: usize,
    ) -> Result<Option<Prepared>, LookupError> {
        Ok(None)
    }

    /// The answer of row `i` into `row` ([`Self::COLUMNS`]).
    #[doc(hidden)]
    fn answer(
        &self,
        table: &Table,
        pairs: &PairColumns<'_>,
        prepared: Option<&Prepared>,
        i: usize,
        row: &mut [f64],
    ) -> Result<(), LookupError>;
}

/// Names of the numbers of a 2-D rebound's row ([`Table::rebound`]; `other_*` NaN for a wall):
/// velocities in m/s, spins in rad/s, impulses in N s, angles in rad, energy in J.
pub const REBOUND_COLUMNS: [&str; 19] = [
    "v_x",
    "v_z",
    "omega",
    "other_v_x",
    "other_v_z",
    "other_omega",
    "gamma",
    "alpha",
    "p",
    "e_t",
    "slip_before",
    "slip_after",
    "tangential_impulse",
    "normal_impulse",
    "e_n",
    "incidence_angle",
    "rebound_angle_centre",
    "rebound_angle_contact",
    "energy_lost",
];

/// Names of the numbers of a 3-D rebound's row ([`Table::rebound_3d`]; vectors as their `_x`,
/// `_y`, `_z` components, adjacent; `other_*` NaN for a wall). Units as in
/// [`REBOUND_COLUMNS`].
pub const REBOUND_3D_COLUMNS: [&str; 31] = [
    "velocity_x",
    "velocity_y",
    "velocity_z",
    "spin_x",
    "spin_y",
    "spin_z",
    "other_velocity_x",
    "other_velocity_y",
    "other_velocity_z",
    "other_spin_x",
    "other_spin_y",
    "other_spin_z",
    "gamma",
    "alpha",
    "p",
    "e_t",
    "slip_before",
    "slip_after",
    "tangential_impulse",
    "normal_impulse",
    "e_n",
    "approach_speed",
    "centre_speed_before",
    "centre_speed_after",
    "energy_lost",
    "tangent_x",
    "tangent_y",
    "tangent_z",
    "incidence_angle",
    "rebound_angle_centre",
    "rebound_angle_contact",
];

/// `a` as a row of [`REBOUND_COLUMNS`].
fn write_2d(a: &Answer<Rebound>, r: &mut [f64]) {
    let b = &a.rebound;
    let o = b.other.unwrap_or(State {
        v_x: f64::NAN,
        v_z: f64::NAN,
        omega: f64::NAN,
    });
    r.copy_from_slice(&[
        b.sphere.v_x,
        b.sphere.v_z,
        b.sphere.omega,
        o.v_x,
        o.v_z,
        o.omega,
        a.gamma,
        a.alpha,
        b.p,
        b.e_t,
        b.slip_before,
        b.slip_after,
        b.tangential_impulse,
        b.normal_impulse,
        b.e_n,
        b.incidence_angle,
        b.rebound_angle_centre,
        b.rebound_angle_contact,
        b.energy_lost,
    ]);
}

/// `a` as a row of [`REBOUND_3D_COLUMNS`].
fn write_3d(a: &Answer<Rebound3>, r: &mut [f64]) {
    let b = &a.rebound;
    let o = b.other.unwrap_or(Motion3 {
        velocity: [f64::NAN; 3],
        spin: [f64::NAN; 3],
    });
    r[0..3].copy_from_slice(&b.sphere.velocity);
    r[3..6].copy_from_slice(&b.sphere.spin);
    r[6..9].copy_from_slice(&o.velocity);
    r[9..12].copy_from_slice(&o.spin);
    r[12..25].copy_from_slice(&[
        a.gamma,
        a.alpha,
        b.p,
        b.e_t,
        b.slip_before,
        b.slip_after,
        b.tangential_impulse,
        b.normal_impulse,
        b.e_n,
        b.approach_speed,
        b.centre_speed_before,
        b.centre_speed_after,
        b.energy_lost,
    ]);
    r[25..28].copy_from_slice(&b.frame.tangent);
    r[28] = b.incidence_angle();
    r[29] = b.rebound_angle_centre();
    r[30] = b.rebound_angle_contact();
}

impl Motions for PlaneColumns<'_> {
    const COLUMNS: &'static [&'static str] = &REBOUND_COLUMNS;

    fn columns(&self) -> Vec<Column<'_>> {
        vec![
            self.v_x,
            self.v_z,
            self.omega,
            self.other_v_x,
            self.other_v_z,
            self.other_omega,
        ]
    }

    fn answer(
        &self,
        table: &Table,
        pairs: &PairColumns<'_>,
        _prepared: Option<&Prepared>,
        i: usize,
        row: &mut [f64],
    ) -> Result<(), LookupError> {
        let a = table.rebound(&pairs.pair(i), &pairs.contact(i), &self.incident(i))?;
        write_2d(&a, row);
        Ok(())
    }
}

impl Motions for SpaceColumns<'_> {
    const COLUMNS: &'static [&'static str] = &REBOUND_3D_COLUMNS;

    fn columns(&self) -> Vec<Column<'_>> {
        vec![
            self.velocity,
            self.spin,
            self.other_velocity,
            self.other_spin,
            self.normal,
        ]
    }

    /// One pair and contact for every row: checked once. For many rows, prepared for this
    /// table (with an `e_n` axis: its `P(α)` at the pair's `(γ, e_n)` computed once, 2-9 µs,
    /// then about 15 ns less per row; the same bits).
    fn prepare(
        table: &Table,
        pairs: &PairColumns<'_>,
        rows: usize,
    ) -> Result<Option<Prepared>, LookupError> {
        if !pairs.is_shared() {
            return Ok(None);
        }
        let (pair, contact) = (pairs.pair(0), pairs.contact(0));
        let k = if rows >= PREPARE_FOR_TABLE_ROWS {
            // A pair that this table does not prepare for (the table of one pair at another
            // γ) goes the way of fewer rows: its rows are answered or refused one by one, so
            // the answer does not depend on the number of rows.
            table
                .prepare(&pair, &contact)
                .or_else(|_| Prepared::new(&pair, &contact))
        } else {
            Prepared::new(&pair, &contact)
        };
        k.map(Some)
    }

    fn answer(
        &self,
        table: &Table,
        pairs: &PairColumns<'_>,
        prepared: Option<&Prepared>,
        i: usize,
        row: &mut [f64],
    ) -> Result<(), LookupError> {
        let a = match prepared {
            Some(k) => table.rebound_3d_prepared(k, &self.incident(i))?,
            None => table.rebound_3d(&pairs.pair(i), &pairs.contact(i), &self.incident(i))?,
        };
        write_3d(&a, row);
        Ok(())
    }
}

/// A batch of rebounds: the bodies and contacts, and the incident states (`M`:
/// [`PlaneColumns`] or [`SpaceColumns`]), broadcast ([`Table::rebound_columns`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReboundColumns<'a, M> {
    pairs: PairColumns<'a>,
    motions: M,
    rows: usize,
}

impl<'a, M: Motions> ReboundColumns<'a, M> {
    /// The batch of `pairs` and `motions`, or the error naming a column that does not
    /// broadcast.
    pub fn new(pairs: PairColumns<'a>, motions: M) -> Result<ReboundColumns<'a, M>, ColumnError> {
        let rows = broadcast(pairs.columns().into_iter().chain(motions.columns()))?;
        Ok(ReboundColumns {
            pairs,
            motions,
            rows,
        })
    }

    /// The number of impacts.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The bodies and contacts.
    pub fn pairs(&self) -> &PairColumns<'a> {
        &self.pairs
    }

    /// The incident states.
    pub fn motions(&self) -> &M {
        &self.motions
    }
}

impl Table {
    /// The rebound of every row of `batch` ([`Table::rebound`] in 2-D, [`Table::rebound_3d`]
    /// in 3-D) into `out`, row after row, each `M::COLUMNS.len()` numbers in the order of
    /// [`Motions::COLUMNS`] ([`REBOUND_COLUMNS`], [`REBOUND_3D_COLUMNS`]), on the calling
    /// thread.
    ///
    /// The `e_n` of every row must be one the table answers, also where `P` is not needed. An
    /// `e_n`, pair or contact shared by every row is checked once: its error has no index.
    /// Otherwise the first invalid row is [`LookupError::Batch`] (`out` filled before it); an
    /// `out` of another length is [`LookupError::Length`].
    pub fn rebound_columns<M: Motions>(
        &self,
        batch: &ReboundColumns<'_, M>,
        out: &mut [f64],
    ) -> Result<(), LookupError> {
        let k = self.rebound_setup(batch, out)?;
        fill_rows(out, M::COLUMNS.len(), |i, r| {
            self.rebound_row(batch, k.as_ref(), i, r)
        })
        .map_err(batch_error)
    }

    /// [`Table::rebound_columns`] on the current rayon pool ([`super::fill_rows_par`]); the
    /// error names the lowest invalid row.
    #[cfg(feature = "rayon")]
    pub fn rebound_columns_par<M: Motions>(
        &self,
        batch: &ReboundColumns<'_, M>,
        out: &mut [f64],
    ) -> Result<(), LookupError> {
        let k = self.rebound_setup(batch, out)?;
        super::fill_rows_par(out, M::COLUMNS.len(), |i, r| {
            self.rebound_row(batch, k.as_ref(), i, r)
        })
        .map_err(batch_error)
    }

    /// The checks shared by every row: the length of `out`, an `e_n` shared by every row
    /// (no index), and the pair prepared once where every row has the same one.
    fn rebound_setup<M: Motions>(
        &self,
        batch: &ReboundColumns<'_, M>,
        out: &[f64],
    ) -> Result<Option<Prepared>, LookupError> {
        crate::batch::check_length("out", out.len(), batch.rows * M::COLUMNS.len())?;
        let e_n = &batch.pairs.restitution;
        if e_n.is_shared() {
            self.check_restitution(e_n.at(0))?;
        }
        M::prepare(self, &batch.pairs, batch.rows)
    }

    /// Row `i` of `batch` into `row`: its own `e_n` checked first (one not shared), then the
    /// rebound.
    #[inline]
    fn rebound_row<M: Motions>(
        &self,
        batch: &ReboundColumns<'_, M>,
        prepared: Option<&Prepared>,
        i: usize,
        row: &mut [f64],
    ) -> Result<(), LookupError> {
        let e_n = &batch.pairs.restitution;
        if !e_n.is_shared() {
            self.check_restitution(e_n.at(i))?;
        }
        batch.motions.answer(self, &batch.pairs, prepared, i, row)
    }
}
