//! Critical values of α (`α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`), friction regimes and the
//! closed forms of `P(γ, α)`.

use serde::Serialize;

/// `α_c1 = 2γ²/(7(2γ² − 1))`.
#[inline]
pub fn alpha_c1(gamma: f64) -> f64 {
    alpha_c1_of_squared(gamma * gamma)
}

/// `α_c1` from `γ²` (for callers that hold `γ²` already; the same operations as
/// [`alpha_c1`]). Where `7(2γ² − 1)` overflows (`γ ≳ 3.6e153`), the same value as
/// `1/(7(1 − 1/(2γ²)))`, which does not (`1/7`, the limit); elsewhere these exact operations,
/// whose bits the tables, `oblique_eval.h` and `scripts/read_table.py` share.
#[inline(always)]
pub fn alpha_c1_of_squared(g2: f64) -> f64 {
    let d = 7.0 * (2.0 * g2 - 1.0);
    if d == f64::INFINITY {
        return 1.0 / (7.0 * (1.0 - 1.0 / (2.0 * g2)));
    }
    2.0 * g2 / d
}

/// `α_c2 = 2γ²/7`.
#[inline]
pub fn alpha_c2(gamma: f64) -> f64 {
    2.0 * gamma * gamma / 7.0
}

/// Upper end of the exact line `P = 1 − 7α`: `α_c1` for `γ > 1`, `α_c2` for `γ ≤ 1`.
#[inline]
pub fn linear_limit(gamma: f64) -> f64 {
    if gamma > 1.0 {
        alpha_c1(gamma)
    } else {
        alpha_c2(gamma)
    }
}

/// Friction regime of an impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Regime {
    /// The whole contact slips throughout: `P = 1 − 7α`.
    FullSlip,
    /// Part of the contact sticks (between the critical curves).
    PartialSlip,
    /// No slip during compression (`α ≥ α_c2`), including `α = ∞`.
    Stick,
}

impl Regime {
    /// Classify `(γ, α)`.
    pub fn of(gamma: f64, alpha: f64) -> Self {
        if alpha <= linear_limit(gamma) {
            Regime::FullSlip
        } else if alpha < alpha_c2(gamma) {
            Regime::PartialSlip
        } else {
            Regime::Stick
        }
    }

    /// Classify `(γ, α)` for normal restitution `e_n` (Kelvin–Voigt law): full slip up to
    /// [`linear_limit_dissipative`]; `α_c2`, where the contact sticks at first touch
    /// (`|u0| ≤ c v_z0`), does not move with `e_n`. `e_n = 1` is [`Regime::of`].
    pub fn of_dissipative(gamma: f64, alpha: f64, e_n: f64) -> Self {
        if alpha <= linear_limit_dissipative(gamma, e_n) {
            Regime::FullSlip
        } else if alpha < alpha_c2(gamma) {
            Regime::PartialSlip
        } else {
            Regime::Stick
        }
    }

    /// Lower-case name as printed by the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Regime::FullSlip => "full-slip",
            Regime::PartialSlip => "partial-slip",
            Regime::Stick => "stick",
        }
    }
}

