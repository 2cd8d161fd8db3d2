//! The kink surfaces of the Kelvin–Voigt law as traced once over their widest range, stored
//! with the crate (`crates/sweep/data/kink_surfaces.txt`): the rows of the end-of-contact
//! surface E₋ ([`super::end_minus_surface`]) and of the sheet I₊ ([`super::interlude_sheet`])
//! depend on the law alone, not on the table, and tracing them took about 30 s of every
//! production build on 2 cores. A build takes a row from here where this file holds it (for
//! E₋: the same columns or more, traced from the same start), else traces it; the stored rows
//! are the traced ones bit for bit (the tests trace rows again and compare), so a table is the
//! same either way.
//!
//! The file is written by `cargo run --release -p oblique-tools --bin kinkdata >
//! crates/sweep/data/kink_surfaces.txt` ([`trace_all`]); after a change of the solver that
//! moves these rows, the tests fail until it is written again. Format, one record per line,
//! numbers as Rust prints an `f64` (shortest text that reads back to the same bits; `NaN` where
//! the kink was not found):
//!
//! - `E t_lo t_hi start rows`: the E₋ grid, columns `t_lo..=t_hi` (γ = `i` · 0.02), traced
//!   from column `start`; then `rows` lines, row `l` (`e_n = 1 − 0.02 l`), each `t_hi − t_lo + 1`
//!   values `1/α_E`;
//! - `I i n x₁ e₁ … x_n e_n`: the I₊ row at γ = `i` · 0.02, its samples `(ln α, e_I)`.
//!
//! Lines starting with `#` are comments.

use std::sync::OnceLock;

use rayon::prelude::*;

use super::{end_minus, interlude};
use crate::SweepError;

/// The stored E₋ grid.
#[derive(Debug, Clone, PartialEq)]
pub struct EndMinusGrid {
    /// First and last column.
    columns: (i64, i64),
    /// The column every row was traced from.
    start: i64,
    /// Row `l` over the columns.
    rows: Vec<Vec<f64>>,
}

impl EndMinusGrid {
    /// Row `l` over the columns `t_lo..=t_hi` as [`end_minus::trace_row`] traces it from
    /// `start`, where the stored row holds it: the same start, the columns within the stored
    /// ones, and the start's upper neighbour among them (the way down extrapolates from it).
    pub(super) fn row(&self, l: usize, (t_lo, t_hi): (i64, i64), start: i64) -> Option<Vec<f64>> {
        let (lo, hi) = self.columns;
        if start != self.start || t_lo < lo || t_hi > hi || t_hi <= start || t_lo > start {
            return None;
        }
        let row = self.rows.get(l)?;
        let from = (t_lo - lo) as usize;
        row.get(from..=from + (t_hi - t_lo) as usize)
            .map(<[f64]>::to_vec)
    }
}

/// What the file holds.
#[derive(Debug, Clone, PartialEq, Default)]
struct Stored {
    end_minus: Option<EndMinusGrid>,
    /// The I₊ rows by index `i`.
    interlude: Vec<(i64, Vec<(f64, f64)>)>,
}

const DATA: &str = include_str!("../../data/kink_surfaces.txt");

/// The stored data, parsed once (nothing where the file does not parse: then every row is
/// traced, and the tests say why).
fn stored() -> &'static Stored {
    static STORED: OnceLock<Stored> = OnceLock::new();
    STORED.get_or_init(|| parse(DATA).unwrap_or_default())
}

/// The stored E₋ grid, if any.
pub(super) fn end_minus() -> Option<&'static EndMinusGrid> {
    stored().end_minus.as_ref()
}

/// The stored I₊ row `i`, if any.
pub(super) fn interlude_row(i: i64) -> Option<&'static [(f64, f64)]> {
    stored()
        .interlude
        .iter()
        .find(|(j, _)| *j == i)
        .map(|(_, s)| s.as_slice())
}

fn parse(text: &str) -> Result<Stored, String> {
    let mut out = Stored::default();
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let num = |n: usize, w: &str| -> Result<f64, String> {
        w.parse::<f64>()
            .map_err(|e| format!("line {}: {w:?}: {e}", n + 1))
    };
    let int = |n: usize, w: Option<&str>| -> Result<i64, String> {
        w.ok_or_else(|| format!("line {}: a number is missing", n + 1))?
            .parse::<i64>()
            .map_err(|e| format!("line {}: {e}", n + 1))
    };
    while let Some((n, line)) = lines.next() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("E") => {
                let (t_lo, t_hi) = (int(n, words.next())?, int(n, words.next())?);
                let (start, count) = (int(n, words.next())?, int(n, words.next())?);
                let width = usize::try_from(t_hi - t_lo + 1).map_err(|e| e.to_string())?;
                let mut rows = Vec::new();
                for _ in 0..count {
                    let (m, row) = lines.next().ok_or("an E row is missing")?;
                    let row = row
                        .split_whitespace()
                        .map(|w| num(m, w))
                        .collect::<Result<Vec<f64>, String>>()?;
                    if row.len() != width {
                        return Err(format!("line {}: {} values, not {width}", m + 1, row.len()));
                    }
                    rows.push(row);
                }
                out.end_minus = Some(EndMinusGrid {
                    columns: (t_lo, t_hi),
                    start,
                    rows,
                });
            }
            Some("I") => {
                let (i, count) = (int(n, words.next())?, int(n, words.next())?);
                let values = words
                    .map(|w| num(n, w))
                    .collect::<Result<Vec<f64>, String>>()?;
                if values.len() as i64 != 2 * count {
                    return Err(format!(
                        "line {}: {} values, not {}",
                        n + 1,
                        values.len(),
                        2 * count
                    ));
                }
                let samples = values.chunks_exact(2).map(|p| (p[0], p[1])).collect();
                out.interlude.push((i, samples));
            }
            _ => return Err(format!("line {}: unknown record {line:?}", n + 1)),
        }
    }
    Ok(out)
}

