//! Where the Kelvin–Voigt error arises: `cargo run --release -p oblique-tools --bin kvtrace --
//! γ α e_n [PARTS] [UNTIL]` prints the slip velocity `u` at the instants `j t_c/PARTS` (default
//! 16) up to `UNTIL t_c` (default 1) for 256 … 16 384 steps: per instant the last difference
//! between levels and the ratios of successive differences (4 at order 2). With
//! `KVDUMP=a,b` it also prints, to stderr, every kick of the 4 096-step run between `a t_c` and
//! `b t_c`: the time, `u` before the kick and the step's mean friction force.
use oblique_solver::impact::run_contact_with;
use oblique_solver::kelvin_voigt::{
    dimensionless_normal, row::ViscoelasticRow, tau_for_restitution,
};
use oblique_solver::model::TangentialBodies;
use oblique_solver::NormalModel;

/// The dimensionless contact point (`m_t = 2/7`) recording `u` at the instants `j t_c/PARTS`.
struct Recorder {
    u: f64,
    t: f64,
    every: f64,
    seen: Vec<f64>,
    dump: bool,
    window: (f64, f64),
}

impl TangentialBodies for Recorder {
    fn slip_velocity(&self) -> f64 {
        self.u
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        -3.5 * f
    }
    fn kick(&mut self, h: f64, f: f64) {
        if self.dump && self.t > self.window.0 && self.t < self.window.1 {
            eprintln!("{:.9} {:.12e} {:.12e}", self.t, self.u, f);
        }
        self.u -= 3.5 * h * f;
        self.t += h;
        let next = self.seen.len() as f64 * self.every;
        if (self.t - next).abs() <= 1e-9 * self.every {
            self.seen.push(self.u);
        }
    }
}

fn main() -> anyhow::Result<()> {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let (g, al, e) = match a[..] {
        [g, al, e, ..] => (g, al, e),
        _ => anyhow::bail!("usage: kvtrace GAMMA ALPHA E_N [PARTS] [UNTIL]"),
    };
    let parts = a.get(3).map_or(16, |&p| p as usize);
    let until = a.get(4).map_or(1.0, |&u| u);
    let tau = tau_for_restitution(e)?;
    let shear = 2.0 / 7.0 * g * g;
    let limit = if al.is_finite() {
        al / shear
    } else {
        f64::INFINITY
    };
    let window = std::env::var("KVDUMP").ok().and_then(|w| {
        let (a, b) = w.split_once(',')?;
        Some((a.parse::<f64>().ok()?, b.parse::<f64>().ok()?))
    });
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut steps = 256;
    while steps <= 16384 {
        let normal = dimensionless_normal(steps, tau);
        let every = normal.contact_time() / parts as f64;
        let mut b = Recorder {
            u: 1.0,
            t: 0.0,
            every,
            seen: vec![1.0],
            dump: steps == 4096 && window.is_some(),
            window: window.map_or((0.0, 0.0), |(a, b)| {
                (a * normal.contact_time(), b * normal.contact_time())
            }),
        };
        run_contact_with(
            &mut b,
            &*normal,
            ViscoelasticRow::new(1.0, tau),
            1.0,
            shear,
            limit,
        );
        b.seen.resize(parts + 1, f64::NAN);
        b.seen[parts] = b.u;
        rows.push(b.seen);
        steps *= 2;
    }
    println!("gamma {g} alpha {al} e_n {e}: per t/t_c, last difference and ratios");
    for j in 1..=parts {
        if j as f64 > until * parts as f64 {
            break;
        }
        let col: Vec<f64> = rows.iter().map(|r| r[j]).collect();
        let d: Vec<f64> = col.windows(2).map(|w| w[1] - w[0]).collect();
        let ratios: Vec<String> = d
            .windows(2)
            .map(|w| format!("{:5.2}", w[0] / w[1]))
            .collect();
        println!(
            "{:5.3} {:>10.2e} {}",
            j as f64 / parts as f64,
            d[d.len() - 1],
            ratios.join(" ")
        );
    }
    Ok(())
}
