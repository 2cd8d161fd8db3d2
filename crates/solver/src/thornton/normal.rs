//! The normal motion of Thornton's law, exact: a Hertz approach up to the yield indentation
//! `d_y`, a harmonic motion under the truncated pressure (the force is linear in `d` there) up
//! to the maximum indentation `d_max`, and a Hertz rebound of radius `R_p` from it down to the
//! plastic indentation `d_p` (`physics.md`, "Elastic–plastic impacts").
//!
//! With `k = (4/3) E* √R*` the law is, in `k` and `d_y` alone:
//! - loading: `F = k d^{3/2}` for `d ≤ d_y`, `F = F_y + S (d − d_y)` beyond, `F_y = k d_y^{3/2}`,
//!   `S = (3/2) k √d_y` (`= π p_y R*`: the pressure capped at `p_y` over the growing contact);
//! - unloading from `(d_max, F_max)`: `F = k √ρ (d − d_p)^{3/2}`, `ρ = R_p/R* = k d_max^{3/2}/F_max`,
//!   `d_max − d_p = d_max/ρ` (force and contact radius `a² = R* ρ (d − d_p)` continuous).
//!
//! The Hertz phases are sampled by inverting their time integral
//! `t(d) = (d_H/v₀) T(d/d_H)`, `T(ξ) = ∫₀^ξ (1 − s^{5/2})^{−1/2} ds` (an incomplete beta
//! function, summed as one of two series), the plastic phase in closed form: every node of the
//! time grid is exact to the rounding, the switch from loading to unloading (`ḋ = 0`) is a node
//! of the grid, and the contact time, `d_max` and the rebound speed are closed forms.

use crate::hertz::{hermite, HERTZ_TIME_INTEGRAL};

/// Terms of the two series of [`hertz_time`]: `x^n` or `y^n` with `x, y ≤ 1/2` falls below
/// `2^{−60}` (with coefficients ≤ 1) before the last term.
const TERMS: usize = 60;

/// `T(ξ) = ∫₀^ξ (1 − s^{5/2})^{−1/2} ds` for `ξ ∈ [0, 1]`: the time a Hertz approach with speed
/// `v₀` and turning indentation `d_H` takes to reach `d = ξ d_H`, in units of `d_H/v₀`
/// (`T(1) =` [`HERTZ_TIME_INTEGRAL`]).
///
/// With `x = ξ^{5/2}` it is `(2/5) B(x; 2/5, 1/2)`: for `x ≤ 1/2` the series
/// `ξ Σ (1/2)_n/n! · (2/5)/(2/5 + n) · x^n`, above it `T(1) − (2/5) √y Σ (3/5)_n/n! · y^n/(1/2 + n)`
/// with `y = 1 − x` ([`upper_series`]).
pub fn hertz_time(xi: f64) -> f64 {
    let xi = xi.clamp(0.0, 1.0);
    let x = xi.powf(2.5);
    if x <= 0.5 {
        xi * lower_series(x)
    } else {
        let y = -(2.5 * xi.ln()).exp_m1();
        HERTZ_TIME_INTEGRAL - 0.4 * y.sqrt() * upper_series(y)
    }
}

/// Coefficients `(1/2)_n/n! · (2/5)/(2/5 + n)` of the lower series of [`hertz_time`].
const LOWER: [f64; TERMS] = {
    let mut out = [0.0; TERMS];
    let mut c = 1.0;
    let mut n = 0;
    while n < TERMS {
        let nf = n as f64;
        out[n] = c * 0.4 / (0.4 + nf);
        c *= (nf + 0.5) / (nf + 1.0);
        n += 1;
    }
    out
};

/// Coefficients `(3/5)_n/n! / (1/2 + n)` of the upper series `G` of [`hertz_time`].
const UPPER: [f64; TERMS] = {
    let mut out = [0.0; TERMS];
    let mut c = 1.0;
    let mut n = 0;
    while n < TERMS {
        let nf = n as f64;
        out[n] = c / (0.5 + nf);
        c *= (nf + 0.6) / (nf + 1.0);
        n += 1;
    }
    out
};

/// `Σ (1/2)_n/n! · (2/5)/(2/5 + n) · x^n` (Horner over [`TERMS`] terms).
fn lower_series(x: f64) -> f64 {
    LOWER.iter().rev().fold(0.0, |acc, &k| acc * x + k)
}

