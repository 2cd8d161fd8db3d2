//! Honesty and cost of the error estimate of Thornton's law:
//! `cargo run --release -p oblique-tools --bin thornhonest -- N SEED [TOL...]` solves the nine
//! benchmark points at `e_n` 0.9 and 0.6, the cusp of the stick patch at γ = 1.9182,
//! α = 3.1582, `e_n` = 0.9143, and `N` random points (γ 0.3–3.5 log-uniform, `e_n` uniform in
//! 0.3–1; α: a tenth at ∞, a third within 1e-4–1e-1 (relative) of α = 2/7, the Kelvin–Voigt
//! `α_c1(γ, e_n)` or `α_c2`, the rest log-uniform over 0.01–30) at each tolerance (default
//! 1e-4, 1e-5, 1e-6, 1e-7), and compares each answer with the Richardson value of 16 384 and
//! 32 768 steps (points where that reference is itself uncertain beyond 1e-9, by its difference
//! to the Richardson value of 8 192 and 16 384 steps, are left out and counted). Prints, per
//! tolerance, the points whose estimate is below the error, the count of such points, the
//! largest error/estimate, the answers above the tolerance and the sum of the finest steps.
//! Points run in parallel.
use oblique_solver::{Accuracy, Law, Request, Resolution};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let n: usize = oblique_tools::arg_or(&args, 0, "N", 300)?;
    let seed: u64 = oblique_tools::arg_or(&args, 1, "SEED", 1)?;
    let tols: Vec<f64> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|s| s.parse())
            .collect::<Result<_, _>>()?
    } else {
        vec![1e-4, 1e-5, 1e-6, 1e-7]
    };
    let points = oblique_tools::thornton_honesty_points(n, seed);
    // Per point: the reference and its uncertainty, then (P, estimate, steps) per tolerance.
    type Answers = Vec<Option<(f64, f64, usize)>>;
    let rows: Vec<(f64, f64, Answers)> = points
        .par_iter()
        .map(|&(g, a, e)| {
            let req = Request::new(g, a).e_n(e).law(Law::Thornton).forced(true);
            let at = |steps| {
                req.simulate(Resolution { springs: 0, steps })
                    .unwrap_or(f64::NAN)
            };
            let (p8, p16, p32) = (at(8192), at(16_384), at(32_768));
            let reference = p32 + (p32 - p16) / 3.0;
            let spread = (reference - (p16 + (p16 - p8) / 3.0)).abs();
            let answers = tols
                .iter()
                .map(|&tol| {
                    req.accuracy(Accuracy::Tolerance(tol))
                        .solve()
                        .ok()
                        .map(|s| (s.p, s.error_estimate, s.resolution.steps))
                })
                .collect();
            (reference, spread, answers)
        })
        .collect();
    println!("tol gamma alpha e_n steps error estimate error/estimate");
    for (t, &tol) in tols.iter().enumerate() {
        let (mut under, mut above_tol, mut failed, mut uncertain, mut steps) = (0, 0, 0, 0, 0);
        let mut worst = 0.0f64;
        for (&(g, a, e), (reference, spread, answers)) in points.iter().zip(&rows) {
            let Some((p, est, n)) = answers[t] else {
                failed += 1;
                continue;
            };
            steps += n;
            if spread.is_nan() || *spread > 1e-9 {
                uncertain += 1;
                continue;
            }
            let error = (p - reference).abs();
            worst = worst.max(error / est);
            if error > tol {
                above_tol += 1;
            }
            if error > est {
                under += 1;
                println!(
                    "{tol:e} {g:.6} {a:.6} {e:.6} {n} {error:.3e} {est:.3e} {:.3}",
                    error / est
                );
            }
        }
        println!(
            "# tol {tol:e}: {under} estimates below the error, largest error/estimate {worst:.3}, \
             {above_tol} errors above tol; sum of finest steps {steps}; {failed} not solved, \
             {uncertain} with an uncertain reference"
        );
    }
    Ok(())
}
