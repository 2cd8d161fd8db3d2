//! The fold curve F₋ of `P(γ, α, e_n)` for the Kelvin–Voigt law: `α_F(γ, e_n)` on a grid and,
//! for every `e_n`, the smallest γ at which F₋ exists, at a fixed number of steps.
//!
//! ```sh
//! cargo run --release -p oblique-solver --example fold_minus_e            # 2048 steps
//! cargo run --release -p oblique-solver --example fold_minus_e -- 4096    # another resolution
//! ```
//!
//! Each `α_F` is continued along `e_n` from the one at the next larger `e_n` (at `e_n = 1` from
//! the elastic curve, continued along γ from 0.5002 at γ = 2.45) by
//! [`fold_minus_at_e`]; where that finds nothing, α ∈ [0.3, 0.8] is scanned for the predicate
//! ([`fold_minus_scan_e`], 200 intervals, then [`restitution_minus_somewhere_e`]). `—`: no F₋.
//! Then, at γ = 2.15, 2.2, 2.3, where the restitution `−μF_N` episode disappears and when it
//! ends just before ([`restitution_minus_edges_e`]): a fold hidden beyond the predicate's
//! 0.97 t_c would show there.
//! The birth is [`fold_minus_birth_e`] over γ ∈ [1.8, 3.6], α ∈ [0.25, 0.8], to ±0.005.

use oblique_solver::history::{
    fold_minus_at_e, fold_minus_birth_e, fold_minus_scan_e, restitution_minus_edges_e,
    restitution_minus_somewhere_e, slip_history_e, SlipSign, RESTITUTION_WINDOW,
};
use oblique_solver::PhysicsError;

const GAMMAS: [f64; 9] = [2.15, 2.2, 2.25, 2.3, 2.35, 2.4, 2.45, 2.5, 2.6];
const RESTITUTIONS: [f64; 10] = [1.0, 0.999, 0.99, 0.97, 0.95, 0.9, 0.8, 0.7, 0.5, 0.3];
const ALPHAS: (f64, f64) = (0.3, 0.8);
/// The α range of the search for the birth (F₋ lies at lower α as γ grows: 0.314 at 3.5).
const BIRTH_ALPHAS: (f64, f64) = (0.25, 0.8);
const BIRTH_GAMMAS: (f64, f64) = (1.8, 3.6);

/// `α_F` at (γ, e_n) from `guess`, by continuation, else by a scan (the edge nearest `guess`).
fn locate(gamma: f64, e_n: f64, guess: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    if let Some(a) = fold_minus_at_e(gamma, e_n, guess, steps)? {
        return Ok(Some(a));
    }
    let edges = fold_minus_scan_e(gamma, e_n, ALPHAS, 200, steps)?;
    let nearest = edges
        .iter()
        .copied()
        .min_by(|a, b| (a - guess).abs().total_cmp(&(b - guess).abs()));
    if nearest.is_some() {
        return Ok(nearest);
    }
    match restitution_minus_somewhere_e(gamma, e_n, ALPHAS, steps)? {
        Some(a) => fold_minus_at_e(gamma, e_n, a, steps),
        None => Ok(None),
    }
}

fn main() -> Result<(), PhysicsError> {
    let steps = match std::env::args().nth(1) {
        Some(s) => s.parse().unwrap_or(2048),
        None => 2048,
    };
    println!("F- of the Kelvin-Voigt law, alpha_F(gamma, e_n) at {steps} steps");
    println!("(the restitution -muF_N episode just below alpha_F: start-end in t_c)\n");
    // The elastic curve, continued along γ from γ = 2.45 both ways.
    let mut elastic = [f64::NAN; GAMMAS.len()];
    let start = GAMMAS.iter().position(|&g| g == 2.45).unwrap_or(0);
    let mut guess = 0.5002;
    for i in (start..GAMMAS.len()).chain((0..start).rev()) {
        if i + 1 == start {
            guess = elastic[start];
        }
        if let Some(a) = locate(GAMMAS[i], 1.0, guess, steps)? {
            elastic[i] = a;
            guess = a;
        }
    }
    print!("| e_n |");
    for g in GAMMAS {
        print!(" γ {g} |");
    }
    println!();
    let mut table = vec![[f64::NAN; GAMMAS.len()]; RESTITUTIONS.len()];
    for (k, &e_n) in RESTITUTIONS.iter().enumerate() {
        print!("| {e_n} |");
        for (i, &g) in GAMMAS.iter().enumerate() {
            let guess = if k == 0 {
                elastic[i]
            } else {
                // The last α_F found at this γ for a larger e_n, else the elastic curve's or
                // the middle of the scan.
                (0..k)
                    .rev()
                    .map(|j| table[j][i])
                    .find(|a| a.is_finite())
                    .unwrap_or(if elastic[i].is_finite() {
                        elastic[i]
                    } else {
                        0.5
                    })
            };
            let found = if k == 0 {
                elastic[i].is_finite().then_some(elastic[i])
            } else {
                locate(g, e_n, guess, steps)?
            };
            match found {
                Some(a) => {
                    table[k][i] = a;
                    let below = slip_history_e(g, a * (1.0 - 1e-9), e_n, steps)?;
                    let ep = below.episodes.iter().find(|e| {
                        e.sign == SlipSign::Minus
                            && e.start >= RESTITUTION_WINDOW.0
                            && e.start <= RESTITUTION_WINDOW.1
                    });
                    match ep {
                        Some(e) => print!(" {a:.6} ({:.3}-{:.3}) |", e.start, e.end),
                        None => print!(" {a:.6} (?) |"),
                    }
                }
                None => print!(" — |"),
            }
        }
        println!();
    }
    println!(
        "\nwhere the restitution -muF_N episode disappears as alpha grows (alpha in {ALPHAS:?}), \
         and where it ends just below: inside the contact (< 0.97 t_c) a fold, at the \
         separation (~1) none"
    );
    for g in [2.15, 2.2, 2.3] {
        for e_n in RESTITUTIONS {
            print!("gamma {g}, e_n {e_n}:");
            for (a, ep) in restitution_minus_edges_e(g, e_n, ALPHAS, 100, steps)? {
                match ep {
                    Some(e) => print!("  alpha {a:.6} (episode {:.4}-{:.4})", e.start, e.end),
                    None => print!("  alpha {a:.6} (?)"),
                }
            }
            println!();
        }
    }
    println!(
        "\nsmallest gamma with F- (predicate somewhere in alpha in {BIRTH_ALPHAS:?}; bracket \
         {BIRTH_GAMMAS:?}, +-0.005):"
    );
    for e_n in RESTITUTIONS {
        match fold_minus_birth_e(e_n, BIRTH_GAMMAS, BIRTH_ALPHAS, 0.005, steps)? {
            Some((g, a)) => {
                println!(
                    "e_n {e_n}: gamma_b in ({:.4}, {g:.4}], alpha {a:.4}",
                    g - 0.01
                )
            }
            None => println!("e_n {e_n}: not bracketed by {BIRTH_GAMMAS:?}"),
        }
    }
    Ok(())
}
