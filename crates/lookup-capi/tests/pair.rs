//! The table of one pair of materials (`tables/dissipative-pair.h5`: `P(α, e_n)` at a single γ)
//! through the C ABI: `oblique_table_domain` gives its γ as both ends, `oblique_p_e` and
//! `oblique_p` the bits of `Table::p_e` at that γ (and at γ within 5e-10, relative, which the
//! rule takes as the pair's), another γ above the full-slip line is refused with
//! `OBLIQUE_ERR_QUERY` and a message naming `gamma` and the pair's γ (or clamped to it), and the
//! rebounds at the pair's γ give the bits of `Table::rebound_3d`.

use std::ffi::{CStr, CString};

use oblique::{
    oblique_last_error, oblique_p, oblique_p_e, oblique_rebound_wall_e, oblique_table_close,
    oblique_table_domain, oblique_table_open, oblique_table_restitution, ObliqueBody,
    ObliqueContact, ObliqueMaterial, ObliqueMotion, ObliqueRebound, ObliqueTable,
    OBLIQUE_ERR_QUERY, OBLIQUE_OK,
};
use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
use oblique_lookup::{Contact, OutOfDomain, Table};

const PAIR: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tables/dissipative-pair.h5"
);
/// γ of the table (alumina-96 on soda-lime glass).
const GAMMA: f64 = 1.749_785_860_077_429_9;

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

