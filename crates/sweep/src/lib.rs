//! Builds a `P(γ, α)` table: places nodes on curve-aligned patches, refines them until the
//! predicted interpolation error meets the target, runs independent impacts in parallel (rayon)
//! and measures the interpolation error at held-out points. [`nodestore`] owns the checkpoint
//! and shard-part files; the table file itself is written by `oblique_table::write`.

pub mod config;
pub mod job;
pub mod nodestore;

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};

use oblique_table::surface::{
    stencil, OutOfDomain, PartialMap, Patch, PatchId, PatchKind, Point, Region, RestitutionAxis,
    Surface, Warp,
};
pub use oblique_table::write::{Built, BuiltPatch};
use oblique_table::Check;
use rayon::prelude::*;
use thiserror::Error;

pub use config::Config;
use oblique_solver::{Accuracy, Law, PhysicsError, Request};
pub mod kink;
pub mod warp;

/// Engine version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// Git commit the engine was built from (`-dirty` when the work tree had changes).
pub const GIT_COMMIT: &str = env!("OBLIQUE_GIT_COMMIT");

/// Current UTC time as RFC 3339 (`YYYY-MM-DDTHH:MM:SSZ`).
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// The provenance of a table built now by this engine from `cfg` (whose text is `config_text`)
/// in `wall_time_s` seconds.
pub fn provenance(
    cfg: &Config,
    config_text: String,
    wall_time_s: f64,
) -> oblique_table::Provenance {
    let dissipative = cfg.domain.e_n_range().is_some();
    let law = if dissipative {
        format!(" law={}", cfg.law().name())
    } else {
        String::new()
    };
    oblique_table::Provenance {
        schema_version: if dissipative {
            oblique_table::format::SCHEMA_VERSION
        } else {
            oblique_table::format::ELASTIC_SCHEMA_VERSION
        },
        engine_version: VERSION.into(),
        git_commit: GIT_COMMIT.into(),
        config: config_text,
        solver: format!(
            "scheme=accurate{law} tol={:e} (automatic refinement, error estimate per node)",
            cfg.solver.tol
        ),
        law: if dissipative {
            cfg.law().name().to_string()
        } else {
            String::new()
        },
        created: crate::utc_now(),
        wall_time_s,
        node_tol: cfg.solver.tol,
        check_tol: cfg.check_tol(),
        target_error: cfg.nodes.target_error,
    }
}

/// `", e_n = …"` for a point of a dissipative table, nothing at `e_n = 1`.
fn e_n_words(e_n: f64) -> String {
    if e_n == 1.0 {
        String::new()
    } else {
        format!(", e_n = {e_n}")
    }
}

/// Errors of a sweep.
#[derive(Debug, Error)]
pub enum SweepError {
    /// The table model refused what the build assembled (a defect of the build, not of the
    /// config).
    #[error("the built table is inconsistent: {0}")]
    Model(String),
    /// The fold curve F₊ could not be traced for the warp of the partial-slip patch.
    #[error(
        "fold curve F+ at gamma = {gamma}: {what} (set nodes.fold_warp = false to build without \
         the warp)"
    )]
    Fold {
        /// γ of the failed point.
        gamma: f64,
        /// What went wrong.
        what: String,
    },
    /// A kink curve could not be traced for the probes of `nodes.probe_kinks`.
    #[error(
        "kink curve {curve} at gamma = {gamma}: {what} (set nodes.probe_kinks = false to build \
         without its probes)"
    )]
    Kink {
        /// Which curve.
        curve: &'static str,
        /// γ of the failed point.
        gamma: f64,
        /// What went wrong.
        what: String,
    },
    /// A node could not be computed.
    #[error("node gamma = {gamma}, alpha = {alpha}{en}: {source}", en = e_n_words(*e_n))]
    Node {
        /// γ of the node.
        gamma: f64,
        /// α of the node.
        alpha: f64,
        /// e_n of the node.
        e_n: f64,
        /// The solver's error.
        source: PhysicsError,
    },
    /// The refinement would exceed `nodes.max_nodes`.
    #[error(
        "patch {patch}: refinement round {round} needs {more} more nodes, {needed} in all, more \
         than nodes.max_nodes = {max}{worst}; raise nodes.max_nodes or loosen \
         nodes.target_error",
        worst = match predicted {
            Some(p) => format!(
                " (the cells being refined predict errors up to {p:.1e} > target_error {target:e})"
            ),
            None => String::new(),
        }
    )]
    TooManyNodes {
        /// Patch name.
        patch: &'static str,
        /// Target error.
        target: f64,
        /// The limit.
        max: usize,
        /// Refinement round of the patch (1: its root cells).
        round: usize,
        /// New nodes the round needs.
        more: usize,
        /// Nodes of the whole build with those of the round.
        needed: usize,
        /// Largest predicted error of the cells the round refines (`None` in round 0, where no
        /// cell has been evaluated yet).
        predicted: Option<f64>,
    },
    /// The pre-flight probe found a tolerance the solver cannot reach in reasonable time.
    #[error(
        "{key} = {tol:e} cannot be reached at gamma = {gamma}, alpha = {alpha} (the hardest \
         point of the domain), where every node would take seconds or more ({reason}); {advice}"
    )]
    Unreachable {
        /// Config key of the tolerance.
        key: &'static str,
        /// The tolerance.
        tol: f64,
        /// γ of the probe.
        gamma: f64,
        /// α of the probe.
        alpha: f64,
        /// The solver's reason.
        reason: String,
        /// What to change in the config.
        advice: String,
    },
    /// A cell at the deepest level still predicts more than the target: `P` is not smooth
    /// there at the scale the node tolerance resolves (node noise or a kink).
    #[error(
        "patch {patch}: a cell of depth {depth} (gamma {gamma_lo:.6}..{gamma_hi:.6}, coordinate \
         {c_lo:.6}..{c_hi:.6}) still predicts an interpolation error of {predicted:.2e} > \
         target_error {target:e}, with node error estimates up to {node_error:.1e}; loosen \
         nodes.target_error or tighten solver.tol"
    )]
    DepthLimit {
        /// Patch name.
        patch: &'static str,
        /// Depth of the cell.
        depth: u32,
        /// γ range of the cell.
        gamma_lo: f64,
        /// Upper γ of the cell.
        gamma_hi: f64,
        /// Patch coordinate range of the cell.
        c_lo: f64,
        /// Upper coordinate of the cell.
        c_hi: f64,
        /// Predicted interpolation error.
        predicted: f64,
        /// Target error.
        target: f64,
        /// Largest node error estimate of the cell.
        node_error: f64,
    },
}

