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

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use thiserror::Error;

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

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> OutputError + '_ {
    move |source| OutputError::Io {
        path: path.display().to_string(),
        source: explain_io(source),
    }
}

/// A write that went past the largest file allowed (EFBIG): the process's file size limit
/// (`ulimit -f`, RLIMIT_FSIZE) when it has one, else the file system's largest file.
#[derive(Debug, Error)]
pub struct FileSizeLimit {
    /// The process's file size limit in bytes when it was reached; `None`: no limit is set, the
    /// file system refused the size.
    pub limit: Option<u64>,
}

impl std::fmt::Display for FileSizeLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.limit {
            Some(n) => write!(
                f,
                "file size limit reached: this process may write files of at most {n} bytes \
                 (ulimit -f, RLIMIT_FSIZE); raise the limit or write elsewhere"
            ),
            None => write!(f, "file too large for the file system (EFBIG)"),
        }
    }
}

/// The soft file size limit of this process (RLIMIT_FSIZE, `ulimit -f`) in bytes; `None` when
/// there is none.
pub fn file_size_limit() -> Option<u64> {
    #[cfg(unix)]
    {
        let mut r = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit writes into the struct we own; no other memory is touched.
        let rc = unsafe { libc::getrlimit(libc::RLIMIT_FSIZE, &mut r) };
        if rc == 0 && r.rlim_cur != libc::RLIM_INFINITY {
            // `rlim_t` is `u64` on Linux, narrower or signed on some other systems.
            #[allow(clippy::useless_conversion)]
            return u64::try_from(r.rlim_cur).ok();
        }
    }
    None
}

/// `e`, or for a write past the largest file allowed (EFBIG) an error of the same kind
/// ([`std::io::ErrorKind::FileTooLarge`]) whose message is [`FileSizeLimit`]'s: it names the
/// limit instead of the bare "File too large". For the writers of files outside this crate
/// (checkpoint records, lock files), so that their errors read like this crate's.
pub fn explain_io(e: std::io::Error) -> std::io::Error {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::EFBIG) {
        return std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            FileSizeLimit {
                limit: file_size_limit(),
            },
        );
    }
    e
}

/// Whether the message of a writer's error (a library that reports its I/O errors as text,
/// such as HDF5 or an image encoder) says that a write went past the largest file allowed:
/// it contains this process's own text for EFBIG ("File too large" from `strerror`).
fn mentions_file_too_large(message: &str) -> bool {
    #[cfg(unix)]
    {
        let text = std::io::Error::from_raw_os_error(libc::EFBIG).to_string();
        let bare = text.split(" (os error").next().unwrap_or(&text);
        !bare.is_empty() && message.contains(bare)
    }
    #[cfg(not(unix))]
    {
        let _ = message;
        false
    }
}

/// What is at `path` in words ("a directory", "a FIFO", …), when it is not a regular file;
/// `None` for a regular file. A symbolic link is reported as one (with its target), never
/// followed.
fn non_file_kind(meta: &std::fs::Metadata, path: &Path) -> Option<String> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)".into());
        }
        if t.is_char_device() {
            return Some("a character device".into());
        }
        if t.is_block_device() {
            return Some("a block device".into());
        }
        if t.is_socket() {
            return Some("a socket".into());
        }
    }
    Some(if t.is_dir() {
        "a directory".into()
    } else if t.is_symlink() {
        match std::fs::read_link(path) {
            Ok(target) => format!("a symbolic link (to {})", target.display()),
            Err(_) => "a symbolic link".into(),
        }
    } else {
        "not a regular file".into()
    })
}

/// Check that `path` may be written as an output file: it does not exist, or it is a regular
/// file (not a directory, symbolic link, FIFO, device or socket, which writing would replace or
/// write into).
pub fn check_output(path: &Path) -> Result<(), OutputPathError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) => match non_file_kind(&meta, path) {
            None => Ok(()),
            Some(kind) => Err(OutputPathError::NotAFile {
                path: path.display().to_string(),
                kind,
            }),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(source) => Err(OutputPathError::Io {
            path: path.display().to_string(),
            source,
        }),
    }
}