/// `G(y) = Σ (3/5)_n/n! · y^n/(1/2 + n)` and `G′(y)` (Horner over [`TERMS`] terms).
fn upper_series_with_slope(y: f64) -> (f64, f64) {
    let value = UPPER.iter().rev().fold(0.0, |acc, &k| acc * y + k);
    let slope = UPPER
        .iter()
        .enumerate()
        .skip(1)
        .rev()
        .fold(0.0, |acc, (n, &k)| acc * y + n as f64 * k);
    (value, slope)
}

/// `G(y)` of [`upper_series_with_slope`].
fn upper_series(y: f64) -> f64 {
    upper_series_with_slope(y).0
}

/// The Hertz phase `d̈ = −K d^{3/2}` started at `d = 0` with speed `v₀ > 0`: its turning
/// indentation `d_H = (5 v₀²/(4K))^{2/5}`, and its state at any time up to the turning time
/// `t_H = (d_H/v₀) T(1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzPhase {
    /// Speed at `d = 0`, `v₀` (m/s).
    pub speed: f64,
    /// Turning indentation `d_H` (m).
    pub top: f64,
}

impl HertzPhase {
    /// The phase of `d̈ = −K d^{3/2}` (`K` in m^{−1/2} s^{−2}) with speed `v₀` at `d = 0`.
    pub fn new(accel_factor: f64, speed: f64) -> Self {
        HertzPhase {
            speed,
            top: (1.25 * speed * speed / accel_factor).powf(0.4),
        }
    }

    /// Time unit `d_H/v₀` (s).
    pub fn time_unit(&self) -> f64 {
        self.top / self.speed
    }

    /// Turning time `t_H = (d_H/v₀) T(1)` (s).
    pub fn turning_time(&self) -> f64 {
        self.time_unit() * HERTZ_TIME_INTEGRAL
    }

    /// Time from `d = 0` to `d = ξ d_H` (s).
    pub fn time_to(&self, xi: f64) -> f64 {
        self.time_unit() * hertz_time(xi)
    }

    /// Speed `ḋ = v₀ √(1 − ξ^{5/2}) ≥ 0` at `d = ξ d_H` (m/s).
    pub fn speed_at(&self, xi: f64) -> f64 {
        self.speed * (-(2.5 * xi.ln()).exp_m1()).max(0.0).sqrt()
    }

    /// `(d, ḋ)` at time `t ∈ [0, t_H]` after `d = 0` (clamped to that range), by inverting
    /// [`hertz_time`]: Newton in `ξ` below `x = ξ^{5/2} = 1/2`, in `σ = √(1 − x)` above it (smooth
    /// through the turning point, where `ξ` is not).
    pub fn state(&self, t: f64) -> (f64, f64) {
        let target = (t / self.time_unit()).clamp(0.0, HERTZ_TIME_INTEGRAL);
        let half = 0.5f64.powf(0.4);
        if target <= hertz_time(half) {
            // T(ξ) − target is increasing and convex with T′(ξ) = (1 − ξ^{5/2})^{−1/2}, and
            // T(ξ) ≥ ξ: Newton from ξ = target comes down monotonically.
            let mut xi = target;
            for _ in 0..100 {
                let x = xi.powf(2.5);
                let f = xi * lower_series(x) - target;
                let next = xi - f * (1.0 - x).sqrt();
                if next.is_nan() || next >= xi || next < 0.0 {
                    break;
                }
                xi = next;
            }
            (self.top * xi, self.speed * (1.0 - xi.powf(2.5)).sqrt())
        } else {
            // (2/5) σ G(σ²) = T(1) − target =: u, increasing and convex in σ; G(0) = 2, so
            // σ = u/0.8 is above the root and Newton comes down monotonically.
            let u = (HERTZ_TIME_INTEGRAL - target) / 0.4;
            let mut s = 0.5 * u;
            for _ in 0..100 {
                let (g, dg) = upper_series_with_slope(s * s);
                let f = s * g - u;
                let next = s - f / (g + 2.0 * s * s * dg);
                if next.is_nan() || next >= s || next < 0.0 {
                    break;
                }
                s = next;
            }
            let y = s * s;
            (self.top * (1.0 - y).powf(0.4), self.speed * s)
        }
    }
}