/// Errors of a sweep beyond the node computations: interruption and stored results.
#[derive(Debug, Error)]
pub enum RunError {
    /// The run was stopped (Ctrl-C); the node store holds what was finished.
    #[error("interrupted")]
    Interrupted,
    /// The node store could not take results.
    #[error("cannot save results: {0}")]
    Store(String),
    /// A merge needs a node that none of the parts holds.
    #[error(
        "{count} node(s) needed by the table are in none of the parts (first: gamma = {gamma}, \
         alpha = {alpha}{en}); the parts are incomplete or come from different builds: rerun the \
         missing shards",
        en = e_n_words(*e_n)
    )]
    Missing {
        /// Number of missing nodes in the first batch that had any.
        count: usize,
        /// γ of the first missing node.
        gamma: f64,
        /// α of the first missing node.
        alpha: f64,
        /// e_n of the first missing node.
        e_n: f64,
    },
    /// A node or the refinement failed.
    #[error(transparent)]
    Sweep(#[from] SweepError),
}

impl RunError {
    /// Whether the user can fix the cause in the config or on the command line (a limit, a
    /// tolerance, the parts given to a merge), as opposed to an interruption or a failed write.
    pub fn user_can_fix(&self) -> bool {
        match self {
            RunError::Sweep(e) => e.user_can_fix(),
            RunError::Missing { .. } => true,
            RunError::Interrupted | RunError::Store(_) => false,
        }
    }
}

