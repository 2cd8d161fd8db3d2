//! `sweep scene`: evaluate a scene file, write its CSV and plot, print a summary.

use crate::failure::outln;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::failure::{Context, Result};
use clap::Args;

use oblique_lookup::Table;
use oblique_physics::regimes::Regime;
use oblique_study::scene::{self, Dissipation, PSource, RowMethod, Scene, SceneTarget};

#[derive(Args)]
pub struct SceneArgs {
    /// Scene file (TOML; see configs/scenes/ and docs/scenes.md).
    scene: PathBuf,
    /// Look P up in this table (written by `sweep run`) instead of simulating each case.
    #[arg(long)]
    table: Option<PathBuf>,
    /// Output folder for NAME.csv and NAME.png, NAME being the scene's name (created if missing).
    #[arg(short, long, default_value = ".")]
    output: PathBuf,
    /// Also write the plot as NAME.svg.
    #[arg(long)]
    svg: bool,
    /// Write nothing: compare what would be written with the files in the output folder and
    /// exit with status 1, naming the files, if any differs or is missing (shipped outputs:
    /// `sweep scene configs/scenes/seed000_alumina_on_glass.toml -o docs/figures --check`).
    #[arg(long)]
    check: bool,
}

/// The command line that reproduces the output, for the figure's caption (no output folder:
/// the caption must not depend on where the files go).
fn command_line(args: &SceneArgs) -> String {
    let mut c = format!("sweep scene {}", args.scene.display());
    if let Some(t) = &args.table {
        c.push_str(&format!(" --table {}", t.display()));
    }
    c
}

/// Compare the bytes `want` with the file at `path`; a line for the report if they differ.
fn stale(path: &Path, want: &[u8]) -> Option<String> {
    match std::fs::read(path) {
        Ok(have) if have == want => None,
        Ok(_) => Some(format!("{} differs", path.display())),
        Err(_) => Some(format!("{} is missing", path.display())),
    }
}

