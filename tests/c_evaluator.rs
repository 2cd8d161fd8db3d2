//! The dependency-free evaluator `include/oblique_eval.h` against the Rust library: the same P
//! on random points (10⁶ in the release check, `common::size`), the same curves and rebounds, the conservation laws, every refusal, and
//! mutated exports under AddressSanitizer and UndefinedBehaviorSanitizer. The C side is
//! `examples/c/query.c` and the driver `tests/c/eval_check.c`, compiled here with gcc, g++ and
//! clang (scripts/setup.sh installs clang; a missing compiler fails the test).

mod common;
mod evaluator;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use common::size::sized;
use evaluator::{
    points_e, python_p_e, random_body, random_impact, rebound_fields, run_ok, sealed, status_of,
};
use oblique_lookup::rebound::{Body, Incident, Incident3, Motion3, Pair, State};
use oblique_lookup::{Contact, OutOfDomain, Prepared, Table};
use oblique_physics::regimes::{alpha_c1, alpha_c2, linear_limit};
use oblique_physics::sample::SplitMix;
use oblique_table::export;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const WARNINGS: [&str; 5] = ["-Wall", "-Wextra", "-Werror", "-pedantic", "-O2"];

fn root(p: &str) -> PathBuf {
    Path::new(ROOT).join(p)
}

/// This process's scratch folder for compiled programs and exports (made once).
fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| common::subdir("c_evaluator"))
}

/// What the C driver's `open` prints for `bytes` written to the scratch file `name`: `0 ok`, or
/// the status code and its message.
fn open_export(name: &str, bytes: &[u8]) -> String {
    let p = dir().join(name);
    std::fs::write(&p, bytes).expect("write");
    run_ok(gcc_driver(), &["open", p.to_str().expect("path")], "")
}

/// The little-endian `u32` at byte `at` of an export.
fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().expect("4"))
}

/// The little-endian `u64` at byte `at` of an export.
fn u64_at(b: &[u8], at: usize) -> u64 {
    u64::from_le_bytes(b[at..at + 8].try_into().expect("8"))
}

/// A patch record of an export that names split masks (offset 144, `docs/export-format.md`).
struct MaskedRecord {
    /// The patch's index (0 `stick_low`, 1 `partial_high`, 2 `stick_high`).
    k: usize,
    /// Offset of the record.
    record: usize,
    /// Offset of the masks, one byte per cell.
    masks: usize,
    /// Cells of the tree.
    cells: usize,
    /// Offset of the tree (`i32` per cell).
    tree: usize,
}

impl MaskedRecord {
    /// The tree's entry for cell `i` of export `b`: the first child (≥ 0) or `−1 − leaf`.
    fn link(&self, b: &[u8], i: usize) -> i32 {
        i32::from_le_bytes(b[self.tree + 4 * i..][..4].try_into().expect("4"))
    }
}

/// The patch records of export `b` that name split masks.
fn masked_records(b: &[u8]) -> Vec<MaskedRecord> {
    let dir_at = u64_at(b, 72) as usize;
    (0..3)
        .map(|k| (k, dir_at + 160 * k))
        .filter(|&(_, r)| u64_at(b, r + 144) != 0)
        .map(|(k, r)| MaskedRecord {
            k,
            record: r,
            masks: u64_at(b, r + 144) as usize,
            cells: u32_at(b, r + 36) as usize,
            tree: u64_at(b, r + 48) as usize,
        })
        .collect()
}

/// Compile `src` with `compiler` and `flags` into `out` (in the scratch folder).
fn compile(compiler: &str, flags: &[&str], src: &str, out: &str) -> PathBuf {
    let exe = dir().join(out);
    let inc = root("include");
    let r = Command::new(compiler)
        .args(flags)
        .arg("-I")
        .arg(&inc)
        .arg("-o")
        .arg(&exe)
        .arg(root(src))
        .arg("-lm")
        .output()
        .unwrap_or_else(|e| {
            panic!("cannot run {compiler} ({e}): install it (scripts/setup.sh does)")
        });
    assert!(
        r.status.success(),
        "{compiler} {flags:?} {src} failed:\n{}",
        String::from_utf8_lossy(&r.stderr)
    );
    exe
}

fn gcc_driver() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let mut f = vec!["-std=c99"];
        f.extend(WARNINGS);
        compile("gcc", &f, "tests/c/eval_check.c", "eval_check")
    })
}

/// `examples/c/query.c` compiled once with gcc (C99, the warnings as errors), shared by the
/// comparisons on random points.
fn query_program() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(|| {
        let mut f = vec!["-std=c99"];
        f.extend(WARNINGS);
        compile("gcc", &f, "examples/c/query.c", "query")
    })
}

fn table(name: &str) -> &'static Table {
    static FULL: OnceLock<Table> = OnceLock::new();
    static QUICK: OnceLock<Table> = OnceLock::new();
    let cell = if name == "full" { &FULL } else { &QUICK };
    cell.get_or_init(|| Table::open(root(&format!("tables/{name}.h5"))).expect("shipped table"))
}

/// Curves of the export tests: γ ≤ 1, γ = 1 and above, an isotropic material, the warped range.
const GAMMAS: [f64; 6] = [0.3, 0.95, 1.0, 1.749_785_860_077_429_9, 2.6, 3.2];

/// The export of `name` with the curves of those `GAMMAS` inside its domain, written once per
/// process; its path.
fn export_file(name: &str, curves_only: bool) -> PathBuf {
    static MADE: OnceLock<std::sync::Mutex<Vec<String>>> = OnceLock::new();
    let file = format!("{name}{}.oblq", if curves_only { "_curves" } else { "" });
    let path = dir().join(&file);
    let mut made = MADE.get_or_init(Default::default).lock().expect("lock");
    if made.contains(&file) {
        return path;
    }
    let t = table(name);
    let s = t.surface();
    let curves: Vec<_> = GAMMAS
        .iter()
        .filter(|&&g| g >= s.gamma_min() && g <= s.gamma_max())
        .map(|&g| {
            t.curve(g, OutOfDomain::Error)
                .expect("curve")
                .export_data()
                .expect("inside the domain")
        })
        .collect();
    let bytes = export::export(s, t.error_bound(), !curves_only, &curves);
    std::fs::write(&path, bytes).expect("write export");
    made.push(file);
    path
}

/// Random points over the domain, with α = 0, ∞ and the critical curves in the mix.
fn points(n: usize, seed: u64, g_lo: f64, g_hi: f64) -> Vec<(f64, f64)> {
    let mut r = SplitMix(seed);
    (0..n)
        .map(|i| {
            let g = g_lo + (g_hi - g_lo) * r.uniform();
            let a = match i % 50 {
                0 => f64::INFINITY,
                1 => 0.0,
                2 => alpha_c2(g),
                3 if g > 1.0 => alpha_c1(g),
                _ => 3.0 * r.uniform() * r.uniform(),
            };
            (g, a)
        })
        .collect()
}

fn parse_line(line: &str) -> Vec<f64> {
    line.split([' ', ','])
        .map(|x| {
            x.parse::<f64>()
                .unwrap_or_else(|_| panic!("not a number: {line}"))
        })
        .collect()
}

#[test]
fn header_compiles_without_warnings_as_c99_cxx11_and_with_clang() {
    for (compiler, std, lang) in [
        ("gcc", "-std=c99", "c"),
        ("gcc", "-std=c11", "c"),
        ("g++", "-std=c++11", "c++"),
        ("g++", "-std=c++17", "c++"),
        ("clang", "-std=c99", "c"),
        ("clang++", "-std=c++11", "c++"),
    ] {
        let mut f = vec!["-x", lang, std];
        f.extend(WARNINGS);
        let out = format!("eval_check_{compiler}_{}", std.trim_start_matches("-std="));
        compile(compiler, &f, "tests/c/eval_check.c", &out);
        let mut f = vec!["-x", lang, std];
        f.extend(WARNINGS);
        compile(compiler, &f, "examples/c/query.c", &format!("query_{out}"));
    }
}

/// `examples/c/query.c` links libm and libc only and gives the bits of `Table::p` on random
/// points: 10⁶ of the shipped table and 10⁵ of the quick one in the release check, 10⁵ and
/// 2·10⁴ otherwise.
#[test]
fn query_example_gives_the_bits_of_the_rust_rule_on_random_points() {
    let query = query_program();
    // ldd: libm and libc only (and the loader).
    let ldd = Command::new("ldd").arg(query).output().expect("ldd");
    let libs = String::from_utf8_lossy(&ldd.stdout).to_string();
    for line in libs.lines() {
        let lib = line.trim();
        assert!(
            ["linux-vdso", "libm.so", "libc.so", "ld-linux"]
                .iter()
                .any(|ok| lib.starts_with(ok) || lib.contains(&format!("/{ok}"))),
            "query links {lib}:\n{libs}"
        );
    }
    for (name, n) in [
        ("full", sized(100_000, 1_000_000)),
        ("quick", sized(20_000, 100_000)),
    ] {
        let t = table(name);
        let s = t.surface();
        let pts = points(n, 7, s.gamma_min(), s.gamma_max());
        let input: String = pts.iter().map(|(g, a)| format!("{g:?},{a:?}\n")).collect();
        let path = export_file(name, false);
        let out = run_ok(query, &[path.to_str().expect("path")], &input);
        let mut differ = 0;
        let mut lines = 0;
        for ((g, a), line) in pts.iter().zip(out.lines()) {
            lines += 1;
            let c: f64 = line.rsplit(',').next().expect("P").parse().expect("P");
            let r = t.p(*g, *a).expect("inside");
            if c.to_bits() != r.to_bits() {
                differ += 1;
                if differ < 5 {
                    eprintln!("{name}: gamma {g:?} alpha {a:?}: C {c:?}, Rust {r:?}");
                }
            }
        }
        assert_eq!(lines, n, "{name}: every point answered");
        assert_eq!(
            differ, 0,
            "{name}: {differ} of {n} points differ in some bit"
        );
    }
}

#[test]
fn clamp_and_refusals_of_queries_match_the_rust_rule() {
    let path = export_file("quick", false);
    let t = table("quick");
    let s = t.surface();
    let pts = points(20_000, 9, 0.5 * s.gamma_min(), 1.2 * s.gamma_max());
    let input: String = pts.iter().map(|(g, a)| format!("{g:?} {a:?}\n")).collect();
    for clamp in [0, 1] {
        let out = run_ok(
            gcc_driver(),
            &["p", path.to_str().expect("path"), &clamp.to_string()],
            &input,
        );
        let outside = if clamp == 1 {
            OutOfDomain::Clamp
        } else {
            OutOfDomain::Error
        };
        let mut refused = 0;
        for ((g, a), line) in pts.iter().zip(out.lines()) {
            match t.p_with(*g, *a, outside) {
                Ok(r) => {
                    let c: f64 = line.parse().expect("P");
                    assert_eq!(
                        c.to_bits(),
                        r.to_bits(),
                        "gamma {g:?} alpha {a:?} clamp {clamp}"
                    );
                }
                Err(_) => {
                    refused += 1;
                    assert_eq!(line, "error 9", "gamma {g} alpha {a}: {line}");
                }
            }
        }
        assert_eq!(
            refused > 1000,
            clamp == 0,
            "clamp {clamp}: {refused} refused"
        );
    }
    // Invalid arguments, each with its code.
    let out = run_ok(
        gcc_driver(),
        &["p", path.to_str().expect("path"), "0"],
        "nan 0.5\n-1 0.5\ninf 0.5\n0 0.5\n1.5 -0.1\n1.5 nan\n",
    );
    assert_eq!(
        out.lines().collect::<Vec<_>>(),
        ["error 7", "error 7", "error 7", "error 7", "error 8", "error 8"]
    );
}

/// Curve `index` (at `gamma`) of `export` through the C driver at `n` values of α (every 40th
/// ∞, the next α_c2, the others `4·u·u`, seeded by `seed`): each answer has the bits of the
/// Rust curve of `t`. Returns the α and the C answers.
fn curve_bits(
    t: &Table,
    export: &Path,
    index: usize,
    gamma: f64,
    n: usize,
    seed: u64,
) -> Vec<(f64, f64)> {
    let curve = t.curve(gamma, OutOfDomain::Error).expect("curve");
    let mut r = SplitMix(seed);
    let alphas: Vec<f64> = (0..n)
        .map(|k| match k % 40 {
            0 => f64::INFINITY,
            1 => alpha_c2(gamma),
            _ => 4.0 * r.uniform() * r.uniform(),
        })
        .collect();
    let input: String = alphas.iter().map(|a| format!("{a:?}\n")).collect();
    let out = run_ok(
        gcc_driver(),
        &[
            "curve",
            export.to_str().expect("path"),
            &index.to_string(),
            "0",
        ],
        &input,
    );
    assert_eq!(
        out.lines().count(),
        alphas.len(),
        "every alpha answered by C"
    );
    alphas
        .iter()
        .zip(out.lines())
        .map(|(&a, line)| {
            let c: f64 = line.parse().expect("P");
            let want = curve.p(a).expect("valid");
            assert_eq!(c.to_bits(), want.to_bits(), "gamma {gamma} alpha {a:?}");
            (a, c)
        })
        .collect()
}

#[test]
fn curves_give_the_bits_of_the_rust_curves() {
    let t = table("full");
    for curves_only in [false, true] {
        let path = export_file("full", curves_only);
        for (i, &g) in GAMMAS.iter().enumerate() {
            for (a, c) in curve_bits(t, &path, i, g, 10_000, i as u64 + 3) {
                // And within 1e-13 of the table's rule itself.
                assert!((c - t.p(g, a).expect("inside")).abs() < 1e-13);
            }
        }
        // A curves-only export refuses P at any gamma above the line.
        if curves_only {
            let out = run_ok(
                gcc_driver(),
                &["p", path.to_str().expect("path"), "0"],
                "1.5 1\n1.5 0.01\n",
            );
            assert_eq!(
                out.lines().collect::<Vec<_>>(),
                ["error 11", "0.92999999999999994"]
            );
        }
    }
}

