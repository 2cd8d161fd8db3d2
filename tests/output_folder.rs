//! An output folder that exists as a file is the user's to fix: `plot` and `reference` refuse
//! it before any work, with exit status 2 and a message naming `-o`, and leave the file alone.

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
