//! The shortest zone of each level of a refinement (scratch): `zonelevels GAMMA ALPHA E_N`
//! prints, for 128 … 16384 steps, `P` and the steps spanned by the run's shortest zone that
//! lasts at least `oblique_solver::zones::ZONE_MIN` `t_c`.
use oblique_solver::{ContactLaw, Law, Resolution, Scheme};

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let g: f64 = oblique_tools::arg(&args, 0, "GAMMA")?;
    let a: f64 = oblique_tools::arg(&args, 1, "ALPHA")?;
    let e: f64 = oblique_tools::arg(&args, 2, "E_N")?;
    for k in 0..8 {
        let res = Resolution {
            springs: 0,
            steps: 128 << k,
        };
        let level = if Law::KelvinVoigt.answering(e) == Law::Elastic {
            let (g, a, p) = oblique_solver::elastic::Elastic::prepare(g, a, 1.0, Scheme::Accurate)?;
            oblique_solver::elastic::Elastic::simulate(g, a, p, res, Scheme::Accurate)?
        } else {
            use oblique_solver::kelvin_voigt::KelvinVoigt as L;
            let (g, a, p) = L::prepare(g, a, e, Scheme::Accurate)?;
            L::simulate(g, a, p, res, Scheme::Accurate)?
        };
        println!(
            "{:6} P {:.10} shortest zone {:.1} steps",
            res.steps, level.p, level.shortest_zone
        );
    }
    Ok(())
}
