//! Thornton's `P` to the last bit on a fixed set of cases, for refactors of the row that must
//! not change a bit: `thornbits [STEPS]` prints one line per `(γ, α, e_n)` (γ 0.5–3, α 0.1–∞,
//! `e_n` 0.3–1, with the MDR-unloading variant at `e_n` 0.8) and a checksum of all the bits.
use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_p, yield_pressure_for_restitution,
};
use oblique_solver::thornton_mdr;

fn main() -> anyhow::Result<()> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(512), |s| s.parse())?;
    let mut sum: u64 = 0;
    for e_n in [1.0, 0.95, 0.8, 0.6, 0.3] {
        let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
        for gamma in [0.5, 1.2, 1.754, 2.1, 3.0] {
            for alpha in [0.1, 0.3, 0.7, 1.0, 1.5, 2.5, f64::INFINITY] {
                let shear = 2.0 / 7.0 * gamma * gamma;
                let p = dimensionless_p(shear, alpha / shear, &motion, steps);
                sum = sum.rotate_left(7) ^ p.to_bits();
                println!("{e_n} {gamma} {alpha} {p:.17e}");
            }
        }
    }
    let m =
        thornton_mdr::dimensionless_motion(thornton_mdr::yield_pressure_for_restitution_mdr(0.8)?);
    for gamma in [0.5, 1.754, 3.0] {
        for alpha in [0.3, 1.0, f64::INFINITY] {
            let shear = 2.0 / 7.0 * gamma * gamma;
            let p = thornton_mdr::dimensionless_p(shear, alpha / shear, &m, steps);
            sum = sum.rotate_left(7) ^ p.to_bits();
            println!("mdr 0.8 {gamma} {alpha} {p:.17e}");
        }
    }
    println!("checksum {sum:016x}");
    Ok(())
}
