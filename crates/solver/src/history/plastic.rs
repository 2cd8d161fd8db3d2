//! The gross-slip history of an impact under Thornton's elastic–plastic law
//! ([`slip_history_thornton`]), its partial-slip zones ([`slip_pattern_thornton`],
//! [`slip_zones_thornton`]), the edge of its full-slip region ([`full_slip_edge_thornton`]), the
//! fold of its loading slip zone in the stick patch ([`loading_fold_thornton`]) and the folds of
//! its partial-slip patch ([`reslip_fold_thornton`], [`switch_fold_thornton`]).
//!
//! Thornton's law has no closed-form full-slip line: at the switch to unloading its Coulomb
//! limits jump (centre up, edge down), the central springs stick for a moment, and `P` leaves
//! `1 − (7/2)(1 + e_n)α` at every `α > 0` (`physics.md`, "Elastic–plastic impacts"). It keeps a
//! full-slip *region*, though: below an edge `α₁(γ, e_n)` the contact is back in gross slip
//! `F_t = +μF_N` after the switch and stays there until it separates, and `P` is smooth in `α`;
//! above it that last episode ends before the separation and `P` leaves its smooth continuation
//! like the Kelvin–Voigt law at `α_c1` (`(α − α₁)^{3/2}`). `α₁` lies above the Kelvin–Voigt
//! `α_c1(γ, e_n) = 2γ²/(7(γ²(1 + e_n) − e_n))` (the law's closed form at the same `e_n`) by
//! `1e-4` to a few `1e-2` of it, so a table of this law must trace it.

use super::*;
use crate::law::{check_restitution, shear_and_limit};
use crate::model::NormalModel;
use crate::registry::Law;
use crate::thornton::row::ThorntonRow;
use crate::thornton::yield_pressure_for_restitution;
use crate::thornton::{dimensionless_motion, dimensionless_trajectory};

/// [`slip_history`] for Thornton's law at normal restitution `e_n ∈ [0.3, 1]` (its limiting
/// pressure from Thornton's closed form): the impact with the law's continuum row on `steps`
/// steps, a step in gross slip where the whole contact is at one Coulomb limit at its end (the
/// row's own pieces, no force ratio), episodes merged as [`slip_history`] merges them. Times are
/// fractions of the law's contact time.
///
/// At `e_n = 1` the elastic law answers (as [`crate::registry`] does): exactly
/// [`slip_history`]. Errors: those of [`slip_history`], and `e_n` outside `[0.3, 1]`.
pub fn slip_history_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<SlipHistory, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    if Law::Thornton.answering(e_n) == Law::Elastic {
        return slip_history(gamma, alpha, steps);
    }
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let (log, p, times) = run_logged(gamma, alpha, e_n, steps)?;
    let mut episodes: Vec<Episode> = Vec::new();
    let contact_time = times.last().map_or(1.0, |&(t, h)| t + h);
    for (&(t, h), (state, _)) in times.iter().zip(&log) {
        let q = match state {
            Some(true) => 1.0,
            Some(false) => -1.0,
            None => 0.0,
        };
        record_step(&mut episodes, t + 0.5 * h, q, contact_time);
    }
    Ok(SlipHistory { episodes, p })
}

/// The partial-slip pattern of one run of Thornton's law at `steps` steps per contact time:
/// after every step, `(t, plus, minus, zones_plus, zones_minus)` with `t` the step's end
/// (fraction of the contact time), `plus`, `minus` the fractions of the contact radius at the
/// `+μq` and `−μq` limits and the numbers of separate zones at each; and `P`. Diagnostics for
/// the kinks of `P` (slip zones that open and close inside the contact, which the gross-slip
/// history does not show). Errors as [`slip_history_thornton`]; `e_n = 1` runs Thornton's row
/// without a plastic phase.
#[allow(clippy::type_complexity)]
pub fn slip_pattern_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<(Vec<(f64, f64, f64, usize, usize)>, f64), PhysicsError> {
    let e_n = check_restitution(e_n)?;
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let (log, p, times) = run_logged_with(gamma, alpha, e_n, steps, |row| {
        let (plus, minus, stuck, zp, zm) = row.slip_extent();
        let total = plus + minus + stuck;
        if total > 0.0 {
            (plus / total, minus / total, zp, zm)
        } else {
            (0.0, 0.0, 0, 0)
        }
    })?;
    let contact_time = times.last().map_or(1.0, |&(t, h)| t + h);
    let out = times
        .iter()
        .zip(&log)
        .map(|(&(t, h), &(p, m, zp, zm))| ((t + h) / contact_time, p, m, zp, zm))
        .collect();
    Ok((out, p))
}

/// One logged run: the gross-slip state after every step (whether the whole contact is at one
/// Coulomb limit, `ThorntonRow::gross_slip`, and whether anything is still in contact), `P`,
/// and `(start, length)` of every step (dimensionless time).
#[allow(clippy::type_complexity)]
fn run_logged(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<(Vec<(Option<bool>, bool)>, f64, Vec<(f64, f64)>), PhysicsError> {
    run_logged_with(gamma, alpha, e_n, steps, |row| {
        (row.gross_slip(), row.pieces() > 0)
    })
}

/// One run of Thornton's row with `f` of the row logged after every step: the log, `P`, and
/// `(start, length)` of every step (dimensionless time). `γ`, `α` and `e_n` checked by the
/// caller.
#[allow(clippy::type_complexity)]
fn run_logged_with<T>(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
    mut f: impl FnMut(&ThorntonRow) -> T,
) -> Result<(Vec<T>, f64, Vec<(f64, f64)>), PhysicsError> {
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
    let trajectory = dimensionless_trajectory(&motion, steps);
    let (shear, limit) = shear_and_limit(gamma, alpha);
    let mut rec = Recorder {
        point: ContactPoint { u: 1.0 },
        t: 0.0,
        log: Vec::with_capacity(steps + steps / 8),
    };
    let mut log = Vec::with_capacity(steps + steps / 8);
    let row = LoggedRow {
        row: ThorntonRow::new(
            1.0,
            motion.loading.yield_indentation,
            motion.unloading.ratio,
            motion.unloading.plastic_indentation,
        ),
        log: |row: &ThorntonRow, _: &StepMotion, _: f64| log.push(f(row)),
    };
    run_contact_with(&mut rec, &*trajectory, row, 1.0, shear, limit);
    let times = rec.log.iter().map(|&(t, h, _)| (t, h)).collect();
    debug_assert!(trajectory.contact_time() > 0.0);
    Ok((log, rec.point.u, times))
}

/// Whether the impact at `(γ, α, e_n)` on `steps` steps ends in gross slip at the `+` limit:
/// the whole contact at `F_t = +μF_N` after the last step that leaves something in contact.
/// Just above the edge `α₁` the contact sticks before it separates and a short `−μF_N` episode
/// ends it; where the central springs that stick at the switch to unloading never slip again
/// (small γ, small `e_n`), the edge is where that happens.
pub fn ends_in_full_slip_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<bool, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let (log, _, _) = run_logged(gamma, alpha, e_n, steps)?;
    let last = log.iter().rev().find(|&&(_, in_contact)| in_contact);
    Ok(last.and_then(|&(state, _)| state) == Some(true))
}

