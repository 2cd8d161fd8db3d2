//! `sweep verify`: check a table against direct simulation at random points, against the error
//! bound the table states (`Table::error_bound`, docs/table-format.md "The stated error bound").

use crate::failure::outln;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use crate::failure::{Context, Failure, Result};
use clap::Args;
use rayon::prelude::*;

use oblique_lookup::Table;
use oblique_solver::{Accuracy, Law, Request};
use oblique_table::Point;

/// Loosest simulation tolerance `--tol` accepts: the reference must be far more accurate than
/// the table's bound (1e-5 for the shipped table).
const MAX_TOL: f64 = 1e-8;

/// Every this many points, one is at `alpha = inf` (when the table includes no slip).
const NO_SLIP_EVERY: usize = 100;

#[derive(Args)]
pub struct VerifyArgs {
    /// Table to verify (HDF5, written by `sweep run`).
    table: PathBuf,
    /// Number of random points (>= 1).
    #[arg(long, default_value_t = 1000)]
    points: usize,
    /// Seed of the random points (the same seed gives the same points for a given domain).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Solver tolerance of the reference simulations (absolute error of P); in (0, 1e-8].
    #[arg(long, default_value = "1e-8")]
    tol: f64,
    /// Worker threads for the simulations (0 = one per core).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Draw alpha next to the critical curves instead of over the whole range: alternately
    /// alpha_c1(gamma, e_n) and alpha_c2(gamma) times 1 + s·r, s = +1 or -1, r log-uniform in
    /// [1e-4, 0.1], where the surface has its kinks (points outside the table's alpha range
    /// are drawn again).
    #[arg(long)]
    near_curves: bool,
    /// Draw (gamma, alpha) next to the fold F- instead: gamma uniform over the table's range
    /// above 2.40 (an elastic table whose gamma range spans 0.03 or more there), or (gamma,
    /// e_n) uniform over the part of a Kelvin-Voigt or thornton table's range where F- exists
    /// (under the thornton law from gamma 1.87 at e_n = 0.3); alpha =
    /// alpha_F times 1 + s·r, s = +1 or -1, r log-uniform in [1e-4, 1e-2], where the surface
    /// leaves its smooth continuation like (alpha - alpha_F)^(3/2) (F- is traced first: about
    /// 1 s for a curve, seconds for a surface).
    #[arg(long, conflicts_with = "near_curves")]
    near_fold: bool,
    /// Draw (gamma, alpha) next to the end-of-contact curve E- instead: gamma uniform over the
    /// table's range within [1.74, 2.40], where the last -mu F_N episode of the impact leaves
    /// the separation as alpha grows (alpha from 20.9 at gamma = 1.74 through the stick
    /// region, alpha_c2 at 1.907, to 0.513 at 2.40), or for a Kelvin-Voigt table (gamma, e_n)
    /// uniform where its surface alpha_E(gamma, e_n) is traced (gamma 1.72-2.62); alpha =
    /// alpha_E times 1 + s·r, s = +1 or -1, r log-uniform in [1e-4, 0.1] (E- is traced first:
    /// about 2 s for the curve, 10-25 s for a surface on 2 cores).
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold"])]
    near_end: bool,
    /// Draw points next to the sheet I+ of a Kelvin-Voigt table instead, where a + slip
    /// interlude is born in the restitution (gamma 2.32-2.62, alpha from about 0.41 to
    /// alpha_c2, e_n 0.86-0.999) and P leaves its smooth continuation like
    /// (e_n - e_I)^(3/2): gamma uniform where the sheet is traced, ln(alpha) uniform up to
    /// alpha_c2, e_n = e_I(gamma, alpha) + s·r, s = +1 or -1, r log-uniform in [1e-4, 0.03]
    /// (I+ is traced first: about 10 s on 2 cores).
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold", "near_end"])]
    near_sheet: bool,
    /// Draw points next to the kinks of a table of Thornton's law instead, where P leaves its
    /// smooth continuation, in turn: (gamma, e_n) uniform over the table's range (e_n at most
    /// 0.9999) and alpha = alpha_K times 1 + s·r, s = +1 or -1, r log-uniform in [1e-4, 1e-2],
    /// next to the re-slip fold alpha_R, the line 2/7, the switch fold alpha_S, the loading
    /// fold alpha_L, the fold F- (from gamma ~ 1.9), the end-of-contact curves E- (one of
    /// those up to 100 alpha_c2) and the edges F+lo and F+hi of the strip where a +mu F_N
    /// episode of the restitution exists (gamma above ~2); and next to the switch sheet e_S of
    /// the stick patch (below e_n ~ 0.52 at gamma 1.7; from gamma ~ 2 in bands of e_n, with a
    /// lower edge too): gamma uniform, alpha/alpha_c2 log-uniform in [1.2, 10], e_n = e_S +
    /// s·r next to the edge of the sheet nearest a uniform e_n (each kink located at its point first,
    /// 0.1-2 s; a point where it does not exist is drawn again, a kink found nowhere is left
    /// out); the largest error next to each is printed too.
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold", "near_end", "near_sheet"])]
    near_folds: bool,
    /// Draw e_n next to 1 instead of uniform (a table with an e_n range up to 1): e_n = 1 - r, r
    /// log-uniform in [1e-6, 0.05] (within the range), gamma and alpha as without it. Under
    /// Thornton's law P leaves e_n = 1 like P(1) - a(1 - e_n) + b(1 - e_n)^(5/4), which a linear
    /// e_n axis cannot follow (docs/table-format.md, "Schema v5").
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold", "near_end", "near_sheet", "near_folds"])]
    near_one: bool,
    /// Draw points next to the two edges of the loading band of a table of Thornton's law
    /// instead, in turn: the alpha where a zone of the contact at the +mu q limit opens and
    /// closes while it loads, a band that rises through alpha_c2 as e_n falls (at gamma 1.7:
    /// 0.63-0.64 alpha_c2 at e_n 0.98, 0.86-0.92 at 0.9, 0.95-1.12 at 0.8); P changes its
    /// slope at the upper edge (the loading fold alpha_L above alpha_c2) and shows no kink at
    /// the lower one, where the zone is born: (gamma, e_n) uniform over the
    /// table's range (e_n at most 0.9999), the band located there (0.1-0.4 s; a point where
    /// none is found is drawn again), alpha = edge times 1 + s·r, s = +1 or -1, r log-uniform
    /// in [1e-4, 1e-2]; the largest error next to each edge is printed too.
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold", "near_end", "near_sheet", "near_folds", "near_one"])]
    near_band: bool,
    /// Draw points next to the end-of-contact sheet e_E of a table of Thornton's law instead:
    /// the e_n where the contact stops ending in a -mu F_N episode (a short +mu F_N episode
    /// takes the end), a sheet across the e_n axis nearly flat in alpha far from alpha_c2
    /// (gamma 1.66: e_n 0.307 at 2 alpha_c2, 0.328 at 3, 0.322 at 10; rising with gamma to
    /// 0.44 at 2.0 and 0.74 at 2.6, into the partial-slip patch from gamma 1.86), where the
    /// curvature of P jumps: gamma uniform over the table's range, alpha/alpha_c2
    /// log-uniform in [0.5, 30], e_n = e_E + s·r next to the edge of the sheet
    /// nearest a uniform e_n (located at its point first, 0.1-0.5 s; a point where none lies in
    /// the table's e_n range is drawn again), s = +1 or -1, r log-uniform in [1e-4, 1e-2].
    #[arg(long, conflicts_with_all = ["near_curves", "near_fold", "near_end", "near_sheet", "near_folds", "near_one", "near_band"])]
    near_end_sheet: bool,
    /// No progress lines (otherwise one every 10 s on stderr: points done, rate, ETA).
    #[arg(long)]
    quiet: bool,
}

