//! The quantities each suite reports, as functions of the state before and after an impact,
//! with their error bounds.
//!
//! Notation (physics.md): `V_cn` is the relative normal approach speed `v_1z − v_2z`, `V'_cn`
//! the separation speed after (equal for the elastic model, `e_n = 1`), `V_st = u0` the slip
//! velocity of the contact points before, `V'_st = P u0` after. Centre quantities are relative
//! (`v_1x − v_2x`); on a wall, sphere 1's own.

use oblique_lookup::rebound::Incident;

use super::eval::{Outcome, Post};
use super::spec::{Convention, Setup};

/// A quantity of the state after the impact.
#[derive(Debug, Clone, Copy)]
pub struct Quantity {
    /// CSV column (its error bound is the column `NAME_err`).
    pub name: &'static str,
    /// Axis label, with symbol and unit.
    pub label: &'static str,
    /// Its value.
    pub value: fn(&Ctx) -> f64,
}

/// What a quantity is computed from.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    /// The bodies.
    pub setup: &'a Setup,
    /// The state before.
    pub incident: &'a Incident,
    /// The state after.
    pub post: &'a Post,
    /// Normal restitution of the impact (1: elastic).
    pub e_n: f64,
}

impl Ctx<'_> {
    fn v_cn(&self) -> f64 {
        self.incident.sphere.v_z - self.incident.other.v_z
    }
    fn v_cn_after(&self) -> f64 {
        -(self.post.sphere.v_z - self.post.other.map_or(0.0, |o| o.v_z))
    }
    fn slip_before(&self) -> f64 {
        self.setup.pair().slip_velocity(self.incident)
    }
    fn slip_after(&self) -> f64 {
        let after = Incident {
            sphere: self.post.sphere,
            other: self.post.other.unwrap_or_default(),
        };
        self.setup.pair().slip_velocity(&after)
    }
    fn centre_before(&self) -> f64 {
        self.incident.sphere.v_x - self.incident.other.v_x
    }
    fn centre_after(&self) -> f64 {
        self.post.sphere.v_x - self.post.other.map_or(0.0, |o| o.v_x)
    }
    fn mu_v_cn(&self) -> f64 {
        self.setup.friction * self.v_cn()
    }
}

const P: Quantity = Quantity {
    name: "P",
    label: "P = V'_st/V_st",
    value: |c| c.post.p,
};
const E_T: Quantity = Quantity {
    name: "e_t",
    label: "e_t = v'_x/v_x (centre)",
    value: |c| c.centre_after() / c.centre_before(),
};
const E_T_ABS: Quantity = Quantity {
    name: "e_t",
    label: "e_t = |v'_t|/|v_t| (centre)",
    value: |c| c.centre_after().abs() / c.centre_before().abs(),
};
const OMEGA: Quantity = Quantity {
    name: "omega_rad_s",
    label: "ω' (rad/s)",
    value: |c| c.post.sphere.omega,
};
const OMEGA_ABS: Quantity = Quantity {
    name: "omega_abs_rad_s",
    label: "|ω'| (rad/s)",
    value: |c| c.post.sphere.omega.abs(),
};
const OMEGA_2: Quantity = Quantity {
    name: "omega_2_rad_s",
    label: "ω'_2 (rad/s)",
    value: |c| c.post.other.map_or(f64::NAN, |o| o.omega),
};
const V_X: Quantity = Quantity {
    name: "v_x_m_s",
    label: "v'_x (m/s)",
    value: |c| c.post.sphere.v_x,
};
const V_X_2: Quantity = Quantity {
    name: "v_x_2_m_s",
    label: "v'_x2 (m/s)",
    value: |c| c.post.other.map_or(f64::NAN, |o| o.v_x),
};
const V_Z: Quantity = Quantity {
    name: "v_z_m_s",
    label: "v'_z (m/s)",
    value: |c| c.post.sphere.v_z,
};
const ANGLE_CONTACT: Quantity = Quantity {
    name: "rebound_angle_contact_deg",
    label: "contact-point rebound angle (°)",
    value: |c| c.slip_after().atan2(c.v_cn_after()).to_degrees(),
};
const ANGLE_CENTRE: Quantity = Quantity {
    name: "rebound_angle_centre_deg",
    label: "centre rebound angle (°)",
    value: |c| c.centre_after().atan2(c.v_cn_after()).to_degrees(),
};
const ANGLE_CENTRE_ABS: Quantity = Quantity {
    name: "rebound_angle_deg",
    label: "rebound angle atan(|v'_t|/v'_n) (°)",
    value: |c| c.centre_after().abs().atan2(c.v_cn_after()).to_degrees(),
};
const RECOIL_NORMALISED: Quantity = Quantity {
    name: "recoil_normalised",
    label: "V'_st/(μ V'_cn)",
    value: |c| c.slip_after() / (c.setup.friction * c.v_cn_after()),
};
const SPIN_NORMALISED: Quantity = Quantity {
    name: "spin_normalised",
    label: "R ω'/(μ V_cn)",
    value: |c| c.setup.sphere.radius * c.post.sphere.omega / c.mu_v_cn(),
};
const FRICTION_RATIO: Quantity = Quantity {
    name: "friction_ratio",
    label: "3.5 μ (1 + e) V_cn/V_st",
    // 3.5 (1 + e_n) is 7 exactly at e_n = 1: the elastic value's bits.
    value: |c| 3.5 * (1.0 + c.e_n) * c.mu_v_cn() / c.slip_before(),
};
const BETA: Quantity = Quantity {
    name: "beta",
    label: "β = −V'_st/V_st",
    value: |c| -c.slip_after() / c.slip_before(),
};
const TAN_INCIDENCE: Quantity = Quantity {
    name: "tan_incidence",
    label: "V_st/V_cn",
    value: |c| c.slip_before() / c.v_cn(),
};
const TAN_RECOIL: Quantity = Quantity {
    name: "tan_recoil",
    label: "V'_st/V'_cn",
    value: |c| c.slip_after() / c.v_cn_after(),
};
const SLIP_ANGLE: Quantity = Quantity {
    name: "slip_angle_deg",
    label: "90° − θ (°)",
    value: |c| 90.0 - c.centre_before().atan2(c.v_cn()).to_degrees(),
};
// 2x/((1 + e) y) is x/y to the bit at e = 1 (both doublings are exact).
const PSI2: Quantity = Quantity {
    name: "psi2",
    label: "Ψ₂ = 2V'_st/(μ(1+e)V_n)",
    value: |c| 2.0 * c.slip_after() / ((1.0 + c.e_n) * c.mu_v_cn()),
};
const OMEGA2_NORMALISED: Quantity = Quantity {
    name: "spin_normalised",
    label: "2Rω'/(μ(1+e)V_n)",
    value: |c| 2.0 * (c.setup.sphere.radius * c.post.sphere.omega) / ((1.0 + c.e_n) * c.mu_v_cn()),
};

