//! Builds a `P(γ, α)` table: places nodes on curve-aligned patches, refines them until the
//! predicted interpolation error meets the target ([`tree`]), runs independent impacts in
//! parallel ([`solve`], rayon) and measures the interpolation error at held-out points.
//! [`nodestore`] owns the checkpoint and shard-part files; the table file itself is written by
//! `oblique_table::write`.

pub mod config;
pub mod error;
pub mod job;
pub mod kink;
pub mod knots;
pub mod nodestore;
pub mod preflight;
pub mod solve;
mod tree;
pub mod warp;

use oblique_table::surface::{OutOfDomain, PatchId, PatchKind, Point, Surface};
pub use oblique_table::write::{Built, BuiltPatch};
use oblique_table::Check;

pub use config::Config;
pub use error::{RunError, SweepError};
pub use preflight::{check_tol_in_store, default_check_tols, preflight, probe_limits, Preflight};
pub use solve::{
    solve_points, solve_points_kept, solve_points_with, NodeKey, NodeRecord, NodeStore, Progress,
    RunOptions, Shard, Silent,
};
use tree::{build_patch, patch_specs, root_count, RunState};

/// Engine version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// Git commit the engine was built from (`-dirty` when the work tree had changes).
pub const GIT_COMMIT: &str = env!("OBLIQUE_GIT_COMMIT");

/// Current UTC time as RFC 3339 (`YYYY-MM-DDTHH:MM:SSZ`).
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// The provenance of a table built now by this engine from `cfg` (whose text is `config_text`)
/// in `wall_time_s` seconds.
pub fn provenance(
    cfg: &Config,
    config_text: String,
    wall_time_s: f64,
) -> oblique_table::Provenance {
    let dissipative = cfg.domain.e_n_range().is_some();
    let law = if dissipative {
        format!(" law={}", cfg.law().name())
    } else {
        String::new()
    };
    oblique_table::Provenance {
        schema_version: if dissipative {
            oblique_table::format::SCHEMA_VERSION
        } else {
            oblique_table::format::ELASTIC_SCHEMA_VERSION
        },
        engine_version: VERSION.into(),
        git_commit: GIT_COMMIT.into(),
        config: config_text,
        solver: format!(
            "scheme=accurate{law} tol={:e} (automatic refinement, error estimate per node)",
            cfg.solver.tol
        ),
        law: if dissipative {
            cfg.law().name().to_string()
        } else {
            String::new()
        },
        created: crate::utc_now(),
        wall_time_s,
        node_tol: cfg.solver.tol,
        check_tol: cfg.check_tol(),
        target_error: cfg.nodes.target_error,
    }
}

/// Name of the stage that traces the fold curve F₊ (before the partial-slip patch).
pub const STAGE_FOLD: &str = "fold tracing";
/// Name of the stage that traces the kink curves of `nodes.probe_kinks` (before the
/// partial-slip patch).
pub const STAGE_KINKS: &str = "kink tracing";
/// Name of the stage that traces the kinks of `nodes.knots` (before each patch with knots).
pub const STAGE_KNOTS: &str = "knot tracing";
/// Name of the held-out checks' stage (the last of a build).
pub const STAGE_CHECKS: &str = "held-out checks";

/// The stage of a patch's refinement rounds.
pub(crate) fn stage_refine(patch: &str) -> String {
    format!("{patch} refinement")
}

/// The stages of a build (or of one shard) of `cfg`, in the order [`Progress::phase`] reports
/// them: each patch's refinement (the partial-slip patch's preceded by [`STAGE_FOLD`] when it
/// is warped; each patch's by [`STAGE_KNOTS`] when it has knots and by [`STAGE_KINKS`] when
/// kinks are probed), then [`STAGE_CHECKS`].
pub fn stages(cfg: &Config) -> Vec<String> {
    let mut out = Vec::new();
    for spec in patch_specs(cfg) {
        if cfg.nodes.fold_warp && spec.kind == PatchKind::PartialSlip {
            out.push(STAGE_FOLD.to_string());
        }
        if tree::has_knots(cfg, &spec) {
            out.push(STAGE_KNOTS.to_string());
        }
        if cfg.nodes.probe_kinks {
            out.push(STAGE_KINKS.to_string());
        }
        out.push(stage_refine(spec.name));
    }
    out.push(STAGE_CHECKS.to_string());
    out
}

/// The generator of the held-out check points and of `sweep verify`'s sample.
pub use oblique_physics::sample::SplitMix;

