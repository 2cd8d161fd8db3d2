//! Every zone of one impact under Thornton's law (`history::slip_zones_thornton`):
//! `thornzones GAMMA ALPHA E_N STEPS [T0 T1 [EVERY]]` prints, every `EVERY`-th step with
//! `T0 ≤ t ≤ T1` (fractions of the contact time), `t` and the zones from the centre as
//! `kind[x0,x1]` (`S` stuck, `+`, `-` at the limits; `x` in fractions of the contact radius).
//! `--diff GAMMA A1 A2 E_N STEPS` prints only the steps whose sequences of zone kinds differ
//! between `A1` and `A2`; `--switch GAMMA E_N A0 A1 N STEPS` the field clipped at the switch to
//! unloading at `N + 1` values of α from `A0` to `A1` (multiples of `α_c2`).

use oblique_solver::history::{slip_zones_thornton, switch_zones_thornton, ZoneSnapshot};

fn show(z: &[(i8, f64, f64)]) -> String {
    z.iter()
        .map(|&(k, a, b)| {
            let c = match k {
                1 => '+',
                -1 => '-',
                _ => 'S',
            };
            format!("{c}[{a:.5},{b:.5}]")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

fn kinds(z: &[(i8, f64, f64)]) -> Vec<i8> {
    z.iter().map(|z| z.0).collect()
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--switch") {
        let a: Vec<f64> = args[1..]
            .iter()
            .map(|s| s.parse())
            .collect::<Result<_, _>>()?;
        anyhow::ensure!(
            a.len() >= 6,
            "usage: thornzones --switch GAMMA E_N A0 A1 N STEPS"
        );
        let n = a[4] as usize;
        let c2 = 2.0 / 7.0 * a[0] * a[0];
        for i in 0..=n {
            let x = a[2] + (a[3] - a[2]) * i as f64 / n.max(1) as f64;
            let z = switch_zones_thornton(a[0], x * c2, a[1], a[5] as usize)?;
            println!("{x:.6} {:.8} {}", x * c2, show(&z));
        }
        return Ok(());
    }
    if args.first().map(String::as_str) == Some("--diff") {
        let a: Vec<f64> = args[1..]
            .iter()
            .map(|s| s.parse())
            .collect::<Result<_, _>>()?;
        anyhow::ensure!(
            a.len() >= 5,
            "usage: thornzones --diff GAMMA A1 A2 E_N STEPS"
        );
        let (l1, p1): (Vec<ZoneSnapshot>, f64) =
            slip_zones_thornton(a[0], a[1], a[3], a[4] as usize)?;
        let (l2, p2) = slip_zones_thornton(a[0], a[2], a[3], a[4] as usize)?;
        println!("P {p1:.12} {p2:.12}; entries {} {}", l1.len(), l2.len());
        for (i, (x, y)) in l1.iter().zip(&l2).enumerate() {
            if kinds(&x.1) != kinds(&y.1) {
                println!("{i} {:.5} A1: {}", x.0, show(&x.1));
                println!("{i} {:.5} A2: {}", y.0, show(&y.1));
            }
        }
        return Ok(());
    }
    let a: Vec<f64> = args.iter().map(|s| s.parse()).collect::<Result<_, _>>()?;
    anyhow::ensure!(
        a.len() >= 4,
        "usage: thornzones GAMMA ALPHA E_N STEPS [T0 T1 [EVERY]]"
    );
    let (t0, t1) = if a.len() >= 6 {
        (a[4], a[5])
    } else {
        (0.0, 1.0)
    };
    let every = if a.len() > 6 { a[6] as usize } else { 1 };
    let (log, p) = slip_zones_thornton(a[0], a[1], a[2], a[3] as usize)?;
    println!("P {p:.12}");
    for (i, (t, z)) in log.iter().enumerate() {
        if *t >= t0 && *t <= t1 && i % every == 0 {
            println!("{i} {t:.5} {}", show(z));
        }
    }
    Ok(())
}
