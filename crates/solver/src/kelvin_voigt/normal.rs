//! The Kelvin–Voigt normal law: Hertz springs with one relaxation time `τ` and non-adhesive
//! unloading (`physics.md`, "Dissipative impacts").
//!
//! Each spring of the MDR row at profile height `y = x²/R*` carries `E* (d − y + τ ḋ)` per unit
//! length while it is in contact. With `D = d + τ ḋ` (the *load*: the indentation an elastic
//! row would need for the same spring forces):
//!
//! - compression (`ḋ ≥ 0`): every spring with `y < d` is in contact,
//!   `F = k (d^{3/2} + (3/2) τ ḋ d^{1/2})` with `k = (4/3) E* √R*` (Kuwabara–Kono, Brilliantov's
//!   `A = τ`);
//! - restitution (`ḋ < 0`): a spring whose force would turn tensile leaves contact for good, so
//!   the springs in contact are those with `y < D` and `F = k D^{3/2}`;
//! - the contact ends when `D = 0`, with a residual indentation `d > 0`.
//!
//! The force is continuous with a continuous derivative in `ḋ` at `ḋ = 0`. The normal motion
//! is integrated by RK4 on fine substeps (graded at first touch, where `F ∝ √d`), and sampled
//! on the uniform time grid of the contact like [`crate::hertz::NormalTrajectory`].

use crate::hertz::HertzClosedForm;

/// Two bodies pressed by the Kelvin–Voigt normal force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViscoelasticBodies {
    /// `1/m1` (1/kg).
    pub inv_mass1: f64,
    /// `1/m2` (1/kg); 0 for a wall.
    pub inv_mass2: f64,
    /// Hertz stiffness `k = (4/3) E* √R*` (N/m^{3/2}).
    pub stiffness: f64,
    /// Approach speed `v_z0` at first touch (m/s), > 0.
    pub approach_speed: f64,
    /// Relaxation time `τ` (s), ≥ 0 (0: elastic Hertz).
    pub tau: f64,
}

/// Steps of the integration that measures the contact time and the end state of the normal
/// motion ([`ViscoelasticBodies::fine`]): against 131 072 steps, `t_c` within 2.5e-12 and `d`,
/// `ḋ` at the end within 7e-13 (e_n = 0.3–0.999).
const CONTACT_SUBSTEPS: usize = 2048;

/// Steps of the integration behind [`ViscoelasticBodies::restitution`]: a restitution accurate
/// and smooth in `τ` to about 2e-15, which the fitted relaxation time of an `e_n`
/// (`kelvin_voigt::tau_for_restitution`) is checked against.
const RESTITUTION_SUBSTEPS: usize = 16384;

/// Steps of the fine normal motion ([`ViscoelasticBodies::fine`]), one RK4 step each after a
/// graded start; the refinement's grids (powers of two up to this) are sampled from it, finer
/// ones integrated on their own grid. Against 65 536 steps (e_n = 0.3, 0.8, 0.99) its nodes
/// are within 1e-12 in `d` and 1.1e-11 in `ḋ`. With only the first step graded (`F ∝ √t`
/// then left an error of order 1.5 in the step), 8 192 steps were within 4.9e-10 and 1.1e-9.
pub const FINE_STEPS: usize = 2048;

/// Steps before the end of contact that [`ViscoelasticBodies::restitution`] integrates again on
/// substeps graded towards it (3 left 1e-14 of error in `e_n` at 16 384 steps, 32 left 2e-15).
const END_STEPS: usize = 32;

/// Normal state: indentation `d` (m) and its rate `ḋ` (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
struct State {
    d: f64,
    rate: f64,
}

impl ViscoelasticBodies {
    /// `1/m*` (1/kg).
    fn inv_mass(&self) -> f64 {
        self.inv_mass1 + self.inv_mass2
    }

    /// Normal force `F(d, ḋ)` (N) of the law; 0 out of contact.
    pub fn force(&self, d: f64, rate: f64) -> f64 {
        if rate >= 0.0 {
            if d > 0.0 {
                let r = d.sqrt();
                self.stiffness * r * (d + 1.5 * self.tau * rate)
            } else {
                0.0
            }
        } else {
            let load = d + self.tau * rate;
            if load > 0.0 {
                self.stiffness * load * load.sqrt()
            } else {
                0.0
            }
        }
    }

