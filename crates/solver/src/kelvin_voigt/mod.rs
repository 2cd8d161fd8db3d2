//! The Kelvin–Voigt dissipation law (`physics.md`, "Dissipative impacts"): every MDR spring a
//! Kelvin–Voigt element with one relaxation time `τ` in the normal and tangential direction,
//! non-adhesive unloading. Within the law `P` depends on `(γ, α, e_n)` only.

pub mod fit;
pub mod normal;
pub mod row;

pub use fit::{contact_fit, tau_fit, TAU_HAT_MAX};

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use oblique_physics::regimes;
use serde::Serialize;

use crate::error::PhysicsError;
use crate::impact::{
    check_alpha, check_gamma, run_contact_with, ContactPoint, Resolution, Scheme, TangentialBodies,
};
use crate::law::{
    accurate_only, continuum_only, shear_and_limit, BodiesNormal, ContactLaw, Floor, NormalSummary,
    PARAMETER_KEYS,
};
use crate::model::{close_step_elastic, NormalModel, StepEnd, TangentialModel};
use crate::springs::{StepMotion, StepResult};
use crate::zones::Level;
use normal::{FineMotion, ViscoelasticBodies, ViscoelasticTrajectory};
use row::ViscoelasticRow;

/// The floor of the Richardson error estimate, as a share of the last raw difference between
/// levels: the elastic law's ([`crate::elastic::RAW_FLOOR`], 0.1) where the last two ratios of
/// differences are regular, the law converging at order 2 as the elastic one does (ratios
/// 3.78–4.25 from 256 to 32 768 steps at γ = 1.620185, α = 0.335640, e_n = 0.5, 3.96–4.00 at
/// γ = 2.2, α = 0.98, e_n = 0.3; `crates/solver/tests/kelvin_voigt.rs`), and 0.5 elsewhere.
/// Near separation the constant of the second-order term can change irregularly between
/// levels (γ = 3.2763, α = 2.5414, e_n = 0.5779: ratios 1.95, 6.63, 1.63, 3.98, 7.77), where
/// 0.1 put an estimate at 0.78 of its error (tol 1e-8); and before the asymptotic range
/// (γ = 3.5, α = 1.001 α_c2, e_n = 0.3: ratios −8.0, 51, −0.9 from 256 to 4096 steps) the
/// Richardson value of 256 and 512 steps erred by 3.5e-6, 0.46 of the last difference
/// (`crates/solver/tests/extremes.rs`).
pub const RAW_FLOOR: Floor = Floor {
    regular: crate::elastic::RAW_FLOOR,
    steady: crate::elastic::STEADY_FLOOR,
    tight: crate::elastic::TIGHT_FLOOR,
    irregular: 0.5,
    scatter: crate::law::ROW_SCATTER,
};

/// Smallest normal restitution the solver takes ([`crate::law`] owns the range).
pub use crate::law::MIN_RESTITUTION;

/// `C1 = √π Γ(3/5) / (2^{1/5} 5^{2/5} Γ(21/10))` of `e_n = 1 − C1 b + C2′ b² + …`
/// (Schwager & Pöschel 2008), to the double nearest the closed form.
pub const C1: f64 = 1.153_448_858_095_288_4;

/// `C2′` of `e_n = 1 − C1 b + C2′ b² − C3 b³ + …` for this law's non-adhesive unloading:
/// least squares of the integrated restitution over `b ∈ [2e-4, 4e-3]` (residuals ≤ 1.3e-12;
/// `physics.md` gives 1.0887, measured with an independent prototype).
pub const C2_PRIME: f64 = 1.088_729;

/// `C3` of the same series and fit.
pub const C3: f64 = 0.9645;

/// Below this damping number `b` the normal restitution is the series
/// `1 − C1 b + C2′ b² − C3 b³` (its truncation and the uncertainty of `C2′` stay below 1e-15
/// there), from twice it the integrated normal motion; in between a smooth blend of the two.
/// The integration alone is accurate to about 2e-15 absolute, which is more than `1 − e_n`
/// itself for `b ≲ 2e-15` (an earlier, coarser one gave `e_n = 1 + 7.3e-12` as `τ̂ → 0`).
pub const SERIES_DAMPING: f64 = 1e-5;

