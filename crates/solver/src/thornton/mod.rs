//! Thornton's elastic–perfectly plastic law (Thornton 1997; `physics.md`, "Elastic–plastic
//! impacts"): Hertz contact up to the limiting pressure `p_y`, the Hertz pressure truncated at
//! `p_y` beyond, and unloading as a Hertz contact of a larger radius `R_p` from a plastic
//! indentation `d_p`, continuous in force and contact radius. Within the law `P` depends on
//! `(γ, α, e_n)` only: `p_y` and `e_n` are one-to-one at a given impact speed.
//!
//! What is here so far: the closed forms of the normal law ([`restitution`],
//! [`yield_pressure_for_restitution`], [`speed_ratio`]), its exact normal motion
//! ([`normal`]) and the line density of the pressure that bounds each MDR spring
//! ([`line`]). Dimensionless units as in [`crate::impact`]: `m* = R* = E* = v_z0 = 1`, so that
//! the Hertz force is `F = (4/3) d^{3/2}` and pressures are in units of `E*`.

pub mod line;
pub mod normal;
pub mod row;

use crate::error::PhysicsError;
use crate::impact::{run_contact_with, ContactPoint};
use crate::model::{NormalModel, TangentialModel};
use crate::springs::{StepMotion, StepResult};
use normal::{Loading, Motion, Trajectory};
use row::ThorntonRow;

/// The peak Hertz pressure of the elastic impact at `v_z0 = 1`,
/// `p_0 = (2/π)(15/16)^{1/5}` (units of `E*`): a limiting pressure `p_y ≥ p_0` leaves the
/// impact elastic.
pub fn elastic_peak_pressure() -> f64 {
    2.0 / std::f64::consts::PI * (15.0f64 / 16.0).powf(0.2)
}

/// `V_y/V = (p_y/p_0)^{5/2}`: the yield speed over the impact speed for a dimensionless limiting
/// pressure `p_y` (units of `E*` at `v_z0 = 1`; [`elastic_peak_pressure`]).
pub fn speed_ratio(yield_pressure: f64) -> f64 {
    (yield_pressure / elastic_peak_pressure()).powf(2.5)
}

/// Thornton's closed form of the normal restitution as a function of `r = V_y/V`,
///
/// `e_n = √(6√3/5) √(1 − r²/6) [r / (r + 2√(6/5 − r²/5))]^{1/4}` for `0 < r ≤ 1`,
///
/// and `e_n = 1` for `r ≥ 1` (no plastic flow: `V ≤ V_y`). It is the exact energy balance of
/// the normal law (loading work against the Hertz work of unloading, [`normal::Loading`]), which
/// a test checks to the rounding. NaN for NaN.
pub fn restitution(r: f64) -> f64 {
    if r.is_nan() {
        return f64::NAN;
    }
    if r >= 1.0 {
        return 1.0;
    }
    if r <= 0.0 {
        return 0.0;
    }
    let lead = (6.0 * 3.0f64.sqrt() / 5.0).sqrt();
    let ratio = r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt());
    (lead * (1.0 - r * r / 6.0).sqrt() * ratio.sqrt().sqrt()).min(1.0)
}

