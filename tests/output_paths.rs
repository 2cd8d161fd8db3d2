//! Output paths the user must fix, refused before any work with exit status 2, nothing replaced:
//! an output folder that is a file (`plot`, `reference`); an export over a FIFO, a symbolic
//! link, a device or its own input (`export`).

use std::process::Command;

#[test]
fn an_output_folder_that_is_a_file_is_refused_up_front() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("output_folder-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("suites")).expect("create test directory");
    let file = dir.join("a_file");
    std::fs::write(&file, b"keep me").expect("write");
    std::fs::write(dir.join("suites/thornton"), b"keep me too").expect("write");
    let f = file.to_str().expect("utf-8");
    let suites = dir.join("suites");
    let s = suites.to_str().expect("utf-8");
    let table = format!("{root}/tables/quick.h5");
    for args in [
        vec!["plot", &table, "-o", f],
        vec!["reference", "chung-ooi", "-o", f],
        vec!["reference", "all", "-o", s],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .args(&args)
            .output()
            .expect("run sweep");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("-o") && err.contains("not a folder"),
            "{args:?}: {err}"
        );
        // Refused before computing: nothing printed on stdout.
        assert!(o.stdout.is_empty(), "{args:?} computed first");
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"keep me");
    assert_eq!(
        std::fs::read(dir.join("suites/thornton")).unwrap(),
        b"keep me too"
    );
    // Nothing else was written into the folder of suites.
    let names: Vec<_> = std::fs::read_dir(&suites).unwrap().collect();
    assert_eq!(names.len(), 1);
}

#[cfg(unix)]
#[test]
fn export_replaces_no_special_file_and_not_its_input() {
    use std::os::unix::fs::FileTypeExt;
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("export_paths-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create test directory");
    let input = dir.join("t.h5");
    std::fs::copy(format!("{root}/tables/quick.h5"), &input).expect("copy table");
    let original = std::fs::read(&input).unwrap();
    let hard = dir.join("same.h5");
    std::fs::hard_link(&input, &hard).expect("hard link");
    let link = dir.join("link.bin");
    std::os::unix::fs::symlink(dir.join("target.bin"), &link).expect("symlink");
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    for (out, what) in [
        (&input, "is the input"),
        (&hard, "is the input"),
        (&link, "symbolic link"),
        (&fifo, "FIFO"),
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .args([
                "export",
                input.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ])
            .output()
            .expect("run sweep");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{out:?}: {err}");
        assert!(err.contains(what), "{out:?}: {err}");
    }
    assert_eq!(std::fs::read(&input).unwrap(), original);
    assert!(!dir.join("target.bin").exists());
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
}

#[cfg(target_os = "linux")]
#[test]
fn export_removes_the_temporary_file_a_killed_export_left() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("export_stale-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create test directory");
    // The PID of a process that has ended: what a killed export leaves in the name.
    let mut child = Command::new("true").spawn().expect("spawn");
    let dead = child.id();
    child.wait().expect("wait");
    let stale = dir.join(format!(".out.bin.tmp{dead}"));
    std::fs::write(&stale, b"half an export").expect("write");
    // A file of a running process (this test) and an unrelated one stay.
    let live = dir.join(format!(".out.bin.tmp{}", std::process::id()));
    std::fs::write(&live, b"in progress").expect("write");
    let other = dir.join(".other.bin.tmp1");
    std::fs::write(&other, b"not ours").expect("write");
    let out = dir.join("out.bin");
    let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(["export", &format!("{root}/tables/quick.h5"), "-o"])
        .arg(&out)
        .output()
        .expect("run sweep");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.exists());
    assert!(
        !stale.exists(),
        "the killed export's temporary file is still there"
    );
    assert!(live.exists() && other.exists());
}

#[test]
fn export_names_the_gamma_range_for_a_curve_outside_it() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("export_gamma-{}.bin", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args([
            "export",
            &format!("{root}/tables/quick.h5"),
            "--gamma",
            "4",
            "-o",
        ])
        .arg(&out)
        .output()
        .expect("run sweep");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--gamma 4") && err.contains("[0.5, 2.5]"),
        "{err}"
    );
    // Export has no clamping and no alpha to ask for: the message must not offer them.
    assert!(!err.contains("clamp") && !err.contains("alpha"), "{err}");
    assert!(!out.exists());
}

/// An output folder that is a file, or below one (`notdir/sub`), is the user's to fix: exit
/// status 2 and a message saying so, for every command that writes into a folder (`scene` said
/// "cannot create output folder notdir: File exists" with exit status 1).
#[test]
fn an_output_folder_in_the_way_of_a_file_is_a_usage_error() {
    let root = env!("CARGO_MANIFEST_DIR");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("output_notdir-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create test directory");
    let file = dir.join("notdir");
    std::fs::write(&file, b"keep me").expect("write");
    let f = file.to_str().expect("utf-8");
    let below = file.join("sub");
    let b = below.to_str().expect("utf-8");
    let table = format!("{root}/tables/quick.h5");
    let scene = format!("{root}/configs/scenes/steel_on_steel.toml");
    for out in [f, b] {
        for args in [
            vec!["scene", &scene, "--table", &table, "-o", out],
            vec!["plot", &table, "-o", out],
            vec!["reference", "mfix-dem05", "-o", out],
            vec!["accuracy", "--quick", "--out", out],
        ] {
            let o = Command::new(env!("CARGO_BIN_EXE_sweep"))
                .args(&args)
                .output()
                .expect("run sweep");
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
            assert!(
                err.contains(out) && err.contains("exists and is not a folder"),
                "{args:?}: {err}"
            );
            assert!(!err.contains("File exists"), "{args:?}: {err}");
            assert!(o.stdout.is_empty(), "{args:?} computed first");
        }
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"keep me");
    let _ = std::fs::remove_dir_all(&dir);
}
