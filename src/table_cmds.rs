//! `sweep run` and `sweep inspect`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;

use oblique::nodestore::{fingerprint, Checkpoint, Header, Kind, Merged};
use oblique::storage::{provenance, write_table};
use oblique::sweep::{self, Built, Config, RunError, RunOptions, Shard};
use oblique_lookup::Table;

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

#[derive(Args)]
pub struct MergeArgs {
    /// Part files written by `sweep run CONFIG --shard K/N -o PART`, one per shard.
    #[arg(required = true)]
    parts: Vec<PathBuf>,
    /// Output table.
    #[arg(short, long)]
    output: PathBuf,
    /// No summary output.
    #[arg(long)]
    quiet: bool,
}

/// A usage error of `sweep run`/`sweep merge` (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// Set by the Ctrl-C handler; the sweep stops after its current batch.
static STOP: AtomicBool = AtomicBool::new(false);

fn checkpoint_path(out: &Path) -> PathBuf {
    let mut s = out.as_os_str().to_owned();
    s.push(".ckpt");
    PathBuf::from(s)
}

#[derive(Args)]
pub struct InspectArgs {
    /// Table file written by `sweep run`.
    table: PathBuf,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

/// Fail early (before hours of work) if the output directory cannot take a file.
fn check_writable(out: &std::path::Path) -> Result<()> {
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    std::fs::create_dir_all(dir)
        .with_context(|| format!("output {}: cannot create directory", out.display()))?;
    let probe = dir.join(format!(".sweep-probe-{}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("output {}: directory is not writable", out.display()))?;
    let _ = std::fs::remove_file(probe);
    if out.is_dir() {
        anyhow::bail!("output {} is a directory; give a file path", out.display());
    }
    Ok(())
}

pub fn run(args: RunArgs) -> Result<()> {
    let (mut cfg, text) = Config::load(&args.config)?;
    if let Some(o) = args.output {
        cfg.output = o;
    }
    if let Some(t) = args.threads {
        if t > 1024 {
            return Err(UsageError(format!(
                "--threads {t}: must be in [0, 1024] (0 = one per core)"
            ))
            .into());
        }
        cfg.run.threads = t;
    }
    check_writable(&cfg.output)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.run.threads)
        .build()
        .context("cannot start worker threads")?;
    let pre = sweep::preflight(&cfg)?;
    if !args.quiet {
        eprintln!(
            "preflight: tolerances reachable; the slowest node probed took {:.1} ms",
            pre.slowest_node_s * 1e3
        );
    }
    let ckpt_path = checkpoint_path(&cfg.output);
    let header = Header {
        kind: Kind::Checkpoint,
        shard: args.shard,
        fingerprint: fingerprint(&cfg),
        config: text.clone(),
    };
    let ckpt = if ckpt_path.exists() {
        if !args.resume {
            return Err(UsageError(format!(
                "{} holds the checkpoint of an interrupted run: add --resume to continue it, \
                 or delete it to start over",
                ckpt_path.display()
            ))
            .into());
        }
        let c = Checkpoint::resume(&ckpt_path, header)?;
        if !args.quiet {
            eprintln!(
                "resuming from {}: {} nodes already computed",
                ckpt_path.display(),
                c.resumed_nodes()
            );
        }
        c
    } else {
        Checkpoint::create(&ckpt_path, header)?
    };
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
    let progress = CliProgress::new(args.quiet);
    let start = Instant::now();
    let result = pool.install(|| match args.shard {
        Some(shard) => sweep::build_shard(&cfg, &progress, opts, shard).map(|()| None),
        None => sweep::build_with(&cfg, &progress, opts).map(Some),
    });
    progress.finish();
    let built = match result {
        Err(RunError::Interrupted) => {
            let shard = args
                .shard
                .map(|s| format!(" --shard {}/{}", s.index + 1, s.count))
                .unwrap_or_default();
            eprintln!(
                "interrupted: finished nodes are saved in {}; continue with\n  sweep run {}{shard} -o {} --resume",
                ckpt_path.display(),
                args.config.display(),
                cfg.output.display()
            );
            std::process::exit(130);
        }
        other => other?,
    };
    let wall = start.elapsed().as_secs_f64();
    let Some(built) = built else {
        ckpt.finish_part(&cfg.output)?;
        if !args.quiet {
            eprintln!(
                "wrote part {} ({wall:.1} s); merge all parts with `sweep merge PARTS... -o TABLE`",
                cfg.output.display()
            );
        }
        return Ok(());
    };
    write_built(&cfg, text, &built, wall, args.quiet)?;
    ckpt.remove()?;
    Ok(())
}

/// `sweep merge`: the table of a sharded run from its parts.
pub fn merge(args: MergeArgs) -> Result<()> {
    let merged = Merged::read(&args.parts)?;
    let (mut cfg, text) = (
        Config::parse(&merged.config, "config stored in the parts")?,
        merged.config.clone(),
    );
    cfg.output = args.output;
    check_writable(&cfg.output)?;
    let opts = RunOptions {
        store: Some(&merged),
        strict: true,
        stop: None,
    };
    let start = Instant::now();
    let built = sweep::build_with(&cfg, &sweep::Silent, opts)?;
    write_built(
        &cfg,
        text,
        &built,
        start.elapsed().as_secs_f64(),
        args.quiet,
    )
}

fn write_built(cfg: &Config, text: String, built: &Built, wall: f64, quiet: bool) -> Result<()> {
    let prov = provenance(cfg, text, wall);
    write_table(&cfg.output, built, &prov)?;
    if !quiet {
        let nodes: usize = built.patches.iter().map(|p| p.unique_nodes).sum();
        let simulated: usize = built.patches.iter().map(|p| p.simulated).sum();
        for p in &built.patches {
            eprintln!(
                "  {:13} {} x {} roots, {} leaves at depth {}..{}, {} nodes ({} simulated), max predicted error {:.1e}",
                p.name,
                p.patch.blocks_gamma,
                p.patch.blocks_coord,
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
    Ok(())
}

fn stats(v: impl Iterator<Item = f64>) -> (usize, f64, f64) {
    let (mut n, mut max, mut sq) = (0usize, 0.0_f64, 0.0);
    for x in v {
        n += 1;
        max = max.max(x);
        sq += x * x;
    }
    (n, max, if n > 0 { (sq / n as f64).sqrt() } else { 0.0 })
}

pub fn inspect(args: InspectArgs) -> Result<()> {
    let t = Table::open(&args.table)?;
    let s = &t.surface;
    let patches: Vec<_> = [
        ("stick_low", &s.stick_low),
        ("partial_high", &s.partial_high),
        ("stick_high", &s.stick_high),
    ]
    .into_iter()
    .filter_map(|(n, p)| p.as_ref().map(|p| (n, p)))
    .collect();
    let (nc, cmax, crms) = stats(t.checks.iter().map(|c| c.interpolation_error));
    let pv = &t.provenance;
    if args.json {
        let ps: Vec<_> = patches
            .iter()
            .map(|(n, p)| {
                let depth = p.leaf_depths();
                json!({
                    "name": n, "kind": p.kind.name(), "gamma_lo": p.gamma_lo, "gamma_hi": p.gamma_hi,
                    "blocks_gamma": p.blocks_gamma, "blocks_coord": p.blocks_coord,
                    "leaf_intervals": p.leaf_intervals,
                    "leaves": p.leaves(),
                    "depth_min": depth.iter().min(), "depth_max": depth.iter().max(),
                    "nodes": p.p.len(),
                    "nodes_note": "stored node values; leaves store their shared edges each",
                    "max_node_error_estimate": p.error_estimate.iter().copied().fold(0.0, f64::max),
                    "warp": p.warp.as_ref().map(|w| json!({
                        "start": w.start,
                        "gamma_start": w.start_gamma(p.gamma_lo, p.gamma_hi, p.blocks_gamma),
                        "c_star": w.c_star, "gamma_0": w.gamma_0, "gamma_step": w.gamma_step,
                        "knots": w.knot.len(),
                    })),
                })
            })
            .collect();
        let out = json!({
            "path": args.table.display().to_string(),
            "schema_version": pv.schema_version,
            "gamma_min": s.gamma_min, "gamma_max": s.gamma_max,
            "alpha_max": if s.alpha_max.is_finite() { json!(s.alpha_max) } else { json!("inf") },
            "stencil_points": s.stencil,
            "nodes": patches.iter().map(|(_, p)| p.p.len()).sum::<usize>(),
            "patches": ps,
            "checks": { "count": nc, "max_interpolation_error": cmax, "rms_interpolation_error": crms },
            "error_bound": if t.error_bound().is_nan() { json!(null) } else { json!(t.error_bound()) },
            "provenance": {
                "engine_version": pv.engine_version, "git_commit": pv.git_commit,
                "created": pv.created, "wall_time_s": pv.wall_time_s, "solver": pv.solver,
                "node_tol": pv.node_tol, "check_tol": pv.check_tol, "target_error": pv.target_error, "config": pv.config,
            }
        });
        println!("{out}");
        return Ok(());
    }
    println!("table {}", args.table.display());
    println!(
        "domain gamma in [{}, {}], alpha in [0, {}]; stencil {} points per axis (schema v{})",
        s.gamma_min, s.gamma_max, s.alpha_max, s.stencil, pv.schema_version
    );
    for (n, p) in &patches {
        let depth = p.leaf_depths();
        println!(
            "  {n:13} {:12} gamma [{:.4}, {:.4}]  {} x {} roots, {} leaves at depth {}..{}, {} nodes stored (shared leaf edges once per leaf), max node error estimate {:.1e}",
            p.kind.name(),
            p.gamma_lo,
            p.gamma_hi,
            p.blocks_gamma,
            p.blocks_coord,
            p.leaves(),
            depth.iter().min().unwrap_or(&0),
            depth.iter().max().unwrap_or(&0),
            p.p.len(),
            p.error_estimate.iter().copied().fold(0.0, f64::max)
        );
        if let Some(w) = &p.warp {
            println!(
                "                fold edge: from gamma {} (root row {}) the fold F+ lies on c' = {} (graded below it; {} knots from gamma {}, step {})",
                w.start_gamma(p.gamma_lo, p.gamma_hi, p.blocks_gamma),
                w.start,
                w.c_star,
                w.knot.len(),
                w.gamma_0,
                w.gamma_step
            );
        }
    }
    println!("held-out checks: {nc} points, max interpolation error {cmax:.2e}, rms {crms:.2e}");
    println!(
        "stated error bound: {:.2e} (largest leaf prediction + 2.66 x node error estimate; docs/table-format.md)",
        t.error_bound()
    );
    println!(
        "built {} in {:.1} s by engine {} (commit {}); {}",
        pv.created, pv.wall_time_s, pv.engine_version, pv.git_commit, pv.solver
    );
    Ok(())
}
