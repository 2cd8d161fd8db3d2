//! Thornton's law along α at fixed resolution: `thornscan GAMMA E_N A0 A1 N [STEPS]` prints
//! `P` at `N + 1` values of α from `A0` to `A1` (multiples of `α_c2`) and the second
//! differences `P(α−h) − 2P(α) + P(α+h)` divided by `h`: a slope jump of size `J` at α shows as
//! a spike of about `J` there, a smooth `P` as `P'' h`.

use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_p, yield_pressure_for_restitution,
};

fn main() -> anyhow::Result<()> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let f = |i: usize| -> anyhow::Result<f64> { Ok(a[i].parse()?) };
    let (gamma, e_n, a0, a1, n) = (f(0)?, f(1)?, f(2)?, f(3)?, f(4)? as usize);
    let steps = if a.len() > 5 { f(5)? as usize } else { 4096 };
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
    let shear = 2.0 / 7.0 * gamma * gamma;
    let c2 = shear;
    let xs: Vec<f64> = (0..=n)
        .map(|i| a0 + (a1 - a0) * i as f64 / n as f64)
        .collect();
    let ps: Vec<f64> = {
        use std::sync::Mutex;
        let out = Mutex::new(vec![0.0; xs.len()]);
        let chunks: Vec<usize> = (0..xs.len()).collect();
        std::thread::scope(|s| {
            for part in chunks.chunks(xs.len().div_ceil(2)) {
                let out = &out;
                let xs = &xs;
                let motion = &motion;
                s.spawn(move || {
                    for &i in part {
                        let alpha = xs[i] * c2;
                        let p = dimensionless_p(shear, alpha / shear, motion, steps);
                        out.lock().expect("lock")[i] = p;
                    }
                });
            }
        });
        out.into_inner().expect("lock")
    };
    let h = (a1 - a0) / n as f64 * c2;
    for i in 0..xs.len() {
        let d2 = if i > 0 && i < n {
            (ps[i - 1] - 2.0 * ps[i] + ps[i + 1]) / h
        } else {
            f64::NAN
        };
        println!("{:.6} {:.8} {:.12} {:>11.3e}", xs[i], xs[i] * c2, ps[i], d2);
    }
    Ok(())
}
