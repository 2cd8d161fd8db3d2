//! The dissipative laws against the elastic one: one impact solved to a tolerance at the same
//! `(γ, α)`.
//!
//! For every `γ ∈ {0.5, 1.754, 3}` and `α ∈ {0.3, 1, ∞}` (simulated even where a closed form
//! applies):
//! - `elastic_1e-6`: `Request::new(γ, α)` at tol 1e-6, the whole automatic refinement;
//! - `kelvin_voigt_1e-6/e0.9` and `/e0.6`: the same at `e_n = 0.9` and `0.6`;
//! - `thornton_1e-6/e0.9` and `/e0.6`: the same under Thornton's law (its normal trajectories
//!   cached per thread by limiting pressure, as the elastic ones are).
//!
//! The relaxation time of an `e_n` and the fine normal motion of a relaxation time are cached per
//! thread (as the elastic normal trajectory is), so after the first call (made before timing)
//! only the refinement is timed: the situation of a sweep. Their one-off costs are the groups
//! `kelvin_voigt_once` (the fine normal motion of a relaxation time, and its restitution).
//!
//! Before timing, a summary line per case prints `P`, the final resolution and the estimate.
//! `IMPACT_BENCH_CLOCK=cpu` measures the thread's CPU time (groups suffixed `_cpu`).
//!
//! `cargo bench --bench dissipative` (all), `cargo bench --bench dissipative -- e0.9` (a subset).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion};
use oblique_bench::ClockIter;
use oblique_clock::Clock;
use oblique_solver::kelvin_voigt::{contact_fit, tau_for_restitution, unit_bodies};
use oblique_solver::{Accuracy, Law, Request};

const GAMMAS: [f64; 3] = [0.5, 1.754, 3.0];
const ALPHAS: [f64; 3] = [0.3, 1.0, f64::INFINITY];
const TOL: f64 = 1e-6;

fn label(gamma: f64, alpha: f64) -> String {
    if alpha.is_infinite() {
        format!("g{gamma}/a_inf")
    } else {
        format!("g{gamma}/a{alpha}")
    }
}

fn request(gamma: f64, alpha: f64, e_n: f64, law: Option<Law>) -> Request {
    let r = Request::new(gamma, alpha)
        .e_n(e_n)
        .accuracy(Accuracy::Tolerance(TOL))
        .forced(true);
    match law {
        Some(l) => r.law(l),
        None => r,
    }
}

fn check() {
    eprintln!(
        "{:>6} {:>5} {:>5} {:>14} {:>6} {:>9}",
        "gamma", "alpha", "e_n", "P", "steps", "estimate"
    );
    for &g in &GAMMAS {
        for &a in &ALPHAS {
            for (e, law) in [
                (1.0, None),
                (0.9, None),
                (0.6, None),
                (0.9, Some(Law::Thornton)),
                (0.6, Some(Law::Thornton)),
            ] {
                let s = request(g, a, e, law).solve().expect("solve");
                eprintln!(
                    "{g:>6} {a:>5} {e:>5} {:>14.10} {:>6} {:>9.1e} {}",
                    s.p,
                    s.resolution.steps,
                    s.error_estimate,
                    s.law.name()
                );
            }
        }
    }
}

fn bench_solve(c: &mut Criterion, clock: Clock, name: &str, e_n: f64, law: Option<Law>) {
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
                        request(black_box(g), black_box(a), e_n, law)
                            .solve()
                            .expect("solve")
                    })
                },
            );
        }
    }
    group.finish();
}

/// What a first Kelvin–Voigt impact computes once per thread: the fine normal motion of a
/// relaxation time; the restitution of one, integrated (the root search that checks the
/// fitted relaxation time of an `e_n`) and fitted with the contact time (the end of every
/// normal motion, the `e_n` of physical bodies).
fn bench_once(c: &mut Criterion, clock: Clock) {
    let mut group = c.benchmark_group(format!("kelvin_voigt_once{}", clock.suffix()));
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(1));
    let tau = tau_for_restitution(0.9).expect("tau");
    group.bench_function("fine_normal_motion/e0.9", |b| {
        clock.iter(b, || unit_bodies(black_box(tau)).fine())
    });
    group.bench_function("restitution/e0.9", |b| {
        clock.iter(b, || unit_bodies(black_box(tau)).restitution())
    });
    group.bench_function("contact_fit/e0.9", |b| {
        clock.iter(b, || contact_fit(black_box(tau)))
    });
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    if std::env::args().any(|a| a == "--bench") {
        check();
    }
    let clock =
        Clock::from_env("IMPACT_BENCH_CLOCK", Clock::ThreadCpu).unwrap_or_else(|e| panic!("{e}"));
    bench_solve(&mut c, clock, "elastic_1e-6", 1.0, None);
    bench_solve(&mut c, clock, "kelvin_voigt_1e-6/e0.9", 0.9, None);
    bench_solve(&mut c, clock, "kelvin_voigt_1e-6/e0.6", 0.6, None);
    bench_solve(
        &mut c,
        clock,
        "thornton_1e-6/e0.9",
        0.9,
        Some(Law::Thornton),
    );
    bench_solve(
        &mut c,
        clock,
        "thornton_1e-6/e0.6",
        0.6,
        Some(Law::Thornton),
    );
    bench_once(&mut c, clock);
    c.final_summary();
}
