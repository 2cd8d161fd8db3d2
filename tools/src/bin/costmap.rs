//! Cost map of the automatic refinement over the (γ, α) plane (a scratch tool):
//! `cargo run --release -p oblique-tools --bin costmap -- TOL`.
use oblique_solver::Request;
use oblique_solver::*;
use std::time::Instant;

fn main() -> anyhow::Result<()> {
    let tol: f64 = oblique_tools::arg_or(&oblique_tools::args(), 0, "TOL", 1e-5)?;
    let gammas: [f64; 9] = [0.3, 0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.2, 3.5];
    for &g in &gammas {
        let c1 = if g > 1.0 {
            2.0 * g * g / (7.0 * (2.0 * g * g - 1.0))
        } else {
            2.0 * g * g / 7.0
        };
        let c2 = 2.0 * g * g / 7.0;
        let mut alphas: Vec<f64> = Vec::new();
        if g > 1.0 {
            for k in 1..4 {
                alphas.push(c1 * (c2 / c1).powf(k as f64 / 4.0));
            }
        }
        for r in [0.3, 1.0, 3.0, 30.0] {
            alphas.push(c2 * (1.0 + r));
        }
        alphas.push(f64::INFINITY);
        let mut line = format!("g={g:4}:");
        let mut tot = 0.0;
        for &a in &alphas {
            let t = Instant::now();
            let s = Request::new(g, a)
                .accuracy(Accuracy::Tolerance(tol))
                .solve()?;
            let ms = t.elapsed().as_secs_f64() * 1e3;
            tot += ms;
            line += &format!(" {:.0}:{:.1}ms", s.resolution.steps, ms);
        }
        println!("{line}  total {tot:.0} ms");
    }
    Ok(())
}
