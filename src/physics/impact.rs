//! One impact in dimensionless form: `(γ, α) → P`.
//!
//! Units as in `physics.md`: `m* = R* = E* = v_z0 = 1`, `G* = (2/7)γ²`, tangential mass
//! `m_t = 2/7`, `μ = α`, `u0 = 1` (for `α = ∞` the Coulomb limit is removed). The Hertz contact
//! time is then ≈ 2.868.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use serde::Serialize;

use super::error::{positive, PhysicsError};
use super::hertz::{HertzClosedForm, NormalBodies, NormalTrajectory};
use super::regimes;
use super::springs::{SpringRow, StepMotion};

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

impl Scheme {
    /// Name as used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Accurate => "accurate",
            Scheme::Euler => "euler",
        }
    }

    /// Order of convergence in the resolution `h ∝ 1/steps ∝ 1/springs`.
    pub fn order(self) -> i32 {
        match self {
            Scheme::Accurate => 2,
            Scheme::Euler => 1,
        }
    }
}

/// Spatial and temporal resolution of one simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Resolution {
    /// Springs on the half-row `[0, a_max]`.
    pub springs: usize,
    /// Time steps per contact time.
    pub steps: usize,
}

impl Resolution {
    /// Both counts multiplied by `2^k`.
    pub fn doubled(self, k: u32) -> Self {
        Self {
            springs: self.springs << k,
            steps: self.steps << k,
        }
    }

