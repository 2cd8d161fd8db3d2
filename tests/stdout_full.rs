//! A full standard output (a full disk, `/dev/full`) is an error of the machine, not a panic:
//! every command that prints fails with exit status 1 and says why on standard error.

use std::fs::OpenOptions;
use std::process::{Command, Stdio};

#[test]
fn commands_writing_to_a_full_stdout_fail_cleanly() {
    let root = env!("CARGO_MANIFEST_DIR");
    let table = format!("{root}/tables/quick.h5");
    let out_dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("stdout_full-{}", std::process::id()));
    let out = out_dir.to_str().expect("utf-8").to_string();
    let cases: Vec<Vec<&str>> = vec![
        vec!["query", &table, "--gamma", "1.754", "--alpha", "1"],
        vec![
            "query", &table, "--gamma", "1.754", "--alpha", "1", "--json",
        ],
        vec!["inspect", &table],
        vec!["impact", "--gamma", "1.754", "--alpha", "1"],
        vec![
            "impact", "--gamma", "1.754", "--alpha", "1", "--e-n", "0.9", "--json",
        ],
        vec!["reference", "chung-ooi", "-o", &out],
        vec![
            "kinks",
            "--gamma-max",
            "2.95",
            "--points",
            "2",
            "--steps",
            "256",
        ],
    ];
    for args in cases {
        let full = OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .expect("/dev/full (Linux)");
        let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .args(&args)
            .stdout(Stdio::from(full))
            .output()
            .expect("run sweep");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("cannot write to standard output"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}
