//! The storage layer's node files: checkpoints of interrupted runs and the parts of sharded runs.
//!
//! A node file holds node values `(γ, α, e_n, tol) → (P, error estimate)` that a sweep computed, so
//! that a resumed run or a merge does not compute them again. Layout (little-endian):
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `OBLQNODE` |
//! | 4 | format version (2) |
//! | 4 | kind: 1 = checkpoint (still being written), 2 = finished shard part |
//! | 4, 4 | shard index `k` (0-based) and count `n` (0, 1 for an unsharded run) |
//! | 8 | fingerprint of the config sections that decide the values (FNV-1a 64) |
//! | 8 + L | length `L` and UTF-8 text of the config |
//! | 56 each | records: `γ, α, e_n, tol, P, error` as float64, then the FNV-1a 64 of those 48 bytes |
//!
//! Records are appended in batches and synced to disk after each batch. A record cut short by a
//! crash (or one whose checksum does not match) ends the readable part of a checkpoint; the
//! file is truncated there before appending. In a finished part every record must be intact.

use std::collections::HashMap;
use std::fs::File;
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use oblique_table::format::fnv1a64;
use thiserror::Error;

use crate::{Config, NodeKey, NodeRecord, NodeStore, Shard};

const MAGIC: &[u8; 8] = b"OBLQNODE";
const VERSION: u32 = 2;
const RECORD: usize = 56;
/// Bytes of a record before its checksum.
const RECORD_DATA: usize = RECORD - 8;

/// What a node file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The checkpoint of a run in progress (or interrupted).
    Checkpoint,
    /// The finished output of one shard.
    Part,
}

/// Errors of node files.
#[derive(Debug, Error)]
pub enum NodeFileError {
    /// Filesystem error.
    #[error("{path}: {source}")]
    Io {
        /// File path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not a node file, or a damaged one.
    #[error("{path}: {message}")]
    Invalid {
        /// File path.
        path: String,
        /// What is wrong and what to do.
        message: String,
    },
    /// A checkpoint or part could not be written (or its path is not a regular file).
    #[error(transparent)]
    Output(#[from] oblique_output::OutputError),
}

impl NodeFileError {
    /// Whether the caller can fix it: true for a file that is missing, unreadable, damaged or
    /// from another config, or an output path in the way; false for a failed write.
    pub fn user_can_fix(&self) -> bool {
        match self {
            NodeFileError::Output(e) => e.user_can_fix(),
            _ => true,
        }
    }
}

/// Fingerprint of what decides the node values and their placement: domain, nodes, solver and
/// checks (not the output path or the thread count), and the engine version: FNV-1a 64 of
/// those sections written as TOML (every field, floats so that they read back exactly).
pub fn fingerprint(cfg: &Config) -> u64 {
    #[derive(serde::Serialize)]
    struct Decisive<'a> {
        engine_version: &'a str,
        domain: &'a crate::config::Domain,
        nodes: &'a crate::config::Nodes,
        solver: &'a crate::config::Solver,
        checks: &'a crate::config::Checks,
    }
    let decisive = Decisive {
        engine_version: crate::VERSION,
        domain: &cfg.domain,
        nodes: &cfg.nodes,
        solver: &cfg.solver,
        checks: &cfg.checks,
    };
    // Plain structs of numbers, strings and options: TOML can write every value of them.
    let text = toml::to_string(&decisive).unwrap_or_else(|e| format!("unserialisable: {e}"));
    fnv1a64(text.as_bytes())
}

/// The header of a node file.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// Checkpoint or finished part.
    pub kind: Kind,
    /// The shard, `None` for an unsharded run.
    pub shard: Option<Shard>,
    /// [`fingerprint`] of the config.
    pub fingerprint: u64,
    /// The config text.
    pub config: String,
}

impl Header {
    fn bytes(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(48 + self.config.len());
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        let kind: u32 = match self.kind {
            Kind::Checkpoint => 1,
            Kind::Part => 2,
        };
        b.extend_from_slice(&kind.to_le_bytes());
        let (k, n) = self
            .shard
            .map_or((0, 1), |s| (s.index as u32, s.count as u32));
        b.extend_from_slice(&k.to_le_bytes());
        b.extend_from_slice(&n.to_le_bytes());
        b.extend_from_slice(&self.fingerprint.to_le_bytes());
        b.extend_from_slice(&(self.config.len() as u64).to_le_bytes());
        b.extend_from_slice(self.config.as_bytes());
        b
    }
}

