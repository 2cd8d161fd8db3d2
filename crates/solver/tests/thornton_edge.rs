//! The edge `α₁(γ, e_n)` of the full-slip region of Thornton's law
//! (`history::full_slip_edge_thornton`): where the impact stops ending in gross slip, `P(α)`
//! is smooth below and its curvature jumps; it converges in the steps, tends to the elastic
//! `α_c1` as `e_n → 1`, and lies below the Kelvin–Voigt `α_c1` next to γ = 1 (where the
//! springs that stick at the switch to unloading never slip again) and above it from γ ≈ 1.1.
//! And four kinks inside: the re-slip fold `α_R(γ, e_n)` and the switch fold `α_S(γ, e_n)` of
//! the partial-slip patch (`history::reslip_fold_thornton`, `history::switch_fold_thornton`)
//! and the loading fold `α_L(γ, e_n)` of the stick patch (`history::loading_fold_thornton`),
//! all `3/2`-power departures, and the curvature jump at `α = 2/7`, where the first gross-slip
//! episode ends at the switch to unloading. And the fold F₋ of the partial-slip patch
//! (`history::fold_minus_thornton`) and the end-of-contact curves E₋
//! (`history::end_minus_edges_thornton`), the elastic law's continued to `e_n < 1`, and the
//! strip where a `+μF_N` episode of the restitution exists
//! (`history::restitution_plus_strip_thornton`).

use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2};
use oblique_solver::history::{
    end_minus_at, end_minus_edges_thornton, end_minus_sheet_edges_thornton,
    ends_in_full_slip_thornton, fold_minus_thornton, full_slip_edge_thornton, has_end_minus,
    has_loading_zone_thornton, has_reslip_thornton, has_switch_zone_thornton,
    loading_fold_thornton, reslip_fold_thornton, restitution_plus_strip_thornton,
    slip_history_thornton, switch_fold_thornton, switch_sheet_edges_thornton,
    switch_sheet_thornton, switch_zones_thornton, SlipSign,
};
use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_p, yield_pressure_for_restitution,
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

/// `P` of Thornton's law at `(γ, α, e_n)` on a fixed number of steps (no refinement: a kink
/// stays where it is between neighbouring α).
fn p_fixed(gamma: f64, alpha: f64, e_n: f64, steps: usize) -> f64 {
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n).unwrap());
    let shear = alpha_c2(gamma);
    dimensionless_p(shear, alpha / shear, &motion, steps)
}

#[test]
fn the_loading_fold_is_a_three_halves_kink_of_p() {
    let (g, e) = (1.6, 0.8);
    let c2 = alpha_c2(g);
    // Converges in the steps (second order: 7.5e-7, then 2.0e-7 at 4 096 and 8 192 steps).
    let coarse = loading_fold_thornton(g, e, 2048).unwrap().expect("a fold");
    let fine = loading_fold_thornton(g, e, 8192).unwrap().expect("a fold");
    assert!((coarse / fine - 1.0).abs() < 2e-6, "{coarse} {fine}");
    assert!((fine / c2 - 1.14291).abs() < 1e-4, "{}", fine / c2);
    // The predicate on either side.
    assert!(has_loading_zone_thornton(g, fine * (1.0 - 1e-4), e, 8192).unwrap());
    assert!(!has_loading_zone_thornton(g, fine * (1.0 + 1e-4), e, 8192).unwrap());
    // Smooth above (a cubic through 30 values over 3 % of α_L to 1e-8), and below it `P`
    // leaves that cubic like 0.6 (1 − α/α_L)^{3/2}: positive, and 8 times more at 4
    // times the distance (a slope or curvature jump would give 4 or 16).
    let x: Vec<f64> = (0..30).map(|k| 2e-4 + 1e-3 * k as f64).collect();
    let y: Vec<f64> = x
        .iter()
        .map(|&d| p_fixed(g, fine * (1.0 + d), e, 8192))
        .collect();
    let xs: Vec<f64> = x.iter().map(|d| d / 0.03).collect();
    for (&xi, &yi) in xs.iter().zip(&y).step_by(7) {
        assert!((fit_at(&xs, &y, 3, xi) - yi).abs() < 1e-8);
    }
    let departure = |d: f64| p_fixed(g, fine * (1.0 - d), e, 8192) - fit_at(&xs, &y, 3, -d / 0.03);
    let (near, far) = (departure(1e-3), departure(4e-3));
    assert!(near > 1e-5 && near < 3e-5, "{near}");
    let ratio = far / near;
    assert!((6.5..9.5).contains(&ratio), "{ratio} ({near}, {far})");
    // The fold has reached α_c2 at e_n = 0.9 (γ = 1.6); none at e_n = 1 (elastic).
    assert_eq!(loading_fold_thornton(g, 0.9, 2048).unwrap(), None);
    assert_eq!(loading_fold_thornton(g, 1.0, 2048).unwrap(), None);
}

