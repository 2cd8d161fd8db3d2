//! The end-of-contact sheet `e_E` of Thornton's stick patch (`docs/solver.md`, "The
//! end-of-contact sheet"): `sweep verify --near-end-sheet` draws points next to it, checks them
//! against direct solves and prints the largest error next to it; a table without the sheet in
//! its range, of another law or without an `e_n` axis is refused (exit 2).

mod common;
use common::{sweep_ok as ok, sweep_refused as refused};

use std::path::{Path, PathBuf};

use oblique_solver::history::end_minus_sheet_edges_thornton;

fn root(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// A small table across the sheet (γ 1.64–1.68, `e_n` 0.31–0.35, where it lies at 0.32–0.33
/// from 3 `α_c2` up): about 10 s.
fn across_the_sheet() -> PathBuf {
    common::build_table(
        "end-sheet",
        "t",
        "[domain]\ngamma_min = 1.64\ngamma_max = 1.68\nalpha_max = \"inf\"\ne_n_min = 0.31\n\
         e_n_max = 0.35\n[nodes]\ntarget_error = 3e-4\nleaf_intervals = 6\nblocks_coord = 2\n\
         [solver]\nlaw = \"thornton\"\ntol = 3e-5\n",
    )
}

#[test]
fn verify_near_end_sheet_draws_next_to_the_sheet() {
    let table = across_the_sheet();
    let t = table.to_str().expect("path");
    let args = [
        "verify",
        t,
        "--near-end-sheet",
        "--points",
        "12",
        "--seed",
        "3",
        "--quiet",
    ];
    let out = ok(&args);
    let line = out
        .lines()
        .find(|l| l.starts_with("near e_E "))
        .unwrap_or_else(|| panic!("no line for e_E: {out}"));
    assert!(line.contains("12 points, max |error|"), "{line}");
    assert!(out.contains("points above it: 0"), "{out}");
    // The worst point lies within 1e-2 of an upper edge of the sheet at its (γ, α).
    let worst = out
        .lines()
        .find(|l| l.starts_with("worst point"))
        .expect("worst point")
        .to_owned();
    let value = |key: &str| -> f64 {
        let rest = &worst[worst.find(key).expect(key) + key.len()..];
        rest.split([',', ':'])
            .next()
            .and_then(|s| s.trim().parse().ok())
            .expect("a number")
    };
    let (g, a, e) = (value("gamma = "), value("alpha = "), value("e_n = "));
    let edges = end_minus_sheet_edges_thornton(g, a, (0.31, 0.35), 0.01, 2048).expect("solve");
    assert!(
        edges
            .iter()
            .any(|&(edge, above)| !above
                && (1e-4 * 0.999..=1e-2 * 1.001).contains(&(e - edge).abs())),
        "{worst}: {edges:?}"
    );
    // The same seed draws the same points.
    assert!(ok(&args).contains(&worst), "{worst}");
}

#[test]
fn verify_near_end_sheet_refuses_tables_without_it() {
    // The demo table's range (e_n 0.8-1) holds no upper edge of the sheet.
    let demo = common::shared_build(&root("configs/thornton-demo.toml"));
    let (kv, elastic) = (root("tables/dissipative-demo.h5"), root("tables/quick.h5"));
    for (table, needles) in [
        (&demo, &["no sheet was found"][..]),
        (&kv, &["kelvin-voigt law", "thornton"][..]),
        (&elastic, &["no e_n axis"][..]),
    ] {
        let t = table.to_str().expect("path");
        refused(
            &["verify", t, "--near-end-sheet", "--points", "4"],
            &[&["--near-end-sheet"][..], needles].concat(),
        );
    }
    refused(
        &[
            "verify",
            elastic.to_str().expect("path"),
            "--near-end-sheet",
            "--near-band",
            "--points",
            "4",
        ],
        &["--near-end-sheet", "--near-band"],
    );
}
