//! The impact in 3-D: the states of both bodies and the contact normal, reduced to the plane of
//! impact ([`Frame`]), the 2-D rebound applied back along its axes.

use super::planar::check_restitution;
use super::{query, Incident, InvalidInput, Pair, State};
use crate::vec3::{axpy, cross, dot, sub, Vec3};

/// Translational and rotational state of one body in 3-D.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Motion3 {
    /// Velocity of the centre `v` (m/s).
    pub velocity: Vec3,
    /// Angular velocity `ω` (rad/s), right-handed.
    pub spin: Vec3,
}

/// Both bodies before a 3-D impact, and the contact normal.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Incident3 {
    /// Sphere 1.
    pub sphere: Motion3,
    /// Sphere 2 (must be all zero for a wall).
    pub other: Motion3,
    /// Contact normal `n` pointing from sphere 1's centre into the other body (into the wall, or
    /// towards sphere 2's centre). Any non-zero length; it is normalised.
    pub normal: Vec3,
}

/// The plane of impact: orthonormal, right-handed (`b = n × t`), the 2-D `x, y, z` axes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    /// `t` (the 2-D `x`): direction of the incident slip velocity `u0` of the contact point
    /// (when `u0 = 0`, of the relative tangential centre velocity, else any tangent).
    pub tangent: Vec3,
    /// `b = n × t` (the 2-D `y`, the spin axis of the 2-D problem).
    pub binormal: Vec3,
    /// `n` (the 2-D `z`), unit.
    pub normal: Vec3,
}

/// The outcome of one 3-D impact (`Default`: all zero, for pre-filling batch outputs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rebound3 {
    /// Sphere 1 after the impact.
    pub sphere: Motion3,
    /// Sphere 2 after the impact (`None` for a wall).
    pub other: Option<Motion3>,
    /// The plane of impact used.
    pub frame: Frame,
    /// `P = u_after/u_before` used (NaN when `u0 = 0`: nothing tangential happens then).
    pub p: f64,
    /// Magnitude of the incident slip velocity of the contact point, `|u0| ≥ 0` (m/s), along
    /// `frame.tangent`.
    pub slip_before: f64,
    /// Slip velocity after along `frame.tangent`, `P |u0|` (m/s; negative when it reversed).
    pub slip_after: f64,
    /// Friction impulse `J` on body 2 along `+t` (N s); body 1 receives `−J t`.
    pub tangential_impulse: f64,
    /// Normal impulse `(1 + e_n) m* v_z0` on body 2 along `+n` (N s); body 1 receives the
    /// opposite.
    pub normal_impulse: f64,
    /// Normal restitution `e_n` used: the bodies separate at `e_n v_z0`.
    pub e_n: f64,
    /// Tangential restitution of the centres, `e_t = (w_after · w_before)/|w_before|²` with `w`
    /// the tangential part of `v_1 − v_2` (the 2-D `e_t` when `w` lies along `t`); NaN when
    /// `w_before = 0`.
    pub e_t: f64,
    /// `|w_before|`, tangential speed of the relative centre velocity before (m/s).
    pub centre_speed_before: f64,
    /// `|w_after|`, tangential speed of the relative centre velocity after (m/s).
    pub centre_speed_after: f64,
    /// Approach speed `v_z0 = (v_1 − v_2)·n > 0` (m/s); the bodies separate at `e_n v_z0`.
    pub approach_speed: f64,
    /// Kinetic energy lost, `(m_t/2) |u0|² (1 − P²) + (m*/2) v_z0² (1 − e_n²)` (J).
    pub energy_lost: f64,
}

impl Rebound3 {
    /// Incidence angle of the relative centre velocity from the normal (rad),
    /// `atan2(|w_before|, v_z0)`.
    pub fn incidence_angle(&self) -> f64 {
        self.centre_speed_before.atan2(self.approach_speed)
    }

    /// Rebound angle of the relative centre velocity from the normal (rad),
    /// `atan2(|w_after|, e_n v_z0)`, in `[0, π/2)`.
    pub fn rebound_angle_centre(&self) -> f64 {
        self.centre_speed_after
            .atan2(self.e_n * self.approach_speed)
    }

