//! Impacts in physical units (SI), simulated directly: each body's equations of motion are
//! integrated and the springs are driven by the relative motion of the contact points.
//!
//! 2-D convention (the plane of the impact): `z` is the common normal pointing from sphere 1
//! into the other body, `x` the tangent. A spin `ω` (rad/s) is signed so that the contact point
//! of sphere 1 moves at `v_x + R ω`; the contact point of sphere 2 (on its opposite side) then
//! moves at `v_x − R ω`. The slip velocity is `u = (v_1x + R_1 ω_1) − (v_2x − R_2 ω_2)` and for a
//! wall `u = v_x + R ω` (the seed's convention).

use oblique_physics::rebound::{effective_moduli, Body, Elastic, Incident, Pair, State};
use serde::Serialize;

use super::elastic::RAW_FLOOR;
use super::error::PhysicsError;
use super::impact::{Limits, Resolution, Scheme, TangentialBodies};
use super::law::{BodiesNormal, ContactLaw, Floor};
use super::refine::{refine_to, Ladder};
use super::registry::{with_bodies_law, BodiesLaw, LawParameters};
use super::zones::Level;

/// One impact in physical units, in the vocabulary of the lookup ([`oblique_physics::rebound`]):
/// the same [`Pair`], materials and [`Incident`] state that a table query takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalImpact {
    /// Sphere 1 and what it hits: a fixed wall (`other = None`) or sphere 2 (masses in kg, radii
    /// in m, inertia factors κ).
    pub pair: Pair,
    /// Elastic constants of sphere 1 and of the wall or sphere 2 (`E` in Pa, `ν`; `E = ∞` for a
    /// rigid body, not both).
    pub materials: [Elastic; 2],
    /// Both bodies' motion before the impact (m/s, rad/s; `other` all zero for a wall). The
    /// approach speed `v_z0 = v_1z − v_2z` must be > 0.
    pub incident: Incident,
    /// Coulomb friction coefficient `μ` (≥ 0; `∞` for no slip).
    pub friction: f64,
    /// The bodies' contact law with its physical parameters (elastic by default; e.g. the
    /// Kelvin–Voigt law with a relaxation time, [`PhysicalImpact::with_relaxation_time`]). The
    /// normal restitution it gives may depend on the impact speed ([`PhysicalOutcome::e_n`]).
    pub law: BodiesLaw,
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
    pub sphere: State,
    /// Sphere 2 after the impact (`None` for a wall).
    pub other: Option<State>,
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
    /// Normal restitution `e_n` of the impact (1 for elastic bodies): the relative normal
    /// speed after over before.
    pub e_n: f64,
    /// The law of the bodies with its parameters: for Kelvin–Voigt bodies the dimensionless
    /// relaxation time `τ̂`, that of the dimensionless impact with the same `(γ, α, e_n)`.
    pub law: LawParameters,
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
    /// A sphere (`sphere`: m in kg, R in m, κ; `material`: E in Pa, ν) moving at `motion`
    /// (m/s, rad/s; `v_z > 0` towards the wall) onto a fixed wall of `wall`, friction `μ`.
    pub fn sphere_on_wall(
        (sphere, material): (Body, Elastic),
        wall: Elastic,
        motion: State,
        friction: f64,
    ) -> PhysicalImpact {
        PhysicalImpact {
            pair: Pair {
                sphere,
                other: None,
            },
            materials: [material, wall],
            incident: Incident {
                sphere: motion,
                other: State::default(),
            },
            friction,
            law: BodiesLaw::default(),
        }
    }

    /// Sphere 1 on sphere 2, each with its body, material and incident motion (units as in
    /// [`PhysicalImpact::sphere_on_wall`]; `z` points from sphere 1 towards sphere 2).
    pub fn sphere_on_sphere(
        (sphere, material): (Body, Elastic),
        motion: State,
        (other, other_material): (Body, Elastic),
        other_motion: State,
        friction: f64,
    ) -> PhysicalImpact {
        PhysicalImpact {
            pair: Pair {
                sphere,
                other: Some(other),
            },
            materials: [material, other_material],
            incident: Incident {
                sphere: motion,
                other: other_motion,
            },
            friction,
            law: BodiesLaw::default(),
        }
    }

    /// The same impact with bodies of the contact law `law` ([`BodiesLaw`]).
    pub fn with_law(mut self, law: BodiesLaw) -> PhysicalImpact {
        self.law = law;
        self
    }

    /// The same impact with Kelvin–Voigt bodies of relaxation time `τ` (s; `physics.md`,
    /// "Dissipative impacts"), elastic ones for `τ = 0` ([`BodiesLaw::of_relaxation_time`]).
    pub fn with_relaxation_time(self, tau: f64) -> PhysicalImpact {
        self.with_law(BodiesLaw::of_relaxation_time(tau))
    }

    /// The bodies' law checked, with its dimensionless parameters at this impact's speed
    /// (for Kelvin–Voigt bodies `τ̂`) and the normal restitution `e_n` they give (in the law's
    /// range).
    pub fn restitution(&self) -> Result<(LawParameters, f64), PhysicsError> {
        let g = self.groups()?;
        self.law.of_bodies(&self.normal(&g))
    }

    /// The normal constants of the bodies.
    fn normal(&self, g: &Groups) -> BodiesNormal {
        let bodies = self.bodies();
        BodiesNormal {
            inv_mass1: bodies.inv_m1,
            inv_mass2: bodies.inv_m2,
            normal_mass: g.normal_mass,
            stiffness: 4.0 / 3.0 * g.e_star * g.radius.sqrt(),
            radius: g.radius,
            approach_speed: g.approach_speed,
        }
    }

    fn bodies(&self) -> TwoBodies {
        let (s, inc) = (&self.pair.sphere, &self.incident);
        let (v2, w2, inv_m2, r2, inv_i2) = match &self.pair.other {
            None => (0.0, 0.0, 0.0, 0.0, 0.0),
            Some(o) => (
                inc.other.v_x,
                inc.other.omega,
                1.0 / o.mass,
                o.radius,
                1.0 / o.inertia(),
            ),
        };
        TwoBodies {
            v1: inc.sphere.v_x,
            w1: inc.sphere.omega,
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

    /// The dimensionless groups `γ`, `α` and the effective quantities behind them, by the
    /// rebound algebra's own definitions ([`Pair`]). Checks every input.
    pub fn groups(&self) -> Result<Groups, PhysicsError> {
        let (pair, inc) = (&self.pair, &self.incident);
        let [a, b] = &self.materials;
        let gamma = pair.gamma_from_materials(a, b)?;
        let alpha = pair.alpha(inc, self.friction)?;
        let (e_star, g_star) = effective_moduli(a, b);
        Ok(Groups {
            gamma,
            alpha,
            e_star,
            g_star,
            normal_mass: pair.normal_mass(),
            tangential_mass: pair.tangential_mass(),
            radius: pair.effective_radius(),
            approach_speed: pair.approach_speed(inc),
            slip_velocity: pair.slip_velocity(inc),
        })
    }

    /// Simulate at a fixed resolution (`springs` on the half-row, `steps` per contact time;
    /// Kelvin–Voigt bodies take the continuum row only, `springs = 0`).
    pub fn simulate(&self, res: Resolution) -> Result<PhysicalOutcome, PhysicsError> {
        Ok(self.simulate_level(res)?.0)
    }

    /// [`PhysicalImpact::simulate`] with how finely the run resolved its approach to gross
    /// slip ([`Level::shortest_zone`]).
    fn simulate_level(&self, res: Resolution) -> Result<(PhysicalOutcome, f64), PhysicsError> {
        let res = res.validate()?;
        let groups = self.groups()?;
        let normal = self.normal(&groups);
        let (law, e_n) = self.law.of_bodies(&normal)?;
        let mut bodies = self.bodies();
        // Beyond ALPHA_NO_SLIP the finite-μ clamp is decided by rounding: simulate no slip.
        let limit = if groups.alpha > super::impact::ALPHA_NO_SLIP {
            f64::INFINITY
        } else {
            self.friction * groups.e_star / groups.g_star
        };
        let contact = (groups.radius, groups.g_star, limit);
        // The registry picks the implementation of the bodies' law.
        let normal = with_bodies_law!(self.law, L, p => {
            L::run_bodies(&mut bodies, &normal, p, res, contact)?
        });
        let u0 = groups.slip_velocity;
        let p = (u0 != 0.0).then(|| bodies.slip_velocity() / u0);
        let sphere = State {
            v_x: bodies.v1,
            v_z: self.incident.sphere.v_z + normal.delta_v1,
            omega: bodies.w1,
        };
        let other = self.pair.other.map(|_| State {
            v_x: bodies.v2,
            v_z: self.incident.other.v_z + normal.delta_v2,
            omega: bodies.w2,
        });
        let outcome = PhysicalOutcome {
            sphere,
            other,
            p,
            error_estimate: 0.0,
            contact_time: normal.contact_time,
            peak_force: normal.peak_force,
            max_indentation: normal.max_indentation,
            e_n,
            law,
            groups,
            resolution: res,
        };
        Ok((outcome, normal.shortest_zone))
    }

    /// Simulate with automatic refinement until the error estimate of `P` is ≤ `tol`.
    /// For `u0 = 0` a single run at the base resolution is returned (nothing tangential happens).
    pub fn solve(&self, tol: f64) -> Result<PhysicalOutcome, PhysicsError> {
        let groups = self.groups()?;
        let base = super::impact::base_resolution(groups.gamma, Scheme::Accurate);
        if groups.slip_velocity == 0.0 {
            return self.simulate(base);
        }
        // The driver of every solve ([`refine_to`]), from the base level with the plain
        // estimate of the finest value (no Richardson value: the outcome reported is one run's).
        let ladder = Ladder {
            start: base,
            order: 2,
            floor: Floor::fixed(RAW_FLOOR),
            richardson: false,
        };
        let mut last = None;
        let (_, est, _) = refine_to(
            groups.gamma,
            tol,
            (Scheme::Accurate, Limits::default()),
            ladder,
            |res| {
                let (out, shortest_zone) = self.simulate_level(res)?;
                let p = out.p.unwrap_or(0.0);
                last = Some(out);
                Ok(Level { p, shortest_zone })
            },
            &mut |_| {},
        )?;
        let mut out = last.expect("refine runs at least three levels");
        out.error_estimate = est;
        Ok(out)
    }
}
