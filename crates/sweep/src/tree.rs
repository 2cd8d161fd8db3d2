//! The refinement of one patch: its root grid and node lattice ([`Layout`]), the prediction of
//! a cell's error from its surplus, the probes of cells next to a kink curve, and
//! [`build_patch`], which splits cells until every leaf meets the target.

use std::collections::HashMap;

use oblique_solver::KeptLevels;
use oblique_table::surface::{
    stencil, Axis, Knots, PartialMap, Patch, PatchData, PatchId, PatchKind, Point, Warp,
};
use oblique_table::write::BuiltPatch;

use crate::config::Config;
use crate::{
    kink, knots, solve_points_kept, solve_points_with, stage_refine, warp, Progress, RunError,
    RunOptions, Shard, SweepError, STAGE_FOLD, STAGE_KINKS, STAGE_KNOTS,
};

/// Deepest quadtree level (a leaf at this depth has `2^-MAX_DEPTH` of its root's size).
const MAX_DEPTH: u32 = 12;

pub(crate) struct PatchSpec {
    pub(crate) name: &'static str,
    pub(crate) kind: PatchKind,
    pub(crate) gamma_lo: f64,
    pub(crate) gamma_hi: f64,
}

/// Whether the patch of `spec` has knots (`nodes.knots`): the partial-slip patch, and the stick
/// patch `stick_high` of a table of Thornton's law (its loading fold).
pub(crate) fn has_knots(cfg: &Config, spec: &PatchSpec) -> bool {
    cfg.nodes.knots
        && (spec.kind == PatchKind::PartialSlip
            || (cfg.law() == oblique_solver::Law::Thornton
                && spec.name == PatchId::StickHigh.name()))
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
        .map(|(lo, hi)| {
            Axis::restitution(lo, hi, cfg.blocks_e_n())
                .map(|a| a.with_map(cfg.e_n_map()))
                .map_err(SweepError::Model)
        })
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
    /// Knots of the partial-slip patch (a table with an `e_n` axis): inside their region the
    /// lattice is in `c'`, α comes from `c`.
    knots: Option<&'a Knots>,
    /// The `e_n` axis of a dissipative table: the lattice has a third axis.
    restitution: Option<Axis>,
    /// The partial-slip coordinate's map ([`Config::partial_map`]).
    map: PartialMap,
}

/// A node on the finest lattice of a patch: `(γ index, c index, e_n index, warped)`. A node on
/// the warp's `start` row exists twice: unwarped for the leaves below it, warped for those
/// above. The `e_n` index is 0 without an `e_n` axis.
type Key = (u64, u64, u64, bool);

