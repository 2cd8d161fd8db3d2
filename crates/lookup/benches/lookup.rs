//! Query speed of `oblique-lookup`: one `P(γ, α)`, one rebound, batches.
//!
//! - `p/<region>`: one `Table::p` at a fixed point of each region (full-slip line, partial
//!   slip, stick, no slip, `γ < 1`), and `p/mixed`: cycling through 4096 points spread over the
//!   whole domain (γ uniform, α log-uniform in [1e-3, 1e3] plus 10 % α = ∞), so that branch
//!   prediction and cache see a realistic stream.
//! - `p_e/mixed`: `Table::p_e` of a table with an e_n axis (`tables/dissipative-demo.h5`, or
//!   `LOOKUP_BENCH_TABLE_E_N=path`) at 4096 points cycled (e_n uniform in its range);
//!   `p_e/elastic_same_points`: the elastic table at the same (γ, α); `p_e/curve_mixed_alpha`:
//!   its curve at (γ, e_n) = (1.754, 0.8) at the α of `curve/mixed_alpha`.
//! - `curve/<region>`: the same points through `Table::curve` (built once per γ), and
//!   `curve/mixed_alpha`: the α of `p/mixed` at γ = 1.754.
//! - `rebound/<case>`: one `Table::rebound` (2-D sphere–wall) and `Table::rebound_3d`
//!   (sphere–wall, sphere–sphere) from materials and μ.
//!   `rebound/spheres_3d_prepared`: the sphere–sphere case through `Table::prepare` (pair and
//!   materials checked once, as a DEM code does per material pair); `rebound/spheres_3d_curve`:
//!   the same with `P` from the pair's `Table::curve`; `rebound/spheres_3d_e_n`: the
//!   sphere–sphere case at e_n = 0.8 from the table with an e_n axis;
//!   `rebound/spheres_3d_prepared_e_n`: that pair prepared (`Table::prepare`, which stores the
//!   pair's line through the table); `…_prepared_new_e_n`: prepared without the table
//!   (`Prepared::new`); `…_curve_e_n`: the same through its curve at (γ, 0.8);
//!   `rebound/prepare_e_n`: one `Table::prepare` of that pair.
//! - `batch/serial`, `batch/rayon`: 2²⁰ mixed points through `p_batch` / `p_batch_par` (on all
//!   cores of the rayon pool); throughput in queries/s.
//! - `rebound_batch/serial`, `rebound_batch/rayon`: 2¹⁶ random sphere–sphere impacts of one
//!   prepared pair through `rebound_3d_batch` / `rebound_3d_batch_par`.
//! - `open/table`, `open/table_e_n`: one `Table::open` of each table (the file read,
//!   decompressed, checked and indexed), the cost a program pays once; `open/embedded`: one
//!   `Table::embedded` (the built-in table written to a temporary file and opened).
//! - `cycle/dependent_add_x64`: 64 dependent `f64` additions, to read the times above in
//!   processor cycles (an addition waits 3 cycles for the previous one on the x86-64 cores
//!   this was measured on, so the cycle is this time / 192).
//!
//! Table: `tables/full.h5` (override with `LOOKUP_BENCH_TABLE=path`).
//! `LOOKUP_BENCH_CLOCK=cpu` measures the process CPU time (`CLOCK_PROCESS_CPUTIME_ID`) instead
//! of elapsed time (groups suffixed `_cpu`): other processes on a shared machine do not inflate
//! it (for `batch/rayon` it sums the CPU time of all workers).
//!
//! `cargo bench -p oblique-lookup --bench lookup` (all), `... -- 'p/'` (a subset).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput};
use oblique_bench::timed;
use oblique_clock::Clock;
use oblique_lookup::rebound::{Incident, Incident3, Motion3, Pair, State};
use oblique_lookup::{testing, Answer, OutOfDomain, Prepared, Table};

/// Deterministic points over the table's domain (`testing::domain_points`).
fn mixed_points(t: &Table, n: usize) -> (Vec<f64>, Vec<f64>) {
    testing::domain_points(t.surface(), n, 0x9E37_79B9_7F4A_7C15)
        .into_iter()
        .unzip()
}

/// Sphere–sphere incident states with random velocities, spins and normals (the normal is
/// turned so that the spheres approach).
fn mixed_incidents(n: usize) -> Vec<Incident3> {
    let mut uniform = testing::uniform(0x2545_F491_4F6C_DD1D);
    let mut next = move || uniform() - 0.5;
    (0..n)
        .map(|_| {
            let mut v = || [next(), next(), next()];
            let (v1, w1, v2, w2, mut normal) = (v(), v(), v(), v(), v());
            let d: f64 = (0..3).map(|i| (v1[i] - v2[i]) * normal[i]).sum();
            if d < 0.0 {
                normal = normal.map(|x| -x);
            }
            Incident3 {
                sphere: Motion3 {
                    velocity: v1,
                    spin: w1.map(|x| 400.0 * x),
                },
                other: Motion3 {
                    velocity: v2,
                    spin: w2.map(|x| 200.0 * x),
                },
                normal,
            }
        })
        .collect()
}

