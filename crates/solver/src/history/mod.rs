//! The gross-slip history of one impact, and the fold curves of `P(γ, α)` it reveals.
//!
//! *Gross slip* is the whole contact at the Coulomb limit: `F_t = ±μ F_N`. Where the sequence
//! of gross-slip episodes changes as `α` varies, `P` is not smooth. When an episode strictly
//! inside the contact shrinks to nothing (a *fold*), `P` has a jump of slope: at γ = 3.2 the
//! slope `dP/d ln α` goes from −0.90 to −0.32 across α = 1.3431, where a `+μF_N` episode at
//! t ≈ 0.86 t_c vanishes (`docs/solver.md`, "Kink curves"). Such curves limit how well a table
//! can interpolate `P`; this module finds them.
//!
//! Dimensionless units as in [`crate::Request::simulate`]: `m* = R* = E* = v_z0 = 1`,
//! `u0 = 1`, so `μ = α` and `F_N = (4/3) d^{3/2}`; times are fractions of the contact time `t_c`.

use super::error::PhysicsError;
use super::hertz::NormalTrajectory;
use super::impact::{
    check_alpha, check_gamma, dimensionless_normal, mean_sqrt, run_contact, run_contact_with,
    ContactPoint, TangentialBodies, ALPHA_NO_SLIP,
};
use super::model::{StepEnd, TangentialModel};
use super::springs::{StepMotion, StepResult};

mod damped;
mod plastic;
pub use damped::{
    end_minus_at_e, end_minus_at_e_within, fold_minus_at_e, fold_minus_birth_e,
    fold_minus_free_below, fold_minus_scan_e, friction_ratio_e, has_plus_interlude_e,
    plus_interlude_edge_e, plus_interlude_edge_e_within, restitution_minus_edges_e,
    restitution_minus_somewhere_e, slip_history_e, zone_runs_e, INTERLUDE_LONG, INTERLUDE_MIN,
};
pub use plastic::{
    end_minus_at_thornton_within, end_minus_edges_thornton, end_minus_sheet_edges_thornton,
    ends_in_full_slip_thornton, fold_minus_at_thornton, fold_minus_free_below_thornton,
    fold_minus_thornton, full_slip_edge_thornton, has_loading_zone_thornton, has_reslip_thornton,
    has_switch_zone_thornton, loading_band_thornton, loading_band_top_within_thornton,
    loading_fold_thornton, reslip_fold_thornton, restitution_plus_change_thornton,
    restitution_plus_strip_thornton, slip_history_thornton, slip_pattern_thornton,
    slip_zones_thornton, switch_fold_thornton, switch_sheet_edges_thornton, switch_sheet_thornton,
    switch_zones_thornton, ZoneSnapshot, FOLD_MINUS_BIRTH_MARGIN, FOLD_MINUS_SCAN,
    LOADING_BAND_MIN, LOADING_BAND_SCAN, LOADING_ZONE_MIN, PLUS_STRIP_MAX, SWITCH_FOLD_MAX,
    SWITCH_ZONE_MIN,
};

/// Direction of the friction force during a gross-slip episode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlipSign {
    /// `F_t = +μ F_N` (opposing a positive slip velocity, as at the start of the impact).
    Plus,
    /// `F_t = −μ F_N`.
    Minus,
}

/// One gross-slip episode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Episode {
    /// Direction of the friction force.
    pub sign: SlipSign,
    /// Start, as a fraction of the contact time `t_c` (midpoint of the first step in gross slip).
    pub start: f64,
    /// End, as a fraction of `t_c` (midpoint of the last step in gross slip).
    pub end: f64,
}

/// The gross-slip episodes of one impact and its `P`.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipHistory {
    /// Episodes in time order. Two steps in gross slip of the same sign separated by less than
    /// [`MERGE_GAP`] `t_c` belong to the same episode.
    pub episodes: Vec<Episode>,
    /// Tangential restitution `P` of the same run (fixed resolution, not extrapolated).
    pub p: f64,
}

/// Gaps shorter than this (fraction of `t_c`) do not split an episode: near the separation the
/// graded substeps sample the ratio `F_t/(μF_N)` so finely that its rounding flickers.
pub const MERGE_GAP: f64 = 0.01;

/// A step is in gross slip when `|F_t| ≥ (1 − SLIP_THRESHOLD) μ F_N`, with `F_t` the step's
/// mean friction force and `μ F_N` averaged over the step by the stepper's own product rule.
pub const SLIP_THRESHOLD: f64 = 1e-6;

/// The contact point of [`crate::Request::simulate`], recording the mean friction force
/// of every step.
struct Recorder {
    point: ContactPoint,
    t: f64,
    /// `(start time, length, mean friction force)` of every step.
    log: Vec<(f64, f64, f64)>,
}

impl TangentialBodies for Recorder {
    fn slip_velocity(&self) -> f64 {
        self.point.slip_velocity()
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        self.point.slip_acceleration(f)
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.point.kick(h, f);
        self.log.push((self.t, h, f));
        self.t += h;
    }
}

/// A row that calls `log` with itself and the step after every step it takes, and is otherwise
/// the row: the histories of the dissipative laws record what their own rows know.
struct LoggedRow<R, F> {
    row: R,
    log: F,
}

