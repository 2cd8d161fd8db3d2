//! `sweep`: the command-line front end. Thin: parses arguments, calls the library, prints.

use std::process::ExitCode;
use std::time::Instant;

use anyhow::Result;
use clap::{Args, Parser, Subcommand, ValueEnum};
use serde_json::json;

use oblique_physics::regimes;
use oblique_solver::history::{fold_plus_curve, slip_history, Episode, SlipSign, FOLD_MIN_STEPS};
use oblique_solver::impact::{Limits, ALPHA_NO_SLIP};
use oblique_solver::{Accuracy, Method, PhysicsError, Preset, Resolution, Scheme};
use oblique_sweep::config::ConfigError;

mod cmd;
mod impact_progress;
mod progress;

use cmd::{accuracy as accuracy_cmd, plot as plot_cmd, query as query_cmd, scene as scene_cmd};
use cmd::{table as table_cmds, verify as verify_cmd};

#[derive(Parser)]
#[command(
    name = "sweep",
    version,
    about = "Oblique elastic impacts with friction: the universal tangential restitution P(gamma, alpha)",
    long_about = "Oblique elastic impacts with friction by the method of dimensionality reduction \
(Hertz normal contact, Cattaneo-Mindlin partial slip).\n\n\
Every rebound of a sphere on a half-space is decided by one function P(gamma, alpha):\n  \
gamma = sqrt((7/2) G*/E*)        material group (1.52 < gamma < 2.16 for one isotropic material)\n  \
alpha = mu v_z0 / |v_x0 + R w0|  friction group (alpha = inf: no slip)\n  \
P     = u_after / u_before       restitution of the contact-point velocity u = v_x + R w\n\
For a solid sphere without initial spin, e_t = v_x/v_x0 = (2P + 5)/7."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate one impact in dimensionless form and print P(gamma, alpha) with its error estimate.
    #[command(after_help = "Examples:\n  \
sweep impact --gamma 1.754 --alpha 1\n  \
sweep impact --gamma 1.754 --alpha inf --tol 1e-8 --json\n  \
sweep impact --gamma 1.754 --alpha 0.5 --preset fast\n  \
sweep impact --gamma 3.2 --alpha 1.3 --history          # gross-slip episodes of the impact\n  \
sweep impact --gamma 2 --alpha 0.3 --springs 1024 --steps 512 --scheme euler\n\n\
gamma must lie in [0.01, 5], the range the solver is tested in (docs/accuracy.md, extremes).\n\
At a fixed resolution (--springs/--steps) the error estimate compares runs at 1/2, 1/4 and 1/8 \
of it and is printed only where they converge steadily (else \"no error estimate\" and why; \
--json: error_estimate null with no_estimate_reason).\n\
Progress (level, resolution, estimate against the tolerance) goes to stderr on a terminal \
after 1 s, or always with --progress.\n\
Presets (measured error and cost: docs/accuracy.md): fast = tol 1e-4, standard = tol 1e-6 \
(the default), reference = tol 1e-8.\n\
A tolerance that cannot be reached within the work limit (2^34 spring-steps per run) is refused \
before anything is simulated, or after the first cheap levels when their convergence shows it (exit code 2).")]
    Impact(ImpactArgs),
    /// Build a P(gamma, alpha) table from a TOML config and write it as HDF5.
    #[command(after_help = "Examples:\n  \
sweep run configs/full.toml\n  \
sweep run configs/quick.toml -o /tmp/quick.h5 --threads 2 --quiet\n\n\
The table is written atomically: a temporary file next to the output, renamed when complete.\n\
Finished nodes are saved in OUTPUT.ckpt as the run goes; after Ctrl-C, kill -9 or power loss,\n\
`sweep run CONFIG --resume` continues from there and writes the same table as an uninterrupted\n\
run; `--restart` discards the checkpoint instead. A run locks OUTPUT.lock: a second run on the\n\
same output is refused, naming the first. The output must be a regular file or not exist.\n\
`--shard K/N -o PART` computes 1/N of the work for `sweep merge` (see `sweep merge --help`).\n\
Config keys, defaults and ranges: docs/config.md. The file format: docs/table-format.md.")]
    Run(table_cmds::RunArgs),
    /// Print a table's domain, node counts, error statistics and provenance.
    Inspect(table_cmds::InspectArgs),
    /// Merge the parts of a sharded run (`sweep run CONFIG --shard K/N -o PART`) into the table.
    #[command(after_help = "Examples:\n  \
