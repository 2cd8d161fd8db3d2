//! `sweep`: the command-line front end. Thin: parses arguments, calls the library, prints.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod args;
mod cmd;
mod failure;
mod impact_progress;
mod progress;

use cmd::verify as verify_cmd;
use cmd::{accuracy as accuracy_cmd, plot as plot_cmd, query as query_cmd, scene as scene_cmd};

#[derive(Parser)]
#[command(
    name = "sweep",
    version,
    about = "Oblique impacts of spheres with friction, elastic and viscoelastic: the universal \
tangential restitution P(gamma, alpha, e_n)",
    long_about = "Oblique impacts of spheres with friction by the method of dimensionality \
reduction (Hertz normal contact, Cattaneo-Mindlin partial slip), elastic or viscoelastic \
(every spring a Kelvin-Voigt element; normal restitution e_n from 0.3 to 1, --e-n).\n\n\
Every rebound of a sphere on a half-space is decided by one function P(gamma, alpha):\n  \
gamma = sqrt((m*/m_t) G*/E*)        material group\n  \
alpha = (2/7)(m*/m_t) mu v_z0/|u0|  friction group (alpha = inf: no slip)\n  \
P     = u_after / u_before          restitution of the contact-point velocity u\n\
with E*, G* the effective moduli, m* the normal and m_t the tangential reduced mass, v_z0 the \
approach speed and u0 the incident slip of the contact point (u = v_x + R w on a wall).\n\
For one sphere on a wall, or two spheres of the same inertia factor kappa (I = kappa m R^2), \
m*/m_t = (1 + kappa)/kappa whatever the masses and radii: for solid spheres (kappa = 0.4) \
gamma = sqrt((7/2) G*/E*) (1.52 < gamma < 2.16 for one isotropic material) and \
alpha = mu v_z0/|u0|. `sweep gamma` prints gamma and alpha of your materials and bodies.\n\
For a solid sphere without initial spin, e_t = v_x/v_x0 = (2P + 5)/7."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate one impact in dimensionless form and print P(gamma, alpha, e_n) with its error
    /// estimate.
    #[command(after_help = "Examples:\n  \
sweep impact --gamma 1.754 --alpha 1\n  \
sweep impact --gamma 1.754 --alpha 1 --e-n 0.9      # a dissipative impact (Kelvin-Voigt law)\n  \
sweep impact --gamma 1.754 --alpha inf --tol 1e-8 --json\n  \
sweep impact --gamma 1.754 --alpha 0.5 --preset fast\n  \
sweep impact --gamma 3.2 --alpha 1.3 --history          # gross-slip episodes of the impact\n  \
sweep impact --gamma 2 --alpha 0.3 --springs 1024 --steps 512 --scheme euler\n\n\
gamma must lie in [0.01, 5], the range the solver is tested in (docs/accuracy.md, extremes).\n\
e_n < 1 solves the Kelvin-Voigt law (docs/solver.md, \"Dissipative impacts\"): P depends on \
(gamma, alpha, e_n) only; the full-slip line is P = 1 - (7/2)(1 + e_n) alpha up to \
alpha_c1(e_n) = 2 gamma^2/(7(gamma^2 (1 + e_n) - e_n)).\n\
At a fixed resolution (--springs/--steps) the error estimate compares runs at 1/2, 1/4 and 1/8 \
of it and is printed only where they converge steadily (else \"no error estimate\" and why; \
--json: error_estimate null with no_estimate_reason).\n\
Progress (level, resolution, estimate against the tolerance) goes to stderr on a terminal \
after 1 s, or always with --progress.\n\
Presets (measured error and cost: docs/accuracy.md): fast = tol 1e-4, standard = tol 1e-6 \
(the default), reference = tol 1e-8.\n\
A tolerance that cannot be reached within the work limit (2^34 spring-steps per run) is refused \
before anything is simulated, or after the first cheap levels when their convergence shows it (exit code 2).")]
    Impact(cmd::impact::ImpactArgs),
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
    Run(cmd::run::RunArgs),
    /// Print a table's domain, node counts, error statistics and provenance.
    #[command(after_help = "Examples:\n  \
