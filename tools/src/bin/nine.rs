//! Quick timing of the nine benchmark solves (`benches/impact.rs`) at one tolerance:
//! `cargo run --release -p oblique-tools --bin nine -- [TOL] [E_N] [REPEATS] [LAW]` prints, per
//! `(γ, α)`, the median thread CPU time of a whole refinement (normal motion cached), the final
//! steps and P, and the geometric mean; `LAW` names a law other than the one `E_N` implies
//! (`thornton`). The criterion benchmark is the published measure; this is for quick
//! before/after checks while changing the solver.
use oblique_solver::{Accuracy, Law, Request};

/// Thread CPU time (s).
fn cpu() -> f64 {
    oblique_clock::thread_cpu_time().map_or(f64::NAN, |d| d.as_secs_f64())
}

fn main() -> anyhow::Result<()> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let tol: f64 = a.first().map_or(Ok(1e-6), |s| s.parse())?;
    let e_n: f64 = a.get(1).map_or(Ok(1.0), |s| s.parse())?;
    let reps: usize = a.get(2).map_or(Ok(21), |s| s.parse())?;
    let law = a.get(3).map(|s| Law::from_name(s)).transpose()?;
    let mut log_sum = 0.0;
    for g in [0.5, 1.754, 3.0] {
        for al in [0.3, 1.0, f64::INFINITY] {
            let mut req = Request::new(g, al)
                .e_n(e_n)
                .accuracy(Accuracy::Tolerance(tol))
                .forced(true);
            if let Some(law) = law {
                req = req.law(law);
            }
            let s = req.solve()?;
            let mut t: Vec<f64> = (0..reps)
                .map(|_| {
                    let t0 = cpu();
                    let r = req.solve();
                    let dt = cpu() - t0;
                    std::hint::black_box(r).map(|_| dt)
                })
                .collect::<Result<_, _>>()?;
            t.sort_by(f64::total_cmp);
            let med = t[reps / 2];
            log_sum += med.ln();
            println!(
                "{g:6} {al:4} {:9.1} us  steps {:6}  P {:.10} est {:.1e}",
                med * 1e6,
                s.resolution.steps,
                s.p,
                s.error_estimate
            );
        }
    }
    println!("geometric mean {:.1} us", (log_sum / 9.0).exp() * 1e6);
    Ok(())
}
