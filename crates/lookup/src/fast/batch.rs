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

use super::{alpha_c1_of, Accel, FastPatch, BATCH};
use crate::LookupError;
use oblique_table::surface::{bound_p, cubic_weights, OutOfDomain, PatchKind, Surface};

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

/// `min(floor(u), max)` for `u ≥ 0`, `0` for `u < 0` or NaN, for `max < 2³¹`: the same as
/// `fast::floor_index`, through a 32-bit conversion (which vector units have): `as i32`
/// saturates, so `u ≥ 2³¹` gives `i32::MAX`, then `max`, as the 64-bit conversion does.
#[inline(always)]
fn floor_index32(u: f64, max: u32) -> u32 {
    ((u as i32).max(0) as u32).min(max)
}

/// [`floor_index32`] in floating point (`max` an integer below 2³¹), for a vector unit that
/// truncates (SSE4.1 `roundpd`): `max(u, 0)` is `0` for NaN and negative `u` (where the integer
/// conversion gives a value `≤ 0`, then `0`), and for `u ≥ 0` truncating and taking the minimum
/// with an integer commute.
#[inline(always)]
fn floor_f64(u: f64, max: f64) -> f64 {
    u.max(0.0).min(max).trunc()
}

/// `x` as `u32`, for an integer `0 ≤ x < 2³²`: `2⁵² + x` is exact and its significand's low 32
/// bits are `x` (a bit cast, which vector units do, where a saturating conversion is several
/// instructions per value).
#[inline(always)]
fn exact_u32(x: f64) -> u32 {
    (x + 4_503_599_627_370_496.0).to_bits() as u32
}

/// [`oblique_table::surface::stencil4`] with [`floor_index32`] (`n ≤ 2³¹`): the same start and weights.
#[inline(always)]
fn stencil4_32(u: f64, n: u32) -> (u32, [f64; 4]) {
    let cell = floor_index32(u, n - 2);
    let start = cell.saturating_sub(1).min(n - 4);
    (start, cubic_weights(u - f64::from(start)))
}

/// [`stencil4_32`] in floating point: the same start (as a float) and weights. The cell is
/// [`floor_f64`]; `start = min(max(cell − 1, 0), n − 4)` is the saturating subtraction.
#[inline(always)]
fn stencil4_f64(u: f64, n: f64) -> (f64, [f64; 4]) {
    let cell = floor_f64(u, n - 2.0);
    let start = (cell - 1.0).max(0.0).min(n - 4.0);
    (start, cubic_weights(u - start))
}

impl FastPatch {
    /// Whether the batch path can use 32-bit positions for this patch (always for shipped
    /// tables: the fine index, the node array and the leaf grid are far below 2³¹ entries),
    /// and every leaf the quadtree names has its whole node grid in `p`, so that the first
    /// node of any 4 × 4 block is an integer below `p.len() < 2³¹` (see [`exact_u32`]).
    pub(super) fn fits_u32(&self) -> bool {
        let small = |n: usize| n < (1 << 31);
        let leaves_end = self
            .cells
            .iter()
            .filter(|c| c.link < 0)
            .map(|c| (-(c.link as i64)) as usize)
            .max()
            .unwrap_or(0);
        small(self.index.len())
            && small(self.p.len())
            && small(self.n1)
            && small(self.rows)
            && leaves_end
                .checked_mul(self.size)
                .is_some_and(|e| e <= self.p.len())
    }