/// Run a whole sweep: build every patch, then simulate and compare the held-out checks.
pub fn build(cfg: &Config, progress: &dyn Progress) -> Result<Built, SweepError> {
    build_with(cfg, progress, RunOptions::default()).map_err(|e| match e {
        RunError::Sweep(e) => e,
        other => unreachable!("build without options: {other}"),
    })
}

/// [`build`] with stored values, saving and interruption ([`RunOptions`]). With a store that
/// holds every node (a finished checkpoint, merged shard parts) nothing is simulated, and the
/// table is the same, bit for bit, as that of an uninterrupted single run.
pub fn build_with(
    cfg: &Config,
    progress: &dyn Progress,
    opts: RunOptions,
) -> Result<Built, RunError> {
    let mut run = RunState::default();
    let mut patches = Vec::new();
    for spec in patch_specs(cfg) {
        patches.extend(build_patch(cfg, &spec, progress, &mut run, opts, 0, None)?);
    }
    let find = |id: PatchId| {
        patches
            .iter()
            .find(|p| p.name == id.name())
            .map(|p| p.patch.clone())
    };
    let surface = Surface::with_restitution(
        cfg.domain.gamma_min,
        cfg.domain.gamma_max,
        cfg.domain.alpha_max,
        cfg.nodes.stencil,
        PatchId::ALL.map(find),
        cfg.domain.e_n_range(),
    )
    .and_then(|s| s.with_partial_map(cfg.partial_map()))
    .map_err(SweepError::Model)?;
    let points = check_points(cfg);
    progress.phase(STAGE_CHECKS, &format!("{} points", points.len()));
    let sims = solve_points_with(&points, cfg.check_tol(), cfg.law(), progress, opts)?;
    let checks = points
        .iter()
        .zip(&sims)
        .map(|(pt, &(p_sim, _))| {
            let p_int = surface
                .eval_point(pt.gamma, pt.alpha, pt.e_n, OutOfDomain::Error)
                .unwrap_or(f64::NAN);
            Check {
                gamma: pt.gamma,
                alpha: pt.alpha,
                e_n: pt.e_n,
                p_simulated: p_sim,
                p_interpolated: p_int,
                interpolation_error: (p_int - p_sim).abs(),
                patch: surface.region_at(pt.gamma, pt.alpha, pt.e_n).index(),
            }
        })
        .collect();
    Ok(Built {
        surface,
        patches,
        checks,
    })
}

/// Compute one shard's share of a sweep into `opts.store`: the root cells and held-out checks
/// whose global index `i` has `i mod count == index`. Merging the stores of all shards and
/// running [`build_with`] on them (strictly) gives the single run's table.
pub fn build_shard(
    cfg: &Config,
    progress: &dyn Progress,
    opts: RunOptions,
    shard: Shard,
) -> Result<(), RunError> {
    let mut run = RunState::default();
    let mut first_root = 0;
    for spec in patch_specs(cfg) {
        build_patch(
            cfg,
            &spec,
            progress,
            &mut run,
            opts,
            first_root,
            Some(shard),
        )?;
        first_root += root_count(cfg, &spec);
    }
    let points: Vec<Point> = check_points(cfg)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| shard.owns(*i))
        .map(|(_, pt)| pt)
        .collect();
    progress.phase(STAGE_CHECKS, &format!("{} points", points.len()));
    solve_points_with(&points, cfg.check_tol(), cfg.law(), progress, opts)?;
    Ok(())
}

/// `n` points next to the critical curves, where `P` has its kinks: `γ` uniform in
/// `[gamma_min, gamma_max]`, `e_n` uniform in `e_range` (1 without), `α = α_k (1 + s·r)` with
/// `α_k` alternately `α_c1(γ, e_n)` (`α_c2` for `γ ≤ 1`) and `α_c2(γ)`, `s = ±1` and
/// `r = 10^u`, `u` uniform in `[−4, −1]`; a point beyond `alpha_max` is drawn again. The same
/// `seed` gives the same points (`sweep verify --near-curves` and the held-out checks of
/// `checks.near_curves`).
pub fn near_curve_points(
    gamma_min: f64,
    gamma_max: f64,
    e_range: Option<(f64, f64)>,
    alpha_max: f64,
    n: usize,
    seed: u64,
) -> Vec<Point> {
    use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2};
    let mut rng = SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let i = out.len();
        let gamma = (gamma_min + (gamma_max - gamma_min) * rng.uniform()).min(gamma_max);
        let e_n = match e_range {
            Some((lo, hi)) => (lo + (hi - lo) * rng.uniform()).min(hi),
            None => 1.0,
        };
        let curve = if i % 2 == 0 && gamma > 1.0 {
            alpha_c1_dissipative(gamma, e_n)
        } else {
            alpha_c2(gamma)
        };
        let r = 10f64.powf(-4.0 + 3.0 * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        let alpha = curve * (1.0 + sign * r);
        if alpha <= alpha_max {
            out.push(Point::new(gamma, alpha, e_n));
        }
    }
    out
}

