//! `sweep run` and `sweep inspect`.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;

use oblique::storage::{write_table, Provenance};
use oblique::sweep::{self, Config};
use oblique_lookup::Table;

use crate::progress::CliProgress;

#[derive(Args)]
pub struct RunArgs {
    /// TOML config (see configs/ and docs/config.md).
    config: PathBuf,
    /// Output table; overrides the config's `output`.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Worker threads (0 = one per core); overrides `run.threads`.
    #[arg(long)]
    threads: Option<usize>,
    /// No progress output.
    #[arg(long)]
    quiet: bool,
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
            anyhow::bail!("--threads {t}: must be in [0, 1024] (0 = one per core)");
        }
        cfg.run.threads = t;
    }
    check_writable(&cfg.output)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.run.threads)
        .build()
        .context("cannot start worker threads")?;
    let progress = CliProgress::new(args.quiet);
    let start = Instant::now();
    let built = pool.install(|| sweep::build(&cfg, &progress));
    progress.finish();
    let built = built?;
    let wall = start.elapsed().as_secs_f64();
    let prov = Provenance {
        schema_version: oblique_lookup::format::SCHEMA_VERSION,
        engine_version: oblique::VERSION.into(),
        git_commit: oblique::GIT_COMMIT.into(),
        config: text,
        solver: format!(
            "scheme=accurate tol={:e} (automatic refinement, error estimate per node)",
            cfg.solver.tol
        ),
        created: oblique::utc_now(),
        wall_time_s: wall,
        node_tol: cfg.solver.tol,
        check_tol: cfg.check_tol(),
        target_error: cfg.nodes.target_error,
    };
    write_table(&cfg.output, &built, &prov)?;
    if !args.quiet {
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
    }
    println!("held-out checks: {nc} points, max interpolation error {cmax:.2e}, rms {crms:.2e}");
    println!(
        "built {} in {:.1} s by engine {} (commit {}); {}",
        pv.created, pv.wall_time_s, pv.engine_version, pv.git_commit, pv.solver
    );
    Ok(())
}