#[test]
fn at_alpha_two_sevenths_the_curvature_of_p_jumps() {
    // The first gross-slip episode would end where the tangential impulse `(7/2) α J` has
    // stopped the contact point, `J = 2/(7α)`; the normal impulse at the switch to unloading is
    // `J = 1` whatever γ and `e_n`, so at α = 2/7 the episode ends at the switch, where the
    // limits jump. Quadratics through 20 values on each side (4 096 steps): their second
    // derivatives differ by about 10 (−5.7 and +5.0 at γ = 1.754, e_n = 0.8).
    let a = 2.0 / 7.0;
    for (g, e) in [(1.754, 0.8), (2.3, 0.9)] {
        let side = |s: f64| {
            let x: Vec<f64> = (0..20).map(|k| s * (2e-5 + 1e-5 * k as f64)).collect();
            let y: Vec<f64> = x.iter().map(|&d| p_fixed(g, a + d, e, 4096)).collect();
            let xs: Vec<f64> = x.iter().map(|d| d / 2e-4).collect();
            let h = 0.5;
            let at = |u: f64| fit_at(&xs, &y, 2, u);
            let mid = s * 0.5;
            (at(mid + h) - 2.0 * at(mid) + at(mid - h)) / (h * 2e-4).powi(2)
        };
        let (below, above) = (side(-1.0), side(1.0));
        assert!(above - below > 5.0, "{g} {e}: {below} {above}");
    }
}

#[test]
fn the_reslip_fold_is_a_three_halves_kink_of_p() {
    let (g, e) = (1.754, 0.8);
    // 0.240005327 / 0.240005581 / 0.240005593 at 2 048 / 4 096 / 8 192 steps.
    let coarse = reslip_fold_thornton(g, e, 2048).unwrap().expect("a fold");
    let fine = reslip_fold_thornton(g, e, 8192).unwrap().expect("a fold");
    assert!((coarse / fine - 1.0).abs() < 2e-6, "{coarse} {fine}");
    assert!((fine - 0.2400056).abs() < 1e-6, "{fine}");
    assert!(has_reslip_thornton(g, fine * (1.0 - 1e-4), e, 8192).unwrap());
    assert!(!has_reslip_thornton(g, fine * (1.0 + 1e-4), e, 8192).unwrap());
    // Smooth below (a cubic through 30 values over 3 % of α_R), and above it `P` leaves that
    // cubic by about 1.06 (α/α_R − 1)^{3/2}: 8 times more at 4 times the distance.
    let x: Vec<f64> = (0..30).map(|k| -(2e-4 + 1e-3 * k as f64)).collect();
    let y: Vec<f64> = x
        .iter()
        .map(|&d| p_fixed(g, fine * (1.0 + d), e, 8192))
        .collect();
    let xs: Vec<f64> = x.iter().map(|d| d / 0.03).collect();
    let departure = |d: f64| p_fixed(g, fine * (1.0 + d), e, 8192) - fit_at(&xs, &y, 3, d / 0.03);
    let (near, far) = (departure(1e-3), departure(4e-3));
    assert!(near > 2e-5 && near < 5e-5, "{near}");
    let ratio = far / near;
    assert!((6.5..9.5).contains(&ratio), "{ratio} ({near}, {far})");
    // Next to γ = 1 the springs stuck at the switch never slip back at `+`: no such fold.
    assert_eq!(reslip_fold_thornton(1.02, 0.7, 2048).unwrap(), None);
    assert_eq!(reslip_fold_thornton(g, 1.0, 2048).unwrap(), None);
}

