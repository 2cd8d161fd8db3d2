//! 3-D rebounds for a pair of bodies and a contact checked once: [`Prepared`].
//!
//! A DEM code meets the same pair of materials, radii and masses over and over; validating them
//! and computing `γ` from the elastic constants (`E*`, `G*`, a square root) costs more than the
//! table lookup. [`Prepared::new`] does that once ([`Table::prepare`] too, and for a table with
//! an `e_n` axis it also computes the pair's `P(α)` through the table once, [`crate::line`]);
//! [`Table::rebound_3d_prepared`] then checks
//! only the incident state and answers with as few divisions and square roots as the algebra
//! allows (one square root and one division for the normal, one each for the slip direction,
//! one division for `α`). It computes what [`Pair::plane`] and [`Pair::rebound_3d`] compute,
//! rearranged: the slip `u0` is the length `|u_t|` of the tangential slip itself rather than its
//! projection on `t`, and the changes of the velocities and spins are applied as `−J/m_1 t`
//! etc. rather than as differences of 2-D states. The answers agree up to rounding (the tests
//! compare them at 1e-13 of the velocity scale). Inputs the fast path does not handle itself
//! (any invalid input, which then gets the error [`Table::rebound_3d`] gives, and a contact point
//! that does not slip, `u0 = 0`) are passed to the step-by-step path.

use std::sync::Arc;

use crate::line::PairLine;
use crate::rebound::{Frame, Incident3, Motion3, Pair, Rebound3};
use crate::{Answer, Contact, Curve, LookupError, OutOfDomain, Table};
use oblique_physics::vec3::{axpy, cross, dot, scale, sub};

/// A pair of bodies with its contact, validated and reduced once, for many 3-D rebounds
/// ([`Table::rebound_3d_prepared`], [`Table::rebound_3d_batch`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Prepared {
    pair: Pair,
    contact: Contact,
    gamma: f64,
    /// `(2/7)(m*/m_t) μ`, so that `α = alpha_scale · v_z0/|u0|`.
    alpha_scale: f64,
    /// `m_t` (kg).
    tangential_mass: f64,
    /// `(1 + e_n) m*` (kg): the normal impulse per unit approach speed (`2 m*` elastic).
    two_normal_mass: f64,
    /// `(m*/2)(1 − e_n²)` (kg): the normal energy lost per unit squared approach speed.
    normal_loss: f64,
    /// `1/m_1`, `R_1/I_1`, `R_1` and the same for sphere 2 (zero for a wall).
    inv_m1: f64,
    spin1: f64,
    r1: f64,
    inv_m2: f64,
    spin2: f64,
    r2: f64,
    /// `P(α)` of this pair through the table it was prepared for ([`Table::prepare`], a table
    /// with an `e_n` axis), shared by the clones.
    line: Option<Arc<PairLine>>,
}

#[cold]
fn friction_error(mu: f64) -> LookupError {
    LookupError::Query {
        name: "friction",
        value: mu,
        allowed: ">= 0 (or inf for no slip)".into(),
    }
}

impl Prepared {
    /// Check `pair` (masses, radii, inertia factors) and `contact` (`γ` or the materials,
    /// `μ ≥ 0`) and precompute what every rebound of this pair needs (`γ`, the reduced masses).
    pub fn new(pair: &Pair, contact: &Contact) -> Result<Prepared, LookupError> {
        pair.validate()?;
        let gamma = contact.gamma(pair)?;
        let mu = contact.friction;
        if mu.is_nan() || mu < 0.0 {
            return Err(friction_error(mu));
        }
        let e_n = contact.restitution;
        if !(0.0..=1.0).contains(&e_n) {
            return Err(LookupError::Query {
                name: "e_n",
                value: e_n,
                allowed: "in [0, 1] (and in the table's e_n range)".into(),
            });
        }
        // The same operations, in the same order, as `Pair::alpha_checked` and
        // `Pair::impulses`, so that α, J and the normal impulse have the same bits.
        let alpha_scale = 2.0 / 7.0 * pair.mass_ratio() * mu;
        let b1 = &pair.sphere;
        let (inv_m2, spin2, r2) = pair.other.as_ref().map_or((0.0, 0.0, 0.0), |b2| {
            (1.0 / b2.mass, b2.radius / b2.inertia(), b2.radius)
        });
        Ok(Prepared {
            pair: *pair,
            contact: *contact,
            gamma,
            alpha_scale,
            tangential_mass: pair.tangential_mass(),
            two_normal_mass: (1.0 + contact.restitution) * pair.normal_mass(),
            normal_loss: 0.5
                * pair.normal_mass()
                * (1.0 - contact.restitution * contact.restitution),
            inv_m1: 1.0 / b1.mass,
            spin1: b1.radius / b1.inertia(),
            r1: b1.radius,
            inv_m2,
            spin2,
            r2,
            line: None,
        })
    }

    /// The pair of bodies.
    pub fn pair(&self) -> &Pair {
        &self.pair
    }

    /// The contact (stiffness, friction, out-of-domain choice).
    pub fn contact(&self) -> &Contact {
        &self.contact
    }