/// The edge `α₁(γ, e_n)` of Thornton's full-slip region on `steps` steps ([module docs](self)):
/// the `α` where the impact stops ending in gross slip at the `+` limit
/// ([`ends_in_full_slip_thornton`]), bisected to `1e-12` relative in a bracket found by
/// doubling the distance from the Kelvin–Voigt `α_c1(γ, e_n)` (up where the impact at `α_c1`
/// ends in full slip, down where it does not). `γ > 1` (at and below 1 the elastic full-slip
/// line ends at `α_c2`, where no such edge has been traced), `e_n ∈ [0.3, 1)`.
///
/// Errors: `γ ≤ 1` or not finite, `e_n` outside `[0.3, 1)`, `steps < 8`, and
/// [`PhysicsError::InvalidParameter`] naming `alpha` if no bracket is found between 0 and
/// `α_c2`.
pub fn full_slip_edge_thornton(gamma: f64, e_n: f64, steps: usize) -> Result<f64, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    if !(gamma > 1.0 && gamma.is_finite()) {
        return Err(PhysicsError::InvalidParameter {
            name: "gamma",
            value: gamma,
            allowed: "> 1 and finite (the full-slip edge is traced above gamma = 1)",
        });
    }
    let e_n = check_restitution(e_n)?;
    if Law::Thornton.answering(e_n) == Law::Elastic {
        return Err(PhysicsError::InvalidParameter {
            name: "e_n",
            value: e_n,
            allowed: "in [0.3, 1) (at e_n = 1 the edge is the elastic alpha_c1)",
        });
    }
    let c1 = oblique_physics::regimes::alpha_c1_dissipative(gamma, e_n);
    let c2 = oblique_physics::regimes::alpha_c2(gamma);
    let ends = |a: f64| ends_in_full_slip_thornton(gamma, a, e_n, steps);
    let no_bracket = |a: f64| PhysicsError::InvalidParameter {
        name: "alpha",
        value: a,
        allowed: "a bracket of the full-slip edge between 0 and alpha_c2",
    };
    // A bracket `ends(lo) && !ends(hi)`, by doubling the distance from α_c1 upwards or
    // downwards.
    let (mut lo, mut hi);
    let mut step = 1e-3 * c1;
    if ends(c1)? {
        lo = c1;
        hi = c1 + step;
        while ends(hi)? {
            lo = hi;
            step *= 2.0;
            hi = c1 + step;
            if hi >= c2 {
                return Err(no_bracket(hi));
            }
        }
    } else {
        hi = c1;
        lo = c1 - step;
        while !ends(lo)? {
            hi = lo;
            step *= 2.0;
            lo = c1 - step;
            if lo <= 0.0 {
                return Err(no_bracket(lo));
            }
        }
    }
    while hi - lo > 1e-12 * hi {
        let mid = 0.5 * (lo + hi);
        if ends(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Smallest fraction of the contact radius at the `+` limit that counts as a loading zone in
/// [`has_loading_zone_thornton`] (the row leaves pieces of zero length at the limit for a step
/// now and then; a zone next to its fold is `√(α_L − α)` wide, 1e-6 of the radius about 1e-12
/// below `α_L` relative).
pub const LOADING_ZONE_MIN: f64 = 1e-6;

/// The predicate of the loading fold `α_L(γ, e_n)` of Thornton's law
/// ([`loading_fold_thornton`]): in the impact at `steps` steps per contact time a zone of the
/// contact reaches the `+μq` limit (more than [`LOADING_ZONE_MIN`] of the radius at some step),
/// opening after the first step and closing before `0.95 t_s` (`t_s` the switch to unloading).
/// Errors as [`slip_pattern_thornton`].
pub fn has_loading_zone_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<bool, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
    let t_switch = motion.switch_time / motion.contact_time;
    let (log, _) = slip_pattern_thornton(gamma, alpha, e_n, steps)?;
    let mut open: Option<(f64, f64)> = None;
    let mut prev = 0.0;
    for &(t, plus, ..) in &log {
        match (&mut open, plus > 0.0) {
            (None, true) => open = Some((prev, plus)),
            (Some((_, m)), true) => *m = m.max(plus),
            (Some((t0, m)), false) => {
                if *t0 > 0.0 && prev < 0.95 * t_switch && *m > LOADING_ZONE_MIN {
                    return Ok(true);
                }
                open = None;
            }
            (None, false) => {}
        }
        prev = t;
    }
    Ok(false)
}

/// The loading fold `α_L(γ, e_n)` of Thornton's law in the stick patch (`docs/solver.md`,
/// "Kinks inside the slip regions"): below it a `+` partial-slip zone opens and closes again
/// while the contact loads ([`has_loading_zone_thornton`]), above it none does, and `P` leaves
/// its smooth continuation from above like `(α_L − α)^{3/2}` (0.6 `(1 − α/α_L)^{3/2}` at
/// γ = 1.6, `e_n` = 0.8, where `α_L = 1.1429 α_c2`). Located on `steps` steps: from
/// `α_c2 (1 + 1e-4)` up by factors of 1.1 to the first `α` where the predicate fails, then
/// bisected to `1e-10` in `ln α`. `None` where the predicate fails just above `α_c2` (the fold
/// has reached `α_c2`: at γ = 1.6 between `e_n` = 0.85 and 0.9) or still holds at
/// `1e3 α_c2`; `e_n = 1` (elastic: no fold) gives `None`.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn loading_fold_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let Some((gamma, e_n)) = fold_inputs(gamma, e_n)? else {
        return Ok(None);
    };
    let c2 = oblique_physics::regimes::alpha_c2(gamma);
    let holds = |a: f64| has_loading_zone_thornton(gamma, a, e_n, steps);
    let start = c2 * (1.0 + 1e-4);
    if !holds(start)? {
        return Ok(None);
    }
    fold_above(start, 1.1, 1e3 * c2, holds)
}