#[test]
fn the_switch_fold_is_a_three_halves_kink_of_p() {
    let (g, e) = (1.754, 0.8);
    // 0.364385815 / 0.364385691 / 0.364385659 at 2 048 / 4 096 / 8 192 steps.
    let coarse = switch_fold_thornton(g, e, 2048).unwrap().expect("a fold");
    let fine = switch_fold_thornton(g, e, 8192).unwrap().expect("a fold");
    assert!((coarse / fine - 1.0).abs() < 1e-6, "{coarse} {fine}");
    assert!((fine - 0.3643857).abs() < 1e-6, "{fine}");
    // The predicate on either side; below, the zone clipped at `+` at the switch lies inside
    // the contact, between a stuck centre and a stuck ring (and a `−` zone at the edge).
    assert!(has_switch_zone_thornton(g, fine * (1.0 - 1e-4), e, 8192).unwrap());
    assert!(!has_switch_zone_thornton(g, fine * (1.0 + 1e-4), e, 8192).unwrap());
    let kinds: Vec<i8> = switch_zones_thornton(g, fine * (1.0 - 1e-3), e, 8192)
        .unwrap()
        .iter()
        .map(|z| z.0)
        .collect();
    assert_eq!(kinds, [0, 1, 0, -1]);
    // Smooth above (a cubic through 30 values over 3 % of α_S), and below it `P` leaves that
    // cubic from below like (1 − α/α_S)^{3/2}: 8 times more at 4 times the distance.
    let x: Vec<f64> = (0..30).map(|k| 2e-4 + 1e-3 * k as f64).collect();
    let y: Vec<f64> = x
        .iter()
        .map(|&d| p_fixed(g, fine * (1.0 + d), e, 8192))
        .collect();
    let xs: Vec<f64> = x.iter().map(|d| d / 0.03).collect();
    for (&xi, &yi) in xs.iter().zip(&y).step_by(7) {
        assert!((fit_at(&xs, &y, 3, xi) - yi).abs() < 1e-8);
    }
    // (4.95e-6 at 1e-3, 3.95e-5 at 4e-3: about 0.156 (1 − α/α_S)^{3/2}.)
    let departure = |d: f64| p_fixed(g, fine * (1.0 - d), e, 8192) - fit_at(&xs, &y, 3, -d / 0.03);
    let (near, far) = (departure(1e-3), departure(4e-3));
    assert!(near > 3e-6 && near < 8e-6, "{near}");
    let ratio = far / near;
    assert!((6.5..9.5).contains(&ratio), "{ratio} ({near}, {far})");
    // None at e_n = 1: the elastic law's limits do not jump at the switch.
    assert_eq!(switch_fold_thornton(g, 1.0, 2048).unwrap(), None);
}