/// The normal restitution `e_n` of the dimensionless impact with relaxation time `τ̂ ≥ 0`
/// ([`unit_bodies`]): `1` at `τ̂ = 0`, the small-damping series for
/// `b ≤` [`SERIES_DAMPING`], the integrated normal motion for `b ≥ 2·SERIES_DAMPING`, and a
/// smoothstep blend between them. Continuous, decreasing and below 1 for every `τ̂ > 0` whose
/// `b` is representable; NaN for NaN. Every path from a relaxation time to `e_n` (the
/// root searches [`tau_for_restitution_search`] and [`tau_for_restitution_from_series`]
/// behind the fitted [`tau_for_restitution`], physical bodies) uses it.
pub fn restitution(tau: f64) -> f64 {
    if tau.is_nan() {
        return f64::NAN;
    }
    if tau <= 0.0 {
        return 1.0;
    }
    let b = damping_number(tau);
    let series = 1.0 - b * (C1 - b * (C2_PRIME - C3 * b));
    if b <= SERIES_DAMPING {
        return series;
    }
    let integrated = unit_bodies(tau).restitution();
    if b >= 2.0 * SERIES_DAMPING {
        return integrated;
    }
    let w = b / SERIES_DAMPING - 1.0;
    let w = w * w * (3.0 - 2.0 * w);
    (1.0 - w) * series + w * integrated
}

/// The dimensionless bodies (`m* = R* = E* = v_z0 = 1`, `k = 4/3`) with relaxation time `τ̂`.
pub fn unit_bodies(tau: f64) -> ViscoelasticBodies {
    ViscoelasticBodies {
        inv_mass1: 1.0,
        inv_mass2: 0.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
        tau,
    }
}

/// The damping number `b = (3/2) τ ρ^{2/5} v_z0^{1/5}`, `ρ = k/m*`, of the dimensionless
/// relaxation time `τ̂` (`ρ = 4/3`, `v_z0 = 1`).
pub fn damping_number(tau: f64) -> f64 {
    1.5 * tau * (4.0f64 / 3.0).powf(0.4)
}

/// The dimensionless relaxation time `τ̂` (time unit `(m*/k)^{2/5} v_z0^{-1/5} (4/3)^{2/5}`,
/// the unit of [`unit_bodies`]) of a relaxation time `τ` (s) for bodies of reduced mass `m*`
/// (kg), Hertz stiffness `k` (N/m^{3/2}) meeting at `v_z0` (m/s).
pub fn dimensionless_tau(tau: f64, mass: f64, stiffness: f64, approach_speed: f64) -> f64 {
    tau * (stiffness / mass).powf(0.4) * approach_speed.powf(0.2) * 0.75f64.powf(0.4)
}

/// Check a normal restitution: finite, in `[0.3, 1]` ([`crate::law`] owns the range).
pub use crate::law::check_restitution;

thread_local! {
    static TRAJECTORY_CACHE: RefCell<HashMap<(usize, u64), Rc<ViscoelasticTrajectory>>> =
        RefCell::new(HashMap::new());
    static FINE_CACHE: RefCell<HashMap<u64, Rc<FineMotion>>> = RefCell::new(HashMap::new());
}

/// The dimensionless relaxation time `τ̂` whose impact has normal restitution `e_n`
/// (`e_n ∈ [0.3, 1]`; `τ̂ = 0` at 1), nothing integrated: where [`restitution`] is the
/// small-damping series (`b ≤` [`SERIES_DAMPING`]) the series inverted to the rounding of
/// `e_n`, from `b = 2·SERIES_DAMPING` on the fit [`tau_fit`], and a smoothstep blend of the two
/// in between (they agree there to 2e-10 of `τ̂`, 2e-15 of `e_n`). The root search on
/// [`restitution`] ([`tau_for_restitution_search`]) is its reference.
pub fn tau_for_restitution(e_n: f64) -> Result<f64, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if e_n == 1.0 {
        return Ok(0.0);
    }
    let x = 1.0 - e_n;
    let (x1, x2) = (
        series_deficit(SERIES_DAMPING),
        series_deficit(2.0 * SERIES_DAMPING),
    );
    if x <= x1 {
        return Ok(series_tau(x));
    }
    let fit = tau_fit(e_n);
    if x >= x2 {
        return Ok(fit);
    }
    let w = (x - x1) / (x2 - x1);
    let w = w * w * (3.0 - 2.0 * w);
    Ok((1.0 - w) * series_tau(x) + w * fit)
}