sweep inspect tables/full.h5\n  \
sweep inspect out/full.h5        # the table the main job built\n\n\
Per patch: its regime and gamma range, roots and leaves, the nodes stored and the largest node\n\
error estimate; then the held-out checks (maximum and rms interpolation error), the stated\n\
error bound and the build's provenance (date, time, engine commit, solver settings). The\n\
format: docs/table-format.md.")]
    Inspect(cmd::inspect::InspectArgs),
    /// Merge the parts of a sharded run (`sweep run CONFIG --shard K/N -o PART`) into the table.
    #[command(after_help = "Examples:\n  \
for k in 1 2 3 4; do sweep run configs/full.toml --shard $k/4 -o part$k.bin & done; wait\n  \
sweep merge part1.bin part2.bin part3.bin part4.bin -o tables/full.h5\n\n\
The parts must come from the same config and cover every shard exactly once; the merged table's\n\
datasets are identical to those of a single `sweep run`. On a cluster: scripts/slurm-array.sh.")]
    Merge(cmd::merge::MergeArgs),
    /// Rebound curves of a scene (materials, friction, impact conditions): CSV, plot, summary.
    #[command(after_help = "Examples:\n  \
sweep scene configs/scenes/seed000_alumina_on_glass.toml -o out/\n  \
sweep scene configs/scenes/steel_on_steel.toml --table tables/full.h5 -o out/\n  \
sweep scene configs/scenes/seed000_alumina_on_glass.toml -o docs/figures --check   # shipped copy up to date?\n\n\
Without --table, only the scene's own cases are simulated (closed forms never are).\n\
--check writes nothing: it compares what would be written with the files in the output folder\n\
(exit status 1 naming those that differ or are missing).\n\
Materials of the catalogue: `sweep gamma --catalogue`.\n\
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
sweep query --gamma 1.754 --alpha 1              (the built-in tables/default.h5)\n  \
sweep query --gamma 1.754 --alpha 1 --e-n 0.8    (normal restitution 0.8, Kelvin-Voigt law)\n  \
sweep query tables/full.h5 --gamma 1.754 --alpha 1\n  \
sweep query tables/full.h5 --gamma 1.754 --alpha inf --json\n  \
sweep query tables/full.h5 --batch points.csv > answers.csv\n  \
printf '1.75,0.3\\n2,inf\\n' | sweep query tables/full.h5 --batch -\n\n\
Batch lines are `gamma,alpha`; the output lines are `gamma,alpha,P,e_t` in the same order,\n\
e_t = (2P + 5)/7 (solid sphere, no spin). A header line `gamma,alpha` (before the first point)\n\
becomes `gamma,alpha,P,e_t`; blank lines and lines starting with `#` are copied unchanged; a\n\
UTF-8 byte-order mark is ignored; a line holds at most 4096 bytes. The whole input is read and\n\
checked before anything is written, in 16 bytes of memory per `gamma,alpha` line and 24 per\n\
`gamma,alpha,e_n` line beside the table (10^7 lines peak at 172 MB and 250 MB with\n\
tables/dissipative-demo.h5; 194 MB for `gamma,alpha` with tables/full.h5): a malformed line, a\n\
longer one or a point outside the table's domain stops the batch with its line number and no\n\
output at all (exit 2), whatever the size.\n\
--clamp answers points outside the domain at the nearest gamma of the table instead.\n\
Points on the full-slip line (alpha below alpha_c1, or alpha_c2 for gamma <= 1) are answered\n\
in closed form, P = 1 - 7 alpha, for any gamma > 0, inside the table's domain or not.\n\
Without TABLE, the table built into sweep answers: tables/default.h5 (Kelvin-Voigt law,\n\
1.3 <= gamma <= 2.2, 0.3 <= e_n <= 1: every body of the material catalogue; give\n\
tables/full.h5 for 0.1 <= gamma <= 3.5 at e_n = 1).")]
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
sweep verify tables/quick.h5 --points 100 --tol 1e-9\n  \
sweep verify tables/dissipative-demo.h5 --points 300 --near-curves   # next to the kinks\n  \
sweep verify out/thornton-demo.h5 --points 200 --near-folds   # a Thornton table next to its folds\n  \
sweep verify out/thornton-demo.h5 --points 200 --near-band    # ... next to its loading band\n\n\
Points: gamma uniform over the table's domain, alpha/(1 + alpha) uniform in [0, 1) (so alpha from 0\n\
to infinity, half of them below 1); when the table includes no slip, every 100th point is at\n\
alpha = inf instead; e_n uniform in the range of a table with an e_n axis. With --near-curves,\n\
alpha is drawn next to alpha_c1(gamma, e_n) and alpha_c2(gamma), where the surface has kinks;\n\
with --near-folds next to the folds of a table of Thornton's law, with --near-band next to the\n\
edges of its loading band. Each point is simulated at\n\
--tol (at most 1e-8) in parallel and compared with the table's answer. The stated bound is the\n\
one `sweep inspect` prints and `sweep query` shows as +/- (docs/table-format.md, \"The stated\n\
error bound\"). Exit status: 0 when every point is within it, 1 when one is not, 2 for a bad\n\
argument. Published results: docs/accuracy.md.")]
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
    Kinks(cmd::kinks::KinksArgs),
    /// Write a table (or the curves of a few gamma) for the dependency-free C/C++/Fortran
    /// evaluator include/oblique_eval.h: a binary file or a C source.
    #[command(after_help = "Examples:\n  \
