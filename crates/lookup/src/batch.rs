//! Many queries at once, over slices: serially and (feature `rayon`, on by default) on the
//! current rayon pool. `P(γ, α)` here; the 3-D rebounds of a prepared pair in
//! [`crate::prepared`] use the same two drivers.

use crate::{LookupError, Table};
use oblique_table::surface::OutOfDomain;

/// Queries per parallel task: large enough to amortise scheduling, small enough to balance.
#[cfg(feature = "rayon")]
const CHUNK: usize = 4096;

/// [`LookupError::Length`] unless `len == expected`.
pub(crate) fn check_length(
    name: &'static str,
    len: usize,
    expected: usize,
) -> Result<(), LookupError> {
    if len == expected {
        Ok(())
    } else {
        Err(LookupError::Length {
            name,
            len,
            expected,
        })
    }
}

fn batch_error(index: usize, e: LookupError) -> LookupError {
    LookupError::Batch {
        index,
        source: Box::new(e),
    }
}

/// `out[i] = f(&input[i])` in order, stopping at the first error (index and error).
#[inline]
fn run<I, O>(
    input: &[I],
    out: &mut [O],
    f: &impl Fn(&I) -> Result<O, LookupError>,
) -> Result<(), (usize, LookupError)> {
    for (i, (o, x)) in out.iter_mut().zip(input).enumerate() {
        *o = f(x).map_err(|e| (i, e))?;
    }
    Ok(())
}

/// `out[i] = f(&input[i])` for slices of equal length, serially; the first error becomes
/// [`LookupError::Batch`].
pub(crate) fn serial<I, O>(
    input: &[I],
    out: &mut [O],
    f: impl Fn(&I) -> Result<O, LookupError>,
) -> Result<(), LookupError> {
    run(input, out, &f).map_err(|(i, e)| batch_error(i, e))
}

/// [`serial`] on the current rayon pool, in chunks of [`CHUNK`]; the error names the lowest
/// invalid index.
#[cfg(feature = "rayon")]
pub(crate) fn parallel<I: Sync, O: Send>(
    input: &[I],
    out: &mut [O],
    f: impl Fn(&I) -> Result<O, LookupError> + Sync,
) -> Result<(), LookupError> {
    parallel_chunks(out, |start, o| run(&input[start..start + o.len()], o, &f))
}

/// `fill(start, chunk)` for every chunk of [`CHUNK`] outputs (`start` the index of its first),
/// on the current rayon pool; a chunk's error `(i, e)` is at index `start + i`, and the lowest
/// such index becomes [`LookupError::Batch`].
#[cfg(feature = "rayon")]
fn parallel_chunks<O: Send>(
    out: &mut [O],
    fill: impl Fn(usize, &mut [O]) -> Result<(), (usize, LookupError)> + Sync,
) -> Result<(), LookupError> {
    use rayon::prelude::*;
    let first_error = out
        .par_chunks_mut(CHUNK)
        .enumerate()
        .filter_map(|(k, o)| {
            let start = k * CHUNK;
            fill(start, o).err().map(|(i, e)| (start + i, e))
        })
        .min_by_key(|(i, _)| *i);
    match first_error {
        None => Ok(()),
        Some((index, e)) => Err(batch_error(index, e)),
    }
}

fn check_lengths(gamma: &[f64], alpha: &[f64], out: &[f64]) -> Result<(), LookupError> {
    check_length("alpha", alpha.len(), gamma.len())?;
    check_length("out", out.len(), gamma.len())
}

impl Table {
    /// `out[i] = P(gamma[i], alpha[i])` for every `i`, in order ([`Table::p_with`]).
    ///
    /// The three slices must have the same length. On the first invalid query the error
    /// ([`LookupError::Batch`]) names its index; `out` before that index is filled, after it
    /// untouched.
    pub fn p_batch(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        check_lengths(gamma, alpha, out)?;
        self.p_slices(gamma, alpha, out, outside)
            .map_err(|(index, e)| batch_error(index, e))
    }

    fn p_slices(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        if let Some(accel) = self.accel() {
            return accel.eval_batch(self.surface(), gamma, alpha, out, outside);
        }
        for (i, ((o, &g), &a)) in out.iter_mut().zip(gamma).zip(alpha).enumerate() {
            *o = self.p_with(g, a, outside).map_err(|e| (i, e))?;
        }
        Ok(())
    }

    /// [`Table::p_batch`] in parallel on the current rayon pool (chunks of 4096 queries). If
    /// some queries are invalid, the error names the lowest invalid index; `out` is then filled
    /// only partly (every valid query of a chunk before its first invalid one).
    #[cfg(feature = "rayon")]
    pub fn p_batch_par(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        check_lengths(gamma, alpha, out)?;
        parallel_chunks(out, |s, o| {
            let end = s + o.len();
            self.p_slices(&gamma[s..end], &alpha[s..end], o, outside)
        })
    }

    /// `out[i] = P(gamma[i], alpha[i], e_n[i])` for every `i`, in order ([`Table::p_e_with`]):
    /// [`Table::p_batch`] with a normal-restitution slice (all four of one length). A batch
    /// whose `e_n` are all 1 takes the path of [`Table::p_batch`].
    pub fn p_e_batch(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        e_n: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        check_lengths(gamma, alpha, out)?;
        check_length("e_n", e_n.len(), gamma.len())?;
        self.p_e_slices(gamma, alpha, e_n, out, outside)
            .map_err(|(index, e)| batch_error(index, e))
    }

    fn p_e_slices(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        e_n: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        if e_n.iter().all(|&e| e == 1.0) {
            return self.p_slices(gamma, alpha, out, outside);
        }
        for (i, o) in out.iter_mut().enumerate() {
            *o = self
                .p_e_with(gamma[i], alpha[i], e_n[i], outside)
                .map_err(|e| (i, e))?;
        }
        Ok(())
    }

    /// [`Table::p_e_batch`] in parallel on the current rayon pool (chunks of 4096 queries);
    /// the error names the lowest invalid index, as [`Table::p_batch_par`].
    #[cfg(feature = "rayon")]
    pub fn p_e_batch_par(
        &self,
        gamma: &[f64],
        alpha: &[f64],
        e_n: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), LookupError> {
        check_lengths(gamma, alpha, out)?;
        check_length("e_n", e_n.len(), gamma.len())?;
        parallel_chunks(out, |s, o| {
            let end = s + o.len();
            self.p_e_slices(&gamma[s..end], &alpha[s..end], &e_n[s..end], o, outside)
        })
    }
}
