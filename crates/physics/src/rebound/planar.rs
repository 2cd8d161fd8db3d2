//! The impact in its plane: the 2-D states of both bodies, the groups `γ` and `α` of a pair,
//! and the rebound from `P` (impulses, restitution of the centres, angles, energy lost).

use super::{effective_moduli, query, Body, Elastic, InvalidInput};

/// Translational and rotational state of one body in the plane of the impact.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct State {
    /// Tangential velocity `v_x` (m/s).
    pub v_x: f64,
    /// Normal velocity `v_z` (m/s), along the normal from sphere 1 into the other body.
    pub v_z: f64,
    /// Spin `ω` (rad/s), signed as in the module documentation.
    pub omega: f64,
}

/// Sphere 1 and what it hits: a wall (`other = None`, fixed) or sphere 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    /// Sphere 1.
    pub sphere: Body,
    /// Sphere 2, or `None` for a fixed wall.
    pub other: Option<Body>,
}

/// The state of both bodies before the impact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Incident {
    /// Sphere 1.
    pub sphere: State,
    /// Sphere 2 (must be all zero for a wall).
    pub other: State,
}

/// The outcome of one impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rebound {
    /// Sphere 1 after the impact.
    pub sphere: State,
    /// Sphere 2 after the impact (`None` for a wall).
    pub other: Option<State>,
    /// `P = u_after/u_before` used (NaN when `u0 = 0`: nothing tangential happens then).
    pub p: f64,
    /// Slip velocity before, `u0` (m/s).
    pub slip_before: f64,
    /// Slip velocity after, `P u0` (m/s).
    pub slip_after: f64,
    /// Friction impulse `J` on body 2 along `+x` (N s); body 1 receives `−J`.
    pub tangential_impulse: f64,
    /// Normal impulse `(1 + e_n) m* v_z0` on body 2 along `+z` (N s); body 1 receives the
    /// opposite.
    pub normal_impulse: f64,
    /// Normal restitution `e_n` used: the relative normal velocity after is `−e_n v_z0`.
    pub e_n: f64,
    /// Tangential restitution of the centres, `e_t = (v_1x − v_2x)_after/(v_1x − v_2x)_before`
    /// (for a wall `v_x/v_x0`); NaN when the incident relative tangential velocity is 0.
    pub e_t: f64,
    /// Incidence angle of the relative centre velocity from the normal (rad),
    /// `atan2(v_x0,rel, v_z0)`.
    pub incidence_angle: f64,
    /// Rebound angle of the relative centre velocity from the normal (rad),
    /// `atan2(v_x,rel, e_n v_z0)` after the impact; positive on the side of `+x`.
    pub rebound_angle_centre: f64,
    /// Rebound angle of the contact-point velocity from the normal (rad),
    /// `atan2(P u0, e_n v_z0)`: negative when the contact point's tangential motion reversed
    /// (for `u0 > 0`).
    pub rebound_angle_contact: f64,
    /// Kinetic energy lost, `(m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²)` (J): to friction
    /// (and tangential damping) and to normal damping (0 for `e_n = 1`).
    pub energy_lost: f64,
}