    fn deriv(&self, y: State) -> State {
        State {
            d: y.rate,
            rate: -self.force(y.d, y.rate) * self.inv_mass(),
        }
    }

    fn rk4(&self, y: State, h: f64) -> State {
        let i = self.rk4_increment(y, h);
        State {
            d: y.d + i.d,
            rate: y.rate + i.rate,
        }
    }

    /// Compensated (Kahan) `y + RK4 increment`, carrying the rounding in `c`.
    fn rk4_kahan(&self, y: State, c: &mut State, h: f64) -> State {
        let i = self.rk4_increment(y, h);
        let (id, ir) = (i.d - c.d, i.rate - c.rate);
        let (d, rate) = (y.d + id, y.rate + ir);
        c.d = (d - y.d) - id;
        c.rate = (rate - y.rate) - ir;
        State { d, rate }
    }

    fn rk4_increment(&self, y: State, h: f64) -> State {
        let add = |a: State, b: State, c: f64| State {
            d: a.d + c * b.d,
            rate: a.rate + c * b.rate,
        };
        let k1 = self.deriv(y);
        let k2 = self.deriv(add(y, k1, 0.5 * h));
        let k3 = self.deriv(add(y, k2, 0.5 * h));
        let k4 = self.deriv(add(y, k3, h));
        State {
            d: h / 6.0 * (k1.d + 2.0 * k2.d + 2.0 * k3.d + k4.d),
            rate: h / 6.0 * (k1.rate + 2.0 * k2.rate + 2.0 * k3.rate + k4.rate),
        }
    }

    /// `n` uniform RK4 substeps over `h`.
    fn uniform(&self, y: State, h: f64, n: usize) -> State {
        let hs = h / n as f64;
        (0..n).fold(y, |acc, _| self.rk4(acc, hs))
    }

    fn start(&self) -> State {
        State {
            d: 0.0,
            rate: self.approach_speed,
        }
    }

    /// The load `D = d + τ ḋ` of a state (m).
    fn load(&self, y: State) -> f64 {
        y.d + self.tau * y.rate
    }

    /// Whether the contact has ended at state `y` (restitution with `D ≤ 0`).
    fn ended(&self, y: State) -> bool {
        y.rate < 0.0 && self.load(y) <= 0.0
    }

    /// The elastic contact time, the scale of the substeps.
    fn hertz_time(&self) -> f64 {
        HertzClosedForm {
            mass: 1.0 / self.inv_mass(),
            stiffness: self.stiffness,
            approach_speed: self.approach_speed,
        }
        .contact_time()
    }

    /// The contact time `t_c` (s) and the state at the end of contact (`D = 0`), the span and
    /// the last node of the motion's grid: from the fitted contact of the dimensionless
    /// relaxation time `τ̂ = τ t̂_H/t_H` (`kelvin_voigt::contact_fit`, scaled by the Hertz time
    /// `t_H`; the end `ḋ = −e_n v_z0`, `d = −τ ḋ`) wherever it covers `τ̂`, else integrated
    /// on [`CONTACT_SUBSTEPS`] steps ([`Self::separation`]).
    fn until_separation(&self) -> (f64, State) {
        let t_h = self.hertz_time();
        let hat = self.tau * (unit_hertz_time() / t_h);
        match super::fit::contact_fit(hat) {
            Some((ratio, e_n)) => {
                let rate = -e_n * self.approach_speed;
                (
                    ratio * t_h,
                    State {
                        d: -self.tau * rate,
                        rate,
                    },
                )
            }
            None => self.separation(CONTACT_SUBSTEPS),
        }
    }

