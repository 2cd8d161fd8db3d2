//! The knot of the stick patch of a table of Thornton's law (`nodes.knots = true`): the builder
//! traces the loading fold `α_L(γ, e_n)` where it lies in the stick patch and sends it to the
//! cell edge `c' = 1/2`; the fold lies there, the table holds its stated bound next to it, and
//! the reference reader and the C header (on the export, layout version 7) answer it with the
//! rule's bits and refuse a damaged or missing stick knots block.

mod common;
mod evaluator;
use common::{build_table, sweep_ok as ok, sweep_refused as refused};
use evaluator::{assert_same_bits, gcc_driver, run_ok, sealed};
use oblique_physics::sample::SplitMix;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use oblique_lookup::Table;
use oblique_solver::history::loading_fold_thornton;
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::surface::{PartialMap, PatchId, PatchKind};

/// γ 1.6–1.7 and `e_n` 0.6–0.75: `α_L` lies 1.25–2.0 `α_c2` there (stick coordinate 0.2–0.5).
const BODY: &str = "[domain]
gamma_min = 1.6
gamma_max = 1.7
alpha_max = \"inf\"
e_n_min = 0.6
e_n_max = 0.75

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
per_patch = 30
seed = 1
";

/// The table of [`BODY`], built once per test process.
fn table() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| build_table("thornton-stick-knots", "stick", BODY))
}

/// `α_L` at `(γ, e_n)`, located at 4096 steps.
fn loading_fold(gamma: f64, e_n: f64) -> f64 {
    loading_fold_thornton(gamma, e_n, 4096)
        .expect("solve")
        .expect("alpha_L")
}

#[test]
fn the_loading_fold_lies_on_the_stick_knot() {
    let path = table();
    let table = Table::open(path).expect("open");
    let patch = table
        .surface()
        .patch_by_id(PatchId::StickHigh)
        .expect("stick_high");
    let knots = patch.knots().expect("the stick patch has a knot");
    assert_eq!(knots.c_star(), &[0.5]);
    assert_eq!(knots.grade_values(), vec![1], "graded below");
    // α_L lies above LOADING_C_MIN over the whole range: the region is every root cell.
    assert_eq!(
        knots.region(),
        [
            0.0,
            patch.blocks_gamma() as f64,
            0.0,
            patch.blocks_e_n() as f64
        ]
    );
    for &(g, e) in &[(1.6, 0.6), (1.63, 0.67), (1.68, 0.72), (1.7, 0.75)] {
        let a_l = loading_fold(g, e);
        let line = patch.knots_at(g, e).expect("inside the region");
        let a_k = PatchKind::Stick.alpha_at(PartialMap::Slip, g, line.knots()[0], e, f64::INFINITY);
        assert!(
            (a_k / a_l - 1.0).abs() < 2e-5,
            "γ {g}, e_n {e}: knot at α {a_k}, α_L at {a_l}"
        );
        // The knot maps to the cell edge c' = 1/2 exactly (the fold within 2e-5 of it in α:
        // its departure (1 − α/α_L)^{3/2} off the edge is then below 1e-7).
        let c_k = line.knots()[0];
        assert_eq!(patch.knotted(g, c_k, e), 0.5, "γ {g}, e_n {e}");
    }
    let text = ok(&["inspect", path.to_str().expect("path")]);
    assert!(
        text.contains("knots: 1 kink on c' = 0.5 (grades [1]"),
        "{text}"
    );
    // The partial-slip patch keeps its four knots.
    let partial = table
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .expect("partial_high");
    assert_eq!(
        partial.knots().expect("knots").c_star(),
        &[0.5, 0.625, 0.75, 0.875]
    );
}