/// How far below `α_c2` (a multiple of it) [`loading_band_thornton`] looks for the loading
/// band: as `e_n` grows to 1 the band falls (at γ = 1.7: 0.955–1.115 `α_c2` at `e_n` = 0.8,
/// 0.635–0.645 at 0.98, 0.450–0.451 at 0.999; `thornband`).
pub const LOADING_BAND_MIN: f64 = 0.2;

/// The factor of the scan down from `α_c2` with which [`loading_band_thornton`] looks for a
/// band that lies wholly below it: a band narrower than 0.2 % in α is missed (at γ = 1.7 the
/// band is 0.5 % wide at `e_n` = 0.99, 0.2 % at 0.999).
pub const LOADING_BAND_SCAN: f64 = 1.002;

/// The loading band of Thornton's law at `(γ, e_n)`: the interval `(α_lo, α_hi)` of α where a
/// zone at the `+μq` limit opens and closes while the contact loads
/// ([`has_loading_zone_thornton`]). Its upper edge is a kink of `P` (`P` changes its slope
/// there), the loading fold `α_L` ([`loading_fold_thornton`]) while that lies above `α_c2`; at
/// its lower edge the zone is born with zero size and `P` shows no kink (second differences
/// smooth to 1e-9 at γ = 1.7, `e_n` = 0.6, 0.9, 0.98 and γ = 2.5, `e_n` = 0.85), and the located
/// edge moves by up to 4e-3 between 2 048 and 8 192 steps. As `e_n` falls the band
/// rises through `α_c2` (γ = 1.7: 0.635–0.645 `α_c2` at `e_n` = 0.98, 0.86–0.925 at 0.9,
/// 0.955–1.115 at 0.8), its lower edge ever closer below `α_c2` (0.996 `α_c2` at 0.6, 0.9999
/// at 0.4) and its upper edge ever higher (2.3 `α_c2` at 0.5).
///
/// Located on `steps` steps: a point of the band at `α_c2 (1 + 1e-4)` where the predicate holds
/// there, else the first α where it holds on a scan down
/// from `α_c2` by factors of [`LOADING_BAND_SCAN`] to [`LOADING_BAND_MIN`] `α_c2`; from that
/// point each edge is bracketed by steps that double in `ln α` (from 1 %) and bisected to
/// `1e-8` in `ln α`. `None` where no point of the band is found, its upper edge lies beyond
/// `1e3 α_c2` or its lower edge below [`LOADING_BAND_MIN`] `α_c2`; `e_n = 1` (elastic) gives
/// `None`.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn loading_band_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<(f64, f64)>, PhysicsError> {
    let Some((gamma, e_n)) = fold_inputs(gamma, e_n)? else {
        return Ok(None);
    };
    let c2 = oblique_physics::regimes::alpha_c2(gamma);
    let holds = |a: f64| has_loading_zone_thornton(gamma, a, e_n, steps);
    let (min, max) = (LOADING_BAND_MIN * c2, 1e3 * c2);
    let mut inside = None;
    if holds(c2 * (1.0 + 1e-4))? {
        inside = Some(c2 * (1.0 + 1e-4));
    } else {
        let mut a = c2;
        while a > min {
            a /= LOADING_BAND_SCAN;
            if holds(a)? {
                inside = Some(a);
                break;
            }
        }
    }
    let Some(inside) = inside else {
        return Ok(None);
    };
    let (Some(lo), Some(hi)) = (
        band_edge(inside, min, &holds)?,
        band_edge(inside, max, &holds)?,
    ) else {
        return Ok(None);
    };
    Ok(Some((lo, hi)))
}