#[test]
fn rebounds_agree_with_the_rust_library_and_conserve_momentum_and_energy() {
    let t = table("full");
    let path = export_file("full", false);
    let mut r = SplitMix(21);
    for case in 0..24 {
        let wall = case % 3 == 0;
        let use_curve = case % 2 == 1;
        let b1 = random_body(&mut r);
        let b2 = random_body(&mut r);
        let pair = Pair {
            sphere: b1,
            other: (!wall).then_some(b2),
        };
        let gamma = GAMMAS[case % GAMMAS.len()];
        let mu = if case == 5 {
            f64::INFINITY
        } else {
            0.05 + r.uniform()
        };
        let contact = Contact::with_gamma(gamma, mu);
        let prepared = Prepared::new(&pair, &contact).expect("valid pair");
        let curve = t.curve(gamma, OutOfDomain::Error).expect("curve");
        let mut incidents = Vec::new();
        while incidents.len() < 500 {
            incidents.extend(random_impact(&mut r, wall));
        }
        let input: String = incidents
            .iter()
            .map(|s| {
                let v: Vec<String> = [
                    s.sphere.velocity,
                    s.sphere.spin,
                    s.other.velocity,
                    s.other.spin,
                    s.normal,
                ]
                .iter()
                .flatten()
                .map(|x| format!("{x:?}"))
                .collect();
                v.join(" ") + "\n"
            })
            .collect();
        let m2 = if wall { 0.0 } else { b2.mass };
        let args: Vec<String> = [
            "rebound".to_string(),
            path.display().to_string(),
            (if use_curve { "curve" } else { "table" }).to_string(),
            format!("{:?}", b1.mass),
            format!("{:?}", b1.radius),
            format!("{:?}", b1.kappa),
            format!("{m2:?}"),
            format!("{:?}", b2.radius),
            format!("{:?}", b2.kappa),
            format!("{gamma:?}"),
            format!("{mu:?}"),
        ]
        .to_vec();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(gcc_driver(), &args, &input);
        for (s, line) in incidents.iter().zip(out.lines()) {
            let c = parse_line(line);
            let a = if use_curve {
                t.rebound_3d_curve(&prepared, &curve, s)
            } else {
                t.rebound_3d_prepared(&prepared, s)
            }
            .expect("valid impact");
            let want = rebound_fields(&a);
            for (k, (x, y)) in c.iter().zip(&want).enumerate() {
                assert!(
                    x.to_bits() == y.to_bits() || (x - y).abs() <= 1e-13 * (1.0 + y.abs()),
                    "case {case} field {k}: C {x:?}, Rust {y:?}"
                );
            }
            // Conservation, on the C answer: momentum (spheres), energy balance.
            let (v1, w1, v2, w2) = (&c[0..3], &c[3..6], &c[6..9], &c[9..12]);
            let ke = |v: &[f64], w: &[f64], b: &Body| {
                0.5 * b.mass * v.iter().map(|x| x * x).sum::<f64>()
                    + 0.5 * b.inertia() * w.iter().map(|x| x * x).sum::<f64>()
            };
            let before = ke(&s.sphere.velocity, &s.sphere.spin, &b1)
                + if wall {
                    0.0
                } else {
                    ke(&s.other.velocity, &s.other.spin, &b2)
                };
            let after = ke(v1, w1, &b1) + if wall { 0.0 } else { ke(v2, w2, &b2) };
            let lost = c[14];
            assert!(lost >= 0.0 && c[12].abs() <= 1.0);
            assert!(
                (before - after - lost).abs() <= 1e-11 * before,
                "case {case}: energy {before} -> {after}, lost {lost}"
            );
            if !wall {
                for k in 0..3 {
                    let p0 = b1.mass * s.sphere.velocity[k] + b2.mass * s.other.velocity[k];
                    let p1 = b1.mass * v1[k] + b2.mass * v2[k];
                    assert!((p0 - p1).abs() <= 1e-12 * (b1.mass + b2.mass) * 10.0);
                }
            }
        }
    }
}

#[test]
fn rebound_2d_agrees_with_the_rust_algebra() {
    let t = table("full");
    let path = export_file("full", false);
    let mut r = SplitMix(5);
    for wall in [true, false] {
        let b1 = random_body(&mut r);
        let b2 = random_body(&mut r);
        let pair = Pair {
            sphere: b1,
            other: (!wall).then_some(b2),
        };
        let contact = Contact::with_gamma(1.6, 0.3);
        let mut states = Vec::new();
        while states.len() < 2000 {
            let s = Incident {
                sphere: State {
                    v_x: 3.0 * (2.0 * r.uniform() - 1.0),
                    v_z: 3.0 * r.uniform() + 0.1,
                    omega: 400.0 * (2.0 * r.uniform() - 1.0),
                },
                other: if wall {
                    State::default()
                } else {
                    State {
                        v_x: 2.0 * r.uniform() - 1.0,
                        v_z: -r.uniform(),
                        omega: 400.0 * (2.0 * r.uniform() - 1.0),
                    }
                },
            };
            states.push(s);
        }
        let input: String = states
            .iter()
            .map(|s| {
                format!(
                    "{:?} {:?} {:?} {:?} {:?} {:?}\n",
                    s.sphere.v_x,
                    s.sphere.v_z,
                    s.sphere.omega,
                    s.other.v_x,
                    s.other.v_z,
                    s.other.omega
                )
            })
            .collect();
        let m2 = if wall { 0.0 } else { b2.mass };
        let args = [
            "rebound2".to_string(),
            path.display().to_string(),
            format!("{:?}", b1.mass),
            format!("{:?}", b1.radius),
            format!("{:?}", b1.kappa),
            format!("{m2:?}"),
            format!("{:?}", b2.radius),
            format!("{:?}", b2.kappa),
            "1.6".into(),
            "0.3".into(),
        ];
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(gcc_driver(), &args, &input);
        for (s, line) in states.iter().zip(out.lines()) {
            let c = parse_line(line);
            let a = t.rebound(&pair, &contact, s).expect("valid");
            let b = &a.rebound;
            let o = b.other.unwrap_or_default();
            let want = [
                b.sphere.v_x,
                b.sphere.v_z,
                b.sphere.omega,
                o.v_x,
                o.v_z,
                o.omega,
                b.p,
                b.e_t,
                b.energy_lost,
                a.alpha,
                b.tangential_impulse,
            ];
            for (k, (x, y)) in c.iter().zip(want).enumerate() {
                let scale = 1.0 + y.abs() + if k < 6 { 400.0 * b1.radius } else { 0.0 };
                assert!(
                    (x - y).abs() <= 1e-12 * scale || (x.is_nan() && y.is_nan()),
                    "wall {wall} field {k}: C {x:?}, Rust {y:?}"
                );
            }
        }
    }
}

#[test]
fn damaged_truncated_and_foreign_files_are_refused_with_their_code() {
    let path = export_file("quick", false);
    let good = std::fs::read(&path).expect("export");
    let case = |name: &str, bytes: &[u8]| -> String {
        let p = dir().join(name);
        std::fs::write(&p, bytes).expect("write");
        let out = Command::new(gcc_driver())
            .args(["open", p.to_str().expect("path")])
            .output()
            .expect("run");
        assert!(out.status.success(), "{name}: {}", out.status);
        String::from_utf8(out.stdout).expect("utf-8")
    };
    assert!(case("good", &good).starts_with("0 ok"));
    assert!(case("empty", &[]).starts_with("2 "));
    assert!(case("truncated", &good[..good.len() / 2]).starts_with("2 the export is truncated"));
    let mut flipped = good.clone();
    flipped[good.len() / 3] ^= 0x10;
    assert!(case("flipped", &flipped).starts_with("5 the export is damaged"));
    let hdf5 = std::fs::read(root("tables/quick.h5")).expect("table");
    assert!(case("hdf5", &hdf5).starts_with("3 not an export"));
    let mut newer = good.clone();
    // 1, 2 (a table with an e_n axis), 3 (the table of one pair), 4 (Thornton's law), 5
    // (knots of the partial-slip coordinate), 6 (an elastic table with split masks), 7
    // (knots of the stick patch too) and 8 (a mapped e_n axis) are known.
    newer[8] = 9;
    assert!(case("newer", &newer).starts_with("4 "));
    // A consistent checksum over inconsistent contents: an offset beyond the end.
    let mut bad = good.clone();
    bad[72..80].copy_from_slice(&(good.len() as u64 + 8).to_le_bytes());
    let sum = oblique_table::format::fnv1a64(&bad[32..]);
    bad[24..32].copy_from_slice(&sum.to_le_bytes());
    assert!(case("offset", &bad).starts_with("6 the export is inconsistent"));
}

/// A header value changed and the checksum recomputed: `oblq_open` checks each against what
/// the data implies and refuses the export (6, inconsistent) instead of answering NaN (an
/// `alpha_max` at `α_c2` of a queried γ made the stick coordinate 0/0: NaN with `OBLQ_OK`).
#[test]
fn header_values_the_data_contradicts_are_refused_after_resealing() {
    let path = export_file("quick", false);
    let good = std::fs::read(&path).expect("export");
    let s = table("quick").surface();
    let with = |at: usize, v: f64| -> Vec<u8> {
        let mut b = good.clone();
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
        let sum = oblique_table::format::fnv1a64(&b[32..]);
        b[24..32].copy_from_slice(&sum.to_le_bytes());
        b
    };
    let open = |name: &str, bytes: &[u8]| open_export(&format!("header_{name}"), bytes);
    let c2 = |g: f64| g * g * (2.0 / 7.0);
    for (name, at, v) in [
        ("alpha_max_at_c2", 48, c2(2.2)),
        ("alpha_max_at_c2_end", 48, c2(s.gamma_max())),
        ("alpha_max_below", 48, alpha_c2(s.gamma_max()) * 0.5),
        ("alpha_max_nan", 48, f64::NAN),
        ("alpha_max_zero", 48, 0.0),
        ("bound_nan", 56, f64::NAN),
        ("bound_inf", 56, f64::INFINITY),
        ("bound_negative", 56, -1e-6),
        ("gamma_min_other", 32, 0.6),
        ("gamma_min_zero", 32, 0.0),
        ("gamma_max_other", 40, 2.4),
        ("gamma_max_huge", 40, 1e300),
        ("gamma_max_inf", 40, f64::INFINITY),
        ("gamma_max_nan", 40, f64::NAN),
    ] {
        let said = open(name, &with(at, v));
        assert!(
            said.starts_with("6 the export is inconsistent"),
            "{name}: {said}"
        );
    }
    // What the data does not fix stays the writer's: the bound. (A finite alpha_max above
    // α_c2 is the curves' business here: their records hold it.)
    assert!(open("bound_other", &with(56, 0.5)).starts_with("0 ok"));
    assert!(open("alpha_max_finite", &with(48, 10.0)).starts_with("6 "));
    // Swapped: gamma_min > gamma_max.
    let mut b = with(32, s.gamma_max());
    b[40..48].copy_from_slice(&s.gamma_min().to_le_bytes());
    let sum = oblique_table::format::fnv1a64(&b[32..]);
    b[24..32].copy_from_slice(&sum.to_le_bytes());
    assert!(open("swapped", &b).starts_with("6 "));
    // A curve's γ outside the header's domain (every other field of the record recomputed).
    let path = export_file("quick", true);
    let curves = std::fs::read(&path).expect("export");
    assert!(open("curves", &curves).starts_with("0 ok"));
    let mut b = curves.clone();
    b[40..48].copy_from_slice(&0.9_f64.to_le_bytes()); // gamma_max below the curve at 1.0
    let sum = oblique_table::format::fnv1a64(&b[32..]);
    b[24..32].copy_from_slice(&sum.to_le_bytes());
    assert!(
        open("curve_outside", &b).starts_with("6 "),
        "curve outside the domain"
    );
}

/// The full-slip line for every γ > 0: where `2γ²` overflows (γ ≳ 1.3e154; `α_c1` was NaN and
/// the point refused) `oblq_p` and `oblq_p_e` answer `1 − 7α` and `1 − (7/2)(1 + e_n)α` as the
/// Rust library does, to the bit, and refuse the points above the line as it does.
#[test]
fn the_line_at_overflowing_gamma_as_in_rust() {
    let t = table("quick");
    let path = export_file("quick", false);
    let mut input = String::new();
    let mut pts = Vec::new();
    for g in [3.0e153, 3.6e153, 1e154, 1.4e154, 1e200, f64::MAX] {
        for a in [0.0, 0.1, 1.0 / 7.0, 0.15, 0.3] {
            input.push_str(&format!("{g:?} {a:?}\n"));
            pts.push((g, a));
        }
    }
    let out = run_ok(
        gcc_driver(),
        &["p", path.to_str().expect("path"), "0"],
        &input,
    );
    for ((g, a), line) in pts.iter().zip(out.lines()) {
        match t.p(*g, *a) {
            Ok(p) => {
                assert!(*a < 0.15, "({g:e}, {a})");
                let c: f64 = line.parse().expect("P");
                assert_eq!(c.to_bits(), p.to_bits(), "({g:e}, {a})");
            }
            Err(_) => {
                assert!(*a >= 0.15, "({g:e}, {a})");
                assert_eq!(line, "error 9", "({g:e}, {a})");
            }
        }
    }
    let (t, path) = dissipative();
    let mut input = String::new();
    let mut pts = Vec::new();
    for g in [1e154, 1e200, f64::MAX] {
        for (a, e) in [(0.1, 0.7), (0.15, 0.8), (0.14, 1.0), (0.2, 0.7)] {
            input.push_str(&format!("{g:?} {a:?} {e:?}\n"));
            pts.push((g, a, e));
        }
    }
    let out = run_ok(
        gcc_driver(),
        &["pe", path.to_str().expect("path"), "0"],
        &input,
    );
    for ((g, a, e), line) in pts.iter().zip(out.lines().skip(1)) {
        match t.p_e(*g, *a, *e) {
            Ok(p) => {
                let c: f64 = line.parse().expect("P");
                assert_eq!(c.to_bits(), p.to_bits(), "({g:e}, {a}, {e})");
            }
            Err(_) => {
                assert!(*a == 0.2, "({g:e}, {a}, {e})");
                assert_eq!(line, "error 9", "({g:e}, {a}, {e})");
            }
        }
    }
}

