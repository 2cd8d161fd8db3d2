//! The error-controlled driver shared by every law: the automatic refinement (resolution
//! doubling until the error estimate is below a tolerance), the estimate of a fixed resolution,
//! and the [`Solution`] it answers with. The time loop it drives is [`crate::impact`]; the
//! law it solves comes from [`crate::law`].

use serde::Serialize;

use crate::elastic::FLOOR;
use crate::error::{positive, PhysicsError};
use crate::impact::{ladder_start, memory_bytes, plan, work, Limits, Scheme};
use crate::law::Floor;
use crate::registry::LawParameters;
use crate::resolution::Resolution;
use crate::zones::Level;

/// How the accuracy of a result is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Accuracy {
    /// Refine (doubling springs and steps together) until the error estimate is ≤ the tolerance.
    Tolerance(f64),
    /// A fixed resolution; the error estimate comes from three coarser runs (1/2, 1/4 and 1/8
    /// of the springs and steps) and is given only where they converge steadily at the scheme's
    /// order ([`NoEstimate`] says why not).
    Fixed(Resolution),
}

/// How a result was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Exact closed form (full-slip line, γ = 1 plateau, α = 0); nothing simulated.
    ClosedForm,
    /// Simulated at the reported resolution.
    Simulated,
}

/// A value of `P` with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Solution {
    /// Tangential restitution of the contact point `P = u_after/u_before`.
    pub p: f64,
    /// Estimated absolute error of `p` (0 for closed forms). `+∞` when there is no trustworthy
    /// estimate (a fixed resolution only: see [`Solution::no_estimate`] for why), so that a
    /// comparison with a tolerance fails safe.
    pub error_estimate: f64,
    /// Why a fixed-resolution result has no error estimate (`None`: it has one).
    pub no_estimate: Option<NoEstimate>,
    /// Resolution of the finest run (zero for closed forms).
    pub resolution: Resolution,
    /// Scheme used.
    pub scheme: Scheme,
    /// Closed form or simulation.
    pub method: Method,
    /// The dissipation law asked for, with its parameters for `e_n` (the Kelvin–Voigt law's
    /// relaxation time `τ̂`, 0 at `e_n = 1`); outputs print them through it
    /// ([`LawParameters::values`], [`LawParameters::describe`]).
    pub law: LawParameters,
    /// Normal restitution `e_n` of the impact (1 for the elastic law).
    pub e_n: f64,
}

impl Solution {
    /// The error estimate, or `None` when there is no trustworthy one.
    pub fn estimate(&self) -> Option<f64> {
        match self.no_estimate {
            None => Some(self.error_estimate),
            Some(_) => None,
        }
    }
}

/// Why a result at a fixed resolution comes without an error estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "kebab-case")]
pub enum NoEstimate {
    /// The resolution cannot be halved [`FIXED_HALVINGS`] times (springs ≥ 16 or the continuum
    /// row, steps ≥ 64 are needed).
    TooCoarse {
        /// Springs asked for (0: the continuum row).
        springs: usize,
        /// Steps asked for.
        steps: usize,
    },
    /// The differences between the runs at full, 1/2, 1/4 and 1/8 of the resolution do not
    /// shrink steadily at the scheme's order: the resolution is not in the asymptotic range,
    /// and no difference says how far the value is from the converged one.
    NotAsymptotic {
        /// `P(h) − P(2h)`, `P(2h) − P(4h)`, `P(4h) − P(8h)`.
        differences: [f64; 3],
    },
    /// Where the stuck part of the contact shrinks to nothing before gross slip, that zone
    /// spans fewer than [`crate::zones::ZONE_STEPS`] steps: until it spans more, the error does
    /// not follow the scheme's order and the coarser runs say nothing of it.
    Unresolved {
        /// Grid steps the zone spans ([`Level::shortest_zone`]).
        zone_steps: f64,
        /// Steps asked for.
        steps: usize,
    },
}