for k in 1 2 3 4; do sweep run configs/full.toml --shard $k/4 -o part$k.bin & done; wait\n  \
sweep merge part1.bin part2.bin part3.bin part4.bin -o tables/full.h5\n\n\
The parts must come from the same config and cover every shard exactly once; the merged table's\n\
datasets are identical to those of a single `sweep run`. On a cluster: scripts/slurm-array.sh.")]
    Merge(table_cmds::MergeArgs),
    /// Rebound curves of a scene (materials, friction, impact conditions): CSV, plot, summary.
    #[command(after_help = "Examples:\n  \
sweep scene configs/scenes/seed000_alumina_on_glass.toml -o out/\n  \
sweep scene configs/scenes/steel_on_steel.toml --table tables/full.h5 -o out/\n\n\
Without --table, only the scene's own cases are simulated (closed forms never are).\n\
Scene file keys: docs/scenes.md.")]
    Scene(scene_cmd::SceneArgs),
    /// Figures of a table: P surface, slices, regime diagram, held-out errors (PNG or SVG).
    #[command(after_help = "Examples:\n  \
sweep plot tables/full.h5 -o figures/\n  \
sweep plot tables/full.h5 -o docs/img --figure surface\n  \
sweep plot tables/quick.h5 -o out/ --format svg --gammas 1.52,1.84,2.16 --alphas 0.5,1,inf\n\n\
Writes, into the output folder:\n  \
p_surface     P(gamma, alpha) as a colour map with contours; alpha_c1, alpha_c2; isotropic band\n  \
p_slices      P against alpha for fixed gamma (--gammas); P against gamma for fixed alpha\n                \
(--alphas), with the seed-001 fit (29) of the no-slip limit\n  \
regimes       full slip / partial slip / stick in the (gamma, alpha) plane\n  \
check_errors  interpolation error at the table's held-out checks, over its quadtree leaves\n\
The alpha axis is alpha/(1 + alpha), so alpha = inf (no slip) is on the plot. Each figure's\n\
caption names the table, its provenance and the command. More: docs/figures.md.")]
    Plot(plot_cmd::PlotArgs),
    /// Answer P(gamma, alpha) from a table without simulating: one point, or a batch of lines.
    #[command(after_help = "Examples:\n  \
sweep query tables/full.h5 --gamma 1.754 --alpha 1\n  \
sweep query tables/full.h5 --gamma 1.754 --alpha inf --json\n  \
sweep query tables/full.h5 --batch points.csv > answers.csv\n  \
printf '1.75,0.3\\n2,inf\\n' | sweep query tables/full.h5 --batch -\n\n\
Batch lines are `gamma,alpha`; the output lines are `gamma,alpha,P,e_t` in the same order,\n\
e_t = (2P + 5)/7 (solid sphere, no spin). A header line `gamma,alpha` (before the first point)\n\
becomes `gamma,alpha,P,e_t`; blank lines and lines starting with `#` are copied unchanged; a\n\
UTF-8 byte-order mark is ignored. The whole input is read and checked before anything is\n\
written (about 32 bytes of memory per line): a malformed line or a point outside the table's\n\
domain stops the batch with its line number and no output at all (exit 2), whatever the size.\n\
--clamp answers points outside the domain at the nearest gamma of the table instead.\n\
Points on the full-slip line (alpha below alpha_c1, or alpha_c2 for gamma <= 1) are answered\n\
in closed form, P = 1 - 7 alpha, for any gamma > 0, inside the table's domain or not.")]
    Query(query_cmd::QueryArgs),
    /// Accuracy against cost: error of each scheme over a ladder of resolutions against a tight
    /// reference, time per impact, CSV and log-log plot; optionally the table-level trade.
    #[command(after_help = "Examples:\n  \
