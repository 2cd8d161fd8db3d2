//! The batch path of [`Accel`]: [`Accel::eval_batch`] answers a chunk of [`BATCH`] queries in
//! passes over small arrays, each pass a loop of one kind of work, written so that the compiler
//! can vectorize the arithmetic (classification, patch coordinates, stencil weights) and the
//! processor can overlap the memory reads of consecutive queries (index, cell, nodes).
//!
//! Every pass performs the operations of the single-query path ([`Accel::eval_with`]) in the
//! same order on the same values, so the answers have the same bits: IEEE division, square
//! root, `min`/`max` and the integer conversions do not depend on whether a value is in a
//! vector lane or a scalar register, and no multiply–add is fused (Rust never contracts them).
//! The few places where a vector unit needs a different formulation (32-bit conversions, the
//! floor by truncation in floating point) are shown equal to the single-query path's, and tested.
//!
//! The passes are compiled twice: for baseline x86-64 (SSE2), and with AVX2 enabled
//! (`#[target_feature]`, used when the processor reports AVX2 at run time), where the
//! compiler's vectorization pays most (SSE4.1 truncation and blends, 4 lanes). No
//! `-C target-cpu` is needed: binaries and tables run on any x86-64.

use super::{Accel, BATCH};
use crate::LookupError;
use oblique_table::indexed::IndexedPatch;
use oblique_table::leaf::{cubic_stencils_f64, cubic_stencils_u32, cubic_sum, exact_u32};
use oblique_table::surface::{
    bound_p, full_slip_line, partial_arg, partial_ratio, stick_coord_from, stick_parts,
    OutOfDomain, PartialMap, PatchKind, Region, Surface,
};

/// The per-patch arrays of one chunk (structure of arrays, `BATCH` entries each).
struct Lanes {
    /// γ and α of the patch's queries, gathered from the chunk.
    g: [f64; BATCH],
    a: [f64; BATCH],
    /// Position along γ and `c` in units of the root cells (`v` of the rule's step 5); later,
    /// the position inside the leaf (`fγ`, `fc` of step 6).
    vg: [f64; BATCH],
    vc: [f64; BATCH],
    /// Fine index entry; later, the leaf number.
    slot: [u32; BATCH],
    /// Scratch for the partial-slip coordinate (the arguments of the two logarithms).
    x: [f64; BATCH],
    r: [f64; BATCH],
    /// First node of each query's 4 × 4 block in `p`, and the stencil weights (four along γ,
    /// then four along `c`).
    start: [u32; BATCH],
    w: [[f64; BATCH]; 8],
}

impl Lanes {
    fn new() -> Lanes {
        Lanes {
            g: [0.0; BATCH],
            a: [0.0; BATCH],
            vg: [0.0; BATCH],
            vc: [0.0; BATCH],
            slot: [0; BATCH],
            x: [0.0; BATCH],
            r: [0.0; BATCH],
            start: [0; BATCH],
            w: [[0.0; BATCH]; 8],
        }
    }
}

