//! `sweep run`: build a table from a config, with checkpoints, resume and shards: the
//! arguments, the messages and the exit status around `oblique_sweep::job`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::failure::{Failure, Result};
use clap::Args;

use oblique_sweep::job::{CheckpointAfter, Earlier, Job, JobError, Outcome, MAX_THREADS};
use oblique_sweep::{Built, Config, Shard};

use crate::progress::CliProgress;

#[derive(Args)]
pub struct RunArgs {
    /// TOML config (see configs/ and docs/config.md).
    config: PathBuf,
    /// Output table (or, with --shard, the shard's part file); overrides the config's `output`.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Worker threads (0 = one per core); overrides `run.threads`.
    #[arg(long)]
    threads: Option<usize>,
    /// No progress output.
    #[arg(long)]
    quiet: bool,
    /// Continue an interrupted run from its checkpoint (OUTPUT.ckpt); starts afresh if there is
    /// none. The config must be the one the checkpoint was written for.
    #[arg(long)]
    resume: bool,
    /// Discard the checkpoint (OUTPUT.ckpt) of an earlier run, if any, and start afresh.
    #[arg(long, conflicts_with = "resume")]
    restart: bool,
    /// Compute shard K of N (1 <= K <= N) and write it as a part file (-o) for `sweep merge`.
    #[arg(long, value_name = "K/N", value_parser = parse_shard)]
    shard: Option<Shard>,
}

/// Parse `K/N` (1-based) into a 0-based shard.
fn parse_shard(s: &str) -> std::result::Result<Shard, String> {
    let bad = || format!("'{s}': expected K/N with integers 1 <= K <= N <= 100000, e.g. 3/8");
    let (k, n) = s.split_once('/').ok_or_else(bad)?;
    let k: usize = k.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if k == 0 || k > n || n > 100_000 {
        return Err(bad());
    }
    Ok(Shard {
        index: k - 1,
        count: n,
    })
}

/// A path as a shell word: quoted when it holds anything but plain characters.
fn shell_word(p: &Path) -> String {
    let s = p.display().to_string();
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "/._-+,:=@%".contains(c));
    if plain {
        s
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// Set by the Ctrl-C handler; the sweep stops after its current batch.
static STOP: AtomicBool = AtomicBool::new(false);

/// `sweep run CONFIG -o OUTPUT [--shard K/N] FLAG`, to quote in messages.
fn run_command(args: &RunArgs, output: &Path, flag: &str) -> String {
    let shard = args
        .shard
        .map(|s| format!(" --shard {}/{}", s.index + 1, s.count))
        .unwrap_or_default();
    format!(
        "sweep run {} -o {}{shard} {flag}",
        shell_word(&args.config),
        shell_word(output)
    )
}

/// The error of a job that did not finish, with the commands that go on where there are any.
fn failure(args: &RunArgs, output: &Path, e: JobError) -> Failure {
    let resume = || run_command(args, output, "--resume");
    let restart = || run_command(args, output, "--restart");
    match e {
        JobError::CheckpointPending { checkpoint, nodes } => Failure::usage(format!(
            "{} holds the checkpoint of an interrupted run ({nodes} nodes) of this config: \
             continue it with\n  {}\nor discard it and start afresh with\n  {}",
            checkpoint.display(),
            resume(),
            restart()
        )),
        ref e @ JobError::CheckpointForeign { ref checkpoint, .. } => {
            let (what, why) = e.foreign_checkpoint_words().unwrap_or_default();
            Failure::usage(format!(
                "{} holds {what}: {why} discard it and start afresh with\n  {}",
                checkpoint.display(),
                restart()
            ))
        }
        JobError::Build {
            error,
            checkpoint,
            after,
        } => {
            match after {
                CheckpointAfter::Removed => {}
                CheckpointAfter::NotRemoved(r) => {
                    eprintln!("warning: cannot remove the checkpoint of this run: {r}")
                }
                CheckpointAfter::Kept => eprintln!(
                    "finished nodes are kept in {}; continue with\n  {}\nor discard them \
                     with\n  {}",
                    checkpoint.display(),
                    resume(),
                    restart()
                ),
            }
            (*error).into()
        }
        e => e.into(),
    }
}

pub fn run(args: RunArgs) -> Result<()> {
    let (mut cfg, text) = Config::load(&args.config)?;
    if let Some(o) = &args.output {
        cfg.output = o.clone();
    }
    if let Some(t) = args.threads {
        if t > MAX_THREADS {
            return Err(Failure::usage(format!(
                "--threads {t}: must be in [0, {MAX_THREADS}] (0 = one per core)"
            )));
        }
        cfg.run.threads = t;
    }
    let output = cfg.output.clone();
    let mut job = Job::new(cfg, text, "sweep run");
    job.inputs.push(args.config.clone());
    job.shard = args.shard;
    job.earlier = if args.resume {
        Earlier::Resume
    } else if args.restart {
        Earlier::Restart
    } else {
        Earlier::Refuse
    };
    let progress = CliProgress::new(args.quiet, job.stages());
    // A second Ctrl-C (or a handler that cannot be installed) kills the process as usual; the
    // checkpoint is durable after every batch either way.
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    let result = job.run(&progress, &STOP);
    progress.finish();
    match result {
        Ok(Outcome::Table { built, wall_s }) => {
            if !args.quiet {
                summary(&output, &built, wall_s);
            }
            Ok(())
        }
        Ok(Outcome::Part { wall_s }) => {
            if !args.quiet {
                eprintln!(
                    "wrote part {} ({wall_s:.1} s); merge all parts with `sweep merge PARTS... -o TABLE`",
                    output.display()
                );
            }
            Ok(())
        }
        Err(e @ JobError::InterruptedEarly) => {
            eprintln!("{e}");
            std::process::exit(130);
        }
        Err(JobError::Interrupted { checkpoint }) => {
            eprintln!(
                "interrupted: finished nodes are saved in {}; continue with\n  {}",
                checkpoint.display(),
                run_command(&args, &output, "--resume")
            );
            std::process::exit(130);
        }
        Err(e) => Err(failure(&args, &output, e)),
    }
}

/// What was written to `output`: per patch, then the whole table.
pub(crate) fn summary(output: &Path, built: &Built, wall: f64) {
    let nodes: usize = built.patches.iter().map(|p| p.unique_nodes).sum();
    let simulated: usize = built.patches.iter().map(|p| p.simulated).sum();
    for p in &built.patches {
        eprintln!(
                "  {:13} {} roots, {} leaves at depth {}..{}, {} nodes ({} simulated), max predicted error {:.1e}",
                p.name,
                (0..p.patch.dims() as usize)
                    .map(|k| p.patch.axis(k).2.to_string())
                    .collect::<Vec<_>>()
                    .join(" x "),
                p.leaf_depth.len(),
                p.leaf_depth.iter().min().unwrap_or(&0),
                p.leaf_depth.iter().max().unwrap_or(&0),
                p.unique_nodes,
                p.simulated,
                p.leaf_error.iter().copied().fold(0.0, f64::max)
            );
    }
    let max_err = built
        .checks
        .iter()
        .map(|c| c.interpolation_error)
        .fold(0.0, f64::max);
    eprintln!(
            "wrote {}: {nodes} nodes ({simulated} simulated) + {} held-out checks, max check error {max_err:.2e}, {wall:.1} s",
            output.display(),
            built.checks.len()
        );
}
