//! A write that fails part-way (a full disk; here the file size limit of `ulimit -f`, which
//! fails the write the same way, as root and as any user) leaves every output as it was or
//! complete: no truncated file under the final name, and no temporary file beside it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("write_failure-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create test directory");
    dir
}

/// `sweep ARGS` with files limited to `kib` KiB: a write beyond it fails with EFBIG (SIGXFSZ
/// ignored, as bash's `trap '' XFSZ` leaves it across exec).
fn sweep_limited(kib: u32, args: &[&str]) -> Output {
    Command::new("bash")
        .arg("-c")
        .arg(r#"trap '' XFSZ; ulimit -f "$1" || exit 99; shift; exec "$@""#)
        .arg("bash")
        .arg(kib.to_string())
        .arg(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run bash")
}

fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .output()
        .expect("run sweep")
}

/// Every file in `dir` by name, with its bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .expect("read folder")
        .map(|e| {
            let e = e.expect("entry");
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).expect("read"))
        })
        .collect()
}

const OLD: &[u8] = b"the previous contents";

/// Run `args` (writing into `out`) once without a limit into a fresh folder for the complete
/// files, then with every file already there holding `OLD` and a limit of `kib` KiB: the run
/// fails, and each file is either `OLD` or complete, with nothing else in the folder.
fn check(name: &str, kib: u32, args: impl Fn(&str) -> Vec<String>, sub: &str) {
    let full = scratch(&format!("{name}-full"));
    std::fs::create_dir_all(full.join(sub)).expect("create folder");
    let a = args(full.to_str().expect("utf-8"));
    let o = sweep(&a.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let complete = files(&full.join(sub));
    assert!(!complete.is_empty());

    let dir = scratch(name);
    std::fs::create_dir_all(dir.join(sub)).expect("create folder");
    for file in complete.keys() {
        std::fs::write(dir.join(sub).join(file), OLD).expect("write");
    }
    let a = args(dir.to_str().expect("utf-8"));
    let o = sweep_limited(kib, &a.iter().map(String::as_str).collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{a:?}: {err}");
    assert!(
        err.contains("cannot write") && err.contains("file size limit"),
        "{err}"
    );
    let after = files(&dir.join(sub));
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        complete.keys().collect::<Vec<_>>(),
        "a temporary file was left, or a file is missing"
    );
    let mut kept = 0;
    for (file, bytes) in &after {
        if bytes == OLD {
            kept += 1;
        } else {
            assert!(
                bytes == &complete[file],
                "{file}: neither its previous contents nor complete ({} of {} bytes)",
                bytes.len(),
                complete[file].len()
            );
        }
    }
    assert!(kept > 0, "the limit stopped no write");
    let _ = std::fs::remove_dir_all(&full);
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn plot_with_a_failing_write_leaves_no_truncated_figure() {
    let table = format!("{}/tables/quick.h5", env!("CARGO_MANIFEST_DIR"));
    for format in ["png", "svg"] {
        check(
            &format!("plot-{format}"),
            8,
            |out| {
                ["plot", &table, "-o", out, "--format", format]
                    .iter()
                    .map(|s| s.to_string())
                    .collect()
            },
            "",
        );
    }
}

#[cfg(unix)]
#[test]
fn reference_with_a_failing_write_leaves_no_truncated_csv() {
    check(
        "reference",
        4,
        |out| {
            ["reference", "mfix-dem05", "-o", out]
                .iter()
                .map(|s| s.to_string())
                .collect()
        },
        "mfix-dem05",
    );
}

#[cfg(unix)]
#[test]
fn export_and_scene_with_a_failing_write_leave_no_partial_file() {
    let root = env!("CARGO_MANIFEST_DIR");
    let table = format!("{root}/tables/quick.h5");
    check(
        "export",
        4,
        |out| {
            vec![
                "export".into(),
                table.clone(),
                "-o".into(),
                format!("{out}/sub/quick.bin"),
            ]
        },
        "sub",
    );
    let scene = format!("{root}/configs/scenes/seed000_alumina_on_glass.toml");
    check(
        "scene",
        8,
        |out| {
            ["scene", &scene, "--table", &table, "-o", out]
                .iter()
                .map(|s| s.to_string())
                .collect()
        },
        "",
    );
}
