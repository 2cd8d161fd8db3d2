//! Where the `+` strip and the loading fold lie in the stick patch of a Thornton table:
//! `stickstrip GAMMA_LO GAMMA_HI E_LO E_HI` traces the strip's edges over that range and
//! prints, on a 9 × 11 grid, `α₊lo/α_c2`, `α₊hi/α_c2` (`-` where the edge is missing) and
//! `α_L/α_c2` (the loading fold, `-` where it is gone).

use oblique_physics::regimes::alpha_c2;
use oblique_solver::history::loading_fold_thornton;

fn main() -> anyhow::Result<()> {
    let [g0, g1, e0, e1] = oblique_tools::gamma_e_box("stickstrip")?;
    let strip = oblique_sweep::kink::thornton_plus_strip_surfaces((g0, g1), (e0, e1))?;
    for i in 0..=8 {
        let g = g0 + (g1 - g0) * i as f64 / 8.0;
        let c2 = alpha_c2(g);
        let mut line = format!("gamma {g:.4}:");
        for l in 0..=10 {
            let e = e0 + (e1 - e0) * l as f64 / 10.0;
            let show = |a: Option<f64>| a.map_or("-".to_string(), |a| format!("{:.3}", a / c2));
            let edge = |k: usize| strip[k].as_ref().and_then(|s| s.alpha_at(g, e));
            let fold = loading_fold_thornton(g, e, oblique_sweep::knots::STEPS)?;
            line += &format!(" {}/{}/{}", show(edge(0)), show(edge(1)), show(fold));
        }
        println!("{line}");
    }
    Ok(())
}
