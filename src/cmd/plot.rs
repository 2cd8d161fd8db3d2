//! `sweep plot`: the figures of a table (`oblique_study::figures`), written as PNG or SVG.

use crate::failure::outln;
use std::path::PathBuf;
use std::time::Instant;

use crate::failure::{Failure, Result};
use clap::{Args, ValueEnum};

use oblique_lookup::Table;
use oblique_study::figures::{self, FigureKind, Source};

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// Bitmap (default).
    Png,
    /// Vector.
    Svg,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FigureArg {
    /// p_surface: P(gamma, alpha) colour map with contours, alpha_c1, alpha_c2, isotropic band.
    Surface,
    /// p_slices: P against alpha for fixed gamma; P against gamma for fixed alpha, with fit (29).
    Slices,
    /// regimes: full slip / partial slip / stick in the (gamma, alpha) plane.
    Regimes,
    /// check_errors: interpolation error at the held-out checks.
    Quality,
    /// p_restitution: P against alpha at fixed gamma for several e_n beside the elastic curve
    /// (a table with an e_n axis; only when asked for).
    Restitution,
}

impl From<FigureArg> for FigureKind {
    fn from(f: FigureArg) -> Self {
        match f {
            FigureArg::Surface => FigureKind::Surface,
            FigureArg::Slices => FigureKind::Slices,
            FigureArg::Regimes => FigureKind::Regimes,
            FigureArg::Quality => FigureKind::Quality,
            FigureArg::Restitution => FigureKind::Restitution,
        }
    }
}

#[derive(Args)]
pub struct PlotArgs {
    /// Table file written by `sweep run` (HDF5, schema v2 or v3).
    table: PathBuf,
    /// Output folder (created if missing).
    #[arg(short, long, default_value = ".")]
    output: PathBuf,
    /// Image format.
    #[arg(long, value_enum, default_value = "png")]
    format: FormatArg,
    /// Only this figure (repeat for several); all four by default (restitution only when
    /// named).
    #[arg(long = "figure", value_enum)]
    figures: Vec<FigureArg>,
    /// gamma values of the P-against-alpha panel, comma-separated (default: round values in the
    /// table's domain).
    #[arg(long, value_delimiter = ',', value_parser = parse_number, allow_hyphen_values = true)]
    gammas: Vec<f64>,
    /// alpha values of the P-against-gamma panel, comma-separated; `inf` is the no-slip limit
    /// (default: 0.3,0.5,0.7,1,2,4,12,inf).
    #[arg(long, value_delimiter = ',', value_parser = parse_number, allow_hyphen_values = true)]
    alphas: Vec<f64>,
    /// e_n values of the restitution figure, comma-separated, in the table's e_n range
    /// (default: 0.5,0.7,0.9,1 where it covers them; 1 is the elastic curve).
    #[arg(long = "e-n", value_delimiter = ',', value_parser = parse_number, allow_hyphen_values = true)]
    e_ns: Vec<f64>,
}

fn parse_number(s: &str) -> Result<f64, String> {
    let t = s.trim().to_ascii_lowercase();
    match t.as_str() {
        "inf" | "infinity" | "+inf" | "∞" => Ok(f64::INFINITY),
        _ => match t.parse::<f64>() {
            Ok(v) if !v.is_nan() => Ok(v),
            _ => Err(format!("`{s}` is not a number")),
        },
    }
}

fn command_line(args: &PlotArgs) -> String {
    let mut c = format!("sweep plot {}", args.table.display());
    c.push_str(&format!(" -o {}", args.output.display()));
    if args.format == FormatArg::Svg {
        c.push_str(" --format svg");
    }
    for f in &args.figures {
        if let Some(v) = f.to_possible_value() {
            c.push_str(&format!(" --figure {}", v.get_name()));
        }
    }
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| {
                if x.is_infinite() {
                    "inf".to_string()
                } else {
                    x.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join(",")
    };
    if !args.gammas.is_empty() {
        c.push_str(&format!(" --gammas {}", list(&args.gammas)));
    }
    if !args.alphas.is_empty() {
        c.push_str(&format!(" --alphas {}", list(&args.alphas)));
    }
    if !args.e_ns.is_empty() {
        c.push_str(&format!(" --e-n {}", list(&args.e_ns)));
    }
    c
}

pub fn run(args: PlotArgs) -> Result<()> {
    let start = Instant::now();
    let table = Table::open(&args.table)?;
    let src = Source {
        table: args.table.display().to_string(),
        command: command_line(&args),
    };
    let kinds: Vec<FigureKind> = if args.figures.is_empty() {
        FigureKind::ALL.to_vec()
    } else {
        let mut k: Vec<FigureKind> = Vec::new();
        for f in &args.figures {
            let f = FigureKind::from(*f);
            if !k.contains(&f) {
                k.push(f);
            }
        }
        k
    };
    let gammas = if args.gammas.is_empty() {
        figures::default_gammas(&table)
    } else {
        args.gammas.clone()
    };
    let alphas = if args.alphas.is_empty() {
        figures::default_alphas(&table)
    } else {
        args.alphas.clone()
    };
    let e_ns = if args.e_ns.is_empty() {
        figures::default_restitutions(&table)
    } else {
        args.e_ns.clone()
    };
    crate::failure::check_output_folder(&args.output, "-o")?;
    // Build every figure first: a bad option fails before anything is written.
    let sheets = kinds
        .iter()
        .map(|&k| {
            let restitution_gammas;
            let gammas = if k == FigureKind::Restitution && args.gammas.is_empty() {
                restitution_gammas = figures::default_restitution_gammas(&table);
                &restitution_gammas
            } else {
                &gammas
            };
            let sheet =
                figures::build(k, &table, &src, gammas, &alphas, &e_ns).map_err(|e| match e {
                    // The library names the option; on the command line it is the flag.
                    figures::FigureError::Invalid { name, message } => {
                        Failure::usage(format!("invalid --{name}: {message}"))
                    }
                    other => other.into(),
                })?;
            Ok((k, sheet))
        })
        .collect::<Result<Vec<_>>>()?;
    crate::failure::create_output_folder(&args.output, "-o")?;
    let ext = match args.format {
        FormatArg::Png => "png",
        FormatArg::Svg => "svg",
    };
    let paths: Vec<PathBuf> = sheets
        .iter()
        .map(|(kind, _)| args.output.join(format!("{}.{ext}", kind.stem())))
        .collect();
    for path in &paths {
        oblique_output::check_output(path)?;
    }
    // The figures are replaced together: all new, or (on a full disk, the file size limit, a
    // failed drawing) all as they were.
    let mut files = oblique_output::Files::new();
    for ((_, sheet), path) in sheets.iter().zip(&paths) {
        oblique_plot::render_sheet_into(sheet, path, &mut files)?;
    }
    files.commit()?;
    for ((kind, _), path) in sheets.iter().zip(&paths) {
        outln!("wrote {}  ({})", path.display(), kind.describe())?;
    }
    outln!(
        "{} figure(s) of {} in {:.2} s",
        sheets.len(),
        args.table.display(),
        start.elapsed().as_secs_f64()
    )?;
    Ok(())
}