/// The upper edge of the loading band ([`loading_band_thornton`]) inside `(below, above)`, where
/// [`has_loading_zone_thornton`] holds at `below` and fails at `above`, bisected to `1e-8` in
/// `ln α` on `steps` steps; `None` where the ends do not differ so (the tracing of the probes
/// then searches the band again).
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`, a bracket not
/// `0 < below < above`, finite.
pub fn loading_band_top_within_thornton(
    gamma: f64,
    e_n: f64,
    (below, above): (f64, f64),
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    if !(below > 0.0 && above > below && above.is_finite()) {
        return Err(PhysicsError::InvalidParameter {
            name: "alpha bracket",
            value: above,
            allowed: "0 < below < above, finite",
        });
    }
    let Some((gamma, e_n)) = fold_inputs(gamma, e_n)? else {
        return Ok(None);
    };
    let holds = |a: f64| has_loading_zone_thornton(gamma, a, e_n, steps);
    if !holds(below)? || holds(above)? {
        return Ok(None);
    }
    let edge = bisect_edge((below.ln(), above.ln()), BAND_LN_TOL, |l| holds(l.exp()))?;
    Ok(Some(edge.exp()))
}

/// How closely (in `ln α`) the edges of the loading band are located: the upper edge moves by
/// about 1e-6 relative between 2 048 and 8 192 steps (γ = 1.7, `e_n` = 0.9: 0.922311 and 0.922310
/// `α_c2`), the lower one by up to 4e-3 (0.85575 and 0.85501).
const BAND_LN_TOL: f64 = 1e-8;

/// The edge of a band from a point `inside` it towards `limit` (below or above): steps from
/// `inside` that double in `ln α` from 1 % while the predicate holds (`None` once a step passes
/// `limit`), then the last bracket bisected to `1e-8` in `ln α`.
fn band_edge(
    inside: f64,
    limit: f64,
    holds: &impl Fn(f64) -> Result<bool, PhysicsError>,
) -> Result<Option<f64>, PhysicsError> {
    let dir = if limit > inside { 1.0 } else { -1.0 };
    let (start, end) = (inside.ln(), limit.ln());
    let (mut held, mut step) = (start, 0.01);
    loop {
        let next = held + dir * step;
        if dir * (next - end) > 0.0 {
            return Ok(None);
        }
        if !holds(next.exp())? {
            // The edge lies between `held` (holds) and `next` (fails).
            let (a, b) = if dir > 0.0 {
                (held, next)
            } else {
                (next, held)
            };
            let edge = bisect_edge((a, b), BAND_LN_TOL, |l| {
                holds(l.exp()).map(|h| h == (dir > 0.0))
            })?;
            return Ok(Some(edge.exp()));
        }
        held = next;
        step *= 2.0;
    }
}

/// The predicate of the re-slip fold `α_R(γ, e_n)` of Thornton's law
/// ([`reslip_fold_thornton`]): the impact at `steps` steps per contact time has a `+μF_N`
/// gross-slip episode that starts after the switch to unloading (past `1.01 t_s`) and ends
/// before the last step (the contact slips back at `+` for a while after the central springs
/// stuck at the switch, then sticks and ends in `−` slip). Errors as [`slip_history_thornton`].
pub fn has_reslip_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<bool, PhysicsError> {
    let e_n = check_restitution(e_n)?;
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
    let t_switch = motion.switch_time / motion.contact_time;
    let h = slip_history_thornton(gamma, alpha, e_n, steps)?;
    let last = h.episodes.last().map_or(1.0, |e| e.end);
    Ok(h.episodes
        .iter()
        .any(|e| e.sign == SlipSign::Plus && e.start > 1.01 * t_switch && e.end < last.min(0.999)))
}

/// The re-slip fold `α_R(γ, e_n)` of Thornton's partial-slip patch (`docs/solver.md`, "Kinks
/// inside the slip regions"): above the full-slip edge `α₁` the contact slips back at `+μF_N`
/// for a while after the switch to unloading ([`has_reslip_thornton`]); that episode shrinks as
/// α grows and vanishes at `α_R`, where `P` leaves its smooth continuation from below like
/// `(α − α_R)^{3/2}` (0.2400 at γ = 1.754, `e_n` = 0.8). Located on `steps` steps: from
/// `1.001 α_c1(γ, e_n)` (the Kelvin–Voigt `α_c1`, within −3.3 % to +0.65 % of `α₁`) up by
/// factors of 1.01 to the first `α` where the predicate holds, on to the first where it fails
/// again, then bisected to `1e-10` in `ln α`. `None` where it never holds below `α_c2` or still
/// holds there; `e_n = 1` gives `None` (the elastic law answers; its folds are F₊ and F₋).
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn reslip_fold_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let Some((gamma, e_n)) = fold_inputs(gamma, e_n)? else {
        return Ok(None);
    };
    let c1 = oblique_physics::regimes::alpha_c1_dissipative(gamma, e_n);
    let c2 = oblique_physics::regimes::alpha_c2(gamma);
    let holds = |a: f64| has_reslip_thornton(gamma, a, e_n, steps);
    // Up from just above α_c1 to where the episode first shows apart from the first one (next
    // to α₁ it ends at the separation, and first it is less than `MERGE_GAP` after the
    // switch), then on to where it has gone.
    let mut lo = 1.001 * c1;
    while !holds(lo)? {
        lo *= 1.01;
        if lo >= c2 {
            return Ok(None);
        }
    }
    fold_above(lo, 1.01, c2, holds)
}

/// One entry of [`slip_zones_thornton`]: the time (fraction of the contact time) and the zones
/// `(kind, x0, x1)` from the centre, `kind` +1 at the `+μq` limit, −1 at the `−μq` limit, 0
/// stuck, `x` in fractions of the contact radius (neighbouring pieces of one kind joined).
pub type ZoneSnapshot = (f64, Vec<(i8, f64, f64)>);

/// A Thornton row that records its zones after the switch to unloading and, with `every`,
/// after every step.
struct ZoneRow<'a> {
    row: ThorntonRow,
    every: bool,
    log: &'a mut Vec<Vec<(i8, f64, f64)>>,
    /// Index into the log of the entry made at the switch.
    switch_at: &'a mut Option<usize>,
}

impl TangentialModel for ZoneRow<'_> {
    const END_STATE: bool = true;
    fn at_limit(&self) -> (bool, bool) {
        self.row.at_limit()
    }
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let r = self.row.step(m, d1, c);
        if self.every {
            self.log.push(self.row.zones());
        }
        r
    }
    fn jump(&mut self, start: (f64, f64), end: (f64, f64), c: f64) -> Option<StepResult> {
        let r = self.row.jump(start, end, c);
        if r.is_some() {
            *self.switch_at = Some(self.log.len());
            self.log.push(self.row.zones());
        }
        r
    }
}

/// Zones in fractions of the outer end of the last one (the contact radius).
fn scaled_zones(zones: Vec<(i8, f64, f64)>) -> Vec<(i8, f64, f64)> {
    let edge = zones.last().map_or(0.0, |z| z.2);
    let scale = if edge > 0.0 { 1.0 / edge } else { 0.0 };
    zones
        .into_iter()
        .map(|(k, x0, x1)| (k, x0 * scale, x1 * scale))
        .collect()
}

/// One run recording zones ([`ZoneRow`]): the zone log, the index of the switch's entry, the
/// `(start, length)` of every step, `P` and the switch time (fraction of the contact time).
#[allow(clippy::type_complexity)]
fn run_zones(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
    every: bool,
) -> Result<
    (
        Vec<Vec<(i8, f64, f64)>>,
        Option<usize>,
        Vec<(f64, f64)>,
        f64,
        f64,
    ),
    PhysicsError,
> {
    let e_n = check_restitution(e_n)?;
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let motion = dimensionless_motion(yield_pressure_for_restitution(e_n)?);
    let trajectory = dimensionless_trajectory(&motion, steps);
    let (shear, limit) = shear_and_limit(gamma, alpha);
    let mut rec = Recorder {
        point: ContactPoint { u: 1.0 },
        t: 0.0,
        log: Vec::with_capacity(steps + steps / 8),
    };
    let mut log = Vec::with_capacity(if every { steps + steps / 8 } else { 1 });
    let mut switch_at = None;
    let row = ZoneRow {
        row: ThorntonRow::new(
            1.0,
            motion.loading.yield_indentation,
            motion.unloading.ratio,
            motion.unloading.plastic_indentation,
        ),
        every,
        log: &mut log,
        switch_at: &mut switch_at,
    };
    run_contact_with(&mut rec, &*trajectory, row, 1.0, shear, limit);
    let times = rec.log.iter().map(|&(t, h, _)| (t, h)).collect();
    let t_switch = motion.switch_time / motion.contact_time;
    Ok((log, switch_at, times, rec.point.u, t_switch))
}

/// Every zone of the contact after every step of one run of Thornton's law, and one entry for
/// the field clipped at the switch to unloading (at the switch's time): `(t, zones)` with `t`
/// the step's end (fraction of the contact time) and the zones from the centre
/// ([`ZoneSnapshot`]); and `P`. Diagnostics for the kinks of `P` that the numbers of lasting
/// zones ([`slip_pattern_thornton`]) do not show: a zone of the clipped field at the switch
/// lasts no step. Errors as [`slip_pattern_thornton`].
pub fn slip_zones_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<(Vec<ZoneSnapshot>, f64), PhysicsError> {
    let (log, switch_at, times, p, t_switch) = run_zones(gamma, alpha, e_n, steps, true)?;
    let contact_time = times.last().map_or(1.0, |&(t, h)| t + h);
    let mut ends = times.iter().map(|&(t, h)| (t + h) / contact_time);
    let out = log
        .into_iter()
        .enumerate()
        .map(|(i, zones)| {
            let t = if Some(i) == switch_at {
                t_switch
            } else {
                ends.next().unwrap_or(1.0)
            };
            (t, scaled_zones(zones))
        })
        .collect();
    Ok((out, p))
}

/// The zones of the field clipped at the switch to unloading, from the centre (`x` in
/// fractions of the contact radius, [`ZoneSnapshot`]); empty where the run has no switch.
/// Errors as [`slip_pattern_thornton`].
pub fn switch_zones_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<Vec<(i8, f64, f64)>, PhysicsError> {
    let (mut log, switch_at, ..) = run_zones(gamma, alpha, e_n, steps, false)?;
    Ok(switch_at
        .and_then(|i| log.get_mut(i).map(std::mem::take))
        .map(scaled_zones)
        .unwrap_or_default())
}

/// Smallest fraction of the contact radius at the `+` limit that counts as a zone of the field
/// clipped at the switch in [`has_switch_zone_thornton`] (the zone next to its fold is
/// `√(α_S − α)` wide: 1e-6 of the radius about 1e-12 below `α_S` relative).
pub const SWITCH_ZONE_MIN: f64 = 1e-6;

/// The largest `α` up to which [`switch_fold_thornton`] looks for the fold (it lies between
/// 0.29 and 0.40 over γ 1.05–2.6, `e_n` 0.3–0.9999).
pub const SWITCH_FOLD_MAX: f64 = 1.0;

/// The predicate of the switch fold `α_S(γ, e_n)` of Thornton's law
/// ([`switch_fold_thornton`]): in the impact at `steps` steps per contact time, the field
/// clipped against the unloading limits at the switch to unloading has a zone at the `+μq`
/// limit more than [`SWITCH_ZONE_MIN`] of the contact radius wide ([`switch_zones_thornton`]).
/// Errors as [`slip_pattern_thornton`].
pub fn has_switch_zone_thornton(
    gamma: f64,
    alpha: f64,
    e_n: f64,
    steps: usize,
) -> Result<bool, PhysicsError> {
    let zones = switch_zones_thornton(gamma, alpha, e_n, steps)?;
    Ok(zones
        .iter()
        .any(|&(k, x0, x1)| k == 1 && x1 - x0 > SWITCH_ZONE_MIN))
}

/// The switch fold `α_S(γ, e_n)` of Thornton's partial-slip patch (`docs/solver.md`, "Kinks
/// inside the slip regions"). At the switch to unloading the limits jump (centre up, edge
/// down) and every spring keeps its displacement: outside the radius where the two limits
/// cross, the springs that are at or near the loading `+` limit stand above the unloading one
/// and are clipped to it ([`has_switch_zone_thornton`]). Above `α = 2/7` the first gross-slip
/// episode ends before the switch and the contact sticks from its edge inwards; as α grows the
/// stuck field lies further below the loading limit, the clipped zone shrinks to a point inside
/// the contact (the field touches the unloading limit there) and vanishes at `α_S`, where `P`
/// leaves its smooth continuation from below like `(α_S − α)^{3/2}` (the clipped area is its
/// depth times its width, `√(α_S − α)`): 0.3644 at γ = 1.754, `e_n` = 0.8.
///
/// Located on `steps` steps: from `(2/7)(1 + 1e-4)` up by factors of 1.01 to the first `α`
/// where the predicate fails, then bisected to `1e-10` in `ln α`; the search does not stop at
/// `α_c2` (next to γ = 1, at γ 1.02–1.1, `α_S` lies in the stick patch, where `P` has the same
/// kink). `None` where the predicate fails at the start or still holds at
/// [`SWITCH_FOLD_MAX`]; `e_n = 1` gives `None` (the elastic law's limits do not jump).
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn switch_fold_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let Some((gamma, e_n)) = fold_inputs(gamma, e_n)? else {
        return Ok(None);
    };
    let holds = |a: f64| has_switch_zone_thornton(gamma, a, e_n, steps);
    let start = 2.0 / 7.0 * (1.0 + 1e-4);
    if !holds(start)? {
        return Ok(None);
    }
    fold_above(start, 1.01, SWITCH_FOLD_MAX, holds)
}

/// The switch sheet `e_S(γ, α)` of Thornton's stick patch (`docs/solver.md`, "Kinks inside the
/// slip regions"): at small `e_n` the field clipped at the switch to unloading has a `+` zone at
/// the contact's edge there too ([`has_switch_zone_thornton`], the predicate of
/// [`switch_fold_thornton`]), which lasts into the restitution; it ceases as `e_n` grows, on a
/// sheet across the `e_n` axis nearly flat in α (γ = 1.7: between 0.515 and 0.5225 at 3 `α_c2`),
/// where `P` leaves its smooth continuation below it. Located on `steps` steps by bisection in
/// `e_n` to `1e-9` inside `(e_lo, e_hi)`, where the predicate holds at `e_lo` and fails at
/// `e_hi`; `None` where it does not (no sheet there, or more than one edge between them that
/// the ends do not show).
///
/// Errors: `γ` or `α` not positive and finite, `e_lo < e_hi` not inside `[0.3, 1]`, `steps < 8`.
pub fn switch_sheet_thornton(
    gamma: f64,
    alpha: f64,
    (e_lo, e_hi): (f64, f64),
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    let (lo, hi) = (check_restitution(e_lo)?, check_restitution(e_hi)?);
    if lo >= hi {
        return Err(PhysicsError::InvalidParameter {
            name: "e_n range",
            value: hi - lo,
            allowed: "> 0 (its upper end above its lower)",
        });
    }
    let holds = |e: f64| has_switch_zone_thornton(gamma, alpha, e, steps);
    if !holds(lo)? || holds(hi)? {
        return Ok(None);
    }
    bisect_edge((lo, hi), 1e-9, holds).map(Some)
}

/// Every edge of the switch sheet in `(e_lo, e_hi)` at `(γ, α)`: where the `+` zone of the
/// clipped field ([`has_switch_zone_thornton`]) appears or ceases as `e_n` grows, bracketed by
/// a scan in steps of at most `scan` and bisected to `1e-9` (as [`switch_sheet_thornton`]), in
/// increasing `e_n`, each with whether the zone exists above it (a lower edge of a band, where
/// `P` leaves its smooth continuation above it) or below it (an upper edge). The zone exists in
/// a band of `e_n` over much of the stick patch from γ ≈ 2: at γ 2.3, 10 `α_c2` in two,
/// `e_n` 0.3–0.305 and 0.400–0.725 (`cargo run --release -p oblique-tools --bin thornfold --
/// --band 2.3 10`). Two edges closer than the scan are missed.
///
/// Errors: as [`switch_sheet_thornton`], or `scan` not positive.
pub fn switch_sheet_edges_thornton(
    gamma: f64,
    alpha: f64,
    range: (f64, f64),
    scan: f64,
    steps: usize,
) -> Result<Vec<(f64, bool)>, PhysicsError> {
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    edges_along_e_n(range, scan, |e| {
        has_switch_zone_thornton(gamma, alpha, e, steps)
    })
}

