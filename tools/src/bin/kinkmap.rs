//! Map the kink curves of P(γ, α) in the slip regions from the gross-slip history:
//! `cargo run --release -p oblique-tools --bin kinkmap -- GAMMA_FROM GAMMA_TO GAMMA_STEP [STEPS [HI [LO]]]`
//! (α scanned up to HI α_c2, default 1.5, from max(α_c1, LO α_c2); e.g. `-- 1.8 3.5 0.1 4096`, 40 s).
//!
//! For each γ, the α range [α_c1, 1.5 α_c2] is scanned on a 300-point log grid; at every α one
//! impact is run (continuum row, STEPS steps, default 4096) and its *signature* is recorded:
//! the signs of its gross-slip episodes (`oblique_solver::history`), each marked as touching
//! the start (`<`) or the separation (`>`) when it does. Where the signature changes between two
//! grid points, the change is located by bisection and printed with the one-sided slopes
//! `dP/d ln α` on both sides (over 1e-4) and the episodes on both sides. An episode vanishing
//! strictly inside the contact is a fold, where P has a slope jump (docs/solver.md).
use oblique_solver::history::{locate_change, slip_history, Episode, SlipHistory, SlipSign};

fn mark(e: &Episode) -> String {
    let s = if e.sign == SlipSign::Plus { '+' } else { '-' };
    let a = if e.start < 0.03 { "<" } else { "" };
    let b = if e.end > 0.97 { ">" } else { "" };
    format!("{a}{s}{b}")
}

fn signature(h: &SlipHistory) -> String {
    h.episodes.iter().map(mark).collect::<Vec<_>>().join(" ")
}

fn describe(h: &SlipHistory) -> String {
    let v: Vec<String> = h
        .episodes
        .iter()
        .map(|e| format!("{}{:.3}..{:.3}", mark(e), e.start, e.end))
        .collect();
    v.join(" ")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    if a.len() < 3 {
        return Err("usage: kinkmap GAMMA_FROM GAMMA_TO GAMMA_STEP [STEPS [HI [LO]]]".into());
    }
    let (g0, g1, dg) = (a[0], a[1], a[2]);
    let steps = a.get(3).map_or(4096, |&s| s as usize);
    let hi_factor = a.get(4).copied().unwrap_or(1.5);
    let lo_factor = a.get(5).copied().unwrap_or(0.0);
    let n = 300;
    let mut k = 0;
    loop {
        let g = g0 + k as f64 * dg;
        if g > g1 + 1e-9 {
            break;
        }
        k += 1;
        let c1 = oblique_physics::regimes::alpha_c1(g).max(1e-3);
        let c2 = oblique_physics::regimes::alpha_c2(g);
        let (lo, hi) = ((c1 * 1.0001).max(lo_factor * c2), c2 * hi_factor);
        let xs: Vec<f64> = (0..=n)
            .map(|i| (lo.ln() + (hi / lo).ln() * i as f64 / n as f64).exp())
            .collect();
        let sigs = xs
            .iter()
            .map(|&x| slip_history(g, x, steps).map(|h| signature(&h)))
            .collect::<Result<Vec<_>, _>>()?;
        for i in 0..n {
            if sigs[i] == sigs[i + 1] {
                continue;
            }
            let before = sigs[i].clone();
            let Some(ak) =
                locate_change(g, (xs[i], xs[i + 1]), steps, 40, |h| signature(h) != before)?
            else {
                continue;
            };
            let p = |x: f64| slip_history(g, x, steps).map(|h| h.p);
            let e = 1e-4_f64;
            let (l, r) = (ak * (-1e-9_f64).exp(), ak * (1e-9_f64).exp());
            let left = (p(l)? - p(l * (-e).exp())?) / e;
            let right = (p(r * e.exp())? - p(r)?) / e;
            println!(
                "g {g:.3} alpha_k {ak:.6} a/ac2 {:.4} dP/dlna {left:+.4} -> {right:+.4}  [{}] -> [{}]",
                ak / c2,
                describe(&slip_history(g, l, steps)?),
                describe(&slip_history(g, r, steps)?)
            );
        }
    }
    Ok(())
}
