//! A table against direct simulation at given points (a scratch tool for studies of the stated
//! bound): `probe TABLE TOL < points.csv > out.csv`. Each input line is `tag,gamma,alpha,e_n`
//! (`e_n` 1 for an elastic table); each output line `tag,gamma,alpha,e_n,p_table,p_sim,est,err`
//! with `err = |p_table − p_sim|`. Points are simulated at `TOL` in parallel (rayon), by the
//! table's law.
use oblique_lookup::Table;
use oblique_solver::{Accuracy, Request};
use oblique_table::surface::{partial_coord_map, stick_coord, PatchKind, Region};
use rayon::prelude::*;

/// `patch:leaf` of a point (`-` outside the patches): by the region and the coordinate at
/// `e_n` (knotted or warped as the table's rule does), the leaf of the patch's tree.
fn leaf_of(table: &Table, g: f64, a: f64, e: f64) -> String {
    let surface = table.surface();
    let has_e = table.restitution().is_some();
    let region = if has_e {
        Region::of_e(g, a, e)
    } else {
        Region::of(g, a)
    };
    let Some(id) = region.patch_id() else {
        return "-".into();
    };
    let Some(patch) = surface.patch_by_id(id) else {
        return "-".into();
    };
    let c = match patch.kind() {
        PatchKind::PartialSlip => partial_coord_map(surface.partial_map(), g, a, e),
        _ => stick_coord(g, a, surface.alpha_max()),
    };
    let leaf = match patch.restitution() {
        None => patch.find_leaf(g, patch.warped(g, c)).0,
        Some(r) if patch.is_pair() => patch.find_leaf_at([c, r.x(e)]).0,
        Some(r) => {
            let c = patch.knotted(g, c, e);
            patch.find_leaf_at([patch.x_gamma(g), c, r.x(e)]).0
        }
    };
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
                    leaf_of(&table, *g, *a, *e)
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
