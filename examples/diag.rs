use oblique::physics::*;
fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let (g, a) = (args[0], args[1]);
    let big = 8192usize;
    let r = |s, t| {
        simulate(
            g,
            a,
            Resolution {
                springs: s,
                steps: t,
            },
            Scheme::Accurate,
        )
        .unwrap()
    };
    println!("vary steps, springs={big}");
    let refs = r(big, 65536);
    for k in 0..7 {
        let t = 128usize << k;
        let p = r(big, t);
        println!("{t:6} err={:.3e}", p - refs);
    }
    println!("vary springs, steps=65536");
    for k in 0..7 {
        let s = 32usize << k;
        let p = r(s, 65536);
        println!("{s:6} err={:.3e}", p - refs);
    }
}