impl SweepError {
    /// Whether a config key decides the failure (every variant names the key to change).
    pub fn user_can_fix(&self) -> bool {
        match self {
            SweepError::Node { source, .. } => matches!(
                source,
                PhysicsError::ToleranceUnreachable { .. }
                    | PhysicsError::Infeasible { .. }
                    | PhysicsError::TooLarge { .. }
            ),
            SweepError::Model(_) => false,
            SweepError::Fold { .. }
            | SweepError::Kink { .. }
            | SweepError::TooManyNodes { .. }
            | SweepError::Unreachable { .. }
            | SweepError::DepthLimit { .. } => true,
        }
    }
}

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
    fn owns(&self, i: usize) -> bool {
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

/// Name of the stage that traces the fold curve F₊ (before the partial-slip patch).
pub const STAGE_FOLD: &str = "fold tracing";
/// Name of the stage that traces the kink curves of `nodes.probe_kinks` (before the
/// partial-slip patch).
pub const STAGE_KINKS: &str = "kink tracing";
/// Name of the held-out checks' stage (the last of a build).
pub const STAGE_CHECKS: &str = "held-out checks";

/// The stage of a patch's refinement rounds.
fn stage_refine(patch: &str) -> String {
    format!("{patch} refinement")
}

/// The stages of a build (or of one shard) of `cfg`, in the order [`Progress::phase`] reports
/// them: each patch's refinement (the partial-slip patch's preceded by [`STAGE_FOLD`] when it
/// is warped and by [`STAGE_KINKS`] when its kinks are probed), then [`STAGE_CHECKS`].
pub fn stages(cfg: &Config) -> Vec<String> {
    let mut out = Vec::new();
    for spec in patch_specs(cfg) {
        if cfg.nodes.fold_warp && spec.kind == PatchKind::PartialSlip {
            out.push(STAGE_FOLD.to_string());
        }
        if cfg.nodes.probe_kinks && spec.kind == PatchKind::PartialSlip {
            out.push(STAGE_KINKS.to_string());
        }
        out.push(stage_refine(spec.name));
    }
    out.push(STAGE_CHECKS.to_string());
    out
}

/// Deepest quadtree level (a leaf at this depth has `2^-MAX_DEPTH` of its root's size).
const MAX_DEPTH: u32 = 12;

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

fn solve_one(pt: Point, tol: f64, law: Law) -> Result<(f64, f64), SweepError> {
    Request::new(pt.gamma, pt.alpha)
        .e_n(pt.e_n)
        .law(law)
        .accuracy(Accuracy::Tolerance(tol))
        .solve()
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
    let rec = |pt: &Point| NodeRecord::at(*pt, tol);
    let mut out: Vec<Option<(f64, f64)>> = points
        .iter()
        .map(|pt| opts.store.and_then(|s| s.get(rec(pt).key())))
        .collect();
    let todo: Vec<usize> = (0..points.len()).filter(|&i| out[i].is_none()).collect();
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
        let values: Vec<(f64, f64)> = batch
            .par_iter()
            .map(|&i| {
                let r = solve_one(points[i], tol, law);
                progress.inc(1);
                r
            })
            .collect::<Result<_, _>>()?;
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

struct PatchSpec {
    name: &'static str,
    kind: PatchKind,
    gamma_lo: f64,
    gamma_hi: f64,
}

fn patch_specs(cfg: &Config) -> Vec<PatchSpec> {
    let d = &cfg.domain;
    let mut specs = Vec::new();
    if d.gamma_min < 1.0 {
        specs.push(PatchSpec {
            name: PatchId::StickLow.name(),
            kind: PatchKind::Stick,
            gamma_lo: d.gamma_min,
            gamma_hi: d.gamma_max.min(1.0),
        });
    }
    if d.gamma_max > 1.0 {
        let lo = d.gamma_min.max(1.0);
        specs.push(PatchSpec {
            name: PatchId::PartialHigh.name(),
            kind: PatchKind::PartialSlip,
            gamma_lo: lo,
            gamma_hi: d.gamma_max,
        });
        specs.push(PatchSpec {
            name: PatchId::StickHigh.name(),
            kind: PatchKind::Stick,
            gamma_lo: lo,
            gamma_hi: d.gamma_max,
        });
    }
    specs
}

/// The `e_n` axis of every patch of a dissipative table (`None`: elastic).
fn restitution_axis(cfg: &Config) -> Result<Option<RestitutionAxis>, SweepError> {
    cfg.domain
        .e_n_range()
        .map(|(lo, hi)| RestitutionAxis::new(lo, hi, cfg.blocks_e_n()).map_err(SweepError::Model))
        .transpose()
}

/// Root cells of a patch along γ.
fn roots_gamma(cfg: &Config, spec: &PatchSpec) -> usize {
    ((spec.gamma_hi - spec.gamma_lo) * cfg.nodes.blocks_per_unit_gamma)
        .ceil()
        .max(1.0) as usize
}

/// Root cells of a patch.
fn root_count(cfg: &Config, spec: &PatchSpec) -> usize {
    let be = if cfg.domain.e_n_range().is_some() {
        cfg.blocks_e_n()
    } else {
        1
    };
    roots_gamma(cfg, spec) * cfg.nodes.blocks_coord * be
}

/// The root grid of a patch being built and the exact lattice its nodes live on.
struct Layout<'a> {
    spec: &'a PatchSpec,
    bg: usize,
    bc: usize,
    m: usize,
    alpha_max: f64,
    /// Fold warp of the partial-slip patch: the lattice is in `c'`, α comes from `c`.
    warp: Option<&'a Warp>,
    /// The `e_n` axis of a dissipative table: the lattice has a third axis.
    restitution: Option<RestitutionAxis>,
}

/// A node on the finest lattice of a patch: `(γ index, c index, e_n index, warped)`. A node on
/// the warp's `start` row exists twice: unwarped for the leaves below it, warped for those
/// above. The `e_n` index is 0 without an `e_n` axis.
type Key = (u64, u64, u64, bool);

/// A point where a cell is measured: its position `(u, v)` in node intervals of the cell
/// (along γ, along the coordinate) and the point simulated there.
type Probe = (f64, f64, Point);

/// A tree cell: the number of splits above it (`depth`), its depth along each axis and its
/// integer position per axis at that axis's depth (`ie = 0` without an `e_n` axis). Without
/// an `e_n` axis every split halves both axes, so `d = [depth, depth, 0]`.
#[derive(Debug, Clone, Copy)]
struct Cell {
    depth: u32,
    d: [u32; 3],
    ig: u64,
    ic: u64,
    ie: u64,
}

impl Layout<'_> {
    /// Lattice units per root cell per axis.
    fn fine(&self) -> u64 {
        (self.m as u64) << MAX_DEPTH
    }

    /// The partial-slip coordinate's map ([`Patch::partial_map`]).
    fn partial_map(&self) -> PartialMap {
        PartialMap::of_table(self.restitution.is_some())
    }

    /// Axes of the tree: 2, or 3 with an `e_n` axis, or 2 (`c`, `e_n`) for one pair.
    fn dims(&self) -> u32 {
        oblique_table::surface::tree_dims(self.restitution.is_some(), self.pair())
    }

    /// The patch of one pair: a single γ, no node spacing along it ([`Patch::is_pair`]).
    fn pair(&self) -> bool {
        self.spec.gamma_lo == self.spec.gamma_hi
    }

    /// Root cells along `e_n` (1 without the axis).
    fn be(&self) -> usize {
        self.restitution.map_or(1, |r| r.blocks())
    }

    /// The root cells, in the order of the format (`γ` outer, `e_n` inner).
    fn roots(&self) -> Vec<Cell> {
        let (bc, be) = (self.bc as u64, self.be() as u64);
        (0..self.bg as u64)
            .flat_map(|ig| {
                (0..bc).flat_map(move |ic| {
                    (0..be).map(move |ie| Cell {
                        depth: 0,
                        d: [0; 3],
                        ig,
                        ic,
                        ie,
                    })
                })
            })
            .collect()
    }

    /// `(γ, c, α)` and the point `(γ, α, e_n)` of a lattice node (computed from the key
    /// alone, so shared nodes agree).
    fn point(&self, key: Key) -> (f64, f64, Point) {
        let ng = self.bg as u64 * self.fine();
        let nc = self.bc as u64 * self.fine();
        let xg = key.0 as f64 / ng as f64;
        let gamma = if key.0 == ng {
            self.spec.gamma_hi
        } else {
            self.spec.gamma_lo + (self.spec.gamma_hi - self.spec.gamma_lo) * xg
        };
        let c = key.1 as f64 / nc as f64;
        let e_n = match self.restitution {
            Some(r) => r.e_n(key.2 as f64 / (self.be() as u64 * self.fine()) as f64),
            None => 1.0,
        };
        (gamma, c, self.point_at(gamma, c, e_n, key.3))
    }

    /// The point at `γ`, lattice coordinate `c` (`c'` where `warped`) and `e_n`.
    fn point_at(&self, gamma: f64, c: f64, e_n: f64, warped: bool) -> Point {
        let unwarped = match self.warp {
            Some(w) if warped => w.invert(gamma, c),
            _ => c,
        };
        let alpha =
            self.spec
                .kind
                .alpha_at(self.partial_map(), gamma, unwarped, e_n, self.alpha_max);
        Point::new(gamma, alpha, e_n)
    }

    /// Where a cell of an elastic partial-slip patch crossed by the kink curve `curve` is
    /// measured ([`kink::PROBE_OFFSETS`] from the kink along the coordinate, on every node row
    /// and half row along γ where the curve lies within the cell): `(u, v, point)` with `u`, `v`
    /// the position in node intervals of the cell. Empty when the curve misses the cell.
    fn kink_probes(&self, cell: Cell, curve: &kink::KinkCurve) -> Vec<Probe> {
        let m = self.m as f64;
        let ng = (self.bg as u64 * self.fine()) as f64;
        let nc = (self.bc as u64 * self.fine()) as f64;
        let sg = (1u64 << (MAX_DEPTH - cell.d[0])) as f64;
        let sc = (1u64 << (MAX_DEPTH - cell.d[1])) as f64;
        let warped = self.warped(cell);
        let (lo, hi) = (self.spec.gamma_lo, self.spec.gamma_hi);
        let mut out = Vec::new();
        for i in 0..=self.m {
            let u = i as f64;
            let xg = (cell.ig as f64 * m + u) * sg / ng;
            let gamma = if xg >= 1.0 { hi } else { lo + (hi - lo) * xg };
            let Some(alpha_k) = curve.alpha_at(gamma) else {
                continue;
            };
            let c_k =
                self.spec
                    .kind
                    .coord_at(self.partial_map(), gamma, alpha_k, 1.0, self.alpha_max);
            let lattice = match self.warp {
                Some(w) if warped => w.apply(gamma, c_k),
                _ => c_k,
            };
            let v_k = lattice * nc / sc - cell.ic as f64 * m;
            // Also a cell whose edge is near the kink: its first intervals see the steep side.
            if !(-kink::PROBE_OFFSETS[6]..=m - kink::PROBE_OFFSETS[0]).contains(&v_k) {
                continue;
            }
            for d in kink::PROBE_OFFSETS {
                let v = v_k + d;
                if (0.0..=m).contains(&v) {
                    let c = (cell.ic as f64 * m + v) * sc / nc;
                    out.push((u, v, self.point_at(gamma, c, 1.0, warped)));
                }
            }
        }
        out
    }

    /// The cell's extent along γ in root-row units (exact dyadic values).
    fn rows(cell: Cell) -> (f64, f64) {
        let scale = f64::from(1u32 << cell.d[0]);
        (cell.ig as f64 / scale, (cell.ig + 1) as f64 / scale)
    }

    /// Whether the cell lies at or beyond the warp's start (its nodes are warped).
    fn warped(&self, cell: Cell) -> bool {
        self.warp.is_some_and(|w| Self::rows(cell).0 >= w.start())
    }

    /// Whether the warp's start cuts through the cell: it is split without being evaluated, so
    /// that every leaf lies on one side.
    fn straddles(&self, cell: Cell) -> bool {
        let (lo, hi) = Self::rows(cell);
        self.warp.is_some_and(|w| lo < w.start() && w.start() < hi)
    }

    /// Lattice keys of a cell's `(m+1)^dims` nodes, row-major (`γ` outer, `e_n` inner).
    fn cell_keys(&self, cell: Cell) -> Vec<Key> {
        let sg = 1u64 << (MAX_DEPTH - cell.d[0]);
        let sc = 1u64 << (MAX_DEPTH - cell.d[1]);
        let se = 1u64 << (MAX_DEPTH - cell.d[2]);
        let m = self.m as u64;
        let warped = self.warped(cell);
        let me = if self.restitution.is_some() { m } else { 0 };
        let mg = if self.pair() { 0 } else { m };
        let mut keys = Vec::with_capacity((self.m + 1).pow(self.dims()));
        for i in 0..=mg {
            for j in 0..=m {
                for l in 0..=me {
                    keys.push((
                        (cell.ig * m + i) * sg,
                        (cell.ic * m + j) * sc,
                        (cell.ie * m + l) * se,
                        warped,
                    ));
                }
            }
        }
        keys
    }

    /// The children of a cell split along the axes of `bits` (bit `dims − 1 − k` for axis
    /// `k`), in the order of the format: row-major over the halved axes (`2·q_γ + q_c` for a
    /// quadtree, `4·q_γ + 2·q_c + q_e` for an octree cell that halves every axis).
    fn children(&self, cell: Cell, bits: u8) -> Vec<Cell> {
        let has_e = self.restitution.is_some();
        let mask = if has_e {
            [bits & 4 != 0, bits & 2 != 0, bits & 1 != 0]
        } else {
            [bits & 2 != 0, bits & 1 != 0, false]
        };
        let mut out = Vec::with_capacity(1 << bits.count_ones());
        let top = |b: bool| u64::from(b);
        for qg in 0..=top(mask[0]) {
            for qc in 0..=top(mask[1]) {
                for qe in 0..=top(mask[2] && has_e) {
                    let d = [
                        cell.d[0] + u32::from(mask[0]),
                        cell.d[1] + u32::from(mask[1]),
                        cell.d[2] + u32::from(mask[2] && has_e),
                    ];
                    out.push(Cell {
                        depth: cell.depth + 1,
                        d,
                        ig: if mask[0] { 2 * cell.ig + qg } else { cell.ig },
                        ic: if mask[1] { 2 * cell.ic + qc } else { cell.ic },
                        ie: if mask[2] && has_e {
                            2 * cell.ie + qe
                        } else {
                            cell.ie
                        },
                    });
                }
            }
        }
        out
    }
}