sweep accuracy --out docs/accuracy\n  \
sweep accuracy --out /tmp/acc --quick\n  \
sweep accuracy --out docs/accuracy --tables      # also builds quick, isotropic, full and a denser full (minutes)\n\n\
Writes accuracy.csv, accuracy.png, presets.csv (and tables.csv with --tables) into --out and \
prints a summary. Times are thread CPU time (Linux), which other processes do not inflate.\n\
What the columns mean and the published results: docs/accuracy.md.")]
    Accuracy(accuracy_cmd::AccuracyArgs),
    /// Check a table against direct simulation at random points: max and rms error, the worst
    /// point, and whether the table holds the error bound it states.
    #[command(after_help = "Examples:\n  \
sweep verify tables/full.h5 --points 300                 # a sample (about 10 s on 2 cores)\n  \
sweep verify tables/full.h5 --points 20000 --seed 1      # the published measurement (15 min)\n  \
sweep verify tables/quick.h5 --points 100 --tol 1e-9\n\n\
Points: gamma uniform over the table's domain, alpha/(1 + alpha) uniform in [0, 1) (so alpha from 0\n\
to infinity, half of them below 1); when the table includes no slip, every 100th point is at\n\
alpha = inf instead. Each point is simulated at --tol (at most 1e-8) in parallel and compared\n\
with the table's answer. The stated bound is the one `sweep inspect` prints and `sweep query`\n\
shows as +/- (docs/table-format.md, \"The stated error bound\"). Exit status: 0 when every point\n\
is within it, 1 when one is not, 2 for a bad argument. Published results: docs/accuracy.md.")]
    Verify(verify_cmd::VerifyArgs),
    /// The fold curve F+ of P(gamma, alpha): where a +mu F_N gross-slip episode in the
    /// restitution phase vanishes as alpha grows, and P(alpha) has a kink.
    #[command(after_help = "Examples:\n  \
sweep kinks                                   # gamma from the birth point to 3.5, 16 points\n  \
sweep kinks --gamma-max 3.2 --points 5 --steps 4096\n  \
sweep kinks --json\n\n\
Output: a comment line with the birth point (gamma_b, alpha_b), a comment line naming the\n\
columns, then one CSV line per point: gamma,alpha_F,alpha_F/alpha_c2,slope_jump, gamma from\n\
gamma_b to --gamma-max evenly spaced. alpha_F is the fold (located to 1e-10 relative at --steps\n\
steps per contact time, continuum row; about 6e-6 from the converged value at 2048 steps);\n\
slope_jump is the jump of dP/d ln(alpha) across it (one-sided slopes over 1e-4 in ln alpha).\n\
gamma and alpha are dimensionless (physics.md). Below gamma_b there is no fold curve: a\n\
--gamma-max below it prints that and exits 0. Just above gamma_b (up to gamma ~ 2.906) the\n\
points are where the episode stops ending before 0.97 t_c, with no slope jump. About 1.3 s\n\
for the birth and 0.05 s per point at 2048 steps. More: docs/solver.md, \"Kink curves\".")]
    Kinks(KinksArgs),
}

#[derive(Clone, Copy, ValueEnum)]
enum SchemeArg {
    /// Second order, with an error estimate (default).
    Accurate,
    /// The seed paper's explicit Euler scheme (first order; baseline for comparisons).
    Euler,
}

