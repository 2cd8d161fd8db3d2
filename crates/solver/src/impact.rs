//! One impact in dimensionless form: `(γ, α) → P`.
//!
//! Units as in `physics.md`: `m* = R* = E* = v_z0 = 1`, `G* = (2/7)γ²`, tangential mass
//! `m_t = 2/7`, `μ = α`, `u0 = 1` (for `α = ∞` the Coulomb limit is removed). The Hertz contact
//! time is then ≈ 2.868.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use serde::Serialize;

use super::continuum::ContinuumRow;
use super::error::{positive, PhysicsError};
use super::hertz::{HertzClosedForm, NormalBodies, NormalTrajectory};
use super::model::{
    ExplicitEuler, Integrator, NormalModel, StepEnd, TangentialModel, VelocityVerlet,
};
use super::springs::{SpringRow, StepMotion};
use super::zones::{self, Level, ZoneClock, ZoneLog};
pub use crate::model::TangentialBodies;
pub use crate::resolution::Resolution;

/// Numerical scheme of an impact simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Scheme {
    /// Second order: velocity-Verlet steps on a Hertz normal motion integrated to 1e-11,
    /// partial increments for springs entering contact, trapezoid force with the partial edge cell.
    #[default]
    Accurate,
    /// The seed paper's scheme as published: explicit Euler, springs at cell midpoints that all
    /// receive the full step increment, normal force summed over the springs. First order.
    Euler,
}

/// `$body` with `$I` the [`Integrator`] of `scheme`: the one place a scheme's name picks its
/// integrator.
macro_rules! with_integrator {
    ($scheme:expr, $I:ident => $body:expr) => {
        match $scheme {
            Scheme::Accurate => {
                type $I = VelocityVerlet;
                $body
            }
            Scheme::Euler => {
                type $I = ExplicitEuler;
                $body
            }
        }
    };
}

impl Scheme {
    /// Name as used on the command line ([`Integrator::NAME`] of the scheme's integrator).
    pub fn name(self) -> &'static str {
        with_integrator!(self, I => I::NAME)
    }

    /// Order of convergence in the resolution `h ∝ 1/steps ∝ 1/springs`
    /// ([`Integrator::ORDER`]).
    pub fn order(self) -> i32 {
        with_integrator!(self, I => I::ORDER)
    }

    /// Whether the refinement reports the Richardson value of the scheme's last levels
    /// ([`Integrator::RICHARDSON`]).
    pub fn richardson(self) -> bool {
        with_integrator!(self, I => I::RICHARDSON)
    }
}

/// The checks of a [`Resolution`] live with the loop that runs it.
impl Resolution {
    /// Validate the counts (springs 0 (continuum) or ≥ 2, steps ≥ 8).
    pub fn validate(self) -> Result<Self, PhysicsError> {
        if self.springs == 1 {
            return Err(PhysicsError::InvalidParameter {
                name: "springs",
                value: self.springs as f64,
                allowed: "0 (the continuum limit) or an integer >= 2",
            });
        }
        if self.steps < 8 {
            return Err(PhysicsError::InvalidParameter {
                name: "steps",
                value: self.steps as f64,
                allowed: "an integer >= 8",
            });
        }
        Ok(self)
    }
}

/// Check `γ` (finite, > 0).
pub fn check_gamma(gamma: f64) -> Result<f64, PhysicsError> {
    positive("gamma", gamma)
}

/// Check `α` (≥ 0, `+∞` allowed, not NaN).
pub fn check_alpha(alpha: f64) -> Result<f64, PhysicsError> {
    if alpha >= 0.0 {
        Ok(alpha)
    } else {
        Err(PhysicsError::InvalidParameter {
            name: "alpha",
            value: alpha,
            allowed: ">= 0 (or inf for no slip)",
        })
    }
}

/// The contact-point coordinate of one solid sphere in dimensionless units (`m_t = 2/7`).
pub(crate) struct ContactPoint {
    /// Slip velocity `u` (`u0 = 1` at the start).
    pub(crate) u: f64,
}

const INV_TANGENTIAL_MASS: f64 = 3.5;

impl TangentialBodies for ContactPoint {
    fn slip_velocity(&self) -> f64 {
        self.u
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        -f * INV_TANGENTIAL_MASS
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.u -= h * f * INV_TANGENTIAL_MASS;
    }
}

/// State of the accurate scheme ([`VelocityVerlet`]) between steps.
struct Stepper<'a, N: NormalModel, T: TangentialModel> {
    row: T,
    normal: &'a N,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
    /// Friction force at the current time (N).
    force: f64,
    /// Mean spring displacement at the current time (m).
    mean: f64,
    /// How far the mean displacement was from its gross-slip value at the start of the
    /// previous grid step (m; [`Stepper::gross_slip_onset`]).
    limit_gap: f64,
    /// The zones of the row so far ([`crate::zones`]).
    zones: ZoneClock,
}