    /// Rebound angle of the contact-point velocity from the normal, in the plane of impact
    /// (rad), `atan2(P |u0|, e_n v_z0)`: negative when the slip reversed.
    pub fn rebound_angle_contact(&self) -> f64 {
        self.slip_after.atan2(self.e_n * self.approach_speed)
    }
}

/// A 3-D impact reduced to its plane of impact ([`Pair::plane`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// The frame.
    pub frame: Frame,
    /// The 2-D incident state in that frame (`v_x = v·t`, `v_z = v·n`, `ω = ω·b`).
    pub incident: Incident,
}

impl Pair {
    #[inline]
    /// Reduce a 3-D impact to its plane of impact.
    ///
    /// The friction impulse acts along the incident slip of the contact point
    /// `u = (v_1 + ω_1 × R_1 n) − (v_2 − ω_2 × R_2 n)`, tangential part `u0 = |u_t|`, direction
    /// `t`, and only changes `v·t` and the spin about `b = n × t`; the normal impulse changes
    /// `v·n`. Every other component (velocity along `b`, spin about `t` and about the normal `n`)
    /// is left untouched: the model has no torsional (spin about the normal) friction.
    pub fn plane(&self, s: &Incident3) -> Result<Plane, InvalidInput> {
        let fields = [
            ("sphere.velocity", s.sphere.velocity),
            ("sphere.spin", s.sphere.spin),
            ("other.velocity", s.other.velocity),
            ("other.spin", s.other.spin),
            ("normal", s.normal),
        ];
        for (name, v) in fields {
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return Err(query(name, *x, "finite components"));
            }
        }
        if self.other.is_none() && s.other != Motion3::default() {
            let named = |name: &'static str, v: Vec3| v.into_iter().map(move |x| (name, x));
            let (name, value) = named("other.velocity", s.other.velocity)
                .chain(named("other.spin", s.other.spin))
                .find(|(_, x)| *x != 0.0)
                .unwrap_or(("other.velocity", s.other.velocity[0]));
            return Err(query(
                name,
                value,
                "zero motion for a fixed wall (velocity = spin = 0)",
            ));
        }
        let len = dot(s.normal, s.normal).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return Err(query("normal", len, "a vector of non-zero, finite length"));
        }
        let n = [s.normal[0] / len, s.normal[1] / len, s.normal[2] / len];
        let r1 = self.sphere.radius;
        let r2 = self.other.map_or(0.0, |o| o.radius);
        // Contact-point velocities: sphere 1's at +R1 n, sphere 2's at −R2 n.
        let c1 = axpy(s.sphere.velocity, r1, cross(s.sphere.spin, n));
        let c2 = axpy(s.other.velocity, -r2, cross(s.other.spin, n));
        let u = sub(c1, c2);
        let u_t = axpy(u, -dot(u, n), n);
        let slip = dot(u_t, u_t).sqrt();
        let tangent = if slip > 0.0 {
            [u_t[0] / slip, u_t[1] / slip, u_t[2] / slip]
        } else {
            any_tangent(sub(s.sphere.velocity, s.other.velocity), n)
        };
        let b = cross(n, tangent);
        let in_plane = |m: &Motion3| State {
            v_x: dot(m.velocity, tangent),
            v_z: dot(m.velocity, n),
            omega: dot(m.spin, b),
        };
        let frame = Frame {
            tangent,
            binormal: b,
            normal: n,
        };
        let mut incident = Incident {
            sphere: in_plane(&s.sphere),
            other: in_plane(&s.other),
        };
        if slip == 0.0 {
            // Make the in-plane slip exactly zero too (the projections could leave a rounding
            // residue): nothing tangential happens, and only differences are applied back.
            incident.sphere.omega = 0.0;
            incident.other.omega = 0.0;
            incident.sphere.v_x = 0.0;
            incident.other.v_x = 0.0;
        }
        Ok(Plane { frame, incident })
    }

    /// The state after a 3-D impact for a given `P` (ignored when `u0 = 0`): the 2-D
    /// [`Pair::rebound`] in the plane of impact ([`Pair::plane`]), its changes applied along `t`,
    /// `n` and about `b`; all other components unchanged.
    pub fn rebound_3d(&self, s: &Incident3, p: f64) -> Result<Rebound3, InvalidInput> {
        self.rebound_3d_dissipative(s, p, 1.0)
    }

    /// [`Pair::rebound_3d`] with normal restitution `e_n ∈ [0, 1]`: the normal relative
    /// velocity reverses with `e_n` ([`Pair::rebound_dissipative`]).
    pub fn rebound_3d_dissipative(
        &self,
        s: &Incident3,
        p: f64,
        e_n: f64,
    ) -> Result<Rebound3, InvalidInput> {
        let plane = self.plane(s)?;
        self.check_incident(&plane.incident)?;
        self.rebound_in_plane_dissipative(s, &plane, p, e_n)
    }

    /// [`Pair::rebound_3d`] for a plane already found by [`Pair::plane`] (`s` is the state the
    /// plane was found from): skips finding the plane again. The plane's incident state is
    /// checked by [`Pair::alpha`]; call that first, as the lookup does.
    #[inline]
    pub fn rebound_in_plane(
        &self,
        s: &Incident3,
        plane: &Plane,
        p: f64,
    ) -> Result<Rebound3, InvalidInput> {
        self.rebound_in_plane_dissipative(s, plane, p, 1.0)
    }

    /// [`Pair::rebound_in_plane`] with normal restitution `e_n ∈ [0, 1]`.
    #[inline]
    pub fn rebound_in_plane_dissipative(
        &self,
        s: &Incident3,
        plane: &Plane,
        p: f64,
        e_n: f64,
    ) -> Result<Rebound3, InvalidInput> {
        let c = self.impulses(&plane.incident, p, check_restitution(e_n)?)?;
        let Frame {
            tangent: t,
            binormal: b,
            normal: n,
        } = plane.frame;
        let apply = |m: &Motion3, before: &State, after: &State| Motion3 {
            velocity: axpy(
                axpy(m.velocity, after.v_x - before.v_x, t),
                after.v_z - before.v_z,
                n,
            ),
            spin: axpy(m.spin, after.omega - before.omega, b),
        };
        let sphere = apply(&s.sphere, &plane.incident.sphere, &c.sphere);
        let other = c
            .other
            .as_ref()
            .map(|o| apply(&s.other, &plane.incident.other, o));
        let rel = |a: &Motion3, b: &Motion3| {
            let w = sub(a.velocity, b.velocity);
            axpy(w, -dot(w, n), n)
        };
        let w0 = rel(&s.sphere, &s.other);
        let w1 = rel(&sphere, other.as_ref().unwrap_or(&Motion3::default()));
        let w0w0 = dot(w0, w0);
        Ok(Rebound3 {
            sphere,
            other,
            frame: plane.frame,
            p: c.p,
            slip_before: c.slip_before,
            slip_after: c.slip_after,
            tangential_impulse: c.tangential_impulse,
            normal_impulse: c.normal_impulse,
            e_n: c.e_n,
            e_t: if w0w0 == 0.0 {
                f64::NAN
            } else {
                dot(w1, w0) / w0w0
            },
            centre_speed_before: w0w0.sqrt(),
            centre_speed_after: dot(w1, w1).sqrt(),
            approach_speed: c.approach_speed,
            energy_lost: c.energy_lost,
        })
    }
}

/// A unit vector perpendicular to the unit `n`: along the tangential part of `w` if it is not
/// zero, else along the axis least aligned with `n`.
fn any_tangent(w: Vec3, n: Vec3) -> Vec3 {
    let w_t = axpy(w, -dot(w, n), n);
    let len = dot(w_t, w_t).sqrt();
    if len > 0.0 {
        return [w_t[0] / len, w_t[1] / len, w_t[2] / len];
    }
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let e_t = axpy(e, -n[k], n);
    let len = dot(e_t, e_t).sqrt();
    [e_t[0] / len, e_t[1] / len, e_t[2] / len]
}