/// Largest deviation, over the nodes of an `n`-interval grid over `dims` axes (2 or 3,
/// row-major) that are not on its `n/2`-interval sub-grid, between the value and the `k`-point
/// tensor interpolation from the sub-grid.
fn surplus(values: &[f64], n: usize, k: usize, dims: u32) -> f64 {
    let coarse_n = n / 2;
    let n1 = n + 1;
    let me = if dims == 3 { n } else { 0 };
    let at = |i: usize, j: usize, l: usize| values[(i * n1 + j) * (me + 1) + l];
    let mut w = [[0.0; 8]; 3];
    let mut worst = 0.0_f64;
    for i in 0..=n {
        for j in 0..=n {
            for l in 0..=me {
                if i % 2 == 0 && j % 2 == 0 && l % 2 == 0 {
                    continue;
                }
                let (sg, kg) = stencil(i as f64 / 2.0, coarse_n + 1, k, &mut w[0]);
                let (sc, kc) = stencil(j as f64 / 2.0, coarse_n + 1, k, &mut w[1]);
                let (se, ke) = if dims == 3 {
                    stencil(l as f64 / 2.0, coarse_n + 1, k, &mut w[2])
                } else {
                    w[2][0] = 1.0;
                    (0, 1)
                };
                let mut v = 0.0;
                for (x, wx) in w[0].iter().enumerate().take(kg) {
                    for (y, wy) in w[1].iter().enumerate().take(kc) {
                        for (z, wz) in w[2].iter().enumerate().take(ke) {
                            v += wx * wy * wz * at(2 * (sg + x), 2 * (sc + y), 2 * (se + z));
                        }
                    }
                }
                worst = worst.max((v - at(i, j, l)).abs());
            }
        }
    }
    worst
}

/// The `k`-point tensor interpolant of a cell's `(m+1)²` values (row-major, `γ` outer) at `u`
/// node intervals along γ and `v` along the coordinate: the rule a leaf answers with.
fn interp_cell(values: &[f64], m: usize, k: usize, u: f64, v: f64) -> f64 {
    let (mut wg, mut wc) = ([0.0; 8], [0.0; 8]);
    let (sg, kg) = stencil(u, m + 1, k, &mut wg);
    let (sc, kc) = stencil(v, m + 1, k, &mut wc);
    let mut out = 0.0;
    for (x, wx) in wg.iter().enumerate().take(kg) {
        for (y, wy) in wc.iter().enumerate().take(kc) {
            out += wx * wy * values[(sg + x) * (m + 1) + sc + y];
        }
    }
    out
}

/// Largest deviation between the values at odd positions along `axis` and the `k`-point
/// interpolation along that axis alone from the even ones.
fn surplus_axis(values: &[f64], n: usize, k: usize, dims: u32, axis: usize) -> f64 {
    let n1 = n + 1;
    let me = if dims == 3 { n } else { 0 };
    let at = |i: usize, j: usize, l: usize| values[(i * n1 + j) * (me + 1) + l];
    let mut w = [0.0; 8];
    let mut worst = 0.0_f64;
    for i in 0..=n {
        for j in 0..=n {
            for l in 0..=me {
                let idx = [i, j, l][axis];
                if idx % 2 == 0 {
                    continue;
                }
                let (s0, kk) = stencil(idx as f64 / 2.0, n / 2 + 1, k, &mut w);
                let mut v = 0.0;
                for (x, wx) in w.iter().enumerate().take(kk) {
                    let e = 2 * (s0 + x);
                    let mut ix = [i, j, l];
                    ix[axis] = e;
                    v += wx * at(ix[0], ix[1], ix[2]);
                }
                worst = worst.max((v - at(i, j, l)).abs());
            }
        }
    }
    worst
}

/// The axes a cell of a patch with an `e_n` axis halves when its prediction exceeds `target`
/// (bit `dims − 1 − k` for axis `k`: `γ`, `c`, `e_n`, or `c`, `e_n` for one pair): each axis
/// whose own surplus
/// ([`surplus_axis`], a quarter of it as the cell's own error along that axis) exceeds the
/// target, or else the axis with the largest. Along `e_n` `P` is smooth and the kink curves
/// lie across `c`, so most cells need only one or two axes halved (measured on γ 1.9–2.6,
/// target 1e-4: 55 315 nodes in the partial-slip patch against 188 131 halving every axis).
fn split_axes(values: &[f64], m: usize, k: usize, target: f64, dims: u32) -> u8 {
    let s: Vec<f64> = (0..dims as usize)
        .map(|a| surplus_axis(values, m, k, dims, a) / 4.0)
        .collect();
    let big = s.iter().copied().fold(0.0, f64::max);
    let mut bits = 0u8;
    for (a, &sa) in s.iter().enumerate() {
        if sa > target || sa >= big {
            bits |= 1 << (dims as usize - 1 - a);
        }
    }
    bits
}