impl<N: NormalModel, T: TangentialModel> Stepper<'_, N, T> {
    /// The motion over a step of length `h` from `(d0, rate0)` to `(d1, rate1)`.
    fn motion<B: TangentialBodies>(
        &self,
        bodies: &B,
        h: f64,
        (d0, rate0): (f64, f64),
        (d1, rate1): (f64, f64),
    ) -> StepMotion {
        StepMotion {
            h,
            d0,
            rate0,
            accel0: self.normal.acceleration(d0, rate0),
            slip_velocity: bodies.slip_velocity(),
            slip_accel: bodies.slip_acceleration(self.force),
            rate1,
            accel1: if T::END_STATE {
                self.normal.acceleration(d1, rate1)
            } else {
                0.0
            },
        }
    }

    /// One velocity-Verlet step of length `h` from indentation `d0` (rate `rate0`) to `d1`
    /// (rate `rate1`).
    fn step<B: TangentialBodies>(
        &mut self,
        bodies: &mut B,
        h: f64,
        start: (f64, f64),
        end: (f64, f64),
    ) {
        let motion = self.motion(bodies, h, start, end);
        let step = self.row.step_accurate(&motion, end.0, self.limit);
        self.zones
            .record(zones::state(self.row.at_limit(), self.row.stuck()), h);
        // The contact's reach (`d` for an elastic law) at both ends: the contact radius is
        // `a = √(R* reach)`.
        let (b0, b1) = (self.normal.reach(start), self.normal.reach(end));
        // Impulse by product integration: F = 2 G* a(t) · mean(t), with ∫ a dt exact for the
        // reach linear over the step. Near separation a ∝ √(t_c − t), where the plain trapezoid
        // rule would drop to order 1.5 (no slip keeps a finite mean displacement to the end).
        let mean_radius = mean_sqrt(b0, b1) * self.radius.sqrt();
        let end_mean = if b1 <= 0.0 && self.limit.is_finite() {
            separation_mean(self.mean, self.limit * b0)
        } else {
            step.mean
        };
        // The impulse over the step and the force and mean at its end: the model's
        // ([`TangentialModel::close_step`]; the elastic rule by default).
        let end = StepEnd {
            motion: &motion,
            step,
            radius: self.radius,
            shear_modulus: self.shear_modulus,
            mean_radius,
            mean0: self.mean,
            end_mean,
            reach1: b1,
        };
        (self.force, self.mean) = self.row.close_step(bodies, &end);
    }

    /// Grid step `n`, split at the release instant of the springs at a Coulomb limit when it
    /// falls inside ([`TangentialModel::release_time`]): F(t) has a kink there and the
    /// trapezoid impulse across a kink is only first order locally.
    fn grid_step<B: TangentialBodies>(&mut self, bodies: &mut B, n: usize) {
        let nt = self.normal;
        let h = nt.step_length(n);
        let start = (nt.indentation(n), nt.rate(n));
        let end = (nt.indentation(n + 1), nt.rate(n + 1));
        // A jump of the field at this node ([`TangentialModel::jump`]): the step starts from
        // the new force.
        if let Some(j) = self.row.jump(start, end, self.limit) {
            self.force = 2.0 * self.shear_modulus * j.integral;
            self.mean = j.mean;
        }
        let gap = if T::LOCATES_GROSS_SLIP {
            self.gap_to_gross_slip(start)
        } else {
            f64::INFINITY
        };
        let split = self
            .row
            .release_time(&self.motion(bodies, h, start, end), self.limit)
            .or_else(|| self.gross_slip_onset(h, gap));
        self.limit_gap = gap;
        match split {
            Some(t) => {
                let mid = nt.within_step(n, t);
                self.step(bodies, t, start, mid);
                self.step(bodies, h - t, mid, end);
            }
            None => self.step(bodies, h, start, end),
        }
    }
}

impl<N: NormalModel, T: TangentialModel> Stepper<'_, N, T> {
    /// The instant (s into a grid step of length `h`) at which the whole contact reaches a
    /// Coulomb limit, when `gap`, the gap of the mean displacement to its gross-slip value at
    /// the step's start ([`Stepper::gap_to_gross_slip`]), closing at the rate of the previous
    /// step, closes inside this one; `None` otherwise, for a model that does not locate gross
    /// slip ([`TangentialModel::LOCATES_GROSS_SLIP`]), or within 1e-3 of the step of its ends.
    /// The extrapolation places the onset within `O(h²)` of the step, where the kink's error
    /// is of higher order than the scheme's.
    fn gross_slip_onset(&self, h: f64, gap: f64) -> Option<f64> {
        if !T::LOCATES_GROSS_SLIP {
            return None;
        }
        let closing = self.limit_gap - gap;
        if !(gap > 0.0 && closing > gap) {
            return None;
        }
        let t = h * gap / closing;
        (t > 1e-3 * h && t < (1.0 - 1e-3) * h).then_some(t)
    }
}