sweep export tables/full.h5 -o full.oblq                           # the whole table\n  \
sweep export tables/full.h5 -o pairs.oblq --gamma 1.7498 --gamma 1.6977 --curves-only\n  \
sweep export tables/full.h5 -o table_data.c --name oblique_table   # a C source to compile in\n\n\
The evaluator reads the file in place (read or mmap it, then oblq_open) and answers P(gamma,\n\
alpha), the per-gamma curves, e_t and rebounds with no library but libm. The layout (little-\n\
endian, versioned, FNV-1a checksum) is documented in docs/export-format.md. A curve answers the\n\
same P as the whole table to about 1e-15 in a few KB; gamma of a pair of materials:\n\
sqrt((m*/m_t) G*/E*) (sweep --help). A table with an e_n axis is exported whole (layout\n\
version 2; oblq_p_e answers P(gamma, alpha, e_n)); curves hold elastic tables only.")]
    Export(cmd::export::ExportArgs),
    /// gamma, m*/m_t and alpha of a pair of materials and bodies (a sphere on a wall or on a
    /// sphere), or the material catalogue with gamma of every pair.
    #[command(after_help = "Examples:\n  \
sweep gamma --sphere alumina-96 --other soda-lime-glass      # a solid sphere on a wall\n  \
sweep gamma --sphere nylon --other steel --kappa 0.5         # a hollow sphere on a wall\n  \
sweep gamma --sphere steel --other nylon --radius 5e-3 --other-radius 0.01   # two solid spheres\n  \
sweep gamma --sphere steel --other nylon --radius 5e-3 --other-radius 0.01 --other-kappa 0.5 \
--other-mass 2e-3\n  \
sweep gamma --sphere E=200e9,nu=0.29,rho=7900 --other rigid --json\n  \
sweep gamma --catalogue            # E, nu, density and gamma of every pair, with the sources\n\n\
SI units: E in Pa, density in kg/m^3, radii in m, masses in kg. The groups (physics.md):\n  \
gamma^2 = (m*/m_t) G*/E*        1/E* = sum (1 - nu^2)/E, 1/G* = sum (2 - nu)/(4G), G = E/(2(1 + nu))\n  \
alpha = (2/7)(m*/m_t) mu v_z0/|u0|   v_z0 the approach speed, u0 the incident slip of the contact point\n  \
m* = m_1 m_2/(m_1 + m_2) (m_1 on a wall), 1/m_t = sum (1/m + R^2/I), I = kappa m R^2\n\
For one sphere on a wall, and for two spheres of the same kappa, m*/m_t = (1 + kappa)/kappa\n\
whatever the radii and masses: gamma = sqrt((7/2) G*/E*) and alpha = mu v_z0/|u0| for solid\n\
spheres (kappa = 0.4). Radii and masses change gamma only between spheres of different kappa\n\
(a mass is the density times (4/3) pi R^3 for kappa = 0.4, else --mass). A rigid body\n\
(E = inf) adds no compliance. gamma goes to `sweep query --gamma`, `sweep export --gamma` and\n\
oblq_p; alpha_c1 and alpha_c2 bound full slip and stick. Values and sources: docs/materials.md.")]
    Gamma(cmd::gamma::GammaArgs),
    /// Exact references for the oblique-impact tests DEM codes verify themselves against
    /// (Chung & Ooi 1-8, MFIX DEM05, Thornton, seed 000): CSVs, figures, closed-form checks.
    #[command(after_help = "Examples:\n  \
