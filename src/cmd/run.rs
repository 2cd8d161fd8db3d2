//! `sweep run`: build a table from a config, with checkpoints, resume and shards.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use crate::failure::{Context, Failure, Result};
use clap::Args;

use oblique_output::{check_output, check_output_not_input};
use oblique_sweep::nodestore::{fingerprint, Checkpoint, Header, Kind, NodeFile, OutputLock};
use oblique_sweep::provenance;
use oblique_sweep::{Built, Config, Progress, RunError, RunOptions, Shard};
use oblique_table::write::write_table;

use crate::progress::{CliProgress, STEP_PREFLIGHT, STEP_WRITING};

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

fn checkpoint_path(out: &Path) -> PathBuf {
    let mut s = out.as_os_str().to_owned();
    s.push(".ckpt");
    PathBuf::from(s)
}

/// Fail early (before hours of work) if the output directory cannot take a file.
pub(crate) fn check_writable(out: &std::path::Path) -> Result<()> {
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    std::fs::create_dir_all(dir)
        .with_context(|| format!("output {}: cannot create directory", out.display()))?;
    let probe = dir.join(format!(".sweep-probe-{}", std::process::id()));
    // A probe, not an output: created and removed at once (a temporary file and a rename
    // would only widen the window in which a killed run leaves it).
    std::fs::write(&probe, b"")
        .with_context(|| format!("output {}: directory is not writable", out.display()))?;
    let _ = std::fs::remove_file(probe);
    Ok(())
}

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

/// Open the checkpoint of this run: continue it (`--resume`), discard it (`--restart`) or
/// create it. Returns it and whether this run created it.
fn open_checkpoint(
    args: &RunArgs,
    cfg: &Config,
    ckpt_path: &Path,
    header: Header,
    progress: &CliProgress,
) -> Result<(Checkpoint, bool)> {
    let exists = std::fs::symlink_metadata(ckpt_path).is_ok();
    if exists && args.restart {
        std::fs::remove_file(ckpt_path)
            .with_context(|| format!("cannot discard the checkpoint {}", ckpt_path.display()))?;
        if !args.quiet {
            progress.println(&format!("discarded the checkpoint {}", ckpt_path.display()));
        }
    } else if exists {
        let restart = run_command(args, &cfg.output, "--restart");
        let (nodes, fits) = match NodeFile::read(ckpt_path) {
            Ok(f) => (
                Some(f.records.len()),
                f.header.kind == Kind::Checkpoint
                    && f.header.fingerprint == header.fingerprint
                    && f.header.shard == header.shard,
            ),
            Err(_) => (None, false),
        };
        let what = match nodes {
            Some(n) => format!("the checkpoint of an interrupted run ({n} nodes)"),
            None => "no readable checkpoint".to_string(),
        };
        if !fits {
            let why = if nodes.is_some() {
                "it was written for a different config or shard (domain, nodes, solver or \
                 checks differ, or another engine version); resume with the config it was \
                 started with, or"
            } else {
                "it cannot be resumed;"
            };
            return Err(Failure::usage(format!(
                "{} holds {what}: {why} discard it and start afresh with\n  {restart}",
                ckpt_path.display()
            )));
        }
        if !args.resume {
            return Err(Failure::usage(format!(
                "{} holds {what} of this config: continue it with\n  {}\nor discard it and \
                 start afresh with\n  {restart}",
                ckpt_path.display(),
                run_command(args, &cfg.output, "--resume")
            )));
        }
        let c = Checkpoint::resume(ckpt_path, header)?;
        if !args.quiet {
            progress.println(&format!(
                "resuming from {}: {} nodes already computed",
                ckpt_path.display(),
                c.resumed_nodes()
            ));
        }
        return Ok((c, false));
    }
    Ok((Checkpoint::create(ckpt_path, header)?, true))
}