fn last_error() -> String {
    // SAFETY: the library's NUL-terminated message of this thread.
    unsafe { CStr::from_ptr(oblique_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// `oblique_p_e` of the handle `t`: the status and `P` (NaN where it was not written).
fn p_e(t: *const ObliqueTable, gamma: f64, alpha: f64, e_n: f64, clamp: i32) -> (i32, f64) {
    let mut p = f64::NAN;
    // SAFETY: a live handle and a valid out-pointer.
    let rc = unsafe { oblique_p_e(t, gamma, alpha, e_n, clamp, &mut p) };
    (rc, p)
}

#[test]
fn the_c_abi_answers_the_table_of_one_pair_with_the_bits_of_rust() {
    let rust = Table::open(PAIR).expect("the shipped table of one pair");
    let t = open(PAIR);
    let (mut g0, mut g1, mut amax, mut e0, mut e1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    // SAFETY: a live handle and valid out-pointers.
    unsafe {
        assert_eq!(
            oblique_table_domain(t, &mut g0, &mut g1, &mut amax),
            OBLIQUE_OK
        );
        assert_eq!(oblique_table_restitution(t, &mut e0, &mut e1), OBLIQUE_OK);
    }
    assert_eq!((g0, g1), (GAMMA, GAMMA), "a single gamma");
    assert_eq!((e0, e1), (0.5, 1.0));
    let mut u = oblique_lookup::testing::uniform(83);
    let near = [
        GAMMA,
        GAMMA * (1.0 + 5e-10),
        GAMMA * (1.0 - 5e-10),
        GAMMA * (1.0 + 1e-6),
    ];
    let (mut answered, mut refused) = (0, 0);
    for i in 0..20_000 {
        let s = u();
        let alpha = match i % 40 {
            0 => f64::INFINITY,
            1 => 0.0,
            _ => s / (1.0 - s),
        };
        let e_n = 0.5 + 0.5 * u();
        let gamma = near[i % near.len()];
        for (clamp, outside) in [(0, OutOfDomain::Error), (1, OutOfDomain::Clamp)] {
            let (rc, p) = p_e(t, gamma, alpha, e_n, clamp);
            match rust.p_e_with(gamma, alpha, e_n, outside) {
                Ok(want) => {
                    assert_eq!(
                        rc, OBLIQUE_OK,
                        "({gamma:?}, {alpha:?}, {e_n:?}) clamp {clamp}"
                    );
                    assert_eq!(
                        p.to_bits(),
                        want.to_bits(),
                        "({gamma:?}, {alpha:?}, {e_n:?})"
                    );
                    if gamma != near[3] {
                        // Within 5e-10: the pair's answer, to the bit.
                        let at_pair = rust.p_e(GAMMA, alpha, e_n).expect("inside");
                        assert_eq!(p.to_bits(), at_pair.to_bits());
                    }
                    answered += 1;
                }
                Err(err) => {
                    assert_eq!(
                        rc, OBLIQUE_ERR_QUERY,
                        "({gamma:?}, {alpha:?}, {e_n:?}): {err}"
                    );
                    assert!(p.is_nan(), "P written on a refusal");
                    let said = last_error();
                    assert!(
                        said.contains("gamma") && said.contains("1.7497858600774299"),
                        "{said}"
                    );
                    assert_eq!(said, err.to_string());
                    refused += 1;
                }
            }
        }
    }
    assert!(answered > 30_000 && refused > 3000, "{answered} {refused}");
    // oblique_p: the e_n = 1 slice at the pair's γ; another γ refused.
    let mut p = f64::NAN;
    // SAFETY: a live handle and a valid out-pointer.
    unsafe {
        assert_eq!(oblique_p(t, GAMMA, 0.3, 0, &mut p), OBLIQUE_OK);
        assert_eq!(p.to_bits(), rust.p(GAMMA, 0.3).expect("inside").to_bits());
        assert_eq!(
            oblique_p(t, GAMMA * (1.0 + 1e-6), 0.3, 0, &mut p),
            OBLIQUE_ERR_QUERY
        );
    }
    // SAFETY: the handle from `open`, closed once.
    unsafe { oblique_table_close(t) };
}

#[test]
fn wall_rebounds_on_the_table_of_one_pair_give_the_bits_of_rust() {
    let rust = Table::open(PAIR).expect("the shipped table of one pair");
    let t = open(PAIR);
    let mut u = oblique_lookup::testing::uniform(89);
    let (mut compared, mut refused) = (0, 0);
    for case in 0..6 {
        let sphere = Body {
            mass: 1e-4 + 1e-2 * u(),
            radius: 1e-3 + 1e-2 * u(),
            kappa: 0.2 + 0.6 * u(),
        };
        let pair = Pair {
            sphere,
            other: None,
        };
        let gamma = if case == 2 {
            GAMMA * (1.0 + 1e-6)
        } else {
            GAMMA
        };
        let (mu, e_n) = (0.05 + u(), 0.5 + 0.5 * u());
        let contact = Contact::with_gamma(gamma, mu).with_restitution(e_n);
        let none = ObliqueMaterial {
            youngs_modulus: 0.0,
            poisson_ratio: 0.0,
        };
        let cc = ObliqueContact {
            gamma,
            sphere_material: none,
            other_material: none,
            friction: mu,
            clamp: 0,
        };
        let b1 = ObliqueBody {
            mass: sphere.mass,
            radius: sphere.radius,
            kappa: sphere.kappa,
        };
        for _ in 0..200 {
            let mut v3 = |scale: f64| [0; 3].map(|_| scale * (2.0 * u() - 1.0));
            let s = Incident3 {
                sphere: Motion3 {
                    velocity: v3(3.0),
                    spin: v3(500.0),
                },
                other: Motion3::default(),
                normal: v3(1.0),
            };
            let v0: f64 = (0..3).map(|k| s.sphere.velocity[k] * s.normal[k]).sum();
            if v0 <= 1e-3 {
                continue;
            }
            let m1 = ObliqueMotion {
                velocity: s.sphere.velocity,
                spin: s.sphere.spin,
            };
            let mut out = ObliqueRebound::default();
            // SAFETY: a live handle and valid pointers.
            let rc = unsafe {
                oblique_rebound_wall_e(t, &b1, &cc, e_n, &m1, s.normal.as_ptr(), &mut out)
            };
            match rust.rebound_3d(&pair, &contact, &s) {
                Ok(a) => {
                    assert_eq!(rc, OBLIQUE_OK);
                    let b = &a.rebound;
                    let got = [
                        out.sphere.velocity,
                        out.sphere.spin,
                        [out.p, out.energy_lost, out.alpha],
                    ];
                    let want = [
                        b.sphere.velocity,
                        b.sphere.spin,
                        [b.p, b.energy_lost, a.alpha],
                    ];
                    for (x, y) in got.iter().flatten().zip(want.iter().flatten()) {
                        assert_eq!(
                            x.to_bits(),
                            y.to_bits(),
                            "case {case}: C ABI {x:?}, Rust {y:?}"
                        );
                    }
                    compared += 1;
                }
                Err(err) => {
                    assert_eq!(rc, OBLIQUE_ERR_QUERY, "{err}");
                    assert!(last_error().contains("gamma"), "{}", last_error());
                    refused += 1;
                }
            }
        }
    }
    assert!(compared > 300 && refused > 20, "{compared} {refused}");
    // SAFETY: the handle from `open`, closed once.
    unsafe { oblique_table_close(t) };
}

/// `oblique_prepare_table` refuses at once a pair whose γ is not the table's
/// (`OBLIQUE_ERR_QUERY`, naming `gamma`); at the pair's γ, or clamping, it prepares.
#[test]
fn prepare_table_refuses_a_pair_of_another_gamma() {
    use oblique::{oblique_prepare_table, oblique_prepared_free};
    let t = open(PAIR);
    let none = ObliqueMaterial {
        youngs_modulus: 0.0,
        poisson_ratio: 0.0,
    };
    let b1 = ObliqueBody {
        mass: 2.4e-4,
        radius: 2.5e-3,
        kappa: 0.4,
    };
    for (gamma, clamp, want) in [
        (GAMMA, 0, OBLIQUE_OK),
        (GAMMA * (1.0 + 1e-6), 0, OBLIQUE_ERR_QUERY),
        (1.2, 0, OBLIQUE_ERR_QUERY),
        (1.2, 1, OBLIQUE_OK),
    ] {
        let cc = ObliqueContact {
            gamma,
            sphere_material: none,
            other_material: none,
            friction: 0.3,
            clamp,
        };
        let mut k = std::ptr::null_mut();
        // SAFETY: a live handle, valid pointers; the handle made is freed below.
        let rc = unsafe { oblique_prepare_table(t, &b1, std::ptr::null(), &cc, 0.8, &mut k) };
        assert_eq!(rc, want, "gamma {gamma}, clamp {clamp}: {}", last_error());
        if rc == OBLIQUE_OK {
            // SAFETY: the handle made above, freed once.
            unsafe { oblique_prepared_free(k) };
        } else {
            assert!(last_error().contains("gamma"), "{}", last_error());
            assert!(k.is_null());
        }
    }
    // SAFETY: the handle opened above, closed once.
    unsafe { oblique_table_close(t) };
}