/// Some points exceed the table's stated bound (exit status 1).
#[derive(Debug, thiserror::Error)]
#[error(
    "{count} of {points} points exceed the table's stated error bound {bound:.2e} (worst \
     {worst:.3e}): the table does not hold its bound"
)]
pub struct BoundExceeded {
    count: usize,
    points: usize,
    bound: f64,
    worst: f64,
}

/// The `n` points: γ uniform in `[gamma_min, gamma_max]`, `s = α/(1 + α)` uniform in
/// `[0, s_max)` with `s_max = alpha_max/(1 + alpha_max)` (1 for `alpha_max = inf`), and, when
/// the table includes no slip, every [`NO_SLIP_EVERY`]-th point at `α = inf` instead; `e_n`
/// uniform in the table's range for a table with an `e_n` axis (1 otherwise).
/// The range of `1 − e_n` of `--near-one`, log-uniform.
const NEAR_ONE_MIN: f64 = 1e-6;
const NEAR_ONE_MAX: f64 = 0.05;

fn sample(table: &Table, n: usize, seed: u64, near_curves: bool, near_one: bool) -> Vec<Point> {
    if near_curves {
        return sample_near_curves(table, n, seed);
    }
    let s = &table.surface();
    let s_max = if s.alpha_max().is_infinite() {
        1.0
    } else {
        s.alpha_max() / (1.0 + s.alpha_max())
    };
    let mut rng = oblique_sweep::SplitMix(seed);
    (0..n)
        .map(|i| {
            let gamma = s.gamma_min() + (s.gamma_max() - s.gamma_min()) * rng.uniform();
            let u = s_max * rng.uniform();
            let alpha = if s.alpha_max().is_infinite() && i % NO_SLIP_EVERY == NO_SLIP_EVERY - 1 {
                f64::INFINITY
            } else {
                (u / (1.0 - u)).min(s.alpha_max())
            };
            // Drawn last, and only with an e_n axis: an elastic table's points are unchanged.
            let e_n = match s.restitution() {
                Some((lo, _)) if near_one => {
                    // 1 − e_n log-uniform in [NEAR_ONE_MIN, min(NEAR_ONE_MAX, 1 − e_n_min)].
                    let (a, b) = (NEAR_ONE_MIN.log10(), NEAR_ONE_MAX.min(1.0 - lo).log10());
                    (1.0 - 10f64.powf(a + (b - a) * rng.uniform())).max(lo)
                }
                Some((lo, hi)) => (lo + (hi - lo) * rng.uniform()).min(hi),
                None => 1.0,
            };
            Point::new(gamma.min(s.gamma_max()), alpha, e_n)
        })
        .collect()
}

