//! What the Kelvin–Voigt normal motion costs a solve (scratch): `kvnormalcost [N]` times, for
//! `N` random `e_n` in [0.3, 1) (default 200), the relaxation time `τ̂(e_n)` and the normal
//! motion of the levels 128 … 2048 (the fine motion, once per `τ̂`, then its samples), against
//! a solve at tol 1e-6 at γ = 1.754, α = 1 with that `e_n` once the motion is cached.
use std::time::Instant;

use oblique_solver::kelvin_voigt::{dimensionless_normal, tau_for_restitution};
use oblique_solver::Request;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let n: usize = oblique_tools::arg_or(&args, 0, "N", 200)?;
    let mut x: u64 = 12345;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut t_tau, mut t_normal, mut t_solve) = (0.0, 0.0, 0.0);
    for _ in 0..n {
        let e_n = 0.3 + 0.69 * next();
        let t0 = Instant::now();
        let tau = tau_for_restitution(e_n)?;
        let t1 = Instant::now();
        for k in 0..5 {
            std::hint::black_box(dimensionless_normal(128 << k, tau));
        }
        let t2 = Instant::now();
        std::hint::black_box(Request::new(1.754, 1.0).e_n(e_n).solve()?);
        let t3 = Instant::now();
        t_tau += (t1 - t0).as_secs_f64();
        t_normal += (t2 - t1).as_secs_f64();
        t_solve += (t3 - t2).as_secs_f64();
    }
    let us = |t: f64| t / n as f64 * 1e6;
    println!(
        "{n} e_n: tau {:.1} us, normal motion of 5 levels {:.1} us, solve at tol 1e-6 (motion cached) {:.1} us",
        us(t_tau),
        us(t_normal),
        us(t_solve)
    );
    Ok(())
}