/// Thornton's normal law of two bodies in contact ([module docs](self)): loading force and
/// the unloading that follows a maximum indentation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loading {
    /// Hertz stiffness `k = (4/3) E* √R*` (N/m^{3/2}).
    pub stiffness: f64,
    /// Yield indentation `d_y` (m): `∞` for elastic bodies.
    pub yield_indentation: f64,
}

impl Loading {
    /// The loading force `F(d)` (N), `d ≥ 0`.
    pub fn force(&self, d: f64) -> f64 {
        let (k, dy) = (self.stiffness, self.yield_indentation);
        if d <= dy {
            k * d * d.max(0.0).sqrt()
        } else {
            k * dy.sqrt() * (dy + 1.5 * (d - dy))
        }
    }

    /// The unloading from the maximum indentation `d_max` (m).
    pub fn unloading(&self, max_indentation: f64) -> Unloading {
        let peak = self.force(max_indentation);
        let ratio = (self.stiffness * max_indentation * max_indentation.sqrt() / peak).max(1.0);
        let depth = max_indentation / ratio;
        Unloading {
            stiffness: self.stiffness * ratio.sqrt(),
            ratio,
            plastic_indentation: max_indentation - depth,
            depth,
        }
    }
}

/// The unloading branch of Thornton's law from `(d_max, F_max)`: a Hertz contact of radius
/// `R_p = ρ R*` pressed by `d − d_p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unloading {
    /// `k √ρ` (N/m^{3/2}): `F = k √ρ (d − d_p)^{3/2}`.
    pub stiffness: f64,
    /// `ρ = R_p/R* = k d_max^{3/2}/F_max ≥ 1`.
    pub ratio: f64,
    /// Plastic indentation `d_p = d_max (1 − 1/ρ)` (m), where the contact ends.
    pub plastic_indentation: f64,
    /// `d_max − d_p = d_max/ρ` (m).
    pub depth: f64,
}

impl Unloading {
    /// The unloading force (N) at indentation `d` (m).
    pub fn force(&self, d: f64) -> f64 {
        let e = (d - self.plastic_indentation).max(0.0);
        self.stiffness * e * e.sqrt()
    }

    /// The contact's reach `ρ (d − d_p)` (m): the contact radius is `√(R* reach)`, and the
    /// Coulomb limit of the spring at profile height `y` is `(c/ρ)(reach − y)`.
    pub fn reach(&self, d: f64) -> f64 {
        self.ratio * (d - self.plastic_indentation)
    }
}

/// The exact normal motion of one Thornton impact ([module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The law.
    pub loading: Loading,
    /// `1/m1 + 1/m2` (1/kg).
    pub inv_mass: f64,
    /// Approach speed `V = v_z0` (m/s).
    pub approach_speed: f64,
    /// The Hertz approach.
    pub approach: HertzPhase,
    /// Time at which `d = d_y` (s; the turning time when the impact stays elastic).
    pub yield_time: f64,
    /// The plastic phase, `None` when the impact stays elastic (`V ≤ V_y`).
    pub plastic: Option<Plastic>,
    /// Time of the maximum indentation, the switch to unloading (s).
    pub switch_time: f64,
    /// Maximum indentation `d_max` (m).
    pub max_indentation: f64,
    /// Peak force `F_max` (N).
    pub peak_force: f64,
    /// The unloading branch.
    pub unloading: Unloading,
    /// The Hertz rebound, as the time-reversed approach of `d − d_p` with the rebound speed.
    pub rebound: HertzPhase,
    /// Contact time `t_c` (s).
    pub contact_time: f64,
}

/// The plastic phase: `d̈ = −(1/m*)(F_y + S (d − d_y))`, a harmonic motion about `d_y/3`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plastic {
    /// Angular frequency `ω = √(S/m*)` (1/s).
    pub omega: f64,
    /// Amplitude `A` (m): `d = d_y/3 + A cos(ψ)`, `ḋ = A ω sin ψ`, `ψ` falling from `ψ₀` to 0.
    pub amplitude: f64,
    /// Phase `ψ₀` at the yield time.
    pub phase: f64,
}

