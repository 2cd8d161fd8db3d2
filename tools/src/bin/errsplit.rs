//! Splits the error of the accurate scheme into its spatial (springs) and temporal (steps) parts:
//! `cargo run --release -p oblique-tools --bin errsplit -- 1.9,0.5 3.2,1.0` (pairs `gamma,alpha`; `inf`
//! allowed). For each point it prints, per step count (rows) and spring count (columns), the
//! error against a 32768 × 32768 reference and the time of one impact. The base resolution of
//! the automatic refinement (`impact::base_resolution`) was chosen from these tables.
use oblique_solver::Request;
use oblique_solver::*;

fn parse(arg: &str) -> Option<(f64, f64)> {
    let (g, a) = arg.split_once(',')?;
    Some((g.trim().parse().ok()?, a.trim().parse().ok()?))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut pts = Vec::new();
    for arg in std::env::args().skip(1) {
        pts.push(parse(&arg).ok_or_else(|| format!("'{arg}': expected gamma,alpha"))?);
    }
    if pts.is_empty() {
        return Err("give at least one point gamma,alpha (e.g. 1.9,0.5)".into());
    }
    let run = |g, a, steps, springs| Request::new(g, a).simulate(Resolution { springs, steps });
    for (g, a) in pts {
        let r = run(g, a, 32768, 32768)?;
        println!("g={g} a={a} ref={r:.10}");
        for &st in &[256usize, 512, 1024, 2048, 4096] {
            let mut line = format!("steps {st:5}:");
            for &sp in &[128usize, 256, 512, 1024, 2048, 4096, 16384] {
                let t = std::time::Instant::now();
                let p = run(g, a, st, sp)?;
                let dt = t.elapsed().as_secs_f64() * 1e3;
                line += &format!(" {:8.1e}({:.1}ms)", p - r, dt);
            }
            println!("{line}");
        }
    }
    Ok(())
}
