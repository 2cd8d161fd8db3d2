//! A table built as `sweep run` builds it, but without the probes of `nodes.probe_kinks`:
//! `cargo run --release -p oblique-tools --bin noprobe -- CONFIG OUT` (`docs/accuracy.md`,
//! "Tables with an e_n axis"). `sweep run` refuses a table with an `e_n` range that reaches the
//! fold F₋ without the probes, since its bound would not hold there; this builds one anyway
//! (CONFIG must set `probe_kinks = true`; the table's stored config says `false`), to measure
//! what the probes change. The build runs on one thread per core, silently.
use std::sync::atomic::AtomicBool;

use anyhow::{bail, Context};
use oblique_sweep::job::Job;
use oblique_sweep::{Config, Silent};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [config, out] = &args[..] else {
        bail!("usage: noprobe CONFIG OUT");
    };
    let (mut cfg, text) = Config::load(config.as_ref())?;
    if !cfg.nodes.probe_kinks {
        bail!("{config}: set nodes.probe_kinks = true (this builds the same table without them)");
    }
    cfg.nodes.probe_kinks = false;
    cfg.output = out.into();
    let text = text.replace("probe_kinks = true", "probe_kinks = false");
    let start = std::time::Instant::now();
    Job::new(cfg, text, "noprobe")
        .run(&Silent, &AtomicBool::new(false))
        .with_context(|| format!("building {out}"))?;
    eprintln!("wrote {out} in {:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}