impl<R: TangentialModel, F: FnMut(&R, &StepMotion, f64)> TangentialModel for LoggedRow<R, F> {
    const END_STATE: bool = R::END_STATE;
    const LOCATES_GROSS_SLIP: bool = R::LOCATES_GROSS_SLIP;
    #[inline(always)]
    fn at_limit(&self) -> (bool, bool) {
        self.row.at_limit()
    }
    #[inline(always)]
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let r = self.row.step_accurate(m, d1, c);
        (self.log)(&self.row, m, d1);
        r
    }
    #[inline(always)]
    fn touch_mean(&self, slip_velocity: f64, rate0: f64, c: f64) -> f64 {
        self.row.touch_mean(slip_velocity, rate0, c)
    }
    #[inline(always)]
    fn close_step<B: TangentialBodies>(&self, bodies: &mut B, end: &StepEnd) -> (f64, f64) {
        self.row.close_step(bodies, end)
    }
    #[inline(always)]
    fn release_time(&self, m: &StepMotion, c: f64) -> Option<f64> {
        self.row.release_time(m, c)
    }
    #[inline(always)]
    fn jump(&mut self, start: (f64, f64), end: (f64, f64), c: f64) -> Option<StepResult> {
        self.row.jump(start, end, c)
    }
}

/// Indentation at time `t` (s) by linear interpolation between the grid nodes.
fn indentation_at(nt: &NormalTrajectory, t: f64) -> f64 {
    let steps = nt.indentation.len() - 1;
    let x = (t / nt.dt).max(0.0);
    let j = (x.floor() as usize).min(steps - 1);
    let s = x - j as f64;
    nt.indentation[j] * (1.0 - s) + nt.indentation[j + 1] * s
}

/// The checked `(γ, α)` of a gross-slip history: `γ` finite and positive, `α` finite and
/// positive (with `α = ∞` or above [`ALPHA_NO_SLIP`] nothing ever slips, so that is refused as
/// meaningless here), `steps ≥ 8`.
fn check_history_input(gamma: f64, alpha: f64, steps: usize) -> Result<(f64, f64), PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let alpha = check_alpha(alpha)?;
    if !(alpha > 0.0 && alpha <= ALPHA_NO_SLIP) {
        return Err(PhysicsError::InvalidParameter {
            name: "alpha",
            value: alpha,
            allowed: "> 0 and <= 1e10 (above, the impact is simulated as no slip)",
        });
    }
    if steps < 8 {
        return Err(PhysicsError::InvalidParameter {
            name: "steps",
            value: steps as f64,
            allowed: ">= 8",
        });
    }
    Ok((gamma, alpha))
}

/// Run one impact with the continuum row on `steps` steps and record its gross-slip episodes.
///
/// `γ` must be finite and positive, `α` finite and positive (with `α = ∞` or above
/// [`ALPHA_NO_SLIP`] nothing ever slips, so that is refused as meaningless here), `steps ≥ 8`.
pub fn slip_history(gamma: f64, alpha: f64, steps: usize) -> Result<SlipHistory, PhysicsError> {
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let shear = 2.0 / 7.0 * gamma * gamma;
    let nt = dimensionless_normal(steps);
    let mut rec = Recorder {
        point: ContactPoint { u: 1.0 },
        t: 0.0,
        log: Vec::with_capacity(steps + steps / 8),
    };
    run_contact(&mut rec, &*nt, 0, 1.0, shear, alpha / shear);
    let mut episodes: Vec<Episode> = Vec::new();
    for &(t, h, f) in &rec.log {
        // The Coulomb limit of the step's mean force, by the product rule the stepper uses for
        // the impulse: μ F_N = (4/3) μ √d · d, averaged as mean(√d) · (d₀ + d₁)/2.
        let d0 = indentation_at(&nt, t).max(0.0);
        let d1 = indentation_at(&nt, t + h).max(0.0);
        let root_mean = mean_sqrt(d0, d1);
        if root_mean <= 0.0 {
            continue;
        }
        let limit = alpha * 2.0 / 3.0 * root_mean * (d0 + d1);
        record_step(&mut episodes, t + 0.5 * h, f / limit, nt.contact_time);
    }
    Ok(SlipHistory {
        episodes,
        p: rec.point.u,
    })
}

/// Add one step, its midpoint at time `t` (s) and its friction force `q` times the Coulomb
/// limit, to the episodes of a contact of duration `contact_time` (s): a step in gross slip
/// ([`SLIP_THRESHOLD`]) extends the last episode of its sign within [`MERGE_GAP`] or opens one.
fn record_step(episodes: &mut Vec<Episode>, t: f64, q: f64, contact_time: f64) {
    let sign = if q >= 1.0 - SLIP_THRESHOLD {
        SlipSign::Plus
    } else if q <= -(1.0 - SLIP_THRESHOLD) {
        SlipSign::Minus
    } else {
        return;
    };
    let tau = t / contact_time;
    match episodes.last_mut() {
        Some(e) if e.sign == sign && tau - e.end < MERGE_GAP => e.end = tau,
        _ => episodes.push(Episode {
            sign,
            start: tau,
            end: tau,
        }),
    }
}

impl SlipHistory {
    /// Whether an episode of `sign` starts within `window` (fractions of `t_c`, inclusive) and
    /// ends before [`INTERIOR_END`] `t_c`, i.e. strictly inside the contact.
    pub fn has_interior(&self, sign: SlipSign, window: (f64, f64)) -> bool {
        self.episodes.iter().any(|e| {
            e.sign == sign && e.start >= window.0 && e.start <= window.1 && e.end < INTERIOR_END
        })
    }
}

