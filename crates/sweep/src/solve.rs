//! Nodes computed in parallel: the points of a build, the store that keeps what was computed
//! ([`NodeStore`], [`NodeRecord`]), a run's options, shard and progress, and
//! [`solve_points_with`].

use std::sync::atomic::{AtomicBool, Ordering};

use oblique_solver::{Accuracy, KeptLevels, Law, Request};
use oblique_table::surface::Point;
use rayon::prelude::*;

use crate::{job, RunError, SweepError};

/// The exact key of a node: bit patterns of `(γ, α, e_n, tol)`.
pub type NodeKey = (u64, u64, u64, u64);

/// One computed node: `P(γ, α, e_n)` at solver tolerance `tol`, with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeRecord {
    /// γ.
    pub gamma: f64,
    /// α (`∞` allowed).
    pub alpha: f64,
    /// Normal restitution (1 for an elastic table).
    pub e_n: f64,
    /// Solver tolerance the value was computed with.
    pub tol: f64,
    /// `P`.
    pub p: f64,
    /// Solver error estimate of `P`.
    pub error: f64,
}

impl NodeRecord {
    /// The exact key of a node: bit patterns of `(γ, α, e_n, tol)`.
    pub fn key(&self) -> NodeKey {
        (
            self.gamma.to_bits(),
            self.alpha.to_bits(),
            self.e_n.to_bits(),
            self.tol.to_bits(),
        )
    }

    /// The record of `point` at `tol`, without values yet (for its key).
    pub fn at(point: Point, tol: f64) -> NodeRecord {
        NodeRecord {
            gamma: point.gamma,
            alpha: point.alpha,
            e_n: point.e_n,
            tol,
            p: f64::NAN,
            error: f64::NAN,
        }
    }
}

/// Where a sweep finds values computed before (a checkpoint, shard parts) and saves new ones.
/// The storage layer implements it; the sweep does no I/O itself.
pub trait NodeStore: Sync {
    /// A value computed before, by its exact key.
    fn get(&self, key: NodeKey) -> Option<(f64, f64)>;
    /// Save newly computed values durably (called after every batch of a few hundred).
    fn put(&self, records: &[NodeRecord]) -> Result<(), String>;
}

/// How a sweep runs beyond its config: stored values, sharding, interruption.
#[derive(Default, Clone, Copy)]
pub struct RunOptions<'a> {
    /// Values computed before and the place to save new ones.
    pub store: Option<&'a dyn NodeStore>,
    /// Every node must come from the store (a merge): a missing one is an error.
    pub strict: bool,
    /// Set (e.g. by a Ctrl-C handler) to stop after the current batch.
    pub stop: Option<&'a AtomicBool>,
}

/// Which part of the work a shard does: root cells and check points whose global index `i`
/// has `i mod count == index` (`index` in `0..count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0 ≤ index < count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    pub(crate) fn owns(&self, i: usize) -> bool {
        i % self.count == self.index
    }
}

/// Points per batch between saves and interruption checks.
const BATCH: usize = 256;

/// Progress reporting for long runs (implemented by the CLI and the Python package).
///
/// A build goes through the stages of [`stages`] in order; each begins with [`Progress::phase`].
/// A stage that simulates (a refinement round, the checks) then announces how many impacts it
/// runs with [`Progress::total`] (known from the moment its nodes are placed; the number of
/// rounds of a refinement is not known in advance) and reports them with [`Progress::inc`].
/// A whole [`job::Job`] adds a stage before and after those ([`job::Job::stages`]) and
/// [`job::Note`]s between them.
pub trait Progress: Sync {
    /// `stage` (one of [`stages`]) begins or goes on, `detail` says with what (e.g. the round).
    fn phase(&self, stage: &str, detail: &str);
    /// The current phase simulates `n` impacts (nodes found in a checkpoint are not counted).
    fn total(&self, n: u64);
    /// `n` impacts finished.
    fn inc(&self, n: u64);
    /// Something a [`job::Job`] tells its user besides progress (its `Display` is the text);
    /// ignored unless implemented.
    fn note(&self, note: &job::Note<'_>) {
        let _ = note;
    }
}

/// A progress sink that reports nothing.
pub struct Silent;

impl Progress for Silent {
    fn phase(&self, _: &str, _: &str) {}
    fn total(&self, _: u64) {}
    fn inc(&self, _: u64) {}
}

/// Compute `(P, error estimate)` at many points of law `law` in parallel, in order
/// (deterministic whatever the thread count).
pub fn solve_points(
    points: &[Point],
    tol: f64,
    law: Law,
    progress: &dyn Progress,
) -> Result<Vec<(f64, f64)>, SweepError> {
    solve_points_with(points, tol, law, progress, RunOptions::default()).map_err(|e| match e {
        RunError::Sweep(e) => e,
        // No store and no stop flag: nothing else can happen.
        other => unreachable!("solve_points without options: {other}"),
    })
}