    /// Integrate from first touch to the end of contact (`D = 0`) by RK4 on steps
    /// `h = t_H/substeps` (`t_H` the elastic contact time), with compensated (Kahan) updates of
    /// the state: the contact time `t_c` (s) and the state there. Both ends are singular and
    /// are graded:
    ///
    /// - at touch `F ∝ √t`: the first `t_H/64` on `8 substeps/64` substeps at times
    ///   `t₀ (k/n)³`. With the first step alone graded, the steps after it kept an error of
    ///   order 1.5 in `h` (2e-10 in `e_n` at 8 192 steps);
    /// - at separation `F = k D^{3/2}` with `D ∝ t_c − t`: a step that ends `j h` before it
    ///   errs by about `h^{5/2} j^{-5/2}`, which jumped by 4e-12 between neighbouring `τ` at
    ///   8 192 steps. The end is located once on the uniform steps, then the last
    ///   [`END_STEPS`] steps are integrated again on substeps of 1/16 of the time left (down to
    ///   `1e-7 h`), and the end is bisected on the last one.
    ///
    /// Measured against 262 144 steps at e_n = 0.3–1: at 16 384 steps `e_n` is within 5e-16 –
    /// 1.8e-15, at 8 192 within 4e-15 – 1e-14, and smooth between neighbouring `τ` to the
    /// roundoff of the sums.
    fn separation(&self, substeps: usize) -> (f64, State) {
        let h = self.hertz_time() / substeps as f64;
        let span = (substeps / 64).max(1);
        let n0 = 8 * span;
        let t0 = h * span as f64;
        let mut c = State { d: 0.0, rate: 0.0 };
        let mut y = self.start();
        let mut t = 0.0;
        for k in 1..=n0 {
            let next = t0 * (k as f64 / n0 as f64).powi(3);
            y = self.rk4_kahan(y, &mut c, next - t);
            t = next;
        }
        let mut t = t0;
        // The last nodes and their compensations, to integrate the end again.
        let mut last = [(t, y, c); END_STEPS + 1];
        let mut j = 0usize;
        // A dissipative contact ends before the elastic one does; 4× is a safe cap.
        for _ in 0..4 * substeps {
            let mut c1 = c;
            let next = self.rk4_kahan(y, &mut c1, h);
            if self.ended(next) {
                break;
            }
            (y, c) = (next, c1);
            j += 1;
            t = t0 + j as f64 * h;
            last[j % (END_STEPS + 1)] = (t, y, c);
        }
        let estimate = t + self.end_within(y, h);
        (t, y, c) = last[(j - j.min(END_STEPS)) % (END_STEPS + 1)];
        for _ in 0..100_000 {
            let dt = ((estimate - t) / 16.0).clamp(1e-7 * h, h);
            let mut c1 = c;
            let next = self.rk4_kahan(y, &mut c1, dt);
            if self.ended(next) {
                let (mut lo, mut hi) = (0.0, dt);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if self.ended(self.rk4(y, mid)) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return (t + hi, self.rk4(y, hi));
            }
            (y, c) = (next, c1);
            t += dt;
        }
        // Only where the end lies more than 0.01 h past its estimate: whole steps, then the
        // end located on the last one.
        for _ in 0..4 * substeps {
            let next = self.rk4(y, h);
            if self.ended(next) {
                break;
            }
            (y, t) = (next, t + h);
        }
        let dt = self.end_within(y, h);
        (t + dt, self.uniform(y, dt, 4))
    }