/// The speed ratio `r = V_y/V ∈ (0, 1]` whose normal restitution ([`restitution`]) is `e_n`
/// (`e_n ∈ (0, 1]`; `r = 1` at `e_n = 1`), by bisection to the rounding: `restitution` is
/// increasing in `r`.
pub fn speed_ratio_for_restitution(e_n: f64) -> Result<f64, PhysicsError> {
    if !(e_n > 0.0 && e_n <= 1.0) {
        return Err(PhysicsError::InvalidParameter {
            name: "e_n",
            value: e_n,
            allowed: "a number in (0, 1] for the limiting pressure of Thornton's law",
        });
    }
    if e_n == 1.0 {
        return Ok(1.0);
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    // 1100 halvings reach the smallest subnormal: the loop ends when the bracket is two
    // adjacent doubles.
    for _ in 0..1100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if restitution(mid) < e_n {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(hi)
}

/// The dimensionless limiting pressure `p_y = p_0 r^{2/5}` (units of `E*` at `v_z0 = 1`) whose
/// impact has normal restitution `e_n ∈ (0, 1]` ([`speed_ratio_for_restitution`]); `p_0` at
/// `e_n = 1` (where every `p_y ≥ p_0` gives the same elastic impact).
pub fn yield_pressure_for_restitution(e_n: f64) -> Result<f64, PhysicsError> {
    let r = speed_ratio_for_restitution(e_n)?;
    Ok(elastic_peak_pressure() * r.powf(0.4))
}

/// The yield indentation `d_y = R* (π p_y/(2 E*))²` (m) at which the peak Hertz pressure
/// `2 a E*/(π R*)` reaches the limiting pressure `p_y` (Pa): the contact radius there is
/// `a_y = π p_y R*/(2 E*)`.
pub fn yield_indentation(yield_pressure: f64, radius: f64, modulus: f64) -> f64 {
    let a = std::f64::consts::FRAC_PI_2 * yield_pressure * radius / modulus;
    a * a / radius
}

/// The dimensionless motion (`m* = R* = E* = v_z0 = 1`, `k = 4/3`) with limiting pressure `p_y`
/// (units of `E*`).
pub fn dimensionless_motion(yield_pressure: f64) -> Motion {
    let loading = Loading {
        stiffness: 4.0 / 3.0,
        yield_indentation: yield_indentation(yield_pressure, 1.0, 1.0),
    };
    Motion::new(loading, 1.0, 1.0)
}

/// `P` of the dimensionless impact (`u0 = 1`, `m_t = 2/7`) of `motion` on `steps` steps, with
/// `G* = shear` and Coulomb limit factor `limit` (`∞`: no slip).
pub fn dimensionless_p(shear: f64, limit: f64, motion: &Motion, steps: usize) -> f64 {
    let trajectory = motion.trajectory(steps);
    let row = ThorntonRow::new(
        1.0,
        motion.loading.yield_indentation,
        motion.unloading.ratio,
        motion.unloading.plastic_indentation,
    );
    let mut cp = ContactPoint { u: 1.0 };
    run_contact_with(&mut cp, &trajectory, row, 1.0, shear, limit);
    cp.u
}

impl NormalModel for Trajectory {
    #[inline(always)]
    fn steps(&self) -> usize {
        self.indentation.len() - 1
    }
    /// The unloading's step (the grid's last part).
    #[inline(always)]
    fn dt(&self) -> f64 {
        self.unloading_step
    }
    #[inline(always)]
    fn step_length(&self, n: usize) -> f64 {
        Trajectory::step_length(self, n)
    }
    #[inline(always)]
    fn contact_time(&self) -> f64 {
        self.motion.contact_time
    }
    #[inline(always)]
    fn max_indentation(&self) -> f64 {
        self.motion.max_indentation
    }
    #[inline(always)]
    fn indentation(&self, n: usize) -> f64 {
        self.indentation[n]
    }
    #[inline(always)]
    fn rate(&self, n: usize) -> f64 {
        self.rate[n]
    }
    /// The loading force while `ḋ ≥ 0`, the unloading force after (they agree at `d_max`).
    #[inline(always)]
    fn acceleration(&self, d: f64, rate: f64) -> f64 {
        let m = &self.motion;
        let f = if rate < 0.0 {
            m.unloading.force(d)
        } else {
            m.loading.force(d)
        };
        -f * m.inv_mass
    }
    #[inline(always)]
    fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        Trajectory::within_step(self, n, t)
    }
    /// `d` in loading, `ρ (d − d_p)` in unloading.
    #[inline(always)]
    fn reach(&self, (d, rate): (f64, f64)) -> f64 {
        if rate < 0.0 {
            self.motion.unloading.reach(d)
        } else {
            d
        }
    }
}

impl TangentialModel for ThorntonRow {
    const END_STATE: bool = true;
    #[inline(always)]
    fn at_limit(&self) -> (bool, bool) {
        ThorntonRow::at_limit(self)
    }
    #[inline(always)]
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        self.step(m, d1, c)
    }
    #[inline(always)]
    fn jump(&mut self, start: (f64, f64), end: (f64, f64), c: f64) -> Option<StepResult> {
        ThorntonRow::jump(self, start, end, c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `physics.md`: the limiting pressures of `e_n = 0.95, 0.9, 0.8, 0.6`, measured with an
    /// independent prototype to 9 decimals.
    #[test]
    fn the_limiting_pressures_of_physics_md() {
        for (e_n, p) in [
            (0.95, 0.501431593),
            (0.9, 0.441734416),
            (0.8, 0.350980351),
            (0.6, 0.214225241),
        ] {
            let got = yield_pressure_for_restitution(e_n).unwrap();
            assert!((got - p).abs() < 1e-9, "e_n {e_n}: {got} against {p}");
            let back = restitution(speed_ratio(got));
            assert!(
                (back - e_n).abs() < 4.0 * f64::EPSILON,
                "{back} against {e_n}"
            );
        }
        // p_y = 0.5 gives 0.9489676 (prototype) against the formula's 0.94896.
        let e = restitution(speed_ratio(0.5));
        assert!((e - 0.9489676).abs() < 5e-8, "{e}");
    }

    #[test]
    fn the_closed_form_ends_and_refuses() {
        assert_eq!(restitution(1.0), 1.0);
        assert_eq!(restitution(2.0), 1.0);
        assert_eq!(restitution(0.0), 0.0);
        assert!(restitution(f64::NAN).is_nan());
        // Near r = 1 the loss is second order in 1 − r.
        assert!(restitution(1.0 - 1e-6) < 1.0);
        // Increasing in r (the search relies on it).
        let mut last = 0.0;
        for i in 1..=1000 {
            let e = restitution(i as f64 / 1000.0);
            assert!(e > last, "at r = {}", i as f64 / 1000.0);
            last = e;
        }
        assert_eq!(speed_ratio_for_restitution(1.0), Ok(1.0));
        for bad in [0.0, -0.1, 1.0 + 1e-15, f64::NAN, f64::INFINITY] {
            assert!(speed_ratio_for_restitution(bad).is_err(), "{bad}");
        }
        assert!(
            (yield_pressure_for_restitution(1.0).unwrap() - elastic_peak_pressure()).abs() < 1e-16
        );
    }

    #[test]
    fn the_yield_indentation_in_units() {
        // R* = E* = 1: d_y = (π p_y/2)².
        let p = 0.35;
        let d = yield_indentation(p, 1.0, 1.0);
        assert!((d - (std::f64::consts::FRAC_PI_2 * p).powi(2)).abs() < 1e-16);
        // Steel-like: R* = 5 mm, E* = 115 GPa, p_y = 1 GPa: a_y = π·1e9·5e-3/(2·115e9).
        let a = std::f64::consts::PI * 1e9 * 5e-3 / (2.0 * 115e9);
        let d = yield_indentation(1e9, 5e-3, 115e9);
        assert!((d - a * a / 5e-3).abs() < 1e-12 * d);
    }
}
