//! The default table, built into the library: `tables/default.h5` (`configs/default.toml`:
//! `P(γ, α, e_n)` of the Kelvin–Voigt law for `1.3 ≤ γ ≤ 2.2`, every α from 0 to ∞ and
//! `0.3 ≤ e_n ≤ 1`; about 3.6 MB), so that a program answers `P` with no table file at hand
//! ([`Table::embedded`]): `sweep query` without a table, and the Python package's
//! `oblique.Table()`. That γ range holds every body of the material catalogue (solid spheres,
//! thin shells and pairs of them) and every solid sphere of one isotropic material.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::{LookupError, Table};

/// The shipped table built in, as the repository names it.
pub const EMBEDDED_TABLE: &str = "tables/default.h5";

/// Its bytes (the HDF5 file as committed).
static BYTES: &[u8] = include_bytes!("../../../tables/default.h5");

/// How the built-in table is named in messages and provenance: `built-in tables/default.h5`.
pub fn embedded_name() -> String {
    format!("built-in {EMBEDDED_TABLE}")
}

impl Table {
    /// The table built into the library ([`EMBEDDED_TABLE`]: the Kelvin–Voigt law,
    /// `1.3 ≤ γ ≤ 2.2`, α in `[0, ∞]`, `0.3 ≤ e_n ≤ 1`, stated error bound 8.1e-6; `e_n = 1`
    /// is the elastic surface), loaded and validated as
    /// [`Table::open`] does. The HDF5 library reads files only, so the bytes are written to a
    /// private temporary file (in [`std::env::temp_dir`], created new, removed before this
    /// returns) and opened from there; a few milliseconds.
    pub fn embedded() -> Result<Table, LookupError> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let io = |message: String| LookupError::Io {
            path: embedded_name(),
            message,
        };
        let dir = std::env::temp_dir();
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let (path, mut file) = (0..16)
            .find_map(|attempt| {
                let path: PathBuf = dir.join(format!(
                    ".oblique-built-in-{}-{nanos}-{}-{attempt}.h5",
                    std::process::id(),
                    COUNTER.fetch_add(1, Ordering::Relaxed)
                ));
                create_new(&path).ok().map(|f| (path, f))
            })
            .ok_or_else(|| {
                io(format!(
                    "cannot create a temporary file in {} to open it from (set TMPDIR to a \
                     writable folder)",
                    dir.display()
                ))
            })?;
        let written = file.write_all(BYTES).and_then(|()| file.flush());
        drop(file);
        let opened = match written {
            Ok(()) => Table::open(&path).map_err(|e| match e {
                LookupError::Io { message, .. } => io(message),
                LookupError::Invalid { message, .. } => LookupError::Invalid {
                    path: embedded_name(),
                    message,
                },
                other => other,
            }),
            Err(e) => Err(io(format!(
                "cannot write a temporary file {}: {e}",
                path.display()
            ))),
        };
        let _ = std::fs::remove_file(&path);
        opened
    }
}

/// A new file only this user can read (never an existing one).
fn create_new(path: &Path) -> std::io::Result<std::fs::File> {
    let mut o = std::fs::OpenOptions::new();
    o.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.mode(0o600);
    }
    o.open(path)
}
