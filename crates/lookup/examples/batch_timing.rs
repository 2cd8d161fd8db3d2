//! The Rust side of `python/benches/bench.py`: times the batch paths on inputs read from files,
//! so that the Python package and the Rust library answer the same queries in one run.
//!
//! `batch_timing TABLE POINTS IMPACTS REPS` where `POINTS` holds `(γ, α)` pairs and `IMPACTS`
//! rows of 15 values (`v_1`, `ω_1`, `v_2`, `ω_2`, `n`), little-endian f64. Prints one line per
//! measurement: `name count median_wall_s median_cpu_s` (medians over `REPS` runs; CPU time of
//! the whole process, all threads). The pair of the rebounds is fixed: two steel spheres
//! (E = 210 GPa, ν = 0.29, density 7850 kg/m³, R = 5 mm and 3 mm, κ = 0.4), μ = 0.3.

use std::hint::black_box;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use oblique_lookup::rebound::{Body, Elastic, Incident3, Motion3, Pair, Rebound3};
use oblique_lookup::{Answer, Contact, OutOfDomain, Prepared, Table};

/// The pair `bench.py` uses.
fn steel_pair() -> (Pair, Contact) {
    let steel = Elastic {
        youngs_modulus: 210e9,
        poisson_ratio: 0.29,
    };
    let sphere = |r: f64| Body {
        mass: 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r,
        radius: r,
        kappa: 0.4,
    };
    let pair = Pair {
        sphere: sphere(5e-3),
        other: Some(sphere(3e-3)),
    };
    (pair, Contact::with_materials(steel, steel, 0.3))
}

fn read_f64(path: &str, width: usize) -> Result<Vec<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
    if bytes.len() % (8 * width) != 0 {
        return Err(format!(
            "{path}: {} bytes, not a whole number of rows of {width} f64",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("chunks of 8")))
        .collect())
}

/// Median wall and process-CPU time of `reps` runs of `f`.
fn time(reps: usize, mut f: impl FnMut()) -> (f64, f64) {
    let cpu = || oblique_clock::process_cpu_time().unwrap_or(Duration::ZERO);
    let mut runs: Vec<(f64, f64)> = (0..reps.max(1))
        .map(|_| {
            let (w0, c0) = (Instant::now(), cpu());
            f();
            (w0.elapsed().as_secs_f64(), (cpu() - c0).as_secs_f64())
        })
        .collect();
    let mid = runs.len() / 2;
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let wall = runs[mid].0;
    runs.sort_by(|a, b| a.1.total_cmp(&b.1));
    (wall, runs[mid].1)
}

fn run(args: &[String]) -> Result<(), String> {
    let [_, table, points, impacts, reps] = args else {
        return Err("usage: batch_timing TABLE POINTS IMPACTS REPS".into());
    };
    let reps: usize = reps
        .parse()
        .map_err(|_| format!("REPS = {reps}: must be a positive integer"))?;
    let table = Table::open(table).map_err(|e| e.to_string())?;
    let pts = read_f64(points, 2)?;
    let (gamma, alpha): (Vec<f64>, Vec<f64>) = pts.chunks_exact(2).map(|c| (c[0], c[1])).unzip();
    let n = gamma.len();
    let mut out = vec![0.0; n];
    let show = |name: &str, count: usize, (w, c): (f64, f64)| println!("{name} {count} {w} {c}");

    let single = 100_000.min(n);
    show(
        "p_single",
        single,
        time(reps, || {
            for i in 0..single {
                black_box(table.p(black_box(gamma[i]), black_box(alpha[i])).ok());
            }
        }),
    );
    let check = |r: Result<(), oblique_lookup::LookupError>| {
        if let Err(e) = r {
            eprintln!("batch_timing: {e}");
        }
    };
    show(
        "p_batch",
        n,
        time(reps, || {
            check(table.p_batch(&gamma, &alpha, &mut out, OutOfDomain::Error))
        }),
    );
    show(
        "p_batch_par",
        n,
        time(reps, || {
            check(table.p_batch_par(&gamma, &alpha, &mut out, OutOfDomain::Error))
        }),
    );

    let rows = read_f64(impacts, 15)?;
    let incidents: Vec<Incident3> = rows
        .chunks_exact(15)
        .map(|r| {
            let v = |k: usize| [r[k], r[k + 1], r[k + 2]];
            Incident3 {
                sphere: Motion3 {
                    velocity: v(0),
                    spin: v(3),
                },
                other: Motion3 {
                    velocity: v(6),
                    spin: v(9),
                },
                normal: v(12),
            }
        })
        .collect();
    let (pair, contact) = steel_pair();
    let prepared = Prepared::new(&pair, &contact).map_err(|e| e.to_string())?;
    let mut answers = vec![Answer::<Rebound3>::default(); incidents.len()];
    show(
        "rebound_3d_batch",
        incidents.len(),
        time(reps, || {
            check(table.rebound_3d_batch(&prepared, &incidents, &mut answers))
        }),
    );
    show(
        "rebound_3d_batch_par",
        incidents.len(),
        time(reps, || {
            check(table.rebound_3d_batch_par(&prepared, &incidents, &mut answers))
        }),
    );
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("batch_timing: {e}");
            ExitCode::from(2)
        }
    }
}
