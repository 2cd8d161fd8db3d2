//! Steps 6 to 9 of the interpolation rule (`docs/table-format.md`), once for a tree over any
//! number of axes: the root cell and the descent ([`locate`], [`descend`]), the stencils
//! ([`stencil`], [`stencil4`], [`cubic_weights`]) and the tensor product of a leaf
//! ([`cubic_tensor`], [`cubic_sum`], [`lagrange_tensor`]). A patch of an elastic table is a
//! quadtree over `(γ, c)` (`D = 2`), a patch of a table with an `e_n` axis an octree over
//! `(γ, c, e_n)` (`D = 3`); both run these functions, and so do the rule
//! ([`crate::surface::Patch`]), the indexed query path ([`crate::indexed::IndexedPatch`]) and
//! the batch and curve paths of `oblique-lookup`.
//!
//! The vector formulations ([`stencil4_u32`], [`stencil4_f64`], [`floor_f64`], [`exact_u32`])
//! are the same operations written as vector units take them (32-bit conversions, the floor by
//! truncation in floating point), with the same results (tested here).

/// Axes a tree can have at most (2: `γ`, `c`; 3: and `e_n`; one more fits).
pub const MAX_AXES: usize = 4;

/// `min(floor(u), max)` for `u ≥ 0` (`0` for `u < 0` or NaN): `as i64` truncates with one
/// instruction plus saturation, where `floor` is a library call on baseline x86-64.
#[inline(always)]
pub fn floor_index(u: f64, max: usize) -> usize {
    ((u as i64).max(0) as usize).min(max)
}

/// [`floor_index`] through a 32-bit conversion (which vector units have), for `max < 2³¹`:
/// `as i32` saturates, so `u ≥ 2³¹` gives `i32::MAX`, then `max`, as the 64-bit conversion does.
#[inline(always)]
pub fn floor_index32(u: f64, max: u32) -> u32 {
    ((u as i32).max(0) as u32).min(max)
}

/// [`floor_index32`] in floating point (`max` an integer below 2³¹), for a vector unit that
/// truncates (SSE4.1 `roundpd`): `max(u, 0)` is `0` for NaN and negative `u` (where the integer
/// conversion gives a value `≤ 0`, then `0`), and for `u ≥ 0` truncating and taking the minimum
/// with an integer commute.
#[inline(always)]
pub fn floor_f64(u: f64, max: f64) -> f64 {
    u.max(0.0).min(max).trunc()
}

/// `x` as `u32`, for an integer `0 ≤ x < 2³²`: `2⁵² + x` is exact and its significand's low 32
/// bits are `x` (a bit cast, which vector units do, where a saturating conversion is several
/// instructions per value).
#[inline(always)]
pub fn exact_u32(x: f64) -> u32 {
    (x + 4_503_599_627_370_496.0).to_bits() as u32
}

/// Step 6 per axis: root cell and position inside it (in `[0, 1]`) of a patch coordinate
/// `x ∈ [0, 1]` over `blocks` root cells.
#[inline]
pub fn locate(x: f64, blocks: usize) -> (usize, f64) {
    let u = (x * blocks as f64).clamp(0.0, blocks as f64);
    let a = floor_index(u, blocks - 1);
    (a, u - a as f64)
}

/// One step of the descent (step 7): each position `f[k]` doubled, `q_k = 1` where it reaches
/// 1 (then 1 subtracted); returns the child's offset `Σ q_k·2^(D−1−k)` from the first child
/// (`2·q_γ + q_c`, or `4·q_γ + 2·q_c + q_e`). All exact in binary floating point.
#[inline(always)]
pub fn descend<const D: usize>(f: &mut [f64; D]) -> usize {
    let mut child = 0;
    for x in f.iter_mut() {
        *x *= 2.0;
        let q = usize::from(*x >= 1.0);
        *x -= q as f64;
        child = 2 * child + q;
    }
    child
}

