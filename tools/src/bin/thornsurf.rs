//! The kink surfaces that `nodes.probe_kinks` traces for a table of Thornton's law:
//! `thornsurf GAMMA_LO GAMMA_HI E_LO E_HI` traces F₋ (`kink::thornton_fold_minus_surface`) and
//! the lowest E₋ (`kink::thornton_end_minus_surface`) and the edges of the `+` strip
//! (`kink::thornton_plus_strip_surfaces`) over that range and prints the time each took and how
//! many grid nodes hold the kink, then the upper and lower edges of the switch sheet `e_S` of
//! the stick patch (`kink::switch_sheet_surfaces`). With `--only-strip` (`--only-sheet`) only the strip (the
//! sheet); with `--print G,X ...` also the strip's edges interpolated at those `(γ, e_n)` pairs
//! (with `--only-sheet`: `e_S` at those `(γ, α/α_c2)`, and with `--nodes` its located nodes).
//! With `--only-band` only the upper edge of the loading band
//! (`kink::thornton_loading_band_surface`), and with `--print` it interpolated. With
//! `--end-sheet` the end-of-contact sheet `e_E` (`kink::end_minus_sheet_surface`: its stick
//! and partial-slip parts in place of the upper and lower edges) in place of `e_S`, alone or
//! with `--only-sheet`.

use oblique_table::surface::PatchKind;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let a: Vec<f64> = args
        .iter()
        .take(4)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    anyhow::ensure!(
        a.len() == 4,
        "usage: thornsurf GAMMA_LO GAMMA_HI E_LO E_HI [--only-strip|--only-sheet|--only-band] [--end-sheet] [--print G,X ...]"
    );
    let (gammas, e_range) = ((a[0], a[1]), (a[2], a[3]));
    let only_strip = args.iter().any(|s| s == "--only-strip");
    let only_sheet = args.iter().any(|s| s == "--only-sheet");
    let end_sheet = args.iter().any(|s| s == "--end-sheet");
    let points = args
        .iter()
        .skip_while(|s| *s != "--print")
        .skip(1)
        .map(|s| oblique_tools::point(s))
        .collect::<Result<Vec<_>, _>>()?;
    if args.iter().any(|s| s == "--only-band") {
        let t = std::time::Instant::now();
        let band = oblique_sweep::kink::thornton_loading_band_surface(gammas, e_range)?;
        let n = band.as_ref().map_or(0, |s| s.traced_nodes());
        println!("L-hi: {:.1} s, {n} nodes", t.elapsed().as_secs_f64());
        for &(g, e) in &points {
            println!(
                "{g} {e}: {:?}",
                band.as_ref().and_then(|s| s.alpha_at(g, e))
            );
        }
        return Ok(());
    }
    if only_sheet {
        let sheets = switch_sheet(gammas, e_range, end_sheet)?;
        let labels = if end_sheet {
            ["stick", "partial"]
        } else {
            ["upper", "lower"]
        };
        for (sheet, edge) in sheets.iter().zip(labels) {
            if args.iter().any(|s| s == "--nodes") {
                for (g, r, e) in sheet.iter().flat_map(|s| s.points()) {
                    println!("{edge} node {g:.2} {r:.4} {e:.6}");
                }
            }
            for &(g, r) in &points {
                let alpha = r * oblique_physics::regimes::alpha_c2(g);
                let e = sheet.as_ref().and_then(|s| s.e_at(g, alpha));
                println!("{edge} {g} {r}: {e:?}");
            }
        }
        return Ok(());
    }
    let t = std::time::Instant::now();
    let strip = oblique_sweep::kink::thornton_plus_strip_surfaces(gammas, e_range)?;
    for (edge, name) in strip.iter().zip(["F+lo", "F+hi"]) {
        let n = edge.as_ref().map_or(0, |s| s.traced_nodes());
        println!(
            "{name}: {:.1} s (both), {n} nodes",
            t.elapsed().as_secs_f64()
        );
    }
    for &(g, e) in &points {
        let at = |k: usize| strip[k].as_ref().and_then(|s| s.alpha_at(g, e));
        println!("{g} {e}: {:?} {:?}", at(0), at(1));
    }
    if only_strip {
        return Ok(());
    }
    let t = std::time::Instant::now();
    let f = oblique_sweep::kink::thornton_fold_minus_surface(gammas, e_range)?;
    let n = f.as_ref().map_or(0, |s| s.traced_nodes());
    println!("F-: {:.1} s, {n} nodes", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    let e = oblique_sweep::kink::thornton_end_minus_surface(gammas, e_range)?;
    let n = e.as_ref().map_or(0, |s| s.traced_nodes());
    println!("E-: {:.1} s, {n} nodes", t.elapsed().as_secs_f64());
    switch_sheet(gammas, e_range, end_sheet)?;
    Ok(())
}

/// The upper and lower edges of the switch sheet (the end-of-contact sheet with `end`) over
/// the range, with the time they took and their located nodes printed.
fn switch_sheet(
    gammas: (f64, f64),
    e_range: (f64, f64),
    end: bool,
) -> anyhow::Result<[Option<oblique_sweep::kink::SwitchSheet>; 2]> {
    let t = std::time::Instant::now();
    let sheets = if end {
        [PatchKind::Stick, PatchKind::PartialSlip]
            .map(|p| oblique_sweep::kink::end_minus_sheet_surface(p, gammas, e_range))
            .into_iter()
            .collect::<Result<Vec<_>, _>>()?
            .try_into()
            .map_err(|_| anyhow::anyhow!("two patches"))?
    } else {
        oblique_sweep::kink::switch_sheet_surfaces(gammas, e_range)?
    };
    let n = sheets
        .each_ref()
        .map(|s| s.as_ref().map_or(0, |s| s.traced_nodes()));
    println!(
        "{}: {:.1} s, {} nodes {}, {} {}",
        if end { "e_E" } else { "e_S" },
        t.elapsed().as_secs_f64(),
        n[0],
        if end {
            "in the stick patch"
        } else {
            "on its upper edges"
        },
        n[1],
        if end {
            "in the partial-slip patch"
        } else {
            "on its lower edges"
        },
    );
    Ok(sheets)
}
