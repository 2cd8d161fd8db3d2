//! The zones of the Kelvin–Voigt row over one impact (a scratch tool for the sheet I₊):
//! `zones_e GAMMA ALPHA E_N [STEPS]` prints the runs of steps in one state: `+`/`−` where part
//! of the contact is at that limit, `s` where part is stuck (`G`: none, gross slip), with
//! their times as fractions of `t_c`.
use oblique_solver::history::zone_runs_e;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let g: f64 = oblique_tools::arg(&args, 0, "GAMMA")?;
    let al: f64 = oblique_tools::arg(&args, 1, "ALPHA")?;
    let e: f64 = oblique_tools::arg(&args, 2, "E_N")?;
    let steps: usize = oblique_tools::arg_or(&args, 3, "STEPS", 2048)?;
    for (label, t0, t1) in zone_runs_e(g, al, e, steps)? {
        print!("{label}[{t0:.4}-{t1:.4}] ");
    }
    println!();
    Ok(())
}