impl std::fmt::Display for NoEstimate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NoEstimate::TooCoarse { springs, steps } => write!(
                f,
                "{} is too coarse (the estimate compares runs at 1/2, 1/4 and 1/8 of the \
                 springs and steps: at least {} springs, or the continuum row, and {} steps)",
                Resolution {
                    springs: *springs,
                    steps: *steps
                },
                2 << FIXED_HALVINGS,
                8 << FIXED_HALVINGS
            ),
            NoEstimate::NotAsymptotic {
                differences: [a, b, c],
            } => write!(
                f,
                "the runs at 1, 1/2, 1/4 and 1/8 of the resolution differ by {a:.1e}, {b:.1e}, \
                 {c:.1e}, not steadily shrinking at the scheme's order (outside the asymptotic \
                 range)"
            ),
            NoEstimate::Unresolved { zone_steps, steps } => write!(
                f,
                "at {steps} steps the zone where the stuck part of the contact shrinks to nothing \
                 before gross slip spans {zone_steps:.1} steps, fewer than {}: the error is not \
                 yet of the scheme's order there (more steps resolve it)",
                crate::zones::ZONE_STEPS
            ),
        }
    }
}

/// Number of coarser runs (each halving springs and steps) behind the error estimate at a fixed
/// resolution.
pub const FIXED_HALVINGS: u32 = 3;

/// Error estimate of the finest of the values `P(h), P(2h), P(4h), P(8h)` of a scheme of order
/// `p`, or why there is none.
///
/// With `d_k = P(2^k h) − P(2^{k+1} h)` and `r = 2^p`, the sequence counts as asymptotic when
/// every `d_k` has the same sign and each ratio `q_k = d_{k+1}/d_k` lies in `(r/2, 4r]`
/// (between one order less and two orders more than the nominal one). The estimate is then the
/// tail of a geometric series at the observed rate, with a margin of 3:
/// `3 max(|d_0|, |d_1|/r) / (min(q_0, r) − 1)`; at the nominal rate this is `3|d_0|/(r − 1)`,
/// i.e. `|d_0|` for the accurate scheme and `3|d_0|` for Euler.
///
/// Measured (`cargo run --release -p oblique-tools --bin fixedest_probe`;
/// `crates/solver/tests/physics_core.rs` checks 12 points) on 8 points (γ 0.3–3.2, α 0.05–∞),
/// springs {0, 2, 8, 64, 1024} × steps {8, 32, 256,
/// 1024}, both schemes, against tol 1e-9 references: the accepted estimates exceed the true
/// error by 2.6–54× (median 3.3); the half-resolution difference used
/// before under-stated it up to 10⁴× where the spring count or the step count could not be
/// halved (2 springs × 1024 steps: ±1.6e-5 for an error of 0.44). Refused, for example: the
/// Euler scheme at γ = 3.2 (differences of alternating sign), spring rows at α = 1000 (the slip
/// annulus thinner than the spacing: ratios 5.3 then 1.1).
fn fixed_estimate(values: [f64; 4], order: i32) -> Result<f64, [f64; 3]> {
    let d = [
        values[0] - values[1],
        values[1] - values[2],
        values[2] - values[3],
    ];
    let largest = d.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    // Converged to rounding (e.g. the full-slip line, exact at any resolution).
    if largest <= ROUNDING_FLOOR {
        return Ok(ROUNDING_FLOOR);
    }
    let r = 2f64.powi(order);
    let same_sign = d.iter().all(|&x| x > 0.0) || d.iter().all(|&x| x < 0.0);
    let q = [d[1] / d[0], d[2] / d[1]];
    if !same_sign || q.iter().any(|&q| !(q > r / 2.0 && q <= 4.0 * r)) {
        return Err(d);
    }
    Ok(3.0 * d[0].abs().max(d[1].abs() / r) / (q[0].min(r) - 1.0))
}

/// Differences between resolutions below this are rounding, not discretisation error.
const ROUNDING_FLOOR: f64 = 1e-13;