fn main() {
    let path = std::env::var("LOOKUP_BENCH_TABLE").unwrap_or_else(|_| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../tables/full.h5").to_string()
    });
    let table = Table::open(&path).unwrap_or_else(|e| panic!("{e}"));
    let clock =
        Clock::from_env("LOOKUP_BENCH_CLOCK", Clock::ProcessCpu).unwrap_or_else(|e| panic!("{e}"));
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .configure_from_args();

    // Opening a table (read, decompress, validate, index).
    let path_e = std::env::var("LOOKUP_BENCH_TABLE_E_N").unwrap_or_else(|_| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../tables/dissipative-demo.h5"
        )
        .to_string()
    });
    let mut g = c.benchmark_group(format!("open{}", clock.suffix()));
    g.sample_size(10);
    for (name, p) in [("table", &path), ("table_e_n", &path_e)] {
        timed(&mut g, name, clock, || {
            Table::open(black_box(p)).unwrap_or_else(|e| panic!("{e}"))
        });
    }
    timed(&mut g, "embedded", clock, || {
        Table::embedded().unwrap_or_else(|e| panic!("{e}"))
    });
    g.finish();

    // One P.
    let mut g = c.benchmark_group(format!("p{}", clock.suffix()));
    let points = [
        ("line", 1.754, 0.1),
        ("partial", 1.754, 0.3),
        ("stick", 1.754, 1.0),
        ("no_slip", 1.754, f64::INFINITY),
        ("low_gamma", 0.5, 1.0),
        ("partial_g3", 3.0, 0.3),
    ];
    for (name, gamma, alpha) in points {
        timed(&mut g, name, clock, || {
            table.p(black_box(gamma), black_box(alpha))
        });
    }
    let (mg, ma) = mixed_points(&table, 4096);
    let mut i = 0usize;
    timed(&mut g, "mixed", clock, || {
        i = (i + 1) & 4095;
        table.p(black_box(mg[i]), black_box(ma[i]))
    });
    g.finish();

    // One P(γ, α, e_n) of a table with an e_n axis, at 4096 points cycled (γ, α as in
    // `p/mixed` over its domain, e_n uniform in its range), and the elastic table at the same
    // (γ, α) for the ratio.
    let table_e = Table::open(&path_e).unwrap_or_else(|e| panic!("{e}"));
    let (lo, hi) = table_e.restitution().unwrap_or((1.0, 1.0));
    let (eg, ea) = mixed_points(&table_e, 4096);
    let mut u = testing::uniform(0x5DEE_CE66_D1CE_4E5B);
    let ee: Vec<f64> = (0..4096).map(|_| lo + (hi - lo) * u()).collect();
    let mut g = c.benchmark_group(format!("p_e{}", clock.suffix()));
    let mut i = 0usize;
    timed(&mut g, "mixed", clock, || {
        i = (i + 1) & 4095;
        table_e.p_e(black_box(eg[i]), black_box(ea[i]), black_box(ee[i]))
    });
    let mut i = 0usize;
    timed(&mut g, "elastic_same_points", clock, || {
        i = (i + 1) & 4095;
        table.p(black_box(eg[i]), black_box(ea[i]))
    });
    // A curve at fixed (γ, e_n) = (1.754, 0.8) of that table, at the α of `p/mixed`, next to
    // the elastic table's curve at γ = 1.754 (`curve/mixed_alpha`).
    let curve_e = table_e
        .curve_e(1.754, 0.8, OutOfDomain::Error)
        .unwrap_or_else(|e| panic!("{e}"));
    let (_, alphas) = mixed_points(&table, 4096);
    let mut i = 0usize;
    timed(&mut g, "curve_mixed_alpha", clock, || {
        i = (i + 1) & 4095;
        curve_e.p(black_box(alphas[i]))
    });
    g.finish();

    // The processor's cycle: a chain of 64 dependent additions (no reassociation of floats).
    let mut g = c.benchmark_group(format!("cycle{}", clock.suffix()));
    // The chain runs on across iterations, so that consecutive iterations cannot overlap.
    let (step, mut x) = (black_box(1e-300), black_box(1.0f64));
    timed(&mut g, "dependent_add_x64", clock, || {
        for _ in 0..64 {
            x += step;
        }
        x
    });
    g.finish();

    // One P at a fixed γ through a precomputed curve (the same points as `p/`).
    let mut g = c.benchmark_group(format!("curve{}", clock.suffix()));
    for (name, gamma, alpha) in points {
        let curve = table
            .curve(gamma, OutOfDomain::Error)
            .unwrap_or_else(|e| panic!("{e}"));
        timed(&mut g, name, clock, || curve.p(black_box(alpha)));
    }
    let curve = table
        .curve(1.754, OutOfDomain::Error)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut i = 0usize;
    timed(&mut g, "mixed_alpha", clock, || {
        i = (i + 1) & 4095;
        curve.p(black_box(ma[i]))
    });
    g.finish();

    // One rebound.
    let mut g = c.benchmark_group(format!("rebound{}", clock.suffix()));
    // An alumina sphere on a steel sphere (and on a wall), μ = 0.15, γ from the materials.
    let (spheres, contact, inc3) = testing::reference_spheres();
    let wall = Pair {
        sphere: spheres.sphere,
        other: None,
    };
    let inc2 = Incident {
        sphere: State {
            v_x: 1.0,
            v_z: 2.0,
            omega: 50.0,
        },
        ..Default::default()
    };
    let inc3_wall = Incident3 {
        sphere: Motion3 {
            velocity: [1.0, 0.4, 2.0],
            spin: [10.0, -50.0, 30.0],
        },
        normal: [0.0, 0.0, 1.0],
        ..Default::default()
    };
    timed(&mut g, "wall_2d", clock, || {
        table.rebound(black_box(&wall), black_box(&contact), black_box(&inc2))
    });
    timed(&mut g, "wall_3d", clock, || {
        table.rebound_3d(black_box(&wall), black_box(&contact), black_box(&inc3_wall))
    });
    timed(&mut g, "spheres_3d", clock, || {
        table.rebound_3d(black_box(&spheres), black_box(&contact), black_box(&inc3))
    });
    let prepared = table
        .prepare(&spheres, &contact)
        .unwrap_or_else(|e| panic!("{e}"));
    timed(&mut g, "spheres_3d_prepared", clock, || {
        table.rebound_3d_prepared(black_box(&prepared), black_box(&inc3))
    });
    let curve = table
        .curve(prepared.gamma(), contact.outside)
        .unwrap_or_else(|e| panic!("{e}"));
    timed(&mut g, "spheres_3d_curve", clock, || {
        table.rebound_3d_curve(black_box(&prepared), black_box(&curve), black_box(&inc3))
    });
    // The same pair at e_n = 0.8, from the table with an e_n axis: unprepared, prepared and
    // through its curve.
    let contact_e = contact.with_restitution(0.8);
    timed(&mut g, "spheres_3d_e_n", clock, || {
        table_e.rebound_3d(black_box(&spheres), black_box(&contact_e), black_box(&inc3))
    });
    let prepared_e = table_e
        .prepare(&spheres, &contact_e)
        .unwrap_or_else(|e| panic!("{e}"));
    timed(&mut g, "spheres_3d_prepared_e_n", clock, || {
        table_e.rebound_3d_prepared(black_box(&prepared_e), black_box(&inc3))
    });
    // The cost of `Table::prepare` itself (the pair's line through the table).
    timed(&mut g, "prepare_e_n", clock, || {
        table_e.prepare(black_box(&spheres), black_box(&contact_e))
    });
    // Prepared without the table (`Prepared::new`): `P` from the table's octree index.
    let unbound_e = Prepared::new(&spheres, &contact_e).unwrap_or_else(|e| panic!("{e}"));
    timed(&mut g, "spheres_3d_prepared_new_e_n", clock, || {
        table_e.rebound_3d_prepared(black_box(&unbound_e), black_box(&inc3))
    });
    let curve_e = table_e
        .curve_e(prepared_e.gamma(), 0.8, contact_e.outside)
        .unwrap_or_else(|e| panic!("{e}"));
    timed(&mut g, "spheres_3d_curve_e_n", clock, || {
        table_e.rebound_3d_curve(
            black_box(&prepared_e),
            black_box(&curve_e),
            black_box(&inc3),
        )
    });
    g.finish();

    // Batches.
    let n = 1 << 20;
    let (bg, ba) = mixed_points(&table, n);
    let mut out = vec![0.0; n];
    let mut g = c.benchmark_group(format!("batch{}", clock.suffix()));
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(20);
    timed(&mut g, "serial", clock, || {
        table.p_batch(&bg, &ba, &mut out, OutOfDomain::Error)
    });
    timed(&mut g, "rayon", clock, || {
        table.p_batch_par(&bg, &ba, &mut out, OutOfDomain::Error)
    });
    g.finish();

    // Batches of sphere-sphere rebounds of one prepared pair (random incident states).
    let n3 = 1 << 16;
    let incidents = mixed_incidents(n3);
    let mut answers = vec![Answer::default(); n3];
    let mut g = c.benchmark_group(format!("rebound_batch{}", clock.suffix()));
    g.throughput(Throughput::Elements(n3 as u64));
    g.sample_size(20);
    timed(&mut g, "serial", clock, || {
        table.rebound_3d_batch(&prepared, &incidents, &mut answers)
    });
    timed(&mut g, "rayon", clock, || {
        table.rebound_3d_batch_par(&prepared, &incidents, &mut answers)
    });
    g.finish();
    c.final_summary();
}