/// `1 − e_n = C1 b − C2′ b² + C3 b³` of the small-damping series at damping number `b`.
fn series_deficit(b: f64) -> f64 {
    b * (C1 - b * (C2_PRIME - C3 * b))
}

/// The `τ̂` whose small-damping series gives `1 − e_n = x` (`b ≤ 2·SERIES_DAMPING`): Newton on
/// the cubic from `b = x/C1`, whose correction terms are below `3e-5` of `b` there.
fn series_tau(x: f64) -> f64 {
    let mut b = x / C1;
    for _ in 0..4 {
        let slope = C1 - b * (2.0 * C2_PRIME - 3.0 * C3 * b);
        b -= (series_deficit(b) - x) / slope;
    }
    b / damping_number(1.0)
}

/// The root of `restitution(τ̂) = e_n` by a bracketed secant (Illinois) search on
/// [`restitution`], to the rounding of `e_n`: the reference of [`tau_for_restitution`].
pub fn tau_for_restitution_search(e_n: f64) -> Result<f64, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if e_n == 1.0 {
        return Ok(0.0);
    }
    tau_search(e_n, &|tau: f64| restitution(tau) - e_n)
}

/// The root of `f` (`restitution(τ) − e_n`, decreasing): bracketed around the fitted
/// [`tau_fit`] (±1e-12, widened ×100 up to ±1e-2 where that does not bracket); without a
/// bracket there, the search from the series `e_n ≈ 1 − C1 b` widened by doubling.
fn tau_search(e_n: f64, f: &dyn Fn(f64) -> f64) -> Result<f64, PhysicsError> {
    let guess = tau_fit(e_n);
    let mut width = 1e-12;
    while width <= 1e-2 {
        let (lo, hi) = (guess * (1.0 - width), guess * (1.0 + width));
        let (f_lo, f_hi) = (f(lo), f(hi));
        if f_lo > 0.0 && f_hi < 0.0 {
            return Ok(illinois(f, (lo, f_lo), (hi, f_hi)));
        }
        width *= 100.0;
    }
    tau_search_from_series(e_n, f)
}

/// The search without a guess: from the series `e_n ≈ 1 − C1 b` widened until it brackets.
fn tau_search_from_series(e_n: f64, f: &dyn Fn(f64) -> f64) -> Result<f64, PhysicsError> {
    // First guess from the series e_n ≈ 1 − C1 b (too small a b: e decreases with b faster
    // than linearly only beyond its curvature), then widened until it brackets.
    let mut hi = (1.0 - e_n) / C1 / damping_number(1.0);
    let mut f_hi = f(hi);
    let (mut lo, mut f_lo) = (0.0, 1.0 - e_n);
    while f_hi > 0.0 {
        (lo, f_lo) = (hi, f_hi);
        hi *= 2.0;
        f_hi = f(hi);
        if hi > 1e3 {
            return Err(PhysicsError::InvalidParameter {
                name: "e_n",
                value: e_n,
                allowed: "a number in [0.3, 1] (1: elastic)",
            });
        }
    }
    Ok(illinois(f, (lo, f_lo), (hi, f_hi)))
}

/// The Illinois (bracketed secant) search for the root of a decreasing `f` between `lo`
/// (`f > 0`) and `hi` (`f < 0`), until `|f| ≤ 4 ε` or the bracket is `4 ε hi` wide.
fn illinois(
    f: &dyn Fn(f64) -> f64,
    (mut lo, mut f_lo): (f64, f64),
    (mut hi, mut f_hi): (f64, f64),
) -> f64 {
    let mut side = 0;
    let mut x = hi;
    for _ in 0..200 {
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let fx = f(x);
        // Within four ulps of e_n ≤ 1 the restitution is the asked one to its rounding.
        if fx.abs() <= 4.0 * f64::EPSILON || (hi - lo) <= 4.0 * f64::EPSILON * hi {
            break;
        }
        if fx > 0.0 {
            (lo, f_lo) = (x, fx);
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        } else {
            (hi, f_hi) = (x, fx);
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        }
    }
    x
}

/// The root search from the series alone, without the fit: the data of the fit
/// (`fit::TAU_FIT`) and an independent check of it.
pub fn tau_for_restitution_from_series(e_n: f64) -> Result<f64, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if e_n == 1.0 {
        return Ok(0.0);
    }
    tau_search_from_series(e_n, &|tau: f64| restitution(tau) - e_n)
}

