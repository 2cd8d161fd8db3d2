//! Rebounds at a normal restitution `e_n` through the C ABI (`oblique_rebound_wall_e`,
//! `oblique_rebound_spheres_e`, `oblique_prepare_e` or `oblique_prepare_table` +
//! `oblique_rebound_prepared`): the bits of
//! `Table::rebound_3d` with `Contact::with_restitution` on the shipped table with an `e_n` axis
//! (`tables/dissipative-demo.h5`), the bits of the elastic functions at `e_n = 1`, and the
//! refusals (`e_n` outside [0, 1], outside the table's range, an elastic table at `e_n < 1`).

use std::ffi::CString;

use oblique::{
    oblique_prepare, oblique_prepare_e, oblique_prepare_table, oblique_prepared_free,
    oblique_rebound_prepared, oblique_rebound_spheres, oblique_rebound_spheres_e,
    oblique_rebound_wall, oblique_rebound_wall_e, oblique_table_close, oblique_table_open,
    ObliqueBody, ObliqueContact, ObliqueMaterial, ObliqueMotion, ObliquePrepared, ObliqueRebound,
    ObliqueTable, OBLIQUE_ERR_NULL, OBLIQUE_ERR_QUERY, OBLIQUE_OK,
};
use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
use oblique_lookup::{Contact, Table};

const DEMO: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tables/dissipative-demo.h5"
);
const QUICK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tables/quick.h5");

fn open(path: &str) -> *mut ObliqueTable {
    let c = CString::new(path).expect("path");
    let mut t = std::ptr::null_mut();
    // SAFETY: a NUL-terminated path and a valid out-pointer.
    assert_eq!(
        unsafe { oblique_table_open(c.as_ptr(), &mut t) },
        OBLIQUE_OK
    );
    t
}

fn c_body(b: &Body) -> ObliqueBody {
    ObliqueBody {
        mass: b.mass,
        radius: b.radius,
        kappa: b.kappa,
    }
}

fn c_contact(gamma: f64, mu: f64) -> ObliqueContact {
    let m = ObliqueMaterial {
        youngs_modulus: 0.0,
        poisson_ratio: 0.0,
    };
    ObliqueContact {
        gamma,
        sphere_material: m,
        other_material: m,
        friction: mu,
        clamp: 0,
    }
}

fn c_motion(m: &Motion3) -> ObliqueMotion {
    ObliqueMotion {
        velocity: m.velocity,
        spin: m.spin,
    }
}

/// Every field of an answer, to compare bit for bit.
fn fields(r: &ObliqueRebound) -> Vec<f64> {
    [
        r.sphere.velocity,
        r.sphere.spin,
        r.other.velocity,
        r.other.spin,
    ]
    .iter()
    .chain([&r.tangent, &r.binormal, &r.normal])
    .flatten()
    .copied()
    .chain([
        r.gamma,
        r.alpha,
        r.p,
        r.slip_before,
        r.slip_after,
        r.tangential_impulse,
        r.normal_impulse,
        r.e_t,
        r.incidence_angle,
        r.rebound_angle_centre,
        r.rebound_angle_contact,
        r.energy_lost,
    ])
    .collect()
}

fn same(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()))
}

