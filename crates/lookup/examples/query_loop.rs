//! Instruction counts for `docs/benchmarks.md`: loads a table, then answers `N` queries of one
//! kind in a loop. Run under `valgrind --tool=callgrind` with `N = 0` and `N > 0`; the difference
//! of the instruction counts divided by `N` is the cost of one query, independent of the load of
//! the machine.
//!
//! `cargo run --release -p oblique-lookup --example query_loop -- TABLE KIND N` with `KIND` one
//! of `line`, `partial`, `stick`, `no_slip`, `low_gamma`, `partial_g3`, `mixed`, `spheres_3d`,
//! `spheres_3d_prepared` (the same rebound through
//! [`Table::prepare`](oblique_lookup::Table::prepare)),
//! `batch` (the `mixed` stream through `Table::p_batch`, 4096 queries per call; `N` is rounded
//! down to a multiple of 4096).

use std::hint::black_box;
use std::process::ExitCode;

use oblique_lookup::Table;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: query_loop TABLE KIND N (KIND: line, partial, stick, no_slip, low_gamma, \
                 partial_g3, mixed, spheres_3d, spheres_3d_prepared, batch)";
    let (Some(path), Some(kind), Some(n)) = (args.get(1), args.get(2), args.get(3)) else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    let Ok(n) = n.parse::<usize>() else {
        eprintln!("N = {n}: must be a non-negative integer\n{usage}");
        return ExitCode::from(2);
    };
    let table = match Table::open(path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let point = match kind.as_str() {
        "line" => Some((1.754, 0.1)),
        "partial" => Some((1.754, 0.3)),
        "stick" => Some((1.754, 1.0)),
        "no_slip" => Some((1.754, f64::INFINITY)),
        "low_gamma" => Some((0.5, 1.0)),
        "partial_g3" => Some((3.0, 0.3)),
        "mixed" | "spheres_3d" | "spheres_3d_prepared" | "batch" => None,
        _ => {
            eprintln!("unknown KIND {kind}\n{usage}");
            return ExitCode::from(2);
        }
    };
    let mut sum = 0.0;
    if let Some((g, a)) = point {
        for _ in 0..n {
            sum += table.p(black_box(g), black_box(a)).unwrap_or(f64::NAN);
        }
    } else if kind == "mixed" || kind == "batch" {
        // The same stream as the criterion benchmark's `p/mixed` (xorshift).
        let pts =
            oblique_lookup::testing::domain_points(table.surface(), 4096, 0x9E37_79B9_7F4A_7C15);
        if kind == "batch" {
            let (g, a): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
            let mut out = vec![0.0; g.len()];
            for _ in 0..n / 4096 {
                let r = table.p_batch(black_box(&g), black_box(&a), &mut out, Default::default());
                sum += r.map_or(f64::NAN, |()| out[0]);
            }
        } else {
            for i in 0..n {
                let (g, a) = pts[i & 4095];
                sum += table.p(black_box(g), black_box(a)).unwrap_or(f64::NAN);
            }
        }
    } else {
        let (pair, contact, inc) = oblique_lookup::testing::reference_spheres();
        if kind == "spheres_3d" {
            for _ in 0..n {
                sum += table
                    .rebound_3d(black_box(&pair), black_box(&contact), black_box(&inc))
                    .map_or(f64::NAN, |a| a.rebound.energy_lost);
            }
        } else {
            let prepared = match table.prepare(&pair, &contact) {
                Ok(p) => p,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::FAILURE;
                }
            };
            for _ in 0..n {
                sum += table
                    .rebound_3d_prepared(black_box(&prepared), black_box(&inc))
                    .map_or(f64::NAN, |a| a.rebound.energy_lost);
            }
        }
    }
    println!("{kind}: {n} queries, checksum {sum}");
    ExitCode::SUCCESS
}