/// The dimensionless Kelvin–Voigt normal motion with relaxation time `τ̂` on `steps` steps,
/// cached per thread.
pub fn dimensionless_normal(steps: usize, tau: f64) -> Rc<ViscoelasticTrajectory> {
    TRAJECTORY_CACHE.with(|cache| {
        let mut cache = cache.borrow_mut();
        let key = (steps, tau.to_bits());
        if let Some(t) = cache.get(&key) {
            return Rc::clone(t);
        }
        if cache.len() > 64 {
            cache.clear();
        }
        let t = if normal::FINE_STEPS.is_multiple_of(steps) {
            Rc::new(fine_normal(tau).sample(steps))
        } else {
            Rc::new(unit_bodies(tau).trajectory(steps))
        };
        cache.insert(key, Rc::clone(&t));
        t
    })
}

/// The fine dimensionless normal motion with relaxation time `τ̂`, cached per thread.
fn fine_normal(tau: f64) -> Rc<FineMotion> {
    FINE_CACHE.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some(t) = cache.get(&tau.to_bits()) {
            return Rc::clone(t);
        }
        if cache.len() > 16 {
            cache.clear();
        }
        let t = Rc::new(unit_bodies(tau).fine());
        cache.insert(tau.to_bits(), Rc::clone(&t));
        t
    })
}

/// `P` of the dimensionless Kelvin–Voigt impact (`m* = R* = E* = v_z0 = 1`, `u0 = 1`,
/// `m_t = 2/7`) with relaxation time `τ̂ > 0`, `G* = shear`, Coulomb limit factor `limit`
/// (`∞`: no slip), at resolution `res` (continuum row: `res.springs` is ignored).
pub fn dimensionless_p(shear: f64, limit: f64, tau: f64, res: Resolution) -> f64 {
    dimensionless_level(shear, limit, tau, res).p
}

/// [`dimensionless_p`] with how finely the run resolved its zones ([`Level`]).
pub fn dimensionless_level(shear: f64, limit: f64, tau: f64, res: Resolution) -> Level {
    let normal = dimensionless_normal(res.steps, tau);
    let mut cp = ContactPoint { u: 1.0 };
    let row = ViscoelasticRow::new(1.0, tau);
    let shortest_zone = run_contact_with(&mut cp, &*normal, row, 1.0, shear, limit);
    Level {
        p: cp.u,
        shortest_zone,
    }
}

impl NormalModel for ViscoelasticTrajectory {
    crate::model::grid_accessors!();
    #[inline(always)]
    fn acceleration(&self, d: f64, rate: f64) -> f64 {
        let law = &self.law;
        -law.force(d, rate) * (law.inv_mass1 + law.inv_mass2)
    }
    #[inline(always)]
    fn within_step(&self, n: usize, t: f64) -> (f64, f64) {
        ViscoelasticTrajectory::within_step(self, n, t)
    }
    #[inline(always)]
    fn reach(&self, (d, rate): (f64, f64)) -> f64 {
        if rate < 0.0 {
            self.load(d, rate).max(0.0)
        } else {
            d
        }
    }
    #[inline(always)]
    fn limit_level(&self, (d, rate): (f64, f64)) -> f64 {
        self.load(d, rate)
    }
}