/// `P(γ, α)` where it is known exactly without simulation: the full-slip line `1 − 7α` for
/// `α ≤` [`linear_limit`] and the `γ = 1` plateau `P = −1` for `α ≥ 2/7`.
pub fn closed_form(gamma: f64, alpha: f64) -> Option<f64> {
    if alpha <= linear_limit(gamma) {
        Some(1.0 - 7.0 * alpha)
    } else if gamma == 1.0 && alpha >= 2.0 / 7.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// `α_c1(e_n) = 2γ²/(7(γ²(1 + e_n) − e_n))`: the end of the full-slip line of a dissipative
/// impact with normal restitution `e_n` (Kelvin–Voigt law, `physics.md`); `e_n = 1` gives
/// [`alpha_c1`]. Meaningful for `γ > 1`.
#[inline]
pub fn alpha_c1_dissipative(gamma: f64, e_n: f64) -> f64 {
    let g2 = gamma * gamma;
    let d = 7.0 * (g2 * (1.0 + e_n) - e_n);
    if d == f64::INFINITY {
        // γ² or the denominator overflows: `2/(7((1 + e_n) − e_n/γ²))`, the same value
        // (`2/(7(1 + e_n))` in the limit; `1/7`, [`alpha_c1`]'s, at `e_n = 1`).
        return 2.0 / (7.0 * ((1.0 + e_n) - e_n / g2));
    }
    2.0 * g2 / d
}

/// Upper end of the exact line `P = 1 − (7/2)(1 + e_n) α` of a dissipative impact:
/// [`alpha_c1_dissipative`] for `γ > 1`, `α_c2` for `γ ≤ 1` (measured with this project's
/// Kelvin–Voigt solver at γ = 0.5, 0.8, 0.95, 1: the line holds to 2e-7 up to 0.99 α_c2 and
/// departs at 1.01 α_c2, as in the elastic case).
#[inline]
pub fn linear_limit_dissipative(gamma: f64, e_n: f64) -> f64 {
    if gamma > 1.0 {
        alpha_c1_dissipative(gamma, e_n)
    } else {
        alpha_c2(gamma)
    }
}

/// The full-slip line of an impact with normal restitution `e_n`: the tangential impulse is
/// `μ (1 + e_n) m* v_z0`, so `P = 1 − (7/2)(1 + e_n) α` (`1 − 7α` at `e_n = 1`).
#[inline]
pub fn full_slip_line(alpha: f64, e_n: f64) -> f64 {
    1.0 - 3.5 * (1.0 + e_n) * alpha
}

/// Tangential restitution `e_t = v_x/v_x0 = (2P + 5)/7` of a solid sphere hitting without spin.
pub fn tangential_restitution(p: f64) -> f64 {
    (2.0 * p + 5.0) / 7.0
}

/// Tangential restitution of the centre, `e_t = v_x/v_x0 = 1 − (κ/(1 + κ))(1 − P)`, of a sphere
/// with inertia factor `κ` (`I = κ m R²`) hitting a wall without spin (then `u0 = v_x0` and the
/// friction impulse is `m_t (1 − P) u0` with `m_t = κ m/(1 + κ)`). For `κ = 2/5` it is
/// [`tangential_restitution`].
pub fn centre_restitution(p: f64, kappa: f64) -> Result<f64, crate::InvalidInput> {
    if !(p.is_finite() && (-1.0..=1.0).contains(&p)) {
        return Err(crate::InvalidInput {
            name: "P",
            value: p,
            allowed: "in [-1, 1]".into(),
        });
    }
    if !(kappa.is_finite() && kappa > 0.0) {
        return Err(crate::InvalidInput {
            name: "kappa",
            value: kappa,
            allowed: "a finite number > 0".into(),
        });
    }
    Ok(1.0 - kappa / (1.0 + kappa) * (1.0 - p))
}

/// Seed 001's fit (29) of the no-slip limit: `−1 + 2 e^{−0.195γ} cos²(1.685(γ − 0.061))`.
/// A fit, off by about 0.01 in places; for comparison only.
pub fn no_slip_fit(gamma: f64) -> f64 {
    let c = (1.685 * (gamma - 0.061)).cos();
    -1.0 + 2.0 * (-0.195 * gamma).exp() * c * c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dissipative_line_and_its_end_reduce_to_the_elastic_ones() {
        for g in [1.2, 1.754, 2.5] {
            assert!((alpha_c1_dissipative(g, 1.0) - alpha_c1(g)).abs() < 1e-15);
            // Less normal impulse: the line reaches further in α.
            assert!(alpha_c1_dissipative(g, 0.6) > alpha_c1(g));
        }
        assert_eq!(full_slip_line(0.1, 1.0), 1.0 - 7.0 * 0.1);
    }

    #[test]
    fn the_end_of_full_slip_is_finite_for_every_gamma() {
        let seventh = 1.0 / 7.0;
        // 7(2γ²) overflows from 3.59e153 (the old formula gave 0 there, then NaN from
        // 1.35e154, where 2γ² overflows).
        assert_eq!(alpha_c1(3.6e153), seventh);
        for g in [1e154, 1.3e154, 1.4e154, 1e200, f64::MAX, f64::INFINITY] {
            assert_eq!(alpha_c1(g), seventh, "gamma {g:e}");
            assert_eq!(linear_limit(g), seventh, "gamma {g:e}");
            assert_eq!(alpha_c1_dissipative(g, 1.0), seventh, "gamma {g:e}");
            assert_eq!(
                alpha_c1_dissipative(g, 0.5),
                2.0 / (7.0 * 1.5),
                "gamma {g:e}"
            );
            assert_eq!(Regime::of(g, 0.1), Regime::FullSlip);
            assert_eq!(Regime::of(g, 0.15), Regime::PartialSlip);
            assert_eq!(Regime::of_dissipative(g, 0.17, 0.6), Regime::FullSlip);
            assert_eq!(closed_form(g, 0.1), Some(1.0 - 7.0 * 0.1));
        }
        // Where the formula does not overflow, its bits are those of the written operations
        // (the tables, oblique_eval.h and read_table.py share them).
        let old = |g2: f64| 2.0 * g2 / (7.0 * (2.0 * g2 - 1.0));
        let old_e = |g: f64, e: f64| {
            let g2 = g * g;
            2.0 * g2 / (7.0 * (g2 * (1.0 + e) - e))
        };
        let mut r = crate::sample::SplitMix(7);
        for i in 0..200_000 {
            // log-uniform from 1e-3 to just below the overflow (3.58e153), and near 1.
            let g = if i % 4 == 0 {
                1.0 + 1e-3 * r.uniform()
            } else {
                10f64.powf(-3.0 + 156.55 * r.uniform())
            };
            let e = 0.3 + 0.7 * r.uniform();
            assert!((7.0 * (2.0 * g * g - 1.0)).is_finite());
            assert_eq!(alpha_c1(g).to_bits(), old(g * g).to_bits(), "gamma {g:e}");
            let want = old_e(g, e);
            assert_eq!(
                alpha_c1_dissipative(g, e).to_bits(),
                want.to_bits(),
                "{g:e}, {e}"
            );
            assert_eq!(alpha_c1_dissipative(g, 1.0).to_bits(), old(g * g).to_bits());
        }
        // Across the switch the values stay at 1/7 to rounding, without a step.
        let mut g = 1e150;
        while g < 1e160 {
            assert!(
                (alpha_c1(g) - seventh).abs() <= f64::EPSILON * seventh,
                "{g:e}"
            );
            g *= 1.01;
        }
    }

    #[test]
    fn critical_values_coincide_at_gamma_one() {
        assert!((alpha_c1(1.0) - 2.0 / 7.0).abs() < 1e-15);
        assert!((alpha_c2(1.0) - 2.0 / 7.0).abs() < 1e-15);
        assert!(alpha_c1(2.0) < alpha_c2(2.0));
    }

    #[test]
    fn centre_restitution_of_a_solid_sphere_is_the_seven_sevenths_rule() {
        for p in [-1.0, -0.3, 0.0, 0.25, 1.0] {
            let e = centre_restitution(p, 0.4).unwrap();
            assert!((e - tangential_restitution(p)).abs() < 1e-15, "{p}: {e}");
        }
        assert_eq!(centre_restitution(1.0, 2.0 / 3.0).unwrap(), 1.0);
        assert!(centre_restitution(1.5, 0.4).is_err());
        assert!(centre_restitution(0.5, 0.0).is_err());
        assert!(centre_restitution(f64::NAN, 0.4).is_err());
    }

    #[test]
    fn regimes_follow_the_critical_curves() {
        let g = 1.754;
        assert_eq!(Regime::of(g, 0.5 * alpha_c1(g)), Regime::FullSlip);
        assert_eq!(
            Regime::of(g, 0.5 * (alpha_c1(g) + alpha_c2(g))),
            Regime::PartialSlip
        );
        assert_eq!(Regime::of(g, f64::INFINITY), Regime::Stick);
        assert_eq!(Regime::of(0.8, 0.9 * alpha_c2(0.8)), Regime::FullSlip);
    }
}
