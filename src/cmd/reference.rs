//! `sweep reference`: the exact references of the DEM verification suites, as CSVs and figures,
//! with the closed-form checks printed beside the computed values.

use crate::failure::outln;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::failure::{Context, Failure, Result};
use clap::Args;

use oblique_lookup::Table;
use oblique_study::reference::output::{self, Content};
use oblique_study::reference::{self, Method, Suite, SuiteResult};

/// Default tolerance of `P` (absolute).
const DEFAULT_TOL: f64 = 1e-8;

#[derive(Args)]
pub struct ReferenceArgs {
    /// Suite: chung-ooi, mfix-dem05, thornton, seed000, or all.
    suite: String,
    /// Output folder; each suite writes into its own subfolder (created if missing).
    #[arg(short, long, default_value = "reference")]
    output: PathBuf,
    /// Compute every case by direct two-body simulation in SI units instead of the universal
    /// mapping to (gamma, alpha) (slower; the numbers agree within their error bounds).
    #[arg(long, conflicts_with = "table")]
    direct: bool,
    /// Take P(gamma, alpha) from this table (written by `sweep run`) instead of simulating each
    /// case; the error bound of P is then the table's stated bound.
    #[arg(long)]
    table: Option<PathBuf>,
    /// Target absolute error of P where simulated, in [1e-10, 1e-4].
    #[arg(long, default_value = "1e-8")]
    tol: f64,
    /// Write nothing: compare what would be written with the files in the output folder and
    /// exit with status 1, naming the files, if any differs or is missing.
    #[arg(long)]
    check: bool,
}

/// The command line that reproduces the output (no output folder: captions must not depend on
/// where the files go).
fn command_line(args: &ReferenceArgs, suite: Suite) -> String {
    let mut c = format!("sweep reference {}", suite.name());
    if args.direct {
        c.push_str(" --direct");
    }
    if let Some(t) = &args.table {
        c.push_str(&format!(" --table {}", t.display()));
    }
    if args.tol != DEFAULT_TOL {
        c.push_str(&format!(" --tol {:e}", args.tol));
    }
    c
}

fn suites(name: &str) -> Result<Vec<Suite>> {
    if name == "all" {
        return Ok(Suite::ALL.to_vec());
    }
    match Suite::from_name(name) {
        Some(s) => Ok(vec![s]),
        None => Err(Failure::usage(format!(
            "unknown suite `{name}`: must be one of {}, all",
            Suite::ALL.map(|s| s.name()).join(", ")
        ))),
    }
}

/// The bytes of a file as it would be written.
fn bytes(content: &Content, scratch: &Path) -> Result<Vec<u8>> {
    match content {
        Content::Csv(text) => Ok(text.clone().into_bytes()),
        Content::Figure(fig) => {
            let path = scratch.join("figure.png");
            oblique_plot::render(fig, &path)?;
            std::fs::read(&path).with_context(|| format!("cannot read back {}", path.display()))
        }
    }
}

fn print_summary(res: &SuiteResult) -> Result<()> {
    outln!(
        "{}: {} ({} cases in {:.2} s)",
        res.suite.name(),
        res.suite.describe(),
        res.cases(),
        res.elapsed_s
    )?;
    outln!("  {}", res.method)?;
    outln!("  closed-form checks (closed form | computed | difference | bound):")?;
    outln!(
        "  (ok: an exact result, asserted within its bound; fit: a published fit, shown for \
         comparison only, its bound the fit's stated accuracy)"
    )?;
    for c in &res.checks {
        let mark = match (c.exact, c.holds()) {
            (true, true) => "ok  ",
            (true, false) => "FAIL",
            (false, _) => "fit ",
        };
        outln!(
            "    {mark} {}: {}: {:.10e} | {:.10e} | {:+.2e} | {:.1e}",
            c.test,
            c.name,
            c.closed_form,
            c.computed,
            c.difference(),
            c.bound
        )?;
    }
    for (id, rows) in &res.measured {
        let parts: Vec<String> = output::rms(rows)
            .iter()
            .map(|(col, r, n)| format!("{col} {r:.4} (n = {n})"))
            .collect();
        outln!(
            "  {id}: RMS model - measured (Kharaz et al. 2001): {}",
            parts.join(", ")
        )?;
    }
    Ok(())
}

pub fn run(args: ReferenceArgs) -> Result<()> {
    let start = Instant::now();
    let suites = suites(&args.suite)?;
    if !(1e-10..=1e-4).contains(&args.tol) {
        return Err(Failure::usage(format!(
            "invalid --tol {}: must be in [1e-10, 1e-4]",
            args.tol
        )));
    }
    crate::failure::check_output_folder(&args.output, "-o")?;
    for suite in &suites {
        crate::failure::check_output_folder(&args.output.join(suite.name()), "-o")?;
    }
    let table = match &args.table {
        Some(p) => Some(Table::open(p)?),
        None => None,
    };
    let method = match (&table, args.direct) {
        (Some(t), _) => Method::Table(t),
        (None, true) => Method::Direct { tol: args.tol },
        (None, false) => Method::Slice { tol: args.tol },
    };
    let scratch = std::env::temp_dir().join(format!("sweep-reference-{}", std::process::id()));
    let mut failed_checks = 0;
    let mut stale = Vec::new();
    let mut written = 0;
    for suite in suites {
        let res = reference::run(suite, &method)?;
        print_summary(&res)?;
        failed_checks += res.checks.iter().filter(|c| c.exact && !c.holds()).count();
        let files = output::files(&res, &command_line(&args, suite));
        let dir = args.output.join(suite.name());
        if args.check {
            std::fs::create_dir_all(&scratch)
                .with_context(|| format!("cannot create {}", scratch.display()))?;
            for (name, content) in &files {
                let path = dir.join(name);
                let want = bytes(content, &scratch)?;
                match std::fs::read(&path) {
                    Ok(have) if have == want => {}
                    Ok(_) => stale.push(format!("{} differs", path.display())),
                    Err(_) => stale.push(format!("{} is missing", path.display())),
                }
            }
            continue;
        }
        crate::failure::create_output_folder(&dir, "-o")?;
        // Nothing of a suite is written unless every one of its paths can be.
        for (name, _) in &files {
            oblique_output::check_output(&dir.join(name))?;
        }
        // A suite's files are replaced together: all new, or (on a full disk, the file size
        // limit, a failed drawing) all as they were.
        let mut set = oblique_output::Files::new();
        for (name, content) in &files {
            let path = dir.join(name);
            match content {
                Content::Csv(text) => set.write_bytes(&path, text.as_bytes())?,
                Content::Figure(fig) => oblique_plot::render_into(fig, &path, &mut set)?,
            }
        }
        set.commit()?;
        written += files.len();
        outln!("  wrote {} files in {}", files.len(), dir.display())?;
    }
    let _ = std::fs::remove_dir_all(&scratch);
    if args.check {
        if !stale.is_empty() {
            return Err(anyhow::anyhow!(
                "{} file(s) are not what `sweep reference {}` writes now (regenerate them with it, \
                 -o {}):\n  {}",
                stale.len(),
                args.suite,
                args.output.display(),
                stale.join("\n  ")
            )
            .into());
        }
        outln!("every file in {} is up to date", args.output.display())?;
    } else {
        outln!(
            "wrote {written} files in {:.2} s",
            start.elapsed().as_secs_f64()
        )?;
    }
    if failed_checks > 0 {
        return Err(anyhow::anyhow!("{failed_checks} closed-form check(s) failed").into());
    }
    Ok(())
}