/// Estimate the error of a sequence of results at resolutions doubling each time.
///
/// For clean convergence of order `p` the error of the finest value is
/// `|P_k − P_{k−1}| / (2^p − 1)`; at partial slip the time error is O(h²) but irregular (kinks
/// of F(t) inside steps), and that formula was measured to under-estimate by up to 6×. So the
/// estimate keeps a margin of `2^p − 1` (it is the last difference itself) and never falls below
/// the previous difference scaled by one order, `|P_{k−1} − P_{k−2}| / 2^p`. Where the
/// differences shrink more slowly than the order says, by `q = |P_{k−1} − P_{k−2}| /
/// |P_k − P_{k−1}| < 2^p`, the rest of a convergence at that rate, `|P_k − P_{k−1}| / (q − 1)`,
/// is a floor too: at γ = 1.6202, α = 3.4290 (the continuum row, 256 → 1024 steps) the
/// differences fell by 1.3 and 1.6 only, and the last difference, 8.5e-8, was below the error,
/// 9.4e-8; the rate's floor gives 1.3e-7. Where the last two differences have opposite signs
/// the sequence has turned, and the previous difference is the floor: at γ = 1.7498,
/// α = 1.2474 (512 → 1024 steps) the last difference was 5.7e-8, the error 9.0e-8 and the
/// previous difference 1.6e-7. Where the differences do not shrink (`q ≤ 1`) the last
/// difference is kept and the refinement goes on while it exceeds the tolerance.
fn estimate(values: &[f64], order: i32) -> f64 {
    let r = 2f64.powi(order);
    let n = values.len();
    let d = |k: usize| values[k] - values[k - 1];
    let last = d(n - 1).abs();
    if n < 3 {
        return last;
    }
    let prev = d(n - 2).abs();
    let q = prev / last;
    let tail = if d(n - 1) * d(n - 2) < 0.0 {
        prev
    } else if q > 1.0 && q < r {
        last / (q - 1.0)
    } else {
        last
    };
    last.max(prev / r).max(tail)
}

/// Richardson extrapolation of the last two values for order `p` and its error estimate:
/// `R_k = P_k + (P_k − P_{k−1})/(2^p − 1)`, estimated by
/// `max(|R_k − R_{k−1}|, s |P_k − P_{k−1}|)`, the share `s` the law's floor (0.1 for the
/// elastic law), raised by [`tail_share`] where the regular ratios are away from `2^p`. Measured on
/// 32 points spanning every regime (γ 0.3–3.5, α from just above the linear limit to ∞,
/// 128–8192 steps): never below the true error where that error exceeds the 2e-8 accuracy of
/// the reference (`tools/src/bin/estim.rs`).
pub fn extrapolate(values: &[f64], order: i32, floor: Floor, steps: usize) -> (f64, f64) {
    let r = 2f64.powi(order) - 1.0;
    let n = values.len();
    let rich = |k: usize| values[k] + (values[k] - values[k - 1]) / r;
    let last = rich(n - 1);
    let share = if tight(values, order) {
        floor.tight.max(tail_share(values, order))
    } else if steady(values, order) {
        floor.steady.max(tail_share(values, order))
    } else if regular(values, order) {
        floor.regular.max(tail_share(values, order))
    } else {
        floor.irregular
    };
    let est = (last - rich(n - 2))
        .abs()
        .max(share * (values[n - 1] - values[n - 2]).abs())
        .max(floor.scatter / (steps as f64).powi(2));
    (last, est)
}

/// The share of the last raw difference `d = P_k − P_{k−1}` by which the Richardson value
/// misses the limit if the differences go on shrinking at one of the last two ratios `q`, with
/// a margin of [`TAIL_MARGIN`]: `1.5 |2^p − q| / ((2^p − 1)(q − 1))`, the larger of the two.
/// The extrapolation assumes the nominal ratio `2^p` (the rest of the error `d/(2^p − 1)`),
/// while at a steady ratio `q` the rest is `d/(q − 1)`: 0.111 |d| off at `q = 3.25` or 5.5,
/// beyond the elastic law's floor of 0.1 |d|.
///
/// At γ = 1.754, α = 1 (elastic, tol 1e-8) the ratios before 4096 steps were 3.25 and 3.75
/// and the Richardson value erred by 3.00e-9 = 0.115 |d|, above that floor (estimate 2.61e-9);
/// this share is 0.167 there (estimate 4.31e-9). Over 761 regular levels of 159 points
/// (`cargo run --release -p oblique-tools --bin ladder -- 150 7 11`, against the Richardson
/// value of the two finest levels) no other level needed more than 0.031 |d|.
pub fn tail_share(values: &[f64], order: i32) -> f64 {
    let Some(ratios) = last_ratios(values) else {
        return 0.0;
    };
    let r = 2f64.powi(order);
    ratios
        .iter()
        .filter(|&&q| q > 1.0)
        .map(|&q| TAIL_MARGIN * (r - q).abs() / ((r - 1.0) * (q - 1.0)))
        .fold(0.0, f64::max)
}