/// Build one patch by adaptive refinement of its quadtree (octree with an `e_n` axis).
///
/// Every open cell gets its `(m+1)^dims` nodes (nodes shared with cells already done are
/// reused).
/// Its surplus `s` (the error of interpolating from its own half grid) measures the error of a
/// grid twice as coarse; the cell's own error is predicted as `s/4`, the second-order rate that
/// holds where a kink curve (curvature jump) crosses the cell (smooth cells converge faster, so
/// the prediction is conservative there). A cell whose prediction exceeds the target is split:
/// into four children without an `e_n` axis; with one, halving only the axes that need it
/// ([`split_axes`]), into two, four or eight children. The children reuse part of its nodes.
///
/// With a `shard`, only the root cells whose global index (`first_root` + index in the patch)
/// the shard owns are refined, their nodes go to the store, and nothing is assembled (`None`).
/// Each root's tree depends only on its own nodes, so the shards together compute every node of
/// the whole run.
fn build_patch(
    cfg: &Config,
    spec: &PatchSpec,
    progress: &dyn Progress,
    total_nodes: &mut usize,
    opts: RunOptions,
    first_root: usize,
    shard: Option<Shard>,
) -> Result<Option<BuiltPatch>, RunError> {
    let k = cfg.nodes.stencil;
    let warp = if cfg.nodes.fold_warp && spec.kind == PatchKind::PartialSlip {
        progress.phase(
            STAGE_FOLD,
            &format!("the fold curve F+ for the warp of {}", spec.name),
        );
        warp::fold_warp(
            spec.gamma_lo,
            spec.gamma_hi,
            roots_gamma(cfg, spec),
            cfg.nodes.blocks_coord,
        )?
    } else {
        None
    };
    let kinks = if cfg.nodes.probe_kinks && spec.kind == PatchKind::PartialSlip {
        progress.phase(
            STAGE_KINKS,
            &format!("the fold curve F- for the probes of {}", spec.name),
        );
        kink::fold_minus_curve(spec.gamma_lo, spec.gamma_hi)?
    } else {
        None
    };
    let layout = Layout {
        spec,
        bg: roots_gamma(cfg, spec),
        bc: cfg.nodes.blocks_coord,
        m: cfg.nodes.leaf_intervals,
        alpha_max: cfg.domain.alpha_max,
        warp: warp.as_ref(),
        restitution: restitution_axis(cfg)?,
    };
    let m = layout.m;
    let law = cfg.law();
    // All cells ever created, roots first; `child[i]` is the first child of a split cell.
    let mut cells: Vec<Cell> = layout.roots();
    let mut child: Vec<Option<usize>> = vec![None; cells.len()];
    let mut predicted = vec![f64::NAN; cells.len()];
    let mut open: Vec<usize> = (0..cells.len())
        .filter(|&i| shard.is_none_or(|sh| sh.owns(first_root + i)))
        .collect();
    let mut cache: HashMap<Key, (f64, f64)> = HashMap::new();
    // The axes each split cell halves (bit `dims − 1 − k` for axis `k`); 0 for a leaf.
    let mut mask = vec![0u8; cells.len()];
    for round in 0.. {
        let mut wanted: Vec<Key> = open
            .iter()
            .filter(|&&c| !layout.straddles(cells[c]))
            .flat_map(|&c| layout.cell_keys(cells[c]))
            .filter(|key| !cache.contains_key(key))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        if *total_nodes + wanted.len() > cfg.nodes.max_nodes {
            // The cells this round refines are the children of cells that predicted too much.
            let worst = (0..cells.len())
                .filter(|&c| child[c].is_some() && predicted[c].is_finite())
                .map(|c| predicted[c])
                .reduce(f64::max);
            return Err(RunError::Sweep(SweepError::TooManyNodes {
                patch: spec.name,
                target: cfg.nodes.target_error,
                max: cfg.nodes.max_nodes,
                round: round + 1,
                more: wanted.len(),
                needed: *total_nodes + wanted.len(),
                predicted: worst,
            }));
        }
        progress.phase(
            &stage_refine(spec.name),
            &format!(
                "round {}: {} open cells, {} new nodes",
                round + 1,
                open.len(),
                wanted.len()
            ),
        );
        let points: Vec<Point> = wanted.iter().map(|&key| layout.point(key).2).collect();
        let values = solve_points_with(&points, cfg.solver.tol, law, progress, opts)?;
        *total_nodes += wanted.len();
        cache.extend(wanted.into_iter().zip(values));
        // Every open cell is decided first (split, leaf, or measured next to a kink curve),
        // then split in the order of `open`: the order of the cells, and so of the leaves, in
        // the file.
        let values_of = |cell: Cell| -> Vec<f64> {
            layout
                .cell_keys(cell)
                .iter()
                .map(|key| cache[key].0)
                .collect()
        };
        let mut split = vec![false; open.len()];
        let mut probed: Vec<(usize, Vec<Probe>)> = Vec::new();
        for (o, &c) in open.iter().enumerate() {
            // A cell across the warp's start is split without being evaluated: no leaf may
            // straddle it.
            if layout.straddles(cells[c]) {
                split[o] = true;
                continue;
            }
            let vals = values_of(cells[c]);
            let pred = surplus(&vals, m, k, layout.dims()) / 4.0;
            predicted[c] = pred;
            if pred <= cfg.nodes.target_error {
                if let Some(curve) = &kinks {
                    let probes = layout.kink_probes(cells[c], curve);
                    if !probes.is_empty() {
                        probed.push((o, probes));
                    }
                }
                continue;
            }
            mask[c] = if layout.restitution.is_some() {
                split_axes(&vals, m, k, cfg.nodes.target_error, layout.dims())
            } else {
                0b11
            };
            split[o] = true;
        }
        if !probed.is_empty() {
            // A cell a kink curve crosses is a leaf only if the error measured next to the
            // kink (the probe's difference to the cell's interpolant plus the probe's own error
            // estimate) is within the target too; that error becomes its prediction.
            let points: Vec<Point> = probed
                .iter()
                .flat_map(|(_, probes)| probes.iter().map(|p| p.2))
                .collect();
            progress.phase(
                &stage_refine(spec.name),
                &format!(
                    "round {}: {} probes next to F- in {} cells",
                    round + 1,
                    points.len(),
                    probed.len()
                ),
            );
            let mut values =
                solve_points_with(&points, cfg.solver.tol, law, progress, opts)?.into_iter();
            for (o, probes) in probed {
                let c = open[o];
                let vals = values_of(cells[c]);
                let measured = probes
                    .iter()
                    .zip(values.by_ref())
                    .map(|(&(u, v, _), (p, e))| (interp_cell(&vals, m, k, u, v) - p).abs() + e)
                    .fold(0.0, f64::max);
                predicted[c] = predicted[c].max(measured);
                if predicted[c] > cfg.nodes.target_error {
                    mask[c] = 0b11;
                    split[o] = true;
                }
            }
        }
        let mut next = Vec::new();
        for (o, &c) in open.iter().enumerate() {
            if !split[o] {
                continue;
            }
            if mask[c] == 0 {
                // Split without being evaluated (across the warp's start): every axis.
                mask[c] = (1 << layout.dims()) - 1;
            } else if cells[c].d.iter().any(|&d| d >= MAX_DEPTH) {
                let keys = layout.cell_keys(cells[c]);
                let (g0, c0, _) = layout.point(keys[0]);
                let (g1, c1, _) = layout.point(keys[keys.len() - 1]);
                return Err(RunError::Sweep(SweepError::DepthLimit {
                    patch: spec.name,
                    depth: cells[c].depth,
                    gamma_lo: g0,
                    gamma_hi: g1,
                    c_lo: c0,
                    c_hi: c1,
                    predicted: predicted[c],
                    target: cfg.nodes.target_error,
                    node_error: keys.iter().map(|k| cache[k].1).fold(0.0, f64::max),
                }));
            }
            child[c] = Some(cells.len());
            for ch in layout.children(cells[c], mask[c]) {
                next.push(cells.len());
                cells.push(ch);
                child.push(None);
                predicted.push(f64::NAN);
                mask.push(0);
            }
        }
        if next.is_empty() {
            break;
        }
        open = next;
    }
    if shard.is_some() {
        return Ok(None);
    }
    // Leaves are numbered in cell order.
    let mut tree = Vec::with_capacity(cells.len());
    let mut leaf_error = Vec::new();
    let mut leaf_depth = Vec::new();
    let (mut p, mut err, mut gamma, mut coord, mut alpha, mut e_n) = (
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
        Vec::new(),
    );
    for (c, cell) in cells.iter().enumerate() {
        match child[c] {
            Some(first) => tree.push(first as i32),
            None => {
                tree.push(-(leaf_error.len() as i32) - 1);
                leaf_error.push(predicted[c]);
                leaf_depth.push(cell.depth);
                for key in layout.cell_keys(*cell) {
                    let (g, cc, pt) = layout.point(key);
                    let (v, e) = cache[&key];
                    p.push(v);
                    err.push(e);
                    gamma.push(g);
                    coord.push(cc);
                    alpha.push(pt.alpha);
                    if layout.restitution.is_some() {
                        e_n.push(pt.e_n);
                    }
                }
            }
        }
    }
    let simulated = cache.values().filter(|(_, e)| *e > 0.0).count();
    Ok(Some(BuiltPatch {
        name: spec.name,
        patch: Patch::with_split(
            spec.kind,
            spec.gamma_lo,
            spec.gamma_hi,
            layout.bg,
            layout.bc,
            m,
            tree,
            p,
            err,
            warp.clone(),
            layout.restitution,
            layout.restitution.is_some().then_some(mask),
        )
        .map_err(|m| SweepError::Model(format!("patch '{}': {m}", spec.name)))?,
        gamma,
        coord,
        alpha,
        e_n,
        leaf_error,
        leaf_depth,
        unique_nodes: cache.len(),
        simulated,
    }))
}

