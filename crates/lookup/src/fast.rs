//! The query path of [`crate::Table`]: the interpolation rule of [`oblique_table::surface`] (steps 1–10
//! of `docs/table-format.md`) on an acceleration structure built once at [`crate::Table::open`].
//!
//! It returns the same bits as [`Surface::eval_with`] (the rule written step by step); only the
//! way to the leaf differs. Instead of descending each patch's quadtree from its root, a query
//! reads a **fine index**: a uniform grid at depth `D` (the deepest leaf's depth, or less if the
//! grid would exceed [`MAX_INDEX_ENTRIES`]) over the patch, each entry naming the deepest cell
//! of depth `≤ D` that contains it. That cell is a leaf unless `D` was capped, in which case the
//! descent of the rule continues from it. The position inside a cell of depth `d` with integer
//! origin `(A, B)` (in units of its own size) is `v·2^d − A`, where `v = x·blocks` is what the
//! rule's first step computes: multiplying by a power of two and subtracting an integer below
//! the value are exact in binary floating point, so this equals the rule's repeated
//! `f ← 2f − q` bit for bit, and the leaf and the weights are the rule's.
//!
//! The patch with its fine index ([`IndexedPatch`]) and the arithmetic of its leaves
//! (`oblique_table::leaf`) are the format crate's, the same code as the rule's: this module
//! chooses the patch and its coordinate and applies the domain policy. Only the shipped
//! stencil (`k = 4`) takes this path; other stencils use [`Surface`] directly.
//!
//! One structure for every number of axes ([`Accel`] over `D` axes: 2 for an elastic table,
//! 3 with an `e_n` axis) and one query sequence ([`Accel::eval`]): the checks, the region, the
//! full-slip line, the domain policy ([`Surface::apply_domain_e`]), the patch coordinate, the
//! leaf. The number of axes is a constant of each instance, so the branches on it cost nothing.
//!
//! Batches ([`Accel::eval_batch`], in `fast/batch.rs`) run the same operations in passes over
//! arrays (classification, coordinates, index, stencils, tensor product) that the compiler
//! vectorizes, in a baseline x86-64 build and an AVX2 build chosen at run time; both return the
//! same bits as the single-query path (tested on both builds and all shipped tables). They are
//! written out for the two axes of an elastic table: the passes keep one query per vector lane
//! and cannot share the scalar sequence. A batch at normal restitution `e_n < 1` is answered
//! query by query. The per-γ curves (`curve.rs`) and the lines of a prepared pair (`line.rs`)
//! keep the sequence's order with the `γ`-only parts computed once (their comments say where).

use crate::LookupError;
use oblique_table::indexed::IndexedPatch;
use oblique_table::leaf::cubic_tensor;
#[cfg(target_arch = "x86_64")]
use oblique_table::leaf::cubic_tensor3_avx;
use oblique_table::surface::{full_slip_line, partial_coord, partial_coord_map, stick_coord};
use oblique_table::surface::{OutOfDomain, PartialMap, PatchKind, Region, Surface};

mod batch;

/// The structure of a table with an `e_n` axis: [`Accel`] over `(γ, c, e_n)`.
pub(crate) type Accel3 = Accel<3>;

/// Largest number of entries of one patch's fine index (`Patch::fine_index`). A full-depth
/// index for `partial_high` of `tables/full.h5` (327 680 entries, 1.3 MB) answered a repeated
/// point in the deepest leaves 10 % faster but a random stream of 2²⁰ queries 10–15 % slower
/// (cache misses).
pub(crate) use oblique_table::surface::MAX_INDEX_ENTRIES;

/// Queries per chunk of [`Accel::eval_batch`] (fits its `u16` query numbers).
const BATCH: usize = 256;

/// The acceleration structure of a table: its three patches with their fine indexes over `D`
/// axes (`γ`, `c`, and `e_n` when `D = 3`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Accel<const D: usize> {
    gamma_min: f64,
    gamma_max: f64,
    alpha_max: f64,
    /// The partial-slip coordinate's map ([`Surface::partial_map`]).
    partial_map: PartialMap,
    /// The patches with their indexes, indexed by [`PatchId::index`].
    ///
    /// [`PatchId::index`]: oblique_table::surface::PatchId::index
    patches: [Option<IndexedPatch<D>>; 3],
    /// Every patch passes [`IndexedPatch::fits_u32`] (the batch path's 32-bit positions).
    batch_u32: bool,
}

