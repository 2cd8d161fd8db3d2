//! The knots of a table of Thornton's law (`nodes.knots = true`): the builder traces the kinks
//! of `P` inside the partial-slip patch and sends them to fixed cell edges; the written file
//! holds them, the rule, the curves and `sweep query` answer it alike, the folds lie where the
//! knots put them, the table holds its stated bound next to them, and the export, whose layout
//! has no knots, refuses it.

mod common;
use common::{build_table, sweep_ok as ok, sweep_refused as refused};

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use oblique_lookup::{OutOfDomain, Table};
use oblique_solver::history::{reslip_fold_thornton, switch_fold_thornton};
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::surface::{PartialMap, PatchId, PatchKind};

const BODY: &str = "[domain]
gamma_min = 1.6
gamma_max = 1.8
alpha_max = \"inf\"
e_n_min = 0.8
e_n_max = 0.99

[nodes]
target_error = 1e-4
leaf_intervals = 6
blocks_per_unit_gamma = 2.5
blocks_coord = 8
knots = true
max_nodes = 200000

[solver]
law = \"thornton\"
tol = 1e-5

[checks]
per_patch = 50
seed = 1
";

/// The table of [`BODY`], built once per test process.
fn table() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| build_table("thornton-knots", "knots", BODY))
}

/// `P` of Thornton's law by a direct solve at tolerance 1e-8.
fn solve(gamma: f64, alpha: f64, e_n: f64) -> f64 {
    Request::new(gamma, alpha)
        .e_n(e_n)
        .law(Law::Thornton)
        .accuracy(Accuracy::Tolerance(1e-8))
        .solve()
        .expect("a Thornton solve")
        .p
}

#[test]
fn the_folds_lie_on_the_knots_cell_edges() {
    let table = Table::open(table()).expect("open");
    let patch = table
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .expect("partial_high");
    let knots = patch.knots().expect("knots");
    assert_eq!(knots.c_star(), &[0.5, 0.625, 0.75, 0.875]);
    // Up to e_n = 0.98, rounded down to a sixteenth of the one root cell along e_n: 0.97875.
    let top = knots.region()[3];
    assert_eq!(top, 0.9375, "{:?}", knots.region());
    for &(g, e) in &[
        (1.6, 0.8),
        (1.66, 0.85),
        (1.754, 0.9),
        (1.8, 0.95),
        (1.7, 0.975),
    ] {
        let c_of =
            |a: f64| PatchKind::PartialSlip.coord_at(PartialMap::Slip, g, a, e, f64::INFINITY);
        let line = patch.knots_at(g, e).expect("inside the knots' region");
        let ar = reslip_fold_thornton(g, e, 4096)
            .expect("solve")
            .expect("alpha_R");
        let as_ = switch_fold_thornton(g, e, 4096)
            .expect("solve")
            .expect("alpha_S");
        // The knots (in c) where the folds are, to the tracing's resolution (2048 steps) and
        // the interpolation between the grid's points: within 2e-6 up to e_n 0.95, 1.1e-5 at
        // 0.975 next to the region's top, where α_R(e_n) steepens (it tends to 2/7 as e_n → 1).
        // A fold `1.06 (α/α_R − 1)^{3/2}` that far from a cell edge moves the leaf's cubic by
        // about 1e-7. Each knot is sent to its c*.
        let tol = if e > 0.96 { 3e-5 } else { 2e-6 };
        for (j, a) in [(1, ar), (2, 2.0 / 7.0), (3, as_)] {
            let k = line.knots()[j];
            assert!(
                (k - c_of(a)).abs() < tol,
                "γ {g}, e_n {e}: knot {j} at c {k}, fold {a} at {}",
                c_of(a)
            );
            assert!((line.apply(k) - knots.c_star()[j]).abs() < 1e-15);
        }
        // α_c1 stays at c = 1/2, to the rounding of the interpolation's weights.
        assert!((line.knots()[0] - 0.5).abs() < 1e-15, "{:?}", line.knots());
    }
    // Above the region the coordinate is not mapped.
    let c = PatchKind::PartialSlip.coord_at(PartialMap::Slip, 1.7, 0.3, 0.985, f64::INFINITY);
    assert_eq!(patch.knotted(1.7, c, 0.985).to_bits(), c.to_bits());
}

#[test]
fn the_table_holds_its_bound_next_to_the_folds() {
    let table = Table::open(table()).expect("open");
    let bound = table.error_bound();
    assert!(bound > 0.0 && bound < 3e-4, "bound {bound:e}");
    let mut worst: f64 = 0.0;
    for &(g, e) in &[(1.63, 0.82), (1.754, 0.9), (1.79, 0.96)] {
        let ar = reslip_fold_thornton(g, e, 4096)
            .expect("solve")
            .expect("alpha_R");
        let as_ = switch_fold_thornton(g, e, 4096)
            .expect("solve")
            .expect("alpha_S");
        for a in [ar, 2.0 / 7.0, as_] {
            for f in [0.98, 0.995, 0.9995, 1.0005, 1.005, 1.02] {
                let got = table.p_e(g, a * f, e).expect("inside the table");
                let err = (got - solve(g, a * f, e)).abs();
                worst = worst.max(err);
                assert!(
                    err <= bound,
                    "γ {g}, α {}, e_n {e}: error {err:e} > {bound:e}",
                    a * f
                );
            }
        }
    }
    assert!(worst > 0.0, "the checks compared something");
}