/// Next to `α_L` (`α_L (1 ± r)`, r from 1e-4 to 2e-2, on both sides) the table against direct
/// solves at tol 1e-8: within the stated bound.
#[test]
fn the_table_holds_its_bound_next_to_the_loading_fold() {
    let t = Table::open(table()).expect("open");
    let bound = t.error_bound();
    let mut worst: f64 = 0.0;
    for &(g, e) in &[(1.61, 0.62), (1.655, 0.69), (1.69, 0.74)] {
        let a_l = loading_fold(g, e);
        for f in [0.98, 0.995, 0.9999, 1.0001, 1.005, 1.02] {
            let a = a_l * f;
            let p = Request::new(g, a)
                .e_n(e)
                .law(Law::Thornton)
                .accuracy(Accuracy::Tolerance(1e-8))
                .solve()
                .expect("a Thornton solve")
                .p;
            let err = (t.p_e(g, a, e).expect("inside") - p).abs();
            worst = worst.max(err);
            assert!(
                err <= bound,
                "γ {g}, α {a} ({f} α_L), e_n {e}: error {err:e} > bound {bound:e}"
            );
        }
    }
    eprintln!("largest error next to alpha_L: {worst:e} (bound {bound:e})");
}

/// The export by `sweep export` (once per process) and the C driver `tests/c/eval_check.c`.
fn export() -> &'static (PathBuf, PathBuf) {
    static E: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    E.get_or_init(|| {
        let d = common::subdir("thornton-stick-knots-export");
        let out = d.join("t.oblq");
        ok(&[
            "export",
            table().to_str().expect("path"),
            "-o",
            out.to_str().expect("path"),
        ]);
        (out, gcc_driver(&d.join("eval_check"), &[]))
    })
}

/// `Table::p_e`, the reference reader and `oblq_p_e` of the C header on the export (layout
/// version 7) give the same bits at 1 500 points: half next to the stick knot (`c` within 1e-9
/// to 1e-3 of it, both sides), the rest random over the domain.
#[test]
fn the_reference_reader_and_the_c_header_give_the_bits_of_the_rule() {
    let table_path = table();
    let t = Table::open(table_path).expect("open");
    let (export, driver) = export();
    let bytes = std::fs::read(export).expect("export");
    assert_eq!(
        &bytes[8..16],
        &[7, 0, 0, 0, 112, 0, 0, 0],
        "version 7, 112-byte header"
    );
    assert_eq!(&bytes[68..72], &[1, 0, 0, 0], "no full-slip line");
    let s = t.surface();
    let patch = s.patch_by_id(PatchId::StickHigh).expect("stick_high");
    let (e_lo, e_hi) = t.restitution().expect("an e_n axis");
    let mut r = SplitMix(0x7374_6963);
    let n = 1500;
    let mut pts = Vec::with_capacity(n);
    while pts.len() < n / 2 {
        let g = s.gamma_min() + (s.gamma_max() - s.gamma_min()) * r.uniform();
        let e = e_lo + (e_hi - e_lo) * r.uniform();
        let k = patch.knots_at(g, e).expect("inside the region").knots()[0];
        for side in [-1.0, 1.0] {
            let d = 10f64.powf(-9.0 + 6.0 * r.uniform());
            let a = PatchKind::Stick.alpha_at(PartialMap::Slip, g, k + side * d, e, f64::INFINITY);
            pts.push((g, a, e));
        }
    }
    while pts.len() < n {
        let g = s.gamma_min() + (s.gamma_max() - s.gamma_min()) * r.uniform();
        let e = e_lo + (e_hi - e_lo) * r.uniform();
        let u = r.uniform();
        pts.push((g, u / (1.0 - u), e));
    }
    assert_same_bits(&t, table_path, export, driver, &pts);
}

