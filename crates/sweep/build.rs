//! Records the git commit of the engine for table provenance.
//!
//! Reruns only when the repository's HEAD, index or refs change: the paths are the git
//! directory's own (absolute), so that cargo finds them; relative to this crate's folder they
//! would never exist and the script would rerun, and the binary relink, on every build. A
//! commit rewrites the branch's ref file (`refs/heads/NAME`) and appends to `logs/HEAD`, but
//! changes neither `HEAD` nor the mtime of the folder `refs`: both are watched too, or a binary
//! built before a commit would keep naming the earlier commit. The workspace's sources
//! (`crates/`, `Cargo.toml`, `Cargo.lock`) are watched as well: an edit that is not yet
//! committed changes none of git's files, and a binary built from it must say `-dirty`, not
//! name the commit it does not match.
use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    // No optional locks: `git status` would otherwise refresh and rewrite the index, whose
    // change makes the next build rerun this script.
    Command::new("git")
        .args(args)
        .env("GIT_OPTIONAL_LOCKS", "0")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
}

fn main() {
    let commit = git(&["rev-parse", "HEAD"]).unwrap_or_else(|| "unknown".into());
    let dirty =
        git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    let suffix = if dirty { "-dirty" } else { "" };
    println!("cargo:rustc-env=OBLIQUE_GIT_COMMIT={commit}{suffix}");
    println!("cargo:rerun-if-changed=build.rs");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for name in ["crates", "Cargo.toml", "Cargo.lock"] {
        let path = root.join(name);
        if path.exists() {
            println!("cargo:rerun-if-changed={}", path.display());
        }
    }
    if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        let branch = git(&["symbolic-ref", "-q", "HEAD"]);
        let names = ["HEAD", "index", "refs", "packed-refs", "logs/HEAD"];
        for name in names.iter().copied().chain(branch.as_deref()) {
            let path = std::path::Path::new(&dir).join(name);
            if path.exists() {
                println!("cargo:rerun-if-changed={}", path.display());
            }
        }
    }
}
