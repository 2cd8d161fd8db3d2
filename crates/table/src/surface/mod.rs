//! The interpolation rule of schema v3 (stated in `docs/table-format.md`).
//!
//! The nonlinear part of the `(γ, α)` plane is covered by up to three patches whose edges lie on
//! the curves where `P` has curvature jumps, so that `P` is smooth inside each patch:
//!
//! | patch          | γ range        | α range          | coordinate `c ∈ [0, 1]`                        |
//! |----------------|----------------|------------------|------------------------------------------------|
//! | `stick_low`    | `γ_min ≤ γ ≤ 1` | `α_c2 … α_max`  | `S(α)/S(α_max)`, `S = r/(r + ρ)`               |
//! | `partial_high` | `1 ≤ γ ≤ γ_max` | `α_c1 … α_c2`   | `1 − √(1 − ℓ)`, `ℓ = ln(α/α_c1)/ln(α_c2/α_c1)` |
//! | `stick_high`   | `1 ≤ γ ≤ γ_max` | `α_c2 … α_max`  | `S(α)/S(α_max)`, `S = r/(r + ρ)`               |
//!
//! with `r = α/α_c2 − 1`, `ρ = 2(1 − γ²)` for `γ < 1` and `ρ = 1` for `γ ≥ 1`, `S(∞) = 1`. Each
//! patch is cut into equal root cells in `(γ, c)`, each refined as a quadtree where `P` needs it
//! (the kink curves inside the partial-slip patch for `γ ≳ 2`); every leaf stores `P` on its own
//! uniform grid. Inside a leaf `P` is the tensor product of 1-D Lagrange polynomials through `k`
//! consecutive nodes of that leaf per axis (`k = stencil_points`). The partial-slip patch may
//! carry a [`Warp`] of its coordinate (schema 3), applied before the leaf is located.
//!
//! One file per concern: the patch coordinates ([`coord`]), the patch and its tree walks
//! ([`patch`]), the axes and points ([`axis`]), the fold warp ([`warp`]), the checks of a
//! stored tree ([`checks`]), and the regions, domain and [`Surface`] ([`domain`]).

pub mod axis;
pub mod checks;
pub mod coord;
pub mod domain;
pub mod knots;
pub mod patch;
pub mod warp;

pub use axis::*;
pub use checks::*;
pub use coord::*;
pub use domain::*;
pub use knots::*;
pub use patch::*;
pub use warp::*;

use crate::leaf::{cubic_tensor, descend, descend_masked, lagrange_tensor, MAX_AXES};
use crate::TableError;

pub use crate::leaf::{cubic_weights, floor_index, locate, stencil, stencil4};

pub use oblique_physics::regimes::{
    alpha_c1, alpha_c1_dissipative, alpha_c2, full_slip_line, linear_limit,
    linear_limit_dissipative,
};

