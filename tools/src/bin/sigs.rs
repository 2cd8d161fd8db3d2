//! Gross-slip signatures at given points (a scratch tool for studies of where the table's
//! refinement may trust its prediction): `sigs STEPS < points.csv`. Each input line is
//! `tag,gamma,alpha,...`; each output line `tag,gamma,alpha,signature`, the signature being the
//! episodes of `oblique_solver::history::slip_history` at `STEPS` steps, each written as its
//! sign with `<` when it starts at the start of the contact and `>` when it runs into the
//! separation (as `kinkmap` writes them). Points are run in parallel (rayon).
use oblique_solver::history::{slip_history, Episode, SlipSign};
use rayon::prelude::*;

fn mark(e: &Episode) -> String {
    let s = if e.sign == SlipSign::Plus { '+' } else { '-' };
    let a = if e.start < 0.03 { "<" } else { "" };
    let b = if e.end > 0.97 { ">" } else { "" };
    format!("{a}{s}{b}")
}

fn main() -> anyhow::Result<()> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(1024), |s| s.parse())?;
    let pts: Vec<(String, f64, f64)> = oblique_tools::tagged_rows(2)?
        .into_iter()
        .map(|(tag, x)| (tag, x[0], x[1]))
        .collect();
    let out: Vec<String> = pts
        .par_iter()
        .map(|(tag, g, a)| match slip_history(*g, *a, steps) {
            Ok(h) => {
                let s: Vec<String> = h.episodes.iter().map(mark).collect();
                format!("{tag},{g:.17e},{a:.17e},{}", s.join(" "))
            }
            Err(e) => format!("{tag},{g},{a},ERR {e}"),
        })
        .collect();
    for l in out {
        println!("{l}");
    }
    Ok(())
}