#[test]
fn the_switch_sheet_of_the_stick_patch_lies_across_e_n() {
    let g = 1.7;
    let c2 = alpha_c2(g);
    // Nearly flat in α: between 0.515 and 0.5225 at 3 and 5 α_c2, 0.50 and 0.51 at 1.9 α_c2.
    let sheet = |r: f64, steps: usize| {
        switch_sheet_thornton(g, r * c2, (0.45, 0.6), steps)
            .unwrap()
            .expect("a sheet")
    };
    for (r, lo, hi) in [
        (3.0, 0.515, 0.5225),
        (5.0, 0.515, 0.5225),
        (1.9, 0.50, 0.51),
    ] {
        let e = sheet(r, 2048);
        assert!(e > lo && e < hi, "{r} α_c2: {e}");
    }
    let (a, e_s) = (3.0 * c2, sheet(3.0, 8192));
    assert!((sheet(3.0, 2048) - e_s).abs() < 1e-4, "{e_s}");
    // The clipped field's `+` zone lies at the contact's edge, beyond a `−` zone.
    let zones = switch_zones_thornton(g, a, e_s - 2e-3, 8192).unwrap();
    let last = zones.last().expect("zones");
    assert!(last.0 == 1 && last.2 == 1.0 && last.1 > 0.999, "{zones:?}");
    assert!(zones.iter().any(|z| z.0 == -1), "{zones:?}");
    // None where the predicate fails at both ends, and an empty range is refused.
    assert_eq!(
        switch_sheet_thornton(g, a, (0.53, 0.6), 2048).unwrap(),
        None
    );
    assert!(switch_sheet_thornton(g, a, (0.6, 0.53), 2048).is_err());
    // `P` is not smooth across it: at a fixed 8 192 steps its second differences along `e_n`
    // (spacing 1e-3) keep their value above the sheet and move below it.
    let d2 = |e: f64| {
        let h = 1e-3;
        (p_fixed(g, a, e - h, 8192) - 2.0 * p_fixed(g, a, e, 8192) + p_fixed(g, a, e + h, 8192)) / h
    };
    let (above, further, below) = (d2(e_s + 3e-3), d2(e_s + 6e-3), d2(e_s - 3e-3));
    assert!((above / further - 1.0).abs() < 0.05, "{above} {further}");
    assert!((below / above - 1.0).abs() > 0.2, "{below} {above}");
}

#[test]
fn from_gamma_two_the_switch_sheet_bounds_bands_of_e_n() {
    // γ = 2.3, 10 α_c2 (docs/solver.md, the bands table): the zone exists in e_n 0.3–0.3051 and
    // 0.4001–0.7252, so three edges, the middle one a lower edge.
    let g = 2.3;
    let a = 10.0 * alpha_c2(g);
    let edges = switch_sheet_edges_thornton(g, a, (0.3, 0.99), 0.01, 2048).unwrap();
    let expected = [(0.305124, false), (0.400095, true), (0.725186, false)];
    assert_eq!(edges.len(), 3, "{edges:?}");
    for (&(e, above), (want, want_above)) in edges.iter().zip(expected) {
        assert_eq!(above, want_above, "{edges:?}");
        assert!((e - want).abs() < 1e-5, "{e} against {want}");
    }
    // The upper edges are those of `switch_sheet_thornton` on their brackets.
    let top = switch_sheet_thornton(g, a, (0.7, 0.75), 2048)
        .unwrap()
        .expect("upper edge");
    assert!((top - edges[2].0).abs() < 2e-9, "{top}");
    // `P` leaves its smooth continuation above the lower edge, where the zone exists: at a fixed
    // 8 192 steps its second differences along `e_n` (spacing 1e-3) keep their trend below it
    // (−217 and −211 at 6e-3 and 3e-3 below) and move above it (−169 at 6e-3 above).
    let lower = edges[1].0;
    let d2 = |e: f64| {
        let h = 1e-3;
        (p_fixed(g, a, e - h, 8192) - 2.0 * p_fixed(g, a, e, 8192) + p_fixed(g, a, e + h, 8192))
            / h
            / h
    };
    let (below, further, above) = (d2(lower - 3e-3), d2(lower - 6e-3), d2(lower + 6e-3));
    assert!((below / further - 1.0).abs() < 0.05, "{below} {further}");
    assert!((above / below - 1.0).abs() > 0.15, "{above} {below}");
    // A range without an edge has none; an empty range or scan is refused.
    assert!(switch_sheet_edges_thornton(g, a, (0.45, 0.6), 0.01, 2048)
        .unwrap()
        .is_empty());
    assert!(switch_sheet_edges_thornton(g, a, (0.6, 0.45), 0.01, 2048).is_err());
    assert!(switch_sheet_edges_thornton(g, a, (0.45, 0.6), 0.0, 2048).is_err());
}

