//! Long runs that survive interruption and scale out: `sweep run --resume` after
//! SIGKILL and Ctrl-C, `sweep run --shard K/N` + `sweep merge`, and the refusals of bad
//! checkpoints and parts. Every comparison is of the table's datasets, value for value (bit
//! patterns), against an uninterrupted single run.

use std::collections::BTreeMap;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

mod common;
use common::sweep;
use common::{scratch, subdir};

const CONFIG: &str = r#"# tests/resume_shard.rs
output = "unused.h5"

[domain]
gamma_min = 0.8
gamma_max = 1.6
alpha_max = "inf"

[nodes]
target_error = 1e-5
leaf_intervals = 8
blocks_per_unit_gamma = 2.0
blocks_coord = 3

[solver]
tol = 2e-6

[checks]
per_patch = 6
seed = 3
"#;

fn config(name: &str, text: &str) -> PathBuf {
    let p = scratch().join(name);
    std::fs::write(&p, text).expect("write config");
    p
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn spawn(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start sweep")
}

fn ok(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what} failed ({:?}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every dataset of a table (path → raw values as bit patterns).
fn datasets(path: &Path) -> BTreeMap<String, Vec<u64>> {
    fn walk(g: &hdf5::Group, prefix: &str, out: &mut BTreeMap<String, Vec<u64>>) {
        for name in g.member_names().expect("member names") {
            let full = format!("{prefix}/{name}");
            if let Ok(ds) = g.dataset(&name) {
                let v: Vec<u64> = match ds.read_raw::<f64>() {
                    Ok(v) => v.iter().map(|x| x.to_bits()).collect(),
                    Err(_) => ds
                        .read_raw::<i64>()
                        .expect("dataset of float64 or integers")
                        .iter()
                        .map(|&x| x as u64)
                        .collect(),
                };
                out.insert(full, v);
            } else if let Ok(sub) = g.group(&name) {
                walk(&sub, &full, out);
            }
        }
    }
    let f = hdf5::File::open(path).expect("open table");
    let mut out = BTreeMap::new();
    walk(&f, "", &mut out);
    assert!(out.len() > 10, "too few datasets in {}", path.display());
    out
}

/// The uninterrupted single run everything is compared with.
fn reference() -> &'static BTreeMap<String, Vec<u64>> {
    static R: OnceLock<BTreeMap<String, Vec<u64>>> = OnceLock::new();
    R.get_or_init(|| {
        let cfg = config("reference.toml", CONFIG);
        let out = subdir("reference").join("t.h5");
        ok(
            &sweep(&["run", s(&cfg), "-o", s(&out), "--quiet"]),
            "reference run",
        );
        datasets(&out)
    })
}

fn assert_same_as_reference(table: &Path, what: &str) {
    let got = datasets(table);
    let want = reference();
    assert_eq!(
        got.keys().collect::<Vec<_>>(),
        want.keys().collect::<Vec<_>>(),
        "{what}: other datasets"
    );
    for (name, v) in want {
        assert!(got[name] == *v, "{what}: dataset {name} differs");
    }
}

/// Deterministic pseudo-random delays (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

#[test]
fn killed_runs_resume_to_the_uninterrupted_table() {
    reference();
    let cfg = config("kill.toml", CONFIG);
    let dir = subdir("kill");
    let out = dir.join("t.h5");
    let ckpt = dir.join("t.h5.ckpt");
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let (mut kills, mut grew) = (0, 0);
    let mut last_len = 0;
    let start = Instant::now();
    loop {
        let mut child = spawn(&["run", s(&cfg), "-o", s(&out), "--quiet", "--resume"]);
        // Kill at a random moment between 20 and 250 ms, unless the run finishes first (the
        // whole run takes about 0.8 s on 2 cores, and each run resumes the last one's work: the
        // kills must land well inside it).
        let delay = Duration::from_millis(20 + rng.next() % 230);
        let t = Instant::now();
        let status = loop {
            if let Some(st) = child.try_wait().expect("wait") {
                break st;
            }
            if t.elapsed() >= delay {
                child.kill().expect("kill -9");
                break child.wait().expect("wait");
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        if status.success() {
            break;
        }
        assert_eq!(status.signal(), Some(9), "run failed: {status:?}");
        kills += 1;
        let len = std::fs::metadata(&ckpt).map(|m| m.len()).unwrap_or(0);
        if len > last_len {
            grew += 1;
        }
        last_len = len;
        assert!(
            start.elapsed() < Duration::from_secs(600),
            "no run finished in 600 s ({kills} kills)"
        );
    }
    eprintln!("{kills} kills, checkpoint grew {grew} times");
    assert!(
        kills >= 3,
        "only {kills} kills: the runs end too fast to test"
    );
    assert!(
        grew >= 2,
        "the checkpoint did not keep the killed runs' work"
    );
    assert!(!ckpt.exists(), "checkpoint left after the finished run");
    assert_same_as_reference(&out, "resumed run");
}

#[test]
fn ctrl_c_stops_cleanly_and_says_how_to_resume() {
    reference();
    let cfg = config("sigint.toml", CONFIG);
    let dir = subdir("sigint");
    let out = dir.join("t.h5");
    let child = spawn(&["run", s(&cfg), "-o", s(&out)]);
    std::thread::sleep(Duration::from_millis(700));
    let pid = child.id().to_string();
    let st = Command::new("kill").args(["-INT", &pid]).status();
    assert!(st.is_ok_and(|s| s.success()), "send SIGINT");
    let o = child.wait_with_output().expect("wait");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(130),
        "exit status after Ctrl-C: {err}"
    );
    assert!(
        err.contains("interrupted") && err.contains("--resume"),
        "no resume hint: {err}"
    );
    assert!(!out.exists(), "a table was written by an interrupted run");
    // Without --resume the checkpoint is not overwritten silently.
    let o = sweep(&["run", s(&cfg), "-o", s(&out), "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--resume"));
    ok(
        &sweep(&["run", s(&cfg), "-o", s(&out), "--quiet", "--resume"]),
        "resume",
    );
    assert_same_as_reference(&out, "run resumed after Ctrl-C");
}

#[test]
fn resuming_with_another_config_is_refused() {
    let cfg = config("a.toml", CONFIG);
    let other = config("b.toml", &CONFIG.replace("tol = 2e-6", "tol = 1e-6"));
    let dir = subdir("other_config");
    let out = dir.join("t.h5");
    let mut child = spawn(&["run", s(&cfg), "-o", s(&out), "--quiet"]);
    std::thread::sleep(Duration::from_millis(500));
    child.kill().expect("kill");
    let _ = child.wait();
    assert!(dir.join("t.h5.ckpt").exists(), "no checkpoint after kill");
    let o = sweep(&["run", s(&other), "-o", s(&out), "--quiet", "--resume"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("different config"), "{err}");
    assert!(!out.exists());
}

#[test]
fn shards_in_separate_processes_merge_to_the_single_run() {
    reference();
    let cfg = config("shard.toml", CONFIG);
    let dir = subdir("shards");
    let parts: Vec<PathBuf> = (1..=3).map(|k| dir.join(format!("p{k}.part"))).collect();
    let children: Vec<Child> = (1..=3)
        .map(|k| {
            spawn(&[
                "run",
                s(&cfg),
                "--shard",
                &format!("{k}/3"),
                "-o",
                s(&parts[k - 1]),
                "--quiet",
                "--threads",
                "1",
            ])
        })
        .collect();
    for c in children {
        let o = c.wait_with_output().expect("wait for shard");
        ok(&o, "shard");
    }
    let table = dir.join("merged.h5");
    let mut args = vec!["merge"];
    args.extend(parts.iter().map(|p| s(p)));
    args.extend(["-o", s(&table), "--quiet"]);
    ok(&sweep(&args), "merge");
    assert_same_as_reference(&table, "merged shards");

    // Bad merges: each a clear refusal (exit 2), no table written.
    let bad = |args: &[&str], needle: &str| {
        let out = dir.join("bad.h5");
        let mut a = vec!["merge"];
        a.extend_from_slice(args);
        a.extend(["-o", s(&out)]);
        let o = sweep(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "merge {args:?}: {err}");
        assert!(err.contains(needle), "merge {args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists(), "merge {args:?} wrote a table");
    };
    bad(&[s(&parts[0]), s(&parts[1])], "missing");
    bad(&[s(&parts[0]), s(&parts[1]), s(&parts[1])], "twice");
    // A part of another config.
    let other_cfg = config("shard_other.toml", &CONFIG.replace("seed = 3", "seed = 4"));
    let other = dir.join("other.part");
    ok(
        &sweep(&[
            "run",
            s(&other_cfg),
            "--shard",
            "3/3",
            "-o",
            s(&other),
            "--quiet",
        ]),
        "other shard",
    );
    bad(&[s(&parts[0]), s(&parts[1]), s(&other)], "different config");
    // A corrupted part (one byte flipped in a record).
    let corrupt = dir.join("corrupt.part");
    let mut bytes = std::fs::read(&parts[2]).expect("read part");
    let n = bytes.len();
    bytes[n - 30] ^= 0x40;
    std::fs::write(&corrupt, bytes).expect("write part");
    bad(&[s(&parts[0]), s(&parts[1]), s(&corrupt)], "corrupted");
    // Not a part at all.
    bad(&[s(&parts[0]), s(&parts[1]), s(&cfg)], "not a node file");
}

/// A table with the fold edge (schema-3 warp, `nodes.fold_warp`): the tracing of F₊ and the
/// forced splits at the warp's start give the same table with one thread, with all threads, and
/// from two shards merged.
#[test]
fn a_table_with_the_fold_edge_is_the_same_from_threads_and_shards() {
    let cfg = config(
        "fold.toml",
        r#"output = "unused.h5"
[domain]
gamma_min = 2.88
gamma_max = 2.96
alpha_max = "inf"
[nodes]
target_error = 2e-2
leaf_intervals = 6
fold_warp = true
[solver]
tol = 1e-4
[checks]
per_patch = 5
"#,
    );
    let dir = subdir("fold");
    let all = dir.join("all.h5");
    ok(
        &sweep(&["run", s(&cfg), "-o", s(&all), "--quiet"]),
        "fold run",
    );
    let want = datasets(&all);
    let knot = want
        .get("/patches/partial_high/warp/knot")
        .expect("the table has the fold edge");
    assert!(knot.len() >= 4, "{} knots", knot.len());
    let one = dir.join("one.h5");
    ok(
        &sweep(&["run", s(&cfg), "-o", s(&one), "--threads", "1", "--quiet"]),
        "fold run, one thread",
    );
    assert_eq!(datasets(&one), want, "one thread");
    let parts: Vec<PathBuf> = (1..=2).map(|k| dir.join(format!("f{k}.part"))).collect();
    for (k, part) in parts.iter().enumerate() {
        let shard = format!("{}/2", k + 1);
        ok(
            &sweep(&["run", s(&cfg), "--shard", &shard, "-o", s(part), "--quiet"]),
            "fold shard",
        );
    }
    let merged = dir.join("merged.h5");
    ok(
        &sweep(&[
            "merge",
            s(&parts[0]),
            s(&parts[1]),
            "-o",
            s(&merged),
            "--quiet",
        ]),
        "fold merge",
    );
    assert_eq!(datasets(&merged), want, "merged shards");
}

#[test]
fn bad_shard_arguments_are_usage_errors() {
    let cfg = config("shard_args.toml", CONFIG);
    for arg in ["0/3", "4/3", "1/0", "a/b", "3"] {
        let o = sweep(&["run", s(&cfg), "--shard", arg, "-o", "/tmp/x.part"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "--shard {arg}: {err}");
        assert!(err.contains("K/N"), "--shard {arg}: {err}");
    }
}

/// A table with an `e_n` axis, whose cells halve only some axes (the `split` dataset), built in
/// three shards and merged: every dataset equal to a single run's; the same for the table of
/// one pair (`domain.gamma`).
#[test]
fn shards_of_a_table_with_an_e_n_axis_merge_to_the_single_run() {
    for (name, domain) in [
        ("e_n", "gamma_min = 1.3\ngamma_max = 1.6\n"),
        ("pair", "gamma = 1.7497858600774299\n"),
    ] {
        let text = format!(
            "output = \"unused.h5\"\n[domain]\n{domain}e_n_min = 0.7\ne_n_max = 1.0\n\
             [nodes]\ntarget_error = 1e-4\nleaf_intervals = 6\nblocks_coord = 2\n\
             blocks_e_n = 2\n[solver]\ntol = 1e-5\n[checks]\nper_patch = 10\n"
        );
        let cfg = config(&format!("{name}.toml"), &text);
        let dir = subdir(&format!("{name}_shards"));
        let single = dir.join("single.h5");
        ok(
            &sweep(&["run", s(&cfg), "-o", s(&single), "--quiet"]),
            "single run",
        );
        let parts: Vec<PathBuf> = (1..=3).map(|k| dir.join(format!("p{k}.part"))).collect();
        for (k, part) in parts.iter().enumerate() {
            let shard = format!("{}/3", k + 1);
            ok(
                &sweep(&["run", s(&cfg), "--shard", &shard, "-o", s(part), "--quiet"]),
                "shard",
            );
        }
        let merged = dir.join("merged.h5");
        let mut args = vec!["merge"];
        args.extend(parts.iter().map(|p| s(p)));
        args.extend(["-o", s(&merged), "--quiet"]);
        ok(&sweep(&args), "merge");
        let (want, got) = (datasets(&single), datasets(&merged));
        assert!(
            want.contains_key("/patches/partial_high/split"),
            "{name}: {:?}",
            want.keys().collect::<Vec<_>>()
        );
        assert_eq!(
            want, got,
            "{name}: merged shards differ from the single run"
        );
    }
}
