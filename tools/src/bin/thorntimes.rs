//! Event times of Thornton's normal motion: `thorntimes E_N...` prints, for each `e_n`, the
//! yield time, the switch to unloading and the contact time (fractions of the contact time).

use oblique_solver::thornton::{dimensionless_motion, yield_pressure_for_restitution};

fn main() -> anyhow::Result<()> {
    for a in std::env::args().skip(1) {
        let e: f64 = a.parse()?;
        let m = dimensionless_motion(yield_pressure_for_restitution(e)?);
        println!(
            "e_n {e}: t_y {:.6} t_switch {:.6} (of t_c {:.6})",
            m.yield_time / m.contact_time,
            m.switch_time / m.contact_time,
            m.contact_time
        );
    }
    Ok(())
}