/// The end-of-contact sheet `e_E` of the stick patch: at γ 1.66 the contact ends in a `−μF_N`
/// episode below about `e_n` 0.33 and a `+` episode takes the end above it, on a sheet across
/// `e_n` nearly flat in α (0.3276 at 3 `α_c2`, 0.322 at 10) that the search along α misses;
/// `P`'s curvature in `e_n` jumps there.
#[test]
fn the_end_of_contact_sheet_lies_across_e_n() {
    let g = 1.66;
    let c2 = alpha_c2(g);
    let edge = |r: f64, steps: usize| {
        let edges = end_minus_sheet_edges_thornton(g, r * c2, (0.3, 0.45), 0.01, steps).unwrap();
        assert_eq!(edges.len(), 1, "{r} α_c2: {edges:?}");
        // An upper edge: the `−` episode ends the contact below it.
        assert!(!edges[0].1, "{edges:?}");
        edges[0].0
    };
    let e_e = edge(3.0, 2048);
    assert!((e_e - 0.32762).abs() < 1e-4, "{e_e}");
    assert!((edge(3.0, 8192) - e_e).abs() < 1e-5, "{e_e}");
    assert!((edge(10.0, 2048) - 0.3224).abs() < 1e-3);
    let a = 3.0 * c2;
    let ends_minus = |e: f64| has_end_minus(&slip_history_thornton(g, a, e, 2048).unwrap());
    assert!(ends_minus(e_e - 1e-5) && !ends_minus(e_e + 1e-5));
    // Along α at e_n = 0.33 the predicate does not change between 2.5 and 30 α_c2: the curves
    // E₋ of the search along α do not hold this sheet.
    let along = end_minus_edges_thornton(g, 0.33, (2.5 * c2, 30.0 * c2), 100, 2048).unwrap();
    assert!(along.is_empty(), "{along:?}");
    // At a fixed 8 192 steps the second differences of `P` along `e_n` (spacing 1e-3) keep their
    // value below the sheet (9.2e-5 at 1e-3 spacing) and grow about fourfold above it.
    let d2 = |e: f64| {
        let h = 1e-3;
        p_fixed(g, a, e - h, 8192) - 2.0 * p_fixed(g, a, e, 8192) + p_fixed(g, a, e + h, 8192)
    };
    let (below, further, above) = (d2(e_e - 3e-3), d2(e_e - 6e-3), d2(e_e + 4e-3));
    assert!((below / further - 1.0).abs() < 0.05, "{below} {further}");
    assert!(above / below > 3.0, "{above} {below}");
    // A range without an edge has none; an empty range or scan is refused.
    assert!(
        end_minus_sheet_edges_thornton(g, a, (0.34, 0.45), 0.01, 2048)
            .unwrap()
            .is_empty()
    );
    assert!(end_minus_sheet_edges_thornton(g, a, (0.45, 0.34), 0.01, 2048).is_err());
    assert!(end_minus_sheet_edges_thornton(g, a, (0.34, 0.45), 0.0, 2048).is_err());
}