/// [`check_output`], and that `path` is none of `inputs` (compared by device and inode, so
/// another name or a hard link of an input is caught too).
pub fn check_output_not_input(path: &Path, inputs: &[&Path]) -> Result<(), OutputPathError> {
    check_output(path)?;
    let Ok(out) = std::fs::metadata(path) else {
        return Ok(());
    };
    for input in inputs {
        if std::fs::metadata(input).is_ok_and(|m| same_file(&m, &out)) {
            return Err(OutputPathError::IsInput {
                path: path.display().to_string(),
                input: input.display().to_string(),
            });
        }
    }
    Ok(())
}

#[cfg(unix)]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_file(_: &std::fs::Metadata, _: &std::fs::Metadata) -> bool {
    false
}

/// The folder of `path` (`.` for a bare file name).
fn folder(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned())
}

/// The temporary name this process writes `path` under: `.NAME.tmp-PID` beside it, with the
/// target's extension appended (`.p_surface.png.tmp-PID.png`) so that writers which choose the
/// format by the extension write the right one.
pub fn temporary_path(path: &Path) -> PathBuf {
    let mut name = format!(".{}.tmp-{}", file_name(path), std::process::id());
    if let Some(ext) = path.extension() {
        name.push('.');
        name.push_str(&ext.to_string_lossy());
    }
    folder(path).join(name)
}

/// The name under which [`Files::commit`] keeps the previous `path` (a hard link to it) until
/// every file of the set is in place: `.NAME.tmp-PID-old` beside it.
fn backup_path(path: &Path) -> PathBuf {
    folder(path).join(format!(
        ".{}.tmp-{}-old",
        file_name(path),
        std::process::id()
    ))
}

