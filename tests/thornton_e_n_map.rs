//! The `e_n` axis of a table of Thornton's law over `t = (1 − e_n)^{1/4}`
//! (`nodes.e_n_coordinate = "quarter-root"`, schema 5): next to `e_n = 1` the plastic radius
//! grows like `t`, and `P` like `P(1) − a t⁴ + b t⁵`, smooth in `t` but not in `e_n`. A small
//! table over `e_n` 0.95–1 built both ways, against direct solves next to `e_n = 1`: the linear
//! axis errs beyond its stated bound there, the quarter-root one holds it; the file names its
//! map, every Rust query path answers from it, and a reader refuses a map it does not know.

mod common;
use common::{build_table, sweep_ok as ok, sweep_refused as refused};

use oblique_lookup::Table;
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::surface::AxisMap;

/// The config of both tables (`MAP` replaced): γ 1.70–1.74, `e_n` 0.95–1, target 4e-5.
const BODY: &str = "[domain]\ngamma_min = 1.70\ngamma_max = 1.74\nalpha_max = \"inf\"\n\
                    e_n_min = 0.95\ne_n_max = 1.0\n[nodes]\ntarget_error = 4e-5\n\
                    leaf_intervals = 6\nblocks_coord = 8\ne_n_coordinate = \"MAP\"\n\
                    [solver]\nlaw = \"thornton\"\ntol = 4e-6\n[checks]\nper_patch = 5\n";

/// Points next to `e_n = 1`: γ uniform, `α/(1 + α)` uniform, `1 − e_n = 10^u`, `u` uniform in
/// `[−5, log10 0.05]` (a fixed sequence).
fn points(n: usize) -> Vec<(f64, f64, f64)> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut u = move || {
        s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let gamma = 1.70 + 0.04 * u();
            let w = u();
            let alpha = w / (1.0 - w);
            let r = 10f64.powf(-5.0 + (5.0 + 0.05f64.log10()) * u());
            (gamma, alpha, 1.0 - r)
        })
        .collect()
}

fn solve(gamma: f64, alpha: f64, e_n: f64) -> f64 {
    Request::new(gamma, alpha)
        .e_n(e_n)
        .law(Law::Thornton)
        .accuracy(Accuracy::Tolerance(1e-8))
        .solve()
        .expect("a Thornton solve")
        .p
}

/// The largest error of the table over its stated bound at the points.
fn worst(table: &Table, pts: &[(f64, f64, f64)], truth: &[f64]) -> f64 {
    pts.iter()
        .zip(truth)
        .map(|(&(g, a, e), p)| {
            let t = table.p_e(g, a, e).expect("inside");
            (t - p).abs() / table.error_bound()
        })
        .fold(0.0, f64::max)
}

#[test]
fn next_to_e_n_one_only_the_quarter_root_axis_holds_its_bound() {
    let linear = build_table("linear", "t", &BODY.replace("MAP", "linear"));
    let quarter = build_table("quarter", "t", &BODY.replace("MAP", "quarter-root"));
    let pts = points(120);
    let truth: Vec<f64> = pts.iter().map(|&(g, a, e)| solve(g, a, e)).collect();
    let lin = Table::open(&linear).expect("open");
    let qr = Table::open(&quarter).expect("open");
    assert_eq!(lin.provenance().schema_version, 4);
    assert_eq!(lin.surface().e_n_map(), AxisMap::Linear);
    assert_eq!(qr.provenance().schema_version, 5);
    assert_eq!(qr.surface().e_n_map(), AxisMap::QuarterRoot);
    let (wl, wq) = (worst(&lin, &pts, &truth), worst(&qr, &pts, &truth));
    eprintln!("error over bound next to e_n = 1: linear {wl:.3}, quarter-root {wq:.3}");
    assert!(wl > 1.0, "the linear axis: {wl}");
    assert!(wq <= 1.0, "the quarter-root axis: {wq}");

    // `sweep query` answers from it with the bits of `Table::p_e`.
    let q = quarter.to_str().expect("path");
    let (g, a, e) = pts[7];
    let out = ok(&[
        "query",
        q,
        "--gamma",
        &g.to_string(),
        "--alpha",
        &a.to_string(),
        "--e-n",
        &e.to_string(),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(
        v["P"].as_f64(),
        Some(qr.p_e(g, a, e).expect("inside")),
        "{out}"
    );
    // The export layout has no map yet: refused by name, exit 2.
    let dir = common::subdir("refused");
    let oblq = dir.join("t.oblq");
    refused(
        &["export", q, "-o", oblq.to_str().expect("path")],
        &["(1-e_n)^(1/4)", "schema 5"],
    );
    // A map this reader does not know, and a schema-5 file without its map, are refused.
    for (name, edit, needle) in [
        (
            "unknown",
            "f.attrs['e_n_coordinate'] = 'sqrt(1-e_n)'",
            "sqrt(1-e_n)",
        ),
        ("missing", "del f.attrs['e_n_coordinate']", "e_n_coordinate"),
    ] {
        let bad = dir.join(format!("{name}.h5"));
        common::edited_copy(&quarter, &bad, edit);
        let err = Table::open(&bad).expect_err("refused").to_string();
        assert!(err.contains(needle), "{name}: {err}");
    }
}
