//! The optional warp of the partial-slip coordinate (schema 3, `docs/table-format.md`) in a
//! file: a shipped (schema-2) table edited to carry a warp is read by `Table::open` with the
//! warp applied on the query path (the same bits as `Surface::eval_with`, and the Python
//! reference reader agrees), and files with a bad warp are refused by both readers with a
//! message naming the attribute or dataset.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use oblique_lookup::testing::fork_guard;
use oblique_lookup::Table;
use oblique_table::format::seal_of;
use oblique_table::surface::{PatchId, Warp};

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("warp_file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir.join(name)
}

/// Seal a file edited on purpose (as `oblique_table::write::seal`).
fn seal(path: &Path) {
    let mut bytes = std::fs::read(path).expect("read");
    let s = seal_of(&bytes);
    bytes[..24].copy_from_slice(&s);
    std::fs::write(path, bytes).expect("write");
}

/// What to write into the warp group (`None`: leave the attribute or dataset out).
#[derive(Clone)]
struct Spec {
    patch: &'static str,
    schema: f64,
    start: Option<f64>,
    gamma_0: Option<f64>,
    gamma_step: Option<f64>,
    c_star: Option<f64>,
    knot: Option<Vec<f64>>,
}

/// A valid warp of `tables/quick.h5` (partial_high spans γ ∈ [1, 2.5] in 3 root rows): from
/// the third row on (γ ≥ 2), with a knot grid from 1.9.
fn good() -> Spec {
    Spec {
        patch: "partial_high",
        schema: 3.0,
        start: Some(2.0),
        gamma_0: Some(1.9),
        gamma_step: Some(0.05),
        c_star: Some(0.5),
        knot: Some(
            (0..13)
                .map(|i| 0.4 + 0.25 * (i as f64 * 0.5).sin() * (i as f64 / 12.0))
                .collect(),
        ),
    }
}

/// `tables/quick.h5` with a warp group as `spec` says, sealed again.
fn write(name: &str, spec: &Spec) -> PathBuf {
    let path = scratch(name);
    let _g = fork_guard();
    std::fs::copy(repo().join("tables/quick.h5"), &path).expect("copy quick.h5");
    {
        let f = hdf5::File::open_rw(&path).expect("open_rw");
        f.attr("schema_version")
            .unwrap()
            .write_scalar(&spec.schema)
            .unwrap();
        let g = f
            .group(&format!("patches/{}", spec.patch))
            .unwrap()
            .create_group("warp")
            .unwrap();
        for (a, v) in [
            ("start", spec.start),
            ("gamma_0", spec.gamma_0),
            ("gamma_step", spec.gamma_step),
            ("c_star", spec.c_star),
        ] {
            if let Some(v) = v {
                g.new_attr::<f64>()
                    .create(a)
                    .unwrap()
                    .write_scalar(&v)
                    .unwrap();
            }
        }
        if let Some(k) = &spec.knot {
            g.new_dataset_builder()
                .with_data(&k[..])
                .create("knot")
                .unwrap();
        }
    }
    seal(&path);
    path
}