/// Step 10 of the rule: the interpolated `P` limited to `[−1, 1]` (`|P| ≤ 1`: a rebound never
/// gains energy). Every read path applies it to the tensor product, so that near `P = −1` (where
/// the interpolant can overshoot by up to the table's error) no path answers `|P| > 1`; a NaN
/// stays NaN.
#[inline(always)]
pub fn bound_p(p: f64) -> f64 {
    p.clamp(-1.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn warp() -> Warp {
        Warp {
            start: 1.0,
            gamma_0: 2.9,
            gamma_step: 0.05,
            c_star: 0.5,
            knot: (0..13)
                .map(|i| 0.35 + 0.2 * (i as f64 * 0.4).sin() * (i as f64 / 12.0))
                .collect(),
        }
    }

    #[test]
    fn the_knot_rule_reproduces_the_knot_values_at_the_grid_points() {
        let w = warp();
        for (i, &k) in w.knot.iter().enumerate() {
            let g = w.gamma_0 + i as f64 * w.gamma_step;
            assert!((w.knot_at(g) - k).abs() <= 1e-14, "knot {i}");
        }
        // Clamped outside the grid.
        assert_eq!(w.knot_at(1.0), w.knot[0]);
        assert_eq!(w.knot_at(100.0), w.knot[w.knot.len() - 1]);
        // Between grid points: a cubic reproduces a cubic exactly.
        let cubic =
            |g: f64| 0.3 + 0.1 * (g - 3.0) - 0.2 * (g - 3.0).powi(2) + 0.3 * (g - 3.0).powi(3);
        let wc = Warp {
            knot: (0..13).map(|i| cubic(2.9 + 0.05 * i as f64)).collect(),
            ..warp()
        };
        for j in 0..=96 {
            let g = 2.9 + 0.6 * j as f64 / 96.0;
            assert!((wc.knot_at(g) - cubic(g)).abs() <= 1e-13, "gamma {g}");
        }
    }

    #[test]
    fn apply_sends_the_knot_to_c_star_and_invert_undoes_it() {
        let w = warp();
        for j in 0..=200 {
            let g = 2.5 + 1.0 * j as f64 / 200.0;
            let k = w.knot_at(g);
            assert_eq!(w.apply(g, k), w.c_star, "gamma {g}");
            assert_eq!(w.apply(g, 0.0), 0.0);
            assert!((w.apply(g, 1.0) - 1.0).abs() <= 1e-15);
            assert_eq!(w.apply(g, 0.3).to_bits(), w.apply_with(k, 0.3).to_bits());
            let mut prev = -1.0;
            for i in 0..=100 {
                let c = i as f64 / 100.0;
                let cp = w.apply(g, c);
                assert!(cp > prev && (0.0..=1.0).contains(&cp), "monotone in [0, 1]");
                prev = cp;
                assert!(
                    (w.invert(g, cp) - c).abs() <= 1e-15,
                    "invert(apply) at {g}, {c}"
                );
                // The square root of the grading amplifies rounding next to the knot
                // (c' − c* ∝ √(K − c)): 1e-16/(2·0.02) at the nearest grid point.
                assert!(
                    (w.apply(g, w.invert(g, c)) - c).abs() <= 1e-13,
                    "apply(invert) at {g}, {c}"
                );
            }
        }
    }

    #[test]
    fn the_grading_makes_the_fold_singularity_a_cubic() {
        // Below the fold P ≈ smooth + C(α_F − α)^{3/2}; in c' the power is (1 − c'/c*)³ times
        // K^{3/2}, a polynomial: a cubic through four points of it reproduces it.
        let w = warp();
        let g = 3.13;
        let k = w.knot_at(g);
        let f = |c_prime: f64| (k - w.invert(g, c_prime)).max(0.0).powf(1.5);
        let nodes = [0.1, 0.2, 0.3, 0.4];
        let vals = nodes.map(f);
        for i in 0..=50 {
            let x = 0.1 + 0.3 * i as f64 / 50.0;
            let lagrange: f64 = (0..4)
                .map(|j| {
                    let mut l = vals[j];
                    for m in (0..4).filter(|&m| m != j) {
                        l *= (x - nodes[m]) / (nodes[j] - nodes[m]);
                    }
                    l
                })
                .sum();
            assert!((lagrange - f(x)).abs() <= 1e-14, "c' = {x}");
        }
        // Linear in c the same power is not: the cubic through four c-points misses it.
        let fc = |c: f64| (k - c).max(0.0).powf(1.5);
        let cn = nodes.map(|x| k * x / w.c_star);
        let mid = 0.5 * (cn[2] + cn[3]);
        let lag: f64 = (0..4)
            .map(|j| {
                let mut l = fc(cn[j]);
                for m in (0..4).filter(|&m| m != j) {
                    l *= (mid - cn[m]) / (cn[j] - cn[m]);
                }
                l
            })
            .sum();
        assert!((lag - fc(mid)).abs() > 1e-6, "{}", (lag - fc(mid)).abs());
    }

    #[test]
    fn the_warp_applies_from_its_start_row_on() {
        let patch = Patch {
            kind: PatchKind::PartialSlip,
            axes: vec![Axis::gamma(1.0, 3.5, 5), Axis::coord(4)],
            leaf_intervals: 8,
            tree: (0..20).map(|i| -(i + 1)).collect(),
            p: vec![0.0; 20 * 81],
            error_estimate: vec![0.0; 20 * 81],
            warp: Some(Warp {
                start: 3.8125,
                gamma_0: 2.90625,
                gamma_step: 0.01,
                c_star: 0.5,
                knot: vec![0.6; 61],
            }),
            knots: None,
            split: None,
        };
        // γ(start) = 2.90625: unwarped below, warped from it on.
        let w = patch.warp.as_ref().expect("warp");
        assert_eq!(patch.warped(2.9, 0.3).to_bits(), 0.3f64.to_bits());
        assert_eq!(patch.warped(2.90625, 0.3), w.apply(2.90625, 0.3));
        assert_eq!(patch.warped(3.2, 0.3), w.apply(3.2, 0.3));
        assert_ne!(patch.warped(3.2, 0.3), 0.3);
        // Leaves at depth 0 straddle a start inside a root row: refused, naming 'start'.
        let e = patch.check_warp().expect_err("root leaves straddle 3.8125");
        assert!(e.contains("'start' = 3.8125"), "{e}");
        // At a root boundary it is valid.
        let mut ok = patch.clone();
        if let Some(w) = ok.warp.as_mut() {
            w.start = 4.0;
            w.gamma_0 = 3.0;
        }
        assert_eq!(ok.check_warp(), Ok(()));
        // A knot grid that starts after γ(start) is refused.
        let mut late = ok.clone();
        if let Some(w) = late.warp.as_mut() {
            w.gamma_0 = 3.05;
        }
        assert!(late
            .check_warp()
            .expect_err("late grid")
            .contains("gamma_0"));
    }
}
