//! The targets: which paths may be written (regular files, none of the inputs), the temporary
//! names beside a target, and the removal of those that killed writers left.

use std::fs::File;
use std::path::{Path, PathBuf};

use crate::OutputPathError;

/// What is at `path` in words ("a directory", "a FIFO", …), when it is not a regular file;
/// `None` for a regular file. A symbolic link is reported as one (with its target), never
/// followed.
pub(crate) fn non_file_kind(meta: &std::fs::Metadata, path: &Path) -> Option<String> {
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
pub(crate) fn backup_path(path: &Path) -> PathBuf {
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
pub(crate) fn sync_folder(path: &Path) {
    if let Ok(dir) = File::open(folder(path)) {
        let _ = dir.sync_all();
    }
}