/// Trace both surfaces over their widest range and write the file's text (rows in parallel).
pub fn trace_all() -> Result<String, SweepError> {
    let ((t_lo, t_hi), start, count) = end_minus::widest_grid();
    let rows = (0..count)
        .into_par_iter()
        .map(|l| end_minus::trace_row(l, (t_lo, t_hi), start))
        .collect::<Result<Vec<Vec<f64>>, SweepError>>()?;
    let (i_lo, i_hi) = interlude::row_indices();
    let sheet = (i_lo..=i_hi)
        .into_par_iter()
        .map(|i| interlude::trace_row(i as f64 * interlude::SHEET_STEP).map(|r| (i, r.samples)))
        .collect::<Result<Vec<_>, SweepError>>()?;
    let mut text = String::from(
        "# The kink surfaces of the Kelvin-Voigt law for the probes of table builds\n\
         # (crates/sweep/src/kink/stored.rs). Written by\n\
         # cargo run --release -p oblique-tools --bin kinkdata > crates/sweep/data/kink_surfaces.txt\n",
    );
    text += &format!("E {t_lo} {t_hi} {start} {count}\n");
    for row in &rows {
        let words: Vec<String> = row.iter().map(|v| format!("{v:?}")).collect();
        text += &words.join(" ");
        text += "\n";
    }
    for (i, samples) in &sheet {
        text += &format!("I {i} {}", samples.len());
        for (x, e) in samples {
            text += &format!(" {x:?} {e:?}");
        }
        text += "\n";
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stored_file_parses_and_holds_both_surfaces() {
        let s = parse(DATA).expect("the stored kink surfaces parse");
        let grid = s.end_minus.expect("E- stored");
        let ((t_lo, t_hi), start, count) = end_minus::widest_grid();
        assert_eq!(grid.columns, (t_lo, t_hi));
        assert_eq!(grid.start, start);
        assert_eq!(grid.rows.len(), count);
        let (i_lo, i_hi) = interlude::row_indices();
        let indices: Vec<i64> = s.interlude.iter().map(|r| r.0).collect();
        assert_eq!(indices, (i_lo..=i_hi).collect::<Vec<_>>());
    }

    /// The stored rows are what the tracing gives today, to the bit: two rows of E₋ over the
    /// widest grid and two rows of I₊.
    #[test]
    fn stored_rows_are_the_traced_ones() {
        let grid = end_minus().expect("E- stored");
        for l in [7, 30] {
            let traced = end_minus::trace_row(l, grid.columns, grid.start).expect("traced");
            let stored = &grid.rows[l];
            assert_eq!(traced.len(), stored.len());
            for (a, b) in traced.iter().zip(stored) {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "E- row {l}: traced {a}, stored {b}"
                );
            }
        }
        for i in [118, 129] {
            let traced = interlude::trace_row(i as f64 * interlude::SHEET_STEP).expect("traced");
            let stored = interlude_row(i).expect("I+ row stored");
            assert_eq!(traced.samples.len(), stored.len(), "I+ row {i}");
            for (a, b) in traced.samples.iter().zip(stored) {
                assert!(
                    a.0.to_bits() == b.0.to_bits() && a.1.to_bits() == b.1.to_bits(),
                    "I+ row {i}: traced {a:?}, stored {b:?}"
                );
            }
        }
    }

    /// A narrower range takes its rows from the stored grid: the same surface as traced.
    #[test]
    fn a_surface_from_stored_rows_is_the_traced_one() {
        let grid = end_minus().expect("E- stored");
        // γ 1.9–2.1: columns 94..=106 (one beyond each end), start 100; e_n down to 0.9.
        let (cols, start) = ((94, 106), 100);
        for l in 0..7 {
            let traced = end_minus::trace_row(l, cols, start).expect("traced");
            let stored = grid.row(l, cols, start).expect("held");
            assert!(traced
                .iter()
                .zip(&stored)
                .all(|(a, b)| a.to_bits() == b.to_bits()));
        }
        // Not held: another start, or columns beyond the stored ones.
        assert!(grid.row(0, (101, 110), 101).is_none());
        assert!(grid.row(0, (80, 106), 100).is_none());
    }

    #[test]
    fn a_malformed_file_is_refused_with_its_line() {
        assert!(parse("E 1 2 1 1\n0.5\n").unwrap_err().contains("line 2"));
        assert!(parse("I 5 2 0.1 0.9\n").unwrap_err().contains("line 1"));
        assert!(parse("X\n").unwrap_err().contains("unknown record"));
        assert_eq!(parse("# nothing\n"), Ok(Stored::default()));
    }
}
