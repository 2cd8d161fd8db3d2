//! Lookup against simulation, side by side in one run: for a few `(γ, α)` in the
//! simulated regions, one `Table::p` from `tables/full.h5` and one accurate simulated impact
//! `solve(γ, α, Tolerance(1e-6), Accurate)` (automatic refinement to an estimated error ≤ 1e-6;
//! the normal trajectory cache is warm, as in a sweep). The ratio of the two medians is the
//! lookup's speed-up. Prints the medians and ratios at the end.
//!
//! `cargo bench --bench speedup`; `LOOKUP_BENCH_CLOCK=cpu` measures the process CPU time instead
//! of elapsed time (groups suffixed `_cpu`).

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use oblique_bench::timed;
use oblique_clock::Clock;
use oblique_lookup::Table;
use oblique_solver::{Accuracy, Request};

const POINTS: [(f64, f64); 4] = [
    (1.754, 0.3),
    (1.754, 1.0),
    (1.754, f64::INFINITY),
    (0.5, 1.0),
];

fn case(gamma: f64, alpha: f64) -> String {
    if alpha.is_infinite() {
        format!("g{gamma}_a_inf")
    } else {
        format!("g{gamma}_a{alpha}")
    }
}

fn median_ns(group: &str, case: &str) -> Option<f64> {
    let path = format!("target/criterion/{group}/{case}/new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v["median"]["point_estimate"].as_f64()
}

fn main() {
    let clock =
        Clock::from_env("LOOKUP_BENCH_CLOCK", Clock::ProcessCpu).unwrap_or_else(|e| panic!("{e}"));
    let suffix = clock.suffix();
    let table = Table::open(concat!(env!("CARGO_MANIFEST_DIR"), "/tables/full.h5"))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .configure_from_args();
    let lookup = format!("speedup_lookup{suffix}");
    let simulate = format!("speedup_simulate_1e-6{suffix}");
    let mut g = c.benchmark_group(&lookup);
    for (gamma, alpha) in POINTS {
        timed(&mut g, &case(gamma, alpha), clock, || {
            table.p(black_box(gamma), black_box(alpha))
        });
    }
    g.finish();
    let mut g = c.benchmark_group(&simulate);
    g.sample_size(10);
    for (gamma, alpha) in POINTS {
        let sol = Request::new(gamma, alpha)
            .accuracy(Accuracy::Tolerance(1e-6))
            .solve()
            .unwrap_or_else(|e| panic!("{e}"));
        let p = table.p(gamma, alpha).unwrap_or(f64::NAN);
        println!(
            "({gamma}, {alpha}): simulated P = {:.9} +/- {:.1e}, table P = {p:.9} (diff {:.1e})",
            sol.p,
            sol.error_estimate,
            (p - sol.p).abs()
        );
        timed(&mut g, &case(gamma, alpha), clock, || {
            Request::new(black_box(gamma), black_box(alpha))
                .accuracy(Accuracy::Tolerance(1e-6))
                .solve()
        });
    }
    g.finish();
    c.final_summary();
    println!("\n| γ | α | lookup (median) | simulated 1e-6 (median) | speed-up |");
    println!("|---|---|---|---|---|");
    for (gamma, alpha) in POINTS {
        let k = case(gamma, alpha);
        if let (Some(l), Some(s)) = (median_ns(&lookup, &k), median_ns(&simulate, &k)) {
            let a = if alpha.is_infinite() {
                "∞".to_string()
            } else {
                alpha.to_string()
            };
            println!(
                "| {gamma} | {a} | {l:.1} ns | {:.3} ms | {:.2e}× |",
                s * 1e-6,
                s / l
            );
        }
    }
}
