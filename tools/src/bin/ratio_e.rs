//! The friction ratio `F_t/(μF_N)` of one Kelvin–Voigt impact over time (a scratch tool for
//! kinks of `P` without a gross-slip episode): `ratio_e GAMMA ALPHA E_N [STEPS [FROM]]` prints
//! `t/t_c ratio` for every step from `FROM` t_c on (default 0.5), then the local extrema.
use oblique_solver::history::friction_ratio_e;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let g: f64 = oblique_tools::arg(&args, 0, "GAMMA")?;
    let al: f64 = oblique_tools::arg(&args, 1, "ALPHA")?;
    let e: f64 = oblique_tools::arg(&args, 2, "E_N")?;
    let steps: usize = oblique_tools::arg_or(&args, 3, "STEPS", 4096)?;
    let from: f64 = oblique_tools::arg_or(&args, 4, "FROM", 0.5)?;
    let (r, p) = friction_ratio_e(g, al, e, steps)?;
    println!("# P {p:.15}");
    let quiet = std::env::var_os("RATIO_QUIET").is_some();
    for w in r.windows(3) {
        let (t, q) = w[1];
        if t < from {
            continue;
        }
        let ext = (q - w[0].1) * (w[2].1 - q) < 0.0;
        if !quiet || ext {
            println!("{t:.6} {q:.9}{}", if ext { " extremum" } else { "" });
        }
    }
    Ok(())
}
