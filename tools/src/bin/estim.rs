//! Measures how well the error estimates of the accurate scheme bracket the true error:
//! `cargo run --release -p oblique-tools --bin estim` (about 3 minutes). Prints, per point and level, the true
//! error / estimate of the plain finest value (P) and of the Richardson value (R).
use oblique_physics::regimes;
use oblique_solver::{impact::base_resolution, Request, *};
fn main() {
    let gammas = [0.3, 0.7, 0.95, 1.2, 1.754, 2.2, 2.8, 3.5];
    let alphas_rel = [1.1, 1.5, 3.0, 0.0]; // multiples of linear limit; 0 => inf
    let mut worst_plain = 0.0f64;
    let mut worst_rich = 0.0f64;
    for &g in &gammas {
        for &ar in &alphas_rel {
            let lim = regimes::linear_limit(g).max(0.02);
            let a = if ar == 0.0 {
                f64::INFINITY
            } else {
                ar * lim.max(regimes::alpha_c2(g) * 0.3)
            };
            let base = base_resolution(g, Scheme::Accurate);
            let pk: Vec<f64> = (0..7)
                .map(|k| {
                    Request::new(g, a)
                        .simulate(base.doubled(k))
                        .expect("valid point")
                })
                .collect();
            let reference = Request::new(g, a)
                .simulate(base.doubled(9))
                .expect("valid point");
            let mut line = format!("g={g} a={a:.3}:");
            for k in 2..7 {
                let plain_est = (pk[k] - pk[k - 1])
                    .abs()
                    .max((pk[k - 1] - pk[k - 2]).abs() / 4.0);
                let plain_err = (pk[k] - reference).abs();
                let r = |j: usize| pk[j] + (pk[j] - pk[j - 1]) / 3.0;
                let rich_est = (r(k) - r(k - 1)).abs().max(0.1 * (pk[k] - pk[k - 1]).abs());
                let rich_err = (r(k) - reference).abs();
                if plain_err > plain_est {
                    worst_plain = worst_plain.max(plain_err / plain_est);
                }
                if rich_err > rich_est && rich_err > 2e-8 {
                    worst_rich = worst_rich.max(rich_err / rich_est);
                }
                line += &format!(
                    " [{}: P {:.0e}/{:.0e} R {:.0e}/{:.0e}]",
                    base.doubled(k as u32).steps,
                    plain_err,
                    plain_est,
                    rich_err,
                    rich_est
                );
            }
            println!("{line}");
        }
    }
    println!("worst under-estimate ratio: plain {worst_plain:.2} rich {worst_rich:.2}");
}
