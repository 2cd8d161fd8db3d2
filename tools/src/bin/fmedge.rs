//! Where the fold curve F₋ of the Kelvin–Voigt law exists (`docs/solver.md`, "Kink curves"):
//! `cargo run --release -p oblique-tools --bin fmedge -- [STEPS]` (default 2048; 21 s on 2
//! cores) prints `α_F(γ, e_n)` at γ = 2.3 … 3.5 (step 0.1) and ten `e_n` from 1 to 0.3, then,
//! per γ, the lowest `e_n` at which F₋ exists (bisection to ±5e-4 on whether its predicate
//! holds somewhere in α ∈ [0.25, 0.8]) and `α_F` approaching that end.
//!
//! Each `α_F` is continued down `e_n` from 1 % above the one at the next larger `e_n` (at
//! `e_n = 1` from the elastic curve's tabulated position), and where that finds nothing,
//! located from `restitution_minus_somewhere_e` over α ∈ [0.25, 0.8]. `—`: no F₋.
use oblique_solver::history::{fold_minus_at_e, restitution_minus_somewhere_e};
use oblique_solver::PhysicsError;
use rayon::prelude::*;

const GAMMAS: [f64; 13] = [
    2.3, 2.4, 2.5, 2.6, 2.7, 2.8, 2.9, 3.0, 3.1, 3.2, 3.3, 3.4, 3.5,
];
const RESTITUTIONS: [f64; 10] = [1.0, 0.99, 0.97, 0.95, 0.93, 0.9, 0.85, 0.8, 0.5, 0.3];
const ALPHAS: (f64, f64) = (0.25, 0.8);
/// `α_F` at `e_n = 1` (`docs/solver.md`), the first guesses (raised by 1 %).
const ELASTIC: [(f64, f64); 9] = [
    (2.4, 0.5211),
    (2.5, 0.4821),
    (2.6, 0.4516),
    (2.7, 0.4265),
    (2.8, 0.4052),
    (2.9, 0.3870),
    (3.0, 0.3711),
    (3.2, 0.3447),
    (3.5, 0.3144),
];

fn elastic_guess(gamma: f64) -> f64 {
    let i = ELASTIC
        .iter()
        .position(|&(g, _)| g >= gamma)
        .unwrap_or(ELASTIC.len() - 1)
        .max(1);
    let ((g0, a0), (g1, a1)) = (ELASTIC[i - 1], ELASTIC[i]);
    1.01 * (a0 + (a1 - a0) * (gamma - g0) / (g1 - g0))
}

/// `α_F` at (γ, e_n) by continuation from `guess`, else from wherever the predicate holds.
fn locate(gamma: f64, e_n: f64, guess: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    if let Some(a) = fold_minus_at_e(gamma, e_n, guess, steps)? {
        return Ok(Some(a));
    }
    match restitution_minus_somewhere_e(gamma, e_n, ALPHAS, steps)? {
        Some(a) => fold_minus_at_e(gamma, e_n, a, steps),
        None => Ok(None),
    }
}

fn exists(gamma: f64, e_n: f64, steps: usize) -> Result<bool, PhysicsError> {
    Ok(restitution_minus_somewhere_e(gamma, e_n, ALPHAS, steps)?.is_some())
}

struct Row {
    alphas: Vec<Option<f64>>,
    /// `(e_lo, e_hi)`: no F₋ at `e_lo`, F₋ at `e_hi`.
    edge: Option<(f64, f64)>,
    approach: Vec<(f64, Option<f64>)>,
}

fn row(gamma: f64, steps: usize) -> Result<Row, PhysicsError> {
    let mut alphas = Vec::new();
    let mut guess = elastic_guess(gamma);
    for e_n in RESTITUTIONS {
        let a = locate(gamma, e_n, guess, steps)?;
        if let Some(a) = a {
            guess = 1.01 * a;
        }
        alphas.push(a);
    }
    // The end in e_n: between the lowest e_n with F₋ and the next one below it.
    let Some(k) = alphas.iter().rposition(Option::is_some) else {
        return Ok(Row {
            alphas,
            edge: None,
            approach: Vec::new(),
        });
    };
    if k + 1 == RESTITUTIONS.len() {
        return Ok(Row {
            alphas,
            edge: Some((f64::NAN, RESTITUTIONS[k])),
            approach: Vec::new(),
        });
    }
    let (mut lo, mut hi) = (RESTITUTIONS[k + 1], RESTITUTIONS[k]);
    while hi - lo > 1e-3 {
        let mid = 0.5 * (lo + hi);
        if exists(gamma, mid, steps)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let mut approach = Vec::new();
    let mut guess = 1.01 * alphas[k].unwrap_or(0.5);
    for d in [0.03, 0.01, 0.003, 0.001] {
        let e_n = hi + d;
        if e_n > RESTITUTIONS[k] {
            continue;
        }
        let a = locate(gamma, e_n, guess, steps)?;
        if let Some(a) = a {
            guess = 1.01 * a;
        }
        approach.push((d, a));
    }
    Ok(Row {
        alphas,
        edge: Some((lo, hi)),
        approach,
    })
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let steps: usize = oblique_tools::arg_or(&args, 0, "STEPS", 2048)?;
    let start = std::time::Instant::now();
    let rows = GAMMAS
        .par_iter()
        .map(|&g| row(g, steps))
        .collect::<Result<Vec<_>, _>>()?;
    println!("F- of the Kelvin-Voigt law: alpha_F(gamma, e_n) at {steps} steps (—: none)\n");
    print!("| γ |");
    for e in RESTITUTIONS {
        print!(" e_n {e} |");
    }
    println!(" ends at e_n |");
    print!("|---|");
    for _ in RESTITUTIONS {
        print!("---|");
    }
    println!("---|");
    for (g, r) in GAMMAS.iter().zip(&rows) {
        print!("| {g} |");
        for a in &r.alphas {
            match a {
                Some(a) => print!(" {a:.5} |"),
                None => print!(" — |"),
            }
        }
        match r.edge {
            Some((lo, hi)) if lo.is_finite() => println!(" {:.4} ± 0.0005 |", 0.5 * (lo + hi)),
            Some(_) => println!(" below 0.3 |"),
            None => println!(" — |"),
        }
    }
    println!("\nalpha_F approaching the end (e_n = end + d, the end's upper bracket):");
    for (g, r) in GAMMAS.iter().zip(&rows) {
        if let Some((_, hi)) = r.edge {
            print!("gamma {g} (end {hi:.4}):");
            for (d, a) in &r.approach {
                match a {
                    Some(a) => print!("  d {d}: {a:.5}"),
                    None => print!("  d {d}: —"),
                }
            }
            println!();
        }
    }
    eprintln!("{:.1} s", start.elapsed().as_secs_f64());
    Ok(())
}
