//! Thornton's loading with the MDR's own unloading (`physics.md`, "Elastic–plastic impacts",
//! the variant): the same elastic–perfectly plastic loading as [`crate::thornton`], and an
//! unloading in which every MDR spring shortens by the same `d_max − d` from its state at the
//! maximum indentation, so that the line density of the pressure is
//! `q(x) = E* max(0, Q(d_max − x²/R*) − (d_max − d))` ([`crate::thornton::line::Truncated`]).
//! The Coulomb limits `μ q` are continuous at the switch (they jump under Thornton's Hertzian
//! unloading), so this law keeps the full-slip line `1 − (7/2)(1 + e_n) α` up to its critical
//! `α`. It is a solver-only law, for comparison with Thornton's: no table, no closed form of
//! `e_n` (found from the integrated motion).
//!
//! The unloading force is `F = 2 E* [∫₀^{x*} Q(d_max − x²/R*) dx − (d_max − d) x*]` with the
//! contact edge `x*² = R* (d_max − Q⁻¹(d_max − d))`, in closed form; the contact ends at
//! `d = d_max − Q(d_max)`. The unloading motion is integrated (RK4, 8 sub-steps a grid step, 256
//! in the last), the contact's end located by bisection.

use std::cell::RefCell;
use std::collections::HashMap;

use crate::error::PhysicsError;
use crate::hertz::hermite;
use crate::impact::{
    check_alpha, check_gamma, run_contact_with, ContactPoint, Scheme, TangentialBodies,
};
use crate::law::{
    accurate_only, continuum_only, shear_and_limit, BodiesNormal, ContactLaw, Floor, NormalSummary,
    PARAMETER_KEYS,
};
use crate::model::NormalModel;
use crate::resolution::Resolution;
use crate::thornton::line::Truncated;
use crate::thornton::normal::{two_part_grid, Loading, Motion};
use crate::thornton::row::ThorntonRow;
use crate::thornton::{elastic_peak_pressure, yield_indentation, yield_pressure_for_restitution};
use crate::zones::Level;

/// Sub-steps of RK4 per grid step of the unloading, and in its last step.
const SUBSTEPS: usize = 8;
const LAST_SUBSTEPS: usize = 256;

/// The unloading by the MDR rule from `(d_max, F_max)` of a Thornton loading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MdrUnloading {
    /// The loading's line density (its `d_y`).
    pub line: Truncated,
    /// Maximum indentation `d_max` (m).
    pub max_indentation: f64,
    /// Effective radius `R*` (m).
    pub radius: f64,
    /// `2 E*` (Pa): `F = 2 E* ∫₀^{x*} q dx / E*`.
    pub twice_modulus: f64,
}

impl MdrUnloading {
    /// The unloading of bodies with Hertz stiffness `k = (4/3) E* √R*` and radius `R*`.
    pub fn new(loading: &Loading, radius: f64, max_indentation: f64) -> Self {
        MdrUnloading {
            line: Truncated {
                yield_indentation: loading.yield_indentation,
            },
            max_indentation,
            radius,
            twice_modulus: 1.5 * loading.stiffness / radius.sqrt(),
        }
    }

    /// Indentation at which the contact ends, `d_max − Q(d_max)` (m).
    pub fn end(&self) -> f64 {
        self.max_indentation - self.line.value(self.max_indentation)
    }

    /// The contact's reach `y* = d_max − Q⁻¹(d_max − d)` (m): the contact radius is `√(R* y*)`.
    pub fn reach(&self, d: f64) -> f64 {
        let shift = (self.max_indentation - d).max(0.0);
        (self.max_indentation - self.line.inverse(shift)).max(0.0)
    }

    /// The unloading force (N) at indentation `d` (m).
    pub fn force(&self, d: f64) -> f64 {
        let shift = (self.max_indentation - d).max(0.0);
        let x = (self.radius * self.reach(d)).sqrt();
        let f = self.line.integral(self.max_indentation, x, self.radius) - shift * x;
        (self.twice_modulus * f).max(0.0)
    }
}

