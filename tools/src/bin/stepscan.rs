//! How `P` converges step by step at a fixed resolution, and how much of its error depends on
//! where events fall inside the steps: `cargo run --release -p oblique-tools --bin stepscan --
//! GAMMA ALPHA E_N [N0 [COUNT [LAW [STRIDE]]]]` solves the continuum row at the step counts
//! `N0, N0 + STRIDE, …` (`COUNT` of them; defaults 1000, 101 and 1; `LAW` names a law other than
//! the one `E_N` implies, e.g. `thornton`, whose grids are nested at multiples of 16: use
//! `STRIDE` 16 there), fits `P∞ + C/N²` by least squares and prints the
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
    let law = args
        .get(5)
        .map(|s| oblique_solver::Law::from_name(s))
        .transpose()?;
    let stride: usize = oblique_tools::arg_or(&args, 6, "STRIDE", 1)?;
    anyhow::ensure!(
        count >= 3 && n0 >= 16 && stride >= 1,
        "N0 >= 16, COUNT >= 3 and STRIDE >= 1"
    );
    let mut req = Request::new(g, al).e_n(e);
    if let Some(law) = law {
        req = req.law(law);
    }
    let ns: Vec<usize> = (0..count).map(|k| n0 + k * stride).collect();
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
        ns[count - 1],
        rms * n2,
        max * n2
    );
    Ok(())
}
