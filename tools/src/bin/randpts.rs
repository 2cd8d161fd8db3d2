//! Random points as `probe` input: `randpts GAMMA_LO GAMMA_HI E_LO E_HI N SEED > points.csv`,
//! γ and `e_n` uniform, α log-uniform over 0.05–50 (every patch of a table over all α), one
//! `r,gamma,alpha,e_n` line each. The same seed gives the same points.
use oblique_tools::arg;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (g0, g1): (f64, f64) = (arg(&args, 0, "GAMMA_LO")?, arg(&args, 1, "GAMMA_HI")?);
    let (e0, e1): (f64, f64) = (arg(&args, 2, "E_LO")?, arg(&args, 3, "E_HI")?);
    let (n, seed): (usize, u64) = (arg(&args, 4, "N")?, arg(&args, 5, "SEED")?);
    let mut u = oblique_physics::sample::uniform(seed);
    for _ in 0..n {
        let g = g0 + (g1 - g0) * u();
        let e = e0 + (e1 - e0) * u();
        let a = 10f64.powf(-1.3 + 3.0 * u());
        println!("r,{g:.17e},{a:.17e},{e}");
    }
    Ok(())
}
