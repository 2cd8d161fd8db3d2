//! Batches as columns (struct of arrays), for the bindings: one [`Column`] per argument, of one
//! value shared by every row or one value per row (NumPy's broadcasting of a length-1 axis),
//! answered by the table's own batch and rebound functions.
//!
//! - [`PointColumns`]: the points `(γ, α[, e_n])` of `P` queries, answered by
//!   [`Table::p_columns`] (and [`Table::p_columns_par`], feature `rayon`) through
//!   [`Table::p_batch`] / [`Table::p_e_batch`].
//! - [`ReboundColumns`]: rebounds of many impacts, the bodies and contacts in [`PairColumns`] and
//!   the incident states in [`PlaneColumns`] (2-D, [`Table::rebound`]) or [`SpaceColumns`] (3-D,
//!   [`Table::rebound_3d`], through one [`Prepared`](crate::Prepared) pair when every row has the
//!   same pair and contact), answered by [`Table::rebound_columns`] as rows of numbers whose
//!   names and order are [`REBOUND_COLUMNS`] and [`REBOUND_3D_COLUMNS`].
//! - [`fill_rows`] (and [`fill_rows_par`]): the row loop of both, for other row functions.
//!
//! Building a batch checks that its columns broadcast ([`ColumnError`]); answering it reports
//! the first invalid row as [`LookupError::Batch`] with the row's index, as the slice batches
//! do.

use std::borrow::Cow;

use crate::{LookupError, Table};
use oblique_table::format::{EXTRA_AXES, E_N};
use oblique_table::surface::OutOfDomain;
use thiserror::Error;

mod rebounds;

pub use rebounds::{
    BodyColumns, ElasticColumns, Motions, PairColumns, PlaneColumns, ReboundColumns, SpaceColumns,
    StiffnessColumns, REBOUND_3D_COLUMNS, REBOUND_COLUMNS,
};

/// Rows per parallel task of the `_par` functions; below two tasks' worth the rows run on the
/// calling thread.
pub const CHUNK_ROWS: usize = 4096;

/// Columns that do not form a batch.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ColumnError {
    /// A column's number of values is not a whole number of rows of its width (3 for a
    /// vector).
    #[error("column '{name}' has {len} values, not a whole number of rows of {width}")]
    Width {
        /// The column's name.
        name: &'static str,
        /// Its number of values.
        len: usize,
        /// Values per row.
        width: usize,
    },
    /// A column of a point names no extra axis ([`oblique_table::format::EXTRA_AXES`]), or
    /// the same axis as another column.
    #[error(
        "column '{name}' is not an axis of a point, or repeats one: the extra axes are {allowed}"
    )]
    Axis {
        /// The column's name.
        name: &'static str,
        /// The names of the extra axes, separated by commas.
        allowed: String,
    },
    /// Two columns of more than one row differ in their number of rows.
    #[error(
        "column '{name}' has {rows} rows and column '{other}' {other_rows}: the columns of a \
         batch have one row (shared by every row) or the same number"
    )]
    Broadcast {
        /// The column found not to match.
        name: &'static str,
        /// Its number of rows.
        rows: usize,
        /// The first column of more than one row (`out`: the output).
        other: &'static str,
        /// That column's number of rows.
        other_rows: usize,
    },
}

/// The data of one argument of a batch: `width` values (1, or 3 for a vector) shared by every
/// row, or `width` values for each row, row after row. Units those of the argument.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Column<'a> {
    name: &'static str,
    data: &'a [f64],
    width: usize,
}

impl<'a> Column<'a> {
    /// A column of one number per row (or one for every row), named `name` in errors.
    pub const fn scalar(name: &'static str, data: &'a [f64]) -> Column<'a> {
        Column {
            name,
            data,
            width: 1,
        }
    }

    /// A column of 3-vectors `(x, y, z)`, one per row (or one for every row), flattened.
    pub const fn vector(name: &'static str, data: &'a [f64]) -> Column<'a> {
        Column {
            name,
            data,
            width: 3,
        }
    }

    /// The column's name.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// Its number of rows (values / width).
    pub fn rows(&self) -> Result<usize, ColumnError> {
        if self.data.len().is_multiple_of(self.width) {
            Ok(self.data.len() / self.width)
        } else {
            Err(ColumnError::Width {
                name: self.name,
                len: self.data.len(),
                width: self.width,
            })
        }
    }

    /// Whether every row has the same value (the column holds one row).
    #[inline]
    pub fn is_shared(&self) -> bool {
        self.data.len() == self.width
    }

    /// The value of row `row` (a scalar column).
    ///
    /// # Panics
    /// When `row` is not a row of the column (a batch checks its columns once).
    #[inline]
    pub fn at(&self, row: usize) -> f64 {
        if self.is_shared() {
            self.data[0]
        } else {
            self.data[row]
        }
    }

    /// The vector of row `row` (a vector column).
    ///
    /// # Panics
    /// As [`Column::at`].
    #[inline]
    pub fn vec3(&self, row: usize) -> [f64; 3] {
        let k = if self.is_shared() { 0 } else { 3 * row };
        [self.data[k], self.data[k + 1], self.data[k + 2]]
    }

    /// One value per row for `rows` rows of a scalar column: its data when it has them, else
    /// its one value repeated.
    fn full(&self, rows: usize) -> Cow<'a, [f64]> {
        if self.data.len() == rows {
            Cow::Borrowed(self.data)
        } else {
            Cow::Owned(vec![self.at(0); rows])
        }
    }
}