/// [`descend`] along the axes of `mask` only (bit `D − 1 − k` for axis `k`; a tree whose
/// cells halve different axes, [`crate::surface::check_split`]): the other positions are
/// unchanged, and the child's offset is `Σ q_k·2^j` over the halved axes, numbered row-major
/// in axis order. With every bit set it is [`descend`].
#[inline(always)]
pub fn descend_masked<const D: usize>(f: &mut [f64; D], mask: u8) -> usize {
    let mut child = 0;
    for (k, x) in f.iter_mut().enumerate() {
        if mask >> (D - 1 - k) & 1 == 1 {
            *x *= 2.0;
            let q = usize::from(*x >= 1.0);
            *x -= q as f64;
            child = 2 * child + q;
        }
    }
    child
}

/// Start index and weights of the `k`-point Lagrange stencil at grid position `u` (in units of
/// the node spacing, node `i` at `u = i`) on `n` nodes. Weights are written to `w[..k']` where
/// `k' = min(k, n)` is returned with the start.
#[inline]
pub fn stencil(u: f64, n: usize, k: usize, w: &mut [f64; 8]) -> (usize, usize) {
    let k = k.min(n).min(8);
    // `as usize` truncates towards zero and saturates (NaN → 0): the floor for `u ≥ 0`, without
    // a call to `floor` (not an instruction on baseline x86-64).
    let cell = (u.max(0.0) as usize).min(n - 2);
    let start = (cell + 1).saturating_sub(k / 2).min(n - k);
    for (j, wj) in w.iter_mut().enumerate().take(k) {
        let mut prod = 1.0;
        for m in 0..k {
            if m != j {
                prod *= (u - (start + m) as f64) / (j as f64 - m as f64);
            }
        }
        *wj = prod;
    }
    (start, k)
}

/// [`stencil`] for `k = 4` on `n ≥ 4` nodes (cubic Lagrange): start index and the four
/// weights, from the closed forms of the cubic basis on nodes `0, 1, 2, 3` at `t = u − start`.
#[inline(always)]
pub fn stencil4(u: f64, n: usize) -> (usize, [f64; 4]) {
    let cell = floor_index(u, n - 2);
    let start = cell.saturating_sub(1).min(n - 4);
    (start, cubic_weights(u - start as f64))
}

/// [`stencil4`] with [`floor_index32`] (`n ≤ 2³¹`): the same start and weights.
#[inline(always)]
pub fn stencil4_u32(u: f64, n: u32) -> (u32, [f64; 4]) {
    let cell = floor_index32(u, n - 2);
    let start = cell.saturating_sub(1).min(n - 4);
    (start, cubic_weights(u - f64::from(start)))
}

/// [`stencil4_u32`] in floating point: the same start (as a float) and weights. The cell is
/// [`floor_f64`]; `start = min(max(cell − 1, 0), n − 4)` is the saturating subtraction.
#[inline(always)]
pub fn stencil4_f64(u: f64, n: f64) -> (f64, [f64; 4]) {
    let cell = floor_f64(u, n - 2.0);
    let start = (cell - 1.0).max(0.0).min(n - 4.0);
    (start, cubic_weights(u - start))
}

/// The cubic Lagrange weights on nodes `0, 1, 2, 3` at `a` (the one statement of these
/// operations, shared by every path that must give the rule's bits).
#[inline(always)]
pub fn cubic_weights(a: f64) -> [f64; 4] {
    let (b, c, d) = (a - 1.0, a - 2.0, a - 3.0);
    let (ab, cd) = (a * b, c * d);
    [
        -(b * cd) * (1.0 / 6.0),
        a * cd * 0.5,
        -(ab * d) * 0.5,
        ab * c * (1.0 / 6.0),
    ]
}