/// A point where a cell is measured: its position `(u, v, w)` in node intervals of the cell
/// (along γ, along the coordinate, along `e_n`), the point simulated there, and whether it
/// measures a kink across the `e_n` axis ([`kink::Kink::across_e_n`]).
type Probe = (f64, f64, f64, Point, bool);

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

    /// The point at `γ`, lattice coordinate `c` (`c'` where `warped`: the warp's or the
    /// knots') and `e_n`.
    fn point_at(&self, gamma: f64, c: f64, e_n: f64, warped: bool) -> Point {
        let unwarped = match (self.warp, self.knots) {
            (Some(w), _) if warped => w.invert(gamma, c),
            (_, Some(k)) if warped => k.line(gamma, e_n).invert(c),
            _ => c,
        };
        let alpha =
            self.spec
                .kind
                .alpha_at(self.partial_map(), gamma, unwarped, e_n, self.alpha_max);
        Point::new(gamma, alpha, e_n)
    }

    /// Where a cell next to a kink (`kinks`, those of this patch) is measured: on every node
    /// row of the cell (each γ row, and each `e_n` row with an `e_n` axis) and between them
    /// (with an `e_n` axis at the centre of every square of four node rows; without, on rows
    /// between two γ rows across which the kink moves by more than one node interval), at
    /// [`kink::Kink::offsets`] node intervals from the kink along the coordinate, those that land
    /// inside the cell: `(u, v, w, point)` with `u`, `v`, `w` the position in node intervals of
    /// the cell along γ, the coordinate and `e_n` (`w = 0` without an `e_n` axis, `u = 0` in
    /// the patch of one pair). Empty when no kink passes near the cell. With `skip_knotted`
    /// (inside the knots' region) the kinks the knots put on cell edges are left out.
    ///
    /// The centres: the kink moves across the coordinate from row to row (about one node
    /// interval per row along `e_n` at γ ≈ 2.43, where `dα_F/de_n` ≈ 0.6), so the cell's
    /// tensor interpolant errs most between the rows. On γ 2.43–2.47, e_n 0.98–1 (target 3e-5),
    /// the node rows alone passed a leaf that errs by 3.96e-5 midway between them; with the
    /// centres the largest error at 200 points next to F₋ is 1.56e-5 (`docs/accuracy.md`).
    /// Without an `e_n` axis, E₋ moved by 2.4 node intervals of c per γ row in the stick leaf of
    /// `configs/full.toml` at γ 1.75–1.875 (`dα_E/dγ` ≈ −9), which erred by 8.1e-6 between its
    /// last two rows, where its probes on the rows found 1.8e-6 and it predicted 3.2e-6.
    fn kink_probes(
        &self,
        cell: Cell,
        kinks: &[Box<dyn kink::Kink>],
        skip_knotted: bool,
    ) -> Vec<Probe> {
        let m = self.m as f64;
        let nc = (self.bc as u64 * self.fine()) as f64;
        let sc = (1u64 << (MAX_DEPTH - cell.d[1])) as f64;
        let se = 1u64 << (MAX_DEPTH - cell.d[2]);
        let warped = self.warped(cell);
        let mg = if self.pair() { 0 } else { self.m as u64 };
        let me = if self.restitution.is_some() {
            self.m as u64
        } else {
            0
        };
        // The rows `(u, w)`: the node rows, γ outer; then the centres (with an `e_n` axis).
        let mut rows: Vec<(f64, f64)> = (0..=mg)
            .flat_map(|i| (0..=me).map(move |l| (i as f64, l as f64)))
            .collect();
        if me > 0 {
            let centres_g: Vec<f64> = if mg == 0 {
                vec![0.0]
            } else {
                (0..mg).map(|i| i as f64 + 0.5).collect()
            };
            for &u in &centres_g {
                rows.extend((0..me).map(|l| (u, l as f64 + 0.5)));
            }
        }
        let ne = (self.be() as u64 * self.fine()) as f64;
        // The row's γ and e_n, and the kink's position on it in node intervals of the cell
        // along the coordinate (`None` where the kink is not defined there).
        let place = |u: f64, w: f64, k: &dyn kink::Kink| -> (f64, f64, Option<f64>) {
            // A node row's γ and e_n are its nodes' (computed from the lattice index).
            let gamma = self.gamma_in_cell(cell, u);
            let e_n = match self.restitution {
                Some(r) => r.at(((cell.ie * self.m as u64) as f64 + w) * se as f64 / ne),
                None => 1.0,
            };
            let v_k = k.alpha(gamma, e_n).map(|alpha_k| {
                let c_k = self.spec.kind.coord_at(
                    self.partial_map(),
                    gamma,
                    alpha_k,
                    e_n,
                    self.alpha_max,
                );
                let lattice = match (self.warp, self.knots) {
                    (Some(warp), _) if warped => warp.apply(gamma, c_k),
                    (_, Some(k)) if warped => k.line(gamma, e_n).apply(c_k),
                    _ => c_k,
                };
                lattice * nc / sc - cell.ic as f64 * m
            });
            (gamma, e_n, v_k)
        };
        let mut out = Vec::new();
        for k in kinks {
            if skip_knotted && k.knotted() {
                continue;
            }
            if k.across_e_n() {
                if let Some(r) = self.restitution {
                    self.sheet_probes(cell, &**k, r, &mut out);
                }
                continue;
            }
            let mut rows_k = rows.clone();
            if me == 0 && mg > 0 {
                // Without an `e_n` axis, rows between the γ rows too where the kink moves by
                // more than one node interval of the coordinate from one row to the next:
                // close enough that it moves by at most one interval between them (at most 16
                // per interval), within the span its offsets cover on each row.
                let v: Vec<Option<f64>> = (0..=mg).map(|i| place(i as f64, 0.0, &**k).2).collect();
                for i in 0..mg as usize {
                    let moves = match (v[i], v[i + 1]) {
                        (Some(a), Some(b)) if (a - b).is_finite() => (a - b).abs(),
                        _ => 0.0,
                    };
                    let n = moves.ceil().clamp(1.0, 16.0) as usize;
                    rows_k.extend((1..n).map(|j| (i as f64 + j as f64 / n as f64, 0.0)));
                }
            }
            for &(u, w) in &rows_k {
                let (gamma, e_n, Some(v_k)) = place(u, w, &**k) else {
                    continue;
                };
                // The offsets that land inside the cell: also when the kink lies just outside
                // it (up to 1.4 intervals below, 0.7 above), whose first intervals see the
                // steep side.
                for &d in k.offsets() {
                    let v = v_k + d;
                    if (0.0..=m).contains(&v) {
                        let c = (cell.ic as f64 * m + v) * sc / nc;
                        out.push((u, v, w, self.point_at(gamma, c, e_n, warped), false));
                    }
                }
            }
        }
        out
    }

    /// γ at `u` node intervals into `cell` along γ: a node row's own γ (from its lattice index,
    /// as its nodes have it) where `u` is whole, else linear between them.
    fn gamma_in_cell(&self, cell: Cell, u: f64) -> f64 {
        let sg = 1u64 << (MAX_DEPTH - cell.d[0]);
        if u.fract() == 0.0 {
            self.gamma_of_row((cell.ig * self.m as u64 + u as u64) * sg)
        } else {
            let ng = (self.bg as u64 * self.fine()) as f64;
            let x = ((cell.ig * self.m as u64) as f64 + u) * sg as f64 / ng;
            self.spec.gamma_lo + (self.spec.gamma_hi - self.spec.gamma_lo) * x
        }
    }

    /// The probes of a cell next to a kink across the `e_n` axis (`k`, a sheet
    /// `e_n = e_K(γ, α)`): on every line of nodes along `e_n` (each γ row and coordinate column
    /// of the cell) and on the lines through the centres of the squares of four such lines, at
    /// [`kink::Kink::offsets`] node intervals from where the line meets the sheet, those inside
    /// the cell. On a line `α` moves with `e_n` (the coordinate's map depends on `α_c1(e_n)`),
    /// so the meeting point is a root of `e_n − e_K(γ, α(e_n))`: the first sign change on 16
    /// steps over the cell and 1.5 intervals beyond each end, bisected.
    fn sheet_probes(&self, cell: Cell, k: &dyn kink::Kink, r: Axis, out: &mut Vec<Probe>) {
        let m = self.m as f64;
        let nc = (self.bc as u64 * self.fine()) as f64;
        let ne = (self.be() as u64 * self.fine()) as f64;
        let sc = (1u64 << (MAX_DEPTH - cell.d[1])) as f64;
        let se = (1u64 << (MAX_DEPTH - cell.d[2])) as f64;
        let warped = self.warped(cell);
        let mg = if self.pair() { 0 } else { self.m };
        let mut lines: Vec<(f64, f64)> = (0..=mg)
            .flat_map(|i| (0..=self.m).map(move |j| (i as f64, j as f64)))
            .collect();
        let centres_g: Vec<f64> = if mg == 0 {
            vec![0.0]
        } else {
            (0..mg).map(|i| i as f64 + 0.5).collect()
        };
        for &u in &centres_g {
            lines.extend((0..self.m).map(|j| (u, j as f64 + 0.5)));
        }
        let e_of = |w: f64| r.at((((cell.ie * self.m as u64) as f64 + w) * se / ne).max(0.0));
        for (u, v) in lines {
            let gamma = self.gamma_in_cell(cell, u);
            let c = (cell.ic as f64 * m + v) * sc / nc;
            let miss = |w: f64| -> Option<f64> {
                let e_n = e_of(w);
                let alpha = self.point_at(gamma, c, e_n, warped).alpha;
                k.e_n_at(gamma, alpha).map(|e_k| e_n - e_k)
            };
            let ws: Vec<f64> = (0..=16)
                .map(|j| -1.5 + (m + 3.0) * j as f64 / 16.0)
                .collect();
            let fs: Vec<Option<f64>> = ws.iter().map(|&w| miss(w)).collect();
            let Some(j) = (0..16).find(|&j| match (fs[j], fs[j + 1]) {
                (Some(a), Some(b)) => a <= 0.0 && b > 0.0 || a >= 0.0 && b < 0.0,
                _ => false,
            }) else {
                continue;
            };
            let (mut lo, mut hi) = (ws[j], ws[j + 1]);
            let below = fs[j].is_some_and(|f| f < 0.0);
            for _ in 0..50 {
                let mid = 0.5 * (lo + hi);
                match miss(mid) {
                    Some(f) if (f < 0.0) == below => lo = mid,
                    Some(_) => hi = mid,
                    None => break,
                }
            }
            let w_k = 0.5 * (lo + hi);
            for &d in k.offsets() {
                let w = w_k + d;
                if (0.0..=m).contains(&w) {
                    out.push((u, v, w, self.point_at(gamma, c, e_of(w), warped), true));
                }
            }
        }
    }

    /// The cell's extent along γ in root-row units (exact dyadic values).
    fn rows(cell: Cell) -> (f64, f64) {
        let scale = f64::from(1u32 << cell.d[0]);
        (cell.ig as f64 / scale, (cell.ig + 1) as f64 / scale)
    }

    /// The cell's extent along `e_n` in root-cell units (exact dyadic values).
    fn e_rows(cell: Cell) -> (f64, f64) {
        let scale = f64::from(1u32 << cell.d[2]);
        (cell.ie as f64 / scale, (cell.ie + 1) as f64 / scale)
    }

    /// Whether the cell's nodes are warped: it lies at or beyond the warp's start, or inside
    /// the knots' region.
    fn warped(&self, cell: Cell) -> bool {
        if let Some(k) = self.knots {
            let r = k.region();
            let ((g0, g1), (e0, e1)) = (Self::rows(cell), Self::e_rows(cell));
            return g0 >= r[0] && g1 <= r[1] && e0 >= r[2] && e1 <= r[3];
        }
        self.warp.is_some_and(|w| Self::rows(cell).0 >= w.start())
    }

    /// The axes along which the warp's start or an edge of the knots' region cuts through the
    /// cell (bit `dims − 1 − k` for axis `k`; 0: none): it is split along them without being
    /// evaluated, so that every leaf lies on one side.
    fn straddles(&self, cell: Cell) -> u8 {
        let cuts = |(lo, hi): (f64, f64), at: f64| lo < at && at < hi;
        if let Some(k) = self.knots {
            let r = k.region();
            let (g, e) = (Self::rows(cell), Self::e_rows(cell));
            let bits = (1u8 << (self.dims() - 1)) * u8::from(cuts(g, r[0]) || cuts(g, r[1]));
            let bits = bits | u8::from(cuts(e, r[2]) || cuts(e, r[3]));
            // Inside the region, a knot sent inside the cell along the coordinate (one not on
            // a root-cell edge): split along it.
            if bits == 0 && self.warped(cell) {
                let scale = f64::from(1u32 << cell.d[1]) * self.bc as f64;
                let c = (cell.ic as f64 / scale, (cell.ic + 1) as f64 / scale);
                let inside = |s: &f64| c.0 < s - 1e-12 && s + 1e-12 < c.1;
                return u8::from(k.c_star().iter().any(inside)) << (self.dims() - 2);
            }
            return bits;
        }
        match self.warp {
            Some(w) if cuts(Self::rows(cell), w.start()) => (1u8 << self.dims()) - 1,
            _ => 0,
        }
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

/// The `k`-point tensor interpolant of a cell's nodes (row-major, `γ` outer, `e_n` inner; one
/// node along γ in the patch of one pair) at `u`, `v`, `w` node intervals along γ, the
/// coordinate and `e_n`: the rule a leaf with an `e_n` axis answers with.
fn interp_cell_e(
    values: &[f64],
    m: usize,
    k: usize,
    pair: bool,
    (u, v, w): (f64, f64, f64),
) -> f64 {
    let (mut wg, mut wc, mut we) = ([0.0; 8], [0.0; 8], [0.0; 8]);
    let (sg, kg) = if pair {
        wg[0] = 1.0;
        (0, 1)
    } else {
        stencil(u, m + 1, k, &mut wg)
    };
    let (sc, kc) = stencil(v, m + 1, k, &mut wc);
    let (se, ke) = stencil(w, m + 1, k, &mut we);
    let mut out = 0.0;
    for (x, wx) in wg.iter().enumerate().take(kg) {
        for (y, wy) in wc.iter().enumerate().take(kc) {
            for (z, wz) in we.iter().enumerate().take(ke) {
                out += wx * wy * wz * values[((sg + x) * (m + 1) + sc + y) * (m + 1) + se + z];
            }
        }
    }
    out
}

/// Largest deviation between the values at odd positions along `axis` and the `k`-point
/// interpolation along that axis alone from the even ones.
fn surplus_axis(values: &[f64], n: usize, k: usize, dims: u32, axis: usize) -> f64 {
    surplus_axis_within(values, n, k, dims, axis, [0; 3], [n; 3])
}

/// [`surplus_axis`] over the nodes whose indices lie within `lo..=hi` on every axis (the part
/// of a cell that one of its children covers).
fn surplus_axis_within(
    values: &[f64],
    n: usize,
    k: usize,
    dims: u32,
    axis: usize,
    lo: [usize; 3],
    hi: [usize; 3],
) -> f64 {
    let n1 = n + 1;
    let me = if dims == 3 { n } else { 0 };
    let at = |i: usize, j: usize, l: usize| values[(i * n1 + j) * (me + 1) + l];
    let mut w = [0.0; 8];
    let mut worst = 0.0_f64;
    for i in lo[0]..=hi[0].min(n) {
        for j in lo[1]..=hi[1].min(n) {
            for l in lo[2].min(me)..=hi[2].min(me) {
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

/// [`surplus_axis`] along each of the `dims` axes of a cell's values (0 beyond them).
fn axis_surpluses(values: &[f64], m: usize, k: usize, dims: u32) -> [f64; 3] {
    let mut axes = [0.0; 3];
    for (a, s) in axes.iter_mut().enumerate().take(dims as usize) {
        *s = surplus_axis(values, m, k, dims, a);
    }
    axes
}

/// Bounds of the rate at which a cell's surplus falls from one level to the next along an
/// axis, as [`observed_rates`] accepts it: at most 1/4 (the second order of a kink curve
/// crossing the cell, the rate the quarter-surplus prediction assumes everywhere), at least
/// 1/16 (fourth order, the cubic's own on smooth `P`).
const RATE_RANGE: (f64, f64) = (1.0 / 16.0, 0.25);

/// The factor on the prediction from [`observed_rates`]: one level's rate only estimates the
/// next one's. Measured on `configs/default.toml` without it: over 20 000 random points at
/// tol 1e-8, the largest error in a leaf reached 1.42 times its prediction (14 of 513 leaves
/// above 1, the median 0.32).
const RATE_SAFETY: f64 = 1.5;

/// The rate per axis at which the cell `child`'s surplus fell from its parent's
/// (`nodes.observed_rate`): along each axis the split halved, the child's own surplus along it
/// (`child_axes`) over the parent's on the nodes of the part the child covers, within
/// [`RATE_RANGE`]; along the others the parent's rate (`parent_rates`). `axis_depth` maps a
/// surplus axis to the index of [`Cell::d`].
fn observed_rates(
    parent: (Cell, &[f64], [f64; 3]),
    child: (Cell, [f64; 3]),
    m: usize,
    k: usize,
    dims: u32,
    axis_depth: &[usize],
) -> [f64; 3] {
    let (p_cell, p_vals, parent_rates) = parent;
    let (c_cell, child_axes) = child;
    let idx = [c_cell.ig, c_cell.ic, c_cell.ie];
    // The child's part of the parent's node grid, per surplus axis.
    let (mut lo, mut hi) = ([0usize; 3], [m; 3]);
    for (a, &d) in axis_depth.iter().enumerate() {
        if c_cell.d[d] > p_cell.d[d] {
            let b = (idx[d] & 1) as usize;
            (lo[a], hi[a]) = (b * m / 2, b * m / 2 + m / 2);
        }
    }
    let mut out = parent_rates;
    for (a, &d) in axis_depth.iter().enumerate() {
        if c_cell.d[d] > p_cell.d[d] {
            let before = surplus_axis_within(p_vals, m, k, dims, a, lo, hi);
            let r = if before > 0.0 {
                child_axes[a] / before
            } else {
                RATE_RANGE.1
            };
            out[a] = r.clamp(RATE_RANGE.0, RATE_RANGE.1);
        }
    }
    out
}

/// The axes a cell of a patch with an `e_n` axis (or of any patch with `nodes.anisotropic`)
/// halves when its prediction exceeds `target` (bit `dims − 1 − k` for axis `k`: `γ`, `c`,
/// `e_n`; `c`, `e_n` for one pair; `γ`, `c` without the axis): each axis
/// whose own surplus
/// (`axes`, from [`axis_surpluses`]; a quarter of it as the cell's own error along that axis) exceeds the
/// target, or else the axis with the largest. Along `e_n` `P` is smooth and the kink curves
/// lie across `c`, so most cells need only one or two axes halved (measured on γ 1.9–2.6,
/// target 1e-4: 55 315 nodes in the partial-slip patch against 188 131 halving every axis).
fn split_axes(axes: &[f64; 3], target: f64, dims: u32) -> u8 {
    let s: Vec<f64> = axes[..dims as usize].iter().map(|sa| sa / 4.0).collect();
    let big = s.iter().copied().fold(0.0, f64::max);
    let mut bits = 0u8;
    for (a, &sa) in s.iter().enumerate() {
        if sa > target || sa >= big {
            bits |= 1 << (dims as usize - 1 - a);
        }
    }
    bits
}

/// The axes a cell halves whose probes next to a kink measured more than `target` (bit
/// `dims − 1 − k` for axis `k`), from the largest error measured on its node rows (`on_rows`)
/// and at the centres between them (`centres`). Without stored split masks (`masked` false)
/// every axis, as every quadtree split. With them: the coordinate where the node rows err (the
/// interpolation along it across the kink), and the other axes where the centres err (the kink
/// moves across the coordinate between rows); every axis where both do. Measured on γ 2.4–2.5,
/// e_n 0.95–1 (target 1e-5, tol 2e-6): 181 922 nodes against 222 593 halving every axis, the
/// same largest error (8.51e-6) at 300 points next to F₋.
fn probe_split(
    dims: u32,
    has_e: bool,
    masked: bool,
    on_rows: [f64; 2],
    centres: [f64; 2],
    target: f64,
) -> u8 {
    let every = (1u8 << dims) - 1;
    if !masked {
        return every;
    }
    // The coordinate is axis 1 (bit 1) with an `e_n` axis (axis 0 in the patch of one pair,
    // with two axes: bit 1 too); axis 1 of two (bit 0) without. `e_n` is the last axis (bit 0).
    let coord = if has_e { 1u8 << 1 } else { 1u8 };
    let mut bits = 0;
    if on_rows[0] > target {
        bits |= coord;
    }
    if centres[0] > target {
        bits |= every & !coord;
    }
    // A kink across `e_n`: its lines along `e_n` where they err, the other axes where the
    // centres between the lines do.
    if has_e && on_rows[1] > target {
        bits |= 1;
    }
    if has_e && centres[1] > target {
        bits |= every & !1;
    }
    if bits == 0 {
        every
    } else {
        bits
    }
}

/// What the patches of one build share: the nodes solved so far (for `nodes.max_nodes`) and
/// the kinks traced once for all of them.
#[derive(Debug, Default)]
pub(crate) struct RunState {
    pub(crate) nodes: usize,
    pub(crate) traced: kink::Traced,
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
    run: &mut RunState,
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
    let e_range = cfg.domain.e_n_range();
    let knots = match e_range {
        Some(e_range) if has_knots(cfg, spec) => {
            progress.phase(
                STAGE_KNOTS,
                &format!("the kinks of P for the knots of {}", spec.name),
            );
            let (gammas, bg, be) = (
                (spec.gamma_lo, spec.gamma_hi),
                roots_gamma(cfg, spec),
                cfg.nodes.blocks_e_n.unwrap_or(1),
            );
            let tracing = |what: &str| {
                progress.phase(
                    STAGE_KNOTS,
                    &format!("{what} for the knots of {}", spec.name),
                )
            };
            if spec.kind == PatchKind::Stick {
                let alpha_max = cfg.domain.alpha_max;
                knots::loading_fold_knots(gammas, bg, e_range, be, cfg.e_n_map(), alpha_max)?
            } else if cfg.law() == oblique_solver::Law::Thornton {
                tracing("the edges of the + strip");
                let strip = kink::plus_strip(&mut run.traced, gammas, e_range)?;
                tracing("alpha_R, 2/7 and alpha_S");
                knots::thornton_knots(gammas, bg, e_range, be, cfg.e_n_map(), Some(&strip))?
            } else {
                let bc = cfg.nodes.blocks_coord;
                knots::fold_minus_knots(gammas, bg, e_range, be, bc, cfg.partial_map())?
            }
        }
        _ => None,
    };
    let kinks = if cfg.nodes.probe_kinks {
        progress.phase(
            STAGE_KINKS,
            &format!(
                "the kink {} for the probes of {}",
                if e_range.is_some() {
                    "surfaces"
                } else {
                    "curves"
                },
                spec.name
            ),
        );
        kink::trace(
            cfg.law(),
            spec.kind,
            (spec.gamma_lo, spec.gamma_hi),
            e_range,
            &mut run.traced,
            &|what| {
                progress.phase(
                    STAGE_KINKS,
                    &format!("{what} for the probes of {}", spec.name),
                )
            },
        )?
    } else {
        Vec::new()
    };
    let kink_names = kinks
        .iter()
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(" and ");
    let layout = Layout {
        spec,
        bg: roots_gamma(cfg, spec),
        bc: cfg.nodes.blocks_coord,
        m: cfg.nodes.leaf_intervals,
        alpha_max: cfg.domain.alpha_max,
        warp: warp.as_ref(),
        knots: knots.as_ref(),
        restitution: restitution_axis(cfg)?,
        map: cfg.partial_map(),
    };
    let m = layout.m;
    let law = cfg.law();
    // Whether a split halves only the axes a cell needs, its masks stored (always with an
    // `e_n` axis; `nodes.anisotropic` without).
    let masked = layout.restitution.is_some() || cfg.nodes.anisotropic;
    // All cells ever created, roots first; `child[i]` is the first child of a split cell.
    let mut cells: Vec<Cell> = layout.roots();
    let mut child: Vec<Option<usize>> = vec![None; cells.len()];
    let mut predicted = vec![f64::NAN; cells.len()];
    let mut open: Vec<usize> = (0..cells.len())
        .filter(|&i| shard.is_none_or(|sh| sh.owns(first_root + i)))
        .collect();
    let mut cache: HashMap<Key, (f64, f64)> = HashMap::new();
    // The levels of the nodes a polish may solve again ([`polish`]).
    let mut kept: HashMap<Key, KeptLevels> = HashMap::new();
    // The axes each split cell halves (bit `dims − 1 − k` for axis `k`); 0 for a leaf.
    let mut mask = vec![0u8; cells.len()];
    // With `nodes.observed_rate`: each cell's parent and the rate per surplus axis at which its
    // surplus fell from its parent's (NaN until evaluated).
    let mut parent: Vec<Option<usize>> = vec![None; cells.len()];
    let mut rates = vec![[f64::NAN; 3]; cells.len()];
    let axis_depth: &[usize] = match (layout.pair(), layout.dims()) {
        (true, _) => &[1, 2],
        (false, 3) => &[0, 1, 2],
        _ => &[0, 1],
    };
    for round in 0.. {
        let mut wanted: Vec<Key> = open
            .iter()
            .filter(|&&c| layout.straddles(cells[c]) == 0)
            .flat_map(|&c| layout.cell_keys(cells[c]))
            .filter(|key| !cache.contains_key(key))
            .collect();
        wanted.sort_unstable();
        wanted.dedup();
        if run.nodes + wanted.len() > cfg.nodes.max_nodes {
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
                needed: run.nodes + wanted.len(),
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
        // With a polish, each node that may be solved again (its estimate above `polish_tol`)
        // keeps the levels of its refinement, so that the polish continues from them.
        let mut levels: Vec<KeptLevels> = Vec::new();
        if cfg.nodes.polish_tol.is_some() {
            levels.resize_with(points.len(), KeptLevels::new);
        }
        let keep_above = cfg.nodes.polish_tol.unwrap_or(f64::INFINITY);
        let values = solve_points_kept(
            &points,
            cfg.solver.tol,
            law,
            progress,
            opts,
            (&mut levels, keep_above),
        )?;
        run.nodes += wanted.len();
        kept.extend(
            wanted
                .iter()
                .zip(levels)
                .filter(|(_, l)| !l.is_empty())
                .map(|(&key, l)| (key, l)),
        );
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
            // A cell across the warp's start or an edge of the knots' region is split without
            // being evaluated: no leaf may straddle it.
            let cut = layout.straddles(cells[c]);
            if cut != 0 {
                mask[c] = cut;
                split[o] = true;
                continue;
            }
            let vals = values_of(cells[c]);
            let dims = layout.dims();
            let mut pred = surplus(&vals, m, k, dims) / 4.0;
            // The surplus along each axis: for the observed rate, and (computed then if not
            // yet) for the axes a split halves.
            let axes = cfg
                .nodes
                .observed_rate
                .then(|| axis_surpluses(&vals, m, k, dims));
            if let Some(axes) = axes {
                rates[c] = match parent[c] {
                    Some(p) if rates[p][0].is_finite() => observed_rates(
                        (cells[p], &values_of(cells[p]), rates[p]),
                        (cells[c], axes),
                        m,
                        k,
                        dims,
                        axis_depth,
                    ),
                    _ => [RATE_RANGE.1; 3],
                };
                let by_axis: f64 = (0..dims as usize).map(|a| axes[a] * rates[c][a]).sum();
                pred = pred.min(RATE_SAFETY * by_axis);
            }
            predicted[c] = pred;
            if pred <= cfg.nodes.target_error {
                // Inside the knots' region the knotted kink lies on a cell edge: not probed.
                let aligned = layout.knots.is_some() && layout.warped(cells[c]);
                if !kinks.is_empty() {
                    let probes = layout.kink_probes(cells[c], &kinks, aligned);
                    if !probes.is_empty() {
                        probed.push((o, vals, probes));
                    }
                }
                continue;
            }
            mask[c] = if masked {
                let axes = axes.unwrap_or_else(|| axis_surpluses(&vals, m, k, dims));
                split_axes(&axes, cfg.nodes.target_error, dims)
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
                .flat_map(|(_, _, probes)| probes.iter().map(|p| p.3))
                .collect();
            progress.phase(
                &stage_refine(spec.name),
                &format!(
                    "round {}: {} probes next to {kink_names} in {} cells",
                    round + 1,
                    points.len(),
                    probed.len()
                ),
            );
            let mut values =
                solve_points_with(&points, cfg.solver.tol, law, progress, opts)?.into_iter();
            for (o, vals, probes) in probed {
                let c = open[o];
                // The largest error measured on the node rows and at the centres between them,
                // for the kinks along the coordinate ([0]) and across `e_n` ([1]).
                let mut on_rows = [0.0_f64; 2];
                let mut centres = [0.0_f64; 2];
                for (&(u, v, w, _, across), (p, e)) in probes.iter().zip(values.by_ref()) {
                    let at = if layout.restitution.is_some() {
                        interp_cell_e(&vals, m, k, layout.pair(), (u, v, w))
                    } else {
                        interp_cell(&vals, m, k, u, v)
                    };
                    let err = (at - p).abs() + e;
                    let (along, a) = if across { (v, 1) } else { (w, 0) };
                    if u.fract() == 0.0 && along.fract() == 0.0 {
                        on_rows[a] = on_rows[a].max(err);
                    } else {
                        centres[a] = centres[a].max(err);
                    }
                }
                let measured = on_rows.into_iter().chain(centres).fold(0.0, f64::max);
                predicted[c] = predicted[c].max(measured);
                if predicted[c] > cfg.nodes.target_error {
                    mask[c] = probe_split(
                        layout.dims(),
                        layout.restitution.is_some(),
                        masked,
                        on_rows,
                        centres,
                        cfg.nodes.target_error,
                    );
                    split[o] = true;
                } else if layout.restitution.is_none() && cells[c].d[0] < cells[c].d[1] {
                    // An anisotropic cell of a table over (γ, α) that a kink crosses is no
                    // longer along γ than along c, as a quadtree's: the kink moves across c
                    // between the node rows, and the probes measured on the rows and midway.
                    mask[c] = 0b10;
                    split[o] = true;
                }
            }
        }
        let mut next = Vec::new();
        for (o, &c) in open.iter().enumerate() {
            if !split[o] {
                continue;
            }
            if layout.straddles(cells[c]) != 0 {
                // Split without being evaluated (across the warp's start or a knots' edge).
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
                parent.push(Some(c));
                rates.push([f64::NAN; 3]);
            }
        }
        if next.is_empty() {
            break;
        }
        open = next;
    }
    if let Some(tol) = cfg.nodes.polish_tol {
        polish(
            &layout,
            &cells,
            &child,
            &predicted,
            (&mut cache, &mut kept),
            tol,
            cfg,
            progress,
            opts,
        )?;
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
                split: masked.then_some(mask),
                p,
                error_estimate: err,
                warp: warp.clone(),
                knots: knots.clone(),
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

/// Each node's value and error estimate.
type NodeValues = HashMap<Key, (f64, f64)>;

/// Solve again, at `tol`, the nodes that hold a leaf's bound above `target_error + Λ^d · tol`
/// (`nodes.polish_tol`): in every leaf (a cell this run evaluated and did not split) whose
/// `predicted + Λ^d · max error_estimate` exceeds that limit, each node whose estimate exceeds
/// the leaf's own share `(limit − predicted)/Λ^d` (at least `tol`: a leaf predicts at most
/// `target_error`). Afterwards every leaf's bound is at most the limit: its nodes' estimates
/// are at most `tol` where solved again and at most its share elsewhere. The values replace
/// the nodes' first ones in `cache` (the more accurate answer at the same point); a shard
/// polishes the leaves of its own roots, so that a strict merge finds every value it needs in
/// the store.
#[allow(clippy::too_many_arguments)]
fn polish(
    layout: &Layout,
    cells: &[Cell],
    child: &[Option<usize>],
    predicted: &[f64],
    (cache, kept): (&mut NodeValues, &mut HashMap<Key, KeptLevels>),
    tol: f64,
    cfg: &Config,
    progress: &dyn Progress,
    opts: RunOptions,
) -> Result<(), RunError> {
    let factor = oblique_table::bound::node_error_factor_of(cfg.nodes.stencil, layout.dims());
    let limit = cfg.nodes.target_error + factor * tol;
    let mut wanted: Vec<Key> = Vec::new();
    for (c, cell) in cells.iter().enumerate() {
        if child[c].is_some() || !predicted[c].is_finite() {
            continue;
        }
        let keys = layout.cell_keys(*cell);
        let errs: Vec<f64> = keys.iter().map(|k| cache[k].1).collect();
        if oblique_table::bound::leaf_bound(predicted[c], &errs, factor) > limit {
            let share = ((limit - predicted[c]) / factor).max(tol);
            wanted.extend(keys.into_iter().filter(|k| cache[k].1 > share));
        }
    }
    wanted.sort_unstable();
    wanted.dedup();
    if wanted.is_empty() {
        return Ok(());
    }
    progress.phase(
        &stage_refine(layout.spec.name),
        &format!(
            "polish: {} nodes again at tol {tol:e} (stated bound <= {limit:.2e})",
            wanted.len()
        ),
    );
    let points: Vec<Point> = wanted.iter().map(|&key| layout.point(key).2).collect();
    // From the levels each node's first solve kept: the same values, fewer simulations.
    let mut levels: Vec<KeptLevels> = wanted
        .iter()
        .map(|key| kept.remove(key).unwrap_or_default())
        .collect();
    let values = solve_points_kept(
        &points,
        tol,
        cfg.law(),
        progress,
        opts,
        (&mut levels, f64::INFINITY),
    )?;
    cache.extend(wanted.into_iter().zip(values));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kink::{Kink, PROBE_OFFSETS};

    /// A kink surface of the partial-slip patch that ends below `e_n` = 0.95.
    #[derive(Debug)]
    struct Slanted;

    impl Kink for Slanted {
        fn name(&self) -> &'static str {
            "slanted"
        }

        fn patch(&self) -> PatchKind {
            PatchKind::PartialSlip
        }

        fn alpha(&self, gamma: f64, e_n: f64) -> Option<f64> {
            (e_n >= 0.95).then_some(0.45 - 0.3 * (gamma - 2.5) + 0.6 * (e_n - 1.0))
        }
    }

    /// The partial-slip patch over γ 2.3–2.6 of a Kelvin–Voigt table (one root row, four root
    /// columns along c, e_n 0.9–1 in two), leaves of 6 intervals.
    fn kv_spec() -> PatchSpec {
        PatchSpec {
            name: PatchId::PartialHigh.name(),
            kind: PatchKind::PartialSlip,
            gamma_lo: 2.3,
            gamma_hi: 2.6,
        }
    }

    fn kv_layout(spec: &PatchSpec) -> Layout<'_> {
        Layout {
            spec,
            bg: 1,
            bc: 4,
            m: 6,
            alpha_max: f64::INFINITY,
            warp: None,
            knots: None,
            restitution: Some(Axis::restitution(0.9, 1.0, 2).unwrap()),
            map: PartialMap::SqrtBoth,
        }
    }

    /// A sheet across `e_n` in the partial-slip patch: `e_K = 0.95 + 0.05 (α − 0.6) + 0.1 (γ − 2.45)`
    /// for α in 0.5–1.2.
    #[derive(Debug)]
    struct Sheet;

    impl Kink for Sheet {
        fn name(&self) -> &'static str {
            "sheet"
        }

        fn patch(&self) -> PatchKind {
            PatchKind::PartialSlip
        }

        fn alpha(&self, _gamma: f64, _e_n: f64) -> Option<f64> {
            None
        }

        fn e_n_at(&self, gamma: f64, alpha: f64) -> Option<f64> {
            (0.5..=1.2)
                .contains(&alpha)
                .then_some(0.95 + 0.05 * (alpha - 0.6) + 0.1 * (gamma - 2.45))
        }

        fn across_e_n(&self) -> bool {
            true
        }

        fn offsets(&self) -> &'static [f64] {
            &crate::kink::SHEET_PROBE_OFFSETS
        }
    }

    /// A knot sent inside a root cell along the coordinate (here 5/16 and 3/8 with root cells of
    /// 1/4) splits every cell across it inside the knots' region, along the coordinate only,
    /// until it lies on an edge; a cell outside the region, or with the knot on its edge, is not.
    #[test]
    fn a_cell_across_a_knot_off_the_root_edges_is_split_along_the_coordinate() {
        let spec = kv_spec();
        let knots = Knots::new(
            2.3,
            0.1,
            0.9,
            0.05,
            [0.0, 1.0, 0.0, 1.0],
            vec![0.3125, 0.375],
            vec![0, 0],
            [2, 4, 4],
            [vec![0.3; 16], vec![0.4; 16]].concat(),
        )
        .expect("knots");
        let layout = Layout {
            knots: Some(&knots),
            ..kv_layout(&spec)
        };
        let cell = |d: [u32; 3], ic: u64, ie: u64| Cell {
            depth: d[1],
            d,
            ig: 0,
            ic,
            ie,
        };
        // Root column 1 (c 1/4–1/2) holds both: split along c; its upper half (3/8–1/2) not.
        assert_eq!(layout.straddles(cell([0, 0, 0], 1, 0)), 0b010);
        assert_eq!(layout.straddles(cell([0, 1, 0], 2, 0)), 0b010);
        assert_eq!(layout.straddles(cell([0, 1, 0], 3, 0)), 0);
        // Its halves 1/4–5/16 and 5/16–3/8 hold none inside.
        assert_eq!(layout.straddles(cell([0, 2, 0], 4, 0)), 0);
        assert_eq!(layout.straddles(cell([0, 2, 0], 5, 0)), 0);
        // Outside the region (the second root cell along e_n) the knots do not apply.
        assert_eq!(layout.straddles(cell([0, 0, 0], 1, 1)), 0);
        assert_eq!(layout.straddles(cell([0, 0, 0], 0, 0)), 0);
    }

    #[test]
    fn probes_land_on_every_line_along_e_n_that_meets_a_sheet() {
        let spec = kv_spec();
        let layout = kv_layout(&spec);
        let kinks: Vec<Box<dyn Kink>> = vec![Box::new(Sheet)];
        let d = 3;
        let (mut probed_cells, mut lines, mut centres) = (0, 0, 0);
        for ig in 0..1u64 << d {
            for ic in 0..(layout.bc as u64) << d {
                for ie in 0..(2u64 << d) {
                    let cell = Cell {
                        depth: d,
                        d: [d; 3],
                        ig,
                        ic,
                        ie,
                    };
                    let probes = layout.kink_probes(cell, &kinks, false);
                    probed_cells += usize::from(!probes.is_empty());
                    let keys = layout.cell_keys(cell);
                    let e0 = layout.point(keys[0]).2.e_n;
                    let e1 = layout.point(keys[keys.len() - 1]).2.e_n;
                    let de = (e1 - e0) / 6.0;
                    let mut seen = std::collections::BTreeMap::new();
                    for &(u, v, w, pt, across) in &probes {
                        assert!(across && (0.0..=6.0).contains(&w), "{u} {v} {w}");
                        assert!((u * 2.0).fract() == 0.0 && (v * 2.0).fract() == 0.0);
                        assert_eq!(u.fract() == 0.0, v.fract() == 0.0, "{u} {v}");
                        // On the line, at an offset from where it meets the sheet (α moves
                        // along the line with α_c1(e_n): e_K at the probe's own α is a few
                        // thousandths of an interval from e_K where the line meets it).
                        seen.insert(((u * 2.0) as i64, (v * 2.0) as i64), ());
                        centres += usize::from(u.fract() != 0.0);
                        let Some(e_k) = Sheet.e_n_at(pt.gamma, pt.alpha) else {
                            continue; // at the edge of the sheet's span in α
                        };
                        let off = (pt.e_n - e_k) / de;
                        assert!(
                            crate::kink::SHEET_PROBE_OFFSETS
                                .iter()
                                .any(|&o| (o - off).abs() < 0.02),
                            "offset {off} at {pt:?}"
                        );
                        assert!((pt.e_n - (e0 + de * w)).abs() < 1e-12);
                    }
                    lines += seen.len();
                }
            }
        }
        assert!(probed_cells > 0 && lines > probed_cells && centres > 0);
    }

    /// The `(m+1)²` values of `f(x, y)` on a cell of a quadtree over the unit square
    /// (`x` outer): depth `d`, position `(i, j)`.
    fn grid(f: impl Fn(f64, f64) -> f64, m: usize, d: u32, (i, j): (u64, u64)) -> Vec<f64> {
        let h = 1.0 / f64::from(1u32 << d);
        (0..=m)
            .flat_map(|a| (0..=m).map(move |b| (a, b)))
            .map(|(a, b)| {
                let x = (i as f64 + a as f64 / m as f64) * h;
                let y = (j as f64 + b as f64 / m as f64) * h;
                f(x, y)
            })
            .collect()
    }

    #[test]
    fn the_observed_rate_is_fast_on_smooth_cells_and_a_quarter_across_a_kink() {
        let (m, k) = (6, 4);
        let cell = |d: u32, ig: u64, ic: u64| Cell {
            depth: d,
            d: [d, d, 0],
            ig,
            ic,
            ie: 0,
        };
        let rates = |f: &dyn Fn(f64, f64) -> f64, child: (u64, u64)| {
            let p = grid(f, m, 2, (1, 1));
            let c = grid(f, m, 3, child);
            let axes = [
                surplus_axis(&c, m, k, 2, 0),
                surplus_axis(&c, m, k, 2, 1),
                0.0,
            ];
            observed_rates(
                (cell(2, 1, 1), &p, [0.25; 3]),
                (cell(3, child.0, child.1), axes),
                m,
                k,
                2,
                &[0, 1],
            )
        };
        // Smooth: near the cubic's fourth order (1/16).
        let smooth = |x: f64, y: f64| (1.3 * x).sin() * (0.7 + y).exp();
        for child in [(2, 2), (3, 3), (2, 3)] {
            let r = rates(&smooth, child);
            assert!(r[0] < 0.1 && r[1] < 0.1, "{child:?}: {r:?}");
        }
        // A curvature jump along y = 0.4 (inside the child (2, 3), which covers y 0.375–0.5;
        // not inside (2, 2)): second order across it, so a quarter along y there; the child
        // beside it converges as fast as smooth cells, measured on its own part of the parent.
        let kink = |x: f64, y: f64| smooth(x, y) + 3.0 * (y - 0.4).max(0.0).powi(2);
        let r = rates(&kink, (2, 3));
        assert!(r[1] > 0.2, "{r:?}");
        let r = rates(&kink, (2, 2));
        assert!(r[1] < 0.1, "{r:?}");
    }

    #[test]
    fn a_probed_cell_halves_the_axes_its_probes_point_to() {
        // (γ, c, e_n): bits 4, 2, 1; one pair (c, e_n): 2, 1; elastic (γ, c): 2, 1 with
        // stored masks, every axis without.
        assert_eq!(
            probe_split(3, true, true, [2.0, 0.0], [0.5, 0.0], 1.0),
            0b010
        );
        assert_eq!(
            probe_split(3, true, true, [0.5, 0.0], [2.0, 0.0], 1.0),
            0b101
        );
        assert_eq!(
            probe_split(3, true, true, [2.0, 0.0], [2.0, 0.0], 1.0),
            0b111
        );
        assert_eq!(
            probe_split(2, true, true, [2.0, 0.0], [0.5, 0.0], 1.0),
            0b10
        );
        assert_eq!(
            probe_split(2, true, true, [0.5, 0.0], [2.0, 0.0], 1.0),
            0b01
        );
        // (γ, c) with masks: c is bit 0, γ bit 1; a quadtree halves both.
        assert_eq!(
            probe_split(2, false, true, [2.0, 0.0], [0.5, 0.0], 1.0),
            0b01
        );
        assert_eq!(
            probe_split(2, false, true, [0.5, 0.0], [2.0, 0.0], 1.0),
            0b10
        );
        assert_eq!(
            probe_split(2, false, true, [2.0, 0.0], [2.0, 0.0], 1.0),
            0b11
        );
        assert_eq!(
            probe_split(2, false, false, [2.0, 0.0], [0.0, 0.0], 1.0),
            0b11
        );
        // A kink across e_n: its lines halve e_n (bit 0), its centres the other axes.
        assert_eq!(
            probe_split(3, true, true, [0.0, 2.0], [0.0, 0.5], 1.0),
            0b001
        );
        assert_eq!(
            probe_split(3, true, true, [0.0, 0.5], [0.0, 2.0], 1.0),
            0b110
        );
        assert_eq!(
            probe_split(2, true, true, [0.0, 2.0], [0.0, 0.0], 1.0),
            0b01
        );
    }

    /// A kink of the stick patch of an elastic table steep in the patch coordinate.
    #[derive(Debug)]
    struct Steep;

    impl Kink for Steep {
        fn name(&self) -> &'static str {
            "steep"
        }

        fn patch(&self) -> PatchKind {
            PatchKind::Stick
        }

        fn alpha(&self, gamma: f64, e_n: f64) -> Option<f64> {
            (e_n == 1.0).then(|| 1.0 / (0.75 + 5.0 * (gamma - 1.87)))
        }
    }

    #[test]
    fn a_kink_steep_across_the_rows_of_a_table_without_e_n_is_probed_between_them() {
        let spec = PatchSpec {
            name: PatchId::StickHigh.name(),
            kind: PatchKind::Stick,
            gamma_lo: 1.75,
            gamma_hi: 2.0,
        };
        let layout = Layout {
            spec: &spec,
            bg: 1,
            bc: 4,
            m: 8,
            alpha_max: f64::INFINITY,
            warp: None,
            knots: None,
            restitution: None,
            map: PartialMap::SqrtBoth,
        };
        let kinks: Vec<Box<dyn Kink>> = vec![Box::new(Steep)];
        let per_c = |d: u32| ((layout.bc * layout.m) << d) as f64;
        let v_of = |pt: &Point, d: u32| {
            let a = Steep.alpha(pt.gamma, 1.0).unwrap();
            PatchKind::Stick.coord_at(PartialMap::SqrtBoth, pt.gamma, a, 1.0, f64::INFINITY)
                * per_c(d)
        };
        let (mut between, mut cells) = (0, 0);
        for (dg, dc) in [(1u32, 3u32), (3, 1)] {
            for ig in 0..1u64 << dg {
                for ic in 0..(layout.bc as u64) << dc {
                    let cell = Cell {
                        depth: dg.max(dc),
                        d: [dg, dc, 0],
                        ig,
                        ic,
                        ie: 0,
                    };
                    let probes = layout.kink_probes(cell, &kinks, false);
                    cells += usize::from(!probes.is_empty());
                    // The rows that hold probes, in order along γ, each with the kink's position
                    // along c in node intervals.
                    let mut rows: Vec<(f64, f64)> = probes
                        .iter()
                        .map(|&(u, _, w, pt, _)| {
                            assert_eq!((w, pt.e_n), (0.0, 1.0));
                            (u, v_of(&pt, dc))
                        })
                        .collect();
                    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
                    rows.dedup_by(|a, b| a.0 == b.0);
                    between += rows.iter().filter(|r| r.0.fract() != 0.0).count();
                    // Consecutive rows next to the kink: it moves by at most one interval
                    // between rows off the node rows (unless they are the closest allowed,
                    // 1/16 of a row apart), and by more only between two node rows.
                    for w in rows.windows(2) {
                        let ((u0, v0), (u1, v1)) = (w[0], w[1]);
                        if u1 - u0 <= 1.0 && (u0.fract() != 0.0 || u1.fract() != 0.0) {
                            assert!(
                                (v1 - v0).abs() <= 1.0 + 1e-9 || u1 - u0 == 1.0 / 16.0,
                                "{cell:?}: {w:?}"
                            );
                        }
                    }
                }
            }
        }
        assert!(cells > 0 && between > 0, "{cells} {between}");
    }

    #[test]
    fn probes_land_in_the_cells_next_to_a_kink_surface_on_every_node_row() {
        // γ 2.3–2.6 in one root row, c in four, e_n 0.9–1 in two; cells at depth 3 (1/8 of a
        // root cell along each axis).
        let spec = kv_spec();
        let layout = kv_layout(&spec);
        let kinks: Vec<Box<dyn Kink>> = vec![Box::new(Slanted)];
        let d = 3;
        // Node intervals per unit of c at depth 3.
        let per_c = ((layout.bc * layout.m) << d) as f64;
        let mut probed_cells = 0;
        let mut rows_with_kink_inside = 0;
        let mut centres = 0;
        for ig in 0..1u64 << d {
            for ic in 0..(layout.bc as u64) << d {
                for ie in 0..(2u64 << d) {
                    let cell = Cell {
                        depth: d,
                        d: [d; 3],
                        ig,
                        ic,
                        ie,
                    };
                    let probes = layout.kink_probes(cell, &kinks, false);
                    probed_cells += usize::from(!probes.is_empty());
                    let keys = layout.cell_keys(cell);
                    let (g0, c0, e0) = {
                        let (g, c, p) = layout.point(keys[0]);
                        (g, c, p.e_n)
                    };
                    let (g1, _, e1) = {
                        let (g, c, p) = layout.point(keys[keys.len() - 1]);
                        (g, c, p.e_n)
                    };
                    for &(u, v, w, pt, _) in &probes {
                        // On a node row of the cell or at the centre between four, inside it
                        // along the coordinate.
                        assert!((u * 2.0).fract() == 0.0 && (w * 2.0).fract() == 0.0);
                        assert_eq!(u.fract() == 0.0, w.fract() == 0.0, "{u} {w}");
                        assert!((0.0..=6.0).contains(&v) && u <= 6.0 && w <= 6.0);
                        centres += usize::from(u.fract() != 0.0);
                        let g = g0 + (g1 - g0) * u / 6.0;
                        let e_n = e0 + (e1 - e0) * w / 6.0;
                        assert!((pt.gamma - g).abs() < 1e-12 && (pt.e_n - e_n).abs() < 1e-12);
                        if u.fract() == 0.0 {
                            let (i, l) = (u as usize, w as usize);
                            let (gn, _, node) = layout.point(keys[(i * 7) * 7 + l]);
                            assert_eq!((pt.gamma, pt.e_n), (gn, node.e_n));
                        }
                        assert!(pt.e_n >= 0.95, "{pt:?}");
                        // At one of the offsets from the kink on that row.
                        let coord = |a: f64| {
                            PatchKind::PartialSlip.coord_at(
                                PartialMap::SqrtBoth,
                                pt.gamma,
                                a,
                                pt.e_n,
                                f64::INFINITY,
                            )
                        };
                        let c_k = coord(Slanted.alpha(pt.gamma, pt.e_n).unwrap());
                        let off = (coord(pt.alpha) - c_k) * per_c;
                        assert!(
                            PROBE_OFFSETS.iter().any(|o| (o - off).abs() < 1e-6),
                            "{off} at {pt:?}"
                        );
                        assert!(((coord(pt.alpha) - c0) * per_c - v).abs() < 1e-6);
                    }
                    // Every node row the kink crosses inside the cell has the probe on it.
                    for i in 0..=6usize {
                        for l in 0..=6usize {
                            let (g, c0, node) = layout.point(keys[(i * 7) * 7 + l]);
                            let Some(a) = Slanted.alpha(g, node.e_n) else {
                                continue;
                            };
                            let v = (PatchKind::PartialSlip.coord_at(
                                PartialMap::SqrtBoth,
                                g,
                                a,
                                node.e_n,
                                f64::INFINITY,
                            ) - c0)
                                * per_c;
                            if (0.0..=6.0).contains(&v) {
                                rows_with_kink_inside += 1;
                                assert!(
                                    probes.iter().any(|p| p.0 == i as f64
                                        && p.2 == l as f64
                                        && (p.1 - v).abs() < 1e-6),
                                    "row {i}, {l} of {cell:?}"
                                );
                            }
                        }
                    }
                }
            }
        }
        // The kink crosses a few columns of cells along c; the other cells get no probes.
        assert!(rows_with_kink_inside > 0 && centres > 0);
        assert!(
            probed_cells > 0 && probed_cells < (1 << d) * (2 << d) * 4,
            "{probed_cells}"
        );
    }
}