    /// Validate the counts (springs ≥ 2, steps ≥ 8).
    pub fn validate(self) -> Result<Self, PhysicsError> {
        if self.springs < 2 {
            return Err(PhysicsError::InvalidParameter {
                name: "springs",
                value: self.springs as f64,
                allowed: "an integer >= 2",
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

/// The tangential degrees of freedom driven by the friction force `F_f` through the springs.
///
/// Implemented once for the dimensionless contact point and once for two bodies in physical
/// units; the time stepping ([`run_contact`]) is shared.
pub trait TangentialBodies {
    /// Relative tangential velocity of the contact points `u` (m/s).
    fn slip_velocity(&self) -> f64;
    /// `du/dt` produced by a friction force `f` (N), from each body's equations of motion.
    fn slip_acceleration(&self, f: f64) -> f64;
    /// Advance every velocity by `h` under the constant friction force `f`.
    fn kick(&mut self, h: f64, f: f64);
}

/// The contact-point coordinate of one solid sphere in dimensionless units (`m_t = 2/7`).
struct ContactPoint {
    u: f64,
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

/// State of the accurate scheme between steps.
struct Stepper<'a> {
    row: SpringRow,
    normal: &'a NormalTrajectory,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
    /// Friction force at the current time (N).
    force: f64,
    /// Mean spring displacement at the current time (m).
    mean: f64,
}

impl Stepper<'_> {
    fn motion<B: TangentialBodies>(&self, bodies: &B, h: f64, d0: f64, rate0: f64) -> StepMotion {
        StepMotion {
            h,
            d0,
            rate0,
            accel0: -self.normal.accel_factor * d0 * d0.max(0.0).sqrt(),
            slip_velocity: bodies.slip_velocity(),
            slip_accel: bodies.slip_acceleration(self.force),
        }
    }

    /// One velocity-Verlet step of length `h` from indentation `d0` (rate `rate0`) to `d1`.
    fn step<B: TangentialBodies>(&mut self, bodies: &mut B, h: f64, d0: f64, rate0: f64, d1: f64) {
        let motion = self.motion(bodies, h, d0, rate0);
        let step = self.row.step_accurate(&motion, d1, self.limit);
        // Impulse by product integration: F = 2 G* a(t) · mean(t), with ∫ a dt exact for d
        // linear over the step. Near separation a ∝ √(t_c − t), where the plain trapezoid rule
        // would drop to order 1.5 (no slip keeps a finite mean displacement to the end).
        let mean_radius = mean_sqrt(d0, d1) * self.radius.sqrt();
        bodies.kick(
            h,
            self.shear_modulus * mean_radius * (self.mean + step.mean),
        );
        self.force = 2.0 * self.shear_modulus * step.integral;
        self.mean = step.mean;
    }

    /// Grid step `n`, split at the release instant of the springs at a Coulomb limit when it
    /// falls inside: F(t) has a kink there and the trapezoid impulse across a kink is only first
    /// order locally.
    fn grid_step<B: TangentialBodies>(&mut self, bodies: &mut B, n: usize) {
        let nt = self.normal;
        let (h, d) = (nt.dt, &nt.indentation);
        let (at_plus, at_minus) = self.row.at_limit();
        let (tp, tm) = self
            .motion(bodies, h, d[n], nt.rate[n])
            .release_times(self.limit);
        let split = [tp.filter(|_| at_plus), tm.filter(|_| at_minus)]
            .into_iter()
            .flatten()
            .filter(|&t| t > 1e-3 * h && t < (1.0 - 1e-3) * h)
            .reduce(f64::min);
        match split {
            Some(t) => {
                let (dm, rm) = nt.within_step(n, t);
                self.step(bodies, t, d[n], nt.rate[n], dm);
                self.step(bodies, h - t, dm, rm, d[n + 1]);
            }
            None => self.step(bodies, h, d[n], nt.rate[n], d[n + 1]),
        }
    }
}

/// Run the tangential contact of the accurate scheme on a given normal motion: velocity Verlet
/// for the bodies, [`SpringRow::step_accurate`] for the springs.
///
/// `shear_modulus` is `G*` (Pa), `limit` is `c = μ E*/G*` (`∞` for no slip), `radius` is `R*` (m).
pub fn run_contact<B: TangentialBodies>(
    bodies: &mut B,
    normal: &NormalTrajectory,
    springs: usize,
    radius: f64,
    shear_modulus: f64,
    limit: f64,
) {
    let a_max = (radius * normal.max_indentation).sqrt();
    let mut stepper = Stepper {
        row: SpringRow::nodes(a_max, springs, radius),
        normal,
        radius,
        shear_modulus,
        limit,
        force: 0.0,
        mean: 0.0,
    };
    for n in 0..normal.indentation.len() - 1 {
        stepper.grid_step(bodies, n);
    }
}

/// Mean of `√d(t)` over a step on which `d` goes linearly from `d0` to `d1` (both ≥ 0).
fn mean_sqrt(d0: f64, d1: f64) -> f64 {
    let (r0, r1) = (d0.sqrt(), d1.sqrt());
    // (2/3)(d1^{3/2} − d0^{3/2})/(d1 − d0), written without the cancelling difference.
    let s = r0 + r1;
    if s > 0.0 {
        2.0 / 3.0 * (r0 * r0 + r0 * r1 + r1 * r1) / s
    } else {
        0.0
    }
}

thread_local! {
    static NORMAL_CACHE: RefCell<HashMap<usize, Rc<NormalTrajectory>>> =
        RefCell::new(HashMap::new());
}

/// The universal dimensionless normal motion (`m* = R* = E* = v_z0 = 1`) on `steps` steps,
/// cached per thread.
pub fn dimensionless_normal(steps: usize) -> Rc<NormalTrajectory> {
    NORMAL_CACHE.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some(t) = cache.get(&steps) {
            return Rc::clone(t);
        }
        if cache.len() > 64 {
            cache.clear();
        }
        let t = Rc::new(
            NormalBodies {
                inv_mass1: 1.0,
                inv_mass2: 0.0,
                stiffness: 4.0 / 3.0,
                approach_speed: 1.0,
            }
            .trajectory(steps),
        );
        cache.insert(steps, Rc::clone(&t));
        t
    })
}

/// Simulate one impact at a fixed resolution and return `P` (no closed-form shortcut).
pub fn simulate(
    gamma: f64,
    alpha: f64,
    res: Resolution,
    scheme: Scheme,
) -> Result<f64, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let alpha = check_alpha(alpha)?;
    let res = res.validate()?;
    let shear = 2.0 / 7.0 * gamma * gamma;
    let limit = alpha / shear;
    Ok(match scheme {
        Scheme::Accurate => {
            let normal = dimensionless_normal(res.steps);
            let mut cp = ContactPoint { u: 1.0 };
            run_contact(&mut cp, &normal, res.springs, 1.0, shear, limit);
            cp.u
        }
        Scheme::Euler => simulate_euler(shear, limit, res),
    })
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

/// How the accuracy of a result is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Accuracy {
    /// Refine (doubling springs and steps together) until the error estimate is ≤ the tolerance.
    Tolerance(f64),
    /// A fixed resolution; the error estimate comes from a second run at half resolution.
    Fixed(Resolution),
}

/// How a result was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Exact closed form (full-slip line, γ = 1 plateau, α = 0); nothing simulated.
    ClosedForm,
    /// Simulated at the reported resolution.
    Simulated,
}

/// Limits of the automatic refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest number of time steps a refinement may use.
    pub max_steps: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self { max_steps: 1 << 20 }
    }
}