/// Relative size of a gap to gross slip that is the rounding of the mean displacement in gross
/// slip ([`Stepper::gap_to_gross_slip`]). Without it, the gap's rounding noise (±1e-17 where
/// the contact slips as a whole) read as a gap closing inside a step about once in a few
/// steps, and the step was split there: `P` on a fixed grid then moved by up to 2.6e-7 at 256
/// steps (0.017/N²) when the row's integral moved by one ulp (`kvbits 300 elastic`, 12 of 300
/// points at 256 steps, 56 at 1 024); with it, by at most 3.4e-15. A real onset this close to
/// the gross-slip value lies within 1e-9 of a step of its start and is not split anyway.
const GROSS_SLIP_ROUNDING: f64 = 1e-12;

impl<N: NormalModel, T: TangentialModel> Stepper<'_, N, T> {
    /// How far (m) the mean displacement lies from its value in gross slip, `±c (D − b/3)` for
    /// the limit level `D` and the reach `b` at the normal state `at`: the whole contact
    /// `y < b` at a Coulomb limit `±c (D − y)`. A gap within [`GROSS_SLIP_ROUNDING`] of that
    /// value is none: the contact is in gross slip, and the rounding of its mean must not look
    /// like a gap closing inside the next step.
    fn gap_to_gross_slip(&self, at: (f64, f64)) -> f64 {
        let (level, reach) = (self.normal.limit_level(at), self.normal.reach(at));
        let full = self.limit * (level - reach / 3.0);
        let gap = full - self.mean.abs();
        if gap.abs() <= GROSS_SLIP_ROUNDING * full.abs() {
            0.0
        } else {
            gap
        }
    }
}

impl<N: NormalModel, T: TangentialModel> Stepper<'_, N, T> {
    /// The grid steps from `first` to the separation, in substeps of length `h R/R₀` where `R`
    /// is the time left to the separation and `R₀ = GRADED_SPAN t_c` (at most `h`), down to
    /// `R = GRADED_FLOOR h`, then one last substep to the separation.
    ///
    /// With a finite Coulomb limit the stuck displacement of the shrinking contact is released
    /// where the limit `c (d − y)` falls below it: a ring at the edge whose width in `y` is
    /// about `|ũ|/c`, which takes over the whole contact once `d ≲ |ũ|/c`, a time
    /// `τ ≈ |ũ|/(c |ḋ|)` before separation that shrinks like `1/α`. On the uniform grid that
    /// phase is resolved only once `h ≪ τ`; before, the error jumps as `h` crosses `τ`
    /// (measured at γ = 1.989, α = 691: differences of −7.9e-7 and −9.4e-7 between 4096, 8192
    /// and 16384 steps, an estimate 2× below the true error at 2048). Substeps proportional to
    /// `R` (and to `h`) resolve every `τ` with the same relative resolution `h/R₀`, so the
    /// error stays O(h²) whatever α; it costs about `(R₀/h) ln(R₀/(GRADED_FLOOR h))` extra
    /// substeps, in a contact that is small by then.
    fn graded_end<B: TangentialBodies>(&mut self, bodies: &mut B, first: usize) {
        let nt = self.normal;
        // The steps from `first` to the separation are of one length (the last part of the
        // grid: the graded span lies after any event node).
        let h = nt.step_length(first);
        let steps = nt.steps();
        let span = (GRADED_SPAN * nt.contact_time()).max(h);
        // Grid step `n`, time `s` into it; `d`, `rate` at that instant.
        let (mut n, mut s) = (first, 0.0);
        let (mut d, mut rate) = (nt.indentation(first), nt.rate(first));
        loop {
            let left = (steps - n) as f64 * h - s;
            let sub = (h * left / span).min(h);
            if left <= GRADED_FLOOR * h {
                break;
            }
            // Substeps never straddle a grid node: stop at the node and continue from it.
            let (s1, d1, r1) = if s + sub >= h * (1.0 - 1e-12) {
                (h, nt.indentation(n + 1), nt.rate(n + 1))
            } else {
                let (d1, r1) = nt.within_step(n, s + sub);
                (s + sub, d1, r1)
            };
            if n + 1 == steps && (s1 >= h || d1.is_nan() || nt.reach((d1, r1)) <= 0.0) {
                break;
            }
            self.step(bodies, s1 - s, (d, rate), (d1, r1));
            (d, rate) = (d1, r1);
            if s1 >= h {
                (n, s) = (n + 1, 0.0);
            } else {
                s = s1;
            }
        }
        let end = h - s;
        let last = (nt.indentation(steps), nt.rate(steps));
        self.step(bodies, end, (d, rate), last);
    }
}

/// Part of the contact time before separation over which the steps are graded
/// ([`Stepper::graded_end`]).
const GRADED_SPAN: f64 = 1.0 / 32.0;

