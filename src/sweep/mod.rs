//! The sweep layer: places nodes on curve-aligned patches, refines them until the predicted
//! interpolation error meets the target, runs independent impacts in parallel (rayon) and
//! measures the interpolation error at held-out points. No file I/O here (see `storage`).

pub mod config;

use std::collections::HashMap;

use oblique_lookup::surface::{stencil, Patch, PatchKind, Region, Surface};
use oblique_lookup::Check;
use rayon::prelude::*;
use thiserror::Error;

use crate::physics::{self, Accuracy, PhysicsError, Scheme};
pub use config::Config;

/// Errors of a sweep.
#[derive(Debug, Error)]
pub enum SweepError {
    /// A node could not be computed.
    #[error("node gamma = {gamma}, alpha = {alpha}: {source}")]
    Node {
        /// γ of the node.
        gamma: f64,
        /// α of the node.
        alpha: f64,
        /// The solver's error.
        source: PhysicsError,
    },
    /// The refinement would exceed `nodes.max_nodes`.
    #[error(
        "patch {patch}: reaching target_error {target:e} needs more than nodes.max_nodes = {max} \
         nodes (predicted error {predicted:e} at {nodes} nodes); raise nodes.max_nodes or \
         loosen nodes.target_error"
    )]
    TooManyNodes {
        /// Patch name.
        patch: &'static str,
        /// Target error.
        target: f64,
        /// The limit.
        max: usize,
        /// Predicted error reached.
        predicted: f64,
        /// Nodes placed so far.
        nodes: usize,
    },
}

/// Progress reporting for long runs (implemented by the CLI).
pub trait Progress: Sync {
    /// `n` more impacts are scheduled.
    fn add(&self, n: u64);
    /// `n` impacts finished.
    fn inc(&self, n: u64);
    /// A phase begins.
    fn phase(&self, msg: &str);
}

/// A progress sink that reports nothing.
pub struct Silent;

impl Progress for Silent {
    fn add(&self, _: u64) {}
    fn inc(&self, _: u64) {}
    fn phase(&self, _: &str) {}
}

/// One patch as built, with the α of every node (the patch itself stores only P).
#[derive(Debug, Clone)]
pub struct BuiltPatch {
    /// Patch name in the file.
    pub name: &'static str,
    /// The patch.
    pub patch: Patch,
    /// α at every node, row-major like `patch.p` (`∞` allowed).
    pub alpha: Vec<f64>,
    /// Predicted interpolation error along γ and along the coordinate.
    pub predicted_error: (f64, f64),
    /// Nodes that were simulated (the others are closed forms).
    pub simulated: usize,
}

/// The result of a sweep.
#[derive(Debug, Clone)]
pub struct Built {
    /// Surface (patches and domain) as the lookup crate reads it.
    pub surface: Surface,
    /// The patches with their node α values, in file order.
    pub patches: Vec<BuiltPatch>,
    /// Held-out checks.
    pub checks: Vec<Check>,
}

/// Maximum doublings per axis beyond the initial grid.
const MAX_LEVELS: u32 = 12;

/// Compute P at many points in parallel, in order (deterministic whatever the thread count).
pub fn solve_points(
    points: &[(f64, f64)],
    tol: f64,
    progress: &dyn Progress,
) -> Result<Vec<(f64, f64)>, SweepError> {
    progress.add(points.len() as u64);
    points
        .par_iter()
        .map(|&(gamma, alpha)| {
            let r = physics::solve(
                gamma,
                alpha,
                Accuracy::Tolerance(tol),
                Scheme::Accurate,
                false,
            )
            .map(|s| (s.p, s.error_estimate))
            .map_err(|source| SweepError::Node {
                gamma,
                alpha,
                source,
            });
            progress.inc(1);
            r
        })
        .collect()
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
            name: oblique_lookup::format::PATCH_STICK_LOW,
            kind: PatchKind::Stick,
            gamma_lo: d.gamma_min,
            gamma_hi: d.gamma_max.min(1.0),
        });
    }
    if d.gamma_max > 1.0 {
        let lo = d.gamma_min.max(1.0);
        specs.push(PatchSpec {
            name: oblique_lookup::format::PATCH_PARTIAL_HIGH,
            kind: PatchKind::PartialSlip,
            gamma_lo: lo,
            gamma_hi: d.gamma_max,
        });
        specs.push(PatchSpec {
            name: oblique_lookup::format::PATCH_STICK_HIGH,
            kind: PatchKind::Stick,
            gamma_lo: lo,
            gamma_hi: d.gamma_max,
        });
    }
    specs
}

