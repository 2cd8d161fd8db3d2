//! Single-impact benchmark: the accurate scheme with automatic refinement
//! against the seed paper's explicit Euler scheme at equal accuracy.
//!
//! For every `γ ∈ {0.5, 1.754, 3}` and `α ∈ {0.3, 1, ∞}` (simulated even where the closed form
//! applies; none of these nine does):
//! - `accurate_1e-6`: `Request::new(γ, α).accuracy(Tolerance(1e-6)).scheme(Accurate).forced(force_simulation = true).solve()`, the
//!   whole automatic refinement (every level, coarsest first) down to an estimated error ≤ 1e-6.
//!   The dimensionless normal trajectory is cached per process, so after the first call (done
//!   before timing) only the tangential contact is timed: the situation of a sweep.
//! - `accurate_1e-5`: the same with tolerance 1e-5 (equal accuracy with the Euler baseline).
//! - `euler`: one `Request::new(γ, α).scheme(Euler).simulate(res)` at the resolution in [`EULER_1E5`], the cheapest
//!   one found whose true error is ≤ 1e-5 (see [`search`]).
//! - `normal_trajectory`: the one-off cost of a cached normal trajectory, for reference.
//!
//! Before timing, every case is checked against the reference
//! `Request::new(γ, α).scheme(Accurate).simulate({springs: 16384, steps: 8192})` (accurate to ~1e-8) and a summary
//! line is printed (`P`, resolution, error estimate, true error, closed-form region).
//!
//! Modes (environment variables, the criterion arguments pass through unchanged):
//! - `IMPACT_BENCH_SEARCH=1`: do not time anything; search the Euler resolutions instead (minutes).
//! - `IMPACT_BENCH_NO_CHECK=1`: skip the summary/check pass before timing.
//! - `IMPACT_BENCH_CLOCK=cpu`: measure the thread's CPU time instead of elapsed time (groups
//!   suffixed `_cpu`), for a machine shared with other work.
//!
//! `cargo bench --bench impact` (all), `cargo bench --bench impact -- accurate_1e-6` (a subset).

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, SamplingMode};
use oblique_bench::ClockIter;
use oblique_clock::Clock;
use oblique_physics::regimes;
use oblique_solver::hertz::NormalBodies;
use oblique_solver::{Accuracy, Request, Resolution, Scheme};

const GAMMAS: [f64; 3] = [0.5, 1.754, 3.0];
const ALPHAS: [f64; 3] = [0.3, 1.0, f64::INFINITY];

/// Tolerance of the accurate refinement (estimated error).
const ACCURATE_TOL: f64 = 1e-6;
/// Accuracy the Euler baseline has to reach (true error against the reference).
const EULER_TARGET: f64 = 1e-5;
/// The reference resolution (accurate scheme, ~1e-8).
const REFERENCE: Resolution = Resolution {
    springs: 16384,
    steps: 8192,
};

/// Ratios `steps / springs` tried by the search, and where each ratio's doubling starts.
/// (Ratios 16 and 64 give the same errors as 256, the time step dominating, at 16× and 4× the
/// cost; 65536 was never cheaper than 16384.)
const SEARCH_RATIOS: [usize; 4] = [256, 1024, 4096, 16384];
const SEARCH_START_STEPS: usize = 8192;
/// A ratio is abandoned once a single run takes longer than this.
const SEARCH_MAX_RUN: Duration = Duration::from_secs(40);

/// Cheapest Euler resolution with true error ≤ 1e-5, per `(γ, α)`, as found by
/// `IMPACT_BENCH_SEARCH=1 cargo bench --bench impact` ([`search`]; the fastest single run over
/// the ratios). Comments: ratio steps/springs and the error against the reference.
const EULER_1E5: [(f64, f64, Resolution); 9] = [
    (0.5, 0.3, res(60, 245_760)),              // 4096, -9.9e-6
    (0.5, 1.0, res(96, 393_216)),              // 4096, -9.0e-6
    (0.5, f64::INFINITY, res(104, 425_984)),   // 4096, -9.7e-6
    (1.754, 0.3, res(96, 393_216)),            // 4096, -9.6e-6
    (1.754, 1.0, res(40, 163_840)),            // 4096, -9.8e-6
    (1.754, f64::INFINITY, res(208, 851_968)), // 4096, -8.6e-6
    (3.0, 0.3, res(60, 61_440)),               // 1024, -9.3e-6
    (3.0, 1.0, res(128, 524_288)),             // 4096, +9.8e-6
    (3.0, f64::INFINITY, res(256, 4_194_304)), // 16384, -9.7e-6
];

const fn res(springs: usize, steps: usize) -> Resolution {
    Resolution { springs, steps }
}

fn euler_resolution(gamma: f64, alpha: f64) -> Resolution {
    EULER_1E5
        .iter()
        .find(|(g, a, _)| *g == gamma && *a == alpha)
        .map(|(_, _, r)| *r)
        .expect("every benchmarked (gamma, alpha) has an Euler resolution")
}

