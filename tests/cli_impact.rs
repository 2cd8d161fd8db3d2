//! Tests of `sweep impact` through the real binary.

use oblique_solver::{Request, Resolution};

mod common;
use common::sweep;

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
    // The continuum row has no spring count: `"springs": null` with `"row": "continuum"`.
    let springs = match map["row"].as_str() {
        Some("continuum") => {
            assert!(map["springs"].is_null(), "{map:?}");
            0
        }
        Some("springs") => count(map, "springs"),
        other => panic!("row {other:?} in {map:?}"),
    };
    let steps = count(map, "steps");
    assert!((springs == 0 || springs >= 2) && steps >= 8, "{map:?}");
    assert!(
        est > 0.0 && est <= 1e-6,
        "default tolerance is 1e-6: {map:?}"
    );
    let reference = Request::new(gamma, alpha)
        .simulate(Resolution {
            springs: 8 * springs,
            steps: 8 * steps,
        })
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
    let cases: [(&[&str], &str); 8] = [
        (&["--gamma", "0", "--alpha", "1"], "--gamma"),
        (&["--gamma", "-1", "--alpha", "1"], "--gamma"),
        (&["--gamma", "nan", "--alpha", "1"], "--gamma"),
        (&["--gamma", "1.754", "--alpha", "-0.1"], "--alpha"),
        (&["--gamma", "1.754", "--alpha", "nan"], "--alpha"),
        (&["--gamma", "1.754", "--alpha", "1", "--tol", "0"], "--tol"),
        (&["--gamma", "1.754", "--alpha", "1", "--tol", "1"], "--tol"),
        (
            &[
                "--gamma",
                "1.754",
                "--alpha",
                "1",
                "--springs",
                "1",
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

/// The true P at (1.7, 1) (automatic refinement to 1e-9: −0.0000657391).
const P_REF_17_1: f64 = -0.000_065_739_08;

/// At a fixed resolution the printed estimate is absent (with its reason) or bounds the error:
/// the reproducers used to print ±1.6e-5, ±2.9e-6, ±0 and ±7.4e-3 for errors of 0.44, 0.034,
/// 0.41 and 0.10.
#[test]
fn fixed_resolution_prints_no_estimate_it_cannot_trust() {
    let cases: [&[&str]; 4] = [
        &["--springs", "2", "--steps", "1024"],
        &["--springs", "1024", "--steps", "8"],
        &["--springs", "2", "--steps", "8"],
        &["--scheme", "euler", "--springs", "8", "--steps", "32"],
    ];
    for extra in cases {
        let mut args = vec!["impact", "--gamma", "1.7", "--alpha", "1"];
        args.extend_from_slice(extra);
        let out = sweep(&args);
        assert!(out.status.success(), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout);
        let first = text.lines().next().unwrap_or_default();
        assert!(
            first.contains("(no error estimate: ") && first.contains("too coarse"),
            "{args:?}: {first}"
        );
        assert!(!first.contains("+/-"), "{args:?}: {first}");
        args.push("--json");
        let map = stdout_json(&args);
        assert!(map["error_estimate"].is_null(), "{args:?}: {map:?}");
        let why = map["no_estimate_reason"].as_str().unwrap_or_default();
        assert!(why.contains("too coarse"), "{args:?}: {map:?}");
    }
    // Fine enough and converging: an estimate that bounds the true error.
    for (extra, scheme) in [
        (["--springs", "1024", "--steps", "1024"], "accurate"),
        (["--springs", "64", "--steps", "256"], "euler"),
    ] {
        let mut args = vec![
            "impact", "--gamma", "1.7", "--alpha", "1", "--scheme", scheme,
        ];
        args.extend_from_slice(&extra);
        args.push("--json");
        let map = stdout_json(&args);
        let est = num(&map, "error_estimate");
        let err = (num(&map, "P") - P_REF_17_1).abs();
        assert!(est >= err, "{args:?}: estimate {est:e} < error {err:e}");
        assert!(!map.contains_key("no_estimate_reason"), "{map:?}");
        assert_eq!(map["row"], "springs");
        assert_eq!(count(&map, "springs"), extra[1].parse::<usize>().unwrap());
    }
    // Not converging steadily (Euler at γ = 3.2: differences of alternating sign): no estimate.
    let map = stdout_json(&[
        "impact",
        "--gamma",
        "3.2",
        "--alpha",
        "1.3",
        "--scheme",
        "euler",
        "--springs",
        "64",
        "--steps",
        "1024",
        "--json",
    ]);
    assert!(map["error_estimate"].is_null(), "{map:?}");
    let why = map["no_estimate_reason"].as_str().unwrap_or_default();
    assert!(why.contains("asymptotic"), "{map:?}");
}

#[test]
fn gamma_outside_the_tested_range_is_refused_naming_it() {
    for g in ["1e308", "5.001", "0.009", "1e-300"] {
        let out = sweep(&["impact", "--gamma", g, "--alpha", "1"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "--gamma {g}: {stderr}");
        assert!(
            stderr.contains("--gamma") && stderr.contains("from 0.01 to 5"),
            "--gamma {g}: {stderr}"
        );
        assert!(out.stdout.is_empty());
    }
    for g in ["0.01", "5"] {
        let map = stdout_json(&[
            "impact", "--gamma", g, "--alpha", "0.5", "--preset", "fast", "--json",
        ]);
        assert!(num(&map, "P").abs() <= 1.0, "{map:?}");
    }
    let out = sweep(&["impact", "--help"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("[0.01, 5]"));
}

/// Huge or tiny numbers are printed in exponent notation, never as hundreds of digits.
#[test]
fn extreme_alpha_prints_compact_numbers() {
    for a in ["1e308", "1e-300"] {
        let out = sweep(&["impact", "--gamma", "0.5", "--alpha", a]);
        assert!(out.status.success(), "--alpha {a}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains(&format!("alpha = {a})")), "{text}");
        let longest = text
            .split(|c: char| !c.is_ascii_digit())
            .map(str::len)
            .max()
            .unwrap_or(0);
        assert!(longest <= 20, "a run of {longest} digits in {text}");
    }
}

/// α_c1 only where it means something (γ ≥ 1); the continuum row is not "0 springs".
#[test]
fn json_reports_only_meaningful_fields() {
    let map = stdout_json(&["impact", "--gamma", "0.5", "--alpha", "1", "--json"]);
    assert!(map["alpha_c1"].is_null(), "{map:?}");
    assert!((num(&map, "alpha_c2") - 0.5 / 7.0).abs() < 1e-15);
    assert!(map["springs"].is_null(), "{map:?}");
    assert_eq!(map["row"], "continuum");
    assert!(count(&map, "steps") >= 8);
    let text =
        String::from_utf8_lossy(&sweep(&["impact", "--gamma", "0.5", "--alpha", "1"]).stdout)
            .to_string();
    assert!(!text.contains("alpha_c1 ="), "{text}");
    assert!(text.contains("alpha_c1 does not apply"), "{text}");
    assert!(text.contains("continuum row x "), "{text}");
    let map = stdout_json(&["impact", "--gamma", "1.754", "--alpha", "1", "--json"]);
    assert!((num(&map, "alpha_c1") - 0.170_580).abs() < 1e-6, "{map:?}");
    // A closed form has no resolution at all.
    let map = stdout_json(&["impact", "--gamma", "1.754", "--alpha", "0.01", "--json"]);
    assert_eq!(map["method"], "closed-form");
    assert!(map["springs"].is_null() && map["steps"].is_null() && map["row"].is_null());
    assert_eq!(num(&map, "error_estimate"), 0.0);
}

/// `--progress` reports every level on stderr (level, resolution, estimate against the
/// tolerance) and leaves stdout's one JSON object intact; without it (and without a terminal)
/// stderr stays empty.
#[test]
fn progress_goes_to_stderr_only() {
    let args = [
        "impact",
        "--gamma",
        "1.754",
        "--alpha",
        "1",
        "--tol",
        "1e-8",
        "--json",
        "--progress",
    ];
    let out = sweep(&args);
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    assert!(lines.len() >= 8, "{stderr}");
    assert!(
        lines[0].starts_with("impact: level 0 running, continuum row x "),
        "{stderr}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains(" done, continuum row x ") && l.contains("(tol 1.0e-8)")),
        "{stderr}"
    );
    let map = stdout_json(&args);
    assert!(num(&map, "error_estimate") <= 1e-8);
    let quiet = sweep(&args[..args.len() - 1]);
    assert!(quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
}

#[test]
fn a_dissipative_impact_names_its_law_e_n_and_relaxation_time() {
    let map = stdout_json(&[
        "impact", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.9", "--json",
    ]);
    assert_eq!(num(&map, "e_n"), 0.9);
    assert_eq!(map["law"], "kelvin-voigt");
    let tau = num(&map, "tau");
    assert!((tau - 0.056135553).abs() < 3e-8, "{tau}");
    // P within its estimate of the library at 8× the resolution.
    let p = num(&map, "P");
    let est = num(&map, "error_estimate");
    let steps = count(&map, "steps");
    let fine = Request::new(1.754, 1.0)
        .e_n(0.9)
        .simulate(Resolution {
            springs: 0,
            steps: 8 * steps,
        })
        .unwrap();
    assert!((p - fine).abs() <= est, "{p} vs {fine} ± {est}");
    // The elastic answer names its law too, with e_n 1 and tau 0.
    let el = stdout_json(&["impact", "--gamma", "1.754", "--alpha", "1", "--json"]);
    assert_eq!(el["law"], "elastic");
    assert_eq!((num(&el, "e_n"), num(&el, "tau")), (1.0, 0.0));
    assert!((num(&el, "P") - p).abs() > 0.05);
    // Full slip: the dissipative line, in closed form, and the regime follows α_c1(e_n).
    let line = stdout_json(&[
        "impact", "--gamma", "1.754", "--alpha", "0.15", "--e-n", "0.9", "--json",
    ]);
    assert_eq!(line["method"], "closed-form");
    assert_eq!(line["regime"], "full-slip");
    assert!((num(&line, "P") - (1.0 - 3.5 * 1.9 * 0.15)).abs() < 1e-15);
}

#[test]
fn a_thornton_impact_names_its_limiting_pressure_and_no_regime() {
    let map = stdout_json(&[
        "impact", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.8", "--law", "thornton", "--json",
    ]);
    assert_eq!(map["law"], "thornton");
    // physics.md: p_y = 0.350980351 gives e_n = 0.8.
    let p_y = num(&map, "yield_pressure");
    assert!((p_y - 0.350980351).abs() < 1e-9, "{p_y}");
    assert_eq!(num(&map, "tau"), 0.0);
    // Its full-slip line is not exact, so no closed-form regime is named.
    assert!(
        map["regime"].is_null() && map["alpha_c1"].is_null(),
        "{map:?}"
    );
    let (p, est, steps) = (
        num(&map, "P"),
        num(&map, "error_estimate"),
        count(&map, "steps"),
    );
    let fine = Request::new(1.754, 1.0)
        .e_n(0.8)
        .law(oblique_solver::Law::Thornton)
        .simulate(Resolution {
            springs: 0,
            steps: 8 * steps,
        })
        .unwrap();
    assert!((p - fine).abs() <= est, "{p} vs {fine} ± {est}");
    // Another law at the same e_n: another P.
    let kv = stdout_json(&[
        "impact", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.8", "--json",
    ]);
    assert!((num(&kv, "P") - p).abs() > 0.1);
    // The variant with the MDR's own unloading keeps the full-slip line, within its estimate.
    let mdr = stdout_json(&[
        "impact",
        "--gamma",
        "1.754",
        "--alpha",
        "0.1",
        "--e-n",
        "0.8",
        "--law",
        "thornton-mdr",
        "--json",
    ]);
    assert_eq!(mdr["law"], "thornton-mdr");
    assert!(mdr["regime"].is_null());
    let line = 1.0 - 3.5 * 1.8 * 0.1;
    assert!(
        (num(&mdr, "P") - line).abs() <= num(&mdr, "error_estimate"),
        "{mdr:?}"
    );
    // Thornton's law takes the accurate scheme and the continuum row only.
    let out = sweep(&[
        "impact", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.8", "--law", "thornton",
        "--scheme", "euler",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("scheme"));
}

#[test]
fn bad_dissipation_input_is_refused_with_exit_2() {
    for (args, needle) in [
        (vec!["--e-n", "0.2"], "e-n"),
        (vec!["--e-n", "1.5"], "e-n"),
        (vec!["--e-n", "nan"], "e-n"),
        (vec!["--e-n", "0.9", "--law", "elastic"], "e_n"),
        (vec!["--law", "plastic"], "law"),
        (vec!["--e-n", "0.9", "--history"], "--history"),
        (vec!["--e-n", "0.9", "--scheme", "euler"], "scheme"),
        (
            vec!["--e-n", "0.9", "--springs", "64", "--steps", "256"],
            "springs",
        ),
    ] {
        let mut all = vec!["impact", "--gamma", "1.754", "--alpha", "1"];
        all.extend(args.iter().copied());
        let out = sweep(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{all:?}: {err}");
        assert!(err.contains(needle), "{all:?}: {err}");
        assert!(out.stdout.is_empty(), "{all:?}");
    }
}
