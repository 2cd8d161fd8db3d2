//! `sweep inspect`: a table's domain, patches, node counts, error statistics, stated bound and
//! provenance.

use crate::failure::outln;
use std::path::PathBuf;

use crate::failure::Result;
use clap::Args;
use serde_json::json;

use oblique_lookup::{Table, EXTRA_AXES};
use oblique_table::surface::AxisMap;

#[derive(Args)]
pub struct InspectArgs {
    /// Table file written by `sweep run`.
    table: PathBuf,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

fn stats(v: impl Iterator<Item = f64>) -> (usize, f64, f64) {
    let (mut n, mut max, mut sq) = (0usize, 0.0_f64, 0.0);
    for x in v {
        n += 1;
        max = max.max(x);
        sq += x * x;
    }
    (n, max, if n > 0 { (sq / n as f64).sqrt() } else { 0.0 })
}

/// Run `sweep inspect`.
pub fn run(args: InspectArgs) -> Result<()> {
    let t = Table::open(&args.table)?;
    let s = t.surface();
    let patches: Vec<_> = s.patches().map(|(id, p)| (id.name(), p)).collect();
    let (nc, cmax, crms) = stats(t.checks().iter().map(|c| c.interpolation_error));
    let pv = t.provenance();
    if args.json {
        let ps: Vec<_> = patches
            .iter()
            .map(|(n, p)| {
                let depth = p.leaf_depths();
                let mut patch = json!({
                    "name": n, "kind": p.kind().name(), "gamma_lo": p.gamma_lo(), "gamma_hi": p.gamma_hi(),
                    "blocks_gamma": p.blocks_gamma(), "blocks_coord": p.blocks_coord(),
                    "leaf_intervals": p.leaf_intervals(),
                    "leaves": p.leaves(),
                    "depth_min": depth.iter().min(), "depth_max": depth.iter().max(),
                    "nodes": p.p().len(),
                    "nodes_note": "stored node values; leaves store their shared edges each",
                    "max_node_error_estimate": p.error_estimate().iter().copied().fold(0.0, f64::max),
                    "warp": p.warp().as_ref().map(|w| json!({
                        "start": w.start(),
                        "gamma_start": w.start_gamma(p.gamma_lo(), p.gamma_hi(), p.blocks_gamma()),
                        "c_star": w.c_star(), "gamma_0": w.gamma_0(), "gamma_step": w.gamma_step(),
                        "knots": w.knot().len(),
                    })),
                    "knots": p.knots().map(|k| {
                        let [n, ng, ne] = k.shape();
                        let r = k.region();
                        json!({
                            "count": n, "c_star": k.c_star(), "grade": k.grade_values(),
                            "region_roots": r, "gamma_0": k.gamma_0(), "gamma_step": k.gamma_step(),
                            "e_n_0": k.e_n_0(), "e_n_step": k.e_n_step(), "grid": [ng, ne],
                        })
                    }),
                });
                // Root cells along each extra axis (1 where the patch has none).
                for a in EXTRA_AXES {
                    let blocks = p.axes().iter().find(|x| x.name.name() == a.name);
                    patch[a.attr_blocks] = json!(blocks.map_or(1, |x| x.blocks()));
                }
                patch
            })
            .collect();
        let mut out = json!({
            "path": args.table.display().to_string(),
            "schema_version": pv.schema_version,
            "gamma_min": s.gamma_min(), "gamma_max": s.gamma_max(),
            "alpha_max": if s.alpha_max().is_finite() { json!(s.alpha_max()) } else { json!("inf") },
            "axes": s.axes().iter().map(|a| a.name.name()).collect::<Vec<_>>(),
            "law": if s.restitution().is_some() { pv.law.as_str() } else { "elastic" },
            "e_n_coordinate": s.restitution().map(|_| s.e_n_map().name()),
            "stencil_points": s.stencil(),
            "nodes": patches.iter().map(|(_, p)| p.p().len()).sum::<usize>(),
            "patches": ps,
            "checks": { "count": nc, "max_interpolation_error": cmax, "rms_interpolation_error": crms },
            "error_bound": if t.error_bound().is_nan() { json!(null) } else { json!(t.error_bound()) },
            "provenance": {
                "engine_version": pv.engine_version, "git_commit": pv.git_commit,
                "created": pv.created, "wall_time_s": pv.wall_time_s, "solver": pv.solver,
                "node_tol": pv.node_tol, "check_tol": pv.check_tol, "target_error": pv.target_error, "config": pv.config,
            }
        });
        // The range of each extra axis (null where the table has none).
        let axes = s.axes();
        for a in EXTRA_AXES {
            let range = axes.iter().find(|x| x.name.name() == a.name);
            out[a.attr_min] = json!(range.map(|x| x.lo()));
            out[a.attr_max] = json!(range.map(|x| x.hi()));
        }
        outln!("{out}")?;
        return Ok(());
    }
    outln!("table {}", args.table.display())?;
    // The extra axes and their ranges, then the law of the node values.
    let extra: Vec<String> = s
        .axes()
        .iter()
        .filter(|a| a.name.extra().is_some())
        .map(|a| {
            let map = match a.map {
                AxisMap::Linear => String::new(),
                m => format!(" over {}", m.name()),
            };
            format!(", {} in [{}, {}]{map}", a.name.name(), a.lo(), a.hi())
        })
        .collect();
    let e_n = match extra.is_empty() {
        false => format!("{} ({} law)", extra.concat(), pv.law),
        true => String::new(),
    };
    let gamma = match s.pair_gamma() {
        Some(g) => format!("gamma = {g} (one pair of materials)"),
        None => format!("gamma in [{}, {}]", s.gamma_min(), s.gamma_max()),
    };
    outln!(
        "domain {gamma}, alpha in [0, {}]{e_n}; stencil {} points per axis (schema v{})",
        s.alpha_max(),
        s.stencil(),
        pv.schema_version
    )?;
    for (n, p) in &patches {
        let depth = p.leaf_depths();
        let roots = p
            .axes()
            .iter()
            .map(|a| a.blocks().to_string())
            .collect::<Vec<_>>()
            .join(" x ");
        outln!(
            "  {n:13} {:12} gamma [{:.4}, {:.4}]  {roots} roots, {} leaves at depth {}..{}, {} nodes stored (shared leaf edges once per leaf), max node error estimate {:.1e}",
            p.kind().name(),
            p.gamma_lo(),
            p.gamma_hi(),
            p.leaves(),
            depth.iter().min().unwrap_or(&0),
            depth.iter().max().unwrap_or(&0),
            p.p().len(),
            p.error_estimate().iter().copied().fold(0.0, f64::max)
        )?;
        if let Some(w) = &p.warp() {
            outln!(
                "                fold edge: from gamma {} (root row {}) the fold F+ lies on c' = {} (graded below it; {} knots from gamma {}, step {})",
                w.start_gamma(p.gamma_lo(), p.gamma_hi(), p.blocks_gamma()),
                w.start(),
                w.c_star(),
                w.knot().len(),
                w.gamma_0(),
                w.gamma_step()
            )?;
        }
        if let (Some(k), Some(r)) = (p.knots(), p.restitution()) {
            let reg = k.region();
            let at = |lo: f64, hi: f64, blocks: usize, v: f64| lo + (hi - lo) * v / blocks as f64;
            // A root-cell position along e_n through the axis's map (over (1 - e_n)^(1/4) the
            // edges are not equally spaced in e_n).
            let at_e = |v: f64| match r.map {
                oblique_table::surface::AxisMap::Linear => at(r.lo(), r.hi(), r.blocks(), v),
                _ => r.at(v / r.blocks() as f64),
            };
            let stars: Vec<String> = k.c_star().iter().map(|c| c.to_string()).collect();
            outln!(
                "                knots: {} {} on c' = {} (grades {:?}: 0 linear, 1 graded below, 2 above) for gamma [{}, {}], e_n [{}, {}]; traced on a {} x {} grid",
                stars.len(),
                if stars.len() == 1 { "kink" } else { "kinks" },
                stars.join(", "),
                k.grade_values(),
                at(p.gamma_lo(), p.gamma_hi(), p.blocks_gamma(), reg[0]),
                at(p.gamma_lo(), p.gamma_hi(), p.blocks_gamma(), reg[1]),
                at_e(reg[2]),
                at_e(reg[3]),
                k.shape()[1],
                k.shape()[2]
            )?;
        }
    }
    outln!("held-out checks: {nc} points, max interpolation error {cmax:.2e}, rms {crms:.2e}")?;
    // Λ_k per axis of the patches' trees: 2 (γ, c or c, e_n), or 3 (γ, c, e_n).
    let dims = s.patches().map(|(_, p)| p.dims()).max().unwrap_or(2);
    let factor = oblique_table::bound::node_error_factor_of(s.stencil(), dims);
    outln!(
        "stated error bound: {:.2e} (largest leaf prediction + {factor:.2} x node error estimate; docs/table-format.md)",
        t.error_bound()
    )?;
    outln!(
        "built {} in {:.1} s by engine {} (commit {}); {}",
        pv.created,
        pv.wall_time_s,
        pv.engine_version,
        pv.git_commit,
        pv.solver
    )?;
    Ok(())
}