#[test]
fn a_narrow_switch_zone_is_found_up_to_its_fold() {
    // γ = 2.6, e_n = 0.3: the clipped zone is a narrow hump of the gap to the unloading limit
    // inside one smooth stretch of a stuck piece, still about 0.02 of the radius wide 1e-5 below
    // α_S. Its search decides it by the gap's concavity, not by samples, so the fold converges
    // in the steps as at γ = 1.754 (0.309996367 / 0.309996398 at 2 048 / 8 192 steps).
    let (g, e) = (2.6, 0.3);
    let coarse = switch_fold_thornton(g, e, 2048).unwrap().expect("a fold");
    let fine = switch_fold_thornton(g, e, 8192).unwrap().expect("a fold");
    assert!((coarse - fine).abs() < 1e-6, "{coarse} {fine}");
    // The zone at 2 048 steps up to 2e-6 below the 8 192-step fold, inside the contact.
    let alpha = fine - 2e-6;
    assert!(has_switch_zone_thornton(g, alpha, e, 2048).unwrap());
    let zones = switch_zones_thornton(g, alpha, e, 2048).unwrap();
    let plus: Vec<&(i8, f64, f64)> = zones.iter().filter(|z| z.0 == 1).collect();
    assert_eq!(plus.len(), 1, "{zones:?}");
    let (_, x0, x1) = *plus[0];
    assert!(x0 > 0.8 && x1 < 0.95 && x1 - x0 > 1e-3, "{zones:?}");
}

#[test]
fn the_fold_minus_is_a_kink_of_p() {
    let (g, e) = (2.3, 0.6);
    // 0.434576669 / 0.434577100 / 0.434577208 at 2 048 / 4 096 / 8 192 steps.
    let coarse = fold_minus_thornton(g, e, 2048).unwrap().expect("a fold");
    let fine = fold_minus_thornton(g, e, 8192).unwrap().expect("a fold");
    assert!((coarse / fine - 1.0).abs() < 2e-6, "{coarse} {fine}");
    assert!((fine - 0.4345772).abs() < 1e-6, "{fine}");
    // Above the switch fold, inside the partial-slip patch.
    let switch = switch_fold_thornton(g, e, 2048)
        .unwrap()
        .expect("a switch fold");
    assert!(fine > 1.2 * switch && fine < alpha_c2(g), "{fine} {switch}");
    // The predicate: a `−μF_N` episode late in the restitution, inside the contact, below it.
    let late_minus = |a: f64| {
        slip_history_thornton(g, a, e, 8192)
            .unwrap()
            .episodes
            .iter()
            .any(|ep| ep.sign == SlipSign::Minus && ep.start > 0.5 && ep.end < 0.97)
    };
    assert!(late_minus(fine * (1.0 - 1e-4)));
    assert!(!late_minus(fine * (1.0 + 1e-4)));
    // A kink of `P`, not smooth on either side: at fixed steps the second differences
    // (spacing 1e-3 α_F) across it are 8.6 times those 3 % below (−0.0789 against −0.0091,
    // in units of the spacing), and next to it below they have risen already (−0.0109 at
    // 2e-3 α_F): the same at 8 192 and 32 768 steps, so not the steps' error.
    let d2 = |a: f64, steps: usize| {
        let h = 1e-3 * fine;
        (p_fixed(g, a - h, e, steps) - 2.0 * p_fixed(g, a, e, steps) + p_fixed(g, a + h, e, steps))
            / h
    };
    let (across, below, next) = (
        d2(fine, 8192),
        d2(0.97 * fine, 8192),
        d2(0.998 * fine, 8192),
    );
    assert!(across / below > 6.0, "{across} {below}");
    assert!(next / below > 1.1, "{next} {below}");
    let finer = d2(fine, 32768);
    assert!((finer / across - 1.0).abs() < 0.05, "{finer} {across}");
    // Born at lower γ the lower e_n: none at γ 1.8 (e_n 0.3), nor at γ 2.3 for e_n 0.99; at
    // e_n = 1 the elastic F₋ (0.45158 at γ 2.6).
    assert_eq!(fold_minus_thornton(1.8, 0.3, 2048).unwrap(), None);
    assert_eq!(fold_minus_thornton(2.3, 0.99, 2048).unwrap(), None);
    let elastic = fold_minus_thornton(2.6, 1.0, 2048)
        .unwrap()
        .expect("the elastic F-");
    assert!((elastic - 0.45158).abs() < 1e-4, "{elastic}");
    assert!(fold_minus_thornton(2.3, 0.2, 2048).is_err());
}