impl Motion {
    /// The motion of bodies with `1/m1 + 1/m2 = inv_mass` (1/kg) under `loading`, meeting at
    /// `approach_speed` (m/s, > 0).
    pub fn new(loading: Loading, inv_mass: f64, approach_speed: f64) -> Self {
        let k_acc = loading.stiffness * inv_mass;
        let approach = HertzPhase::new(k_acc, approach_speed);
        let dy = loading.yield_indentation;
        let (yield_time, plastic, switch_time, max_indentation) = if dy >= approach.top {
            let t = approach.turning_time();
            (t, None, t, approach.top)
        } else {
            let xi = dy / approach.top;
            let t_y = approach.time_to(xi);
            let v_y = approach.speed_at(xi);
            let omega = (1.5 * k_acc * dy.sqrt()).sqrt();
            let (lift, reach) = (2.0 / 3.0 * dy, v_y / omega);
            let amplitude = lift.hypot(reach);
            let phase = reach.atan2(lift);
            // d_max − d_y = A − (2/3) d_y without the cancellation.
            let beyond = reach * reach / (amplitude + lift);
            let p = Plastic {
                omega,
                amplitude,
                phase,
            };
            (t_y, Some(p), t_y + phase / omega, dy + beyond)
        };
        let unloading = loading.unloading(max_indentation);
        let rebound_speed = if plastic.is_none() {
            approach_speed
        } else {
            (0.8 * unloading.stiffness * inv_mass * unloading.depth.powf(2.5)).sqrt()
        };
        let rebound = HertzPhase {
            speed: rebound_speed,
            top: unloading.depth,
        };
        Motion {
            loading,
            inv_mass,
            approach_speed,
            approach,
            yield_time,
            plastic,
            switch_time,
            max_indentation,
            peak_force: loading.force(max_indentation),
            unloading,
            rebound,
            contact_time: switch_time + rebound.turning_time(),
        }
    }

    /// Normal restitution `e_n = v_r/V`.
    pub fn restitution(&self) -> f64 {
        self.rebound.speed / self.approach_speed
    }

    /// `(d, ḋ)` at time `t ≤ t_m` (s) of the loading.
    pub fn loading_state(&self, t: f64) -> (f64, f64) {
        match self.plastic {
            Some(p) if t > self.yield_time => {
                let psi = (p.phase - p.omega * (t - self.yield_time)).max(0.0);
                let dy = self.loading.yield_indentation;
                // d = d_y/3 + A cos ψ, written from d_max to keep its digits near the peak.
                let s = (0.5 * psi).sin();
                let d = self.max_indentation - 2.0 * p.amplitude * s * s;
                (d.max(dy), p.amplitude * p.omega * psi.sin())
            }
            _ => self.approach.state(t),
        }
    }

    /// `(d, ḋ)` at time `left` (s) before separation, in the unloading.
    pub fn unloading_state(&self, left: f64) -> (f64, f64) {
        let (e, v) = self.rebound.state(left);
        (self.unloading.plastic_indentation + e, -v)
    }

    /// The motion sampled on a grid of `steps` steps with the switch at a node
    /// ([`Trajectory`]).
    pub fn trajectory(&self, steps: usize) -> Trajectory {
        let (loading_steps, unloading_steps, h1, h2) =
            two_part_grid(steps, self.switch_time, self.rebound.turning_time());
        let mut indentation = Vec::with_capacity(steps + 1);
        let mut rate = Vec::with_capacity(steps + 1);
        for j in 0..loading_steps {
            let (d, v) = self.loading_state(j as f64 * h1);
            indentation.push(d);
            rate.push(v);
        }
        indentation.push(self.max_indentation);
        rate.push(0.0);
        for j in 1..=unloading_steps {
            let (d, v) = self.unloading_state((unloading_steps - j) as f64 * h2);
            indentation.push(d);
            rate.push(v);
        }
        Trajectory {
            motion: *self,
            indentation,
            rate,
            switch: loading_steps,
            loading_step: h1,
            unloading_step: h2,
        }
    }
}

/// Parts of the grid that the split between loading and unloading is rounded to
/// ([`two_part_grid`]).
pub const SPLIT_PARTS: usize = 16;