/// The number of rows of a batch of `columns`: that of every column of more than one row (1
/// when there is none), or the error naming a column that differs and both numbers of rows.
pub fn broadcast<'a>(columns: impl IntoIterator<Item = Column<'a>>) -> Result<usize, ColumnError> {
    let mut found: Option<(&'static str, usize)> = None;
    for c in columns {
        let rows = c.rows()?;
        if rows == 1 {
            continue;
        }
        match found {
            None => found = Some((c.name, rows)),
            Some((other, other_rows)) if other_rows != rows => {
                return Err(ColumnError::Broadcast {
                    name: c.name,
                    rows,
                    other,
                    other_rows,
                })
            }
            Some(_) => {}
        }
    }
    Ok(found.map_or(1, |(_, rows)| rows))
}

/// `Ok` when every column has one row or `rows` (those of an output, named `out` in the
/// error).
pub fn check_rows<'a>(
    columns: impl IntoIterator<Item = Column<'a>>,
    rows: usize,
) -> Result<(), ColumnError> {
    for c in columns {
        let n = c.rows()?;
        if n != 1 && n != rows {
            return Err(ColumnError::Broadcast {
                name: c.name,
                rows: n,
                other: "out",
                other_rows: rows,
            });
        }
    }
    Ok(())
}

/// The points `(γ, α, e_n)` of a batch of `P` queries, broadcast ([`Table::p_columns`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointColumns<'a> {
    gamma: Column<'a>,
    alpha: Column<'a>,
    /// `None`: `e_n = 1` for every row.
    e_n: Option<Column<'a>>,
    rows: usize,
}

impl<'a> PointColumns<'a> {
    /// The points of material group `gamma`, friction group `alpha` and normal restitution
    /// `e_n` (`None`: 1, elastic), all dimensionless.
    pub fn new(
        gamma: Column<'a>,
        alpha: Column<'a>,
        e_n: Option<Column<'a>>,
    ) -> Result<PointColumns<'a>, ColumnError> {
        let rows = broadcast([gamma, alpha].into_iter().chain(e_n))?;
        Ok(PointColumns {
            gamma,
            alpha,
            e_n,
            rows,
        })
    }

    /// The points of `gamma`, `alpha` and the columns `extra`, each named by its axis
    /// ([`oblique_table::format::EXTRA_AXES`]: `e_n`); an axis without a column is at its
    /// fixed value (`e_n = 1`). A column of another name, or two of one name, is
    /// [`ColumnError::Axis`].
    pub fn with_axes(
        gamma: Column<'a>,
        alpha: Column<'a>,
        extra: &[Column<'a>],
    ) -> Result<PointColumns<'a>, ColumnError> {
        let mut e_n = None;
        for c in extra {
            match c.name {
                n if n == E_N.name && e_n.is_none() => e_n = Some(*c),
                n => {
                    return Err(ColumnError::Axis {
                        name: n,
                        allowed: EXTRA_AXES
                            .iter()
                            .map(|a| a.name)
                            .collect::<Vec<_>>()
                            .join(", "),
                    })
                }
            }
        }
        PointColumns::new(gamma, alpha, e_n)
    }

    /// The number of points.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The `e_n` column unless it is 1 for every row.
    fn restitution(&self) -> Option<Column<'a>> {
        self.e_n
            .filter(|e| !(e.is_shared() && e.at(0) == 1.0) && self.rows > 0)
    }
}

/// `out[i] = f(i, row i of out)` for every row of `width` values, in order on the calling
/// thread, stopping at the first error (its row and the error).
pub fn fill_rows<E>(
    out: &mut [f64],
    width: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E>,
) -> Result<(), (usize, E)> {
    fill_from(0, out, width, &row)
}

fn fill_from<E>(
    start: usize,
    out: &mut [f64],
    width: usize,
    row: &impl Fn(usize, &mut [f64]) -> Result<(), E>,
) -> Result<(), (usize, E)> {
    for (j, r) in out.chunks_mut(width.max(1)).enumerate() {
        row(start + j, r).map_err(|e| (start + j, e))?;
    }
    Ok(())
}

/// [`fill_rows`] on the current rayon pool, [`CHUNK_ROWS`] rows per task (on the calling
/// thread below two tasks); the error of the lowest failing row. On an error `out` is filled
/// only in part.
#[cfg(feature = "rayon")]
pub fn fill_rows_par<E: Send>(
    out: &mut [f64],
    width: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync,
) -> Result<(), (usize, E)> {
    use rayon::prelude::*;
    let width = width.max(1);
    if out.len() < 2 * CHUNK_ROWS * width {
        return fill_rows(out, width, row);
    }
    let first_error = out
        .par_chunks_mut(CHUNK_ROWS * width)
        .enumerate()
        .filter_map(|(k, block)| fill_from(k * CHUNK_ROWS, block, width, &row).err())
        .min_by_key(|(i, _)| *i);
    match first_error {
        None => Ok(()),
        Some(e) => Err(e),
    }
}