/// A value of `P` with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Solution {
    /// Tangential restitution of the contact point `P = u_after/u_before`.
    pub p: f64,
    /// Estimated absolute error of `p` (0 for closed forms).
    pub error_estimate: f64,
    /// Resolution of the finest run (zero for closed forms).
    pub resolution: Resolution,
    /// Scheme used.
    pub scheme: Scheme,
    /// Closed form or simulation.
    pub method: Method,
}

/// Starting resolution of the automatic refinement for a given `γ`: the tangential oscillation
/// frequency grows like `γ`, so the number of steps does too; the spring count does not.
pub fn base_resolution(gamma: f64, scheme: Scheme) -> Resolution {
    // Powers of two only, so that the per-thread cache of normal trajectories stays small.
    let scale = gamma.clamp(1.0, 64.0).log2().ceil().exp2();
    match scheme {
        // The spatial error (discretised traction, ≈ 2/N² for N springs) does not depend on γ;
        // the time error grows with γ (≈ 1.4/S² at γ = 1.9, ≈ 8/S² at γ = 3.2 for S steps,
        // `examples/errsplit.rs`). One spring per step (at least 64) keeps the spatial part
        // below the time part at every γ ≥ 1 and halves the cost of the former two per step.
        // 64 springs whatever the γ would balance both better still, but then the two errors
        // cancel by chance at some points (γ = 2.8) and the Richardson estimate under-estimates
        // by up to 5×; with one per step it bounds the true error at all 32 points of
        // `examples/estim.rs`.
        Scheme::Accurate => {
            let steps = (32.0 * scale).ceil() as usize;
            Resolution {
                springs: steps.max(64),
                steps,
            }
        }
        Scheme::Euler => {
            let steps = (256.0 * scale).ceil() as usize;
            Resolution {
                springs: steps / 4,
                steps,
            }
        }
    }
}

/// First level of the automatic refinement: the base resolution, and for the accurate scheme
/// one level below it, so that the acceptance guard ([`previous_estimate_agrees`]) has its
/// coarser estimate at the same finest resolution as the three-level estimate alone (the extra
/// level costs about 1/8 of the finest one).
fn ladder_start(gamma: f64, scheme: Scheme) -> Resolution {
    let base = base_resolution(gamma, scheme);
    match scheme {
        Scheme::Accurate => Resolution {
            springs: base.springs / 2,
            steps: base.steps / 2,
        },
        Scheme::Euler => base,
    }
}

/// Estimate the error of a sequence of results at resolutions doubling each time.
///
/// For clean convergence of order `p` the error of the finest value is
/// `|P_k − P_{k−1}| / (2^p − 1)`; at partial slip the time error is O(h²) but irregular (kinks
/// of F(t) inside steps), and that formula was measured to under-estimate by up to 6×. So the
/// estimate keeps a margin of `2^p − 1` (it is the last difference itself) and never falls below
/// the previous difference scaled by one order, `|P_{k−1} − P_{k−2}| / 2^p`.
fn estimate(values: &[f64], order: i32) -> f64 {
    let r = 2f64.powi(order);
    let n = values.len();
    let last = (values[n - 1] - values[n - 2]).abs();
    if n >= 3 {
        last.max((values[n - 2] - values[n - 3]).abs() / r)
    } else {
        last
    }
}

/// Richardson extrapolation of the last two values for order `p` and its error estimate:
/// `R_k = P_k + (P_k − P_{k−1})/(2^p − 1)`, estimated by
/// `max(|R_k − R_{k−1}|, 0.1 |P_k − P_{k−1}|)`. Measured on 32 points spanning every regime
/// (γ 0.3–3.5, α from just above the linear limit to ∞, 128–8192 steps): never below the true
/// error where that error exceeds the 2e-8 accuracy of the reference (`examples/estim.rs`).
fn extrapolate(values: &[f64], order: i32) -> (f64, f64) {
    let r = 2f64.powi(order) - 1.0;
    let n = values.len();
    let rich = |k: usize| values[k] + (values[k] - values[k - 1]) / r;
    let last = rich(n - 1);
    let est = (last - rich(n - 2))
        .abs()
        .max(0.1 * (values[n - 1] - values[n - 2]).abs());
    (last, est)
}

