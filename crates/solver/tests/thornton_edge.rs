//! The edge `α₁(γ, e_n)` of the full-slip region of Thornton's law
//! (`history::full_slip_edge_thornton`): where the impact stops ending in gross slip, `P(α)`
//! is smooth below and its curvature jumps; it converges in the steps, tends to the elastic
//! `α_c1` as `e_n → 1`, and lies below the Kelvin–Voigt `α_c1` next to γ = 1 (where the
//! springs that stick at the switch to unloading never slip again) and above it from γ ≈ 1.1.

use oblique_physics::regimes::alpha_c1_dissipative;
use oblique_solver::history::{
    ends_in_full_slip_thornton, full_slip_edge_thornton, slip_history_thornton, SlipSign,
};
use oblique_solver::{Accuracy, Law, PhysicsError, Request};

/// `P` of Thornton's law at tol 1e-10.
fn p(gamma: f64, alpha: f64, e_n: f64) -> f64 {
    Request::new(gamma, alpha)
        .e_n(e_n)
        .law(Law::Thornton)
        .accuracy(Accuracy::Tolerance(1e-10))
        .solve()
        .unwrap()
        .p
}

/// Least-squares polynomial of degree `deg` through `(x, y)` (normal equations; `x` scaled to
/// about 1 by the caller), evaluated at `at`. Index loops: a dense elimination reads clearer so.
#[allow(clippy::needless_range_loop)]
fn fit_at(x: &[f64], y: &[f64], deg: usize, at: f64) -> f64 {
    let n = deg + 1;
    let mut a = vec![vec![0.0; n + 1]; n];
    for (&xi, &yi) in x.iter().zip(y) {
        for r in 0..n {
            for c in 0..n {
                a[r][c] += xi.powi((r + c) as i32);
            }
            a[r][n] += yi * xi.powi(r as i32);
        }
    }
    for k in 0..n {
        let piv = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, piv);
        for r in 0..n {
            if r != k {
                let f = a[r][k] / a[k][k];
                for c in k..=n {
                    a[r][c] -= f * a[k][c];
                }
            }
        }
    }
    (0..n).map(|k| a[k][n] / a[k][k] * at.powi(k as i32)).sum()
}

/// At γ = 1.754, e_n = 0.8 the edge converges in the steps (4096 against 16384: 1e-6
/// relative), and `P` is smooth below it (a quartic through 10 points over 2 % of α below the
/// edge predicts `P` at the edge and just below it to 1e-10) and departs from that continuation
/// above it like a curvature jump: `(α − α₁)²`, the departure at `2δ` four times that at `δ`.
#[test]
fn the_edge_is_a_curvature_jump_of_p() {
    let (gamma, e_n) = (1.754, 0.8);
    let a1 = full_slip_edge_thornton(gamma, e_n, 16384).unwrap();
    let coarse = full_slip_edge_thornton(gamma, e_n, 4096).unwrap();
    assert!((coarse / a1 - 1.0).abs() < 1e-6, "{coarse} against {a1}");
    assert!(
        a1 > alpha_c1_dissipative(gamma, e_n) * (1.0 + 5e-4),
        "{a1} against the Kelvin-Voigt alpha_c1 {}",
        alpha_c1_dissipative(gamma, e_n)
    );
    // Below the edge (x = (α − α₁)/(0.01 α₁), in [-2, -0.05]).
    let xs: Vec<f64> = (0..10).map(|i| -2.0 + 1.95 * i as f64 / 9.0).collect();
    let ys: Vec<f64> = xs
        .iter()
        .map(|&x| p(gamma, a1 * (1.0 + 0.01 * x), e_n))
        .collect();
    let below = p(gamma, a1 * (1.0 - 0.0002), e_n);
    let miss = (fit_at(&xs, &ys, 4, -0.02) - below).abs();
    assert!(miss < 1e-10, "smooth below the edge: {miss:e}");
    // Above: departures from the continuation at δ = 1e-4 and 2e-4 of α₁.
    let dep = |d: f64| p(gamma, a1 * (1.0 + d), e_n) - fit_at(&xs, &ys, 4, 100.0 * d);
    let (d1, d2) = (dep(1e-4), dep(2e-4));
    assert!(d1 > 1e-8, "a departure above the edge: {d1:e}");
    let ratio = d2 / d1;
    assert!(
        (3.5..4.5).contains(&ratio),
        "departure like (alpha - alpha_1)^2: {d1:e}, {d2:e}, ratio {ratio}"
    );
}