/// The three ways of the C ABI to a rebound at `e_n` (`None`: the elastic functions; the
/// pair prepared for the table at e_n = 1): direct, prepared, prepared for the table.
///
/// # Safety
/// `t` is a live table handle.
unsafe fn c_rebounds(
    t: *const ObliqueTable,
    pair: &Pair,
    contact: &ObliqueContact,
    e_n: Option<f64>,
    s: &Incident3,
) -> [(i32, ObliqueRebound); 3] {
    let b1 = c_body(&pair.sphere);
    let (m1, m2) = (c_motion(&s.sphere), c_motion(&s.other));
    let mut direct = ObliqueRebound::default();
    let rc = match (pair.other.as_ref().map(c_body), e_n) {
        (None, None) => oblique_rebound_wall(t, &b1, contact, &m1, s.normal.as_ptr(), &mut direct),
        (None, Some(e)) => {
            oblique_rebound_wall_e(t, &b1, contact, e, &m1, s.normal.as_ptr(), &mut direct)
        }
        (Some(b2), None) => oblique_rebound_spheres(
            t,
            &b1,
            &b2,
            contact,
            &m1,
            &m2,
            s.normal.as_ptr(),
            &mut direct,
        ),
        (Some(b2), Some(e)) => oblique_rebound_spheres_e(
            t,
            &b1,
            &b2,
            contact,
            e,
            &m1,
            &m2,
            s.normal.as_ptr(),
            &mut direct,
        ),
    };
    let b2 = pair.other.as_ref().map(c_body);
    let b2p = b2
        .as_ref()
        .map_or(std::ptr::null(), |b| b as *const ObliqueBody);
    let mut k: *mut ObliquePrepared = std::ptr::null_mut();
    let rc_k = match e_n {
        None => oblique_prepare(&b1, b2p, contact, &mut k),
        Some(e) => oblique_prepare_e(&b1, b2p, contact, e, &mut k),
    };
    let mut k_t: *mut ObliquePrepared = std::ptr::null_mut();
    let rc_kt = oblique_prepare_table(t, &b1, b2p, contact, e_n.unwrap_or(1.0), &mut k_t);
    let other = if pair.other.is_some() {
        &m2 as *const ObliqueMotion
    } else {
        std::ptr::null()
    };
    let through = |rc_k: i32, k: *mut ObliquePrepared| {
        let mut out = ObliqueRebound::default();
        if rc_k != OBLIQUE_OK {
            return (rc_k, out);
        }
        let rc = oblique_rebound_prepared(t, k, &m1, other, s.normal.as_ptr(), &mut out);
        oblique_prepared_free(k);
        (rc, out)
    };
    [(rc, direct), through(rc_k, k), through(rc_kt, k_t)]
}

/// Random incident states (approaching along the normal), random bodies and contacts.
fn impacts(seed: u64, wall: bool, n: usize) -> (Pair, Vec<Incident3>, f64) {
    let mut u = oblique_lookup::testing::uniform(seed);
    let mut body = || Body {
        mass: 1e-4 + 1e-2 * u(),
        radius: 1e-3 + 1e-2 * u(),
        kappa: 0.2 + 0.6 * u(),
    };
    let pair = Pair {
        sphere: body(),
        other: (!wall).then(&mut body),
    };
    let mut u = oblique_lookup::testing::uniform(seed ^ 0x5eed);
    let mut v3 = |scale: f64| [0; 3].map(|_| scale * (2.0 * u() - 1.0));
    let mut out = Vec::new();
    while out.len() < n {
        let s = Incident3 {
            sphere: Motion3 {
                velocity: v3(3.0),
                spin: v3(500.0),
            },
            other: if wall {
                Motion3::default()
            } else {
                Motion3 {
                    velocity: v3(3.0),
                    spin: v3(500.0),
                }
            },
            normal: v3(1.0),
        };
        let d: f64 = (0..3)
            .map(|k| (s.sphere.velocity[k] - s.other.velocity[k]) * s.normal[k])
            .sum();
        if d > 1e-3 {
            out.push(s);
        }
    }
    let mu = 0.05 + v3(1.0)[0].abs();
    (pair, out, mu)
}

