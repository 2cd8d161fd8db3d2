//! The whole refinement ladder of many points, for studies of error estimators and stopping
//! rules: `cargo run --release -p oblique-tools --bin ladder -- N SEED [LEVELS] > ladder.csv`.
//! For the nine benchmark points and `N` random ones (γ 0.1–3.5, α from the full-slip limit
//! to ∞, e_n ∈ {1, 0.9, 0.6}) it prints `P` at every level from the refinement's first
//! resolution up to `LEVELS` doublings (default 9) with the thread CPU time of each run, as CSV:
//! `id,gamma,alpha,e_n,level,steps,p,seconds`. With `LAW` `thornton` (fourth argument) the
//! points are solved under Thornton's law, `e_n` drawn uniformly from 0.3–1 and the nine
//! benchmark points at `e_n` 0.9 and 0.6.
use oblique_physics::regimes;
use oblique_solver::{impact::base_resolution, Law, Request, Scheme};

/// Thread CPU time (s).
fn cpu() -> f64 {
    oblique_clock::thread_cpu_time().map_or(f64::NAN, |d| d.as_secs_f64())
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().map_or(Ok(100), |s| s.parse())?;
    let seed: u64 = args.get(1).map_or(Ok(1), |s| s.parse())?;
    let levels: u32 = args.get(2).map_or(Ok(9), |s| s.parse())?;
    let law = args.get(3).map(|s| Law::from_name(s)).transpose()?;
    let thornton = law == Some(Law::Thornton);
    let mut rnd = oblique_tools::xorshift(seed);
    let mut points = Vec::new();
    for e in if thornton { vec![0.9, 0.6] } else { vec![1.0] } {
        for g in [0.5, 1.754, 3.0] {
            for a in [0.3, 1.0, f64::INFINITY] {
                points.push((g, a, e));
            }
        }
    }
    for _ in 0..n {
        let g = 0.1 * 35f64.powf(rnd());
        let e = if thornton {
            0.3 + 0.7 * rnd()
        } else {
            [1.0, 1.0, 0.9, 0.6][(rnd() * 4.0) as usize]
        };
        let lim = regimes::linear_limit_dissipative(g, e).max(1e-3);
        let pick = rnd();
        let a = if pick < 0.1 {
            f64::INFINITY
        } else if pick < 0.4 {
            // Next to a critical curve, on either side, 1e-4 to 1e-1 away (relative).
            let curves = if e < 1.0 {
                [
                    lim,
                    regimes::alpha_c1_dissipative(g, e),
                    regimes::alpha_c2(g),
                    2.0 / 7.0,
                ]
            } else {
                [lim, regimes::alpha_c1(g), regimes::alpha_c2(g), 2.0 / 7.0]
            };
            // 2/7 (where Thornton's first gross-slip episode ends at the switch) for that law.
            let count = if thornton { 4.0 } else { 3.0 };
            let curve = curves[(rnd() * count) as usize];
            let off = 10f64.powf(-4.0 + 3.0 * rnd()) * if rnd() < 0.5 { -1.0 } else { 1.0 };
            (curve * (1.0 + off)).max(lim * 1.0001)
        } else {
            lim * (1.0 + 1e3f64.powf(rnd()) * 0.999)
        };
        points.push((g, a, e));
    }
    println!("id,gamma,alpha,e_n,level,steps,p,seconds");
    for (id, &(g, a, e)) in points.iter().enumerate() {
        let start = base_resolution(g, Scheme::Accurate);
        let start = oblique_solver::Resolution {
            springs: 0,
            steps: start.steps / 2,
        };
        for k in 0..=levels {
            let res = start.doubled(k);
            let t0 = cpu();
            let mut req = Request::new(g, a).e_n(e);
            if let Some(law) = law {
                req = req.law(law);
            }
            let p = req.simulate(res)?;
            let t = cpu() - t0;
            println!(
                "{id},{g:.17e},{a:.17e},{e},{k},{},{p:.17e},{t:.3e}",
                res.steps
            );
        }
    }
    Ok(())
}
