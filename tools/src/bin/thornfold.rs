//! Folds of Thornton's law: `thornfold [--reslip | --switch | --minus] GAMMAS E_NS [STEPS]`
//! (comma-separated lists) prints, for every pair, the loading fold `α_L(γ, e_n)` of the stick
//! patch (`oblique_solver::history::loading_fold_thornton`), with `--reslip` the re-slip fold
//! `α_R(γ, e_n)` of the partial-slip patch (`reslip_fold_thornton`), with `--switch` its switch
//! fold `α_S(γ, e_n)` (`switch_fold_thornton`), with `--minus` its fold F₋
//! (`fold_minus_thornton`), and its ratio to `α_c2`; `none` where there is
//! none. `thornfold --strip GAMMAS E_NS [STEPS]` prints the strip where a `+μF_N` episode of
//! the restitution exists (`restitution_plus_strip_thornton`), its edges and their ratios to
//! `α_c2`. `thornfold --minus-birth E_NS [STEPS]` brackets the γ where F₋ is first found at
//! each `e_n` (bisection in [1.7, 2.4] to 1e-3). `thornfold --end GAMMAS E_NS [STEPS]` prints the end-of-contact curves E₋
//! (`end_minus_edges_thornton`, α from 0.8 · 2/7 to 100 `α_c2`, 250 log intervals) and their
//! ratios to `α_c2`. `thornfold --sheet GAMMAS RATIOS [STEPS]` prints the switch sheet `e_S(γ, α)` of the
//! stick patch (`switch_sheet_thornton`, searched in `e_n` 0.3–0.99) at `α = RATIO α_c2`.
//! `thornfold --band GAMMAS RATIOS [STEPS]` prints the bands of `e_n` in 0.3–0.99 where the
//! sheet's `+` zone exists (`has_switch_zone_thornton`), their edges located on a scan of 0.01
//! (`switch_sheet_edges_thornton`; `0.3` or `0.99` where a band reaches the end of the scan).

use oblique_solver::history::{
    end_minus_edges_thornton, fold_minus_thornton, has_switch_zone_thornton, loading_fold_thornton,
    reslip_fold_thornton, restitution_plus_strip_thornton, switch_fold_thornton,
    switch_sheet_edges_thornton, switch_sheet_thornton,
};

fn list(s: &str) -> anyhow::Result<Vec<f64>> {
    Ok(s.split(',').map(str::parse).collect::<Result<_, _>>()?)
}