pub fn run(args: RunArgs) -> Result<()> {
    let (mut cfg, text) = Config::load(&args.config)?;
    if let Some(o) = &args.output {
        cfg.output = o.clone();
    }
    if let Some(t) = args.threads {
        if t > 1024 {
            return Err(Failure::usage(format!(
                "--threads {t}: must be in [0, 1024] (0 = one per core)"
            )));
        }
        cfg.run.threads = t;
    }
    let ckpt_path = checkpoint_path(&cfg.output);
    check_output_not_input(&cfg.output, &[&args.config])?;
    check_output(&ckpt_path)?;
    check_writable(&cfg.output)?;
    // Held until the run ends (the operating system releases it if the process dies).
    let lock = OutputLock::acquire(&cfg.output, "sweep run")?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.run.threads)
        .build()
        .context("cannot start worker threads")?;
    let steps: Vec<String> = std::iter::once(STEP_PREFLIGHT.to_string())
        .chain(oblique_sweep::stages(&cfg))
        .chain(std::iter::once(STEP_WRITING.to_string()))
        .collect();
    let progress = CliProgress::new(args.quiet, steps);
    progress.phase(STEP_PREFLIGHT, "probing the hardest points of the domain");
    let pre = oblique_sweep::preflight(&cfg)?;
    if !args.quiet {
        progress.println(&format!(
            "preflight: tolerances reachable; the slowest node probed took {:.1} ms",
            pre.slowest_node_s * 1e3
        ));
        if pre.check_tol_loosened {
            progress.println(&format!(
                "note: checks.tol is not set and solver.tol/10 is out of reach at gamma = {}: \
                 the held-out checks use checks.tol = {:e} (set checks.tol to choose)",
                cfg.domain.gamma_max, pre.check_tol
            ));
        }
    }
    cfg.derived_check_tol = Some(pre.check_tol);
    let header = Header {
        kind: Kind::Checkpoint,
        shard: args.shard,
        fingerprint: fingerprint(&cfg),
        config: text.clone(),
    };
    let (ckpt, created) = open_checkpoint(&args, &cfg, &ckpt_path, header, &progress)?;
    // A second Ctrl-C (or a handler that cannot be installed) kills the process as usual; the
    // checkpoint is durable after every batch either way.
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
    });
    let opts = RunOptions {
        store: Some(&ckpt),
        strict: false,
        stop: Some(&STOP),
    };
    let start = Instant::now();
    let result = pool.install(|| match args.shard {
        Some(shard) => oblique_sweep::build_shard(&cfg, &progress, opts, shard).map(|()| None),
        None => oblique_sweep::build_with(&cfg, &progress, opts).map(Some),
    });
    let built = match result {
        Ok(b) => b,
        Err(RunError::Interrupted) => {
            progress.finish();
            eprintln!(
                "interrupted: finished nodes are saved in {}; continue with\n  {}",
                ckpt_path.display(),
                run_command(&args, &cfg.output, "--resume")
            );
            drop(lock);
            std::process::exit(130);
        }
        Err(e) => {
            progress.finish();
            // A failure the config decides would only repeat on resume: the checkpoint this
            // run created must not stand in the way of the next run. Other failures (a full
            // disk) and the checkpoint of an earlier, interrupted run keep their nodes.
            if created && matches!(e, RunError::Sweep(_)) {
                if let Err(r) = ckpt.remove() {
                    eprintln!("warning: cannot remove the checkpoint of this run: {r}");
                }
            } else {
                eprintln!(
                    "finished nodes are kept in {}; continue with\n  {}\nor discard them \
                     with\n  {}",
                    ckpt_path.display(),
                    run_command(&args, &cfg.output, "--resume"),
                    run_command(&args, &cfg.output, "--restart")
                );
            }
            return Err(e.into());
        }
    };
    let wall = start.elapsed().as_secs_f64();
    progress.phase(STEP_WRITING, &cfg.output.display().to_string());
    let Some(built) = built else {
        ckpt.finish_part(&cfg.output)?;
        progress.finish();
        if !args.quiet {
            eprintln!(
                "wrote part {} ({wall:.1} s); merge all parts with `sweep merge PARTS... -o TABLE`",
                cfg.output.display()
            );
        }
        return Ok(());
    };
    let written = write_table(&cfg.output, &built, &provenance(&cfg, text, wall));
    progress.finish();
    written?;
    ckpt.remove()?;
    drop(lock);
    if !args.quiet {
        summary(&cfg, &built, wall);
    }
    Ok(())
}

/// What was written: per patch, then the whole table.
pub(crate) fn summary(cfg: &Config, built: &Built, wall: f64) {
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
            cfg.output.display(),
            built.checks.len()
        );
}