    /// The time (within `h`, by bisection on four RK4 substeps) from state `y` to the end of
    /// contact, which lies within `h` of it.
    fn end_within(&self, y: State, h: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.ended(self.uniform(y, mid, 4)) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// Normal restitution `e_n = −ḋ_end / v_z0` of the impact, integrated on
    /// [`RESTITUTION_SUBSTEPS`] steps ([`Self::separation`]): within 2e-15 of 262 144 steps,
    /// and smooth in `τ` to its roundoff.
    pub fn restitution(&self) -> f64 {
        self.contact_integrated().1
    }

    /// The contact time `t_c` (s) and the normal restitution `e_n` of the impact, both
    /// integrated on [`RESTITUTION_SUBSTEPS`] steps ([`Self::separation`]; `t_c` within 1e-15
    /// of 262 144 steps): the data of the fitted contact (`kelvin_voigt::contact_fit`).
    pub fn contact_integrated(&self) -> (f64, f64) {
        let (tc, end) = self.separation(RESTITUTION_SUBSTEPS);
        (tc, -end.rate / self.approach_speed)
    }

    /// The normal motion on `steps` uniform steps spanning the measured contact. Sampled from
    /// [`ViscoelasticBodies::fine`] when `steps` divides [`FINE_STEPS`]; integrated on its own
    /// grid otherwise, with RK4 substeps no longer than the fine motion's.
    pub fn trajectory(&self, steps: usize) -> ViscoelasticTrajectory {
        let steps = steps.max(2);
        if FINE_STEPS.is_multiple_of(steps) {
            return self.fine().sample(steps);
        }
        let (tc, end) = self.until_separation();
        self.integrate(steps, tc, end, FINE_STEPS.div_ceil(steps))
    }

    /// The normal motion on [`FINE_STEPS`] uniform steps (one RK4 step each, the first graded
    /// from touch), from which [`FineMotion::sample`] takes the coarser grids.
    pub fn fine(&self) -> FineMotion {
        let (tc, end) = self.until_separation();
        FineMotion {
            grid: self.integrate(FINE_STEPS, tc, end, 1),
        }
    }

    fn integrate(&self, steps: usize, tc: f64, end: State, sub: usize) -> ViscoelasticTrajectory {
        let h = tc / steps as f64;
        let mut indentation = Vec::with_capacity(steps + 1);
        let mut rate = Vec::with_capacity(steps + 1);
        indentation.push(0.0);
        rate.push(self.approach_speed);
        // The first steps (about t_c/64, at least one) on substeps graded as t₀ (k/n)³ towards
        // touch, where F ∝ √t, stopping at each node on the way; then `sub` RK4 substeps a step.
        let graded = steps.div_ceil(64).clamp(1, steps - 1);
        let t0 = graded as f64 * h;
        let n0 = 8 * graded * sub;
        let (mut y, mut t, mut node) = (self.start(), 0.0, 1);
        for k in 1..=n0 {
            let tk = t0 * (k as f64 / n0 as f64).powi(3);
            while node <= graded && node as f64 * h <= tk {
                let tn = node as f64 * h;
                if tn > t {
                    (y, t) = (self.rk4(y, tn - t), tn);
                }
                indentation.push(y.d);
                rate.push(y.rate);
                node += 1;
            }
            if tk > t {
                (y, t) = (self.rk4(y, tk - t), tk);
            }
        }
        for _ in graded + 1..steps {
            y = self.uniform(y, h, sub);
            indentation.push(y.d);
            rate.push(y.rate);
        }
        // The last node ends the contact exactly: D = d + τ ḋ = 0 (ḋ moved by rounding only).
        let mut end_rate = end.rate;
        if self.tau > 0.0 {
            end_rate = -end.d / self.tau;
            while end.d + self.tau * end_rate > 0.0 {
                end_rate = f64::from_bits(end_rate.to_bits() + 1);
            }
        }
        indentation.push(end.d);
        rate.push(end_rate);
        let max_indentation = self.max_indentation(&indentation, &rate, h, sub.max(4));
        let inv_m = self.inv_mass();
        let delta = end.rate - self.approach_speed;
        ViscoelasticTrajectory {
            indentation,
            rate,
            tau: self.tau,
            law: *self,
            dt: h,
            contact_time: tc,
            max_indentation,
            peak_force: 0.0,
            delta_v1: delta * self.inv_mass1 / inv_m,
            delta_v2: -delta * self.inv_mass2 / inv_m,
        }
        .with_peak_force()
    }

    /// The maximum indentation, where `ḋ` changes sign: bisection on one grid step.
    fn max_indentation(&self, d: &[f64], rate: &[f64], h: f64, sub: usize) -> f64 {
        let Some(j) = rate.iter().position(|&r| r < 0.0) else {
            return d.iter().copied().fold(0.0, f64::max);
        };
        let j = j.max(1) - 1;
        let y = State {
            d: d[j],
            rate: rate[j],
        };
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.uniform(y, mid, sub).rate >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        self.uniform(y, lo, sub).d
    }
}

/// The Hertz contact time `t̂_H` of the dimensionless bodies (`m* = v_z0 = 1`, `k = 4/3`).
fn unit_hertz_time() -> f64 {
    HertzClosedForm {
        mass: 1.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
    }
    .contact_time()
}

/// The normal motion on [`FINE_STEPS`] steps, sampled for coarser grids.
#[derive(Debug, Clone)]
pub struct FineMotion {
    grid: ViscoelasticTrajectory,
}

impl FineMotion {
    /// The motion on `steps` steps (`steps` must divide [`FINE_STEPS`]): every
    /// `FINE_STEPS/steps`-th node.
    pub fn sample(&self, steps: usize) -> ViscoelasticTrajectory {
        let g = &self.grid;
        let every = FINE_STEPS / steps;
        let pick = |v: &[f64]| {
            let mut out = Vec::with_capacity(steps + 1);
            out.extend(v.iter().step_by(every).copied());
            out
        };
        // Field by field: a copy of the whole fine motion would copy its nodes for nothing.
        ViscoelasticTrajectory {
            indentation: pick(&g.indentation),
            rate: pick(&g.rate),
            tau: g.tau,
            law: g.law,
            dt: g.contact_time / steps as f64,
            contact_time: g.contact_time,
            max_indentation: g.max_indentation,
            peak_force: g.peak_force,
            delta_v1: g.delta_v1,
            delta_v2: g.delta_v2,
        }
    }
}

/// The Kelvin–Voigt normal motion sampled on the uniform time grid of the contact: node 0 is
/// first touch, node `steps` the end of contact (`D = 0`, residual indentation `d > 0`).
#[derive(Debug, Clone)]
pub struct ViscoelasticTrajectory {
    /// Indentation `d_j` (m) at `t_j = j dt`.
    pub indentation: Vec<f64>,
    /// Indentation rate `ḋ_j` (m/s).
    pub rate: Vec<f64>,
    /// Relaxation time `τ` (s).
    pub tau: f64,
    /// The bodies and the law, for the force.
    pub law: ViscoelasticBodies,
    /// Time step `dt = t_c/steps` (s).
    pub dt: f64,
    /// Measured contact time `t_c` (s): first touch to `D = 0`.
    pub contact_time: f64,
    /// Measured maximum indentation `d_max` (m), where `ḋ = 0`.
    pub max_indentation: f64,
    /// Measured peak normal force (N) (the maximum over the grid nodes and `d_max`).
    pub peak_force: f64,
    /// Normal velocity change of body 1 over the contact (m/s, along the normal from 1 to 2).
    pub delta_v1: f64,
    /// Normal velocity change of body 2 (m/s, same axis).
    pub delta_v2: f64,
}

impl ViscoelasticTrajectory {
    fn with_peak_force(mut self) -> Self {
        let law = self.law;
        let nodes = self
            .indentation
            .iter()
            .zip(&self.rate)
            .map(|(&d, &r)| law.force(d, r));
        self.peak_force = nodes.fold(law.force(self.max_indentation, 0.0), f64::max);
        self
    }

