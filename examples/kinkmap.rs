//! Map the kink curves of P(γ, α) in the partial-slip and stick regions from the friction
//! history: `cargo run --release --example kinkmap -- 2.2 3.5 0.1 [steps]`.
//!
//! For each γ, the α range [α_c1, 1.5 α_c2] is scanned on a log grid; at every α the impact is
//! run once (continuum row, `steps` steps) and its *signature* is recorded: the sequence of
//! gross-slip episodes (`+`: friction at +μF_N, `-`: at −μF_N) strictly inside the contact,
//! and whether the contact ends in gross slip. Where the signature changes between two grid
//! points, the change is located by bisection and printed with both signatures: an episode
//! that appears or vanishes strictly inside the contact is a fold (P has a slope jump there);
//! one that appears at the separation changes the curvature only.
use oblique::physics::impact::{dimensionless_normal, run_contact, TangentialBodies};
use std::rc::Rc;

struct Cp {
    u: f64,
    t: f64,
    log: Vec<(f64, f64)>,
}
impl TangentialBodies for Cp {
    fn slip_velocity(&self) -> f64 {
        self.u
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        -f * 3.5
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.u -= h * f * 3.5;
        self.t += h;
        self.log.push((self.t - h / 2.0, f));
    }
}

/// Interior gross-slip episodes (sign, start and end time / t_c) of one impact, the sign of the
/// friction at separation (`+`/`-`, or ` ` if the contact sticks there), and P. Episodes in the
/// first and last 3 % of the contact (initial slip, the final release) are not interior.
fn episodes(
    g: f64,
    alpha: f64,
    nt: &Rc<oblique::physics::hertz::NormalTrajectory>,
) -> (Vec<(char, f64, f64)>, char, f64) {
    let shear = 2.0 / 7.0 * g * g;
    let mut cp = Cp {
        u: 1.0,
        t: 0.0,
        log: vec![],
    };
    run_contact(&mut cp, nt, 0, 1.0, shear, alpha / shear);
    let steps = nt.indentation.len() - 1;
    let mut eps: Vec<(char, f64, f64)> = vec![];
    let mut last = ' ';
    for &(t, f) in &cp.log {
        let tau = t / nt.contact_time;
        let x = t / nt.dt;
        let j = (x as usize).min(steps - 1);
        let s = x - j as f64;
        let d = nt.indentation[j] * (1.0 - s) + nt.indentation[j + 1] * s;
        let q = f / (alpha * 4.0 / 3.0 * d.max(0.0).powf(1.5));
        let st = if q > 1.0 - 1e-6 {
            '+'
        } else if q < -(1.0 - 1e-6) {
            '-'
        } else {
            ' '
        };
        if tau > 0.03 && tau < 0.97 && st != ' ' {
            match eps.last_mut() {
                Some(e) if e.0 == st && tau - e.2 < 0.01 => e.2 = tau,
                _ => eps.push((st, tau, tau)),
            }
        }
        if tau < 0.999 {
            last = st;
        }
    }
    (eps, last, cp.u)
}

fn signature(e: &(Vec<(char, f64, f64)>, char, f64)) -> String {
    let mut s: String = e.0.iter().map(|x| x.0).collect();
    s.push('|');
    s.push(e.1);
    s
}

/// One-sided slope dP/d ln α at `a`, over 1e-4 in ln α to the side `dir`.
fn slope(g: f64, a: f64, dir: f64, nt: &Rc<oblique::physics::hertz::NormalTrajectory>) -> f64 {
    let b = a * (dir * 1e-4).exp();
    (episodes(g, b, nt).2 - episodes(g, a, nt).2) / (dir * 1e-4)
}

fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().expect("number"))
        .collect();
    let (g0, g1, dg) = (a[0], a[1], a[2]);
    let steps = a.get(3).map_or(4096, |&s| s as usize);
    let nt = dimensionless_normal(steps);
    let mut g = g0;
    while g <= g1 + 1e-9 {
        let c1 = 2.0 * g * g / (7.0 * (2.0 * g * g - 1.0));
        let c2 = 2.0 * g * g / 7.0;
        let (lo, hi) = (c1 * 1.0001, c2 * 1.5);
        let n = 300;
        let xs: Vec<f64> = (0..=n)
            .map(|i| (lo.ln() + (hi / lo).ln() * i as f64 / n as f64).exp())
            .collect();
        let sigs: Vec<String> = xs
            .iter()
            .map(|&x| signature(&episodes(g, x, &nt)))
            .collect();
        for i in 0..n {
            if sigs[i] != sigs[i + 1] {
                let (mut l, mut r) = (xs[i], xs[i + 1]);
                for _ in 0..40 {
                    let m = 0.5 * (l + r);
                    if signature(&episodes(g, m, &nt)) == sigs[i] {
                        l = m
                    } else {
                        r = m
                    }
                }
                let (el, er) = (episodes(g, l, &nt), episodes(g, r, &nt));
                let fmt = |e: &(Vec<(char, f64, f64)>, char, f64)| {
                    let v: Vec<String> =
                        e.0.iter()
                            .map(|(c, a, b)| format!("{c}{a:.3}..{b:.3}"))
                            .collect();
                    format!("{} | end {}", v.join(" "), e.1)
                };
                println!(
                    "g {g:.3} alpha_k {:.6} a/ac2 {:.4} dP/dlna {:+.4} -> {:+.4}  [{}] -> [{}]",
                    0.5 * (l + r),
                    0.5 * (l + r) / c2,
                    slope(g, l, -1.0, &nt),
                    slope(g, r, 1.0, &nt),
                    fmt(&el),
                    fmt(&er)
                );
            }
        }
        g += dg;
    }
}