/// Step 9 for the cubic stencil: the sum over the `4^D` block of a leaf's nodes whose first
/// node is `vals[first]` (`vals` the leaf's or the patch's node values, `n1 = m + 1` nodes per
/// axis, the last axis innermost), with the weights `w[k]` along axis `k`. The rows along the
/// last axis first (`v₀·w₀ + … + v₃·w₃`), then each further axis outwards
/// (`w₀·r₀ + … + w₃·r₃`), each sum from left to right: a running sum per axis, which a row
/// completes when its index along that axis is the last (no array of `4^(D−1)` rows). Three
/// axes are summed unrolled ([`cubic_sum3`], the same operations).
#[inline(always)]
pub fn cubic_sum<const D: usize>(vals: &[f64], first: usize, n1: usize, w: &[[f64; 4]; D]) -> f64 {
    if D == 3 {
        return cubic_sum3(vals, first, n1, std::array::from_fn(|k| w[k]));
    }
    // Node offset of one step along each axis: n1^(D − 1 − k).
    let mut stride = [1usize; D];
    for k in (0..D.saturating_sub(1)).rev() {
        stride[k] = stride[k + 1] * n1;
    }
    let last = &w[D - 1];
    let mut running = [0.0; MAX_AXES];
    let mut total = 0.0;
    for r in 0..1usize << (2 * (D - 1)) {
        // The row's index along axis k (of the D − 1 outer axes) is digit D − 2 − k of r.
        let digit = |k: usize| (r >> (2 * (D - 2 - k))) & 3;
        let mut off = 0;
        for (k, &sk) in stride.iter().enumerate().take(D - 1) {
            off += digit(k) * sk;
        }
        let v = &vals[first + off..][..4];
        let mut x = v[0] * last[0] + v[1] * last[1] + v[2] * last[2] + v[3] * last[3];
        // Into the running sums, innermost axis first, as far as the row completes them.
        let mut carry = true;
        for k in (0..D - 1).rev() {
            if carry {
                let d = digit(k);
                let term = w[k][d] * x;
                running[k] = if d == 0 { term } else { running[k] + term };
                carry = d == 3;
                x = running[k];
            }
        }
        total = x;
    }
    total
}

/// [`cubic_sum`] of three axes written out (the same operations in the same order): the 16
/// rows along `e_n`, each `v₀·w₀ + … + v₃·w₃`; per `γ` index the plane `w₀·r₀ + … + w₃·r₃`
/// over `c`; then the planes over `γ`. Unrolled, the rows are independent of each other (no
/// running sums to carry), and the block is bounds-checked once per plane.
#[inline(always)]
fn cubic_sum3(vals: &[f64], first: usize, n1: usize, w: [[f64; 4]; 3]) -> f64 {
    let [wg, wc, we] = w;
    let s0 = n1 * n1;
    let len = 3 * n1 + 4;
    let p0 = sum_plane(&vals[first..][..len], n1, &wc, &we);
    let p1 = sum_plane(&vals[first + s0..][..len], n1, &wc, &we);
    let p2 = sum_plane(&vals[first + 2 * s0..][..len], n1, &wc, &we);
    let p3 = sum_plane(&vals[first + 3 * s0..][..len], n1, &wc, &we);
    weigh4(&wg, [p0, p1, p2, p3])
}

/// One plane of [`cubic_sum3`] (a fixed `γ` index): `b` its nodes from the first, the rows
/// `j·n1 .. j·n1 + 4` for `j < 4`.
#[inline(always)]
fn sum_plane(b: &[f64], n1: usize, wc: &[f64; 4], we: &[f64; 4]) -> f64 {
    let r0 = sum_row(&b[..4], we);
    let r1 = sum_row(&b[n1..][..4], we);
    let r2 = sum_row(&b[2 * n1..][..4], we);
    let r3 = sum_row(&b[3 * n1..][..4], we);
    weigh4(wc, [r0, r1, r2, r3])
}

/// `w₀·x₀ + w₁·x₁ + w₂·x₂ + w₃·x₃`, from the left: one outer level of [`cubic_sum3`] (a plane's
/// rows over `c`, the planes over `γ`), and of the line of a pair ([`crate::line`]).
#[inline(always)]
pub(crate) fn weigh4(w: &[f64; 4], x: [f64; 4]) -> f64 {
    w[0] * x[0] + w[1] * x[1] + w[2] * x[2] + w[3] * x[3]
}

/// `v₀·w₀ + v₁·w₁ + v₂·w₂ + v₃·w₃`, from the left.
#[inline(always)]
pub(crate) fn sum_row(v: &[f64], w: &[f64; 4]) -> f64 {
    v[0] * w[0] + v[1] * w[1] + v[2] * w[2] + v[3] * w[3]
}

