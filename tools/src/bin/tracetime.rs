//! Thread-pool wall time of each kink surface a Kelvin–Voigt table build traces for its probes:
//! `cargo run --release -p oblique-tools --bin tracetime -- [GAMMA_LO GAMMA_HI E_LO E_HI]`
//! (default the production config's γ 1–2.6, e_n 0.3–1). Prints each surface's time and the
//! number of points it holds; with `dump` after the range, every traced point too
//! (`E γ e_n α` and `I γ α e_n`).
use std::time::Instant;

use oblique_sweep::kink::{end_minus_surface, fold_minus_surface, interlude_sheet};
use oblique_table::surface::PatchKind;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .take(4)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    let dump = std::env::args().nth(5).is_some_and(|s| s == "dump");
    let (g, e) = if a.len() >= 4 {
        ((a[0], a[1]), (a[2], a[3]))
    } else {
        ((1.0, 2.6), (0.3, 1.0))
    };
    let t = Instant::now();
    let f = fold_minus_surface(g, e)?;
    println!(
        "F- surface   {:7.2} s, {:?} traced",
        t.elapsed().as_secs_f64(),
        f.map(|s| s.traced_nodes())
    );
    let t = Instant::now();
    let s = end_minus_surface(g, e, PatchKind::PartialSlip)?;
    println!(
        "E- surface   {:7.2} s, {:?} values",
        t.elapsed().as_secs_f64(),
        s.as_ref().map(|s| s.traced_nodes())
    );
    if let (true, Some(s)) = (dump, &s) {
        for (g, e, a) in s.nodes() {
            println!("E {g:.12e} {e:.12e} {a:.12e}");
        }
    }
    let t = Instant::now();
    let i = interlude_sheet(g, e)?;
    println!(
        "I+ sheet     {:7.2} s, {:?} points",
        t.elapsed().as_secs_f64(),
        i.as_ref().map(|s| s.traced_points())
    );
    if let (true, Some(i)) = (dump, &i) {
        for (g, a, e) in i.points() {
            println!("I {g:.12e} {a:.12e} {e:.12e}");
        }
    }
    Ok(())
}