/// A grid of `steps` (at least 2) over a loading of `loading_time` and an unloading of
/// `unloading_time` (s) with the switch at a node: the steps of each part, shared in
/// proportion to the times (at least one each), and their lengths (s).
///
/// Where `steps` is a multiple of [`SPLIT_PARTS`] (every level of a refinement) the share is
/// rounded to sixteenths, `(steps/16)·round(16·share)` loading steps, so that doubling the steps
/// doubles both parts and halves both step lengths: the errors of the two parts keep their
/// ratio from level to level, and the differences between levels shrink regularly. Rounded
/// per level instead, the loading step moved by up to half a step against the unloading one
/// between levels, and at γ = 0.51, α = ∞, `e_n` = 0.75 the differences from 16 to 512 steps
/// had ratios −8.0, 78.8, 3.1 and 0.65 (the estimate at 256 steps 6.1e-8 for an error of
/// 2.2e-7); with the sixteenths 5.7, 4.8, 4.4, 4.3, 4.2.
pub fn two_part_grid(
    steps: usize,
    loading_time: f64,
    unloading_time: f64,
) -> (usize, usize, f64, f64) {
    let steps = steps.max(2);
    let share = loading_time / (loading_time + unloading_time);
    let loading_steps = if steps.is_multiple_of(SPLIT_PARTS) {
        let parts = ((SPLIT_PARTS as f64 * share).round() as usize).clamp(1, SPLIT_PARTS - 1);
        parts * (steps / SPLIT_PARTS)
    } else {
        ((steps as f64 * share).round() as usize).clamp(1, steps - 1)
    };
    let unloading_steps = steps - loading_steps;
    (
        loading_steps,
        unloading_steps,
        loading_time / loading_steps as f64,
        unloading_time / unloading_steps as f64,
    )
}

/// The motion on a time grid of two uniform parts: `switch` steps of `loading_step` up to the
/// maximum indentation, then steps of `unloading_step` to the separation. Node 0 is first touch,
/// node `switch` the switch to unloading (`ḋ = 0` there exactly), the last node separation
/// (`d = d_p`).
#[derive(Debug, Clone)]
pub struct Trajectory {
    /// The motion sampled.
    pub motion: Motion,
    /// Indentation `d_j` (m) at the nodes.
    pub indentation: Vec<f64>,
    /// Indentation rate `ḋ_j` (m/s) at the nodes.
    pub rate: Vec<f64>,
    /// Node of the switch.
    pub switch: usize,
    /// Step before the switch (s).
    pub loading_step: f64,
    /// Step after the switch (s).
    pub unloading_step: f64,
}

impl Trajectory {
    /// Number of steps.
    pub fn steps(&self) -> usize {
        self.indentation.len() - 1
    }

    /// Length of step `n` (s).
    pub fn step_length(&self, n: usize) -> f64 {
        if n < self.switch {
            self.loading_step
        } else {
            self.unloading_step
        }
    }

    /// Whether step `n` is part of the unloading.
    pub fn unloads(&self, n: usize) -> bool {
        n >= self.switch
    }