/// Finest level a pre-flight probe may use (one impact at 32768 steps × 32768 springs takes
/// about a second).
const PROBE_MAX_STEPS: usize = 1 << 15;

/// The refinement limits of a pre-flight probe (and of the default of `checks.tol`).
pub fn probe_limits() -> oblique_solver::impact::Limits {
    oblique_solver::impact::Limits {
        max_steps: PROBE_MAX_STEPS,
        ..oblique_solver::impact::Limits::default()
    }
}

/// What the pre-flight probe measured.
#[derive(Debug, Clone, Copy)]
pub struct Preflight {
    /// Wall time of the slowest probe (s): an upper estimate of one node's cost.
    pub slowest_node_s: f64,
    /// Tolerance of the held-out checks: `checks.tol` when set, else the tightest of
    /// [`default_check_tols`] that the probes reached (`solver.tol` at worst).
    pub check_tol: f64,
    /// `checks.tol` is not set and `solver.tol / 10` was out of reach: `check_tol` is looser.
    pub check_tol_loosened: bool,
}

/// The candidates for the default of `checks.tol`, tightest first: `solver.tol` / 10, / 5, / 2,
/// / 1 (at least 1e-10). The pre-flight takes the first it can reach.
pub fn default_check_tols(cfg: &Config) -> [f64; 4] {
    let tol = cfg.solver.tol;
    [tol / 10.0, tol / 5.0, tol / 2.0, tol].map(|t| t.max(1e-10))
}

/// The default check tolerance a sharded run used, found in its merged parts: the candidate
/// of [`default_check_tols`] at which the parts hold the first held-out check (`None` when
/// `checks.tol` is set, or when no candidate fits).
pub fn check_tol_in_store(cfg: &Config, store: &dyn NodeStore) -> Option<f64> {
    if cfg.checks.tol.is_some() {
        return None;
    }
    let &first = check_points(cfg).first()?;
    default_check_tols(cfg)
        .into_iter()
        .find(|&tol| store.get(NodeRecord::at(first, tol).key()).is_some())
}

/// Why a probe failed, naming only the limits that were exceeded.
fn unreachable_reason(e: &PhysicsError) -> String {
    match e {
        PhysicsError::Infeasible {
            springs,
            steps,
            work,
            memory_mb,
            max_steps,
            max_work,
            max_memory_mb,
            ..
        } => {
            let mut over = Vec::new();
            if steps > max_steps {
                over.push(format!("{steps} steps, more than the {max_steps} allowed"));
            }
            if work > max_work {
                over.push(format!(
                    "{work:.1e} spring-steps, more than the {max_work:.1e} allowed"
                ));
            }
            if memory_mb > max_memory_mb {
                over.push(format!(
                    "{memory_mb:.0} MB, more than the {max_memory_mb:.0} MB allowed"
                ));
            }
            let res = oblique_solver::Resolution {
                springs: *springs,
                steps: *steps,
            };
            format!("even at best it needs {res}: {}", over.join(", "))
        }
        other => {
            let text = other.to_string();
            text.split("; loosen").next().unwrap_or(&text).to_string()
        }
    }
}

