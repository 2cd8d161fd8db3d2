//! `|P| ≤ 1` through the C ABI (`oblique_p`, `oblique_p_batch`): on 1e6 random queries of the
//! shipped `tables/full.h5` (γ ∈ [0.1, 3.5], α ∈ [0, 20]) with the point where it answered
//! P = −1.000008644 before the bound (the Rust paths: `crates/lookup/tests/energy.rs`).

use std::ffi::CString;

use oblique::{oblique_p, oblique_p_batch, oblique_table_close, oblique_table_open};

const FULL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tables/full.h5");

/// Where the table of before the bound answered P = −1.000008644 (simulation: −0.999998276).
const OVERSHOOT: (f64, f64) = (2.829218718427729, 5.60402202817959);

const QUERIES: usize = 1_000_000;

/// `n` queries uniform in γ ∈ [0.1, 3.5], α ∈ [0, 20], after the overshooting point.
fn queries(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut next = oblique_lookup::testing::uniform(seed);
    let mut g = vec![OVERSHOOT.0];
    let mut a = vec![OVERSHOOT.1];
    for _ in 1..n {
        g.push(0.1 + 3.4 * next());
        a.push(20.0 * next());
    }
    (g, a)
}

fn assert_bounded(what: &str, g: &[f64], a: &[f64], p: &[f64]) {
    let bad = p.iter().position(|x| x.is_nan() || x.abs() > 1.0);
    if let Some(i) = bad {
        panic!("{what}: P({}, {}) = {} (|P| > 1)", g[i], a[i], p[i]);
    }
}

#[test]
fn the_c_abi_answers_no_p_beyond_one() {
    let path = CString::new(FULL).expect("path");
    let mut table = std::ptr::null_mut();
    // SAFETY: valid NUL-terminated path and out-pointer; the handle is closed below.
    unsafe {
        assert_eq!(oblique_table_open(path.as_ptr(), &mut table), 0);
        let mut p = f64::NAN;
        assert_eq!(oblique_p(table, OVERSHOOT.0, OVERSHOOT.1, 0, &mut p), 0);
        assert!(p.abs() <= 1.0, "oblique_p: P = {p}");
        let (g, a) = queries(QUERIES, 0x5EED_0004);
        let mut out = vec![f64::NAN; g.len()];
        let rc = oblique_p_batch(table, g.as_ptr(), a.as_ptr(), g.len(), 0, out.as_mut_ptr());
        assert_eq!(rc, 0);
        assert_bounded("oblique_p_batch", &g, &a, &out);
        for i in (0..g.len()).step_by(97) {
            let mut p = f64::NAN;
            assert_eq!(oblique_p(table, g[i], a[i], 0, &mut p), 0);
            assert!(p.abs() <= 1.0, "oblique_p({}, {}) = {p}", g[i], a[i]);
        }
        oblique_table_close(table);
    }
}
