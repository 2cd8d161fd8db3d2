//! Shipped outputs and the examples of the docs: the files under docs/ that a command writes are
//! what it writes now (`sweep scene … --check`, like `sweep reference all -o docs/reference
//! --check` in the test command), `--check` names a stale or missing file and writes nothing,
//! and no example of README.md or docs/*.md writes into a tracked folder (examples write under
//! `out/`, which git ignores).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("run sweep")
}

const SEED000: &str = "configs/scenes/seed000_alumina_on_glass.toml";

#[test]
fn shipped_scene_outputs_are_what_sweep_scene_writes() {
    let o = sweep(&["scene", SEED000, "-o", "docs/figures", "--check"]);
    assert!(
        o.status.success(),
        "docs/figures is stale: regenerate it with `sweep scene {SEED000} -o docs/figures`\n{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("up to date: docs/figures/seed000_alumina_on_glass.csv"),
        "{out}"
    );
}

#[test]
fn check_names_stale_and_missing_files_and_writes_nothing() {
    let dir = common::subdir("stale");
    let d = dir.to_str().unwrap();
    // Written into an empty folder, then checked: up to date (the caption does not name -o).
    let o = sweep(&["scene", SEED000, "-o", d]);
    assert!(o.status.success());
    let csv = dir.join("seed000_alumina_on_glass.csv");
    let png = dir.join("seed000_alumina_on_glass.png");
    for f in [&csv, &png] {
        let shipped = root().join("docs/figures").join(f.file_name().unwrap());
        assert_eq!(
            std::fs::read(f).unwrap(),
            std::fs::read(shipped).unwrap(),
            "{f:?}"
        );
    }
    assert!(sweep(&["scene", SEED000, "-o", d, "--check"])
        .status
        .success());

    let mut text = std::fs::read_to_string(&csv).unwrap();
    text.push_str("# edited\n");
    std::fs::write(&csv, &text).unwrap();
    std::fs::remove_file(&png).unwrap();
    let o = sweep(&["scene", SEED000, "-o", d, "--check"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("{} differs", csv.display())), "{err}");
    assert!(
        err.contains(&format!("{} is missing", png.display())),
        "{err}"
    );
    assert!(
        err.contains(&format!("sweep scene {SEED000} -o {d}")),
        "{err}"
    );
    // Nothing was written.
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), text);
    assert!(!png.exists());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

/// Top-level folders of the checkout that hold tracked files.
const TRACKED: [&str; 13] = [
    "docs", "tables", "configs", "include", "examples", "python", "src", "crates", "tests",
    "scripts", "tools", "fortran", "benches",
];

/// The paths a command line writes: after `-o`, `--output`, `--out`, `>` and `>>`, and any
/// argument naming a file under docs/ (an example's positional output, e.g. a figure).
fn outputs(command: &str) -> Vec<String> {
    let words: Vec<&str> = command.split_whitespace().collect();
    let mut out = Vec::new();
    let mut next_is_output = false;
    for w in words {
        if next_is_output || w.starts_with("docs/") {
            out.push(w.to_string());
            next_is_output = false;
        } else if let Some(v) = w.strip_prefix("--output=").or(w.strip_prefix("--out=")) {
            out.push(v.to_string());
        } else {
            next_is_output = ["-o", "--output", "--out", ">", ">>"].contains(&w);
        }
    }
    out
}

fn writes_into_tracked(path: &str) -> bool {
    let p = Path::new(path.trim_start_matches("./"));
    let first = p.components().next().and_then(|c| c.as_os_str().to_str());
    first.is_some_and(|f| TRACKED.contains(&f))
}

#[test]
fn doc_examples_write_under_out_not_into_tracked_files() {
    let mut docs = vec![root().join("README.md")];
    let mut md: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    md.sort();
    docs.extend(md);
    let mut bad = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(doc).unwrap();
        for (n, line) in text.lines().enumerate() {
            let Some(command) = line.trim_start().strip_prefix("$ ") else {
                continue;
            };
            // A check compares and writes nothing.
            if command.contains("--check") {
                continue;
            }
            for path in outputs(command) {
                if writes_into_tracked(&path) {
                    bad.push(format!(
                        "{}:{}: `{command}` writes {path}",
                        doc.strip_prefix(root()).unwrap().display(),
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(
        bad.is_empty(),
        "examples must write under out/ (git-ignored), not into tracked folders:\n  {}",
        bad.join("\n  ")
    );
    // The rule sees what it must.
    assert_eq!(
        outputs("sweep scene s.toml -o docs/figures"),
        ["docs/figures"]
    );
    assert!(writes_into_tracked("docs/figures") && writes_into_tracked("./tables/x.h5"));
    assert!(!writes_into_tracked("out/") && !writes_into_tracked("full.oblq"));
}