impl Pair {
    #[inline]
    /// Check masses, radii and inertia factors.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        self.sphere.validate(&["mass", "radius", "kappa"])?;
        if let Some(o) = &self.other {
            o.validate(&["other.mass", "other.radius", "other.kappa"])?;
        }
        Ok(())
    }

    #[inline]
    /// Normal reduced mass `m* = m_1 m_2/(m_1 + m_2)` (kg); `m_1` for a wall.
    pub fn normal_mass(&self) -> f64 {
        match &self.other {
            None => self.sphere.mass,
            Some(o) => 1.0 / (1.0 / self.sphere.mass + 1.0 / o.mass),
        }
    }

    #[inline]
    /// Tangential reduced mass `m_t`, `1/m_t = Σ (1/m + R²/I)` (kg); `κ m/(1 + κ)` for one sphere.
    pub fn tangential_mass(&self) -> f64 {
        let inv = |b: &Body| 1.0 / b.mass + b.radius * b.radius / b.inertia();
        1.0 / (inv(&self.sphere) + self.other.as_ref().map_or(0.0, inv))
    }

    #[inline]
    /// `m*/m_t` (dimensionless); `(1 + κ)/κ` for one sphere on a wall (7/2 for a solid sphere).
    pub fn mass_ratio(&self) -> f64 {
        self.normal_mass() / self.tangential_mass()
    }

    #[inline]
    /// Effective radius `R* = R_1 R_2/(R_1 + R_2)` (m); `R_1` for a flat wall.
    pub fn effective_radius(&self) -> f64 {
        match &self.other {
            None => self.sphere.radius,
            Some(o) => self.sphere.radius * o.radius / (self.sphere.radius + o.radius),
        }
    }

    #[inline]
    /// `γ = √((m*/m_t) G*/E*)` from the effective moduli (Pa).
    pub fn gamma(&self, e_star: f64, g_star: f64) -> f64 {
        (self.mass_ratio() * g_star / e_star).sqrt()
    }

    #[inline]
    /// `γ` from the two materials (sphere 1, then the wall or sphere 2).
    pub fn gamma_from_materials(&self, a: &Elastic, b: &Elastic) -> Result<f64, InvalidInput> {
        self.validate()?;
        a.validate()?;
        b.validate()?;
        if a.youngs_modulus.is_infinite() && b.youngs_modulus.is_infinite() {
            return Err(query(
                "youngs_modulus",
                f64::INFINITY,
                "finite for at least one of the two bodies (two rigid bodies have no contact \
                 mechanics)",
            ));
        }
        let (e, g) = effective_moduli(a, b);
        Ok(self.gamma(e, g))
    }

    #[inline]
    /// Relative approach speed `v_z0 = v_1z − v_2z` (m/s; `v_1z` for a wall).
    pub fn approach_speed(&self, s: &Incident) -> f64 {
        match &self.other {
            None => s.sphere.v_z,
            Some(_) => s.sphere.v_z - s.other.v_z,
        }
    }

    #[inline]
    /// Slip velocity `u = (v_1x + R_1 ω_1) − (v_2x − R_2 ω_2)` (m/s).
    pub fn slip_velocity(&self, s: &Incident) -> f64 {
        let u1 = s.sphere.v_x + self.sphere.radius * s.sphere.omega;
        match &self.other {
            None => u1,
            Some(o) => u1 - (s.other.v_x - o.radius * s.other.omega),
        }
    }

    #[inline]
    /// `α = (2/7)(m*/m_t) μ v_z0/|u0|` for the friction coefficient `μ` (`∞` when `u0 = 0`).
    pub fn alpha(&self, s: &Incident, mu: f64) -> Result<f64, InvalidInput> {
        self.check_incident(s)?;
        self.alpha_checked(s, mu)
    }

    /// [`Pair::alpha`] for an incident state already checked.
    #[inline]
    pub(crate) fn alpha_checked(&self, s: &Incident, mu: f64) -> Result<f64, InvalidInput> {
        if mu.is_nan() || mu < 0.0 {
            return Err(query("friction", mu, ">= 0 (or inf for no slip)"));
        }
        let u0 = self.slip_velocity(s).abs();
        let a = 2.0 / 7.0 * self.mass_ratio() * mu * self.approach_speed(s) / u0;
        Ok(if a.is_nan() { f64::INFINITY } else { a })
    }

    #[inline]
    pub(super) fn check_incident(&self, s: &Incident) -> Result<(), InvalidInput> {
        self.validate()?;
        let finite = [
            s.sphere.v_x,
            s.sphere.v_z,
            s.sphere.omega,
            s.other.v_x,
            s.other.v_z,
            s.other.omega,
        ]
        .iter()
        .all(|v| v.is_finite());
        let still = self.other.is_some() || s.other == State::default();
        let v = self.approach_speed(s);
        if finite && still && v > 0.0 && v < f64::INFINITY {
            return Ok(());
        }
        self.bad_incident(s)
    }

    #[cold]
    fn bad_incident(&self, s: &Incident) -> Result<(), InvalidInput> {
        let fields = [
            ("v_x", s.sphere.v_x),
            ("v_z", s.sphere.v_z),
            ("omega", s.sphere.omega),
            ("other.v_x", s.other.v_x),
            ("other.v_z", s.other.v_z),
            ("other.omega", s.other.omega),
        ];
        for (name, v) in fields {
            if !v.is_finite() {
                return Err(query(name, v, "a finite number"));
            }
        }
        if self.other.is_none() && s.other != State::default() {
            let (name, value) = [
                ("other.v_x", s.other.v_x),
                ("other.v_z", s.other.v_z),
                ("other.omega", s.other.omega),
            ]
            .into_iter()
            .find(|(_, v)| *v != 0.0)
            .unwrap_or(("other.v_x", s.other.v_x));
            return Err(query(
                name,
                value,
                "zero motion for a fixed wall (v_x = v_z = omega = 0)",
            ));
        }
        let v = self.approach_speed(s);
        if !(v > 0.0 && v < f64::INFINITY) {
            return Err(query(
                "v_z",
                v,
                "a finite approach speed v_z0 > 0 (the bodies must move towards each other)",
            ));
        }
        Ok(())
    }

    /// The state after the impact for a given `P` (ignored when `u0 = 0`), elastic in the
    /// normal direction ([`Pair::rebound_dissipative`] at `e_n = 1`).
    pub fn rebound(&self, s: &Incident, p: f64) -> Result<Rebound, InvalidInput> {
        self.rebound_dissipative(s, p, 1.0)
    }

    /// The state after the impact for a given `P` (ignored when `u0 = 0`) and normal
    /// restitution `e_n ∈ [0, 1]`.
    ///
    /// Linear momentum is conserved exactly (sphere–sphere), and so is the angular momentum
    /// about the contact point; the normal velocity difference reverses with `e_n`, the
    /// contact point's tangential velocity with `P`. Energy:
    /// `ΔE = (m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²)` ([`Rebound::energy_lost`]).
    pub fn rebound_dissipative(
        &self,
        s: &Incident,
        p: f64,
        e_n: f64,
    ) -> Result<Rebound, InvalidInput> {
        self.check_incident(s)?;
        let c = self.impulses(s, p, check_restitution(e_n)?)?;
        let rel_x0 = s.sphere.v_x - s.other.v_x;
        let rel_x1 = c.sphere.v_x - c.other.map_or(0.0, |o| o.v_x);
        let v0 = c.approach_speed;
        Ok(Rebound {
            sphere: c.sphere,
            other: c.other,
            p: c.p,
            slip_before: c.slip_before,
            slip_after: c.slip_after,
            tangential_impulse: c.tangential_impulse,
            normal_impulse: c.normal_impulse,
            e_n: c.e_n,
            e_t: if rel_x0 == 0.0 {
                f64::NAN
            } else {
                rel_x1 / rel_x0
            },
            incidence_angle: rel_x0.atan2(v0),
            rebound_angle_centre: rel_x1.atan2(c.e_n * v0),
            rebound_angle_contact: c.slip_after.atan2(c.e_n * v0),
            energy_lost: c.energy_lost,
        })
    }

    /// The impulses and states after the impact for an incident state already checked.
    #[inline]
    pub(super) fn impulses(&self, s: &Incident, p: f64, e_n: f64) -> Result<Core, InvalidInput> {
        let u0 = self.slip_velocity(s);
        let p = if u0 == 0.0 { f64::NAN } else { p };
        if u0 != 0.0 && !p.is_finite() {
            return Err(query("P", p, "a finite number"));
        }
        let m_t = self.tangential_mass();
        let j = if u0 == 0.0 { 0.0 } else { m_t * (1.0 - p) * u0 };
        let v0 = self.approach_speed(s);
        let n = (1.0 + e_n) * self.normal_mass() * v0;
        let b1 = &self.sphere;
        let sphere = State {
            v_x: s.sphere.v_x - j / b1.mass,
            v_z: s.sphere.v_z - n / b1.mass,
            omega: s.sphere.omega - j * b1.radius / b1.inertia(),
        };
        let other = self.other.as_ref().map(|b2| State {
            v_x: s.other.v_x + j / b2.mass,
            v_z: s.other.v_z + n / b2.mass,
            omega: s.other.omega - j * b2.radius / b2.inertia(),
        });
        Ok(Core {
            sphere,
            other,
            p,
            slip_before: u0,
            slip_after: if u0 == 0.0 { 0.0 } else { p * u0 },
            tangential_impulse: j,
            normal_impulse: n,
            e_n,
            approach_speed: v0,
            energy_lost: if u0 == 0.0 {
                0.0
            } else {
                0.5 * m_t * u0 * u0 * (1.0 - p * p)
            } + 0.5 * self.normal_mass() * v0 * v0 * (1.0 - e_n * e_n),
        })
    }
}

/// What [`Pair::rebound`] computes before the angles.
pub(super) struct Core {
    pub(super) sphere: State,
    pub(super) other: Option<State>,
    pub(super) p: f64,
    pub(super) slip_before: f64,
    pub(super) slip_after: f64,
    pub(super) tangential_impulse: f64,
    pub(super) normal_impulse: f64,
    pub(super) e_n: f64,
    pub(super) approach_speed: f64,
    pub(super) energy_lost: f64,
}

/// Check a normal restitution for the rebound algebra: finite, in `[0, 1]`. Not the solver's
/// range (`oblique_solver::law::check_restitution`, `[0.3, 1]`): the algebra holds for any
/// `e_n` a caller brings, e.g. from a measurement, and this crate sits below the solver.
pub(super) fn check_restitution(e_n: f64) -> Result<f64, InvalidInput> {
    if (0.0..=1.0).contains(&e_n) {
        Ok(e_n)
    } else {
        Err(query("e_n", e_n, "a number in [0, 1] (1: elastic)"))
    }
}
