//! Helpers shared by the tests of the dependency-free evaluator (`tests/c_evaluator.rs`,
//! `tests/fortran.rs`): running a compiled program on an input, the random bodies, impacts and
//! points both compare with the Rust library, and a small table with an `e_n` axis.

// Each test file uses a part of this module.
#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use oblique_lookup::rebound::{Body, Incident3, Motion3, Rebound3};
use oblique_lookup::{Answer, Table};
use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2};
use oblique_physics::sample::SplitMix;

/// Run `exe` with `args`, `input` on its standard input. A program that exits early may leave
/// the input unread; that is an error only when it succeeds.
pub fn run(exe: &Path, args: &[&str], input: &str) -> Output {
    let mut child = Command::new(exe)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("spawn {}: {e}", exe.display()));
    let mut stdin = child.stdin.take().expect("stdin");
    let input = input.to_owned();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("wait");
    let written = writer.join().expect("writer");
    if out.status.success() {
        written.expect("write stdin");
    }
    out
}

/// [`run`], requiring success; the standard output.
pub fn run_ok(exe: &Path, args: &[&str], input: &str) -> String {
    let out = run(exe, args, input);
    assert!(
        out.status.success(),
        "{} {args:?}: {}\n{}",
        exe.display(),
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

/// A sphere of random mass (0.1–10 g), radius (1–11 mm) and inertia factor (0.2–0.8).
pub fn random_body(r: &mut SplitMix) -> Body {
    Body {
        mass: 1e-4 + 1e-2 * r.uniform(),
        radius: 1e-3 + 1e-2 * r.uniform(),
        kappa: 0.2 + 0.6 * r.uniform(),
    }
}

/// A vector with components uniform in `[−scale, scale]`.
pub fn random_vec3(r: &mut SplitMix, scale: f64) -> [f64; 3] {
    [
        scale * (2.0 * r.uniform() - 1.0),
        scale * (2.0 * r.uniform() - 1.0),
        scale * (2.0 * r.uniform() - 1.0),
    ]
}

/// A random 3-D impact on a wall (the other body at rest) or of two spheres: a normal in the
/// unit cube, velocities up to 3 m/s, spins up to 500 rad/s; `None` unless the bodies approach
/// along the normal faster than 1e-3 (so that a caller drawing until it has enough keeps the
/// same stream of draws).
pub fn random_impact(r: &mut SplitMix, wall: bool) -> Option<Incident3> {
    let n = random_vec3(r, 1.0);
    let s = Incident3 {
        sphere: Motion3 {
            velocity: random_vec3(r, 3.0),
            spin: random_vec3(r, 500.0),
        },
        other: if wall {
            Motion3::default()
        } else {
            Motion3 {
                velocity: random_vec3(r, 3.0),
                spin: random_vec3(r, 500.0),
            }
        },
        normal: n,
    };
    let d: Vec<f64> = (0..3)
        .map(|k| s.sphere.velocity[k] - s.other.velocity[k])
        .collect();
    (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] > 1e-3).then_some(s)
}

/// The fields of a 3-D rebound the C and Fortran programs print, in their order: sphere 1's
/// velocity and spin, sphere 2's (zero for a wall), P, e_t, the energy lost, α, `|u0|`.
pub fn rebound_fields(a: &Answer<Rebound3>) -> Vec<f64> {
    let b = &a.rebound;
    let o = b.other.unwrap_or_default();
    [b.sphere.velocity, b.sphere.spin, o.velocity, o.spin]
        .iter()
        .flatten()
        .copied()
        .chain([b.p, b.e_t, b.energy_lost, a.alpha, b.slip_before])
        .collect()
}

/// Run the sweep binary; its standard output (it must succeed).
pub fn sweep_ok(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run the sweep binary");
    assert!(
        out.status.success(),
        "sweep {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8")
}

/// A small table with an e_n axis, e_n in [0.7, 1], built in the folder `d` with the CLI (about
/// 2.5 s on 2 cores): γ from 0.9 to 1.6, so that all three patches are there, and octree leaves
/// of depth 1 in partial slip; and its export by `sweep export` (layout version 2), `d/kv.oblq`.
pub fn dissipative_table(d: &Path) -> (Table, PathBuf) {
    std::fs::create_dir_all(d).expect("folder");
    let (table, cfg, export) = (d.join("kv.h5"), d.join("kv.toml"), d.join("kv.oblq"));
    std::fs::write(
        &cfg,
        format!(
            "output = {:?}\n[domain]\ngamma_min = 0.9\ngamma_max = 1.6\n\
             e_n_min = 0.7\ne_n_max = 1.0\n[nodes]\ntarget_error = 4e-4\n\
             leaf_intervals = 6\nblocks_coord = 2\n[solver]\ntol = 4e-5\n\
             [checks]\nper_patch = 30\n",
            table.display().to_string()
        ),
    )
    .expect("write config");
    let path = |p: &Path| p.to_str().expect("utf-8 path").to_string();
    sweep_ok(&["run", &path(&cfg), "--quiet"]);
    let said = sweep_ok(&["export", &path(&table), "-o", &path(&export)]);
    assert!(said.contains("e_n in [0.7, 1]"), "{said}");
    let t = Table::open(&table).expect("the table");
    assert_eq!(t.restitution(), Some((0.7, 1.0)));
    assert!(t.surface().patches().count() == 3);
    (t, export)
}

/// The curves of [`anisotropic_table`]'s export: `γ < 1`, an isotropic material's `γ` and two
/// in the warped range.
pub const ANISOTROPIC_GAMMAS: [f64; 4] = [0.3, 1.749_785_860_077_429_9, 2.6, 3.2];

/// A small elastic table whose split cells halve only the axes they need
/// (`nodes.anisotropic`, split masks 1 to 3 over `(γ, c)`) with a warp, γ from 0.1 to 3.5,
/// built once for every test process of this build (`common::shared_build`, about 15 s on 2
/// cores); and its export with the curves of [`ANISOTROPIC_GAMMAS`] by `sweep export` (layout
/// version 6) into the folder `d`, `d/anisotropic.oblq`. Panics unless some split cell halves
/// one axis only (mask 1 or 2) and the partial-slip patch has a warp: a reader that ignored
/// the masks would answer such a table wrongly.
pub fn anisotropic_table(d: &Path) -> (Table, PathBuf, PathBuf) {
    std::fs::create_dir_all(d).expect("folder");
    let cfg = d.join("anisotropic.toml");
    std::fs::write(
        &cfg,
        "output = \"unused.h5\"\n[domain]\ngamma_min = 0.1\ngamma_max = 3.5\n\
         alpha_max = \"inf\"\n[nodes]\ntarget_error = 4e-4\nleaf_intervals = 8\n\
         fold_warp = true\nanisotropic = true\n[solver]\ntol = 4e-5\n[checks]\n\
         per_patch = 30\n",
    )
    .expect("write config");
    let table = crate::common::shared_build(&cfg);
    let export = d.join("anisotropic.oblq");
    let path = |p: &Path| p.to_str().expect("utf-8 path").to_string();
    let mut args = vec![
        "export".to_string(),
        path(&table),
        "-o".into(),
        path(&export),
    ];
    for g in ANISOTROPIC_GAMMAS {
        args.extend(["--gamma".to_string(), format!("{g:?}")]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let said = sweep_ok(&args);
    assert!(said.contains("the table and 4 curves"), "{said}");
    let bytes = std::fs::read(&export).expect("the export");
    assert_eq!(bytes[8..12], 6u32.to_le_bytes(), "layout version 6");
    let t = Table::open(&table).expect("the table");
    let s = t.surface();
    let one_axis = s
        .patches()
        .filter_map(|(_, p)| p.split())
        .flatten()
        .filter(|&&m| m == 1 || m == 2)
        .count();
    assert!(one_axis > 10, "{one_axis} cells halve one axis only");
    assert!(
        s.patches().any(|(_, p)| p.warp().is_some()),
        "the partial-slip patch has a warp"
    );
    (t, export, table)
}

/// Random `(γ, α, e_n)` with `γ` in `[g_lo, g_hi]` and `e_n` in `[e_lo, e_hi]`; α = 0, ∞, α_c2
/// and α_c1(γ, e_n) in the mix, `γ = 1` and the ends of the `e_n` range now and then.
pub fn points_e(n: usize, seed: u64, g: (f64, f64), e: (f64, f64)) -> Vec<(f64, f64, f64)> {
    let mut r = SplitMix(seed);
    (0..n)
        .map(|i| {
            let gamma = if i % 101 == 7 {
                1.0
            } else {
                g.0 + (g.1 - g.0) * r.uniform()
            };
            let e_n = match i % 89 {
                0 => e.0,
                1 => e.1,
                _ => e.0 + (e.1 - e.0) * r.uniform(),
            };
            let alpha = match i % 50 {
                0 => f64::INFINITY,
                1 => 0.0,
                2 => alpha_c2(gamma),
                3 if gamma > 1.0 => alpha_c1_dissipative(gamma, e_n),
                4 if gamma > 1.0 => alpha_c1_dissipative(gamma, e_n) * (1.0 + 1e-12),
                _ => 3.0 * r.uniform() * r.uniform(),
            };
            (gamma, alpha, e_n)
        })
        .collect()
}

/// The status `oblq_p_e` gives where the Rust rule refuses `(γ, α)` with `err`.
pub fn status_of(err: &oblique_lookup::LookupError, g: f64, a: f64) -> i32 {
    use oblique_lookup::LookupError::Query;
    match err {
        Query { name: "e_n", .. } => 24,
        Query { name: "gamma", .. } if g.is_finite() && g > 0.0 => 9,
        Query { name: "gamma", .. } => 7,
        Query { name: "alpha", .. } if a >= 0.0 => 10,
        Query { name: "alpha", .. } => 8,
        other => panic!("unexpected refusal: {other}"),
    }
}

/// `P(γ, α, e_n)` of the reference reader `scripts/read_table.py` at `pts` (one `repr` a
/// point, the same text Rust's `{:?}` parses back to the same bits).
pub fn python_p_e(table: &Path, pts: &[(f64, f64, f64)]) -> Vec<f64> {
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table\n\
                  t = Table(sys.argv[2])\n\
                  out = []\n\
                  for line in sys.stdin:\n    \
                      g, a, e = (float(x) for x in line.split(','))\n    \
                      out.append(repr(t.p_e(g, a, e)))\n\
                  sys.stdout.write('\\n'.join(out) + '\\n')\n";
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?},{a:?},{e:?}\n"))
        .collect();
    let scripts = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts");
    let args = [
        "-c",
        script,
        scripts.to_str().expect("path"),
        table.to_str().expect("path"),
    ];
    run_ok(Path::new("python3"), &args, &input)
        .lines()
        .map(|l| l.parse().unwrap_or_else(|_| panic!("read_table.py: {l}")))
        .collect()
}

/// `b` with its checksum recomputed (an export edited after it was written, resealed).
pub fn sealed(mut b: Vec<u8>) -> Vec<u8> {
    let sum = oblique_table::format::fnv1a64(&b[32..]);
    b[24..32].copy_from_slice(&sum.to_le_bytes());
    b
}

/// The flags every C compilation of the evaluator's tests starts with: C99, every warning an
/// error, pedantic.
pub const C_STRICT: [&str; 5] = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"];

/// The driver `tests/c/eval_check.c` compiled with gcc (C99, warnings as errors, no fused
/// multiply-add) and the further `flags` (sanitizers) into `exe`.
pub fn gcc_driver(exe: &Path, flags: &[&str]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("gcc")
        .args(C_STRICT)
        .arg("-O2")
        .args(flags)
        .arg("-I")
        .arg(root.join("include"))
        .arg("-o")
        .arg(exe)
        .arg(root.join("tests/c/eval_check.c"))
        .arg("-lm")
        .output()
        .unwrap_or_else(|e| panic!("cannot run gcc ({e}): install it (scripts/setup.sh does)"));
    assert!(
        out.status.success(),
        "gcc tests/c/eval_check.c failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe.to_path_buf()
}

/// `Table::p_e` of `t` (opened from `table`), the reference reader `scripts/read_table.py` on
/// that file and `oblq_p_e` of the C driver `driver` on `export` give the same bits at every
/// point of `pts`.
pub fn assert_same_bits(
    t: &Table,
    table: &Path,
    export: &Path,
    driver: &Path,
    pts: &[(f64, f64, f64)],
) {
    let n = pts.len();
    let rust: Vec<f64> = pts
        .iter()
        .map(|&(g, a, e)| t.p_e(g, a, e).expect("inside the domain"))
        .collect();
    let py = python_p_e(table, pts);
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?} {a:?} {e:?}\n"))
        .collect();
    let out = run_ok(driver, &["pe", export.to_str().expect("path"), "0"], &input);
    let c: Vec<f64> = out
        .lines()
        .skip(1)
        .map(|l| l.parse().unwrap_or_else(|_| panic!("oblq_p_e: {l}")))
        .collect();
    assert_eq!((py.len(), c.len()), (n, n), "every point answered");
    for (i, &(g, a, e)) in pts.iter().enumerate() {
        assert_eq!(
            (py[i].to_bits(), c[i].to_bits()),
            (rust[i].to_bits(), rust[i].to_bits()),
            "γ {g:?}, α {a:?}, e_n {e:?}: Rust {:?}, read_table.py {:?}, C {:?}",
            rust[i],
            py[i],
            c[i]
        );
    }
}
