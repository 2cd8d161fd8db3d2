//! The `e_n` axis of a table of Thornton's law over `t = (1 − e_n)^{1/4}`
//! (`nodes.e_n_coordinate = "quarter-root"`, schema 5): next to `e_n = 1` the plastic radius
//! grows like `t`, and `P` like `P(1) − a t⁴ + b t⁵`, smooth in `t` but not in `e_n`. A small
//! table over `e_n` 0.95–1 built both ways, against direct solves next to `e_n = 1`: the linear
//! axis errs beyond its stated bound there, the quarter-root one holds it; the file names its
//! map, every Rust query path answers from it, and a reader refuses a map it does not know. Its
//! export (layout version 8, also of a table with knots whose region the map places) is
//! answered by the C header, and the file by the reference reader, with the bits of
//! `Table::p_e`; an export whose map field contradicts its version is refused.

mod common;
mod evaluator;
use common::{build_table, sweep_ok as ok};
use evaluator::{assert_same_bits, gcc_driver, run_ok, sealed};

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use oblique_lookup::Table;
use oblique_physics::regimes::alpha_c2;
use oblique_physics::sample::SplitMix;
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::surface::{AxisMap, PatchId};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// The config of both tables (`MAP` replaced): γ 1.70–1.74, `e_n` 0.95–1, target 4e-5.
const BODY: &str = "[domain]\ngamma_min = 1.70\ngamma_max = 1.74\nalpha_max = \"inf\"\n\
                    e_n_min = 0.95\ne_n_max = 1.0\n[nodes]\ntarget_error = 4e-5\n\
                    leaf_intervals = 6\nblocks_coord = 8\ne_n_coordinate = \"MAP\"\n\
                    [solver]\nlaw = \"thornton\"\ntol = 4e-6\n[checks]\nper_patch = 5\n";

/// A quarter-root table with the knots of the partial-slip coordinate: `e_n` 0.9–1, whose
/// knots' region ends at `e_n` 0.98 or below, 0.3125 of the root cell along the mapped axis
/// (`e_n` ≈ 0.978, where a linear axis would put 0.93125).
const KNOTTED: &str = "[domain]\ngamma_min = 1.70\ngamma_max = 1.74\nalpha_max = \"inf\"\n\
                       e_n_min = 0.9\ne_n_max = 1.0\n[nodes]\ntarget_error = 1e-4\n\
                       leaf_intervals = 6\nblocks_coord = 8\nknots = true\n\
                       e_n_coordinate = \"quarter-root\"\n[solver]\nlaw = \"thornton\"\n\
                       tol = 4e-6\n[checks]\nper_patch = 5\n";

/// The quarter-root table of [`BODY`], built once per test process.
fn quarter() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| build_table("quarter", "t", &BODY.replace("MAP", "quarter-root")))
}

/// The table of [`KNOTTED`], built once per test process.
fn knotted() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| build_table("knotted", "k", KNOTTED))
}

/// `sweep export` of `table` into a fresh folder `dir`: the export and what the command said.
fn export_of(table: &Path, dir: &str) -> (PathBuf, String) {
    let out = common::subdir(dir).join("t.oblq");
    let said = ok(&[
        "export",
        table.to_str().expect("path"),
        "-o",
        out.to_str().expect("path"),
    ]);
    (out, said)
}

/// The C driver `tests/c/eval_check.c`, compiled once per test process.
fn driver() -> &'static Path {
    static D: OnceLock<PathBuf> = OnceLock::new();
    D.get_or_init(|| gcc_driver(&common::subdir("driver").join("eval_check"), &[]))
}

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