/// `P` at `pt` to `tol` and its estimate; with `kept`, continuing from the levels it holds and
/// keeping this solve's ([`Request::solve_continuing`]), else a plain solve.
fn solve_one(
    pt: Point,
    tol: f64,
    law: Law,
    kept: Option<&mut KeptLevels>,
) -> Result<(f64, f64), SweepError> {
    let req = Request::new(pt.gamma, pt.alpha)
        .e_n(pt.e_n)
        .law(law)
        .accuracy(Accuracy::Tolerance(tol));
    match kept {
        Some(kept) => req.solve_continuing(kept),
        None => req.solve(),
    }
    .map(|s| (s.p, s.error_estimate))
    .map_err(|source| SweepError::Node {
        gamma: pt.gamma,
        alpha: pt.alpha,
        e_n: pt.e_n,
        source,
    })
}

/// [`solve_points`] with stored values, saving in batches and stopping when asked.
pub fn solve_points_with(
    points: &[Point],
    tol: f64,
    law: Law,
    progress: &dyn Progress,
    opts: RunOptions,
) -> Result<Vec<(f64, f64)>, RunError> {
    solve_points_kept(points, tol, law, progress, opts, (&mut [], f64::INFINITY))
}

/// [`solve_points_with`] that continues from the levels in `kept` (one per point, or none:
/// an empty slice) and keeps there the levels of each point it simulates whose estimate
/// exceeds `keep_above` (nothing for the others): a later solve of the same points at a
/// smaller tolerance, such as the polish of `nodes.polish_tol`, then simulates only the levels
/// beyond them, with the bits of a solve from scratch ([`Request::solve_continuing`]).
pub fn solve_points_kept(
    points: &[Point],
    tol: f64,
    law: Law,
    progress: &dyn Progress,
    opts: RunOptions,
    (kept, keep_above): (&mut [KeptLevels], f64),
) -> Result<Vec<(f64, f64)>, RunError> {
    let rec = |pt: &Point| NodeRecord::at(*pt, tol);
    let mut out: Vec<Option<(f64, f64)>> = points
        .iter()
        .map(|pt| opts.store.and_then(|s| s.get(rec(pt).key())))
        .collect();
    // Solved grouped by `e_n` (stable: in their order within one `e_n`): the threads then take
    // runs of one `e_n`, whose normal motion each thread computes once and caches, instead of
    // again for nearly every node when the values of `e_n` alternate along the list (the
    // answers do not depend on the order).
    let mut todo: Vec<usize> = (0..points.len()).filter(|&i| out[i].is_none()).collect();
    todo.sort_by(|&a, &b| points[a].e_n.total_cmp(&points[b].e_n));
    if opts.strict {
        if let Some(&i) = todo.first() {
            return Err(RunError::Missing {
                count: todo.len(),
                gamma: points[i].gamma,
                alpha: points[i].alpha,
                e_n: points[i].e_n,
            });
        }
    }
    progress.total(todo.len() as u64);
    let stopped = || opts.stop.is_some_and(|s| s.load(Ordering::Relaxed));
    for batch in todo.chunks(BATCH) {
        if stopped() {
            return Err(RunError::Interrupted);
        }
        let mut levels: Vec<KeptLevels> = batch
            .iter()
            .map(|&i| kept.get_mut(i).map(std::mem::take).unwrap_or_default())
            .collect();
        let values: Vec<(f64, f64)> = batch
            .par_iter()
            .zip(levels.par_iter_mut())
            .map(|(&i, levels)| {
                // Levels are only worth recording where they are kept or continued from.
                let memo = keep_above.is_finite() || !levels.is_empty();
                let r = solve_one(points[i], tol, law, memo.then_some(&mut *levels));
                if !r.as_ref().is_ok_and(|v| v.1 > keep_above) {
                    *levels = KeptLevels::new();
                }
                progress.inc(1);
                r
            })
            .collect::<Result<_, _>>()?;
        for (&i, levels) in batch.iter().zip(levels) {
            if let Some(slot) = kept.get_mut(i) {
                *slot = levels;
            }
        }
        if let Some(store) = opts.store {
            let records: Vec<NodeRecord> = batch
                .iter()
                .zip(&values)
                .map(|(&i, &(p, error))| NodeRecord {
                    p,
                    error,
                    ..rec(&points[i])
                })
                .collect();
            store.put(&records).map_err(RunError::Store)?;
        }
        for (&i, v) in batch.iter().zip(values) {
            out[i] = Some(v);
        }
    }
    Ok(out.into_iter().flatten().collect())
}
