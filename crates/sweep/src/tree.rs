//! The refinement of one patch: its root grid and node lattice ([`Layout`]), the prediction of
//! a cell's error from its surplus, the probes of cells next to a kink curve, and
//! [`build_patch`], which splits cells until every leaf meets the target.

use std::collections::HashMap;

use oblique_table::surface::{
    stencil, Axis, PartialMap, Patch, PatchData, PatchId, PatchKind, Point, Warp,
};
use oblique_table::write::BuiltPatch;

use crate::config::Config;
use crate::{
    kink, solve_points_with, stage_refine, warp, Progress, RunError, RunOptions, Shard, SweepError,
    STAGE_FOLD, STAGE_KINKS,
};

/// Deepest quadtree level (a leaf at this depth has `2^-MAX_DEPTH` of its root's size).
const MAX_DEPTH: u32 = 12;

pub(crate) struct PatchSpec {
    pub(crate) name: &'static str,
    pub(crate) kind: PatchKind,
    pub(crate) gamma_lo: f64,
    pub(crate) gamma_hi: f64,
}

pub(crate) fn patch_specs(cfg: &Config) -> Vec<PatchSpec> {
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
fn restitution_axis(cfg: &Config) -> Result<Option<Axis>, SweepError> {
    cfg.domain
        .e_n_range()
        .map(|(lo, hi)| Axis::restitution(lo, hi, cfg.blocks_e_n()).map_err(SweepError::Model))
        .transpose()
}

/// Root cells of a patch along γ.
fn roots_gamma(cfg: &Config, spec: &PatchSpec) -> usize {
    ((spec.gamma_hi - spec.gamma_lo) * cfg.nodes.blocks_per_unit_gamma)
        .ceil()
        .max(1.0) as usize
}

/// Root cells of a patch.
pub(crate) fn root_count(cfg: &Config, spec: &PatchSpec) -> usize {
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
    restitution: Option<Axis>,
    /// The partial-slip coordinate's map ([`Config::partial_map`]).
    map: PartialMap,
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

    /// The partial-slip coordinate's map ([`Config::partial_map`]).
    fn partial_map(&self) -> PartialMap {
        self.map
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
        let nc = self.bc as u64 * self.fine();
        let gamma = self.gamma_of_row(key.0);
        let c = key.1 as f64 / nc as f64;
        let e_n = match self.restitution {
            Some(r) => r.at(key.2 as f64 / (self.be() as u64 * self.fine()) as f64),
            None => 1.0,
        };
        (gamma, c, self.point_at(gamma, c, e_n, key.3))
    }

    /// γ of the lattice row `k` (`gamma_hi` exactly on the last row).
    fn gamma_of_row(&self, k: u64) -> f64 {
        let ng = self.bg as u64 * self.fine();
        if k == ng {
            self.spec.gamma_hi
        } else {
            let xg = k as f64 / ng as f64;
            self.spec.gamma_lo + (self.spec.gamma_hi - self.spec.gamma_lo) * xg
        }
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

    /// Where a cell of an elastic partial-slip patch next to the kink curve `curve` is measured
    /// ([`kink::PROBE_OFFSETS`] from the kink along the coordinate, on every node row along γ,
    /// those that land inside the cell): `(u, v, point)` with `u`, `v` the position in node
    /// intervals of the cell. Empty when the curve passes far from the cell.
    fn kink_probes(&self, cell: Cell, curve: &kink::KinkCurve) -> Vec<Probe> {
        let m = self.m as f64;
        let nc = (self.bc as u64 * self.fine()) as f64;
        let sg = 1u64 << (MAX_DEPTH - cell.d[0]);
        let sc = (1u64 << (MAX_DEPTH - cell.d[1])) as f64;
        let warped = self.warped(cell);
        let mut out = Vec::new();
        for i in 0..=self.m as u64 {
            let u = i as f64;
            let gamma = self.gamma_of_row((cell.ig * self.m as u64 + i) * sg);
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
            // The offsets that land inside the cell: also when the kink lies just outside it
            // (up to 1.4 intervals below, 0.7 above), whose first intervals see the steep side.
            let v_k = lattice * nc / sc - cell.ic as f64 * m;
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
pub(crate) fn build_patch(
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
        map: cfg.partial_map(),
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
        let mut probed: Vec<(usize, Vec<f64>, Vec<Probe>)> = Vec::new();
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
                        probed.push((o, vals, probes));
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
                .flat_map(|(_, _, probes)| probes.iter().map(|p| p.2))
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
            for (o, vals, probes) in probed {
                let c = open[o];
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
        patch: Patch::new(
            spec.kind,
            [
                Axis::gamma(spec.gamma_lo, spec.gamma_hi, layout.bg),
                Axis::coord(layout.bc),
            ]
            .into_iter()
            .chain(layout.restitution)
            .collect(),
            PatchData {
                leaf_intervals: m,
                tree,
                split: layout.restitution.is_some().then_some(mask),
                p,
                error_estimate: err,
                warp: warp.clone(),
            },
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
