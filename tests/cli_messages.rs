//! Error messages of the `sweep` binary as a user reads them: each cause said once, exit code 2
//! for a missing file the user named.

use std::process::Command;

fn stderr_of(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run the sweep binary");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn an_os_error_is_said_once() {
    for args in [
        vec!["run", "/nonexistent/config.toml"],
        vec!["scene", "/nonexistent/scene.toml", "-o", "/tmp"],
        vec!["inspect", "/nonexistent/table.h5"],
    ] {
        let (code, stderr) = stderr_of(&args);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(stderr.contains("/nonexistent/"), "{args:?}: {stderr}");
        let said = stderr.matches("No such file").count() + stderr.matches("no such file").count();
        assert_eq!(said, 1, "{args:?}: the cause once: {stderr}");
    }
}

/// A number beyond the largest double (`1e400`) is refused naming the flag, exit 2, not read
/// as `inf`; `inf` spelled out stays allowed where it was.
#[test]
fn an_overflowing_number_is_refused_naming_its_flag() {
    let table = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/quick.h5");
    for (flag, args) in [
        (
            "--gamma",
            vec!["query", table, "--gamma", "1e400", "--alpha", "0.3"],
        ),
        (
            "--alpha",
            vec!["query", table, "--gamma", "1.5", "--alpha", "1e400"],
        ),
        (
            "--alpha",
            vec!["query", table, "--gamma", "1.5", "--alpha", "-1E999"],
        ),
        (
            "--e-n",
            vec![
                "query", table, "--gamma", "1.5", "--alpha", "0.3", "--e-n", "2e308",
            ],
        ),
        (
            "--alpha",
            vec!["impact", "--gamma", "1.5", "--alpha", "1e400"],
        ),
        (
            "--tol",
            vec![
                "impact", "--gamma", "1.5", "--alpha", "0.3", "--tol", "1e400",
            ],
        ),
    ] {
        let (code, stderr) = stderr_of(&args);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(flag) && stderr.contains("overflows"),
            "{args:?}: {stderr}"
        );
    }
    let out = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(["query", table, "--gamma", "1.5", "--alpha", "inf"])
        .output()
        .expect("run the sweep binary");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