fn record_bytes(r: &NodeRecord) -> [u8; RECORD] {
    let mut b = [0u8; RECORD];
    for (i, v) in [r.gamma, r.alpha, r.e_n, r.tol, r.p, r.error]
        .iter()
        .enumerate()
    {
        b[8 * i..8 * i + 8].copy_from_slice(&v.to_le_bytes());
    }
    let sum = fnv1a64(&b[..RECORD_DATA]);
    b[RECORD_DATA..].copy_from_slice(&sum.to_le_bytes());
    b
}

fn parse_record(b: &[u8]) -> Option<NodeRecord> {
    let sum = u64::from_le_bytes(b[RECORD_DATA..RECORD].try_into().ok()?);
    if sum != fnv1a64(&b[..RECORD_DATA]) {
        return None;
    }
    let f = |i: usize| -> Option<f64> {
        Some(f64::from_le_bytes(b[8 * i..8 * i + 8].try_into().ok()?))
    };
    Some(NodeRecord {
        gamma: f(0)?,
        alpha: f(1)?,
        e_n: f(2)?,
        tol: f(3)?,
        p: f(4)?,
        error: f(5)?,
    })
}

/// A node file read into memory.
#[derive(Debug)]
pub struct NodeFile {
    /// Its header.
    pub header: Header,
    /// Intact records, in file order.
    pub records: Vec<NodeRecord>,
    /// Byte length of the intact part (header and intact records).
    pub intact_len: u64,
}

impl NodeFile {
    /// Read a node file. A damaged tail is tolerated in a checkpoint (it is where a crash cut
    /// the last write) and refused in a finished part.
    pub fn read(path: &Path) -> Result<NodeFile, NodeFileError> {
        let p = path.display().to_string();
        let io = |source| NodeFileError::Io {
            path: p.clone(),
            source,
        };
        let invalid = |message: String| NodeFileError::Invalid {
            path: p.clone(),
            message,
        };
        let mut bytes = Vec::new();
        File::open(path)
            .and_then(|mut f| f.read_to_end(&mut bytes))
            .map_err(io)?;
        if bytes.len() < 40 || &bytes[..8] != MAGIC {
            return Err(invalid(
                "not a node file (a checkpoint or a shard part of a table build)".into(),
            ));
        }
        let u32_at =
            |i: usize| u32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
        let u64_at = |i: usize| {
            let mut a = [0u8; 8];
            a.copy_from_slice(&bytes[i..i + 8]);
            u64::from_le_bytes(a)
        };
        let version = u32_at(8);
        if version != VERSION {
            return Err(invalid(format!(
                "node file version {version}, this engine reads {VERSION}; recompute it with this engine"
            )));
        }
        let kind = match u32_at(12) {
            1 => Kind::Checkpoint,
            2 => Kind::Part,
            k => return Err(invalid(format!("unknown node file kind {k}"))),
        };
        let (k, n) = (u32_at(16) as usize, u32_at(20) as usize);
        if n == 0 || k >= n {
            return Err(invalid(format!("shard {k} of {n} is not a valid shard")));
        }
        let shard = (n > 1).then_some(Shard { index: k, count: n });
        let fingerprint = u64_at(24);
        let len = u64_at(32) as usize;
        let start = 40usize
            .checked_add(len)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| invalid("truncated header".into()))?;
        let config = String::from_utf8(bytes[40..start].to_vec())
            .map_err(|_| invalid("config text is not UTF-8".into()))?;
        let mut records = Vec::with_capacity((bytes.len() - start) / RECORD);
        let mut end = start;
        for chunk in bytes[start..].chunks(RECORD) {
            match (chunk.len() == RECORD)
                .then(|| parse_record(chunk))
                .flatten()
            {
                Some(r) => {
                    records.push(r);
                    end += RECORD;
                }
                None => {
                    if kind == Kind::Part {
                        return Err(invalid(format!(
                            "damaged record at byte {end}: the part is corrupted; rerun its shard"
                        )));
                    }
                    break;
                }
            }
        }
        Ok(NodeFile {
            header: Header {
                kind,
                shard,
                fingerprint,
                config,
            },
            records,
            intact_len: end as u64,
        })
    }
}

/// A node store backed by an append-only checkpoint file.
pub struct Checkpoint {
    path: PathBuf,
    known: HashMap<NodeKey, (f64, f64)>,
    out: Mutex<BufWriter<File>>,
    header: Header,
}

