//! Bad sweep configs through the CLI: each is refused before any work with a one-line
//! message naming the key (or the problem) and the allowed range (a TOML error: the parser's
//! report with the line and a caret), exit code 2, no panic, and an existing table at the
//! output path is left as it was.

use std::path::{Path, PathBuf};
use std::process::Command;

const GOOD: &str = r#"output = "OUT"

[domain]
gamma_min = 0.8
gamma_max = 1.6
alpha_max = "inf"

[nodes]
target_error = 1e-3

[solver]
tol = 1e-4
"#;

fn dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bad_input-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("create test directory");
    d
}

/// Run `sweep run` on `text` (with `OUT` replaced by an output path that already holds a file)
/// and check the refusal.
fn refused(name: &str, text: &str, needles: &[&str]) {
    let d = dir();
    let out = d.join(format!("{name}.h5"));
    std::fs::write(&out, b"previous table").expect("write placeholder");
    let cfg = d.join(format!("{name}.toml"));
    std::fs::write(&cfg, text.replace("OUT", out.to_str().expect("utf-8"))).expect("write");
    let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(["run", cfg.to_str().expect("utf-8"), "--quiet"])
        .output()
        .expect("run sweep");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{name}: exit {:?}: {err}",
        o.status
    );
    assert!(!err.contains("panicked"), "{name}: {err}");
    // A TOML syntax or key error keeps the parser's report: the line, a caret under the error.
    if err.contains("TOML parse error") {
        assert!(
            err.contains(" | ") && err.contains('^'),
            "{name}: no caret: {err}"
        );
    } else {
        assert_eq!(err.trim().lines().count(), 1, "{name}: not one line: {err}");
    }
    for n in needles {
        assert!(err.contains(n), "{name}: message lacks '{n}': {err}");
    }
    assert_eq!(
        std::fs::read(&out).expect("read output"),
        b"previous table",
        "{name}: the existing output was touched"
    );
    assert!(!Path::new(&format!("{}.ckpt", out.display())).exists());
}

#[test]
fn malformed_toml() {
    refused("malformed", &GOOD.replace("[solver]", "[solver"), &["TOML"]);
}

#[test]
fn unknown_key() {
    refused(
        "unknown",
        &GOOD.replace("tol = 1e-4", "tol = 1e-4\ntolerance = 2"),
        &["tolerance"],
    );
}

#[test]
fn nan_negative_and_inverted_ranges() {
    refused(
        "nan",
        &GOOD.replace("gamma_min = 0.8", "gamma_min = nan"),
        &["domain.gamma_min", "> 0"],
    );
    refused(
        "negative",
        &GOOD.replace("gamma_min = 0.8", "gamma_min = -1"),
        &["domain.gamma_min"],
    );
    refused(
        "inverted",
        &GOOD.replace("gamma_max = 1.6", "gamma_max = 0.5"),
        &["domain.gamma_max", "gamma_min = 0.8"],
    );
    refused(
        "negative_tol",
        &GOOD.replace("tol = 1e-4", "tol = -1e-4"),
        &["solver.tol"],
    );
    refused(
        "alpha_max_below_alpha_c2",
        &GOOD.replace("alpha_max = \"inf\"", "alpha_max = 0.1"),
        &["domain.alpha_max", "alpha_c2"],
    );
    // An e_n range whose gamma reaches the fold curve F- (born at gamma 2.3666 for e_n = 1),
    // next to which such a table cannot yet hold its bound; the file in place is kept.
    refused(
        "e_n_range_into_fold_minus",
        &GOOD.replace("gamma_max = 1.6", "gamma_max = 2.6").replace(
            "alpha_max = \"inf\"",
            "alpha_max = \"inf\"\ne_n_min = 0.5\ne_n_max = 1.0",
        ),
        &["domain.gamma_max", "< 2.3666", "fold curve F-"],
    );
}

#[test]
fn absurd_resolution_is_refused_before_the_work_starts() {
    // Both tolerances are valid numbers, but no node at γ = 3.5 can reach 1e-10 in reasonable
    // time: the pre-flight probe says so (and what is reachable) before any node is placed.
    refused(
        "absurd_tol",
        &GOOD
            .replace("gamma_max = 1.6", "gamma_max = 3.5")
            .replace("target_error = 1e-3", "target_error = 1e-9")
            .replace("tol = 1e-4", "tol = 1e-10"),
        &["solver.tol = 1e-10 cannot be reached", "loosen solver.tol"],
    );
    // A node budget that cannot hold the first refinement round.
    refused(
        "max_nodes",
        &GOOD.replace("target_error = 1e-3", "target_error = 1e-3\nmax_nodes = 10"),
        &["nodes.max_nodes"],
    );
}
