//! `[DEGREE] [POINTS]`: the fit behind `kelvin_voigt::tau_for_restitution`. The relaxation
//! time `τ̂(e_n)` of the Kelvin–Voigt law by the root search from the series
//! (`tau_for_restitution_from_series`, no fit involved) at `POINTS` (default 600) points of
//! `x = 1 − e_n ∈ (0, 0.7]` spread as Chebyshev nodes, and the least-squares Chebyshev series of
//! `g = τ̂/x` in `u = x/0.35 − 1` of degree `DEGREE` (default 28). Each point weighs as the
//! error in `τ̂` it gives (`x (g − τ̂/x)`): the search knows `τ̂` to a few ulps of `e_n`, so
//! `τ̂/x` only to `~ε/x` near `x = 0`; there the fit is pinned by the exact limit
//! `g(0) = 1/(C1 b₁)` of the small-damping series (`b₁` the damping number of `τ̂ = 1`).
//! Prints the coefficients as a Rust array and the residuals (relative, in `τ̂`) to stderr.
use oblique_solver::kelvin_voigt::{damping_number, tau_for_restitution_from_series, C1};
use oblique_tools::{chebyshev, least_squares};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let degree: usize = args.next().map_or(Ok(28), |s| s.parse())?;
    let points: usize = args.next().map_or(Ok(600), |s| s.parse())?;
    let n = degree + 1;
    let data: Vec<(f64, f64)> = (0..points)
        .map(|k| {
            let t = std::f64::consts::PI * (k as f64 + 0.5) / points as f64;
            let x = 0.35 * (1.0 - t.cos());
            tau_for_restitution_from_series(1.0 - x).map(|tau| (x, tau))
        })
        .collect::<Result<_, _>>()?;
    let limit = 1.0 / (C1 * damping_number(1.0));
    let mut rows = Vec::new();
    let mut rhs = Vec::new();
    for &(x, tau) in &data {
        let u = x / 0.35 - 1.0;
        rows.push(chebyshev(u, n).iter().map(|t| x * t).collect());
        rhs.push(tau);
    }
    // The exact limit at x = 0, weighted as a point at x = 0.35.
    rows.push(chebyshev(-1.0, n).iter().map(|t| 0.35 * t).collect());
    rhs.push(0.35 * limit);
    let c = least_squares(rows, rhs);
    let fit = |x: f64| {
        let u = x / 0.35 - 1.0;
        x * chebyshev(u, n)
            .iter()
            .zip(&c)
            .map(|(t, c)| t * c)
            .sum::<f64>()
    };
    let mut worst = [(0.0f64, 0.0f64); 3];
    for &(x, tau) in &data {
        let r = (fit(x) / tau - 1.0).abs();
        let band = if x < 0.01 {
            0
        } else if x < 0.1 {
            1
        } else {
            2
        };
        if r > worst[band].0 {
            worst[band] = (r, x);
        }
    }
    let g0 = fit(1e-300) / 1e-300;
    eprintln!(
        "degree {degree}, {points} points: relative residual in tau {:.2e} (x < 0.01, at x = {:.2e}), \
         {:.2e} (0.01-0.1), {:.2e} (x >= 0.1); g(0) off the limit by {:.1e}",
        worst[0].0,
        worst[0].1,
        worst[1].0,
        worst[2].0,
        g0 / limit - 1.0
    );
    println!("const TAU_FIT: [f64; {n}] = [");
    for v in &c {
        println!("    {v:e},");
    }
    println!("];");
    Ok(())
}