/// A row's error as [`LookupError::Batch`].
fn batch_error((index, source): (usize, LookupError)) -> LookupError {
    LookupError::Batch {
        index,
        source: Box::new(source),
    }
}

impl Table {
    /// `out[i] = P(γ_i, α_i, e_n,i)` for every row of `points` ([`Table::p_e_with`]), in order:
    /// [`Table::p_batch`] when `e_n` is 1 for every row, else [`Table::p_e_batch`] (a shared
    /// column repeated for them). `out` has one value per row ([`LookupError::Length`]
    /// otherwise); the first invalid row is [`LookupError::Batch`], `out` filled before it.
    pub fn p_columns(
        &self,
        points: &PointColumns<'_>,
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        crate::batch::check_length("out", out.len(), points.rows)?;
        let (g, a) = (
            points.gamma.full(points.rows),
            points.alpha.full(points.rows),
        );
        match points.restitution() {
            None => self.p_batch(&g, &a, out, outside),
            Some(e) => self.p_e_batch(&g, &a, &e.full(points.rows), out, outside),
        }
    }

    /// [`Table::p_columns`] through [`Table::p_batch_par`] / [`Table::p_e_batch_par`] on the
    /// current rayon pool (on the calling thread below `2 ×` [`CHUNK_ROWS`] rows); the error
    /// names the lowest invalid row.
    #[cfg(feature = "rayon")]
    pub fn p_columns_par(
        &self,
        points: &PointColumns<'_>,
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        if points.rows < 2 * CHUNK_ROWS {
            return self.p_columns(points, out, outside);
        }
        crate::batch::check_length("out", out.len(), points.rows)?;
        let (g, a) = (
            points.gamma.full(points.rows),
            points.alpha.full(points.rows),
        );
        match points.restitution() {
            None => self.p_batch_par(&g, &a, out, outside),
            Some(e) => self.p_e_batch_par(&g, &a, &e.full(points.rows), out, outside),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn broadcast_takes_the_rows_of_the_long_columns() {
        let (one, three) = ([1.0], [1.0, 2.0, 3.0]);
        let rows = broadcast([
            Column::scalar("a", &one),
            Column::scalar("b", &three),
            Column::vector("v", &[0.0; 9]),
        ]);
        assert_eq!(rows, Ok(3));
        assert_eq!(broadcast([Column::scalar("a", &one)]), Ok(1));
        assert_eq!(broadcast([Column::scalar("a", &[])]), Ok(0));
    }

    #[test]
    fn broadcast_names_the_column_and_both_lengths() {
        let e = broadcast([
            Column::scalar("gamma", &[1.0, 2.0]),
            Column::scalar("alpha", &[1.0]),
            Column::scalar("e_n", &[1.0, 1.0, 1.0]),
        ]);
        assert_eq!(
            e,
            Err(ColumnError::Broadcast {
                name: "e_n",
                rows: 3,
                other: "gamma",
                other_rows: 2
            })
        );
        let e = broadcast([Column::vector("normal", &[0.0; 4])]);
        assert_eq!(
            e,
            Err(ColumnError::Width {
                name: "normal",
                len: 4,
                width: 3
            })
        );
    }

    #[test]
    fn a_column_answers_its_rows() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let c = Column::vector("v", &v);
        assert_eq!(c.vec3(1), [4.0, 5.0, 6.0]);
        assert!(!c.is_shared());
        let s = Column::scalar("s", &v[..1]);
        assert!(s.is_shared());
        assert_eq!(s.at(5), 1.0);
        assert_eq!(&*s.full(3), &[1.0, 1.0, 1.0]);
    }

    #[test]
    fn fill_rows_stops_at_the_first_error() {
        let mut out = [0.0; 6];
        let r = fill_rows(&mut out, 2, |i, r| {
            if i == 2 {
                return Err("bad");
            }
            r.fill(i as f64);
            Ok(())
        });
        assert_eq!(r, Err((2, "bad")));
        assert_eq!(out, [0.0, 0.0, 1.0, 1.0, 0.0, 0.0]);
    }

    #[cfg(feature = "rayon")]
    #[test]
    fn fill_rows_par_names_the_lowest_failing_row() {
        let rows = 5 * CHUNK_ROWS;
        let mut out = vec![0.0; rows];
        let r = fill_rows_par(&mut out, 1, |i, r| {
            if i == 3 * CHUNK_ROWS + 7 || i == 4 * CHUNK_ROWS {
                return Err(i);
            }
            r[0] = i as f64;
            Ok(())
        });
        assert_eq!(r, Err((3 * CHUNK_ROWS + 7, 3 * CHUNK_ROWS + 7)));
        assert_eq!(out[CHUNK_ROWS], CHUNK_ROWS as f64);
    }
}
