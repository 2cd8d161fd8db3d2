//! `[N]`: the bits of `P` of the Kelvin–Voigt law at `N` points (default 300) of
//! `γ ∈ [0.05, 5]`, `α ∈ [0.05, 20] ∪ {∞}`, `e_n ∈ [0.3, 0.99]` (a Halton sequence), at 256 and
//! 1024 steps and at tol 1e-6 (with the error estimate and the finest steps), one line per
//! point, for comparing two builds of the solver bit for bit (`cmp` of their outputs): a change
//! meant to make a step cheaper without changing its arithmetic must leave every line as it was.
//!
//! `N elastic`: the same at `e_n = 1` (the elastic law, the continuum row): the same `γ` and
//! `α` per point. `N thornton`: the same points under Thornton's law.
use oblique_solver::{Accuracy, Law, Request, Resolution};

/// Element `i` of the van der Corput sequence in base `b`, in `[0, 1)`.
fn halton(mut i: usize, b: usize) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

fn main() -> anyhow::Result<()> {
    let n: usize = std::env::args().nth(1).map_or(Ok(300), |s| s.parse())?;
    let (elastic, law) = match std::env::args().nth(2).as_deref() {
        None => (false, None),
        Some("elastic") => (true, None),
        Some("thornton") => (false, Some(Law::from_name("thornton")?)),
        Some(other) => anyhow::bail!("usage: kvbits [N] [elastic|thornton], not {other:?}"),
    };
    for i in 1..=n {
        let gamma = 0.05 + 4.95 * halton(i, 2);
        // Every tenth point without slip; the others log-uniform in [0.05, 20].
        let alpha = if i % 10 == 0 {
            f64::INFINITY
        } else {
            0.05 * 400f64.powf(halton(i, 3))
        };
        let e_n = if elastic {
            1.0
        } else {
            0.3 + 0.69 * halton(i, 5)
        };
        let mut req = Request::new(gamma, alpha).e_n(e_n).forced(true);
        if let Some(law) = law {
            req = req.law(law);
        }
        let mut line = format!("{gamma:.17e} {alpha:.17e} {e_n:.17e}");
        for steps in [256, 1024] {
            let p = req.simulate(Resolution { springs: 0, steps })?;
            line += &format!(" {:016x}", p.to_bits());
        }
        let sol = req.accuracy(Accuracy::Tolerance(1e-6)).solve()?;
        line += &format!(
            " {:016x} {:016x} {}",
            sol.p.to_bits(),
            sol.error_estimate.to_bits(),
            sol.resolution.steps
        );
        println!("{line}");
    }
    Ok(())
}