/// Episodes that reach past this fraction of `t_c` run into the separation (the final release of
/// the shrinking contact) and are not interior.
pub const INTERIOR_END: f64 = 0.97;

/// Locate by bisection, at a fixed number of `steps`, the `α` in `[alpha_lo, alpha_hi]` at which
/// `present(history)` changes. `present` must differ at the two ends; the result is the midpoint
/// of the last bracket, after `iterations` halvings (in `ln α`).
pub fn locate_change(
    gamma: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    steps: usize,
    iterations: usize,
    present: impl Fn(&SlipHistory) -> bool,
) -> Result<Option<f64>, PhysicsError> {
    locate_change_with(
        |a| slip_history(gamma, a, steps),
        (alpha_lo, alpha_hi),
        iterations,
        present,
    )
}

/// [`locate_change`] for the histories `history(α)` of any law at a fixed γ and resolution.
fn locate_change_with(
    history: impl Fn(f64) -> Result<SlipHistory, PhysicsError>,
    (alpha_lo, alpha_hi): (f64, f64),
    iterations: usize,
    present: impl Fn(&SlipHistory) -> bool,
) -> Result<Option<f64>, PhysicsError> {
    let at_lo = present(&history(alpha_lo)?);
    let at_hi = present(&history(alpha_hi)?);
    if at_lo == at_hi {
        return Ok(None);
    }
    bisect_change(history, (alpha_lo, alpha_hi), at_lo, iterations, present).map(Some)
}

