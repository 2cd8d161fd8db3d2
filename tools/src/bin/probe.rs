//! A table against direct simulation at given points (a scratch tool for studies of the stated
//! bound): `probe TABLE TOL < points.csv > out.csv`. Each input line is `tag,gamma,alpha,e_n`
//! (`e_n` 1 for an elastic table); each output line `tag,gamma,alpha,e_n,p_table,p_sim,est,err`
//! with `err = |p_table − p_sim|`. Points are simulated at `TOL` in parallel (rayon), by the
//! table's law.
use oblique_lookup::Table;
use oblique_solver::{Accuracy, Request};
use oblique_table::surface::{partial_coord, stick_coord, PatchKind, Region};
use rayon::prelude::*;

/// `patch:leaf` of an elastic table's point (`-` outside the patches).
fn leaf_of(table: &Table, g: f64, a: f64) -> String {
    let surface = table.surface();
    let region = Region::of(g, a);
    let Some(id) = region.patch_id() else {
        return "-".into();
    };
    let Some(patch) = surface.patch_by_id(id) else {
        return "-".into();
    };
    let c = match patch.kind() {
        PatchKind::PartialSlip => partial_coord(g, a),
        _ => stick_coord(g, a, surface.alpha_max()),
    };
    let (leaf, _, _) = patch.find_leaf(g, patch.warped(g, c));
    format!("{}:{leaf}", id.name())
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let table = Table::open(args.first().map_or("tables/full.h5", String::as_str))?;
    let tol: f64 = args.get(1).map_or(Ok(1e-9), |s| s.parse())?;
    let pts: Vec<(String, f64, f64, f64)> = oblique_tools::tagged_rows(3)?
        .into_iter()
        .map(|(tag, x)| (tag, x[0], x[1], x[2]))
        .collect();
    let has_e = table.restitution().is_some();
    // The law of the table's node values (an elastic table: elastic).
    let law = if has_e {
        oblique_solver::Law::from_name(&table.provenance().law)?
    } else {
        oblique_solver::Law::Elastic
    };
    let out: Vec<String> = pts
        .par_iter()
        .map(|(tag, g, a, e)| {
            let pt = if has_e {
                table.p_e(*g, *a, *e)
            } else {
                table.p(*g, *a)
            };
            let sol = Request::new(*g, *a)
                .e_n(*e)
                .law(law)
                .accuracy(Accuracy::Tolerance(tol))
                .solve();
            match (pt, sol) {
                (Ok(pt), Ok(s)) => format!(
                    "{tag},{g:.17e},{a:.17e},{e},{pt:.17e},{:.17e},{:.3e},{:.4e},{}",
                    s.p,
                    s.error_estimate,
                    (pt - s.p).abs(),
                    leaf_of(&table, *g, *a)
                ),
                (t, s) => format!("{tag},{g},{a},{e},ERR,{:?},{:?}", t.err(), s.err()),
            }
        })
        .collect();
    for l in out {
        println!("{l}");
    }
    Ok(())
}