/// Time left to separation, in steps, below which the grading stops and one substep ends the
/// contact ([`separation_mean`] integrates it).
///
/// The grading costs `(R₀/h) ln(R₀/(GRADED_FLOOR h))` substeps: with 1e-7 it was about 60 %
/// more steps than the grid at 1 024–8 192 steps. With 1e-4 (28 % fewer graded substeps; 5–9 %
/// fewer instructions per warm solve at finite α, tol 1e-6), `P` at 256 and 4096 steps moved
/// by at most 2.3e-11 (γ = 1.989, α = 1e7, 256 steps, where the discretisation error is 1e-4;
/// 7e-13 at 4096) over γ ∈ {0.5, 1.989, 3}, α ∈ {3, 691, 1e5, 1e7, 1e9}, and by at most
/// 7e-15 at every level of 309 points (`tools` bin `ladder`).
const GRADED_FLOOR: f64 = 1e-4;

/// Run the tangential contact of the accurate scheme on a given normal motion: velocity Verlet
/// for the bodies, [`SpringRow::step_accurate`] for the springs (`springs ≥ 2`) or
/// [`ContinuumRow::step_accurate`] for the continuum row (`springs = 0`).
///
/// `shear_modulus` is `G*` (Pa), `limit` is `c = μ E*/G*` (`∞` for no slip), `radius` is `R*` (m).
/// Returns how finely the run resolved its approach to gross slip
/// ([`crate::zones::Level::shortest_zone`], grid steps).
pub fn run_contact<B: TangentialBodies, N: NormalModel>(
    bodies: &mut B,
    normal: &N,
    springs: usize,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
) -> f64 {
    if springs == 0 {
        let row = ContinuumRow::new(radius);
        run_contact_with(bodies, normal, row, radius, shear_modulus, limit)
    } else {
        let a_max = (radius * normal.max_indentation()).sqrt();
        let row = SpringRow::nodes(a_max, springs, radius);
        run_contact_with(bodies, normal, row, radius, shear_modulus, limit)
    }
}

/// [`run_contact`] with any normal and tangential model ([`NormalModel`], [`TangentialModel`]),
/// integrated by the accurate scheme ([`VelocityVerlet`]); monomorphised, so a model costs
/// nothing for being behind a trait. Returns the shortest zone that ended in gross slip, in
/// grid steps ([`crate::zones`]).
pub fn run_contact_with<B: TangentialBodies, N: NormalModel, T: TangentialModel>(
    bodies: &mut B,
    normal: &N,
    row: T,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
) -> f64 {
    let clock = ZoneClock::new(normal.contact_time(), normal.steps());
    run_contact_clocked(bodies, normal, row, (radius, shear_modulus, limit), clock).shortest()
}

/// [`run_contact_with`] that returns every zone of the run, of any kind ([`ZoneLog`]): a
/// diagnostic; the run itself is the same.
pub fn run_contact_zones<B: TangentialBodies, N: NormalModel, T: TangentialModel>(
    bodies: &mut B,
    normal: &N,
    row: T,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
) -> ZoneLog {
    let clock = ZoneClock::logging(normal.contact_time(), normal.steps());
    run_contact_clocked(bodies, normal, row, (radius, shear_modulus, limit), clock).log()
}

/// The run of [`run_contact_with`], its zones counted by `clock`.
fn run_contact_clocked<B: TangentialBodies, N: NormalModel, T: TangentialModel>(
    bodies: &mut B,
    normal: &N,
    row: T,
    (radius, shear_modulus, limit): (f64, f64, f64),
    clock: ZoneClock,
) -> ZoneClock {
    let mean = row.touch_mean(bodies.slip_velocity(), normal.rate(0), limit);
    let mut stepper = Stepper {
        row,
        normal,
        radius,
        shear_modulus,
        limit,
        force: 0.0,
        mean,
        limit_gap: f64::INFINITY,
        zones: clock,
    };
    let steps = normal.steps();
    // Grid steps that end within GRADED_SPAN of the separation are graded (finite limit only).
    let graded = if limit.is_finite() {
        ((steps as f64 * GRADED_SPAN).ceil() as usize).clamp(1, steps)
    } else {
        0
    };
    for n in 0..steps - graded {
        stepper.grid_step(bodies, n);
    }
    if graded > 0 {
        stepper.graded_end(bodies, steps - graded);
    }
    stepper.zones
}

