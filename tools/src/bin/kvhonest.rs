//! Honesty of the Kelvin–Voigt error estimate: `cargo run --release -p oblique-tools --bin
//! kvhonest -- [N] [SEED]` solves `N` random points (default 50; γ 0.5–3.5, α 0.05–5
//! log-uniform or ∞ for one in eight, e_n 0.3–0.99) at tol 1e-6 and 1e-8 and compares each
//! answer with a reference, the Richardson value of 2× and 4× the finest steps of the tol-1e-8
//! solve: prints the error, the estimate and their ratio per point and tolerance, and the
//! smallest ratio (below 1: an estimate under the error).
use oblique_solver::{Accuracy, Request, Resolution};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().map_or(Ok(50), |s| s.parse())?;
    let seed: u64 = args.get(1).map_or(Ok(7), |s| s.parse())?;
    let mut rnd = oblique_tools::xorshift(seed);
    let mut worst = f64::INFINITY;
    let mut under = 0;
    println!("gamma alpha e_n tol steps error estimate estimate/error");
    for _ in 0..n {
        let g = 0.5 + 3.0 * rnd();
        let a = if rnd() < 0.125 {
            f64::INFINITY
        } else {
            0.05 * 100f64.powf(rnd())
        };
        let e = 0.3 + 0.69 * rnd();
        let req = Request::new(g, a).e_n(e).forced(true);
        let fine = req.accuracy(Accuracy::Tolerance(1e-8)).solve()?;
        let at = |m: usize| {
            req.simulate(Resolution {
                springs: 0,
                steps: m * fine.resolution.steps,
            })
        };
        let (p2, p4) = (at(2)?, at(4)?);
        let reference = p4 + (p4 - p2) / 3.0;
        for tol in [1e-6, 1e-8] {
            let s = if tol == 1e-8 {
                fine
            } else {
                req.accuracy(Accuracy::Tolerance(tol)).solve()?
            };
            let err = (s.p - reference).abs();
            let ratio = s.error_estimate / err;
            worst = worst.min(ratio);
            if ratio < 1.0 {
                under += 1;
            }
            println!(
                "{g:.4} {a:.4} {e:.4} {tol:e} {} {err:.2e} {:.2e} {ratio:.2}{}",
                s.resolution.steps,
                s.error_estimate,
                if ratio < 1.0 { "  UNDER" } else { "" }
            );
        }
    }
    println!("smallest estimate/error {worst:.2}, {under} below 1");
    Ok(())
}
