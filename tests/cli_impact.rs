//! Tests of `sweep impact` through the real binary.

use std::process::{Command, Output};

use oblique::physics::{simulate, Resolution, Scheme};

fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run the sweep binary")
}

fn stdout_json(args: &[&str]) -> serde_json::Map<String, serde_json::Value> {
    let out = sweep(args);
    let stdout = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    let lines: Vec<&str> = stdout.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "expected one JSON line, got {stdout:?}");
    match serde_json::from_str::<serde_json::Value>(lines[0]) {
        Ok(serde_json::Value::Object(map)) => map,
        other => panic!("not a JSON object: {other:?} from {stdout:?}"),
    }
}

fn num(map: &serde_json::Map<String, serde_json::Value>, key: &str) -> f64 {
    map.get(key)
        .and_then(serde_json::Value::as_f64)
        .unwrap_or_else(|| panic!("key {key} missing or not a number in {map:?}"))
}

fn count(map: &serde_json::Map<String, serde_json::Value>, key: &str) -> usize {
    map.get(key)
        .and_then(serde_json::Value::as_u64)
        .unwrap_or_else(|| panic!("key {key} missing or not an integer in {map:?}")) as usize
}

/// Check P against a run at 8x the reported resolution (springs 0: the continuum row, exact in
/// space): within the reported error estimate.
fn check_p(map: &serde_json::Map<String, serde_json::Value>, gamma: f64, alpha: f64) {
    let p = num(map, "P");
    let est = num(map, "error_estimate");
    let (springs, steps) = (count(map, "springs"), count(map, "steps"));
    assert!((springs == 0 || springs >= 2) && steps >= 8, "{map:?}");
    assert!(
        est > 0.0 && est <= 1e-6,
        "default tolerance is 1e-6: {map:?}"
    );
    let reference = simulate(
        gamma,
        alpha,
        Resolution {
            springs: 8 * springs,
            steps: 8 * steps,
        },
        Scheme::Accurate,
    )
    .unwrap();
    assert!(
        (p - reference).abs() <= est,
        "P = {p} +/- {est:e}, reference {reference} (diff {:e})",
        (p - reference).abs()
    );
    assert!((num(map, "e_t") - (2.0 * p + 5.0) / 7.0).abs() < 1e-12);
    assert_eq!(map["scheme"], "accurate");
    assert!(num(map, "elapsed_s") >= 0.0);
}

const KEYS: [&str; 9] = [
    "gamma",
    "alpha",
    "P",
    "e_t",
    "error_estimate",
    "springs",
    "steps",
    "scheme",
    "elapsed_s",
];

#[test]
fn impact_json_reports_p_with_its_error() {
    let map = stdout_json(&["impact", "--gamma", "1.754", "--alpha", "1", "--json"]);
    for key in KEYS {
        assert!(map.contains_key(key), "missing {key} in {map:?}");
    }
    assert_eq!(num(&map, "gamma"), 1.754);
    assert_eq!(num(&map, "alpha"), 1.0);
    check_p(&map, 1.754, 1.0);
}

#[test]
fn impact_json_accepts_alpha_inf() {
    let map = stdout_json(&["impact", "--gamma", "1.754", "--alpha", "inf", "--json"]);
    for key in KEYS {
        assert!(map.contains_key(key), "missing {key} in {map:?}");
    }
    // JSON has no infinity: the CLI documents the string "inf".
    assert_eq!(map["alpha"], "inf");
    check_p(&map, 1.754, f64::INFINITY);
}

#[test]
fn invalid_values_fail_with_a_message_naming_the_flag() {
    let cases: [(&[&str], &str); 7] = [
        (&["--gamma", "0", "--alpha", "1"], "--gamma"),
        (&["--gamma", "-1", "--alpha", "1"], "--gamma"),
        (&["--gamma", "nan", "--alpha", "1"], "--gamma"),
        (&["--gamma", "1.754", "--alpha", "-0.1"], "--alpha"),
        (&["--gamma", "1.754", "--alpha", "nan"], "--alpha"),
        (&["--gamma", "1.754", "--alpha", "1", "--tol", "0"], "--tol"),
        (
            &[
                "--gamma",
                "1.754",
                "--alpha",
                "1",
                "--springs",
                "0",
                "--steps",
                "10",
            ],
            "--springs",
        ),
    ];
    for (args, flag) in cases {
        let mut all = vec!["impact"];
        all.extend_from_slice(args);
        all.push("--json");
        let out = sweep(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{all:?} should fail");
        assert!(out.status.code().is_some(), "{all:?}: killed by a signal");
        assert!(
            stderr.contains(flag),
            "{all:?}: stderr does not name {flag}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{all:?} panicked: {stderr}");
        assert!(out.stdout.is_empty(), "{all:?} printed a result");
    }
}

/// The gross-slip episodes of `--history`, as (sign, start, end).
fn episodes(args: &[&str]) -> Vec<(String, f64, f64)> {
    let map = stdout_json(args);
    let list = map
        .get("gross_slip")
        .and_then(serde_json::Value::as_array)
        .unwrap_or_else(|| panic!("gross_slip missing or not a list in {map:?}"));
    list.iter()
        .map(|e| {
            let sign = e["sign"].as_str().expect("sign").to_string();
            (
                sign,
                e["start"].as_f64().expect("start"),
                e["end"].as_f64().expect("end"),
            )
        })
        .collect()
}

#[test]
fn history_lists_the_gross_slip_episodes() {
    // Full slip (α below α_c1 = 0.1706 at γ = 1.754): one + episode over the whole contact.
    let full = episodes(&[
        "impact",
        "--gamma",
        "1.754",
        "--alpha",
        "0.05",
        "--history",
        "--json",
    ]);
    assert_eq!(full.len(), 1, "{full:?}");
    assert_eq!(full[0].0, "+");
    assert!(full[0].1 < 0.01 && full[0].2 > 0.99, "{full:?}");
    // Just below the fold F+ at γ = 3.2 (α ≈ 1.3431, docs/solver.md) a + episode sits inside the
    // restitution phase; just above it, it is gone.
    let inside = |e: &(String, f64, f64)| e.0 == "+" && e.1 > 0.6 && e.2 < 0.97;
    let below = episodes(&[
        "impact",
        "--gamma",
        "3.2",
        "--alpha",
        "1.30",
        "--history",
        "--json",
    ]);
    let above = episodes(&[
        "impact",
        "--gamma",
        "3.2",
        "--alpha",
        "1.40",
        "--history",
        "--json",
    ]);
    assert!(below.iter().any(inside), "{below:?}");
    assert!(!above.iter().any(inside), "{above:?}");
    // No slip: there is nothing to list, and the summary says why.
    let out = sweep(&["impact", "--gamma", "3.2", "--alpha", "inf", "--history"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("gross slip: no slip"), "{text}");
}
