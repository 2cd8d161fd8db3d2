//! Impacts in physical units (SI), simulated directly: each body's equations of motion are
//! integrated and the springs are driven by the relative motion of the contact points.
//!
//! 2-D convention (the plane of the impact): `z` is the common normal pointing from sphere 1
//! into the other body, `x` the tangent. A spin `ω` (rad/s) is signed so that the contact point
//! of sphere 1 moves at `v_x + R ω`; the contact point of sphere 2 (on its opposite side) then
//! moves at `v_x − R ω`. The slip velocity is `u = (v_1x + R_1 ω_1) − (v_2x − R_2 ω_2)` and for a
//! wall `u = v_x + R ω` (the seed's convention).

use serde::Serialize;

use super::error::{positive, PhysicsError};
use super::hertz::NormalBodies;
use super::impact::{refine, run_contact, Limits, Resolution, TangentialBodies};

/// An isotropic elastic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Material {
    /// Young's modulus `E` (Pa), > 0.
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`, in (−1, 0.5].
    pub poisson_ratio: f64,
}

impl Material {
    /// Validate `E > 0` and `−1 < ν ≤ 0.5`.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        positive("youngs_modulus", self.youngs_modulus)?;
        let nu = self.poisson_ratio;
        if !(nu > -1.0 && nu <= 0.5) {
            return Err(PhysicsError::InvalidParameter {
                name: "poisson_ratio",
                value: nu,
                allowed: "in (-1, 0.5]",
            });
        }
        Ok(())
    }

    /// Shear modulus `G = E / (2(1 + ν))` (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }
}

/// Effective moduli of a pair: `1/E* = Σ (1−ν²)/E`, `1/G* = Σ (2−ν)/(4G)`. Returns `(E*, G*)` (Pa).
pub fn effective_moduli(a: &Material, b: &Material) -> (f64, f64) {
    let e_inv = (1.0 - a.poisson_ratio.powi(2)) / a.youngs_modulus
        + (1.0 - b.poisson_ratio.powi(2)) / b.youngs_modulus;
    let g_inv = (2.0 - a.poisson_ratio) / (4.0 * a.shear_modulus())
        + (2.0 - b.poisson_ratio) / (4.0 * b.shear_modulus());
    (1.0 / e_inv, 1.0 / g_inv)
}

/// A sphere: geometry, inertia and material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sphere {
    /// Radius `R` (m).
    pub radius: f64,
    /// Mass `m` (kg).
    pub mass: f64,
    /// Inertia factor `κ` in `I = κ m R²` (2/5 solid, 2/3 thin shell).
    pub kappa: f64,
    /// Material.
    pub material: Material,
}

impl Sphere {
    /// Validate every field.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        positive("radius", self.radius)?;
        positive("mass", self.mass)?;
        positive("kappa", self.kappa)?;
        self.material.validate()
    }

    /// Moment of inertia `I = κ m R²` (kg m²).
    pub fn inertia(&self) -> f64 {
        self.kappa * self.mass * self.radius * self.radius
    }
}

/// Translational and rotational state in the impact plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct Motion {
    /// Tangential velocity `v_x` (m/s).
    pub v_x: f64,
    /// Normal velocity `v_z` (m/s), along the normal from sphere 1 into the other body.
    pub v_z: f64,
    /// Spin `ω` (rad/s), signed as in the module documentation.
    pub omega: f64,
}

/// What sphere 1 hits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A fixed elastic half-space (infinite mass, flat).
    Wall(Material),
    /// A second free sphere with its own incident motion.
    Sphere(Sphere, Motion),
}

/// One impact in physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalImpact {
    /// The incident sphere.
    pub sphere: Sphere,
    /// Its incident motion (`v_z > 0` towards the target).
    pub motion: Motion,
    /// Wall or second sphere.
    pub target: Target,
    /// Coulomb friction coefficient `μ` (≥ 0; `∞` for no slip).
    pub friction: f64,
}

/// Dimensionless groups of an impact (physics.md): `γ² = (m*/m_t) G*/E*`,
/// `α = (2/7)(m*/m_t) μ v_z0/|u0|`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Groups {
    /// `γ`.
    pub gamma: f64,
    /// `α` (`∞` when `u0 = 0` or `μ = ∞`).
    pub alpha: f64,
    /// `E*` (Pa).
    pub e_star: f64,
    /// `G*` (Pa).
    pub g_star: f64,
    /// Normal reduced mass `m*` (kg).
    pub normal_mass: f64,
    /// Tangential reduced mass `m_t` (kg), `1/m_t = Σ (1/m + R²/I)`.
    pub tangential_mass: f64,
    /// Effective radius `R*` (m).
    pub radius: f64,
    /// Approach speed `v_z0` (m/s).
    pub approach_speed: f64,
    /// Incident slip velocity `u0` (m/s).
    pub slip_velocity: f64,
}

/// Result of a physical-units simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhysicalOutcome {
    /// Sphere 1 after the impact.
    pub sphere: Motion,
    /// Sphere 2 after the impact (`None` for a wall).
    pub other: Option<Motion>,
    /// `P = u_after/u0` (`None` when `u0 = 0`).
    pub p: Option<f64>,
    /// Error estimate of `P` (0 when `u0 = 0`).
    pub error_estimate: f64,
    /// Measured contact time (s).
    pub contact_time: f64,
    /// Measured peak normal force (N).
    pub peak_force: f64,
    /// Measured maximum indentation (m).
    pub max_indentation: f64,
    /// Dimensionless groups.
    pub groups: Groups,
    /// Resolution of the run reported.
    pub resolution: Resolution,
}

/// Tangential degrees of freedom of the two bodies (body 2 absent for a wall).
#[derive(Debug, Clone, Copy)]
struct TwoBodies {
    v1: f64,
    w1: f64,
    inv_m1: f64,
    r1: f64,
    inv_i1: f64,
    v2: f64,
    w2: f64,
    inv_m2: f64,
    r2: f64,
    inv_i2: f64,
}

impl TangentialBodies for TwoBodies {
    fn slip_velocity(&self) -> f64 {
        (self.v1 + self.r1 * self.w1) - (self.v2 - self.r2 * self.w2)
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        // Body 1: m1 v1' = −F, I1 ω1' = −F R1. Body 2: m2 v2' = +F, I2 ω2' = −F R2.
        let a1 = -f * self.inv_m1 + self.r1 * (-f * self.r1 * self.inv_i1);
        let a2 = f * self.inv_m2 - self.r2 * (-f * self.r2 * self.inv_i2);
        a1 - a2
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.v1 -= h * f * self.inv_m1;
        self.w1 -= h * f * self.r1 * self.inv_i1;
        self.v2 += h * f * self.inv_m2;
        self.w2 -= h * f * self.r2 * self.inv_i2;
    }
}

impl PhysicalImpact {
    fn validate(&self) -> Result<(), PhysicsError> {
        self.sphere.validate()?;
        if let Target::Sphere(s, m) = &self.target {
            s.validate()?;
            check_motion(m)?;
        }
        if let Target::Wall(w) = &self.target {
            w.validate()?;
        }
        check_motion(&self.motion)?;
        if self.friction.is_nan() || self.friction < 0.0 {
            return Err(PhysicsError::InvalidParameter {
                name: "friction",
                value: self.friction,
                allowed: ">= 0 (or inf for no slip)",
            });
        }
        let approach = self.approach_speed();
        if approach.is_nan() || approach <= 0.0 || !approach.is_finite() {
            return Err(PhysicsError::InvalidParameter {
                name: "v_z",
                value: approach,
                allowed: "an approach speed > 0 (the bodies must move towards each other)",
            });
        }
        Ok(())
    }

    fn approach_speed(&self) -> f64 {
        match &self.target {
            Target::Wall(_) => self.motion.v_z,
            Target::Sphere(_, m) => self.motion.v_z - m.v_z,
        }
    }

    fn bodies(&self) -> TwoBodies {
        let s = &self.sphere;
        let (v2, w2, inv_m2, r2, inv_i2) = match &self.target {
            Target::Wall(_) => (0.0, 0.0, 0.0, 0.0, 0.0),
            Target::Sphere(o, m) => (m.v_x, m.omega, 1.0 / o.mass, o.radius, 1.0 / o.inertia()),
        };
        TwoBodies {
            v1: self.motion.v_x,
            w1: self.motion.omega,
            inv_m1: 1.0 / s.mass,
            r1: s.radius,
            inv_i1: 1.0 / s.inertia(),
            v2,
            w2,
            inv_m2,
            r2,
            inv_i2,
        }
    }

    /// The dimensionless groups `γ`, `α` and the effective quantities behind them.
    pub fn groups(&self) -> Result<Groups, PhysicsError> {
        self.validate()?;
        let b = self.bodies();
        let (other_mat, radius) = match &self.target {
            Target::Wall(m) => (*m, self.sphere.radius),
            Target::Sphere(o, _) => (
                o.material,
                self.sphere.radius * o.radius / (self.sphere.radius + o.radius),
            ),
        };
        let (e_star, g_star) = effective_moduli(&self.sphere.material, &other_mat);
        let normal_mass = 1.0 / (b.inv_m1 + b.inv_m2);
        let tangential_mass =
            1.0 / (b.inv_m1 + b.r1 * b.r1 * b.inv_i1 + b.inv_m2 + b.r2 * b.r2 * b.inv_i2);
        let ratio = normal_mass / tangential_mass;
        let u0 = b.slip_velocity();
        let v = self.approach_speed();
        let alpha = 2.0 / 7.0 * ratio * self.friction * v / u0.abs();
        Ok(Groups {
            gamma: (ratio * g_star / e_star).sqrt(),
            alpha: if alpha.is_nan() { f64::INFINITY } else { alpha },
            e_star,
            g_star,
            normal_mass,
            tangential_mass,
            radius,
            approach_speed: v,
            slip_velocity: u0,
        })
    }

    /// Simulate at a fixed resolution (`springs` on the half-row, `steps` per contact time).
    pub fn simulate(&self, res: Resolution) -> Result<PhysicalOutcome, PhysicsError> {
        let res = res.validate()?;
        let groups = self.groups()?;
        let mut bodies = self.bodies();
        let normal = NormalBodies {
            inv_mass1: bodies.inv_m1,
            inv_mass2: bodies.inv_m2,
            stiffness: 4.0 / 3.0 * groups.e_star * groups.radius.sqrt(),
            approach_speed: groups.approach_speed,
        }
        .trajectory(res.steps);
        // Beyond ALPHA_NO_SLIP the finite-μ clamp is decided by rounding: simulate no slip.
        let limit = if groups.alpha > super::impact::ALPHA_NO_SLIP {
            f64::INFINITY
        } else {
            self.friction * groups.e_star / groups.g_star
        };
        run_contact(
            &mut bodies,
            &normal,
            res.springs,
            groups.radius,
            groups.g_star,
            limit,
        );
        let u0 = groups.slip_velocity;
        let p = (u0 != 0.0).then(|| bodies.slip_velocity() / u0);
        let sphere = Motion {
            v_x: bodies.v1,
            v_z: self.motion.v_z + normal.delta_v1,
            omega: bodies.w1,
        };
        let other = match &self.target {
            Target::Wall(_) => None,
            Target::Sphere(_, m) => Some(Motion {
                v_x: bodies.v2,
                v_z: m.v_z + normal.delta_v2,
                omega: bodies.w2,
            }),
        };
        Ok(PhysicalOutcome {
            sphere,
            other,
            p,
            error_estimate: 0.0,
            contact_time: normal.contact_time,
            peak_force: normal.peak_force,
            max_indentation: normal.max_indentation,
            groups,
            resolution: res,
        })
    }

    /// Simulate with automatic refinement until the error estimate of `P` is ≤ `tol`.
    /// For `u0 = 0` a single run at the base resolution is returned (nothing tangential happens).
    pub fn solve(&self, tol: f64) -> Result<PhysicalOutcome, PhysicsError> {
        let groups = self.groups()?;
        let base = super::impact::base_resolution(groups.gamma, super::Scheme::Accurate);
        if groups.slip_velocity == 0.0 {
            return self.simulate(base);
        }
        // Refuse before simulating what cannot fit the limits even in the best case.
        super::impact::plan(
            groups.gamma,
            tol,
            super::Scheme::Accurate,
            Limits::default(),
        )?;
        let mut last = None;
        let (_, est, _) = refine(base, 2, tol, false, Limits::default(), |res| {
            let out = self.simulate(res)?;
            let p = out.p.unwrap_or(0.0);
            last = Some(out);
            Ok(p)
        })
        .map_err(|e| e.with_gamma(groups.gamma))?;
        let mut out = last.expect("refine runs at least three levels");
        out.error_estimate = est;
        Ok(out)
    }
}

fn check_motion(m: &Motion) -> Result<(), PhysicsError> {
    for (name, v) in [("v_x", m.v_x), ("v_z", m.v_z), ("omega", m.omega)] {
        if !v.is_finite() {
            return Err(PhysicsError::InvalidParameter {
                name,
                value: v,
                allowed: "a finite number",
            });
        }
    }
    Ok(())
}