/// As `e_n → 1` the edge tends to the Kelvin–Voigt `α_c1(γ, e_n)` faster than that moves from
/// the elastic `α_c1 = 2γ²/(7(2γ² − 1))`: at `e_n = 0.999` within 2e-6 of it (relative), where
/// the Kelvin–Voigt `α_c1` is 1e-4 away from the elastic one; at `e_n = 0.99`, 3e-6 to 1e-4
/// away (the gap falls like `(1 − e_n)^{1.5}`).
#[test]
fn the_edge_tends_to_the_kelvin_voigt_alpha_c1() {
    for gamma in [1.5, 2.3] {
        let elastic = alpha_c1_dissipative(gamma, 1.0);
        let kv = alpha_c1_dissipative(gamma, 0.999);
        assert!((kv / elastic - 1.0).abs() > 1e-4);
        let near = full_slip_edge_thornton(gamma, 0.999, 8192).unwrap();
        assert!((near / kv - 1.0).abs() < 2e-6, "{gamma}: {near} vs {kv}");
        let farther = full_slip_edge_thornton(gamma, 0.99, 8192).unwrap();
        let gap = farther / alpha_c1_dissipative(gamma, 0.99) - 1.0;
        assert!(
            (3e-6..1e-4).contains(&gap),
            "{gamma}: {farther}, gap {gap:e}"
        );
    }
}

/// Next to γ = 1 the central springs that stick at the switch to unloading stay stuck above an
/// `α` below the Kelvin–Voigt `α_c1`: at γ = 1.05, e_n = 0.7 the edge lies 1.3 % below it, the
/// impact just above the edge has no gross-slip episode between the switch and the final `−`
/// episode, and the one just below ends in `+` gross slip.
#[test]
fn next_to_gamma_one_the_edge_lies_below_the_kelvin_voigt_alpha_c1() {
    let (gamma, e_n) = (1.05, 0.7);
    let a1 = full_slip_edge_thornton(gamma, e_n, 8192).unwrap();
    let c1 = alpha_c1_dissipative(gamma, e_n);
    assert!(a1 < c1 * (1.0 - 5e-3), "{a1} against {c1}");
    assert!(ends_in_full_slip_thornton(gamma, a1 * (1.0 - 1e-4), e_n, 8192).unwrap());
    assert!(!ends_in_full_slip_thornton(gamma, a1 * (1.0 + 1e-4), e_n, 8192).unwrap());
    let h = slip_history_thornton(gamma, a1 * (1.0 + 1e-3), e_n, 8192).unwrap();
    let signs: Vec<SlipSign> = h.episodes.iter().map(|e| e.sign).collect();
    assert_eq!(signs, [SlipSign::Plus, SlipSign::Minus], "{:?}", h.episodes);
}

/// At `e_n = 1` Thornton's history is the elastic one, bit for bit; the edge refuses `γ ≤ 1`
/// and `e_n = 1`, naming the parameter.
#[test]
fn the_history_at_e_n_1_is_elastic_and_bad_input_is_named() {
    let a = slip_history_thornton(1.754, 0.3, 1.0, 1024).unwrap();
    let b = oblique_solver::history::slip_history(1.754, 0.3, 1024).unwrap();
    assert_eq!(a, b);
    for (gamma, e_n, name) in [(1.0, 0.8, "gamma"), (0.5, 0.8, "gamma"), (1.5, 1.0, "e_n")] {
        match full_slip_edge_thornton(gamma, e_n, 1024) {
            Err(PhysicsError::InvalidParameter { name: n, .. }) => assert_eq!(n, name),
            other => panic!("({gamma}, {e_n}): {other:?}"),
        }
    }
    assert!(full_slip_edge_thornton(1.5, 0.2, 1024).is_err());
}
