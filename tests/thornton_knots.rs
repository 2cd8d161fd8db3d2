//! The knots of a table of Thornton's law (`nodes.knots = true`): the builder traces the kinks
//! of `P` inside the partial-slip patch and sends them to fixed cell edges; the written file
//! holds them, the rule, the curves and `sweep query` answer it alike, the folds lie where the
//! knots put them, the table holds its stated bound next to them, and the reference reader and
//! the C header (on the export, layout version 5) answer it with the rule's bits and refuse
//! damaged knots.

mod common;
mod evaluator;
use common::{build_table, sweep_ok as ok, sweep_refused as refused};
use evaluator::{assert_same_bits, gcc_driver, run_ok, sealed};
use oblique_physics::sample::SplitMix;

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

/// The re-slip fold `α_R` and the switch fold `α_S` at `(γ, e_n)`, located at 4096 steps.
fn folds(gamma: f64, e_n: f64) -> (f64, f64) {
    let ar = reslip_fold_thornton(gamma, e_n, 4096)
        .expect("solve")
        .expect("alpha_R");
    let as_ = switch_fold_thornton(gamma, e_n, 4096)
        .expect("solve")
        .expect("alpha_S");
    (ar, as_)
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
    // Up to e_n = 0.98, rounded down to a sixteenth of the one root cell along e_n: 0.978125.
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
        let (ar, as_) = folds(g, e);
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
        let (ar, as_) = folds(g, e);
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

/// The export of the table by `sweep export` (once per process) and the C driver
/// `tests/c/eval_check.c`.
fn export() -> &'static (PathBuf, PathBuf) {
    static E: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    E.get_or_init(|| {
        let d = common::subdir("thornton-knots-export");
        let out = d.join("t.oblq");
        let said = ok(&[
            "export",
            table().to_str().expect("path"),
            "-o",
            out.to_str().expect("path"),
        ]);
        assert!(
            said.contains("the table of the thornton law (e_n in [0.8, 0.99])"),
            "{said}"
        );
        (out, gcc_driver(&d.join("eval_check"), &[]))
    })
}

/// `e_n` of the top edge of the knots' region (`region[3]` root cells along `e_n`).
fn region_top(table: &Table) -> f64 {
    let patch = table
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .expect("partial_high");
    let (lo, hi) = table.restitution().expect("an e_n axis");
    let top = patch.knots().expect("knots").region()[3];
    lo + (hi - lo) * top / patch.blocks_e_n() as f64
}

/// The points of the bit tests: a third next to the knots (`c` within 1e-9 to 1e-3 of each
/// `K_j` of [`oblique_table::surface::Patch::knots_at`], on both sides, at random `(γ, e_n)` of
/// the region), a tenth at the region's top edge in `e_n` (at it, and 1 ulp, 1e-12, 1e-9 and
/// 1e-6 either side), the rest random over the domain (mostly partial slip).
fn knot_points(table: &Table, n: usize) -> Vec<(f64, f64, f64)> {
    let s = table.surface();
    let patch = s.patch_by_id(PatchId::PartialHigh).expect("partial_high");
    let (e_lo, e_hi) = table.restitution().expect("an e_n axis");
    let top = region_top(table);
    let mut r = SplitMix(0x6b6e_6f74);
    let g_of = |r: &mut SplitMix| s.gamma_min() + (s.gamma_max() - s.gamma_min()) * r.uniform();
    let alpha_of = |g: f64, c: f64, e: f64| {
        PatchKind::PartialSlip.alpha_at(PartialMap::Slip, g, c, e, f64::INFINITY)
    };
    let mut pts = Vec::with_capacity(n);
    while pts.len() < n / 3 {
        let (g, e) = (g_of(&mut r), e_lo + (top - e_lo) * r.uniform());
        let line = patch.knots_at(g, e).expect("inside the knots' region");
        for &k in line.knots() {
            for side in [-1.0, 1.0] {
                let d = 10f64.powf(-9.0 + 6.0 * r.uniform());
                pts.push((g, alpha_of(g, k + side * d, e), e));
            }
        }
    }
    let offsets = [0.0, 1e-12, 1e-9, 1e-6];
    while pts.len() < n / 3 + n / 10 {
        let g = g_of(&mut r);
        let off = offsets[(r.uniform() * 4.0) as usize % 4];
        let e = match (r.uniform() * 4.0) as usize {
            0 => f64::from_bits(top.to_bits() + 1),
            1 => f64::from_bits(top.to_bits() - 1),
            2 => top + off,
            _ => top - off,
        };
        pts.push((g, alpha_of(g, r.uniform(), e), e));
    }
    while pts.len() < n {
        let (g, e) = (g_of(&mut r), e_lo + (e_hi - e_lo) * r.uniform());
        let a = if pts.len() % 5 == 0 {
            3.0 * r.uniform()
        } else {
            alpha_of(g, r.uniform(), e)
        };
        pts.push((g, a, e));
    }
    pts
}