impl Checkpoint {
    /// Start a new checkpoint at `path` (replacing any regular file there): its header is
    /// written whole (`oblique_output`), then records are appended in place.
    pub fn create(path: &Path, header: Header) -> Result<Checkpoint, NodeFileError> {
        let io = |source| NodeFileError::Io {
            path: path.display().to_string(),
            source,
        };
        oblique_output::write_bytes(path, &header.bytes())?;
        let mut f = oblique_output::open_in_place(path, false)?;
        f.seek(SeekFrom::End(0)).map_err(io)?;
        Ok(Checkpoint {
            path: path.to_path_buf(),
            known: HashMap::new(),
            out: Mutex::new(BufWriter::new(f)),
            header,
        })
    }

    /// Continue the checkpoint at `path`, which must have been written for `header`'s config and
    /// shard. Its intact records are loaded; a damaged tail is cut off.
    pub fn resume(path: &Path, header: Header) -> Result<Checkpoint, NodeFileError> {
        let p = path.display().to_string();
        let file = NodeFile::read(path)?;
        if file.header.kind != Kind::Checkpoint {
            return Err(NodeFileError::Invalid {
                path: p,
                message: "is a finished shard part, not a checkpoint".into(),
            });
        }
        if file.header.fingerprint != header.fingerprint {
            return Err(NodeFileError::Invalid {
                path: p,
                message: "the checkpoint was written for a different config (domain, nodes, \
                          solver or checks differ, or another engine version); resume with the \
                          config it was started with"
                    .into(),
            });
        }
        if file.header.shard != header.shard {
            let name = |s: Option<Shard>| {
                s.map_or("no shard".to_string(), |s| {
                    format!("shard {}/{}", s.index + 1, s.count)
                })
            };
            return Err(NodeFileError::Invalid {
                path: p,
                message: format!(
                    "the checkpoint is for {}, this run is {}",
                    name(file.header.shard),
                    name(header.shard)
                ),
            });
        }
        let io = |source| NodeFileError::Io {
            path: p.clone(),
            source,
        };
        let mut f = oblique_output::open_in_place(path, false)?;
        f.set_len(file.intact_len).map_err(io)?;
        f.seek(SeekFrom::End(0)).map_err(io)?;
        let known = file
            .records
            .iter()
            .map(|r| (r.key(), (r.p, r.error)))
            .collect();
        Ok(Checkpoint {
            path: path.to_path_buf(),
            known,
            out: Mutex::new(BufWriter::new(f)),
            header,
        })
    }

    /// Values loaded from the file when resuming.
    pub fn resumed_nodes(&self) -> usize {
        self.known.len()
    }

    /// Turn the finished checkpoint of a shard into its part at `part` (atomically: written
    /// next to it, then renamed), and remove the checkpoint.
    pub fn finish_part(self, part: &Path) -> Result<(), NodeFileError> {
        let io = |path: &Path| {
            let path = path.display().to_string();
            move |source| NodeFileError::Io { path, source }
        };
        drop(self.out);
        let file = NodeFile::read(&self.path)?;
        let header = Header {
            kind: Kind::Part,
            ..self.header
        };
        oblique_output::write_with(part, |w| {
            w.write_all(&header.bytes())?;
            for r in &file.records {
                w.write_all(&record_bytes(r))?;
            }
            Ok(())
        })?;
        std::fs::remove_file(&self.path).map_err(io(&self.path))
    }

    /// Remove the checkpoint (the run finished and its table is written).
    pub fn remove(self) -> Result<(), NodeFileError> {
        drop(self.out);
        std::fs::remove_file(&self.path).map_err(|source| NodeFileError::Io {
            path: self.path.display().to_string(),
            source,
        })
    }
}

impl NodeStore for Checkpoint {
    fn get(&self, key: NodeKey) -> Option<(f64, f64)> {
        self.known.get(&key).copied()
    }

    fn put(&self, records: &[NodeRecord]) -> Result<(), String> {
        let mut out = self
            .out
            .lock()
            .map_err(|_| "checkpoint writer poisoned".to_string())?;
        let err = |e: std::io::Error| {
            format!("{}: {}", self.path.display(), oblique_output::explain_io(e))
        };
        for r in records {
            out.write_all(&record_bytes(r)).map_err(err)?;
        }
        out.flush().map_err(err)?;
        out.get_ref().sync_data().map_err(err)
    }
}

/// The merged, read-only values of all parts of a sharded run.
pub struct Merged {
    known: HashMap<NodeKey, (f64, f64)>,
    /// The config text the parts were computed for.
    pub config: String,
}

