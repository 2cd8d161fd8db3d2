//! Hertz normal contact: closed forms and the time-resolved normal motion.
//!
//! Notation follows `physics.md`: indentation `d` (m, counted from first touch), effective radius
//! `R*` (m), effective modulus `E*` (Pa), normal reduced mass `m*` (kg), approach speed `v_z0` (m/s).
//! The MDR normal force in the continuum limit is exactly Hertz's
//! `F_N = k d^{3/2}` with `k = (4/3) E* √R*`.

/// `∫₀¹ (1 − s^{5/2})^{−1/2} ds = (2/5) B(2/5, 1/2) = (2/5) Γ(2/5) Γ(1/2) / Γ(9/10)`.
///
/// The Hertz contact time is `t_c = 2 · HERTZ_TIME_INTEGRAL · d_max / v_z0`.
pub const HERTZ_TIME_INTEGRAL: f64 = 1.471_637_592_162_352_3;

/// Closed-form Hertz impact quantities for `m* ü = −k u^{3/2}` started at `u = 0`, `u̇ = v_z0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzClosedForm {
    /// Normal reduced mass `m*` (kg).
    pub mass: f64,
    /// Hertz stiffness `k = (4/3) E* √R*` (N/m^{3/2}).
    pub stiffness: f64,
    /// Approach speed `v_z0` (m/s), > 0.
    pub approach_speed: f64,
}

impl HertzClosedForm {
    /// Maximum indentation `d_max = (5 m* v_z0² / (4 k))^{2/5}` (m).
    pub fn max_indentation(&self) -> f64 {
        (5.0 * self.mass * self.approach_speed * self.approach_speed / (4.0 * self.stiffness))
            .powf(0.4)
    }

    /// Contact time `t_c = 2 · 1.47164 · d_max / v_z0` (s).
    pub fn contact_time(&self) -> f64 {
        2.0 * HERTZ_TIME_INTEGRAL * self.max_indentation() / self.approach_speed
    }

    /// Peak normal force `F_max = k d_max^{3/2}` (N).
    pub fn peak_force(&self) -> f64 {
        self.stiffness * self.max_indentation().powf(1.5)
    }
}

/// The normal motion of one impact sampled on a uniform time grid aligned with the contact:
/// node 0 is first touch, node `steps` is separation (measured, not assumed).
#[derive(Debug, Clone)]
pub struct NormalTrajectory {
    /// Indentation `d_j` (m) at `t_j = j · dt`, `j = 0..=steps`; `d_0 = d_steps = 0`.
    pub indentation: Vec<f64>,
    /// Indentation rate `ḋ_j` (m/s) at the nodes.
    pub rate: Vec<f64>,
    /// Indentation acceleration `d̈_j = −F_N (1/m1 + 1/m2)` (m/s²) at the nodes.
    pub accel: Vec<f64>,
    /// `k (1/m1 + 1/m2)` (m^{-1/2} s^{-2}): `d̈ = −accel_factor · d^{3/2}`.
    pub accel_factor: f64,
    /// Time step `dt = t_c / steps` (s).
    pub dt: f64,
    /// Measured contact time `t_c` (s): first time after touch at which `d` returns to 0.
    pub contact_time: f64,
    /// Measured maximum indentation `d_max` (m).
    pub max_indentation: f64,
    /// Measured peak normal force `k d_max^{3/2}` (N).
    pub peak_force: f64,
    /// Normal velocity change of body 1 over the contact (m/s, along the normal from body 1 to 2).
    pub delta_v1: f64,
    /// Normal velocity change of body 2 over the contact (m/s, same axis).
    pub delta_v2: f64,
}

/// State of the two bodies along the common normal: positions `s1, s2` (m), velocities `v1, v2`
/// (m/s); the indentation is `s1 − s2`.
#[derive(Debug, Clone, Copy)]
struct NormalState {
    s1: f64,
    v1: f64,
    s2: f64,
    v2: f64,
}

/// Two bodies pressed by the Hertz force; each body's own equation of motion is integrated.
#[derive(Debug, Clone, Copy)]
pub struct NormalBodies {
    /// `1/m1` (1/kg).
    pub inv_mass1: f64,
    /// `1/m2` (1/kg); 0 for a wall.
    pub inv_mass2: f64,
    /// Hertz stiffness `k` (N/m^{3/2}).
    pub stiffness: f64,
    /// Approach speed `v_z0 = v1 − v2` at first touch (m/s), > 0.
    pub approach_speed: f64,
}

/// Sub-steps of the RK4 integration per grid step in the interior of the contact.
const SUBSTEPS: usize = 4;
/// Sub-steps in the first and last grid steps, where `d^{3/2}` is not smooth in time.
const EDGE_SUBSTEPS: usize = 256;

