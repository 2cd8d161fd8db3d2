//! `oblique_lookup::rebound` (pure algebra from P to the post-impact state) against the
//! simulator's physical-units path, which integrates each body's own equations of motion in SI
//! units. The lookup crate cannot call the simulator, so the comparison lives here.
//!
//! For each impact: the groups (γ, α, m*, m_t, R*) agree; `rebound(P_physical)` reproduces the
//! simulated states; and `rebound(P)` with `P` from the dimensionless `solve(γ, α)` agrees with
//! them within the two error estimates.

use oblique::physics::units::{Material, Motion, PhysicalImpact, Sphere, Target};
use oblique::physics::{solve, Accuracy, Scheme};
use oblique_lookup::rebound::{Body, Elastic, Incident, Pair, State};

const TOL: f64 = 1e-6;

fn elastic(m: &Material) -> Elastic {
    Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
    }
}

fn body(s: &Sphere) -> Body {
    Body {
        mass: s.mass,
        radius: s.radius,
        kappa: s.kappa,
    }
}

fn state(m: &Motion) -> State {
    State {
        v_x: m.v_x,
        v_z: m.v_z,
        omega: m.omega,
    }
}

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
    let (pair, other_mat, other_state) = match &imp.target {
        Target::Wall(m) => (
            Pair {
                sphere: body(&imp.sphere),
                other: None,
            },
            *m,
            State::default(),
        ),
        Target::Sphere(s, m) => (
            Pair {
                sphere: body(&imp.sphere),
                other: Some(body(s)),
            },
            s.material,
            state(m),
        ),
    };
    let inc = Incident {
        sphere: state(&imp.motion),
        other: other_state,
    };
    // Same groups.
    let gamma = pair
        .gamma_from_materials(&elastic(&imp.sphere.material), &elastic(&other_mat))
        .unwrap();
    let alpha = pair.alpha(&inc, imp.friction).unwrap();
    close(gamma, g.gamma, 1e-12 * g.gamma, "gamma");
    close(alpha, g.alpha, 1e-12 * g.alpha, "alpha");
    close(
        pair.normal_mass(),
        g.normal_mass,
        1e-12 * g.normal_mass,
        "m*",
    );
    close(
        pair.tangential_mass(),
        g.tangential_mass,
        1e-12 * g.tangential_mass,
        "m_t",
    );
    close(pair.effective_radius(), g.radius, 1e-15, "R*");
    close(pair.slip_velocity(&inc), g.slip_velocity, 1e-12, "u0");

    let p_phys = phys.p.expect("u0 != 0");
    let u0 = g.slip_velocity.abs();
    let scale_v = u0 + imp.motion.v_z.abs();

    // 1. rebound(P of the physical run) reproduces its states (same impulses).
    let r = pair.rebound(&inc, p_phys).unwrap();
    let bodies: Vec<(State, Motion, Body)> = match (&r.other, &phys.other, &pair.other) {
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
    let sol = solve(
        g.gamma,
        g.alpha,
        Accuracy::Tolerance(TOL),
        Scheme::Accurate,
        false,
    )
    .unwrap();
    let err = sol.error_estimate + phys.error_estimate;
    close(sol.p, p_phys, err + 1e-12, "P (dimensionless vs physical)");
    let r = pair.rebound(&inc, sol.p).unwrap();
    let m_t = pair.tangential_mass();
    let bodies: Vec<(State, Motion, Body)> = match (&r.other, &phys.other, &pair.other) {
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
}

const GLASS: Material = Material {
    youngs_modulus: 73e9,
    poisson_ratio: 0.217,
};
const ALUMINA: Material = Material {
    youngs_modulus: 370e9,
    poisson_ratio: 0.25,
};
const STEEL: Material = Material {
    youngs_modulus: 210e9,
    poisson_ratio: 0.3,
};
const NYLON: Material = Material {
    youngs_modulus: 2.9e9,
    poisson_ratio: 0.39,
};

fn alumina_sphere() -> Sphere {
    let r: f64 = 2.5e-3;
    Sphere {
        radius: r,
        mass: 3720.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
        kappa: 0.4,
        material: ALUMINA,
    }
}

#[test]
fn seed_000_sphere_on_glass_at_several_angles() {
    for deg in [8.0_f64, 20.0, 40.0] {
        let t = deg.to_radians();
        check(&PhysicalImpact {
            sphere: alumina_sphere(),
            motion: Motion {
                v_x: 3.9 * t.sin(),
                v_z: 3.9 * t.cos(),
                omega: 0.0,
            },
            target: Target::Wall(GLASS),
            friction: 0.092,
        });
    }
}

#[test]
fn hollow_spinning_sphere_on_a_wall() {
    check(&PhysicalImpact {
        sphere: Sphere {
            radius: 0.01,
            mass: 0.002,
            kappa: 0.55,
            material: NYLON,
        },
        motion: Motion {
            v_x: 0.3,
            v_z: 1.0,
            omega: -80.0,
        },
        target: Target::Wall(STEEL),
        friction: 0.3,
    });
}

#[test]
fn two_spheres_of_different_size_material_and_spin() {
    check(&PhysicalImpact {
        sphere: alumina_sphere(),
        motion: Motion {
            v_x: 0.8,
            v_z: 1.5,
            omega: 120.0,
        },
        target: Target::Sphere(
            Sphere {
                radius: 6e-3,
                mass: 2.4e-3,
                kappa: 0.4,
                material: STEEL,
            },
            Motion {
                v_x: -0.2,
                v_z: -0.4,
                omega: -50.0,
            },
        ),
        friction: 0.15,
    });
}