/// Held-out points: uniform in each patch's (γ, c), and in `e_n` over its range for a
/// dissipative table, strictly inside (c < 1 keeps α finite); then `checks.near_curves` points
/// next to the critical curves ([`near_curve_points`], from a seed derived from
/// `checks.seed`, so that the random points stay where they were).
pub(crate) fn check_points(cfg: &Config) -> Vec<Point> {
    let mut rng = SplitMix(cfg.checks.seed);
    let mut points = Vec::new();
    let range = cfg.domain.e_n_range();
    for p in patch_specs(cfg) {
        for _ in 0..cfg.checks.per_patch {
            let gamma = p.gamma_lo + (p.gamma_hi - p.gamma_lo) * rng.uniform();
            let c = rng.uniform();
            // The elastic sequence of draws is unchanged: e_n draws only with an e_n axis.
            let e_n = match range {
                Some((lo, hi)) => lo + (hi - lo) * rng.uniform(),
                None => 1.0,
            };
            let alpha = p
                .kind
                .alpha_at(cfg.partial_map(), gamma, c, e_n, cfg.domain.alpha_max);
            points.push(Point::new(gamma, alpha, e_n));
        }
    }
    points.extend(near_curve_points(
        cfg.domain.gamma_min,
        cfg.domain.gamma_max,
        range,
        cfg.domain.alpha_max,
        cfg.checks.near_curves,
        cfg.checks.seed ^ NEAR_CURVE_SEED,
    ));
    points
}