impl NormalBodies {
    fn force(&self, d: f64) -> f64 {
        if d > 0.0 {
            self.stiffness * d * d.sqrt()
        } else {
            0.0
        }
    }

    fn deriv(&self, y: &NormalState) -> NormalState {
        let f = self.force(y.s1 - y.s2);
        NormalState {
            s1: y.v1,
            v1: -f * self.inv_mass1,
            s2: y.v2,
            v2: f * self.inv_mass2,
        }
    }

    fn rk4(&self, y: &NormalState, h: f64) -> NormalState {
        let add = |a: &NormalState, b: &NormalState, c: f64| NormalState {
            s1: a.s1 + c * b.s1,
            v1: a.v1 + c * b.v1,
            s2: a.s2 + c * b.s2,
            v2: a.v2 + c * b.v2,
        };
        let k1 = self.deriv(y);
        let k2 = self.deriv(&add(y, &k1, 0.5 * h));
        let k3 = self.deriv(&add(y, &k2, 0.5 * h));
        let k4 = self.deriv(&add(y, &k3, h));
        NormalState {
            s1: y.s1 + h / 6.0 * (k1.s1 + 2.0 * k2.s1 + 2.0 * k3.s1 + k4.s1),
            v1: y.v1 + h / 6.0 * (k1.v1 + 2.0 * k2.v1 + 2.0 * k3.v1 + k4.v1),
            s2: y.s2 + h / 6.0 * (k1.s2 + 2.0 * k2.s2 + 2.0 * k3.s2 + k4.s2),
            v2: y.v2 + h / 6.0 * (k1.v2 + 2.0 * k2.v2 + 2.0 * k3.v2 + k4.v2),
        }
    }

    /// One grid step of length `h` made of RK4 sub-steps (finer in the first/last `edge` steps).
    fn grid_step(&self, y: &NormalState, h: f64, edge: bool) -> NormalState {
        self.sub_stepped(y, h, if edge { EDGE_SUBSTEPS } else { SUBSTEPS })
    }

    fn sub_stepped(&self, y: &NormalState, h: f64, n: usize) -> NormalState {
        let hs = h / n as f64;
        (0..n).fold(*y, |acc, _| self.rk4(&acc, hs))
    }

    fn start(&self) -> NormalState {
        NormalState {
            s1: 0.0,
            v1: self.approach_speed,
            s2: 0.0,
            v2: 0.0,
        }
    }

    fn closed_form(&self) -> HertzClosedForm {
        HertzClosedForm {
            mass: 1.0 / (self.inv_mass1 + self.inv_mass2),
            stiffness: self.stiffness,
            approach_speed: self.approach_speed,
        }
    }

