//! Tables of Thornton's elastic–plastic law, `P(γ, α, e_n)`, end to end: `sweep run
//! configs/thornton-demo.toml` builds one, its partial-slip patch covers `0 ≤ α ≤ α_c2` with
//! simulated nodes below `α_c1` (the law has no closed-form full-slip line), every query path
//! answers with the same bits, the table holds its stated bound against direct solves at
//! random points, next to `α_c1` and at the law's own edge of full slip, the export (layout
//! version 8: version 4 over `(1 − e_n)^{1/4}`) and the reference reader answer it with the same bits, and a file whose law and
//! coordinate disagree or a config it cannot be built from is refused by name.

mod common;
use common::{sweep_ok as ok, sweep_refused as refused};

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use oblique_lookup::{OutOfDomain, Table};
use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2, full_slip_line};
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::surface::{PartialMap, Region};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const KV_DEMO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-demo.h5");

/// `configs/thornton-demo.toml` built once for all test processes of this build
/// (`common::shared_build`; `tests/c_evaluator.rs` checks the same table's bits).
fn table() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| common::shared_build(&Path::new(ROOT).join("configs/thornton-demo.toml")))
}

fn t() -> &'static str {
    table().to_str().expect("path")
}

/// `P` of Thornton's law by a direct solve at tolerance 1e-8: the value and its estimate.
fn solve(gamma: f64, alpha: f64, e_n: f64) -> (f64, f64) {
    let s = Request::new(gamma, alpha)
        .e_n(e_n)
        .law(Law::Thornton)
        .accuracy(Accuracy::Tolerance(1e-8))
        .solve()
        .expect("a Thornton solve");
    (s.p, s.error_estimate)
}

#[test]
fn the_table_names_its_law_and_its_coordinate() {
    let v: serde_json::Value =
        serde_json::from_str(&ok(&["inspect", t(), "--json"])).expect("JSON");
    assert_eq!(v["law"].as_str(), Some("thornton"), "{v}");
    assert!(ok(&["inspect", t()]).contains("(thornton law)"));
    let table = Table::open(table()).expect("open");
    assert_eq!(table.provenance().law, "thornton");
    assert_eq!(table.surface().partial_map(), PartialMap::Slip);
    assert!(!table.surface().has_line());
}

/// Random points, points below `α_c1`, at `α_c1(1 ± 1e-3)` and at the law's own edge `α₁`,
/// against direct solves at tol 1e-8: within the stated bound (plus the solve's estimate), and
/// below `α_c1` answered by the partial-slip patch, not by the line.
#[test]
fn the_table_holds_its_bound_against_direct_solves_below_and_above_alpha_c1() {
    let table = Table::open(table()).expect("open");
    let bound = table.error_bound();
    assert!(bound > 0.0 && bound < 1e-3, "bound {bound:e}");
    let s = table.surface();
    let (g0, g1) = (s.gamma_min(), s.gamma_max());
    let (e0, e1) = table.restitution().expect("an e_n axis");
    let mut next = oblique_lookup::testing::uniform(0x7468_6f72_6e74_6f6e);
    let mut points = Vec::new();
    for i in 0..36 {
        let gamma = g0 + (g1 - g0) * next();
        let e_n = e0 + (e1 - e0) * next();
        let alpha = if i % 9 == 0 {
            f64::INFINITY
        } else {
            10f64.powf(-3.0 + 3.5 * next())
        };
        points.push((gamma, alpha, e_n));
    }
    let mut below = 0;
    for (gamma, e_n) in [(1.61, 0.82), (1.7, 0.85), (1.79, 0.95), (1.65, 0.99)] {
        let c1 = alpha_c1_dissipative(gamma, e_n);
        let edge = oblique_solver::history::full_slip_edge_thornton(gamma, e_n, 4096)
            .expect("the edge of full slip");
        for alpha in [
            0.01,
            0.3 * c1,
            0.9 * c1,
            c1 * (1.0 - 1e-3),
            c1 * (1.0 + 1e-3),
            edge,
        ] {
            points.push((gamma, alpha, e_n));
            below += usize::from(alpha < c1);
        }
    }
    assert!(
        below >= 16 && points.len() >= 60,
        "{below}, {}",
        points.len()
    );
    let mut worst = 0.0_f64;
    for &(gamma, alpha, e_n) in &points {
        let p = table.p_e(gamma, alpha, e_n).expect("inside the domain");
        let (sim, est) = solve(gamma, alpha, e_n);
        let err = (p - sim).abs();
        worst = worst.max(err);
        assert!(
            err <= bound + est,
            "({gamma}, {alpha}, {e_n}): table {p}, simulation {sim}: {err:e} > {bound:e}"
        );
        if alpha <= alpha_c1_dissipative(gamma, e_n) {
            assert_eq!(s.region_at(gamma, alpha, e_n), Region::PartialHigh);
            assert_ne!(p.to_bits(), full_slip_line(alpha, e_n).to_bits());
        }
    }
    // Next to α_c1 the law is off the line by more than the table's error: the line would
    // have been a wrong answer there.
    let (gamma, e_n) = (1.7, 0.85);
    let c1 = alpha_c1_dissipative(gamma, e_n);
    let (sim, _) = solve(gamma, 0.999 * c1, e_n);
    assert!(
        (full_slip_line(0.999 * c1, e_n) - sim).abs() > 3.0 * bound,
        "the line at 0.999 alpha_c1: {:e}",
        (full_slip_line(0.999 * c1, e_n) - sim).abs()
    );
    eprintln!(
        "{} points, worst |error| {worst:.3e}, bound {bound:.3e}",
        points.len()
    );
}