/// Mutated exports (2000 to 3000 per file in the release check, a quarter otherwise) and
/// 2·10⁴ points (5·10³ otherwise) through the driver compiled with AddressSanitizer and
/// UndefinedBehaviorSanitizer.
#[test]
fn mutated_exports_never_read_out_of_bounds_under_sanitizers() {
    let mut f = vec![
        "-std=c99",
        "-g",
        "-fsanitize=address,undefined",
        "-fno-sanitize-recover=all",
    ];
    f.extend(WARNINGS);
    let exe = compile("gcc", &f, "tests/c/eval_check.c", "eval_check_asan");
    for (path, n) in [
        (export_file("quick", false), sized(500, 2000)),
        (export_file("full", true), sized(750, 3000)),
        (dissipative().1.clone(), sized(500, 2000)),
        (pair_table().1.clone(), sized(500, 2000)),
        (thornton().1.clone(), sized(500, 2000)),
        (anisotropic().1.clone(), sized(500, 2000)),
    ] {
        let out = Command::new(&exe)
            .args(["fuzz", path.to_str().expect("path"), &n.to_string(), "17"])
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "fuzz {}: {}\n{}",
            path.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("refused"), "{text}");
        // Each header field set to NaN, ±inf, 0, negative, huge, a critical value, the other
        // end of its range, resealed: refused with a code, or every answer in [−1, 1].
        let out = Command::new(&exe)
            .args(["headers", path.to_str().expect("path")])
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "headers {}: {}\n{}",
            path.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
    for path in [export_file("quick", true), export_file("full", false)] {
        let said = run_ok(gcc_driver(), &["headers", path.to_str().expect("path")], "");
        assert!(said.contains("refused"), "{said}");
    }
    // The comparison on random points once more, under the sanitizers, on a sample.
    let path = export_file("full", false);
    let pts = points(sized(5_000, 20_000), 4, 0.1, 3.5);
    let input: String = pts.iter().map(|(g, a)| format!("{g:?} {a:?}\n")).collect();
    let out = run_ok(&exe, &["p", path.to_str().expect("path"), "0"], &input);
    assert_eq!(out.lines().count(), pts.len());
    // And P(γ, α, e_n) of the table with an e_n axis, inside and outside its domain.
    let pts = points_e(sized(5_000, 20_000), 5, (0.1, 3.5), (0.6, 1.05));
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?} {a:?} {e:?}\n"))
        .collect();
    let path = &dissipative().1;
    for clamp in ["0", "1"] {
        let out = run_ok(&exe, &["pe", path.to_str().expect("path"), clamp], &input);
        assert_eq!(out.lines().count(), pts.len() + 1);
    }
}

#[test]
fn cpp_collision_operator_agrees_with_the_rust_rebound() {
    let mut f = vec!["-std=c++11"];
    f.extend(WARNINGS);
    let exe = compile("g++", &f, "examples/cpp/collision.cpp", "collision");
    compile(
        "clang++",
        &f,
        "examples/cpp/collision.cpp",
        "collision_clang",
    );
    let path = export_file("full", false);
    let text = run_ok(&exe, &[path.to_str().expect("path")], "");
    let get = |key: &str| -> Vec<f64> {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("{key},")))
            .unwrap_or_else(|| panic!("no {key} in:\n{text}"));
        parse_line(&line[key.len() + 1..])
    };
    // The same collision through the Rust library.
    use oblique_lookup::rebound::Elastic;
    let pi = std::f64::consts::PI;
    let (r1, r2) = (5e-3, 3e-3);
    let pair = Pair {
        sphere: Body {
            mass: 7850.0 * 4.0 / 3.0 * pi * r1 * r1 * r1,
            radius: r1,
            kappa: 0.4,
        },
        other: Some(Body {
            mass: 2500.0 * 4.0 / 3.0 * pi * r2 * r2 * r2,
            radius: r2,
            kappa: 0.4,
        }),
    };
    let steel = Elastic {
        youngs_modulus: 210e9,
        poisson_ratio: 0.29,
    };
    let glass = Elastic {
        youngs_modulus: 73e9,
        poisson_ratio: 0.217,
    };
    let s = Incident3 {
        sphere: Motion3 {
            velocity: [1.0, 0.2, 2.0],
            spin: [0.0, 50.0, 0.0],
        },
        other: Motion3 {
            velocity: [0.0, 0.0, -1.0],
            spin: [0.0, 0.0, 10.0],
        },
        normal: [0.0, 0.0, r1 + r2],
    };
    let t = table("full");
    let a = t
        .rebound_3d(&pair, &Contact::with_materials(steel, glass, 0.3), &s)
        .expect("valid");
    assert_eq!(get("gamma")[0].to_bits(), a.gamma.to_bits());
    assert_eq!(get("alpha")[0].to_bits(), a.alpha.to_bits());
    // P of the pair: the table's rule to the bit.
    assert_eq!(
        get("P")[0].to_bits(),
        t.p(a.gamma, a.alpha).expect("inside").to_bits()
    );
    let b = &a.rebound;
    let o = b.other.expect("sphere");
    for (key, want) in [
        ("a.v", b.sphere.velocity),
        ("a.w", b.sphere.spin),
        ("b.v", o.velocity),
        ("b.w", o.spin),
    ] {
        for (x, y) in get(key).iter().zip(want) {
            assert!(
                (x - y).abs() <= 1e-12 * (1.0 + y.abs()),
                "{key}: C++ {x}, Rust {y}"
            );
        }
    }
    assert!(get("energy_balance")[0].abs() < 1e-13, "{text}");
    assert!(text.contains("refused,invalid v_z"), "{text}");
}

#[test]
fn c_rebound_example_agrees_with_the_rust_library() {
    let mut f = vec!["-std=c99"];
    f.extend(WARNINGS);
    let exe = compile("gcc", &f, "examples/c/rebound.c", "rebound");
    let path = export_file("full", false);
    let text = run_ok(&exe, &[path.to_str().expect("path")], "");
    let t = table("full");
    let p: f64 = text
        .split("P(1.754, 0.3) = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .expect("P line");
    assert_eq!(p.to_bits(), t.p(1.754, 0.3).expect("inside").to_bits());
    // The reference impact of the benchmarks, through the Rust library.
    let (pair, contact, s) = oblique_lookup::testing::reference_spheres();
    let a = t.rebound_3d(&pair, &contact, &s).expect("valid");
    let b = &a.rebound;
    let o = b.other.expect("sphere");
    let want = format!(
        "sphere 1: v = [{:.9}, {:.9}, {:.9}] m/s, w = [{:.6}, {:.6}, {:.6}] rad/s",
        b.sphere.velocity[0],
        b.sphere.velocity[1],
        b.sphere.velocity[2],
        b.sphere.spin[0],
        b.sphere.spin[1],
        b.sphere.spin[2]
    );
    assert!(text.contains(&want), "{text}\nwant: {want}");
    let want2 = format!(
        "sphere 2: v = [{:.9}, {:.9}, {:.9}] m/s",
        o.velocity[0], o.velocity[1], o.velocity[2]
    );
    assert!(text.contains(&want2), "{text}\nwant: {want2}");
    let c: f64 = text
        .split(", P = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .expect("rebound P");
    assert!((c - b.p).abs() < 1e-13, "C {c}, Rust {}", b.p);
}

// ---------------------------------------------------------------------------------------------
// A table with a normal-restitution axis (schema 4; export layout version 2)

/// The table with an e_n axis of [`evaluator::dissipative_table`] and its export, made once
/// per process.
fn dissipative() -> &'static (Table, PathBuf) {
    static T: OnceLock<(Table, PathBuf)> = OnceLock::new();
    T.get_or_init(|| evaluator::dissipative_table(&dir().join("dissipative")))
}

/// The shipped table with an e_n axis, `tables/dissipative-demo.h5`, and its export (written
/// by `oblique_table::export`), made once per process.
fn dissipative_demo() -> &'static (Table, PathBuf) {
    static T: OnceLock<(Table, PathBuf)> = OnceLock::new();
    T.get_or_init(|| {
        let t = Table::open(root("tables/dissipative-demo.h5")).expect("shipped table");
        let path = dir().join("dissipative-demo.oblq");
        let bytes = export::export(t.surface(), t.error_bound(), true, &[]);
        std::fs::write(&path, bytes).expect("write export");
        (t, path)
    })
}

/// `P(γ, α, e_n)` with the same bits from every path: `Table::p_e`, the batches
/// `p_e_batch` and `p_e_batch_par`, `oblq_p_e` of the C header on the export, and on every
/// 40th point the reference reader `scripts/read_table.py`. Random points over the domain of
/// the shipped `tables/dissipative-demo.h5` (α = 0, ∞, α_c2, α_c1(γ, e_n) and just above it in
/// the mix, the ends of the e_n range) and of the small table built here: 10⁶ and 10⁵ in the
/// release check, 10⁵ and 2·10⁴ otherwise.
#[test]
fn e_n_tables_give_the_same_bits_in_rust_batches_c_and_python_on_random_points() {
    let start = std::time::Instant::now();
    let query = query_program();
    let shipped = dissipative_demo();
    let tables = [
        ("dissipative-demo", shipped, sized(100_000, 1_000_000), true),
        ("built here", dissipative(), sized(20_000, 100_000), false),
    ];
    for (name, (t, export), n, python) in tables {
        let s = t.surface();
        let (e_lo, e_hi) = t.restitution().expect("an e_n axis");
        // points_e puts γ = 1 in the mix: where the domain starts above it, its lowest γ.
        let pts: Vec<(f64, f64, f64)> =
            points_e(n, 13, (s.gamma_min(), s.gamma_max()), (e_lo, e_hi))
                .into_iter()
                .map(|(g, a, e)| (g.max(s.gamma_min()), a, e))
                .collect();
        let scalar: Vec<f64> = pts
            .iter()
            .map(|&(g, a, e)| t.p_e(g, a, e).expect("inside"))
            .collect();
        let columns = |k: usize| -> Vec<f64> { pts.iter().map(|p| [p.0, p.1, p.2][k]).collect() };
        let (g, a, e) = (columns(0), columns(1), columns(2));
        let (mut serial, mut parallel) = (vec![f64::NAN; n], vec![f64::NAN; n]);
        t.p_e_batch(&g, &a, &e, &mut serial, OutOfDomain::Error)
            .expect("serial batch");
        t.p_e_batch_par(&g, &a, &e, &mut parallel, OutOfDomain::Error)
            .expect("parallel batch");
        let input: String = pts
            .iter()
            .map(|(g, a, e)| format!("{g:?},{a:?},{e:?}\n"))
            .collect();
        let out = run_ok(query, &[export.to_str().expect("path")], &input);
        let c: Vec<f64> = out
            .lines()
            .map(|l| l.rsplit(',').next().expect("P").parse().expect("P"))
            .collect();
        assert_eq!(c.len(), n, "{name}: every point answered by C");
        let (mut differ, mut line_pts) = (0, 0);
        for (i, &(g, a, e)) in pts.iter().enumerate() {
            line_pts += usize::from(a <= oblique_physics::regimes::linear_limit_dissipative(g, e));
            let bits = [scalar[i], serial[i], parallel[i], c[i]].map(f64::to_bits);
            if bits.iter().any(|&b| b != bits[0]) {
                differ += 1;
                if differ < 5 {
                    eprintln!(
                        "{name}: gamma {g:?} alpha {a:?} e_n {e:?}: p_e {:?}, batch {:?}, \
                         parallel {:?}, C {:?}",
                        scalar[i], serial[i], parallel[i], c[i]
                    );
                }
            }
        }
        assert_eq!(
            differ, 0,
            "{name}: {differ} of {n} points differ in some bit"
        );
        assert!(
            line_pts > n / 20 && line_pts < n / 2,
            "{name}: {line_pts} on the line"
        );
        let mut checked_python = 0;
        if python {
            let every = 40;
            let subset: Vec<_> = pts.iter().copied().step_by(every).collect();
            let py = python_p_e(&root("tables/dissipative-demo.h5"), &subset);
            assert_eq!(
                py.len(),
                subset.len(),
                "{name}: every point answered by Python"
            );
            for (k, (&p, &(g, a, e))) in py.iter().zip(&subset).enumerate() {
                let r = scalar[k * every];
                assert_eq!(
                    p.to_bits(),
                    r.to_bits(),
                    "{name}: gamma {g:?} alpha {a:?} e_n {e:?}: read_table.py {p:?}, Rust {r:?}"
                );
            }
            checked_python = subset.len();
        }
        eprintln!(
            "{name}: {n} points (γ, α, e_n), {line_pts} on the full-slip line: p_e == \
             p_e_batch == p_e_batch_par == C bit for bit, {checked_python} of them == \
             read_table.py ({:.1} s so far)",
            start.elapsed().as_secs_f64()
        );
    }
}

/// `oblq_p_e` of the C driver (`pe TABLE CLAMP`) at `pts` against `Table::p_e_with`: the
/// header line `header`, then per point the Rust bits or `error CODE` with the code Rust's
/// error maps to. Returns the refusals per status code and the number answered.
fn pe_against_rust(
    t: &Table,
    path: &str,
    pts: &[(f64, f64, f64)],
    clamp: u8,
    header: &str,
) -> ([usize; 25], usize) {
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?} {a:?} {e:?}\n"))
        .collect();
    let out = run_ok(gcc_driver(), &["pe", path, &clamp.to_string()], &input);
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some(header));
    let outside = if clamp == 1 {
        OutOfDomain::Clamp
    } else {
        OutOfDomain::Error
    };
    let mut refused = [0usize; 25];
    let mut answered = 0;
    for ((g, a, e), line) in pts.iter().zip(lines) {
        match t.p_e_with(*g, *a, *e, outside) {
            Ok(r) => {
                answered += 1;
                let c: f64 = line.parse().unwrap_or_else(|_| {
                    panic!("gamma {g:?} alpha {a:?} e_n {e:?} clamp {clamp}: {line}")
                });
                assert_eq!(
                    c.to_bits(),
                    r.to_bits(),
                    "gamma {g:?} alpha {a:?} e_n {e:?} clamp {clamp}"
                );
            }
            Err(err) => {
                let code = status_of(&err, *g, *a);
                refused[code as usize] += 1;
                assert_eq!(
                    line,
                    format!("error {code}"),
                    "gamma {g:?} alpha {a:?} e_n {e:?} clamp {clamp}: {err}"
                );
            }
        }
    }
    (refused, answered)
}