/// The edge of a predicate between `lo`, where it holds, and `hi`, where it fails: the bracket
/// halved until it is at most `width` wide, then its midpoint (the locators of the switch sheet,
/// of Thornton's folds in `ln α`, and of the Kelvin–Voigt `+` interlude along `e_n`).
pub(crate) fn bisect_edge(
    (mut lo, mut hi): (f64, f64),
    width: f64,
    holds: impl Fn(f64) -> Result<bool, PhysicsError>,
) -> Result<f64, PhysicsError> {
    while hi - lo > width {
        let mid = 0.5 * (lo + hi);
        if holds(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The bisection of [`locate_change_with`] on a bracket whose ends are known to differ, the
/// predicate `at_lo` at its lower end: `iterations` halvings in `ln α`, the midpoint of the last
/// bracket.
fn bisect_change(
    history: impl Fn(f64) -> Result<SlipHistory, PhysicsError>,
    (alpha_lo, alpha_hi): (f64, f64),
    at_lo: bool,
    iterations: usize,
    present: impl Fn(&SlipHistory) -> bool,
) -> Result<f64, PhysicsError> {
    let (mut lo, mut hi) = (alpha_lo.ln(), alpha_hi.ln());
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if present(&history(mid.exp())?) == at_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((0.5 * (lo + hi)).exp())
}

/// The time window (fractions of `t_c`) in which the `+μF_N` episode of the fold curve F₊ starts:
/// the restitution phase (`t > t_c/2`) up to [`INTERIOR_END`]. It excludes the `+` episode that
/// opens every slipping impact (`0 .. ≈0.1–0.27 t_c` for γ ≈ 2.9–3.5); measured on a 300-point
/// α grid over `[0.3 α_c2, α_c2]`, γ = 2.85 … 3.6 (2048 steps), at most one `+` episode ever lies
/// in it, starting at 0.79–0.97 t_c.
pub const RESTITUTION_WINDOW: (f64, f64) = (0.5, INTERIOR_END);

/// The predicate of the fold curve F₊: an interior `+μF_N` episode starts in the restitution
/// phase ([`RESTITUTION_WINDOW`]) and ends before [`INTERIOR_END`]. It holds on an interval of
/// α below F₊ and fails just above it.
pub fn has_restitution_plus(h: &SlipHistory) -> bool {
    h.has_interior(SlipSign::Plus, RESTITUTION_WINDOW)
}

/// The earliest end (fraction of `t_c`) of a `+` episode starting in [`RESTITUTION_WINDOW`], or
/// 1 if there is none: [`has_restitution_plus`] holds exactly when this is below
/// [`INTERIOR_END`]. Used to find where the episode first exists as γ grows.
fn restitution_plus_end(h: &SlipHistory) -> f64 {
    h.episodes
        .iter()
        .filter(|e| {
            e.sign == SlipSign::Plus
                && e.start >= RESTITUTION_WINDOW.0
                && e.start <= RESTITUTION_WINDOW.1
        })
        .map(|e| e.end)
        .fold(1.0, f64::min)
}

/// Fewest steps the fold tracer accepts: below, the episode near 0.97 t_c is a handful of steps.
pub const FOLD_MIN_STEPS: usize = 256;

/// The γ bracket searched for the birth of F₊ (the predicate fails at its low end and holds
/// somewhere at its high end for every resolution from 1024 steps up).
pub const FOLD_BIRTH_BRACKET: (f64, f64) = (2.8, 3.0);

/// Bisections in γ of [`fold_plus_birth`]: `0.2 / 2^18 ≈ 7.6e-7`.
const BIRTH_BISECTIONS: usize = 18;

/// Bisections in `ln α` when locating a point of F₊: from a bracket of at most ~0.1 to ~1e-10.
const FOLD_BISECTIONS: usize = 30;

/// How closely (in `ln α`) the public functions that locate a fold or the end-of-contact curve
/// by continuation bisect the change of their predicate at a fixed resolution: far below the
/// resolution's own error (about 1e-5 relative at 2048 steps), so that the located value is
/// the resolution's to the last digits printed.
pub const LOCATE_LN_ALPHA: f64 = 1e-10;

fn check_fold_steps(steps: usize) -> Result<usize, PhysicsError> {
    if steps < FOLD_MIN_STEPS {
        return Err(PhysicsError::InvalidParameter {
            name: "steps",
            value: steps as f64,
            allowed: ">= 256 (the fold's episode must span several steps)",
        });
    }
    Ok(steps)
}

fn log_grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| (lo.ln() + (hi / lo).ln() * i as f64 / n as f64).exp())
}

/// Some `α` at which [`has_restitution_plus`] holds at this γ, if the search finds one: a
/// 32-interval log grid over `[0.5 α_c2, α_c2]` (where F₊ is born, at ≈ 0.86 α_c2), then three
/// zooms of 12 intervals around the α where the episode ends earliest. Near the birth the set
/// of such α is a short interval around that minimum, which the zooms follow.
fn restitution_plus_somewhere(gamma: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    let c2 = oblique_physics::regimes::alpha_c2(gamma);
    let (mut lo, mut hi, mut n) = (0.5 * c2, c2, 32);
    for _ in 0..4 {
        let mut best = (f64::INFINITY, lo);
        let xs: Vec<f64> = log_grid(lo, hi, n).collect();
        for &x in &xs {
            let end = restitution_plus_end(&slip_history(gamma, x, steps)?);
            if end < INTERIOR_END {
                return Ok(Some(x));
            }
            if end < best.0 {
                best = (end, x);
            }
        }
        let h = (hi / lo).ln() / n as f64;
        lo = (best.1.ln() - 2.0 * h).exp();
        hi = (best.1.ln() + 2.0 * h).exp();
        n = 12;
    }
    Ok(None)
}

/// The birth point `(γ_b, α_b)` of the fold curve F₊ at a fixed number of `steps` (continuum
/// row): the smallest γ in [`FOLD_BIRTH_BRACKET`] at which [`has_restitution_plus`] holds for
/// some α, located by bisection in γ to ≈ 8e-7 (18 halvings; each trial γ scans α as in
/// `restitution_plus_somewhere`, ≤ 72 runs). `α_b` is where the episode was found at the upper
/// end of the last bracket. `None` if the bracket does not straddle the birth (too few steps).
///
/// Measured (`docs/solver.md`, "Kink curves"): γ_b = 2.901570, 2.901666, 2.901708 and
/// α_b = 2.0670, 2.0672, 2.0672 (0.859 α_c2) with 1024, 2048, 4096 steps. This is where the
/// earliest end of the restitution episode over α first drops below [`INTERIOR_END`] = 0.97 t_c,
/// so γ_b moves with that threshold: it is the birth of the *predicate*. For γ_b < γ ≲ 2.905 the
/// upper α edge of the predicate is the episode's end crossing 0.97 t_c (no slope jump of `P`);
/// from γ ≈ 2.906 on it is the episode shrinking to zero length inside the contact, the fold
/// proper (see [`fold_plus_curve`]).
///
/// Cost: 0.5 s, 1.3 s, 3.6 s with 1024, 2048, 4096 steps (20 trial γ of ≤ 72 runs each;
/// linear in `steps`).
pub fn fold_plus_birth(steps: usize) -> Result<Option<(f64, f64)>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    let (mut g_lo, mut g_hi) = FOLD_BIRTH_BRACKET;
    if restitution_plus_somewhere(g_lo, steps)?.is_some() {
        return Ok(None);
    }
    let Some(mut alpha_b) = restitution_plus_somewhere(g_hi, steps)? else {
        return Ok(None);
    };
    for _ in 0..BIRTH_BISECTIONS {
        let mid = 0.5 * (g_lo + g_hi);
        match restitution_plus_somewhere(mid, steps)? {
            Some(a) => {
                g_hi = mid;
                alpha_b = a;
            }
            None => g_lo = mid,
        }
    }
    Ok(Some((g_hi, alpha_b)))
}

/// One-sided slopes `dP/d ln α` just below and just above `alpha` (differences over
/// `1e-4` in `ln α`, starting `1e-9` away), at γ and a fixed number of steps: `(left, right)`.
/// Across F₊, `right − left` is the slope jump (positive: `P(α)` flattens).
pub fn one_sided_slopes(gamma: f64, alpha: f64, steps: usize) -> Result<(f64, f64), PhysicsError> {
    let p = |a: f64| slip_history(gamma, a, steps).map(|h| h.p);
    let e = 1e-4_f64;
    let (l, r) = (alpha * (-1e-9_f64).exp(), alpha * 1e-9_f64.exp());
    let left = (p(l)? - p(l * (-e).exp())?) / e;
    let right = (p(r * e.exp())? - p(r)?) / e;
    Ok((left, right))
}

/// One point of the fold curve F₊.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoldPoint {
    /// Material group γ.
    pub gamma: f64,
    /// Friction group `α_F` where the restitution `+μF_N` episode disappears as α grows.
    pub alpha: f64,
    /// Jump of `dP/d ln α` across `α_F` ([`one_sided_slopes`], right minus left).
    pub slope_jump: f64,
    /// The episode just below `α_F` ([`BELOW_FOLD`] in `ln α`; start, end in fractions of
    /// `t_c`): of zero length on the fold proper, ending at [`INTERIOR_END`] on the threshold
    /// edge just above the birth.
    pub episode: Option<Episode>,
}

