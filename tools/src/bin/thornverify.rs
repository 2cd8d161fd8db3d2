//! A table of Thornton's law next to the traced kinks of the law: `thornverify TABLE N [SEED]`
//! draws `N` points with γ and `e_n` uniform over the table's domain (`e_n < 1`) and α next to
//! one of the re-slip fold `α_R`, the line `α = 2/7`, the loading fold `α_L` and the switch
//! fold `α_S` (in turn;
//! `α_K (1 ± r)`, `r` log-uniform in [1e-4, 1e-2]), and prints the largest difference between
//! the table and a direct solve at tol 1e-8 for each kink, against the table's stated bound.

use oblique_lookup::Table;
use oblique_physics::sample::SplitMix;
use oblique_solver::history::{loading_fold_thornton, reslip_fold_thornton, switch_fold_thornton};
use oblique_solver::{Accuracy, Law, Request};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(a.len() >= 2, "usage: thornverify TABLE N [SEED]");
    let table = Table::open(&a[0])?;
    let n: usize = a[1].parse()?;
    let seed: u64 = if a.len() > 2 { a[2].parse()? } else { 1 };
    let s = table.surface();
    let (g0, g1) = (s.gamma_min(), s.gamma_max());
    let (e0, e1) = table
        .restitution()
        .ok_or_else(|| anyhow::anyhow!("no e_n axis"))?;
    let mut rng = SplitMix(seed);
    let mut pts = Vec::new();
    for i in 0..n {
        let g = g0 + (g1 - g0) * rng.uniform();
        let e = (e0 + (e1 - e0) * rng.uniform()).min(0.9999);
        let r = 10f64.powf(-4.0 + 2.0 * rng.uniform());
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        pts.push((i % 4, g, e, r * sign));
    }
    let out: Vec<(usize, f64, f64, f64, f64)> = pts
        .par_iter()
        .filter_map(|&(k, g, e, r)| {
            let kink = match k {
                0 => reslip_fold_thornton(g, e, 2048).ok()??,
                1 => 2.0 / 7.0,
                2 => loading_fold_thornton(g, e, 2048).ok()??,
                _ => switch_fold_thornton(g, e, 2048).ok()??,
            };
            let alpha = kink * (1.0 + r);
            let t = table.p_e(g, alpha, e).ok()?;
            let sim = Request::new(g, alpha)
                .e_n(e)
                .law(Law::Thornton)
                .accuracy(Accuracy::Tolerance(1e-8))
                .solve()
                .ok()?;
            Some((k, g, alpha, e, (t - sim.p).abs()))
        })
        .collect();
    let bound = table.error_bound();
    for (k, name) in [(0, "alpha_R"), (1, "2/7"), (2, "alpha_L"), (3, "alpha_S")] {
        let v: Vec<_> = out.iter().filter(|o| o.0 == k).collect();
        if let Some(w) = v.iter().max_by(|x, y| x.4.total_cmp(&y.4)) {
            println!(
                "{name}: {} points, max |error| {:.3e} at gamma {:.6} alpha {:.6} e_n {:.6}; \
                 above the bound {bound:.3e}: {}",
                v.len(),
                w.4,
                w.1,
                w.2,
                w.3,
                v.iter().filter(|o| o.4 > bound).count()
            );
        } else {
            println!("{name}: no points");
        }
    }
    Ok(())
}