impl<const D: usize> Accel<D> {
    /// The structure for `surface`, or `None` when its stencil is not the cubic one (those
    /// tables are answered by [`Surface::eval_point`]) or its patches do not have `D` axes
    /// (`D = 3`: only for a table with an `e_n` axis).
    pub(crate) fn new(surface: &Surface) -> Option<Accel<D>> {
        Accel::with_budget(surface, MAX_INDEX_ENTRIES)
    }

    /// [`Accel::new`] with at most `max_entries` index entries per patch.
    fn with_budget(surface: &Surface, max_entries: usize) -> Option<Accel<D>> {
        // An elastic structure never serves a table without the full-slip line (D = 2 has
        // no e_n axis and takes the elastic region).
        if surface.stencil() != 4
            || (D == 3 && surface.restitution().is_none())
            || (D == 2 && !surface.has_line())
        {
            return None;
        }
        let mut patches: [Option<IndexedPatch<D>>; 3] = [None, None, None];
        for (id, p) in surface.patches() {
            patches[id.index()] = Some(IndexedPatch::new(p, max_entries)?);
        }
        let batch_u32 = patches.iter().flatten().all(IndexedPatch::fits_u32);
        Some(Accel {
            gamma_min: surface.gamma_min(),
            gamma_max: surface.gamma_max(),
            alpha_max: surface.alpha_max(),
            partial_map: surface.partial_map(),
            patches,
            batch_u32,
        })
    }

    /// Bytes held by the fine indexes and cell lists (not counting the copy of `P`).
    pub(crate) fn index_bytes(&self) -> usize {
        self.patches
            .iter()
            .flatten()
            .map(IndexedPatch::index_bytes)
            .sum()
    }

    /// [`Surface::eval_point`], bit for bit (`e_n` must be 1 when `D = 2`: the caller's). The
    /// checks and the full-slip line are inlined into the caller; the patches are answered out
    /// of line ([`Accel::eval_off_line`]; with `D = 3` compiled for AVX where the processor
    /// has it, [`Accel::eval_off_line_avx`]).
    #[inline(always)]
    pub(crate) fn eval(
        &self,
        surface: &Surface,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        let region = if D == 2 {
            // An elastic table answers `e_n = 1` only (checked by the caller), where
            // `Region::of_e` is `Region::of`, bit for bit, and `check_e_n` passes.
            oblique_table::surface::check_query(gamma, alpha)?;
            Region::of(gamma, alpha)
        } else {
            surface.region_of(gamma, alpha, e_n)?
        };
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        #[cfg(target_arch = "x86_64")]
        if D == 3 && (cfg!(target_feature = "avx") || std::is_x86_feature_detected!("avx")) {
            // SAFETY: the processor has AVX (checked just above, or enabled for the build).
            return unsafe { self.eval_off_line_avx(surface, region, gamma, alpha, e_n, outside) };
        }
        self.eval_off_line(surface, region, gamma, alpha, e_n, outside)
    }