/// The end value `m₁` that makes the product rule `∫ a dt · (m₀ + m₁)/2` exact over the step
/// in which the contact vanishes (`d` linear from `d₀` to 0, `a = √(R* d)`), for a finite
/// Coulomb limit `c` (`cd0 = c d₀`).
///
/// The mean displacement of the shrinking contact stays at its stuck value `m₀` until the
/// Coulomb limit of the mean, `(2/3) c d(t)`, falls below it, then follows that limit to 0:
/// `mean(t) = min(|m₀|, (2/3) c d(t))` (sign of `m₀`). With `q = d/d₀` and `q* = |m₀|/k`,
/// `k = (2/3) c d₀`: `∫₀¹ √q · mean dq = (2/5) k q*^{5/2} + (2/3)|m₀| (1 − q*^{3/2})`, and
/// `(2/3)(m₀ + m₁)` must equal twice that. Taking `m₁ = 0` instead (the Coulomb limit at the
/// vanishing contact) loses up to half the last step's impulse when `c` is large, where the
/// limit only takes over in the last instant: order 1.5 instead of 2 for large finite α
/// (measured at γ = 0.5, α = 1e9: errors 2.8× smaller per doubling, against 4× at α = ∞).
/// As `c → ∞` this tends to `m₁ = m₀`, the no-slip rule.
fn separation_mean(m0: f64, cd0: f64) -> f64 {
    let k = 2.0 / 3.0 * cd0;
    let m = m0.abs();
    if k.is_nan() || k <= 0.0 || m == 0.0 {
        return 0.0;
    }
    let q = (m / k).min(1.0);
    let integral = 0.4 * k * q * q * q.sqrt() + 2.0 / 3.0 * m * (1.0 - q * q.sqrt());
    (3.0 * integral - m).copysign(m0)
}

/// Mean of `√d(t)` over a step on which `d` goes linearly from `d0` to `d1` (both ≥ 0).
pub(crate) fn mean_sqrt(d0: f64, d1: f64) -> f64 {
    let (r0, r1) = (d0.sqrt(), d1.sqrt());
    // (2/3)(d1^{3/2} − d0^{3/2})/(d1 − d0), written without the cancelling difference.
    let s = r0 + r1;
    if s > 0.0 {
        2.0 / 3.0 * (r0 * r0 + r0 * r1 + r1 * r1) / s
    } else {
        0.0
    }
}

/// The universal dimensionless Hertz bodies (`m* = R* = E* = v_z0 = 1`).
const UNIVERSAL: NormalBodies = NormalBodies {
    inv_mass1: 1.0,
    inv_mass2: 0.0,
    stiffness: 4.0 / 3.0,
    approach_speed: 1.0,
};

/// The trajectories of [`dimensionless_normal`], shared by every thread of the process.
static NORMAL_CACHE: Mutex<BTreeMap<usize, Arc<NormalTrajectory>>> = Mutex::new(BTreeMap::new());

/// The universal motion tabulated at build time (`crates/solver/build.rs`, with this crate's
/// [`NormalBodies`]): little-endian `f64`s, the first and last power of two tabulated, the
/// measured contact time, then for each grid its maximum indentation, peak force, `Δv₁`,
/// `Δv₂`, indentations and rates.
static TABULATED: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/universal_hertz.bin"));

/// The `i`-th value of [`TABULATED`].
fn tabulated(i: usize) -> f64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&TABULATED[8 * i..8 * i + 8]);
    f64::from_le_bytes(b)
}

/// The measured contact time of the universal motion ([`NormalBodies::measure_contact_time`]
/// of [`UNIVERSAL`], tabulated at build time).
fn universal_contact_time() -> f64 {
    tabulated(2)
}

/// The universal motion on `steps` steps as tabulated at build time, where `steps` is one of
/// its powers of two.
fn tabulated_normal(steps: usize) -> Option<NormalTrajectory> {
    let (first, last) = (tabulated(0) as u32, tabulated(1) as u32);
    if !steps.is_power_of_two() || !(first..=last).contains(&steps.trailing_zeros()) {
        return None;
    }
    let mut at = 3;
    for k in first..steps.trailing_zeros() {
        at += 4 + 2 * ((1usize << k) + 1);
    }
    let scalars = [0, 1, 2, 3].map(|i| tabulated(at + i));
    let nodes = |from: usize| (from..from + steps + 1).map(tabulated).collect();
    Some(NormalTrajectory::from_nodes(
        &UNIVERSAL,
        universal_contact_time(),
        nodes(at + 4),
        nodes(at + 5 + steps),
        scalars,
    ))
}

/// The universal dimensionless normal motion (`m* = R* = E* = v_z0 = 1`) on `steps` steps,
/// shared by the threads of a process: tabulated at build time for the powers of two from 16
/// to 8192 steps (the grids of the refinement), computed once per process for others, on the
/// tabulated contact time. Before, every process integrated each level again (246 µs at
/// 1 024 steps, about as much as a warm solve's finest level), and measured the contact time
/// once (0.4 M instructions).
pub fn dimensionless_normal(steps: usize) -> Arc<NormalTrajectory> {
    let cached = |cache: &BTreeMap<usize, Arc<NormalTrajectory>>| cache.get(&steps).cloned();
    // A poisoned lock only means another thread panicked while inserting: the map is valid.
    if let Some(t) = cached(&NORMAL_CACHE.lock().unwrap_or_else(|e| e.into_inner())) {
        return t;
    }
    // Computed outside the lock, so that threads wait only for the map.
    let t = Arc::new(
        tabulated_normal(steps)
            .unwrap_or_else(|| UNIVERSAL.trajectory_over(steps, universal_contact_time())),
    );
    let mut cache = NORMAL_CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(t) = cached(&cache) {
        return t;
    }
    // Bounded memory: the refinement uses powers of two from the base level up; above 64
    // cached levels (never reached by a refinement) start again.
    if cache.len() > 64 {
        cache.clear();
    }
    cache.insert(steps, Arc::clone(&t));
    t
}

