//! Integration tests of the solver's convergence and error estimates: the accurate scheme's
//! order on the refinement ladder against converged references, and error estimates that bound
//! the true error (including pre-asymptotic plateaus and fixed resolutions). References are
//! simulations at a much higher resolution than the run under test.

use oblique_solver::impact::base_resolution;
use oblique_solver::{Accuracy, Method, NoEstimate, Request, Resolution, Scheme};

const ACC: Scheme = Scheme::Accurate;

fn res(springs: usize, steps: usize) -> Resolution {
    Resolution { springs, steps }
}

// ---------------------------------------------------------------------------------------------
// 5. Convergence and error estimates.
// ---------------------------------------------------------------------------------------------

/// The accurate scheme's error against a converged reference, on the refinement ladder of
/// `solve` (base resolution doubled 1..=5 times), must fall by ≥ 3.3 per doubling.
///
/// Why 3.3 and not 4: the ladder starts in the pre-asymptotic range, where the error constant
/// `err·steps²` still drifts. With the continuum row (no spatial error left) the time error at
/// γ = 1.754, α = 1 falls by 3.39, 3.57, 3.53, 3.77 per doubling from 128 to 2048 steps (161×
/// over four doublings, order 1.83) and by 4.07, 3.78 further on (to 16384 steps); at γ = 0.5,
/// α = 1 by 3.38 … 4.15 (195×). 3.3 per doubling and 150× overall (order ≥ 1.8) still reject
/// any order ≤ 1.7 (2^1.5 = 2.83 per doubling, 64× overall).
///
/// A level whose error is within the scatter left by events inside the steps (0.05/N² at `N`
/// steps, `Floor::scatter`'s measure) is not held to the ratio: at γ = 1.754, α = 1 the smooth
/// part of the error nearly vanishes once the onset of gross slip is located (`C` ≈ 0.03), and
/// the errors at 1024 and 2048 steps were 6.1e-10 and 1.0e-8, both within it.
fn check_second_order(g: f64, a: f64) {
    let (errs, ratios, summary) = convergence_ladder(g, a);
    let steps = convergence_steps(g);
    let scattered = |k: usize| errs[k + 1] <= 0.05 / (steps[k + 1] as f64).powi(2);
    assert!(
        ratios
            .iter()
            .enumerate()
            .all(|(k, &r)| r >= 3.3 || scattered(k))
            && errs[0] / errs[4] >= 150.0,
        "not second order: {summary}"
    );
}

/// The steps of the levels [`convergence_ladder`] measures.
fn convergence_steps(g: f64) -> Vec<usize> {
    let base = base_resolution(g, ACC);
    (1..=5).map(|k| base.doubled(k).steps).collect()
}

/// Errors on the refinement ladder of `solve` (base resolution doubled 1..=5 times: the
/// continuum row, exact in space) against the Richardson extrapolation of continuum runs at
/// 16384 and 32768 steps, the ratios per doubling and a printable summary.
fn convergence_ladder(g: f64, a: f64) -> (Vec<f64>, Vec<f64>, String) {
    let fine = Request::new(g, a)
        .scheme(ACC)
        .simulate(res(0, 32768))
        .unwrap();
    let coarse = Request::new(g, a)
        .scheme(ACC)
        .simulate(res(0, 16384))
        .unwrap();
    let reference = fine + (fine - coarse) / 3.0;
    let base = base_resolution(g, ACC);
    let errs: Vec<f64> = (1..=5)
        .map(|k| {
            (Request::new(g, a)
                .scheme(ACC)
                .simulate(base.doubled(k))
                .unwrap()
                - reference)
                .abs()
        })
        .collect();
    let ratios: Vec<f64> = errs.windows(2).map(|w| w[0] / w[1]).collect();
    let errs_s: Vec<String> = errs.iter().map(|e| format!("{e:.3e}")).collect();
    let ratios_s: Vec<String> = ratios.iter().map(|r| format!("{r:.2}")).collect();
    let summary = format!(
        "gamma = {g}, alpha = {a}: steps {}..{}, errors [{}], ratios [{}], total {:.0}",
        base.doubled(1).steps,
        base.doubled(5).steps,
        errs_s.join(", "),
        ratios_s.join(", "),
        errs[0] / errs[4]
    );
    eprintln!("convergence {summary}");
    (errs, ratios, summary)
}

#[test]
fn convergence_gamma_1754_alpha_1() {
    check_second_order(1.754, 1.0);
}