/// The `n` points of `--near-curves`: [`oblique_sweep::near_curve_points`] over the table's
/// domain.
fn sample_near_curves(table: &Table, n: usize, seed: u64) -> Vec<Point> {
    let s = table.surface();
    oblique_sweep::near_curve_points(
        s.gamma_min(),
        s.gamma_max(),
        s.restitution(),
        s.alpha_max(),
        n,
        seed,
    )
}

/// The `n` points of `--near-fold`: next to the fold F₋ over the part of the table's range where
/// it is traced: [`oblique_sweep::kink::near_fold_minus_points`] on the curve of an elastic
/// table, [`oblique_sweep::kink::near_fold_minus_points_e`] on the surface `α_F(γ, e_n)` of a
/// Kelvin–Voigt or Thornton table (`e_n` uniform in the table's range where F₋ exists).
fn sample_near_fold(
    table: &Table,
    path: &std::path::Path,
    law: Law,
    n: usize,
    seed: u64,
) -> Result<Vec<Point>> {
    let s = table.surface();
    let (g_lo, g_hi) = (s.gamma_min(), s.gamma_max());
    let range = match table.restitution() {
        Some((lo, hi)) => format!("gamma in [{g_lo}, {g_hi}] and e_n in [{lo}, {hi}]"),
        None => format!("gamma in [{g_lo}, {g_hi}]"),
    };
    let refuse = |has: String| {
        Failure::usage(format!(
            "--near-fold: {} has {has}; the fold F- is traced for elastic tables whose gamma \
             range spans {} or more above {}, for Kelvin-Voigt tables that reach it (gamma \
             >= 2.37 at e_n = 1, later for lower e_n, none for e_n <= 0.87) and for thornton \
             tables that reach it (gamma >= 1.87 at e_n = 0.3, later for higher e_n)",
            path.display(),
            3.0 * oblique_sweep::kink::STEP,
            oblique_sweep::kink::FOLD_MINUS_FROM
        ))
    };
    let Some(e_range) = table.restitution() else {
        // `None` when the range spans less than three tracing steps above 2.40.
        let curve = oblique_sweep::kink::fold_minus_curve(g_lo, g_hi)
            .context("tracing the fold curve F-")?
            .ok_or_else(|| refuse(range))?;
        return Ok(oblique_sweep::kink::near_fold_minus_points(
            &curve, g_lo, g_hi, n, seed,
        ));
    };
    let Some(traced) = oblique_sweep::kink::fold_minus_surface_of(law, (g_lo, g_hi), e_range)
    else {
        return Err(refuse(format!(
            "the {} law, whose kinks are not traced",
            law.name()
        )));
    };
    let surface = traced.context("tracing the fold surface F-")?;
    let points = surface
        .map(|f| oblique_sweep::kink::near_fold_minus_points_e(&f, (g_lo, g_hi), e_range, n, seed))
        .unwrap_or_default();
    if points.is_empty() {
        return Err(refuse(format!("{range}, where F- has no traced point")));
    }
    Ok(points)
}

