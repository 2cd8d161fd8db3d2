//! The sheet I₊ of the Kelvin–Voigt law (`oblique_solver::history::plus_interlude_edge_e`):
//! `interlude STEPS < points.csv` with lines `tag,gamma,alpha` prints `tag,gamma,alpha,e_I`
//! (`none` where the `+` interlude does not begin inside `e_n` 0.85–0.999). Points run in
//! parallel (rayon).
use oblique_solver::history::plus_interlude_edge_e;
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let steps: usize = oblique_tools::arg_or(&oblique_tools::args(), 0, "STEPS", 2048)?;
    let pts = oblique_tools::tagged_rows(2)?;
    let out: Vec<String> = pts
        .par_iter()
        .map(|(tag, x)| {
            let (g, a) = (x[0], x[1]);
            match plus_interlude_edge_e(g, a, (0.85, 0.999), steps) {
                Ok(Some(e)) => format!("{tag},{g},{a},{e:.7}"),
                Ok(None) => format!("{tag},{g},{a},none"),
                Err(err) => format!("{tag},{g},{a},ERR {err}"),
            }
        })
        .collect();
    for l in out {
        println!("{l}");
    }
    Ok(())
}
