//! The interpolation rule of schema v1 (stated in `docs/table-format.md`).
//!
//! The nonlinear part of the `(γ, α)` plane is covered by up to three patches whose edges lie on
//! the curves where `P` has curvature jumps, so that `P` is smooth inside each patch:
//!
//! | patch          | γ range        | α range          | coordinate `c ∈ [0, 1]`                        |
//! |----------------|----------------|------------------|------------------------------------------------|
//! | `stick_low`    | `γ_min ≤ γ ≤ 1` | `α_c2 … α_max`  | `(1/α_c2 − 1/α) / (1/α_c2 − 1/α_max)`          |
//! | `partial_high` | `1 ≤ γ ≤ γ_max` | `α_c1 … α_c2`   | `ln(α/α_c1) / ln(α_c2/α_c1)`                    |
//! | `stick_high`   | `1 ≤ γ ≤ γ_max` | `α_c2 … α_max`  | `(1/α_c2 − 1/α) / (1/α_c2 − 1/α_max)`          |
//!
//! (`1/α_max = 0` when `α_max = ∞`, so `α = ∞` maps to `c = 1`.) Each patch stores `P` on a grid
//! uniform in `γ` and in `c`; between nodes `P` is the tensor product of 1-D Lagrange
//! polynomials through `k` consecutive nodes per axis (`k = stencil_points`).

use crate::LookupError;

/// `α_c1 = 2γ²/(7(2γ² − 1))`.
pub fn alpha_c1(gamma: f64) -> f64 {
    let g2 = gamma * gamma;
    2.0 * g2 / (7.0 * (2.0 * g2 - 1.0))
}

/// `α_c2 = 2γ²/7`.
pub fn alpha_c2(gamma: f64) -> f64 {
    2.0 * gamma * gamma / 7.0
}

/// Upper end of the exact line `P = 1 − 7α`: `α_c1` for `γ > 1`, `α_c2` for `γ ≤ 1`.
pub fn linear_limit(gamma: f64) -> f64 {
    if gamma > 1.0 {
        alpha_c1(gamma)
    } else {
        alpha_c2(gamma)
    }
}

/// Which part of the plane a patch covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatchKind {
    /// `α_c1 ≤ α ≤ α_c2`, `γ ≥ 1`; coordinate `ln(α/α_c1)/ln(α_c2/α_c1)`.
    PartialSlip,
    /// `α_c2 ≤ α ≤ α_max`; coordinate `(1/α_c2 − 1/α)/(1/α_c2 − 1/α_max)`.
    Stick,
}

impl PatchKind {
    /// Name stored in the patch's `kind` attribute.
    pub fn name(self) -> &'static str {
        match self {
            PatchKind::PartialSlip => "partial-slip",
            PatchKind::Stick => "stick",
        }
    }

    /// Patch coordinate `c` of `(γ, α)`.
    pub fn coord(self, gamma: f64, alpha: f64, alpha_max: f64) -> f64 {
        match self {
            PatchKind::PartialSlip => {
                let c1 = alpha_c1(gamma);
                (alpha / c1).ln() / (alpha_c2(gamma) / c1).ln()
            }
            PatchKind::Stick => {
                let inv2 = 1.0 / alpha_c2(gamma);
                (inv2 - 1.0 / alpha) / (inv2 - 1.0 / alpha_max)
            }
        }
    }

    /// `α` at patch coordinate `c` (inverse of [`PatchKind::coord`]); `∞` at `c = 1` for a stick
    /// patch with `α_max = ∞`.
    pub fn alpha(self, gamma: f64, c: f64, alpha_max: f64) -> f64 {
        match self {
            PatchKind::PartialSlip => {
                let c1 = alpha_c1(gamma);
                c1 * (alpha_c2(gamma) / c1).powf(c)
            }
            PatchKind::Stick => {
                let inv2 = 1.0 / alpha_c2(gamma);
                let inv = inv2 - c * (inv2 - 1.0 / alpha_max);
                if c >= 1.0 {
                    alpha_max
                } else {
                    1.0 / inv
                }
            }
        }
    }
}

/// One patch: `P` on a grid uniform in `γ ∈ [gamma_lo, gamma_hi]` and `c ∈ [0, 1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// Region and coordinate.
    pub kind: PatchKind,
    /// First γ node.
    pub gamma_lo: f64,
    /// Last γ node.
    pub gamma_hi: f64,
    /// Number of γ nodes (≥ 2).
    pub n_gamma: usize,
    /// Number of coordinate nodes (≥ 2).
    pub n_coord: usize,
    /// `P` at the nodes, row-major `[i_gamma][i_coord]`.
    pub p: Vec<f64>,
    /// Solver error estimate of each node, same layout.
    pub error_estimate: Vec<f64>,
}

/// Start index and weights of the `k`-point Lagrange stencil at grid position `u` (in units of
/// the node spacing, node `i` at `u = i`) on `n` nodes. Weights are written to `w[..k']` where
/// `k' = min(k, n)` is returned with the start.
#[inline]
pub fn stencil(u: f64, n: usize, k: usize, w: &mut [f64; 8]) -> (usize, usize) {
    let k = k.min(n).min(8);
    let cell = (u.floor().max(0.0) as usize).min(n - 2);
    let start = (cell + 1).saturating_sub(k / 2).min(n - k);
    for (j, wj) in w.iter_mut().enumerate().take(k) {
        let mut prod = 1.0;
        for m in 0..k {
            if m != j {
                prod *= (u - (start + m) as f64) / (j as f64 - m as f64);
            }
        }
        *wj = prod;
    }
    (start, k)
}