/// The last two ratios of successive differences of `values`,
/// `(P_{k−1} − P_{k−2}) / (P_k − P_{k−1})` and the one before it (`None` with fewer than four
/// values).
pub fn last_ratios(values: &[f64]) -> Option<[f64; 2]> {
    let n = values.len();
    if n < 4 {
        return None;
    }
    let d = |k: usize| values[k] - values[k - 1];
    Some([d(n - 2) / d(n - 1), d(n - 3) / d(n - 2)])
}

/// Margin on the rest of a convergence at a ratio seen ([`tail_share`]).
const TAIL_MARGIN: f64 = 1.5;

/// Whether the last three ratios of successive differences of `values` are within
/// `[0.95, 1.05] · 2^order` ([`Floor::steady`]): the sequence has converged at its order for
/// four levels.
pub fn steady(values: &[f64], order: i32) -> bool {
    within_last_three(values, order, STEADY_SPREAD)
}

/// Relative spread of the ratios around `2^p` that [`steady`] accepts.
const STEADY_SPREAD: f64 = 0.05;

/// Whether the last three ratios of successive differences of `values` are within
/// `[0.99, 1.01] · 2^order` ([`Floor::tight`]): four doublings at the order, to 1 %.
pub fn tight(values: &[f64], order: i32) -> bool {
    within_last_three(values, order, TIGHT_SPREAD)
}

/// Relative spread of the ratios around `2^p` that [`tight`] accepts.
const TIGHT_SPREAD: f64 = 0.01;

/// Whether the last three ratios of successive differences of `values` are within
/// `[1 − spread, 1 + spread] · 2^order` (five values at least).
fn within_last_three(values: &[f64], order: i32, spread: f64) -> bool {
    let n = values.len();
    if n < 5 {
        return false;
    }
    let r = 2f64.powi(order);
    let d = |k: usize| values[k] - values[k - 1];
    [n - 1, n - 2, n - 3]
        .iter()
        .all(|&k| ((1.0 - spread) * r..=(1.0 + spread) * r).contains(&(d(k - 1) / d(k))))
}

/// Whether the last two ratios of successive differences of `values` are within
/// `[0.75, 1.375] · 2^order`.
pub fn regular(values: &[f64], order: i32) -> bool {
    let r = 2f64.powi(order);
    last_ratios(values).is_some_and(|q| q.iter().all(|q| (0.75 * r..=1.375 * r).contains(q)))
}

/// The acceptance guard of the Richardson path: the estimate one level coarser must already be
/// within `2^p · tol`, as it is when the sequence has converged at order `p` for two levels, or
/// the last three ratios of differences are [`tight`] (converged at order `p` to 1 % for four
/// doublings: no plateau looks like that).
///
/// Without it a pre-asymptotic plateau passes for convergence: at γ = 1.80378, α = 5.148 (stick,
/// a short slip episode that 256 steps do not resolve) the values at 64, 128 and 256 steps lie
/// within 1e-5 of each other but 1.5–2.4e-5 below the converged value, and the three-level
/// estimate (2.0e-6) accepted them at `tol = 1e-5` with a true error of 2.5e-5. The estimate one
/// level coarser is 7.8e-5 there: above `4 tol`, so the guard refines on (to 1024 steps, error
/// 6e-8). A looser factor `2^(p+1)` would have let this case through. The guard costs CPU time
/// where a sequence converges fast from a poor start: `configs/quick.toml` needs 13.8 s with it
/// against 10.4 s without (33 %, measured under load). With three values only (no coarser
/// estimate) the result is never accepted.
///
/// `previous_floor` is the level before's [`Level::brief_zone_floor`], which its estimate
/// keeps.
pub fn previous_estimate_agrees(
    values: &[f64],
    order: i32,
    tol: f64,
    floor: Floor,
    steps: usize,
    previous_floor: f64,
) -> bool {
    let n = values.len();
    tight(values, order)
        || (n >= 4
            && extrapolate(&values[..n - 1], order, floor, steps / 2)
                .1
                .max(previous_floor)
                <= 2f64.powi(order) * tol)
}

