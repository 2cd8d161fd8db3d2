//! Errors of a sweep: what the config or the build refused ([`SweepError`], each naming the key
//! to change) and what else stopped a run ([`RunError`]).

use oblique_solver::PhysicsError;
use thiserror::Error;

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
    /// A kink surface could not be traced for the knots of `nodes.knots`.
    #[error(
        "kink {knot} at gamma = {gamma}, e_n = {e_n}: {what} (set nodes.knots = false to build \
         without the knots, or narrow the domain)"
    )]
    Knots {
        /// Which kink.
        knot: &'static str,
        /// γ of the failed point.
        gamma: f64,
        /// `e_n` of the failed point.
        e_n: f64,
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
            | SweepError::Knots { .. }
            | SweepError::TooManyNodes { .. }
            | SweepError::Unreachable { .. }
            | SweepError::DepthLimit { .. } => true,
        }
    }
}
