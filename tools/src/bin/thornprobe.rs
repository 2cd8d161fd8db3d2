//! Thornton's law at fixed resolutions: `thornprobe GAMMA ALPHA E_N [STEPS...]` prints `P` at
//! each number of steps, the differences between levels and the full-slip line.

use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_p, yield_pressure_for_restitution,
};

fn main() -> anyhow::Result<()> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let (gamma, alpha, e_n) = (args[0], args[1], args[2]);
    let steps: Vec<usize> = if args.len() > 3 {
        args[3..].iter().map(|&s| s as usize).collect()
    } else {
        vec![256, 512, 1024, 2048, 4096]
    };
    let p_y = yield_pressure_for_restitution(e_n)?;
    let motion = dimensionless_motion(p_y);
    println!(
        "p_y {p_y:.9} e_n(motion) {:.12} d_max {:.6} rho {:.6} d_p {:.6}",
        motion.restitution(),
        motion.max_indentation,
        motion.unloading.ratio,
        motion.unloading.plastic_indentation
    );
    let shear = 2.0 / 7.0 * gamma * gamma;
    let limit = if alpha.is_finite() {
        alpha / shear
    } else {
        f64::INFINITY
    };
    let line = 1.0 - 3.5 * (1.0 + e_n) * alpha;
    if std::env::var("THORN_TIMING").is_ok() {
        for &n in &steps {
            let t = std::time::Instant::now();
            let reps = 20;
            for _ in 0..reps {
                std::hint::black_box(motion.trajectory(n));
            }
            println!(
                "trajectory({n}): {:.3} ms",
                t.elapsed().as_secs_f64() * 1e3 / reps as f64
            );
        }
    }
    let mut last: Option<f64> = None;
    let mut diffs = Vec::new();
    for &n in &steps {
        let t = std::time::Instant::now();
        let p = if std::env::var("THORN_MDR").is_ok() {
            let m = oblique_solver::thornton_mdr::dimensionless_motion(
                oblique_solver::thornton_mdr::yield_pressure_for_restitution_mdr(e_n)?,
            );
            oblique_solver::thornton_mdr::dimensionless_p(shear, limit, &m, n)
        } else {
            dimensionless_p(shear, limit, &motion, n)
        };
        let el = t.elapsed().as_secs_f64();
        let d = last.map(|l| p - l);
        if let Some(d) = d {
            diffs.push(d);
        }
        let ratio = if diffs.len() >= 2 {
            diffs[diffs.len() - 2] / diffs[diffs.len() - 1]
        } else {
            f64::NAN
        };
        println!(
            "{n:6} P {p:.12} diff {:>10.3e} ratio {ratio:6.2} P-line {:>10.3e} {:.3}s",
            d.unwrap_or(f64::NAN),
            p - line,
            el
        );
        last = Some(p);
    }
    Ok(())
}