sweep reference all -o reference/                  # every suite, a few seconds\n  \
sweep reference chung-ooi -o out/ --direct         # two-body simulation in SI units, no mapping\n  \
sweep reference mfix-dem05 --table tables/full.h5  # P from the table\n  \
sweep reference all -o docs/reference --check      # are the shipped files up to date?\n\n\
Writes, per suite, OUTPUT/SUITE/TEST.csv and TEST.png for each test, TEST_measured.csv where\n\
the suite publishes measured points, setups.csv (bodies, materials, mu) and\n\
closed_form_checks.csv; prints the checks (Hertz contact time, peak overlap and force; the\n\
gross-slip line P = 1 - 7 alpha; the rolling state; the no-slip limit) and the RMS difference\n\
to measured data. Every quantity q has a column q_err, its error bound. Exit status 1 if an\n\
exact check fails (or, with --check, a file differs); 2 for a bad argument.\n\
Suites, parameters, conventions and how to compare a DEM code: docs/reference.md.")]
    Reference(cmd::reference::ReferenceArgs),
}

/// Signal dispositions set at start-up, before any thread exists.
///
/// - SIGPIPE: die quietly when the reader of our output goes away (`sweep query ... | head`),
///   like other Unix tools, instead of panicking in `println!` on a broken pipe.
/// - SIGXFSZ: ignored, so that a write past the file size limit (`ulimit -f`, RLIMIT_FSIZE)
///   fails with EFBIG instead of killing the process (exit status 153, no message, temporary
///   and lock files left behind). The error then goes the way of any failed write: the
///   output module names the file and the limit, removes its temporary files, the lock is
///   released, and the command exits with status 1 (the machine's limit, not the command line).
#[cfg(unix)]
fn set_signal_dispositions() {
    // SAFETY: `signal` with the predefined dispositions SIG_DFL and SIG_IGN, called once at the
    // start of `main`, before any other thread exists; no handler code is installed.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

#[cfg(not(unix))]
fn set_signal_dispositions() {}

fn main() -> ExitCode {
    set_signal_dispositions();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Impact(a) => cmd::impact::run(a),
        Command::Run(a) => cmd::run::run(a),
        Command::Inspect(a) => cmd::inspect::run(a),
        Command::Merge(a) => cmd::merge::run(a),
        Command::Scene(a) => scene_cmd::run(a),
        Command::Plot(a) => plot_cmd::run(a),
        Command::Query(a) => query_cmd::run(a),
        Command::Accuracy(a) => accuracy_cmd::run(a),
        Command::Verify(a) => verify_cmd::run(a),
        Command::Kinks(a) => cmd::kinks::run(a),
        Command::Export(a) => cmd::export::run(a),
        Command::Gamma(a) => cmd::gamma::run(a),
        Command::Reference(a) => cmd::reference::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Not `eprintln!`, which panics (exit status 101) when standard error cannot be
            // written (a file at the size limit, a full disk): the exit status still tells.
            use std::io::Write as _;
            let _ = writeln!(
                std::io::stderr().lock(),
                "error: {}",
                failure::error_text(e.error())
            );
            e.exit_code()
        }
    }
}
