//! The gross-slip history of a Kelvin–Voigt impact ([`slip_history_e`]) and the fold curve F₋
//! it reveals ([`fold_minus_at_e`], [`fold_minus_birth_e`], [`fold_minus_free_below`]): the
//! elastic history's definitions ([`super`]) on the law's own row, whose Coulomb limit includes
//! the viscous normal force. At `e_n = 1` every function here is its elastic counterpart.

use super::*;
use crate::kelvin_voigt::dimensionless_normal as kv_normal;
use crate::kelvin_voigt::row::ViscoelasticRow;
use crate::kelvin_voigt::tau_for_restitution;
use crate::law::check_restitution;
use crate::registry::Law;

/// The Coulomb limit's mean displacement `c`-free part `m = D − b/3` at a node of the
/// Kelvin–Voigt normal motion with indentation `d`, rate `ḋ` and relaxation time `τ̂`: the
/// row's mean `∫₀^a v dx / a` when every spring is at `|v| = c (D − y)`, `D = d + τ̂ ḋ` the
/// load, `b` the reach (`d` in compression, `max(D, 0)` in restitution), `a = √b`. So
/// `μ F_N = 2 μ √b · m`: `(4/3) d^{3/2} + 2 τ̂ ḋ √d` in compression, `(4/3) D^{3/2}` in
/// restitution, the law's normal force with its viscous part (`physics.md`). Also the reach.
fn limit_mean(d: f64, rate: f64, tau: f64) -> (f64, f64) {
    let load = d + tau * rate;
    let reach = if rate < 0.0 { load.max(0.0) } else { d };
    ((load - reach / 3.0).max(0.0), reach.max(0.0))
}

/// [`slip_history`] for the Kelvin–Voigt law at normal restitution `e_n ∈ [0.3, 1]`: one
/// impact with the Kelvin–Voigt continuum row ([`crate::kelvin_voigt::dimensionless_p`]'s run,
/// relaxation time [`crate::kelvin_voigt::tau_for_restitution`]) on `steps` steps, its
/// gross-slip episodes by the same definitions. The Coulomb limit of a step is the product
/// rule the stepper uses for the impulse, `μ F_N ≈ μ · 2 mean(√b) · (m₀ + m₁)` with `m`, `b`
/// of [`limit_mean`] at the step's ends: the law's normal force including its viscous part,
/// as the row limits its springs. Times are fractions of the law's own contact time (first
/// touch to `D = 0`).
///
/// At `e_n = 1` the elastic law answers (as [`crate::registry`] does): exactly
/// [`slip_history`]. Errors: those of [`slip_history`], and `e_n` outside `[0.3, 1]`.
pub fn slip_history_e(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<SlipHistory, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if Law::KelvinVoigt.answering(e_n) == Law::Elastic {
        return slip_history(gamma, alpha, steps);
    }
    let (ratios, p) = friction_ratio_e(gamma, alpha, e_n, steps)?;
    let mut episodes: Vec<Episode> = Vec::new();
    for &(t, q) in &ratios {
        record_step(&mut episodes, t, q, 1.0);
    }
    Ok(SlipHistory { episodes, p })
}