#[test]
fn e_n_clamp_and_refusals_match_the_rust_rule() {
    let (t, path) = dissipative();
    let s = t.surface();
    let path = path.to_str().expect("path");
    let mut pts = points_e(
        40_000,
        17,
        (0.5 * s.gamma_min(), 1.2 * s.gamma_max()),
        (0.6, 1.05),
    );
    pts.extend([
        (f64::NAN, 0.5, 0.8),
        (-1.0, 0.5, 0.8),
        (f64::INFINITY, 0.5, 0.8),
        (1.5, -0.1, 0.8),
        (1.5, f64::NAN, 0.8),
        (1.5, 0.3, f64::NAN),
        (1.5, 0.3, f64::INFINITY),
        (1.5, 0.3, 0.0),
        (1.5, 0.3, 0.7),
        (1.5, 0.3, 1.0),
        (1.5, 0.3, 0.699_999_999_999_999_9),
        (1.5, 0.3, 1.000_000_000_000_000_2),
        (0.5, 0.01, 0.5), // on the line, outside the e_n range: refused (e_n is never clamped)
    ]);
    for clamp in [0, 1] {
        let (refused, _) = pe_against_rust(t, path, &pts, clamp, "e_n 1 0.69999999999999996 1");
        // Refusals of e_n always; of gamma outside the domain only without clamping.
        assert!(refused[24] > 3000, "clamp {clamp}: {refused:?}");
        assert_eq!(refused[9] > 1000, clamp == 0, "clamp {clamp}: {refused:?}");
        assert_eq!(refused[7] + refused[8], 5, "clamp {clamp}: {refused:?}");
    }
    // oblq_p on the table answers its e_n = 1 slice, as Table::p does.
    let pts = points(20_000, 19, s.gamma_min(), s.gamma_max());
    let input: String = pts.iter().map(|(g, a)| format!("{g:?} {a:?}\n")).collect();
    let out = run_ok(gcc_driver(), &["p", path, "0"], &input);
    for ((g, a), line) in pts.iter().zip(out.lines()) {
        let r = t.p(*g, *a).expect("inside");
        let c: f64 = line.parse().expect("P");
        assert_eq!(c.to_bits(), r.to_bits(), "oblq_p: gamma {g:?} alpha {a:?}");
        assert_eq!(r.to_bits(), t.p_e(*g, *a, 1.0).expect("inside").to_bits());
    }
    // `sweep export` wrote the export of the library; it refuses curves of such a table.
    let bytes = std::fs::read(path).expect("export");
    assert_eq!(
        bytes,
        export::export(s, t.error_bound(), true, &[]),
        "sweep export"
    );
    assert_eq!(
        &bytes[8..16],
        &[2, 0, 0, 0, 112, 0, 0, 0],
        "version 2, 112-byte header"
    );
    curves_are_refused(
        &dir().join("dissipative").join("kv.h5"),
        "curves.oblq",
        "1.4",
    );
}

/// `sweep export TABLE --gamma GAMMA` of a table with an e_n axis exits with status 2, saying
/// that curves are for elastic tables, and writes nothing to `out` (in the scratch folder).
fn curves_are_refused(table: &Path, out: &str, gamma: &str) {
    let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .arg("export")
        .arg(table)
        .arg("-o")
        .arg(dir().join(out))
        .args(["--gamma", gamma])
        .output()
        .expect("run sweep");
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("e_n axis") && err.contains("elastic tables"),
        "{err}"
    );
    assert!(!dir().join(out).exists());
}

#[test]
fn elastic_exports_answer_e_n_1_only_and_keep_layout_version_1() {
    let path = export_file("quick", false);
    let bytes = std::fs::read(&path).expect("export");
    assert_eq!(
        &bytes[8..16],
        &[1, 0, 0, 0, 96, 0, 0, 0],
        "version 1, 96-byte header"
    );
    let t = table("quick");
    let s = t.surface();
    let mut pts = points_e(
        20_000,
        23,
        (0.5 * s.gamma_min(), 1.2 * s.gamma_max()),
        (0.9, 1.0),
    );
    for (i, p) in pts.iter_mut().enumerate() {
        if i % 3 != 0 {
            p.2 = 1.0;
        }
    }
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?} {a:?} {e:?}\n"))
        .collect();
    for (file, curves_only) in [(path, false), (export_file("full", true), true)] {
        // A curves-only export answers the full-slip line (the same for every table).
        let out = run_ok(
            gcc_driver(),
            &["pe", file.to_str().expect("path"), "0"],
            &input,
        );
        let mut lines = out.lines();
        assert_eq!(lines.next(), Some("e_n 0 1 1"));
        let mut answered = 0;
        for ((g, a, e), line) in pts.iter().zip(lines) {
            let want = if curves_only && *e == 1.0 && *a > linear_limit(*g) && g.is_finite() {
                Err(11)
            } else {
                t.p_e(*g, *a, *e).map_err(|err| status_of(&err, *g, *a))
            };
            match want {
                Ok(r) => {
                    answered += 1;
                    let c: f64 = line.parse().expect("P");
                    assert_eq!(c.to_bits(), r.to_bits(), "gamma {g:?} alpha {a:?}");
                    assert_eq!(r.to_bits(), t.p(*g, *a).expect("inside").to_bits());
                }
                Err(code) => assert_eq!(line, format!("error {code}"), "{g:?} {a:?} {e:?}"),
            }
        }
        assert!(
            answered > if curves_only { 2000 } else { 5000 },
            "{answered} answered"
        );
    }
}

#[test]
fn damaged_e_n_exports_are_refused_with_their_code() {
    let (_, path) = dissipative();
    let good = std::fs::read(path).expect("export");
    let case = |name: &str, bytes: &[u8]| -> String {
        let p = dir().join(format!("e_{name}"));
        std::fs::write(&p, bytes).expect("write");
        let out = Command::new(gcc_driver())
            .args(["open", p.to_str().expect("path")])
            .output()
            .expect("run");
        assert!(out.status.success(), "{name}: {}", out.status);
        String::from_utf8(out.stdout).expect("utf-8")
    };
    assert!(case("good", &good).starts_with("0 ok"));
    assert!(case("truncated", &good[..good.len() - 8]).starts_with("2 "));
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x04;
    assert!(case("flipped", &flipped).starts_with("5 "));
    let mut newer = good.clone();
    newer[8] = 9;
    assert!(case("newer", &newer).starts_with("4 "));
    // Version 8 (a mapped e_n axis) without its map at offset 84.
    let mut v8 = good.clone();
    v8[8] = 8;
    assert!(case("v8", &v8).starts_with("6 "));
    // Version 4 (Thornton's law) without its flag.
    let mut v4 = good.clone();
    v4[8] = 4;
    assert!(case("v4", &v4).starts_with("6 "));
    // Version 3 (the table of one pair) with the header and patches of version 2.
    let mut v3 = good.clone();
    v3[8] = 3;
    assert!(case("v3", &v3).starts_with("6 "));
    // Version 1 with the header of version 2, and the reverse.
    let mut v1 = good.clone();
    v1[8] = 1;
    assert!(case("v1", &v1).starts_with("6 "));
    let mut elastic = std::fs::read(export_file("quick", false)).expect("export");
    elastic[8] = 2;
    assert!(case("v2_of_elastic", &elastic).starts_with("6 "));
    let dir_at = u64::from_le_bytes(good[72..80].try_into().expect("8 bytes")) as usize;
    let mut edits: Vec<(&str, usize, Vec<u8>)> = vec![
        ("e_n_min_0", 96, 0.0f64.to_le_bytes().to_vec()),
        ("e_n_max_above_1", 104, 1.5f64.to_le_bytes().to_vec()),
        ("e_n_max_nan", 104, f64::NAN.to_le_bytes().to_vec()),
        ("e_n_reversed", 96, 1.0f64.to_le_bytes().to_vec()),
        ("curves", 80, 1u32.to_le_bytes().to_vec()),
    ];
    for k in 0..3 {
        let r = dir_at + 160 * k;
        edits.push(("blocks_e_n_0", r + 136, 0u32.to_le_bytes().to_vec()));
        edits.push(("blocks_e_n_big", r + 136, 9u32.to_le_bytes().to_vec()));
        edits.push(("warp", r + 44, 1u32.to_le_bytes().to_vec()));
        edits.push(("fine_index", r + 120, 8u64.to_le_bytes().to_vec()));
        edits.push(("cells", r + 36, 9u32.to_le_bytes().to_vec()));
    }
    for (name, at, value) in edits {
        let mut b = good.clone();
        b[at..at + value.len()].copy_from_slice(&value);
        let said = case(name, &sealed(b));
        assert!(said.starts_with("6 "), "{name} at {at}: {said}");
    }
}

// ---------------------------------------------------------------------------------------------
// Rebounds at a normal restitution e_n (oblq_pair_init_e)

/// The `eval_check rebound` input line of a 3-D incident state.
fn incident_line(s: &Incident3) -> String {
    let v: Vec<String> = [
        s.sphere.velocity,
        s.sphere.spin,
        s.other.velocity,
        s.other.spin,
        s.normal,
    ]
    .iter()
    .flatten()
    .map(|x| format!("{x:?}"))
    .collect();
    v.join(" ") + "\n"
}

/// The `eval_check` arguments of a rebound of `pair` at `gamma`, `mu`, `e_n`.
fn rebound_args(
    mode: &str,
    path: &Path,
    source: Option<&str>,
    pair: &Pair,
    gamma: f64,
    mu: f64,
    e_n: f64,
) -> Vec<String> {
    let b1 = pair.sphere;
    let b2 = pair.other.unwrap_or(b1);
    let m2 = if pair.other.is_none() { 0.0 } else { b2.mass };
    let mut a = vec![mode.to_string(), path.display().to_string()];
    a.extend(source.map(str::to_string));
    a.extend(
        [
            b1.mass, b1.radius, b1.kappa, m2, b2.radius, b2.kappa, gamma, mu, e_n,
        ]
        .iter()
        .map(|x| format!("{x:?}")),
    );
    a
}

/// The status code of the C header for a refusal of the Rust library's rebound.
fn rebound_status(err: &oblique_lookup::LookupError) -> String {
    use oblique_lookup::LookupError::Query;
    let code = match err {
        Query { name: "e_n", .. } => 24,
        Query { name: "alpha", .. } => 10,
        Query { name: "gamma", .. } => 9,
        other => panic!("unexpected refusal: {other}"),
    };
    format!("error {code}")
}

#[test]
fn rebounds_at_e_n_give_the_bits_of_the_rust_library() {
    let (t, path) = dissipative();
    let mut r = SplitMix(31);
    let (mut compared, mut pure_normal, mut refused) = (0, 0, 0);
    for case in 0..16 {
        let wall = case % 3 == 0;
        let pair = Pair {
            sphere: random_body(&mut r),
            other: (!wall).then(|| random_body(&mut r)),
        };
        let gamma = 1.0 + 0.55 * r.uniform();
        let mu = if case == 5 {
            f64::INFINITY
        } else {
            0.05 + r.uniform()
        };
        let e_n = match case {
            0 => 1.0,
            1 => 0.7,
            _ => 0.7 + 0.3 * r.uniform(),
        };
        let contact = Contact::with_gamma(gamma, mu).with_restitution(e_n);
        let mut incidents = Vec::new();
        while incidents.len() < 400 {
            incidents.extend(random_impact(&mut r, wall));
        }
        // Pure normal impacts (u0 = 0): the table is not consulted.
        let v = 0.5 + r.uniform();
        incidents.push(Incident3 {
            sphere: Motion3 {
                velocity: [0.0, 0.0, v],
                spin: [0.0; 3],
            },
            other: Motion3::default(),
            normal: [0.0, 0.0, 2.0],
        });
        let input: String = incidents.iter().map(incident_line).collect();
        let args = rebound_args("rebound", path, Some("table"), &pair, gamma, mu, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(gcc_driver(), &args, &input);
        let prepared = Prepared::new(&pair, &contact).expect("valid pair");
        assert_eq!(out.lines().count(), incidents.len());
        for (s, line) in incidents.iter().zip(out.lines()) {
            let a = t.rebound_3d(&pair, &contact, s);
            let b = t.rebound_3d_prepared(&prepared, s);
            match (a, b) {
                (Ok(a), Ok(b)) => {
                    let c = parse_line(line);
                    let mut want = rebound_fields(&a);
                    want.extend([a.rebound.normal_impulse, a.rebound.e_n]);
                    assert_eq!(want.len(), 19);
                    assert_eq!(c.len(), 19, "{line}");
                    let u0_zero = a.rebound.slip_before == 0.0;
                    for (k, ((x, y), z)) in c.iter().zip(&want).zip(rebound_fields(&b)).enumerate()
                    {
                        // u0 = 0: Rust's step-by-step path (Pair::plane), which the header
                        // does not copy, sets the velocities and spins up to rounding; the
                        // normal impulse and the energy lost keep the bits.
                        let near = u0_zero
                            && !matches!(k, 14 | 17 | 18)
                            && (x - y).abs() <= 1e-13 * (1.0 + y.abs());
                        assert!(
                            x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()) || near,
                            "case {case} e_n {e_n:?} field {k}: C {x:?}, Rust {y:?}"
                        );
                        assert!(y.to_bits() == z.to_bits() || (y.is_nan() && z.is_nan()));
                    }
                    compared += 1;
                    pure_normal += usize::from(a.rebound.slip_before == 0.0);
                }
                (Err(e), Err(_)) => {
                    assert_eq!(line, rebound_status(&e), "case {case}: {e}");
                    refused += 1;
                }
                (a, b) => panic!("rebound_3d {a:?} and prepared {b:?} disagree"),
            }
        }
    }
    assert!(
        compared > 5000 && pure_normal == 16,
        "{compared} {pure_normal}"
    );
    eprintln!(
        "3-D rebounds at e_n: {compared} compared ({pure_normal} with u0 = 0), C == Rust bit \
         for bit; {refused} refused by both alike"
    );
}

