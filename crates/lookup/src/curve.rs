//! `P(α)` at one fixed `γ`: [`Curve`], for codes that meet one pair of materials (one `γ`) over
//! and over.
//!
//! Along a line `γ = γ₀` the rule of `docs/table-format.md` is a cubic polynomial in the patch
//! coordinate `c` on every interval between two node positions of the leaves the line crosses:
//! the descent along γ and the γ weights do not depend on `c`, and inside one interval of a
//! leaf's grid the `c` stencil is fixed. [`Table::curve`] evaluates the rule at four points
//! inside each such interval (a uniform grid of `blocks_coord · 2^D · m` intervals per patch,
//! `D` the deepest leaf on the line, which contains every node position) and stores the cubic
//! through them. A query then computes `c` exactly as the rule does (the `γ`-only parts of it
//! precomputed from the same `γ₀`, so the same bits), finds its interval by one multiplication
//! and evaluates three multiply-add steps of Horner's scheme: no quadtree, no stencil weights.
//! Only tables with the cubic stencil (`stencil_points = 4`, the shipped one) have curves.
//!
//! The values agree with [`Table::p_with`] at `(γ₀, α)` up to the rounding of the cubic's
//! coefficients (the tests require 1e-14; measured: at most 2.1e-15 over 7.3 million points
//! on the three shipped tables, `crates/lookup/tests/curve.rs`).

use crate::{LookupError, Table};
use oblique_table::export::{CurveData, CurvePiece};
use oblique_table::surface::{
    alpha_c2, bound_p, floor_index, full_slip_line, partial_coord_from, partial_ratio,
    partial_ratio_e, stick_coord_from, stick_parts, KnotLine, PartialMap, Patch, Warp,
};
use oblique_table::surface::{alpha_outside, bad_alpha, OutOfDomain, PatchId, Surface};

/// Largest number of intervals of one patch's curve (`2²⁰`, 32 MiB of coefficients); a line
/// through leaves so deep that the uniform grid would need more is refused.
const MAX_INTERVALS: usize = 1 << 20;

/// One patch along the line: the cubic of every interval, in the centred local coordinate
/// `s = c·n − i − 1/2 ∈ [−1/2, 1/2]` of interval `i` (better conditioned than `[0, 1]`).
#[derive(Debug, Clone, PartialEq)]
struct Piecewise {
    /// Number of intervals `n` (as a float, for `c·n`) and its last index.
    n: f64,
    last: usize,
    /// `[a0, a1, a2, a3]` of `a0 + a1 s + a2 s² + a3 s³`, per interval.
    coef: Vec<[f64; 4]>,
    /// The patch's warp when the line is at or beyond its start, with `K(γ)` of the line: the
    /// intervals are then in the warped coordinate `c'` ([`Patch::warped`]).
    warp: Option<(f64, Warp)>,
    /// The patch's knots when they apply on the line: the intervals are then in `c'`
    /// ([`Patch::knotted`]).
    knots: Option<KnotLine>,
}

impl Piecewise {
    /// The restriction of `patch`'s interpolant to `γ = gamma` (inside the patch's γ range),
    /// and to `e_n` for a patch with an `e_n` axis (inside its range).
    fn new(patch: &Patch, gamma: f64, e_n: f64) -> Result<Piecewise, LookupError> {
        let m = patch.leaf_intervals();
        let depth = patch.line_depth(gamma, e_n);
        let n = patch
            .blocks_coord()
            .checked_mul(m)
            .and_then(|v| v.checked_shl(depth))
            .filter(|&v| v > 0 && v <= MAX_INTERVALS)
            .ok_or_else(|| LookupError::Query {
                name: "gamma",
                value: gamma,
                allowed: format!(
                    "a line through leaves of depth <= {} for a curve (this one reaches depth \
                     {depth}); use Table::p instead",
                    (MAX_INTERVALS / (patch.blocks_coord() * m).max(1)).ilog2()
                ),
            })?;
        // Four sample points inside each interval, s = −3/8, −1/8, 1/8, 3/8 (t = s + 1/2 all
        // inside, so all in the same leaf and stencil).
        const S: [f64; 4] = [-0.375, -0.125, 0.125, 0.375];
        let k = 4;
        let nf = n as f64;
        let coef = (0..n)
            .map(|i| {
                let v = S.map(|s| patch.tensor_point(gamma, (i as f64 + 0.5 + s) / nf, e_n, k));
                cubic_through(&S, &v)
            })
            .collect();
        // Whether the rule warps `c` on this line, and `K(γ)` of the line.
        let warp = patch.warp_at(gamma).map(|w| (w.knot_at(gamma), w.clone()));
        Ok(Piecewise {
            n: nf,
            last: n - 1,
            coef,
            warp,
            knots: patch.knots_at(gamma, e_n),
        })
    }

