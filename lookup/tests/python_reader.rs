//! The Rust query path against the independent Python reference reader of the rule
//! (`scripts/read_table.py`, h5py + numpy), at a few thousand points of the shipped tables,
//! including the deepest leaves of `tables/full.h5`. Skipped (with a message) when `python3`
//! with h5py and numpy is not available.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};

use oblique_lookup::Table;

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

/// `P` from `scripts/read_table.py` at every point, or `None` when Python cannot run it.
fn python_p(table: &str, points: &[(f64, f64)]) -> Option<Vec<f64>> {
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table\n\
                  t = Table(sys.argv[2])\n\
                  for line in sys.stdin:\n    \
                      g, a = (float(x) for x in line.split(','))\n    \
                      print(repr(t.p(g, a)))\n";
    let probe = Command::new("python3")
        .args(["-c", "import h5py, numpy"])
        .output();
    if !matches!(probe, Ok(ref o) if o.status.success()) {
        eprintln!("skipped: python3 with h5py and numpy is not available");
        return None;
    }
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(repo().join("scripts"))
        .arg(repo().join("tables").join(table))
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
    Some(
        text.lines()
            .map(|l| l.trim().parse::<f64>().expect("a number"))
            .collect(),
    )
}

#[test]
fn rust_and_python_readers_agree() {
    for (name, n) in [("full.h5", 3000), ("quick.h5", 1000)] {
        let t = Table::open(repo().join("tables").join(name)).expect(name);
        let s = &t.surface;
        let mut next = oblique_lookup::testing::uniform(0xA076_1D64_78BD_642F);
        let mut points = oblique_lookup::testing::domain_points_from(s, n, &mut next);
        // The partial-slip band at large γ, where the leaves are deepest.
        if s.gamma_max > 2.5 {
            for _ in 0..n / 2 {
                let g = 2.5 + (s.gamma_max - 2.5) * next();
                let c1 = oblique_lookup::surface::alpha_c1(g);
                let c2 = oblique_lookup::surface::alpha_c2(g);
                points.push((g, c1 + (c2 - c1) * next()));
            }
        }
        let Some(reference) = python_p(name, &points) else {
            return;
        };
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