    /// [`Accel::eval`] for a valid query above the full-slip line.
    #[inline(never)]
    fn eval_off_line(
        &self,
        surface: &Surface,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        let e_n = if D == 2 { 1.0 } else { e_n };
        surface.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n, cubic_tensor)
        })
    }

    /// [`Accel::eval_off_line`] of three axes compiled for AVX, with the leaf's sum in 256-bit
    /// vectors ([`cubic_tensor3_avx`], inlined here): the same operations, so the same bits (no
    /// product is fused with a sum: FMA is not enabled). Called only when `D = 3`.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    fn eval_off_line_avx(
        &self,
        surface: &Surface,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        surface.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n, |vals, n1, f| {
                cubic_tensor3_avx(vals, n1, std::array::from_fn(|k| f[k]))
            })
        })
    }

    /// In a known non-line region: the patch's coordinate, then its tensor product from
    /// `tensor` ([`IndexedPatch::interpolate_by`]) at `(γ, c)` or `(γ, c, e_n)`.
    #[inline(always)]
    fn eval_in(
        &self,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        tensor: impl Fn(&[f64], usize, [f64; D]) -> f64,
    ) -> f64 {
        let patch = match region.patch_id() {
            Some(id) => self.patches[id.index()].as_ref(),
            None => None,
        };
        match patch {
            Some(patch) => {
                let c = match patch.kind() {
                    PatchKind::PartialSlip if D == 2 => partial_coord(gamma, alpha),
                    PatchKind::PartialSlip => {
                        partial_coord_map(self.partial_map, gamma, alpha, e_n)
                    }
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                let point = [gamma, c.clamp(0.0, 1.0), e_n];
                patch.interpolate_by(std::array::from_fn(|k| point[k]), tensor)
            }
            None => -e_n,
        }
    }
}

