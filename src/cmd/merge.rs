//! `sweep merge`: the table of a sharded run from its parts.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::failure::Result;
use clap::Args;

use oblique_output::check_output_not_input;
use oblique_sweep::job::check_writable;
use oblique_sweep::nodestore::{Merged, OutputLock};
use oblique_sweep::{provenance, Config, RunOptions};
use oblique_table::write::write_table;

use super::run::summary;

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

/// `sweep merge`: the table of a sharded run from its parts.
pub fn run(args: MergeArgs) -> Result<()> {
    let inputs: Vec<&Path> = args.parts.iter().map(PathBuf::as_path).collect();
    check_output_not_input(&args.output, &inputs)?;
    let merged = Merged::read(&args.parts)?;
    let (mut cfg, text) = (
        Config::parse(&merged.config, "config stored in the parts")?,
        merged.config.clone(),
    );
    cfg.output = args.output;
    cfg.derived_check_tol = oblique_sweep::check_tol_in_store(&cfg, &merged);
    check_writable(&cfg.output)?;
    let _lock = OutputLock::acquire(&cfg.output, "sweep merge")?;
    let opts = RunOptions {
        store: Some(&merged),
        strict: true,
        stop: None,
    };
    let start = Instant::now();
    let built = oblique_sweep::build_with(&cfg, &oblique_sweep::Silent, opts)?;
    let wall = start.elapsed().as_secs_f64();
    write_table(&cfg.output, &built, &provenance(&cfg, text, wall))?;
    if !args.quiet {
        summary(&cfg.output, &built, wall);
    }
    Ok(())
}
