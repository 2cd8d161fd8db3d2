//! `γ α N [e_n [LAW]]`: N solves at tol 1e-6 (simulated even on the full-slip line), for instruction
//! counts (`valgrind --tool=callgrind target/release/solveloop 3 1 20`), which compare two
//! builds of the solver without the noise of timings.
use oblique_solver::{Accuracy, Law, Request};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let law = args.get(4).map(|s| Law::from_name(s)).transpose()?;
    let a: Vec<f64> = args
        .iter()
        .take(4)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (gamma, alpha, n) = match a[..] {
        [g, al, n, ..] => (g, al, n as usize),
        _ => anyhow::bail!("usage: solveloop GAMMA ALPHA N [E_N [LAW]]"),
    };
    let e_n = a.get(3).copied().unwrap_or(1.0);
    let mut s = 0.0;
    for _ in 0..n {
        let mut r = Request::new(gamma, alpha).e_n(e_n);
        if let Some(law) = law {
            r = r.law(law);
        }
        s += r
            .accuracy(Accuracy::Tolerance(1e-6))
            .forced(true)
            .solve()?
            .p;
    }
    println!("{s}");
    Ok(())
}
