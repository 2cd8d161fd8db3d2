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

/// One patch as built, with the coordinates of every node (same flat layout as `patch.p`).
#[derive(Debug, Clone)]
pub struct BuiltPatch {
    /// Patch name in the file.
    pub name: &'static str,
    /// The patch.
    pub patch: Patch,
    /// γ of every node.
    pub gamma: Vec<f64>,
    /// Patch coordinate `c` of every node.
    pub coord: Vec<f64>,
    /// α of every node (`∞` allowed).
    pub alpha: Vec<f64>,
    /// Predicted interpolation error of every leaf.
    pub leaf_error: Vec<f64>,
    /// Depth of every leaf.
    pub leaf_depth: Vec<u32>,
    /// Distinct nodes (leaves share their edges).
    pub unique_nodes: usize,
    /// Distinct nodes that were simulated (the others are closed forms).
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

/// Deepest quadtree level (a leaf at this depth has `2^-MAX_DEPTH` of its root's size).
const MAX_DEPTH: u32 = 12;

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

/// The root grid of a patch being built and the exact lattice its nodes live on.
struct Layout<'a> {
    spec: &'a PatchSpec,
    bg: usize,
    bc: usize,
    m: usize,
    alpha_max: f64,
}

/// A node on the finest lattice of a patch: `(γ index, c index)`.
type Key = (u64, u64);

/// A quadtree cell: its depth and integer position at that depth.
#[derive(Debug, Clone, Copy)]
struct Cell {
    depth: u32,
    ig: u64,
    ic: u64,
}

impl Layout<'_> {
    /// Lattice units per root cell per axis.
    fn fine(&self) -> u64 {
        (self.m as u64) << MAX_DEPTH
    }

    /// `(γ, c, α)` of a lattice node (computed from the key alone, so shared nodes agree).
    fn point(&self, key: Key) -> (f64, f64, f64) {
        let ng = self.bg as u64 * self.fine();
        let nc = self.bc as u64 * self.fine();
        let xg = key.0 as f64 / ng as f64;
        let gamma = if key.0 == ng {
            self.spec.gamma_hi
        } else {
            self.spec.gamma_lo + (self.spec.gamma_hi - self.spec.gamma_lo) * xg
        };
        let c = key.1 as f64 / nc as f64;
        (gamma, c, self.spec.kind.alpha(gamma, c, self.alpha_max))
    }

    /// Lattice keys of a cell's `(m+1)²` nodes, row-major (`γ` outer).
    fn cell_keys(&self, cell: Cell) -> Vec<Key> {
        let step = 1u64 << (MAX_DEPTH - cell.depth);
        let m = self.m as u64;
        (0..=m)
            .flat_map(|i| (0..=m).map(move |j| (i, j)))
            .map(|(i, j)| ((cell.ig * m + i) * step, (cell.ic * m + j) * step))
            .collect()
    }
}

impl Cell {
    fn children(self) -> [Cell; 4] {
        let child = |qg: u64, qc: u64| Cell {
            depth: self.depth + 1,
            ig: 2 * self.ig + qg,
            ic: 2 * self.ic + qc,
        };
        // Order fixed by the format: child `2·q_γ + q_c`.
        [child(0, 0), child(0, 1), child(1, 0), child(1, 1)]
    }
}

/// Largest deviation, over the nodes of an `n`-interval grid that are not on its `n/2`-interval
/// sub-grid, between the value and the `k`-point tensor interpolation from the sub-grid.
fn surplus(values: &[f64], n: usize, k: usize) -> f64 {
    let coarse_n = n / 2;
    let at = |i: usize, j: usize| values[i * (n + 1) + j];
    let mut wg = [0.0; 8];
    let mut wc = [0.0; 8];
    let mut worst = 0.0_f64;
    for i in 0..=n {
        for j in 0..=n {
            if i % 2 == 0 && j % 2 == 0 {
                continue;
            }
            let (sg, kg) = stencil(i as f64 / 2.0, coarse_n + 1, k, &mut wg);
            let (sc, kc) = stencil(j as f64 / 2.0, coarse_n + 1, k, &mut wc);
            let mut v = 0.0;
            for (x, wx) in wg.iter().enumerate().take(kg) {
                for (y, wy) in wc.iter().enumerate().take(kc) {
                    v += wx * wy * at(2 * (sg + x), 2 * (sc + y));
                }
            }
            worst = worst.max((v - at(i, j)).abs());
        }
    }
    worst
}