/// Every edge in `e_n` of the end-of-contact sheet `e_E(γ, α)` of Thornton's law (the stick
/// patch, and from γ ≈ 1.86 the partial-slip patch) in `(e_lo, e_hi)` at `(γ, α)`: where the impact starts or stops ending in a `−μF_N` episode
/// that runs into the separation ([`has_end_minus`], the predicate of the curves E₋ of
/// [`end_minus_edges_thornton`]) as `e_n` grows, bracketed by a scan in steps of at most `scan`
/// and bisected to `1e-9`, in increasing `e_n`, each with whether the episode exists above it
/// (a lower edge) or below it (an upper edge). At small `e_n` the contact ends in a `−` episode
/// over most of the stick patch, and a short `+` episode takes the end from an upper edge
/// nearly flat in α above about 2.5 `α_c2` (γ 1.66: 0.307 at 2 `α_c2`, 0.328 at 3, 0.322 at
/// 10), where the curvature of `P` along `e_n` jumps (about fourfold there at 3 `α_c2`;
/// `docs/solver.md`, "The end-of-contact sheet"). Along α that edge is nearly parallel to the
/// axis, so the search of [`end_minus_edges_thornton`] finds it only where it falls towards
/// `α_c2`. Two edges closer than the scan are missed.
///
/// Errors: `γ` or `α` not positive and finite, `e_lo < e_hi` not inside `[0.3, 1]`, `scan` not
/// positive, `steps < 8`.
pub fn end_minus_sheet_edges_thornton(
    gamma: f64,
    alpha: f64,
    range: (f64, f64),
    scan: f64,
    steps: usize,
) -> Result<Vec<(f64, bool)>, PhysicsError> {
    let (gamma, alpha) = check_history_input(gamma, alpha, steps)?;
    edges_along_e_n(range, scan, |e| {
        Ok(has_end_minus(&slip_history_thornton(
            gamma, alpha, e, steps,
        )?))
    })
}