    /// The value at (unwarped) patch coordinate `c ∈ [0, 1]`.
    #[inline(always)]
    fn eval(&self, c: f64) -> f64 {
        let c = match (&self.warp, &self.knots) {
            (Some((k, w)), _) => w.apply_with(*k, c),
            (_, Some(line)) => line.apply(c),
            _ => c,
        };
        let u = c * self.n;
        let i = floor_index(u, self.last);
        let s = u - i as f64 - 0.5;
        let [a0, a1, a2, a3] = self.coef[i];
        // The cubic of the tensor product, then the rule's bound (step 10).
        bound_p(((a3 * s + a2) * s + a1) * s + a0)
    }
}

/// Coefficients `[a0, a1, a2, a3]` of the cubic through `(t[j], v[j])`.
fn cubic_through(t: &[f64; 4], v: &[f64; 4]) -> [f64; 4] {
    // Lagrange basis polynomials expanded into monomials.
    let mut out = [0.0; 4];
    for j in 0..4 {
        let others: Vec<f64> = (0..4).filter(|&i| i != j).map(|i| t[i]).collect();
        let denom: f64 = others.iter().map(|&x| t[j] - x).product();
        let (p, q, r) = (others[0], others[1], others[2]);
        // (t − p)(t − q)(t − r) = t³ − (p+q+r) t² + (pq+pr+qr) t − pqr
        let basis = [-p * q * r, p * q + p * r + q * r, -(p + q + r), 1.0];
        for (o, b) in out.iter_mut().zip(basis) {
            *o += v[j] * b / denom;
        }
    }
    out
}

/// `P(α)` of a table at one fixed `γ` ([`Table::curve`]): the table's interpolant restricted to
/// that line, precomputed as one cubic per node interval, for codes that query one `γ` (one
/// pair of materials) many times. Answers what [`Table::p_with`] answers at `(γ, α)`, to about
/// 1e-15, in fewer operations.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// The `γ` asked for and the one used (clamped into the domain with
    /// [`OutOfDomain::Clamp`]).
    requested: f64,
    gamma: f64,
    outside: OutOfDomain,
    alpha_max: f64,
    /// Normal restitution of the line (1 for an elastic curve).
    e_n: f64,
    /// The partial-slip coordinate's map ([`Surface::partial_map`]).
    map: PartialMap,
    /// `1 − (7/2)(1 + e_n)α` up to here: at the requested `γ` (the rule's first test, for any
    /// `γ`) and at the one used (its test after clamping); `−∞` in a table without the line
    /// ([`Surface::line_end`]).
    alpha_lin_requested: f64,
    alpha_lin: f64,
    /// Partial slip below, stick above (`γ > 1`).
    alpha_c2: f64,
    /// [`Surface::high`]: the line crosses `partial_high` and `stick_high`; else `stick_low`.
    high: bool,
    /// The rule's `2γ²`, `α_c2/α_c1` (`2γ² − 1`, or `γ²(1 + e_n) − e_n`) and its log
    /// (partial-slip coordinate).
    g2: f64,
    ratio: f64,
    ln_ratio: f64,
    /// The rule's `α_c2`, `ρ α_c2` (stick coordinate) and `S(α_max)` (`None` for `α_max = ∞`).
    stick_c2: f64,
    rho_c2: f64,
    s_max: Option<f64>,
    /// The patches along the line (`None` where the table has no such patch: `P = −1` there,
    /// as in the rule).
    partial: Option<Piecewise>,
    stick: Option<Piecewise>,
}

