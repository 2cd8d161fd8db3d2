//! `sweep query` through the real binary: single queries (text and JSON), batches from a file
//! and stdin, clamping, and bad input (exit 2 with the field or the line number, never a panic).

use std::io::Write;
use std::process::{Command, Output, Stdio};

use oblique_lookup::{OutOfDomain, Table};

const TABLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/quick.h5");

fn sweep(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the sweep binary");
    let mut input = child.stdin.take().expect("stdin");
    input
        .write_all(stdin.unwrap_or("").as_bytes())
        .expect("write stdin");
    drop(input);
    child.wait_with_output().expect("wait for sweep")
}

fn table() -> Table {
    Table::open(TABLE).expect("quick.h5")
}

fn refused(out: &Output, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "exit status; stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "stderr lacks {n:?}: {stderr}");
    }
    assert!(out.stdout.is_empty(), "no partial output expected here");
}

#[test]
fn single_query_json_matches_the_library() {
    let t = table();
    for (g, a, a_arg) in [
        (1.754, 1.0, "1"),
        (2.0, f64::INFINITY, "inf"),
        (0.7, 0.02, "0.02"),
    ] {
        let out = sweep(
            &[
                "query",
                TABLE,
                "--gamma",
                &g.to_string(),
                "--alpha",
                a_arg,
                "--json",
            ],
            None,
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
        let p = v["P"].as_f64().expect("P");
        assert_eq!(p, t.p(g, a).unwrap());
        assert_eq!(v["e_t"].as_f64().unwrap(), (2.0 * p + 5.0) / 7.0);
        assert!(v["error_bound"].as_f64().unwrap() >= 0.0);
    }
    let out = sweep(&["query", TABLE, "--gamma", "1.754", "--alpha", "1"], None);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("P(gamma = 1.754, alpha = 1) ="),
        "{text}"
    );
}

#[test]
fn batch_keeps_order_and_matches_the_library() {
    let t = table();
    let points = [
        (1.75, 0.3),
        (2.0, f64::INFINITY),
        (0.6, 0.01),
        (1.1, 5.0),
        (2.4, 0.2),
    ];
    let text: String = points
        .iter()
        .map(|(g, a)| format!("{g}, {a}\n"))
        .collect::<String>();
    let file = std::env::temp_dir().join(format!("sweep-query-{}.csv", std::process::id()));
    std::fs::write(&file, format!("gamma,alpha\n{text}")).unwrap();
    for (source, stdin) in [(file.to_str().unwrap(), None), ("-", Some(text.as_str()))] {
        let out = sweep(&["query", TABLE, "--batch", source], stdin);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stdout = String::from_utf8(out.stdout).unwrap();
        let mut lines: Vec<&str> = stdout.lines().collect();
        if source != "-" {
            assert_eq!(lines.remove(0), "gamma,alpha,P,e_t");
        }
        assert_eq!(lines.len(), points.len(), "{stdout}");
        for (line, (g, a)) in lines.iter().zip(points) {
            let f: Vec<f64> = line
                .split(',')
                .map(|x| x.parse::<f64>().expect("number"))
                .collect();
            assert_eq!(f.len(), 4, "{line}");
            assert_eq!((f[0], f[1]), (g, a), "order");
            let p = t.p(g, a).unwrap();
            assert_eq!(f[2], p, "{line}");
            assert_eq!(f[3], (2.0 * p + 5.0) / 7.0);
        }
    }
    std::fs::remove_file(&file).ok();
}

#[test]
fn outside_the_domain_is_refused_unless_clamped() {
    let t = table();
    let hi = t.surface.gamma_max;
    let g = (hi + 1.0).to_string();
    let out = sweep(&["query", TABLE, "--gamma", &g, "--alpha", "1"], None);
    refused(&out, &["gamma", &hi.to_string(), "--clamp"]);
    let out = sweep(
        &[
            "query", TABLE, "--gamma", &g, "--alpha", "1", "--json", "--clamp",
        ],
        None,
    );
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        v["P"].as_f64().unwrap(),
        t.p_with(hi + 1.0, 1.0, OutOfDomain::Clamp).unwrap()
    );
    assert_eq!(v["P"].as_f64().unwrap(), t.p(hi, 1.0).unwrap());
}

#[test]
fn bad_batch_lines_name_their_line_number() {
    let hi = table().surface.gamma_max;
    for (input, needles) in [
        ("1.5,0.3\n2.0\n", vec!["line 2", "1 field"]),
        (
            "1.5,0.3\n1.5,0.3\n1.5,abc\n",
            vec!["line 3", "alpha", "abc"],
        ),
        ("1.5,0.3,7\n", vec!["line 1", "3 field"]),
        ("1.5,0.3\n\n1.5,0.3\n", vec!["line 2"]),
        ("1.5,-0.5\n", vec!["line 1", "alpha"]),
        ("nan,0.5\n", vec!["line 1", "gamma"]),
    ] {
        let out = sweep(&["query", TABLE, "--batch", "-"], Some(input));
        refused(&out, &needles);
    }
    let input = format!("1.5,0.3\n{},1\n", hi + 1.0);
    let out = sweep(&["query", TABLE, "--batch", "-"], Some(&input));
    refused(&out, &["line 2", "gamma"]);
}

#[test]
fn bad_arguments_and_files_fail_cleanly() {
    let out = sweep(&["query", TABLE, "--gamma", "-1", "--alpha", "1"], None);
    refused(&out, &["gamma"]);
    let out = sweep(&["query", TABLE, "--gamma", "1.5"], None);
    refused(&out, &["--alpha"]);
    let out = sweep(
        &["query", TABLE, "--batch", "/nonexistent/points.csv"],
        None,
    );
    refused(&out, &["/nonexistent/points.csv"]);
    let out = sweep(
        &["query", "/nonexistent/t.h5", "--gamma", "1", "--alpha", "1"],
        None,
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(stderr.contains("/nonexistent/t.h5"), "{stderr}");
}

/// `|P| ≤ 1` from the CLI (step 10 of the rule): the point where `tables/full.h5` answered
/// P = −1.000008644, alone and first in a batch of 1e6 random lines (γ ∈ [0.1, 3.5],
/// α ∈ [0, 20]).
#[test]
fn query_answers_no_p_beyond_one() {
    let full = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/full.h5");
    let (g0, a0) = ("2.829218718427729", "5.60402202817959");
    let out = sweep(
        &["query", full, "--gamma", g0, "--alpha", a0, "--json"],
        None,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let p = v["P"].as_f64().expect("P");
    assert!(p.abs() <= 1.0, "P = {p}");
    let mut next = oblique_lookup::testing::uniform(0xC11_0001);
    let mut input = format!("{g0},{a0}\n");
    for _ in 0..1_000_000 {
        let (g, a) = (0.1 + 3.4 * next(), 20.0 * next());
        input.push_str(&format!("{g:?},{a:?}\n"));
    }
    // Large input: written from a thread while the output is read (the pipes would fill).
    let mut child = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(["query", full, "--batch", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the sweep binary");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("wait for sweep");
    writer.join().expect("writer").expect("write the batch");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("UTF-8");
    let mut lines = 0;
    for line in text.lines() {
        let p: f64 = line
            .split(',')
            .nth(2)
            .expect("P column")
            .parse()
            .expect("P");
        assert!(p.abs() <= 1.0, "|P| > 1: {line}");
        lines += 1;
    }
    assert_eq!(lines, 1_000_001);
}