/// Node coordinates on the finest lattice: node `i` of `n` intervals ↦ `i · (LATTICE / n)`.
fn lattice(cfg: &Config) -> u64 {
    (cfg.nodes.initial_intervals as u64) << MAX_LEVELS
}

/// Largest deviation of the values at odd nodes from the `k`-point interpolation through the
/// even nodes, along one axis of an `(n0+1) × (n1+1)` grid (`axis` 0 or 1).
fn axis_surplus(p: &[f64], n0: usize, n1: usize, axis: usize, k: usize) -> f64 {
    let (na, nb) = if axis == 0 { (n0, n1) } else { (n1, n0) };
    let at = |a: usize, b: usize| {
        if axis == 0 {
            p[a * (n1 + 1) + b]
        } else {
            p[b * (n1 + 1) + a]
        }
    };
    let coarse = na / 2 + 1;
    let mut w = [0.0; 8];
    let mut worst = 0.0_f64;
    for a in (1..na).step_by(2) {
        let (start, kk) = stencil(a as f64 / 2.0, coarse, k, &mut w);
        for b in 0..=nb {
            let interp: f64 = (0..kk).map(|j| w[j] * at(2 * (start + j), b)).sum();
            worst = worst.max((interp - at(a, b)).abs());
        }
    }
    worst
}

fn build_patch(
    cfg: &Config,
    spec: &PatchSpec,
    progress: &dyn Progress,
    total_nodes: &mut usize,
) -> Result<BuiltPatch, SweepError> {
    let k = cfg.nodes.stencil;
    let m = cfg.nodes.initial_intervals;
    let lat = lattice(cfg);
    let alpha_max = cfg.domain.alpha_max;
    let mut cache: HashMap<(u64, u64), (f64, f64)> = HashMap::new();
    let node = |key: (u64, u64)| {
        let gamma = if key.0 == lat {
            spec.gamma_hi
        } else {
            spec.gamma_lo + (spec.gamma_hi - spec.gamma_lo) * (key.0 as f64 / lat as f64)
        };
        let c = key.1 as f64 / lat as f64;
        (gamma, spec.kind.alpha(gamma, c, alpha_max))
    };
    let (mut a, mut b) = (0u32, 0u32);
    loop {
        let (ng, nc) = (m << a, m << b);
        let (sg, sc) = (lat / ng as u64, lat / nc as u64);
        let keys: Vec<(u64, u64)> = (0..=ng as u64)
            .flat_map(|i| (0..=nc as u64).map(move |j| (i * sg, j * sc)))
            .collect();
        let missing: Vec<(u64, u64)> = keys
            .iter()
            .copied()
            .filter(|k| !cache.contains_key(k))
            .collect();
        if *total_nodes + missing.len() > cfg.nodes.max_nodes {
            return Err(SweepError::TooManyNodes {
                patch: spec.name,
                target: cfg.nodes.target_error,
                max: cfg.nodes.max_nodes,
                predicted: f64::NAN,
                nodes: *total_nodes,
            });
        }
        progress.phase(&format!("{}: {} x {} nodes", spec.name, ng + 1, nc + 1));
        let points: Vec<(f64, f64)> = missing.iter().map(|&key| node(key)).collect();
        let values = solve_points(&points, cfg.solver.tol, progress)?;
        *total_nodes += missing.len();
        cache.extend(missing.into_iter().zip(values));
        let p: Vec<f64> = keys.iter().map(|key| cache[key].0).collect();
        let eg = axis_surplus(&p, ng, nc, 0, k);
        let ec = axis_surplus(&p, ng, nc, 1, k);
        // The surplus measures the error of the grid with twice the spacing; the current grid's
        // error is smaller by 2^k asymptotically. Predict with 2^(k-1) for a margin of 2.
        let shrink = 2f64.powi(k as i32 - 1);
        let (pg, pc) = (eg / shrink, ec / shrink);
        if pg + pc <= cfg.nodes.target_error {
            let err: Vec<f64> = keys.iter().map(|key| cache[key].1).collect();
            let alpha: Vec<f64> = keys.iter().map(|&key| node(key).1).collect();
            let simulated = err.iter().filter(|e| **e > 0.0).count();
            return Ok(BuiltPatch {
                name: spec.name,
                patch: Patch {
                    kind: spec.kind,
                    gamma_lo: spec.gamma_lo,
                    gamma_hi: spec.gamma_hi,
                    n_gamma: ng + 1,
                    n_coord: nc + 1,
                    p,
                    error_estimate: err,
                },
                alpha,
                predicted_error: (pg, pc),
                simulated,
            });
        }
        let half = 0.5 * cfg.nodes.target_error;
        let (grow_g, grow_c) = (pg > half || pg >= pc, pc > half || pc > pg);
        if (grow_g && a >= MAX_LEVELS) || (grow_c && b >= MAX_LEVELS) {
            return Err(SweepError::TooManyNodes {
                patch: spec.name,
                target: cfg.nodes.target_error,
                max: cfg.nodes.max_nodes,
                predicted: pg + pc,
                nodes: *total_nodes,
            });
        }
        a += grow_g as u32;
        b += grow_c as u32;
    }
}