/// Refine a computation `run(level)` (resolution doubling each level from `base`) until the
/// error estimate of the result is ≤ `tol`. With `richardson`, the result is the extrapolated
/// value ([`extrapolate`]); otherwise the finest value with the conservative [`estimate`].
/// Returns `(value, estimate, resolution)`.
pub fn refine(
    base: Resolution,
    order: i32,
    tol: f64,
    richardson: bool,
    limits: Limits,
    run: impl FnMut(Resolution) -> Result<f64, PhysicsError>,
) -> Result<(f64, f64, Resolution), PhysicsError> {
    refine_observed(base, order, tol, richardson, limits, run, &mut |_| {})
}

/// One step of an automatic refinement, reported to the observer of [`refine_observed`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RefineEvent {
    /// Level `level` (0 for the first) is about to run at `resolution`.
    Started {
        /// Index of the level.
        level: u32,
        /// Its resolution.
        resolution: Resolution,
    },
    /// Level `level` has run; `estimate` is the error estimate of the result so far (`None`
    /// before three levels exist), to be compared with `tol`. The refinement stops at the first
    /// level whose estimate is accepted.
    Finished {
        /// Index of the level.
        level: u32,
        /// Its resolution.
        resolution: Resolution,
        /// Error estimate after this level (absolute error of `P`).
        estimate: Option<f64>,
        /// The tolerance asked for.
        tol: f64,
    },
}

/// [`refine`] that reports each level to `observer` ([`RefineEvent`]).
pub fn refine_observed(
    base: Resolution,
    order: i32,
    tol: f64,
    richardson: bool,
    limits: Limits,
    mut run: impl FnMut(Resolution) -> Result<f64, PhysicsError>,
    observer: &mut dyn FnMut(RefineEvent),
) -> Result<(f64, f64, Resolution), PhysicsError> {
    refine_core(
        base,
        (order, FLOOR),
        tol,
        richardson,
        limits,
        |res| run(res).map(Level::unwatched),
        observer,
    )
}

/// [`refine_observed`] with the floor of the Richardson estimate as a share of the last raw
/// difference (`(order, floor)`), which a law sets by how regularly it converges, and runs
/// that report how finely they resolved their zones: a level whose estimate is within `tol`
/// is accepted only where [`Level::resolved`].
pub(crate) fn refine_core(
    base: Resolution,
    (order, floor): (i32, Floor),
    tol: f64,
    richardson: bool,
    limits: Limits,
    mut run: impl FnMut(Resolution) -> Result<Level, PhysicsError>,
    observer: &mut dyn FnMut(RefineEvent),
) -> Result<(f64, f64, Resolution), PhysicsError> {
    let tol = positive("tol", tol)?;
    let mut values = Vec::new();
    // The brief-zone floor of the level before ([`Level::brief_zone_floor`]).
    let mut previous_floor = 0.0;
    let mut best = (f64::INFINITY, base);
    // The zone's steps where the last estimate was within `tol` but its level unresolved.
    let mut unresolved = f64::INFINITY;
    let unreachable =
        |(achieved, at): (f64, Resolution), zone_steps| PhysicsError::ToleranceUnreachable {
            tol,
            achieved,
            springs: at.springs,
            steps: at.steps,
            max_steps: limits.max_steps,
            zone_steps,
        };
    for k in 0.. {
        let res = base.doubled(k);
        if res.steps > limits.max_steps
            || work(res) > limits.max_work
            || memory_bytes(res, Scheme::Accurate) > limits.max_memory
        {
            return Err(unreachable(best, unresolved));
        }
        observer(RefineEvent::Started {
            level: k,
            resolution: res,
        });
        let level = run(res)?;
        values.push(level.p);
        let level_floor = level.brief_zone_floor(res.steps);
        if values.len() < 3 {
            observer(RefineEvent::Finished {
                level: k,
                resolution: res,
                estimate: None,
                tol,
            });
        } else {
            let (value, est) = if richardson {
                extrapolate(&values, order, floor, res.steps)
            } else {
                (values[values.len() - 1], estimate(&values, order))
            };
            let est = est.max(level_floor);
            observer(RefineEvent::Finished {
                level: k,
                resolution: res,
                estimate: Some(est),
                tol,
            });
            best = (est, res);
            unresolved = if est <= tol && !level.resolved() {
                level.shortest_zone
            } else {
                f64::INFINITY
            };
            if est <= tol
                && level.resolved()
                && (!richardson
                    || previous_estimate_agrees(
                        &values,
                        order,
                        tol,
                        floor,
                        res.steps,
                        previous_floor,
                    ))
            {
                return Ok((value, est, res));
            }
            // Stop before the expensive levels when even an optimistic rate (the nominal order
            // for a plain value, twice it for a Richardson value) cannot reach `tol` within the
            // limits: the seed scheme at 1e-6 would otherwise run for an hour before failing.
            let rate = 2f64.powi(if richardson { 2 * order } else { order });
            let more = ((est / tol).ln() / rate.ln()).ceil().clamp(1.0, 40.0) as u32;
            let target = Resolution {
                springs: res.springs.saturating_mul(1usize << more),
                steps: res.steps.saturating_mul(1usize << more),
            };
            if !limits.admits(target, Scheme::Accurate) {
                if unresolved.is_finite() {
                    // The estimate is within `tol`; only the zone asks for the next level.
                    return Err(unreachable(best, unresolved));
                }
                return Err(PhysicsError::Infeasible {
                    tol,
                    gamma: f64::NAN,
                    scheme: if order == 1 { "euler" } else { "accurate" },
                    springs: target.springs,
                    steps: target.steps,
                    work: work(target),
                    memory_mb: memory_bytes(target, Scheme::Accurate) / 1e6,
                    max_steps: limits.max_steps,
                    max_work: limits.max_work,
                    max_memory_mb: limits.max_memory / 1e6,
                });
            }
        }
        previous_floor = level_floor;
    }
    unreachable!("the refinement loop only exits by returning")
}

