//! The CPU time of the automatic refinement over a set of points, as a table build pays it:
//! `cargo run --release -p oblique-tools --bin nodetime -- TOL < points.csv` reads
//! `gamma,alpha,e_n` lines, solves each at tolerance `TOL` on one thread (the normal motions
//! cached after the first), and prints the count, the thread CPU time, how many solves ended at
//! each step count and the sum of `P` (the same sum: the same answers).
use std::collections::BTreeMap;
use std::io::BufRead;

use oblique_solver::refine::Accuracy;
use oblique_solver::Request;

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let tol: f64 = oblique_tools::arg(&args, 0, "TOL")?;
    let mut points = Vec::new();
    for line in std::io::stdin().lock().lines() {
        let line = line?;
        let v = line
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<Vec<_>, _>>()?;
        anyhow::ensure!(v.len() == 3, "expected gamma,alpha,e_n: {line}");
        points.push((v[0], v[1], v[2]));
    }
    let cpu = || {
        oblique_clock::thread_cpu_time()
            .unwrap_or_default()
            .as_secs_f64()
    };
    let start = cpu();
    let mut steps = BTreeMap::new();
    let mut sum = 0.0;
    for &(g, a, e) in &points {
        let s = Request::new(g, a)
            .e_n(e)
            .accuracy(Accuracy::Tolerance(tol))
            .forced(true)
            .solve()?;
        *steps.entry(s.resolution.steps).or_insert(0usize) += 1;
        sum += s.p;
    }
    println!(
        "{} points, {:.3} s of CPU; final steps {steps:?}; sum of P {sum:.10}",
        points.len(),
        cpu() - start
    );
    Ok(())
}
