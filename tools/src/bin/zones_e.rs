//! The zones of the Kelvin–Voigt row over one impact (a scratch tool for the sheet I₊):
//! `zones_e GAMMA ALPHA E_N [STEPS]` prints the runs of steps in one state: `+`/`−` where part
//! of the contact is at that limit, `s` where part is stuck (`G`: none, gross slip), with
//! their times as fractions of `t_c`.
use oblique_solver::history::zone_runs_e;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (g, al, e) = match a[..] {
        [g, al, e, ..] => (g, al, e),
        _ => anyhow::bail!("usage: zones_e GAMMA ALPHA E_N [STEPS]"),
    };
    let steps = a.get(3).map_or(2048, |&s| s as usize);
    for (label, t0, t1) in zone_runs_e(g, al, e, steps)? {
        print!("{label}[{t0:.4}-{t1:.4}] ");
    }
    println!();
    Ok(())
}