/// The `n` points of `--near-end`: [`oblique_sweep::kink::near_end_minus_points`] on the curve
/// E₋ over the part of an elastic table's γ range where it is traced,
/// [`oblique_sweep::kink::near_end_minus_points_e`] on the surface `α_E(γ, e_n)` of a
/// Kelvin–Voigt table, and that γ range.
fn sample_near_end(
    table: &Table,
    path: &std::path::Path,
    law: Law,
    n: usize,
    seed: u64,
) -> Result<(Vec<Point>, (f64, f64))> {
    let s = table.surface();
    let (g_lo, g_hi) = (s.gamma_min(), s.gamma_max());
    let refuse = |has: String| {
        Failure::usage(format!(
            "--near-end: {} has {has}; the end-of-contact curve E- is traced for elastic \
             tables whose gamma range reaches into [{}, {}] by {} or more (it leaves for \
             alpha = inf at gamma ~ 1.732), and as a surface for Kelvin-Voigt tables over \
             gamma 1.72-2.62",
            path.display(),
            oblique_sweep::kink::END_MINUS_FROM,
            oblique_sweep::kink::END_MINUS_TO,
            3.0 * oblique_sweep::kink::STEP,
        ))
    };
    if s.pair_gamma().is_some() {
        return Err(refuse("one pair (a single gamma)".into()));
    }
    if let Some(e_range) = table.restitution() {
        if !oblique_sweep::kink::has_damped_surfaces(law) {
            return Err(refuse(format!(
                "the {} law, whose end-of-contact surface is not traced",
                law.name()
            )));
        }
        let surface = oblique_sweep::kink::end_minus_surface(
            (g_lo, g_hi),
            e_range,
            oblique_table::surface::PatchKind::Stick,
        )
        .context("tracing the end-of-contact surface E-")?;
        let points = surface
            .as_ref()
            .map(|f| {
                oblique_sweep::kink::near_end_minus_points_e(f, (g_lo, g_hi), e_range, n, seed)
            })
            .unwrap_or_default();
        let Some(range) = surface
            .and_then(|f| f.gamma_range())
            .filter(|_| !points.is_empty())
        else {
            return Err(refuse(format!(
                "gamma in [{g_lo}, {g_hi}] and e_n in [{}, {}]",
                e_range.0, e_range.1
            )));
        };
        return Ok((points, (g_lo.max(range.0), g_hi.min(range.1))));
    }
    let curve =
        oblique_sweep::kink::end_minus_curve(oblique_table::surface::PatchKind::Stick, g_lo, g_hi)
            .context("tracing the end-of-contact curve E-")?;
    let Some(curve) = curve else {
        return Err(refuse(format!("gamma in [{g_lo}, {g_hi}]")));
    };
    let points = oblique_sweep::kink::near_end_minus_points(&curve, g_lo, g_hi, n, seed);
    if points.is_empty() {
        return Err(refuse(format!("gamma in [{g_lo}, {g_hi}]")));
    }
    let (c_lo, c_hi) = curve.gamma_range();
    Ok((points, (g_lo.max(c_lo), g_hi.min(c_hi))))
}