impl Curve {
    /// The curve of `surface` at `gamma`; `outside` is the domain policy of the queries (and of
    /// `gamma` itself: clamped into the domain, or refused, as [`Surface::eval_with`] does).
    pub(crate) fn new(
        surface: &Surface,
        gamma: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<Curve, LookupError> {
        // The table of one pair takes a γ next to its own as its own.
        let gamma = surface.rule_gamma(gamma);
        if !(gamma.is_finite() && gamma > 0.0) {
            return Err(oblique_table::surface::bad_gamma(gamma));
        }
        surface.check_e_n(e_n)?;
        if surface.stencil() != 4 {
            // Along a line the rule is then a polynomial of another degree.
            return Err(LookupError::Query {
                name: "table stencil_points",
                value: surface.stencil() as f64,
                allowed: "4 (cubic) for a curve; query this table with Table::p".into(),
            });
        }
        if gamma < surface.gamma_min() || gamma > surface.gamma_max() {
            match outside {
                OutOfDomain::Error => return Err(surface.gamma_outside(gamma)),
                OutOfDomain::Clamp => {
                    let clamped = gamma.clamp(surface.gamma_min(), surface.gamma_max());
                    return Ok(Curve {
                        requested: gamma,
                        alpha_lin_requested: surface.line_end(gamma, e_n),
                        ..Curve::new(surface, clamped, e_n, outside)?
                    });
                }
            }
        }
        let high = surface.high(gamma);
        let (partial, stick) = if high {
            (
                surface.patch_by_id(PatchId::PartialHigh),
                surface.patch_by_id(PatchId::StickHigh),
            )
        } else {
            (None, surface.patch_by_id(PatchId::StickLow))
        };
        let piecewise = |p: Option<&Patch>| p.map(|p| Piecewise::new(p, gamma, e_n)).transpose();
        // The γ-only parts of `surface::partial_coord` (an elastic table),
        // `surface::partial_coord_e` (a table with an e_n axis) and `surface::stick_coord`.
        let (map, (ratio, g2)) = if surface.restitution().is_some() {
            (surface.partial_map(), partial_ratio_e(gamma, e_n))
        } else {
            (PartialMap::SqrtEnd, partial_ratio(gamma))
        };
        let (stick_c2, rho_c2, s_max) = stick_parts(gamma, surface.alpha_max());
        Ok(Curve {
            requested: gamma,
            gamma,
            outside,
            alpha_max: surface.alpha_max(),
            e_n,
            map,
            alpha_lin_requested: surface.line_end(gamma, e_n),
            alpha_lin: surface.line_end(gamma, e_n),
            alpha_c2: alpha_c2(gamma),
            high,
            g2,
            ratio,
            ln_ratio: ratio.ln(),
            stick_c2,
            rho_c2,
            s_max,
            partial: piecewise(partial)?,
            stick: piecewise(stick)?,
        })
    }

    /// The `γ` of this curve (clamped into the table's domain if it was built with
    /// [`OutOfDomain::Clamp`]).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// The `γ` the curve was asked for (before any clamping).
    pub fn requested_gamma(&self) -> f64 {
        self.requested
    }

    /// Whether this curve answers for `gamma` with the domain choice `outside` (built from them).
    pub fn matches(&self, gamma: f64, outside: OutOfDomain) -> bool {
        self.requested == gamma && self.outside == outside
    }

    /// The normal restitution `e_n` of the curve (1 for an elastic one).
    pub fn e_n(&self) -> f64 {
        self.e_n
    }

    /// `P(γ, α)` (dimensionless) for `α ≥ 0` (`∞`: no slip). `α > alpha_max` is refused or
    /// clamped as the curve's [`OutOfDomain`] says; a NaN or negative `α` is an error.
    #[inline]
    pub fn p(&self, alpha: f64) -> Result<f64, LookupError> {
        if alpha.is_nan() || alpha < 0.0 {
            return Err(bad_alpha(alpha));
        }
        // The rule's order: the line at the requested point, then the domain, then (after
        // clamping) the line again at the point used.
        if alpha <= self.alpha_lin_requested {
            return Ok(full_slip_line(alpha, self.e_n));
        }
        let alpha = if alpha > self.alpha_max {
            match self.outside {
                OutOfDomain::Error => return Err(alpha_outside(self.alpha_max, alpha)),
                OutOfDomain::Clamp => self.alpha_max,
            }
        } else {
            alpha
        };
        if alpha <= self.alpha_lin {
            return Ok(full_slip_line(alpha, self.e_n));
        }
        Ok(self.eval_above_line(alpha))
    }

    /// [`Curve::p`] for a valid `α` above the full-slip line, inside the domain.
    #[inline(always)]
    fn eval_above_line(&self, alpha: f64) -> f64 {
        if self.high && alpha < self.alpha_c2 {
            let Some(p) = &self.partial else {
                return -self.e_n;
            };
            let c = partial_coord_from(self.map, alpha, self.ratio, self.g2, self.ln_ratio);
            p.eval(c.clamp(0.0, 1.0))
        } else {
            let Some(p) = &self.stick else {
                return -self.e_n;
            };
            let c = stick_coord_from(alpha, self.stick_c2, self.rho_c2, self.s_max);
            p.eval(c.clamp(0.0, 1.0))
        }
    }

    /// `out[i] = P(γ, alpha[i])`; the first invalid `α` stops the batch with its index
    /// ([`LookupError::Batch`]), `out` after it untouched.
    pub fn p_batch(&self, alpha: &[f64], out: &mut [f64]) -> Result<(), LookupError> {
        crate::batch::check_length("out", out.len(), alpha.len())?;
        crate::batch::serial(alpha, out, |&a| self.p(a))
    }

    /// What the export format stores of this curve ([`oblique_table::export::CurveData`]);
    /// `None` for a curve whose `γ` was clamped into the domain (the export holds curves of
    /// `γ` inside it).
    pub fn export_data(&self) -> Option<CurveData> {
        // The export holds elastic curves only.
        if self.requested != self.gamma || self.map != PartialMap::SqrtEnd {
            return None;
        }
        let piece = |p: &Option<Piecewise>| {
            p.as_ref().map(|p| CurvePiece {
                coef: p.coef.clone(),
                warp: p.warp.as_ref().map(|(k, w)| (*k, w.c_star())),
            })
        };
        Some(CurveData {
            gamma: self.gamma,
            alpha_lin: self.alpha_lin,
            alpha_c2: self.alpha_c2,
            g2: self.g2,
            ratio: self.ratio,
            ln_ratio: self.ln_ratio,
            stick_c2: self.stick_c2,
            rho_c2: self.rho_c2,
            s_max: self.s_max,
            alpha_max: self.alpha_max,
            high: self.high,
            partial: piece(&self.partial),
            stick: piece(&self.stick),
        })
    }

    /// Bytes of the precomputed cubics.
    pub fn bytes(&self) -> usize {
        [&self.partial, &self.stick]
            .iter()
            .filter_map(|p| p.as_ref())
            .map(|p| p.coef.len() * std::mem::size_of::<[f64; 4]>())
            .sum()
    }
}

impl Table {
    /// `P(α)` at one fixed `γ`, precomputed from this table for many queries of one pair of
    /// materials ([`Curve`]). `γ` outside the table's domain is an error with
    /// [`OutOfDomain::Error`] and is clamped into it with [`OutOfDomain::Clamp`], which also
    /// sets what the curve's queries do with `α > alpha_max`. Costs one evaluation of the rule
    /// per node interval on the line (milliseconds) and up to a few MB.
    pub fn curve(&self, gamma: f64, outside: OutOfDomain) -> Result<Curve, LookupError> {
        Curve::new(self.surface(), gamma, 1.0, outside)
    }

