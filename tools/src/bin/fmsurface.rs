//! The fold surface F₋ as `sweep run` traces it for a Kelvin–Voigt table with
//! `nodes.probe_kinks` (`oblique_sweep::kink::fold_minus_surface`), and how well it interpolates:
//! `cargo run --release -p oblique-tools --bin fmsurface -- G0 G1 E0 E1 [N]` traces it over
//! γ ∈ [G0, G1], e_n ∈ [E0, E1], prints its traced nodes, where it is defined and the tracing's
//! wall time, then locates F₋ directly (`fold_minus_at_e`, 2048 steps, from the interpolated
//! value) at N random points where the surface is defined (default 100, seed 3) and prints the
//! largest relative difference, overall and at least 0.01 in e_n from its end (`docs/solver.md`,
//! "Kink curves").
use oblique_solver::history::fold_minus_at_e;
use oblique_sweep::kink::{fold_minus_surface, TRACE_STEPS};
use oblique_tools::{arg, arg_or};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (g0, g1): (f64, f64) = (arg(&args, 0, "G0")?, arg(&args, 1, "G1")?);
    let (e0, e1): (f64, f64) = (arg(&args, 2, "E0")?, arg(&args, 3, "E1")?);
    let n: usize = arg_or(&args, 4, "N", 100)?;
    let start = std::time::Instant::now();
    let Some(s) = fold_minus_surface((g0, g1), (e0, e1))? else {
        println!("no F- in gamma [{g0}, {g1}] for e_n <= {e1}");
        return Ok(());
    };
    let wall = start.elapsed().as_secs_f64();
    let (Some((glo, ghi)), Some((elo, ehi))) = (s.gamma_range(), s.e_n_range()) else {
        println!("no F- found in gamma [{g0}, {g1}], e_n [{e0}, {e1}] ({wall:.1} s)");
        return Ok(());
    };
    println!(
        "traced {} nodes in {wall:.1} s: gamma {glo:.4}-{ghi:.4}, e_n {elo}-{ehi}",
        s.traced_nodes()
    );
    if n == 0 {
        return Ok(());
    }
    // Random points where the surface is defined, and whether F₋ exists 0.01 lower in e_n
    // (away from its end).
    let mut rng = oblique_sweep::SplitMix(3);
    let mut points = Vec::new();
    let mut draws = 0;
    while points.len() < n && draws < 1000 * n.max(1) {
        draws += 1;
        let g = glo.max(g0) + (ghi.min(g1) - glo.max(g0)) * rng.uniform();
        let e = elo.max(e0) + (ehi.min(e1) - elo.max(e0)) * rng.uniform();
        if let Some(a) = s.alpha_at(g, e) {
            points.push((g, e, a, s.alpha_at(g, e - 0.01).is_some()));
        }
    }
    let rel = points
        .par_iter()
        .map(|&(g, e, a, inner)| {
            let direct = fold_minus_at_e(g, e, a, TRACE_STEPS)?;
            Ok((g, e, direct.map(|d| a / d - 1.0), inner))
        })
        .collect::<Result<Vec<_>, oblique_solver::PhysicsError>>()?;
    let worst = |inner_only: bool| {
        rel.iter()
            .filter(|r| r.3 || !inner_only)
            .filter_map(|r| r.2.map(|d| (d.abs(), r.0, r.1)))
            .fold(
                (0.0, f64::NAN, f64::NAN),
                |w, x| if x.0 > w.0 { x } else { w },
            )
    };
    let missing = rel.iter().filter(|r| r.2.is_none()).count();
    let (w, g, e) = worst(false);
    println!(
        "{} points ({draws} draws): largest |alpha/alpha_direct - 1| {w:.2e} at gamma {g:.4}, \
         e_n {e:.4}; F- not found directly at {missing}",
        rel.len()
    );
    let (w, g, e) = worst(true);
    println!(
        "  at the {} points 0.01 or more above its end in e_n: {w:.2e} at gamma {g:.4}, e_n {e:.4}",
        rel.iter().filter(|r| r.3).count()
    );
    Ok(())
}
