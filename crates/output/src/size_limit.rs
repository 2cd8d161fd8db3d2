//! Writes past the largest file allowed (EFBIG): the process's file size limit and the error
//! that names it.

use thiserror::Error;

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
pub(crate) fn mentions_file_too_large(message: &str) -> bool {
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