    /// `P(α)` at one fixed `γ` and normal restitution `e_n` ([`Table::curve`] of a table with
    /// an `e_n` axis; `e_n` must be in its range, never clamped; an elastic table answers
    /// `e_n = 1` only).
    pub fn curve_e(
        &self,
        gamma: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<Curve, LookupError> {
        Curve::new(self.surface(), gamma, e_n, outside)
    }

    /// `P(α)` at one fixed `γ` and fixed values `extra` of the table's extra axes
    /// ([`Table::extra_axes`], in that order: empty for an elastic table, `[e_n]` for a table
    /// with an `e_n` axis): [`Table::curve`] / [`Table::curve_e`] with the same bits. Another
    /// number of values is [`LookupError::Point`] (naming `gamma` and the extra axes).
    pub fn curve_at(
        &self,
        gamma: f64,
        extra: &[f64],
        outside: OutOfDomain,
    ) -> Result<Curve, LookupError> {
        let axes = self.extra_axes();
        if extra.len() != axes.len() {
            return Err(LookupError::Point {
                len: 1 + extra.len(),
                expected: 1 + axes.len(),
                axes: std::iter::once("gamma")
                    .chain(axes.iter().map(|a| a.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
        let e_n = extra.first().copied().unwrap_or(1.0);
        Curve::new(self.surface(), gamma, e_n, outside)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cubic_through_four_points_reproduces_a_cubic() {
        let f = |t: f64| 0.3 - 1.7 * t + 2.5 * t * t - 0.75 * t * t * t;
        let t = [-0.375, -0.125, 0.125, 0.375];
        let c = cubic_through(&t, &t.map(f));
        for (got, want) in c.iter().zip([0.3, -1.7, 2.5, -0.75]) {
            assert!((got - want).abs() < 1e-14, "{c:?}");
        }
    }
}