#[test]
fn rebound_2d_at_e_n_gives_the_bits_of_the_3d_rust_rebound() {
    let (t, path) = dissipative();
    let mut r = SplitMix(37);
    for (case, wall) in [true, false, true, false].into_iter().enumerate() {
        let pair = Pair {
            sphere: random_body(&mut r),
            other: (!wall).then(|| random_body(&mut r)),
        };
        let (gamma, mu) = (1.1 + 0.4 * r.uniform(), 0.1 + 0.5 * r.uniform());
        let e_n = 0.7 + 0.3 * r.uniform();
        let contact = Contact::with_gamma(gamma, mu).with_restitution(e_n);
        let mut states = Vec::new();
        while states.len() < 1000 {
            states.push(Incident {
                sphere: State {
                    v_x: 3.0 * (2.0 * r.uniform() - 1.0),
                    v_z: 3.0 * r.uniform() + 0.1,
                    omega: 400.0 * (2.0 * r.uniform() - 1.0),
                },
                other: if wall {
                    State::default()
                } else {
                    State {
                        v_x: 2.0 * r.uniform() - 1.0,
                        v_z: -r.uniform(),
                        omega: 400.0 * (2.0 * r.uniform() - 1.0),
                    }
                },
            });
        }
        let input: String = states
            .iter()
            .map(|s| {
                format!(
                    "{:?} {:?} {:?} {:?} {:?} {:?}\n",
                    s.sphere.v_x,
                    s.sphere.v_z,
                    s.sphere.omega,
                    s.other.v_x,
                    s.other.v_z,
                    s.other.omega
                )
            })
            .collect();
        let args = rebound_args("rebound2", path, None, &pair, gamma, mu, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(gcc_driver(), &args, &input);
        assert_eq!(out.lines().count(), states.len());
        for (s, line) in states.iter().zip(out.lines()) {
            let c = parse_line(line);
            // The plane of impact as a 3-D impact: x the tangent, y the spin axis, z normal.
            let m = |s: &State| Motion3 {
                velocity: [s.v_x, 0.0, s.v_z],
                spin: [0.0, s.omega, 0.0],
            };
            let s3 = Incident3 {
                sphere: m(&s.sphere),
                other: m(&s.other),
                normal: [0.0, 0.0, 1.0],
            };
            let a = t.rebound_3d(&pair, &contact, &s3).expect("valid");
            let b = &a.rebound;
            let o = b.other.unwrap_or_default();
            let want = [
                b.sphere.velocity[0],
                b.sphere.velocity[2],
                b.sphere.spin[1],
                o.velocity[0],
                o.velocity[2],
                o.spin[1],
                b.p,
                b.e_t,
                b.energy_lost,
                a.alpha,
                b.tangential_impulse * b.frame.tangent[0],
                b.normal_impulse,
                b.e_n,
            ];
            assert_eq!(c.len(), want.len(), "{line}");
            for (k, (x, y)) in c.iter().zip(want).enumerate() {
                assert!(
                    x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
                    "case {case} field {k}: C {x:?}, Rust {y:?}"
                );
            }
            // And the 2-D algebra of the library (Pair::rebound_dissipative), up to rounding.
            let d = t.rebound(&pair, &contact, s).expect("valid").rebound;
            let od = d.other.unwrap_or_default();
            let alt = [
                d.sphere.v_x,
                d.sphere.v_z,
                d.sphere.omega,
                od.v_x,
                od.v_z,
                od.omega,
                d.p,
                d.e_t,
                d.energy_lost,
            ];
            for (k, (x, y)) in c.iter().zip(alt).enumerate() {
                let scale = 1.0
                    + y.abs()
                    + if k < 6 {
                        400.0 * pair.sphere.radius
                    } else {
                        0.0
                    };
                assert!(
                    (x - y).abs() <= 1e-12 * scale,
                    "case {case} field {k}: C {x:?}, Rust 2-D {y:?}"
                );
            }
        }
    }
}

#[test]
fn rebounds_refuse_an_e_n_the_table_or_curve_does_not_answer() {
    let (t, path) = dissipative();
    let full = export_file("full", false);
    let mut r = SplitMix(41);
    let pair = Pair {
        sphere: random_body(&mut r),
        other: Some(random_body(&mut r)),
    };
    let mut incidents = Vec::new();
    while incidents.len() < 20 {
        incidents.extend(random_impact(&mut r, false));
    }
    let input: String = incidents.iter().map(incident_line).collect();
    // The table at γ = 1.6; the curves at γ = 2.6, one of the export's.
    let run = |path: &Path, source: &str, mode: &str, e_n: f64| -> Vec<String> {
        let src = (mode == "rebound").then_some(source);
        let gamma = if source == "curve" { 2.6 } else { 1.6 };
        let args = rebound_args(mode, path, src, &pair, gamma, 0.3, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let input = if mode == "rebound" {
            input.clone()
        } else {
            "1 2 3 -1 -1 4\n".repeat(3)
        };
        run_ok(gcc_driver(), &args, &input)
            .lines()
            .map(str::to_string)
            .collect()
    };
    // e_n outside [0, 1]: oblq_pair_init_e refuses it, as Prepared::new does.
    for e_n in [-0.1, 1.5, f64::NAN, f64::INFINITY] {
        let c = Contact::with_gamma(1.6, 0.3).with_restitution(e_n);
        assert!(Prepared::new(&pair, &c).is_err());
        let args = rebound_args("rebound", path, Some("table"), &pair, 1.6, 0.3, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        // (The driver exits at once: no input, no broken pipe.)
        assert_eq!(run_ok(gcc_driver(), &args, ""), "error 24\n", "e_n {e_n:?}");
    }
    // An elastic export answers e_n = 1 only, the table with the axis its range [0.7, 1]; the
    // curves (of elastic exports) e_n = 1 only.
    let elastic = table("full");
    for (tab, p, e_n) in [
        (elastic, &full, 0.9),
        (t, path, 0.6),
        (t, path, 0.699_999_999),
    ] {
        let c = Contact::with_gamma(1.6, 0.3).with_restitution(e_n);
        for s in &incidents {
            let err = tab.rebound_3d(&pair, &c, s).expect_err("refused");
            assert_eq!(rebound_status(&err), "error 24");
        }
        let want = vec!["error 24".to_string(); incidents.len()];
        assert_eq!(run(p, "table", "rebound", e_n), want, "e_n {e_n:?}");
        assert_eq!(run(p, "table", "rebound2", e_n), ["error 24"; 3]);
    }
    let want = vec!["error 24".to_string(); incidents.len()];
    assert_eq!(run(&full, "curve", "rebound", 0.9), want);
    // A pure normal impact (u0 = 0) needs no P, but an e_n the table does not answer is
    // refused all the same, by Rust (single, prepared, 2-D) and by the header; one it answers
    // gives P = NaN and the normal rebound.
    let normal_only = Incident3 {
        sphere: Motion3 {
            velocity: [0.0, 0.0, -2.0],
            spin: [0.0; 3],
        },
        other: Motion3::default(),
        normal: [0.0, 0.0, -1.0],
    };
    let line = incident_line(&normal_only);
    let header = |e_n: f64| {
        let args = rebound_args("rebound", path, Some("table"), &pair, 1.6, 0.3, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        run_ok(gcc_driver(), &args, &line)
    };
    let plane = Incident {
        sphere: State {
            v_x: 0.0,
            v_z: 2.0,
            omega: 0.0,
        },
        other: State::default(),
    };
    for e_n in [0.6, 0.2, 0.0] {
        let c = Contact::with_gamma(1.6, 0.3).with_restitution(e_n);
        let err = t.rebound_3d(&pair, &c, &normal_only).expect_err("refused");
        assert_eq!(rebound_status(&err), "error 24", "e_n {e_n}");
        let prepared = Prepared::new(&pair, &c).expect("in [0, 1]");
        let err = t
            .rebound_3d_prepared(&prepared, &normal_only)
            .expect_err("refused");
        assert_eq!(rebound_status(&err), "error 24", "e_n {e_n}");
        let err = t.rebound(&pair, &c, &plane).expect_err("refused");
        assert_eq!(rebound_status(&err), "error 24", "e_n {e_n}");
        assert_eq!(header(e_n), "error 24\n", "e_n {e_n}");
    }
    let c = Contact::with_gamma(1.6, 0.3).with_restitution(0.8);
    let ok = t.rebound_3d(&pair, &c, &normal_only).expect("answered");
    assert!(ok.rebound.p.is_nan());
    let c_line = parse_line(header(0.8).trim());
    assert!(c_line.iter().any(|x| x.is_nan()), "{c_line:?}");
    // e_n = 1 given explicitly answers as oblq_pair_init (the same bits).
    let one = run(&full, "curve", "rebound", 1.0);
    let args = rebound_args("rebound", &full, Some("curve"), &pair, 2.6, 0.3, 1.0);
    let old: Vec<&str> = args[..args.len() - 1].iter().map(String::as_str).collect();
    let old = run_ok(gcc_driver(), &old, &input);
    assert_eq!(one.len(), incidents.len());
    for (a, b) in one.iter().zip(old.lines()) {
        let (a, b) = (parse_line(a), parse_line(b));
        assert_eq!(a[..17].len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The file loader oblq_load_file

/// The C examples read their export with the header's loader, not with file-reading code of
/// their own.
#[test]
fn c_examples_load_their_export_with_the_header() {
    for src in ["examples/c/query.c", "examples/c/rebound.c"] {
        let text = std::fs::read_to_string(root(src)).expect("example");
        assert!(
            text.contains("oblq_load_file("),
            "{src} does not call oblq_load_file"
        );
        assert!(
            text.contains("oblq_free_file("),
            "{src} does not call oblq_free_file"
        );
        for own in ["fopen", "fread", "malloc"] {
            assert!(!text.contains(own), "{src} reads the file itself ({own})");
        }
    }
}

/// `oblq_load_file` on a sound export, on what is not a regular file (refused before it is
/// opened: a FIFO would block, /dev/zero never ends), on a missing file, and on files that are
/// not exports (oblq_open's code); under AddressSanitizer and LeakSanitizer, so that no path
/// leaks the buffer or reads outside it. The header without the loader (OBLQ_NO_STDIO) has no
/// `oblq_load_file` and needs no stdio.
#[test]
fn load_file_reads_exports_and_refuses_other_paths_with_their_code() {
    let mut f = vec!["-std=c99", "-g", "-fsanitize=address,undefined"];
    f.extend(WARNINGS);
    let query = compile("gcc", &f, "examples/c/query.c", "query_load_asan");
    let rebound = compile("gcc", &f, "examples/c/rebound.c", "rebound_load_asan");
    let run = |exe: &Path, path: &Path| -> (i32, String, String) {
        let mut child = Command::new(exe)
            .arg(path)
            .env("ASAN_OPTIONS", "detect_leaks=1")
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run");
        {
            use std::io::Write;
            let mut stdin = child.stdin.take().expect("stdin");
            // A program that refuses its path exits without reading its input, and may do so
            // before this write: a closed pipe is then no failure (its exit code is checked).
            match stdin.write_all(b"1.754,0.3\n") {
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
                r => r.expect("write"),
            }
        }
        let out = child.wait_with_output().expect("wait");
        (
            out.status.code().expect("exit code (not killed)"),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let good = export_file("quick", false);
    let want = table("quick").p(1.754, 0.3).expect("inside");
    let (code, out, err) = run(&query, &good);
    assert_eq!(code, 0, "{err}");
    let got: f64 = out
        .trim()
        .strip_prefix("1.754,0.3,")
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("query printed {out:?}"));
    assert_eq!(got.to_bits(), want.to_bits());
    let (code, out, err) = run(&rebound, &good);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("P(1.754, 0.3) = "), "{out}");

    let fifo = dir().join("load.fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let empty = dir().join("load.empty");
    std::fs::write(&empty, b"").expect("write");
    let not_file = "the export path is not a regular file";
    for (path, code, says) in [
        (dir().to_path_buf(), 1, not_file),
        (fifo.clone(), 1, not_file),
        (PathBuf::from("/dev/zero"), 1, not_file),
        (dir().join("missing.oblq"), 1, "No such file or directory"),
        (root("tables/quick.h5"), 2, "not an export of oblique"),
        (empty.clone(), 2, "the export is truncated"),
    ] {
        for exe in [&query, &rebound] {
            let (got, _, err) = run(exe, &path);
            assert_eq!(got, code, "{} on {}: {err}", exe.display(), path.display());
            if exe == &query || code == 2 || says == not_file {
                assert!(
                    err.contains(says),
                    "{} on {}: {err}",
                    exe.display(),
                    path.display()
                );
            }
            assert!(!err.contains("Sanitizer"), "{err}");
        }
    }

    // Without the loader: no oblq_load_file, and no stdio.h pulled in by the header.
    let src = dir().join("no_stdio.c");
    std::fs::write(
        &src,
        "#define OBLQ_NO_STDIO\n#include \"oblique_eval.h\"\n\
         #ifdef EOF\n#error stdio.h included\n#endif\n\
         int main(void) { oblq_table t; return oblq_open(&t, 0, 0) == OBLQ_E_NULL ? 0 : 1; }\n",
    )
    .expect("write");
    let out = Command::new("gcc")
        .args(evaluator::C_STRICT)
        .args(["-fsyntax-only", "-I"])
        .arg(root("include"))
        .arg(&src)
        .output()
        .expect("gcc");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(
        &src,
        "#define OBLQ_NO_STDIO\n#include \"oblique_eval.h\"\n\
         int main(void) { oblq_table t; return oblq_load_file(&t, \"x\"); }\n",
    )
    .expect("write");
    let out = Command::new("gcc")
        .args(["-std=c99", "-Werror", "-fsyntax-only", "-I"])
        .arg(root("include"))
        .arg(&src)
        .output()
        .expect("gcc");
    assert!(
        !out.status.success(),
        "OBLQ_NO_STDIO left oblq_load_file in"
    );
}

/// The split masks of an export with an `e_n` axis (offset 144 of a patch record: which axes
/// each split cell halves): `oblq_open` refuses a mask of 0 on a split cell, a mask on a leaf,
/// a mask above 7, masks that do not account for the cells after the roots, and an offset past
/// the end; an elastic export with the field set is refused too.
#[test]
fn damaged_split_masks_are_refused() {
    let (_, path) = dissipative();
    let good = std::fs::read(path).expect("export");
    let open = |name: &str, bytes: &[u8]| open_export(&format!("split_{name}"), bytes);
    assert!(open("good", &good).starts_with("0 ok"));
    let mut cases = 0;
    for rec in masked_records(&good) {
        let MaskedRecord {
            k,
            record: r,
            masks,
            cells,
            ..
        } = rec;
        let link = |i: usize| rec.link(&good, i);
        let Some(split) = (0..cells).find(|&i| link(i) >= 0) else {
            continue; // every root a leaf
        };
        let leaf = (0..cells).find(|&i| link(i) < 0).expect("a leaf");
        let with = |at: usize, v: &[u8]| {
            let mut b = good.clone();
            b[at..at + v.len()].copy_from_slice(v);
            sealed(b)
        };
        for (name, bytes) in [
            ("zero_on_split", with(masks + split, &[0])),
            ("on_leaf", with(masks + leaf, &[1])),
            ("above_7", with(masks + split, &[8])),
            (
                "offset_past_end",
                with(r + 144, &(good.len() as u64).to_le_bytes()),
            ),
        ] {
            let said = open(name, &bytes);
            assert!(said.starts_with("6 "), "patch {k} {name}: {said}");
        }
        // A cell halving other axes than stored: the child count no longer adds up (or the
        // children overlap), unless it happens to stay consistent; either way never a crash.
        let m = good[masks + split];
        let other = if m == 7 { 2 } else { 7 };
        let said = open("other_axes", &with(masks + split, &[other]));
        assert!(said.starts_with("6 "), "patch {k} other axes: {said}");
        cases += 1;
    }
    assert!(cases > 0, "the export has split masks");
    let elastic = std::fs::read(export_file("quick", false)).expect("export");
    let r = u64_at(&elastic, 72) as usize + 160;
    let mut b = elastic.clone();
    b[r + 144..r + 152].copy_from_slice(&8u64.to_le_bytes());
    assert!(open("elastic", &sealed(b)).starts_with("6 "));
}

// ---------------------------------------------------------------------------------------------
// The table of one pair: P(α, e_n) at a single γ (export layout version 3)

/// γ of the shipped `tables/dissipative-pair.h5` (alumina-96 on soda-lime glass).
const PAIR_GAMMA: f64 = 1.749_785_860_077_429_9;

/// The shipped table of one pair and its export by `sweep export`, made once per process.
fn pair_table() -> &'static (Table, PathBuf) {
    static T: OnceLock<(Table, PathBuf)> = OnceLock::new();
    T.get_or_init(|| {
        let table = root("tables/dissipative-pair.h5");
        let t = Table::open(&table).expect("shipped table");
        let path = dir().join("dissipative-pair.oblq");
        let said = evaluator::sweep_ok(&[
            "export",
            table.to_str().expect("path"),
            "-o",
            path.to_str().expect("path"),
        ]);
        assert!(
            said.contains("the table of one pair (gamma = 1.7497858600774299, e_n in [0.5, 1])"),
            "{said}"
        );
        (t, path)
    })
}

/// `x` one ulp up (`x` finite, > 0).
fn ulp_up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

/// Random `(γ_pair, α, e_n)` over the pair's `e_n` range: [`points_e`] at the pair's γ, with
/// α = 0, ∞, α_c2, α_c1(γ, e_n), 1e-12 above it, one ulp above it and one ulp below α_c2 in the
/// mix, and the ends of the `e_n` range.
fn pair_points(n: usize, seed: u64, e: (f64, f64)) -> Vec<(f64, f64, f64)> {
    use oblique_physics::regimes::alpha_c1_dissipative;
    points_e(n, seed, (PAIR_GAMMA, PAIR_GAMMA), e)
        .into_iter()
        .enumerate()
        .map(|(i, (_, a, e))| {
            let a = match i % 50 {
                2 => alpha_c2(PAIR_GAMMA),
                3 => alpha_c1_dissipative(PAIR_GAMMA, e),
                4 => alpha_c1_dissipative(PAIR_GAMMA, e) * (1.0 + 1e-12),
                5 => ulp_up(alpha_c1_dissipative(PAIR_GAMMA, e)),
                6 => f64::from_bits(alpha_c2(PAIR_GAMMA).to_bits() - 1),
                _ => a,
            };
            (PAIR_GAMMA, a, e)
        })
        .collect()
}

/// `P(γ, α, e_n)` of the table of one pair with the same bits in Rust (`Table::p_e`) and in C
/// (`oblq_p_e` of `examples/c/query.c` on the export of `sweep export`): random points `(α,
/// e_n)` (10⁶ in the release check, 10⁵ otherwise) at the pair's γ, and at γ within 5e-10
/// (relative) of it, which both take as the pair's. The export is layout version 3, the format
/// crate's bytes.
#[test]
fn pair_table_gives_the_same_bits_in_rust_and_c_on_random_points() {
    let start = std::time::Instant::now();
    let (t, path) = pair_table();
    let s = t.surface();
    assert_eq!(s.pair_gamma(), Some(PAIR_GAMMA));
    let bytes = std::fs::read(path).expect("export");
    assert_eq!(bytes, export::export(s, t.error_bound(), true, &[]));
    assert_eq!(
        &bytes[8..16],
        &[3, 0, 0, 0, 112, 0, 0, 0],
        "version 3, 112-byte header"
    );
    assert_eq!(bytes[32..40], bytes[40..48], "gamma_min == gamma_max");
    let query = query_program();
    let range = t.restitution().expect("an e_n axis");
    let n = sized(100_000, 1_000_000);
    let mut pts = pair_points(n, 53, range);
    // Every 20th point at a γ within 5e-10 (relative) of the pair's: the pair's answer.
    let near = |i: usize| match i % 80 {
        10 => PAIR_GAMMA * (1.0 + 5e-10),
        30 => PAIR_GAMMA * (1.0 - 5e-10),
        50 => ulp_up(PAIR_GAMMA),
        70 => f64::from_bits(PAIR_GAMMA.to_bits() - 1),
        _ => PAIR_GAMMA,
    };
    for (i, p) in pts.iter_mut().enumerate() {
        p.0 = near(i);
    }
    let rust: Vec<f64> = pts
        .iter()
        .map(|&(g, a, e)| t.p_e(g, a, e).expect("at the pair's gamma"))
        .collect();
    let rust_s = start.elapsed().as_secs_f64();
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?},{a:?},{e:?}\n"))
        .collect();
    let c_start = std::time::Instant::now();
    let out = run_ok(query, &[path.to_str().expect("path")], &input);
    let c_s = c_start.elapsed().as_secs_f64();
    let c: Vec<f64> = out
        .lines()
        .map(|l| l.rsplit(',').next().expect("P").parse().expect("P"))
        .collect();
    assert_eq!(c.len(), n, "every point answered by C");
    let (mut differ, mut line_pts, mut snapped) = (0, 0, 0);
    for (i, &(g, a, e)) in pts.iter().enumerate() {
        line_pts += usize::from(a <= oblique_physics::regimes::linear_limit_dissipative(g, e));
        if c[i].to_bits() != rust[i].to_bits() {
            differ += 1;
            if differ < 5 {
                eprintln!(
                    "gamma {g:?} alpha {a:?} e_n {e:?}: p_e {:?}, C {:?}",
                    rust[i], c[i]
                );
            }
        }
        if g != PAIR_GAMMA {
            // γ within 5e-10: the answer at the pair's γ, to the bit.
            let at_pair = t.p_e(PAIR_GAMMA, a, e).expect("inside");
            assert_eq!(rust[i].to_bits(), at_pair.to_bits(), "{g:?} {a:?} {e:?}");
            snapped += 1;
        }
    }
    assert_eq!(differ, 0, "{differ} of {n} points differ in some bit");
    assert!(
        line_pts > n / 20 && line_pts < n / 2,
        "{line_pts} on the line"
    );
    assert!(snapped >= n / 20, "{snapped} near the pair's gamma");
    eprintln!(
        "table of one pair: {n} points (α, e_n), {line_pts} on the full-slip line, {snapped} at \
         γ within 5e-10 of the pair's: p_e == C bit for bit (Rust {rust_s:.2} s, C with its \
         I/O {c_s:.2} s, in all {:.1} s)",
        start.elapsed().as_secs_f64()
    );
}

/// The table of one pair refuses another γ above the full-slip line (1e-6 off, 2e-9 off, other
/// materials) with `OBLQ_E_GAMMA_DOMAIN` where Rust refuses it naming `gamma`, answers the line
/// at any γ, clamps to the pair's γ with clamping, and refuses `e_n` outside its range; `oblq_p`
/// answers its `e_n = 1` slice, all with Rust's bits.
#[test]
fn pair_table_refuses_another_gamma_as_rust_does() {
    use oblique_physics::regimes::alpha_c1_dissipative;
    let (t, path) = pair_table();
    let path = path.to_str().expect("path");
    let base = pair_points(20_000, 59, (0.45, 1.02));
    let gammas = [
        PAIR_GAMMA * (1.0 + 1e-6),
        PAIR_GAMMA * (1.0 - 1e-6),
        PAIR_GAMMA * (1.0 + 2e-9),
        PAIR_GAMMA * (1.0 - 2e-9),
        PAIR_GAMMA * (1.0 + 5e-10),
        PAIR_GAMMA,
        1.2,
        0.8,
        3.0,
    ];
    let mut pts: Vec<(f64, f64, f64)> = base
        .iter()
        .enumerate()
        .map(|(i, &(_, a, e))| (gammas[i % gammas.len()], a, e))
        .collect();
    // The edge of the tolerance: |γ − γ_pair| against 1e-9·γ_pair, either side of it.
    let tol = 1e-9 * PAIR_GAMMA;
    let mut edge = PAIR_GAMMA + tol;
    while (edge - PAIR_GAMMA).abs() > tol {
        edge = f64::from_bits(edge.to_bits() - 1);
    }
    for g in [edge, ulp_up(edge), ulp_up(ulp_up(edge))] {
        pts.push((g, 0.3, 0.8));
        pts.push((g, f64::INFINITY, 0.6));
    }
    let a1 = alpha_c1_dissipative(3.0, 0.8);
    pts.extend([
        (f64::NAN, 0.3, 0.8),
        (-PAIR_GAMMA, 0.3, 0.8),
        (f64::INFINITY, 0.3, 0.8),
        (PAIR_GAMMA, -0.1, 0.8),
        (PAIR_GAMMA, 0.3, 0.499_999_999_999_999_9),
        (PAIR_GAMMA * (1.0 + 1e-6), 0.3, 0.4), // e_n is checked first
        (3.0, 0.5 * a1, 0.8),                  // on the line at γ = 3: answered
        (3.0, 2.0 * a1, 0.8),                  // above it: refused
    ]);
    // A γ refused names the pair's.
    for &(g, a, e) in &pts {
        if let Err(err) = t.p_e_with(g, a, e, OutOfDomain::Error) {
            if status_of(&err, g, a) == 9 {
                assert!(err.to_string().contains("1.7497858600774299"), "{err}");
            }
        }
    }
    for clamp in [0, 1] {
        let (refused, answered) = pe_against_rust(t, path, &pts, clamp, "e_n 1 0.5 1");
        // Another γ above the line: refused without clamping, answered at the pair's with it.
        assert_eq!(refused[9] > 8000, clamp == 0, "clamp {clamp}: {refused:?}");
        assert!(refused[24] > 500, "clamp {clamp}: {refused:?}");
        assert_eq!(refused[7] + refused[8], 4, "clamp {clamp}: {refused:?}");
        assert!(answered > 1000, "clamp {clamp}: {answered} answered");
    }
    // The tolerance's edge: within it the pair's bits, one ulp beyond it refused (above the
    // line), in Rust and C alike (checked above); here that the edge is where Rust puts it.
    let at_pair = t.p_e(PAIR_GAMMA, 0.3, 0.8).expect("inside");
    assert_eq!(
        t.p_e(edge, 0.3, 0.8).expect("inside").to_bits(),
        at_pair.to_bits()
    );
    assert!(t.p_e(ulp_up(edge), 0.3, 0.8).is_err());
    // oblq_p: the e_n = 1 slice at the pair's γ (and its refusals elsewhere).
    let mut pts = points(4_000, 61, PAIR_GAMMA, PAIR_GAMMA);
    pts.extend([
        (PAIR_GAMMA * (1.0 + 1e-6), 0.3),
        (PAIR_GAMMA * (1.0 + 5e-10), 0.3),
    ]);
    let input: String = pts.iter().map(|(g, a)| format!("{g:?} {a:?}\n")).collect();
    let out = run_ok(gcc_driver(), &["p", path, "0"], &input);
    for ((g, a), line) in pts.iter().zip(out.lines()) {
        match t.p(*g, *a) {
            Ok(r) => {
                let c: f64 = line.parse().expect("P");
                assert_eq!(c.to_bits(), r.to_bits(), "oblq_p: gamma {g:?} alpha {a:?}");
            }
            Err(err) => assert_eq!(line, format!("error {}", status_of(&err, *g, *a))),
        }
    }
    // `sweep export --gamma` refuses a curve of the table, as of every table with an e_n axis.
    curves_are_refused(
        &root("tables/dissipative-pair.h5"),
        "pair_curves.oblq",
        "1.7497858600774299",
    );
}

/// Rebounds of the pair's bodies on the table of one pair (`oblq_pair_init_e` with the pair's
/// γ, or one 1e-6 off): the bits of `Table::rebound_3d`, and its refusals with their codes.
#[test]
fn rebounds_on_the_table_of_one_pair_give_the_bits_of_the_rust_library() {
    let (t, path) = pair_table();
    let mut r = SplitMix(67);
    let (mut compared, mut refused) = (0, 0);
    for case in 0..8 {
        let wall = case % 2 == 0;
        let pair = Pair {
            sphere: random_body(&mut r),
            other: (!wall).then(|| random_body(&mut r)),
        };
        let gamma = match case {
            3 => PAIR_GAMMA * (1.0 + 1e-6),
            5 => PAIR_GAMMA * (1.0 - 3e-10),
            _ => PAIR_GAMMA,
        };
        let mu = 0.05 + r.uniform();
        let e_n = match case {
            0 => 1.0,
            1 => 0.5,
            6 => 0.4, // below the table's range: refused (24)
            _ => 0.5 + 0.5 * r.uniform(),
        };
        let contact = Contact::with_gamma(gamma, mu).with_restitution(e_n);
        let mut incidents = Vec::new();
        while incidents.len() < 300 {
            incidents.extend(random_impact(&mut r, wall));
        }
        let input: String = incidents.iter().map(incident_line).collect();
        let args = rebound_args("rebound", path, Some("table"), &pair, gamma, mu, e_n);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(gcc_driver(), &args, &input);
        assert_eq!(out.lines().count(), incidents.len());
        for (s, line) in incidents.iter().zip(out.lines()) {
            match t.rebound_3d(&pair, &contact, s) {
                Ok(a) => {
                    let c = parse_line(line);
                    let mut want = rebound_fields(&a);
                    want.extend([a.rebound.normal_impulse, a.rebound.e_n]);
                    assert_eq!(c.len(), want.len(), "{line}");
                    for (k, (x, y)) in c.iter().zip(&want).enumerate() {
                        assert!(
                            x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
                            "case {case} gamma {gamma:?} e_n {e_n:?} field {k}: C {x:?}, \
                             Rust {y:?}"
                        );
                    }
                    compared += 1;
                }
                Err(e) => {
                    assert_eq!(line, rebound_status(&e), "case {case}: {e}");
                    refused += 1;
                }
            }
        }
    }
    assert!(compared > 1500 && refused > 400, "{compared} {refused}");
    eprintln!(
        "rebounds on the table of one pair: {compared} C == Rust bit for bit, {refused} \
         refused by both alike"
    );
}

/// Exports of the table of one pair edited and resealed: a γ bit in a split mask, a patch whose
/// γ edges differ, a header whose γ range is not a single γ, a patch of two γ blocks, a leaf
/// marked split, the pair's export read as version 2 or a range's export as version 3: each
/// refused (`OBLQ_E_CORRUPT`); an unknown version by its version; damage by the checksum.
#[test]
fn damaged_pair_exports_are_refused() {
    let (_, path) = pair_table();
    let good = std::fs::read(path).expect("export");
    let open = |name: &str, bytes: &[u8]| open_export(&format!("pair_{name}"), bytes);
    let with = |edits: &[(usize, Vec<u8>)]| {
        let mut b = good.clone();
        for (at, v) in edits {
            b[*at..*at + v.len()].copy_from_slice(v);
        }
        sealed(b)
    };
    assert!(open("good", &good).starts_with("0 ok"));
    assert!(open("truncated", &good[..good.len() - 8]).starts_with("2 "));
    let mut flipped = good.clone();
    flipped[good.len() / 2] ^= 0x08;
    assert!(open("flipped", &flipped).starts_with("5 "));
    let mut newer = good.clone();
    newer[8] = 9;
    assert!(open("newer", &newer).starts_with("4 "));
    let mut v2 = good.clone();
    v2[8] = 2;
    assert!(open("as_v2", &v2).starts_with("6 "), "a single gamma in v2");
    let mut ranged = std::fs::read(&dissipative().1).expect("export");
    ranged[8] = 3;
    assert!(open("range_as_v3", &ranged).starts_with("6 "));
    let g = f64::from_le_bytes(good[32..40].try_into().expect("8"));
    let f = |x: f64| x.to_le_bytes().to_vec();
    let mut cases: Vec<(String, Vec<u8>)> = vec![
        ("gamma_max_up".into(), with(&[(40, f(ulp_up(g)))])),
        ("gamma_min_down".into(), with(&[(32, f(g * (1.0 - 1e-12)))])),
        (
            "gamma_both_other".into(),
            with(&[(32, f(1.5)), (40, f(1.5))]),
        ),
        ("gamma_range".into(), with(&[(32, f(1.5)), (40, f(2.0))])),
        ("curves".into(), with(&[(80, 1u32.to_le_bytes().to_vec())])),
    ];
    let dir_at = u64_at(&good, 72) as usize;
    let mut masked = 0;
    for k in 0..3 {
        let r = dir_at + 160 * k;
        if u32_at(&good, r) == 0 {
            continue;
        }
        let lo = f64::from_le_bytes(good[r + 8..r + 16].try_into().expect("8"));
        cases.push((format!("{k}_gamma_hi_up"), with(&[(r + 16, f(ulp_up(lo)))])));
        cases.push((
            format!("{k}_gamma_lo_down"),
            with(&[(r + 8, f(lo * (1.0 - 1e-9)))]),
        ));
        cases.push((
            format!("{k}_both_edges_other"),
            with(&[(r + 8, f(1.5)), (r + 16, f(1.5))]),
        ));
        cases.push((
            format!("{k}_blocks_gamma_2"),
            with(&[(r + 24, 2u32.to_le_bytes().to_vec())]),
        ));
        cases.push((
            format!("{k}_blocks_e_n_0"),
            with(&[(r + 136, 0u32.to_le_bytes().to_vec())]),
        ));
        cases.push((
            format!("{k}_warp"),
            with(&[(r + 44, 1u32.to_le_bytes().to_vec())]),
        ));
        cases.push((
            format!("{k}_fine_index"),
            with(&[(r + 120, 8u64.to_le_bytes().to_vec())]),
        ));
        let (masks, cells) = (
            u64_at(&good, r + 144) as usize,
            u32_at(&good, r + 36) as usize,
        );
        let tree_at = u64_at(&good, r + 48) as usize;
        let link =
            |i: usize| i32::from_le_bytes(good[tree_at + 4 * i..][..4].try_into().expect("4"));
        assert!(masks != 0, "patch {k} has split masks");
        let split = (0..cells).find(|&i| link(i) >= 0).expect("a split cell");
        let leaf = (0..cells).find(|&i| link(i) < 0).expect("a leaf");
        let m = good[masks + split];
        assert!((1..=3).contains(&m), "patch {k}: mask {m}");
        for (name, v) in [
            ("gamma_bit", m | 4),
            ("gamma_only", 4),
            ("all_three", 7),
            ("zero_on_split", 0),
        ] {
            cases.push((format!("{k}_{name}"), with(&[(masks + split, vec![v])])));
        }
        cases.push((
            format!("{k}_mask_on_leaf"),
            with(&[(masks + leaf, vec![3])]),
        ));
        masked += 1;
    }
    assert!(masked >= 2, "{masked} patches");
    for (name, bytes) in &cases {
        let said = open(name, bytes);
        assert!(said.starts_with("6 "), "{name}: {said}");
    }
}

/// `oblq_p_at` of the C header (driver `pat TABLE CLAMP N`, lines of `N` values) on the exports
/// of `tables/default.h5` (axes γ, α, e_n) and `tables/full.h5` (γ, α): the axes it lists are
/// `Table::axes`, and every point gets the bits of `Table::p_at_with` (itself those of `p` and
/// `p_e`, `crates/lookup/tests/point.rs`) or its refusal's code; a point of another number of
/// values is `OBLQ_E_AXES` (28).
#[test]
fn p_at_gives_the_bits_of_the_rust_point_query() {
    for name in ["default", "full"] {
        let t = Table::open(root(&format!("tables/{name}.h5"))).expect("shipped table");
        let path = dir().join(format!("{name}_p_at.oblq"));
        std::fs::write(
            &path,
            export::export(t.surface(), t.error_bound(), true, &[]),
        )
        .expect("write export");
        let path = path.to_str().expect("path");
        let s = t.surface();
        let (g0, g1) = (s.gamma_min(), s.gamma_max());
        let e = t.restitution().unwrap_or((1.0, 1.0));
        // γ a little beyond the domain at both ends.
        let pts = points_e(
            sized(20_000, 100_000),
            52,
            (g0 - 0.05 * (g1 - g0), g1 + 0.05 * (g1 - g0)),
            e,
        );
        let n = t.axes().len();
        let header = format!("axes {}", t.axes().join(" "));
        let row = |&(g, a, e): &(f64, f64, f64)| -> Vec<f64> { [g, a, e][..n].to_vec() };
        for clamp in [0u8, 1] {
            let input: String = pts
                .iter()
                .map(|p| {
                    let v: Vec<String> = row(p).iter().map(|x| format!("{x:?}")).collect();
                    v.join(" ") + "\n"
                })
                .collect();
            let out = run_ok(
                gcc_driver(),
                &["pat", path, &clamp.to_string(), &n.to_string()],
                &input,
            );
            let mut lines = out.lines();
            assert_eq!(lines.next(), Some(header.as_str()), "{name}");
            let outside = if clamp == 1 {
                OutOfDomain::Clamp
            } else {
                OutOfDomain::Error
            };
            let mut count = 0;
            for (p, line) in pts.iter().zip(lines) {
                count += 1;
                match t.p_at_with(&row(p), outside) {
                    Ok(r) => assert_eq!(
                        line.parse::<f64>().map(f64::to_bits),
                        Ok(r.to_bits()),
                        "{name} {p:?} clamp {clamp}"
                    ),
                    Err(err) => assert_eq!(
                        line,
                        format!("error {}", status_of(&err, p.0, p.1)),
                        "{name} {p:?} clamp {clamp}: {err}"
                    ),
                }
            }
            assert_eq!(count, pts.len(), "{name}");
        }
        for wrong in [n - 1, n + 1] {
            let input = "1.5 0.3 0.9 1.0\n".repeat(3);
            let out = run_ok(
                gcc_driver(),
                &["pat", path, "0", &wrong.to_string()],
                &input,
            );
            let refused: Vec<&str> = out.lines().skip(1).collect();
            assert!(!refused.is_empty(), "{name}: {out}");
            assert!(
                refused.iter().all(|l| *l == "error 28"),
                "{name} n = {wrong}: {out}"
            );
            assert!(t.p_at(&[1.5, 0.3, 0.9, 1.0][..wrong]).is_err());
        }
    }
}

// ---------------------------------------------------------------------------------------------
// A table of Thornton's law: no closed-form full-slip line (export layout version 8: version 4
// with its e_n axis over (1 - e_n)^(1/4))

/// `configs/thornton-demo.toml` built (once for all test processes of this build,
/// `common::shared_build`), its export by `sweep export` (once per process) and the table file.
fn thornton() -> &'static (Table, PathBuf, PathBuf) {
    static T: OnceLock<(Table, PathBuf, PathBuf)> = OnceLock::new();
    T.get_or_init(|| {
        let d = dir().join("thornton");
        std::fs::create_dir_all(&d).expect("folder");
        let path = d.join("thornton-demo.oblq");
        let table = common::shared_build(&root("configs/thornton-demo.toml"));
        let arg = |p: &Path| p.to_str().expect("path").to_string();
        let said = evaluator::sweep_ok(&["export", &arg(&table), "-o", &arg(&path)]);
        assert!(
            said.contains("the table of the thornton law (e_n in [0.8, 1], over (1-e_n)^(1/4))"),
            "{said}"
        );
        (Table::open(&table).expect("the table"), path, table)
    })
}

/// Random `(γ, α, e_n)` over the domain of a table of Thornton's law: [`points_e`] (γ = 1 in
/// the mix taken to the lowest γ of the domain when it starts above 1), with `α` below
/// `α_c1(γ, e_n)` (uniform, or at `1e-6·α_c1`), at `α_c1(1 ± 1e-12)`, one ulp either side of
/// `α_c2`, `α = 0` and `α = ∞` in the mix.
fn thornton_points(t: &Table, n: usize, seed: u64) -> Vec<(f64, f64, f64)> {
    use oblique_physics::regimes::alpha_c1_dissipative;
    let s = t.surface();
    let range = t.restitution().expect("an e_n axis");
    let mut r = SplitMix(seed ^ 0x7468);
    points_e(n, seed, (s.gamma_min(), s.gamma_max()), range)
        .into_iter()
        .enumerate()
        .map(|(i, (g, a, e))| {
            let g = if g == 1.0 && s.gamma_min() > 1.0 {
                s.gamma_min()
            } else {
                g
            };
            let c1 = alpha_c1_dissipative(g, e);
            let a = match i % 50 {
                3 => c1,
                4 => c1 * (1.0 + 1e-12),
                5 => c1 * (1.0 - 1e-12),
                6 => ulp_up(alpha_c2(g)),
                7 => f64::from_bits(alpha_c2(g).to_bits() - 1),
                8 => 1e-6 * c1,
                9..=14 => c1 * r.uniform(),
                _ => a,
            };
            (g, a, e)
        })
        .collect()
}

/// `P(γ, α, e_n)` of a table of Thornton's law with the same bits from every path:
/// `Table::p_e`, the batches `p_e_batch` and `p_e_batch_par`, `oblq_p_e` of the C header on
/// the export of `sweep export` (layout version 4), and on every 40th point the reference
/// reader `scripts/read_table.py`: random points of `configs/thornton-demo.toml` built here
/// (10⁵ in the release check, 2·10⁴ otherwise), with points below `α_c1`, at `α_c1(1 ± 1e-12)`
/// and at `α = 0`, `∞` in the mix.
#[test]
fn thornton_tables_give_the_same_bits_in_rust_batches_c_and_python_on_random_points() {
    let start = std::time::Instant::now();
    let (t, path, h5) = thornton();
    let s = t.surface();
    assert!(!s.has_line());
    let bytes = std::fs::read(path).expect("export");
    assert_eq!(
        bytes,
        export::export(s, t.error_bound(), true, &[]),
        "sweep export"
    );
    assert_eq!(
        &bytes[8..16],
        &[8, 0, 0, 0, 112, 0, 0, 0],
        "version 8 (version 4 over (1 - e_n)^(1/4)), 112-byte header"
    );
    assert_eq!(
        &bytes[68..72],
        &[1, 0, 0, 0],
        "the flag of a table without the line"
    );
    let n = sized(20_000, 100_000);
    let pts = thornton_points(t, n, 61);
    let scalar: Vec<f64> = pts
        .iter()
        .map(|&(g, a, e)| t.p_e(g, a, e).expect("inside"))
        .collect();
    let columns = |k: usize| -> Vec<f64> { pts.iter().map(|p| [p.0, p.1, p.2][k]).collect() };
    let (g, a, e) = (columns(0), columns(1), columns(2));
    let (mut serial, mut parallel) = (vec![f64::NAN; n], vec![f64::NAN; n]);
    t.p_e_batch(&g, &a, &e, &mut serial, OutOfDomain::Error)
        .expect("serial batch");
    t.p_e_batch_par(&g, &a, &e, &mut parallel, OutOfDomain::Error)
        .expect("parallel batch");
    let input: String = pts
        .iter()
        .map(|(g, a, e)| format!("{g:?},{a:?},{e:?}\n"))
        .collect();
    let out = run_ok(query_program(), &[path.to_str().expect("path")], &input);
    let c: Vec<f64> = out
        .lines()
        .map(|l| l.rsplit(',').next().expect("P").parse().expect("P"))
        .collect();
    assert_eq!(c.len(), n, "every point answered by C");
    let (mut differ, mut below, mut off_line) = (0, 0, 0.0f64);
    for (i, &(g, a, e)) in pts.iter().enumerate() {
        let c1 = oblique_physics::regimes::alpha_c1_dissipative(g, e);
        if a <= c1 {
            below += 1;
            // Not answered from the line: the table's own values there.
            off_line =
                off_line.max((scalar[i] - oblique_physics::regimes::full_slip_line(a, e)).abs());
        }
        let bits = [scalar[i], serial[i], parallel[i], c[i]].map(f64::to_bits);
        if bits.iter().any(|&b| b != bits[0]) {
            differ += 1;
            if differ < 5 {
                eprintln!(
                    "gamma {g:?} alpha {a:?} e_n {e:?}: p_e {:?}, batch {:?}, parallel {:?}, \
                     C {:?}",
                    scalar[i], serial[i], parallel[i], c[i]
                );
            }
        }
    }
    assert_eq!(differ, 0, "{differ} of {n} points differ in some bit");
    assert!(below > n / 10 && below < n / 2, "{below} below alpha_c1");
    assert!(
        off_line > 1e-6,
        "P below alpha_c1 off the line by at most {off_line:e}"
    );
    let every = 40;
    let subset: Vec<_> = pts.iter().copied().step_by(every).collect();
    let py = python_p_e(h5, &subset);
    assert_eq!(py.len(), subset.len(), "every point answered by Python");
    for (k, (&p, &(g, a, e))) in py.iter().zip(&subset).enumerate() {
        let r = scalar[k * every];
        assert_eq!(
            p.to_bits(),
            r.to_bits(),
            "gamma {g:?} alpha {a:?} e_n {e:?}: read_table.py {p:?}, Rust {r:?}"
        );
    }
    eprintln!(
        "Thornton's law: {n} points (γ, α, e_n), {below} at α ≤ α_c1 (P off the line there by up \
         to {off_line:.2e}): p_e == p_e_batch == p_e_batch_par == C bit for bit, {} of them == \
         read_table.py ({:.1} s)",
        subset.len(),
        start.elapsed().as_secs_f64()
    );
}

/// `oblq_p_e` of a table of Thornton's law refuses and clamps as the Rust rule does, with its
/// bits: `γ` below the domain (`γ = 1` and below, where an elastic or Kelvin–Voigt table would
/// answer the full-slip line) is refused even at `α = 0`, or clamped; `α` above `alpha_max`,
/// `e_n` outside the range and invalid values are refused with Rust's codes.
#[test]
fn thornton_clamp_and_refusals_match_the_rust_rule() {
    let (t, path, _) = thornton();
    let s = t.surface();
    let path = path.to_str().expect("path");
    let range = t.restitution().expect("an e_n axis");
    let mut pts = points_e(
        sized(20_000, 40_000),
        67,
        (0.5 * s.gamma_min(), 1.2 * s.gamma_max()),
        (range.0 - 0.05, 1.0),
    );
    pts.extend([
        (1.0, 0.0, 0.9),
        (1.0, 0.01, 0.9),
        (0.5, 0.01, 0.9),
        (1.2, 0.0, 0.9),
        (s.gamma_min(), 0.0, 0.9),
        (s.gamma_max(), f64::INFINITY, 0.9),
        (f64::NAN, 0.5, 0.9),
        (1.7, -0.1, 0.9),
        (1.7, 0.3, f64::NAN),
        (1.7, 0.3, 0.799_999_999_999_999_9),
    ]);
    for clamp in [0, 1] {
        let (refused, answered) =
            pe_against_rust(t, path, &pts, clamp, "e_n 1 0.80000000000000004 1");
        assert!(refused[24] > 1000, "clamp {clamp}: {refused:?}");
        assert_eq!(refused[9] > 3000, clamp == 0, "clamp {clamp}: {refused:?}");
        assert_eq!(refused[7] + refused[8], 2, "clamp {clamp}: {refused:?}");
        assert!(answered > 1000, "clamp {clamp}: {answered} answered");
    }
}

/// An export of version 4 whose flag, version or domain was edited (and resealed) is refused
/// as damaged (`OBLQ_E_CORRUPT`); a version-2 export with the flag set likewise.
#[test]
fn damaged_thornton_exports_are_refused_with_their_code() {
    let (_, path, _) = thornton();
    let good = std::fs::read(path).expect("export");
    let case = |name: &str, bytes: &[u8]| -> String {
        let p = dir().join(format!("thornton_{name}"));
        std::fs::write(&p, bytes).expect("write");
        run_ok(gcc_driver(), &["open", p.to_str().expect("path")], "")
    };
    assert!(case("good", &good).starts_with("0 ok"));
    let mut newer = good.clone();
    newer[8] = 9;
    assert!(case("newer", &newer).starts_with("4 "));
    let dir_at = u64::from_le_bytes(good[72..80].try_into().expect("8 bytes")) as usize;
    let partial = dir_at + 160;
    let bc = u32::from_le_bytes(
        good[partial + 28..partial + 32]
            .try_into()
            .expect("4 bytes"),
    );
    let edits: Vec<(&str, usize, Vec<u8>)> = vec![
        ("as_v2", 8, 2u32.to_le_bytes().to_vec()),
        ("as_v3", 8, 3u32.to_le_bytes().to_vec()),
        // The map in a version that has none, and version 8 without it.
        ("as_v4", 8, 4u32.to_le_bytes().to_vec()),
        ("no_map", 84, 0u32.to_le_bytes().to_vec()),
        ("flag_2", 68, 2u32.to_le_bytes().to_vec()),
        ("gamma_min_below_1", 32, 0.9f64.to_le_bytes().to_vec()),
        (
            "odd_blocks_coord",
            partial + 28,
            (bc + 1).to_le_bytes().to_vec(),
        ),
    ];
    for (name, at, value) in edits {
        let mut b = good.clone();
        b[at..at + value.len()].copy_from_slice(&value);
        let said = case(name, &sealed(b));
        assert!(said.starts_with("6 "), "{name} at {at}: {said}");
    }
    // A version-2 export (Kelvin–Voigt) with the flag of version 4.
    let mut kv = std::fs::read(&dissipative().1).expect("export");
    kv[68] = 1;
    assert!(case("kv_flagged", &sealed(kv.clone())).starts_with("6 "));
    kv[8] = 4;
    // Labelled 4 with the flag: answered only if the domain starts at γ ≥ 1 (this one does not).
    assert!(case("kv_as_v4", &sealed(kv)).starts_with("6 "));
}

// ---------------------------------------------------------------------------------------------
// An elastic table whose split cells halve only the axes they need (export layout version 6)

/// The table of [`evaluator::anisotropic_table`] (built once per build), its export (once per
/// process) and the table file.
fn anisotropic() -> &'static (Table, PathBuf, PathBuf) {
    static T: OnceLock<(Table, PathBuf, PathBuf)> = OnceLock::new();
    T.get_or_init(|| evaluator::anisotropic_table(&dir().join("anisotropic")))
}

/// An elastic table with split masks (cells halving γ only, `c` only, or both) and a warp:
/// `examples/c/query.c` gives the bits of `Table::p` at random points (10⁵, 10⁶ in the release
/// check), the exported curves the bits of `Curve::p`, the clamp and refusals those of the Rust
/// rule, and the reference reader `scripts/read_table.py` agrees within 1e-14 on every 50th
/// point (its rule for tables without an `e_n` axis is not written for the same bits), 1e-10
/// just below `α_c2` where the partial-slip coordinate amplifies rounding.
#[test]
fn anisotropic_table_gives_the_bits_of_rust_in_c_and_agrees_with_python() {
    let start = std::time::Instant::now();
    let (t, export, table) = anisotropic();
    let s = t.surface();
    let n = sized(100_000, 1_000_000);
    let pts = points(n, 31, s.gamma_min(), s.gamma_max());
    let input: String = pts.iter().map(|(g, a)| format!("{g:?},{a:?}\n")).collect();
    let out = run_ok(query_program(), &[export.to_str().expect("path")], &input);
    let c: Vec<f64> = out
        .lines()
        .map(|l| l.rsplit(',').next().expect("P").parse().expect("P"))
        .collect();
    assert_eq!(c.len(), n, "every point answered by C");
    let rust: Vec<f64> = pts
        .iter()
        .map(|&(g, a)| t.p(g, a).expect("inside"))
        .collect();
    let differ = (0..n)
        .filter(|&i| c[i].to_bits() != rust[i].to_bits())
        .count();
    assert_eq!(differ, 0, "{differ} of {n} points differ in some bit");
    // The curves of the export.
    for (i, &g) in evaluator::ANISOTROPIC_GAMMAS.iter().enumerate() {
        curve_bits(t, export, i, g, 5_000, i as u64 + 41);
    }
    // Clamped and refused outside the domain as in Rust.
    let pts_out = points(20_000, 33, 0.05, 4.0);
    let input: String = pts_out
        .iter()
        .map(|(g, a)| format!("{g:?} {a:?}\n"))
        .collect();
    for (clamp, outside) in [(0, OutOfDomain::Error), (1, OutOfDomain::Clamp)] {
        let out = run_ok(
            gcc_driver(),
            &["p", export.to_str().expect("path"), &clamp.to_string()],
            &input,
        );
        for ((g, a), line) in pts_out.iter().zip(out.lines()) {
            match t.p_with(*g, *a, outside) {
                Ok(r) => {
                    let p: f64 = line.parse().expect("P");
                    assert_eq!(p.to_bits(), r.to_bits(), "gamma {g:?} alpha {a:?}");
                }
                Err(_) => assert_eq!(line, "error 9", "gamma {g} alpha {a}"),
            }
        }
    }
    // The reference reader.
    let every = 50;
    let subset: Vec<(f64, f64, f64)> = pts
        .iter()
        .step_by(every)
        .map(|&(g, a)| (g, a, 1.0))
        .collect();
    let py = python_p_e(table, &subset);
    assert_eq!(py.len(), subset.len(), "every point answered by Python");
    let mut worst = 0.0f64;
    for (k, (&p, &(g, a, _))) in py.iter().zip(&subset).enumerate() {
        let r = rust[k * every];
        let ill = g > 1.0 && a < alpha_c2(g) && a > alpha_c2(g) * (1.0 - 1e-9);
        let tol = if ill { 1e-10 } else { 1e-14 };
        assert!(
            (p - r).abs() <= tol,
            "gamma {g:?} alpha {a:?}: read_table.py {p:?}, Rust {r:?}"
        );
        if !ill {
            worst = worst.max((p - r).abs());
        }
    }
    eprintln!(
        "anisotropic: {n} points C == Rust bit for bit, {} curves, {} points read_table.py \
         within {worst:.1e} ({:.1} s)",
        evaluator::ANISOTROPIC_GAMMAS.len(),
        subset.len(),
        start.elapsed().as_secs_f64()
    );
}

/// The split masks of a version-6 export (offset 144 of a patch record): `oblq_open` refuses
/// a mask of 0 on a split cell, a mask on a leaf, a mask above 3 (an `e_n` bit), masks that do
/// not account for the cells after the roots, an offset past the end, a fine index beside the
/// masks, and the export labelled version 1 (whose records have no masks); a header of version
/// 5 refuses it by its version.
#[test]
fn damaged_masks_of_an_elastic_export_are_refused() {
    let (_, path, _) = anisotropic();
    let good = std::fs::read(path).expect("export");
    let open = |name: &str, bytes: &[u8]| open_export(&format!("aniso_{name}"), bytes);
    assert!(open("good", &good).starts_with("0 ok"));
    let with = |at: usize, v: &[u8]| {
        let mut b = good.clone();
        b[at..at + v.len()].copy_from_slice(v);
        sealed(b)
    };
    assert!(open("as_v1", &with(8, &1u32.to_le_bytes())).starts_with("6 "));
    assert!(open("as_v8", &with(8, &8u32.to_le_bytes())).starts_with("6 "));
    assert!(open("as_v9", &with(8, &9u32.to_le_bytes())).starts_with("4 "));
    let mut cases = 0;
    for rec in masked_records(&good) {
        let MaskedRecord {
            k,
            record: r,
            masks,
            cells,
            ..
        } = rec;
        assert_eq!(u64_at(&good, r + 120), 0, "no fine index beside masks");
        let link = |i: usize| rec.link(&good, i);
        let leaf = (0..cells).find(|&i| link(i) < 0).expect("a leaf");
        for split in (0..cells).filter(|&i| link(i) >= 0).take(3) {
            for (name, bytes) in [
                ("zero_on_split", with(masks + split, &[0])),
                ("on_leaf", with(masks + leaf, &[1])),
                ("e_n_bit", with(masks + split, &[4])),
                ("above_3", with(masks + split, &[good[masks + split] | 4])),
                (
                    "offset_past_end",
                    with(r + 144, &(good.len() as u64).to_le_bytes()),
                ),
                // A fine index beside the masks (its offset, anywhere inside).
                ("index", with(r + 120, &8u64.to_le_bytes())),
                ("index_depth", with(r + 112, &1u32.to_le_bytes())),
            ] {
                let said = open(name, &bytes);
                assert!(
                    said.starts_with("6 "),
                    "patch {k} cell {split} {name}: {said}"
                );
            }
            // Another mask (1 <-> 2 <-> 3): the children no longer add up or a descent takes
            // other children; refused, or answered inside [-1, 1] without a crash (the
            // sanitizers' fuzz below reads such exports).
            let m = good[masks + split];
            let other = if m == 3 { 1 } else { 3 };
            let said = open("other_axes", &with(masks + split, &[other]));
            assert!(said.starts_with("6 "), "patch {k} other axes: {said}");
            cases += 1;
        }
    }
    assert!(cases > 0, "the export has split masks");
}

/// Damaged split masks in the HDF5 table itself (edited and sealed again): a mask of 4 (an
/// `e_n` bit the table does not have), a mask on a leaf and a split cell without one are refused
/// by the library and by the reference reader, each naming the dataset `split`; another mask on
/// a split cell (its children no longer add up to the cells of the tree), naming `tree`.
#[test]
fn damaged_masks_of_an_elastic_table_are_refused_by_rust_and_python() {
    let (_, _, table) = anisotropic();
    let d = dir().join("aniso_h5");
    std::fs::create_dir_all(&d).expect("folder");
    // `s`: the masks of partial_high; `i`: its first split cell, `j` its first leaf.
    let find = "g = f['patches/partial_high']; s = g['split'][()]; \
                i = int((s > 0).argmax()); j = int((s == 0).argmax()); ";
    for (name, edit, needle) in [
        ("e_n_bit", "s[i] = 4", "'split'"),
        ("above_3", "s[i] = s[i] | 4", "'split'"),
        ("on_leaf", "s[j] = 1", "'split'"),
        ("zero_on_split", "s[i] = 0", "'split'"),
        ("other_axes", "s[i] = 1 if s[i] == 3 else 3", "'tree'"),
    ] {
        let bad = d.join(format!("{name}.h5"));
        common::edited_copy(table, &bad, &format!("{find}{edit}; g['split'][...] = s"));
        let e = Table::open(&bad).map(|_| ()).expect_err(name);
        assert!(e.to_string().contains(needle), "{name}: {e}");
        let reader = Command::new("python3")
            .args([
                root("scripts/read_table.py").to_str().expect("path"),
                bad.to_str().expect("path"),
                "--gamma",
                "1.5",
                "--alpha",
                "0.3",
            ])
            .output()
            .expect("the reference reader");
        let err = String::from_utf8_lossy(&reader.stderr);
        assert!(!reader.status.success(), "{name}: read_table.py answered");
        assert!(err.contains(needle), "{name}: {err}");
    }
}