/// Build one patch by adaptive quadtree refinement.
///
/// Every open cell gets its `(m+1)²` nodes (nodes shared with cells already done are reused).
/// Its surplus `s` (the error of interpolating from its own half grid) measures the error of a
/// grid twice as coarse; the cell's own error is predicted as `s/4`, the second-order rate that
/// holds where a kink curve (curvature jump) crosses the cell (smooth cells converge faster, so
/// the prediction is conservative there). A cell whose prediction exceeds the target is split
/// into four children, which reuse a quarter of its nodes.
fn build_patch(
    cfg: &Config,
    spec: &PatchSpec,
    progress: &dyn Progress,
    total_nodes: &mut usize,
) -> Result<BuiltPatch, SweepError> {
    let k = cfg.nodes.stencil;
    let layout = Layout {
        spec,
        bg: ((spec.gamma_hi - spec.gamma_lo) * cfg.nodes.blocks_per_unit_gamma)
            .ceil()
            .max(1.0) as usize,
        bc: cfg.nodes.blocks_coord,
        m: cfg.nodes.leaf_intervals,
        alpha_max: cfg.domain.alpha_max,
    };
    let m = layout.m;
    // All cells ever created, roots first; `child[i]` is the first child of a split cell.
    let mut cells: Vec<Cell> = (0..layout.bg as u64)
        .flat_map(|ig| (0..layout.bc as u64).map(move |ic| Cell { depth: 0, ig, ic }))
        .collect();
    let mut child: Vec<Option<usize>> = vec![None; cells.len()];
    let mut predicted = vec![f64::NAN; cells.len()];
    let mut open: Vec<usize> = (0..cells.len()).collect();
    let mut cache: HashMap<Key, (f64, f64)> = HashMap::new();
    for round in 0.. {
        let mut wanted: Vec<Key> = open
            .iter()
            .flat_map(|&c| layout.cell_keys(cells[c]))
            .filter(|key| !cache.contains_key(key))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        if *total_nodes + wanted.len() > cfg.nodes.max_nodes {
            let worst = predicted.iter().copied().fold(0.0, f64::max);
            return Err(SweepError::TooManyNodes {
                patch: spec.name,
                target: cfg.nodes.target_error,
                max: cfg.nodes.max_nodes,
                predicted: worst,
                nodes: *total_nodes,
            });
        }
        progress.phase(&format!(
            "{} round {round}: {} open cells, {} new nodes",
            spec.name,
            open.len(),
            wanted.len()
        ));
        let points: Vec<(f64, f64)> = wanted
            .iter()
            .map(|&key| {
                let (g, _, a) = layout.point(key);
                (g, a)
            })
            .collect();
        let values = solve_points(&points, cfg.solver.tol, progress)?;
        *total_nodes += wanted.len();
        cache.extend(wanted.into_iter().zip(values));
        let mut next = Vec::new();
        for &c in &open {
            let vals: Vec<f64> = layout
                .cell_keys(cells[c])
                .iter()
                .map(|key| cache[key].0)
                .collect();
            let pred = surplus(&vals, m, k) / 4.0;
            predicted[c] = pred;
            if pred <= cfg.nodes.target_error {
                continue;
            }
            if cells[c].depth >= MAX_DEPTH {
                let keys = layout.cell_keys(cells[c]);
                let (g0, c0, _) = layout.point(keys[0]);
                let (g1, c1, _) = layout.point(keys[keys.len() - 1]);
                return Err(SweepError::DepthLimit {
                    patch: spec.name,
                    depth: cells[c].depth,
                    gamma_lo: g0,
                    gamma_hi: g1,
                    c_lo: c0,
                    c_hi: c1,
                    predicted: pred,
                    target: cfg.nodes.target_error,
                    node_error: keys.iter().map(|k| cache[k].1).fold(0.0, f64::max),
                });
            }
            child[c] = Some(cells.len());
            for ch in cells[c].children() {
                next.push(cells.len());
                cells.push(ch);
                child.push(None);
                predicted.push(f64::NAN);
            }
        }
        if next.is_empty() {
            break;
        }
        open = next;
    }
    // Leaves are numbered in cell order.
    let mut tree = Vec::with_capacity(cells.len());
    let mut leaf_error = Vec::new();
    let mut leaf_depth = Vec::new();
    let (mut p, mut err, mut gamma, mut coord, mut alpha) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (c, cell) in cells.iter().enumerate() {
        match child[c] {
            Some(first) => tree.push(first as i32),
            None => {
                tree.push(-(leaf_error.len() as i32) - 1);
                leaf_error.push(predicted[c]);
                leaf_depth.push(cell.depth);
                for key in layout.cell_keys(*cell) {
                    let (g, cc, a) = layout.point(key);
                    let (v, e) = cache[&key];
                    p.push(v);
                    err.push(e);
                    gamma.push(g);
                    coord.push(cc);
                    alpha.push(a);
                }
            }
        }
    }
    let simulated = cache.values().filter(|(_, e)| *e > 0.0).count();
    Ok(BuiltPatch {
        name: spec.name,
        patch: Patch {
            kind: spec.kind,
            gamma_lo: spec.gamma_lo,
            gamma_hi: spec.gamma_hi,
            blocks_gamma: layout.bg,
            blocks_coord: layout.bc,
            leaf_intervals: m,
            tree,
            p,
            error_estimate: err,
        },
        gamma,
        coord,
        alpha,
        leaf_error,
        leaf_depth,
        unique_nodes: cache.len(),
        simulated,
    })
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
    let sims = solve_points(&points, cfg.check_tol(), progress)?;
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