/// Above this `α` an impact is simulated as no slip (`α = ∞`).
///
/// For a finite `μ` the Coulomb limit `c (d − x²/R*)` is compared with spring displacements of
/// order `u0 t_c`; once `α = μ v_z0/|u0|` exceeds about 1e11 they differ by more than the
/// rounding of `d − x²/R*`, and the clamp near the contact edge is decided by rounding: 5e-6
/// errors at α = 3.9e11 and |P| ≈ 1e82 at α = 4e99 (u0 = 1e-100 m/s in physical units) were
/// measured before this cut-off. The no-slip limit is what such an impact tends to: at γ = 0.5,
/// `P(1e9)` and `P(∞)` agree to 1e-9 (8192 steps, `crates/solver/tests/extremes.rs`), and the gap shrinks
/// as `α` grows (7e-4 at α = 390, 6e-6 at 3.9e5).
pub const ALPHA_NO_SLIP: f64 = 1e10;

/// Simulate one elastic impact at a fixed resolution and return `P` with how finely the run
/// resolved its zones (no closed-form shortcut; [`crate::Request::simulate`] is the public door).
pub(crate) fn simulate_elastic(
    gamma: f64,
    alpha: f64,
    res: Resolution,
    scheme: Scheme,
) -> Result<Level, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let alpha = check_alpha(alpha)?;
    let res = res.validate()?;
    let shear = 2.0 / 7.0 * gamma * gamma;
    let limit = if alpha > ALPHA_NO_SLIP {
        f64::INFINITY
    } else {
        alpha / shear
    };
    with_integrator!(scheme, I => Ok(I::dimensionless_p(shear, limit, I::check(res)?)))
}

impl Integrator for VelocityVerlet {
    const NAME: &'static str = "accurate";
    const ORDER: i32 = 2;
    const RICHARDSON: bool = true;

    /// The continuum row (springs = 0) has no spatial error, so only the time error is left;
    /// it grows with γ (≈ 1.4/S² at γ = 1.9, ≈ 8/S² at γ = 3.2 for S steps,
    /// `tools/src/bin/errsplit.rs`). With springs (one per step, as this refinement used
    /// before the continuum row) the spatial error fell slowly and irregularly at large finite
    /// α (a slip ring thinner than the spacing): 8192 springs × 4096 steps for 1e-6 at
    /// γ = 2.8, α = 69, where the continuum needs 2048–4096 steps.
    fn base_resolution(scale: f64) -> Resolution {
        Resolution {
            springs: 0,
            steps: (32.0 * scale).ceil() as usize,
        }
    }

    /// One level below the base, so that the acceptance guard (`refine::previous_estimate_agrees`)
    /// has its coarser estimate at the same finest resolution as the three-level estimate
    /// alone (the extra level costs about 1/8 of the finest one).
    fn ladder_start(base: Resolution) -> Resolution {
        Resolution {
            springs: base.springs / 2,
            steps: base.steps / 2,
        }
    }

    /// The normal trajectory: 3 arrays of `steps + 1` values, counted twice because the
    /// process-wide cache keeps the coarser levels of a refinement too.
    fn normal_memory(res: Resolution) -> f64 {
        2.0 * 3.0 * 8.0 * (res.steps as f64 + 1.0)
    }

    /// About 1e-3 up to γ ≈ 2, growing like γ^1.2 beyond (1e-2 at γ = 16, 2.3e-2 at γ = 64).
    fn base_error(gamma: f64, _base: Resolution) -> f64 {
        1e-3 * (gamma / 2.0).max(1.0).powf(1.2)
    }

    /// Hertz normal motion on `res.steps` steps ([`dimensionless_normal`]), the continuum row
    /// (`res.springs = 0`) or `res.springs` springs, [`run_contact`].
    fn dimensionless_p(shear: f64, limit: f64, res: Resolution) -> Level {
        let normal = dimensionless_normal(res.steps);
        let mut cp = ContactPoint { u: 1.0 };
        let shortest_zone = run_contact(&mut cp, &*normal, res.springs, 1.0, shear, limit);
        Level {
            p: cp.u,
            shortest_zone,
        }
    }
}

impl Integrator for ExplicitEuler {
    const NAME: &'static str = "euler";
    const ORDER: i32 = 1;
    const RICHARDSON: bool = false;

    fn base_resolution(scale: f64) -> Resolution {
        let steps = (256.0 * scale).ceil() as usize;
        Resolution {
            springs: steps / 4,
            steps,
        }
    }