/// The `n` points of `--near-sheet`: [`oblique_sweep::kink::near_interlude_points`] on the
/// sheet I₊ of a Kelvin–Voigt table, and the γ range they are drawn from.
fn sample_near_sheet(
    table: &Table,
    path: &std::path::Path,
    law: Law,
    n: usize,
    seed: u64,
) -> Result<(Vec<Point>, (f64, f64))> {
    let s = table.surface();
    let (g_lo, g_hi) = (s.gamma_min(), s.gamma_max());
    let refuse = |has: String| {
        Failure::usage(format!(
            "--near-sheet: {} has {has}; the sheet I+ is traced for Kelvin-Voigt tables over \
             gamma 2.32-{} with e_n reaching into 0.86-0.999",
            path.display(),
            oblique_sweep::kink::SHEET_TO
        ))
    };
    let Some(e_range) = table.restitution() else {
        return Err(refuse("no e_n axis (an elastic table)".into()));
    };
    if !oblique_sweep::kink::has_damped_surfaces(law) {
        return Err(refuse(format!(
            "the {} law, whose sheet I+ is not traced",
            law.name()
        )));
    }
    if s.pair_gamma().is_some() {
        return Err(refuse("one pair (a single gamma)".into()));
    }
    let sheet = oblique_sweep::kink::interlude_sheet((g_lo, g_hi), e_range)
        .context("tracing the sheet I+")?;
    let points = sheet
        .as_ref()
        .map(|sh| oblique_sweep::kink::near_interlude_points(sh, (g_lo, g_hi), e_range, n, seed))
        .unwrap_or_default();
    if points.is_empty() {
        return Err(refuse(format!(
            "gamma in [{g_lo}, {g_hi}] and e_n in [{}, {}]",
            e_range.0, e_range.1
        )));
    }
    let lo = points.iter().map(|p| p.gamma).fold(f64::INFINITY, f64::min);
    let hi = points
        .iter()
        .map(|p| p.gamma)
        .fold(f64::NEG_INFINITY, f64::max);
    Ok((points, (lo, hi)))
}

/// The `n` points of `--near-folds` ([`oblique_sweep::kink::near_thornton_fold_points`]),
/// `--near-band` ([`oblique_sweep::kink::near_loading_band_points`]) or `--near-end-sheet`
/// ([`oblique_sweep::kink::near_end_sheet_points`]) over a table of Thornton's law, each with
/// the index of its kink.
fn sample_near_thornton_kinks(
    table: &Table,
    path: &std::path::Path,
    law: Law,
    (n, seed): (usize, u64),
    set: ThorntonKinks,
) -> Result<Vec<(usize, Point)>> {
    let s = table.surface();
    let flag = set.flag();
    let what = match set {
        ThorntonKinks::Band => "the loading band is located",
        ThorntonKinks::EndSheet => "the end-of-contact sheet is located",
        ThorntonKinks::Folds => {
            "the folds alpha_R, 2/7, alpha_S, alpha_L and F-, the curves E-, the strip's edges \
             F+lo and F+hi and the switch sheet e_S are located"
        }
    };
    let refuse = |has: String| {
        Failure::usage(format!(
            "{flag}: {} has {has}; {what} for tables of the thornton law (an e_n axis over a \
             range of gamma)",
            path.display()
        ))
    };
    let Some(e_range) = table.restitution() else {
        return Err(refuse("no e_n axis (an elastic table)".into()));
    };
    if law != Law::Thornton {
        return Err(refuse(format!("the {} law", law.name())));
    }
    let gammas = (s.gamma_min(), s.gamma_max());
    let a_max = s.alpha_max();
    let points = match set {
        ThorntonKinks::Band => {
            oblique_sweep::kink::near_loading_band_points(gammas, e_range, a_max, n, seed)
                .context("locating the loading band")?
        }
        ThorntonKinks::EndSheet => {
            oblique_sweep::kink::near_end_sheet_points(gammas, e_range, a_max, n, seed)
                .context("locating the end-of-contact sheet")?
        }
        ThorntonKinks::Folds => {
            oblique_sweep::kink::near_thornton_fold_points(gammas, e_range, a_max, n, seed)
                .context("locating the folds")?
        }
    };
    if points.is_empty() {
        return Err(refuse(format!(
            "gamma in [{}, {}] and e_n in [{}, {}], where no {} was found",
            s.gamma_min(),
            s.gamma_max(),
            e_range.0,
            e_range.1,
            match set {
                ThorntonKinks::Band => "band",
                ThorntonKinks::EndSheet => "sheet",
                ThorntonKinks::Folds => "fold",
            }
        )));
    }
    Ok(points)
}