    /// `out[list[k]] = self.interpolate(γ_k, c_k)` for the `n` queries gathered in `lanes`
    /// whose patch coordinates `c_k` are in `lanes.vc` (not yet clamped).
    #[inline(always)]
    fn interpolate_lanes<const AVX2: bool>(
        &self,
        lanes: &mut Lanes,
        n: usize,
        list: &[u16],
        out: &mut [f64],
    ) {
        let (rows1, cols1) = (self.rows as u32 - 1, self.cols as u32 - 1);
        let cols = self.cols as u32;
        // Step 5: `v = x·blocks`, clamped, and the clamped coordinate.
        for ((vg, vc), &g) in lanes.vg[..n]
            .iter_mut()
            .zip(&mut lanes.vc[..n])
            .zip(&lanes.g[..n])
        {
            let xg = (g - self.gamma_lo) / self.width;
            *vg = (xg * self.bg).clamp(0.0, self.bg);
            *vc = vc.clamp(0.0, 1.0);
        }
        // The warp from its start on (`Patch::warped`, the same operations).
        if let Some(w) = &self.warp {
            for ((&vg, vc), &g) in lanes.vg[..n]
                .iter()
                .zip(&mut lanes.vc[..n])
                .zip(&lanes.g[..n])
            {
                if vg >= w.start() {
                    *vc = w.apply(g, *vc);
                }
            }
        }
        // The fine index entry.
        for ((&vg, vc), slot) in lanes.vg[..n]
            .iter()
            .zip(&mut lanes.vc[..n])
            .zip(&mut lanes.slot[..n])
        {
            *vc = (*vc * self.bc).clamp(0.0, self.bc);
            *slot = if AVX2 {
                let ig = floor_f64(vg * self.fine, f64::from(rows1));
                let ic = floor_f64(*vc * self.fine, f64::from(cols1));
                // An integer below `rows·cols = index.len() < 2³¹`.
                exact_u32(ig * f64::from(cols) + ic)
            } else {
                let ig = floor_index32(vg * self.fine, rows1);
                let ic = floor_index32(*vc * self.fine, cols1);
                ig * cols + ic
            };
        }
        // Step 6: the cell from the index, the position in it, the rest of the descent.
        for ((vg, vc), slot) in lanes.vg[..n]
            .iter_mut()
            .zip(&mut lanes.vc[..n])
            .zip(&mut lanes.slot[..n])
        {
            let (leaf, fg, fc) = self.leaf_from(*slot as usize, *vg, *vc);
            // The leaf number `−link − 1` of an `i32` link is below 2³¹.
            *vg = fg;
            *vc = fc;
            *slot = leaf as u32;
        }
        // Step 7: the stencils (first node of the 4 × 4 block, weights), in a loop of their
        // own so that it is vectorized.
        let [w0g, w1g, w2g, w3g, w0c, w1c, w2c, w3c] = &mut lanes.w;
        for (k, ((&fg, &fc), &leaf)) in lanes.vg[..n]
            .iter()
            .zip(&lanes.vc[..n])
            .zip(&lanes.slot[..n])
            .enumerate()
        {
            let ((sg, wg), (sc, wc)) = if AVX2 {
                let n1 = self.n1 as f64;
                (stencil4_f64(fg * self.m, n1), stencil4_f64(fc * self.m, n1))
            } else {
                let n1 = self.n1 as u32;
                let (sg, wg) = stencil4_32(fg * self.m, n1);
                let (sc, wc) = stencil4_32(fc * self.m, n1);
                ((f64::from(sg), wg), (f64::from(sc), wc))
            };
            [w0g[k], w1g[k], w2g[k], w3g[k]] = wg;
            [w0c[k], w1c[k], w2c[k], w3c[k]] = wc;
            // An integer below `(leaf + 1)·size ≤ p.len() < 2³¹` (`fits_u32`).
            let start = f64::from(leaf) * self.size as f64 + (sg * self.n1 as f64 + sc);
            lanes.start[k] = exact_u32(start);
        }
        // Step 8: the tensor product.
        let stride = self.n1;
        let [w0g, w1g, w2g, w3g, w0c, w1c, w2c, w3c] = &lanes.w;
        for (k, (&start, &i)) in lanes.start[..n].iter().zip(list).enumerate() {
            let start = start as usize;
            let block = &self.p[start..start + 3 * stride + 4];
            let (r0, rest) = block.split_at(stride);
            let (r1, rest) = rest.split_at(stride);
            let (r2, r3) = rest.split_at(stride);
            let (wc0, wc1, wc2, wc3) = (w0c[k], w1c[k], w2c[k], w3c[k]);
            let row = |r: &[f64]| r[0] * wc0 + r[1] * wc1 + r[2] * wc2 + r[3] * wc3;
            out[i as usize] =
                bound_p(w0g[k] * row(r0) + w1g[k] * row(r1) + w2g[k] * row(r2) + w3g[k] * row(r3));
        }
    }
}

