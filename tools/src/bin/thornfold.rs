//! The loading fold of Thornton's law in the stick patch: `thornfold GAMMAS E_NS [STEPS]`
//! (comma-separated lists) prints `α_L(γ, e_n)` and `α_L/α_c2` for every pair
//! (`oblique_solver::history::loading_fold_thornton`; `none` where the fold has reached
//! `α_c2`).

use oblique_solver::history::loading_fold_thornton;

fn list(s: &str) -> anyhow::Result<Vec<f64>> {
    Ok(s.split(',').map(str::parse).collect::<Result<_, _>>()?)
}

fn main() -> anyhow::Result<()> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(a.len() >= 2, "usage: thornfold GAMMAS E_NS [STEPS]");
    let (gammas, e_ns) = (list(&a[0])?, list(&a[1])?);
    let steps = if a.len() > 2 { a[2].parse()? } else { 2048 };
    for &g in &gammas {
        for &e in &e_ns {
            let c2 = 2.0 * g * g / 7.0;
            match loading_fold_thornton(g, e, steps)? {
                Some(al) => println!("{g} {e} {al:.9} {:.6}", al / c2),
                None => println!("{g} {e} none"),
            }
        }
    }
    Ok(())
}