/// The edges of `holds` in `(e_lo, e_hi)` (checked): a scan in steps of at most `scan`, each
/// change bisected to `1e-9`, with whether `holds` is true above it.
fn edges_along_e_n(
    (e_lo, e_hi): (f64, f64),
    scan: f64,
    holds: impl Fn(f64) -> Result<bool, PhysicsError>,
) -> Result<Vec<(f64, bool)>, PhysicsError> {
    let (lo, hi) = (check_restitution(e_lo)?, check_restitution(e_hi)?);
    if lo >= hi || scan.is_nan() || scan <= 0.0 {
        return Err(PhysicsError::InvalidParameter {
            name: "e_n range",
            value: hi - lo,
            allowed: "> 0 (its upper end above its lower), scanned in steps > 0",
        });
    }
    let n = ((hi - lo) / scan).ceil().max(1.0) as usize;
    let e = |k: usize| {
        if k == n {
            hi
        } else {
            lo + (hi - lo) * k as f64 / n as f64
        }
    };
    let mut edges = Vec::new();
    let mut below = holds(e(0))?;
    for k in 1..=n {
        let here = holds(e(k))?;
        if here != below {
            let bracket = (e(k - 1), e(k));
            let edge = if below {
                bisect_edge(bracket, 1e-9, &holds)?
            } else {
                bisect_edge(bracket, 1e-9, |e| holds(e).map(|h| !h))?
            };
            edges.push((edge, here));
        }
        below = here;
    }
    Ok(edges)
}

/// The factor by which [`fold_minus_thornton`] steps up in α while it looks for F₋'s
/// predicate: the interval below F₋ where it holds is 1.2 % of α wide at γ 2.0, `e_n` 0.3
/// (next to its birth), 3–12 % elsewhere up to γ 2.6.
pub const FOLD_MINUS_SCAN: f64 = 1.005;

