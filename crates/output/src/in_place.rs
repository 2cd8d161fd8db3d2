//! Files that grow in place (checkpoints, lock files): opened, never replaced.

use std::fs::{File, OpenOptions};
use std::path::Path;

use crate::paths::{check_output, non_file_kind};
use crate::{io_error, OutputError, OutputPathError};

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