/// How far below `α_F` (in `ln α`) [`FoldPoint::episode`] is read. On the fold proper the
/// episode is one step that touches the limit; where the stepper splits a step at the onset of
/// gross slip ([`crate::model::TangentialModel::LOCATES_GROSS_SLIP`]) whether that step counts
/// flickers within about 1e-8 of `α_F` (at γ = 3.5, 1024 steps: none at 1e-9 below the located
/// fold, one at 1e-7, 1e-5 and 1e-3 below).
pub const BELOW_FOLD: f64 = 1e-7;

/// The fold curve F₊ at a fixed number of steps.
#[derive(Debug, Clone, PartialEq)]
pub struct FoldCurve {
    /// Birth point `(γ_b, α_b)` ([`fold_plus_birth`]).
    pub birth: (f64, f64),
    /// Steps per contact time of every run.
    pub steps: usize,
    /// Points at γ increasing from γ_b (the first is the birth point itself, slope jump measured
    /// there); empty when the requested `γ_max` is below γ_b.
    pub points: Vec<FoldPoint>,
}

/// Locate F₊ at `gamma` by continuation from `guess` (the fold at a nearby γ, or the birth α):
/// step from `guess` in `ln α` (first step 1e-3, doubling) upwards while the predicate holds,
/// or downwards while it fails, until it changes; then bisect with [`locate_change`] to ≈1e-10
/// in `ln α`. `None` if no change is found within a factor `e^{±1}` of `guess`.
pub fn fold_plus_at(gamma: f64, guess: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    fold_at(gamma, guess, steps, has_restitution_plus)
}

/// The predicate of the fold curve F₋: an interior `−μF_N` episode starts in the restitution
/// phase ([`RESTITUTION_WINDOW`]) and ends before [`INTERIOR_END`]. It holds on an interval of
/// α below F₋ (from where the episode stops running into the separation: at γ = 2.45,
/// α = 0.4832 to F₋ at 0.5002, 2048 steps) and fails just above it.
pub fn has_restitution_minus(h: &SlipHistory) -> bool {
    h.has_interior(SlipSign::Minus, RESTITUTION_WINDOW)
}

/// Locate the fold curve F₋ (`docs/solver.md`, "Kink curves": a `−μF_N` episode at
/// t ≈ 0.8–0.94 t_c vanishes as α grows; γ ≳ 2.39) at `gamma` by continuation from `guess`, as
/// [`fold_plus_at`] does with [`has_restitution_minus`]. The guess must lie below F₋ within the
/// predicate's interval, or above F₋ (within a factor `e`): from below that interval the
/// continuation finds nothing (`None`).
pub fn fold_minus_at(gamma: f64, guess: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    fold_at(gamma, guess, steps, has_restitution_minus)
}

/// The predicate of the end-of-contact curve E₋: the impact's last gross-slip episode is a
/// `−μF_N` one that runs into the separation (ends after [`INTERIOR_END`]). As α grows the
/// friction force no longer reaches the limit as the contact shrinks to nothing, and the
/// episode vanishes at the separation: it holds below E₋ and fails just above it. E₋ runs from
/// α → ∞ at γ ≈ 1.732 through the stick patch (α = 20.87 at γ = 1.74, 1.3234 at 1.87), crosses
/// α_c2 at γ ≈ 1.907 and goes on through the partial-slip patch (0.8699 at γ = 2.0, 0.5766 at
/// 2.3) to F₋'s birth near γ = 2.40 (`docs/solver.md`, "Kink curves"). P has no slope jump
/// there, but a cubic across it errs more than its neighbours predict.
pub fn has_end_minus(h: &SlipHistory) -> bool {
    h.episodes
        .last()
        .is_some_and(|e| e.sign == SlipSign::Minus && e.end > INTERIOR_END)
}

/// Locate the end-of-contact curve E₋ ([`has_end_minus`]) at `gamma` by continuation from
/// `guess`, as [`fold_plus_at`] does. The guess must lie below E₋ or above it within a factor
/// `e`; `None` when no change is found there (at γ below ≈ 1.732 E₋ does not exist).
pub fn end_minus_at(gamma: f64, guess: f64, steps: usize) -> Result<Option<f64>, PhysicsError> {
    fold_at(gamma, guess, steps, has_end_minus)
}

/// The continuation of [`fold_plus_at`] for a fold whose `present` predicate holds below it.
fn fold_at(
    gamma: f64,
    guess: f64,
    steps: usize,
    present: fn(&SlipHistory) -> bool,
) -> Result<Option<f64>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    fold_at_with(
        |a| slip_history(gamma, a, steps),
        guess,
        present,
        LOCATE_LN_ALPHA,
    )
}

/// [`fold_at`] for the histories `history(α)` of any law at a fixed γ and resolution, the
/// change located to `ln_tol` in `ln α` ([`LOCATE_LN_ALPHA`] for the public functions).
fn fold_at_with(
    history: impl Fn(f64) -> Result<SlipHistory, PhysicsError>,
    guess: f64,
    present: fn(&SlipHistory) -> bool,
    ln_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    let at = |a: f64| history(a).map(|h| present(&h));
    let holds = at(guess)?;
    let (mut near, mut d) = (guess, 1e-3_f64);
    while d < 1.0 {
        // Below the fold the predicate holds: look up from a point where it holds, down from
        // one where it fails.
        let far = if holds {
            near * d.exp()
        } else {
            near * (-d).exp()
        };
        if at(far)? != holds {
            // The predicate holds at the lower end of the bracket (both ends are known).
            let bracket = if holds { (near, far) } else { (far, near) };
            let iterations = ((bracket.1 / bracket.0).ln() / ln_tol)
                .log2()
                .ceil()
                .max(1.0);
            return bisect_change(
                &history,
                bracket,
                true,
                (iterations as usize).min(FOLD_BISECTIONS + 20),
                present,
            )
            .map(Some);
        }
        near = far;
        d *= 2.0;
    }
    Ok(None)
}

