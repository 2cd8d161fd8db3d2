//! Which share of the last raw difference the Richardson estimate of Thornton's law needs at
//! its regular levels, against the shortest zone of the run (a measurement for
//! [`oblique_solver::thornton::RAW_FLOOR`]):
//! `cargo run --release -p oblique-tools --bin thornshare -- N SEED [TOP] [SOLVER]`.
//!
//! Points: `thornhonest`'s draw (the nine benchmark points at `e_n` 0.9 and 0.6, the cusp of
//! the stick patch at γ = 1.9182, α = 3.1582, `e_n` = 0.9143, and `N` random points of seed
//! `SEED`), then a grid around that cusp (γ 1.9, 1.9182, 1.95 × `e_n` 0.9, 0.9143, 0.93 × α
//! 3.100–3.220 every 0.004). For each point the ladder of the automatic refinement from its
//! first level up to `TOP` steps (default 16 384), each level run with its zones logged
//! ([`oblique_solver::thornton::dimensionless_zones`]: every zone, of any kind). The reference
//! is the Richardson value of the two finest levels; a point whose reference differs from the
//! Richardson value of the next-coarser pair by more than 1e-9 is left out of the shares
//! (counted). Lines, space-separated:
//!
//! - `L id gamma alpha e_n steps P zones all head interior list` for every level: the
//!   shortest zone in grid steps of all the zones, of all but the last (head: the last is the
//!   substep of about 1e-4 steps that the separation leaves, in a state of its own), of all but
//!   the first and the last (interior: the first is cut by the touch); list: `state:length` of the first 24 zones, state bits 1 at the
//!   `+` limit, 2 at the `−` limit, 4 stuck);
//! - `R id gamma alpha e_n steps |d| err drich need tail q0 q1 head_k head_k-1 int_k int_k-1
//!   uncertainty` for every level from the fourth on, up to two below the finest, classified
//!   regular but neither steady nor tight as `refine.rs` classifies it: `need` =
//!   `max(0, err − drich)/|d|` with `err` the Richardson value's error against the reference and
//!   `drich` the difference of the last two Richardson values, `tail` the share from the ratios
//!   (`refine::tail_share`), `q0 q1` the last two ratios, the shortest zones (head, interior) at
//!   this level and the one before, in grid steps, and `uncertainty` = spread of the reference
//!   over `|d|`;
//! - `F id gamma alpha e_n tol replica solver` the final steps of the offline replica of the
//!   refinement (current floor; 0: not accepted within `TOP`) and of `solve` at tol 1e-5, 1e-6
//!   and 1e-7 (with `SOLVER` = 1, the default; 0: not run, -1: failed).
//!
//! Points run in parallel (rayon).
use oblique_solver::law::Floor;
use oblique_solver::refine;
use oblique_solver::thornton::{
    dimensionless_motion, dimensionless_zones, yield_pressure_for_restitution, RAW_FLOOR,
};
use oblique_solver::{Accuracy, KeptLevels, Law, Request, Resolution};
use rayon::prelude::*;

const ORDER: i32 = 2;

fn last_ratios(values: &[f64]) -> Option<[f64; 2]> {
    refine::last_ratios(values)
}

fn steady(values: &[f64]) -> bool {
    refine::steady(values, ORDER)
}

fn tight(values: &[f64]) -> bool {
    refine::tight(values, ORDER)
}

fn regular(values: &[f64]) -> bool {
    refine::regular(values, ORDER)
}

fn tail_share(values: &[f64]) -> f64 {
    refine::tail_share(values, ORDER)
}

/// `refine::extrapolate`: the Richardson value and its estimate.
fn extrapolate(values: &[f64], floor: Floor, steps: usize) -> (f64, f64) {
    refine::extrapolate(values, ORDER, floor, steps)
}

/// The offline replica of `refine::refine_core` for this law (its levels are unwatched: no
/// zone floor, every level resolved): the index of the accepted level, if any within `values`.
fn accepted(values: &[f64], steps: &[usize], tol: f64, floor: Floor) -> Option<usize> {
    (2..values.len()).find(|&k| {
        let v = &values[..=k];
        let est = extrapolate(v, floor, steps[k]).1;
        est <= tol && refine::previous_estimate_agrees(v, ORDER, tol, floor, steps[k], 0.0)
    })
}

struct Lv {
    steps: usize,
    p: f64,
    zones: usize,
    all: f64,
    head: f64,
    interior: f64,
    list: String,
}

const TOLS: [f64; 3] = [1e-5, 1e-6, 1e-7];