    /// `γ` of this pair (dimensionless).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// Bytes held for the table this pair was prepared for ([`Table::prepare`]; 0 without).
    pub fn table_bytes(&self) -> usize {
        self.line.as_ref().map_or(0, |l| l.bytes())
    }
}

#[cold]
fn curve_mismatch(curve: &Curve, prepared: &Prepared) -> LookupError {
    LookupError::Query {
        name: "curve gamma",
        value: curve.requested_gamma(),
        allowed: format!(
            "the prepared pair's gamma = {} and e_n = {} with its out-of-domain choice {:?}: \
             build the curve with table.curve_e(prepared.gamma(), prepared.contact().restitution, \
             prepared.contact().outside)",
            prepared.gamma, prepared.contact.restitution, prepared.contact.outside
        ),
    }
}

/// `true` when every component of the incident state is finite (one pass, no early exit).
#[inline(always)]
fn all_finite(s: &Incident3) -> bool {
    let m = |m: &Motion3| {
        m.velocity
            .iter()
            .chain(&m.spin)
            .fold(true, |ok, x| ok & x.is_finite())
    };
    m(&s.sphere) & m(&s.other) & s.normal.iter().fold(true, |ok, x| ok & x.is_finite())
}

impl Table {
    /// [`Prepared::new`] for rebounds through this table, refusing at once an `e_n` the table
    /// does not answer ([`Table::p_e`]) and, for the table of one pair, a pair of another `γ`
    /// (unless the contact clamps: then every rebound answers at the pair's `γ`); its rebounds
    /// would be refused above the full-slip line. For a table with an `e_n` axis it also computes the
    /// pair's `P(α)` at its `(γ, e_n)` once ([`Table::rebound_3d_prepared`] then answers with
    /// the same bits in fewer operations: the leaf's sum over `e_n` and the `γ`- and
    /// `e_n`-only parts of the rule are done here, a few kB per pair,
    /// [`Prepared::table_bytes`]). The result works with any table; with another one than
    /// this (or its clones) it answers as [`Prepared::new`]'s does.
    pub fn prepare(&self, pair: &Pair, contact: &Contact) -> Result<Prepared, LookupError> {
        let mut k = Prepared::new(pair, contact)?;
        let surface = self.surface();
        surface.check_e_n(contact.restitution)?;
        if let (Some(g), OutOfDomain::Error) = (surface.pair_gamma(), contact.outside) {
            if surface.rule_gamma(k.gamma) != g {
                return Err(surface.gamma_outside(k.gamma));
            }
        }
        k.line = PairLine::new(
            self.id(),
            self.surface(),
            k.gamma,
            contact.restitution,
            contact.outside,
        )
        .map(Arc::new);
        Ok(k)
    }

    /// [`Table::rebound_3d`] for a [`Prepared`] pair and contact: only the incident state is
    /// checked, and the algebra is shortened (the same answer up to rounding; the same `P`).
    #[inline]
    pub fn rebound_3d_prepared(
        &self,
        prepared: &Prepared,
        s: &Incident3,
    ) -> Result<Answer<Rebound3>, LookupError> {
        if let Some(line) = prepared.line.as_deref().filter(|l| l.serves(self.id())) {
            return self.rebound_3d_fast(prepared, s, |alpha| line.p(self.surface(), alpha));
        }
        self.rebound_3d_fast(prepared, s, |alpha| {
            self.p_e_with(
                prepared.gamma,
                alpha,
                prepared.contact.restitution,
                prepared.contact.outside,
            )
        })
    }

    /// [`Table::rebound_3d_prepared`] with `P` from `curve`, a [`Curve`] of this table built
    /// at the pair's `γ` with the contact's out-of-domain choice
    /// (`table.curve(prepared.gamma(), prepared.contact().outside)`): the same answer to about
    /// 1e-15 in `P`, without the table's quadtree on the query path. A curve built for another
    /// `γ` or domain choice is refused.
    #[inline]
    pub fn rebound_3d_curve(
        &self,
        prepared: &Prepared,
        curve: &Curve,
        s: &Incident3,
    ) -> Result<Answer<Rebound3>, LookupError> {
        if !curve.matches(prepared.gamma, prepared.contact.outside)
            || curve.e_n() != prepared.contact.restitution
        {
            return Err(curve_mismatch(curve, prepared));
        }
        self.rebound_3d_fast(prepared, s, |alpha| curve.p(alpha))
    }