/// Mixed into `checks.seed` for the points next to the critical curves.
const NEAR_CURVE_SEED: u64 = 0x6e65_6172_6375_7276;

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_solver::Law;

    fn config(near: usize) -> Config {
        Config::parse(
            &format!(
                "output = \"t.h5\"\n[domain]\ngamma_min = 0.5\ngamma_max = 3.0\n\
                 alpha_max = \"inf\"\n[nodes]\ntarget_error = 1e-4\n[solver]\ntol = 1e-5\n\
                 [checks]\nper_patch = 7\nnear_curves = {near}\n"
            ),
            "t.toml",
        )
        .expect("a valid config")
    }

    #[test]
    fn near_curve_checks_follow_the_random_ones_and_lie_next_to_a_curve() {
        use oblique_physics::regimes::{alpha_c1, alpha_c2};
        let plain = check_points(&config(0));
        let with = check_points(&config(40));
        assert_eq!(with.len(), plain.len() + 40);
        // The random points do not move.
        for (a, b) in plain.iter().zip(&with) {
            assert_eq!((a.gamma, a.alpha), (b.gamma, b.alpha));
        }
        for pt in &with[plain.len()..] {
            assert!((0.5..=3.0).contains(&pt.gamma), "{pt:?}");
            let near = |k: f64| {
                let r = (pt.alpha / k - 1.0).abs();
                (0.99e-4..=0.1001).contains(&r)
            };
            let c1 = pt.gamma > 1.0 && near(alpha_c1(pt.gamma));
            assert!(c1 || near(alpha_c2(pt.gamma)), "{pt:?}");
        }
        // Both curves are visited.
        let on_c2 = with[plain.len()..]
            .iter()
            .filter(|p| (p.alpha / alpha_c2(p.gamma) - 1.0).abs() <= 0.1001)
            .count();
        assert!(on_c2 > 5 && on_c2 < 40, "{on_c2}");
    }

    #[test]
    fn too_many_near_curve_checks_are_refused_naming_the_key() {
        let text = "output = \"t.h5\"\n[domain]\ngamma_min = 0.5\ngamma_max = 3.0\n\
                    [nodes]\ntarget_error = 1e-4\n[solver]\ntol = 1e-5\n\
                    [checks]\nnear_curves = 100001\n";
        let e = Config::parse(text, "t.toml").expect_err("refused");
        assert!(e.to_string().contains("checks.near_curves"), "{e}");
    }

    /// The largest `error / (leaf prediction + 2.66 × the leaf's largest node estimate)` of a
    /// table built over γ 2.80–2.84 (below F₊; target 3e-5, tol 3e-6: about 12 000 nodes), at
    /// 336 points next to F₋ simulated at tol 1e-8: the per-leaf bound's ratio, at most 1 where
    /// the bound holds.
    fn worst_leaf_ratio_next_to_fold_minus(probe: bool) -> f64 {
        let text = format!(
            "output = \"t.h5\"\n[domain]\ngamma_min = 2.8\ngamma_max = 2.84\n\
             alpha_max = \"inf\"\n[nodes]\ntarget_error = 3e-5\nprobe_kinks = {probe}\n\
             [solver]\ntol = 3e-6\n[checks]\nper_patch = 5\n"
        );
        let cfg = Config::parse(&text, "t.toml").expect("a valid config");
        let built = build(&cfg, &Silent).expect("built");
        let slip = built
            .patches
            .iter()
            .find(|p| p.name == PatchId::PartialHigh.name())
            .expect("a partial-slip patch");
        let per_leaf = (cfg.nodes.leaf_intervals + 1).pow(2);
        let curve = kink::fold_minus_curve(2.8, 2.84).unwrap().unwrap();
        let points: Vec<Point> = (0..16)
            .flat_map(|i| {
                let g = 2.8012 + 0.0025 * f64::from(i);
                let a = curve.alpha_at(g).unwrap();
                (0..21).map(move |j| Point::new(g, a * (1.0 + 5e-4 * f64::from(j - 10)), 1.0))
            })
            .collect();
        let truth = solve_points(&points, 1e-8, Law::Elastic, &Silent).unwrap();
        let mut worst = 0.0_f64;
        for (pt, (p, _)) in points.iter().zip(truth) {
            let table = built
                .surface
                .eval_point(pt.gamma, pt.alpha, 1.0, OutOfDomain::Error)
                .unwrap();
            let c = slip.patch.warped(
                pt.gamma,
                oblique_table::surface::partial_coord(pt.gamma, pt.alpha),
            );
            let (leaf, _, _) = slip.patch.find_leaf(pt.gamma, c);
            let est = slip.patch.error_estimate()[leaf * per_leaf..(leaf + 1) * per_leaf]
                .iter()
                .fold(0.0_f64, |a, &b| a.max(b));
            worst = worst.max((table - p).abs() / (slip.leaf_error[leaf] + 2.66 * est));
        }
        worst
    }

    #[test]
    fn leaves_next_to_fold_minus_are_measured_before_they_are_trusted() {
        let without = worst_leaf_ratio_next_to_fold_minus(false);
        let with = worst_leaf_ratio_next_to_fold_minus(true);
        // Without the probes a leaf next to F₋ errs beyond its own bound (2.03×); with them none
        // does (0.84).
        assert!(without > 1.0, "without probes: {without}");
        assert!(with <= 1.0, "with probes: {with}");
    }

    #[test]
    fn an_e_n_table_measures_its_leaves_next_to_the_fold_surface() {
        // The table of one pair at γ = 2.6, e_n 0.95–1 (Kelvin–Voigt; target 4e-5, tol 4e-6:
        // about 1 500 nodes), against 80 points next to the fold surface F₋ simulated at tol
        // 1e-7: the largest error over the stated bound, at most 1 where the bound holds.
        let text = "output = \"t.h5\"\n[domain]\ngamma = 2.6\nalpha_max = \"inf\"\n\
                    e_n_min = 0.95\ne_n_max = 1.0\n[nodes]\ntarget_error = 4e-5\n\
                    leaf_intervals = 6\nprobe_kinks = true\n[solver]\ntol = 4e-6\n\
                    [checks]\nper_patch = 5\n";
        let mut cfg = Config::parse(text, "t.toml").expect("a valid config");
        let surface = kink::fold_minus_surface((2.6, 2.6), (0.95, 1.0))
            .unwrap()
            .expect("F- at gamma 2.6");
        let points = kink::near_fold_minus_points_e(&surface, (2.6, 2.6), (0.95, 1.0), 80, 3);
        assert_eq!(points.len(), 80);
        let truth = solve_points(&points, 1e-7, cfg.law(), &Silent).unwrap();
        let mut worst = |probe: bool| {
            // `sweep run` refuses this γ without the probes: built here to show why.
            cfg.nodes.probe_kinks = probe;
            let built = build(&cfg, &Silent).expect("built");
            let bound = oblique_table::write::error_bound(&built);
            points
                .iter()
                .zip(&truth)
                .map(|(pt, (p, _))| {
                    let table = built
                        .surface
                        .eval_point(pt.gamma, pt.alpha, pt.e_n, OutOfDomain::Error)
                        .unwrap();
                    (table - p).abs() / bound
                })
                .fold(0.0, f64::max)
        };
        let without = worst(false);
        let with = worst(true);
        // Without the probes the table errs beyond its stated bound next to F₋ (2.27× at
        // 80 points); with them it holds it (0.68).
        assert!(without > 1.0, "without probes: {without}");
        assert!(with <= 1.0, "with probes: {with}");
    }
}
