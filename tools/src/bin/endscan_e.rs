//! E₋ of the Kelvin–Voigt law at a few (γ, e_n), continued down in e_n from the elastic curve:
//! `endscan_e GAMMA...` prints `gamma e_n alpha_E` for e_n = 1, 0.99, …, 0.3 until lost.
use oblique_solver::history::{end_minus_at, end_minus_at_e};

fn main() -> anyhow::Result<()> {
    for g in std::env::args().skip(1) {
        let g: f64 = g.parse()?;
        let guess = if g < 1.9 {
            1.0 / (5.9 * (g - 1.732))
        } else {
            1.0
        };
        let Some(mut a) = end_minus_at(g, guess, 2048)? else {
            println!("{g} 1 none");
            continue;
        };
        println!("{g} 1 {a:.6}");
        for l in 1..=70 {
            let e = 1.0 - l as f64 / 100.0;
            match end_minus_at_e(g, e, a, 2048)? {
                Some(x) => {
                    a = x;
                    if l % 5 == 0 || l < 5 {
                        println!("{g} {e:.2} {a:.6}");
                    }
                }
                None => {
                    println!("{g} {e:.2} lost");
                    break;
                }
            }
        }
    }
    Ok(())
}
