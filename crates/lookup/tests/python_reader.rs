//! The Rust query path against the independent Python reference reader of the rule
//! (`scripts/read_table.py`, h5py + numpy), at a few thousand points of the shipped tables,
//! including the deepest leaves of `tables/full.h5`. Skipped (with a message) when `python3`
//! with h5py and numpy is not available.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use oblique_lookup::Table;

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The numbers `script` prints (one per line) when run by python3 with the arguments
/// `scripts/`, the table `tables/TABLE` and `extra`, and the points on standard input as
/// `gamma,alpha` lines.
fn run_python(script: &str, table: &str, extra: &[&str], points: &[(f64, f64)]) -> Vec<f64> {
    require_python();
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(repo().join("scripts"))
        .arg(repo().join("tables").join(table))
        .args(extra)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("run python3");
    let mut input = String::new();
    for (g, a) in points {
        // `{:?}` prints the shortest decimal that reads back to the same f64 (and `inf`).
        input.push_str(&format!("{g:?},{a:?}\n"));
    }
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("python3 output");
    writer.join().expect("writer").expect("write points");
    assert!(out.status.success(), "read_table.py failed");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    text.lines()
        .map(|l| l.trim().parse::<f64>().expect("a number"))
        .collect()
}

/// `P` from `scripts/read_table.py` at every point.
fn python_p(table: &str, points: &[(f64, f64)]) -> Vec<f64> {
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table\n\
                  t = Table(sys.argv[2])\n\
                  for line in sys.stdin:\n    \
                      g, a = (float(x) for x in line.split(','))\n    \
                      print(repr(t.p(g, a)))\n";
    run_python(script, table, &[], points)
}

#[test]
fn rust_and_python_readers_agree() {
    for (name, n) in [("full.h5", 3000), ("quick.h5", 1000)] {
        let t = Table::open(repo().join("tables").join(name)).expect(name);
        let s = &t.surface();
        let mut next = oblique_lookup::testing::uniform(0xA076_1D64_78BD_642F);
        let mut points = oblique_lookup::testing::domain_points_from(s, n, &mut next);
        // The partial-slip band at large γ, where the leaves are deepest.
        if s.gamma_max() > 2.5 {
            for _ in 0..n / 2 {
                let g = 2.5 + (s.gamma_max() - 2.5) * next();
                let c1 = oblique_table::surface::alpha_c1(g);
                let c2 = oblique_table::surface::alpha_c2(g);
                points.push((g, c1 + (c2 - c1) * next()));
            }
        }
        let reference = python_p(name, &points);
        assert_eq!(reference.len(), points.len());
        let mut worst = 0.0_f64;
        for (&(g, a), &r) in points.iter().zip(&reference) {
            let p = t.p(g, a).expect("inside the domain");
            worst = worst.max((p - r).abs());
            assert!(
                (p - r).abs() <= 1e-12,
                "{name} ({g}, {a}): Rust {p}, read_table.py {r}"
            );
        }
        eprintln!(
            "{name}: max |Rust - read_table.py| = {worst:e} over {} points",
            points.len()
        );
    }
}

/// `P` and the stated bound from `read_table.py` with the node values of every patch replaced
/// by noise next to ±1 (the same on both sides: `seed`-driven, see `noisy` below) when `noisy`.
fn python_bounded(table: &str, points: &[(f64, f64)], noisy: bool) -> (f64, Vec<f64>) {
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table\n\
                  t = Table(sys.argv[2])\n\
                  if sys.argv[3] == '1':\n    \
                      for p in t.patches.values():\n        \
                          flat = p.p.reshape(-1)\n        \
                          size = p.p.shape[1] * p.p.shape[2]\n        \
                          for i in range(flat.size):\n            \
                              sign = -1.0 if (i // size) % 2 == 0 else 1.0\n            \
                              flat[i] = sign * (1.0 - (0.0 if i % 3 == 0 else 0.1 * ((i * 7919) % 1000) / 1000))\n\
                  print(repr(t.error_bound))\n\
                  for line in sys.stdin:\n    \
                      g, a = (float(x) for x in line.split(','))\n    \
                      print(repr(t.p(g, a)))\n";
    let mut values = run_python(script, table, &[if noisy { "1" } else { "0" }], points);
    let bound = values.remove(0);
    (bound, values)
}

/// The Python reader applies step 10 (`|P| ≤ 1`) and derives the same stated bound: at the
/// point where `full.h5` answered −1.000008644 and near the minima P = −1 (γ ≈ 2.83, γ ≈ 1),
/// and on a noisy copy whose tensor product overshoots ±1 (the same bits as Rust's rule).
#[test]
fn python_reader_bounds_p_and_states_the_same_bound() {
    let t = Table::open(repo().join("tables").join("full.h5")).expect("full.h5");
    let mut next = oblique_lookup::testing::uniform(0x0DD_BA11);
    let mut points = vec![(2.829218718427729, 5.60402202817959)];
    for _ in 0..3000 {
        let g = if next() < 0.5 {
            2.80 + 0.06 * next()
        } else {
            0.97 + 0.06 * next()
        };
        let c2 = oblique_table::surface::alpha_c2(g);
        points.push((g, c2 + 40.0 * next() * next()));
    }
    let (bound, reference) = python_bounded("full.h5", &points, false);
    assert!(
        (bound - t.error_bound()).abs() <= 1e-12 * t.error_bound(),
        "Python bound {bound}, Rust {}",
        t.error_bound()
    );
    for (&(g, a), &r) in points.iter().zip(&reference) {
        assert!(r.abs() <= 1.0, "read_table.py: P({g}, {a}) = {r}");
        let p = t.p(g, a).expect("inside");
        assert!((p - r).abs() <= 1e-12, "({g}, {a}): Rust {p}, Python {r}");
    }
    // The noisy copy, the same noise on both sides.
    let t = oblique_lookup::testing::overshooting(t, |i| 0.1 * ((i * 7919) % 1000) as f64 / 1000.0);
    let points = oblique_lookup::testing::domain_points(t.surface(), 3000, 31);
    let (_, reference) = python_bounded("full.h5", &points, true);
    let mut at_one = 0;
    for (&(g, a), &r) in points.iter().zip(&reference) {
        assert!(r.abs() <= 1.0, "read_table.py (noisy): P({g}, {a}) = {r}");
        let p = t.p(g, a).expect("inside");
        assert!(
            (p - r).abs() <= 1e-12,
            "noisy ({g}, {a}): Rust {p}, Python {r}"
        );
        at_one += usize::from(r.abs() == 1.0);
    }
    assert!(
        at_one > 20,
        "only {at_one} points bounded: the test has no teeth"
    );
}

/// The cross-check needs python3 with h5py and numpy (`scripts/test` installs them): without
/// them the test fails, naming what is missing, instead of passing unchecked.
fn require_python() {
    let probe = Command::new("python3")
        .args(["-c", "import h5py, numpy"])
        .output();
    assert!(
        matches!(probe, Ok(ref o) if o.status.success()),
        "python3 with h5py and numpy is needed for the reference-reader cross-check \
         (pip install h5py numpy; scripts/test installs them)"
    );
}