#[derive(Args)]
struct ImpactArgs {
    /// Material group gamma = sqrt((7/2) G*/E*), from 0.01 to 5 (the tested range).
    #[arg(long, value_parser = parse_gamma, allow_hyphen_values = true)]
    gamma: f64,
    /// Friction group alpha = mu v_z0/|u0|; >= 0, or `inf` for no slip.
    #[arg(long, value_parser = parse_alpha, allow_hyphen_values = true)]
    alpha: f64,
    /// Target absolute error of P; the resolution is doubled until the error estimate is below it.
    #[arg(long, value_parser = parse_tol, allow_hyphen_values = true, conflicts_with_all = ["springs", "steps"])]
    tol: Option<f64>,
    /// Accuracy preset: fast (tol 1e-4), standard (1e-6, the default) or reference (1e-8).
    #[arg(long, value_parser = parse_preset, conflicts_with_all = ["tol", "springs", "steps"])]
    preset: Option<Preset>,
    /// Springs on the half-row [0, a_max] (>= 2; an error estimate needs >= 16); use with --steps
    /// instead of --tol.
    #[arg(long, requires = "steps", value_parser = parse_springs)]
    springs: Option<usize>,
    /// Time steps per contact time (>= 8; an error estimate needs >= 64); use with --springs
    /// instead of --tol.
    #[arg(long, requires = "springs", value_parser = parse_steps)]
    steps: Option<usize>,
    /// Numerical scheme.
    #[arg(long, value_enum, default_value = "accurate")]
    scheme: SchemeArg,
    /// Simulate even where P is known in closed form (full-slip line, gamma = 1 plateau).
    #[arg(long)]
    simulate: bool,
    /// Print one JSON object instead of a summary (alpha = inf is written as the string "inf").
    #[arg(long)]
    json: bool,
    /// Also list the gross-slip episodes (the whole contact at the Coulomb limit, F_t = +/-mu F_N)
    /// of one continuum-row run at the solver's number of steps (at least 1024), with start and
    /// end as fractions of the contact time. Where such an episode vanishes inside the contact,
    /// P(alpha) has a kink (docs/solver.md).
    #[arg(long)]
    history: bool,
    /// Report every level of the automatic refinement on stderr (level, resolution, error
    /// estimate against the tolerance); shown on a terminal anyway once a solve takes 1 s.
    #[arg(long)]
    progress: bool,
}

#[derive(Args)]
struct KinksArgs {
    /// Largest gamma of the curve, in (0, 3.6]; the curve starts at its birth point gamma_b ~ 2.90.
    #[arg(long, default_value_t = 3.5, value_parser = parse_gamma_max, allow_hyphen_values = true)]
    gamma_max: f64,
    /// Number of points from gamma_b to --gamma-max (both included), 2 to 1000.
    #[arg(long, default_value_t = 16, value_parser = parse_points, allow_hyphen_values = true)]
    points: usize,
    /// Time steps per contact time of every run (continuum row), 256 to 65536.
    #[arg(long, default_value_t = 2048, value_parser = parse_kink_steps, allow_hyphen_values = true)]
    steps: usize,
    /// Print one JSON object instead of CSV.
    #[arg(long)]
    json: bool,
}

/// Largest `--gamma-max` of `sweep kinks`: the continuation is tested up to 3.5.
const KINKS_GAMMA_MAX: f64 = 3.6;

fn parse_gamma_max(s: &str) -> Result<f64, String> {
    match parse_f64(s) {
        Ok(v) if v > 0.0 && v <= KINKS_GAMMA_MAX => Ok(v),
        _ => Err(format!(
            "gamma-max must be a number in (0, {KINKS_GAMMA_MAX}]"
        )),
    }
}

fn parse_range(s: &str, name: &str, min: usize, max: usize) -> Result<usize, String> {
    parse_integer(s, min, Some(max))
        .ok_or_else(|| format!("{name} must be an integer from {min} to {max}"))
}

/// An integer `>= min` (and `<= max` if given), or `None`.
fn parse_integer(s: &str, min: usize, max: Option<usize>) -> Option<usize> {
    s.trim()
        .parse::<usize>()
        .ok()
        .filter(|&v| v >= min && max.map_or(true, |m| v <= m))
}

fn parse_points(s: &str) -> Result<usize, String> {
    parse_range(s, "points", 2, 1000)
}

fn parse_kink_steps(s: &str) -> Result<usize, String> {
    parse_range(s, "steps", FOLD_MIN_STEPS, 65536)
}