/// `Table::p_e`, the reference reader `scripts/read_table.py` and `oblq_p_e` of the C header on
/// the export (layout version 5, flag of a table without a full-slip line) give the same bits
/// at 2 400 points, 800 of them next to the knots and 240 at the region's top edge in `e_n`.
#[test]
fn the_reference_reader_and_the_c_header_give_the_bits_of_the_rule() {
    let table_path = table();
    let t = Table::open(table_path).expect("open");
    let (export, driver) = export();
    let bytes = std::fs::read(export).expect("export");
    assert_eq!(
        &bytes[8..16],
        &[5, 0, 0, 0, 112, 0, 0, 0],
        "version 5, 112-byte header"
    );
    assert_eq!(&bytes[68..72], &[1, 0, 0, 0], "no full-slip line");
    let n = 2400;
    let pts = knot_points(&t, n);
    let patch = t
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .expect("partial_high");
    let knotted = pts
        .iter()
        .filter(|&&(g, a, e)| {
            a < oblique_physics::regimes::alpha_c2(g) && patch.knots_at(g, e).is_some()
        })
        .count();
    assert!(
        knotted > n / 2,
        "{knotted} of {n} points where the knots apply"
    );
    assert_same_bits(&t, table_path, export, driver, &pts);
}

/// The reference reader refuses a table whose knots break a rule of the format (exit 2, naming
/// the field): `c_star` not increasing, a grade it does not know, a region edge that a leaf
/// straddles, a knot grid that does not cover the region.
#[test]
fn the_reference_reader_refuses_damaged_knots() {
    let dir = common::subdir("thornton-knots-damaged");
    let k = "f['patches/partial_high/knots']";
    for (name, edit, want) in [
        ("c_star", format!("{k}['c_star'][1] = 0.45"), "'c_star'[1]"),
        ("grade", format!("{k}['grade'][0] = 3"), "'grade'[0]"),
        (
            "straddled",
            format!("{k}['region'][3] = 0.90625"),
            "straddle",
        ),
        (
            "grid",
            format!("{k}.attrs['e_n_0'] = 0.81"),
            "must cover the region",
        ),
    ] {
        let bad = dir.join(format!("{name}.h5"));
        common::edited_copy(table(), &bad, &edit);
        let out = std::process::Command::new("python3")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/read_table.py"))
            .arg(&bad)
            .args(["--gamma", "1.7", "--alpha", "0.3", "--e-n", "0.9"])
            .output()
            .expect("python3 (with h5py: the test command installs it)");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains("partial_high/knots") && err.contains(want),
            "{name}: {err}"
        );
        // The Rust reader refuses it too.
        assert!(Table::open(&bad).is_err(), "{name}");
    }
}