/// The quantities of a convention, in CSV order; the first ones are plotted.
pub fn quantities(conv: Convention, sphere_sphere: bool) -> Vec<Quantity> {
    match conv {
        Convention::ChungOoiAngle => vec![E_T, OMEGA, ANGLE_CONTACT, ANGLE_CENTRE, P],
        Convention::ChungOoiNormalised => vec![RECOIL_NORMALISED, SPIN_NORMALISED, E_T, OMEGA, P],
        Convention::ChungOoiSpin => {
            let mut q = vec![
                BETA,
                TAN_RECOIL,
                OMEGA,
                FRICTION_RATIO,
                TAN_INCIDENCE,
                V_X,
                P,
            ];
            if sphere_sphere {
                q.extend([OMEGA_2, V_X_2]);
            }
            q
        }
        Convention::ChungOoiNoSlip => vec![V_X, OMEGA, V_X_2, OMEGA_2, V_Z],
        Convention::Mfix => vec![E_T_ABS, OMEGA_ABS, ANGLE_CENTRE_ABS, P],
        Convention::Seed000 => vec![E_T, OMEGA, ANGLE_CONTACT, ANGLE_CENTRE, SLIP_ANGLE, P],
        Convention::Thornton => vec![PSI2, OMEGA2_NORMALISED, E_T, P],
    }
}

/// The figure's x axis where a suite plots against a quantity rather than the swept value:
/// Chung & Ooi's tests 6 and 8 plot against `3.5 μ (1 + e) V_cn/V_st`, on which the gross-slip
/// line is straight (`β = x − 1`).
pub fn figure_x(conv: Convention) -> Option<Quantity> {
    match conv {
        Convention::ChungOoiSpin => Some(FRICTION_RATIO),
        _ => None,
    }
}

/// How many of a convention's quantities the figure shows.
pub fn plotted(conv: Convention) -> usize {
    match conv {
        Convention::ChungOoiNormalised | Convention::Thornton => 2,
        Convention::ChungOoiNoSlip => 2,
        // β against Chung & Ooi's abscissa; the other columns vary over decades on it.
        Convention::ChungOoiSpin => 1,
        _ => 3,
    }
}

/// A quantity's value and error bound for an outcome: the largest change over `P ± error`
/// (every quantity is monotonic in `P`) and, for a direct simulation, the difference to the
/// rebound algebra at its own `P` (its error in the normal motion).
pub fn value(q: &Quantity, setup: &Setup, o: &Outcome) -> (f64, f64) {
    let at = |post: &Post| {
        (q.value)(&Ctx {
            setup,
            incident: &o.case.incident,
            post,
            e_n: o.e_n,
        })
    };
    let v = at(&o.post);
    let err = o
        .bracket
        .iter()
        .map(|b| (at(b) - v).abs())
        .filter(|e| e.is_finite())
        .fold(0.0, f64::max);
    (v, err)
}

/// A quantity evaluated at another `P` (the approximations drawn beside the model).
pub fn at_p(q: &Quantity, setup: &Setup, o: &Outcome, p: f64) -> f64 {
    match setup.pair().rebound_dissipative(&o.case.incident, p, o.e_n) {
        Ok(r) => (q.value)(&Ctx {
            setup,
            incident: &o.case.incident,
            post: &Post {
                sphere: r.sphere,
                other: r.other,
                p: r.p,
            },
            e_n: o.e_n,
        }),
        Err(_) => f64::NAN,
    }
}