#[test]
fn the_rule_the_curves_and_the_query_command_answer_alike() {
    let t = table().to_str().expect("path");
    // Points inside and above the knots' region, next to the folds and elsewhere.
    let mut rows = String::new();
    let mut next = oblique_lookup::testing::uniform(0x006b_6e6f_7473);
    for i in 0..400 {
        let g = 1.6 + 0.2 * next();
        let e = if i % 4 == 0 {
            0.975 + 0.015 * next()
        } else {
            0.8 + 0.19 * next()
        };
        let a = 0.05 + 0.9 * next();
        rows.push_str(&format!("{g},{a},{e}\n"));
    }
    let table = Table::open(table()).expect("open");
    let mut want = Vec::new();
    for line in rows.lines() {
        let v: Vec<f64> = line
            .split(',')
            .map(|s| s.parse().expect("number"))
            .collect();
        want.push(table.p_e(v[0], v[1], v[2]).expect("inside"));
        // The per-(γ, e_n) curve answers the same bits (within the curve's own rounding).
        let curve = table
            .curve_e(v[0], v[2], OutOfDomain::Error)
            .expect("a curve");
        let pc = curve.p(v[1]).expect("inside");
        assert!(
            (pc - want[want.len() - 1]).abs() < 1e-13,
            "{line}: {pc} vs curve"
        );
    }
    let csv = common::subdir("thornton-knots-query").join("points.csv");
    let body: String = rows
        .lines()
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            format!("{},{},{}\n", v[0], v[1], v[2])
        })
        .collect();
    std::fs::write(&csv, format!("gamma,alpha,e_n\n{body}")).expect("write");
    let out = ok(&["query", t, "--batch", csv.to_str().expect("path")]);
    // Lines `gamma,alpha,e_n,P,e_t` after the header.
    let got: Vec<f64> = out
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).expect("P").parse().expect("number"))
        .collect();
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g.to_bits(), w.to_bits());
    }
}

#[test]
fn the_export_refuses_a_table_with_knots() {
    let out = common::subdir("thornton-knots-export").join("t.bin");
    refused(
        &[
            "export",
            table().to_str().expect("path"),
            "-o",
            out.to_str().expect("path"),
        ],
        &["knots"],
    );
}

#[test]
fn knots_are_refused_for_the_elastic_law_and_the_table_of_one_pair() {
    let dir = common::subdir("thornton-knots-refused");
    for (name, body) in [
        (
            "elastic",
            BODY.replace("e_n_min = 0.8\ne_n_max = 0.99\n", "")
                .replace("law = \"thornton\"", "law = \"elastic\""),
        ),
        (
            "pair",
            BODY.replace("gamma_min = 1.6\ngamma_max = 1.8\n", "gamma = 1.7\n")
                .replace("law = \"thornton\"", "law = \"kelvin-voigt\""),
        ),
    ] {
        let cfg = dir.join(format!("{name}.toml"));
        let out = dir.join(format!("{name}.h5"));
        std::fs::write(
            &cfg,
            format!("output = {:?}\n{body}", out.display().to_string()),
        )
        .expect("write config");
        refused(
            &["run", cfg.to_str().expect("path")],
            &["nodes.knots", "e_n range"],
        );
        assert!(!out.exists());
    }
}

/// The reference reader does not apply knots: it refuses such a table (exit 2, naming the
/// group) instead of answering from the wrong coordinate.
#[test]
fn the_reference_reader_refuses_a_table_with_knots() {
    let out = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/read_table.py"))
        .arg(table())
        .args(["--gamma", "1.7", "--alpha", "0.3", "--e-n", "0.9"])
        .output()
        .expect("python3 (with h5py: the test command installs it)");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("group 'knots'"), "{err}");
}

#[test]
fn inspect_names_the_knots() {
    let t = table().to_str().expect("path");
    let text = ok(&["inspect", t]);
    assert!(
        text.contains("knots: 4 kinks on c' = 0.5, 0.625, 0.75, 0.875"),
        "{text}"
    );
    let v: serde_json::Value = serde_json::from_str(&ok(&["inspect", t, "--json"])).expect("JSON");
    let partial = &v["patches"][0];
    assert_eq!(partial["name"], "partial_high", "{v}");
    assert_eq!(partial["knots"]["count"], 4, "{v}");
    assert_eq!(
        partial["knots"]["grade"],
        serde_json::json!([0, 2, 0, 1]),
        "{v}"
    );
    assert!(v["patches"][1]["knots"].is_null(), "{v}");
}
