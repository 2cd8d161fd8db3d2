//! The rules of README's "What is where", checked on the sources: which crate may depend on
//! which, and that every file the `sweep` binary writes goes through `oblique-output`.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The names in the `[dependencies]` section of a Cargo.toml.
fn dependencies(manifest: &str) -> Vec<String> {
    let text = std::fs::read_to_string(root().join(manifest)).expect("read manifest");
    let mut deps = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == "[dependencies]";
        } else if inside && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.', ' ']).next().unwrap_or("");
            deps.push(name.to_string());
        }
    }
    deps
}

#[test]
fn crates_depend_only_on_what_the_readme_allows() {
    let oblique = |d: &&String| d.starts_with("oblique-");
    for (manifest, allowed) in [
        ("crates/physics/Cargo.toml", &[][..]),
        ("crates/solver/Cargo.toml", &["oblique-physics"][..]),
        ("crates/output/Cargo.toml", &[][..]),
        (
            "crates/table/Cargo.toml",
            &["oblique-physics", "oblique-output"][..],
        ),
        (
            "crates/lookup/Cargo.toml",
            &["oblique-physics", "oblique-table"][..],
        ),
        ("crates/lookup-capi/Cargo.toml", &["oblique-lookup"][..]),
        ("crates/plot/Cargo.toml", &["oblique-output"][..]),
    ] {
        let deps = dependencies(manifest);
        let extra: Vec<_> = deps
            .iter()
            .filter(oblique)
            .filter(|d| !allowed.contains(&d.as_str()))
            .collect();
        assert!(extra.is_empty(), "{manifest} depends on {extra:?}");
    }
    // The pure crates do no I/O: no file formats, no output module.
    for manifest in ["crates/physics/Cargo.toml", "crates/solver/Cargo.toml"] {
        let deps = dependencies(manifest);
        assert!(
            deps.iter()
                .all(|d| ["serde", "thiserror", "oblique-physics"].contains(&d.as_str())),
            "{manifest}: {deps:?}"
        );
    }
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("read folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_written_file_goes_through_the_output_module() {
    let mut files = Vec::new();
    sources(&root().join("src"), &mut files);
    for krate in std::fs::read_dir(root().join("crates")).expect("crates") {
        let src = krate.expect("entry").path().join("src");
        if src.is_dir() && !src.starts_with(root().join("crates/output")) {
            sources(&src, &mut files);
        }
    }
    // What writes a file itself, and why it may: each writes only at the path the output
    // module hands it (the temporary file), or is no output.
    let allowed = [
        ("crates/plot/src/lib.rs", "Backend::new(tmp,"),
        ("crates/plot/src/sheet.rs", "Backend::new(tmp,"),
        // The seal goes into the temporary file before the module renames it.
        (
            "crates/table/src/write.rs",
            "OpenOptions::new().write(true).open(path)?",
        ),
        // A writability probe, created and removed at once.
        ("crates/sweep/src/job.rs", "std::fs::write(&probe"),
        // The built-in table's private scratch copy for HDF5 to open, created new in the
        // temporary folder and removed before returning: no output of the user's.
        ("crates/lookup/src/embedded.rs", "create_new("),
        ("crates/lookup/src/embedded.rs", "OpenOptions::new()"),
    ];
    let patterns = [
        "File::create",
        "fs::write(",
        "OpenOptions::new()",
        "create_new(",
        "BitMapBackend::new(",
        "SVGBackend::new(",
    ];
    let mut found = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).expect("read source");
        // Unit tests write their own fixtures.
        let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or("");
        let name = file.strip_prefix(root()).expect("in the repository");
        let name = name.to_string_lossy();
        for (n, line) in code.lines().enumerate() {
            let l = line.trim();
            if l.starts_with("//") || !patterns.iter().any(|p| l.contains(p)) {
                continue;
            }
            if !allowed.iter().any(|(f, s)| name == *f && l.contains(s)) {
                found.push(format!("{name}:{}: {l}", n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "files written around oblique-output:\n  {}",
        found.join("\n  ")
    );
}
