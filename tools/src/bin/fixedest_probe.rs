//! The fixed-resolution error estimate's raw data: at 8 points (γ 0.3–3.2, α 0.05–∞), for
//! springs {continuum, 2, 8, 64, 1024} × steps {8, 32, 256, 1024} and both schemes, the true
//! error against the automatic refinement to 1e-9 and the differences `P(h) − P(2h)`,
//! `P(2h) − P(4h)`, `P(4h) − P(8h)` behind the estimate (`impact::fixed_estimate`).
//!
//! `cargo run --release -p oblique-tools --bin fixedest_probe` (about 2 s).

use oblique_solver::{Accuracy, Request, Resolution, Scheme};

fn main() -> Result<(), oblique_solver::PhysicsError> {
    let points = [
        (1.7, 1.0),
        (1.754, 0.5),
        (0.8, 0.3),
        (3.2, 1.3),
        (2.5, f64::INFINITY),
        (0.5, 1e3),
        (1.2, 0.25),
        (0.3, 0.05),
    ];
    println!("gamma alpha scheme springs steps error differences");
    for &(g, a) in &points {
        let reference = Request::new(g, a)
            .accuracy(Accuracy::Tolerance(1e-9))
            .forced(true)
            .solve()?
            .p;
        for scheme in [Scheme::Accurate, Scheme::Euler] {
            for &s in &[0usize, 2, 8, 64, 1024] {
                if s == 0 && scheme == Scheme::Euler {
                    continue;
                }
                for &n in &[8usize, 32, 256, 1024] {
                    let mut values = vec![];
                    for k in 0..4u32 {
                        let (springs, steps) = (s >> k, n >> k);
                        if (s != 0 && springs < 2) || steps < 8 {
                            break;
                        }
                        values.push(
                            Request::new(g, a)
                                .scheme(scheme)
                                .simulate(Resolution { springs, steps })?,
                        );
                    }
                    let err = (values[0] - reference).abs();
                    let d: Vec<String> = values
                        .windows(2)
                        .map(|w| format!("{:+.2e}", w[0] - w[1]))
                        .collect();
                    println!(
                        "{g} {a} {} {s} {n} {err:.2e} {}",
                        scheme.name(),
                        d.join(" ")
                    );
                }
            }
        }
    }
    Ok(())
}