/// The motion of one impact under this law: Thornton's loading ([`Motion`]) up to `d_max`,
/// then the MDR unloading, integrated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MdrMotion {
    /// The loading (and Thornton's unloading, unused).
    pub thornton: Motion,
    /// The unloading.
    pub unloading: MdrUnloading,
    /// Duration of the unloading (s).
    pub unloading_time: f64,
    /// Rebound speed (m/s).
    pub rebound_speed: f64,
}

/// `(d, ḋ)` advanced by one RK4 step of length `h` under `d̈ = −a(d)`.
fn rk4(a: &dyn Fn(f64) -> f64, (d, v): (f64, f64), h: f64) -> (f64, f64) {
    let k1 = (v, -a(d));
    let k2 = (v + 0.5 * h * k1.1, -a(d + 0.5 * h * k1.0));
    let k3 = (v + 0.5 * h * k2.1, -a(d + 0.5 * h * k2.0));
    let k4 = (v + h * k3.1, -a(d + h * k3.0));
    (
        d + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
        v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
    )
}

impl MdrMotion {
    /// The motion of bodies with `1/m1 + 1/m2 = inv_mass` (1/kg), radius `R*` (m) under
    /// `loading`, meeting at `approach_speed` (m/s).
    pub fn new(loading: Loading, radius: f64, inv_mass: f64, approach_speed: f64) -> Self {
        let thornton = Motion::new(loading, inv_mass, approach_speed);
        let unloading = MdrUnloading::new(&loading, radius, thornton.max_indentation);
        if thornton.plastic.is_none() {
            // Elastic: the MDR unloading is Hertz's own.
            return MdrMotion {
                thornton,
                unloading,
                unloading_time: thornton.rebound.turning_time(),
                rebound_speed: approach_speed,
            };
        }
        let acc = |d: f64| unloading.force(d) * inv_mass;
        let end = unloading.end();
        // March with steps of a 1024th of the loading time until the contact ends, then bisect
        // the last step on its sub-stepped integration.
        let h = thornton.switch_time / 1024.0;
        let sub = |y: (f64, f64), span: f64, n: usize| {
            let hs = span / n as f64;
            (0..n).fold(y, |acc_y, _| rk4(&acc, acc_y, hs))
        };
        let mut y = (thornton.max_indentation, 0.0);
        let mut t = 0.0;
        for _ in 0..1_000_000 {
            let next = sub(y, h, SUBSTEPS);
            if next.0 <= end {
                break;
            }
            y = next;
            t += h;
        }
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if sub(y, mid, LAST_SUBSTEPS).0 > end {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let last = sub(y, hi, LAST_SUBSTEPS);
        MdrMotion {
            thornton,
            unloading,
            unloading_time: t + 0.5 * (lo + hi),
            rebound_speed: -last.1,
        }
    }

    /// Normal restitution `e_n = v_r/V`.
    pub fn restitution(&self) -> f64 {
        self.rebound_speed / self.thornton.approach_speed
    }

    /// Contact time (s).
    pub fn contact_time(&self) -> f64 {
        self.thornton.switch_time + self.unloading_time
    }

    /// The motion on a grid of `steps` steps with the switch at a node ([`MdrTrajectory`]).
    pub fn trajectory(&self, steps: usize) -> MdrTrajectory {
        let m = &self.thornton;
        let (loading_steps, unloading_steps, h1, h2) =
            two_part_grid(steps, m.switch_time, self.unloading_time);
        let mut indentation = Vec::with_capacity(steps + 1);
        let mut rate = Vec::with_capacity(steps + 1);
        for j in 0..loading_steps {
            let (d, v) = m.loading_state(j as f64 * h1);
            indentation.push(d);
            rate.push(v);
        }
        let inv_mass = m.inv_mass;
        let un = self.unloading;
        let acc = |d: f64| un.force(d) * inv_mass;
        let mut y = (m.max_indentation, 0.0);
        indentation.push(y.0);
        rate.push(y.1);
        for j in 0..unloading_steps {
            let n = if j + 1 == unloading_steps {
                LAST_SUBSTEPS
            } else {
                SUBSTEPS
            };
            let hs = h2 / n as f64;
            y = (0..n).fold(y, |acc_y, _| rk4(&acc, acc_y, hs));
            if j + 1 == unloading_steps {
                y.0 = un.end();
            }
            indentation.push(y.0.max(un.end()));
            rate.push(y.1);
        }
        MdrTrajectory {
            motion: *self,
            indentation,
            rate,
            switch: loading_steps,
            loading_step: h1,
            unloading_step: h2,
        }
    }
}

/// [`MdrMotion`] on a grid of two uniform parts, the switch at node `switch`.
#[derive(Debug, Clone)]
pub struct MdrTrajectory {
    /// The motion sampled.
    pub motion: MdrMotion,
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

impl NormalModel for MdrTrajectory {
    fn steps(&self) -> usize {
        self.indentation.len() - 1
    }
    fn dt(&self) -> f64 {
        self.unloading_step
    }
    fn step_length(&self, n: usize) -> f64 {
        if n < self.switch {
            self.loading_step
        } else {
            self.unloading_step
        }
    }
    fn contact_time(&self) -> f64 {
        self.motion.contact_time()
    }
    fn max_indentation(&self) -> f64 {
        self.motion.thornton.max_indentation
    }
    fn indentation(&self, n: usize) -> f64 {
        self.indentation[n]
    }
    fn rate(&self, n: usize) -> f64 {
        self.rate[n]
    }
    fn acceleration(&self, d: f64, rate: f64) -> f64 {
        let m = &self.motion;
        let f = if rate < 0.0 {
            m.unloading.force(d)
        } else {
            m.thornton.loading.force(d)
        };
        -f * m.thornton.inv_mass
    }
    fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        hermite(
            self.step_length(n),
            (self.indentation[n], self.indentation[n + 1]),
            (self.rate[n], self.rate[n + 1]),
            t,
        )
    }
    /// `d` in loading, `d_max − Q⁻¹(d_max − d)` in unloading.
    fn reach(&self, (d, rate): (f64, f64)) -> f64 {
        if rate < 0.0 {
            self.motion.unloading.reach(d)
        } else {
            d
        }
    }
}

/// The dimensionless motion (`m* = R* = E* = v_z0 = 1`) with limiting pressure `p_y`.
pub fn dimensionless_motion(yield_pressure: f64) -> MdrMotion {
    let loading = Loading {
        stiffness: 4.0 / 3.0,
        yield_indentation: yield_indentation(yield_pressure, 1.0, 1.0),
    };
    MdrMotion::new(loading, 1.0, 1.0, 1.0)
}

thread_local! {
    static PRESSURE_CACHE: RefCell<HashMap<u64, f64>> = RefCell::new(HashMap::new());
    static MOTION_CACHE: RefCell<HashMap<u64, MdrMotion>> = RefCell::new(HashMap::new());
}

/// The dimensionless motion of `p_y`, cached per thread.
fn cached_motion(yield_pressure: f64) -> MdrMotion {
    MOTION_CACHE.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() > 256 {
            c.clear();
        }
        *c.entry(yield_pressure.to_bits())
            .or_insert_with(|| dimensionless_motion(yield_pressure))
    })
}

