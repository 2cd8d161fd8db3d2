//! Points next to the end-of-contact curve E₋ as `probe` input:
//! `nearend KIND GAMMA_LO GAMMA_HI N SEED R_LO_EXP R_HI_EXP > points.csv` with KIND `stick` or
//! `partial`: γ uniform over the traced range, α = α_E(γ)(1 + s·10^u), u uniform in
//! [R_LO_EXP, R_HI_EXP] (e.g. -4 -1), s = ±1.
use oblique_sweep::kink::end_minus_curve;
use oblique_table::surface::PatchKind;

fn main() -> anyhow::Result<()> {
    let a: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(
        a.len() == 7,
        "usage: nearend KIND GAMMA_LO GAMMA_HI N SEED R_LO_EXP R_HI_EXP"
    );
    let kind = if a[0] == "stick" {
        PatchKind::Stick
    } else {
        PatchKind::PartialSlip
    };
    let (g0, g1): (f64, f64) = (a[1].parse()?, a[2].parse()?);
    let n: usize = a[3].parse()?;
    let seed: u64 = a[4].parse()?;
    let (r0, r1): (f64, f64) = (a[5].parse()?, a[6].parse()?);
    let curve = end_minus_curve(kind, g0, g1)?.ok_or_else(|| anyhow::anyhow!("no E- in range"))?;
    let (c0, c1) = curve.gamma_range();
    let (lo, hi) = (g0.max(c0), g1.min(c1));
    let mut rng = oblique_physics::sample::SplitMix(seed);
    let mut k = 0;
    while k < n {
        let g = lo + (hi - lo) * rng.uniform();
        let u = r0 + (r1 - r0) * rng.uniform();
        let s = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        if let Some(ae) = curve.alpha_at(g) {
            println!("{u:.3},{g},{},1", ae * (1.0 + s * 10f64.powf(u)));
            k += 1;
        }
    }
    Ok(())
}
