//! Scan P(α) at fixed γ (tol 1e-7) and print P, its slope and the change of slope on a log grid:
//! `cargo run --release -p oblique-tools --bin kinkscan -- GAMMA [N] [LO HI]` (LO, HI as fractions of α_c2;
//! default α_c1 to 3 α_c2). See docs/solver.md, "Kink curves".
use oblique_solver::Request;
use oblique_solver::*;
use oblique_tools::{arg, arg_or, args};

fn main() -> anyhow::Result<()> {
    let args = args();
    let g: f64 = arg(&args, 0, "GAMMA")?;
    let n: usize = arg_or(&args, 1, "N", 400)?;
    let c1 = 2.0 * g * g / (7.0 * (2.0 * g * g - 1.0));
    let c2 = 2.0 * g * g / 7.0;
    let lo = arg_or(&args, 2, "LO", c1.max(1e-3) / c2)? * c2;
    let hi = arg_or(&args, 3, "HI", 3.0)? * c2;
    let xs: Vec<f64> = (0..=n)
        .map(|i| (lo.ln() + (hi / lo).ln() * i as f64 / n as f64).exp())
        .collect();
    let ps = xs
        .iter()
        .map(|&a| {
            Ok(Request::new(g, a)
                .accuracy(Accuracy::Tolerance(1e-7))
                .solve()?
                .p)
        })
        .collect::<anyhow::Result<Vec<f64>>>()?;
    println!("# gamma {g} ac1 {c1} ac2 {c2}");
    for i in 1..n {
        let s0 = (ps[i] - ps[i - 1]) / (xs[i] - xs[i - 1]);
        let s1 = (ps[i + 1] - ps[i]) / (xs[i + 1] - xs[i]);
        println!(
            "{:.6} {:.9} {:.5} {:.4}",
            xs[i],
            ps[i],
            s1,
            (s1 - s0) / (xs[i + 1] - xs[i - 1]) * 2.0
        );
    }
    Ok(())
}