fn label(gamma: f64, alpha: f64) -> String {
    if alpha.is_infinite() {
        format!("g{gamma}/a_inf")
    } else {
        format!("g{gamma}/a{alpha}")
    }
}

fn reference(gamma: f64, alpha: f64) -> f64 {
    Request::new(gamma, alpha)
        .simulate(REFERENCE)
        .expect("reference run")
}

fn region(gamma: f64, alpha: f64) -> &'static str {
    if regimes::closed_form(gamma, alpha).is_some() {
        "closed-form"
    } else {
        regimes::Regime::of(gamma, alpha).name()
    }
}

/// Print, for every case, what the timed runs compute and how far it is from the reference.
fn check() {
    eprintln!(
        "{:>6} {:>5} {:>12} {:>13} | {:>10} {:>8} {:>8} | {:>10} {:>8} {:>8} | {:>11} {:>8} {:>7}",
        "gamma",
        "alpha",
        "region",
        "P_ref",
        "acc6_res",
        "acc6_est",
        "acc6_err",
        "acc5_res",
        "acc5_est",
        "acc5_err",
        "euler_res",
        "eul_err",
        "eul_s"
    );
    for &gamma in &GAMMAS {
        for &alpha in &ALPHAS {
            let p_ref = reference(gamma, alpha);
            let acc = |tol| {
                let s = Request::new(gamma, alpha)
                    .accuracy(Accuracy::Tolerance(tol))
                    .forced(true)
                    .solve()
                    .expect("accurate solve");
                (
                    format!("{}x{}", s.resolution.springs, s.resolution.steps),
                    s.error_estimate,
                    (s.p - p_ref).abs(),
                )
            };
            let (r6, e6, t6) = acc(ACCURATE_TOL);
            let (r5, e5, t5) = acc(EULER_TARGET);
            let er = euler_resolution(gamma, alpha);
            let t = Instant::now();
            let p = Request::new(gamma, alpha)
                .scheme(Scheme::Euler)
                .simulate(er)
                .expect("euler run");
            let euler_s = t.elapsed().as_secs_f64();
            eprintln!(
                "{:>6} {:>5} {:>12} {:>13.9} | {:>10} {:>8.1e} {:>8.1e} | {:>10} {:>8.1e} {:>8.1e} | {:>11} {:>8.1e} {:>7.3}",
                gamma,
                alpha,
                region(gamma, alpha),
                p_ref,
                r6,
                e6,
                t6,
                r5,
                e5,
                t5,
                format!("{}x{}", er.springs, er.steps),
                (p - p_ref).abs(),
                euler_s
            );
        }
    }
}

/// Find, for every case, the cheapest Euler resolution whose true error is reliably ≤
/// [`EULER_TARGET`]. For each ratio `steps/springs` in [`SEARCH_RATIOS`]:
/// 1. double springs and steps together from [`SEARCH_START_STEPS`] steps until the error
///    against the reference is ≤ the target at some `S` *and* at `2S` (a pass at `S` alone may
///    be a lucky zero crossing of the error); a ratio is abandoned once one run takes longer
///    than [`SEARCH_MAX_RUN`];
/// 2. narrow down between `S/2` and `S` in eighths, from the top, while the error stays ≤ the
///    target (so it is ≤ the target at every tried resolution from the chosen one up to `2S`).
///
/// The cheapest is the fastest single run over the ratios (the time is not proportional to
/// `springs × steps`: with few springs the per-step cost dominates).
fn search() {
    let run = |gamma, alpha, p_ref: f64, r: Resolution, ratio| {
        let t = Instant::now();
        let p = Request::new(gamma, alpha)
            .scheme(Scheme::Euler)
            .simulate(r)
            .expect("euler run");
        let secs = t.elapsed().as_secs_f64();
        let err = p - p_ref;
        println!(
            "  ratio {ratio:>5} springs {:>6} steps {:>8} err {err:+.3e} time {secs:.3} s",
            r.springs, r.steps
        );
        (err, secs)
    };
    let ok = |err: f64| err.abs() <= EULER_TARGET;
    // `IMPACT_BENCH_SEARCH_RATIOS=1024,4096` overrides the ratios tried.
    let ratios: Vec<usize> = match std::env::var("IMPACT_BENCH_SEARCH_RATIOS") {
        Ok(list) => list
            .split(',')
            .map(|r| {
                r.trim()
                    .parse()
                    .expect("IMPACT_BENCH_SEARCH_RATIOS: integers")
            })
            .collect(),
        Err(_) => SEARCH_RATIOS.to_vec(),
    };
    for &gamma in &GAMMAS {
        for &alpha in &ALPHAS {
            let p_ref = reference(gamma, alpha);
            println!(
                "== gamma {gamma} alpha {alpha} ({}) P_ref {p_ref:.10}",
                region(gamma, alpha)
            );
            let mut best: Option<(Resolution, usize, f64, f64)> = None;
            for &ratio in &ratios {
                let at = |steps: usize| res((steps / ratio).max(2), steps);
                let mut seen = std::collections::HashMap::new();
                let mut eval = |steps: usize| {
                    *seen
                        .entry(steps)
                        .or_insert_with(|| run(gamma, alpha, p_ref, at(steps), ratio))
                };
                let mut steps = SEARCH_START_STEPS;
                let found = loop {
                    let (err, secs) = eval(steps);
                    if ok(err) && ok(eval(2 * steps).0) {
                        break true;
                    }
                    if Duration::from_secs_f64(secs) > SEARCH_MAX_RUN {
                        println!("  ratio {ratio:>5}: abandoned (run too long)");
                        break false;
                    }
                    steps *= 2;
                };
                if !found {
                    continue;
                }
                while steps / 2 >= SEARCH_START_STEPS / 8 && ok(eval(steps / 2).0) {
                    steps /= 2;
                }
                let half = steps / 2;
                let mut chosen = steps;
                for k in (1..8).rev() {
                    let s = half + half * k / 8;
                    if !ok(eval(s).0) {
                        break;
                    }
                    chosen = s;
                }
                let (err, secs) = eval(chosen);
                let r = at(chosen);
                println!(
                    "  ratio {ratio:>5} -> springs {} steps {} err {err:+.3e}",
                    r.springs, r.steps
                );
                if best.is_none_or(|(.., b_secs)| secs < b_secs) {
                    best = Some((r, ratio, err, secs));
                }
            }
            match best {
                Some((r, ratio, err, secs)) => println!(
                    "  BEST ({gamma}, {alpha}): res({}, {}) ratio {ratio} err {err:+.3e} time {secs:.3} s",
                    r.springs, r.steps
                ),
                None => println!("  BEST ({gamma}, {alpha}): none reached {EULER_TARGET:e}"),
            }
        }
    }
}