/// The ladder of one automatic refinement: its first level, the order of its scheme, the floor
/// of its Richardson estimate (a law's, [`crate::law::ContactLaw::FLOOR`]) and whether it
/// reports the Richardson value (else the finest value with the plain [`estimate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ladder {
    /// First level.
    pub start: Resolution,
    /// Order of convergence in the resolution.
    pub order: i32,
    /// Floor of the Richardson estimate.
    pub floor: Floor,
    /// Whether the Richardson value is reported.
    pub richardson: bool,
}

/// The refinement to `tol` of every solve, dimensionless ([`solve_core`]) or in physical units
/// ([`crate::units::PhysicalImpact::solve`]): refuses first what cannot fit the limits even in
/// the best case at `γ` ([`plan`]), then refines `run` along `ladder` ([`refine_core`]);
/// errors carry `γ`. Returns `(value, estimate, resolution)`.
pub(crate) fn refine_to(
    gamma: f64,
    tol: f64,
    (scheme, limits): (Scheme, Limits),
    ladder: Ladder,
    run: impl FnMut(Resolution) -> Result<Level, PhysicsError>,
    observer: &mut dyn FnMut(RefineEvent),
) -> Result<(f64, f64, Resolution), PhysicsError> {
    plan(gamma, tol, scheme, limits)?;
    refine_core(
        ladder.start,
        (ladder.order, ladder.floor),
        tol,
        ladder.richardson,
        limits,
        run,
        observer,
    )
    .map_err(|e| e.with_gamma(gamma))
}