/// Remove the temporary files that writers of `path` left when they were killed (kill -9, a
/// power cut): `.NAME.tmp-PID[.EXT]` (also `.NAME.tmpPID`, an older export's, and
/// `.NAME.tmp-PID-old`, the link to a previous file that [`Files::commit`] keeps while it
/// renames) whose process no longer runs (Linux: no `/proc/PID`). A running writer's file, and
/// anything else, is left alone. Best effort: errors are ignored.
pub fn remove_stale_temporaries(path: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let prefix = format!(".{}.tmp", file_name(path));
    let Ok(entries) = std::fs::read_dir(folder(path)) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(rest) = name.to_str().and_then(|n| n.strip_prefix(&prefix)) else {
            continue;
        };
        let rest = rest.strip_prefix('-').unwrap_or(rest);
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let tail = &rest[digits.len()..];
        let ours = tail == "-old"
            || match path.extension() {
                Some(ext) => tail.is_empty() || tail == format!(".{}", ext.to_string_lossy()),
                None => tail.is_empty(),
            };
        let Ok(pid) = digits.parse::<u32>() else {
            continue;
        };
        let running = pid == std::process::id() || Path::new(&format!("/proc/{pid}")).exists();
        if ours && !running {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Sync the folder of `path`, so that a rename in it survives a power cut. Best effort (some
/// file systems refuse to sync a folder).
fn sync_folder(path: &Path) {
    if let Ok(dir) = File::open(folder(path)) {
        let _ = dir.sync_all();
    }
}

/// Write the file at `path` by a writer that creates it itself at the path it is given (a
/// library such as HDF5, or an image encoder that chooses the format by the extension):
/// `write` gets the temporary path ([`temporary_path`]); once it returns `Ok`, the file there is
/// synced and renamed over `path`. On any error the temporary file is removed and `path` is
/// left as it was.
///
/// Such writers report their I/O errors as text: an error whose text says that a write went
/// past the largest file allowed (EFBIG) is replaced by an [`OutputError::Io`] that names the
/// file size limit ([`explain_io`]).
pub fn write_via_path<E: From<OutputError> + std::fmt::Display>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    let mut files = Files::new();
    files.write_via_path(path, write)?;
    files.commit().map_err(E::from)
}

/// A file of a [`Files`] set: written and synced at `tmp`, not yet renamed over `target`.
#[derive(Debug)]
struct Staged {
    target: PathBuf,
    tmp: PathBuf,
}

/// Files that are replaced together: each is written to its temporary file beside its target
/// (as [`write_with`] and [`write_via_path`] do), and [`Files::commit`] renames them over their
/// targets only once all are complete. So a failure while writing any of them (a full disk, the
/// file size limit, a failed drawing) leaves every target as it was.
///
/// While renaming, [`Files::commit`] keeps a hard link to each previous target; should a
/// rename fail after others succeeded (a rename in a folder writes no file data, so this is
/// rare), the previous files are put back. Where the file system has no hard links, a target
/// already renamed then stays new. A process killed during the renames (a few system calls)
/// can leave some targets new; the links it kept are removed by the next write of the same
/// targets.
///
/// Dropping a set without committing it removes its temporary files.
#[derive(Debug, Default)]
pub struct Files {
    staged: Vec<Staged>,
}

impl Files {
    /// An empty set.
    pub fn new() -> Files {
        Files::default()
    }

    /// Write the file of `path` by a writer that creates it at the path it is given (see
    /// [`write_via_path`]), to be renamed over `path` by [`Files::commit`]. On an error, this
    /// file's temporary is removed (the others of the set are kept until the set is dropped).
    pub fn write_via_path<E: From<OutputError> + std::fmt::Display>(
        &mut self,
        path: &Path,
        write: impl FnOnce(&Path) -> Result<(), E>,
    ) -> Result<(), E> {
        check_output(path).map_err(OutputError::from)?;
        if self.staged.iter().any(|s| s.target == path) {
            // The same target twice: the later content wins; the earlier one's file goes.
            self.discard(path);
        }
        remove_stale_temporaries(path);
        let tmp = temporary_path(path);
        // What a killed process with this pid left; `create_new` below must not meet it.
        let _ = std::fs::remove_file(&tmp);
        let result = write(&tmp)
            .map_err(|e| {
                if mentions_file_too_large(&e.to_string()) {
                    E::from(OutputError::Io {
                        path: path.display().to_string(),
                        source: std::io::Error::new(
                            std::io::ErrorKind::FileTooLarge,
                            FileSizeLimit {
                                limit: file_size_limit(),
                            },
                        ),
                    })
                } else {
                    e
                }
            })
            .and_then(|()| {
                File::open(&tmp)
                    .and_then(|f| f.sync_all())
                    .map_err(|e| E::from(io_error(path)(e)))
            });
        match result {
            Ok(()) => {
                self.staged.push(Staged {
                    target: path.to_path_buf(),
                    tmp,
                });
                Ok(())
            }
            Err(e) => {
                let _ = std::fs::remove_file(&tmp);
                Err(e)
            }
        }
    }

    /// Write the file of `path` with `write`, which gets a buffered writer (see
    /// [`write_with`]), to be renamed over `path` by [`Files::commit`].
    pub fn write_with(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        self.write_through(path, |f| f, write)
    }

    /// Write `bytes` as the file of `path` ([`Files::write_with`]).
    pub fn write_bytes(&mut self, path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
        self.write_with(path, |w| w.write_all(bytes))
    }

    /// [`Files::write_with`], the bytes going to the temporary file through `wrap` (tests inject
    /// write errors with it).
    fn write_through<W: Write>(
        &mut self,
        path: &Path,
        wrap: impl FnOnce(File) -> W,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        self.write_via_path(path, |tmp| {
            let file = OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(tmp)
                .map_err(io_error(path))?;
            let mut w = BufWriter::new(wrap(file));
            write(&mut w)
                .and_then(|()| w.flush())
                .map_err(io_error(path))
        })
    }

    /// Remove the staged file of `target`.
    fn discard(&mut self, target: &Path) {
        self.staged.retain(|s| {
            if s.target == target {
                let _ = std::fs::remove_file(&s.tmp);
                false
            } else {
                true
            }
        });
    }

    /// Put every file of the set in place: each target is checked again (it may have changed
    /// while the files were written), then the files are renamed over their targets and their
    /// folders synced. On an error every target is as it was (see [`Files`]) and no temporary
    /// file is left.
    pub fn commit(self) -> Result<(), OutputError> {
        self.commit_by(|from, to| std::fs::rename(from, to))
    }

    /// [`Files::commit`] with the rename given (tests make one fail).
    fn commit_by(
        mut self,
        mut rename: impl FnMut(&Path, &Path) -> std::io::Result<()>,
    ) -> Result<(), OutputError> {
        let staged = std::mem::take(&mut self.staged);
        let remove_all = |staged: &[Staged]| {
            for s in staged {
                let _ = std::fs::remove_file(&s.tmp);
            }
        };
        // Checked again just before the renames: the writes may have taken a while.
        for s in &staged {
            if let Err(e) = check_output(&s.target) {
                remove_all(&staged);
                return Err(e.into());
            }
        }
        // A single file needs no backup: its rename is atomic.
        let keep_old = staged.len() > 1;
        let mut done: Vec<(&Staged, Before)> = Vec::with_capacity(staged.len());
        let mut failure = None;
        for s in &staged {
            let before = if !keep_old {
                Before::Unknown
            } else if std::fs::symlink_metadata(&s.target).is_err() {
                Before::Absent
            } else {
                let b = backup_path(&s.target);
                let _ = std::fs::remove_file(&b);
                match std::fs::hard_link(&s.target, &b) {
                    Ok(()) => Before::Linked(b),
                    Err(_) => Before::Unknown,
                }
            };
            match rename(&s.tmp, &s.target) {
                Ok(()) => done.push((s, before)),
                Err(e) => {
                    if let Before::Linked(b) = before {
                        let _ = std::fs::remove_file(b);
                    }
                    failure = Some(io_error(&s.target)(e));
                    break;
                }
            }
        }
        if let Some(e) = failure {
            // Put back what was there before, the last renamed first.
            for (s, before) in done.iter().rev() {
                match before {
                    Before::Linked(b) => {
                        let _ = std::fs::rename(b, &s.target);
                    }
                    Before::Absent => {
                        let _ = std::fs::remove_file(&s.target);
                    }
                    Before::Unknown => {}
                }
            }
            remove_all(&staged);
            return Err(e);
        }
        for (s, before) in &done {
            if let Before::Linked(b) = before {
                let _ = std::fs::remove_file(b);
            }
            sync_folder(&s.target);
        }
        Ok(())
    }
}

/// What a target of [`Files::commit`] was before its rename, to put it back.
enum Before {
    /// A file, kept at this hard link.
    Linked(PathBuf),
    /// Nothing: the new file is removed.
    Absent,
    /// Not kept (a single file, or no hard links): the new file stays.
    Unknown,
}

impl Drop for Files {
    /// A set dropped without [`Files::commit`] (an error while writing one of its files)
    /// removes the temporary files of those written.
    fn drop(&mut self) {
        for s in &self.staged {
            let _ = std::fs::remove_file(&s.tmp);
        }
    }
}

/// Write the file at `path` with `write`, which gets a buffered writer: see the crate's
/// documentation. On any error, of `write` or of the disk, `path` is left as it was and no
/// temporary file remains.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), OutputError> {
    let mut files = Files::new();
    files.write_with(path, write)?;
    files.commit()
}

/// Write `bytes` to the file at `path` ([`write_with`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_with(path, |w| w.write_all(bytes))
}