    /// The shortened algebra of [`Table::rebound_3d_prepared`] with `P(α)` from `p_of`.
    #[inline(always)]
    fn rebound_3d_fast(
        &self,
        prepared: &Prepared,
        s: &Incident3,
        p_of: impl Fn(f64) -> Result<f64, LookupError>,
    ) -> Result<Answer<Rebound3>, LookupError> {
        let k = prepared;
        let wall = k.pair.other.is_none();
        if !all_finite(s) || (wall && s.other != Motion3::default()) {
            return self.rebound_3d_reference(k, s);
        }
        let len = dot(s.normal, s.normal).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return self.rebound_3d_reference(k, s);
        }
        let n = scale(1.0 / len, s.normal);
        // Slip of the contact point: sphere 1's at +R1 n, sphere 2's at −R2 n.
        let (m1, m2) = (&s.sphere, &s.other);
        let c1 = axpy(m1.velocity, k.r1, cross(m1.spin, n));
        let c2 = axpy(m2.velocity, -k.r2, cross(m2.spin, n));
        let u = sub(c1, c2);
        let u_t = axpy(u, -dot(u, n), n);
        let slip = dot(u_t, u_t).sqrt();
        if !(slip > 0.0 && slip.is_finite()) {
            // u0 = 0 (a pure normal impact; the tangent is chosen otherwise) or overflow.
            return self.rebound_3d_reference(k, s);
        }
        let t = scale(1.0 / slip, u_t);
        let b = cross(n, t);
        // The approach speed and the slip (`u0 = |u_t| > 0` along `t`) in the plane of impact.
        let v0 = if wall {
            dot(m1.velocity, n)
        } else {
            dot(sub(m1.velocity, m2.velocity), n)
        };
        let u0 = slip;
        if v0.is_nan() || v0 <= 0.0 {
            return self.rebound_3d_reference(k, s);
        }
        let alpha = k.alpha_scale * v0 / u0;
        let alpha = if alpha.is_nan() { f64::INFINITY } else { alpha };
        let p = p_of(alpha)?;
        // Impulses along +t and +n on body 2 (body 1 receives the opposite).
        let j = k.tangential_mass * (1.0 - p) * u0;
        let nn = k.two_normal_mass * v0;
        let sphere = Motion3 {
            velocity: axpy(axpy(m1.velocity, -j * k.inv_m1, t), -nn * k.inv_m1, n),
            spin: axpy(m1.spin, -j * k.spin1, b),
        };
        let other = (!wall).then(|| Motion3 {
            velocity: axpy(axpy(m2.velocity, j * k.inv_m2, t), nn * k.inv_m2, n),
            spin: axpy(m2.spin, -j * k.spin2, b),
        });
        // Tangential relative centre velocity before and after (the normal impulse has no
        // tangential part).
        let d = sub(m1.velocity, m2.velocity);
        let w_before = axpy(d, -dot(d, n), n);
        let w_after = axpy(w_before, -j * (k.inv_m1 + k.inv_m2), t);
        let w0w0 = dot(w_before, w_before);
        Ok(Answer {
            gamma: k.gamma,
            alpha,
            rebound: Rebound3 {
                sphere,
                other,
                frame: Frame {
                    tangent: t,
                    binormal: b,
                    normal: n,
                },
                p,
                slip_before: u0,
                slip_after: p * u0,
                tangential_impulse: j,
                normal_impulse: nn,
                e_n: k.contact.restitution,
                e_t: if w0w0 == 0.0 {
                    f64::NAN
                } else {
                    dot(w_after, w_before) / w0w0
                },
                centre_speed_before: w0w0.sqrt(),
                centre_speed_after: dot(w_after, w_after).sqrt(),
                approach_speed: v0,
                energy_lost: 0.5 * k.tangential_mass * u0 * u0 * (1.0 - p * p)
                    + if k.normal_loss == 0.0 {
                        0.0
                    } else {
                        k.normal_loss * v0 * v0
                    },
            },
        })
    }

    /// The step-by-step path ([`Pair::plane`], then [`Pair::rebound_3d`]'s algebra), for the
    /// inputs the fast path leaves to it: invalid ones (it names the field) and `u0 = 0`.
    #[cold]
    #[inline(never)]
    fn rebound_3d_reference(
        &self,
        k: &Prepared,
        s: &Incident3,
    ) -> Result<Answer<Rebound3>, LookupError> {
        self.rebound_3d_steps(&k.pair, &k.contact, s)
    }

    /// [`Table::rebound_3d_prepared`] for every incident state of a slice, in order:
    /// `out[i]` answers `incidents[i]`. The slices must have the same length; on the first
    /// invalid state the error ([`LookupError::Batch`]) names its index, and `out` before that
    /// index is filled, after it untouched.
    pub fn rebound_3d_batch(
        &self,
        prepared: &Prepared,
        incidents: &[Incident3],
        out: &mut [Answer<Rebound3>],
    ) -> Result<(), LookupError> {
        crate::batch::check_length("out", out.len(), incidents.len())?;
        crate::batch::serial(incidents, out, |s| self.rebound_3d_prepared(prepared, s))
    }

    /// [`Table::rebound_3d_batch`] in parallel on the current rayon pool (chunks of 4096). If
    /// some states are invalid, the error names the lowest invalid index; `out` is then filled
    /// only partly.
    #[cfg(feature = "rayon")]
    pub fn rebound_3d_batch_par(
        &self,
        prepared: &Prepared,
        incidents: &[Incident3],
        out: &mut [Answer<Rebound3>],
    ) -> Result<(), LookupError> {
        crate::batch::check_length("out", out.len(), incidents.len())?;
        crate::batch::parallel(incidents, out, |s| self.rebound_3d_prepared(prepared, s))
    }
}