/// The error-controlled driver shared by every law: checks the accuracy, answers `closed`
/// (a closed form, unless the simulation is forced), or refines `run` (`P` at a resolution)
/// to the tolerance, or runs a fixed resolution with its estimate. `γ` and `α` are checked;
/// the answer reports the law `law` at `e_n`.
pub(crate) fn solve_core(
    (gamma, accuracy, scheme, force_simulation, limits): (f64, Accuracy, Scheme, bool, Limits),
    (law, e_n): (LawParameters, f64),
    floor: Floor,
    closed: Option<f64>,
    mut run: impl FnMut(Resolution) -> Result<Level, PhysicsError>,
    observer: &mut dyn FnMut(RefineEvent),
) -> Result<Solution, PhysicsError> {
    match accuracy {
        Accuracy::Tolerance(tol) => {
            positive("tol", tol)?;
        }
        Accuracy::Fixed(res) => {
            check_fixed(res.validate()?, scheme, limits)?;
        }
    }
    if !force_simulation {
        if let Some(p) = closed {
            return Ok(Solution {
                p,
                error_estimate: 0.0,
                resolution: Resolution {
                    springs: 0,
                    steps: 0,
                },
                scheme,
                method: Method::ClosedForm,
                no_estimate: None,
                law,
                e_n,
            });
        }
    }
    let mut no_estimate = None;
    let (p, error_estimate, resolution) = match accuracy {
        Accuracy::Tolerance(tol) => {
            let ladder = Ladder {
                start: ladder_start(gamma, scheme),
                order: scheme.order(),
                floor,
                richardson: scheme.richardson(),
            };
            refine_to(gamma, tol, (scheme, limits), ladder, run, observer)?
        }
        Accuracy::Fixed(res) => {
            let res = res.validate()?;
            let level = run(res)?;
            let fine = level.p;
            let halved = |k: u32| Resolution {
                springs: res.springs >> k,
                steps: res.steps >> k,
            };
            let coarsest = halved(FIXED_HALVINGS);
            if (res.springs != 0 && coarsest.springs < 2) || coarsest.steps < 8 {
                no_estimate = Some(NoEstimate::TooCoarse {
                    springs: res.springs,
                    steps: res.steps,
                });
                (fine, f64::INFINITY, res)
            } else if !level.resolved() {
                no_estimate = Some(NoEstimate::Unresolved {
                    zone_steps: level.shortest_zone,
                    steps: res.steps,
                });
                (fine, f64::INFINITY, res)
            } else {
                let mut values = [fine; 4];
                for k in 1..=FIXED_HALVINGS {
                    values[k as usize] = run(halved(k))?.p;
                }
                match fixed_estimate(values, scheme.order()) {
                    // A brief zone before gross slip scatters `P` beyond what the halved runs
                    // show ([`Level::brief_zone_floor`]).
                    Ok(est) => (fine, est.max(level.brief_zone_floor(res.steps)), res),
                    Err(differences) => {
                        no_estimate = Some(NoEstimate::NotAsymptotic { differences });
                        (fine, f64::INFINITY, res)
                    }
                }
            }
        }
    };
    Ok(Solution {
        // Friction and damping only dissipate: |P| ≤ 1 exactly (elastic: 7ΔE/(m u0²) = P² − 1).
        // The discrete value or its Richardson extrapolation can overshoot by up to its error
        // near P = ±1 (γ ≈ 1: −1 − 9e-7 at 128 steps). Projecting onto [−1, 1] never moves it
        // away from the true value, so the error estimate (computed from the unprojected
        // values) still holds.
        p: p.clamp(-1.0, 1.0),
        error_estimate,
        resolution,
        scheme,
        method: Method::Simulated,
        no_estimate,
        law,
        e_n,
    })
}

