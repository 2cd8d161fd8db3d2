//! Where Thornton's law has a zone at the `+μq` limit while the contact loads
//! (`oblique_solver::history::has_loading_zone_thornton`, 2048 steps): `thornband GAMMA E_N LO
//! HI N` prints, at `N + 1` values of `α/α_c2` from `LO` to `HI`, `Y` where the zone exists and
//! `.` where it does not. Both edges of that band are folds of `P`; the upper one is the loading
//! fold `α_L` (`loading_fold_thornton`) while it lies above `α_c2`.

use oblique_solver::history::has_loading_zone_thornton;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
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
