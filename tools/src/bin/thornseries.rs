//! The slip pattern of one impact under Thornton's law over a time window:
//! `thornseries GAMMA ALPHA E_N STEPS T0 T1 [EVERY]` prints `t`, the fractions of the contact
//! radius at the `+` and `−` limits and the numbers of separate zones at each, every `EVERY`-th
//! step with `T0 ≤ t ≤ T1` (fractions of the contact time).

use oblique_solver::history::slip_pattern_thornton;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    anyhow::ensure!(
        a.len() >= 6,
        "usage: thornseries GAMMA ALPHA E_N STEPS T0 T1 [EVERY]"
    );
    let every = if a.len() > 6 { a[6] as usize } else { 1 };
    let (log, p) = slip_pattern_thornton(a[0], a[1], a[2], a[3] as usize)?;
    println!("P {p:.12}");
    for (i, &(t, pl, mi, zp, zm)) in log.iter().enumerate() {
        if t >= a[4] && t <= a[5] && i % every == 0 {
            println!("{t:.5} {pl:.6} {mi:.6} {zp} {zm}");
        }
    }
    Ok(())
}