fn main() -> anyhow::Result<()> {
    let mut a: Vec<String> = std::env::args().skip(1).collect();
    if a.first().is_some_and(|s| s == "--sheet") {
        anyhow::ensure!(
            a.len() >= 3,
            "usage: thornfold --sheet GAMMAS RATIOS [STEPS]"
        );
        let (gammas, ratios) = (list(&a[1])?, list(&a[2])?);
        let steps = if a.len() > 3 { a[3].parse()? } else { 2048 };
        for &g in &gammas {
            for &r in &ratios {
                let alpha = r * 2.0 * g * g / 7.0;
                match switch_sheet_thornton(g, alpha, (0.3, 0.99), steps)? {
                    Some(e) => println!("{g} {r} {e:.6}"),
                    None => println!("{g} {r} none"),
                }
            }
        }
        return Ok(());
    }
    if a.first().is_some_and(|s| s == "--band") {
        anyhow::ensure!(
            a.len() >= 3,
            "usage: thornfold --band GAMMAS RATIOS [STEPS]"
        );
        let (gammas, ratios) = (list(&a[1])?, list(&a[2])?);
        let steps = if a.len() > 3 { a[3].parse()? } else { 2048 };
        for &g in &gammas {
            for &r in &ratios {
                let alpha = r * 2.0 * g * g / 7.0;
                let edges = switch_sheet_edges_thornton(g, alpha, (0.3, 0.99), 0.01, steps)?;
                // The bands: from a lower edge (or 0.3 where the zone holds there) to the next
                // upper edge (or 0.99).
                let mut bands = Vec::new();
                let mut from =
                    has_switch_zone_thornton(g, alpha, 0.3, steps)?.then(|| "0.3".to_string());
                for (e, above) in edges {
                    if above {
                        from = Some(format!("{e:.6}"));
                    } else if let Some(f) = from.take() {
                        bands.push(format!("{f}-{e:.6}"));
                    }
                }
                if let Some(f) = from {
                    bands.push(format!("{f}-0.99"));
                }
                let text = if bands.is_empty() {
                    "none".to_string()
                } else {
                    bands.join(" ")
                };
                println!("{g} {r} {text}");
            }
        }
        return Ok(());
    }
    if a.first().is_some_and(|s| s == "--minus-birth") {
        anyhow::ensure!(a.len() >= 2, "usage: thornfold --minus-birth E_NS [STEPS]");
        let e_ns = list(&a[1])?;
        let steps = if a.len() > 2 { a[2].parse()? } else { 2048 };
        for &e in &e_ns {
            // Bisection in γ on whether F₋ is found, in [1.7, 2.4] to 1e-3.
            let has = |g: f64| fold_minus_thornton(g, e, steps).map(|f| f.is_some());
            let (mut lo, mut hi) = (1.7, 2.4);
            if has(lo)? || !has(hi)? {
                println!("{e} no bracket in [{lo}, {hi}]");
                continue;
            }
            while hi - lo > 1e-3 {
                let mid = 0.5 * (lo + hi);
                if has(mid)? {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            println!("{e} {lo:.4} {hi:.4}");
        }
        return Ok(());
    }
    if a.first().is_some_and(|s| s == "--strip") {
        anyhow::ensure!(a.len() >= 3, "usage: thornfold --strip GAMMAS E_NS [STEPS]");
        let (gammas, e_ns) = (list(&a[1])?, list(&a[2])?);
        let steps = if a.len() > 3 { a[3].parse()? } else { 2048 };
        for &g in &gammas {
            for &e in &e_ns {
                let c2 = 2.0 * g * g / 7.0;
                match restitution_plus_strip_thornton(g, e, steps)? {
                    Some((lo, hi)) => {
                        println!("{g} {e} {lo:.9} {hi:.9} ({:.4}-{:.4})", lo / c2, hi / c2)
                    }
                    None => println!("{g} {e} none"),
                }
            }
        }
        return Ok(());
    }
    if a.first().is_some_and(|s| s == "--end") {
        anyhow::ensure!(a.len() >= 3, "usage: thornfold --end GAMMAS E_NS [STEPS]");
        let (gammas, e_ns) = (list(&a[1])?, list(&a[2])?);
        let steps = if a.len() > 3 { a[3].parse()? } else { 2048 };
        for &g in &gammas {
            for &e in &e_ns {
                let c2 = 2.0 * g * g / 7.0;
                let edges =
                    end_minus_edges_thornton(g, e, (0.8 * 2.0 / 7.0, 100.0 * c2), 250, steps)?;
                let text: Vec<String> = edges
                    .iter()
                    .map(|a| format!("{a:.6} ({:.4})", a / c2))
                    .collect();
                println!(
                    "{g} {e} {}",
                    if text.is_empty() {
                        "none".into()
                    } else {
                        text.join(" ")
                    }
                );
            }
        }
        return Ok(());
    }
    let reslip = a.first().is_some_and(|s| s == "--reslip");
    let switch = a.first().is_some_and(|s| s == "--switch");
    let minus = a.first().is_some_and(|s| s == "--minus");
    if reslip || switch || minus {
        a.remove(0);
    }
    anyhow::ensure!(
        a.len() >= 2,
        "usage: thornfold [--reslip | --switch | --minus] GAMMAS E_NS [STEPS]"
    );
    let (gammas, e_ns) = (list(&a[0])?, list(&a[1])?);
    let steps = if a.len() > 2 { a[2].parse()? } else { 2048 };
    for &g in &gammas {
        for &e in &e_ns {
            let c2 = 2.0 * g * g / 7.0;
            let fold = if reslip {
                reslip_fold_thornton(g, e, steps)?
            } else if switch {
                switch_fold_thornton(g, e, steps)?
            } else if minus {
                fold_minus_thornton(g, e, steps)?
            } else {
                loading_fold_thornton(g, e, steps)?
            };
            match fold {
                Some(al) => println!("{g} {e} {al:.9} {:.6}", al / c2),
                None => println!("{g} {e} none"),
            }
        }
    }
    Ok(())
}