impl Merged {
    /// Read the parts and check that they come from one config, have the same shard count and
    /// cover every shard exactly once, and that nodes computed by two shards agree.
    pub fn read(parts: &[PathBuf]) -> Result<Merged, NodeFileError> {
        let invalid = |path: &Path, message: String| NodeFileError::Invalid {
            path: path.display().to_string(),
            message,
        };
        let first = parts.first().ok_or_else(|| NodeFileError::Invalid {
            path: "(none)".into(),
            message: "no parts given".into(),
        })?;
        let mut known: HashMap<NodeKey, (f64, f64)> = HashMap::new();
        let mut seen: Vec<Option<&Path>> = Vec::new();
        let mut reference: Option<(u64, usize, String)> = None;
        for path in parts {
            let f = NodeFile::read(path)?;
            if f.header.kind != Kind::Part {
                return Err(invalid(
                    path,
                    "is a checkpoint of an unfinished run, not a finished part; resume that \
                     shard's run to finish it"
                        .into(),
                ));
            }
            let shard = f.header.shard.unwrap_or(Shard { index: 0, count: 1 });
            match &reference {
                None => {
                    reference = Some((f.header.fingerprint, shard.count, f.header.config.clone()));
                    seen = vec![None; shard.count];
                }
                Some((fp, n, _)) => {
                    if *fp != f.header.fingerprint {
                        return Err(invalid(
                            path,
                            format!(
                                "computed for a different config than {} (parts of different \
                                 builds cannot be merged)",
                                first.display()
                            ),
                        ));
                    }
                    if *n != shard.count {
                        return Err(invalid(
                            path,
                            format!(
                                "is shard {}/{}, but {} has {n} shards",
                                shard.index + 1,
                                shard.count,
                                first.display()
                            ),
                        ));
                    }
                }
            }
            if let Some(other) = seen[shard.index] {
                return Err(invalid(
                    path,
                    format!(
                        "shard {}/{} is given twice (also {})",
                        shard.index + 1,
                        shard.count,
                        other.display()
                    ),
                ));
            }
            seen[shard.index] = Some(path);
            for r in &f.records {
                let v = (r.p, r.error);
                if let Some(old) = known.insert(r.key(), v) {
                    if old.0.to_bits() != v.0.to_bits() || old.1.to_bits() != v.1.to_bits() {
                        return Err(invalid(
                            path,
                            format!(
                                "node gamma = {}, alpha = {}, e_n = {} has P = {} here and {} in \
                                 another part: the parts were computed by different engines",
                                r.gamma, r.alpha, r.e_n, v.0, old.0
                            ),
                        ));
                    }
                }
            }
        }
        let missing: Vec<String> = seen
            .iter()
            .enumerate()
            .filter(|(_, s)| s.is_none())
            .map(|(i, _)| format!("{}/{}", i + 1, seen.len()))
            .collect();
        if !missing.is_empty() {
            return Err(invalid(
                first,
                format!(
                    "shard(s) {} missing: give every part of the run",
                    missing.join(", ")
                ),
            ));
        }
        let config = reference.map(|r| r.2).unwrap_or_default();
        Ok(Merged { known, config })
    }
}

impl NodeStore for Merged {
    fn get(&self, key: NodeKey) -> Option<(f64, f64)> {
        self.known.get(&key).copied()
    }

    fn put(&self, _: &[NodeRecord]) -> Result<(), String> {
        Err("a merge computes nothing".into())
    }
}

/// Errors of taking the lock of an output.
#[derive(Debug, Error)]
pub enum LockError {
    /// Another process holds the lock: a run on the same output is going on.
    #[error(
        "{path} is locked by {holder}: another run is writing {output}; wait for it to finish \
         or stop it"
    )]
    Held {
        /// The lock file.
        path: String,
        /// The output it protects.
        output: String,
        /// Who holds it, as it wrote itself into the lock file ("pid 123, started …").
        holder: String,
    },
    /// Something that is not a regular file is at the lock file's path.
    #[error(transparent)]
    Path(#[from] oblique_output::OutputPathError),
    /// The lock file could not be created, read or written.
    #[error("lock file {path}: {source}")]
    Io {
        /// The lock file.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
}

impl LockError {
    /// Whether the caller can fix it: another run holds the output, or the output path is not
    /// a regular file (not: an I/O failure on the lock file).
    pub fn user_can_fix(&self) -> bool {
        matches!(self, LockError::Held { .. } | LockError::Path(_))
    }
}

/// An exclusive lock on an output for the duration of a run: an advisory `flock` on the file
/// `OUTPUT.lock`, which holds the owner's pid and start time. The operating system releases
/// it when the process ends in any way (also `kill -9`); dropping the lock removes the file.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
    /// Held open: the lock lives as long as this descriptor.
    file: File,
}

