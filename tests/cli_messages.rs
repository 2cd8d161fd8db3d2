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
