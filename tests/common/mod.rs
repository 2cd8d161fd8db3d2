//! Scratch directories and the `sweep` binary, shared by the end-to-end tests (`mod common;` in
//! each test file; each uses a part of it).
#![allow(dead_code)]

pub mod size;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// `sweep ARGS`: the binary under test, run to its end.
pub fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run the sweep binary")
}

/// `dst`: a copy of the table `src` changed by the Python (h5py) statement `edit` (with `f`
/// the file open for writing) and sealed again, so that only the edit is wrong with it.
pub fn edited_copy(src: &Path, dst: &Path, edit: &str) {
    std::fs::copy(src, dst).expect("copy");
    let script = format!("import h5py, sys; f = h5py.File(sys.argv[1], 'r+'); {edit}");
    let out = Command::new("python3")
        .args(["-c", &script, dst.to_str().expect("path")])
        .output()
        .expect("python3 with h5py");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    oblique_table::write::seal(dst).expect("seal again");
}

/// A table built by `sweep run` from the config `body` (everything but `output`) into
/// `DIR/STEM.h5`, `DIR` a fresh sub-directory of the scratch directory.
pub fn build_table(dir: &str, stem: &str, body: &str) -> PathBuf {
    let dir = subdir(dir);
    let out = dir.join(format!("{stem}.h5"));
    let cfg = dir.join(format!("{stem}.toml"));
    let text = format!("output = {:?}\n{body}", out.display().to_string());
    std::fs::write(&cfg, text).expect("write config");
    sweep_ok(&["run", cfg.to_str().expect("path"), "--quiet"]);
    out
}

/// The table that `sweep run CONFIG` builds, made once for every test process of this build:
/// kept under `CARGO_TARGET_TMPDIR/shared-tables/STEM-KEY.h5`, where `KEY` hashes the config's
/// text and the size and modification time of the `sweep` binary, so a changed config or a
/// rebuilt binary builds it again (the files of older keys are removed then). Built under a
/// name of this process and renamed into place, so a process that finds the file finds it
/// whole.
pub fn shared_build(config: &Path) -> PathBuf {
    use std::hash::{Hash, Hasher};
    let text = std::fs::read(config).expect("read the config");
    let bin = std::fs::metadata(env!("CARGO_BIN_EXE_sweep")).expect("the sweep binary");
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    bin.len().hash(&mut h);
    bin.modified().ok().hash(&mut h);
    let stem = config
        .file_stem()
        .expect("a config file name")
        .to_string_lossy()
        .into_owned();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("shared-tables");
    std::fs::create_dir_all(&dir).expect("create the shared tables folder");
    let out = dir.join(format!("{stem}-{:016x}.h5", h.finish()));
    if out.exists() {
        return out;
    }
    if let Ok(entries) = std::fs::read_dir(&dir) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with(&format!("{stem}-")) && name.ends_with(".h5") {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
    let tmp = dir.join(format!(".{stem}-{}.h5", std::process::id()));
    let _ = std::fs::remove_file(&tmp);
    let path = |p: &Path| p.to_str().expect("path").to_string();
    sweep_ok(&["run", &path(config), "--output", &path(&tmp), "--quiet"]);
    std::fs::rename(&tmp, &out).expect("move the shared table into place");
    out
}

/// `sweep ARGS` succeeds: its standard output.
pub fn sweep_ok(args: &[&str]) -> String {
    let out = sweep(args);
    assert!(
        out.status.success(),
        "sweep {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8")
}

/// `sweep ARGS` fails with exit status 2, without a panic, and a message containing every
/// needle.
pub fn sweep_refused(args: &[&str], needles: &[&str]) {
    let out = sweep(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "sweep {args:?}: {err}");
    assert!(!err.contains("panicked"), "sweep {args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "sweep {args:?}: {err:?} lacks {n:?}");
    }
}

/// Scratch directory of this test process, `CARGO_TARGET_TMPDIR/NAME-PID` where NAME is the
/// test file's name; the stale ones of test processes that no longer run are removed first.
pub fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let base = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
        let prefix = format!("{}-", env!("CARGO_CRATE_NAME"));
        if Path::new("/proc/self").exists() {
            if let Ok(entries) = std::fs::read_dir(&base) {
                for e in entries.flatten() {
                    let name = e.file_name().to_string_lossy().to_string();
                    if let Some(pid) = name.strip_prefix(&prefix) {
                        if !Path::new("/proc").join(pid).exists() {
                            let _ = std::fs::remove_dir_all(e.path());
                        }
                    }
                }
            }
        }
        let dir = base.join(format!("{prefix}{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create scratch directory");
        dir
    })
}

/// A fresh, empty sub-directory of the scratch directory.
pub fn subdir(name: &str) -> PathBuf {
    let d = scratch().join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("create test directory");
    d
}

/// `scripts/read_table.py TABLE QUERY` refuses the table (status 2), its message naming every
/// one of `want`.
pub fn python_refuses(path: &Path, query: &[&str], want: &[&str]) {
    let r = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/read_table.py"))
        .arg(path)
        .args(query)
        .output()
        .expect("python3 (with h5py: the test command installs it)");
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{}: {err}", path.display());
    for w in want {
        assert!(err.contains(w), "{}: {w:?} not in {err}", path.display());
    }
}

/// `scripts/read_table.py TABLE --check-stored` succeeds: the reference reader gives every
/// stored node value back from the table.
pub fn python_check_stored(path: &Path) {
    let r = Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/read_table.py"))
        .arg(path)
        .arg("--check-stored")
        .output()
        .expect("python3");
    assert!(
        r.status.success(),
        "{}{}",
        String::from_utf8_lossy(&r.stdout),
        String::from_utf8_lossy(&r.stderr)
    );
}
