//! A whole table build from a config, as `sweep run` and Python's `oblique.build_table` run
//! it: the output checked and locked, the pre-flight probe, the checkpoint (`OUTPUT.ckpt`)
//! created, continued or discarded, the build on a pool of worker threads until it finishes or
//! a stop flag is set, and the table (or a shard's part) written with its provenance.
//!
//! The caller words everything: progress and [`Note`]s go to its [`Progress`], failures come
//! back as [`JobError`]s that carry what the caller needs to say how to go on (which checkpoint
//! holds the finished nodes, whether it was kept).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use thiserror::Error;

use oblique_output::{check_output, check_output_not_input, OutputPathError};
use oblique_table::write::{write_table, StorageError};

use crate::config::Config;
use crate::nodestore::{
    fingerprint, Checkpoint, Header, Kind, LockError, NodeFile, NodeFileError, OutputLock,
};
use crate::{provenance, Built, Preflight, Progress, RunError, RunOptions, Shard, SweepError};

/// The stage before the build: the pre-flight probe ([`crate::preflight`]).
pub const STAGE_PREFLIGHT: &str = "preflight";
/// The stage after the build: writing the table or the part.
pub const STAGE_WRITING: &str = "writing";
/// Most worker threads a job may ask for (`run.threads`; 0 = one per core).
pub const MAX_THREADS: usize = 1024;

/// What a job does with the checkpoint an earlier run of the same output left.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Earlier {
    /// Refuse to run while there is one ([`JobError::CheckpointPending`],
    /// [`JobError::CheckpointForeign`]); create one otherwise.
    #[default]
    Refuse,
    /// Continue it (it must have been written for this config and shard); start afresh when
    /// there is none.
    Resume,
    /// Discard it, if any, and start afresh.
    Restart,
}

/// One table build (or one shard's part of it).
#[derive(Debug, Clone)]
pub struct Job {
    /// The config, with `output` and `run.threads` as the caller settled them (`run.threads`
    /// at most [`MAX_THREADS`]).
    pub config: Config,
    /// The config's text, stored in the checkpoint and in the table's provenance.
    pub config_text: String,
    /// Files the output must not be (the config file).
    pub inputs: Vec<PathBuf>,
    /// What to do with an earlier run's checkpoint.
    pub earlier: Earlier,
    /// Compute this shard only and write its part to the output (for `sweep merge`).
    pub shard: Option<Shard>,
    /// Who runs the job, written into the output's lock file (e.g. `sweep run`).
    pub holder: String,
}

/// A finished job.
#[derive(Debug)]
pub enum Outcome {
    /// The table was written to the config's output.
    Table {
        /// What was built.
        built: Box<Built>,
        /// Wall time of the build, pre-flight and writing excluded (s).
        wall_s: f64,
    },
    /// A shard's part was written to the config's output.
    Part {
        /// Wall time of the build, pre-flight excluded (s).
        wall_s: f64,
    },
}

/// What a job tells its user besides progress, in the order it happens.
#[derive(Debug, Clone, Copy)]
pub enum Note<'a> {
    /// The checkpoint of an earlier run was discarded ([`Earlier::Restart`]).
    Discarded {
        /// The checkpoint.
        checkpoint: &'a Path,
    },
    /// The pre-flight probe found the tolerances reachable.
    Preflight {
        /// What it measured.
        preflight: &'a Preflight,
        /// γ of the hardest points it probed (`domain.gamma_max`).
        gamma: f64,
    },
    /// The job continues the checkpoint of an earlier run ([`Earlier::Resume`]).
    Resuming {
        /// The checkpoint.
        checkpoint: &'a Path,
        /// Nodes it already holds.
        nodes: usize,
    },
}

impl std::fmt::Display for Note<'_> {
    /// One line, or two for a pre-flight that loosened the check tolerance.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Note::Discarded { checkpoint } => {
                write!(f, "discarded the checkpoint {}", checkpoint.display())
            }
            Note::Preflight { preflight, gamma } => {
                write!(
                    f,
                    "preflight: tolerances reachable; the slowest node probed took {:.1} ms",
                    preflight.slowest_node_s * 1e3
                )?;
                if preflight.check_tol_loosened {
                    write!(
                        f,
                        "\nnote: checks.tol is not set and solver.tol/10 is out of reach at \
                         gamma = {gamma}: the held-out checks use checks.tol = {:e} (set \
                         checks.tol to choose)",
                        preflight.check_tol
                    )?;
                }
                Ok(())
            }
            Note::Resuming { checkpoint, nodes } => write!(
                f,
                "resuming from {}: {nodes} nodes already computed",
                checkpoint.display()
            ),
        }
    }
}