#[test]
fn the_end_of_contact_curves_continue_the_elastic_one() {
    // One E₋ at γ 1.8, e_n 0.7 (0.8501967 / 0.8501972 at 2 048 / 8 192 steps), inside the
    // partial-slip patch; at e_n = 1 the elastic E₋ itself (the same histories); two at e_n 0.3.
    let edges = |g: f64, e: f64, range: (f64, f64), steps: usize| {
        end_minus_edges_thornton(g, e, range, 100, steps).unwrap()
    };
    let coarse = edges(1.8, 0.7, (0.5, 5.0), 2048);
    let fine = edges(1.8, 0.7, (0.5, 5.0), 8192);
    assert_eq!((coarse.len(), fine.len()), (1, 1), "{coarse:?} {fine:?}");
    assert!(
        (coarse[0] / fine[0] - 1.0).abs() < 1e-6,
        "{coarse:?} {fine:?}"
    );
    assert!((fine[0] - 0.850197).abs() < 1e-5 && fine[0] < alpha_c2(1.8));
    let elastic = edges(1.8, 1.0, (0.5, 5.0), 2048);
    let direct = end_minus_at(1.8, 2.5, 2048)
        .unwrap()
        .expect("the elastic E-");
    assert_eq!(elastic.len(), 1);
    assert!(
        (elastic[0] / direct - 1.0).abs() < 1e-9,
        "{elastic:?} {direct}"
    );
    let low = end_minus_edges_thornton(1.75, 0.3, (0.2, 30.0), 200, 2048).unwrap();
    assert_eq!(low.len(), 2, "{low:?}");
    assert!(
        (low[0] - 0.4235).abs() < 1e-3 && (low[1] - 14.765).abs() < 0.05,
        "{low:?}"
    );
    assert!(end_minus_edges_thornton(1.8, 0.7, (5.0, 0.5), 100, 2048).is_err());
}

#[test]
fn the_plus_strip_rises_with_e_n_into_the_stick_patch() {
    let g = 2.3;
    let c2 = alpha_c2(g);
    // γ 2.3, e_n 0.55: 1.626512549–1.774265662 at 8 192 steps, 1.626512743–1.774266532 at
    // 16 384; the lower edge (where the episode is born) needs the finer steps: 1.6263 at 2 048.
    let (lo, hi) = restitution_plus_strip_thornton(g, 0.55, 8192)
        .unwrap()
        .expect("the strip");
    let (lo2, hi2) = restitution_plus_strip_thornton(g, 0.55, 16384)
        .unwrap()
        .expect("the strip");
    assert!(
        (lo / lo2 - 1.0).abs() < 1e-6 && (hi / hi2 - 1.0).abs() < 1e-6,
        "{lo} {hi}"
    );
    assert!(lo > c2 && (lo / c2 - 1.0761).abs() < 1e-3 && (hi / c2 - 1.1739).abs() < 1e-3);
    // At e_n 0.3 in the partial-slip patch (0.3807–0.4007 α_c2), gone at 0.6.
    let (lo3, hi3) = restitution_plus_strip_thornton(g, 0.3, 2048)
        .unwrap()
        .expect("the strip");
    assert!((lo3 / c2 - 0.3807).abs() < 1e-3 && (hi3 / c2 - 0.4007).abs() < 1e-3);
    assert_eq!(restitution_plus_strip_thornton(g, 0.6, 2048).unwrap(), None);
    // The predicate between the edges and not outside.
    let plus = |a: f64| {
        let h = slip_history_thornton(g, a, 0.55, 8192).unwrap();
        h.episodes
            .iter()
            .any(|ep| ep.sign == SlipSign::Plus && ep.start > 0.5 && ep.end < 0.97)
    };
    assert!(plus(0.5 * (lo + hi)) && !plus(lo * 0.999) && !plus(hi * 1.001));
}
