use oblique::physics::*;
fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let (g, a) = (args[0], args[1]);
    let ratio = args.get(2).copied().unwrap_or(4.0);
    let reference = simulate(
        g,
        a,
        Resolution {
            springs: (8192.0 / ratio) as usize,
            steps: 8192,
        },
        Scheme::Accurate,
    )
    .unwrap();
    println!("ref {reference:.12}");
    let mut prev = f64::NAN;
    for k in 0..8 {
        let steps = 64usize << k;
        let res = Resolution {
            springs: ((steps as f64) / ratio) as usize,
            steps,
        };
        let t = std::time::Instant::now();
        let p = simulate(g, a, res, Scheme::Accurate).unwrap();
        let el = t.elapsed().as_secs_f64();
        let rich = p + (p - prev) / 3.0;
        println!(
            "{:6} {:6} P={:.10} err={:.2e} rich_err={:.2e} t={:.2e}",
            res.springs,
            res.steps,
            p,
            (p - reference).abs(),
            (rich - reference).abs(),
            el
        );
        prev = p;
    }
}
