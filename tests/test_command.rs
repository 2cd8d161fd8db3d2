//! The test command (scripts/test) installs nothing into the user's Python: every Python step
//! runs in its own virtual environment (scripts/venv.sh), so that it works where the system's
//! Python refuses pip (Debian 12, PEP 668's EXTERNALLY-MANAGED).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// Commands of a shell script: lines without comments, continuation lines (`\`) joined.
fn code_lines(text: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut continued = false;
    for line in text.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (body, more) = match line.strip_suffix('\\') {
            Some(b) => (b.trim_end(), true),
            None => (line, false),
        };
        match out.last_mut() {
            Some(last) if continued => {
                last.push(' ');
                last.push_str(body);
            }
            _ => out.push(body.to_string()),
        }
        continued = more;
    }
    out
}

#[test]
fn scripts_install_python_packages_only_into_their_own_environment() {
    for script in [
        "scripts/test",
        "scripts/check_table.sh",
        "scripts/check_slurm.sh",
        "scripts/check_cuda.sh",
    ] {
        let text = read(script);
        let lines = code_lines(&text);
        for (i, line) in lines.iter().enumerate() {
            // A pip install is allowed into a folder of the project's (--target), or through the
            // python3 of the environment after scripts/venv.sh was sourced.
            if !line.contains("pip install") || line.contains("--target") {
                continue;
            }
            let sourced_before = lines[..i].iter().any(|l| l.contains("scripts/venv.sh"));
            assert!(
                sourced_before && !line.contains("--user"),
                "{script}: `{line}` installs into a Python that is not the checks' own \
                 environment (source scripts/venv.sh first)"
            );
        }
    }
    let test = read("scripts/test");
    // A step run through the timer, `step "NAME" COMMAND...`, is its command.
    let lines: Vec<String> = code_lines(&test)
        .into_iter()
        .map(|l| {
            l.strip_prefix("step \"")
                .and_then(|rest| rest.split_once("\" "))
                .map_or(l.clone(), |(_, command)| command.to_string())
        })
        .collect();
    let venv = lines
        .iter()
        .position(|l| *l == "source scripts/venv.sh")
        .expect("scripts/test sources scripts/venv.sh");
    let first_python = lines
        .iter()
        .position(|l| l.contains("python3") || l.starts_with("cargo test"))
        .expect("scripts/test runs python3 and the Rust tests");
    assert!(
        venv < first_python,
        "scripts/test must source scripts/venv.sh before its first Python step and the Rust tests"
    );
    // The portable wheel is built once: installed into the environment for pytest, then checked
    // in a fresh one (the same file, not a second build).
    let position = |what: &str, f: &dyn Fn(&str) -> bool| {
        lines
            .iter()
            .position(|l| f(l))
            .unwrap_or_else(|| panic!("scripts/test {what}"))
    };
    let build = position("builds the wheel (scripts/build_wheel.sh)", &|l| {
        l.starts_with("background ") && l.ends_with(" bash scripts/build_wheel.sh")
    });
    let wait = position("waits for the wheel", &|l| {
        l == "finish \"scripts/build_wheel.sh\""
    });
    let install = position("installs the wheel it built", &|l| {
        l.contains("pip install") && l.ends_with("\"$wheel\"")
    });
    let pytest = position("runs pytest", &|l| l.contains("-m pytest"));
    let check = position("checks the wheel it built", &|l| {
        l == "bash scripts/check_wheel.sh \"$wheel\""
    });
    assert!(
        build < wait && wait < install && install < pytest && install < check,
        "scripts/test: build the wheel, install it, then pytest; check_wheel.sh checks that wheel"
    );
    assert!(
        !lines.iter().any(|l| l.contains("./python")),
        "scripts/test builds the package once (scripts/build_wheel.sh), not again from ./python"
    );
    let venv_sh = read("scripts/venv.sh");
    assert!(venv_sh.contains("-m venv"), "scripts/venv.sh makes a venv");
    assert!(venv_sh.contains("target/venv"), "scripts/venv.sh's folder");
    let ignore = read(".gitignore");
    assert!(
        ignore.lines().any(|l| l == "target/" || l == "/target/"),
        "target/ (holding target/venv) is git-ignored"
    );
}

/// Under the test command (which exports OBLIQUE_VENV), the `python3` that the Rust tests run is
/// the environment's own, not the system's.
#[test]
fn python3_of_the_test_command_is_its_own_environment() {
    let Some(venv) = std::env::var_os("OBLIQUE_VENV") else {
        eprintln!("skipped: OBLIQUE_VENV is not set (run under scripts/test)");
        return;
    };
    let out = Command::new("python3")
        .args([
            "-c",
            "import sys, h5py, numpy; print(sys.prefix); print(sys.base_prefix)",
        ])
        .output()
        .expect("run python3");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let prefix = Path::new(lines.next().unwrap()).canonicalize().unwrap();
    let base = Path::new(lines.next().unwrap()).to_path_buf();
    let venv = Path::new(&venv).canonicalize().unwrap();
    assert_eq!(prefix, venv, "python3 on PATH is not the environment's");
    assert_ne!(prefix, base, "python3 is not in a virtual environment");
}

/// scripts/build_wheel.sh teaches with --help (what it builds: the manylinux_2_28 tag, and how)
/// and refuses a bad argument with exit 2 before installing or building anything.
#[test]
fn build_wheel_script_teaches_and_refuses_bad_arguments() {
    let script = root().join("scripts/build_wheel.sh");
    let run = |args: &[&str]| {
        Command::new("bash")
            .arg(&script)
            .args(args)
            .output()
            .expect("bash runs")
    };
    let help = run(&["--help"]);
    assert!(help.status.success(), "--help: {}", help.status);
    let text = String::from_utf8_lossy(&help.stdout);
    for word in [
        "manylinux_2_28",
        "glibc 2.28",
        "static-hdf5",
        "OUT_DIR",
        "auditwheel show",
    ] {
        assert!(
            text.contains(word),
            "--help does not mention {word}:\n{text}"
        );
    }
    for bad in [&["--bogus"][..], &["a", "b"][..]] {
        let out = run(bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}: {}", out.status);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("see --help"), "{bad:?}: {err}");
    }
}