    fn ladder_start(base: Resolution) -> Resolution {
        base
    }

    /// The scheme integrates its own normal motion: nothing stored.
    fn normal_memory(_res: Resolution) -> f64 {
        0.0
    }

    /// `C/S` with `C ≈ 2` at the base `S`.
    fn base_error(_gamma: f64, base: Resolution) -> f64 {
        2.0 / base.steps as f64
    }

    /// At least 2 springs: the scheme has no continuum row.
    fn check(res: Resolution) -> Result<Resolution, PhysicsError> {
        if res.springs == 0 {
            return Err(PhysicsError::InvalidParameter {
                name: "springs",
                value: 0.0,
                allowed:
                    "an integer >= 2 for the euler scheme (0, the continuum, is accurate only)",
            });
        }
        Ok(res)
    }

    /// The seed's scheme: explicit Euler for the normal and tangential motion together, springs
    /// at the cell midpoints ([`SpringRow::midpoints`], `res.springs ≥ 2`).
    fn dimensionless_p(shear: f64, limit: f64, res: Resolution) -> Level {
        Level::unwatched(simulate_euler(shear, limit, res))
    }
}

/// The seed's explicit Euler scheme in dimensionless units.
fn simulate_euler(shear: f64, limit: f64, res: Resolution) -> f64 {
    let hertz = HertzClosedForm {
        mass: 1.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
    };
    let h = hertz.contact_time() / res.steps as f64;
    let mut row = SpringRow::midpoints(hertz.max_indentation().sqrt(), res.springs, 1.0);
    let (mut d, mut vd, mut u) = (0.0_f64, 1.0_f64, 1.0_f64);
    let (mut f_n, mut f_t) = (0.0_f64, 0.0_f64);
    for _ in 0..10 * res.steps {
        let d1 = d + h * vd;
        let dw = h * u;
        vd -= h * f_n;
        u -= h * f_t * INV_TANGENTIAL_MASS;
        if d1 <= 0.0 {
            break;
        }
        let (sz, sx) = row.step_euler(dw, d1, limit);
        f_n = 2.0 * sz;
        f_t = 2.0 * shear * sx;
        d = d1;
    }
    u
}

/// Limits on the work and memory of one solve; a request beyond them is refused before any
/// simulation starts ([`plan`]) or, for the automatic refinement, before the level that would
/// exceed them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest number of time steps a refinement may use.
    pub max_steps: usize,
    /// Largest work of one run, in spring-steps (`springs × steps`); about 2–6 ns each on one
    /// core, so the default 2^34 ≈ 1.7e10 is about a minute.
    pub max_work: f64,
    /// Largest memory of one run (bytes), as [`memory_bytes`] counts it.
    pub max_memory: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_steps: 1 << 20,
            max_work: (1u64 << 34) as f64,
            max_memory: (1u64 << 31) as f64,
        }
    }
}

impl Limits {
    /// Whether one run at `res` fits (steps, work and memory).
    pub fn admits(&self, res: Resolution, scheme: Scheme) -> bool {
        res.steps <= self.max_steps
            && work(res) <= self.max_work
            && memory_bytes(res, scheme) <= self.max_memory
    }
}

/// Work of one run in spring-steps, `springs × steps`. The continuum row (`springs = 0`) holds
/// about one piece per compression step, grouped in chunks that a step skips unless something
/// in them slips; its work is counted as `steps²/16` spring-steps (measured: 4096 steps take
/// 2–10 ms, like 1024 × 4096 spring-steps).
pub fn work(res: Resolution) -> f64 {
    if res.springs == 0 {
        res.steps as f64 * res.steps as f64 / 16.0
    } else {
        res.springs as f64 * res.steps as f64
    }
}

/// Memory of one run (bytes): the spring row (positions, weights, heights, displacements: 5
/// arrays of `springs + 4` values) and what the scheme stores of the normal motion
/// ([`Integrator::normal_memory`]). The continuum row holds at most about two pieces of 96
/// bytes per step.
pub fn memory_bytes(res: Resolution, scheme: Scheme) -> f64 {
    let row = if res.springs == 0 {
        2.0 * 96.0 * res.steps as f64
    } else {
        5.0 * 8.0 * (res.springs as f64 + 4.0)
    };
    row + with_integrator!(scheme, I => I::normal_memory(res))
}

/// What a refinement to `tol` is predicted to need, before anything is simulated.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Plan {
    /// First level of the refinement ([`base_resolution`]).
    pub base: Resolution,
    /// Finest level a typical point needs (error model of `docs/accuracy.md`).
    pub typical: Resolution,
    /// Finest level the most favourable point needs (30× smaller error constant); a request is
    /// refused only when even this exceeds the [`Limits`].
    pub minimum: Resolution,
}