/// [`fold_plus_at`] with `steps` and `2 steps`, extrapolated (Richardson, second order):
/// `a₂ₛ + (a₂ₛ − aₛ)/3`. `None` if either resolution does not find the fold.
pub fn fold_plus_at_extrapolated(
    gamma: f64,
    guess: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let coarse = fold_plus_at(gamma, guess, steps)?;
    let fine = fold_plus_at(gamma, coarse.unwrap_or(guess), 2 * steps)?;
    Ok(match (coarse, fine) {
        (Some(c), Some(f)) => Some(f + (f - c) / 3.0),
        _ => None,
    })
}

/// The fold curve F₊ at `n` points of γ evenly spaced over `[γ_b, gamma_max]` (`n ≥ 2`), by
/// continuation from the birth point ([`fold_plus_birth`], [`fold_plus_at`]), each `α_F`
/// located to ≈1e-10 relative at `steps` steps, with its slope jump.
///
/// Measured at 2048 steps (`docs/solver.md`, "Kink curves"):
/// - `α_F` converges in the steps at second order: at γ = 3.2, 1.3430746, 1.3430906, 1.3430955,
///   1.3430969, 1.3430973 with 1024 … 16384 steps. Richardson over two step counts
///   ([`fold_plus_at_extrapolated`]) gains 10–30×: from 2048/4096 steps it is within 2e-7 of the
///   16384-step extrapolation at γ = 2.95, 3.2, 3.5, where 2048 steps alone are off by ≤ 1.3e-5.
/// - Near the birth `α_F` first *rises*: `α_F − α_b` = 2.1e-3, 4.9e-3, 1.43e-2, 4.18e-2 at
///   `γ − γ_b` = 1e-6, 1e-5, 1e-4, 1e-3, i.e. `∝ (γ − γ_b)^p` with p = 0.47 (0.38 from the two
///   closest points, where the staircase of step times matters): a square root, as the earliest
///   end of the episode has a quadratic minimum in α. These points are the threshold edge (the
///   episode ends at 0.9700 t_c, slope jump ≤ 0.002). At γ ≈ 2.906 (α ≈ 2.14) the fold proper
///   takes over: the episode vanishes at 0.969 t_c, and `α_F` then decreases monotonically
///   (2.1098 at 2.9117, 1.7574 at 3.0017, 0.9982 at 3.5017).
/// - The slope jump of `dP/d ln α` across the fold proper: 0.070 (γ = 2.9067), 0.120 (2.9117),
///   0.188 (2.9217), 0.316 (2.9517), 0.431 (3.0017), 0.542 (3.1017), 0.565 (3.2017), 0.575
///   (3.3017), 0.554 (3.4017), 0.524 (3.5017). Near its start the *square* of the jump is linear
///   in γ (≈ 2.0 (γ − 2.9042)), so the fold proper is born with zero jump at γ* ≈ 2.904, where its
///   episode vanishes at ≈ 0.98 t_c, beyond [`INTERIOR_END`]; this predicate sees it only from
///   ≈ 2.906 on.
///
/// Errors: γ_max not finite or ≤ 0, `n < 2`, `steps < 256`; [`PhysicsError::NotFound`] when
/// the birth or a point of the curve is not found (e.g. γ_max far beyond 3.5, where F₊ leaves
/// the bracket of the continuation).
pub fn fold_plus_curve(gamma_max: f64, n: usize, steps: usize) -> Result<FoldCurve, PhysicsError> {
    let gamma_max = check_gamma(gamma_max)?;
    if n < 2 {
        return Err(PhysicsError::InvalidParameter {
            name: "points",
            value: n as f64,
            allowed: ">= 2",
        });
    }
    let steps = check_fold_steps(steps)?;
    let Some((gb, ab)) = fold_plus_birth(steps)? else {
        return Err(PhysicsError::NotFound {
            what: "the birth of the fold curve F+",
            gamma: f64::NAN,
            steps,
        });
    };
    let mut curve = FoldCurve {
        birth: (gb, ab),
        steps,
        points: Vec::new(),
    };
    if gamma_max < gb {
        return Ok(curve);
    }
    let mut guess = ab;
    for i in 0..n {
        let gamma = gb + (gamma_max - gb) * i as f64 / (n - 1) as f64;
        let alpha = if i == 0 {
            ab
        } else {
            fold_plus_at(gamma, guess, steps)?.ok_or(PhysicsError::NotFound {
                what: "the fold curve F+",
                gamma,
                steps,
            })?
        };
        let (left, right) = one_sided_slopes(gamma, alpha, steps)?;
        let below = slip_history(gamma, alpha * (-BELOW_FOLD).exp(), steps)?;
        let episode = below.episodes.iter().copied().find(|e| {
            e.sign == SlipSign::Plus
                && e.start >= RESTITUTION_WINDOW.0
                && e.start <= RESTITUTION_WINDOW.1
        });
        curve.points.push(FoldPoint {
            gamma,
            alpha,
            slope_jump: right - left,
            episode,
        });
        guess = alpha;
    }
    Ok(curve)
}