    /// Measure the contact time by integrating until the bodies separate.
    ///
    /// The closed form is used only to size the search step; the separation instant is found by
    /// bisection on a single RK4 step from the last grid node before separation.
    pub fn measure_contact_time(&self) -> f64 {
        let guess = self.closed_form().contact_time();
        let n = 256;
        let h = guess / n as f64;
        let mut y = self.start();
        let mut t = 0.0;
        let mut j = 0usize;
        loop {
            let edge = j == 0;
            let next = self.grid_step(&y, h, edge);
            if next.s1 - next.s2 <= 0.0 && j > 0 {
                break;
            }
            y = next;
            t += h;
            j += 1;
            if j > 4 * n {
                // Cannot happen for Hertz motion; stop rather than loop forever.
                return guess;
            }
        }
        // Separation lies in (t, t + h]: bisect on the sub-stepped integration from y.
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..64 {
            let mid = 0.5 * (lo + hi);
            let z = self.sub_stepped(&y, mid, 32);
            if z.s1 - z.s2 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        t + 0.5 * (lo + hi)
    }

    /// Integrate the normal motion on `steps` uniform steps spanning the measured contact.
    pub fn trajectory(&self, steps: usize) -> NormalTrajectory {
        self.trajectory_over(steps, self.measure_contact_time())
    }

    /// [`NormalBodies::trajectory`] with the contact time `tc` (s) measured before
    /// ([`NormalBodies::measure_contact_time`] of the same bodies): the same values, without
    /// measuring it again (the measurement costs about as much as integrating 1 000 steps).
    pub fn trajectory_over(&self, steps: usize, tc: f64) -> NormalTrajectory {
        let steps = steps.max(2);
        let h = tc / steps as f64;
        let mut d = Vec::with_capacity(steps + 1);
        let mut rate = Vec::with_capacity(steps + 1);
        let mut accel = Vec::with_capacity(steps + 1);
        let inv_m = self.inv_mass1 + self.inv_mass2;
        let mut y = self.start();
        d.push(0.0);
        rate.push(self.approach_speed);
        accel.push(0.0);
        let mut best = (0.0_f64, 0usize);
        for j in 0..steps {
            let edge = j == 0 || j + 1 == steps;
            y = self.grid_step(&y, h, edge);
            let dj = if j + 1 == steps {
                0.0
            } else {
                (y.s1 - y.s2).max(0.0)
            };
            if dj > best.0 {
                best = (dj, j + 1);
            }
            d.push(dj);
            rate.push(y.v1 - y.v2);
            accel.push(-self.force(dj) * inv_m);
        }
        // Refine the maximum with a parabola through the three nodes around it.
        let j = best.1;
        let dmax = if j > 0 && j < steps {
            let (a, b, c) = (d[j - 1], d[j], d[j + 1]);
            let denom = a - 2.0 * b + c;
            if denom < 0.0 {
                b - 0.125 * (c - a) * (c - a) / denom
            } else {
                b
            }
        } else {
            best.0
        };
        NormalTrajectory {
            indentation: d,
            rate,
            accel,
            accel_factor: self.stiffness * inv_m,
            dt: h,
            contact_time: tc,
            max_indentation: dmax,
            peak_force: self.force(dmax),
            delta_v1: y.v1 - self.approach_speed,
            delta_v2: y.v2,
        }
    }
}

impl NormalTrajectory {
    /// The trajectory of `bodies` from its nodes as [`NormalBodies::trajectory_over`] computed
    /// them (`indentation`, `rate`, both `steps + 1` long, and the scalars it measured): the
    /// accelerations and the step are derived the same way, to the bit.
    pub(crate) fn from_nodes(
        bodies: &NormalBodies,
        tc: f64,
        indentation: Vec<f64>,
        rate: Vec<f64>,
        [max_indentation, peak_force, delta_v1, delta_v2]: [f64; 4],
    ) -> Self {
        let steps = indentation.len() - 1;
        let inv_m = bodies.inv_mass1 + bodies.inv_mass2;
        let accel = std::iter::once(0.0)
            .chain(indentation[1..].iter().map(|&d| -bodies.force(d) * inv_m))
            .collect();
        NormalTrajectory {
            indentation,
            rate,
            accel,
            accel_factor: bodies.stiffness * inv_m,
            dt: tc / steps as f64,
            contact_time: tc,
            max_indentation,
            peak_force,
            delta_v1,
            delta_v2,
        }
    }

    /// Indentation and its rate at time `t ∈ [0, dt]` into step `n`, by cubic Hermite
    /// interpolation of the nodes (error O(dt⁴)).
    pub fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        hermite(
            self.dt,
            (self.indentation[n], self.indentation[n + 1]),
            (self.rate[n], self.rate[n + 1]),
            t,
        )
    }
}

/// Cubic Hermite interpolation over a step of length `h` between values `p0, p1` with rates
/// `r0, r1`: the value and the rate at time `t ∈ [0, h]`, the value clamped at 0.
pub fn hermite(h: f64, (p0, p1): (f64, f64), (r0, r1): (f64, f64), t: f64) -> (f64, f64) {
    let s = t / h;
    let (m0, m1) = (r0 * h, r1 * h);
    let s2 = s * s;
    let s3 = s2 * s;
    let d = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
        + (s3 - 2.0 * s2 + s) * m0
        + (-2.0 * s3 + 3.0 * s2) * p1
        + (s3 - s2) * m1;
    let dd = ((6.0 * s2 - 6.0 * s) * p0
        + (3.0 * s2 - 4.0 * s + 1.0) * m0
        + (-6.0 * s2 + 6.0 * s) * p1
        + (3.0 * s2 - 2.0 * s) * m1)
        / h;
    (d.max(0.0), dd)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dimensionless_closed_form_values() {
        let h = HertzClosedForm {
            mass: 1.0,
            stiffness: 4.0 / 3.0,
            approach_speed: 1.0,
        };
        assert!((h.max_indentation() - 0.974_514_960_229_047_3).abs() < 1e-14);
        assert!((h.contact_time() - 2.868_265_699_195_331_5).abs() < 1e-13);
    }

    #[test]
    fn measured_trajectory_matches_closed_form() {
        let b = NormalBodies {
            inv_mass1: 1.0,
            inv_mass2: 0.0,
            stiffness: 4.0 / 3.0,
            approach_speed: 1.0,
        };
        let tr = b.trajectory(400);
        let cf = b.closed_form();
        assert!((tr.contact_time / cf.contact_time() - 1.0).abs() < 1e-9);
        assert!((tr.peak_force / cf.peak_force() - 1.0).abs() < 1e-6);
        // Elastic: the normal velocity reverses.
        assert!((tr.delta_v1 + 2.0).abs() < 1e-9, "{}", tr.delta_v1);
    }
}