fn kinks(args: KinksArgs) -> Result<()> {
    let start = Instant::now();
    let curve = fold_plus_curve(args.gamma_max, args.points, args.steps)?;
    let elapsed = start.elapsed().as_secs_f64();
    let (gb, ab) = curve.birth;
    let below = format!(
        "no fold curve F+ below its birth point gamma_b = {gb:.6} (--gamma-max {})",
        fmt_num(args.gamma_max)
    );
    if args.json {
        let points: Vec<serde_json::Value> = curve
            .points
            .iter()
            .map(|p| {
                json!({
                    "gamma": p.gamma,
                    "alpha_F": p.alpha,
                    "alpha_F_over_alpha_c2": p.alpha / regimes::alpha_c2(p.gamma),
                    "slope_jump": p.slope_jump,
                    "episode": p.episode.map(|e| json!({"start": e.start, "end": e.end})),
                })
            })
            .collect();
        let mut out = json!({
            "curve": "F+",
            "steps": curve.steps,
            "birth": {"gamma": gb, "alpha": ab, "alpha_over_alpha_c2": ab / regimes::alpha_c2(gb)},
            "gamma_max": args.gamma_max,
            "points": points,
            "elapsed_s": elapsed,
        });
        if curve.points.is_empty() {
            out["note"] = json!(below);
        }
        println!("{out}");
        return Ok(());
    }
    if curve.points.is_empty() {
        println!("{below}");
        return Ok(());
    }
    println!(
        "# fold curve F+ ({} steps, continuum row): birth at gamma_b = {gb:.6}, alpha_b = {ab:.6} \
         ({:.4} alpha_c2); {elapsed:.2} s",
        curve.steps,
        ab / regimes::alpha_c2(gb)
    );
    println!("# gamma,alpha_F,alpha_F/alpha_c2,slope_jump");
    for p in &curve.points {
        println!(
            "{:.6},{:.9},{:.6},{:.4}",
            p.gamma,
            p.alpha,
            p.alpha / regimes::alpha_c2(p.gamma),
            p.slope_jump
        );
    }
    Ok(())
}

/// Steps of the run behind `sweep impact --history` when the solver answered in closed form.
const HISTORY_MIN_STEPS: usize = 1024;

/// The gross-slip episodes for `--history`, or why there are none to compute.
fn slip_episodes(
    gamma: f64,
    alpha: f64,
    steps: usize,
) -> Result<std::result::Result<Vec<Episode>, &'static str>> {
    if alpha == 0.0 {
        return Ok(Err("frictionless (alpha = 0): nothing resists the slip"));
    }
    if alpha > ALPHA_NO_SLIP {
        return Ok(Err("no slip: the contact never reaches the Coulomb limit"));
    }
    let h = slip_history(gamma, alpha, steps.max(HISTORY_MIN_STEPS))?;
    Ok(Ok(h.episodes))
}

fn sign_str(e: &Episode) -> &'static str {
    match e.sign {
        SlipSign::Plus => "+",
        SlipSign::Minus => "-",
    }
}

/// Default tolerance of `sweep impact` when neither `--tol`, `--preset` nor `--springs/--steps`
/// is given: the `standard` preset.
const DEFAULT_TOL: f64 = 1e-6;

fn parse_f64(s: &str) -> Result<f64, String> {
    let t = s.trim().to_ascii_lowercase();
    match t.as_str() {
        "inf" | "infinity" | "+inf" | "∞" => Ok(f64::INFINITY),
        _ => t
            .parse::<f64>()
            .map_err(|_| format!("`{s}` is not a number")),
    }
}

/// Range of `sweep impact --gamma`: the γ range of the extremes suite (`tests/extremes.rs`,
/// docs/accuracy.md), in which the solver is tested for boundedness and convergence.
const IMPACT_GAMMA_RANGE: (f64, f64) = (0.01, 5.0);

fn parse_gamma(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    let (lo, hi) = IMPACT_GAMMA_RANGE;
    if (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "gamma must be a number from {lo} to {hi}, the range the solver is tested in \
             (docs/accuracy.md)"
        ))
    }
}

/// γ of a table query: any finite number > 0 (the table's domain is checked by the lookup; the
/// full-slip closed form holds for every γ).
fn parse_table_gamma(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err("gamma must be a finite number > 0".into())
    }
}

/// A number as written by a person: plain decimals from 1e-4 to 1e9, exponent notation
/// outside (Rust's `{}` would print 1e308 with 309 digits).
fn fmt_num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn parse_alpha(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err("alpha must be >= 0 (or inf for no slip)".into())
    }
}

fn parse_tol(s: &str) -> Result<f64, String> {
    let v = parse_f64(s)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err("tol must be a finite number > 0 (e.g. 1e-6)".into())
    }
}

fn parse_preset(s: &str) -> Result<Preset, String> {
    Preset::from_name(s).map_err(|e| e.to_string())
}

fn parse_count(s: &str, name: &str, min: usize) -> Result<usize, String> {
    parse_integer(s, min, None).ok_or_else(|| format!("{name} must be an integer >= {min}"))
}