impl Accel<2> {
    /// [`Accel::eval`] of an elastic table (`e_n = 1`): [`Surface::eval_with`], bit for bit.
    #[inline(always)]
    pub(crate) fn eval_with(
        &self,
        surface: &Surface,
        gamma: f64,
        alpha: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        self.eval(surface, gamma, alpha, 1.0, outside)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Table;
    use oblique_table::surface::{PatchId, Warp};

    pub(super) fn table(name: &str) -> Table {
        Table::open(format!(
            "{}/../../tables/{name}",
            env!("CARGO_MANIFEST_DIR")
        ))
        .expect(name)
    }

    /// A warp of `partial_high` from its middle root row boundary on (the node values stay
    /// those of the table: only the bits of the query paths are compared). A root boundary is
    /// a valid start whatever the quadtree: no leaf straddles it.
    pub(super) fn warped(t: Table) -> Table {
        let surface = t
            .surface()
            .map_patches(|id, p| {
                if id != PatchId::PartialHigh {
                    return Ok(p.clone());
                }
                let start = p.blocks_gamma().div_ceil(2) as f64;
                let from =
                    p.gamma_lo() + (p.gamma_hi() - p.gamma_lo()) * start / p.blocks_gamma() as f64;
                let knot = (0..13)
                    .map(|i| 0.4 + 0.25 * (i as f64 * 0.5).sin() * (i as f64 / 12.0))
                    .collect();
                let gamma_step = (p.gamma_hi() - from) / 12.0;
                p.with_warp(Some(Warp::new(start, from, gamma_step, 0.5, knot)?))
            })
            .expect("a valid warp");
        Table::from_parts(
            surface,
            t.provenance().clone(),
            t.checks().to_vec(),
            t.error_bound(),
        )
    }

    /// The shipped tables, and each with a warp of its partial-slip patch.
    fn tables() -> Vec<(String, Table)> {
        let mut v = Vec::new();
        for name in ["quick.h5", "full.h5"] {
            v.push((name.to_string(), table(name)));
            v.push((format!("{name} warped"), warped(table(name))));
        }
        v
    }

    /// Points spread over the plane, plus points exactly on the edges of the finest cells
    /// (where the rule sends a point to the upper cell).
    pub(super) fn points(t: &Table) -> Vec<(f64, f64)> {
        let s = &t.surface();
        let mut pts = crate::testing::domain_points(s, 20_000, 0x1234_5678_9ABC_DEF1);
        for patch in s.patches().map(|(_, p)| p) {
            let steps = patch.blocks_gamma() << 7;
            for i in 0..=steps {
                let g = patch.gamma_lo()
                    + (patch.gamma_hi() - patch.gamma_lo()) * i as f64 / steps as f64;
                for j in 0..=(patch.blocks_coord() << 5) {
                    let c = j as f64 / (patch.blocks_coord() << 5) as f64;
                    pts.push((g, patch.kind().alpha(g, c, s.alpha_max())));
                    // The cell edges are at c' of the warp: c = invert(c').
                    if let Some(w) = &patch.warp() {
                        pts.push((g, patch.kind().alpha(g, w.invert(g, c), s.alpha_max())));
                    }
                }
            }
        }
        pts
    }

    #[test]
    fn the_fine_index_gives_the_bits_of_the_descent() {
        for (name, t) in tables() {
            let s = &t.surface();
            // Full depth, and capped depths from which the descent continues.
            for budget in [1 << 20, MAX_INDEX_ENTRIES, 64, 1] {
                let accel = Accel::<2>::with_budget(s, budget).expect("cubic table");
                for &(g, a) in &points(&t) {
                    for o in [OutOfDomain::Error, OutOfDomain::Clamp] {
                        let fast = accel.eval_with(s, g, a, o).ok().map(f64::to_bits);
                        let rule = s.eval_with(g, a, o).ok().map(f64::to_bits);
                        assert_eq!(fast, rule, "{name}, budget {budget}: ({g}, {a})");
                    }
                }
            }
        }
    }

    #[test]
    fn batches_sorted_by_region_give_the_bits_of_single_queries() {
        for t in [table("full.h5"), warped(table("full.h5"))] {
            batches_give_the_bits_of_single_queries(&t);
        }
    }

    fn batches_give_the_bits_of_single_queries(t: &Table) {
        let s = &t.surface();
        let accel = Accel::<2>::new(s).expect("cubic table");
        let mut pts = points(t);
        // Outside the domain, on the line outside it, at γ = 1.
        pts.extend([
            (0.05, 0.001),
            (0.05, 1.0),
            (5.0, 0.1),
            (5.0, 3.0),
            (1.0, 0.5),
        ]);
        pts.extend([(1.0, f64::INFINITY), (2.0, 1e300), (s.gamma_max(), 0.5)]);
        let (g, a): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
        let mut out = vec![f64::NAN; g.len()];
        accel
            .eval_batch(s, &g, &a, &mut out, OutOfDomain::Clamp)
            .expect("clamped");
        for i in 0..g.len() {
            let one = accel.eval_with(s, g[i], a[i], OutOfDomain::Clamp).unwrap();
            assert_eq!(out[i].to_bits(), one.to_bits(), "({}, {})", g[i], a[i]);
        }
        // Without clamping: the first point outside is the error, out after it untouched.
        let first = (0..g.len())
            .find(|&i| accel.eval_with(s, g[i], a[i], OutOfDomain::Error).is_err())
            .expect("a point outside");
        let mut out = vec![f64::NAN; g.len()];
        let (index, _) = accel
            .eval_batch(s, &g, &a, &mut out, OutOfDomain::Error)
            .expect_err("outside");
        assert_eq!(index, first);
        assert!(out[..first].iter().all(|p| !p.is_nan()));
        assert!(out[first..].iter().all(|p| p.is_nan()));
        // Invalid values.
        let mut bad = a.clone();
        bad[777] = f64::NAN;
        let r = accel.eval_batch(s, &g, &bad, &mut out, OutOfDomain::Clamp);
        assert_eq!(r.map_err(|(i, _)| i), Err(777));
    }

    #[test]
    fn both_paths_apply_the_warp() {
        let plain = table("full.h5");
        let t = warped(table("full.h5"));
        let w = t
            .surface()
            .patch_by_id(PatchId::PartialHigh)
            .and_then(|p| p.warp().cloned());
        let w = w.expect("warp");
        let (mut changed, mut same) = (0, 0);
        for i in 0..200 {
            let g = 2.0 + 1.5 * i as f64 / 199.0;
            let (c1, c2) = (
                oblique_table::surface::alpha_c1(g),
                oblique_table::surface::alpha_c2(g),
            );
            let a = c1 + (c2 - c1) * 0.37;
            let p = t.p(g, a).expect("inside");
            assert_eq!(
                p.to_bits(),
                t.surface().eval(g, a).expect("inside").to_bits()
            );
            // By hand: the unwarped patch interpolated at c' = apply(γ, c).
            let patch = t
                .surface()
                .patch_by_id(PatchId::PartialHigh)
                .expect("partial_high");
            let c = oblique_table::surface::partial_coord(g, a).clamp(0.0, 1.0);
            let by_hand = patch.interpolate(g, patch.warped(g, c), 4);
            assert_eq!(p.to_bits(), by_hand.to_bits(), "({g}, {a})");
            if p != plain.p(g, a).expect("inside") {
                changed += 1;
            } else {
                same += 1;
            }
            let v = (g - patch.gamma_lo()) / (patch.gamma_hi() - patch.gamma_lo()) * 5.0;
            if v < w.start() {
                assert_eq!(p, plain.p(g, a).unwrap(), "({g}, {a})");
            }
        }
        assert!(changed > 0 && same > 0, "{changed} changed, {same} same");
    }

    #[test]
    fn a_table_made_from_a_changed_surface_answers_from_it() {
        let t = table("quick.h5");
        let before = t.p(1.754, 1.0).expect("stick_high");
        let changed = t
            .surface()
            .map_patches(|id, p| {
                if id == PatchId::StickHigh {
                    p.map_values(|_, _| 0.5)
                } else {
                    Ok(p.clone())
                }
            })
            .expect("valid values");
        let t2 = Table::from_parts(changed, t.provenance().clone(), t.checks().to_vec(), 0.0);
        assert_eq!(
            t.p(1.754, 1.0).expect("stick_high"),
            before,
            "the original is immutable"
        );
        let after = t2.p(1.754, 1.0).expect("stick_high");
        assert!((after - 0.5).abs() < 1e-15, "{after}");
        assert_eq!(after, t2.surface().eval(1.754, 1.0).expect("stick_high"));
    }

    #[test]
    fn the_index_of_the_full_table_is_small() {
        let t = table("full.h5");
        let bytes = t.index_bytes();
        // At most 3 × 128 KiB of index plus 32 bytes per quadtree cell; far below 16 MiB.
        assert!(bytes > 0 && bytes <= 16 << 20, "{bytes} bytes");
        let accel = Accel::<2>::new(t.surface()).expect("cubic table");
        let s = &t.surface();
        for id in PatchId::ALL {
            let (Some(patch), Some(fast)) = (s.patch_by_id(id), &accel.patches[id.index()]) else {
                continue;
            };
            // The index depth per axis: the deepest leaf's along that axis, then, beyond the
            // budget, one less along both axes (a quadtree) or along the deepest one (cells
            // that halve only the axes of their masks, `split`).
            let mut deepest = [0u32; 2];
            let mut stack: Vec<(usize, [u32; 2])> =
                (0..patch.roots()).map(|i| (i, [0, 0])).collect();
            while let Some((cell, d)) = stack.pop() {
                let t = patch.tree()[cell];
                if t < 0 {
                    deepest = [deepest[0].max(d[0]), deepest[1].max(d[1])];
                    continue;
                }
                let mask = patch.split_mask(cell);
                let child = [
                    d[0] + u32::from(mask & 2 != 0),
                    d[1] + u32::from(mask & 1 != 0),
                ];
                stack.extend((0..patch.fanout_of(cell)).map(|q| (t as usize + q, child)));
            }
            let blocks = [patch.blocks_gamma(), patch.blocks_coord()];
            let entries = |d: [u32; 2]| (blocks[0] << d[0]) * (blocks[1] << d[1]);
            let mut d = deepest;
            while entries(d) > MAX_INDEX_ENTRIES && d != [0, 0] {
                if patch.split().is_none() {
                    d = [d[0] - 1, d[1] - 1];
                } else {
                    let k = usize::from(d[1] > d[0]);
                    d[k] -= 1;
                }
            }
            assert_eq!(
                fast.shape(),
                [blocks[0] << d[0], blocks[1] << d[1]],
                "{id:?}"
            );
        }
        // partial_high of tables/full.h5 has leaves down to depth 12: its index is capped.
        let partial = s.patch_by_id(PatchId::PartialHigh).expect("partial_high");
        assert!(partial.leaf_depths().into_iter().max() > Some(5));
        assert!(accel.patches[1]
            .as_ref()
            .map(|p| p.shape()[0] * p.shape()[1])
            .is_some_and(|n| n <= MAX_INDEX_ENTRIES));
    }
}