/// The C header refuses a version-7 export without the stick patch's knots block or with a
/// damaged one (`OBLQ_E_CORRUPT`), one labelled 5 (a reader of version 5 sees the stick
/// record's offset where it reserves 0) or 8 (without the map of the `e_n` axis that version 8
/// states), and a later version by its version (`OBLQ_E_VERSION`);
/// the reference reader refuses a damaged stick knots group, naming it (exit 2).
#[test]
fn damaged_stick_knots_are_refused() {
    let (export, driver) = export();
    let good = std::fs::read(export).expect("export");
    let dir = common::subdir("thornton-stick-knots-damaged");
    let case = |name: &str, bytes: &[u8]| -> String {
        let p = dir.join(name);
        std::fs::write(&p, bytes).expect("write");
        run_ok(driver, &["open", p.to_str().expect("path")], "")
    };
    assert!(case("good", &good).starts_with("0 ok"));
    let u64_at = |at: usize| u64::from_le_bytes(good[at..at + 8].try_into().expect("8 bytes"));
    let record = u64_at(72) as usize + 2 * 160;
    let block = u64_at(record + 152) as usize;
    assert!(
        block > 0 && block.is_multiple_of(8),
        "the stick knots block at {block}"
    );
    for (name, at, value) in [
        ("no_block", record + 152, 0u64.to_le_bytes().to_vec()),
        ("knots_0", block, 0u32.to_le_bytes().to_vec()),
        ("c_star_1", block + 88, 1f64.to_le_bytes().to_vec()),
        ("knot_1", block + 96, 1f64.to_le_bytes().to_vec()),
        ("as_v5", 8, 5u32.to_le_bytes().to_vec()),
        ("as_v8_without_map", 8, 8u32.to_le_bytes().to_vec()),
    ] {
        let mut b = good.clone();
        b[at..at + value.len()].copy_from_slice(&value);
        let said = case(name, &sealed(b));
        assert!(said.starts_with("6 "), "{name} at {at}: {said}");
    }
    let mut newer = good.clone();
    newer[8] = 9;
    assert!(case("newer", &sealed(newer)).starts_with("4 "));

    let bad = dir.join("c_star.h5");
    common::edited_copy(
        table(),
        &bad,
        "f['patches/stick_high/knots']['c_star'][0] = 1.0",
    );
    let out = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/read_table.py"))
        .arg(&bad)
        .args(["--gamma", "1.65", "--alpha", "1.2", "--e-n", "0.7"])
        .output()
        .expect("python3 (with h5py: the test command installs it)");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("stick_high/knots") && err.contains("c_star"),
        "{err}"
    );
    assert!(Table::open(&bad).is_err());
}

/// `sweep verify --near-folds` draws points next to each of the kinks in turn (located at
/// each point), checks them against direct solves and prints the largest error next to each;
/// a table of another law is refused (exit 2), naming the flag.
#[test]
fn verify_near_folds_checks_the_bound_next_to_each_fold() {
    let t = table().to_str().expect("path");
    let run = || {
        ok(&[
            "verify",
            t,
            "--near-folds",
            "--points",
            "25",
            "--seed",
            "2",
            "--quiet",
        ])
    };
    let out = run();
    // Points k, k + 9, k + 18 next to kink k: the four folds and E- (0.81-1.83 here).
    for (name, n) in [
        ("alpha_R", 3),
        ("2/7", 3),
        ("alpha_S", 3),
        ("alpha_L", 3),
        ("E-", 3),
    ] {
        let line = out
            .lines()
            .find(|l| l.starts_with(&format!("near {name} ")))
            .unwrap_or_else(|| panic!("no line for {name}: {out}"));
        assert!(line.contains(&format!("{n} points, max |error|")), "{line}");
    }
    // The switch sheet lies below e_n 0.52, F- beyond gamma 1.87 and the strip of the `+`
    // episode beyond gamma 2, outside this table's range: no points there.
    for name in ["e_S", "F-", "F+lo", "F+hi"] {
        assert!(!out.contains(&format!("near {name} ")), "{out}");
    }
    assert!(out.contains("points above it: 0"), "{out}");
    // The same seed draws the same points.
    let again = run();
    let worst = |s: &str| {
        s.lines()
            .find(|l| l.starts_with("worst point"))
            .map(str::to_owned)
    };
    assert_eq!(worst(&out), worst(&again));
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let kv = root.join("tables/dissipative-demo.h5");
    refused(
        &[
            "verify",
            kv.to_str().expect("path"),
            "--near-folds",
            "--points",
            "4",
        ],
        &["--near-folds", "kelvin-voigt law", "thornton"],
    );
}