fn parse_springs(s: &str) -> Result<usize, String> {
    parse_count(s, "springs", 2)
}

fn parse_steps(s: &str) -> Result<usize, String> {
    parse_count(s, "steps", 8)
}

fn json_number(v: f64) -> serde_json::Value {
    if v.is_finite() {
        json!(v)
    } else {
        json!("inf")
    }
}

fn impact(args: ImpactArgs) -> Result<()> {
    let scheme = match args.scheme {
        SchemeArg::Accurate => Scheme::Accurate,
        SchemeArg::Euler => Scheme::Euler,
    };
    let accuracy = match (args.springs, args.steps) {
        (Some(springs), Some(steps)) => Accuracy::Fixed(Resolution { springs, steps }),
        _ => Accuracy::Tolerance(
            args.tol
                .or(args.preset.map(Preset::tolerance))
                .unwrap_or(DEFAULT_TOL),
        ),
    };
    let start = Instant::now();
    let mut progress = impact_progress::ImpactProgress::new(args.progress);
    let sol = oblique_solver::solve_observed(
        args.gamma,
        args.alpha,
        accuracy,
        scheme,
        args.simulate,
        Limits::default(),
        &mut |event| progress.report(event),
    );
    progress.finish();
    let sol = sol?;
    let elapsed = start.elapsed().as_secs_f64();
    // α_c1 marks the end of the full-slip line only for γ ≥ 1; below, the line ends at α_c2
    // and the formula for α_c1 means nothing (negative for γ < 1/√2; physics.md).
    let alpha_c1 = (args.gamma >= 1.0).then(|| regimes::alpha_c1(args.gamma));
    let alpha_c2 = regimes::alpha_c2(args.gamma);
    // The continuum row has no spring count; a closed form has no resolution at all.
    let (springs, steps, row) = match sol.method {
        Method::ClosedForm => (None, None, None),
        Method::Simulated if sol.resolution.springs == 0 => {
            (None, Some(sol.resolution.steps), Some("continuum"))
        }
        Method::Simulated => (
            Some(sol.resolution.springs),
            Some(sol.resolution.steps),
            Some("springs"),
        ),
    };
    let e_t = regimes::tangential_restitution(sol.p);
    let regime = regimes::Regime::of(args.gamma, args.alpha);
    let method = match sol.method {
        Method::ClosedForm => "closed-form",
        Method::Simulated => "simulated",
    };
    let episodes = if args.history {
        Some(slip_episodes(args.gamma, args.alpha, sol.resolution.steps)?)
    } else {
        None
    };
    if args.json {
        let out = json!({
            "gamma": args.gamma,
            "alpha": json_number(args.alpha),
            "P": sol.p,
            "e_t": e_t,
            "error_estimate": sol.estimate(),
            "springs": springs,
            "steps": steps,
            "row": row,
            "scheme": sol.scheme.name(),
            "method": method,
            "regime": regime.name(),
            "alpha_c1": alpha_c1,
            "alpha_c2": alpha_c2,
            "elapsed_s": elapsed,
        });
        let mut out = out;
        if let Some(why) = sol.no_estimate {
            out["no_estimate_reason"] = json!(why.to_string());
        }
        if let Some(ep) = &episodes {
            out["gross_slip"] = match ep {
                Ok(list) => json!(list
                    .iter()
                    .map(|e| json!({"sign": sign_str(e), "start": e.start, "end": e.end}))
                    .collect::<Vec<_>>()),
                Err(why) => json!(why),
            };
        }
        println!("{out}");
    } else {
        let head = format!(
            "P(gamma = {}, alpha = {}) = {:.9}",
            fmt_num(args.gamma),
            fmt_num(args.alpha),
            sol.p
        );
        match (sol.estimate(), sol.no_estimate) {
            (Some(est), _) => println!("{head}  +/- {est:.1e}"),
            (None, Some(why)) => println!("{head}  (no error estimate: {why})"),
            (None, None) => println!("{head}  (no error estimate)"),
        }
        println!("e_t = (2P + 5)/7 = {e_t:.9}   (solid sphere, no initial spin)");
        match alpha_c1 {
            Some(c1) => println!(
                "regime {} (alpha_c1 = {c1:.6}, alpha_c2 = {alpha_c2:.6})",
                regime.name()
            ),
            None => println!(
                "regime {} (alpha_c2 = {alpha_c2:.6}; for gamma < 1 the full-slip line ends at \
                 alpha_c2, alpha_c1 does not apply)",
                regime.name()
            ),
        }
        match sol.method {
            Method::ClosedForm => println!("closed form (exact; --simulate to simulate anyway)"),
            Method::Simulated => println!(
                "{} scheme, {}, {:.3} ms",
                sol.scheme.name(),
                sol.resolution,
                elapsed * 1e3
            ),
        }
        match &episodes {
            None => {}
            Some(Err(why)) => println!("gross slip: {why}"),
            Some(Ok(list)) if list.is_empty() => {
                println!("gross slip: none (the contact never slips as a whole)")
            }
            Some(Ok(list)) => {
                let parts: Vec<String> = list
                    .iter()
                    .map(|e| format!("{} {:.4}..{:.4}", sign_str(e), e.start, e.end))
                    .collect();
                println!(
                    "gross slip (F_t = +/-mu F_N; start..end in units of t_c): {}",
                    parts.join(", ")
                );
            }
        }
    }
    Ok(())
}