/// The rule written step by step, the indexed query path, the batches, the curves at one
/// `(γ, e_n)` and a prepared pair's line answer alike: the same bits (curves: to 1e-14, as
/// for every table), with and without clamping, inside and outside the domain.
#[test]
fn every_query_path_answers_alike() {
    let table = Table::open(table()).expect("open");
    let s = table.surface();
    let mut next = oblique_lookup::testing::uniform(0x5eed_7ab1_e000_0001);
    let (mut g, mut a, mut e) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..60_000 {
        let gamma = match i % 13 {
            0 => 1.0,
            1 => 1.5,
            2 => 1.9,
            _ => 1.55 + 0.3 * next(),
        };
        let alpha = match i % 10 {
            0 => f64::INFINITY,
            1 => alpha_c2(gamma),
            2 => alpha_c1_dissipative(gamma, 0.8),
            _ => 10f64.powf(-3.5 + 4.0 * next()),
        };
        let e_n = if i % 7 == 0 {
            0.8
        } else {
            0.79 + 0.22 * next()
        };
        for outside in [OutOfDomain::Error, OutOfDomain::Clamp] {
            let fast = table.p_e_with(gamma, alpha, e_n, outside);
            let rule = s.eval_point(gamma, alpha, e_n, outside);
            match (&fast, &rule) {
                (Ok(x), Ok(y)) => assert_eq!(x.to_bits(), y.to_bits(), "({gamma}, {alpha}, {e_n})"),
                (Err(x), Err(y)) => assert_eq!(x.to_string(), y.to_string()),
                _ => panic!("({gamma}, {alpha}, {e_n}): {fast:?} vs {rule:?}"),
            }
        }
        g.push(gamma);
        a.push(alpha);
        // The batch below clamps γ and α; e_n is never clamped, so its e_n is in range.
        e.push(e_n.clamp(0.8, 1.0));
    }
    // Outside the γ range nothing is answered from a line: refused, or clamped into the table.
    let below = table
        .p_e(1.2, 0.01, 0.8)
        .expect_err("gamma below the table");
    assert!(below.to_string().contains("gamma"), "{below}");
    assert_eq!(
        table
            .p_e_with(1.2, 0.01, 0.8, OutOfDomain::Clamp)
            .expect("clamped")
            .to_bits(),
        table
            .p_e(s.gamma_min(), 0.01, 0.8)
            .expect("inside")
            .to_bits()
    );
    let mut out = vec![f64::NAN; g.len()];
    table
        .p_e_batch(&g, &a, &e, &mut out, OutOfDomain::Clamp)
        .expect("batch");
    for i in 0..g.len() {
        let one = table
            .p_e_with(g[i], a[i], e[i], OutOfDomain::Clamp)
            .expect("one");
        assert_eq!(
            out[i].to_bits(),
            one.to_bits(),
            "({}, {}, {})",
            g[i],
            a[i],
            e[i]
        );
    }
    // Curves at one (γ, e_n), also at γ = gamma_min and clamped from below.
    let mut worst = 0.0_f64;
    for (gamma, outside) in [
        (1.6, OutOfDomain::Error),
        (1.73, OutOfDomain::Error),
        (1.8, OutOfDomain::Error),
        (1.3, OutOfDomain::Clamp),
    ] {
        for e_n in [0.8, 0.87, 1.0] {
            let curve = table.curve_e(gamma, e_n, outside).expect("curve");
            for j in 0..=2000 {
                let alpha = if j == 0 {
                    f64::INFINITY
                } else {
                    10f64.powf(-3.5 + 4.5 * f64::from(j) / 2000.0)
                };
                let want = table.p_e_with(gamma, alpha, e_n, outside).expect("p_e");
                worst = worst.max((curve.p(alpha).expect("curve") - want).abs());
            }
        }
    }
    assert!(worst <= 1e-14, "curves: worst {worst:e}");
    // A prepared pair's line (PairLine): the rebound's P is the table's at its α, bit for bit.
    use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
    use oblique_lookup::Contact;
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: None,
    };
    let mut alphas = Vec::new();
    for (gamma, e_n) in [(1.62, 0.87), (1.6, 0.9)] {
        let contact = Contact::with_gamma(gamma, 0.3).with_restitution(e_n);
        let prepared = table.prepare(&pair, &contact).expect("prepared");
        for k in 1..400 {
            let tangential = 0.002 * f64::from(k) * f64::from(k);
            let inc = Incident3 {
                sphere: Motion3 {
                    velocity: [tangential, 0.1 * tangential, 1.2],
                    spin: [0.0, 0.0, 0.0],
                },
                other: Motion3::default(),
                normal: [0.0, 0.0, 1.0],
            };
            let fast = table.rebound_3d_prepared(&prepared, &inc).expect("fast");
            let want = table.p_e(gamma, fast.alpha, e_n).expect("P");
            assert_eq!(
                fast.rebound.p.to_bits(),
                want.to_bits(),
                "alpha {}",
                fast.alpha
            );
            alphas.push(fast.alpha / alpha_c1_dissipative(gamma, e_n));
        }
    }
    assert!(alphas.iter().any(|&r| r < 1.0) && alphas.iter().any(|&r| r > 2.0));
}

