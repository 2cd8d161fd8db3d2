//! The kink surfaces that `nodes.probe_kinks` traces for a table of Thornton's law:
//! `thornsurf GAMMA_LO GAMMA_HI E_LO E_HI` traces F₋ (`kink::thornton_fold_minus_surface`) and
//! the lowest E₋ (`kink::thornton_end_minus_surface`) over that range and prints the time each
//! took and how many grid nodes hold the kink.

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    anyhow::ensure!(a.len() == 4, "usage: thornsurf GAMMA_LO GAMMA_HI E_LO E_HI");
    let (gammas, e_range) = ((a[0], a[1]), (a[2], a[3]));
    let t = std::time::Instant::now();
    let f = oblique_sweep::kink::thornton_fold_minus_surface(gammas, e_range)?;
    let n = f.as_ref().map_or(0, |s| s.traced_nodes());
    println!("F-: {:.1} s, {n} nodes", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    let e = oblique_sweep::kink::thornton_end_minus_surface(gammas, e_range)?;
    let n = e.as_ref().map_or(0, |s| s.traced_nodes());
    println!("E-: {:.1} s, {n} nodes", t.elapsed().as_secs_f64());
    Ok(())
}