/// The dimensionless limiting pressure whose impact under this law has normal restitution
/// `e_n ∈ [0.3, 1]` (`p_0` at 1): a bracketed secant (Illinois) search on the integrated
/// restitution between Thornton's pressure of that `e_n` (this law loses more at equal `p_y`)
/// and `p_0`, to 1e-14 in `e_n`. Cached per thread.
pub fn yield_pressure_for_restitution_mdr(e_n: f64) -> Result<f64, PhysicsError> {
    let e_n = crate::law::check_restitution(e_n)?;
    if e_n == 1.0 {
        return Ok(elastic_peak_pressure());
    }
    if let Some(p) = PRESSURE_CACHE.with(|c| c.borrow().get(&e_n.to_bits()).copied()) {
        return Ok(p);
    }
    // Illinois (bracketed secant) on f(p) = e_n(p) − e_n, increasing in p.
    let f = |p: f64| cached_motion(p).restitution() - e_n;
    let (mut lo, mut hi) = (
        yield_pressure_for_restitution(e_n)?,
        elastic_peak_pressure(),
    );
    let (mut f_lo, mut f_hi) = (f(lo), f(hi));
    let mut p = 0.5 * (lo + hi);
    let mut side = 0;
    for _ in 0..200 {
        p = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if !(p > lo && p < hi) {
            p = 0.5 * (lo + hi);
        }
        let fp = f(p);
        if fp.abs() <= 1e-14 || hi - lo <= 1e-13 {
            break;
        }
        if fp < 0.0 {
            (lo, f_lo) = (p, fp);
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        } else {
            (hi, f_hi) = (p, fp);
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        }
    }
    PRESSURE_CACHE.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() > 4096 {
            c.clear();
        }
        c.insert(e_n.to_bits(), p)
    });
    Ok(p)
}

