//! The gross-slip history of one impact, and the fold curves of `P(γ, α)` it reveals.
//!
//! *Gross slip* is the whole contact at the Coulomb limit: `F_t = ±μ F_N`. Where the sequence
//! of gross-slip episodes changes as `α` varies, `P` is not smooth. When an episode strictly
//! inside the contact shrinks to nothing (a *fold*), `P` has a jump of slope: at γ = 3.2 the
//! slope `dP/d ln α` goes from −0.90 to −0.32 across α = 1.3431, where a `+μF_N` episode at
//! t ≈ 0.86 t_c vanishes (`docs/solver.md`, "Kink curves"). Such curves limit how well a table
//! can interpolate `P`; this module finds them.
//!
//! Dimensionless units as in [`crate::physics::impact::simulate`]: `m* = R* = E* = v_z0 = 1`,
//! `u0 = 1`, so `μ = α` and `F_N = (4/3) d^{3/2}`; times are fractions of the contact time `t_c`.

use super::error::PhysicsError;
use super::hertz::NormalTrajectory;
use super::impact::{
    check_alpha, check_gamma, dimensionless_normal, run_contact, TangentialBodies, ALPHA_NO_SLIP,
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

/// The contact point of [`crate::physics::impact::simulate`], recording the mean friction force
/// of every step.
struct Recorder {
    u: f64,
    t: f64,
    /// `(start time, length, mean friction force)` of every step.
    log: Vec<(f64, f64, f64)>,
}

const INV_TANGENTIAL_MASS: f64 = 3.5;

impl TangentialBodies for Recorder {
    fn slip_velocity(&self) -> f64 {
        self.u
    }
    fn slip_acceleration(&self, f: f64) -> f64 {
        -f * INV_TANGENTIAL_MASS
    }
    fn kick(&mut self, h: f64, f: f64) {
        self.u -= h * f * INV_TANGENTIAL_MASS;
        self.log.push((self.t, h, f));
        self.t += h;
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

/// Run one impact with the continuum row on `steps` steps and record its gross-slip episodes.
///
/// `γ` must be finite and positive, `α` finite and positive (with `α = ∞` or above
/// [`ALPHA_NO_SLIP`] nothing ever slips, so that is refused as meaningless here), `steps ≥ 8`.
pub fn slip_history(gamma: f64, alpha: f64, steps: usize) -> Result<SlipHistory, PhysicsError> {
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
    let shear = 2.0 / 7.0 * gamma * gamma;
    let nt = dimensionless_normal(steps);
    let mut rec = Recorder {
        u: 1.0,
        t: 0.0,
        log: Vec::with_capacity(steps + steps / 8),
    };
    run_contact(&mut rec, &nt, 0, 1.0, shear, alpha / shear);
    let mut episodes: Vec<Episode> = Vec::new();
    for &(t, h, f) in &rec.log {
        // The Coulomb limit of the step's mean force, by the product rule the stepper uses for
        // the impulse: μ F_N = (4/3) μ √d · d, averaged as mean(√d) · (d₀ + d₁)/2.
        let (d0, d1) = (indentation_at(&nt, t), indentation_at(&nt, t + h));
        let (r0, r1) = (d0.max(0.0).sqrt(), d1.max(0.0).sqrt());
        if r0 + r1 <= 0.0 || (r0 + r1).is_nan() {
            continue;
        }
        let mean_sqrt = 2.0 / 3.0 * (r0 * r0 + r0 * r1 + r1 * r1) / (r0 + r1);
        let limit = alpha * 2.0 / 3.0 * mean_sqrt * (d0.max(0.0) + d1.max(0.0));
        let q = f / limit;
        let t = t + 0.5 * h;
        let sign = if q >= 1.0 - SLIP_THRESHOLD {
            SlipSign::Plus
        } else if q <= -(1.0 - SLIP_THRESHOLD) {
            SlipSign::Minus
        } else {
            continue;
        };
        let tau = t / nt.contact_time;
        match episodes.last_mut() {
            Some(e) if e.sign == sign && tau - e.end < MERGE_GAP => e.end = tau,
            _ => episodes.push(Episode {
                sign,
                start: tau,
                end: tau,
            }),
        }
    }
    Ok(SlipHistory { episodes, p: rec.u })
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
    let at_lo = present(&slip_history(gamma, alpha_lo, steps)?);
    let at_hi = present(&slip_history(gamma, alpha_hi, steps)?);
    if at_lo == at_hi {
        return Ok(None);
    }
    let (mut lo, mut hi) = (alpha_lo.ln(), alpha_hi.ln());
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if present(&slip_history(gamma, mid.exp(), steps)?) == at_lo {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(Some((0.5 * (lo + hi)).exp()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::regimes::{alpha_c1, alpha_c2};

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
    fn refuses_what_has_no_history() {
        assert!(slip_history(1.0, f64::INFINITY, 64).is_err());
        assert!(slip_history(1.0, 0.0, 64).is_err());
        assert!(slip_history(1.0, 0.3, 4).is_err());
        assert!(slip_history(f64::NAN, 0.3, 64).is_err());
    }
}
