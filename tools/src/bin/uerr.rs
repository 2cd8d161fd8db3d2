//! Where in time the error of an elastic impact builds up (scratch): `uerr GAMMA ALPHA` runs
//! the continuum row at 256 … 4096 steps and a reference at 32 768, and prints, at 40 instants
//! of the contact, `(u(t) − u_ref(t)) N²` for each level: a second-order error shows the same
//! curve at every level.
use oblique_solver::impact::{dimensionless_normal, run_contact, TangentialBodies};

struct Logged {
    u: f64,
    t: f64,
    log: Vec<(f64, f64)>,
}

impl TangentialBodies for Logged {
    fn slip_velocity(&self) -> f64 {
        self.u
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        -3.5 * f
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.u -= 3.5 * h * f;
        self.t += h;
        self.log.push((self.t, self.u));
    }
}

fn run(g: f64, a: f64, steps: usize) -> (f64, Vec<(f64, f64)>) {
    let nt = dimensionless_normal(steps);
    let shear = 2.0 / 7.0 * g * g;
    let mut b = Logged {
        u: 1.0,
        t: 0.0,
        log: Vec::new(),
    };
    run_contact(&mut b, &*nt, 0, 1.0, shear, a / shear);
    (nt.contact_time, b.log)
}

/// `u` at time `t` by linear interpolation of the log.
fn at(log: &[(f64, f64)], t: f64) -> f64 {
    let i = log.partition_point(|&(s, _)| s < t);
    if i == 0 {
        return log[0].1;
    }
    if i >= log.len() {
        return log[log.len() - 1].1;
    }
    let (t0, u0) = log[i - 1];
    let (t1, u1) = log[i];
    u0 + (u1 - u0) * (t - t0) / (t1 - t0)
}

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let g: f64 = oblique_tools::arg(&args, 0, "GAMMA")?;
    let a: f64 = oblique_tools::arg(&args, 1, "ALPHA")?;
    if let Some(n) = args.get(2) {
        let n: usize = n.parse()?;
        forces(g, a, n, 0.955, 0.9705);
        return Ok(());
    }
    let (tc, reference) = run(g, a, 32768);
    let levels: Vec<usize> = vec![256, 512, 1024, 2048, 4096];
    let runs: Vec<_> = levels.iter().map(|&n| run(g, a, n).1).collect();
    print!("{:>8}", "t/tc");
    for n in &levels {
        print!("{n:>9}");
    }
    println!();
    let mut ts: Vec<f64> = (1..=16).map(|k| k as f64 / 16.0 * 0.9375).collect();
    ts.extend([
        0.945, 0.95, 0.955, 0.957, 0.959, 0.961, 0.963, 0.965, 0.967, 0.97, 0.98, 0.99, 1.0,
    ]);
    for &f in &ts {
        // The grid node of the coarsest level nearest f: every level has it.
        let t = (f * 256.0).round() / 256.0 * tc;
        let t = if f >= 1.0 { tc * 1.0000001 } else { t };
        print!("{:8.4}", t / tc);
        let r = at(&reference, t);
        for (n, log) in levels.iter().zip(&runs) {
            print!("{:9.3}", (at(log, t) - r) * (*n as f64).powi(2));
        }
        println!();
    }
    Ok(())
}

/// The force of every kick between `t0` and `t1` (fractions of `t_c`) at `steps` steps, with
/// its first and second differences per unit time: kinks show as jumps of the first.
pub fn forces(g: f64, a: f64, steps: usize, t0: f64, t1: f64) {
    let (tc, log) = run(g, a, steps);
    let mut prev = (0.0, 1.0);
    let mut fs: Vec<(f64, f64)> = Vec::new();
    for &(t, u) in &log {
        let h = t - prev.0;
        if h > 0.0 {
            fs.push(((t - 0.5 * h) / tc, -(u - prev.1) / (3.5 * h)));
        }
        prev = (t, u);
    }
    for w in fs.windows(2) {
        let (ta, fa) = w[0];
        let (tb, fb) = w[1];
        if ta >= t0 && ta <= t1 {
            println!("{ta:.6} F {fa:.6e} dF/dt {:.4e}", (fb - fa) / (tb - ta));
        }
    }
}