impl Patch {
    /// γ node spacing.
    pub fn gamma_step(&self) -> f64 {
        (self.gamma_hi - self.gamma_lo) / (self.n_gamma - 1) as f64
    }

    /// γ of node `i`.
    pub fn gamma_node(&self, i: usize) -> f64 {
        if i + 1 == self.n_gamma {
            self.gamma_hi
        } else {
            self.gamma_lo + i as f64 * self.gamma_step()
        }
    }

    /// Coordinate of node `j`.
    pub fn coord_node(&self, j: usize) -> f64 {
        j as f64 / (self.n_coord - 1) as f64
    }

    /// Interpolate `P` at `(γ, c)` with a `k`-point stencil per axis.
    #[inline]
    pub fn interpolate(&self, gamma: f64, c: f64, k: usize) -> f64 {
        let mut wg = [0.0; 8];
        let mut wc = [0.0; 8];
        let ug = (gamma - self.gamma_lo) / self.gamma_step();
        let uc = c * (self.n_coord - 1) as f64;
        let (sg, kg) = stencil(ug, self.n_gamma, k, &mut wg);
        let (sc, kc) = stencil(uc, self.n_coord, k, &mut wc);
        let mut total = 0.0;
        for (a, wa) in wg.iter().enumerate().take(kg) {
            let row = &self.p[(sg + a) * self.n_coord + sc..][..kc];
            let inner: f64 = row.iter().zip(&wc[..kc]).map(|(p, w)| p * w).sum();
            total += wa * inner;
        }
        total
    }
}

/// The whole interpolated surface: the patches and the domain.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Lower end of the γ domain.
    pub gamma_min: f64,
    /// Upper end of the γ domain.
    pub gamma_max: f64,
    /// Upper end of the α domain (`∞` allowed).
    pub alpha_max: f64,
    /// Lagrange stencil points per axis.
    pub stencil: usize,
    /// `stick_low` (present when `γ_min < 1`).
    pub stick_low: Option<Patch>,
    /// `partial_high` (present when `γ_max > 1`).
    pub partial_high: Option<Patch>,
    /// `stick_high` (present when `γ_max > 1`).
    pub stick_high: Option<Patch>,
}

/// Which patch answers a query (or none: closed form).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Region {
    /// `α ≤` linear limit: `P = 1 − 7α` exactly.
    Line,
    /// Patch `stick_low`.
    StickLow,
    /// Patch `partial_high`.
    PartialHigh,
    /// Patch `stick_high`.
    StickHigh,
}

impl Region {
    /// Region of `(γ, α)` (assumed valid).
    pub fn of(gamma: f64, alpha: f64) -> Self {
        if alpha <= linear_limit(gamma) {
            Region::Line
        } else if gamma <= 1.0 {
            Region::StickLow
        } else if alpha < alpha_c2(gamma) {
            Region::PartialHigh
        } else {
            Region::StickHigh
        }
    }

    /// Index used in the `checks/patch` dataset (−1 for the line).
    pub fn index(self) -> i32 {
        match self {
            Region::Line => -1,
            Region::StickLow => 0,
            Region::PartialHigh => 1,
            Region::StickHigh => 2,
        }
    }
}

impl Surface {
    /// The patch of a region, if the table has it.
    pub fn patch(&self, region: Region) -> Option<&Patch> {
        match region {
            Region::Line => None,
            Region::StickLow => self.stick_low.as_ref(),
            Region::PartialHigh => self.partial_high.as_ref(),
            Region::StickHigh => self.stick_high.as_ref(),
        }
    }

    /// `P(γ, α)` by the documented rule. `α = ∞` is accepted. The full-slip line is exact and
    /// answered for any `γ > 0`; elsewhere `γ` must lie in `[gamma_min, gamma_max]` and
    /// `α ≤ alpha_max`.
    pub fn eval(&self, gamma: f64, alpha: f64) -> Result<f64, LookupError> {
        if !(gamma.is_finite() && gamma > 0.0) {
            return Err(LookupError::Query {
                name: "gamma",
                value: gamma,
                allowed: "a finite number > 0".into(),
            });
        }
        if alpha.is_nan() || alpha < 0.0 {
            return Err(LookupError::Query {
                name: "alpha",
                value: alpha,
                allowed: ">= 0 (or inf)".into(),
            });
        }
        let region = Region::of(gamma, alpha);
        if region == Region::Line {
            return Ok(1.0 - 7.0 * alpha);
        }
        if gamma < self.gamma_min || gamma > self.gamma_max {
            return Err(LookupError::Query {
                name: "gamma",
                value: gamma,
                allowed: format!(
                    "in the table's domain [{}, {}] (or alpha <= alpha_lin(gamma))",
                    self.gamma_min, self.gamma_max
                ),
            });
        }
        if alpha > self.alpha_max {
            return Err(LookupError::Query {
                name: "alpha",
                value: alpha,
                allowed: format!("<= the table's alpha_max = {}", self.alpha_max),
            });
        }
        Ok(self.eval_in(region, gamma, alpha))
    }

    /// Evaluate in a known non-line region (no checks).
    fn eval_in(&self, region: Region, gamma: f64, alpha: f64) -> f64 {
        match self.patch(region) {
            Some(patch) => {
                let c = patch.kind.coord(gamma, alpha, self.alpha_max);
                patch.interpolate(gamma, c.clamp(0.0, 1.0), self.stencil)
            }
            // A domain that touches γ = 1 only from one side: at γ = 1 exactly P = −1 on the
            // nonlinear part (α ≥ 2/7).
            None => -1.0,
        }
    }
}