#[test]
fn sweep_query_answers_below_alpha_c1_from_the_table() {
    let text = ok(&[
        "query",
        t(),
        "--gamma",
        "1.7",
        "--alpha",
        "0.05",
        "--e-n",
        "0.8",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let p = v["P"].as_f64().expect("P");
    let table = Table::open(table()).expect("open");
    assert_eq!(p, table.p_e(1.7, 0.05, 0.8).expect("P"));
    assert_ne!(p, full_slip_line(0.05, 0.8));
    assert_eq!(v["error_bound"].as_f64(), Some(table.error_bound()));
    assert!(
        v["region"]
            .as_str()
            .is_some_and(|r| r.contains("interpolated")),
        "{text}"
    );
    // A point below the table's γ range is not answered from the line.
    refused(
        &[
            "query",
            t(),
            "--gamma",
            "1.2",
            "--alpha",
            "0.01",
            "--e-n",
            "0.8",
        ],
        &["gamma", "--clamp"],
    );
}

/// `sweep export` writes the table as layout version 8 (version 4 over `(1 − e_n)^{1/4}`) and `scripts/read_table.py` answers it,
/// below `α_c1` too, with the bits of `Table::p_e` (the C header's bits on random points:
/// `tests/c_evaluator.rs`).
#[test]
fn the_export_and_the_reference_reader_answer_it() {
    let out = common::subdir("thornton-export").join("t.bin");
    let said = ok(&["export", t(), "--output", out.to_str().expect("path")]);
    assert!(said.contains("the table of the thornton law"), "{said}");
    let bytes = std::fs::read(&out).expect("the export");
    // Version 8: version 4 with its e_n axis over (1 - e_n)^(1/4) (the default of a Thornton
    // table whose range reaches e_n = 1), the flag at offset 84.
    assert_eq!(&bytes[8..12], &[8, 0, 0, 0], "layout version 8");
    assert_eq!(&bytes[84..88], &[1, 0, 0, 0], "the e_n map");
    assert_eq!(&bytes[68..72], &[1, 0, 0, 0], "no full-slip line");
    let table = Table::open(table()).expect("the table");
    for (g, a, e) in [
        (1.7, 0.05, 0.8),
        (1.65, 0.0, 0.9),
        (1.75, 0.3, 0.95),
        (1.6, 1.0, 1.0),
        (1.8, f64::INFINITY, 0.85),
    ] {
        let r = Command::new("python3")
            .arg(Path::new(ROOT).join("scripts/read_table.py"))
            .arg(t())
            .args(["--gamma", &format!("{g:?}"), "--alpha", &format!("{a:?}")])
            .args(["--e-n", &format!("{e:?}")])
            .output()
            .expect("python3 (with h5py: the test command installs it)");
        let text = String::from_utf8_lossy(&r.stdout);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let p: f64 = text.trim().parse().expect("P");
        let want = table.p_e(g, a, e).expect("inside");
        assert_eq!(
            p.to_bits(),
            want.to_bits(),
            "({g}, {a}, {e}): {p:?} vs {want:?}"
        );
    }
    // Below the γ range nothing is answered from a line.
    let r = Command::new("python3")
        .arg(Path::new(ROOT).join("scripts/read_table.py"))
        .arg(t())
        .args(["--gamma", "1.2", "--alpha", "0.01", "--e-n", "0.8"])
        .output()
        .expect("python3");
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(
        err.contains("gamma") && err.contains("no closed-form full-slip line"),
        "{err}"
    );
}

/// The reference reader `scripts/read_table.py`, which restates the rule with its own code,
/// gives the bits of `Table::p_e` at every point it answers and refuses the same points naming
/// the same argument: random points (2·10⁵ in the release check, 4·10⁴ otherwise) over and
/// around the domain (`γ` a tenth of the range beyond each end, `γ = 1` in the mix; `e_n`
/// beyond its range), with `α` below `α_c1` (uniform, `1e-6·α_c1`, 0), at `α_c1(1 ± 1e-12)`, one ulp
/// either side of `α_c2` and `α = ∞`. Its `--check-stored` matches the held-out checks.
#[test]
fn the_reference_reader_gives_the_bits_of_p_e() {
    use std::io::Write;
    let start = std::time::Instant::now();
    let table_ = Table::open(table()).expect("the table");
    let s = table_.surface();
    let span = s.gamma_max() - s.gamma_min();
    let (g_lo, g_hi) = (s.gamma_min() - 0.1 * span, s.gamma_max() + 0.1 * span);
    let mut r = oblique_physics::sample::SplitMix(0x7468_726e);
    let n = common::size::sized(40_000, 200_000);
    let mut points = Vec::with_capacity(n);
    for i in 0..n {
        let g = if i % 97 == 5 {
            1.0
        } else {
            g_lo + (g_hi - g_lo) * r.uniform()
        };
        let e = match i % 89 {
            0 => 0.8,
            1 => 1.0,
            _ => 0.75 + 0.27 * r.uniform(),
        };
        let c1 = alpha_c1_dissipative(g, e);
        let a = match i % 40 {
            0 => f64::INFINITY,
            1 => 0.0,
            2 => f64::from_bits(alpha_c2(g).to_bits() + 1),
            3 => f64::from_bits(alpha_c2(g).to_bits() - 1),
            4 => c1,
            5 => c1 * (1.0 + 1e-12),
            6 => c1 * (1.0 - 1e-12),
            7 => 1e-6 * c1,
            8..=17 => c1 * r.uniform(),
            _ => 3.0 * r.uniform() * r.uniform(),
        };
        points.push((g, a, e));
    }
    let input: String = points
        .iter()
        .map(|(g, a, e)| format!("{g:?},{a:?},{e:?}\n"))
        .collect();
    let script = "import sys\n\
                  sys.path.insert(0, sys.argv[1])\n\
                  from read_table import Table, DomainError\n\
                  t = Table(sys.argv[2])\n\
                  out = [t.law, repr(t.error_bound)]\n\
                  for line in sys.stdin:\n    \
                      g, a, e = (float(x) for x in line.split(','))\n    \
                      try:\n        \
                          out.append(repr(t.p_at([g, a, e])))\n    \
                      except DomainError as err:\n        \
                          out.append('error ' + err.name)\n\
                  sys.stdout.write('\\n'.join(out) + '\\n')\n";
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(Path::new(ROOT).join("scripts"))
        .arg(table())
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("python3 (with h5py: the test command installs it)");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("python3 output");
    writer.join().expect("writer").expect("write points");
    assert!(out.status.success(), "read_table.py failed");
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), n + 2);
    assert_eq!(lines[0], "thornton");
    let bound: f64 = lines[1].parse().expect("bound");
    assert!(
        (bound - table_.error_bound()).abs() <= 1e-12 * table_.error_bound(),
        "Python bound {bound}, Rust {}",
        table_.error_bound()
    );
    let (mut answered, mut below, mut refused_e_n, mut refused_gamma) = (0, 0, 0, 0);
    for (&(g, a, e), line) in points.iter().zip(&lines[2..]) {
        match table_.p_e(g, a, e) {
            Ok(p) => {
                let py: f64 = line
                    .parse()
                    .unwrap_or_else(|_| panic!("({g:?}, {a:?}, {e:?}): Rust {p:?}, Python {line}"));
                assert_eq!(
                    p.to_bits(),
                    py.to_bits(),
                    "({g:?}, {a:?}, {e:?}): Rust {p:?}, read_table.py {py:?}"
                );
                answered += 1;
                below += usize::from(a <= alpha_c1_dissipative(g, e));
            }
            Err(oblique_lookup::LookupError::Query { name, .. }) => {
                assert_eq!(*line, format!("error {name}"), "({g:?}, {a:?}, {e:?})");
                refused_e_n += usize::from(name == "e_n");
                refused_gamma += usize::from(name == "gamma");
            }
            Err(other) => panic!("({g:?}, {a:?}, {e:?}): {other}"),
        }
    }
    assert!(
        answered > n / 3 && below > n / 10 && refused_e_n > n / 20 && refused_gamma > n / 20,
        "{answered} answered ({below} at alpha <= alpha_c1), refused {refused_e_n} for e_n, \
         {refused_gamma} for gamma"
    );
    common::python_check_stored(Path::new(t()));
    eprintln!(
        "Thornton table: {answered} of {n} points ({below} at α ≤ α_c1) the same bits in Rust \
         and read_table.py, {refused_e_n} refused for e_n and {refused_gamma} for gamma by both \
         ({:.1} s)",
        start.elapsed().as_secs_f64()
    );
}