/// `out[list[k]] = p.interpolate([γ_k, c_k])` for the `n` queries gathered in `lanes` whose
/// patch coordinates `c_k` are in `lanes.vc` (not yet clamped): the steps of
/// [`IndexedPatch::interpolate`] in passes, each through the rule's own functions (the vector
/// formulations of `oblique_table::leaf` where a vector unit needs them).
#[inline(always)]
fn interpolate_lanes<const AVX2: bool>(
    p: &IndexedPatch<2>,
    lanes: &mut Lanes,
    n: usize,
    list: &[u16],
    out: &mut [f64],
) {
    // Step 6 along γ: `v = x·blocks`, clamped, and the clamped coordinate.
    for ((vg, vc), &g) in lanes.vg[..n]
        .iter_mut()
        .zip(&mut lanes.vc[..n])
        .zip(&lanes.g[..n])
    {
        *vg = p.position(0, g);
        *vc = vc.clamp(0.0, 1.0);
    }
    // Step 5, the warp from its start on.
    if p.warp().is_some() {
        for ((&vg, vc), &g) in lanes.vg[..n]
            .iter()
            .zip(&mut lanes.vc[..n])
            .zip(&lanes.g[..n])
        {
            *vc = p.warped(g, vg, *vc);
        }
    }
    // Step 6 along `c`, and the fine index entry.
    for ((&vg, vc), slot) in lanes.vg[..n]
        .iter()
        .zip(&mut lanes.vc[..n])
        .zip(&mut lanes.slot[..n])
    {
        *vc = p.position_c(*vc);
        *slot = if AVX2 {
            // An integer below `index.len() < 2³¹` (`fits_u32`).
            exact_u32(p.entry_f64([vg, *vc]))
        } else {
            p.entry_u32([vg, *vc])
        };
    }
    // Step 7: the cell from the index, the position in it, the rest of the descent.
    for ((vg, vc), slot) in lanes.vg[..n]
        .iter_mut()
        .zip(&mut lanes.vc[..n])
        .zip(&mut lanes.slot[..n])
    {
        let (leaf, [fg, fc]) = p.leaf_from(*slot as usize, [*vg, *vc]);
        // The leaf number `−link − 1` of an `i32` link is below 2³¹.
        *vg = fg;
        *vc = fc;
        *slot = leaf as u32;
    }
    // Step 8: the stencils (first node of the 4 × 4 block, weights), in a loop of their own
    // so that it is vectorized.
    let size = p.leaf_size() as f64;
    let [w0g, w1g, w2g, w3g, w0c, w1c, w2c, w3c] = &mut lanes.w;
    for (k, ((&fg, &fc), &leaf)) in lanes.vg[..n]
        .iter()
        .zip(&lanes.vc[..n])
        .zip(&lanes.slot[..n])
        .enumerate()
    {
        let (first, [wg, wc]) = if AVX2 {
            cubic_stencils_f64([fg, fc], p.n1() as f64)
        } else {
            let (first, w) = cubic_stencils_u32([fg, fc], p.n1() as u32);
            (f64::from(first), w)
        };
        [w0g[k], w1g[k], w2g[k], w3g[k]] = wg;
        [w0c[k], w1c[k], w2c[k], w3c[k]] = wc;
        // An integer below `(leaf + 1)·size ≤ p.len() < 2³¹` (`fits_u32`).
        lanes.start[k] = exact_u32(f64::from(leaf) * size + first);
    }
    // Step 9 and 10: the tensor product, bounded.
    let (vals, n1) = (p.p(), p.n1());
    let [w0g, w1g, w2g, w3g, w0c, w1c, w2c, w3c] = &lanes.w;
    for (k, (&start, &i)) in lanes.start[..n].iter().zip(list).enumerate() {
        let w = [
            [w0g[k], w1g[k], w2g[k], w3g[k]],
            [w0c[k], w1c[k], w2c[k], w3c[k]],
        ];
        out[i as usize] = bound_p(cubic_sum(vals, start as usize, n1, &w));
    }
}

impl Accel<2> {
    /// `out[i] = P(gamma[i], alpha[i])` ([`Accel::eval_with`] for each `i`, the same bits),
    /// in chunks of [`BATCH`] queries sorted by region first: the full-slip line is answered in
    /// the classifying pass, then each patch's queries in passes of their own, so that the
    /// branches on the region (random in a mixed stream) are not mispredicted per query. A
    /// chunk with an invalid query, or one outside the domain without clamping, is answered
    /// query by query, so the error is the first one's and `out` after it stays untouched.
    pub(crate) fn eval_batch(
        &self,
        surface: &Surface,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        self.eval_batch_on(true, surface, gamma, alpha, out, outside)
    }

