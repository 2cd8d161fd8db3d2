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
    /// Predicted interpolation error of every block.
    pub block_error: Vec<f64>,
    /// Distinct nodes (blocks share their edges).
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

/// Highest block level (`block_intervals · 2^MAX_LEVEL` intervals per block axis).
const MAX_LEVEL: u32 = 8;

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

/// The block layout of a patch being built and the exact lattice its nodes live on.
struct Layout<'a> {
    spec: &'a PatchSpec,
    bg: usize,
    bc: usize,
    m: usize,
    alpha_max: f64,
}

/// A node on the finest lattice of a patch: `(γ index, c index)`.
type Key = (u64, u64);

impl Layout<'_> {
    fn fine(&self) -> u64 {
        (self.m as u64) << MAX_LEVEL
    }

    /// Lattice key of node `(i, j)` of block `(a, b)` at level `l`.
    fn key(&self, a: usize, b: usize, l: u32, i: usize, j: usize) -> Key {
        let step = 1u64 << (MAX_LEVEL - l);
        (
            a as u64 * self.fine() + i as u64 * step,
            b as u64 * self.fine() + j as u64 * step,
        )
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

    fn block_keys(&self, a: usize, b: usize, l: u32) -> Vec<Key> {
        let n = self.m << l;
        (0..=n)
            .flat_map(|i| (0..=n).map(move |j| (i, j)))
            .map(|(i, j)| self.key(a, b, l, i, j))
            .collect()
    }
}

/// Largest deviation, over the nodes of a level-`l` block grid that are not on its level-`l−1`
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
        m: cfg.nodes.block_intervals,
        alpha_max: cfg.domain.alpha_max,
    };
    let nblocks = layout.bg * layout.bc;
    let mut level = vec![1u32; nblocks];
    let mut done = vec![false; nblocks];
    let mut predicted = vec![f64::NAN; nblocks];
    let mut cache: HashMap<Key, (f64, f64)> = HashMap::new();
    // The surplus of level l measures the error of level l − 1; level l is predicted smaller by
    // 2^k asymptotically. Predict with 2^(k−1) for a margin of 2.
    let shrink = 2f64.powi(k as i32 - 1);
    for round in 0.. {
        let mut wanted: Vec<Key> = (0..nblocks)
            .filter(|&blk| !done[blk])
            .flat_map(|blk| layout.block_keys(blk / layout.bc, blk % layout.bc, level[blk]))
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
        let open = done.iter().filter(|d| !**d).count();
        progress.phase(&format!("{} round {round}: {open} blocks", spec.name));
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
        let mut refined = false;
        for blk in 0..nblocks {
            if done[blk] {
                continue;
            }
            let (a, b, l) = (blk / layout.bc, blk % layout.bc, level[blk]);
            let vals: Vec<f64> = layout
                .block_keys(a, b, l)
                .iter()
                .map(|key| cache[key].0)
                .collect();
            let pred = surplus(&vals, layout.m << l, k) / shrink;
            predicted[blk] = pred;
            if pred <= cfg.nodes.target_error {
                done[blk] = true;
            } else if l >= MAX_LEVEL {
                return Err(SweepError::TooManyNodes {
                    patch: spec.name,
                    target: cfg.nodes.target_error,
                    max: cfg.nodes.max_nodes,
                    predicted: pred,
                    nodes: *total_nodes,
                });
            } else {
                level[blk] += 1;
                refined = true;
            }
        }
        if !refined {
            break;
        }
    }
    let mut p = Vec::new();
    let mut err = Vec::new();
    let mut gamma = Vec::new();
    let mut coord = Vec::new();
    let mut alpha = Vec::new();
    let mut offset = Vec::with_capacity(nblocks);
    for (blk, &l) in level.iter().enumerate() {
        offset.push(p.len());
        for key in layout.block_keys(blk / layout.bc, blk % layout.bc, l) {
            let (g, c, a) = layout.point(key);
            let (v, e) = cache[&key];
            p.push(v);
            err.push(e);
            gamma.push(g);
            coord.push(c);
            alpha.push(a);
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
            block_intervals: layout.m,
            level,
            offset,
            p,
            error_estimate: err,
        },
        gamma,
        coord,
        alpha,
        block_error: predicted,
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