/// Refuse a fixed resolution beyond the limits (work, memory) before running it.
fn check_fixed(res: Resolution, scheme: Scheme, limits: Limits) -> Result<(), PhysicsError> {
    let unbounded = Limits {
        max_steps: usize::MAX,
        ..limits
    };
    if unbounded.admits(res, scheme) {
        Ok(())
    } else {
        Err(PhysicsError::TooLarge {
            springs: res.springs,
            steps: res.steps,
            work: work(res),
            memory_mb: memory_bytes(res, scheme) / 1e6,
            max_work: limits.max_work,
            max_memory_mb: limits.max_memory / 1e6,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The estimate of a plain (not extrapolated) value on two measured ladders of the continuum
    /// row (64 → 8192 steps), against P at tol 1e-11: never below the error of the last value
    /// from the third level on. Both ladders broke the former estimate (the last difference, at
    /// least the previous one over 2^p): by 1.11× at 1024 steps on the first (the differences
    /// shrink by 1.3 and 1.6 only), by 1.57× at 1024 steps on the second (the differences turn).
    #[test]
    fn the_estimate_of_a_plain_value_covers_slow_and_turning_convergence() {
        let ladders: [(&str, [f64; 8], f64); 2] = [
            (
                "γ 1.6202, α 3.4290",
                [
                    0.023197169646998,
                    0.023437762010608,
                    0.023442123590484,
                    0.023441984554197,
                    0.023441899892503,
                    0.023441823283756,
                    0.023441812484285,
                    0.023441807343223,
                ],
                0.023441805732072364,
            ),
            (
                "γ 1.7498, α 1.2474",
                [
                    0.141262371837329,
                    0.141285597492546,
                    0.141299566602798,
                    0.141299410708446,
                    0.141299467857392,
                    0.141299534744647,
                    0.141299551754288,
                    0.141299556583659,
                ],
                0.141299557669659,
            ),
        ];
        for (name, values, truth) in ladders {
            for n in 3..=values.len() {
                let err = (values[n - 1] - truth).abs();
                let est = estimate(&values[..n], 2);
                assert!(
                    est >= err,
                    "{name}, level {}: estimate {est:e} < error {err:e}",
                    n - 1
                );
            }
        }
    }

    /// The steady share applies only where the last three ratios are within 3.8–4.2: a ladder
    /// `C/N²` is steady from its fifth value on, one ratio off by 6 % (or a turn) is not, and a
    /// steady ladder's estimate is the larger of the steady share and the difference of its
    /// Richardson values.
    #[test]
    fn only_three_ratios_near_the_order_are_steady() {
        let ladder: Vec<f64> = (0..6).map(|k| 0.5 + 1e-3 / 4f64.powi(k)).collect();
        assert!(!steady(&ladder[..4], 2));
        assert!(steady(&ladder[..5], 2));
        assert!(steady(&ladder, 2));
        let mut off = ladder.clone();
        off[3] = 0.5 + 1e-3 / 4f64.powi(3) * 1.25; // ratios 3.2 and 5.0 around it
        assert!(!steady(&off[..5], 2));
        assert!(!steady(&off, 2));
        let mut turn = ladder.clone();
        turn[5] = turn[4] + 1e-6;
        assert!(!steady(&turn, 2));
        let floor = Floor {
            regular: 0.1,
            steady: 0.05,
            tight: 0.05,
            irregular: 0.2,
            scatter: 0.0,
        };
        let (_, est) = extrapolate(&ladder, 2, floor, 512);
        let last = (ladder[5] - ladder[4]).abs();
        assert!((est - 0.05 * last).abs() < 1e-3 * est, "{est:e} {last:e}");
        let (_, est) = extrapolate(&ladder[..4], 2, floor, 64);
        assert!((est - 0.1 * (ladder[3] - ladder[2]).abs()).abs() < 1e-3 * est);
    }

    /// The tight share applies only where the last three ratios are within 1 % of 4, and such
    /// a level passes the acceptance guard whatever the estimate of the level before it: a
    /// ladder `C/N²` with ratios 4.06 is steady but not tight, and its estimate keeps the
    /// steady share.
    #[test]
    fn only_three_ratios_within_one_per_cent_of_the_order_are_tight() {
        let floor = Floor {
            regular: 0.1,
            steady: 0.1,
            tight: 0.01,
            irregular: 0.2,
            scatter: 0.0,
        };
        let ladder = |q: f64| -> Vec<f64> { (0..6).map(|k| 0.5 + 1e-3 / q.powi(k)).collect() };
        let exact = ladder(4.0);
        assert!(!tight(&exact[..4], 2));
        assert!(tight(&exact[..5], 2) && tight(&exact, 2));
        let last = (exact[5] - exact[4]).abs();
        let (_, est) = extrapolate(&exact, 2, floor, 512);
        assert!((est - 0.01 * last).abs() < 1e-3 * est, "{est:e} {last:e}");
        // Tight from a first ratio of 3.5 on: the level before is regular only and states 0.1
        // of a difference four times larger, above 4 tol for a tol just above this level's
        // estimate, and the level is accepted anyway.
        let mut late = vec![0.5, 0.5 + 3.5e-3];
        for k in 0..4 {
            late.push(late[late.len() - 1] + 1e-3 / 4f64.powi(k));
        }
        assert!(tight(&late, 2) && !tight(&late[..5], 2) && !steady(&late[..5], 2));
        let (_, est) = extrapolate(&late, 2, floor, 512);
        let tol = 1.01 * est;
        assert!(extrapolate(&late[..5], 2, floor, 256).1 > 4.0 * tol);
        assert!(previous_estimate_agrees(&late, 2, tol, floor, 512, 0.0));
        let off = ladder(4.06);
        assert!(steady(&off, 2) && !tight(&off, 2));
        let (_, est) = extrapolate(&off, 2, floor, 512);
        assert!(est >= 0.1 * (off[5] - off[4]).abs(), "{est:e}");
        assert!(!previous_estimate_agrees(&off, 2, est, floor, 512, 0.0));
    }
}
