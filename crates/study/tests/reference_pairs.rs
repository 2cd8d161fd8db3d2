//! Sphere–sphere impacts beyond the suites (two materials, unequal radii, both bodies moving
//! and spinning, both signs of slip): every quantity of every convention from the universal
//! mapping agrees with the direct two-body simulation in SI units within the summed bounds.

use oblique_lookup::rebound::{Incident, State};
use oblique_study::reference::columns::{quantities, value};
use oblique_study::reference::eval::{outcome, Method};
use oblique_study::reference::spec::{Ball, Case, Convention, Material, Setup, Target};

const ALUMINA: Material = Material {
    name: "alumina",
    youngs_modulus: 380e9,
    poisson_ratio: 0.23,
    density: 4000.0,
};
const AL_ALLOY: Material = Material {
    name: "aluminium alloy",
    youngs_modulus: 70e9,
    poisson_ratio: 0.33,
    density: 2700.0,
};
const STEEL: Material = Material {
    name: "steel",
    youngs_modulus: 208e9,
    poisson_ratio: 0.30,
    density: 7850.0,
};
const NYLON: Material = Material {
    name: "nylon",
    youngs_modulus: 2.5e9,
    poisson_ratio: 0.40,
    density: 1000.0,
};

const CONVENTIONS: [Convention; 7] = [
    Convention::ChungOoiAngle,
    Convention::ChungOoiNormalised,
    Convention::ChungOoiSpin,
    Convention::ChungOoiNoSlip,
    Convention::Mfix,
    Convention::Seed000,
    Convention::Thornton,
];

#[test]
fn mixed_sphere_pairs_agree_with_direct_simulation() {
    let pairs = [
        (ALUMINA, 2.5e-3, AL_ALLOY, 6e-3, 0.15),
        (STEEL, 5e-3, NYLON, 2e-3, 0.3),
        (NYLON, 0.1, ALUMINA, 0.04, 0.4),
    ];
    // (v_x, v_z, ω) of sphere 1 and sphere 2 (m/s, rad/s, scaled by the radii below).
    let motions = [
        ([1.0, 2.0, 0.0], [0.0, 0.0, 0.0]),
        ([0.3, 1.5, 40.0], [-0.2, -0.5, -25.0]),
        ([-0.8, 0.9, -10.0], [0.1, 0.2, 60.0]),
        ([0.05, 3.0, 0.0], [0.0, -1.0, 0.0]),
        ([2.0, 0.4, 0.0], [0.0, 0.0, 0.0]),
    ];
    let mut checked = 0;
    let mut regimes = std::collections::BTreeSet::new();
    let mut signs = std::collections::BTreeSet::new();
    for (m1, r1, m2, r2, mu) in pairs {
        let setup = Setup {
            label: "pair",
            sphere: Ball {
                material: m1,
                radius: r1,
            },
            target: Target::Sphere(Ball {
                material: m2,
                radius: r2,
            }),
            friction: mu,
            yield_pressure: None,
        };
        for (a, b) in motions {
            // Spins scaled so that R ω is of the order of the speeds.
            let inc = Incident {
                sphere: State {
                    v_x: a[0],
                    v_z: a[1],
                    omega: a[2] * 2.5e-3 / r1,
                },
                other: State {
                    v_x: b[0],
                    v_z: b[1],
                    omega: b[2] * 2.5e-3 / r2,
                },
            };
            let case = Case {
                x: 0.0,
                incident: inc,
            };
            let map = outcome(&setup, &case, &Method::Slice { tol: 1e-8 }).expect("mapping");
            let direct = outcome(&setup, &case, &Method::Direct { tol: 1e-8 }).expect("direct");
            regimes.insert(map.regime.map_or("normal", |r| r.name()));
            signs.insert(setup.pair().slip_velocity(&inc) > 0.0);
            assert!(
                (map.post.p - direct.post.p).abs() <= map.p_error + direct.p_error,
                "P: {} {} ({:?})",
                map.post.p,
                direct.post.p,
                inc
            );
            for conv in CONVENTIONS {
                for q in quantities(conv, true) {
                    let (va, ea) = value(&q, &setup, &map);
                    let (vb, eb) = value(&q, &setup, &direct);
                    if !va.is_finite() && !vb.is_finite() {
                        continue;
                    }
                    let bound = ea + eb + 1e-12 * va.abs();
                    assert!(
                        (va - vb).abs() <= bound,
                        "{}: mapping {va}, direct {vb}, bound {bound} ({m1:?} on {m2:?}, {inc:?})",
                        q.name
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 500, "{checked}");
    for r in ["full-slip", "partial-slip", "stick"] {
        assert!(regimes.contains(r), "{regimes:?}");
    }
    assert_eq!(signs.len(), 2, "both signs of the incident slip");
}