impl TangentialModel for ViscoelasticRow {
    const LOCATES_GROSS_SLIP: bool = true;
    const END_STATE: bool = true;
    #[inline(always)]
    fn at_limit(&self) -> (bool, bool) {
        ViscoelasticRow::at_limit(self)
    }
    #[inline(always)]
    fn stuck(&self) -> bool {
        self.stuck_length() > 0.0
    }
    #[inline(always)]
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        self.step(m, d1, c)
    }
    // `release_time`: the default, the elastic row's. The springs that entered contact slipping
    // and kept slipping share one state, `δ = −s c τ ḋ` (`ViscoelasticRow::enter`), and stick
    // again all at once where `s (δ + τ ẇ) = τ (s ẇ − c ḋ)` falls to 0: where `ẇ = ±c ḋ`, the
    // elastic row's instant. The friction force has a kink there; splitting the step at it
    // makes the differences between levels regular (γ = 2.2, α = 0.98, e_n = 0.3: ratios
    // 4.26, 4.68, 5.43, 2.31, 4.29, 4.69 from 256 to 32 768 steps unsplit, 3.96–4.00 split).
    // Other slipping springs stick one by one; a split where none of the shared state is left
    // only costs a step.
    /// While in contact: the viscous part of the end force, `τ ẇ₁` over the stuck length `ℓ_s`,
    /// was taken at the predicted `ẇ₁ = ẇ₀ + h ẅ₀`; solve the trapezoid rule for `ẇ₁` instead
    /// (linear): `f = A (M + τ σ (ẇ₁ − ŵ))`, `ẇ₁ = ẇ₀ + h a_b f`, `σ = ℓ_s/a₁`. The row's
    /// integral then grows by `τ ℓ_s Δẇ` and its mean by `τ σ Δẇ`. The elastic rule in the step
    /// where the contact vanishes.
    #[inline(always)]
    fn close_step<B: TangentialBodies>(&self, bodies: &mut B, end: &StepEnd) -> (f64, f64) {
        if end.reach1 <= 0.0 {
            return close_step_elastic(bodies, end);
        }
        let (motion, h) = (end.motion, end.motion.h);
        let (tau, stuck) = (self.tau(), self.stuck_length());
        let a1 = (end.radius * end.reach1).sqrt();
        let sigma = stuck / a1;
        let predicted = motion.slip_velocity + h * motion.slip_accel;
        let a = end.shear_modulus * end.mean_radius;
        let response = bodies.slip_acceleration(1.0);
        let f = a * (end.mean0 + end.end_mean + tau * sigma * (motion.slip_velocity - predicted))
            / (1.0 - a * tau * sigma * h * response);
        bodies.kick(h, f);
        let delta = bodies.slip_velocity() - predicted;
        (
            2.0 * end.shear_modulus * (end.step.integral + tau * stuck * delta),
            end.step.mean + tau * sigma * delta,
        )
    }
    /// At first touch every spring in contact carries `v = τ ẇ₀` within the limit `c τ ḋ₀`
    /// (`D = τ ḋ₀` at `d = 0`): the viscous force does not start from zero.
    fn touch_mean(&self, slip_velocity: f64, rate0: f64, c: f64) -> f64 {
        let v = self.tau() * slip_velocity;
        let lim = c * self.tau() * rate0;
        if lim.is_nan() {
            v
        } else {
            v.clamp(-lim, lim)
        }
    }
}

/// The Kelvin–Voigt law ([`ContactLaw`]): `e_n ∈ [0.3, 1]`, the relaxation time `τ̂` that gives
/// it, the accurate scheme on the continuum row only.
#[derive(Debug, Clone, Copy, Default)]
pub struct KelvinVoigt;

/// The Kelvin–Voigt law's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Parameters {
    /// Dimensionless relaxation time `τ̂` that gives the impact's `e_n` (0 at `e_n = 1`; time
    /// unit `(m*/k)^{2/5} v_z0^{-1/5} (4/3)^{2/5}`, `k = (4/3) E* √R*`).
    pub tau: f64,
}

/// `relaxation time tau = τ̂ in units of (m*/k)^(2/5) v_z0^(-1/5) (4/3)^(2/5)` (`τ̂` to 9
/// decimals), the wording of answers in text.
impl std::fmt::Display for Parameters {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "relaxation time tau = {:.9} in units of (m*/k)^(2/5) v_z0^(-1/5) (4/3)^(2/5)",
            self.tau
        )
    }
}

/// The Kelvin–Voigt law's parameters of physical bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodiesParameters {
    /// Relaxation time `τ` (s), > 0 (Brilliantov's dissipative constant `A` for this law). The
    /// normal restitution it gives depends on the impact speed (`1 − e_n ∝ τ v_z0^{1/5}` at
    /// first order).
    pub relaxation_time: f64,
}

impl ContactLaw for KelvinVoigt {
    type Parameters = Parameters;

    type BodiesParameters = BodiesParameters;

    const FLOOR: Floor = RAW_FLOOR;

    fn check_restitution(e_n: f64) -> Result<f64, PhysicsError> {
        check_restitution(e_n)
    }

    /// `τ̂` by [`tau_for_restitution`].
    fn parameters(e_n: f64) -> Result<Parameters, PhysicsError> {
        Ok(Parameters {
            tau: tau_for_restitution(e_n)?,
        })
    }

