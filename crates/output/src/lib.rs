//! Every file the program writes goes through this crate.
//!
//! A file is written under a temporary name beside its target (`.NAME.tmp-PID`, plus `.EXT`
//! when the target has an extension, for writers that choose a format by it), synced to disk,
//! and renamed over the target only once it is complete; the folder is synced after the
//! rename. So on any error (a full disk, a failed drawing, a killed process) the target is
//! either what it was before or the complete new file, and no partial file is left under the
//! target's name; the temporary file is removed on every error this process sees, and one left
//! by a killed writer is removed by the next write of the same target.
//!
//! A target that exists and is not a regular file (a directory, a symbolic link, a FIFO, a
//! device, a socket) is refused before anything is written, and again just before the rename:
//! writing would replace it or write into it.
//!
//! The outputs of one command that belong together (a scene's CSV and its plot) are written as
//! one [`Files`]: each to its temporary file, and none is renamed over its target before all are
//! complete, so the targets are all new or all as they were.
//!
//! A write past the file size limit (`ulimit -f`, RLIMIT_FSIZE; the program ignores SIGXFSZ, so
//! the write fails with EFBIG instead of killing it) is an I/O error like a full disk, whose
//! message names the file and the limit ([`explain_io`]).
//!
//! Files that grow in place (checkpoints, lock files) cannot be replaced by a rename; they are
//! opened with [`open_in_place`], which refuses the same targets and never follows a symbolic
//! link.
//!
//! Where: the targets and their temporary names in `paths.rs`, the writes and the sets in
//! `files.rs`, the file size limit in `size_limit.rs`, files opened in place in `in_place.rs`.

mod files;
mod in_place;
mod paths;
mod size_limit;

use std::path::Path;

use thiserror::Error;

pub use files::{write_bytes, write_via_path, write_with, Files};
pub use in_place::open_in_place;
pub use paths::{check_output, check_output_not_input, remove_stale_temporaries, temporary_path};
pub use size_limit::{explain_io, file_size_limit, FileSizeLimit};

/// An output path that cannot be written: the caller must give another one.
#[derive(Debug, Error)]
pub enum OutputPathError {
    /// The path exists and is not a regular file (writing would replace or write into it).
    #[error("output {path} is {kind}, not a regular file; give the path of a file")]
    NotAFile {
        /// The path.
        path: String,
        /// What is there, e.g. "a directory", "a symbolic link (to /x)", "a FIFO".
        kind: String,
    },
    /// The path is (through any name or hard link) one of the files being read.
    #[error("output {path} is the input {input}; give another output path")]
    IsInput {
        /// The output path.
        path: String,
        /// The input it is the same file as.
        input: String,
    },
    /// The path could not be examined.
    #[error("output {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
}

impl OutputPathError {
    /// Always true: the caller chose the path.
    pub fn user_can_fix(&self) -> bool {
        true
    }
}

