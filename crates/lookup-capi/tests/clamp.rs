//! `clamp` through the C ABI: 0 or 1, every other value refused with `OBLIQUE_ERR_QUERY` and a
//! message naming `clamp` (a C caller's `clamp = -1` or `2` was read as "clamp" silently), in
//! every function that takes it, with nothing written to the outputs.

use std::ffi::{CStr, CString};

use oblique::{
    oblique_curve_free, oblique_curve_new, oblique_last_error, oblique_p, oblique_p_batch,
    oblique_p_e, oblique_prepare, oblique_rebound_wall, oblique_table_close, oblique_table_open,
    ObliqueBody, ObliqueContact, ObliqueMaterial, ObliqueMotion, ObliqueRebound, OBLIQUE_ERR_QUERY,
    OBLIQUE_OK,
};

const QUICK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tables/quick.h5");

fn last_error() -> String {
    // SAFETY: the library returns a NUL-terminated string valid until the next failing call.
    unsafe { CStr::from_ptr(oblique_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn refused(what: &str, rc: i32) {
    assert_eq!(rc, OBLIQUE_ERR_QUERY, "{what}");
    let m = last_error();
    assert!(
        m.contains("clamp") && m.contains("0") && m.contains("1"),
        "{what}: {m}"
    );
}

#[test]
fn clamp_other_than_0_or_1_is_refused_naming_it() {
    let path = CString::new(QUICK).expect("path");
    let mut table = std::ptr::null_mut();
    // SAFETY: valid pointers throughout; the handles are freed below.
    unsafe {
        assert_eq!(oblique_table_open(path.as_ptr(), &mut table), OBLIQUE_OK);
        // Outside the domain (γ = 3 > 2.5, above the line): clamp decides.
        let (g, a) = (3.0, 0.3);
        let mut p = 7.0;
        assert!(oblique_p(table, g, a, 0, &mut p) != OBLIQUE_OK);
        assert_eq!(oblique_p(table, g, a, 1, &mut p), OBLIQUE_OK);
        assert!(p.abs() <= 1.0);
        for clamp in [2, -1, i32::MAX, i32::MIN] {
            let mut p = 7.0;
            refused("oblique_p", oblique_p(table, g, a, clamp, &mut p));
            refused("oblique_p inside", oblique_p(table, 1.5, a, clamp, &mut p));
            refused("oblique_p_e", oblique_p_e(table, g, a, 1.0, clamp, &mut p));
            assert_eq!(p, 7.0, "nothing written");
            let (gs, al, mut out) = ([1.5, g], [a, a], [7.0; 2]);
            let rc = oblique_p_batch(table, gs.as_ptr(), al.as_ptr(), 2, clamp, out.as_mut_ptr());
            refused("oblique_p_batch", rc);
            assert_eq!(out, [7.0; 2], "nothing written");
            let mut curve = std::ptr::null_mut();
            refused(
                "oblique_curve_new",
                oblique_curve_new(table, 1.5, clamp, &mut curve),
            );
            assert!(curve.is_null());
            let sphere = ObliqueBody {
                mass: 1e-3,
                radius: 5e-3,
                kappa: 0.4,
            };
            let steel = ObliqueMaterial {
                youngs_modulus: 210e9,
                poisson_ratio: 0.29,
            };
            let contact = ObliqueContact {
                gamma: 1.5,
                sphere_material: steel,
                other_material: steel,
                friction: 0.3,
                clamp,
            };
            let motion = ObliqueMotion {
                velocity: [1.0, 0.0, 2.0],
                spin: [0.0; 3],
            };
            let normal = [0.0, 0.0, 1.0];
            let mut out = ObliqueRebound::default();
            let rc =
                oblique_rebound_wall(table, &sphere, &contact, &motion, normal.as_ptr(), &mut out);
            refused("oblique_rebound_wall", rc);
            let mut prepared = std::ptr::null_mut();
            refused(
                "oblique_prepare",
                oblique_prepare(&sphere, std::ptr::null(), &contact, &mut prepared),
            );
            assert!(prepared.is_null());
        }
        let mut curve = std::ptr::null_mut();
        assert_eq!(oblique_curve_new(table, 1.5, 1, &mut curve), OBLIQUE_OK);
        oblique_curve_free(curve);
        oblique_table_close(table);
    }
}