/// `P` of the dimensionless impact of `motion` on `steps` steps with `G* = shear` and limit
/// factor `limit`.
pub fn dimensionless_p(shear: f64, limit: f64, motion: &MdrMotion, steps: usize) -> f64 {
    let trajectory = motion.trajectory(steps);
    let row = ThorntonRow::with_mdr_unloading(
        1.0,
        motion.thornton.loading.yield_indentation,
        motion.thornton.max_indentation,
    );
    let mut cp = ContactPoint { u: 1.0 };
    run_contact_with(&mut cp, &trajectory, row, 1.0, shear, limit);
    cp.u
}

/// The law ([`ContactLaw`]): `e_n ∈ [0.3, 1]`, its limiting pressure, the accurate scheme on
/// the continuum row only.
#[derive(Debug, Clone, Copy, Default)]
pub struct ThorntonMdr;

/// The law's parameters: the dimensionless limiting pressure, as Thornton's
/// ([`crate::thornton::Parameters`]).
pub type Parameters = crate::thornton::Parameters;

/// Its parameters of physical bodies: the limiting pressure in Pa.
pub type BodiesParameters = crate::thornton::BodiesParameters;

impl ContactLaw for ThorntonMdr {
    type Parameters = Parameters;
    type BodiesParameters = BodiesParameters;
    const FLOOR: Floor = crate::thornton::RAW_FLOOR;

    fn check_restitution(e_n: f64) -> Result<f64, PhysicsError> {
        crate::law::check_restitution(e_n)
    }

    fn parameters(e_n: f64) -> Result<Parameters, PhysicsError> {
        Ok(Parameters {
            yield_pressure: yield_pressure_for_restitution_mdr(e_n)?,
        })
    }

    fn prepare(
        gamma: f64,
        alpha: f64,
        e_n: f64,
        scheme: Scheme,
    ) -> Result<(f64, f64, Parameters), PhysicsError> {
        let gamma = check_gamma(gamma)?;
        let alpha = check_alpha(alpha)?;
        accurate_only(
            scheme,
            "for the thornton-mdr law",
            "it is solved with the accurate scheme only (euler is for elastic impacts)",
        )?;
        Ok((gamma, alpha, Self::parameters(e_n)?))
    }

    /// `P = 1` at `α = 0`; the full-slip line holds up to the law's critical α, which has no
    /// closed form: it is simulated.
    fn closed_form(_gamma: f64, alpha: f64, _e_n: f64) -> Option<f64> {
        (alpha == 0.0).then_some(1.0)
    }

    fn simulate(
        gamma: f64,
        alpha: f64,
        parameters: Parameters,
        res: Resolution,
        _scheme: Scheme,
    ) -> Result<Level, PhysicsError> {
        let res = res.validate()?;
        continuum_only(
            res.springs,
            "for the thornton-mdr law",
            "it is solved on the continuum row only (springs 0)",
        )?;
        let (shear, limit) = shear_and_limit(gamma, alpha);
        let motion = cached_motion(parameters.yield_pressure);
        Ok(Level::unwatched(dimensionless_p(
            shear, limit, &motion, res.steps,
        )))
    }

    /// Thornton's ([`crate::thornton::Thornton`]): the same parameter.
    fn values(parameters: &Parameters) -> [f64; PARAMETER_KEYS.len()] {
        crate::thornton::Thornton::values(parameters)
    }

    fn describe(parameters: &Parameters) -> Option<String> {
        crate::thornton::Thornton::describe(parameters)
    }

