//! Points of any number of axes through the C ABI: `oblique_table_axes` lists the axes of
//! `Table::axes` with their ranges, and `oblique_p_at` gives the bits and the status of
//! `oblique_p` (elastic `tables/full.h5`) or `oblique_p_e` (`tables/default.h5`, with an `e_n`
//! axis) at every point; a point of another length is `OBLIQUE_ERR_QUERY` naming the axes.

use std::ffi::{CStr, CString};

use oblique::{
    oblique_last_error, oblique_p, oblique_p_at, oblique_p_e, oblique_table_axes,
    oblique_table_close, oblique_table_open, ObliqueTable, OBLIQUE_ERR_NULL, OBLIQUE_ERR_QUERY,
    OBLIQUE_OK,
};
use oblique_lookup::Table;

fn path(name: &str) -> String {
    format!("{}/../../tables/{name}.h5", env!("CARGO_MANIFEST_DIR"))
}

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
    // SAFETY: the library's NUL-terminated thread-local message.
    unsafe { CStr::from_ptr(oblique_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// A deterministic generator of numbers in `[0, 1)`.
fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn p_at_gives_the_bits_of_p_and_p_e() {
    for name in ["default", "full"] {
        let t = Table::open(path(name)).expect("shipped table");
        let c = open(&path(name));
        // The axes and their ranges.
        let mut n = 0usize;
        let mut names = [std::ptr::null(); 4];
        let (mut lo, mut hi) = ([0.0; 4], [0.0; 4]);
        // SAFETY: a live handle and out-arrays of 4 entries.
        let rc = unsafe {
            oblique_table_axes(
                c,
                &mut n,
                names.as_mut_ptr(),
                lo.as_mut_ptr(),
                hi.as_mut_ptr(),
                4,
            )
        };
        assert_eq!(rc, OBLIQUE_OK);
        let axes: Vec<String> = names[..n]
            .iter()
            // SAFETY: static NUL-terminated names.
            .map(|&p| unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
            .collect();
        assert_eq!(axes, t.axes(), "{name}");
        let s = t.surface();
        assert_eq!((lo[0], hi[0]), (s.gamma_min(), s.gamma_max()));
        assert_eq!((lo[1], hi[1]), (0.0, s.alpha_max()));
        if n == 3 {
            assert_eq!(Some((lo[2], hi[2])), t.restitution());
        }
        // SAFETY: NULL out-pointer for the count.
        let rc = unsafe {
            oblique_table_axes(
                c,
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                std::ptr::null_mut(),
                0,
            )
        };
        assert_eq!(rc, OBLIQUE_ERR_NULL);
        // Points: γ a little beyond the domain, α log-uniform and ∞, e_n in range.
        let (e0, e1) = t.restitution().unwrap_or((1.0, 1.0));
        let mut r = rng(52);
        for i in 0..20_000 {
            let g = s.gamma_min() + (s.gamma_max() - s.gamma_min()) * (1.1 * r() - 0.05);
            let a = if i % 13 == 0 {
                f64::INFINITY
            } else {
                10f64.powf(-3.0 + 4.0 * r())
            };
            let e = e0 + (e1 - e0) * r();
            let point = [g, a, e];
            let clamp = i % 2;
            let (mut x, mut y) = (f64::NAN, f64::NAN);
            // SAFETY: a live handle, a point of n values and valid out-pointers.
            let (rx, ry) = unsafe {
                (
                    oblique_p_at(c, point.as_ptr(), n, clamp, &mut x),
                    if n == 3 {
                        oblique_p_e(c, g, a, e, clamp, &mut y)
                    } else {
                        oblique_p(c, g, a, clamp, &mut y)
                    },
                )
            };
            assert_eq!(rx, ry, "{name} {point:?}");
            if rx == OBLIQUE_OK {
                assert_eq!(x.to_bits(), y.to_bits(), "{name} {point:?}");
            }
        }
        // A point of another length names the axes.
        for wrong in [0, 1, n - 1, n + 1, 1000] {
            let point = [1.5, 0.3, 0.9, 1.0];
            let mut p = 0.0;
            // SAFETY: at most 4 values are read (the longest point of any table is 3).
            let rc = unsafe { oblique_p_at(c, point.as_ptr(), wrong, 0, &mut p) };
            assert_eq!(rc, OBLIQUE_ERR_QUERY, "{name} n = {wrong}");
            let m = last_error();
            assert!(m.contains(&t.axes().join(", ")), "{m}");
        }
        // SAFETY: NULL pointers are refused.
        let rc = unsafe { oblique_p_at(c, std::ptr::null(), 2, 0, &mut 0.0) };
        assert_eq!(rc, OBLIQUE_ERR_NULL);
        // SAFETY: the handle is closed once.
        unsafe { oblique_table_close(c) };
    }
}