/// Predicted raw error of the base level of the refinement at `γ` (the difference between
/// the first two levels, measured at α = ∞ and mid partial slip for γ = 0.01–64):
/// [`Integrator::base_error`].
fn base_error(gamma: f64, scheme: Scheme) -> f64 {
    let base = base_resolution(gamma, scheme);
    with_integrator!(scheme, I => I::base_error(gamma, base))
}

/// Predict the finest resolution a refinement to `tol` reaches at `γ` and refuse, before any
/// simulation, a request that cannot fit the limits even in the most favourable case
/// ([`PhysicsError::Infeasible`]).
pub fn plan(gamma: f64, tol: f64, scheme: Scheme, limits: Limits) -> Result<Plan, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let tol = positive("tol", tol)?;
    let base = base_resolution(gamma, scheme);
    let factor = 2f64.powi(scheme.order());
    let levels = |e0: f64| -> u32 {
        let k = ((e0 / tol).ln() / factor.ln()).ceil();
        // At least three levels (two doublings); at most 40 doublings (no overflow below).
        k.clamp(2.0, 40.0) as u32
    };
    let at = |k: u32| Resolution {
        springs: base.springs.saturating_mul(1usize << k.min(40)),
        steps: base.steps.saturating_mul(1usize << k.min(40)),
    };
    let e0 = base_error(gamma, scheme);
    let typical = at(levels(e0));
    let minimum = at(levels(e0 / 30.0));
    if !limits.admits(minimum, scheme) {
        return Err(PhysicsError::Infeasible {
            tol,
            gamma,
            scheme: scheme.name(),
            springs: minimum.springs,
            steps: minimum.steps,
            work: work(minimum),
            memory_mb: memory_bytes(minimum, scheme) / 1e6,
            max_steps: limits.max_steps,
            max_work: limits.max_work,
            max_memory_mb: limits.max_memory / 1e6,
        });
    }
    Ok(Plan {
        base,
        typical,
        minimum,
    })
}

/// Starting resolution of the automatic refinement for a given `γ`: the tangential oscillation
/// frequency grows like `γ`, so the number of steps does too; the spring count does not.
pub fn base_resolution(gamma: f64, scheme: Scheme) -> Resolution {
    // Powers of two only, so that the cache of normal trajectories stays small.
    // Not clamped at large γ (only against overflow): fewer steps than ∝ γ would make the base
    // level useless there, and [`plan`] refuses what does not fit the limits.
    let scale = gamma.clamp(1.0, 1e12).log2().ceil().exp2();
    with_integrator!(scheme, I => I::base_resolution(scale))
}

/// First level of the automatic refinement ([`Integrator::ladder_start`]).
pub(crate) fn ladder_start(gamma: f64, scheme: Scheme) -> Resolution {
    let base = base_resolution(gamma, scheme);
    with_integrator!(scheme, I => I::ladder_start(base))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn universal_normal_motion_is_computed_once_per_process() {
        // Another thread gets the very trajectory this one computed (not its own copy) ...
        let here = dimensionless_normal(96);
        let there = std::thread::spawn(|| dimensionless_normal(96))
            .join()
            .expect("thread");
        assert!(Arc::ptr_eq(&here, &there));
        // ... and it has the bits of a trajectory that measures its own contact time.
        let fresh = UNIVERSAL.trajectory(96);
        assert_eq!(here.contact_time.to_bits(), fresh.contact_time.to_bits());
        for (a, b) in [
            (&here.indentation, &fresh.indentation),
            (&here.rate, &fresh.rate),
            (&here.accel, &fresh.accel),
        ] {
            assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
            assert_eq!(a.len(), 97);
        }
    }

    #[test]
    fn the_tabulated_normal_motion_has_the_bits_of_the_computed_one() {
        // Every grid the build tabulated (16 … 8192 steps) is what this process would integrate,
        // measuring its own contact time, to the bit; other grids are computed.
        assert!(tabulated_normal(8).is_none() && tabulated_normal(16384).is_none());
        assert!(tabulated_normal(96).is_none());
        for k in 4..=13 {
            let steps = 1usize << k;
            let table = tabulated_normal(steps).expect("tabulated");
            let fresh = UNIVERSAL.trajectory(steps);
            for (a, b) in [
                (&table.indentation, &fresh.indentation),
                (&table.rate, &fresh.rate),
                (&table.accel, &fresh.accel),
            ] {
                assert_eq!(a.len(), steps + 1);
                assert!(
                    a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()),
                    "{steps}"
                );
            }
            for (x, y) in [
                (table.accel_factor, fresh.accel_factor),
                (table.dt, fresh.dt),
                (table.contact_time, fresh.contact_time),
                (table.max_indentation, fresh.max_indentation),
                (table.peak_force, fresh.peak_force),
                (table.delta_v1, fresh.delta_v1),
                (table.delta_v2, fresh.delta_v2),
            ] {
                assert_eq!(x.to_bits(), y.to_bits(), "{steps}");
            }
        }
    }
}