/// Check before the work starts that the node and check tolerances can be reached: solve the
/// hardest points of the domain (largest γ in partial slip and at α = ∞, where `P` oscillates
/// fastest) with the refinement capped at [`PROBE_MAX_STEPS`]. A tolerance that needs more would
/// make every node take seconds to minutes: refused, naming the key to change. When `checks.tol`
/// is not set, its default is the tightest of [`default_check_tols`] that is reached: a default
/// never refuses a run.
pub fn preflight(cfg: &Config) -> Result<Preflight, SweepError> {
    let g = cfg.domain.gamma_max;
    // Both ends of the e_n range of a dissipative table.
    let e_ns = match cfg.domain.e_n_range() {
        Some((lo, hi)) => vec![lo, hi],
        None => vec![1.0],
    };
    let mut probes = Vec::new();
    for &e_n in &e_ns {
        probes.push(Point::new(g, f64::INFINITY, e_n));
        if g > 1.0 {
            let (a1, a2) = (
                oblique_table::surface::alpha_c1_dissipative(g, e_n),
                oblique_table::surface::alpha_c2(g),
            );
            probes.push(Point::new(g, (a1 * a2).sqrt(), e_n));
        }
    }
    let limits = probe_limits();
    let law = cfg.law();
    let mut slowest = 0.0f64;
    // Solve every probe point at `tol`: the first failure, as the refusal of `key`.
    let mut probe = |key: &'static str, tol: f64, advice: &str| -> Result<(), SweepError> {
        for &Point { gamma, alpha, e_n } in &probes {
            let start = std::time::Instant::now();
            let r = Request::new(gamma, alpha)
                .e_n(e_n)
                .law(law)
                .accuracy(Accuracy::Tolerance(tol))
                .limits(limits)
                .solve();
            slowest = slowest.max(start.elapsed().as_secs_f64());
            match r {
                Ok(_) => {}
                Err(
                    e @ (PhysicsError::ToleranceUnreachable { .. }
                    | PhysicsError::Infeasible { .. }),
                ) => {
                    return Err(SweepError::Unreachable {
                        key,
                        tol,
                        gamma,
                        alpha,
                        reason: unreachable_reason(&e),
                        advice: advice.to_string(),
                    });
                }
                Err(source) => {
                    return Err(SweepError::Node {
                        gamma,
                        alpha,
                        e_n,
                        source,
                    })
                }
            }
        }
        Ok(())
    };
    probe("solver.tol", cfg.solver.tol, "loosen solver.tol")?;
    let (check_tol, check_tol_loosened) = match cfg.checks.tol {
        Some(t) => {
            probe(
                "checks.tol",
                t,
                &format!(
                    "loosen checks.tol (at most solver.tol = {:e})",
                    cfg.solver.tol
                ),
            )?;
            (t, false)
        }
        None => {
            let candidates = default_check_tols(cfg);
            let last = candidates.len() - 1;
            // `solver.tol` itself (the last candidate) was reached just above.
            let i = (0..last)
                .find(|&i| probe("checks.tol", candidates[i], "").is_ok())
                .unwrap_or(last);
            (candidates[i], i > 0)
        }
    };
    Ok(Preflight {
        slowest_node_s: slowest,
        check_tol,
        check_tol_loosened,
    })
}

/// The generator of the held-out check points and of `sweep verify`'s sample.
pub use oblique_physics::sample::SplitMix;

/// Run a whole sweep: build every patch, then simulate and compare the held-out checks.
pub fn build(cfg: &Config, progress: &dyn Progress) -> Result<Built, SweepError> {
    build_with(cfg, progress, RunOptions::default()).map_err(|e| match e {
        RunError::Sweep(e) => e,
        other => unreachable!("build without options: {other}"),
    })
}

/// [`build`] with stored values, saving and interruption ([`RunOptions`]). With a store that
/// holds every node (a finished checkpoint, merged shard parts) nothing is simulated, and the
/// table is the same, bit for bit, as that of an uninterrupted single run.
pub fn build_with(
    cfg: &Config,
    progress: &dyn Progress,
    opts: RunOptions,
) -> Result<Built, RunError> {
    let mut total = 0usize;
    let mut patches = Vec::new();
    for spec in patch_specs(cfg) {
        patches.extend(build_patch(
            cfg, &spec, progress, &mut total, opts, 0, None,
        )?);
    }
    let find = |id: PatchId| {
        patches
            .iter()
            .find(|p| p.name == id.name())
            .map(|p| p.patch.clone())
    };
    let surface = Surface::with_restitution(
        cfg.domain.gamma_min,
        cfg.domain.gamma_max,
        cfg.domain.alpha_max,
        cfg.nodes.stencil,
        PatchId::ALL.map(find),
        cfg.domain.e_n_range(),
    )
    .map_err(SweepError::Model)?;
    let points = check_points(cfg);
    progress.phase(STAGE_CHECKS, &format!("{} points", points.len()));
    let sims = solve_points_with(&points, cfg.check_tol(), cfg.law(), progress, opts)?;
    let checks = points
        .iter()
        .zip(&sims)
        .map(|(pt, &(p_sim, _))| {
            let p_int = surface
                .eval_point(pt.gamma, pt.alpha, pt.e_n, OutOfDomain::Error)
                .unwrap_or(f64::NAN);
            Check {
                gamma: pt.gamma,
                alpha: pt.alpha,
                e_n: pt.e_n,
                p_simulated: p_sim,
                p_interpolated: p_int,
                interpolation_error: (p_int - p_sim).abs(),
                patch: Region::of_e(pt.gamma, pt.alpha, pt.e_n).index(),
            }
        })
        .collect();
    Ok(Built {
        surface,
        patches,
        checks,
    })
}

/// Compute one shard's share of a sweep into `opts.store`: the root cells and held-out checks
/// whose global index `i` has `i mod count == index`. Merging the stores of all shards and
/// running [`build_with`] on them (strictly) gives the single run's table.
pub fn build_shard(
    cfg: &Config,
    progress: &dyn Progress,
    opts: RunOptions,
    shard: Shard,
) -> Result<(), RunError> {
    let mut total = 0usize;
    let mut first_root = 0;
    for spec in patch_specs(cfg) {
        build_patch(
            cfg,
            &spec,
            progress,
            &mut total,
            opts,
            first_root,
            Some(shard),
        )?;
        first_root += root_count(cfg, &spec);
    }
    let points: Vec<Point> = check_points(cfg)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| shard.owns(*i))
        .map(|(_, pt)| pt)
        .collect();
    progress.phase(STAGE_CHECKS, &format!("{} points", points.len()));
    solve_points_with(&points, cfg.check_tol(), cfg.law(), progress, opts)?;
    Ok(())
}

/// `n` points next to the critical curves, where `P` has its kinks: `γ` uniform in
/// `[gamma_min, gamma_max]`, `e_n` uniform in `e_range` (1 without), `α = α_k (1 + s·r)` with
/// `α_k` alternately `α_c1(γ, e_n)` (`α_c2` for `γ ≤ 1`) and `α_c2(γ)`, `s = ±1` and
/// `r = 10^u`, `u` uniform in `[−4, −1]`; a point beyond `alpha_max` is drawn again. The same
/// `seed` gives the same points (`sweep verify --near-curves` and the held-out checks of
/// `checks.near_curves`).
pub fn near_curve_points(
    gamma_min: f64,
    gamma_max: f64,
    e_range: Option<(f64, f64)>,
    alpha_max: f64,
    n: usize,
    seed: u64,
) -> Vec<Point> {
    use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2};
    let mut rng = SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let i = out.len();
        let gamma = (gamma_min + (gamma_max - gamma_min) * rng.uniform()).min(gamma_max);
        let e_n = match e_range {
            Some((lo, hi)) => (lo + (hi - lo) * rng.uniform()).min(hi),
            None => 1.0,
        };
        let curve = if i % 2 == 0 && gamma > 1.0 {
            alpha_c1_dissipative(gamma, e_n)
        } else {
            alpha_c2(gamma)
        };
        let r = 10f64.powf(-4.0 + 3.0 * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        let alpha = curve * (1.0 + sign * r);
        if alpha <= alpha_max {
            out.push(Point::new(gamma, alpha, e_n));
        }
    }
    out
}

