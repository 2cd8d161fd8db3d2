//! How `P` converges step by step at a fixed resolution, and how much of its error depends on
//! where events fall inside the steps: `cargo run --release -p oblique-tools --bin stepscan --
//! GAMMA ALPHA E_N [N0 [COUNT]]` solves the continuum row at every step count `N0 …
//! N0 + COUNT − 1` (defaults 1000 and 101), fits `P∞ + C/N²` by least squares and prints the
//! fit and the scatter of `P` around it scaled by `N0²`: rms and largest. A second-order error
//! that follows the step smoothly shows as `C` with a scatter near 0; an event whose position
//! inside a step moves the error (a kink of the friction force that no step is split at) shows
//! as a scatter of the size of `C` (`docs/solver.md`, "The onset of gross slip").
use oblique_solver::{Request, Resolution};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let g: f64 = oblique_tools::arg(&args, 0, "GAMMA")?;
    let al: f64 = oblique_tools::arg(&args, 1, "ALPHA")?;
    let e: f64 = oblique_tools::arg(&args, 2, "E_N")?;
    let n0: usize = oblique_tools::arg_or(&args, 3, "N0", 1000)?;
    let count: usize = oblique_tools::arg_or(&args, 4, "COUNT", 101)?;
    anyhow::ensure!(count >= 3 && n0 >= 16, "N0 >= 16 and COUNT >= 3");
    let req = Request::new(g, al).e_n(e);
    let ns: Vec<usize> = (n0..n0 + count).collect();
    let ps = ns
        .par_iter()
        .map(|&steps| req.simulate(Resolution { springs: 0, steps }))
        .collect::<Result<Vec<f64>, _>>()?;
    // Least squares of P = a + b x with x = 1/N².
    let xs: Vec<f64> = ns.iter().map(|&n| 1.0 / (n as f64 * n as f64)).collect();
    let m = count as f64;
    let (sx, sy) = (xs.iter().sum::<f64>(), ps.iter().sum::<f64>());
    let sxx: f64 = xs.iter().map(|x| x * x).sum();
    let sxy: f64 = xs.iter().zip(&ps).map(|(x, p)| x * p).sum();
    let b = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    let a = (sy - b * sx) / m;
    let res: Vec<f64> = xs.iter().zip(&ps).map(|(x, p)| p - a - b * x).collect();
    let rms = (res.iter().map(|r| r * r).sum::<f64>() / m).sqrt();
    let max = res.iter().fold(0.0_f64, |acc, r| acc.max(r.abs()));
    let n2 = (n0 as f64).powi(2);
    println!(
        "gamma {g} alpha {al} e_n {e}, N {n0}..{}: P_inf {a:.10}  C {b:.3e}  scatter rms*N^2 {:.3}  max*N^2 {:.3}",
        n0 + count - 1,
        rms * n2,
        max * n2
    );
    Ok(())
}