/// Which kinks of Thornton's law [`sample_near_thornton_kinks`] draws next to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ThorntonKinks {
    /// `--near-folds` ([`oblique_sweep::kink::THORNTON_FOLDS`]).
    Folds,
    /// `--near-band` ([`oblique_sweep::kink::LOADING_BAND_EDGES`]).
    Band,
    /// `--near-end-sheet` ([`oblique_sweep::kink::END_SHEET_EDGES`]).
    EndSheet,
}

impl ThorntonKinks {
    /// The set the flags ask for, `None` without one of its flags.
    fn of(args: &VerifyArgs) -> Option<Self> {
        if args.near_folds {
            Some(Self::Folds)
        } else if args.near_band {
            Some(Self::Band)
        } else if args.near_end_sheet {
            Some(Self::EndSheet)
        } else {
            None
        }
    }

    /// Its flag.
    fn flag(self) -> &'static str {
        match self {
            Self::Folds => "--near-folds",
            Self::Band => "--near-band",
            Self::EndSheet => "--near-end-sheet",
        }
    }

    /// The names of its kinks, by the index each point carries.
    fn names(self) -> &'static [&'static str] {
        match self {
            Self::Folds => &oblique_sweep::kink::THORNTON_FOLDS,
            Self::Band => &oblique_sweep::kink::LOADING_BAND_EDGES,
            Self::EndSheet => &oblique_sweep::kink::END_SHEET_EDGES,
        }
    }
}

/// One point's result: the table's and the simulation's `P`, the simulation's error estimate.
#[derive(Clone, Copy)]
struct Outcome {
    gamma: f64,
    alpha: f64,
    e_n: f64,
    p_table: f64,
    p_sim: f64,
    sim_error: f64,
}

impl Outcome {
    fn error(&self) -> f64 {
        (self.p_table - self.p_sim).abs()
    }
}

fn fmt_alpha(a: f64) -> String {
    if a.is_infinite() {
        "inf".into()
    } else {
        format!("{a}")
    }
}

