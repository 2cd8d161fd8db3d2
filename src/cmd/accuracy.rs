//! `sweep accuracy`: the accuracy-against-cost study (library: `oblique_study::accuracy`).

use crate::failure::outln;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::failure::{Context, Result};
use clap::Args;

use oblique_plot::{Figure, Legend, Panel, Series, Style};
use oblique_solver::Law;
use oblique_study::accuracy::{self, Settings};
use oblique_sweep::provenance;
use oblique_sweep::{Config, Silent};
use oblique_table::write::write_table;

#[derive(Args)]
pub struct AccuracyArgs {
    /// Output directory (created if missing) for accuracy.csv, accuracy.png, presets.csv,
    /// reach.csv and, with --tables, tables.csv and tables.png.
    #[arg(long, short, default_value = "accuracy-out")]
    out: PathBuf,
    /// Smaller ladders and a coarser reference (seconds; for a quick look, not for publishing).
    #[arg(long)]
    quick: bool,
    /// Also build configs/quick.toml, configs/isotropic.toml, configs/full.toml and a denser
    /// variant of full.toml (target error / 2, node tolerance / 4) into a temporary directory and
    /// report nodes, build time, file size and held-out error (about 6 minutes of CPU).
    #[arg(long)]
    tables: bool,
    /// Directory of the configs used by --tables.
    #[arg(long, default_value = "configs")]
    configs: PathBuf,
    /// Normal restitution of every impact, from 0.3 to 1 (1: elastic, the default). Below 1 the
    /// study measures the Kelvin-Voigt law (its reference, fixed ladder and presets); it has no
    /// Euler series, so the comparison with the seed scheme is left out.
    #[arg(long = "e-n", value_parser = crate::args::parse_e_n, default_value = "1", conflicts_with = "tables")]
    e_n: f64,
    /// The dissipative law of the study below e_n = 1: kelvin-voigt (the default) or thornton
    /// (elastic-perfectly plastic).
    #[arg(long, value_parser = crate::args::parse_law)]
    law: Option<Law>,
}

fn command_line() -> String {
    let args: Vec<String> = std::env::args().skip(1).collect();
    format!("sweep {}", args.join(" "))
}

pub fn run(args: AccuracyArgs) -> Result<()> {
    crate::failure::create_output_folder(&args.out, "--out")?;
    if args.tables {
        // Fail on a bad config before minutes of scheme ladders.
        for name in ["quick", "isotropic", "full"] {
            Config::load(&args.configs.join(format!("{name}.toml")))?;
        }
    }
    let set = Settings {
        e_n: args.e_n,
        law: args.law,
        ..if args.quick {
            Settings::quick()
        } else {
            Settings::default()
        }
    };
    let cmd = command_line();
    let points = accuracy::study_points();
    let mut rows = Vec::new();
    let mut reaches = Vec::new();
    let start = Instant::now();
    eprintln!(
        "{} points{}; reference: accurate scheme to {} steps (Richardson); times are thread CPU time",
        points.len(),
        if set.e_n < 1.0 {
            format!(
                ", e_n = {} ({})",
                set.e_n,
                set.law
                    .unwrap_or_else(|| Law::for_restitution(set.e_n))
                    .name()
            )
        } else {
            String::new()
        },
        set.reference_steps
    );
    for pt in &points {
        let (reference, pr) = accuracy::study_point(pt, &set)?;
        eprintln!(
            "  {:42} P_ref = {:+.12} (+/- {:.0e})",
            pt.label, reference.p, reference.error_estimate
        );
        for target in [1e-4, 1e-6] {
            if let Some(r) = accuracy::reach(&pr, target) {
                reaches.push(r);
            }
        }
        rows.extend(pr);
    }
    oblique_output::write_bytes(
        &args.out.join("accuracy.csv"),
        accuracy::csv(&rows).as_bytes(),
    )?;
    let fig = accuracy::figure(&points, &rows, &set, &cmd);
    oblique_plot::render_log_log(&fig, &args.out.join("accuracy.png"))?;
    // Presets.
    let presets = accuracy::preset_summaries(&rows);
    let mut pcsv = String::from("preset,tol,max_error,max_estimate,median_cpu_s,max_cpu_s\n");
    outln!("preset     tol     max true error  max estimate  CPU time per impact: median   max")?;
    for p in &presets {
        pcsv.push_str(&format!(
            "{},{:e},{:e},{:e},{:e},{:e}\n",
            p.preset.name(),
            p.tol,
            p.max_error,
            p.max_estimate,
            p.median_time,
            p.max_time
        ));
        outln!(
            "{:9} {:7.0e}  {:14.1e}  {:12.1e}  {:>26}  {}",
            p.preset.name(),
            p.tol,
            p.max_error,
            p.max_estimate,
            fmt_time(p.median_time),
            fmt_time(p.max_time)
        )?;
    }
    oblique_output::write_bytes(&args.out.join("presets.csv"), pcsv.as_bytes())?;
    if set.e_n < 1.0 {
        outln!("(e_n < 1: no Euler series, so no comparison with the seed scheme; reach.csv not written)")?;
    } else {
        // Where each scheme reaches the targets.
        let mut rcsv = String::from(
            "point,target,accurate_tol_cpu_s,accurate_fixed_cpu_s,euler_C,euler_measured_cpu_s,euler_cpu_s,euler_cpu_s_lower,ratio,ratio_lower\n",
        );
        outln!()?;
        outln!("target  point                                       accurate(tol)  euler C   euler (extrap.)  euler/accurate (lower bound)")?;
        let opt = |v: Option<f64>| v.map(|x| format!("{x:e}")).unwrap_or_default();
        for r in &reaches {
            let ratio = r.accurate_tol_time.map(|t| r.euler_time / t);
            let lower = r.accurate_tol_time.map(|t| r.euler_time_lower / t);
            rcsv.push_str(&format!(
                "\"{}\",{:e},{},{},{:.3},{},{:e},{:e},{},{}\n",
                r.point,
                r.target,
                opt(r.accurate_tol_time),
                opt(r.accurate_fixed_time),
                r.euler_constant,
                opt(r.euler_measured_time),
                r.euler_time,
                r.euler_time_lower,
                opt(ratio),
                opt(lower)
            ));
            outln!(
                "{:6.0e}  {:42} {:>13}  {:7.2}  {:>15}{}  {:>9} ({})",
                r.target,
                r.point,
                r.accurate_tol_time.map_or("-".into(), fmt_time),
                r.euler_constant,
                fmt_time(r.euler_time),
                if r.euler_measured_time.is_some() {
                    " "
                } else {
                    "*"
                },
                ratio.map_or("-".into(), |x| format!("{x:.0}x")),
                lower.map_or("-".into(), |x| format!("{x:.0}x")),
            )?;
        }
        oblique_output::write_bytes(&args.out.join("reach.csv"), rcsv.as_bytes())?;
        outln!("(* extrapolated from the finest Euler runs: error = C/steps)")?;
    }
    eprintln!(
        "wrote {}/accuracy.csv, accuracy.png, presets.csv{} ({} rows) in {:.1} s",
        args.out.display(),
        if set.e_n < 1.0 { "" } else { ", reach.csv" },
        rows.len(),
        start.elapsed().as_secs_f64()
    );
    if args.tables {
        tables(&args)?;
    }
    Ok(())
}