/// A file that could not be written. The target is as it was before, and no temporary file is
/// left.
#[derive(Debug, Error)]
pub enum OutputError {
    /// The target cannot be written (see [`OutputPathError`]).
    #[error(transparent)]
    Path(#[from] OutputPathError),
    /// Writing, syncing or renaming failed (a full disk, a file size limit, permissions).
    #[error("cannot write {path}: {source}")]
    Io {
        /// The target.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
}

impl OutputError {
    /// Whether the caller can fix it by giving another path (not: a failed write).
    pub fn user_can_fix(&self) -> bool {
        matches!(self, OutputError::Path(_))
    }
}

/// The [`OutputError::Io`] of a failed write of `path`, its cause explained ([`explain_io`]).
fn io_error(path: &Path) -> impl Fn(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.display().to_string(),
        source: explain_io(source),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::write_through;
    use crate::size_limit::mentions_file_too_large;
    use std::io::Write;
    use std::path::PathBuf;

    /// A writer that accepts `left` bytes, then fails like a full disk.
    struct FailAfter<W> {
        inner: W,
        left: usize,
    }

    impl<W: Write> Write for FailAfter<W> {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            if self.left == 0 {
                return Err(std::io::Error::from_raw_os_error(libc::ENOSPC));
            }
            let n = buf.len().min(self.left);
            let n = self.inner.write(&buf[..n])?;
            self.left -= n;
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            self.inner.flush()
        }
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("oblique-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch folder");
        dir
    }

    /// The process id of a child that has exited (a writer killed before it cleaned up).
    #[cfg(target_os = "linux")]
    fn dead_pid() -> u32 {
        let mut child = std::process::Command::new("true").spawn().expect("spawn");
        let pid = child.id();
        child.wait().expect("wait");
        pid
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .expect("read folder")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_failing_write_leaves_the_target_as_it_was_and_no_temporary_file() {
        let dir = scratch("fail");
        let big = vec![7u8; 100_000];
        for n in [0, 1, 4096, 8192, 99_999] {
            // An existing target keeps its bytes.
            let target = dir.join("table.csv");
            std::fs::write(&target, b"old contents").expect("write");
            let r = write_through(
                &target,
                |f| FailAfter { inner: f, left: n },
                |w| w.write_all(&big),
            );
            let e = r.expect_err("the write must fail");
            assert!(!e.user_can_fix(), "{e}");
            assert!(e.to_string().contains("table.csv"), "{e}");
            assert_eq!(std::fs::read(&target).expect("read"), b"old contents");
            assert_eq!(names(&dir), ["table.csv"], "after failing at {n} bytes");
            // A new target is not created.
            std::fs::remove_file(&target).expect("remove");
            let r = write_through(
                &target,
                |f| FailAfter { inner: f, left: n },
                |w| w.write_all(&big),
            );
            assert!(r.is_err());
            assert!(names(&dir).is_empty(), "after failing at {n} bytes");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_error_of_the_writer_itself_leaves_nothing() {
        let dir = scratch("writer");
        let target = dir.join("a.bin");
        std::fs::write(&target, b"keep").expect("write");
        let r = write_with(&target, |w| {
            w.write_all(&[1; 50_000])?;
            Err(std::io::Error::other("drawing failed"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&target).expect("read"), b"keep");
        // A writer that makes its own file and fails after writing part of it.
        #[derive(Debug)]
        struct Failed;
        impl std::fmt::Display for Failed {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("failed")
            }
        }
        impl From<OutputError> for Failed {
            fn from(_: OutputError) -> Self {
                Failed
            }
        }
        let r = write_via_path(&target, |tmp| {
            std::fs::write(tmp, b"half").expect("write");
            Err::<(), Failed>(Failed)
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&target).expect("read"), b"keep");
        assert_eq!(names(&dir), ["a.bin"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_complete_write_replaces_the_target_and_leaves_no_temporary_file() {
        let dir = scratch("ok");
        let target = dir.join("figure.png");
        std::fs::write(&target, b"old").expect("write");
        let seen = std::cell::Cell::new(PathBuf::new());
        write_via_path(&target, |tmp| {
            seen.set(tmp.to_path_buf());
            std::fs::write(tmp, b"new").map_err(|e| OutputError::Io {
                path: String::new(),
                source: e,
            })
        })
        .expect("write");
        let tmp = seen.take();
        assert_eq!(tmp.extension().and_then(|e| e.to_str()), Some("png"));
        assert!(tmp
            .file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with(".figure.png.tmp-"));
        assert_eq!(std::fs::read(&target).expect("read"), b"new");
        write_bytes(&dir.join("b.csv"), b"x,y\n").expect("write");
        assert_eq!(names(&dir), ["b.csv", "figure.png"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(unix)]
    #[test]
    fn special_targets_are_refused_and_left_alone() {
        use std::os::unix::fs::FileTypeExt;
        let dir = scratch("special");
        let link = dir.join("link.csv");
        std::os::unix::fs::symlink(dir.join("elsewhere.csv"), &link).expect("symlink");
        let fifo = dir.join("fifo.csv");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .expect("mkfifo");
        assert!(made.success());
        let sub = dir.join("sub.csv");
        std::fs::create_dir(&sub).expect("mkdir");
        for (target, what) in [
            (&link, "symbolic link"),
            (&fifo, "FIFO"),
            (&sub, "directory"),
        ] {
            let e = write_bytes(target, b"data").expect_err("refused");
            assert!(e.user_can_fix() && e.to_string().contains(what), "{e}");
            let e = open_in_place(target, true).expect_err("refused");
            assert!(e.to_string().contains(what), "{e}");
        }
        assert!(!dir.join("elsewhere.csv").exists());
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
        assert_eq!(names(&dir), ["fifo.csv", "link.csv", "sub.csv"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn temporaries_of_killed_writers_are_removed_and_others_kept() {
        let dir = scratch("stale");
        let dead = dead_pid();
        let target = dir.join("t.h5");
        let stale = [
            format!(".t.h5.tmp-{dead}"),
            format!(".t.h5.tmp-{dead}.h5"),
            format!(".t.h5.tmp{dead}"),
        ];
        for s in &stale {
            std::fs::write(dir.join(s), b"half").expect("write");
        }
        // Another extension, another target's: not this writer's.
        let keep = [format!(".t.h5.tmp-{dead}.h5x"), ".u.h5.tmp-1".to_string()];
        for k in &keep {
            std::fs::write(dir.join(k), b"other").expect("write");
        }
        write_bytes(&target, b"table").expect("write");
        let mut want = vec![keep[0].clone(), keep[1].clone(), "t.h5".to_string()];
        want.sort();
        assert_eq!(names(&dir), want);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_set_is_written_whole_or_not_at_all() {
        let dir = scratch("set");
        let (csv, png) = (dir.join("scene.csv"), dir.join("scene.png"));
        std::fs::write(&csv, b"old csv").expect("write");
        std::fs::write(&png, b"old png").expect("write");
        // The second file fails (a full disk): the first, complete, is not put in place.
        let mut files = Files::new();
        files.write_bytes(&csv, b"new csv").expect("staged");
        let e = files
            .write_through(
                &png,
                |f| FailAfter { inner: f, left: 3 },
                |w| w.write_all(b"new png"),
            )
            .expect_err("the write must fail");
        assert!(e.to_string().contains("scene.png"), "{e}");
        drop(files);
        assert_eq!(std::fs::read(&csv).expect("read"), b"old csv");
        assert_eq!(std::fs::read(&png).expect("read"), b"old png");
        assert_eq!(names(&dir), ["scene.csv", "scene.png"]);
        // Both complete: both replaced.
        let mut files = Files::new();
        files.write_bytes(&csv, b"new csv").expect("staged");
        files.write_bytes(&png, b"new png").expect("staged");
        assert_eq!(std::fs::read(&csv).expect("read"), b"old csv");
        files.commit().expect("commit");
        assert_eq!(std::fs::read(&csv).expect("read"), b"new csv");
        assert_eq!(std::fs::read(&png).expect("read"), b"new png");
        assert_eq!(names(&dir), ["scene.csv", "scene.png"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failed_rename_puts_back_the_files_renamed_before_it() {
        let dir = scratch("rename");
        let (a, b, c) = (dir.join("a.csv"), dir.join("b.png"), dir.join("c.svg"));
        std::fs::write(&a, b"old a").expect("write");
        std::fs::write(&b, b"old b").expect("write");
        // `c` is new: after the failure it must not exist.
        for fail_at in [1, 2] {
            let mut files = Files::new();
            files.write_bytes(&c, b"new c").expect("staged");
            files.write_bytes(&a, b"new a").expect("staged");
            files.write_bytes(&b, b"new b").expect("staged");
            let mut n = 0;
            let e = files
                .commit_by(|from, to| {
                    n += 1;
                    if n > fail_at {
                        Err(std::io::Error::from_raw_os_error(libc::ENOSPC))
                    } else {
                        std::fs::rename(from, to)
                    }
                })
                .expect_err("a rename fails");
            assert!(!e.user_can_fix(), "{e}");
            assert_eq!(
                std::fs::read(&a).expect("read"),
                b"old a",
                "fail at {fail_at}"
            );
            assert_eq!(
                std::fs::read(&b).expect("read"),
                b"old b",
                "fail at {fail_at}"
            );
            assert_eq!(names(&dir), ["a.csv", "b.png"], "fail at {fail_at}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_target_that_changed_while_writing_stops_the_whole_set() {
        let dir = scratch("changed");
        let (a, b) = (dir.join("a.csv"), dir.join("b.png"));
        std::fs::write(&a, b"old a").expect("write");
        let mut files = Files::new();
        files.write_bytes(&a, b"new a").expect("staged");
        files.write_bytes(&b, b"new b").expect("staged");
        std::fs::create_dir(&b).expect("mkdir");
        let e = files.commit().expect_err("refused");
        assert!(
            e.user_can_fix() && e.to_string().contains("directory"),
            "{e}"
        );
        assert_eq!(std::fs::read(&a).expect("read"), b"old a");
        assert_eq!(names(&dir), ["a.csv", "b.png"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(unix)]
    #[test]
    fn a_write_past_the_size_limit_names_the_limit() {
        let e = explain_io(std::io::Error::from_raw_os_error(libc::EFBIG));
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
        assert_ne!(
            e.to_string(),
            std::io::Error::from_raw_os_error(libc::EFBIG).to_string()
        );
        let limited = FileSizeLimit { limit: Some(10240) }.to_string();
        assert!(
            limited.contains("file size limit") && limited.contains("10240 bytes"),
            "{limited}"
        );
        // Other errors are kept as they are.
        let other = explain_io(std::io::Error::from_raw_os_error(libc::ENOSPC));
        assert_eq!(other.raw_os_error(), Some(libc::ENOSPC));
        // A writer's error text: HDF5's and an image encoder's wording of EFBIG.
        assert!(mentions_file_too_large(
            "file write failed: errno = 27, error message = 'File too large'"
        ));
        assert!(mentions_file_too_large(
            "ImageError(IoError(Custom { kind: Other, error: \"File too large (os error 27)\" }))"
        ));
        assert!(!mentions_file_too_large(
            "No space left on device (os error 28)"
        ));
        // Through a writer: the error names the file and the limit (or the file system's).
        let dir = scratch("efbig");
        let target = dir.join("t.bin");
        std::fs::write(&target, b"old").expect("write");
        /// A file that refuses every byte like one at the size limit.
        struct AtLimit;
        impl Write for AtLimit {
            fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
                Err(std::io::Error::from_raw_os_error(libc::EFBIG))
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let e =
            write_through(&target, |_| AtLimit, |w| w.write_all(&[0; 10])).expect_err("too large");
        let text = e.to_string();
        assert!(text.contains("t.bin") && text.contains("file"), "{text}");
        assert!(
            text.contains("file size limit") || text.contains("file system"),
            "{text}"
        );
        assert_eq!(std::fs::read(&target).expect("read"), b"old");
        assert_eq!(names(&dir), ["t.bin"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn links_to_previous_files_left_by_a_killed_commit_are_removed() {
        let dir = scratch("oldlink");
        let dead = dead_pid();
        std::fs::write(dir.join(format!(".s.csv.tmp-{dead}-old")), b"old").expect("write");
        write_bytes(&dir.join("s.csv"), b"new").expect("write");
        assert_eq!(names(&dir), ["s.csv"]);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn open_in_place_keeps_the_contents() {
        let dir = scratch("inplace");
        let p = dir.join("run.ckpt");
        assert!(open_in_place(&p, false).is_err());
        let mut f = open_in_place(&p, true).expect("create");
        f.write_all(b"head").expect("write");
        drop(f);
        let mut f = open_in_place(&p, false).expect("open");
        use std::io::{Seek, SeekFrom};
        f.seek(SeekFrom::End(0)).expect("seek");
        f.write_all(b"+rec").expect("write");
        assert_eq!(std::fs::read(&p).expect("read"), b"head+rec");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
