//! Points next to the fold F₋ of the Kelvin–Voigt law at one γ, for a dense check of a table
//! with an `e_n` axis (`docs/accuracy.md`, "Tables with an e_n axis"): `fmscan_e GAMMA E1,E2,...
//! D0 D1 N` prints `tag,gamma,alpha,e_n` for each listed `e_n` at `α = α_F(1 + d)`, d at N even
//! steps from D0 to D1, with `α_F` located directly (where the predicate holds in α ∈ [0.3,
//! 0.7], then `fold_minus_at_e`, 2048 steps); an `e_n` without F₋ is named on stderr and left
//! out. Pipe into `probe TABLE TOL`.
use oblique_solver::history::{fold_minus_at_e, restitution_minus_somewhere_e};
use oblique_tools::arg;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let gamma: f64 = arg(&args, 0, "GAMMA")?;
    let list: String = arg(&args, 1, "E_LIST")?;
    let (d0, d1): (f64, f64) = (arg(&args, 2, "D0")?, arg(&args, 3, "D1")?);
    let n: usize = arg(&args, 4, "N")?;
    let mut tag = 0;
    for e in list.split(',') {
        let e_n: f64 = e.parse()?;
        let alpha = match restitution_minus_somewhere_e(gamma, e_n, (0.3, 0.7), 2048)? {
            Some(a) => fold_minus_at_e(gamma, e_n, a, 2048)?,
            None => None,
        };
        let Some(alpha) = alpha else {
            eprintln!("gamma {gamma}, e_n {e_n}: no F-");
            continue;
        };
        eprintln!("gamma {gamma}, e_n {e_n}: alpha_F {alpha}");
        for j in 0..n {
            let d = d0 + (d1 - d0) * j as f64 / (n - 1).max(1) as f64;
            println!("g{gamma}e{tag},{gamma},{},{e_n}", alpha * (1.0 + d));
            tag += 1;
        }
    }
    Ok(())
}
