//! The error bound a table states (`docs/table-format.md`, "The stated error bound"): one
//! number, derived from the file's `leaf_predicted_error` and `error_estimate` datasets by one
//! definition, used by every reader and by the writer.
//!
//! Inside a leaf the rule interpolates node values `P_i + e_i` whose solver errors satisfy
//! `|e_i| ≤ error_estimate_i`. The interpolant of the exact values differs from `P` by the
//! leaf's interpolation error (predicted by the refinement: `leaf_predicted_error`), and the
//! node errors reach the result through the Lagrange weights, whose absolute sum is at most
//! `Λ_k` per axis (the Lebesgue constant of `k` equispaced points over the stencil's range,
//! [`lebesgue`]). So the error at any point of leaf `L` is at most
//! `leaf_predicted_error[L] + Λ_k^dims · max_i error_estimate[L, i]` (`dims = 2`, or 3 with an
//! `e_n` axis), and the table's bound is the
//! largest of these over all leaves of all patches. The full-slip line (exact) and the bound
//! `|P| ≤ 1` of the rule (step 10) only make the error smaller.

use crate::surface::{Patch, PatchId, Surface};
use crate::Check;

/// The Lebesgue constant `Λ_k = max_{u ∈ [0, k−1]} Σ_j |ℓ_j(u)|` of the `k`-point Lagrange
/// basis on the equispaced nodes `0 … k−1` (dimensionless): the largest factor by which the
/// rule's 1-D stencil can amplify errors of the node values (the stencil's position `u − start`
/// always lies in `[0, k − 1]`). `Λ_4 = 1.6311`. Evaluated on 4096 points per node interval
/// (the maximum of each interval, sampled; relative accuracy better than 1e-6).
pub fn lebesgue(k: usize) -> f64 {
    let k = k.max(1);
    let per = 4096;
    let mut worst = 1.0_f64;
    for s in 0..=per * (k - 1) {
        let u = s as f64 / per as f64;
        let sum: f64 = (0..k)
            .map(|j| {
                (0..k)
                    .filter(|&n| n != j)
                    .map(|n| (u - n as f64) / (j as f64 - n as f64))
                    .product::<f64>()
                    .abs()
            })
            .sum();
        worst = worst.max(sum);
    }
    worst
}

/// The factor `Λ_k²` by which the tensor-product rule (`k` points per axis) can amplify node
/// errors: `2.6606` for the cubic stencil.
pub fn node_error_factor(k: usize) -> f64 {
    node_error_factor_of(k, 2)
}

/// The factor `Λ_k^dims` of a tensor product over `dims` axes: `Λ_4³ = 4.3397` for the
/// octree leaves of a table with an `e_n` axis.
pub fn node_error_factor_of(k: usize, dims: u32) -> f64 {
    let l = lebesgue(k);
    (0..dims).map(|_| l).product()
}

/// The bound of one leaf: `predicted + factor · max(node_errors)`, `factor =`
/// [`node_error_factor`]. NaN if `predicted` is NaN.
pub fn leaf_bound(predicted: f64, node_errors: &[f64], factor: f64) -> f64 {
    predicted + factor * node_errors.iter().copied().fold(0.0, f64::max)
}

/// The largest [`leaf_bound`] over the leaves of `patch` (stencil `k`), whose predicted errors
/// are `leaf_predicted` (one per leaf, in leaf order). NaN when their number does not match.
pub fn patch_bound(patch: &Patch, leaf_predicted: &[f64], k: usize) -> f64 {
    let leaves = patch.leaves();
    if leaf_predicted.len() != leaves {
        return f64::NAN;
    }
    let size = patch.leaf_size();
    let factor = node_error_factor_of(k, patch.dims());
    leaf_predicted
        .iter()
        .zip(patch.error_estimate().chunks_exact(size))
        .map(|(&pred, errs)| leaf_bound(pred, errs, factor))
        .fold(0.0, |m, b| if b.is_nan() { f64::NAN } else { m.max(b) })
}

/// The stated error bound of a surface: the largest [`patch_bound`] of its patches, with the
/// predicted errors of the leaves of each patch given in the order `stick_low`,
/// `partial_high`, `stick_high` (an absent patch contributes nothing; a missing prediction for
/// a present patch makes the bound NaN: the file states none). 0 when no patch is present
/// (every answer is exact).
pub fn surface_bound(surface: &Surface, leaf_predicted: [Option<&[f64]>; 3]) -> f64 {
    let mut worst = 0.0_f64;
    for (id, pred) in PatchId::ALL.into_iter().zip(leaf_predicted) {
        let Some(patch) = surface.patch_by_id(id) else {
            continue;
        };
        let b = match pred {
            Some(pred) => patch_bound(patch, pred, surface.stencil()),
            None => f64::NAN,
        };
        if b.is_nan() {
            return f64::NAN;
        }
        worst = worst.max(b);
    }
    worst
}

/// The first check whose `interpolation_error` exceeds `bound` (or any check when `bound` is
/// NaN: no bound is stated).
pub fn contradicting_check(checks: &[Check], bound: f64) -> Option<&Check> {
    checks
        .iter()
        .find(|c| bound.is_nan() || c.interpolation_error.is_nan() || c.interpolation_error > bound)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lebesgue_constants_of_few_equispaced_points() {
        // Two points: linear interpolation, weights in [0, 1] summing to 1.
        assert!((lebesgue(2) - 1.0).abs() < 1e-12);
        // Four points: 1.6311 in the outer intervals (known value 1.63113...).
        let l4 = lebesgue(4);
        assert!((l4 - 1.631_13).abs() < 2e-5, "{l4}");
        assert!((node_error_factor(4) - l4 * l4).abs() < 1e-15);
    }

    #[test]
    fn a_leaf_bound_adds_the_amplified_worst_node_error() {
        assert_eq!(leaf_bound(1e-6, &[0.0, 2e-7, 1e-7], 2.5), 1e-6 + 2.5 * 2e-7);
        assert!(leaf_bound(f64::NAN, &[0.0], 2.5).is_nan());
    }
}