pub fn run(args: VerifyArgs) -> Result<()> {
    if !(args.tol > 0.0 && args.tol <= MAX_TOL) {
        return Err(Failure::usage(format!(
            "--tol {:e}: must be in (0, {MAX_TOL:e}] (the reference must be far more accurate \
             than the table)",
            args.tol
        )));
    }
    if args.points == 0 {
        return Err(Failure::usage("--points 0: must be >= 1".into()));
    }
    let table = Table::open(&args.table)?;
    let bound = table.error_bound();
    if bound.is_nan() {
        return Err(anyhow::anyhow!(
            "{}: the table states no error bound (no leaf_predicted_error datasets); nothing to \
             verify against",
            args.table.display()
        )
        .into());
    }
    // The law of the table's node values (an elastic table: elastic).
    let law = match table.restitution() {
        Some(_) => Law::from_name(&table.provenance().law).map_err(|e| {
            anyhow::anyhow!(
                "{}: the table's root attribute 'law' = {:?}: {e}",
                args.table.display(),
                table.provenance().law
            )
        })?,
        None => Law::Elastic,
    };
    let mut near_end_range = None;
    // With --near-folds, --near-band or --near-end-sheet, the kink of each point: an index
    // into the set's names.
    let mut folds: Vec<usize> = Vec::new();
    let thornton_set = ThorntonKinks::of(&args);
    let kink_names: &[&str] = thornton_set.map_or(&[], ThorntonKinks::names);
    let points = if let Some(set) = thornton_set {
        let tagged =
            sample_near_thornton_kinks(&table, &args.table, law, (args.points, args.seed), set)?;
        folds = tagged.iter().map(|&(k, _)| k).collect();
        tagged.into_iter().map(|(_, p)| p).collect()
    } else if args.near_fold {
        sample_near_fold(&table, &args.table, law, args.points, args.seed)?
    } else if args.near_end {
        let (points, range) = sample_near_end(&table, &args.table, law, args.points, args.seed)?;
        near_end_range = Some(range);
        points
    } else if args.near_sheet {
        let (points, range) = sample_near_sheet(&table, &args.table, law, args.points, args.seed)?;
        near_end_range = Some(range);
        points
    } else {
        if args.near_one {
            match table.restitution() {
                Some((_, 1.0)) => {}
                Some((_, hi)) => {
                    return Err(Failure::usage(format!(
                        "--near-one: {} answers e_n up to {hi}, not up to 1",
                        args.table.display()
                    )))
                }
                None => {
                    return Err(Failure::usage(format!(
                        "--near-one: {} has no e_n axis (an elastic table answers e_n = 1 only)",
                        args.table.display()
                    )))
                }
            }
        }
        sample(
            &table,
            args.points,
            args.seed,
            args.near_curves,
            args.near_one,
        )
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .context("starting the worker threads")?;
    eprintln!(
        "verify {}: {} points ({}, {}{}{}), \
         simulated at tol {:e} on {} threads; stated bound {bound:.2e}",
        args.table.display(),
        points.len(),
        match table.surface().pair_gamma() {
            Some(g) => format!("gamma = {g}, the table's one pair"),
            None if near_end_range.is_some() => {
                let (lo, hi) = near_end_range.unwrap_or_default();
                format!("gamma uniform in [{lo}, {hi}]")
            }
            None if args.near_fold && table.restitution().is_none() => format!(
                "gamma uniform in [{}, {}]",
                table
                    .surface()
                    .gamma_min()
                    .max(oblique_sweep::kink::FOLD_MINUS_FROM),
                table.surface().gamma_max()
            ),
            None => format!(
                "gamma uniform in [{}, {}]",
                table.surface().gamma_min(),
                table.surface().gamma_max()
            ),
        },
        if args.near_folds {
            "alpha within 1e-4 to 1e-2 (relative) of alpha_R, 2/7, alpha_S, alpha_L, F-, E-, \
             F+lo and F+hi and e_n within 1e-4 to 1e-2 of the switch sheet e_S, in turn"
        } else if args.near_band {
            "alpha within 1e-4 to 1e-2 (relative) of the lower and upper edges of the loading \
             band, in turn"
        } else if args.near_end_sheet {
            "alpha/alpha_c2 log-uniform in [0.5, 30], e_n within 1e-4 to 1e-2 of the \
             end-of-contact sheet e_E"
        } else if args.near_sheet {
            "ln(alpha) uniform up to alpha_c2, e_n within 1e-4 to 0.03 of the sheet I+"
        } else if args.near_end && table.restitution().is_some() {
            "alpha within 1e-4 to 0.1 (relative) of the end-of-contact surface E-"
        } else if args.near_end {
            "alpha within 1e-4 to 0.1 (relative) of the end-of-contact curve E-"
        } else if args.near_fold && table.restitution().is_some() {
            "alpha within 1e-4 to 1e-2 (relative) of the fold surface F-"
        } else if args.near_fold {
            "alpha within 1e-4 to 1e-2 (relative) of the fold curve F-"
        } else if args.near_curves {
            "alpha within 1e-4 to 0.1 (relative) of alpha_c1(gamma, e_n) and alpha_c2(gamma), \
             alternately"
        } else {
            "alpha/(1+alpha) uniform"
        },
        match table.restitution() {
            Some((lo, hi)) if args.near_sheet => {
                format!(" within e_n [{lo}, {hi}], law {}", law.name())
            }
            Some((lo, _)) if args.near_one => format!(
                ", 1 - e_n log-uniform in [{NEAR_ONE_MIN:e}, {:e}], law {}",
                NEAR_ONE_MAX.min(1.0 - lo),
                law.name()
            ),
            Some((lo, hi)) => format!(
                ", e_n uniform in [{lo}, {hi}]{}, law {}",
                match (args.near_fold, table.surface().pair_gamma()) {
                    (false, _) => "",
                    (true, Some(_)) => " where F- exists",
                    (true, None) => " (gamma and e_n where F- exists)",
                },
                law.name()
            ),
            None => String::new(),
        },
        if table.surface().alpha_max().is_infinite()
            && !args.near_curves
            && !args.near_fold
            && !args.near_end
            && !args.near_sheet
            && !args.near_folds
            && !args.near_band
            && !args.near_end_sheet
        {
            format!(", every {NO_SLIP_EVERY}th point at alpha = inf")
        } else {
            String::new()
        },
        args.tol,
        pool.current_num_threads()
    );
    let start = Instant::now();
    let done = AtomicUsize::new(0);
    let finished = AtomicBool::new(false);
    let outcomes: Vec<Result<Outcome>> = std::thread::scope(|scope| {
        if !args.quiet {
            scope.spawn(|| report(&done, &finished, points.len(), start));
        }
        let out = pool.install(|| {
            points
                .par_iter()
                .map(|&Point { gamma, alpha, e_n }| {
                    let p_table = table.p_e(gamma, alpha, e_n)?;
                    let sim = Request::new(gamma, alpha)
                        .e_n(e_n)
                        .law(law)
                        .accuracy(Accuracy::Tolerance(args.tol))
                        .solve()
                        .with_context(|| {
                            format!(
                                "simulating gamma = {gamma}, alpha = {}, e_n = {e_n}",
                                fmt_alpha(alpha)
                            )
                        })?;
                    done.fetch_add(1, Ordering::Relaxed);
                    Ok(Outcome {
                        gamma,
                        alpha,
                        e_n,
                        p_table,
                        p_sim: sim.p,
                        sim_error: sim.error_estimate,
                    })
                })
                .collect()
        });
        finished.store(true, Ordering::Relaxed);
        out
    });
    let outcomes = outcomes.into_iter().collect::<Result<Vec<_>>>()?;
    let wall = start.elapsed().as_secs_f64();
    let n = outcomes.len();
    let sq: f64 = outcomes.iter().map(|o| o.error() * o.error()).sum();
    let worst = outcomes
        .iter()
        .copied()
        .max_by(|a, b| a.error().total_cmp(&b.error()))
        .context("no points")?;
    let exceeding = outcomes
        .iter()
        .filter(|o| o.error().is_nan() || o.error() > bound)
        .count();
    let max_sim_error = outcomes.iter().map(|o| o.sim_error).fold(0.0, f64::max);
    outln!("table        {}", args.table.display())?;
    outln!(
        "points       {n} (seed {}), simulated at tol {:e} (largest estimate {max_sim_error:.1e}) in {wall:.1} s",
        args.seed, args.tol
    )?;
    outln!("max |error|  {:.3e}", worst.error())?;
    outln!("rms error    {:.3e}", (sq / n as f64).sqrt())?;
    let worst_e_n = if table.restitution().is_some() {
        format!(", e_n = {}", worst.e_n)
    } else {
        String::new()
    };
    outln!(
        "worst point  gamma = {}, alpha = {}{worst_e_n}: table {:.9}, simulation {:.9}",
        worst.gamma,
        fmt_alpha(worst.alpha),
        worst.p_table,
        worst.p_sim
    )?;
    for (k, name) in kink_names.iter().enumerate() {
        let near: Vec<&Outcome> = outcomes
            .iter()
            .zip(&folds)
            .filter(|&(_, &f)| f == k)
            .map(|(o, _)| o)
            .collect();
        if let Some(w) = near.iter().max_by(|a, b| a.error().total_cmp(&b.error())) {
            outln!(
                "near {name:<8} {:>4} points, max |error| {:.3e} at gamma = {}, alpha = {}, e_n = {}",
                near.len(),
                w.error(),
                w.gamma,
                w.alpha,
                w.e_n
            )?;
        }
    }
    outln!("stated bound {bound:.3e}; points above it: {exceeding}")?;
    if exceeding > 0 {
        return Err(anyhow::Error::new(BoundExceeded {
            count: exceeding,
            points: n,
            bound,
            worst: worst.error(),
        })
        .into());
    }
    Ok(())
}

/// Progress lines on stderr every 10 s until `finished`: points done, rate, ETA.
fn report(done: &AtomicUsize, finished: &AtomicBool, total: usize, start: Instant) {
    let mut last = Instant::now();
    while !finished.load(Ordering::Relaxed) {
        std::thread::sleep(Duration::from_millis(100));
        if last.elapsed() < Duration::from_secs(10) {
            continue;
        }
        last = Instant::now();
        let k = done.load(Ordering::Relaxed);
        let t = start.elapsed().as_secs_f64();
        let eta = if k > 0 {
            format!("{:.0} s", t * (total - k) as f64 / k as f64)
        } else {
            "unknown".into()
        };
        eprintln!(
            "verify: {k}/{total} points, elapsed {t:.0} s, {:.1} points/s, ETA {eta}",
            k as f64 / t.max(1e-9)
        );
    }
}