/// [`write_with`], the bytes going to the temporary file through `wrap` (tests inject write
/// errors with it).
#[cfg(test)]
fn write_through<W: Write>(
    path: &Path,
    wrap: impl FnOnce(File) -> W,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), OutputError> {
    let mut files = Files::new();
    files.write_through(path, wrap, write)?;
    files.commit()
}

/// Open the regular file at `path` for reading and writing in place, without truncating it
/// (`create`: create it when missing): for files that grow record by record (checkpoints) or
/// are locked (lock files), which a rename cannot replace. Refuses what [`check_output`]
/// refuses, and never follows a symbolic link.
pub fn open_in_place(path: &Path, create: bool) -> Result<File, OutputError> {
    check_output(path)?;
    let mut options = OpenOptions::new();
    options.read(true).write(true).create(create);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| {
        if e.raw_os_error() == Some(libc::ELOOP) {
            // A symbolic link appeared after the check.
            OutputError::from(check_output(path).err().unwrap_or(OutputPathError::Io {
                path: path.display().to_string(),
                source: e,
            }))
        } else {
            io_error(path)(e)
        }
    })?;
    let meta = file.metadata().map_err(io_error(path))?;
    if let Some(kind) = non_file_kind(&meta, path) {
        return Err(OutputPathError::NotAFile {
            path: path.display().to_string(),
            kind,
        }
        .into());
    }
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;

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