    /// The accurate scheme only.
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
            "for e_n < 1",
            "the Kelvin-Voigt law is solved with the accurate scheme only (euler is for elastic \
             impacts)",
        )?;
        Ok((gamma, alpha, Self::parameters(e_n)?))
    }

    fn closed_form(gamma: f64, alpha: f64, e_n: f64) -> Option<f64> {
        dissipative_closed_form(gamma, alpha, e_n)
    }

    /// The continuum row only ([`dimensionless_level`]).
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
            "for e_n < 1",
            "the Kelvin-Voigt law is solved on the continuum row only (springs 0)",
        )?;
        let (shear, limit) = shear_and_limit(gamma, alpha);
        Ok(dimensionless_level(shear, limit, parameters.tau, res))
    }

    /// `[τ̂, 0]`.
    fn values(parameters: &Parameters) -> [f64; PARAMETER_KEYS.len()] {
        [parameters.tau, 0.0]
    }

    fn describe(parameters: &Parameters) -> Option<String> {
        Some(parameters.to_string())
    }

    /// `τ̂` of the bodies' `τ` at their speed ([`dimensionless_tau`]) and its `e_n`
    /// ([`contact_fit`]; [`restitution`] beyond it), which must lie in `[0.3, 1]`.
    fn of_bodies(
        parameters: BodiesParameters,
        normal: &BodiesNormal,
    ) -> Result<(Parameters, f64), PhysicsError> {
        let tau = parameters.relaxation_time;
        if !(tau.is_finite() && tau >= 0.0) {
            return Err(PhysicsError::InvalidParameter {
                name: "relaxation_time",
                value: tau,
                allowed: "a finite number >= 0 (s; 0 for elastic bodies)",
            });
        }
        let hat = dimensionless_tau(
            tau,
            normal.normal_mass,
            normal.stiffness,
            normal.approach_speed,
        );
        let e_n = contact_fit(hat).map_or_else(|| restitution(hat), |(_, e_n)| e_n);
        // `restitution` is ≤ 1: outside the solver's range means NaN or below 0.3.
        if check_restitution(e_n).is_err() {
            return Err(PhysicsError::InvalidParameter {
                name: "relaxation_time",
                value: tau,
                allowed: "a time whose normal restitution at this impact speed is >= 0.3 (a \
                          shorter relaxation time, or a slower impact)",
            });
        }
        Ok((Parameters { tau: hat }, e_n))
    }

    /// The viscoelastic motion of the bodies with relaxation time `τ` (s) and its row, on the
    /// continuum row only (`res.springs = 0`).
    fn run_bodies<B: TangentialBodies>(
        bodies: &mut B,
        normal: &BodiesNormal,
        parameters: BodiesParameters,
        res: Resolution,
        (radius, shear_modulus, limit): (f64, f64, f64),
    ) -> Result<NormalSummary, PhysicsError> {
        continuum_only(
            res.springs,
            "for Kelvin-Voigt bodies",
            "their law is solved on the continuum row only (springs 0)",
        )?;
        let tau = parameters.relaxation_time;
        let normal = ViscoelasticBodies {
            inv_mass1: normal.inv_mass1,
            inv_mass2: normal.inv_mass2,
            stiffness: normal.stiffness,
            approach_speed: normal.approach_speed,
            tau,
        }
        .trajectory(res.steps);
        let row = ViscoelasticRow::new(radius, tau);
        let shortest_zone = run_contact_with(bodies, &normal, row, radius, shear_modulus, limit);
        Ok(NormalSummary {
            contact_time: normal.contact_time,
            peak_force: normal.peak_force,
            max_indentation: normal.max_indentation,
            delta_v1: normal.delta_v1,
            delta_v2: normal.delta_v2,
            shortest_zone,
        })
    }
}