    /// Indentation and rate at time `t ∈ [0, h_n]` into step `n` (cubic Hermite, O(h⁴)).
    pub fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        hermite(
            self.step_length(n),
            (self.indentation[n], self.indentation[n + 1]),
            (self.rate[n], self.rate[n + 1]),
            t,
        )
    }

    /// The normal force (N) at indentation `d` in step `n` (the law of its phase).
    pub fn force(&self, n: usize, d: f64) -> f64 {
        if self.unloads(n) {
            self.motion.unloading.force(d)
        } else {
            self.motion.loading.force(d)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::thornton::{restitution, speed_ratio};

    #[test]
    fn the_hertz_time_series_meet_and_reach_the_known_integral() {
        // Both series at x = 1/2.
        let xi = 0.5f64.powf(0.4);
        let lower = xi * lower_series(0.5);
        let upper = HERTZ_TIME_INTEGRAL - 0.4 * 0.5f64.sqrt() * upper_series(0.5);
        assert!((lower - upper).abs() < 4e-16, "{lower} {upper}");
        assert_eq!(hertz_time(1.0), HERTZ_TIME_INTEGRAL);
        assert_eq!(hertz_time(0.0), 0.0);
        for xi in [0.1, 0.5, 0.8, 0.95, 0.999] {
            let t = hertz_time(xi);
            let d = 1e-7;
            let numeric = (hertz_time(xi + d) - hertz_time(xi - d)) / (2.0 * d);
            let exact = 1.0 / (1.0 - f64::powf(xi, 2.5)).sqrt();
            assert!(
                (numeric - exact).abs() < 1e-6 * exact,
                "ξ {xi}: {numeric} {exact}"
            );
            assert!(t > 0.0 && t < HERTZ_TIME_INTEGRAL);
        }
    }

    #[test]
    fn a_hertz_phase_inverts_its_time() {
        let phase = HertzPhase::new(4.0 / 3.0, 1.0);
        assert!((phase.top - (15.0f64 / 16.0).powf(0.4)).abs() < 1e-15);
        for i in 0..=1000 {
            let t = phase.turning_time() * i as f64 / 1000.0;
            let (d, v) = phase.state(t);
            let xi = d / phase.top;
            let back = phase.time_to(xi);
            assert!((back - t).abs() < 1e-14, "t {t}: back {back}");
            // Energy: v² + (4/5) K d^{5/2} = v₀².
            let e = v * v + 0.8 * 4.0 / 3.0 * d.powf(2.5);
            assert!((e - 1.0).abs() < 1e-14, "t {t}: energy {e}");
        }
    }

    /// `d̈ = −F(d)/m*` by RK4 on a fine uniform grid, switching to the unloading branch where
    /// `ḋ` changes sign (located by bisection on one step), until the contact ends: the
    /// rebound speed over the approach speed. Independent of [`Motion`]'s closed forms.
    fn integrated_restitution(loading: Loading, steps: usize) -> f64 {
        let m = Motion::new(loading, 1.0, 1.0);
        let h = m.contact_time / steps as f64;
        let rk4 = |(d, v): (f64, f64), h: f64, f: &dyn Fn(f64) -> f64| {
            let k1 = (v, -f(d));
            let k2 = (v + 0.5 * h * k1.1, -f(d + 0.5 * h * k1.0));
            let k3 = (v + 0.5 * h * k2.1, -f(d + 0.5 * h * k2.0));
            let k4 = (v + h * k3.1, -f(d + h * k3.0));
            (
                d + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
                v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
            )
        };
        let load = |d: f64| loading.force(d);
        let mut y = (0.0, 1.0);
        // Loading until ḋ < 0 after a step.
        loop {
            let next = rk4(y, h, &load);
            if next.1 <= 0.0 {
                let (mut lo, mut hi) = (0.0, h);
                for _ in 0..80 {
                    let mid = 0.5 * (lo + hi);
                    if rk4(y, mid, &load).1 > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                y = rk4(y, lo, &load);
                break;
            }
            y = next;
        }
        let un = loading.unloading(y.0);
        let unload = |d: f64| un.force(d);
        loop {
            let next = rk4(y, h, &unload);
            if next.0 <= un.plastic_indentation {
                // Energy of the rest of the fall is exact: v² at d_p.
                let (d, v) = y;
                let e = d - un.plastic_indentation;
                return (v * v + 0.8 * un.stiffness * e * e * e.sqrt()).sqrt();
            }
            y = next;
        }
    }

    /// `physics.md`: `e_n` depends on `V/V_y` only and is Thornton's closed form; measured by
    /// integrating the law's forces over `V/V_y ∈ [1, 1000]`.
    #[test]
    fn the_integrated_restitution_is_thorntons_closed_form() {
        for i in 0..=24 {
            // V/V_y from 1 to 1000, log-spaced.
            let v_over = 1000f64.powf(i as f64 / 24.0);
            let r = 1.0 / v_over;
            // p_y from r: d_y = (π p_y/2)² with p_y = p_0 r^{2/5}.
            let p_y = crate::thornton::elastic_peak_pressure() * r.powf(0.4);
            let loading = Loading {
                stiffness: 4.0 / 3.0,
                yield_indentation: (std::f64::consts::FRAC_PI_2 * p_y).powi(2),
            };
            let closed = restitution(r);
            let motion = Motion::new(loading, 1.0, 1.0);
            assert!(
                (motion.restitution() - closed).abs() < 1e-13,
                "V/V_y {v_over}: {} against {closed}",
                motion.restitution()
            );
            let integrated = integrated_restitution(loading, 20_000);
            assert!(
                (integrated - closed).abs() < 1e-8,
                "V/V_y {v_over}: integrated {integrated} against {closed}"
            );
            assert!((speed_ratio(p_y) - r).abs() < 1e-12 * r.max(1e-300).max(1.0));
        }
    }

    #[test]
    fn the_trajectory_switches_at_a_node_and_is_continuous() {
        let p_y = 0.350980351;
        let loading = Loading {
            stiffness: 4.0 / 3.0,
            yield_indentation: (std::f64::consts::FRAC_PI_2 * p_y).powi(2),
        };
        let m = Motion::new(loading, 1.0, 1.0);
        assert!((m.restitution() - 0.8).abs() < 1e-8);
        // Deeper than the elastic contact.
        assert!(m.max_indentation > (15.0f64 / 16.0).powf(0.4));
        let t = m.trajectory(1024);
        assert_eq!(t.steps(), 1024);
        assert_eq!(t.rate[t.switch], 0.0);
        assert_eq!(t.indentation[t.switch], m.max_indentation);
        assert_eq!(t.indentation[0], 0.0);
        assert!((t.indentation[1024] - m.unloading.plastic_indentation).abs() < 1e-15);
        assert!((t.rate[1024] + m.rebound.speed).abs() < 1e-15);
        // Each node against its neighbours: the rate is the derivative of the indentation
        // (central differences of the exact nodes, second order).
        for n in 1..1024 {
            if n == t.switch {
                continue;
            }
            let (h0, h1) = (t.step_length(n - 1), t.step_length(n));
            if (h0 - h1).abs() > 0.0 {
                continue;
            }
            let slope = (t.indentation[n + 1] - t.indentation[n - 1]) / (2.0 * h0);
            assert!(
                (slope - t.rate[n]).abs() < 2e-4,
                "node {n}: {slope} {}",
                t.rate[n]
            );
        }
        // Energy along the loading and the unloading.
        for n in 0..=1024 {
            let (d, v) = (t.indentation[n], t.rate[n]);
            let work = if n <= t.switch {
                let dy = loading.yield_indentation;
                if d <= dy {
                    0.8 * 4.0 / 3.0 * d.powf(2.5)
                } else {
                    let k = 4.0 / 3.0;
                    0.8 * k * dy.powf(2.5)
                        + 2.0
                            * (k * dy.powf(1.5) * (d - dy)
                                + 0.75 * k * dy.sqrt() * (d - dy).powi(2))
                }
            } else {
                let e = d - m.unloading.plastic_indentation;
                0.8 * m.unloading.stiffness * e.powf(2.5) + 1.0 - m.rebound.speed.powi(2)
            };
            assert!(
                (v * v + work - 1.0).abs() < 1e-13,
                "node {n}: {}",
                v * v + work - 1.0
            );
        }
    }

    /// The grids of a refinement are nested: from 16 steps on, doubling the steps doubles both
    /// parts, and every node of a level is a node of the next, with the same bits.
    #[test]
    fn the_levels_of_a_refinement_share_their_nodes() {
        for p_y in [0.05, 0.2, 0.350980351, 0.6] {
            let loading = Loading {
                stiffness: 4.0 / 3.0,
                yield_indentation: (std::f64::consts::FRAC_PI_2 * p_y).powi(2),
            };
            let m = Motion::new(loading, 1.0, 1.0);
            let mut coarse = m.trajectory(16);
            for k in 1..8 {
                let fine = m.trajectory(16 << k);
                assert_eq!(
                    fine.switch,
                    2 * coarse.switch,
                    "p_y {p_y}, {} steps",
                    16 << k
                );
                for (j, (&d, &v)) in coarse.indentation.iter().zip(&coarse.rate).enumerate() {
                    assert_eq!(fine.indentation[2 * j].to_bits(), d.to_bits(), "node {j}");
                    assert_eq!(fine.rate[2 * j].to_bits(), v.to_bits(), "node {j}");
                }
                coarse = fine;
            }
        }
        // Elsewhere the share is rounded to the step.
        assert_eq!(two_part_grid(100, 1.0, 2.0).0, 33);
        assert_eq!(two_part_grid(96, 1.0, 2.0).0, 30);
    }

    #[test]
    fn an_impact_below_the_yield_speed_is_hertz() {
        let loading = Loading {
            stiffness: 4.0 / 3.0,
            yield_indentation: 2.0,
        };
        let m = Motion::new(loading, 1.0, 1.0);
        assert!(m.plastic.is_none());
        assert_eq!(m.restitution(), 1.0);
        assert_eq!(m.unloading.ratio, 1.0);
        assert_eq!(m.unloading.plastic_indentation, 0.0);
        let tc = 2.0 * HERTZ_TIME_INTEGRAL * (15.0f64 / 16.0).powf(0.4);
        assert!((m.contact_time - tc).abs() < 1e-15);
    }
}