#[test]
fn rebounds_at_e_n_give_the_bits_of_the_rust_library() {
    let rust = Table::open(DEMO).expect("the shipped table with an e_n axis");
    let (e_lo, e_hi) = rust.restitution().expect("an e_n axis");
    let (g_lo, g_hi) = (rust.surface().gamma_min(), rust.surface().gamma_max());
    let t = open(DEMO);
    let mut u = oblique_lookup::testing::uniform(7);
    let (mut compared, mut refused) = (0, 0);
    for case in 0..12u64 {
        let (pair, incidents, mu) = impacts(100 + case, case % 3 == 0, 200);
        let gamma = g_lo + (g_hi - g_lo) * u();
        let e_n = match case {
            0 => e_hi,
            1 => e_lo,
            _ => e_lo + (e_hi - e_lo) * u(),
        };
        let contact = Contact::with_gamma(gamma, mu).with_restitution(e_n);
        let cc = c_contact(gamma, mu);
        for s in &incidents {
            // SAFETY: `t` is live until the end of the test.
            let [(rc, direct), (rc_p, prepared), (rc_t, table_prepared)] =
                unsafe { c_rebounds(t, &pair, &cc, Some(e_n), s) };
            match rust.rebound_3d(&pair, &contact, s) {
                Ok(a) => {
                    assert_eq!((rc, rc_p, rc_t), (OBLIQUE_OK, OBLIQUE_OK, OBLIQUE_OK));
                    let b = &a.rebound;
                    let o = b.other.unwrap_or_default();
                    let want: Vec<f64> = [b.sphere.velocity, b.sphere.spin, o.velocity, o.spin]
                        .iter()
                        .chain([&b.frame.tangent, &b.frame.binormal, &b.frame.normal])
                        .flatten()
                        .copied()
                        .chain([
                            a.gamma,
                            a.alpha,
                            b.p,
                            b.slip_before,
                            b.slip_after,
                            b.tangential_impulse,
                            b.normal_impulse,
                            b.e_t,
                            b.incidence_angle(),
                            b.rebound_angle_centre(),
                            b.rebound_angle_contact(),
                            b.energy_lost,
                        ])
                        .collect();
                    assert!(same(&fields(&direct), &want), "case {case} e_n {e_n:?}");
                    assert!(same(&fields(&prepared), &want), "case {case} e_n {e_n:?}");
                    assert!(
                        same(&fields(&table_prepared), &want),
                        "case {case} e_n {e_n:?}"
                    );
                    assert_eq!(b.e_n, e_n);
                    compared += 1;
                }
                Err(_) => {
                    let refused_all = (OBLIQUE_ERR_QUERY, OBLIQUE_ERR_QUERY, OBLIQUE_ERR_QUERY);
                    assert_eq!((rc, rc_p, rc_t), refused_all);
                    refused += 1;
                }
            }
        }
    }
    // SAFETY: the handle from `open`, closed once.
    unsafe { oblique_table_close(t) };
    assert!(compared > 2000, "{compared} compared, {refused} refused");
}

#[test]
fn e_n_1_gives_the_bits_of_the_elastic_functions_and_bad_e_n_is_refused() {
    let quick = open(QUICK);
    let demo = open(DEMO);
    let rust = Table::open(DEMO).expect("table");
    let (e_lo, _) = rust.restitution().expect("an e_n axis");
    for (case, wall) in [true, false].into_iter().enumerate() {
        let (pair, incidents, mu) = impacts(7 + case as u64, wall, 50);
        let cc = c_contact(1.5, mu);
        for s in &incidents {
            // SAFETY: the handles are live until the end of the test.
            unsafe {
                let [(rc, a), (rc_p, ap), (rc_t, at)] = c_rebounds(quick, &pair, &cc, Some(1.0), s);
                let [(rc0, b), (rc0_p, bp), (rc0_t, bt)] = c_rebounds(quick, &pair, &cc, None, s);
                assert_eq!((rc, rc_p, rc_t), (rc0, rc0_p, rc0_t));
                if rc == OBLIQUE_OK {
                    assert!(same(&fields(&a), &fields(&b)));
                    assert!(same(&fields(&ap), &fields(&bp)));
                    assert!(same(&fields(&at), &fields(&bp)));
                    assert!(same(&fields(&bt), &fields(&bp)));
                }
                // e_n outside [0, 1]: refused by every path; an elastic table at e_n < 1, and
                // the table with the axis below its range, refused when P is needed.
                for e_n in [-0.1, 1.5, f64::NAN, f64::INFINITY] {
                    for (rc, _) in c_rebounds(quick, &pair, &cc, Some(e_n), s) {
                        assert_eq!(rc, OBLIQUE_ERR_QUERY, "e_n {e_n:?}");
                    }
                }
                for (t, e_n) in [(quick, 0.9), (demo, 0.5 * e_lo)] {
                    for (rc, _) in c_rebounds(t, &pair, &cc, Some(e_n), s) {
                        assert_eq!(rc, OBLIQUE_ERR_QUERY, "e_n {e_n:?}");
                    }
                }
            }
        }
    }
    // A pair prepared for no table: NULL is refused, naming it.
    let b = c_body(&impacts(1, true, 1).0.sphere);
    let mut k: *mut ObliquePrepared = std::ptr::null_mut();
    // SAFETY: valid pointers but the NULL table.
    let rc = unsafe {
        oblique_prepare_table(
            std::ptr::null(),
            &b,
            std::ptr::null(),
            &c_contact(1.5, 0.3),
            0.8,
            &mut k,
        )
    };
    assert_eq!(rc, OBLIQUE_ERR_NULL);
    assert!(k.is_null());
    // SAFETY: the handles from `open`, closed once.
    unsafe {
        oblique_table_close(quick);
        oblique_table_close(demo);
    }
}
