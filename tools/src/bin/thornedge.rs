//! The edge `α₁(γ, e_n)` of the full-slip region of Thornton's law
//! (`oblique_solver::history::full_slip_edge_thornton`) against the Kelvin–Voigt `α_c1(γ, e_n)`:
//!
//! `thornedge GAMMAS E_NS [STEPS...]` with comma-separated lists, e.g.
//! `thornedge 1.2,1.754,2.3 0.5,0.8,0.95 1024 2048 4096`. One line per `(γ, e_n)`: `α_c1`, then
//! `α₁` at each number of steps and its distance above `α_c1` (relative). The points run in
//! parallel. `thornedge --history GAMMA ALPHA E_N STEPS` prints the gross-slip episodes of one
//! impact (`slip_history_thornton`) instead.

use oblique_physics::regimes::alpha_c1_dissipative;
use oblique_solver::history::{full_slip_edge_thornton, slip_history_thornton};
use rayon::prelude::*;

fn list(arg: Option<String>, name: &str) -> anyhow::Result<Vec<f64>> {
    let arg = arg.ok_or_else(|| anyhow::anyhow!("missing {name} (comma-separated)"))?;
    arg.split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .map_err(|e| anyhow::anyhow!("{name}: {s}: {e}"))
        })
        .collect()
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1).peekable();
    if args.peek().map(String::as_str) == Some("--history") {
        let v: Vec<f64> = args
            .skip(1)
            .map(|a| a.parse::<f64>())
            .collect::<Result<_, _>>()?;
        anyhow::ensure!(v.len() == 4, "--history GAMMA ALPHA E_N STEPS");
        let h = slip_history_thornton(v[0], v[1], v[2], v[3] as usize)?;
        println!("P {:.12}", h.p);
        for e in &h.episodes {
            println!("{:?} {:.9} .. {:.9}", e.sign, e.start, e.end);
        }
        return Ok(());
    }
    let gammas = list(args.next(), "GAMMAS")?;
    let e_ns = list(args.next(), "E_NS")?;
    let steps: Vec<usize> = args
        .map(|a| a.parse::<usize>())
        .collect::<Result<Vec<_>, _>>()?;
    let steps = if steps.is_empty() { vec![2048] } else { steps };
    let points: Vec<(f64, f64)> = gammas
        .iter()
        .flat_map(|&g| e_ns.iter().map(move |&e| (g, e)))
        .collect();
    let rows: Vec<anyhow::Result<String>> = points
        .par_iter()
        .map(|&(g, e)| {
            let c1 = alpha_c1_dissipative(g, e);
            let mut line = format!("gamma {g:.4} e_n {e:.4} alpha_c1(KV) {c1:.9}");
            for &s in &steps {
                match full_slip_edge_thornton(g, e, s) {
                    Ok(a1) => line += &format!("  {s}: {a1:.9} ({:+.3e})", a1 / c1 - 1.0),
                    Err(err) => line += &format!("  {s}: none ({err})"),
                }
            }
            Ok(line)
        })
        .collect();
    for r in rows {
        println!("{}", r?);
    }
    Ok(())
}
