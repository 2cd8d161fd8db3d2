//! The knots of the `+` strip of a Thornton table (`nodes.knots`): `stripknots GAMMA_LO
//! GAMMA_HI E_LO E_HI` traces the strip's edges and the knots over that range (one root cell
//! each way) and prints, on a 9 × 11 grid, the knots' shares of the span from `α_S` to `α_c2`
//! and (in brackets) the traced edges' minus them where the strip exists inside the patch;
//! then the median, the 90th percentile and the largest of those differences.

use oblique_table::surface::{PartialMap, PatchKind};

fn main() -> anyhow::Result<()> {
    let [g0, g1, e0, e1] = oblique_tools::gamma_e_box("stripknots")?;
    let strip = oblique_sweep::kink::thornton_plus_strip_surfaces((g0, g1), (e0, e1))?;
    let Some(k) = oblique_sweep::knots::thornton_knots(
        (g0, g1),
        1,
        (e0, e1),
        1,
        oblique_table::surface::AxisMap::Linear,
        Some(&strip),
    )?
    else {
        anyhow::bail!("no knots over this range");
    };
    println!("c_star {:?}", k.c_star());
    let coord = |g: f64, a: f64, e: f64| {
        PatchKind::PartialSlip.coord_at(PartialMap::Slip, g, a, e, f64::INFINITY)
    };
    let mut diffs = Vec::new();
    for i in 0..=8 {
        let g = g0 + (g1 - g0) * i as f64 / 8.0;
        let mut line = format!("gamma {g:.4}:");
        for l in 0..=10 {
            let e = e0 + (e1 - e0) * l as f64 / 10.0;
            let knots = k.line(g, e);
            let kn = knots.knots();
            if kn.len() != 6 {
                line += " (no strip knots)";
                continue;
            }
            let share = |x: f64| (x - kn[3]) / (1.0 - kn[3]);
            let traced = |j: usize| {
                strip[j]
                    .as_ref()
                    .and_then(|s| s.alpha_at(g, e))
                    .map(|a| share(coord(g, a, e)))
            };
            let (lo, hi) = (share(kn[4]), share(kn[5]));
            line += &format!(" {lo:.3}/{hi:.3}");
            match (traced(0), traced(1)) {
                (Some(a), Some(b)) if a < b && b < 1.0 => {
                    line += &format!("({:+.4}/{:+.4})", a - lo, b - hi);
                    diffs.extend([(a - lo).abs(), (b - hi).abs()]);
                }
                _ => line += "(-)",
            }
        }
        println!("{line}");
    }
    diffs.sort_by(f64::total_cmp);
    if let Some(&max) = diffs.last() {
        let at = |q: f64| diffs[((diffs.len() - 1) as f64 * q) as usize];
        println!(
            "{} edges: median {:.1e}, 90th percentile {:.1e}, largest {:.1e}",
            diffs.len(),
            at(0.5),
            at(0.9),
            max
        );
    }
    Ok(())
}