/// [`cubic_tensor`] of three axes, the same bits, with 256-bit vectors where the processor
/// has AVX (checked at run time unless the build enables it): [`cubic_tensor3_avx`], else the
/// scalar [`cubic_tensor`]. The query path of a table with an `e_n` axis
/// ([`crate::indexed::IndexedPatch::at`]) calls this; the rule ([`crate::surface::Patch`])
/// keeps the scalar sum, and the tests compare the two.
#[inline(always)]
pub fn cubic_tensor3_fast(vals: &[f64], n1: usize, f: [f64; 3]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if cfg!(target_feature = "avx") || std::is_x86_feature_detected!("avx") {
        // SAFETY: the processor has AVX (checked just above, or enabled for the whole build).
        return unsafe { cubic_tensor3_avx(vals, n1, f) };
    }
    cubic_tensor(vals, n1, f)
}

/// [`cubic_tensor`] of three axes in 256-bit vectors, the same bits. The stencils are
/// [`stencil4_f64`]'s (the same starts and weights as [`stencil4`]; its floor is one
/// instruction here). The sum makes the same operations in the same order, four at a time,
/// with lane `i` for the `γ` index: per `c` index `j`, the rows of the four planes
/// (transposed as they are loaded, before the weights are known) times the `e_n` weights and
/// summed from the left, `((v₀·w₀ + v₁·w₁) + v₂·w₂) + v₃·w₃`, row `(i, j)` in lane `i`; those
/// times the `c` weights, summed the same way over `j`: plane `i` in lane `i`; times the `γ`
/// weights, summed from the left. No product is fused with a sum (FMA is not enabled).
///
/// # Safety
/// The processor must support AVX (code compiled for AVX may call it without `unsafe`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
pub fn cubic_tensor3_avx(vals: &[f64], n1: usize, f: [f64; 3]) -> f64 {
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_permute2f128_pd,
        _mm256_set1_pd, _mm256_setr_pd, _mm256_storeu_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
    };
    /// `Σ_k a[k]·w[k]` lane by lane, from the left.
    #[inline]
    #[target_feature(enable = "avx")]
    fn dot4(a: [__m256d; 4], w: [__m256d; 4]) -> __m256d {
        let s = _mm256_add_pd(_mm256_mul_pd(a[0], w[0]), _mm256_mul_pd(a[1], w[1]));
        let s = _mm256_add_pd(s, _mm256_mul_pd(a[2], w[2]));
        _mm256_add_pd(s, _mm256_mul_pd(a[3], w[3]))
    }
    let (m, n) = ((n1 - 1) as f64, n1 as f64);
    let u = f.map(|fk| fk * m);
    // The weights from the floor in floating point, the first node from the integer floor
    // (the same starts, [`stencil4_f64`]): two short chains side by side.
    let [(_, wg), (_, wc), (_, we)] = u.map(|uk| stencil4_f64(uk, n));
    let start = |uk: f64| floor_index(uk, n1 - 2).saturating_sub(1).min(n1 - 4);
    let first = (start(u[0]) * n1 + start(u[1])) * n1 + start(u[2]);
    let s0 = n1 * n1;
    // The block's nodes, checked once: row `(i, j)` starts at `i·s0 + j·n1` and reads 4.
    let block = &vals[first..][..3 * s0 + 3 * n1 + 4];
    // SAFETY: `i·s0 + j·n1 + 4 ≤ 3·s0 + 3·n1 + 4 = block.len()` for `i, j < 4`.
    let row = |i: usize, j: usize| unsafe { _mm256_loadu_pd(block.as_ptr().add(i * s0 + j * n1)) };
    let we = we.map(|x| _mm256_set1_pd(x));
    // Rows `(i, j)` of the four planes, lane `i`.
    let rows = |j: usize| {
        let (l0, l1, l2, l3) = (row(0, j), row(1, j), row(2, j), row(3, j));
        let t0 = _mm256_unpacklo_pd(l0, l1); // l0[0] l1[0] l0[2] l1[2]
        let t1 = _mm256_unpackhi_pd(l0, l1); // l0[1] l1[1] l0[3] l1[3]
        let t2 = _mm256_unpacklo_pd(l2, l3);
        let t3 = _mm256_unpackhi_pd(l2, l3);
        let v = [
            _mm256_permute2f128_pd::<0x20>(t0, t2), // node k = 0 of each row
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ];
        dot4(v, we)
    };
    let planes = dot4(
        [rows(0), rows(1), rows(2), rows(3)],
        wc.map(|x| _mm256_set1_pd(x)),
    );
    let x = _mm256_mul_pd(planes, _mm256_setr_pd(wg[0], wg[1], wg[2], wg[3]));
    let mut p = [0.0; 4];
    // SAFETY: `p` holds 4 values.
    unsafe { _mm256_storeu_pd(p.as_mut_ptr(), x) };
    p[0] + p[1] + p[2] + p[3]
}