/// Deterministic generator for check points (SplitMix64).
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Run a whole sweep: build every patch, then simulate and compare the held-out checks.
pub fn build(cfg: &Config, progress: &dyn Progress) -> Result<Built, SweepError> {
    let mut total = 0usize;
    let mut patches = Vec::new();
    for spec in patch_specs(cfg) {
        patches.push(build_patch(cfg, &spec, progress, &mut total)?);
    }
    let find = |name: &str| {
        patches
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.patch.clone())
    };
    let surface = Surface {
        gamma_min: cfg.domain.gamma_min,
        gamma_max: cfg.domain.gamma_max,
        alpha_max: cfg.domain.alpha_max,
        stencil: cfg.nodes.stencil,
        stick_low: find(oblique_lookup::format::PATCH_STICK_LOW),
        partial_high: find(oblique_lookup::format::PATCH_PARTIAL_HIGH),
        stick_high: find(oblique_lookup::format::PATCH_STICK_HIGH),
    };
    // Held-out points: uniform in each patch's (γ, c), strictly inside (c < 1 keeps α finite).
    let mut rng = SplitMix(cfg.checks.seed);
    let mut points = Vec::new();
    for p in &patches {
        for _ in 0..cfg.checks.per_patch {
            let gamma = p.patch.gamma_lo + (p.patch.gamma_hi - p.patch.gamma_lo) * rng.uniform();
            let c = rng.uniform();
            let alpha = p.patch.kind.alpha(gamma, c, cfg.domain.alpha_max);
            points.push((gamma, alpha));
        }
    }
    progress.phase(&format!("held-out checks: {} points", points.len()));
    let sims = solve_points(&points, cfg.solver.tol, progress)?;
    let checks = points
        .iter()
        .zip(&sims)
        .map(|(&(gamma, alpha), &(p_sim, _))| {
            let p_int = surface.eval(gamma, alpha).unwrap_or(f64::NAN);
            Check {
                gamma,
                alpha,
                p_simulated: p_sim,
                p_interpolated: p_int,
                interpolation_error: (p_int - p_sim).abs(),
                patch: Region::of(gamma, alpha).index(),
            }
        })
        .collect();
    Ok(Built {
        surface,
        patches,
        checks,
    })
}
