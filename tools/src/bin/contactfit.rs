//! `[DEGREE] [POINTS]`: the fits behind `kelvin_voigt::contact_fit`. The contact time
//! `t̂_c(τ̂)` and the normal restitution `e_n(τ̂)` of the dimensionless Kelvin–Voigt impact
//! (`unit_bodies`), integrated on 16 384 steps (`ViscoelasticBodies::contact_integrated`;
//! `e_n` by `kelvin_voigt::restitution`, the series next to `τ̂ = 0`) at `POINTS` (default
//! 600) Chebyshev-spread `τ̂ ∈ (0, TAU_HAT_MAX]`, and the least-squares Chebyshev series in
//! `u = 2 τ̂/TAU_HAT_MAX − 1` of degree `DEGREE` (default 30) of
//!
//! - `t̂_c/t̂_H` (`t̂_H` the Hertz contact time), pinned to 1 at `τ̂ = 0`;
//! - `(1 − e_n)/τ̂`, each point weighed as the error in `e_n` it gives, pinned to the
//!   small-damping limit `C1 b₁` at `τ̂ = 0` (`b₁` the damping number of `τ̂ = 1`).
//!
//! Prints the coefficients as Rust arrays, and to stderr the residuals at the data and at
//! 1 000 random `τ̂` between them.
use oblique_solver::hertz::HertzClosedForm;
use oblique_solver::kelvin_voigt::{damping_number, restitution, unit_bodies, C1, TAU_HAT_MAX};
use oblique_tools::{chebyshev, least_squares, xorshift};

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let degree: usize = oblique_tools::arg_or(&args, 0, "DEGREE", 30)?;
    let points: usize = oblique_tools::arg_or(&args, 1, "POINTS", 600)?;
    let n = degree + 1;
    let t_h = HertzClosedForm {
        mass: 1.0,
        stiffness: 4.0 / 3.0,
        approach_speed: 1.0,
    }
    .contact_time();
    let at = |tau: f64| {
        (
            unit_bodies(tau).contact_integrated().0 / t_h,
            restitution(tau),
        )
    };
    let data: Vec<(f64, (f64, f64))> = (0..points)
        .map(|k| {
            let t = std::f64::consts::PI * (k as f64 + 0.5) / points as f64;
            let tau = 0.5 * TAU_HAT_MAX * (1.0 - t.cos());
            (tau, at(tau))
        })
        .collect();
    let u_of = |tau: f64| 2.0 * tau / TAU_HAT_MAX - 1.0;
    // t_c/t_H, and its exact value 1 at τ̂ = 0 weighted as a point.
    let mut rows: Vec<Vec<f64>> = data.iter().map(|&(t, _)| chebyshev(u_of(t), n)).collect();
    let mut rhs: Vec<f64> = data.iter().map(|&(_, (r, _))| r).collect();
    rows.push(chebyshev(-1.0, n));
    rhs.push(1.0);
    let ratio = least_squares(rows, rhs);
    // (1 − e_n)/τ̂ weighed by τ̂ (the error in e_n), its limit weighted as at TAU_HAT_MAX/2.
    let limit = C1 * damping_number(1.0);
    let mut rows: Vec<Vec<f64>> = data
        .iter()
        .map(|&(t, _)| chebyshev(u_of(t), n).iter().map(|c| t * c).collect())
        .collect();
    let mut rhs: Vec<f64> = data.iter().map(|&(_, (_, e))| 1.0 - e).collect();
    let w = 0.5 * TAU_HAT_MAX;
    rows.push(chebyshev(-1.0, n).iter().map(|c| w * c).collect());
    rhs.push(w * limit);
    let deficit = least_squares(rows, rhs);
    let eval = |c: &[f64], tau: f64| -> f64 {
        chebyshev(u_of(tau), n)
            .iter()
            .zip(c)
            .map(|(t, c)| t * c)
            .sum()
    };
    let fit = |tau: f64| (eval(&ratio, tau), 1.0 - tau * eval(&deficit, tau));
    let worst = |pts: &[(f64, (f64, f64))]| {
        pts.iter().fold((0.0f64, 0.0f64), |(wr, we), &(t, (r, e))| {
            let (fr, fe) = fit(t);
            (wr.max((fr / r - 1.0).abs()), we.max((fe - e).abs()))
        })
    };
    let (wr, we) = worst(&data);
    let mut next = xorshift(7);
    let random: Vec<(f64, (f64, f64))> = (0..1000)
        .map(|_| {
            let tau = TAU_HAT_MAX * next();
            (tau, at(tau))
        })
        .collect();
    let (rr, re) = worst(&random);
    eprintln!(
        "degree {degree}, {points} points: t_c relative {wr:.2e} (data), {rr:.2e} (1000 random); \
         e_n absolute {we:.2e} (data), {re:.2e} (random); at tau = 0: t_c/t_H - 1 = {:.1e}, \
         deficit/limit - 1 = {:.1e}",
        eval(&ratio, 0.0) - 1.0,
        eval(&deficit, 0.0) / limit - 1.0
    );
    for (name, c) in [("CONTACT_TIME_FIT", &ratio), ("DEFICIT_FIT", &deficit)] {
        println!("const {name}: [f64; {n}] = [");
        for v in c.iter() {
            println!("    {v:e},");
        }
        println!("];");
    }
    Ok(())
}
