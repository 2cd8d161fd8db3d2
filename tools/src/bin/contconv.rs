//! Convergence of the continuum row in the number of steps: `cargo run --release -p oblique-tools --bin contconv -- 2.8,69.4 3,inf`
//! (pairs `gamma,alpha`). Prints P, the difference to the previous level, the ratio of
//! successive differences (4 for clean second order), the Richardson value and the time.
use oblique_solver::Request;
use oblique_solver::*;
use std::time::Instant;
fn main() -> anyhow::Result<()> {
    for arg in oblique_tools::args() {
        let (g, a) = oblique_tools::point(&arg)?;
        let mut prev = f64::NAN;
        let mut pd = f64::NAN;
        println!("g={g} a={a}");
        for k in 0..8 {
            let steps = 128usize << k;
            let t = Instant::now();
            let p = Request::new(g, a).simulate(Resolution { springs: 0, steps })?;
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let d = p - prev;
            println!(
                "  {steps:6} P={p:.10} diff={d:9.2e} ratio={:5.2} rich={:.10} {ms:.2}ms",
                pd / d,
                p + d / 3.0
            );
            prev = p;
            pd = d;
        }
    }
    Ok(())
}