/// The C header refuses an export whose knots block was damaged and resealed (`OBLQ_E_CORRUPT`),
/// one labelled 4 (a reader of version 4 sees the block's offset where it reserves 0) or 8
/// (without the map of the `e_n` axis that version 8 states), and refuses a later version by
/// its version (`OBLQ_E_VERSION`).
#[test]
fn the_c_header_refuses_a_damaged_knots_block() {
    let (export, driver) = export();
    let good = std::fs::read(export).expect("export");
    let dir = common::subdir("thornton-knots-damaged-export");
    let case = |name: &str, bytes: &[u8]| -> String {
        let p = dir.join(name);
        std::fs::write(&p, bytes).expect("write");
        run_ok(driver, &["open", p.to_str().expect("path")], "")
    };
    assert!(case("good", &good).starts_with("0 ok"));
    let u64_at = |at: usize| u64::from_le_bytes(good[at..at + 8].try_into().expect("8 bytes"));
    let record = u64_at(72) as usize + 160;
    let block = u64_at(record + 152) as usize;
    assert!(
        block > 0 && block.is_multiple_of(8),
        "the knots block at {block}"
    );
    let region = |j: usize| block + 48 + 8 * j;
    let edits: Vec<(&str, usize, Vec<u8>)> = vec![
        ("no_block", record + 152, 0u64.to_le_bytes().to_vec()),
        (
            "block_outside",
            record + 152,
            (good.len() as u64).to_le_bytes().to_vec(),
        ),
        ("knots_0", block, 0u32.to_le_bytes().to_vec()),
        ("knots_9", block, 9u32.to_le_bytes().to_vec()),
        ("grid_3", block + 4, 3u32.to_le_bytes().to_vec()),
        ("gamma_step_0", block + 24, 0f64.to_le_bytes().to_vec()),
        ("c_star_1", block + 88, 1f64.to_le_bytes().to_vec()),
        ("c_star_down", block + 96, 0.4f64.to_le_bytes().to_vec()),
        ("grade_3", block + 80, vec![3]),
        ("graded_both_ends", block + 82, vec![1]),
        ("knot_0", block + 88 + 32, 0f64.to_le_bytes().to_vec()),
        (
            "region_not_dyadic",
            region(3),
            (0.9375f64 + 1e-9).to_le_bytes().to_vec(),
        ),
        ("region_empty", region(1), 0f64.to_le_bytes().to_vec()),
        (
            "region_straddled",
            region(3),
            0.90625f64.to_le_bytes().to_vec(),
        ),
        ("region_uncovered", region(3), 1f64.to_le_bytes().to_vec()),
        ("as_v4", 8, 4u32.to_le_bytes().to_vec()),
        ("as_v8_without_map", 8, 8u32.to_le_bytes().to_vec()),
    ];
    for (name, at, value) in edits {
        let mut b = good.clone();
        b[at..at + value.len()].copy_from_slice(&value);
        let said = case(name, &sealed(b));
        assert!(said.starts_with("6 "), "{name} at {at}: {said}");
    }
    let mut newer = good.clone();
    newer[8] = 9;
    assert!(case("newer", &sealed(newer)).starts_with("4 "));
}

/// Mutated copies of the export through `oblq_open` and queries, compiled with
/// AddressSanitizer and UndefinedBehaviorSanitizer: 400 mutated anywhere and 400 mutated inside
/// the knots block (half of them resealed); none reads out of bounds, every answer is in
/// `[−1, 1]`, and some are refused.
#[test]
fn mutated_knots_blocks_never_read_out_of_bounds_under_sanitizers() {
    let (export, _) = export();
    let dir = common::subdir("thornton-knots-asan");
    let exe = gcc_driver(
        &dir.join("eval_check_asan"),
        &[
            "-g",
            "-fsanitize=address,undefined",
            "-fno-sanitize-recover=all",
        ],
    );
    let good = std::fs::read(export).expect("export");
    let word = |at: usize, n: usize| {
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&good[at..at + n]);
        u64::from_le_bytes(b) as usize
    };
    let block = word(word(72, 8) + 160 + 152, 8);
    // The block's 88 bytes, then c_star [k] and the knot values [k][n_γ][n_e].
    let (k, n_gamma, n_e) = (word(block, 4), word(block + 4, 4), word(block + 8, 4));
    let end = block + 88 + 8 * k * (1 + n_gamma * n_e);
    assert!(end <= good.len(), "the block [{block}, {end})");
    let path = export.to_str().expect("path");
    let (from, to) = (block.to_string(), end.to_string());
    for args in [
        vec!["fuzz", path, "400", "23"],
        vec!["fuzz", path, "400", "29", &from, &to],
    ] {
        let out = std::process::Command::new(&exe)
            .args(&args)
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{args:?}: {}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("refused"), "{text}");
        eprintln!("{args:?}: {}", text.trim());
    }
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
