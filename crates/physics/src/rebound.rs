//! From `P` to the state after the impact: pure algebra, no table and no simulation.
//!
//! Two bodies in the plane of the impact: sphere 1 and either a fixed wall or a free sphere 2.
//! SI units throughout (m, kg, s, Pa, rad/s, J). Conventions (the same as the simulator's
//! physical-units path):
//!
//! - `z` is the common normal pointing from sphere 1 into the other body (`v_z > 0` approaches),
//!   `x` the tangent.
//! - A spin `ω` is signed so that sphere 1's contact point moves at `v_x + R ω`; sphere 2's
//!   contact point, on its other side, moves at `v_x − R ω`. Both are the same component of the
//!   angular velocity vector (`ŷ = ẑ × x̂`). In 3-D that component is the spin along the
//!   binormal `b = n × t` of the plane of impact ([`Frame`]), not along a fixed lab axis: for a
//!   sphere on a floor below it (`n = (0, 0, −1)` with the lab's `z` up) slipping along `+x`,
//!   `b = (0, −1, 0)` and the 2-D `ω` is `−ω_y` of the lab.
//! - The slip velocity is `u = (v_1x + R_1 ω_1) − (v_2x − R_2 ω_2)` (for a wall, `u = v_x + R ω`).
//! - The friction impulse `J` acts on body 2 along `+x` and on body 1 along `−x`:
//!   `m_1 Δv_1x = −J`, `I_1 Δω_1 = −J R_1`, `m_2 Δv_2x = +J`, `I_2 Δω_2 = −J R_2`, so that
//!   `Δu = −J/m_t` with `1/m_t = Σ (1/m + R²/I)`.
//!
//! Given `P = u_after/u_before`, `J = m_t (1 − P) u0`. The relative approach velocity reverses
//! with the normal restitution `e_n` (1 for elastic bodies), normal impulse `(1 + e_n) m* v_z0`
//! with `m* = m_1 m_2/(m_1 + m_2)` (`m_1` for a wall). The energy lost is
//! `(m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²)`: to friction (and, for dissipative
//! bodies, tangential damping; `P` carries both) and to normal damping.
//!
//! The groups that decide `P` (`physics.md`): `γ² = (m*/m_t) G*/E*` and
//! `α = (2/7)(m*/m_t) μ v_z0/|u0|`; for one solid sphere on a wall `m*/m_t = 7/2`.
//!
//! The bodies and their materials are in `bodies.rs`, the impact in its plane in `planar.rs`,
//! the 3-D impact reduced to that plane in `spatial.rs`.

mod bodies;
mod planar;
mod spatial;

use thiserror::Error;

pub use crate::vec3::Vec3;
pub use bodies::{effective_moduli, Body, Elastic};
pub use planar::{Incident, Pair, Rebound, State};
pub use spatial::{Frame, Incident3, Motion3, Plane, Rebound3};

/// A physical input outside its range: names the field, the value and the allowed range.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("invalid {name} = {value:?}: must be {allowed}")]
pub struct InvalidInput {
    /// Field name.
    pub name: &'static str,
    /// The value given.
    pub value: f64,
    /// The allowed range, in words.
    pub allowed: String,
}

