//! How far each automatic refinement runs beyond the level it needed (a scratch tool for the
//! solver's cost): `levelneed TOL [LAW] < points.csv` with lines `tag,gamma,alpha,e_n` (`LAW`:
//! a law other than the one `e_n` implies, `thornton`). For each
//! point: the steps at which `solve` at `TOL` stopped, its estimate, and, against a reference
//! (the Richardson value of fixed runs at 4 and 8 times those steps), the first level whose raw
//! value and whose Richardson value (with the level before) err by at most `TOL`; then the
//! work of the refinement (the sum of its levels' steps) over the work of stopping at that
//! Richardson level (itself and the level before). Points run in parallel (rayon).
use oblique_solver::{Accuracy, Law, Request, Resolution};
use rayon::prelude::*;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let tol: f64 = oblique_tools::arg_or(&args, 0, "TOL", 1e-6)?;
    let law = args.get(1).map(|s| Law::from_name(s)).transpose()?;
    let pts = oblique_tools::tagged_rows(3)?;
    let rows: Vec<String> = pts
        .par_iter()
        .map(|(tag, x)| -> anyhow::Result<String> {
            let (g, a, e) = (x[0], x[1], x[2]);
            let req = Request::new(g, a).e_n(e);
            let req = law.map_or(req, |l| req.law(l));
            let sol = req.accuracy(Accuracy::Tolerance(tol)).forced(true).solve()?;
            let fin = sol.resolution.steps;
            let run = |steps: usize| req.simulate(Resolution { springs: 0, steps });
            let (p4, p8) = (run(4 * fin)?, run(8 * fin)?);
            let reference = p8 + (p8 - p4) / 3.0;
            let mut steps = 16;
            let mut prev = f64::NAN;
            let (mut raw_need, mut rich_need) = (0usize, 0usize);
            let mut work = 0usize;
            let mut ladder: Vec<String> = Vec::new();
            let start = 256usize.min(fin);
            while steps <= 2 * fin {
                let p = run(steps)?;
                ladder.push(format!("{p:.17e}"));
                if steps >= start && steps <= fin {
                    work += steps;
                }
                if raw_need == 0 && (p - reference).abs() <= tol {
                    raw_need = steps;
                }
                let r = p + (p - prev) / 3.0;
                if rich_need == 0 && (r - reference).abs() <= tol {
                    rich_need = steps;
                }
                prev = p;
                steps *= 2;
            }
            let ideal = (rich_need + rich_need / 2).max(1);
            Ok(format!(
                "{tag},{g:.6},{a:.6},{e:.6},{fin},{:.2e},{:.2e},{raw_need},{rich_need},{:.2},{reference:.17e},{}",
                sol.error_estimate,
                (sol.p - reference).abs(),
                work as f64 / ideal as f64,
                ladder.join(";")
            ))
        })
        .collect::<anyhow::Result<_>>()?;
    println!("tag,gamma,alpha,e_n,steps,estimate,error,raw_need,rich_need,work_ratio,reference,ladder_from_16");
    for r in rows {
        println!("{r}");
    }
    Ok(())
}
