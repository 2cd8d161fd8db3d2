//! Checks the error estimate of `solve` against the truth at random points:
//! `cargo run --release -p oblique-tools --bin solvecheck -- TOL N` (defaults 2e-6, 200). Points: γ uniform
//! in [0.1, 3.5], α log-uniform from the linear limit to 1e4 times α_c2, plus α = ∞ (1 in 10).
//! Reference: the Richardson value of continuum runs at 16 and 32 times the accepted steps
//! (at least 16384). Prints every point whose true error exceeds the tolerance or the estimate.
use oblique_physics::regimes;
use oblique_solver::Request;
use oblique_solver::*;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let tol: f64 = oblique_tools::arg_or(&args, 0, "TOL", 2e-6)?;
    let n: usize = oblique_tools::arg_or(&args, 1, "N", 200)?;
    let mut next = oblique_physics::sample::uniform(0x9E37_79B9_7F4A_7C15);
    let (mut over_tol, mut over_est, mut worst) = (0, 0, 0.0f64);
    for i in 0..n {
        let g = 0.1 + 3.4 * next();
        let lo = regimes::linear_limit(g).max(1e-3);
        let hi = regimes::alpha_c2(g) * 1e4;
        let a = if next() < 0.1 {
            f64::INFINITY
        } else {
            lo * (hi / lo).powf(next())
        };
        let s = Request::new(g, a)
            .accuracy(Accuracy::Tolerance(tol))
            .solve()?;
        if s.method == Method::ClosedForm {
            continue;
        }
        let steps = (16 * s.resolution.steps).max(16384);
        let run = |st| {
            Request::new(g, a).simulate(Resolution {
                springs: 0,
                steps: st,
            })
        };
        let (c, f) = (run(steps)?, run(2 * steps)?);
        let reference = f + (f - c) / 3.0;
        let err = (s.p - reference).abs();
        worst = worst.max(err / tol);
        if err > tol || err > s.error_estimate {
            over_tol += usize::from(err > tol);
            over_est += usize::from(err > s.error_estimate);
            println!(
                "{i}: g={g:.4} a={a:.4e}: P={:.9} err={err:.2e} est={:.2e} steps={} (ref steps {})",
                s.p,
                s.error_estimate,
                s.resolution.steps,
                2 * steps
            );
        }
    }
    println!("tol {tol:e}, {n} points: {over_tol} over tol, {over_est} over estimate, worst err/tol {worst:.2}");
    Ok(())
}
