//! Cost of one Kelvin–Voigt run against one elastic run at the same resolution and `(γ, α)`:
//! `cargo run --release -p oblique-tools --bin kvcost [E_N]` prints, for the benchmark's nine
//! cases and 1024/4096 steps, the time per run of each (median of 15) and their ratio.

use std::time::Instant;

use oblique_solver::{Request, Resolution};

fn median_time(mut f: impl FnMut() -> f64) -> f64 {
    let _ = f();
    let mut t: Vec<f64> = (0..15)
        .map(|_| {
            let s = Instant::now();
            std::hint::black_box(f());
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[7]
}

fn main() -> anyhow::Result<()> {
    let e_n: f64 = std::env::args().nth(1).map_or(Ok(0.9), |s| s.parse())?;
    println!(
        "{:>6} {:>5} {:>6} {:>10} {:>10} {:>6}",
        "gamma", "alpha", "steps", "elastic_ms", "kv_ms", "ratio"
    );
    for g in [0.5, 1.754, 3.0] {
        for a in [0.3, 1.0, f64::INFINITY] {
            for steps in [1024, 4096] {
                let res = Resolution { springs: 0, steps };
                let el = Request::new(g, a);
                let kv = Request::new(g, a).e_n(e_n);
                let te = median_time(|| el.simulate(res).unwrap_or(f64::NAN));
                let tk = median_time(|| kv.simulate(res).unwrap_or(f64::NAN));
                println!(
                    "{g:>6} {a:>5} {steps:>6} {:>10.3} {:>10.3} {:>6.2}",
                    te * 1e3,
                    tk * 1e3,
                    tk / te
                );
            }
        }
    }
    Ok(())
}
