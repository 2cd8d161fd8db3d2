//! The error bound a table states holds, and `sweep verify` checks it: the point of
//! `tables/full.h5` that was off by 1.32e-5 while the table stated 8.5e-6 (`inspect`) or
//! 2.5e-5 (`query`), a sample of random points, and bad arguments.

mod common;

use std::process::{Command, Output};

const FULL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/full.h5");

fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run the sweep binary")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = sweep(args);
    assert!(
        out.status.success(),
        "sweep {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// The shipped table states one bound (`inspect` and `query` agree), at most 1e-5, and it
/// holds where the table was worst (against a simulation at tol 1e-9).
#[test]
fn full_table_holds_its_stated_bound_where_it_was_worst() {
    let (g, a) = ("2.816329", "5.97606");
    let inspect = json(&["inspect", FULL, "--json"]);
    let bound = inspect["error_bound"]
        .as_f64()
        .expect("inspect --json: error_bound");
    assert!(bound <= 1e-5, "stated bound {bound} > 1e-5");
    let query = json(&["query", FULL, "--gamma", g, "--alpha", a, "--json"]);
    assert_eq!(query["error_bound"].as_f64(), Some(bound), "query's +/-");
    let sim = json(&[
        "impact", "--gamma", g, "--alpha", a, "--tol", "1e-9", "--json",
    ]);
    let p_table = query["P"].as_f64().expect("P");
    let p_sim = sim["P"].as_f64().expect("P");
    let err = (p_table - p_sim).abs();
    assert!(
        err <= bound,
        "table {p_table}, simulation {p_sim}: off by {err:e} > stated {bound:e}"
    );
    // The text of inspect states the same number.
    let text = String::from_utf8(sweep(&["inspect", FULL]).stdout).expect("UTF-8");
    assert!(
        text.contains(&format!("stated error bound: {bound:.2e}")),
        "{text}"
    );
}

#[test]
fn verify_a_sample_of_the_full_table() {
    let out = sweep(&["verify", FULL, "--points", "60", "--seed", "7", "--quiet"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for needle in [
        "points       60 (seed 7)",
        "max |error|",
        "worst point",
        "points above it: 0",
    ] {
        assert!(text.contains(needle), "no '{needle}' in {text}");
    }
}

#[test]
fn verify_refuses_bad_arguments() {
    for (args, needle) in [
        (vec!["--tol", "1e-7"], "--tol 1e-7: must be in (0, 1e-8]"),
        (vec!["--tol", "0"], "--tol 0e0: must be in (0, 1e-8]"),
        (vec!["--points", "0"], "--points 0: must be >= 1"),
    ] {
        let mut all = vec!["verify", FULL];
        all.extend(args);
        let out = sweep(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{all:?}: {err}");
        assert!(err.contains(needle), "{all:?}: {err}");
    }
    // E₋ is traced over a range of γ (a curve, or a surface with an e_n axis), not for one pair.
    let pair = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-pair.h5");
    for (table, needle) in [(pair, "one pair"), (FULL, "cannot be used with")] {
        let mut all = vec!["verify", table, "--near-end"];
        if table == FULL {
            all.push("--near-fold");
        }
        let out = sweep(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{all:?}: {err}");
        assert!(
            err.contains(needle) && err.contains("--near-"),
            "{all:?}: {err}"
        );
    }
    // --near-one needs an e_n range that reaches 1, and draws its points there.
    let out = sweep(&["verify", FULL, "--near-one"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--near-one") && err.contains("no e_n axis"),
        "{err}"
    );
    let demo = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-demo.h5");
    let out = sweep(&[
        "verify",
        demo,
        "--near-one",
        "--points",
        "40",
        "--seed",
        "2",
    ]);
    let (text, err) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{err}");
    assert!(err.contains("1 - e_n log-uniform in [1e-6, 5e-2]"), "{err}");
    let worst_e: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("worst point"))
        .and_then(|l| l.split("e_n = ").nth(1))
        .and_then(|l| l.split(':').next())
        .and_then(|v| v.trim().parse().ok())
        .expect("the worst point's e_n");
    assert!((1.0 - 0.05..1.0).contains(&worst_e), "{text}");
    let out = sweep(&["verify", "/nonexistent/table.h5"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/table.h5"));
}

/// `--near-end` on a Kelvin–Voigt table: (γ, α, e_n) next to the end-of-contact surface
/// `α_E(γ, e_n)` (traced first), none above the stated bound; the worst point lies within 10 %
/// of E₋, which runs through α ≈ 1–10 over γ 1.74–1.9.
#[test]
fn near_end_draws_points_next_to_the_end_of_contact_surface_of_an_e_n_table() {
    let table = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-demo.h5");
    let out = sweep(&[
        "verify",
        table,
        "--points",
        "30",
        "--seed",
        "5",
        "--near-end",
        "--quiet",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("end-of-contact"), "{err}");
    assert!(text.contains("points above it: 0"), "{text}");
    let worst = text
        .lines()
        .find(|l| l.starts_with("worst point"))
        .expect("a worst point");
    let field = |name: &str| -> f64 {
        let rest = worst.split(&format!("{name} = ")).nth(1).expect(name);
        rest.split([',', ':'])
            .next()
            .unwrap_or("")
            .trim()
            .parse()
            .expect(name)
    };
    let (g, a) = (field("gamma"), field("alpha"));
    assert!((1.72..=2.0).contains(&g), "{worst}");
    assert!((0.5..=70.0).contains(&a), "{worst}");
}

/// `--near-curves` draws α next to `α_c1(γ, e_n)` and `α_c2(γ)` (within 10 % of one of them)
/// and the table holds its bound there too: the worst point it reports lies next to a curve.
#[test]
fn near_curves_draws_alpha_next_to_the_critical_curves() {
    let table = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-demo.h5");
    let out = sweep(&[
        "verify",
        table,
        "--points",
        "40",
        "--seed",
        "3",
        "--near-curves",
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}{stderr}");
    assert!(
        stderr.contains("of alpha_c1(gamma, e_n) and alpha_c2(gamma)"),
        "{stderr}"
    );
    let worst = stdout
        .lines()
        .find(|l| l.starts_with("worst point"))
        .expect("worst point line");
    let field = |name: &str| -> f64 {
        let at = worst.find(&format!("{name} = ")).expect(name) + name.len() + 3;
        worst[at..]
            .split([',', ':'])
            .next()
            .and_then(|v| v.trim().parse().ok())
            .expect("a number")
    };
    let (g, a, e) = (field("gamma"), field("alpha"), field("e_n"));
    let c1 = oblique_physics::regimes::alpha_c1_dissipative(g, e);
    let c2 = oblique_physics::regimes::alpha_c2(g);
    let near = |c: f64| (a / c - 1.0).abs() <= 0.1 + 1e-12;
    assert!(
        near(c1) || near(c2),
        "{worst}: alpha_c1 {c1}, alpha_c2 {c2}"
    );
}

/// `--near-fold` draws (γ, α) next to the fold curve F₋ of an elastic table whose γ range spans
/// 0.03 or more above 2.40, and `tables/full.h5` holds its bound there; a table without F₋ is
/// refused (exit 2), elastic or Kelvin–Voigt.
#[test]
fn near_fold_draws_points_next_to_fold_minus() {
    let out = sweep(&[
        "verify",
        FULL,
        "--points",
        "24",
        "--seed",
        "4",
        "--near-fold",
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}{stderr}");
    assert!(
        stderr.contains("gamma uniform in [2.4, 3.5], alpha within 1e-4 to 1e-2 (relative) of the fold curve F-"),
        "{stderr}"
    );
    assert!(stdout.contains("points above it: 0"), "{stdout}");
    for (table, needle) in [
        ("tables/default.h5", "where F- has no traced point"),
        ("tables/isotropic.h5", "gamma in [1.52, 2.16]"),
    ] {
        let path = format!("{}/{table}", env!("CARGO_MANIFEST_DIR"));
        let out = sweep(&["verify", &path, "--points", "3", "--near-fold"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{table}: {err}");
        assert!(
            err.contains("--near-fold") && err.contains(needle),
            "{table}: {err}"
        );
    }
    let out = sweep(&["verify", FULL, "--near-fold", "--near-curves"]);
    assert_eq!(out.status.code(), Some(2));
}

/// `--near-fold` on a Kelvin–Voigt table that reaches F₋ (one pair at γ = 2.6, e_n 0.95–1,
/// built with its leaves measured next to F₋): (α, e_n) next to the fold surface `α_F(γ, e_n)`,
/// none above the stated bound.
#[test]
fn near_fold_draws_points_next_to_the_fold_surface_of_an_e_n_table() {
    let table = common::build_table(
        "near-fold-e",
        "pair",
        "[domain]\ngamma = 2.6\ne_n_min = 0.95\ne_n_max = 1.0\n[nodes]\ntarget_error = 4e-5\n\
         leaf_intervals = 6\nprobe_kinks = true\n[solver]\ntol = 4e-6\n[checks]\nper_patch = 5\n",
    );
    let path = table.to_str().expect("path");
    let out = sweep(&[
        "verify",
        path,
        "--points",
        "20",
        "--seed",
        "4",
        "--near-fold",
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}{stderr}");
    assert!(
        stderr.contains(
            "gamma = 2.6, the table's one pair, alpha within 1e-4 to 1e-2 (relative) of the \
             fold surface F-, e_n uniform in [0.95, 1] where F- exists, law kelvin-voigt"
        ),
        "{stderr}"
    );
    assert!(
        stdout.contains("20 (seed 4)") && stdout.contains("points above it: 0"),
        "{stdout}"
    );
}
