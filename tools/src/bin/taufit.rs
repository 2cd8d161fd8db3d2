//! `N`: the relaxation time `τ̂(e_n)` of the Kelvin–Voigt law at the `N` Chebyshev nodes of
//! `x = 1 − e_n ∈ [0, 0.7]`, by the root search (`tau_for_restitution`), as CSV `x,tau`: the
//! data behind the starting guess of that search (`kelvin_voigt::TAU_GUESS`).
use oblique_solver::kelvin_voigt::tau_for_restitution;

fn main() -> anyhow::Result<()> {
    let n: usize = std::env::args().nth(1).map_or(Ok(40), |s| s.parse())?;
    println!("x,tau");
    for k in 0..n {
        let t = std::f64::consts::PI * (k as f64 + 0.5) / n as f64;
        let x = 0.35 * (1.0 - t.cos());
        println!("{x:.17e},{:.17e}", tau_for_restitution(1.0 - x)?);
    }
    Ok(())
}