/// The lock file of an output: `OUTPUT.lock`.
pub fn lock_path(output: &Path) -> PathBuf {
    let mut s = output.as_os_str().to_owned();
    s.push(".lock");
    PathBuf::from(s)
}

#[cfg(unix)]
fn try_flock(file: &File) -> std::io::Result<bool> {
    use std::os::unix::io::AsRawFd;
    extern "C" {
        fn flock(fd: i32, operation: i32) -> i32;
    }
    const LOCK_EX: i32 = 2;
    const LOCK_NB: i32 = 4;
    // SAFETY: flock on a descriptor this `File` owns; no memory is passed.
    let rc = unsafe { flock(file.as_raw_fd(), LOCK_EX | LOCK_NB) };
    if rc == 0 {
        return Ok(true);
    }
    let e = std::io::Error::last_os_error();
    if e.kind() == std::io::ErrorKind::WouldBlock {
        Ok(false)
    } else {
        Err(e)
    }
}

#[cfg(not(unix))]
fn try_flock(_: &File) -> std::io::Result<bool> {
    Ok(true)
}

#[cfg(unix)]
fn same_inode(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::symlink_metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_inode(_: &File, _: &Path) -> bool {
    true
}

impl OutputLock {
    /// Take the lock of `output` without waiting; [`LockError::Held`] names the holder when
    /// another process has it. `what` (e.g. "sweep run") is written into the lock file with the
    /// pid and the start time.
    pub fn acquire(output: &Path, what: &str) -> Result<OutputLock, LockError> {
        let path = lock_path(output);
        let shown = path.display().to_string();
        let io = |source| LockError::Io {
            path: shown.clone(),
            source: oblique_output::explain_io(source),
        };
        loop {
            let mut file = oblique_output::open_in_place(&path, true).map_err(|e| match e {
                oblique_output::OutputError::Path(p) => LockError::Path(p),
                oblique_output::OutputError::Io { source, .. } => io(source),
            })?;
            if !try_flock(&file).map_err(io)? {
                let mut holder = String::new();
                let _ = file.read_to_string(&mut holder);
                let holder = holder.trim();
                return Err(LockError::Held {
                    path: shown,
                    output: output.display().to_string(),
                    holder: if holder.is_empty() {
                        "another process (it has not written its pid yet)".into()
                    } else {
                        holder.to_string()
                    },
                });
            }
            // The previous holder removes the file when it finishes: a lock taken on a file that
            // is no longer at `path` protects nothing; take it again on the new one.
            if !same_inode(&file, &path) {
                continue;
            }
            let me = format!(
                "pid {} ({what}, started {})\n",
                std::process::id(),
                crate::utc_now()
            );
            let mut lock = OutputLock { path, file };
            // On an error (a full disk, the file size limit) `lock` is dropped, which removes
            // the file: no lock file is left behind.
            let file = &mut lock.file;
            file.set_len(0).map_err(io)?;
            file.seek(SeekFrom::Start(0)).map_err(io)?;
            file.write_all(me.as_bytes()).map_err(io)?;
            file.flush().map_err(io)?;
            return Ok(lock);
        }
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Remove the file while still holding the lock; a process that opened it before sees
        // that it is gone and takes the lock on a new file. The lock goes with the descriptor.
        let _ = std::fs::remove_file(&self.path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CONFIG: &str = r#"
output = "t.h5"
[domain]
gamma_min = 0.1
gamma_max = 3.5
alpha_max = "inf"
[nodes]
target_error = 1e-5
[solver]
tol = 1e-6
"#;

    fn fp(text: &str) -> u64 {
        fingerprint(&Config::parse(text, "x.toml").expect("valid config"))
    }

    #[test]
    fn the_fingerprint_follows_what_decides_the_nodes_and_nothing_else() {
        let base = fp(CONFIG);
        assert_eq!(base, fp(CONFIG), "repeatable");
        // Output and threads decide no node value.
        assert_eq!(base, fp(&CONFIG.replace("t.h5", "other.h5")));
        assert_eq!(base, fp(&format!("{CONFIG}[run]\nthreads = 3\n")));
        // Every decisive section does, down to the last bit of a float.
        for changed in [
            CONFIG.replace("gamma_max = 3.5", "gamma_max = 3.5000000000000004"),
            CONFIG.replace("alpha_max = \"inf\"", "alpha_max = 20"),
            CONFIG.replace("target_error = 1e-5", "target_error = 2e-5"),
            CONFIG.replace("tol = 1e-6", "tol = 1.0000000000000002e-6"),
            format!("{CONFIG}[checks]\nseed = 7\n"),
        ] {
            assert_ne!(base, fp(&changed), "{changed}");
        }
    }
}