fn fmt_time(t: f64) -> String {
    if t >= 1.0 {
        format!("{t:.2} s")
    } else if t >= 1e-3 {
        format!("{:.2} ms", t * 1e3)
    } else {
        format!("{:.1} us", t * 1e6)
    }
}

/// One table build of the table-level trade.
struct TableRow {
    name: String,
    target_error: f64,
    tol: f64,
    nodes: usize,
    simulated: usize,
    wall_s: f64,
    cpu_s: Option<f64>,
    bytes: u64,
    checks: usize,
    max_error: f64,
    rms_error: f64,
}

fn build_one(name: &str, cfg: &Config, text: &str, dir: &Path) -> Result<TableRow> {
    let out = dir.join(format!("{name}.h5"));
    let cpu0 = oblique_clock::process_cpu_time();
    let start = Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cfg.run.threads)
        .build()
        .context("cannot start worker threads")?;
    let built = pool.install(|| oblique_sweep::build(cfg, &Silent))?;
    let wall = start.elapsed().as_secs_f64();
    let cpu = match (cpu0, oblique_clock::process_cpu_time()) {
        (Some(a), Some(b)) => Some((b - a).as_secs_f64()),
        _ => None,
    };
    let prov = provenance(cfg, text.to_string(), wall);
    write_table(&out, &built, &prov)?;
    let bytes = std::fs::metadata(&out).map(|m| m.len()).unwrap_or(0);
    let _ = std::fs::remove_file(&out);
    let errs: Vec<f64> = built.checks.iter().map(|c| c.interpolation_error).collect();
    let max_error = errs.iter().copied().fold(0.0, f64::max);
    let rms_error = (errs.iter().map(|e| e * e).sum::<f64>() / errs.len().max(1) as f64).sqrt();
    Ok(TableRow {
        name: name.to_string(),
        target_error: cfg.nodes.target_error,
        tol: cfg.solver.tol,
        nodes: built.patches.iter().map(|p| p.unique_nodes).sum(),
        simulated: built.patches.iter().map(|p| p.simulated).sum(),
        wall_s: wall,
        cpu_s: cpu,
        bytes,
        checks: errs.len(),
        max_error,
        rms_error,
    })
}

