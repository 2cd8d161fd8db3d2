//! The fold warp of the partial-slip coordinate ([`Warp`], schema 3).

use super::*;

/// Warp of the partial-slip coordinate (group `/patches/partial_high/warp`, schema 3): a map
/// `c → c'` per γ that sends the knot `K(γ)` (the fold curve F₊ of `P`, where its slope jumps)
/// to the fixed `c' = c_star`, a root-cell boundary of the quadtree, so that no leaf straddles
/// the fold; below the knot the map is graded so that `P`, which goes like `(α_F − α)^{3/2}`
/// there, is smooth in `c'` (`docs/solver.md`, "The fold edge").
///
/// It applies from the lattice position `start` along γ on (in units of the patch's root
/// cells, `v = x·blocks_gamma` of the rule, clamped to `[0, blocks_gamma]`): for `v < start`,
/// `c' = c`; for `v ≥ start`, with `K =` [`Warp::knot_at`]`(γ)`,
/// `c' = c_star·(1 − √(1 − c/K))` if `c ≤ K`, else `c' = c_star + (1 − c_star)(c − K)/(1 − K)`.
/// `start` is a dyadic fraction and no leaf of the patch straddles it, so every leaf lies wholly
/// on one side.
///
/// `K(γ)` is the 4-point Lagrange rule of the leaf grids ([`stencil`]`(u, n, 4, ..)`) at
/// `u = (γ − gamma_0)/gamma_step` clamped to `[0, n − 1]`, over the values `knot[i]` at
/// `γ = gamma_0 + i·gamma_step` (`n = knot.len()`).
///
/// Valid warps (as the reader accepts them, [`Warp::validate`]): finite values,
/// `gamma_step > 0`, `0 < c_star < 1`, `n ≥ 4`, every knot in `(0, 1)`,
/// `0 < start < blocks_gamma` with `start·2²⁰` an integer, and a knot grid that covers the
/// warped part of the patch: `gamma_0 ≤ γ(start)` and `gamma_0 + (n − 1)·gamma_step ≥ gamma_hi`
/// (both within `1e-12` relative), where `γ(start) = gamma_lo + (gamma_hi − gamma_lo)·start/
/// blocks_gamma`.
#[derive(Debug, Clone, PartialEq)]
pub struct Warp {
    /// Lattice position along γ (root-cell units) from which the warp applies.
    pub(super) start: f64,
    /// γ of `knot[0]`.
    pub(super) gamma_0: f64,
    /// γ spacing of the knots (`> 0`).
    pub(super) gamma_step: f64,
    /// Where the knot is sent: `c' = c_star` at `c = K(γ)`, in `(0, 1)`.
    pub(super) c_star: f64,
    /// `K` at `γ = gamma_0 + i·gamma_step`, every value in `(0, 1)`, at least 4 values.
    pub(super) knot: Vec<f64>,
}

impl Warp {
    /// A warp from its stored values. Each value must be finite, `gamma_step > 0`,
    /// `0 < c_star < 1`, at least 4 knots, each in `(0, 1)`; the rules that involve the patch
    /// (`start`, the knot grid's span) are checked by [`Patch::new`]. `Err` names the attribute
    /// or dataset and the allowed range.
    pub fn new(
        start: f64,
        gamma_0: f64,
        gamma_step: f64,
        c_star: f64,
        knot: Vec<f64>,
    ) -> Result<Warp, String> {
        let w = Warp {
            start,
            gamma_0,
            gamma_step,
            c_star,
            knot,
        };
        let fields = [
            ("start", w.start, w.start.is_finite()),
            ("gamma_0", w.gamma_0, w.gamma_0.is_finite()),
            (
                "gamma_step",
                w.gamma_step,
                w.gamma_step.is_finite() && w.gamma_step > 0.0,
            ),
            ("c_star", w.c_star, w.c_star > 0.0 && w.c_star < 1.0),
        ];
        for (name, v, ok) in fields {
            if !ok {
                let allowed = match name {
                    "gamma_step" => "finite and > 0",
                    "c_star" => "in (0, 1)",
                    _ => "finite",
                };
                return Err(format!("attribute '{name}' = {v}: must be {allowed}"));
            }
        }
        let n = w.knot.len();
        if n < 4 {
            return Err(format!(
                "dataset 'knot' has {n} values: must have at least 4"
            ));
        }
        if let Some(i) = w.knot.iter().position(|&k| !(k > 0.0 && k < 1.0)) {
            return Err(format!(
                "dataset 'knot'[{i}] = {}: must be in (0, 1)",
                w.knot[i]
            ));
        }
        Ok(w)
    }

    /// Lattice position along γ (root-cell units) from which the warp applies.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// γ of the first knot.
    pub fn gamma_0(&self) -> f64 {
        self.gamma_0
    }

    /// γ spacing of the knots (`> 0`).
    pub fn gamma_step(&self) -> f64 {
        self.gamma_step
    }

    /// Where the knot is sent, in `(0, 1)`.
    pub fn c_star(&self) -> f64 {
        self.c_star
    }

    /// The knot values `K` at `γ = gamma_0 + i·gamma_step`.
    pub fn knot(&self) -> &[f64] {
        &self.knot
    }

