//! Scan P(α) at fixed γ (tol 1e-7) and print P, its slope and the change of slope on a log grid:
//! `cargo run --release --example kinkscan -- GAMMA [N] [LO HI]` (LO, HI as fractions of α_c2;
//! default α_c1 to 3 α_c2). See docs/solver.md, "Kink curves".
use oblique_solver::*;
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let g: f64 = args[0].parse().unwrap();
    let n: usize = args.get(1).map_or(400, |s| s.parse().unwrap());
    let c1 = 2.0 * g * g / (7.0 * (2.0 * g * g - 1.0));
    let c2 = 2.0 * g * g / 7.0;
    let lo = args
        .get(2)
        .map_or(c1.max(1e-3), |s| s.parse::<f64>().unwrap() * c2);
    let hi = args
        .get(3)
        .map_or(c2 * 3.0, |s| s.parse::<f64>().unwrap() * c2);
    let xs: Vec<f64> = (0..=n)
        .map(|i| (lo.ln() + (hi / lo).ln() * i as f64 / n as f64).exp())
        .collect();
    let ps: Vec<f64> = xs
        .iter()
        .map(|&a| {
            solve(g, a, Accuracy::Tolerance(1e-7), Scheme::Accurate, false)
                .unwrap()
                .p
        })
        .collect();
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
}