/// `--check`: what `run` would write, compared with the files there. Figures are rendered into
/// a scratch folder and read back.
fn check(
    args: &SceneArgs,
    csv: &[u8],
    fig: &oblique_plot::Figure,
    paths: &[&PathBuf],
) -> Result<Vec<String>> {
    let mut report: Vec<String> = stale(paths[0], csv).into_iter().collect();
    let scratch = std::env::temp_dir().join(format!("sweep-scene-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)
        .with_context(|| format!("cannot create {}", scratch.display()))?;
    let result = (|| -> Result<()> {
        for path in &paths[1..] {
            let tmp = scratch.join(path.file_name().unwrap_or_default());
            oblique_plot::render(fig, &tmp)?;
            let want = std::fs::read(&tmp)
                .with_context(|| format!("cannot read back {}", tmp.display()))?;
            report.extend(stale(path, &want));
        }
        Ok(())
    })();
    let _ = std::fs::remove_dir_all(&scratch);
    result?;
    if !report.is_empty() {
        return Err(anyhow::anyhow!(
            "{} file(s) are not what `{} -o {}` writes now (regenerate them with it):\n  {}",
            report.len(),
            command_line(args),
            args.output.display(),
            report.join("\n  ")
        )
        .into());
    }
    Ok(paths.iter().map(|p| p.display().to_string()).collect())
}

pub fn run(args: SceneArgs) -> Result<()> {
    let start = Instant::now();
    if !args.check {
        crate::failure::check_output_folder(&args.output, "-o")?;
    }
    let scene = Scene::load(&args.scene)?;
    let table = match &args.table {
        Some(p) => Some(Table::open(p)?),
        None => None,
    };
    let source = match &table {
        Some(t) => PSource::Table(t),
        None => PSource::Simulate,
    };
    let ev = scene::evaluate(&scene, source)?;
    let sphere_sphere = matches!(scene.target, SceneTarget::Sphere { .. });
    let csv_path = args.output.join(format!("{}.csv", scene.name));
    let png_path = args.output.join(format!("{}.png", scene.name));
    let svg_path = args.output.join(format!("{}.svg", scene.name));
    let paths: Vec<&PathBuf> = [&csv_path, &png_path]
        .into_iter()
        .chain(args.svg.then_some(&svg_path))
        .collect();
    let fig = scene::figure::figure(&scene, &ev, &command_line(&args));
    let written = if args.check {
        let mut csv = Vec::new();
        scene::csv::write(&ev, sphere_sphere, &mut csv).context("cannot format the CSV")?;
        check(&args, &csv, &fig, &paths)?
    } else {
        crate::failure::create_output_folder(&args.output, "-o")?;
        // Nothing is written unless every output can be.
        for path in &paths {
            oblique_output::check_output(path)?;
        }
        // The CSV and the figures are replaced together: all new, or (on a full disk, the file
        // size limit, a failed drawing) all as they were.
        let mut files = oblique_output::Files::new();
        files.write_with(&csv_path, |mut w| {
            scene::csv::write(&ev, sphere_sphere, &mut w)
        })?;
        for path in &paths[1..] {
            oblique_plot::render_into(&fig, path, &mut files)?;
        }
        files.commit()?;
        paths.iter().map(|p| p.display().to_string()).collect()
    };

    outln!("scene {} ({})", scene.name, args.scene.display())?;
    if !scene.description.is_empty() {
        outln!("  {}", scene.description)?;
    }
    let target = match &scene.target {
        SceneTarget::Wall { material } => format!("the {} wall", material.describe()),
        SceneTarget::Sphere { body, material, .. } => format!(
            "the {} sphere (R = {:.4e} m, m = {:.4e} kg, kappa = {:.4})",
            material.describe(),
            body.radius,
            body.mass,
            body.kappa
        ),
    };
    outln!(
        "  {} sphere (R = {:.4e} m, m = {:.4e} kg, kappa = {:.4}) on {target}, mu = {}",
        scene.sphere_material.describe(),
        scene.sphere.radius,
        scene.sphere.mass,
        scene.sphere.kappa,
        scene.friction
    )?;
    outln!(
        "  gamma = {:.6}  (E* = {:.4e} Pa, G* = {:.4e} Pa, m* = {:.4e} kg, m_t = {:.4e} kg, R* = {:.4e} m)",
        ev.gamma, ev.e_star, ev.g_star, ev.normal_mass, ev.tangential_mass, ev.effective_radius
    )?;
    if let Some((lo, hi)) = ev.e_n_range().filter(|_| ev.dissipative) {
        let from = match scene.dissipation {
            Dissipation::RelaxationTime(tau) => {
                format!("Kelvin-Voigt law, relaxation time {tau:e} s with each case's impact speed")
            }
            Dissipation::YieldPressure(p) => {
                format!("Thornton's law, limiting pressure {p:e} Pa with each case's impact speed")
            }
            _ => "Kelvin-Voigt law".to_string(),
        };
        if lo == hi {
            outln!("  e_n = {lo} ({from})")?;
        } else {
            outln!("  e_n {lo:.6} .. {hi:.6} ({from})")?;
        }
    }
    let cases = ev.rows.iter().filter(|r| r.in_scene).count();
    match ev.alpha_range() {
        Some((lo, hi)) => outln!(
            "  alpha {lo:.4e} .. {hi:.4e} (alpha_c1 = {:.6}, alpha_c2 = {:.6}): {} full-slip, {} partial-slip, {} stick, {} normal",
            ev.alpha_c1,
            ev.alpha_c2,
            ev.count_regime(Regime::FullSlip),
            ev.count_regime(Regime::PartialSlip),
            ev.count_regime(Regime::Stick),
            ev.count(RowMethod::NormalImpact)
        )?,
        None => outln!("  alpha = inf for every case")?,
    }
    outln!(
        "  {cases} cases: {} simulated, {} interpolated, {} closed form, {} pure normal; max error of P {:.1e}",
        ev.count(RowMethod::Simulated),
        ev.count(RowMethod::Table),
        ev.count(RowMethod::ClosedForm),
        ev.count(RowMethod::NormalImpact),
        ev.max_p_error()
    )?;
    outln!("  P: {}", ev.source)?;
    outln!(
        "  evaluated in {:.3} s ({:.3} s in all)",
        ev.elapsed_s,
        start.elapsed().as_secs_f64()
    )?;
    if let (Some(rms), Some(m)) = (&ev.rms, &scene.measured) {
        let part = |v: Option<(f64, usize)>, unit: &str| match v {
            Some((r, n)) => format!("{r:.4}{unit} (n = {n})"),
            None => "-".into(),
        };
        outln!(
            "  RMS model - measured: e_t {}, omega {}  [{}]",
            part(rms.e_t, ""),
            part(rms.omega, " rad/s"),
            m.source
        )?;
    }
    if args.check {
        outln!("up to date: {}", written.join(", "))?;
    } else {
        outln!("wrote {}", written.join(", "))?;
    }
    Ok(())
}