#[test]
fn convergence_gamma_1754_no_slip() {
    check_second_order(1.754, f64::INFINITY);
}

#[test]
fn convergence_gamma_05_alpha_1() {
    check_second_order(0.5, 1.0);
}

#[test]
fn convergence_gamma_05_no_slip() {
    check_second_order(0.5, f64::INFINITY);
}

#[test]
fn convergence_gamma_3_alpha_4_stick_by_component() {
    // α_c2(3) = 2.57: α = 4 sticks during compression. At this γ the spring (spatial) error is
    // clean and dominant, the time error small and irregular; on the joint ladder the two
    // partly cancel (opposite signs), so each component is checked on its own.
    let (g, a) = (3.0, 4.0);
    let reference = Request::new(g, a)
        .scheme(ACC)
        .simulate(res(16384, 65536))
        .unwrap();
    let spatial: Vec<f64> = (0..5)
        .map(|k| {
            (Request::new(g, a)
                .scheme(ACC)
                .simulate(res(64 << k, 65536))
                .unwrap()
                - reference)
                .abs()
        })
        .collect();
    let ratios: Vec<f64> = spatial.windows(2).map(|w| w[0] / w[1]).collect();
    assert!(
        ratios.iter().all(|&r| r >= 3.5),
        "spatial error not second order: {spatial:?} ratios {ratios:?}"
    );
    let (errs, _, summary) = convergence_ladder(g, a);
    assert!(
        errs[0] / errs[4] >= 200.0,
        "not second order overall: {summary}"
    );
}

/// Partial slip at large γ (γ = 3, α = 1 lies between α_c1 = 0.15 and α_c2 = 2.57). The two
/// error components are checked on their own (`examples/errsplit.rs` prints the full table):
/// the spatial error (springs, at 4096 steps) is clean second order; the time error (steps, at
/// 16384 springs) is O(h²) but irregular (kinks of the friction force inside steps: measured
/// ratios 5.4, 1.7, 4.6, 5.0 per doubling from 256 steps), so it must fall ≥ 200× over four
/// doublings (order ≥ 1.9) and never grow. On the joint ladder of `solve` (one spring per step)
/// the spatial error (positive) cancels part of the time error (negative): one doubling there
/// gains nothing (6.8e-6 at 512 and at 1024 steps), so only the overall order is asserted on it.
/// That `solve`'s error estimate still bounds the true error here is checked by
/// `error_estimate_bounds_the_true_error`, which includes this point.
#[test]
fn convergence_gamma_3_alpha_1_partial_slip_overall_order() {
    let (g, a) = (3.0, 1.0);
    let reference = Request::new(g, a)
        .scheme(ACC)
        .simulate(res(16384, 16384))
        .unwrap();
    let spatial: Vec<f64> = (0..4)
        .map(|k| {
            (Request::new(g, a)
                .scheme(ACC)
                .simulate(res(128 << k, 4096))
                .unwrap()
                - reference)
                .abs()
        })
        .collect();
    let ratios: Vec<f64> = spatial.windows(2).map(|w| w[0] / w[1]).collect();
    assert!(
        ratios.iter().all(|&r| r >= 3.5),
        "spatial error not second order: {spatial:?} ratios {ratios:?}"
    );
    let time: Vec<f64> = (0..5)
        .map(|k| {
            (Request::new(g, a)
                .scheme(ACC)
                .simulate(res(16384, 256 << k))
                .unwrap()
                - reference)
                .abs()
        })
        .collect();
    let ratios: Vec<f64> = time.windows(2).map(|w| w[0] / w[1]).collect();
    assert!(
        time[0] / time[4] >= 200.0 && ratios.iter().all(|&r| r > 1.0),
        "time error not second order overall: {time:?} ratios {ratios:?}"
    );
    let (errs, _, summary) = convergence_ladder(g, a);
    assert!(
        errs[0] / errs[4] >= 200.0,
        "not second order overall: {summary}"
    );
}

#[test]
fn convergence_gamma_3_no_slip() {
    check_second_order(3.0, f64::INFINITY);
}