/// The acceptance guard of the Richardson path: the estimate one level coarser must already be
/// within `2^p · tol`, as it is when the sequence has converged at order `p` for two levels.
///
/// Without it a pre-asymptotic plateau passes for convergence: at γ = 1.80378, α = 5.148 (stick,
/// a short slip episode that 256 steps do not resolve) the values at 64, 128 and 256 steps lie
/// within 1e-5 of each other but 1.5–2.4e-5 below the converged value, and the three-level
/// estimate (2.0e-6) accepted them at `tol = 1e-5` with a true error of 2.5e-5. The estimate one
/// level coarser is 7.8e-5 there: above `4 tol`, so the guard refines on (to 1024 steps, error
/// 6e-8). A looser factor `2^(p+1)` would have let this case through. The guard costs CPU time
/// where a sequence converges fast from a poor start: `configs/quick.toml` needs 13.8 s with it
/// against 10.4 s without (33 %, measured under load). With three values only (no coarser
/// estimate) the result is never accepted.
fn previous_estimate_agrees(values: &[f64], order: i32, tol: f64) -> bool {
    let n = values.len();
    n >= 4 && extrapolate(&values[..n - 1], order).1 <= 2f64.powi(order) * tol
}

/// Refine a computation `run(level)` (resolution doubling each level from `base`) until the
/// error estimate of the result is ≤ `tol`. With `richardson`, the result is the extrapolated
/// value ([`extrapolate`]); otherwise the finest value with the conservative [`estimate`].
/// Returns `(value, estimate, resolution)`.
pub fn refine(
    base: Resolution,
    order: i32,
    tol: f64,
    richardson: bool,
    limits: Limits,
    mut run: impl FnMut(Resolution) -> Result<f64, PhysicsError>,
) -> Result<(f64, f64, Resolution), PhysicsError> {
    let tol = positive("tol", tol)?;
    let mut values = Vec::new();
    let mut best = (f64::INFINITY, base);
    for k in 0.. {
        let res = base.doubled(k);
        if res.steps > limits.max_steps {
            return Err(PhysicsError::ToleranceUnreachable {
                tol,
                achieved: best.0,
                springs: best.1.springs,
                steps: best.1.steps,
                max_steps: limits.max_steps,
            });
        }
        values.push(run(res)?);
        if values.len() >= 3 {
            let (value, est) = if richardson {
                extrapolate(&values, order)
            } else {
                (values[values.len() - 1], estimate(&values, order))
            };
            best = (est, res);
            if est <= tol && (!richardson || previous_estimate_agrees(&values, order, tol)) {
                return Ok((value, est, res));
            }
        }
    }
    unreachable!("the refinement loop only exits by returning")
}

/// `P(γ, α)` to the requested accuracy. Uses the closed form where it is exact unless
/// `force_simulation` is set.
pub fn solve(
    gamma: f64,
    alpha: f64,
    accuracy: Accuracy,
    scheme: Scheme,
    force_simulation: bool,
) -> Result<Solution, PhysicsError> {
    solve_with_limits(
        gamma,
        alpha,
        accuracy,
        scheme,
        force_simulation,
        Limits::default(),
    )
}

/// [`solve`] with explicit refinement limits.
pub fn solve_with_limits(
    gamma: f64,
    alpha: f64,
    accuracy: Accuracy,
    scheme: Scheme,
    force_simulation: bool,
    limits: Limits,
) -> Result<Solution, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let alpha = check_alpha(alpha)?;
    match accuracy {
        Accuracy::Tolerance(tol) => {
            positive("tol", tol)?;
        }
        Accuracy::Fixed(res) => {
            res.validate()?;
        }
    }
    if !force_simulation {
        if let Some(p) = regimes::closed_form(gamma, alpha) {
            return Ok(Solution {
                p,
                error_estimate: 0.0,
                resolution: Resolution {
                    springs: 0,
                    steps: 0,
                },
                scheme,
                method: Method::ClosedForm,
            });
        }
    }
    let (p, error_estimate, resolution) = match accuracy {
        Accuracy::Tolerance(tol) => refine(
            ladder_start(gamma, scheme),
            scheme.order(),
            tol,
            scheme == Scheme::Accurate,
            limits,
            |res| simulate(gamma, alpha, res, scheme),
        )?,
        Accuracy::Fixed(res) => {
            let res = res.validate()?;
            let fine = simulate(gamma, alpha, res, scheme)?;
            let half = Resolution {
                springs: (res.springs / 2).max(2),
                steps: (res.steps / 2).max(8),
            };
            let coarse = simulate(gamma, alpha, half, scheme)?;
            (fine, estimate(&[coarse, fine], scheme.order()), res)
        }
    };
    Ok(Solution {
        p,
        error_estimate,
        resolution,
        scheme,
        method: Method::Simulated,
    })
}