    /// The load `D = d + τ ḋ` (m) at indentation `d` and rate `ḋ`.
    #[inline(always)]
    pub fn load(&self, d: f64, rate: f64) -> f64 {
        d + self.tau * rate
    }

    /// Indentation and its rate at time `t ∈ [0, dt]` into step `n`, by cubic Hermite
    /// interpolation of the nodes.
    pub fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        crate::hertz::hermite(
            self.dt,
            (self.indentation[n], self.indentation[n + 1]),
            (self.rate[n], self.rate[n + 1]),
            t,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::FINE_STEPS;
    use crate::kelvin_voigt::unit_bodies;

    #[test]
    fn without_relaxation_it_is_hertz() {
        let tr = unit_bodies(0.0).trajectory(512);
        assert!((tr.contact_time - 2.868_265_699_195_331_5).abs() < 1e-10);
        assert!((tr.max_indentation - 0.974_514_960_229_047_3).abs() < 1e-10);
        assert!((tr.delta_v1 + 2.0).abs() < 1e-11, "{}", tr.delta_v1);
    }

    #[test]
    fn sampled_grids_are_the_fine_motion() {
        // A grid that divides the fine one is its every k-th node, with the same contact.
        let b = unit_bodies(0.1);
        let (fine, coarse) = (b.fine().sample(FINE_STEPS), b.trajectory(256));
        assert_eq!(coarse.indentation.len(), 257);
        let every = FINE_STEPS / 256;
        assert_eq!(coarse.indentation[100], fine.indentation[100 * every]);
        assert_eq!(coarse.contact_time, fine.contact_time);
        // Off the fine grid: integrated on its own, the same motion to 1e-10.
        let other = b.trajectory(300);
        assert!((other.contact_time - fine.contact_time).abs() < 1e-12);
        assert!((other.rate[300] - fine.rate[FINE_STEPS]).abs() < 1e-10);
    }
}
