//! `oblique_lookup::rebound` (pure algebra from P to the post-impact state) against the
//! simulator's physical-units path, which integrates each body's own equations of motion in SI
//! units. The lookup crate cannot call the simulator, so the comparison lives here.
//!
//! For each impact: the groups (γ, α, m*, m_t, R*) agree; `rebound(P_physical)` reproduces the
//! simulated states; and `rebound(P)` with `P` from the dimensionless `solve(γ, α)` agrees with
//! them within the two error estimates; `Table::rebound` (2-D) and `Table::rebound_3d` (the same
//! impact embedded in a rotated 3-D frame, with extra spin about the normal) answered from
//! `tables/full.h5` agree with the simulation within the table's stated error plus the
//! simulation's.

use oblique_solver::units::PhysicalImpact;
use oblique_solver::{Accuracy, Request};
use std::sync::OnceLock;

use oblique_lookup::rebound::{Body, Elastic, Incident, Incident3, Motion3, Pair, State, Vec3};
use oblique_lookup::{Contact, Table};

fn table() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| {
        Table::open(concat!(env!("CARGO_MANIFEST_DIR"), "/tables/full.h5")).expect("full.h5")
    })
}

/// A right-handed frame `(x, y = z × x, z)` tilted away from the axes.
fn frame() -> (Vec3, Vec3, Vec3) {
    let unit = |v: Vec3| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [v[0] / l, v[1] / l, v[2] / l]
    };
    let z = unit([0.3, -0.5, 0.81]);
    let w = [1.0, 0.2, -0.1];
    let wz = w[0] * z[0] + w[1] * z[1] + w[2] * z[2];
    let x = unit([w[0] - wz * z[0], w[1] - wz * z[1], w[2] - wz * z[2]]);
    let y = [
        z[1] * x[2] - z[2] * x[1],
        z[2] * x[0] - z[0] * x[2],
        z[0] * x[1] - z[1] * x[0],
    ];
    (x, y, z)
}

const TOL: f64 = 1e-6;

fn close(a: f64, b: f64, abs: f64, what: &str) {
    assert!(
        (a - b).abs() <= abs,
        "{what}: {a} vs {b} (diff {:.3e} > {abs:.3e})",
        (a - b).abs()
    );
}