/// The fold F₋ of Thornton's partial-slip patch (`docs/solver.md`, "Kinks inside the slip
/// regions"): the elastic law's F₋ (a `−μF_N` episode late in the restitution that vanishes as
/// α grows, [`has_restitution_minus`]) continued to `e_n < 1`, where plasticity brings it to
/// lower γ (born near γ 1.95 at `e_n` 0.3, 2.05 at 0.6, 2.15 at 0.8, 2.37 at 1), always above the
/// switch fold `α_S`. `P` has a kink there, smooth on neither side (its curvature rises
/// towards it from below and jumps across it): 0.4346 at γ = 2.3, `e_n` = 0.6.
///
/// Located on `steps` steps: from `(2/7)(1 + 1e-4)` up by factors of [`FOLD_MINUS_SCAN`] to the
/// first α where the predicate holds, on to the first where it fails again, then bisected to
/// `1e-10` in `ln α`. `None` where it does not hold below `α_c2` (no F₋ at this γ and `e_n`, or
/// an interval narrower than a step, next to its birth). At `e_n = 1` the elastic histories
/// answer (the elastic F₋).
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn fold_minus_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    let max = oblique_physics::regimes::alpha_c2(gamma);
    let holds = |a: f64| {
        Ok(has_restitution_minus(&slip_history_thornton(
            gamma, a, e_n, steps,
        )?))
    };
    let mut start = 2.0 / 7.0 * (1.0 + 1e-4);
    while !holds(start)? {
        start *= FOLD_MINUS_SCAN;
        if start > max {
            return Ok(None);
        }
    }
    fold_above(start, FOLD_MINUS_SCAN, max, holds)
}

/// Where F₋ of Thornton's law is first found (`thornfold --minus-birth`: bisection in γ to
/// 1e-3 on whether [`fold_minus_thornton`] finds it, 2 048 steps): `(e_n, γ)`, the lower end of
/// each bracket, by rising `e_n`; at `e_n = 1` the elastic birth
/// ([`super::fold_minus_free_below`]).
const FOLD_MINUS_BIRTHS_THORNTON: [(f64, f64); 12] = [
    (0.3, 1.8729),
    (0.35, 1.8976),
    (0.4, 1.9140),
    (0.5, 1.9680),
    (0.6, 2.0281),
    (0.7, 2.0917),
    (0.8, 2.1648),
    (0.9, 2.2510),
    (0.95, 2.3084),
    (0.97, 2.3337),
    (0.99, 2.3679),
    (1.0, 2.3666),
];

/// How far below its measured birth F₋ of Thornton's law may already exist: the search of
/// [`fold_minus_thornton`] steps over an interval of its predicate narrower than
/// [`FOLD_MINUS_SCAN`], as next to the birth, where it finds the elastic F₋ (`e_n` = 1) from
/// γ 2.3815 against 2.3666 measured by a search that zooms in.
pub const FOLD_MINUS_BIRTH_MARGIN: f64 = 0.02;

/// A γ below which Thornton's `P(γ, α, e)` has no fold F₋ for any `e ≥ e_n_min` (`e_n_min` in
/// `[0.3, 1]`): plasticity brings F₋'s birth to lower γ the lower `e_n` (measured at twelve
/// `e_n`), so the birth at the nearest measured `e_n` at or below `e_n_min`, less
/// [`FOLD_MINUS_BIRTH_MARGIN`], bounds it from below. A table that reaches F₋ must measure its
/// leaves next to it.
pub fn fold_minus_free_below_thornton(e_n_min: f64) -> f64 {
    FOLD_MINUS_BIRTHS_THORNTON
        .iter()
        .rev()
        .find(|&&(e, _)| e <= e_n_min)
        .map_or(FOLD_MINUS_BIRTHS_THORNTON[0].1, |&(_, g)| g)
        .min(super::fold_minus_free_below(1.0))
        - FOLD_MINUS_BIRTH_MARGIN
}

/// [`fold_minus_thornton`] by continuation from `guess` (as [`fold_minus_at`] locates the
/// elastic F₋): the guess must lie below F₋ inside its predicate's interval, or above F₋ within
/// a factor `e`; `None` where the search finds no change. A tracing steps from node to node
/// with it (the full search of [`fold_minus_thornton`] costs about four times more).
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn fold_minus_at_thornton(
    gamma: f64,
    e_n: f64,
    guess: f64,
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    fold_at_thornton(
        (gamma, e_n),
        guess,
        steps,
        has_restitution_minus,
        LOCATE_LN_ALPHA,
    )
}

/// The continuation of [`fold_at_with`] on Thornton's histories at `(γ, e_n)` for the curve
/// whose `present` predicate holds below it, located to `ln_tol` in `ln α` (the locators of
/// [`fold_minus_at_thornton`] and [`end_minus_at_thornton_within`]).
fn fold_at_thornton(
    (gamma, e_n): (f64, f64),
    guess: f64,
    steps: usize,
    present: fn(&SlipHistory) -> bool,
    ln_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    let steps = check_fold_steps(steps)?;
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    let ln_tol = crate::error::positive("ln_tol", ln_tol)?;
    fold_at_with(
        |a: f64| slip_history_thornton(gamma, a, e_n, steps),
        guess,
        present,
        ln_tol,
    )
}

/// The end-of-contact curves E₋ of Thornton's law at `(γ, e_n)`: every α in
/// `[alpha_lo, alpha_hi]` where the impact stops ending in a `−μF_N` episode that runs into the
/// separation ([`has_end_minus`], holding below), in increasing α, on `steps` steps (a log grid
/// of `n` intervals, each change bisected to ≈1e-10 in `ln α`; an interval narrower than a
/// grid step can be missed). The elastic law's E₋ (`docs/solver.md`, "Kink curves") continued to
/// `e_n < 1`: it comes down from α → ∞ (γ 1.75: 9.5 at `e_n` 1, 2.85 at 0.9, 0.97 at 0.7) and
/// at small `e_n` there are several. `P` has no slope jump there, but its curvature changes
/// fast on one side: a cubic across it errs more than its neighbours predict.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`, `0 < lo < hi`
/// not within `1e10`, `n < 2`.
pub fn end_minus_edges_thornton(
    gamma: f64,
    e_n: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    n: usize,
    steps: usize,
) -> Result<Vec<f64>, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    super::damped::falling_edges(
        |a: f64| slip_history_thornton(gamma, a, e_n, steps),
        (alpha_lo, alpha_hi),
        n,
        has_end_minus,
    )
}