/// `scripts/read_table.py` on `path` refuses it (status 2), its message naming every one of
/// `want` ([`common::python_refuses`] at one query).
fn python_refuses(path: &Path, want: &[&str]) {
    common::python_refuses(
        path,
        &["--gamma", "1.7", "--alpha", "0.05", "--e-n", "0.9"],
        want,
    );
}

/// A law and a partial-slip coordinate that do not go together are refused, naming both.
#[test]
fn readers_refuse_a_law_with_the_other_laws_coordinate() {
    let dir = common::subdir("thornton-edited");
    let kv_slip = dir.join("kv-slip.h5");
    common::edited_copy(
        Path::new(KV_DEMO),
        &kv_slip,
        "g = f['patches/partial_high']; del g.attrs['coordinate']; \
         g.attrs['coordinate'] = 'slip,1-sqrt(1-sqrt(l))'",
    );
    refused(
        &["inspect", kv_slip.to_str().expect("path")],
        &["coordinate", "slip,1-sqrt(1-sqrt(l))", "kelvin-voigt"],
    );
    python_refuses(
        &kv_slip,
        &["coordinate", "slip,1-sqrt(1-sqrt(l))", "kelvin-voigt"],
    );
    let th_plain = dir.join("thornton-plain.h5");
    common::edited_copy(
        table(),
        &th_plain,
        "g = f['patches/partial_high']; del g.attrs['coordinate']; \
         g.attrs['coordinate'] = '1-sqrt(1-sqrt(l))'",
    );
    refused(
        &["inspect", th_plain.to_str().expect("path")],
        &["coordinate", "'1-sqrt(1-sqrt(l))'", "thornton"],
    );
    python_refuses(
        &th_plain,
        &["coordinate", "'1-sqrt(1-sqrt(l))'", "thornton"],
    );
    // The law changed, the coordinate kept: refused the same way.
    let th_kv = dir.join("thornton-as-kv.h5");
    common::edited_copy(
        table(),
        &th_kv,
        "del f.attrs['law']; f.attrs['law'] = 'kelvin-voigt'",
    );
    refused(
        &["inspect", th_kv.to_str().expect("path")],
        &["slip,1-sqrt(1-sqrt(l))", "kelvin-voigt"],
    );
    python_refuses(&th_kv, &["slip,1-sqrt(1-sqrt(l))", "kelvin-voigt"]);
}

