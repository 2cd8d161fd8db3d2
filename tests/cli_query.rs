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
    let hi = t.surface().gamma_max();
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
    let hi = table().surface().gamma_max();
    for (input, needles) in [
        ("1.5,0.3\n2.0\n", vec!["line 2", "1 field"]),
        (
            "1.5,0.3\n1.5,0.3\n1.5,abc\n",
            vec!["line 3", "alpha", "abc"],
        ),
        ("1.5,0.3,7,1\n", vec!["line 1", "4 field"]),
        ("1.5,0.3,0.7\n", vec!["line 1", "e_n = 0.7", "elastic"]),
        (
            "1.5,0.3,1\n1.5,0.3\n",
            vec!["line 2", "2 field", "gamma,alpha,e_n"],
        ),
        ("1.5,0.3\n \t\n1.5\n", vec!["line 3"]),
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

#[test]
fn a_failing_batch_writes_nothing_whatever_its_size() {
    // More lines than any internal chunk: a bad last line (or a point outside the domain in the
    // middle) must still leave standard output empty.
    let good = "1.5,0.3\n".repeat(100_000);
    let hi = table().surface().gamma_max();
    for (input, needles) in [
        (format!("{good}1.5,oops\n"), vec!["line 100001".to_string()]),
        (
            format!("{good}{},1\n{good}", hi + 1.0),
            vec!["line 100001".to_string(), "gamma".to_string()],
        ),
        (
            "1.5,0.3\n1.5,0.3\n1.5,\n".to_string(),
            vec!["line 3".to_string()],
        ),
    ] {
        let out = sweep(&["query", TABLE, "--batch", "-"], Some(&input));
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        refused(&out, &needles);
    }
}

#[test]
fn batch_passes_blank_and_comment_lines_and_ignores_a_bom() {
    let t = table();
    let input = "\u{feff}# points of run 7\ngamma,alpha\n1.5,0.3\n\n  # a comment\n2,inf\r\n";
    let out = sweep(&["query", TABLE, "--batch", "-"], Some(input));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let lines: Vec<&str> = text.lines().collect();
    let answer = |g: f64, a: f64| {
        let p = t.p(g, a).expect("inside");
        format!("{g},{a},{p},{}", (2.0 * p + 5.0) / 7.0)
    };
    assert_eq!(
        lines,
        vec![
            "# points of run 7".to_string(),
            "gamma,alpha,P,e_t".to_string(),
            answer(1.5, 0.3),
            String::new(),
            "  # a comment".to_string(),
            answer(2.0, f64::INFINITY),
        ]
    );
}

#[test]
fn a_query_without_a_point_names_both_ways_to_ask() {
    let out = sweep(&["query", TABLE], None);
    refused(&out, &["--gamma", "--alpha", "--batch"]);
}

#[test]
fn things_that_are_not_tables_are_named() {
    let dir = std::env::temp_dir().join(format!("oblique-notables-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let part = dir.join("part1.bin");
    let mut bytes = b"OBLQNODE".to_vec();
    bytes.extend_from_slice(&[0u8; 64]);
    std::fs::write(&part, bytes).expect("write a node-file header");
    let empty = dir.join("empty.h5");
    std::fs::write(&empty, b"").expect("write an empty file");
    let dir_s = dir.display().to_string();
    let part_s = part.display().to_string();
    let empty_s = empty.display().to_string();
    for (path, needle) in [
        (dir_s.as_str(), "a directory"),
        ("/dev/null", "a character device"),
        (part_s.as_str(), "shard part"),
        (empty_s.as_str(), "empty file"),
        ("/nonexistent/t.h5", "no such file"),
    ] {
        for cmd in [
            vec!["query", path, "--gamma", "1.5", "--alpha", "1"],
            vec!["inspect", path],
        ] {
            let out = sweep(&cmd, None);
            refused(&out, &[path, needle]);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn extreme_numbers_are_printed_compactly() {
    // 1e308 in a message, 1e-320 echoed on an output line: never hundreds of digits.
    let out = sweep(&["query", TABLE, "--gamma", "1e308", "--alpha", "1"], None);
    refused(&out, &["gamma = 1e308"]);
    let out = sweep(&["query", TABLE, "--batch", "-"], Some("1e308,1\n"));
    refused(&out, &["line 1", "1e308"]);
    let out = sweep(&["query", TABLE, "--batch", "-"], Some("2,1e-320\n"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(text.starts_with("2,1e-320,"), "{text}");
    assert!(text.len() < 80, "{text}");
    let out = sweep(
        &[
            "query", TABLE, "--gamma", "1e-300", "--alpha", "1", "--clamp",
        ],
        None,
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("gamma = 1e-300"), "{text}");
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

/// Without a table, `sweep query` answers from the table built into the binary
/// (tables/default.h5), in any directory, at e_n = 1 and below; `--help` names it; outside its
/// domain the message points to tables/full.h5.
#[test]
fn without_a_table_the_built_in_one_answers() {
    let shipped =
        Table::open(concat!(env!("CARGO_MANIFEST_DIR"), "/tables/default.h5")).expect("default.h5");
    // `sweep query ARGS --json` run in a folder without tables: its JSON answer.
    let answer = |args: &[&str]| -> serde_json::Value {
        let out = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("query")
            .args(args)
            .arg("--json")
            .current_dir(std::env::temp_dir())
            .output()
            .expect("run");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).expect("json")
    };
    let v = answer(&["--gamma", "1.754", "--alpha", "1"]);
    let want = shipped.p(1.754, 1.0).unwrap();
    assert_eq!(v["P"].as_f64().unwrap().to_bits(), want.to_bits());
    assert_eq!(v["table"], "built-in tables/default.h5");
    // A dissipative impact, with no table file.
    let v = answer(&["--gamma", "1.754", "--alpha", "1", "--e-n", "0.8"]);
    let want = shipped.p_e(1.754, 1.0, 0.8).unwrap();
    assert_eq!(v["P"].as_f64().unwrap().to_bits(), want.to_bits());
    assert_ne!(want, shipped.p(1.754, 1.0).unwrap());
    let out = sweep(&["query", "--batch", "-"], Some("1.75,0.3\n2,inf\n"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let p: f64 = text
        .lines()
        .next()
        .unwrap()
        .split(',')
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(p.to_bits(), shipped.p(1.75, 0.3).unwrap().to_bits());
    refused(
        &sweep(&["query", "--gamma", "3", "--alpha", "1"], None),
        &["built-in table is tables/default.h5", "tables/full.h5"],
    );
    refused(
        &sweep(
            &["query", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.2"],
            None,
        ),
        &["--e-n", "0.2"],
    );
    // Outside its gamma range below e_n = 1: where a table for that gamma comes from.
    refused(
        &sweep(
            &["query", "--gamma", "2.5", "--alpha", "1", "--e-n", "0.8"],
            None,
        ),
        &[
            "built-in table is tables/default.h5",
            "configs/dissipative.toml",
        ],
    );
    let help = sweep(&["query", "--help"], None);
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("[TABLE]"), "{help}");
    assert!(
        help.contains("Default: the table built into sweep, tables/default.h5"),
        "{help}"
    );
}

/// `sweep query ARGS` with `input` on standard input written from a thread (sweep may stop
/// reading early and close the pipe: a failed write is ignored), killed after `limit`, and
/// with 4 GiB of address space at most (a reader without a line limit fails there instead of
/// taking the machine's memory).
fn sweep_fed(args: &[&str], input: Vec<u8>, limit: std::time::Duration) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_sweep"));
    cmd.args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: between fork and exec only setrlimit, async-signal-safe, on a local value.
        unsafe {
            cmd.pre_exec(|| {
                let memory = libc::rlimit {
                    rlim_cur: 4 << 30,
                    rlim_max: 4 << 30,
                };
                if libc::setrlimit(libc::RLIMIT_AS, &memory) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
    let mut child = cmd.spawn().expect("run the sweep binary");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(&input);
    });
    // Both outputs are read as they come, so that a long message cannot fill a pipe and stop
    // the command.
    let drain = |mut r: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("stdout")));
    let stderr = drain(Box::new(child.stderr.take().expect("stderr")));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("sweep {args:?} still running after {limit:?}");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    writer.join().expect("writer");
    Output {
        status,
        stdout: stdout.join().expect("stdout reader"),
        stderr: stderr.join().expect("stderr reader"),
    }
}

/// A batch without line ends (`/dev/zero`) is refused after its first 4096 bytes, with the
/// limit in the message, instead of being read into memory without bound.
#[cfg(unix)]
#[test]
fn a_batch_line_longer_than_the_limit_is_refused_without_reading_it() {
    let out = sweep_fed(
        &["query", TABLE, "--batch", "/dev/zero"],
        Vec::new(),
        std::time::Duration::from_secs(20),
    );
    refused(&out, &["batch line 1", "4096 bytes"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.len() < 400, "{} bytes: {stderr}", stderr.len());
    // At the limit a line is read (spaces around a field are allowed); one byte more is not.
    let line = |len: usize| format!("1.5,0.3{}\n", " ".repeat(len - "1.5,0.3".len()));
    let out = sweep(&["query", TABLE, "--batch", "-"], Some(&line(4096)));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = sweep_fed(
        &["query", TABLE, "--batch", "-"],
        format!("1.5,0.3\n{}", line(4097)).into_bytes(),
        std::time::Duration::from_secs(20),
    );
    refused(&out, &["batch line 2", "4096 bytes"]);
}

/// A bad line is quoted in part: a message of a few hundred bytes, whatever the line's length.
#[test]
fn a_long_bad_line_gives_a_short_message() {
    let long = "7".repeat(4000);
    for (input, needles) in [
        // A megabyte on one line.
        (
            format!("1.5,0.3\n1.5,{}\n", "x".repeat(1 << 20)),
            vec!["batch line 2", "4096 bytes"],
        ),
        // Under the limit: a long field, too many fields, a long comment-free line.
        (
            format!("1.5,x{long}\n"),
            vec!["batch line 1", "alpha", "4001 bytes"],
        ),
        (
            format!("1.5,0.3,1,{long}\n"),
            vec!["batch line 1", "4 field"],
        ),
        (
            format!("{}\n", ",".repeat(4000)),
            vec!["batch line 1", "4001 field"],
        ),
    ] {
        let out = sweep_fed(
            &["query", TABLE, "--batch", "-"],
            input.into_bytes(),
            std::time::Duration::from_secs(20),
        );
        refused(&out, &needles);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.len() < 400, "{} bytes: {stderr}", stderr.len());
    }
}

/// `--at NAME=VALUE` takes an axis beyond gamma and alpha by its name: `--at e_n=0.8` prints
/// what `--e-n 0.8` prints; an unknown axis, a repeated one, a value the table does not answer
/// and a malformed argument exit with status 2 and name the axes or the range.
#[test]
fn at_takes_an_extra_axis_by_name() {
    for json in [false, true] {
        let mut at = vec![
            "query", "--gamma", "1.5", "--alpha", "0.3", "--at", "e_n=0.8",
        ];
        let mut e_n = vec!["query", "--gamma", "1.5", "--alpha", "0.3", "--e-n", "0.8"];
        if json {
            at.push("--json");
            e_n.push("--json");
        }
        let (x, y) = (sweep(&at, None), sweep(&e_n, None));
        assert!(x.status.success(), "{}", String::from_utf8_lossy(&x.stderr));
        assert_eq!(x.stdout, y.stdout);
    }
    let q = ["query", "--gamma", "1.5", "--alpha", "0.3"];
    let with = |extra: &[&str]| sweep(&[&q[..], extra].concat(), None);
    let out = with(&["--at", "e_t=0.8"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("unknown axis `e_t`") && stderr.contains("e_n"),
        "{stderr}"
    );
    let out = with(&["--at", "0.8"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("AXIS=VALUE"));
    refused(
        &with(&["--at", "e_n=0.8", "--e-n", "0.8"]),
        &["--at", "'e_n'"],
    );
    refused(&with(&["--at", "e_n=nan"]), &["--at", "e_n", "[0.3, 1]"]);
    refused(
        &sweep(&[&q[..], &[TABLE, "--at", "e_n=0.8"]].concat(), None),
        &["--at", "e_n", "elastic"],
    );
}
