//! Partial-slip zones of Thornton's law: `thornpattern GAMMA ALPHA E_N [STEPS]` prints the
//! intervals of time (fractions of the contact time) in which part of the contact is at the
//! `+` or the `−` limit, with the largest fraction of the contact radius at it.

use oblique_solver::history::slip_pattern_thornton;

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse())
        .collect::<Result<_, _>>()?;
    let steps = if a.len() > 3 { a[3] as usize } else { 4096 };
    let (log, p) = slip_pattern_thornton(a[0], a[1], a[2], steps)?;
    println!("P {p:.12}");
    for (which, k) in [("+", 0usize), ("-", 1)] {
        let mut open: Option<(f64, f64)> = None;
        let mut prev_t = 0.0;
        for &(t, pl, mi, _, _) in &log {
            let f = if k == 0 { pl } else { mi };
            match (&mut open, f > 0.0) {
                (None, true) => open = Some((prev_t, f)),
                (Some((_, m)), true) => *m = m.max(f),
                (Some((t0, m)), false) => {
                    println!("{which} {t0:.5}..{prev_t:.5} max {m:.4}");
                    open = None;
                }
                (None, false) => {}
            }
            prev_t = t;
        }
        if let Some((t0, m)) = open {
            println!("{which} {t0:.5}..{prev_t:.5} max {m:.4} (to the end)");
        }
    }
    // Stretches of at least 5 steps with two or more separate zones of one sign.
    for (which, k) in [("+", 0usize), ("-", 1)] {
        let mut run: Option<(f64, usize, usize)> = None;
        let mut prev_t = 0.0;
        for &(t, _, _, zp, zm) in &log {
            let n = if k == 0 { zp } else { zm };
            match (&mut run, n >= 2) {
                (None, true) => run = Some((prev_t, 1, n)),
                (Some((_, len, m)), true) => {
                    *len += 1;
                    *m = (*m).max(n);
                }
                (Some((t0, len, m)), false) => {
                    if *len >= 5 {
                        println!("{which}x{m} {t0:.5}..{prev_t:.5} ({len} steps)");
                    }
                    run = None;
                }
                (None, false) => {}
            }
            prev_t = t;
        }
    }
    Ok(())
}