/// `Request::new(γ, α).accuracy(Tolerance(tol)).scheme(Accurate).forced(force_simulation = true).solve()` for every case.
fn bench_accurate(c: &mut Criterion, clock: Clock, name: &str, tol: f64) {
    let mut group = c.benchmark_group(format!("{name}{}", clock.suffix()));
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for &gamma in &GAMMAS {
        for &alpha in &ALPHAS {
            group.bench_with_input(
                BenchmarkId::from_parameter(label(gamma, alpha)),
                &(gamma, alpha),
                |b, &(g, a)| {
                    clock.iter(b, || {
                        Request::new(black_box(g), black_box(a))
                            .accuracy(Accuracy::Tolerance(tol))
                            .forced(true)
                            .solve()
                            .expect("accurate solve")
                    })
                },
            );
        }
    }
    group.finish();
}

/// The one-off cost of the dimensionless Hertz trajectory: what the build tabulates for the
/// powers of two from 16 to 8192 steps, and what `dimensionless_normal(steps)` computes on its
/// first call in a process for other grids.
fn bench_normal(c: &mut Criterion, clock: Clock) {
    let mut group = c.benchmark_group(format!("normal_trajectory{}", clock.suffix()));
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    let bodies = NormalBodies {
        inv_mass1: 1.0,
        inv_mass2: 0.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
    };
    for steps in [256, 1024, 4096] {
        group.bench_with_input(BenchmarkId::from_parameter(steps), &steps, |b, &n| {
            clock.iter(b, || bodies.trajectory(black_box(n)))
        });
    }
    group.finish();
}

fn bench_euler(c: &mut Criterion, clock: Clock) {
    let mut group = c.benchmark_group(format!("euler{}", clock.suffix()));
    // One run takes up to seconds: flat sampling, 10 samples of (normally) one iteration each.
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(1))
        .measurement_time(Duration::from_secs(1));
    for &gamma in &GAMMAS {
        for &alpha in &ALPHAS {
            let r = euler_resolution(gamma, alpha);
            group.bench_with_input(
                BenchmarkId::from_parameter(label(gamma, alpha)),
                &(gamma, alpha, r),
                |b, &(g, a, r)| {
                    clock.iter(b, || {
                        Request::new(black_box(g), black_box(a))
                            .scheme(Scheme::Euler)
                            .simulate(r)
                            .expect("euler run")
                    })
                },
            );
        }
    }
    group.finish();
}

fn main() {
    if std::env::var_os("IMPACT_BENCH_SEARCH").is_some() {
        search();
        return;
    }
    // `cargo bench` passes `--bench`; `cargo test --benches` does not: then only smoke-run.
    let mut c = Criterion::default().configure_from_args();
    if std::env::var_os("IMPACT_BENCH_NO_CHECK").is_none()
        && std::env::args().any(|a| a == "--bench")
    {
        check();
    }
    let clock =
        Clock::from_env("IMPACT_BENCH_CLOCK", Clock::ThreadCpu).unwrap_or_else(|e| panic!("{e}"));
    bench_accurate(&mut c, clock, "accurate_1e-6", ACCURATE_TOL);
    bench_accurate(&mut c, clock, "accurate_1e-5", EULER_TARGET);
    bench_euler(&mut c, clock);
    bench_normal(&mut c, clock);
    c.final_summary();
}