/// Step 8 for the cubic stencil on every axis: the first node of the `4^D` block in a leaf of
/// `n1^D` nodes (`n1 = m + 1 ≥ 4`, the last axis innermost) and the weights per axis, of
/// [`stencil4`] at `f·m` (`f` the position inside the leaf, each in `[0, 1]`).
#[inline(always)]
pub fn cubic_stencils<const D: usize>(f: [f64; D], n1: usize) -> (usize, [[f64; 4]; D]) {
    let m = (n1 - 1) as f64;
    stencils_by(f, m, 0, |u| stencil4(u, n1), |first, s| first * n1 + s)
}

/// [`cubic_stencils`] with [`stencil4_u32`] (`n1^D < 2³²`): the same first node and weights.
#[inline(always)]
pub fn cubic_stencils_u32<const D: usize>(f: [f64; D], n1: u32) -> (u32, [[f64; 4]; D]) {
    let m = f64::from(n1 - 1);
    stencils_by(f, m, 0, |u| stencil4_u32(u, n1), |first, s| first * n1 + s)
}

/// [`cubic_stencils`] with [`stencil4_f64`] (`n1` an integer, `n1^D < 2⁵³`): the same first
/// node (as a float) and weights.
#[inline(always)]
pub fn cubic_stencils_f64<const D: usize>(f: [f64; D], n1: f64) -> (f64, [[f64; 4]; D]) {
    let m = n1 - 1.0;
    stencils_by(
        f,
        m,
        0.0,
        |u| stencil4_f64(u, n1),
        |first, s| first * n1 + s,
    )
}

/// The stencil of every axis at `f·m` (`stencil` gives the start and the weights) and the
/// first node of the block, `first ← next(first, start)` from the outermost axis.
#[inline(always)]
fn stencils_by<T: Copy, const D: usize>(
    f: [f64; D],
    m: f64,
    zero: T,
    stencil: impl Fn(f64) -> (T, [f64; 4]),
    next: impl Fn(T, T) -> T,
) -> (T, [[f64; 4]; D]) {
    let mut w = [[0.0; 4]; D];
    let mut first = zero;
    for (wk, &fk) in w.iter_mut().zip(&f) {
        let (s, weights) = stencil(fk * m);
        first = next(first, s);
        *wk = weights;
    }
    (first, w)
}

/// Steps 8 and 9 in a leaf for the cubic stencil: `vals` the leaf's `n1^D` node values
/// (`n1 = m + 1 ≥ 4`, the last axis innermost), `f` the position inside the leaf (each in
/// `[0, 1]`): [`cubic_stencils`], then [`cubic_sum`].
#[inline(always)]
pub fn cubic_tensor<const D: usize>(vals: &[f64], n1: usize, f: [f64; D]) -> f64 {
    let (first, w) = cubic_stencils(f, n1);
    cubic_sum(vals, first, n1, &w)
}

/// Steps 8 and 9 in a leaf with a `k`-point stencil per axis ([`stencil`]): `vals` the leaf's
/// `n1^D` node values, `f` the position inside the leaf. For each axis from the outermost the
/// sum `Σ_i w_i·(sum over the next axis)`, from 0; along the last axis the row's
/// `Σ_j v_j·w_j` (the general rule; [`cubic_tensor`] is the cubic one's closed form).
pub fn lagrange_tensor<const D: usize>(vals: &[f64], n1: usize, f: [f64; D], k: usize) -> f64 {
    let n = n1 - 1;
    let mut w = [[0.0; 8]; D];
    let mut start = [0usize; D];
    let mut count = [0usize; D];
    for axis in 0..D {
        (start[axis], count[axis]) = stencil(f[axis] * n as f64, n1, k, &mut w[axis]);
    }
    let axes = Stencils {
        n1,
        w: &w,
        start: &start,
        count: &count,
    };
    axes.sum(vals, 0, 0)
}