/// `solve` with a tolerance: the true error, measured against a run at ≥ 4x the returned
/// resolution (and ≥ 8192 steps), must not exceed the tolerance nor the reported error
/// estimate. γ = 1.754, α = 1 at tol 1e-4 is accepted at 256 steps after differences that
/// turn (ratios −6.3, 4.13) with a true error of 1.50e-6: a floor of 0.1 of the last
/// difference stated 1.15e-6 there (1.31× below), the irregular floor of 0.2 states 2.3e-6.
#[test]
fn error_estimate_bounds_the_true_error() {
    let points = [
        (0.5, 0.3),
        (0.5, f64::INFINITY),
        (0.8, 1.0),
        (0.8, f64::INFINITY),
        (1.2, 0.6),
        (1.754, 0.3),
        (1.754, 1.0),
        (1.754, 2.0),
        (1.754, f64::INFINITY),
        (2.2, 0.6),
        (2.2, 1.0),
        (3.0, 1.0),
        (3.0, f64::INFINITY),
    ];
    let mut failures = Vec::new();
    let mut checked = 0;
    for &(g, a) in &points {
        for &tol in &[1e-4, 1e-5] {
            let s = Request::new(g, a)
                .accuracy(Accuracy::Tolerance(tol))
                .scheme(ACC)
                .forced(true)
                .solve()
                .unwrap();
            assert_eq!(s.method, Method::Simulated);
            assert!(s.error_estimate <= tol);
            let mut k = 2;
            while s.resolution.doubled(k).steps < 8192 {
                k += 1;
            }
            let reference = Request::new(g, a)
                .scheme(ACC)
                .simulate(s.resolution.doubled(k))
                .unwrap();
            let err = (s.p - reference).abs();
            checked += 1;
            assert!(
                err <= tol,
                "gamma = {g}, alpha = {a}: error {err:e} > tol {tol:e}"
            );
            if err > s.error_estimate {
                failures.push(format!(
                    "gamma = {g}, alpha = {a}, tol = {tol:e}: |P - P_ref| = {err:.3e} > \
                     estimate {:.3e} (x{:.2}) at {} steps",
                    s.error_estimate,
                    err / s.error_estimate,
                    s.resolution.steps
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {checked} error estimates are below the true error:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Where the differences shrink regularly but below the nominal ratio 4 (3.25 and 3.75 before
/// 4096 steps at γ = 1.754, α = 1), the Richardson value keeps more of the error than it
/// assumes: at tol 1e-8 it erred by 3.00e-9 against a tol 1e-10 reference while a floor of
/// 0.1 of the last difference stated 2.61e-9. The share of a tail at the ratios seen states
/// 4.3e-9.
#[test]
fn the_estimate_covers_a_tail_slower_than_the_order() {
    let solve = |tol: f64| {
        Request::new(1.754, 1.0)
            .accuracy(Accuracy::Tolerance(tol))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap()
    };
    let reference = solve(1e-10);
    let s = solve(1e-8);
    let err = (s.p - reference.p).abs();
    assert!(
        err > 2.0 * reference.error_estimate,
        "the reference is not fine enough to measure {err:e}"
    );
    assert!(
        err <= s.error_estimate,
        "|P - P_ref| = {err:.3e} > estimate {:.3e} at {} steps",
        s.error_estimate,
        s.resolution.steps
    );
}

/// Regression: a pre-asymptotic plateau must not pass for convergence. At γ = 1.80378 and
/// α ≈ 5.148 (stick; a short slip episode that 256 steps do not resolve) the values at 64–256
/// steps agree to 1e-5 but sit 1.5–2.4e-5 below the converged value; a three-level estimate
/// accepted them at tol = 2e-6 with a true error of 2.5e-5 (found by the isotropic table's
/// refinement). Along the slice every result must meet the tolerance asked for, against a
/// reference solved to 1e-8. (Where the guard makes `solve` go on to 2048 steps, the estimate is
/// 3.8e-8 and the true error up to 8e-8: far below the tolerance, so not asserted here.)
#[test]
fn error_estimate_is_not_fooled_by_a_pre_asymptotic_plateau() {
    let g = 1.80378;
    let mut failures = Vec::new();
    for i in 0..11 {
        let a = 5.140 + 0.001 * i as f64;
        let reference = Request::new(g, a)
            .accuracy(Accuracy::Tolerance(1e-8))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap();
        for &tol in &[2e-6, 1e-5] {
            let s = Request::new(g, a)
                .accuracy(Accuracy::Tolerance(tol))
                .scheme(ACC)
                .forced(true)
                .solve()
                .unwrap();
            let err = (s.p - reference.p).abs();
            if err > tol {
                failures.push(format!(
                    "alpha = {a}, tol = {tol:e}: |P - P_ref| = {err:.2e} > tol (estimate {:.2e} at {} steps)",
                    s.error_estimate, s.resolution.steps
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Regression: next to the fold where a gross-slip episode of the restitution phase is born
/// (the stick patch at γ ≈ 2, α just above `α_c2`), `P` at `N` steps scatters around its smooth
/// convergence by up to about 1.2/N² while the differences between levels look converged, and
/// the estimates at tol 1e-6 were the row's floor 0.1/N² (2.38e-8 at 2 048 steps) for errors of
/// 0.9–1.5e-7 at these four points (the dense grid of `docs/solver.md`, "Error estimates"). The
/// zone before gross slip lasts under 0.05 `t_c` there, and the estimate keeps 1.5/N², at a
/// fixed resolution too. Reference: the Richardson value of 16 384 and 32 768 steps.
#[test]
fn the_estimate_bounds_the_error_where_a_gross_slip_episode_is_born() {
    let mut failures = Vec::new();
    for (g, a) in [(2.11, 1.40), (2.14, 1.55), (2.05, 2.05), (2.03, 2.35)] {
        let at = |steps| Request::new(g, a).simulate(res(0, steps)).unwrap();
        let (fine, finer) = (at(16384), at(32768));
        let reference = finer + (finer - fine) / 3.0;
        let s = Request::new(g, a)
            .accuracy(Accuracy::Tolerance(1e-6))
            .forced(true)
            .solve()
            .unwrap();
        let err = (s.p - reference).abs();
        if err > s.error_estimate {
            failures.push(format!(
                "gamma {g}, alpha {a}: error {err:.2e} > estimate {:.2e} at {} steps",
                s.error_estimate, s.resolution.steps
            ));
        }
        // The estimate of a fixed resolution from its halved runs keeps the same floor
        // (γ = 2.11, α = 1.40 at 2 048 steps: 1.03e-7 stated for an error of 1.84e-7 before).
        let fixed = Request::new(g, a)
            .accuracy(Accuracy::Fixed(res(0, 2048)))
            .solve()
            .unwrap();
        let err = (fixed.p - reference).abs();
        if fixed.estimate().is_some_and(|est| err > est) {
            failures.push(format!(
                "gamma {g}, alpha {a}, 2048 steps: error {err:.2e} > estimate {:.2e}",
                fixed.error_estimate
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// At a fixed resolution the error estimate is either absent or at least the true error, over
/// a grid of resolutions (springs 2–1024 and the continuum row, 8–1024 steps, both schemes) at
/// points in every regime, including the reproducers where the half-resolution difference used
/// before under-stated the error 10³–10⁴× (γ = 1.7, α = 1: 2 springs × 1024 steps gave ±1.6e-5
/// for an error of 0.44; 1024 × 8 gave ±2.9e-6 for 0.034; 2 × 8 gave ±0; Euler 8 × 32 gave
/// ±7.4e-3 for 0.10). References: the automatic refinement to 1e-9.
#[test]
fn fixed_resolution_estimate_is_absent_or_bounds_the_true_error() {
    let points = [
        (1.7, 1.0),
        (1.754, 0.5),
        (0.8, 0.3),
        (3.2, 1.3),
        (2.5, f64::INFINITY),
        (0.5, 1e3),
        (1.2, 0.25),
        (0.3, 0.05),
        (1.0, 0.5),
        (5.0, 1.0),
        (0.1, 1e9),
        (2.16, 0.35),
    ];
    let (mut given, mut absent) = (0, 0);
    let mut failures = Vec::new();
    let mut ratios = Vec::new();
    for &(g, a) in &points {
        let reference = Request::new(g, a)
            .accuracy(Accuracy::Tolerance(1e-9))
            .scheme(ACC)
            .solve()
            .unwrap()
            .p;
        for scheme in [Scheme::Accurate, Scheme::Euler] {
            for springs in [0, 2, 8, 64, 1024] {
                if springs == 0 && scheme == Scheme::Euler {
                    continue;
                }
                for steps in [8, 32, 256, 1024] {
                    let s = Request::new(g, a)
                        .accuracy(Accuracy::Fixed(res(springs, steps)))
                        .scheme(scheme)
                        .forced(true)
                        .solve()
                        .unwrap_or_else(|e| panic!("{g}, {a}, {springs} x {steps}: {e}"));
                    let err = (s.p - reference).abs();
                    match (s.estimate(), s.no_estimate) {
                        (Some(est), None) => {
                            given += 1;
                            if err > 1e-12 {
                                ratios.push(est / err);
                            }
                            assert!(est.is_finite() && s.error_estimate == est);
                            if est < err {
                                failures.push(format!(
                                    "gamma = {g}, alpha = {a}, {} {springs} x {steps}: \
                                     estimate {est:.2e} < error {err:.2e}",
                                    scheme.name()
                                ));
                            }
                        }
                        (None, Some(why)) => {
                            absent += 1;
                            // No estimate reads as an infinite one: a tolerance check fails safe.
                            assert_eq!(s.error_estimate, f64::INFINITY);
                            assert!(!why.to_string().is_empty());
                        }
                        other => panic!("estimate and reason disagree: {other:?}"),
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // Both outcomes occur: the check above is not vacuous.
    assert!(
        given >= 60 && absent >= 60,
        "{given} estimates, {absent} without"
    );
    ratios.sort_by(f64::total_cmp);
    eprintln!(
        "{given} estimates given, {absent} refused; estimate/error from {:.2} (median {:.1}) to \
         {:.0}",
        ratios[0],
        ratios[ratios.len() / 2],
        ratios[ratios.len() - 1]
    );
    // The reproducers: none of them gets an estimate any more.
    for (springs, steps, scheme) in [
        (2, 1024, ACC),
        (1024, 8, ACC),
        (2, 8, ACC),
        (8, 32, Scheme::Euler),
    ] {
        let s = Request::new(1.7, 1.0)
            .accuracy(Accuracy::Fixed(res(springs, steps)))
            .scheme(scheme)
            .forced(true)
            .solve()
            .unwrap();
        assert_eq!(s.estimate(), None, "{springs} x {steps}: {s:?}");
    }
}

/// `P` at every step count from 1000 to 1040: its scatter around the least-squares fit
/// `P∞ + C/N²`, times `N²`.
fn scatter_n2(gamma: f64, alpha: f64, e_n: f64) -> (f64, f64) {
    let req = Request::new(gamma, alpha).e_n(e_n);
    let ns: Vec<f64> = (1000..=1040).map(|n| n as f64).collect();
    let ps: Vec<f64> = ns
        .iter()
        .map(|&n| {
            req.simulate(res(0, n as usize))
                .expect("simulation at a fixed resolution")
        })
        .collect();
    let xs: Vec<f64> = ns.iter().map(|n| 1.0 / (n * n)).collect();
    let m = xs.len() as f64;
    let (sx, sy) = (xs.iter().sum::<f64>(), ps.iter().sum::<f64>());
    let sxx: f64 = xs.iter().map(|x| x * x).sum();
    let sxy: f64 = xs.iter().zip(&ps).map(|(x, p)| x * p).sum();
    let c = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    let p_inf = (sy - c * sx) / m;
    let scatter = xs
        .iter()
        .zip(&ps)
        .map(|(x, p)| (p - p_inf - c * x).abs())
        .fold(0.0_f64, f64::max);
    (scatter * 1e6, c)
}

/// The onset of gross slip inside a step is located and the step split there: without it, `P`
/// at γ = 3, α = 1 (and γ = 2.5, α = 0.9, `e_n` = 0.95) scattered by up to `4/N²` around its
/// smooth convergence, depending on where in the step the onset fell, as large as its smooth
/// error `C/N²` (`|C|` ≈ 11.5 and 4.7); located, by at most 0.05/N².
#[test]
fn the_error_does_not_depend_on_where_gross_slip_starts_in_a_step() {
    for (g, a, e) in [(3.0, 1.0, 1.0), (2.5, 0.9, 0.95)] {
        let (scatter, c) = scatter_n2(g, a, e);
        assert!(
            scatter < 0.2 && scatter < 0.05 * c.abs(),
            "γ {g}, α {a}, e_n {e}: scatter {scatter:.3}/N² against C = {c:.3}"
        );
    }
}

/// Where a stuck part of the contact shrinks to nothing before gross slip, the levels may
/// converge like `1/N²` only once that zone spans several steps (`oblique_solver::zones`). At
/// γ = 2, α = 1.45 the zone lasts 0.007 `t_c`; the differences from 128 to 512 steps shrank by
/// 3.87, and tol 1e-6 accepted 512 steps with an error of 2.57e-6 (estimate 5.1e-7). The
/// reference is the Richardson value of 16 384 and 32 768 steps.
#[test]
fn a_level_is_accepted_only_once_the_approach_to_gross_slip_is_resolved() {
    for (g, a, tol) in [(2.0, 1.45, 1e-6), (2.0, 1.45, 2e-6)] {
        let req = Request::new(g, a).scheme(ACC);
        let s = req
            .accuracy(Accuracy::Tolerance(tol))
            .forced(true)
            .solve()
            .unwrap();
        let fine = |steps| req.simulate(res(0, steps)).unwrap();
        let (p1, p2) = (fine(16384), fine(32768));
        let reference = p2 + (p2 - p1) / 3.0;
        let err = (s.p - reference).abs();
        assert!(
            err <= tol && err <= s.error_estimate.max(1e-8),
            "gamma = {g}, alpha = {a}, tol = {tol:e}: |P - P_ref| = {err:.3e}, estimate {:.3e} \
             at {} steps",
            s.error_estimate,
            s.resolution.steps
        );
    }
}

/// A fixed resolution whose approach to gross slip spans fewer than 8 steps states no estimate
/// (γ = 2, α = 1.45: 4.1 steps at 512, where the error is 9e-7 and the differences of the
/// halved runs, 5.1e-6 and 2.0e-5, shrink by 3.9 as if second order); at 4096 steps it does.
#[test]
fn a_fixed_resolution_that_does_not_resolve_the_approach_to_gross_slip_has_no_estimate() {
    let at = |steps| {
        Request::new(2.0, 1.45)
            .accuracy(Accuracy::Fixed(res(0, steps)))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap()
    };
    let coarse = at(512);
    assert!(
        matches!(coarse.no_estimate, Some(NoEstimate::Unresolved { zone_steps, steps: 512 }) if zone_steps < 8.0),
        "{:?}",
        coarse.no_estimate
    );
    assert_eq!(coarse.error_estimate, f64::INFINITY);
    let fine = at(4096);
    assert!(!matches!(
        fine.no_estimate,
        Some(NoEstimate::Unresolved { .. })
    ));
}

/// Where the limits stop the refinement after an estimate within the tolerance that was not
/// accepted because its level did not resolve the approach to gross slip, the error says so
/// (γ = 2, α = 1.45, tol 3e-6, at most 1024 steps: the zone spans 7.3 steps there).
#[test]
fn an_unresolved_level_at_the_limit_is_named_in_the_error() {
    let limits = oblique_solver::impact::Limits {
        max_steps: 1024,
        ..Default::default()
    };
    let err = Request::new(2.0, 1.45)
        .scheme(ACC)
        .accuracy(Accuracy::Tolerance(3e-6))
        .limits(limits)
        .solve()
        .unwrap_err();
    assert!(
        matches!(
            err,
            oblique_solver::PhysicsError::ToleranceUnreachable { zone_steps, achieved, .. }
                if zone_steps < 8.0 && achieved <= 3e-6
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("fewer than"), "{err}");
}

/// `P` on a fixed grid is continuous in the parameters down to the rounding where the contact
/// slips as a whole: the rounding noise of the gap to gross slip is not read as an onset inside
/// a step. Before, γ moved by a few ulps moved `P` by up to about 2e-7 at 256 steps at these
/// points (elastic, and Kelvin–Voigt at `e_n` = 0.81), where steps in gross slip were split
/// or not by that noise.
#[test]
fn p_on_a_fixed_grid_is_continuous_in_gamma_through_gross_slip() {
    for (gamma, alpha, e_n, steps) in [
        (3.395117, 0.6032324, 1.0, 256),
        (4.284570, 0.1185093, 1.0, 256),
        (3.105078, 0.9877476, 1.0, 1024),
        (2.457031, 0.1773, 0.81, 256),
    ] {
        let p_at = |g: f64| {
            Request::new(g, alpha)
                .e_n(e_n)
                .forced(true)
                .simulate(res(0, steps))
                .expect("solvable")
        };
        let base = p_at(gamma);
        for k in 1..=12 {
            let p = p_at(gamma * (1.0 + k as f64 * f64::EPSILON));
            assert!(
                (p - base).abs() <= 1e-12,
                "γ = {gamma} + {k} ulps, α = {alpha}, e_n = {e_n}, {steps} steps: {p} against {base}"
            );
        }
    }
}
