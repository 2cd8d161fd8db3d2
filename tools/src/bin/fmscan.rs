//! Points next to the fold curve F₋ for a dense scan of a table (`docs/accuracy.md`, "Next to
//! the fold curve F₋"): `fmscan G0 G1 DG D0 D1 N` prints `tag,gamma,alpha,1` for γ from G0 to G1
//! in steps of DG and `α = α_F(γ)(1 + d)`, d at N even steps from D0 to D1, with F₋ traced as
//! `sweep run` traces it for `nodes.probe_kinks`. Pipe into `probe TABLE TOL`.
use oblique_sweep::kink::fold_minus_curve;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let [g0, g1, dg, d0, d1, n] = a[..] else {
        anyhow::bail!("usage: fmscan G0 G1 DG D0 D1 N");
    };
    let n = n as usize;
    let curve = fold_minus_curve(g0, g1)?.ok_or_else(|| anyhow::anyhow!("no F- in range"))?;
    let rows = ((g1 - g0) / dg).round() as usize;
    let mut tag = 0;
    for i in 0..=rows {
        let g = g0 + dg * i as f64;
        let Some(alpha) = curve.alpha_at(g) else {
            continue;
        };
        for j in 0..n {
            let d = d0 + (d1 - d0) * j as f64 / (n - 1).max(1) as f64;
            println!("f{tag},{g},{},1", alpha * (1.0 + d));
            tag += 1;
        }
    }
    Ok(())
}