/// The config keys a table of this law needs, each refused by name.
#[test]
fn configs_of_this_law_are_checked_by_key() {
    let text = std::fs::read_to_string(Path::new(ROOT).join("configs/thornton-demo.toml"))
        .expect("config");
    let parse = |t: &str| oblique_sweep::Config::parse(t, "t.toml").map_err(|e| e.to_string());
    let cfg = parse(&text).expect("the shipped config");
    assert_eq!(cfg.law(), Law::Thornton);
    assert_eq!(cfg.partial_map(), PartialMap::Slip);
    let e = parse(&text.replace("gamma_min = 1.6", "gamma_min = 0.9")).expect_err("gamma < 1");
    assert!(
        e.contains("domain.gamma_min") && e.contains("thornton"),
        "{e}"
    );
    let e = parse(&text.replace("blocks_coord = 2", "blocks_coord = 3")).expect_err("odd");
    assert!(
        e.contains("nodes.blocks_coord") && e.contains("even"),
        "{e}"
    );
    // Up to F₋ the key that measures the cells next to it is needed (the shipped config sets
    // it, for the loading band).
    assert!(text.contains("probe_kinks = true\n"), "{text}");
    let wide = text.replace("gamma_max = 1.8", "gamma_max = 2.6");
    assert!(parse(&wide).is_ok());
    let e = parse(&wide.replace("probe_kinks = true\n", "")).expect_err("F-");
    assert!(e.contains("domain.gamma_max") && e.contains("F-"), "{e}");
    let pair = text.replace("gamma_min = 1.6\ngamma_max = 1.8", "gamma = 1.7");
    let e = parse(&pair).expect_err("one pair");
    assert!(e.contains("domain.gamma") && e.contains("thornton"), "{e}");
    let e = parse(&text.replace("\"thornton\"", "\"thornton-mdr\"")).expect_err("no table");
    assert!(
        e.contains("solver.law") && e.contains("thornton-mdr"),
        "{e}"
    );
    // The same keys with the Kelvin–Voigt law are fine.
    let kv = text.replace("\"thornton\"", "\"kelvin-voigt\"");
    assert!(parse(&kv.replace("blocks_coord = 2", "blocks_coord = 3")).is_ok());
    assert!(parse(&kv.replace("gamma_min = 1.6", "gamma_min = 0.9")).is_ok());
}