/// `n` points over the domain of `t` for the bit comparisons: γ uniform (its ends now and
/// then), α in partial slip (below `α_c2`) for half of them, `α/(1 + α)` uniform for the rest
/// (0, `α_c2`, one ulp either side of it and ∞ in the mix), and `e_n` at the ends of its range
/// exactly, one and a few ulps below 1, `1 − e_n` log-uniform down to 1e-16 and uniform over
/// the range.
fn bit_points(t: &Table, n: usize, seed: u64) -> Vec<(f64, f64, f64)> {
    let s = t.surface();
    let (g_lo, g_hi) = (s.gamma_min(), s.gamma_max());
    let (e_lo, e_hi) = t.restitution().expect("an e_n axis");
    let mut r = SplitMix(seed);
    (0..n)
        .map(|i| {
            let g = match i % 53 {
                0 => g_lo,
                1 => g_hi,
                _ => g_lo + (g_hi - g_lo) * r.uniform(),
            };
            let e = match i % 11 {
                0 => e_lo,
                1 => e_hi,
                2 => f64::from_bits(e_hi.to_bits() - 1 - (i as u64 / 11) % 4),
                3..=5 => {
                    let top = (e_hi - e_lo).log10();
                    (e_hi - 10f64.powf(-16.0 + (16.0 + top) * r.uniform())).max(e_lo)
                }
                _ => e_lo + (e_hi - e_lo) * r.uniform(),
            };
            let c2 = alpha_c2(g);
            let a = match i % 29 {
                0 => 0.0,
                1 => c2,
                2 => f64::from_bits(c2.to_bits() + 1),
                3 => f64::from_bits(c2.to_bits() - 1),
                4 => f64::INFINITY,
                k if k % 2 == 0 => c2 * r.uniform(),
                _ => {
                    let w = r.uniform();
                    w / (1.0 - w)
                }
            };
            (g, a, e)
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

/// `scripts/read_table.py` on `path` refuses it (status 2), its message naming every one of
/// `want` ([`common::python_refuses`] at one query).
fn python_refuses(path: &Path, want: &[&str]) {
    common::python_refuses(
        path,
        &["--gamma", "1.72", "--alpha", "0.5", "--e-n", "0.99"],
        want,
    );
}

#[test]
fn next_to_e_n_one_only_the_quarter_root_axis_holds_its_bound() {
    let linear = build_table("linear", "t", &BODY.replace("MAP", "linear"));
    let quarter = quarter();
    let pts = points(120);
    let truth: Vec<f64> = pts.iter().map(|&(g, a, e)| solve(g, a, e)).collect();
    let lin = Table::open(&linear).expect("open");
    let qr = Table::open(quarter).expect("open");
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
    // `sweep inspect` names the map (text and JSON).
    let text = ok(&["inspect", q]);
    assert!(
        text.contains("e_n in [0.95, 1] over (1-e_n)^(1/4)"),
        "{text}"
    );
    for (path, want) in [
        (q, "(1-e_n)^(1/4)"),
        (linear.to_str().expect("path"), "e_n"),
    ] {
        let v: serde_json::Value =
            serde_json::from_str(&ok(&["inspect", path, "--json"])).expect("JSON");
        assert_eq!(v["e_n_coordinate"].as_str(), Some(want), "{v}");
    }
}

/// A map a reader does not know, a schema-5 file without its map, the linear name on the
/// quarter-root table (its nodes are not where a linear axis puts them) and a map on a table
/// without an `e_n` axis are refused by the Rust reader and the reference reader, naming what
/// is wrong.
#[test]
fn readers_refuse_a_map_they_cannot_use() {
    let dir = common::subdir("refused");
    let quick = Path::new(ROOT).join("tables/quick.h5");
    for (name, src, edit, needle) in [
        (
            "unknown",
            quarter(),
            "f.attrs['e_n_coordinate'] = 'sqrt(1-e_n)'",
            "sqrt(1-e_n)",
        ),
        (
            "missing",
            quarter(),
            "del f.attrs['e_n_coordinate']",
            "e_n_coordinate",
        ),
        (
            "named_linear",
            quarter(),
            "f.attrs['e_n_coordinate'] = 'e_n'",
            "e_n[",
        ),
        (
            "elastic",
            quick.as_path(),
            "f.attrs['schema_version'] = 5.0; f.attrs['axes'] = 'gamma,alpha'; \
             f.attrs['e_n_coordinate'] = '(1-e_n)^(1/4)'",
            "e_n_coordinate",
        ),
    ] {
        let bad = dir.join(format!("{name}.h5"));
        common::edited_copy(src, &bad, edit);
        let err = Table::open(&bad).expect_err("refused").to_string();
        assert!(err.contains(needle), "{name}: {err}");
        python_refuses(&bad, &[needle]);
    }
    // The map itself, named as schema 5 names it, is read by both.
    common::python_check_stored(Path::new(quarter()));
}

/// `sweep export` writes a quarter-root table as layout version 8: the version it would have
/// with a linear axis (4, Thornton's law; 5 with knots) with the map `1` at offset 84. `Table::
/// p_e`, the reference reader on the file and `oblq_p_e` of the C header on the export give
/// the same bits at 3 000 points per table, `e_n` at the ends of its range and down to one ulp
/// below 1 included, and next to the knots' region, which the map places along `e_n`. Read as
/// its linear version (the map dropped), the export answers otherwise.
#[test]
fn the_export_and_the_reference_reader_give_the_bits_of_p_e() {
    for (table, dir, base) in [
        (quarter(), "export-quarter", 4u32),
        (knotted(), "export-knotted", 5),
    ] {
        let (export, said) = export_of(table, dir);
        assert!(said.contains("over (1-e_n)^(1/4)"), "{said}");
        let bytes = std::fs::read(&export).expect("export");
        let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4"));
        assert_eq!(
            (u32_at(8), u32_at(12), u32_at(68), u32_at(84)),
            (8, 112, 1, 1),
            "version 8, 112-byte header, no full-slip line, the map"
        );
        let t = Table::open(table).expect("open");
        let n = 3000;
        let mut pts = bit_points(&t, n, 0x6d_6170 + u64::from(base));
        let partial = t
            .surface()
            .patch_by_id(PatchId::PartialHigh)
            .expect("partial_high");
        if base == 5 {
            let dir_at = u64::from_le_bytes(bytes[72..80].try_into().expect("8")) as usize;
            assert_ne!(
                u32_at(dir_at + 160 + 152),
                0,
                "the knots block of partial_high"
            );
            // In partial slip next to the top of the knots' region along e_n: where the map
            // puts it, and where a linear axis would.
            let k = partial.knots().expect("knots");
            let (e_lo, e_hi) = t.restitution().expect("an e_n axis");
            let top = k.region()[3];
            let axis = partial.restitution().expect("the e_n axis");
            let blocks = axis.blocks() as f64;
            let e_mapped = axis.at(top / blocks);
            let e_linear = e_lo + (e_hi - e_lo) * top / blocks;
            assert!(e_linear + 0.02 < e_mapped, "{e_linear} vs {e_mapped}");
            // `sweep inspect` states the region's e_n through the map, not linearly.
            let text = ok(&["inspect", table.to_str().expect("path")]);
            let line = text
                .lines()
                .find(|l| l.contains("knots:") && l.contains("c' = 0.5, 0.625"))
                .unwrap_or_else(|| panic!("no knots line: {text}"));
            assert!(
                line.contains(&format!(", {e_mapped}]")) && !line.contains(&format!("{e_linear}]")),
                "{line}: region top {e_mapped} (a linear axis: {e_linear})"
            );
            let mut r = SplitMix(5);
            let mut between = 0;
            for i in 0..1000 {
                let g = 1.70 + 0.04 * r.uniform();
                let e = match i % 4 {
                    0 => e_mapped + 1e-9 * (2.0 * r.uniform() - 1.0),
                    _ => e_linear + (e_mapped - e_linear) * r.uniform(),
                };
                let a = alpha_c2(g) * r.uniform();
                between += usize::from(e > e_linear && partial.knots_at(g, e).is_some());
                pts.push((g, a, e));
            }
            assert!(
                between > 500,
                "{between} points inside the region above {e_linear}"
            );
        }
        assert_same_bits(&t, table, &export, driver(), &pts);

        // The same bytes read as the linear version: other answers inside the range.
        let mut linear = bytes.clone();
        linear[8..12].copy_from_slice(&base.to_le_bytes());
        linear[84..88].copy_from_slice(&0u32.to_le_bytes());
        let relabelled = export.with_file_name("linear.oblq");
        std::fs::write(&relabelled, sealed(linear)).expect("write");
        let input: String = pts
            .iter()
            .map(|(g, a, e)| format!("{g:?} {a:?} {e:?}\n"))
            .collect();
        let out = run_ok(
            driver(),
            &["pe", relabelled.to_str().expect("path"), "0"],
            &input,
        );
        let differ = pts
            .iter()
            .zip(out.lines().skip(1))
            .filter(|&(&(g, a, e), line)| {
                line.parse::<f64>().expect("P").to_bits()
                    != t.p_e(g, a, e).expect("inside").to_bits()
            })
            .count();
        assert!(differ > pts.len() / 2, "{differ} of {} differ", pts.len());
        eprintln!(
            "{}: {} points the same bits in Rust, read_table.py and C; read as version {base}, \
             {differ} differ",
            table.display(),
            pts.len()
        );
    }
}

/// The C header refuses an export whose map contradicts its version (`OBLQ_E_CORRUPT`): version
/// 8 without the map, with a map it does not know, the map in version 4, in an elastic table's
/// export (version 1, or labelled 8 with its 96-byte header); and a later version by its
/// version (`OBLQ_E_VERSION`). Mutated copies of a version-8 export with knots, through the
/// driver compiled with AddressSanitizer and UndefinedBehaviorSanitizer, never read out of
/// bounds and answer within `[−1, 1]` when they open.
#[test]
fn the_c_header_refuses_a_map_that_contradicts_the_version() {
    let (export, _) = export_of(quarter(), "map-damaged");
    let good = std::fs::read(&export).expect("export");
    let dir = export.parent().expect("folder").to_path_buf();
    let open = |name: &str, bytes: &[u8]| -> String {
        let p = dir.join(format!("{name}.oblq"));
        std::fs::write(&p, bytes).expect("write");
        run_ok(driver(), &["open", p.to_str().expect("path")], "")
    };
    assert!(open("good", &good).starts_with("0 ok"));
    let with = |bytes: &[u8], edits: &[(usize, u32)]| {
        let mut b = bytes.to_vec();
        for &(at, v) in edits {
            b[at..at + 4].copy_from_slice(&v.to_le_bytes());
        }
        sealed(b)
    };
    for (name, edits) in [
        ("map_0", vec![(84, 0)]),
        ("map_2", vec![(84, 2)]),
        ("map_max", vec![(84, u32::MAX)]),
        ("v4_mapped", vec![(8, 4)]),
        ("v5_mapped", vec![(8, 5)]),
        ("v2_mapped", vec![(8, 2), (68, 0)]),
    ] {
        let said = open(name, &with(&good, &edits));
        assert!(said.starts_with("6 "), "{name}: {said}");
    }
    assert!(open("newer", &with(&good, &[(8, 9)])).starts_with("4 "));
    // An elastic table's export (version 1) with the map, and labelled 8 as well.
    let quick = dir.join("quick.oblq");
    ok(&[
        "export",
        Path::new(ROOT)
            .join("tables/quick.h5")
            .to_str()
            .expect("path"),
        "-o",
        quick.to_str().expect("path"),
    ]);
    let elastic = std::fs::read(&quick).expect("export");
    assert!(open("elastic", &elastic).starts_with("0 ok"));
    for (name, edits) in [
        ("elastic_mapped", vec![(84, 1)]),
        ("elastic_v8", vec![(8, 8), (84, 1)]),
    ] {
        let said = open(name, &with(&elastic, &edits));
        assert!(said.starts_with("6 "), "{name}: {said}");
    }

    let (export, _) = export_of(knotted(), "map-asan");
    let exe = gcc_driver(
        &dir.join("eval_check_asan"),
        &[
            "-g",
            "-fsanitize=address,undefined",
            "-fno-sanitize-recover=all",
        ],
    );
    let path = export.to_str().expect("path");
    for args in [vec!["fuzz", path, "400", "31"], vec!["headers", path]] {
        let out = Command::new(&exe).args(&args).output().expect("run");
        assert!(
            out.status.success(),
            "{args:?}: {}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("refused"), "{text}");
    }
}
