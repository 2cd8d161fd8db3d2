//! A file size limit (`ulimit -f`, RLIMIT_FSIZE) reached while writing: the command reports it
//! (exit status 1, a message naming the file and the limit) instead of being killed by SIGXFSZ
//! (exit status 153, no message), removes its temporary and lock files, and leaves every
//! previous output as it was. The outputs of one command (a scene's CSV and plot) are all new
//! or all as they were.
#![cfg(unix)]

mod common;

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::subdir;

/// What the child does on SIGXFSZ before `sweep` starts.
#[derive(Clone, Copy)]
enum Xfsz {
    /// The default, kill: what a shell's `ulimit -f` leaves. `sweep` must ignore it itself.
    Default,
    /// Ignored, so that a write past the limit fails like one on a full disk.
    Ignored,
}

/// `sweep ARGS` in `dir`, its files limited to `bytes` bytes.
fn sweep_limited(dir: &Path, bytes: u64, xfsz: Xfsz, args: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_sweep"));
    cmd.args(args).current_dir(dir);
    // SAFETY: between fork and exec only async-signal-safe calls (signal, setrlimit) on values
    // owned by the closure.
    unsafe {
        cmd.pre_exec(move || {
            let handler = match xfsz {
                Xfsz::Default => libc::SIG_DFL,
                Xfsz::Ignored => libc::SIG_IGN,
            };
            libc::signal(libc::SIGXFSZ, handler);
            let limit = libc::rlimit {
                rlim_cur: bytes as libc::rlim_t,
                rlim_max: libc::RLIM_INFINITY,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.output().expect("run sweep")
}

fn sweep_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run sweep")
}

fn root() -> &'static str {
    env!("CARGO_MANIFEST_DIR")
}

/// The names in `dir` (and its sub-folders, as `sub/name`), sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir).expect("read folder") {
        let e = e.expect("entry");
        let name = e.file_name().to_string_lossy().into_owned();
        if e.file_type().expect("type").is_dir() {
            v.extend(names(&e.path()).into_iter().map(|n| format!("{name}/{n}")));
        } else {
            v.push(name);
        }
    }
    v.sort();
    v
}

/// The command failed with exit status 1 (not by a signal, not a panic), naming the file size
/// limit and `file`; nothing in `dir` is a temporary or lock file.
fn assert_reported(o: &Output, dir: &Path, file: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(1),
        "status {:?} (a signal when None): {err}",
        o.status
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains("file size limit"), "{err}");
    assert!(err.contains(file), "{err} does not name {file}");
    let left: Vec<String> = names(dir)
        .into_iter()
        .filter(|n| n.contains(".tmp") || n.ends_with(".lock"))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

const OLD: &[u8] = b"the previous contents";

#[test]
fn export_past_the_file_size_limit_reports_it_and_keeps_the_old_file() {
    let dir = subdir("export");
    let table = format!("{}/tables/quick.h5", root());
    for name in ["t.oblq", "t.c"] {
        // No file yet: none is created.
        let o = sweep_limited(&dir, 4096, Xfsz::Default, &["export", &table, "-o", name]);
        assert_reported(&o, &dir, name);
        assert!(!dir.join(name).exists());
        // A previous file: kept byte for byte.
        std::fs::write(dir.join(name), OLD).expect("write");
        let o = sweep_limited(&dir, 4096, Xfsz::Default, &["export", &table, "-o", name]);
        assert_reported(&o, &dir, name);
        assert_eq!(std::fs::read(dir.join(name)).expect("read"), OLD);
    }
}

#[test]
fn scene_past_the_file_size_limit_reports_it_and_keeps_the_old_files() {
    let dir = subdir("scene");
    let scene = format!("{}/configs/scenes/steel_on_steel.toml", root());
    let table = format!("{}/tables/quick.h5", root());
    let args = ["scene", &scene, "--table", &table, "-o", "out", "--svg"];
    let o = sweep_limited(&dir, 2048, Xfsz::Default, &args);
    assert_reported(&o, &dir, "steel_on_steel.csv");
    assert!(names(&dir).is_empty(), "{:?}", names(&dir));
    std::fs::create_dir_all(dir.join("out")).expect("create folder");
    for ext in ["csv", "png", "svg"] {
        std::fs::write(dir.join(format!("out/steel_on_steel.{ext}")), OLD).expect("write");
    }
    let o = sweep_limited(&dir, 2048, Xfsz::Default, &args);
    assert_reported(&o, &dir, "steel_on_steel.csv");
    for ext in ["csv", "png", "svg"] {
        let path = dir.join(format!("out/steel_on_steel.{ext}"));
        assert_eq!(std::fs::read(&path).expect("read"), OLD, "{ext}");
    }
}

