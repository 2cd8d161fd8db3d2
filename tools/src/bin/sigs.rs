//! Gross-slip signatures at given points (a scratch tool for studies of where the table's
//! refinement may trust its prediction): `sigs STEPS < points.csv`. Each input line is
//! `tag,gamma,alpha,...`; each output line `tag,gamma,alpha,signature`, the signature being the
//! episodes of `oblique_solver::history::slip_history` at `STEPS` steps, each written as its
//! sign with `<` when it starts at the start of the contact and `>` when it runs into the
//! separation (as `kinkmap` writes them). Points are run in parallel (rayon). A line
//! `tag,gamma,alpha,e_n` with `e_n < 1` runs the Kelvin–Voigt law there
//! (`oblique_solver::history::slip_history_e`); the output then ends with `,e_n`.
use oblique_solver::history::{slip_history, slip_history_e, Episode, SlipSign};
use rayon::prelude::*;

fn mark(e: &Episode) -> String {
    let s = if e.sign == SlipSign::Plus { '+' } else { '-' };
    let a = if e.start < 0.03 { "<" } else { "" };
    let b = if e.end > 0.97 { ">" } else { "" };
    if std::env::var_os("SIGS_TIMES").is_some() {
        format!("{a}{s}{b}[{:.4}-{:.4}]", e.start, e.end)
    } else {
        format!("{a}{s}{b}")
    }
}

fn main() -> anyhow::Result<()> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(1024), |s| s.parse())?;
    use std::io::BufRead;
    let mut pts: Vec<(String, f64, f64, Option<f64>)> = Vec::new();
    for line in std::io::stdin().lock().lines() {
        let line = line?;
        let f: Vec<&str> = line.trim().split(',').collect();
        let num = |i: usize| f.get(i).and_then(|s| s.parse::<f64>().ok());
        if let (Some(g), Some(a)) = (num(1), num(2)) {
            pts.push((f[0].to_string(), g, a, num(3)));
        }
    }
    let out: Vec<String> = pts
        .par_iter()
        .map(|(tag, g, a, e)| {
            let h = match e {
                Some(e) => slip_history_e(*g, *a, *e, steps),
                None => slip_history(*g, *a, steps),
            };
            let tail = e.map_or(String::new(), |e| format!(",{e}"));
            match h {
                Ok(h) => {
                    let s: Vec<String> = h.episodes.iter().map(mark).collect();
                    format!("{tag},{g:.17e},{a:.17e},{}{tail}", s.join(" "))
                }
                Err(err) => format!("{tag},{g},{a},ERR {err}{tail}"),
            }
        })
        .collect();
    for l in out {
        println!("{l}");
    }
    Ok(())
}