/// What became of the checkpoint of a build that failed ([`JobError::Build`]).
#[derive(Debug)]
pub enum CheckpointAfter {
    /// Removed: the job created it and the config decided the failure, which would only repeat
    /// on resume.
    Removed,
    /// The job created it and the config decided the failure, but it could not be removed.
    NotRemoved(NodeFileError),
    /// Kept with its finished nodes (a failure of the machine, or an earlier run's checkpoint):
    /// resuming continues it.
    Kept,
}

/// Why a job did not finish.
#[derive(Debug, Error)]
pub enum JobError {
    /// More worker threads than [`MAX_THREADS`].
    #[error("threads = {threads}: must be in [0, {MAX_THREADS}] (0 = one per core)")]
    Threads {
        /// The number asked for.
        threads: usize,
    },
    /// The output (or its checkpoint's path) cannot be written: not a regular file, or an
    /// input.
    #[error(transparent)]
    OutputPath(#[from] OutputPathError),
    /// The output's folder could not be created.
    #[error("output {}: cannot create directory", output.display())]
    CreateDir {
        /// The output.
        output: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// The output's folder does not take a new file.
    #[error("output {}: directory is not writable", output.display())]
    NotWritable {
        /// The output.
        output: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// Another run holds the output, or its lock file cannot be used.
    #[error(transparent)]
    Lock(#[from] LockError),
    /// The pool of worker threads could not be started.
    #[error("cannot start worker threads")]
    Pool(#[source] rayon::ThreadPoolBuildError),
    /// The pre-flight probe refused a tolerance of the config.
    #[error(transparent)]
    Preflight(SweepError),
    /// The earlier run's checkpoint could not be discarded ([`Earlier::Restart`]).
    #[error("cannot discard the checkpoint {}", checkpoint.display())]
    Discard {
        /// The checkpoint.
        checkpoint: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// An earlier run's checkpoint of this config is there, and the job was told neither to
    /// resume nor to restart.
    #[error(
        "{} holds the checkpoint of an interrupted run ({nodes} nodes) of this config: continue \
         it or discard it and start afresh",
        checkpoint.display()
    )]
    CheckpointPending {
        /// The checkpoint.
        checkpoint: PathBuf,
        /// Nodes it holds.
        nodes: usize,
    },
    /// A checkpoint this job cannot continue is there: written for another config or shard,
    /// or not readable. Only discarding it ([`Earlier::Restart`]) or resuming it with its own
    /// config goes on.
    #[error(
        "{} holds {}: it cannot be resumed by this config or shard; discard it and start afresh",
        checkpoint.display(),
        match nodes {
            Some(n) => format!("the checkpoint of an interrupted run ({n} nodes)"),
            None => "no readable checkpoint".to_string(),
        }
    )]
    CheckpointForeign {
        /// The checkpoint.
        checkpoint: PathBuf,
        /// Nodes it holds, `None` when it cannot be read.
        nodes: Option<usize>,
    },
    /// The checkpoint or the part could not be created, read, written or removed.
    #[error(transparent)]
    NodeFile(#[from] NodeFileError),
    /// The stop flag was set during the pre-flight: the job stopped before it touched the
    /// checkpoint, with nothing computed.
    #[error("interrupted during the pre-flight, before any node was computed")]
    InterruptedEarly,
    /// The stop flag was set: the build stopped after its current batch, and the checkpoint
    /// holds every node finished ([`Earlier::Resume`] continues it).
    #[error("interrupted: finished nodes are saved in {}", checkpoint.display())]
    Interrupted {
        /// The checkpoint.
        checkpoint: PathBuf,
    },
    /// The build failed.
    #[error("{error}")]
    Build {
        /// Why.
        #[source]
        error: Box<RunError>,
        /// The checkpoint.
        checkpoint: PathBuf,
        /// Whether it was kept.
        after: CheckpointAfter,
    },
    /// The table could not be written (or its checks contradict the bound it would state).
    #[error(transparent)]
    Write(#[from] StorageError),
}

impl JobError {
    /// For [`JobError::CheckpointForeign`] with `nodes` (`None`: unreadable): what the
    /// checkpoint holds and why this job cannot continue it, in words that end where the
    /// caller names how to discard it (`None` for any other error).
    pub fn foreign_checkpoint_words(&self) -> Option<(String, &'static str)> {
        let JobError::CheckpointForeign { nodes, .. } = self else {
            return None;
        };
        Some(match nodes {
            Some(n) => (
                format!("the checkpoint of an interrupted run ({n} nodes)"),
                "it was written for a different config or shard (domain, nodes, solver or \
                 checks differ, or another engine version); resume with the config it was \
                 started with, or",
            ),
            None => (
                "no readable checkpoint".to_string(),
                "it cannot be resumed;",
            ),
        })
    }

    /// Whether the caller can fix the cause (the config, the arguments, the output path, an
    /// earlier run's checkpoint or another run on the output), as opposed to a failure of the
    /// machine or an interruption.
    pub fn user_can_fix(&self) -> bool {
        match self {
            JobError::Threads { .. }
            | JobError::OutputPath(_)
            | JobError::CheckpointPending { .. }
            | JobError::CheckpointForeign { .. } => true,
            JobError::CreateDir { .. }
            | JobError::NotWritable { .. }
            | JobError::Pool(_)
            | JobError::Discard { .. }
            | JobError::InterruptedEarly
            | JobError::Interrupted { .. } => false,
            JobError::Lock(e) => e.user_can_fix(),
            JobError::Preflight(e) => e.user_can_fix(),
            JobError::NodeFile(e) => e.user_can_fix(),
            JobError::Build { error, .. } => error.user_can_fix(),
            JobError::Write(e) => e.user_can_fix(),
        }
    }
}

/// The checkpoint of the output `out`: `OUT.ckpt`.
pub fn checkpoint_path(out: &Path) -> PathBuf {
    let mut s = out.as_os_str().to_owned();
    s.push(".ckpt");
    PathBuf::from(s)
}

/// Fail early (before hours of work) if the output's folder cannot take a file: create it,
/// then create and remove a probe file in it.
pub fn check_writable(out: &Path) -> Result<(), JobError> {
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|source| JobError::CreateDir {
        output: out.to_path_buf(),
        source,
    })?;
    let probe = dir.join(format!(".sweep-probe-{}", std::process::id()));
    // A probe, not an output: created and removed at once (a temporary file and a rename
    // would only widen the window in which a killed run leaves it).
    std::fs::write(&probe, b"").map_err(|source| JobError::NotWritable {
        output: out.to_path_buf(),
        source,
    })?;
    let _ = std::fs::remove_file(probe);
    Ok(())
}

impl Job {
    /// A job that builds the whole table of `config` (text `config_text`), refusing to run
    /// over an earlier run's checkpoint.
    pub fn new(config: Config, config_text: String, holder: &str) -> Job {
        Job {
            config,
            config_text,
            inputs: Vec::new(),
            earlier: Earlier::Refuse,
            shard: None,
            holder: holder.to_string(),
        }
    }

    /// The output's checkpoint (`OUTPUT.ckpt`).
    pub fn checkpoint_path(&self) -> PathBuf {
        checkpoint_path(&self.config.output)
    }

    /// Every stage the job reports with [`Progress::phase`], in order: [`STAGE_PREFLIGHT`],
    /// those of the build ([`crate::stages`]), [`STAGE_WRITING`].
    pub fn stages(&self) -> Vec<String> {
        std::iter::once(STAGE_PREFLIGHT.to_string())
            .chain(crate::stages(&self.config))
            .chain(std::iter::once(STAGE_WRITING.to_string()))
            .collect()
    }

    /// Run the job: check and lock the output, probe the tolerances, open the checkpoint, build
    /// on `config.run.threads` worker threads (0 = one per core) and write the table or the
    /// part. Setting `stop` (e.g. from a Ctrl-C handler) stops the job at the end of the
    /// pre-flight ([`JobError::InterruptedEarly`]) or the build after its current batch of
    /// impacts ([`JobError::Interrupted`]). The lock is released when it returns.
    pub fn run(self, progress: &dyn Progress, stop: &AtomicBool) -> Result<Outcome, JobError> {
        let Job {
            mut config,
            config_text,
            inputs,
            earlier,
            shard,
            holder,
        } = self;
        if config.run.threads > MAX_THREADS {
            return Err(JobError::Threads {
                threads: config.run.threads,
            });
        }
        let output = config.output.clone();
        let ckpt_path = checkpoint_path(&output);
        let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
        check_output_not_input(&output, &inputs)?;
        check_output(&ckpt_path)?;
        check_writable(&output)?;
        // Held until the job ends (the operating system releases it if the process dies).
        let lock = OutputLock::acquire(&output, &holder)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(config.run.threads)
            .build()
            .map_err(JobError::Pool)?;
        progress.phase(STAGE_PREFLIGHT, "probing the hardest points of the domain");
        let pre = crate::preflight(&config).map_err(JobError::Preflight)?;
        progress.note(&Note::Preflight {
            preflight: &pre,
            gamma: config.domain.gamma_max,
        });
        if stop.load(Ordering::SeqCst) {
            return Err(JobError::InterruptedEarly);
        }
        config.derived_check_tol = Some(pre.check_tol);
        let header = Header {
            kind: Kind::Checkpoint,
            shard,
            fingerprint: fingerprint(&config),
            config: config_text.clone(),
        };
        let (ckpt, created) = open_checkpoint(earlier, &ckpt_path, header, progress)?;
        let opts = RunOptions {
            store: Some(&ckpt),
            strict: false,
            stop: Some(stop),
        };
        let start = Instant::now();
        let result = pool.install(|| match shard {
            Some(shard) => crate::build_shard(&config, progress, opts, shard).map(|()| None),
            None => crate::build_with(&config, progress, opts).map(Some),
        });
        let built = match result {
            Ok(b) => b,
            Err(RunError::Interrupted) => {
                return Err(JobError::Interrupted {
                    checkpoint: ckpt_path,
                })
            }
            Err(error) => {
                // A failure the config decides would only repeat on resume: the checkpoint this
                // job created must not stand in the way of the next run. Other failures (a full
                // disk) and the checkpoint of an earlier, interrupted run keep their nodes.
                let after = if created && matches!(error, RunError::Sweep(_)) {
                    match ckpt.remove() {
                        Ok(()) => CheckpointAfter::Removed,
                        Err(e) => CheckpointAfter::NotRemoved(e),
                    }
                } else {
                    CheckpointAfter::Kept
                };
                return Err(JobError::Build {
                    error: Box::new(error),
                    checkpoint: ckpt_path,
                    after,
                });
            }
        };
        let wall_s = start.elapsed().as_secs_f64();
        progress.phase(STAGE_WRITING, &output.display().to_string());
        let Some(built) = built else {
            ckpt.finish_part(&output)?;
            drop(lock);
            return Ok(Outcome::Part { wall_s });
        };
        write_table(&output, &built, &provenance(&config, config_text, wall_s))?;
        ckpt.remove()?;
        drop(lock);
        Ok(Outcome::Table {
            built: Box::new(built),
            wall_s,
        })
    }
}

/// Open the checkpoint at `path` as `earlier` says: continue it, discard it or create it.
/// Returns it and whether this job created it.
fn open_checkpoint(
    earlier: Earlier,
    path: &Path,
    header: Header,
    progress: &dyn Progress,
) -> Result<(Checkpoint, bool), JobError> {
    let exists = std::fs::symlink_metadata(path).is_ok();
    if exists && earlier == Earlier::Restart {
        std::fs::remove_file(path).map_err(|source| JobError::Discard {
            checkpoint: path.to_path_buf(),
            source,
        })?;
        progress.note(&Note::Discarded { checkpoint: path });
    } else if exists {
        let (nodes, fits) = match NodeFile::read(path) {
            Ok(f) => (
                Some(f.records.len()),
                f.header.kind == Kind::Checkpoint
                    && f.header.fingerprint == header.fingerprint
                    && f.header.shard == header.shard,
            ),
            Err(_) => (None, false),
        };
        let checkpoint = path.to_path_buf();
        match nodes {
            Some(nodes) if fits => {
                if earlier != Earlier::Resume {
                    return Err(JobError::CheckpointPending { checkpoint, nodes });
                }
            }
            _ => return Err(JobError::CheckpointForeign { checkpoint, nodes }),
        }
        let c = Checkpoint::resume(path, header)?;
        progress.note(&Note::Resuming {
            checkpoint: path,
            nodes: c.resumed_nodes(),
        });
        return Ok((c, false));
    }
    Ok((Checkpoint::create(path, header)?, true))
}