fn check(imp: &PhysicalImpact) {
    let phys = imp.solve(TOL).expect("physical simulation");
    let g = phys.groups;
    let (pair, inc) = (imp.pair, imp.incident);
    let [sphere_mat, other_mat] = imp.materials;
    // The groups, by the formulas of physics.md written out here (not the library's code):
    // 1/E* = Σ (1 − ν²)/E, 1/G* = Σ (2 − ν)/(4G), m* = m1 m2/(m1 + m2),
    // 1/m_t = Σ (1/m + R²/I), γ² = (m*/m_t) G*/E*, α = (2/7)(m*/m_t) μ v_z0/|u0|.
    let e_inv = |m: &Elastic| (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus;
    let g_inv = |m: &Elastic| {
        (2.0 - m.poisson_ratio) * 2.0 * (1.0 + m.poisson_ratio) / (4.0 * m.youngs_modulus)
    };
    let e_star = 1.0 / (e_inv(&sphere_mat) + e_inv(&other_mat));
    let g_star = 1.0 / (g_inv(&sphere_mat) + g_inv(&other_mat));
    let b1 = pair.sphere;
    let t_inv = |b: &Body| 1.0 / b.mass + 1.0 / (b.kappa * b.mass);
    let (m_star, m_t, r_star, v_z0, u0) = match pair.other {
        None => (
            b1.mass,
            1.0 / t_inv(&b1),
            b1.radius,
            inc.sphere.v_z,
            inc.sphere.v_x + b1.radius * inc.sphere.omega,
        ),
        Some(b2) => (
            b1.mass * b2.mass / (b1.mass + b2.mass),
            1.0 / (t_inv(&b1) + t_inv(&b2)),
            b1.radius * b2.radius / (b1.radius + b2.radius),
            inc.sphere.v_z - inc.other.v_z,
            (inc.sphere.v_x + b1.radius * inc.sphere.omega)
                - (inc.other.v_x - b2.radius * inc.other.omega),
        ),
    };
    let gamma = (m_star / m_t * g_star / e_star).sqrt();
    let alpha = 2.0 / 7.0 * m_star / m_t * imp.friction * v_z0 / u0.abs();
    close(gamma, g.gamma, 1e-12 * g.gamma, "gamma");
    close(alpha, g.alpha, 1e-12 * g.alpha, "alpha");
    close(e_star, g.e_star, 1e-12 * g.e_star, "E*");
    close(g_star, g.g_star, 1e-12 * g.g_star, "G*");
    close(m_star, g.normal_mass, 1e-12 * g.normal_mass, "m*");
    close(m_t, g.tangential_mass, 1e-12 * g.tangential_mass, "m_t");
    close(r_star, g.radius, 1e-15, "R*");
    close(v_z0, g.approach_speed, 1e-12 * v_z0, "v_z0");
    close(u0, g.slip_velocity, 1e-12 * u0.abs(), "u0");

    let p_phys = phys.p.expect("u0 != 0");
    let u0 = g.slip_velocity.abs();
    let scale_v = u0 + imp.incident.sphere.v_z.abs();

    // 1. rebound(P of the physical run) reproduces its states (same impulses).
    let r = pair.rebound(&inc, p_phys).unwrap();
    let bodies: Vec<(State, State, Body)> = match (&r.other, &phys.other, &pair.other) {
        (Some(a), Some(b), Some(c)) => vec![(r.sphere, phys.sphere, pair.sphere), (*a, *b, *c)],
        _ => vec![(r.sphere, phys.sphere, pair.sphere)],
    };
    for (mine, sim, b) in &bodies {
        close(mine.v_x, sim.v_x, 1e-9 * scale_v, "v_x (same P)");
        close(mine.v_z, sim.v_z, 1e-8 * scale_v, "v_z (same P)");
        close(
            mine.omega,
            sim.omega,
            1e-9 * scale_v / b.radius,
            "omega (same P)",
        );
    }

    // 2. rebound(P from the dimensionless solver) agrees within the error estimates.
    let sol = Request::new(g.gamma, g.alpha)
        .accuracy(Accuracy::Tolerance(TOL))
        .solve()
        .unwrap();
    let err = sol.error_estimate + phys.error_estimate;
    close(sol.p, p_phys, err + 1e-12, "P (dimensionless vs physical)");
    let r = pair.rebound(&inc, sol.p).unwrap();
    let m_t = pair.tangential_mass();
    let bodies: Vec<(State, State, Body)> = match (&r.other, &phys.other, &pair.other) {
        (Some(a), Some(b), Some(c)) => vec![(r.sphere, phys.sphere, pair.sphere), (*a, *b, *c)],
        _ => vec![(r.sphere, phys.sphere, pair.sphere)],
    };
    for (mine, sim, b) in &bodies {
        // |ΔJ| = m_t |ΔP| |u0|; Δv_x = ΔJ/m, Δω = ΔJ R/I.
        let dj = m_t * (err + 1e-12) * u0;
        close(mine.v_x, sim.v_x, dj / b.mass + 1e-9 * scale_v, "v_x");
        close(mine.v_z, sim.v_z, 1e-8 * scale_v, "v_z");
        close(
            mine.omega,
            sim.omega,
            dj * b.radius / b.inertia() + 1e-9 * scale_v / b.radius,
            "omega",
        );
    }

    // 3. From the table, in 2-D and embedded in 3-D: within the table's error + the simulation's.
    let t = table();
    let contact = Contact::with_materials(sphere_mat, other_mat, imp.friction);
    let a = t.rebound(&pair, &contact, &inc).expect("table rebound");
    close(a.gamma, g.gamma, 1e-12 * g.gamma, "gamma (table)");
    close(a.alpha, g.alpha, 1e-12 * g.alpha, "alpha (table)");
    let err = t.error_bound() + phys.error_estimate;
    close(a.rebound.p, p_phys, err, "P (table vs physical)");
    let (x, y, z) = frame();
    let spin_n = [25.0, -60.0];
    let lift = |s: &State, k: usize| Motion3 {
        velocity: [
            s.v_x * x[0] + s.v_z * z[0],
            s.v_x * x[1] + s.v_z * z[1],
            s.v_x * x[2] + s.v_z * z[2],
        ],
        spin: [
            s.omega * y[0] + spin_n[k] * z[0],
            s.omega * y[1] + spin_n[k] * z[1],
            s.omega * y[2] + spin_n[k] * z[2],
        ],
    };
    let inc3 = Incident3 {
        sphere: lift(&inc.sphere, 0),
        other: if pair.other.is_some() {
            lift(&inc.other, 1)
        } else {
            Motion3::default()
        },
        normal: z,
    };
    let a3 = t
        .rebound_3d(&pair, &contact, &inc3)
        .expect("table rebound 3-D");
    close(a3.rebound.p, a.rebound.p, 1e-9, "P (3-D vs 2-D)");
    let dot = |a: Vec3, b: Vec3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut bodies3: Vec<(Motion3, State, Body, usize)> =
        vec![(a3.rebound.sphere, phys.sphere, pair.sphere, 0)];
    if let (Some(m), Some(sim), Some(b)) = (a3.rebound.other, phys.other, pair.other) {
        bodies3.push((m, sim, b, 1));
    }
    let dj = m_t * err * u0;
    for (mine, sim, b, k) in &bodies3 {
        let (vx, vz, wy) = (
            dot(mine.velocity, x),
            dot(mine.velocity, z),
            dot(mine.spin, y),
        );
        close(
            vx,
            sim.v_x,
            dj / b.mass + 1e-9 * scale_v,
            "v_x (table, 3-D)",
        );
        close(vz, sim.v_z, 1e-8 * scale_v, "v_z (table, 3-D)");
        close(
            wy,
            sim.omega,
            dj * b.radius / b.inertia() + 1e-9 * scale_v / b.radius,
            "omega (table, 3-D)",
        );
        close(dot(mine.velocity, y), 0.0, 1e-12 * scale_v, "v_y (3-D)");
        close(
            dot(mine.spin, z),
            spin_n[*k],
            1e-9,
            "spin about the normal (3-D)",
        );
    }
}

const GLASS: Elastic = Elastic {
    youngs_modulus: 73e9,
    poisson_ratio: 0.217,
};
const ALUMINA: Elastic = Elastic {
    youngs_modulus: 370e9,
    poisson_ratio: 0.25,
};
const STEEL: Elastic = Elastic {
    youngs_modulus: 210e9,
    poisson_ratio: 0.3,
};
const NYLON: Elastic = Elastic {
    youngs_modulus: 2.9e9,
    poisson_ratio: 0.39,
};

/// An alumina sphere (its material is [`ALUMINA`]).
fn alumina_sphere() -> Body {
    let r: f64 = 2.5e-3;
    Body {
        radius: r,
        mass: 3720.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
        kappa: 0.4,
    }
}

#[test]
fn seed_000_sphere_on_glass_at_several_angles() {
    for deg in [8.0_f64, 20.0, 40.0] {
        let t = deg.to_radians();
        check(&PhysicalImpact {
            pair: Pair {
                sphere: alumina_sphere(),
                other: None,
            },
            materials: [ALUMINA, GLASS],
            incident: Incident {
                sphere: State {
                    v_x: 3.9 * t.sin(),
                    v_z: 3.9 * t.cos(),
                    omega: 0.0,
                },
                other: State::default(),
            },
            friction: 0.092,
            law: Default::default(),
        });
    }
}

#[test]
fn hollow_spinning_sphere_on_a_wall() {
    check(&PhysicalImpact {
        pair: Pair {
            sphere: Body {
                radius: 0.01,
                mass: 0.002,
                kappa: 0.55,
            },
            other: None,
        },
        materials: [NYLON, STEEL],
        incident: Incident {
            sphere: State {
                v_x: 0.3,
                v_z: 1.0,
                omega: -80.0,
            },
            other: State::default(),
        },
        friction: 0.3,
        law: Default::default(),
    });
}

#[test]
fn two_spheres_of_different_size_material_and_spin() {
    check(&PhysicalImpact {
        pair: Pair {
            sphere: alumina_sphere(),
            other: Some(Body {
                radius: 6e-3,
                mass: 2.4e-3,
                kappa: 0.4,
            }),
        },
        materials: [ALUMINA, STEEL],
        incident: Incident {
            sphere: State {
                v_x: 0.8,
                v_z: 1.5,
                omega: 120.0,
            },
            other: State {
                v_x: -0.2,
                v_z: -0.4,
                omega: -50.0,
            },
        },
        friction: 0.15,
        law: Default::default(),
    });
}
