//! `P` of the Kelvin–Voigt law on fixed step counts (no refinement) and the ratios of
//! successive differences: `cargo run --release -p oblique-tools --bin kvlevels -- γ α e_n
//! [MAX_STEPS [LAW [MIN_STEPS]]]` prints, for `MIN_STEPS` (default 256) … `MAX_STEPS` steps (default 32 768), `P`, the difference to
//! the previous level and the ratio of successive differences (4 at order 2, 2.83 at order 1.5).
use oblique_solver::{Law, Request, Resolution};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let law = args.get(4).map(|s| Law::from_name(s)).transpose()?;
    let a: Vec<f64> = args
        .iter()
        .take(4)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (g, al, e) = match a[..] {
        [g, al, e, ..] => (g, al, e),
        _ => anyhow::bail!("usage: kvlevels GAMMA ALPHA E_N [MAX_STEPS [LAW [MIN_STEPS]]]"),
    };
    let max = a.get(3).map_or(32768, |&m| m as usize);
    let mut req = Request::new(g, al).e_n(e);
    if let Some(law) = law {
        req = req.law(law);
    }
    let mut steps = match args.get(5) {
        Some(s) => s.parse::<usize>()?,
        None => 256,
    };
    let (mut prev, mut prev_diff) = (f64::NAN, f64::NAN);
    println!("gamma {g} alpha {al} e_n {e}");
    while steps <= max {
        let p = req.simulate(Resolution { springs: 0, steps })?;
        let diff = p - prev;
        println!("{steps:>6} {p:.15} {diff:>10.3e} {:>6.2}", prev_diff / diff);
        (prev, prev_diff) = (p, diff);
        steps *= 2;
    }
    Ok(())
}