/// The stencils of [`lagrange_tensor`] per axis.
struct Stencils<'a, const D: usize> {
    n1: usize,
    w: &'a [[f64; 8]; D],
    start: &'a [usize; D],
    count: &'a [usize; D],
}

impl<const D: usize> Stencils<'_, D> {
    /// The sum over axes `axis..D` of the block whose node offset from the outer axes is
    /// `base` (already multiplied through to this axis).
    fn sum(&self, vals: &[f64], axis: usize, base: usize) -> f64 {
        let (s, k, w) = (self.start[axis], self.count[axis], &self.w[axis]);
        if axis + 1 == D {
            let row = &vals[base + s..][..k];
            return row.iter().zip(&w[..k]).map(|(p, w)| p * w).sum();
        }
        let mut total = 0.0;
        for (i, wi) in w.iter().enumerate().take(k) {
            total += wi * self.sum(vals, axis + 1, (base + s + i) * self.n1);
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cubic tensor of 2 and 3 axes, summed as the rule states it (`docs/table-format.md`,
    /// "The same bits"), and the general rule at `k = 4`: the same bits, and the generic sum
    /// of any dimension reproduces a polynomial of degree 3 per axis.
    #[test]
    fn the_tensor_of_any_dimension_sums_in_the_stated_order() {
        let n1 = 7;
        let vals: Vec<f64> = (0..n1 * n1 * n1)
            .map(|i| ((i as f64) * 0.37).sin())
            .collect();
        let mut next = {
            let mut s = 0x9E37_79B9_7F4A_7C15u64;
            move || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s >> 11) as f64 / (1u64 << 53) as f64
            }
        };
        for _ in 0..2000 {
            let f = [next(), next(), next()];
            let m = (n1 - 1) as f64;
            let (sg, wg) = stencil4(f[0] * m, n1);
            let (sc, wc) = stencil4(f[1] * m, n1);
            let (se, we) = stencil4(f[2] * m, n1);
            let row2 = |i: usize| {
                let r = &vals[(sg + i) * n1 + sc..];
                r[0] * wc[0] + r[1] * wc[1] + r[2] * wc[2] + r[3] * wc[3]
            };
            let two = wg[0] * row2(0) + wg[1] * row2(1) + wg[2] * row2(2) + wg[3] * row2(3);
            let row3 = |i: usize, j: usize| {
                let r = &vals[((sg + i) * n1 + sc + j) * n1 + se..];
                r[0] * we[0] + r[1] * we[1] + r[2] * we[2] + r[3] * we[3]
            };
            let plane = |i: usize| {
                wc[0] * row3(i, 0) + wc[1] * row3(i, 1) + wc[2] * row3(i, 2) + wc[3] * row3(i, 3)
            };
            let three = wg[0] * plane(0) + wg[1] * plane(1) + wg[2] * plane(2) + wg[3] * plane(3);
            assert_eq!(
                cubic_tensor(&vals, n1, [f[0], f[1]]).to_bits(),
                two.to_bits()
            );
            assert_eq!(cubic_tensor(&vals, n1, f).to_bits(), three.to_bits());
            let general = lagrange_tensor(&vals, n1, f, 4);
            assert!((general - three).abs() <= 1e-14, "{general} {three}");
        }
        // A polynomial of degree 3 per axis over 4 axes is reproduced.
        let n1: usize = 5;
        let poly = |x: [f64; 4]| {
            (1.0 + x[0] - x[0].powi(3))
                * (0.5 - x[1] * x[1])
                * (2.0 + x[2].powi(3))
                * (1.0 - 0.25 * x[3])
        };
        let mut vals = vec![0.0; n1.pow(4)];
        for (i, v) in vals.iter_mut().enumerate() {
            let x = [i / 125, (i / 25) % 5, (i / 5) % 5, i % 5].map(|k| k as f64 / 4.0);
            *v = poly(x);
        }
        for _ in 0..200 {
            let f = [next(), next(), next(), next()];
            let t = cubic_tensor(&vals, n1, f);
            assert!((t - poly(f)).abs() <= 1e-13, "{t} {}", poly(f));
            let g = lagrange_tensor(&vals, n1, f, 4);
            assert!((g - poly(f)).abs() <= 1e-13, "{g} {}", poly(f));
        }
    }

    /// The vector sum of three axes gives the scalar sum's bits, wherever the block starts,
    /// for values and weights of every magnitude (and where the processor has no AVX, the
    /// dispatch answers with the scalar sum).
    #[test]
    fn the_vector_sum_of_three_axes_has_the_bits_of_the_scalar_sum() {
        let mut s = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for n1 in [4usize, 5, 9, 17] {
            let size = n1 * n1 * n1;
            for _ in 0..2000 {
                // Values of mixed signs and exponents (cancellation, rounding in every sum).
                let vals: Vec<f64> = (0..size)
                    .map(|_| {
                        let r = next();
                        let m = (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                        m * 2f64.powi((r % 41) as i32 - 20)
                    })
                    .collect();
                // Random positions, and (one time in four per axis) the leaf's edges and its
                // nodes, where the stencil's start changes, and their neighbours.
                let mut u = || {
                    let r = next();
                    if r % 4 == 0 {
                        let node = (r >> 8) % n1 as u64;
                        let x = node as f64 / (n1 - 1) as f64;
                        [x, x.next_up(), x.next_down().max(0.0)][(r >> 16) as usize % 3].min(1.0)
                    } else {
                        (r >> 11) as f64 / (1u64 << 53) as f64
                    }
                };
                let f = [u(), u(), u()];
                let scalar = cubic_tensor(&vals, n1, f);
                assert_eq!(cubic_tensor3_fast(&vals, n1, f).to_bits(), scalar.to_bits());
                #[cfg(target_arch = "x86_64")]
                if std::is_x86_feature_detected!("avx") {
                    // SAFETY: the processor has AVX.
                    let avx = unsafe { cubic_tensor3_avx(&vals, n1, f) };
                    assert_eq!(avx.to_bits(), scalar.to_bits(), "n1 = {n1}, f = {f:?}");
                }
            }
        }
    }

    #[test]
    fn the_descent_step_numbers_the_children_as_the_format_does() {
        let mut f = [0.75, 0.25, 0.5];
        assert_eq!(descend(&mut f), 4 + 1);
        assert_eq!(f, [0.5, 0.5, 0.0]);
        let mut f = [0.25, 0.75];
        assert_eq!(descend(&mut f), 1);
        assert_eq!(f, [0.5, 0.5]);
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
                let (s32, w32) = stencil4_u32(u, n);
                let (s64, w64) = stencil4_f64(u, f64::from(n));
                let (s, w) = stencil4(u, n as usize);
                assert_eq!((s32 as usize, f64::from(s32)), (s, s64), "u = {u}, n = {n}");
                for j in 0..4 {
                    let bits = [w32[j], w64[j], w[j]].map(|x| (x.is_nan(), x.to_bits()));
                    let same = |x: (bool, u64)| x == bits[2] || (x.0 && bits[2].0);
                    assert!(same(bits[0]) && same(bits[1]), "u = {u}, n = {n}: {bits:?}");
                }
                let f = [u / f64::from(n - 1), 0.5 * u / f64::from(n - 1)];
                let (first, w) = cubic_stencils(f, n as usize);
                let (first32, w32) = cubic_stencils_u32(f, n);
                let (first64, w64) = cubic_stencils_f64(f, f64::from(n));
                assert_eq!((first32 as usize, f64::from(first32)), (first, first64));
                let bits = |w: [[f64; 4]; 2]| w.map(|a| a.map(|x| x.to_bits()));
                if !u.is_nan() {
                    assert_eq!((bits(w32), bits(w64)), (bits(w), bits(w)), "u = {u}");
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