    /// [`Accel::eval_batch`], with the AVX2 build of the passes if `avx2` and the processor
    /// has it (detected at run time), else the baseline x86-64 (or other target's) build.
    /// Both give the same bits; the tests run both.
    pub(super) fn eval_batch_on(
        &self,
        avx2: bool,
        surface: &Surface,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        if !self.batch_u32 {
            return self.eval_each(surface, gamma, alpha, out, outside, 0);
        }
        #[cfg(target_arch = "x86_64")]
        if avx2 && std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.eval_chunks_avx2(surface, gamma, alpha, out, outside) };
        }
        let _ = avx2;
        self.eval_chunks::<false>(surface, gamma, alpha, out, outside)
    }

    /// [`Accel::eval_chunks`] compiled for AVX2 (the same operations, so the same bits).
    ///
    /// # Safety
    /// The processor must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn eval_chunks_avx2(
        &self,
        surface: &Surface,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        self.eval_chunks::<true>(surface, gamma, alpha, out, outside)
    }

    /// [`Accel::eval_with`] query by query (`first`: the index of `gamma[0]` in the batch).
    fn eval_each(
        &self,
        surface: &Surface,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
        first: usize,
    ) -> Result<(), (usize, LookupError)> {
        for (i, ((o, &g), &a)) in out.iter_mut().zip(gamma).zip(alpha).enumerate() {
            *o = self
                .eval_with(surface, g, a, outside)
                .map_err(|e| (first + i, e))?;
        }
        Ok(())
    }

    /// The passes of [`Accel::eval_batch`] over each chunk; `AVX2`: the formulation for the
    /// AVX2 build (only instantiated inside [`Accel::eval_chunks_avx2`]).
    #[inline(always)]
    fn eval_chunks<const AVX2: bool>(
        &self,
        surface: &Surface,
        gamma: &[f64],
        alpha: &[f64],
        out: &mut [f64],
        outside: OutOfDomain,
    ) -> Result<(), (usize, LookupError)> {
        let mut code = [0u8; BATCH];
        // Query numbers (within the chunk) per class: 0 the line (unused), 1–3 a patch
        // (stick_low, partial_high, stick_high), 4 outside the domain (clamped).
        let mut lists = [[0u16; BATCH]; 5];
        let mut lanes = Lanes::new();
        let clamp = outside == OutOfDomain::Clamp;
        let outside_code = 4 + u8::from(!clamp);
        for (k, ((g, a), o)) in gamma
            .chunks(BATCH)
            .zip(alpha.chunks(BATCH))
            .zip(out.chunks_mut(BATCH))
            .enumerate()
        {
            let len = g.len().min(a.len()).min(o.len());
            let (g, a, o) = (&g[..len], &a[..len], &mut o[..len]);
            // Pass 1, branch-free: 0 line, 1–3 a patch, 4 outside (clamped), 5 refused.
            for ((c, &gi), &ai) in code[..len].iter_mut().zip(g).zip(a) {
                let valid = (gi.abs() < f64::INFINITY) & (gi > 0.0) & (ai >= 0.0);
                let region = Region::code_of(gi, ai);
                let inside =
                    (gi >= self.gamma_min) & (gi <= self.gamma_max) & (ai <= self.alpha_max);
                let r = if inside | (region == 0) {
                    region
                } else {
                    outside_code
                };
                *c = if valid { r } else { 5 };
            }
            if code[..len].iter().fold(false, |r, &c| r | (c == 5)) {
                self.eval_each(surface, g, a, o, outside, k * BATCH)?;
                continue;
            }
            // Pass 2: the line everywhere (the patches overwrite theirs), and the lists.
            for (o, &ai) in o.iter_mut().zip(a) {
                *o = full_slip_line(ai, 1.0);
            }
            let mut counts = [0usize; 5];
            for (i, &c) in code[..len].iter().enumerate() {
                let l = usize::from(c).min(4);
                lists[l][counts[l] & (BATCH - 1)] = i as u16;
                counts[l] += 1;
            }
            // Pass 3: each patch's queries.
            for (l, patch) in self.patches.iter().enumerate() {
                let n = counts[l + 1];
                let list = &lists[l + 1][..n];
                let Some(p) = patch else {
                    for &i in list {
                        o[i as usize] = -1.0;
                    }
                    continue;
                };
                for ((lg, la), &i) in lanes.g[..n].iter_mut().zip(&mut lanes.a[..n]).zip(list) {
                    *lg = g[i as usize];
                    *la = a[i as usize];
                }
                match p.kind() {
                    PatchKind::PartialSlip => partial_coords(&mut lanes, n),
                    PatchKind::Stick => stick_coords(&mut lanes, n, self.alpha_max),
                }
                interpolate_lanes::<AVX2>(p, &mut lanes, n, list, o);
            }
            for &i in &lists[4][..counts[4]] {
                let i = i as usize;
                o[i] = self
                    .eval_with(surface, g[i], a[i], outside)
                    .map_err(|e| (k * BATCH + i, e))?;
            }
        }
        Ok(())
    }
}