/// The table-level trade: quick, isotropic, full and a denser full (`nodes.target_error / 2`,
/// `solver.tol / 4`, `nodes.max_nodes × 4`), the densest variant that builds in minutes.
fn tables(args: &AccuracyArgs) -> Result<()> {
    let dir = std::env::temp_dir().join(format!("oblique-accuracy-{}", std::process::id()));
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create temporary directory {}", dir.display()))?;
    let mut jobs = Vec::new();
    for name in ["quick", "isotropic", "full"] {
        let (cfg, text) = Config::load(&args.configs.join(format!("{name}.toml")))?;
        jobs.push((name.to_string(), cfg, text));
    }
    let (mut dense, text) = Config::load(&args.configs.join("full.toml"))?;
    dense.nodes.target_error /= 2.0;
    dense.solver.tol /= 4.0;
    dense.nodes.max_nodes = dense.nodes.max_nodes.saturating_mul(4);
    let dense_text = format!(
        "{text}\n# sweep accuracy --tables: denser variant, nodes.target_error = {:e}, solver.tol = {:e}\n",
        dense.nodes.target_error, dense.solver.tol
    );
    jobs.push(("full-dense".into(), dense, dense_text));
    let mut rows = Vec::new();
    for (name, cfg, text) in &jobs {
        eprintln!(
            "building {name} (target_error {:e}, solver.tol {:e}) ...",
            cfg.nodes.target_error, cfg.solver.tol
        );
        let row = build_one(name, cfg, text, &dir)?;
        eprintln!(
            "  {} nodes, {:.1} s wall{}, {:.2} MB, max held-out error {:.2e}",
            row.nodes,
            row.wall_s,
            row.cpu_s
                .map_or(String::new(), |c| format!(" ({c:.1} s CPU)")),
            row.bytes as f64 / 1e6,
            row.max_error
        );
        rows.push(row);
    }
    let _ = std::fs::remove_dir(&dir);
    let mut csv = String::from(
        "config,target_error,solver_tol,nodes,simulated,wall_s,cpu_s,file_bytes,checks,max_check_error,rms_check_error\n",
    );
    for r in &rows {
        csv.push_str(&format!(
            "{},{:e},{:e},{},{},{:.2},{},{},{},{:e},{:e}\n",
            r.name,
            r.target_error,
            r.tol,
            r.nodes,
            r.simulated,
            r.wall_s,
            r.cpu_s.map_or(String::new(), |c| format!("{c:.2}")),
            r.bytes,
            r.checks,
            r.max_error,
            r.rms_error
        ));
    }
    oblique_output::write_bytes(&args.out.join("tables.csv"), csv.as_bytes())?;
    oblique_plot::render_log_log(&tables_figure(&rows), &args.out.join("tables.png"))?;
    eprintln!("wrote {0}/tables.csv, {0}/tables.png", args.out.display());
    Ok(())
}

/// The table-level trade as a picture: held-out error (max and rms) against build CPU time,
/// one colour per domain; full.toml and its denser variant are joined (the same domain).
fn tables_figure(rows: &[TableRow]) -> Figure {
    const COLORS: [(u8, u8, u8); 3] = [(31, 119, 180), (214, 39, 40), (44, 160, 44)];
    let cost = |r: &TableRow| r.cpu_s.unwrap_or(r.wall_s);
    let mut max_series = Vec::new();
    let mut rms_series = Vec::new();
    for (i, domain) in ["quick", "isotropic", "full"].iter().enumerate() {
        let members: Vec<&TableRow> = rows
            .iter()
            .filter(|r| r.name.split('-').next() == Some(domain))
            .collect();
        if members.is_empty() {
            continue;
        }
        let label = members
            .iter()
            .map(|r| format!("{} ({:e}/{:e})", r.name, r.target_error, r.tol))
            .collect::<Vec<_>>()
            .join(", ");
        for (series, value) in [
            (
                &mut max_series,
                (|r: &TableRow| r.max_error) as fn(&TableRow) -> f64,
            ),
            (&mut rms_series, |r: &TableRow| r.rms_error),
        ] {
            series.push(Series {
                label: label.clone(),
                points: members.iter().map(|r| (cost(r), value(r))).collect(),
                style: Style::LineMarkers,
                color: COLORS[i],
                sets_range: true,
            });
        }
    }
    Figure {
        title: "Table error against build cost".into(),
        subtitle: "held-out checks of each table; label: config (target_error/solver.tol)".into(),
        x_label: "build CPU time, all threads (s)".into(),
        panels: vec![
            Panel {
                y_label: "max |P_table − P_check|".into(),
                series: max_series,
                legend: Legend::UpperRight,
                ..Panel::default()
            },
            Panel {
                y_label: "rms |P_table − P_check|".into(),
                series: rms_series,
                legend: Legend::UpperRight,
                ..Panel::default()
            },
        ],
        caption: vec![
            format!("command: {}", command_line()),
            "checks: simulated at solver.tol/10, never used for interpolation (docs/table-format.md)"
                .into(),
        ],
        size: (1000, 800),
    }
}
