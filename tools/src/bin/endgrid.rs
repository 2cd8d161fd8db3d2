//! Where E₋ of the Kelvin–Voigt law holds on a log grid of α: `endgrid GAMMA E_N [N]` prints
//! the α intervals of the grid (0.1–100, N points, default 200) on which the last episode of
//! the impact is a `−μF_N` episode that leaves the separation (`has_end_minus`).
use oblique_solver::history::{has_end_minus, slip_history_e};

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    anyhow::ensure!(a.len() >= 2, "usage: endgrid GAMMA E_N [N]");
    let n = a.get(2).map_or(200, |&x| x as usize);
    let (g, e) = (a[0], a[1]);
    let mut prev: Option<(f64, bool)> = None;
    for i in 0..=n {
        let alpha = 0.1 * 1000f64.powf(i as f64 / n as f64);
        let h = has_end_minus(&slip_history_e(g, alpha, e, 1024)?);
        match prev {
            Some((_, p)) if p == h => {}
            _ => println!("{g} {e} from {alpha:.5}: {h}"),
        }
        prev = Some((alpha, h));
    }
    Ok(())
}