/// The error and its causes on one line, each cause once: a library error whose message
/// already quotes its source (`cannot read config X: No such file …`) is not followed by that
/// source again.
fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let part = cause.to_string();
        if text.is_empty() {
            text = part;
        } else if !text.contains(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
    }
    text
}

/// Die quietly when the reader of our output goes away (`sweep query ... | head`), like other
/// Unix tools, instead of panicking in `println!` on a broken pipe.
#[cfg(unix)]
fn restore_sigpipe() {
    extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    const SIGPIPE: i32 = 13;
    const SIG_DFL: usize = 0;
    // SAFETY: setting the default disposition of SIGPIPE at start-up, before any thread exists.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

#[cfg(not(unix))]
fn restore_sigpipe() {}

fn main() -> ExitCode {
    restore_sigpipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Impact(a) => impact(a),
        Command::Run(a) => table_cmds::run(a),
        Command::Inspect(a) => table_cmds::inspect(a),
        Command::Merge(a) => table_cmds::merge(a),
        Command::Scene(a) => scene_cmd::run(a),
        Command::Plot(a) => plot_cmd::run(a),
        Command::Query(a) => query_cmd::run(a),
        Command::Accuracy(a) => accuracy_cmd::run(a),
        Command::Verify(a) => verify_cmd::run(a),
        Command::Kinks(a) => kinks(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", error_text(&e));
            let usage = matches!(
                e.downcast_ref::<PhysicsError>(),
                Some(
                    PhysicsError::InvalidParameter { .. }
                        | PhysicsError::Infeasible { .. }
                        | PhysicsError::TooLarge { .. }
                        | PhysicsError::UnknownPreset { .. }
                        | PhysicsError::NotFound { .. }
                )
            ) || e.downcast_ref::<ConfigError>().is_some()
                || table_cmds::is_usage(&e)
                || matches!(
                    e.downcast_ref::<oblique_sweep::SweepError>(),
                    Some(oblique_sweep::SweepError::Unreachable { .. })
                )
                || e.downcast_ref::<oblique_sweep::nodestore::NodeFileError>()
                    .is_some()
                || e.downcast_ref::<query_cmd::QueryUsageError>().is_some()
                || e.downcast_ref::<verify_cmd::VerifyUsageError>().is_some()
                || matches!(
                    e.downcast_ref::<oblique_lookup::LookupError>(),
                    Some(
                        oblique_lookup::LookupError::Io { .. }
                            | oblique_lookup::LookupError::Invalid { .. }
                    )
                )
                || matches!(
                    e.downcast_ref::<oblique_study::scene::SceneError>(),
                    Some(
                        oblique_study::scene::SceneError::Io { .. }
                            | oblique_study::scene::SceneError::Parse { .. }
                            | oblique_study::scene::SceneError::Invalid { .. }
                            | oblique_study::scene::SceneError::Measured { .. }
                    )
                )
                || matches!(
                    e.downcast_ref::<oblique_plot::figures::FigureError>(),
                    Some(oblique_plot::figures::FigureError::Invalid { .. })
                );
            if usage {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