/// `lanes.vc[k] =` [`partial_coord`](oblique_table::surface::partial_coord)`(g[k], a[k])`,
/// through its parts in passes of their own (the logarithms apart, so that the rest is
/// vectorized).
#[inline(always)]
fn partial_coords(lanes: &mut Lanes, n: usize) {
    for (((x, r), &g), &a) in lanes.x[..n]
        .iter_mut()
        .zip(&mut lanes.r[..n])
        .zip(&lanes.g[..n])
        .zip(&lanes.a[..n])
    {
        let (ratio, two_g2) = partial_ratio(g);
        *x = partial_arg(a, ratio, two_g2);
        *r = ratio;
    }
    for (x, r) in lanes.x[..n].iter_mut().zip(&mut lanes.r[..n]) {
        *x = x.ln();
        *r = r.ln();
    }
    for ((c, &x), &r) in lanes.vc[..n]
        .iter_mut()
        .zip(&lanes.x[..n])
        .zip(&lanes.r[..n])
    {
        *c = PartialMap::SqrtEnd.c_of_l(x / r);
    }
}

/// `lanes.vc[k] =` [`stick_coord`](oblique_table::surface::stick_coord)`(g[k], a[k],
/// alpha_max)`: its parts, branch-free.
#[inline(always)]
fn stick_coords(lanes: &mut Lanes, n: usize, alpha_max: f64) {
    for ((c, &g), &a) in lanes.vc[..n]
        .iter_mut()
        .zip(&lanes.g[..n])
        .zip(&lanes.a[..n])
    {
        let (c2, rho_c2, s_max) = stick_parts(g, alpha_max);
        *c = stick_coord_from(a, c2, rho_c2, s_max);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::tests::{points, table};
    use crate::fast::MAX_INDEX_ENTRIES;
    use crate::Table;
    use oblique_table::surface::{alpha_c1, alpha_c2};

    /// [`points`] plus the edges of the rule: γ = 1 and its neighbours, the domain's and the
    /// patches' γ edges and root-cell edges, and at each of these γ: α on and next to α_c1 and
    /// α_c2 (the patch boundaries), α = 0, tiny, huge, `alpha_max`, ∞; and points outside the
    /// domain (refused, or clamped).
    fn edge_points(t: &Table) -> Vec<(f64, f64)> {
        let s = &t.surface();
        let mut gammas = vec![
            1.0,
            1f64.next_up(),
            1f64.next_down(),
            s.gamma_min(),
            s.gamma_max(),
            s.gamma_min().next_down(),
            s.gamma_max().next_up(),
            0.5 * s.gamma_min(),
            2.0 * s.gamma_max(),
        ];
        for patch in s.patches().map(|(_, p)| p) {
            for i in 0..=patch.blocks_gamma() {
                let g = patch.gamma_lo()
                    + (patch.gamma_hi() - patch.gamma_lo()) * i as f64
                        / patch.blocks_gamma() as f64;
                gammas.extend([g, g.next_up(), g.next_down()]);
            }
        }
        let mut pts = points(t);
        for &g in &gammas {
            let (c1, c2) = (alpha_c1(g), alpha_c2(g));
            for a in [
                c1,
                c1.next_up(),
                c1.next_down(),
                c2,
                c2.next_up(),
                c2.next_down(),
                0.5 * (c1 + c2),
                0.0,
                5e-324,
                1e-300,
                1.0,
                1e300,
                f64::MAX,
                s.alpha_max(),
                f64::INFINITY,
            ] {
                // (α_c1 < 0 for γ < 1/√2: not a query.)
                if a >= 0.0 {
                    pts.push((g, a));
                }
            }
        }
        pts
    }

    /// `out` of [`Accel::eval_batch_on`] (`None` and `out` untouched on an error), and the
    /// error's index.
    fn run(
        accel: &Accel<2>,
        s: &Surface,
        avx2: bool,
        g: &[f64],
        a: &[f64],
        outside: OutOfDomain,
    ) -> (Vec<f64>, Option<usize>) {
        let mut out = vec![f64::NAN; g.len()];
        let r = accel.eval_batch_on(avx2, s, g, a, &mut out, outside);
        (out, r.err().map(|(i, _)| i))
    }

    #[test]
    fn both_builds_give_the_bits_of_the_rule() {
        #[cfg(target_arch = "x86_64")]
        if !std::is_x86_feature_detected!("avx2") {
            eprintln!("no AVX2 on this processor: only the baseline build is tested");
        }
        for name in ["quick.h5", "isotropic.h5", "full.h5"] {
            let t = table(name);
            let s = &t.surface();
            let pts = edge_points(&t);
            let (g, a): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
            // Full index depth, and a capped one from which the descent continues.
            for budget in [MAX_INDEX_ENTRIES, 64] {
                let accel = Accel::<2>::with_budget(s, budget).expect("cubic table");
                assert!(accel.batch_u32);
                for avx2 in [false, true] {
                    let (out, err) = run(&accel, s, avx2, &g, &a, OutOfDomain::Clamp);
                    if let Some(i) = err {
                        let rule = s.eval_with(g[i], a[i], OutOfDomain::Clamp);
                        panic!("{name}: clamped, ({}, {}): {rule:?}", g[i], a[i]);
                    }
                    for i in 0..g.len() {
                        let rule = s.eval_with(g[i], a[i], OutOfDomain::Clamp);
                        let rule = rule.map(f64::to_bits).ok();
                        assert_eq!(
                            Some(out[i].to_bits()),
                            rule,
                            "{name}, budget {budget}, avx2 {avx2}: ({}, {})",
                            g[i],
                            a[i]
                        );
                    }
                    // Without clamping: the queries the rule answers, then one it refuses
                    // (first, inside a chunk, last).
                    let inside: Vec<(f64, f64)> = pts
                        .iter()
                        .copied()
                        .filter(|&(g, a)| s.eval(g, a).is_ok())
                        .collect();
                    let (gi, ai): (Vec<f64>, Vec<f64>) = inside.iter().copied().unzip();
                    let (out, err) = run(&accel, s, avx2, &gi, &ai, OutOfDomain::Error);
                    assert_eq!(err, None);
                    for i in 0..gi.len() {
                        let rule = s.eval(gi[i], ai[i]).map(f64::to_bits).ok();
                        assert_eq!(Some(out[i].to_bits()), rule, "({}, {})", gi[i], ai[i]);
                    }
                    let refused = [(2.0 * s.gamma_max(), 1.0), (1.5, f64::NAN), (-1.0, 1.0)];
                    for (at, bad) in [0, 777, gi.len() - 1].into_iter().zip(refused) {
                        let (mut gb, mut ab) = (gi.clone(), ai.clone());
                        (gb[at], ab[at]) = bad;
                        for outside in [OutOfDomain::Error, OutOfDomain::Clamp] {
                            let rule_err = s.eval_with(bad.0, bad.1, outside).is_err();
                            let (out_b, err) = run(&accel, s, avx2, &gb, &ab, outside);
                            if !rule_err {
                                assert_eq!(err, None);
                                continue;
                            }
                            assert_eq!(err, Some(at), "{name}: {bad:?}");
                            assert_eq!(out_b[..at], out[..at]);
                            assert!(out_b[at..].iter().all(|p| p.is_nan()), "untouched");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn both_builds_bound_p_where_the_tensor_product_overshoots() {
        // Node values of full.h5 replaced by noise next to −1 (even leaves) and +1 (odd): the
        // tensor product overshoots ±1 at most points, step 10 bounds it on both builds.
        let mut next = crate::testing::uniform(5);
        let t = crate::testing::overshooting(table("full.h5"), |_| 0.1 * next());
        let s = &t.surface();
        let pts = crate::testing::domain_points(s, 100_000, 17);
        let (g, a): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
        let accel = Accel::<2>::new(s).expect("cubic table");
        for avx2 in [false, true] {
            let (out, err) = run(&accel, s, avx2, &g, &a, OutOfDomain::Error);
            assert_eq!(err, None);
            for i in 0..g.len() {
                assert!(
                    out[i].abs() <= 1.0,
                    "avx2 {avx2}: ({}, {}): {}",
                    g[i],
                    a[i],
                    out[i]
                );
                let rule = s.eval(g[i], a[i]).map(f64::to_bits).ok();
                assert_eq!(Some(out[i].to_bits()), rule, "({}, {})", g[i], a[i]);
            }
        }
    }
}
