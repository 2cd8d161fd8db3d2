//! Points next to the end-of-contact surface E₋ of the Kelvin–Voigt law as `probe` input:
//! `nearend_e GAMMA_LO GAMMA_HI E_LO E_HI N SEED [U_LO U_HI] > points.csv`. Columns every 0.02
//! in γ are traced from e_n = 1 down every 0.01 (continuation), α_E interpolated bilinearly in
//! (γ, ln α); points at α = α_E(1 + s·10^u), u uniform in [U_LO, U_HI] (default [−4, −1]).
use oblique_solver::history::{end_minus_at, end_minus_at_e};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    anyhow::ensure!(
        a.len() == 6 || a.len() == 8,
        "usage: nearend_e GAMMA_LO GAMMA_HI E_LO E_HI N SEED [U_LO U_HI]"
    );
    let (u_lo, u_hi) = if a.len() == 8 {
        (a[6], a[7])
    } else {
        (-4.0, -1.0)
    };
    let (g0, g1, e0, e1, n, seed) = (a[0], a[1], a[2], a[3], a[4] as usize, a[5] as u64);
    let dg = 0.02;
    let ng = ((g1 - g0) / dg).ceil() as usize + 1;
    let rows = ((1.0 - e0) * 100.0).ceil() as usize + 1;
    let cols: Vec<Vec<f64>> = (0..ng)
        .into_par_iter()
        .map(|i| {
            let g = g0 + i as f64 * dg;
            let mut out = vec![f64::NAN; rows];
            let guess = if g < 1.9 {
                1.0 / (5.9 * (g - 1.732))
            } else {
                1.0
            };
            let Ok(Some(mut a)) = end_minus_at(g, guess, 2048) else {
                return out;
            };
            out[0] = a.ln();
            for (l, o) in out.iter_mut().enumerate().skip(1) {
                let e = 1.0 - l as f64 / 100.0;
                match end_minus_at_e(g, e.max(0.3), a, 2048) {
                    Ok(Some(x)) => {
                        a = x;
                        *o = a.ln();
                    }
                    _ => break,
                }
            }
            out
        })
        .collect();
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut k = 0;
    while k < n {
        let g = g0 + (g1 - g0) * rng.uniform();
        let e = e0 + (e1 - e0) * rng.uniform();
        let u = u_lo + (u_hi - u_lo) * rng.uniform();
        let s = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        let x = ((g - g0) / dg).min(ng as f64 - 1.0 - 1e-9);
        let y = ((1.0 - e) * 100.0).min(rows as f64 - 1.0 - 1e-9);
        let (i, l) = (x as usize, y as usize);
        if i + 1 >= ng || l + 1 >= rows {
            continue;
        }
        let (fx, fy) = (x - i as f64, y - l as f64);
        let v = (1.0 - fx) * ((1.0 - fy) * cols[i][l] + fy * cols[i][l + 1])
            + fx * ((1.0 - fy) * cols[i + 1][l] + fy * cols[i + 1][l + 1]);
        if !v.is_finite() {
            continue;
        }
        println!("{u:.3},{g},{},{e}", v.exp() * (1.0 + s * 10f64.powf(u)));
        k += 1;
    }
    Ok(())
}