#[cfg(test)]
mod tests {
    use super::*;
    use oblique_physics::regimes::{alpha_c1, alpha_c2};

    #[test]
    fn full_slip_is_one_episode_over_the_whole_contact() {
        let g = 1.754;
        let h = slip_history(g, 0.5 * alpha_c1(g), 1024).unwrap();
        assert_eq!(h.episodes.len(), 1, "{:?}", h.episodes);
        let e = h.episodes[0];
        assert_eq!(e.sign, SlipSign::Plus);
        assert!(e.start < 0.01 && e.end > 0.99, "{e:?}");
        // The run's P is the full-slip line to second order in the step.
        assert!(
            (h.p - (1.0 - 7.0 * 0.5 * alpha_c1(g))).abs() < 1e-4,
            "{}",
            h.p
        );
    }

    #[test]
    fn stick_in_compression_has_no_gross_slip_before_restitution() {
        // α ≥ α_c2: no slip during compression (physics.md), so no episode before t_c/2.
        let g = 1.754;
        let h = slip_history(g, 1.5 * alpha_c2(g), 2048).unwrap();
        assert!(h.episodes.iter().all(|e| e.start > 0.5), "{:?}", h.episodes);
    }

    #[test]
    fn the_fold_at_gamma_3_2_is_where_the_restitution_episode_vanishes() {
        // Below the fold a +μF_N episode sits inside the restitution phase; above it, none.
        let restitution = (0.6, 0.95);
        let below = slip_history(3.2, 1.30, 2048).unwrap();
        let above = slip_history(3.2, 1.40, 2048).unwrap();
        assert!(below.has_interior(SlipSign::Plus, restitution), "{below:?}");
        assert!(
            !above.has_interior(SlipSign::Plus, restitution),
            "{above:?}"
        );
        let fold = locate_change(3.2, (1.30, 1.40), 2048, 30, |h| {
            h.has_interior(SlipSign::Plus, restitution)
        })
        .unwrap()
        .expect("one change in the bracket");
        // docs/solver.md: 1.343091 at 2048 steps, 1.343097 at 8192.
        assert!((fold - 1.34309).abs() < 2e-5, "{fold}");
        // P has a slope jump there: one-sided slopes of d P/d ln α over 1e-4 differ by > 0.3
        // (−0.90 against −0.32), where a smooth P would give a difference of about 1e-4.
        let p = |a: f64| slip_history(3.2, a, 2048).unwrap().p;
        let e = 1e-4_f64;
        let left = (p(fold * (-1e-6_f64).exp()) - p(fold * (-1e-6 - e).exp())) / e;
        let right = (p(fold * (1e-6 + e).exp()) - p(fold * (1e-6_f64).exp())) / e;
        assert!(right - left > 0.3, "left {left}, right {right}");
    }

    #[test]
    fn the_fold_curve_is_born_near_gamma_2_9() {
        // docs/solver.md: 2.901570 (1024 steps), 2.901666 (2048).
        let (gb, ab) = fold_plus_birth(1024)
            .unwrap()
            .expect("a birth in the bracket");
        assert!((2.89..=2.92).contains(&gb), "{gb}");
        // Inside the partial-slip region, near 0.86 α_c2.
        assert!(alpha_c1(gb) < ab && ab < alpha_c2(gb), "{ab}");
        assert!((0.8..0.9).contains(&(ab / alpha_c2(gb))), "{ab}");
        // Just below it the predicate holds nowhere, just above it somewhere.
        assert!(restitution_plus_somewhere(gb - 1e-5, 1024)
            .unwrap()
            .is_none());
        assert!(restitution_plus_somewhere(gb + 1e-5, 1024)
            .unwrap()
            .is_some());
    }

    #[test]
    fn the_fold_at_gamma_3_2_by_continuation() {
        // Continued from well below and from well above the fold.
        for guess in [1.2, 1.5] {
            let a = fold_plus_at(3.2, guess, 2048).unwrap().expect("found");
            assert!((a - 1.34309).abs() < 2e-5, "{a} from {guess}");
        }
        // Richardson over 2048/4096 steps: the 16384-step extrapolation is 1.3430974.
        let r = fold_plus_at_extrapolated(3.2, 1.343, 2048)
            .unwrap()
            .unwrap();
        assert!((r - 1.3430974).abs() < 1e-6, "{r}");
    }

    #[test]
    fn the_fold_minus_is_where_kinkmap_sees_its_episode_vanish() {
        // `kinkmap -- 3.2 3.2 0.1 2048`: α = 0.344692; `-- 2.45 2.45 0.1 2048`: 0.500226.
        for (gamma, guesses, want) in [
            (3.2, [0.343, 0.36], 0.344692),
            (2.45, [0.49, 0.52], 0.500226),
        ] {
            for guess in guesses {
                let a = fold_minus_at(gamma, guess, 2048).unwrap().expect("found");
                assert!((a - want).abs() < 2e-6, "{a} at {gamma} from {guess}");
            }
        }
        // Below the predicate's interval (at γ = 2.45 it starts at 0.4832) there is nothing to
        // continue from.
        assert_eq!(fold_minus_at(2.45, 0.3, 2048).unwrap(), None);
        // The located α separates the two signatures to 1e-6 (relative).
        let a = fold_minus_at(3.2, 0.345, 2048).unwrap().unwrap();
        let below = slip_history(3.2, a * (1.0 - 1e-6), 2048).unwrap();
        let above = slip_history(3.2, a * (1.0 + 1e-6), 2048).unwrap();
        assert!(has_restitution_minus(&below) && !has_restitution_minus(&above));
    }

