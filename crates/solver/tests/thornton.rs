//! Thornton's elastic–perfectly plastic law (`physics.md`, "Elastic–plastic impacts"): the
//! continuum row converges at second order, leaves the full-slip line as the independent
//! prototype measured, and is the elastic row where the limiting pressure is never reached.

use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_p, elastic_peak_pressure, yield_pressure_for_restitution,
};
use oblique_solver::{Request, Resolution};

/// `P` of the dimensionless Thornton impact at `(γ, α, e_n)` on `steps` steps.
fn p(gamma: f64, alpha: f64, e_n: f64, steps: usize) -> f64 {
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n).unwrap());
    let shear = 2.0 / 7.0 * gamma * gamma;
    dimensionless_p(shear, alpha / shear, &motion, steps)
}

/// Successive differences fall by 4 per doubling (second order in time), through the switch
/// to unloading, at small and large γ, α and e_n.
#[test]
fn the_row_converges_at_second_order() {
    for (gamma, alpha, e_n) in [
        (0.5, 1.0, 0.9),
        (1.754, 0.3, 0.3),
        (1.754, 1.0, 0.3),
        (3.0, 1.0, 0.3),
        (3.0, 3.0, 0.9),
        (1.754, 0.1, 0.8),
    ] {
        let v: Vec<f64> = [2048, 4096, 8192]
            .iter()
            .map(|&n| p(gamma, alpha, e_n, n))
            .collect();
        let ratio = (v[1] - v[0]) / (v[2] - v[1]);
        assert!(
            (3.3..=4.7).contains(&ratio),
            "γ {gamma} α {alpha} e_n {e_n}: ratio {ratio} ({v:?})"
        );
    }
}

/// `physics.md`: Thornton's unloading makes the limits jump at the switch, the central
/// springs stick for a moment, and `P` leaves the full-slip line `1 − (7/2)(1 + e_n) α` by
/// 2.0e-5 at α = 0.05 and 1.0e-4 at 0.1 (γ = 1.754, e_n = 0.8; an independent prototype, first
/// order near the switch, to its two digits), and by a few 1e-7 at α = 0.01 (4.7e-7 there).
/// Richardson values of 8192 and 16384 steps.
#[test]
fn the_full_slip_line_is_left_as_the_prototype_measured() {
    let (gamma, e_n) = (1.754, 0.8);
    for (alpha, want, within) in [
        (0.01, 4.7e-7, 4e-7),
        (0.05, 2.0e-5, 2.5e-6),
        (0.1, 1.0e-4, 1e-5),
    ] {
        let (a, b) = (p(gamma, alpha, e_n, 8192), p(gamma, alpha, e_n, 16384));
        let value = b + (b - a) / 3.0;
        let departure = value - (1.0 - 3.5 * (1.0 + e_n) * alpha);
        assert!(
            departure > 0.0 && (departure - want).abs() < within,
            "α {alpha}: departure {departure:e} against {want:e}"
        );
    }
}

/// Below the yield speed (`p_y` above the elastic peak pressure `p_0`) the law is the elastic
/// one: the same P as the elastic solver's continuum row to the time error of either.
#[test]
fn below_the_yield_speed_the_row_is_the_elastic_one() {
    let motion = dimensionless_motion(1.01 * elastic_peak_pressure());
    assert!(motion.plastic.is_none());
    for (gamma, alpha) in [(0.5, 0.3), (1.754, 1.0), (3.0, 3.0)] {
        let shear = 2.0 / 7.0 * gamma * gamma;
        let res = Resolution {
            springs: 0,
            steps: 4096,
        };
        let elastic = Request::new(gamma, alpha).simulate(res).unwrap();
        let thornton = dimensionless_p(shear, alpha / shear, &motion, 4096);
        assert!(
            (elastic - thornton).abs() < 2e-7,
            "γ {gamma} α {alpha}: {thornton} against {elastic}"
        );
    }
}