/// The error of `name = value` outside `allowed`.
fn query(name: &'static str, value: f64, allowed: &str) -> InvalidInput {
    InvalidInput {
        name,
        value,
        allowed: allowed.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GLASS: Elastic = Elastic {
        youngs_modulus: 7.3e10,
        poisson_ratio: 0.217,
    };
    const ALUMINA: Elastic = Elastic {
        youngs_modulus: 3.7e11,
        poisson_ratio: 0.25,
    };

    fn solid(mass: f64, radius: f64) -> Body {
        Body {
            mass,
            radius,
            kappa: 0.4,
        }
    }

    #[test]
    fn seed_000_gamma_and_moduli() {
        let (e, g) = effective_moduli(&ALUMINA, &GLASS);
        // Seed 000, §4, quotes E* ≈ 6.42e10 Pa, G* ≈ 5.64e10 Pa and γ ≈ 1.754. The formulas
        // give E* = 6.415e10, G* = 5.612e10 and γ = 1.7498: the quoted G* is 0.5 % high, and γ
        // follows it. Both are checked here.
        assert!((e / 6.42e10 - 1.0).abs() < 1e-3, "E* = {e}");
        assert!((g / 5.64e10 - 1.0).abs() < 6e-3, "G* = {g}");
        assert!((g / 5.612_149e10 - 1.0).abs() < 1e-6, "G* = {g}");
        let pair = Pair {
            sphere: solid(2.6e-4, 2.5e-3),
            other: None,
        };
        let gamma = pair.gamma_from_materials(&ALUMINA, &GLASS).unwrap();
        assert!((gamma - 1.754).abs() < 5e-3, "gamma = {gamma}");
        assert!((gamma - 1.749_786).abs() < 1e-6, "gamma = {gamma}");
        assert!((pair.mass_ratio() - 3.5).abs() < 1e-14);
    }

    #[test]
    fn an_approach_speed_that_overflows_is_refused() {
        // Each velocity is finite, their difference is not: v_z0 = 1e308 − (−1e308) = ∞.
        let pair = Pair {
            sphere: solid(0.01, 0.02),
            other: Some(solid(0.01, 0.02)),
        };
        let state = |v_z| State {
            v_x: 1.0,
            v_z,
            omega: 0.0,
        };
        let s = Incident {
            sphere: state(1e308),
            other: state(-1e308),
        };
        for e in [
            pair.alpha(&s, 0.3).unwrap_err(),
            pair.rebound(&s, 0.5).unwrap_err(),
        ] {
            assert_eq!(e.name, "v_z");
            assert!(e.value.is_infinite(), "{e}");
            assert!(e.to_string().contains("finite approach speed"), "{e}");
        }
        let ok = Incident {
            sphere: state(1e307),
            other: state(-1e307),
        };
        assert!(pair.alpha(&ok, 0.3).is_ok());
    }

    #[test]
    fn solid_sphere_without_spin_matches_the_closed_forms() {
        let (m, r) = (0.01, 0.02);
        let pair = Pair {
            sphere: solid(m, r),
            other: None,
        };
        let s = Incident {
            sphere: State {
                v_x: 2.0,
                v_z: 3.0,
                omega: 0.0,
            },
            ..Default::default()
        };
        let p = -0.3;
        let out = pair.rebound(&s, p).unwrap();
        assert!((out.e_t - (2.0 * p + 5.0) / 7.0).abs() < 1e-14);
        assert!((out.sphere.omega - 5.0 * 2.0 * (p - 1.0) / (7.0 * r)).abs() < 1e-12);
        assert_eq!(out.sphere.v_z, -3.0);
        assert!((out.energy_lost - m * 4.0 * (1.0 - p * p) / 7.0).abs() < 1e-15);
        // Energy balance from the states themselves.
        let ke = |st: &State| {
            0.5 * m * (st.v_x * st.v_x + st.v_z * st.v_z)
                + 0.5 * pair.sphere.inertia() * st.omega * st.omega
        };
        assert!((ke(&s.sphere) - ke(&out.sphere) - out.energy_lost).abs() < 1e-15);
        // α = μ v_z0/|u0| for a solid sphere.
        assert!((pair.alpha(&s, 0.2).unwrap() - 0.2 * 3.0 / 2.0).abs() < 1e-15);
        // Contact-point angle reverses sign with P.
        assert!(out.rebound_angle_contact < 0.0 && out.rebound_angle_centre > 0.0);
    }

    #[test]
    fn sphere_sphere_conserves_momentum_and_angular_momentum_about_the_contact() {
        let pair = Pair {
            sphere: Body {
                mass: 0.3,
                radius: 0.01,
                kappa: 0.4,
            },
            other: Some(Body {
                mass: 1.7,
                radius: 0.03,
                kappa: 0.55,
            }),
        };
        let s = Incident {
            sphere: State {
                v_x: 1.2,
                v_z: 2.0,
                omega: -30.0,
            },
            other: State {
                v_x: -0.4,
                v_z: -0.5,
                omega: 12.0,
            },
        };
        let out = pair.rebound(&s, 0.37).unwrap();
        let o = out.other.unwrap();
        let (b1, b2) = (pair.sphere, pair.other.unwrap());
        let px = |a: &State, b: &State| b1.mass * a.v_x + b2.mass * b.v_x;
        let pz = |a: &State, b: &State| b1.mass * a.v_z + b2.mass * b.v_z;
        // About the contact point: sphere 1's centre at z = −R1, sphere 2's at z = +R2;
        // L_y = Σ (z m v_x) + I ω.
        let l = |a: &State, b: &State| {
            -b1.radius * b1.mass * a.v_x
                + b1.inertia() * a.omega
                + b2.radius * b2.mass * b.v_x
                + b2.inertia() * b.omega
        };
        let rel = |x: f64, y: f64| (x - y).abs() / x.abs().max(y.abs());
        assert!(rel(px(&s.sphere, &s.other), px(&out.sphere, &o)) < 1e-12);
        assert!(rel(pz(&s.sphere, &s.other), pz(&out.sphere, &o)) < 1e-12);
        assert!(rel(l(&s.sphere, &s.other), l(&out.sphere, &o)) < 1e-12);
        // Normal relative velocity reverses; slip velocity scales by P.
        assert!(((out.sphere.v_z - o.v_z) + (s.sphere.v_z - s.other.v_z)).abs() < 1e-14);
        let after = Incident {
            sphere: out.sphere,
            other: o,
        };
        assert!((pair.slip_velocity(&after) - 0.37 * pair.slip_velocity(&s)).abs() < 1e-13);
    }

    #[test]
    fn pure_normal_impact_leaves_the_tangential_state() {
        let pair = Pair {
            sphere: solid(1.0, 1.0),
            other: None,
        };
        let s = Incident {
            sphere: State {
                v_x: 0.0,
                v_z: 1.0,
                omega: 0.0,
            },
            ..Default::default()
        };
        assert_eq!(pair.alpha(&s, 0.1).unwrap(), f64::INFINITY);
        let out = pair.rebound(&s, f64::NAN).unwrap();
        assert_eq!(out.sphere.v_x, 0.0);
        assert_eq!(out.sphere.omega, 0.0);
        assert_eq!(out.energy_lost, 0.0);
        assert!(out.p.is_nan() && out.e_t.is_nan());
    }

    #[test]
    fn dissipative_rebounds_balance_momentum_and_energy() {
        // Sphere–sphere, both moving and spinning, in 2-D and in 3-D: momentum conserved, the
        // relative normal velocity reversed with e_n, the kinetic energy lost equal to
        // (m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²); e_n = 1 is the elastic rebound's bits.
        let pair = Pair {
            sphere: solid(2.0, 0.5),
            other: Some(Body {
                mass: 3.0,
                radius: 0.8,
                kappa: 0.55,
            }),
        };
        let s = Incident {
            sphere: State {
                v_x: 0.7,
                v_z: 2.0,
                omega: 1.5,
            },
            other: State {
                v_x: -0.2,
                v_z: -0.4,
                omega: -0.6,
            },
        };
        let kinetic = |st: &State, b: &Body| {
            0.5 * b.mass * (st.v_x * st.v_x + st.v_z * st.v_z)
                + 0.5 * b.inertia() * st.omega * st.omega
        };
        let b2 = pair.other.unwrap();
        let before = kinetic(&s.sphere, &pair.sphere) + kinetic(&s.other, &b2);
        for (p, e_n) in [(0.3, 0.6), (-0.5, 0.9), (1.0, 0.3), (0.2, 0.0)] {
            let r = pair.rebound_dissipative(&s, p, e_n).unwrap();
            let o = r.other.unwrap();
            let v0 = s.sphere.v_z - s.other.v_z;
            assert!(((r.sphere.v_z - o.v_z) + e_n * v0).abs() < 1e-14);
            for (a, b) in [(s.sphere.v_x, r.sphere.v_x), (s.sphere.v_z, r.sphere.v_z)]
                .iter()
                .zip([(s.other.v_x, o.v_x), (s.other.v_z, o.v_z)])
                .map(|((a1, a2), (b1, b2))| (2.0 * a1 + 3.0 * b1, 2.0 * a2 + 3.0 * b2))
            {
                assert!((a - b).abs() < 1e-13);
            }
            let after = kinetic(&r.sphere, &pair.sphere) + kinetic(&o, &b2);
            assert!(
                (before - after - r.energy_lost).abs() < 1e-13 * before,
                "{before} − {after} vs {}",
                r.energy_lost
            );
            assert!((r.slip_after - p * r.slip_before).abs() < 1e-14);
            assert_eq!(r.e_n, e_n);
            assert!(r.rebound_angle_contact == r.slip_after.atan2(e_n * v0));
        }
        let elastic = pair.rebound(&s, 0.3).unwrap();
        let one = pair.rebound_dissipative(&s, 0.3, 1.0).unwrap();
        assert_eq!(format!("{elastic:?}"), format!("{one:?}"));
        for bad in [-0.1, 1.1, f64::NAN] {
            let err = pair.rebound_dissipative(&s, 0.3, bad).unwrap_err();
            assert_eq!(err.name, "e_n");
        }
    }

    #[test]
    fn rigid_wall_and_bad_input() {
        let (e, g) = effective_moduli(&ALUMINA, &Elastic::RIGID);
        let nu = ALUMINA.poisson_ratio;
        assert!((g / e - 2.0 * (1.0 - nu) / (2.0 - nu)).abs() < 1e-14);
        let pair = Pair {
            sphere: solid(1.0, 1.0),
            other: None,
        };
        assert!(pair
            .gamma_from_materials(&Elastic::RIGID, &Elastic::RIGID)
            .is_err());
        let away = Incident {
            sphere: State {
                v_x: 1.0,
                v_z: -1.0,
                omega: 0.0,
            },
            ..Default::default()
        };
        let err = pair.rebound(&away, 0.5).unwrap_err().to_string();
        assert!(err.contains("v_z"), "{err}");
    }
}