/// The ratio `F_t/(μF_N)` of every step of one Kelvin–Voigt impact at `e_n < 1` (the run of
/// [`slip_history_e`]): `(t/t_c, ratio)` at each step's midpoint (steps without a positive
/// Coulomb limit left out), and the run's `P`. `±1` is gross slip; a local extremum that
/// approaches `±1` without reaching it marks where an episode is about to be born. Errors:
/// those of [`slip_history_e`], and an `e_n` the elastic law answers.
pub fn friction_ratio_e(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<(Vec<(f64, f64)>, f64), PhysicsError> {
    let run = kv_run(gamma, alpha, e_n, steps)?;
    let ratios = run
        .steps
        .iter()
        .filter_map(|s| s.ratio.map(|q| (s.t, q)))
        .collect();
    Ok((ratios, run.p))
}

/// One step of a logged Kelvin–Voigt run ([`kv_run`]).
#[derive(Debug, Clone, Copy)]
struct KvStep {
    /// Midpoint of the step, `t/t_c`.
    t: f64,
    /// `F_t/(μF_N)`, `None` without a positive Coulomb limit.
    ratio: Option<f64>,
    /// Part of the row at the `+` / `−` limit after the step.
    plus: bool,
    minus: bool,
    /// Part of the row stuck after the step.
    stuck: bool,
}

/// A logged Kelvin–Voigt run and its `P`.
struct KvRun {
    steps: Vec<KvStep>,
    p: f64,
}

/// One Kelvin–Voigt impact at `e_n < 1` on `steps` steps, every step logged.
fn kv_run(gamma: f64, alpha: f64, e_n: f64, steps: usize) -> Result<KvRun, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if Law::KelvinVoigt.answering(e_n) == Law::Elastic {
        return Err(PhysicsError::InvalidParameter {
            name: "e_n",
            value: e_n,
            allowed: "< 1 (the elastic law has no viscous part)",
        });
    }
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let tau = tau_for_restitution(e_n)?;
    let shear = 2.0 / 7.0 * gamma * gamma;
    let normal = kv_normal(steps, tau);
    let mut rec = Recorder {
        point: ContactPoint { u: 1.0 },
        t: 0.0,
        log: Vec::with_capacity(steps + steps / 8),
    };
    let mut states = Vec::with_capacity(steps + steps / 8);
    // The normal state `[d₀, ḋ₀, d₁, ḋ₁]` (dimensionless) of every step, and the row's zones.
    let row = LoggedRow {
        row: ViscoelasticRow::new(1.0, tau),
        log: |r: &ViscoelasticRow, m: &StepMotion, d1: f64| {
            let (plus, minus) = r.at_limit();
            states.push((
                [m.d0, m.rate0, d1, m.rate1],
                plus,
                minus,
                r.stuck_length() > 0.0,
            ))
        },
    };
    run_contact_with(&mut rec, &*normal, row, 1.0, shear, alpha / shear);
    let mut out = Vec::with_capacity(rec.log.len());
    for (&(t, h, f), &([d0, r0, d1, r1], plus, minus, stuck)) in rec.log.iter().zip(&states) {
        let (m0, b0) = limit_mean(d0, r0, tau);
        let (m1, b1) = limit_mean(d1, r1, tau);
        let root_mean = mean_sqrt(b0, b1);
        let limit = alpha * root_mean * (m0 + m1);
        let ratio = (!limit.is_nan() && limit > 0.0).then(|| f / limit);
        out.push(KvStep {
            t: (t + 0.5 * h) / normal.contact_time,
            ratio,
            plus,
            minus,
            stuck,
        });
    }
    Ok(KvRun {
        steps: out,
        p: rec.point.u,
    })
}