/// The parts of a sharded build of configs/quick.toml in `dir`: `part1.bin`, `part2.bin`.
fn parts(dir: &Path) -> [PathBuf; 2] {
    let config = format!("{}/configs/quick.toml", root());
    [1, 2].map(|k| {
        let part = format!("part{k}.bin");
        let o = sweep_in(
            dir,
            &[
                "run",
                &config,
                "--shard",
                &format!("{k}/2"),
                "-o",
                &part,
                "--quiet",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        dir.join(part)
    })
}

#[test]
fn merge_past_the_file_size_limit_reports_it_and_keeps_the_old_table() {
    let dir = subdir("merge");
    parts(&dir);
    let args = ["merge", "part1.bin", "part2.bin", "-o", "t.h5", "--quiet"];
    // 0 bytes: not even the lock file's pid can be written; then the table's first blocks.
    for bytes in [0, 4096] {
        let o = sweep_limited(&dir, bytes, Xfsz::Default, &args);
        assert_reported(&o, &dir, "t.h5");
        assert_eq!(names(&dir), ["part1.bin", "part2.bin"], "limit {bytes}");
    }
    std::fs::write(dir.join("t.h5"), OLD).expect("write");
    let o = sweep_limited(&dir, 4096, Xfsz::Default, &args);
    assert_reported(&o, &dir, "t.h5");
    assert_eq!(std::fs::read(dir.join("t.h5")).expect("read"), OLD);
}

#[test]
fn run_past_the_file_size_limit_reports_it_and_keeps_the_old_table() {
    let dir = subdir("run");
    let config = format!("{}/configs/quick.toml", root());
    std::fs::write(dir.join("t.h5"), OLD).expect("write");
    // 0 bytes: the lock file; 4096: the checkpoint, which is kept for --resume.
    for (bytes, file) in [(0, "t.h5.lock"), (4096, "t.h5.ckpt")] {
        let o = sweep_limited(
            &dir,
            bytes,
            Xfsz::Default,
            &["run", &config, "-o", "t.h5", "--quiet", "--restart"],
        );
        assert_reported(&o, &dir, file);
        assert_eq!(std::fs::read(dir.join("t.h5")).expect("read"), OLD);
    }
}

/// The scene's CSV fits under the limit and its plot does not (as on a disk that fills up
/// after the CSV): the previous CSV and plot are both kept, not a new CSV beside an old plot.
#[test]
fn a_scene_is_replaced_whole_or_not_at_all() {
    let dir = subdir("scene-pair");
    let scene = format!("{}/configs/scenes/steel_on_steel.toml", root());
    let table = format!("{}/tables/quick.h5", root());
    let args = ["scene", &scene, "--table", &table, "-o", "out"];
    let o = sweep_in(&dir, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read(dir.join("out/steel_on_steel.csv")).expect("read");
    let png = std::fs::read(dir.join("out/steel_on_steel.png")).expect("read");
    let limit = csv.len() as u64 + 1024;
    assert!(
        png.len() as u64 > limit,
        "the plot must not fit under the limit"
    );
    for ext in ["csv", "png"] {
        std::fs::write(dir.join(format!("out/steel_on_steel.{ext}")), OLD).expect("write");
    }
    for xfsz in [Xfsz::Ignored, Xfsz::Default] {
        let o = sweep_limited(&dir, limit, xfsz, &args);
        for ext in ["csv", "png"] {
            let path = dir.join(format!("out/steel_on_steel.{ext}"));
            assert_eq!(std::fs::read(&path).expect("read"), OLD, "{ext}");
        }
        assert_reported(&o, &dir, "steel_on_steel.png");
    }
    // Without a limit both are replaced.
    let o = sweep_in(&dir, &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(dir.join("out/steel_on_steel.csv")).expect("read"),
        csv
    );
    assert_eq!(
        std::fs::read(dir.join("out/steel_on_steel.png")).expect("read"),
        png
    );
}