fn python_ok() -> bool {
    let child = {
        let _g = fork_guard();
        Command::new("python3")
            .args(["-c", "import h5py, numpy"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
    };
    matches!(child.and_then(|mut c| c.wait()), Ok(st) if st.success())
}

/// Run `scripts/read_table.py` as a library on `path`: `P` at every point, or the error of
/// loading the table (`Err`).
fn python(path: &Path, points: &[(f64, f64)]) -> Result<Vec<f64>, String> {
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table, TableError\n\
                  try:\n    t = Table(sys.argv[2])\n\
                  except TableError as e:\n    print('ERROR', e)\n    sys.exit(0)\n\
                  for line in sys.stdin:\n    \
                      g, a = (float(x) for x in line.split(','))\n    \
                      print(repr(t.p(g, a)))\n";
    let guard = fork_guard();
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(repo().join("scripts"))
        .arg(path)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run python3");
    drop(guard);
    let input: String = points
        .iter()
        .map(|(g, a)| format!("{g:?},{a:?}\n"))
        .collect();
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("python3 output");
    let _ = writer.join().expect("writer");
    assert!(out.status.success(), "read_table.py failed");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    if let Some(e) = text.strip_prefix("ERROR ") {
        return Err(e.trim().to_string());
    }
    Ok(text
        .lines()
        .map(|l| l.trim().parse::<f64>().expect("a number"))
        .collect())
}

fn points(n: usize) -> Vec<(f64, f64)> {
    let mut next = oblique_lookup::testing::uniform(0x9E37_79B9_7F4A_7C15_u64);
    (0..n)
        .map(|i| {
            let g = 1.0 + 1.5 * next();
            if i % 3 == 0 {
                (0.5 + 2.0 * next(), 10f64.powf(-2.0 + 3.0 * next()))
            } else {
                // The partial-slip band, where the warp acts (γ ≥ 2).
                let (c1, c2) = (
                    oblique_table::surface::alpha_c1(g),
                    oblique_table::surface::alpha_c2(g),
                );
                (g, c1 + (c2 - c1) * next())
            }
        })
        .collect()
}

#[test]
fn a_file_with_a_warp_is_read_and_applied() {
    let spec = good();
    let path = write("good.h5", &spec);
    let t = Table::open(&path).expect("a valid warp");
    assert_eq!(t.provenance().schema_version, 3);
    let warp = t
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .and_then(|p| p.warp().cloned());
    assert_eq!(
        warp,
        Some(Warp::new(2.0, 1.9, 0.05, 0.5, spec.knot.clone().unwrap()).unwrap())
    );
    assert!(t
        .surface()
        .patch_by_id(PatchId::StickHigh)
        .unwrap()
        .warp()
        .is_none());
    let plain = Table::open(repo().join("tables/quick.h5")).expect("quick.h5");
    assert_eq!(plain.provenance().schema_version, 2);
    assert!(plain
        .surface()
        .patch_by_id(PatchId::PartialHigh)
        .unwrap()
        .warp()
        .is_none());
    let pts = points(3000);
    let mut changed = 0;
    for &(g, a) in &pts {
        let p = t.p(g, a).expect("inside");
        assert_eq!(
            p.to_bits(),
            t.surface().eval(g, a).unwrap().to_bits(),
            "({g}, {a})"
        );
        changed += usize::from(p != plain.p(g, a).unwrap());
    }
    assert!(changed > 500, "the warp changed only {changed} answers");
    let (g, a): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
    let mut out = vec![0.0; g.len()];
    t.p_batch(&g, &a, &mut out, oblique_lookup::OutOfDomain::Error)
        .expect("batch");
    for i in 0..g.len() {
        assert_eq!(out[i].to_bits(), t.p(g[i], a[i]).unwrap().to_bits());
    }
    if !python_ok() {
        eprintln!("skipped the Python comparison: python3 with h5py and numpy is not available");
        return;
    }
    let reference = python(&path, &pts).expect("Python reads the warp");
    let mut worst = 0.0_f64;
    for (&(g, a), &r) in pts.iter().zip(&reference) {
        let p = t.p(g, a).unwrap();
        worst = worst.max((p - r).abs());
        assert!((p - r).abs() <= 1e-12, "({g}, {a}): Rust {p}, Python {r}");
    }
    eprintln!("warped quick.h5: max |Rust - read_table.py| = {worst:e}");
}

#[test]
fn files_with_a_bad_warp_are_refused_naming_the_field() {
    let g = good();
    let cases: Vec<(&str, Spec, &[&str])> = vec![
        (
            "c_star_1_5",
            Spec {
                c_star: Some(1.5),
                ..g.clone()
            },
            &["c_star", "(0, 1)"],
        ),
        (
            "c_star_0",
            Spec {
                c_star: Some(0.0),
                ..g.clone()
            },
            &["c_star", "(0, 1)"],
        ),
        (
            "no_c_star",
            Spec {
                c_star: None,
                ..g.clone()
            },
            &["c_star"],
        ),
        (
            "knot_short",
            Spec {
                knot: Some(vec![0.4, 0.4, 0.4]),
                gamma_step: Some(0.3),
                ..g.clone()
            },
            &["knot", "at least 4"],
        ),
        (
            "knot_value",
            Spec {
                knot: Some({
                    let mut k = g.knot.clone().unwrap();
                    k[5] = 1.2;
                    k
                }),
                ..g.clone()
            },
            &["knot", "[5]", "(0, 1)"],
        ),
        (
            "knot_nan",
            Spec {
                knot: Some({
                    let mut k = g.knot.clone().unwrap();
                    k[2] = f64::NAN;
                    k
                }),
                ..g.clone()
            },
            &["knot", "[2]"],
        ),
        (
            "no_knot",
            Spec {
                knot: None,
                ..g.clone()
            },
            &["knot"],
        ),
        (
            "not_covering",
            Spec {
                // 1.9 + 12·0.04 = 2.38 < gamma_hi = 2.5.
                gamma_step: Some(0.04),
                ..g.clone()
            },
            &["gamma_step", "cover"],
        ),
        (
            "starts_above",
            Spec {
                gamma_0: Some(2.5),
                ..g.clone()
            },
            &["gamma_0", "cover"],
        ),
        (
            "start_straddles",
            Spec {
                // Inside root row 1, whose leaves are at most at depth 2.
                start: Some(1.3125),
                gamma_0: Some(1.4),
                gamma_step: Some(0.1),
                ..g.clone()
            },
            &["start", "straddle"],
        ),
        (
            "start_not_dyadic",
            Spec {
                start: Some(2.1),
                ..g.clone()
            },
            &["start", "2^-20"],
        ),
        (
            "start_at_the_end",
            Spec {
                start: Some(3.0),
                ..g.clone()
            },
            &["start", "(0, 3)"],
        ),
        (
            "no_start",
            Spec {
                start: None,
                ..g.clone()
            },
            &["start"],
        ),
        (
            "step_zero",
            Spec {
                gamma_step: Some(0.0),
                ..g.clone()
            },
            &["gamma_step", "> 0"],
        ),
        (
            "gamma_0_nan",
            Spec {
                gamma_0: Some(f64::NAN),
                ..g.clone()
            },
            &["gamma_0", "finite"],
        ),
        (
            "schema_2",
            Spec {
                schema: 2.0,
                ..g.clone()
            },
            &["schema", "warp"],
        ),
        (
            "stick_high",
            Spec {
                patch: "stick_high",
                ..g.clone()
            },
            &["stick_high", "only 'partial_high'"],
        ),
    ];
    let py = python_ok();
    for (name, spec, needles) in cases {
        let path = write(&format!("{name}.h5"), &spec);
        let msg = Table::open(&path).map(|_| ()).expect_err(name).to_string();
        for n in needles {
            assert!(msg.contains(n), "{name}: {msg:?} does not contain {n:?}");
        }
        if py {
            let e = python(&path, &[]).expect_err(&format!("Python accepted {name}"));
            for n in needles {
                assert!(
                    e.contains(n),
                    "{name} (Python): {e:?} does not contain {n:?}"
                );
            }
        }
    }
    // Edge of the coverage rule: a grid ending within 1e-12 (relative) below gamma_hi is
    // accepted.
    let path = write(
        "covering_edge.h5",
        &Spec {
            gamma_0: Some(2.5 - 12.0 * 0.05 - 1e-13),
            ..g.clone()
        },
    );
    Table::open(&path).expect("a grid within 1e-12 of gamma_hi");
}

#[test]
fn schema_6_is_refused() {
    let path = write(
        "schema6.h5",
        &Spec {
            schema: 6.0,
            ..good()
        },
    );
    let msg = Table::open(&path)
        .map(|_| ())
        .expect_err("schema 6")
        .to_string();
    assert!(msg.contains("schema version 6"), "{msg}");
}

#[test]
fn schema_4_without_its_axes_attribute_is_refused_naming_it() {
    let path = write(
        "schema4.h5",
        &Spec {
            schema: 4.0,
            ..good()
        },
    );
    let msg = Table::open(&path)
        .map(|_| ())
        .expect_err("schema 4 without axes")
        .to_string();
    assert!(msg.contains("'axes'"), "{msg}");
}