    /// `p̂_y` of the bodies and the `e_n` of its integrated motion (1 at or below the yield
    /// speed); at least 0.3.
    fn of_bodies(
        parameters: BodiesParameters,
        normal: &BodiesNormal,
    ) -> Result<(Parameters, f64), PhysicsError> {
        let (p, _) = crate::thornton::Thornton::of_bodies(parameters, normal)?;
        let e_n = cached_motion(p.yield_pressure).restitution();
        if crate::law::check_restitution(e_n).is_err() {
            return Err(PhysicsError::InvalidParameter {
                name: "yield_pressure",
                value: parameters.yield_pressure,
                allowed: "a pressure whose normal restitution at this impact speed is >= 0.3 (a \
                          higher limiting pressure, or a slower impact)",
            });
        }
        Ok((p, e_n))
    }

    /// The bodies' motion under this law and its row (continuum only); the elastic run at or
    /// below the yield speed.
    fn run_bodies<B: TangentialBodies>(
        bodies: &mut B,
        normal: &BodiesNormal,
        parameters: BodiesParameters,
        res: Resolution,
        (radius, shear_modulus, limit): (f64, f64, f64),
    ) -> Result<NormalSummary, PhysicsError> {
        let modulus = 0.75 * normal.stiffness / normal.radius.sqrt();
        let loading = Loading {
            stiffness: normal.stiffness,
            yield_indentation: yield_indentation(parameters.yield_pressure, normal.radius, modulus),
        };
        let inv_mass = normal.inv_mass1 + normal.inv_mass2;
        let motion = MdrMotion::new(loading, normal.radius, inv_mass, normal.approach_speed);
        if motion.thornton.plastic.is_none() {
            return crate::elastic::Elastic::run_bodies(
                bodies,
                normal,
                crate::elastic::Parameters,
                res,
                (radius, shear_modulus, limit),
            );
        }
        continuum_only(
            res.springs,
            "for thornton-mdr bodies",
            "their law is solved on the continuum row only (springs 0)",
        )?;
        let trajectory = motion.trajectory(res.steps);
        let row = ThorntonRow::with_mdr_unloading(
            radius,
            loading.yield_indentation,
            motion.thornton.max_indentation,
        );
        let shortest_zone =
            run_contact_with(bodies, &trajectory, row, radius, shear_modulus, limit);
        let change = (normal.approach_speed + motion.rebound_speed) / inv_mass;
        Ok(NormalSummary {
            contact_time: motion.contact_time(),
            peak_force: motion.thornton.peak_force,
            max_indentation: motion.thornton.max_indentation,
            delta_v1: -change * normal.inv_mass1,
            delta_v2: change * normal.inv_mass2,
            shortest_zone,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unloading force starts at the loading's peak force and the contact edge at the
    /// loading's contact radius; it falls to zero where the contact ends.
    #[test]
    fn the_unloading_is_continuous_at_the_switch() {
        let m = dimensionless_motion(0.35);
        let un = m.unloading;
        let peak = m.thornton.loading.force(un.max_indentation);
        assert!((un.force(un.max_indentation) - peak).abs() < 1e-14 * peak);
        assert!((un.reach(un.max_indentation) - un.max_indentation).abs() < 1e-15);
        assert!(un.force(un.end()) < 1e-12 * peak);
        assert!(un.force(un.end() + 1e-3) > 0.0);
    }

    /// `physics.md`: this unloading gives `e_n = 0.9394` at `p_y = 0.5`, against Thornton's
    /// 0.9490.
    #[test]
    fn the_restitution_of_physics_md() {
        let m = dimensionless_motion(0.5);
        assert!(
            (m.restitution() - 0.9394).abs() < 5e-5,
            "{}",
            m.restitution()
        );
        assert!((m.thornton.restitution() - 0.94896755712).abs() < 1e-10);
        let p = yield_pressure_for_restitution_mdr(0.8).unwrap();
        assert!((dimensionless_motion(p).restitution() - 0.8).abs() < 1e-10);
        assert!(p > yield_pressure_for_restitution(0.8).unwrap());
    }
}
