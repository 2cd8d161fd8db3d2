//! Files written under a temporary name and renamed over their targets once complete, one
//! at a time ([`write_with`], [`write_via_path`]) or as a set ([`Files`]).

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::paths::{
    backup_path, check_output, remove_stale_temporaries, sync_folder, temporary_path,
};
use crate::size_limit::{file_size_limit, mentions_file_too_large, FileSizeLimit};
use crate::{io_error, OutputError};

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
    pub(crate) fn write_through<W: Write>(
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
    pub(crate) fn commit_by(
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
pub(crate) fn write_through<W: Write>(
    path: &Path,
    wrap: impl FnOnce(File) -> W,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), OutputError> {
    let mut files = Files::new();
    files.write_through(path, wrap, write)?;
    files.commit()
}