/// `P(γ, α, e_n)` where it is exact without simulation: the full-slip line
/// `1 − (7/2)(1 + e_n) α` for `α ≤` [`regimes::linear_limit_dissipative`] (`α_c1(e_n)` for
/// `γ > 1`, `α_c2` for `γ ≤ 1`; `physics.md`), and the `γ = 1` plateau `P = −e_n` for
/// `α ≥ 2/7` (measured: within 2e-7 at 4096 steps for e_n = 0.7, α = 1.01–3 × 2/7; at γ = 1
/// the stuck tangential motion is the normal motion, damping included).
pub fn dissipative_closed_form(gamma: f64, alpha: f64, e_n: f64) -> Option<f64> {
    if alpha <= regimes::linear_limit_dissipative(gamma, e_n) {
        Some(regimes::full_slip_line(alpha, e_n))
    } else if gamma == 1.0 && alpha >= 2.0 / 7.0 {
        Some(-e_n)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::run_contact_with;
    use crate::model::TangentialBodies;
    use std::cell::Cell;

    /// The row, its sums checked against its pieces after every step: `drift` is the largest
    /// gap of a sum to its recount relative to the largest scale of that sum so far in the
    /// impact (where the contact shrinks, a difference rounded while it was wide stays).
    struct Checked {
        row: ViscoelasticRow,
        scales: Cell<[f64; 3]>,
        drift: Rc<Cell<f64>>,
        exact: Rc<Cell<bool>>,
        steps: Rc<Cell<usize>>,
    }

    impl TangentialModel for Checked {
        const LOCATES_GROSS_SLIP: bool = <ViscoelasticRow as TangentialModel>::LOCATES_GROSS_SLIP;
        const END_STATE: bool = <ViscoelasticRow as TangentialModel>::END_STATE;
        fn at_limit(&self) -> (bool, bool) {
            TangentialModel::at_limit(&self.row)
        }
        fn stuck(&self) -> bool {
            TangentialModel::stuck(&self.row)
        }
        fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
            let r = self.row.step_accurate(m, d1, c);
            let (gaps, scales, exact) = self.row.sums_drift();
            let mut seen = self.scales.get();
            for i in 0..3 {
                seen[i] = seen[i].max(scales[i]);
                if seen[i] > 0.0 {
                    self.drift.set(self.drift.get().max(gaps[i] / seen[i]));
                }
            }
            self.scales.set(seen);
            self.exact.set(self.exact.get() && exact);
            self.steps.set(self.steps.get() + 1);
            r
        }
        fn close_step<B: TangentialBodies>(&self, bodies: &mut B, end: &StepEnd) -> (f64, f64) {
            self.row.close_step(bodies, end)
        }
        fn touch_mean(&self, slip_velocity: f64, rate0: f64, c: f64) -> f64 {
            self.row.touch_mean(slip_velocity, rate0, c)
        }
    }

    /// The chunks' sums, kept by differences where one clipped piece changes a chunk, where the
    /// last piece is cut or extended, and counted again elsewhere, stay the sums of their
    /// pieces to the rounding, their counts exact and their bounds bounds, through whole
    /// impacts in stick, partial slip and gross slip, and the wrapped row gives the same `P`.
    #[test]
    fn the_sums_kept_by_differences_stay_those_of_the_pieces() {
        for (gamma, alpha, e_n) in [
            (0.5, 1.0, 0.6),
            (1.754, 0.3, 0.8),
            (3.0, 0.3, 0.6),
            (3.0, 1.0, 0.9),
            (2.2, 0.98, 0.3),
            (1.754, f64::INFINITY, 0.6),
        ] {
            let tau = tau_for_restitution(e_n).unwrap();
            let res = Resolution {
                springs: 0,
                steps: 512,
            };
            let normal = dimensionless_normal(res.steps, tau);
            let shear = 2.0 / 7.0 * gamma * gamma;
            let (drift, exact, steps) = (
                Rc::new(Cell::new(0.0)),
                Rc::new(Cell::new(true)),
                Rc::new(Cell::new(0)),
            );
            let row = Checked {
                row: ViscoelasticRow::new(1.0, tau),
                scales: Cell::new([0.0; 3]),
                drift: drift.clone(),
                exact: exact.clone(),
                steps: steps.clone(),
            };
            let mut cp = ContactPoint { u: 1.0 };
            run_contact_with(&mut cp, &*normal, row, 1.0, shear, alpha / shear);
            let case = format!("γ {gamma}, α {alpha}, e_n {e_n}");
            assert!(steps.get() >= 512, "{case}: {} steps", steps.get());
            assert!(drift.get() < 1e-12, "{case}: drift {:e}", drift.get());
            assert!(
                exact.get(),
                "{case}: a chunk's counts or bounds no longer hold"
            );
            let plain = dimensionless_p(shear, alpha / shear, tau, res);
            assert_eq!(cp.u.to_bits(), plain.to_bits(), "{case}");
        }
    }
}
