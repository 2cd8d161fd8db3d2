//! `sweep export`: a table (or the curves of a few γ) in the flat little-endian layout that the
//! dependency-free evaluator `include/oblique_eval.h` reads, as a binary file or a C source.

use crate::failure::outln;
use std::path::PathBuf;

use clap::{Args, ValueEnum};

use crate::failure::{Failure, Result};
use oblique_lookup::{OutOfDomain, Table};
use oblique_table::export;

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The export's bytes (memory-map or read them, then `oblq_open`).
    Binary,
    /// A C source file defining the bytes as an array (compile the table in).
    C,
}

#[derive(Args)]
pub struct ExportArgs {
    /// Table file written by `sweep run`.
    table: PathBuf,
    /// Output file (written atomically: a temporary file next to it, then renamed).
    #[arg(short, long)]
    output: PathBuf,
    /// Also store the precomputed curve P(alpha) of this gamma (repeat for several pairs of
    /// materials; each inside the table's gamma domain).
    #[arg(long = "gamma", value_name = "GAMMA", allow_hyphen_values = true)]
    gammas: Vec<f64>,
    /// Store only the curves of --gamma, not the whole table (a few KB instead of MB).
    #[arg(long, requires = "gammas")]
    curves_only: bool,
    /// Binary or C source [default: c when the output ends in .c or .h, else binary].
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Name of the array in a C source: a C identifier that is no C or C++ keyword, nothing
    /// <stddef.h> defines (size_t, NULL, ...) and not reserved (__x, _X).
    #[arg(long, default_value = "oblique_table")]
    name: String,
}

/// Run `sweep export`.
pub fn run(args: ExportArgs) -> Result<()> {
    // Checked whatever the format: a name a compiler refuses is a mistake before any work.
    export::check_c_name(&args.name).map_err(|e| Failure::usage(format!("--name: {e}")))?;
    if args.output.is_dir() {
        return Err(Failure::usage(format!(
            "--output {}: is a directory; give a file name",
            args.output.display()
        )));
    }
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty()) {
        if !dir.is_dir() {
            return Err(Failure::usage(format!(
                "--output {}: the folder {} {}",
                args.output.display(),
                dir.display(),
                if dir.exists() {
                    "exists and is not a folder"
                } else {
                    "does not exist"
                }
            )));
        }
    }
    // A device, FIFO or symbolic link at the output is not replaced by a file, and the table
    // being read is not overwritten (also under another name or a hard link).
    oblique_output::check_output_not_input(&args.output, &[&args.table])?;
    let table = Table::open(&args.table)?;
    let axis = table.surface().restitution();
    if let (Some((lo, hi)), false) = (axis, args.gammas.is_empty()) {
        return Err(Failure::usage(format!(
            "--gamma: {} has an e_n axis (e_n in [{lo}, {hi}]); curves P(alpha) hold elastic \
             tables only: export the table without --gamma and query it with oblq_p_e",
            args.table.display()
        )));
    }
    // A mapped e_n axis is written as layout version 8, which holds tables over a range of
    // gamma (the builder makes no other).
    let e_map = table.surface().e_n_map();
    let mapped = e_map != oblique_table::surface::AxisMap::Linear;
    if mapped && table.surface().pair_gamma().is_some() {
        return Err(Failure::usage(format!(
            "{}: the table of one pair with its e_n axis mapped as '{}' (schema 5), which the \
             export layout does not hold: query it with sweep query, Python or the Rust crate \
             oblique-lookup",
            args.table.display(),
            e_map.name()
        )));
    }
    let mut curves = Vec::with_capacity(args.gammas.len());
    let (g_min, g_max) = (table.surface().gamma_min(), table.surface().gamma_max());
    for &g in &args.gammas {
        // A curve is a whole P(α) at one γ of the table: export has no clamping, so the message
        // names the table's γ range only.
        if !(g >= g_min && g <= g_max) {
            return Err(Failure::usage(format!(
                "--gamma {g}: outside the table's gamma domain [{g_min}, {g_max}]"
            )));
        }
        let curve = table.curve(g, OutOfDomain::Error)?;
        let data = curve
            .export_data()
            .ok_or_else(|| Failure::usage(format!("--gamma {g}: outside the table's domain")))?;
        curves.push(data);
    }
    let bytes = export::export(
        table.surface(),
        table.error_bound(),
        !args.curves_only,
        &curves,
    );
    let c_by_name = args
        .output
        .extension()
        .is_some_and(|e| e == "c" || e == "h");
    let format = args
        .format
        .unwrap_or(if c_by_name { Format::C } else { Format::Binary });
    let pair = table.surface().pair_gamma();
    // A table without a closed-form full-slip line (Thornton's law): layout version 4.
    let law = (!table.surface().has_line()).then(|| table.provenance().law.clone());
    let what = format!(
        "{}{} from {}{}",
        match (axis, pair) {
            (Some(_), Some(g)) => format!("P(alpha, e_n) at gamma = {g}"),
            (Some(_), None) => "P(gamma, alpha, e_n)".to_string(),
            (None, _) => "P(gamma, alpha)".to_string(),
        },
        law.as_ref()
            .map(|l| format!(" of the {l} law"))
            .unwrap_or_default(),
        args.table.display(),
        if args.gammas.is_empty() {
            String::new()
        } else {
            format!(
                ", curves at gamma = {}",
                args.gammas
                    .iter()
                    .map(|g| g.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    );
    let content = match format {
        Format::Binary => bytes.clone(),
        Format::C => export::c_source(&bytes, &args.name, &what)
            .map_err(|e| Failure::usage(format!("--name: {e}")))?
            .into_bytes(),
    };
    // A temporary file beside the output, synced, then renamed (`oblique_output`); it also
    // removes the temporary files that a killed export of the same output left.
    oblique_output::write_bytes(&args.output, &content)?;
    outln!(
        "wrote {} ({} bytes{}): {}{} curve{}, stated error bound {:.2e}",
        args.output.display(),
        content.len(),
        if format == Format::C {
            format!(", a C source of {} export bytes", bytes.len())
        } else {
            String::new()
        },
        match (args.curves_only, axis) {
            (true, _) => String::new(),
            (false, None) => "the table and ".into(),
            (false, Some((lo, hi))) => match pair {
                Some(g) => format!("the table of one pair (gamma = {g}, e_n in [{lo}, {hi}]) and "),
                None => {
                    // The map of a schema-5 table's axis (layout version 8).
                    let over = if mapped {
                        format!(", over {}", e_map.name())
                    } else {
                        String::new()
                    };
                    match &law {
                        Some(l) => {
                            format!("the table of the {l} law (e_n in [{lo}, {hi}]{over}) and ")
                        }
                        None => format!("the table (e_n in [{lo}, {hi}]{over}) and "),
                    }
                }
            },
        },
        curves.len(),
        if curves.len() == 1 { "" } else { "s" },
        table.error_bound()
    )?;
    Ok(())
}
