//! Scratch directories shared by the end-to-end tests (`mod common;` in each test file).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

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