    #[test]
    fn the_end_of_contact_curve_is_where_the_last_minus_episode_leaves_the_separation() {
        // `kinkmap -- G G 0.01 2048 HI LO`: 20.874911 at γ = 1.74, 1.323430 at 1.87 (stick),
        // 0.649182 at 2.2 (partial slip); from below and from above. (At 8192 steps: 20.878378,
        // 1.323434, 0.649182.)
        for (gamma, guesses, want, tol) in [
            (1.74, [15.0, 30.0], 20.874911, 1e-6),
            (1.87, [1.1, 1.5], 1.323430, 1e-6),
            (2.2, [0.5, 0.7], 0.649182, 1e-6),
        ] {
            for guess in guesses {
                let a = end_minus_at(gamma, guess, 2048).unwrap().expect("found");
                assert!((a / want - 1.0).abs() < tol, "{a} at {gamma} from {guess}");
            }
        }
        // Below γ ≈ 1.732 the episode reaches the separation at no α.
        assert_eq!(end_minus_at(1.72, 100.0, 2048).unwrap(), None);
        // The located α separates the two histories to 1e-6 (relative); above it nothing slips
        // at the end of a stick impact.
        let a = end_minus_at(1.87, 1.3, 2048).unwrap().unwrap();
        let below = slip_history(1.87, a * (1.0 - 1e-6), 2048).unwrap();
        let above = slip_history(1.87, a * (1.0 + 1e-6), 2048).unwrap();
        assert!(has_end_minus(&below) && !has_end_minus(&above));
        assert!(above.episodes.is_empty(), "{:?}", above.episodes);
        // With damping (`endscan_e 2.0`, continued down from e_n = 1): a surface; at e_n = 1
        // the elastic curve's runs.
        assert_eq!(
            end_minus_at_e(2.2, 1.0, 0.6, 2048).unwrap(),
            end_minus_at(2.2, 0.6, 2048).unwrap()
        );
        let a = end_minus_at_e(2.0, 0.8, 0.82, 2048)
            .unwrap()
            .expect("found");
        assert!((a / 0.817007 - 1.0).abs() < 2e-6, "{a}");
    }

    #[test]
    fn the_fold_curve_decreases_and_its_jump_grows_from_the_birth() {
        let steps = 1024;
        let curve = fold_plus_curve(3.5, 31, steps).unwrap();
        let (gb, ab) = curve.birth;
        assert_eq!(curve.points.len(), 31);
        assert_eq!((curve.points[0].gamma, curve.points[0].alpha), (gb, ab));
        assert!((curve.points[30].gamma - 3.5).abs() < 1e-12);
        let far: Vec<&FoldPoint> = curve
            .points
            .iter()
            .filter(|p| p.gamma >= gb + 0.01)
            .collect();
        assert!(far.len() >= 29);
        for w in far.windows(2) {
            assert!(w[1].alpha < w[0].alpha, "{:?} then {:?}", w[0], w[1]);
        }
        for p in &curve.points {
            assert!(
                alpha_c1(p.gamma) < p.alpha && p.alpha < alpha_c2(p.gamma),
                "{p:?}"
            );
        }
        // On the fold proper the episode shrinks to nothing at α_F.
        let last = curve.points[30];
        let e = last.episode.expect("episode below the fold");
        assert!(e.end - e.start < 0.01 && e.end < INTERIOR_END, "{last:?}");
        // docs/solver.md: 0.9996 at γ = 3.5; slope jump 0.52.
        assert!((last.alpha - 0.99957).abs() < 1e-4, "{last:?}");
        assert!(last.slope_jump > 0.3, "{last:?}");
        // Close to the birth the jump is small, below the jump at γ = 3.0 (0.43).
        let jump_at = |g: f64, guess: f64| {
            let a = fold_plus_at(g, guess, steps).unwrap().expect("found");
            let (l, r) = one_sided_slopes(g, a, steps).unwrap();
            r - l
        };
        let near = jump_at(gb + 0.001, ab);
        let at_3 = jump_at(3.0, 1.76);
        assert!(at_3 > 0.3, "{at_3}");
        assert!(near < at_3, "{near} >= {at_3}");
    }

    #[test]
    fn the_fold_tracer_refuses_bad_input() {
        assert!(fold_plus_birth(64).is_err());
        assert!(fold_plus_curve(3.2, 1, 1024).is_err());
        assert!(fold_plus_curve(-1.0, 5, 1024).is_err());
        assert!(fold_plus_curve(f64::NAN, 5, 1024).is_err());
        // Below the birth: no points, not an error.
        let c = fold_plus_curve(2.5, 5, 1024).unwrap();
        assert!(c.points.is_empty() && c.birth.0 > 2.5);
    }

    #[test]
    fn refuses_what_has_no_history() {
        assert!(slip_history(1.0, f64::INFINITY, 64).is_err());
        assert!(slip_history(1.0, 0.0, 64).is_err());
        assert!(slip_history(1.0, 0.3, 4).is_err());
        assert!(slip_history(f64::NAN, 0.3, 64).is_err());
    }
}