/// Held-out points: uniform in each patch's (γ, c), and in `e_n` over its range for a
/// dissipative table, strictly inside (c < 1 keeps α finite); then `checks.near_curves` points
/// next to the critical curves ([`near_curve_points`], from a seed derived from
/// `checks.seed`, so that the random points stay where they were).
fn check_points(cfg: &Config) -> Vec<Point> {
    let mut rng = SplitMix(cfg.checks.seed);
    let mut points = Vec::new();
    let range = cfg.domain.e_n_range();
    for p in patch_specs(cfg) {
        for _ in 0..cfg.checks.per_patch {
            let gamma = p.gamma_lo + (p.gamma_hi - p.gamma_lo) * rng.uniform();
            let c = rng.uniform();
            // The elastic sequence of draws is unchanged: e_n draws only with an e_n axis.
            let e_n = match range {
                Some((lo, hi)) => lo + (hi - lo) * rng.uniform(),
                None => 1.0,
            };
            let map = if range.is_some() {
                PartialMap::SqrtBoth
            } else {
                PartialMap::SqrtEnd
            };
            let alpha = p.kind.alpha_at(map, gamma, c, e_n, cfg.domain.alpha_max);
            points.push(Point::new(gamma, alpha, e_n));
        }
    }
    points.extend(near_curve_points(
        cfg.domain.gamma_min,
        cfg.domain.gamma_max,
        range,
        cfg.domain.alpha_max,
        cfg.checks.near_curves,
        cfg.checks.seed ^ NEAR_CURVE_SEED,
    ));
    points
}

/// Mixed into `checks.seed` for the points next to the critical curves.
const NEAR_CURVE_SEED: u64 = 0x6e65_6172_6375_7276;

#[cfg(test)]
mod tests {
    use super::*;

    fn config(near: usize) -> Config {
        Config::parse(
            &format!(
                "output = \"t.h5\"\n[domain]\ngamma_min = 0.5\ngamma_max = 3.0\n\
                 alpha_max = \"inf\"\n[nodes]\ntarget_error = 1e-4\n[solver]\ntol = 1e-5\n\
                 [checks]\nper_patch = 7\nnear_curves = {near}\n"
            ),
            "t.toml",
        )
        .expect("a valid config")
    }

    #[test]
    fn near_curve_checks_follow_the_random_ones_and_lie_next_to_a_curve() {
        use oblique_physics::regimes::{alpha_c1, alpha_c2};
        let plain = check_points(&config(0));
        let with = check_points(&config(40));
        assert_eq!(with.len(), plain.len() + 40);
        // The random points do not move.
        for (a, b) in plain.iter().zip(&with) {
            assert_eq!((a.gamma, a.alpha), (b.gamma, b.alpha));
        }
        for pt in &with[plain.len()..] {
            assert!((0.5..=3.0).contains(&pt.gamma), "{pt:?}");
            let near = |k: f64| {
                let r = (pt.alpha / k - 1.0).abs();
                (0.99e-4..=0.1001).contains(&r)
            };
            let c1 = pt.gamma > 1.0 && near(alpha_c1(pt.gamma));
            assert!(c1 || near(alpha_c2(pt.gamma)), "{pt:?}");
        }
        // Both curves are visited.
        let on_c2 = with[plain.len()..]
            .iter()
            .filter(|p| (p.alpha / alpha_c2(p.gamma) - 1.0).abs() <= 0.1001)
            .count();
        assert!(on_c2 > 5 && on_c2 < 40, "{on_c2}");
    }

    #[test]
    fn too_many_near_curve_checks_are_refused_naming_the_key() {
        let text = "output = \"t.h5\"\n[domain]\ngamma_min = 0.5\ngamma_max = 3.0\n\
                    [nodes]\ntarget_error = 1e-4\n[solver]\ntol = 1e-5\n\
                    [checks]\nnear_curves = 100001\n";
        let e = Config::parse(text, "t.toml").expect_err("refused");
        assert!(e.to_string().contains("checks.near_curves"), "{e}");
    }

    /// The largest `error / (leaf prediction + 2.66 × the leaf's largest node estimate)` of a
    /// table built over γ 2.80–2.84 (below F₊; target 3e-5, tol 3e-6: about 12 000 nodes), at
    /// 336 points next to F₋ simulated at tol 1e-8: the per-leaf bound's ratio, at most 1 where
    /// the bound holds.
    fn worst_leaf_ratio_next_to_fold_minus(probe: bool) -> f64 {
        let text = format!(
            "output = \"t.h5\"\n[domain]\ngamma_min = 2.8\ngamma_max = 2.84\n\
             alpha_max = \"inf\"\n[nodes]\ntarget_error = 3e-5\nprobe_kinks = {probe}\n\
             [solver]\ntol = 3e-6\n[checks]\nper_patch = 5\n"
        );
        let cfg = Config::parse(&text, "t.toml").expect("a valid config");
        let built = build(&cfg, &Silent).expect("built");
        let slip = built
            .patches
            .iter()
            .find(|p| p.name == PatchId::PartialHigh.name())
            .expect("a partial-slip patch");
        let per_leaf = (cfg.nodes.leaf_intervals + 1).pow(2);
        let curve = kink::fold_minus_curve(2.8, 2.84).unwrap().unwrap();
        let points: Vec<Point> = (0..16)
            .flat_map(|i| {
                let g = 2.8012 + 0.0025 * f64::from(i);
                let a = curve.alpha_at(g).unwrap();
                (0..21).map(move |j| Point::new(g, a * (1.0 + 5e-4 * f64::from(j - 10)), 1.0))
            })
            .collect();
        let truth = solve_points(&points, 1e-8, Law::Elastic, &Silent).unwrap();
        let mut worst = 0.0_f64;
        for (pt, (p, _)) in points.iter().zip(truth) {
            let table = built
                .surface
                .eval_point(pt.gamma, pt.alpha, 1.0, OutOfDomain::Error)
                .unwrap();
            let c = slip.patch.warped(
                pt.gamma,
                oblique_table::surface::partial_coord(pt.gamma, pt.alpha),
            );
            let (leaf, _, _) = slip.patch.find_leaf(pt.gamma, c);
            let est = slip.patch.error_estimate()[leaf * per_leaf..(leaf + 1) * per_leaf]
                .iter()
                .fold(0.0_f64, |a, &b| a.max(b));
            worst = worst.max((table - p).abs() / (slip.leaf_error[leaf] + 2.66 * est));
        }
        worst
    }

    #[test]
    fn leaves_next_to_fold_minus_are_measured_before_they_are_trusted() {
        let without = worst_leaf_ratio_next_to_fold_minus(false);
        let with = worst_leaf_ratio_next_to_fold_minus(true);
        // Without the probes a leaf next to F₋ errs beyond its own bound (2.03×); with them none
        // does (0.84).
        assert!(without > 1.0, "without probes: {without}");
        assert!(with <= 1.0, "with probes: {with}");
    }
}