impl Accel {
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
                let g2 = gi * gi;
                // `surface::alpha_c2` and `surface::linear_limit`, the same operations.
                let c2 = 2.0 * gi * gi / 7.0;
                let hi = gi > 1.0;
                let lin = if hi { alpha_c1_of(g2) } else { c2 };
                let line = ai <= lin;
                let patch = 1 + u8::from(hi) + u8::from(hi & (ai >= c2));
                let inside =
                    (gi >= self.gamma_min) & (gi <= self.gamma_max) & (ai <= self.alpha_max);
                let r = if inside { patch } else { outside_code };
                let r = if line { 0 } else { r };
                *c = if valid { r } else { 5 };
            }
            if code[..len].iter().fold(false, |r, &c| r | (c == 5)) {
                self.eval_each(surface, g, a, o, outside, k * BATCH)?;
                continue;
            }
            // Pass 2: the line everywhere (the patches overwrite theirs), and the lists.
            for (o, &ai) in o.iter_mut().zip(a) {
                *o = 1.0 - 7.0 * ai;
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
                match p.kind {
                    PatchKind::PartialSlip => partial_coords(&mut lanes, n),
                    PatchKind::Stick => stick_coords(&mut lanes, n, self.alpha_max),
                }
                p.interpolate_lanes::<AVX2>(&mut lanes, n, list, o);
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

/// `lanes.vc[k] =` [`oblique_table::surface::partial_coord`]`(g[k], a[k])`, the same operations.
#[inline(always)]
fn partial_coords(lanes: &mut Lanes, n: usize) {
    for (((x, r), &g), &a) in lanes.x[..n]
        .iter_mut()
        .zip(&mut lanes.r[..n])
        .zip(&lanes.g[..n])
        .zip(&lanes.a[..n])
    {
        let g2 = 2.0 * g * g;
        let ratio = g2 - 1.0;
        *x = 7.0 * a * ratio / g2;
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
        let l = x / r;
        *c = 1.0 - (1.0 - l).max(0.0).sqrt();
    }
}

/// `lanes.vc[k] =` [`oblique_table::surface::stick_coord`]`(g[k], a[k], alpha_max)`, the same
/// operations, branch-free.
#[inline(always)]
fn stick_coords(lanes: &mut Lanes, n: usize, alpha_max: f64) {
    let lanes_iter = lanes.vc[..n]
        .iter_mut()
        .zip(&lanes.g[..n])
        .zip(&lanes.a[..n]);
    let finite_max = !alpha_max.is_infinite();
    for ((c, &g), &a) in lanes_iter {
        let c2 = g * g * (2.0 / 7.0);
        let rho = if g < 1.0 { 2.0 * (1.0 - g * g) } else { 1.0 };
        let d = a - c2;
        let s = d / (d + rho * c2);
        let s = if finite_max {
            let dm = alpha_max - c2;
            s / (dm / (dm + rho * c2))
        } else {
            s
        };
        *c = if a == f64::INFINITY { 1.0 } else { s };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::tests::{points, table};
    use crate::fast::{floor_index, MAX_INDEX_ENTRIES};
    use crate::Table;
    use oblique_table::surface::{alpha_c1, alpha_c2, stencil4};

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
        accel: &Accel,
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
                let accel = Accel::with_budget(s, budget).expect("cubic table");
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
        let accel = Accel::new(s).expect("cubic table");
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

    #[test]
    fn exact_u32_converts_integers() {
        for x in [0u32, 1, 2, 255, 65_536, (1 << 31) - 1, 1 << 31, u32::MAX] {
            assert_eq!(exact_u32(f64::from(x)), x);
        }
    }

    #[test]
    fn the_vector_stencils_are_the_rules() {
        let mut us = vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            -1e-300,
            1e300,
            -3.5,
            4e9,
        ];
        for k in 0..=40 {
            let u = f64::from(k) * 0.25;
            us.extend([u, u.next_up(), u.next_down()]);
        }
        for n in [4u32, 5, 9, 17] {
            for &u in &us {
                let (s32, w32) = stencil4_32(u, n);
                let (s64, w64) = stencil4_f64(u, f64::from(n));
                let (s, w) = stencil4(u, n as usize);
                assert_eq!((s32 as usize, f64::from(s32)), (s, s64), "u = {u}, n = {n}");
                for j in 0..4 {
                    let bits = [w32[j], w64[j], w[j]].map(|x| (x.is_nan(), x.to_bits()));
                    let same = |x: (bool, u64)| x == bits[2] || (x.0 && bits[2].0);
                    assert!(same(bits[0]) && same(bits[1]), "u = {u}, n = {n}: {bits:?}");
                }
                for max in [0u32, 1, 7, 1 << 20] {
                    let f = floor_index32(u, max);
                    assert_eq!(f as usize, floor_index(u, max as usize));
                    let f64_path = floor_f64(u, f64::from(max));
                    assert_eq!(
                        (f64_path, exact_u32(f64_path)),
                        (f64::from(f), f),
                        "u = {u}"
                    );
                }
            }
        }
    }
}
