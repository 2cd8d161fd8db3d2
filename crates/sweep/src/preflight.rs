//! The pre-flight of a build: the hardest points of the domain simulated once, to refuse a
//! `solver.tol` that cannot be reached there and to choose the held-out checks' tolerance.

use oblique_solver::{Accuracy, PhysicsError, Request};
use oblique_table::surface::Point;

use crate::config::Config;
use crate::{check_points, NodeRecord, NodeStore, SweepError};

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
