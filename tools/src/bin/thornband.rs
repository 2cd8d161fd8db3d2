//! Where Thornton's law has a zone at the `+μq` limit while the contact loads
//! (`oblique_solver::history::has_loading_zone_thornton`, 2048 steps): `thornband GAMMA E_N LO
//! HI N` prints, at `N + 1` values of `α/α_c2` from `LO` to `HI`, `Y` where the zone exists and
//! `.` where it does not. `P` changes its slope at the band's upper edge, the loading fold
//! `α_L` (`loading_fold_thornton`) while it lies above `α_c2`, and shows no kink at its lower
//! edge (`docs/solver.md`, "The loading band"). `thornband --locate GAMMA
//! E_N[,E_N…] [STEPS]` prints both edges located (`loading_band_thornton`, on STEPS steps,
//! default 2048) as multiples of `α_c2`.

use oblique_solver::history::{has_loading_zone_thornton, loading_band_thornton};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--locate") {
        anyhow::ensure!(
            (3..=4).contains(&args.len()),
            "usage: thornband --locate GAMMA E_N[,E_N...] [STEPS]"
        );
        let steps: usize = args.get(3).map_or(Ok(2048), |s| s.parse())?;
        let g: f64 = args[1].parse()?;
        let c2 = oblique_physics::regimes::alpha_c2(g);
        for e in args[2].split(',') {
            let e: f64 = e.parse()?;
            let t = std::time::Instant::now();
            let band = loading_band_thornton(g, e, steps)?;
            let us = t.elapsed().as_secs_f64();
            match band {
                Some((lo, hi)) => println!(
                    "gamma {g} e_n {e}: band {:.6}..{:.6} alpha_c2 ({lo:.8}..{hi:.8}) in {us:.2} s",
                    lo / c2,
                    hi / c2
                ),
                None => println!("gamma {g} e_n {e}: no band found in {us:.2} s"),
            }
        }
        return Ok(());
    }
    let a: Vec<f64> = args.iter().map(|s| s.parse()).collect::<Result<_, _>>()?;
    anyhow::ensure!(a.len() == 5, "usage: thornband GAMMA E_N LO HI N");
    let (g, e, lo, hi) = (a[0], a[1], a[2], a[3]);
    let n = a[4] as usize;
    anyhow::ensure!(n >= 1 && hi > lo, "need N >= 1 and HI > LO");
    let c2 = oblique_physics::regimes::alpha_c2(g);
    let mut line = String::new();
    for i in 0..=n {
        let f = lo + (hi - lo) * i as f64 / n as f64;
        let zone = has_loading_zone_thornton(g, f * c2, e, 2048)?;
        line.push_str(&format!("{f:.4}:{} ", if zone { "Y" } else { "." }));
    }
    println!("{}", line.trim_end());
    Ok(())
}