/// An end-of-contact curve E₋ of Thornton's law ([`end_minus_edges_thornton`]) at `(γ, e_n)`
/// by continuation from `guess` (as [`super::end_minus_at`] locates the elastic E₋), located to
/// `ln_tol` (`> 0`) in `ln α`: the guess must lie below the curve or above it within a factor
/// `e`; `None` where the search finds no change.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`, `ln_tol ≤ 0`.
pub fn end_minus_at_thornton_within(
    gamma: f64,
    e_n: f64,
    guess: f64,
    steps: usize,
    ln_tol: f64,
) -> Result<Option<f64>, PhysicsError> {
    fold_at_thornton((gamma, e_n), guess, steps, has_end_minus, ln_tol)
}

/// How far up in α (multiples of `α_c2`) [`restitution_plus_strip_thornton`] looks for the
/// strip (at most 1.41 `α_c2` where it was found, γ 2.0–2.6).
pub const PLUS_STRIP_MAX: f64 = 3.0;

/// The strip of Thornton's law where a `+μF_N` episode of the restitution exists
/// ([`has_restitution_plus`], the predicate of the elastic fold F₊; `docs/solver.md`, "Kinks
/// inside the slip regions"): `(α_lo, α_hi)`, the first interval above `α = 2/7` (above the
/// re-slip episode of `α_R`, which holds the predicate too) on which it holds, both edges kinks
/// of `P`. It rises with `e_n` from the partial-slip patch into the stick patch (γ = 2.3:
/// 0.384–0.402 `α_c2` at `e_n` = 0.3, 1.078–1.177 at 0.55, none from 0.575).
///
/// Located on `steps` steps: from `(2/7)(1 + 1e-3)` up by factors of 1.01 (a strip narrower than
/// that is missed) to the first α where the predicate holds, on to the first where it fails,
/// each edge bisected to `1e-10` in `ln α`. `None` where it does not hold below
/// [`PLUS_STRIP_MAX`] `α_c2`.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`.
pub fn restitution_plus_strip_thornton(
    gamma: f64,
    e_n: f64,
    steps: usize,
) -> Result<Option<(f64, f64)>, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    let max = PLUS_STRIP_MAX * oblique_physics::regimes::alpha_c2(gamma);
    let holds = |a: f64| {
        Ok(has_restitution_plus(&slip_history_thornton(
            gamma, a, e_n, steps,
        )?))
    };
    let factor = 1.01;
    let mut below = 2.0 / 7.0 * (1.0 + 1e-3);
    if holds(below)? {
        return Ok(None);
    }
    let mut at = below * factor;
    while !holds(at)? {
        below = at;
        at *= factor;
        if at > max {
            return Ok(None);
        }
    }
    // Its lower edge: the negation holds below it.
    let lo = bisect_edge((below.ln(), at.ln()), 1e-10, |l| holds(l.exp()).map(|h| !h))?.exp();
    let Some(hi) = fold_above(at, factor, max, holds)? else {
        return Ok(None);
    };
    Ok(Some((lo, hi)))
}

/// An edge of the strip of [`restitution_plus_strip_thornton`] inside `(alpha_lo, alpha_hi)`,
/// where [`has_restitution_plus`] holds at one end and not at the other, bisected to `1e-10`
/// in `ln α` on `steps` steps; `None` where both ends agree. The strip's lower edge converges
/// late in the steps (1.6263 at 2 048 and 4 096 steps, 1.62651 from 8 192 at γ = 2.3,
/// `e_n` = 0.55): a search at 2 048 steps brackets it, this places it at a finer resolution.
///
/// Errors: `γ` not positive and finite, `e_n` outside `[0.3, 1]`, `steps < 8`, a bracket not
/// `0 < lo < hi`.
pub fn restitution_plus_change_thornton(
    gamma: f64,
    e_n: f64,
    (alpha_lo, alpha_hi): (f64, f64),
    steps: usize,
) -> Result<Option<f64>, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    if !(alpha_lo > 0.0 && alpha_hi > alpha_lo && alpha_hi.is_finite()) {
        return Err(PhysicsError::InvalidParameter {
            name: "alpha bracket",
            value: alpha_hi,
            allowed: "0 < lo < hi, finite",
        });
    }
    let iterations = ((alpha_hi / alpha_lo).ln() / 1e-10).log2().ceil().max(1.0) as usize;
    locate_change_with(
        |a: f64| slip_history_thornton(gamma, a, e_n, steps),
        (alpha_lo, alpha_hi),
        iterations,
        has_restitution_plus,
    )
}

/// `(γ, e_n)` of a fold locator checked, or `None` where the elastic law answers (`e_n = 1`:
/// none of Thornton's folds).
fn fold_inputs(gamma: f64, e_n: f64) -> Result<Option<(f64, f64)>, PhysicsError> {
    let gamma = check_gamma(gamma)?;
    let e_n = check_restitution(e_n)?;
    Ok((Law::Thornton.answering(e_n) != Law::Elastic).then_some((gamma, e_n)))
}

/// The fold above `start`, where a predicate that holds at `start` first fails: `α` steps up by
/// `factor` while it holds (`None` once a step passes `max`), then the bracket is bisected to
/// `1e-10` in `ln α` (the locators of [`loading_fold_thornton`], [`reslip_fold_thornton`] and
/// [`switch_fold_thornton`]).
fn fold_above(
    start: f64,
    factor: f64,
    max: f64,
    holds: impl Fn(f64) -> Result<bool, PhysicsError>,
) -> Result<Option<f64>, PhysicsError> {
    let (mut lo, mut hi) = (start, start * factor);
    while holds(hi)? {
        lo = hi;
        hi *= factor;
        if hi > max {
            return Ok(None);
        }
    }
    bisect_edge((lo.ln(), hi.ln()), 1e-10, |l| holds(l.exp())).map(|l| Some(l.exp()))
}
