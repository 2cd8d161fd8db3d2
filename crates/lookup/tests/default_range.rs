//! The built-in table (`tables/default.h5`) covers every body of the material catalogue: a
//! solid sphere (κ = 2/5) or a thin shell (κ = 2/3) of any catalogue material on a wall of any
//! (the rigid one included) or on a sphere of the same κ, and 0.3 ≤ e_n ≤ 1. A pair of
//! spheres of different κ needs no check of its own: `m*/m_t = Σ (1 + 1/κ_i)/m_i / Σ 1/m_i`
//! is a weighted mean of `1 + 1/κ_i`, so its γ lies between the γ of the same materials with
//! both spheres solid and both shells.

use oblique_lookup::Table;
use oblique_physics::materials::CATALOGUE;
use oblique_physics::rebound::{Body, Pair};

#[test]
fn the_built_in_table_holds_every_body_of_the_catalogue() {
    let t = Table::embedded().expect("the built-in table");
    let s = t.surface();
    let (lo, hi) = (s.gamma_min(), s.gamma_max());
    assert_eq!(t.restitution(), Some((0.3, 1.0)));
    let (mut g_min, mut g_max, mut n) = (f64::INFINITY, 0.0_f64, 0);
    for kappa in [0.4, 2.0 / 3.0] {
        let body = Body {
            mass: 1.0,
            radius: 1.0,
            kappa,
        };
        for a in CATALOGUE.iter().filter(|m| m.youngs_modulus.is_finite()) {
            for b in CATALOGUE {
                for other in [None, Some(body)].into_iter().filter(|o| {
                    // A rigid body is a wall only.
                    o.is_none() || b.youngs_modulus.is_finite()
                }) {
                    let pair = Pair {
                        sphere: body,
                        other,
                    };
                    let g = pair
                        .gamma_from_materials(&a.elastic(), &b.elastic())
                        .expect("catalogue materials");
                    assert!(
                        (lo..=hi).contains(&g),
                        "{} on {} (kappa {kappa}, other {other:?}): gamma {g} outside [{lo}, {hi}]",
                        a.name,
                        b.name
                    );
                    // Answered at both ends of the e_n range.
                    for e_n in [0.3, 1.0] {
                        let p = t.p_e(g, 0.5, e_n).expect("inside the domain");
                        assert!(p.abs() <= 1.0);
                    }
                    g_min = g_min.min(g);
                    g_max = g_max.max(g);
                    n += 1;
                }
            }
        }
    }
    assert!(n > 100, "{n} bodies");
    eprintln!("{n} catalogue bodies: gamma {g_min:.4} to {g_max:.4}, table [{lo}, {hi}]");
}