/// The zones of the row over one Kelvin–Voigt impact at `e_n < 1`: runs of steps in one
/// state, `(label, first, last)` with the steps' midpoints as fractions of `t_c` and the label
/// `+` and/or `−` for the limits part of the contact is at, then `s` where part is stuck or
/// `G` where none is (gross slip). For studies of the sheet I₊ ([`has_plus_interlude_e`]).
pub fn zone_runs_e(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<Vec<(String, f64, f64)>, PhysicsError> {
    let run = kv_run(gamma, alpha, e_n, steps)?;
    let mut out: Vec<(String, f64, f64)> = Vec::new();
    for s in &run.steps {
        let label = format!(
            "{}{}{}",
            if s.plus { "+" } else { "" },
            if s.minus { "-" } else { "" },
            if s.stuck { "s" } else { "G" }
        );
        match out.last_mut() {
            Some(last) if last.0 == label => last.2 = s.t,
            _ => out.push((label, s.t, s.t)),
        }
    }
    Ok(out)
}

/// Shortest `+` interlude between two `−` zones ([`has_plus_interlude_e`]), as a fraction of
/// `t_c`: two steps at 2048 steps. An interlude lasts `∝ √(e_n − e_I)` above the sheet I₊,
/// about 0.85 `t_c` per unit of `√(e_n − e_I)` at γ = 2.5, α = 0.9, so this moves the located
/// sheet by about 1.4e-6 in `e_n`.
pub const INTERLUDE_MIN: f64 = 0.001;

/// Shortest `+` interlude that runs into the final gross slip ([`has_plus_interlude_e`]), as a
/// fraction of `t_c`. Where the `−` zone gives way to gross slip the `+` zone takes a short
/// while to spread over the contact (up to 0.0073 `t_c` next to α_c2: γ = 2.6, α = 1.845,
/// `e_n` = 0.95), which is no interlude.
pub const INTERLUDE_LONG: f64 = 0.02;

/// Whether the restitution of a Kelvin–Voigt impact holds a `+` interlude: after a step with
/// part of the contact at the `−` limit, a stretch during which part slips at the `+` limit,
/// none at the `−` limit and part stays stuck, that either ends in a `−` zone again (and
/// lasts at least [`INTERLUDE_MIN`] `t_c`) or runs into the final gross slip (and lasts at least
/// [`INTERLUDE_LONG`] `t_c`: further above I₊ the second `−` zone vanishes). The interlude
/// is born at an interior time of the `−` zone on the sheet I₊ `e_n = e_I(γ, α)` (γ ≳ 2.32,
/// α between about 0.41 and α_c2, `e_n` ≳ 0.85 up to γ = 2.62; [`plus_interlude_edge_e`]), so
/// that `P` departs from its smooth continuation like `(e_n − e_I)^{3/2}` above it. The
/// global friction ratio does not show it (its extremes move smoothly through I₊), nor do the
/// gross-slip episodes of [`slip_history_e`].
pub fn has_plus_interlude_e(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<bool, PhysicsError> {
    let run = kv_run(gamma, alpha, e_n, steps)?;
    let mut seen_minus = false;
    let mut start: Option<f64> = None;
    for s in &run.steps {
        let interlude = seen_minus && s.plus && !s.minus && s.stuck;
        match (interlude, start) {
            (true, None) => start = Some(s.t),
            (false, Some(t0)) => {
                let span = s.t - t0;
                let between = s.minus && span >= INTERLUDE_MIN;
                let into_gross = s.plus && !s.stuck && span >= INTERLUDE_LONG;
                if between || into_gross {
                    return Ok(true);
                }
                start = None;
            }
            _ => {}
        }
        seen_minus |= s.minus;
    }
    Ok(false)
}

/// The sheet I₊ at `(γ, α)`: the `e_n` in `(e_lo, e_hi)` above which [`has_plus_interlude_e`]
/// holds, bisected to `1e-7`; `None` unless it fails at `e_lo` and holds at `e_hi` (`e_hi <
/// 1`).
pub fn plus_interlude_edge_e(
    gamma: f64,
    alpha: f64,
    bracket: (f64, f64),
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    plus_interlude_edge_e_within(gamma, alpha, bracket, steps, 1e-7)
}

/// [`plus_interlude_edge_e`] bisected until the bracket is at most `e_tol` wide (`> 0`): a
/// tracing that needs the sheet to its resolution's own error only (about 1e-5 in `e_n` at 2048
/// steps) stops earlier.
pub fn plus_interlude_edge_e_within(
    gamma: f64,
    alpha: f64,
    (e_lo, e_hi): (f64, f64),
    steps: usize,
    e_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    let e_tol = crate::error::positive("e_tol", e_tol)?;
    let holds = |e: f64| has_plus_interlude_e(gamma, alpha, e, steps);
    if e_lo.is_nan() || e_hi.is_nan() || e_hi <= e_lo || holds(e_lo)? || !holds(e_hi)? {
        return Ok(None);
    }
    // The interlude holds above its edge: the edge of its negation, which holds below.
    bisect_edge((e_lo, e_hi), e_tol, |e| holds(e).map(|h| !h)).map(Some)
}

/// [`fold_minus_at`] for the Kelvin–Voigt law at normal restitution `e_n ∈ [0.3, 1]`: the same
/// continuation from `guess` and the same predicate ([`has_restitution_minus`]) on the
/// histories of [`slip_history_e`]. At `e_n = 1` exactly [`fold_minus_at`] (the same runs).
/// `None` where the continuation finds no change (no F₋ at this γ and `e_n`, or a guess below
/// the predicate's interval: [`fold_minus_scan_e`] then).
pub fn fold_minus_at_e(
    gamma: f64,
    e_n: f64,
    guess: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    fold_at_e(
        (gamma, e_n),
        guess,
        steps,
        has_restitution_minus,
        LOCATE_LN_ALPHA,
    )
}

/// The continuation of [`fold_at_with`] on the Kelvin–Voigt histories at `e_n`, for the curve
/// whose `present` predicate holds below it.
fn fold_at_e(
    (gamma, e_n): (f64, f64),
    guess: f64,
    steps: usize,
    present: fn(&SlipHistory) -> bool,
    ln_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    let e_n = check_restitution(e_n)?;
    let ln_tol = crate::error::positive("ln_tol", ln_tol)?;
    fold_at_with(
        |a| slip_history_e(gamma, a, e_n, steps),
        guess,
        present,
        ln_tol,
    )
}

/// The end-of-contact curve E₋ ([`has_end_minus`]) of the Kelvin–Voigt law at normal
/// restitution `e_n ∈ [0.3, 1]`, located by continuation from `guess` on the histories of
/// [`slip_history_e`] (at `e_n = 1` exactly [`super::end_minus_at`]). `None` where the
/// continuation finds no change.
pub fn end_minus_at_e(
    gamma: f64,
    e_n: f64,
    guess: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    end_minus_at_e_within(gamma, e_n, guess, steps, LOCATE_LN_ALPHA)
}

/// [`end_minus_at_e`] with the change bisected to `ln_tol` (`> 0`) in `ln α` instead of
/// [`LOCATE_LN_ALPHA`]: a tracing that needs E₋ to its resolution's own error only (about 1e-5
/// relative at 2048 steps) stops earlier.
pub fn end_minus_at_e_within(
    gamma: f64,
    e_n: f64,
    guess: f64,
    steps: usize,
    ln_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    fold_at_e((gamma, e_n), guess, steps, has_end_minus, ln_tol)
}

/// Every upper edge of an α interval in `[alpha_lo, alpha_hi]` on which
/// [`has_restitution_minus`] holds for the Kelvin–Voigt law at `e_n` (F₋, where the predicate
/// goes from holding to failing as α grows), in increasing α: a log grid of `n` intervals,
/// each change bisected to ≈1e-10 in `ln α`. An interval narrower than the grid's spacing can
/// be missed ([`restitution_minus_somewhere_e`] zooms in instead).
pub fn fold_minus_scan_e(
    gamma: f64,
    e_n: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    n: usize,
    steps: usize,
) -> Result<Vec<f64>, PhysicsError> {
    falling_edges_e(
        gamma,
        e_n,
        (alpha_lo, alpha_hi),
        n,
        steps,
        has_restitution_minus,
    )
}

/// Every α in `[alpha_lo, alpha_hi]` where `present` goes from holding to failing as α grows,
/// on the Kelvin–Voigt histories at `e_n` and γ, in increasing α ([`falling_edges`]).
fn falling_edges_e(
    gamma: f64,
    e_n: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    n: usize,
    steps: usize,
    present: fn(&SlipHistory) -> bool,
) -> Result<Vec<f64>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    let e_n = check_restitution(e_n)?;
    falling_edges(
        |a: f64| slip_history_e(gamma, a, e_n, steps),
        (alpha_lo, alpha_hi),
        n,
        present,
    )
}

/// Every α in `[alpha_lo, alpha_hi]` where `present` goes from holding to failing as α grows
/// on the histories of `history`, in increasing α: a log grid of `n` intervals, each change
/// bisected to ≈1e-10 in `ln α`. An interval narrower than the grid's spacing can be missed.
pub(super) fn falling_edges(
    history: impl Fn(f64) -> Result<SlipHistory, PhysicsError>,
    (alpha_lo, alpha_hi): (f64, f64),
    n: usize,
    present: fn(&SlipHistory) -> bool,
) -> Result<Vec<f64>, PhysicsError> {
    check_alpha_range(alpha_lo, alpha_hi, n)?;
    let xs: Vec<f64> = log_grid(alpha_lo, alpha_hi, n).collect();
    let mut edges = Vec::new();
    let mut prev = present(&history(xs[0])?);
    for w in xs.windows(2) {
        let now = present(&history(w[1])?);
        if prev && !now {
            let iterations = ((w[1] / w[0]).ln() / 1e-10).log2().ceil().max(1.0) as usize;
            if let Some(a) = locate_change_with(&history, (w[0], w[1]), iterations, present)? {
                edges.push(a);
            }
        }
        prev = now;
    }
    Ok(edges)
}

fn check_alpha_range(lo: f64, hi: f64, n: usize) -> Result<(), PhysicsError> {
    if !(lo > 0.0 && hi > lo && hi <= ALPHA_NO_SLIP) {
        return Err(PhysicsError::InvalidParameter {
            name: "alpha range",
            value: hi,
            allowed: "0 < lo < hi <= 1e10",
        });
    }
    if n < 2 {
        return Err(PhysicsError::InvalidParameter {
            name: "intervals",
            value: n as f64,
            allowed: ">= 2",
        });
    }
    Ok(())
}

/// Whether a `−μF_N` episode starts in the restitution phase (after `t_c/2`, the start of
/// [`RESTITUTION_WINDOW`]), wherever it starts or ends (also one that runs into the separation).
fn has_restitution_minus_any(h: &SlipHistory) -> bool {
    restitution_minus_episode(h).is_some()
}

/// The earliest-ending `−` episode that starts after `t_c/2`.
fn restitution_minus_episode(h: &SlipHistory) -> Option<Episode> {
    h.episodes
        .iter()
        .copied()
        .filter(|e| e.sign == SlipSign::Minus && e.start >= RESTITUTION_WINDOW.0)
        .min_by(|a, b| a.end.total_cmp(&b.end))
}

/// Where the restitution `−μF_N` episode disappears as α grows, for the Kelvin–Voigt law at
/// `e_n` and γ: every α in `[alpha_lo, alpha_hi]` at which a `−` episode starting after
/// `t_c/2` (ending anywhere) exists just below and not just above (a log grid of
/// `n` intervals, each change bisected to ≈1e-10 in `ln α`), with that episode at `α (1 −
/// 1e-9)`. Where the episode then ends before [`INTERIOR_END`] it vanishes inside the contact:
/// the fold F₋ ([`has_restitution_minus`] holds just below). Where it ends at the separation
/// (≈ 1 t_c), the change is one at the end of the contact, no fold.
pub fn restitution_minus_edges_e(
    gamma: f64,
    e_n: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    n: usize,
    steps: usize,
) -> Result<Vec<(f64, Option<Episode>)>, PhysicsError> {
    let edges = falling_edges_e(
        gamma,
        e_n,
        (alpha_lo, alpha_hi),
        n,
        steps,
        has_restitution_minus_any,
    )?;
    edges
        .into_iter()
        .map(|a| {
            let below = slip_history_e(gamma, a * (1.0 - 1e-9), e_n, steps)?;
            Ok((a, restitution_minus_episode(&below)))
        })
        .collect()
}

/// Some `α` in `[alpha_lo, alpha_hi]` at which [`has_restitution_minus`] holds for the
/// Kelvin–Voigt law at `e_n` and γ, if there is one: just below an edge of
/// [`restitution_minus_edges_e`] (64 intervals) whose episode ends inside the contact. Near the
/// birth of F₋ the predicate holds only on a short interval below the fold, which a plain grid
/// misses; the edge where the episode disappears is found whatever the interval's width.
pub fn restitution_minus_somewhere_e(
    gamma: f64,
    e_n: f64,
    alphas: (f64, f64),
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    for (a, _) in restitution_minus_edges_e(gamma, e_n, alphas, 64, steps)? {
        let at = a * (1.0 - 1e-9);
        if has_restitution_minus(&slip_history_e(gamma, at, e_n, steps)?) {
            return Ok(Some(at));
        }
    }
    Ok(None)
}

/// The smallest γ in `[gamma_lo, gamma_hi]` at which F₋ exists for the Kelvin–Voigt law at
/// `e_n` (its predicate [`has_restitution_minus`] holds somewhere in `alphas`,
/// [`restitution_minus_somewhere_e`]), by bisection in γ until the bracket is at most `2 tol`
/// wide: `(γ_b, α)` with γ_b the bracket's upper end (within `2 tol` above the birth) and α
/// where the predicate held there. `None` if it holds already at `gamma_lo` or not at
/// `gamma_hi`. Like [`fold_plus_birth`] this is the birth of the *predicate* (the episode
/// first ends before [`INTERIOR_END`]); the fold proper may start slightly above it.
pub fn fold_minus_birth_e(
    e_n: f64,
    (gamma_lo, gamma_hi): (f64, f64),
    alphas: (f64, f64),
    tol: f64,
    steps: usize,
) -> Result<Option<(f64, f64)>, PhysicsError> {
    let (mut g_lo, mut g_hi) = (check_gamma(gamma_lo)?, check_gamma(gamma_hi)?);
    if !(tol > 0.0 && g_hi > g_lo) {
        return Err(PhysicsError::InvalidParameter {
            name: "gamma bracket",
            value: tol,
            allowed: "gamma_lo < gamma_hi and tol > 0",
        });
    }
    if restitution_minus_somewhere_e(g_lo, e_n, alphas, steps)?.is_some() {
        return Ok(None);
    }
    let Some(mut alpha) = restitution_minus_somewhere_e(g_hi, e_n, alphas, steps)? else {
        return Ok(None);
    };
    while g_hi - g_lo > 2.0 * tol {
        let mid = 0.5 * (g_lo + g_hi);
        match restitution_minus_somewhere_e(mid, e_n, alphas, steps)? {
            Some(a) => {
                g_hi = mid;
                alpha = a;
            }
            None => g_lo = mid,
        }
    }
    Ok(Some((g_hi, alpha)))
}

/// Where F₋ is measured to be born for the Kelvin–Voigt law (`fold_minus_e` example, 2048
/// steps, bisection to ±0.005 in γ): `(e_n, γ)` with no F₋ below γ at that `e_n`, the lower end
/// of each bracket, by falling `e_n`. Below `e_n` = 0.9 none was found up to γ = 3.6.
const FOLD_MINUS_BIRTHS: [(f64, f64); 7] = [
    (1.0, 2.3666),
    (0.999, 2.3736),
    (0.99, 2.4017),
    (0.97, 2.4650),
    (0.95, 2.5494),
    (0.9, 2.9220),
    (0.8, 3.6),
];

/// A γ below which the surface `P(γ, α, e)` has no fold curve F₋ for any `e ≤ e_n_max`
/// (Kelvin–Voigt law, `e_n_max` in `[0.3, 1]`): damping moves F₋'s birth to larger γ
/// (measured at seven `e_n`, [`fold_minus_birth_e`]), so the birth at the nearest measured
/// `e_n` at or above `e_n_max` bounds it from below. 3.6 for `e_n_max ≤ 0.8` (none measured
/// up to there). A table that reaches F₋ must measure its leaves next to it.
pub fn fold_minus_free_below(e_n_max: f64) -> f64 {
    FOLD_MINUS_BIRTHS
        .iter()
        .rev()
        .find(|&&(e, _)| e >= e_n_max)
        .map_or(FOLD_MINUS_BIRTHS[0].1, |&(_, g)| g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kelvin_voigt_history_at_e_n_1_is_the_elastic_one() {
        for (g, a) in [(2.45, 0.49), (3.2, 1.3), (1.754, 0.2)] {
            let elastic = slip_history(g, a, 1024).unwrap();
            let kv = slip_history_e(g, a, 1.0, 1024).unwrap();
            assert_eq!(kv, elastic);
            assert_eq!(kv.p.to_bits(), elastic.p.to_bits());
        }
    }

    #[test]
    fn the_kelvin_voigt_history_tends_to_the_elastic_one() {
        // At e_n = 0.999999 the damped run keeps the elastic episodes (γ = 2.45, α = 0.49:
        // +μF_N from the start to 0.356 t_c, the −μF_N of F₋ at 0.844–0.934, +μF_N at the end)
        // to within one step of 1/2048 t_c, and P to 1e-6.
        let elastic = slip_history(2.45, 0.49, 2048).unwrap();
        let kv = slip_history_e(2.45, 0.49, 0.999_999, 2048).unwrap();
        assert_eq!(kv.episodes.len(), elastic.episodes.len(), "{kv:?}");
        for (k, e) in kv.episodes.iter().zip(&elastic.episodes) {
            assert_eq!(k.sign, e.sign);
            assert!((k.start - e.start).abs() < 1.0 / 2048.0, "{k:?} {e:?}");
            assert!((k.end - e.end).abs() < 1.0 / 2048.0, "{k:?} {e:?}");
        }
        assert!(has_restitution_minus(&kv));
        assert!((kv.p - elastic.p).abs() < 1e-6, "{} {}", kv.p, elastic.p);
    }

    #[test]
    fn the_kelvin_voigt_history_runs_the_law_s_own_row() {
        // Its P is the Kelvin–Voigt solver's at the same resolution, to the bit.
        use crate::kelvin_voigt::{dimensionless_p, tau_for_restitution};
        for (g, a, e_n) in [(2.6, 0.42, 0.95), (1.2, 0.3, 0.5), (2.2, 0.7, 0.8)] {
            let h = slip_history_e(g, a, e_n, 512).unwrap();
            let shear = 2.0 / 7.0 * g * g;
            let tau = tau_for_restitution(e_n).unwrap();
            let res = crate::Resolution {
                springs: 0,
                steps: 512,
            };
            let p = dimensionless_p(shear, a / shear, tau, res);
            assert_eq!(h.p.to_bits(), p.to_bits(), "{g} {a} {e_n}");
        }
        // Full slip (α below α_c1(e_n)): one +μF_N episode over the whole contact, the limit
        // including the viscous force of the compression.
        let g = 1.754;
        let a = 0.5 * oblique_physics::regimes::linear_limit_dissipative(g, 0.7);
        let h = slip_history_e(g, a, 0.7, 1024).unwrap();
        assert_eq!(h.episodes.len(), 1, "{:?}", h.episodes);
        let e = h.episodes[0];
        assert_eq!(e.sign, SlipSign::Plus);
        assert!(e.start < 0.01 && e.end > 0.99, "{e:?}");
        assert!((h.p - (1.0 - 3.5 * 1.7 * a)).abs() < 1e-4, "{}", h.p);
    }

    #[test]
    fn the_kelvin_voigt_fold_minus_at_e_n_1_is_the_elastic_one() {
        for guess in [0.49, 0.52] {
            let e = fold_minus_at(2.45, guess, 2048).unwrap().unwrap();
            let kv = fold_minus_at_e(2.45, 1.0, guess, 2048).unwrap().unwrap();
            assert_eq!(kv.to_bits(), e.to_bits(), "from {guess}");
        }
        assert_eq!(fold_minus_at_e(2.45, 1.0, 0.3, 2048).unwrap(), None);
    }

    #[test]
    fn p_departs_from_its_continuation_at_the_damped_fold_minus() {
        // γ = 2.6, e_n = 0.97 (`fold_minus_e` example: 0.433029 at 2048 steps; 0.451584 at
        // e_n = 1). P computed directly by the Kelvin–Voigt solver at the same steps.
        use crate::kelvin_voigt::{dimensionless_p, tau_for_restitution};
        let (g, e_n, steps) = (2.6, 0.97, 2048);
        let af = fold_minus_at_e(g, e_n, 0.44, steps)
            .unwrap()
            .expect("F- found");
        assert!((af - 0.433029).abs() < 2e-6, "{af}");
        let edges = fold_minus_scan_e(g, e_n, (0.3, 0.8), 100, steps).unwrap();
        assert_eq!(edges.len(), 1, "{edges:?}");
        assert!((edges[0] - af).abs() < 1e-8 * af, "{edges:?}");
        let below = slip_history_e(g, af * (1.0 - 1e-6), e_n, steps).unwrap();
        let above = slip_history_e(g, af * (1.0 + 1e-6), e_n, steps).unwrap();
        assert!(has_restitution_minus(&below) && !has_restitution_minus(&above));
        let tau = tau_for_restitution(e_n).unwrap();
        let shear = 2.0 / 7.0 * g * g;
        let res = crate::Resolution { springs: 0, steps };
        let p = |a: f64| dimensionless_p(shear, a / shear, tau, res);
        // Second differences over a grid of step 1e-4, 21 nodes centred on `centre`.
        let h = 1e-4;
        let second = |centre: f64| -> Vec<f64> {
            let ps: Vec<f64> = (-10..=10).map(|i| p(centre + h * f64::from(i))).collect();
            ps.windows(3).map(|w| w[2] - 2.0 * w[1] + w[0]).collect()
        };
        let max_abs = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        // Around α_F: the largest |Δ²P| sits at the node on α_F or next to it (measured:
        // 3.3e-6 there, 1.0e-6 and 2.2e-6 beside it, 3e-7 nine steps below, decaying like
        // (α − α_F)^{-1/2} above: P departs like (α − α_F)^{3/2}).
        let at = second(af);
        let peak = max_abs(&at);
        let k = at.iter().position(|x| x.abs() == peak).unwrap();
        // Index 9 is the node on α_F.
        assert!((8..=10).contains(&k), "{at:?}");
        // At ±5 % P is smooth: |Δ²P| ≤ 2.2e-7 (measured), well below the spike.
        for centre in [0.95 * af, 1.05 * af] {
            let away = max_abs(&second(centre));
            assert!(away < peak / 8.0, "{away} vs {peak} at {centre}");
        }
        // It stands out of the curvature nine steps below it (10× measured).
        assert!(peak > 5.0 * max_abs(&at[..3]), "{at:?}");
    }

    #[test]
    fn damping_moves_the_birth_of_fold_minus_up() {
        // `fold_minus_e` example (2048 steps): γ_b in (2.3666, 2.3766] at e_n = 1, in
        // (2.4017, 2.4117] at e_n = 0.99.
        let (gb, ab) = fold_minus_birth_e(0.99, (2.38, 2.44), (0.3, 0.8), 0.005, 2048)
            .unwrap()
            .expect("bracketed");
        assert!((2.40..=2.42).contains(&gb), "{gb}");
        assert!((0.45..0.55).contains(&ab), "{ab}");
        // At γ = 2.39 the elastic F₋ exists; at e_n = 0.99 there is none.
        assert!(restitution_minus_somewhere_e(2.39, 1.0, (0.3, 0.8), 2048)
            .unwrap()
            .is_some());
        assert!(restitution_minus_somewhere_e(2.39, 0.99, (0.3, 0.8), 2048)
            .unwrap()
            .is_none());
        // At γ = 2.2 the restitution −μF_N episode disappears at the separation, not inside
        // the contact: no fold, damped or not.
        for e_n in [1.0, 0.9] {
            let edges = restitution_minus_edges_e(2.2, e_n, (0.3, 0.8), 32, 2048).unwrap();
            assert!(!edges.is_empty(), "{e_n}");
            for (a, ep) in edges {
                let ep = ep.expect("an episode just below");
                assert!(ep.start > 0.999, "{a} {ep:?}");
            }
        }
    }

    #[test]
    fn the_fold_free_gamma_bounds_the_birth_from_below() {
        assert_eq!(fold_minus_free_below(1.0), 2.3666);
        assert_eq!(fold_minus_free_below(0.995), 2.3736);
        assert_eq!(fold_minus_free_below(0.99), 2.4017);
        assert_eq!(fold_minus_free_below(0.85), 2.9220);
        assert_eq!(fold_minus_free_below(0.5), 3.6);
        // Falling with e_n_max, and no F₋ just below it where one was measured.
        for w in FOLD_MINUS_BIRTHS.windows(2) {
            assert!(w[0].1 < w[1].1, "{w:?}");
        }
        for e_n in [1.0, 0.97] {
            let g = fold_minus_free_below(e_n) - 0.002;
            assert!(
                restitution_minus_somewhere_e(g, e_n, (0.3, 0.8), 2048)
                    .unwrap()
                    .is_none(),
                "{e_n}"
            );
        }
    }

    #[test]
    fn the_kelvin_voigt_history_refuses_bad_input() {
        assert!(slip_history_e(2.45, 0.49, 0.2, 256).is_err());
        assert!(slip_history_e(2.45, 0.49, f64::NAN, 256).is_err());
        assert!(slip_history_e(2.45, f64::INFINITY, 0.9, 256).is_err());
        assert!(slip_history_e(2.45, 0.49, 0.9, 4).is_err());
        assert!(fold_minus_at_e(2.45, 0.9, 0.49, 64).is_err());
        assert!(fold_minus_scan_e(2.45, 0.9, (0.8, 0.3), 10, 256).is_err());
        assert!(fold_minus_birth_e(0.9, (2.6, 2.4), (0.3, 0.8), 0.005, 256).is_err());
    }

    #[test]
    fn the_plus_interlude_is_born_on_the_sheet() {
        // γ = 2.5, α = 0.9: − zone straight into gross slip below e_I ≈ 0.9446, a + interlude
        // between two − zones above it; located within 1e-5 at 2048 and 4096 steps. P's second
        // difference along e_n changes there (docs/solver.md).
        let runs = |e: f64| -> Vec<String> {
            zone_runs_e(2.5, 0.9, e, 4096)
                .unwrap()
                .into_iter()
                .map(|r| r.0)
                .collect()
        };
        assert_eq!(runs(0.944), ["+G", "s", "-s", "+G", "G"]);
        assert_eq!(runs(0.946), ["+G", "s", "-s", "+s", "-s", "+G", "G"]);
        assert!(!has_plus_interlude_e(2.5, 0.9, 0.944, 2048).unwrap());
        assert!(has_plus_interlude_e(2.5, 0.9, 0.946, 2048).unwrap());
        let coarse = plus_interlude_edge_e(2.5, 0.9, (0.8, 0.999), 2048)
            .unwrap()
            .unwrap();
        let fine = plus_interlude_edge_e(2.5, 0.9, (0.8, 0.999), 4096)
            .unwrap()
            .unwrap();
        assert!(
            (coarse - 0.9446).abs() < 2e-4 && (coarse - fine).abs() < 1e-5,
            "{coarse} {fine}"
        );
        // Next to α_c2 the + zone spreads over a few steps before gross slip: no interlude.
        assert!(!has_plus_interlude_e(2.6, 1.845, 0.9, 2048).unwrap());
        // Not below γ ≈ 2.32; the elastic law is refused.
        assert_eq!(
            plus_interlude_edge_e(2.3, 0.7, (0.8, 0.999), 2048).unwrap(),
            None
        );
        assert!(has_plus_interlude_e(2.5, 0.9, 1.0, 2048).is_err());
    }
}
