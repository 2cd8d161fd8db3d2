//! Tests of `sweep kinks` (the fold curve F+) through the real binary.

mod common;
use common::sweep;

fn alpha_c1(g: f64) -> f64 {
    2.0 * g * g / (7.0 * (2.0 * g * g - 1.0))
}

fn alpha_c2(g: f64) -> f64 {
    2.0 * g * g / 7.0
}

#[test]
fn csv_of_the_fold_curve() {
    let out = sweep(&[
        "kinks",
        "--gamma-max",
        "3.3",
        "--points",
        "5",
        "--steps",
        "1024",
    ]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 7, "{stdout}");
    assert!(
        lines[0].starts_with("# fold curve F+") && lines[0].contains("gamma_b = 2.90"),
        "{stdout}"
    );
    assert_eq!(lines[1], "# gamma,alpha_F,alpha_F/alpha_c2,slope_jump");
    let rows: Vec<Vec<f64>> = lines[2..]
        .iter()
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 4, "{l}");
            v
        })
        .collect();
    assert!((2.89..2.92).contains(&rows[0][0]), "{stdout}");
    assert!((rows[4][0] - 3.3).abs() < 1e-9, "{stdout}");
    for r in &rows {
        let (g, a) = (r[0], r[1]);
        assert!(alpha_c1(g) < a && a < alpha_c2(g), "{r:?}");
        assert!((r[2] - a / alpha_c2(g)).abs() < 1e-5, "{r:?}");
    }
    for w in rows.windows(2) {
        assert!(
            w[1][0] > w[0][0] && w[1][1] < w[0][1],
            "{:?} then {:?}",
            w[0],
            w[1]
        );
    }
    // docs/solver.md: alpha_F = 1.2046 at gamma 3.3, with a slope jump of 0.57.
    assert!((rows[4][1] - 1.2046).abs() < 1e-3, "{stdout}");
    assert!(rows[4][3] > 0.4, "{stdout}");
}

#[test]
fn json_of_the_fold_curve() {
    let out = sweep(&[
        "kinks",
        "--gamma-max",
        "3.2",
        "--points",
        "2",
        "--steps",
        "1024",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let b = v["birth"]["gamma"].as_f64().unwrap();
    assert!((2.89..2.92).contains(&b), "{v}");
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 2);
    assert!(
        (pts[1]["alpha_F"].as_f64().unwrap() - 1.34309).abs() < 5e-5,
        "{v}"
    );
}

#[test]
fn below_the_birth_there_is_no_curve() {
    let out = sweep(&["kinks", "--gamma-max", "2.5", "--steps", "1024"]);
    assert!(out.status.success());
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("no fold curve F+ below"), "{stdout}");
}

#[test]
fn bad_flags_are_refused_by_name() {
    for (args, flag) in [
        (vec!["kinks", "--points", "0"], "--points"),
        (vec!["kinks", "--points", "x"], "--points"),
        (vec!["kinks", "--gamma-max", "-1"], "--gamma-max"),
        (vec!["kinks", "--gamma-max", "nan"], "--gamma-max"),
        (vec!["kinks", "--gamma-max", "9"], "--gamma-max"),
        (vec!["kinks", "--steps", "100"], "--steps"),
    ] {
        let out = sweep(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(flag), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// A tiny --gamma-max is echoed in exponent notation, not as 300 digits.
#[test]
fn tiny_gamma_max_prints_compactly() {
    let out = sweep(&[
        "kinks",
        "--gamma-max",
        "1e-300",
        "--points",
        "2",
        "--steps",
        "256",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("(--gamma-max 1e-300)"), "{text}");
    assert!(text.len() < 200, "{text}");
}