    /// `K(γ)`: the 4-point Lagrange interpolant of `knot` at `u = (γ − gamma_0)/gamma_step`
    /// clamped to `[0, n − 1]`.
    #[inline]
    pub fn knot_at(&self, gamma: f64) -> f64 {
        let n = self.knot.len();
        let u = ((gamma - self.gamma_0) / self.gamma_step).clamp(0.0, (n - 1) as f64);
        // `n ≥ 4` for a valid warp ([`Warp::validate`]); the generic rule otherwise.
        if n < 4 {
            let mut w = [0.0; 8];
            let (start, k) = stencil(u, n, 4, &mut w);
            return (0..k).map(|j| w[j] * self.knot[start + j]).sum();
        }
        let (start, w) = stencil4(u, n);
        let k = &self.knot[start..start + 4];
        w[0] * k[0] + w[1] * k[1] + w[2] * k[2] + w[3] * k[3]
    }

    /// `γ` at the lattice position `start` of a patch over `[gamma_lo, gamma_hi]` with
    /// `blocks_gamma` root rows.
    pub fn start_gamma(&self, gamma_lo: f64, gamma_hi: f64, blocks_gamma: usize) -> f64 {
        gamma_lo + (gamma_hi - gamma_lo) * self.start / blocks_gamma as f64
    }

    /// Check the documented rules of a warp of a patch over `[gamma_lo, gamma_hi]` with
    /// `blocks_gamma` root rows (what the reader refuses otherwise; [`Warp`] lists them). `Err`
    /// names the attribute or dataset and the allowed range.
    pub fn validate(
        &self,
        gamma_lo: f64,
        gamma_hi: f64,
        blocks_gamma: usize,
    ) -> Result<(), String> {
        let bg = blocks_gamma as f64;
        let attrs = [
            (
                "start",
                self.start,
                format!("in (0, {blocks_gamma}) (root rows of the patch) and a multiple of 2^-20"),
                self.start > 0.0 && self.start < bg && (self.start * 1048576.0).fract() == 0.0,
            ),
            (
                "gamma_0",
                self.gamma_0,
                "finite".into(),
                self.gamma_0.is_finite(),
            ),
            (
                "gamma_step",
                self.gamma_step,
                "finite and > 0".into(),
                self.gamma_step.is_finite() && self.gamma_step > 0.0,
            ),
            (
                "c_star",
                self.c_star,
                "in (0, 1)".into(),
                self.c_star > 0.0 && self.c_star < 1.0,
            ),
        ];
        for (name, v, allowed, ok) in attrs {
            if !ok {
                return Err(format!("attribute '{name}' = {v}: must be {allowed}"));
            }
        }
        let n = self.knot.len();
        if n < 4 {
            return Err(format!(
                "dataset 'knot' has {n} values: must have at least 4"
            ));
        }
        if let Some(i) = self.knot.iter().position(|&k| !(k > 0.0 && k < 1.0)) {
            return Err(format!(
                "dataset 'knot'[{i}] = {}: must be in (0, 1)",
                self.knot[i]
            ));
        }
        let from = self.start_gamma(gamma_lo, gamma_hi, blocks_gamma);
        let end = self.gamma_0 + (n - 1) as f64 * self.gamma_step;
        let slack = 1e-12 * gamma_hi.abs();
        if !(self.gamma_0 <= from + slack && end >= gamma_hi - slack) {
            return Err(format!(
                "the knot grid 'gamma_0' + i*'gamma_step' spans [{}, {end}] ({n} values of \
                 'knot'): must cover the warped gamma range [{from}, {gamma_hi}]",
                self.gamma_0
            ));
        }
        Ok(())
    }

    /// `c → c'` for a point at or beyond `start`: `c_star·(1 − √(1 − c/K))` for `c ≤ K` and
    /// `c_star + (1 − c_star)(c − K)/(1 − K)` above, with `K =` [`Warp::knot_at`]`(γ)`.
    #[inline]
    pub fn apply(&self, gamma: f64, c: f64) -> f64 {
        self.apply_with(self.knot_at(gamma), c)
    }

    /// [`Warp::apply`] with `K` given (the same operations, for callers that hold `K(γ)`).
    #[inline(always)]
    pub fn apply_with(&self, k: f64, c: f64) -> f64 {
        if c <= k {
            self.c_star * (1.0 - (1.0 - c / k).max(0.0).sqrt())
        } else {
            self.c_star + (1.0 - self.c_star) * (c - k) / (1.0 - k)
        }
    }

    /// `c' → c`, the inverse of [`Warp::apply`] at the same γ (for laying out nodes at given
    /// `c'`): `K(1 − (1 − c'/c_star)²)` for `c' ≤ c_star` and `K + (c' − c_star)(1 − K)/(1 − c_star)`
    /// above.
    #[inline]
    pub fn invert(&self, gamma: f64, c_prime: f64) -> f64 {
        let k = self.knot_at(gamma);
        if c_prime <= self.c_star {
            let t = 1.0 - c_prime / self.c_star;
            k * (1.0 - t * t)
        } else {
            k + (c_prime - self.c_star) * (1.0 - k) / (1.0 - self.c_star)
        }
    }
}