fn main() -> anyhow::Result<()> {
    let args = oblique_tools::args();
    let n: usize = oblique_tools::arg_or(&args, 0, "N", 100)?;
    let seed: u64 = oblique_tools::arg_or(&args, 1, "SEED", 1)?;
    let top: usize = oblique_tools::arg_or(&args, 2, "TOP", 16_384)?;
    let solver: u8 = oblique_tools::arg_or(&args, 3, "SOLVER", 1)?;
    // thornhonest's draw.
    let mut points = oblique_tools::thornton_honesty_points(n, seed);
    // The grid around the cusp.
    for g in [1.9, 1.9182, 1.95] {
        for e in [0.9, 0.9143, 0.93] {
            for i in 0..31 {
                points.push((g, 3.1 + 0.004 * i as f64, e));
            }
        }
    }
    let rows: Vec<anyhow::Result<String>> = points
        .par_iter()
        .enumerate()
        .map(|(id, &(g, a, e))| -> anyhow::Result<String> {
            let mut out = String::new();
            let req = Request::new(g, a).e_n(e).law(Law::Thornton).forced(true);
            let motion = dimensionless_motion(yield_pressure_for_restitution(e)?);
            let shear = 2.0 / 7.0 * g * g;
            let limit = if a > oblique_solver::impact::ALPHA_NO_SLIP {
                f64::INFINITY
            } else {
                a / shear
            };
            // The solver's first level (`impact::ladder_start` of the accurate scheme).
            let scale = g.clamp(1.0, 1e12).log2().ceil().exp2();
            let start = (32.0 * scale).ceil() as usize / 2;
            let mut lv = Vec::new();
            let mut steps = start;
            while steps <= top {
                let (p, log) = dimensionless_zones(shear, limit, &motion, steps);
                lv.push(Lv {
                    steps,
                    p,
                    zones: log.zones.len(),
                    all: log.shortest(false),
                    interior: log.shortest(true),
                    head: log.zones[..log.zones.len().saturating_sub(1)]
                        .iter()
                        .map(|z| z.steps)
                        .fold(f64::INFINITY, f64::min),
                    list: log
                        .zones
                        .iter()
                        .take(24)
                        .map(|z| format!("{}:{:.3}", z.state, z.steps))
                        .collect::<Vec<_>>()
                        .join(","),
                });
                steps *= 2;
            }
            // The value is the solver's, to the bit.
            let check = req.simulate(Resolution {
                springs: 0,
                steps: start,
            })?;
            anyhow::ensure!(
                check.to_bits() == lv[0].p.to_bits(),
                "{g} {a} {e}: {check} from simulate, {} with zones",
                lv[0].p
            );
            for l in &lv {
                out += &format!(
                    "L {id} {g:.6} {a:.6} {e:.6} {} {:.17e} {} {:.4} {:.4} {:.4} {}\n",
                    l.steps, l.p, l.zones, l.all, l.head, l.interior, l.list
                );
            }
            let values: Vec<f64> = lv.iter().map(|l| l.p).collect();
            let stepv: Vec<usize> = lv.iter().map(|l| l.steps).collect();
            let m = values.len();
            let rich = |k: usize| values[k] + (values[k] - values[k - 1]) / 3.0;
            let reference = rich(m - 1);
            let spread = (reference - rich(m - 2)).abs();
            if spread <= 1e-9 {
                for k in 3..m.saturating_sub(2) {
                    let v = &values[..=k];
                    if !regular(v) || steady(v) || tight(v) {
                        continue;
                    }
                    let d = (values[k] - values[k - 1]).abs();
                    let err = (rich(k) - reference).abs();
                    let drich = (rich(k) - rich(k - 1)).abs();
                    let need = (err - drich).max(0.0) / d;
                    let q = last_ratios(v).unwrap_or([f64::NAN; 2]);
                    out += &format!(
                        "R {id} {g:.6} {a:.6} {e:.6} {} {d:.4e} {err:.4e} {drich:.4e} {need:.5} \
                         {:.5} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4} {:.4e}\n",
                        lv[k].steps,
                        tail_share(v),
                        q[0],
                        q[1],
                        lv[k].head,
                        lv[k - 1].head,
                        lv[k].interior,
                        lv[k - 1].interior,
                        spread / d
                    );
                }
            } else {
                out += &format!("U {id} {g:.6} {a:.6} {e:.6} {spread:.3e}\n");
            }
            let floor = if a.is_finite() {
                RAW_FLOOR
            } else {
                RAW_FLOOR.without_scatter()
            };
            let mut kept = KeptLevels::new();
            for tol in TOLS {
                let replica = accepted(&values, &stepv, tol, floor).map_or(0, |k| stepv[k]);
                let real: i64 = if solver == 1 {
                    req.accuracy(Accuracy::Tolerance(tol))
                        .solve_continuing(&mut kept)
                        .map_or(-1, |s| s.resolution.steps as i64)
                } else {
                    0
                };
                out += &format!("F {id} {g:.6} {a:.6} {e:.6} {tol:e} {replica} {real}\n");
            }
            Ok(out)
        })
        .collect();
    for r in rows {
        print!("{}", r?);
    }
    Ok(())
}
