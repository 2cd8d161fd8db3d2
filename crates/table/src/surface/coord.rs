//! The patch coordinates: which part of the plane a patch covers ([`PatchKind`]), the map of
//! the partial-slip coordinate ([`PartialMap`]), and the coordinates `c` of both kinds of patch.

use super::*;

/// Which part of the plane a patch covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PatchKind {
    /// `α_c1 ≤ α ≤ α_c2`, `γ ≥ 1`; coordinate `1 − √(1 − ℓ)`, `ℓ = ln(α/α_c1)/ln(α_c2/α_c1)`.
    PartialSlip,
    /// `α_c2 ≤ α ≤ α_max`; coordinate `S(α)/S(α_max)`, `S = r/(r + ρ)`, `r = α/α_c2 − 1`,
    /// `ρ =` [`stick_scale`]`(γ)`.
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

    /// Patch coordinate `c` of `(γ, α)` (an elastic table: `e_n = 1`).
    pub fn coord(self, gamma: f64, alpha: f64, alpha_max: f64) -> f64 {
        self.coord_at(PartialMap::SqrtEnd, gamma, alpha, 1.0, alpha_max)
    }

    /// Patch coordinate `c` of `(γ, α, e_n)`: the partial-slip coordinate is `map` of
    /// `ℓ = ln(α/α_c1)/ln(α_c2/α_c1)`, from `α_c1(γ, e_n) = 2γ²/(7(γ²(1 + e_n) − e_n))`
    /// (where the full-slip line ends, `physics.md`) to `α_c2`, which does not move with
    /// `e_n`; the stick coordinate does not depend on `e_n`. [`PartialMap::SqrtEnd`] at
    /// `e_n = 1` is the elastic coordinate, bit for bit.
    ///
    /// The builder (the warp's knot values, the kink probes) and the readers compute `c` with
    /// the same operations: this is [`partial_coord_from`] with [`partial_ratio_e`], and
    /// [`stick_coord`].
    pub fn coord_at(
        self,
        map: PartialMap,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        alpha_max: f64,
    ) -> f64 {
        match self {
            PatchKind::PartialSlip => {
                let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
                partial_coord_from(map, alpha, ratio, two_g2, ratio.ln())
            }
            PatchKind::Stick => stick_coord(gamma, alpha, alpha_max),
        }
    }

    /// `α` at patch coordinate `c` (inverse of [`PatchKind::coord`]); `∞` at `c = 1` for a stick
    /// patch with `α_max = ∞`.
    pub fn alpha(self, gamma: f64, c: f64, alpha_max: f64) -> f64 {
        self.alpha_at(PartialMap::SqrtEnd, gamma, c, 1.0, alpha_max)
    }

    /// `α` at patch coordinate `c` and restitution `e_n` (inverse of [`PatchKind::coord_at`]).
    pub fn alpha_at(self, map: PartialMap, gamma: f64, c: f64, e_n: f64, alpha_max: f64) -> f64 {
        match self {
            PatchKind::PartialSlip => {
                let c1 = alpha_c1_dissipative(gamma, e_n);
                if map == PartialMap::Slip && c <= 0.5 {
                    // Below α_c1 the coordinate is linear in α.
                    return 2.0 * c * c1;
                }
                c1 * (alpha_c2(gamma) / c1).powf(map.l_of_c(c))
            }
            PatchKind::Stick => {
                if c >= 1.0 {
                    return alpha_max;
                }
                let c2 = alpha_c2(gamma);
                let rho = stick_scale(gamma);
                let top = if alpha_max.is_infinite() {
                    1.0
                } else {
                    let r = alpha_max / c2 - 1.0;
                    r / (r + rho)
                };
                let q = c * top;
                c2 * (1.0 + rho * q / (1.0 - q))
            }
        }
    }
}

/// The map from `ℓ = ln(α/α_c1)/ln(α_c2/α_c1) ∈ [0, 1]` to the partial-slip coordinate `c`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartialMap {
    /// `c = 1 − √(1 − ℓ)` (an elastic table): graded towards `α_c2`, where `P` goes like
    /// `√(1 − ℓ)`; at `α_c1` the elastic `P` leaves the full-slip line like `(α − α_c1)²`.
    SqrtEnd,
    /// `c = 1 − √(1 − √ℓ)` (a table with an `e_n` axis): graded at both ends, because a
    /// dissipative impact leaves the full-slip line like `(α − α_c1)^{3/2}` (measured: the
    /// local exponent falls from 1.85 towards 1.5 as `α → α_c1` at `e_n = 0.95`), which is
    /// smooth in `√ℓ`; near `α_c2` it is smooth in `√(1 − ℓ)` as the elastic map is. (The
    /// balanced `(2/π) asin(√ℓ)` needs 15 % fewer nodes but an `asin` in every query.)
    SqrtBoth,
    /// The patch of a law without a closed-form full-slip line (Thornton's, a table with an
    /// `e_n` axis): it covers `0 ≤ α ≤ α_c2`, with `c = α/(2α_c1)` up to `α_c1(γ, e_n)` (where
    /// `P` is smooth in `α` and close to the line) and `c = 1/2 + s/2` above,
    /// `s` the [`PartialMap::SqrtBoth`] coordinate. `α_c1` is the root-cell boundary `c = 1/2`
    /// (an even `blocks_coord`), so no leaf straddles it; the law's own edge of full slip lies
    /// within a few per cent of it (`docs/solver.md`, "The edge of the full-slip region").
    Slip,
}

impl PartialMap {
    /// The map of a table with an `e_n` axis ([`PartialMap::SqrtBoth`]) or without
    /// ([`PartialMap::SqrtEnd`]).
    #[inline(always)]
    pub fn of_table(has_e_n: bool) -> PartialMap {
        if has_e_n {
            PartialMap::SqrtBoth
        } else {
            PartialMap::SqrtEnd
        }
    }

    /// The map of a table with an `e_n` axis of the law whose [`crate::format::ATTR_COORDINATE`]
    /// is `coordinate` ([`crate::format::coordinate_of_law`]); `None` for another value.
    pub fn of_coordinate(coordinate: &str) -> Option<PartialMap> {
        match coordinate {
            crate::format::PARTIAL_MAP_SQRT_BOTH => Some(PartialMap::SqrtBoth),
            crate::format::PARTIAL_MAP_SLIP => Some(PartialMap::Slip),
            _ => None,
        }
    }

    /// The value of [`crate::format::ATTR_COORDINATE`] that names this map (`None` for the
    /// elastic map, which no attribute names).
    pub fn coordinate(self) -> Option<&'static str> {
        match self {
            PartialMap::SqrtEnd => None,
            PartialMap::SqrtBoth => Some(crate::format::PARTIAL_MAP_SQRT_BOTH),
            PartialMap::Slip => Some(crate::format::PARTIAL_MAP_SLIP),
        }
    }

    /// Whether a table of this map answers `α ≤ α_c1` from the closed-form full-slip line
    /// (every map but [`PartialMap::Slip`]).
    #[inline(always)]
    pub fn has_line(self) -> bool {
        self != PartialMap::Slip
    }

    /// `c` of `ℓ` (`ℓ` outside `[0, 1]` by rounding: the ends); for [`PartialMap::Slip`] the
    /// part above `α_c1` (`ℓ ≥ 0`, `c ≥ 1/2`).
    #[inline(always)]
    pub fn c_of_l(self, l: f64) -> f64 {
        match self {
            PartialMap::SqrtEnd => 1.0 - (1.0 - l).max(0.0).sqrt(),
            PartialMap::SqrtBoth => 1.0 - (1.0 - l.clamp(0.0, 1.0).sqrt()).sqrt(),
            PartialMap::Slip => 0.5 + 0.5 * PartialMap::SqrtBoth.c_of_l(l),
        }
    }

    /// `ℓ` of `c` (the inverse of [`PartialMap::c_of_l`]; for [`PartialMap::Slip`], `c ≥ 1/2`).
    #[inline]
    pub fn l_of_c(self, c: f64) -> f64 {
        match self {
            PartialMap::SqrtEnd => {
                let q = 1.0 - c;
                1.0 - q * q
            }
            PartialMap::SqrtBoth => {
                let q = 1.0 - c;
                let s = 1.0 - q * q;
                s * s
            }
            PartialMap::Slip => PartialMap::SqrtBoth.l_of_c(2.0 * c - 1.0),
        }
    }
}

/// Width `ρ(γ)` of the stick coordinate, in units of `r = α/α_c2 − 1`: `2(1 − γ²)` for `γ < 1`
/// (the boundary layer below γ = 1 has width `α_c1/α_c2 − 1 = r₁`, and `r₁/(1 + r₁) = 2(1 − γ²)`),
/// `1` for `γ ≥ 1`.
#[inline]
pub fn stick_scale(gamma: f64) -> f64 {
    if gamma < 1.0 {
        2.0 * (1.0 - gamma * gamma)
    } else {
        1.0
    }
}

/// [`PatchKind::coord_at`] of the partial-slip patch of a table with an `e_n` axis
/// ([`PartialMap::SqrtBoth`]) at normal restitution `e_n`: [`partial_coord_from`] with
/// [`partial_ratio_e`].
#[inline(always)]
pub fn partial_coord_e(gamma: f64, alpha: f64, e_n: f64) -> f64 {
    partial_coord_map(PartialMap::SqrtBoth, gamma, alpha, e_n)
}

/// The partial-slip coordinate of a table with an `e_n` axis whose map is `map`
/// ([`PartialMap::SqrtBoth`]: [`partial_coord_e`]; [`PartialMap::Slip`]): [`partial_coord_from`]
/// with [`partial_ratio_e`].
#[inline(always)]
pub fn partial_coord_map(map: PartialMap, gamma: f64, alpha: f64, e_n: f64) -> f64 {
    let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
    partial_coord_from(map, alpha, ratio, two_g2, ratio.ln())
}

/// [`PatchKind::coord`] of the partial-slip patch: [`partial_coord_from`] with
/// [`partial_ratio`].
#[inline(always)]
pub fn partial_coord(gamma: f64, alpha: f64) -> f64 {
    let (ratio, two_g2) = partial_ratio(gamma);
    partial_coord_from(PartialMap::SqrtEnd, alpha, ratio, two_g2, ratio.ln())
}

/// The `γ`-only parts of the partial-slip coordinate of an elastic table:
/// `α_c2/α_c1 = 2γ² − 1` and `2γ²`.
#[inline(always)]
pub fn partial_ratio(gamma: f64) -> (f64, f64) {
    let two_g2 = 2.0 * gamma * gamma;
    (two_g2 - 1.0, two_g2)
}

/// The `γ`-only parts of the partial-slip coordinate at normal restitution `e_n`:
/// `α_c2/α_c1 = h = γ²(1 + e_n) − e_n` and `2γ²`.
#[inline(always)]
pub fn partial_ratio_e(gamma: f64, e_n: f64) -> (f64, f64) {
    let g2 = gamma * gamma;
    (g2 * (1.0 + e_n) - e_n, 2.0 * g2)
}

/// `α/α_c1 = 7α·ratio/(2γ²)`, the argument of the numerator's logarithm in `ℓ`.
#[inline(always)]
pub fn partial_arg(alpha: f64, ratio: f64, two_g2: f64) -> f64 {
    7.0 * alpha * ratio / two_g2
}

/// The partial-slip coordinate `map(ℓ)`, `ℓ = ln(α/α_c1)/ln(α_c2/α_c1)`, from the `γ`-only
/// parts ([`partial_ratio`], [`partial_ratio_e`]) and `ln_ratio = ln(ratio)`: the one
/// statement of these operations (the rule, the query paths, the curves). With
/// [`PartialMap::Slip`], `q = α/α_c1 ≤ 1` gives `c = 0.5·q` (no logarithm: at `γ = 1`,
/// where `α_c1 = α_c2` and `ln_ratio` is 0, every query of the patch is there).
#[inline(always)]
pub fn partial_coord_from(
    map: PartialMap,
    alpha: f64,
    ratio: f64,
    two_g2: f64,
    ln_ratio: f64,
) -> f64 {
    let q = partial_arg(alpha, ratio, two_g2);
    if map == PartialMap::Slip && q <= 1.0 {
        return 0.5 * q;
    }
    map.c_of_l(q.ln() / ln_ratio)
}

/// [`PatchKind::coord`] of a stick patch: `S(α) = r/(r + ρ) = (α − α_c2)/(α − α_c2 + ρ α_c2)`,
/// [`stick_coord_from`] with [`stick_parts`].
#[inline(always)]
pub fn stick_coord(gamma: f64, alpha: f64, alpha_max: f64) -> f64 {
    if alpha.is_infinite() {
        return 1.0;
    }
    stick_coord_parts(alpha, stick_parts(gamma, alpha_max))
}

/// [`stick_coord`] from the `γ`-only parts `parts` = [`stick_parts`]`(γ, alpha_max)`.
#[inline(always)]
pub fn stick_coord_parts(alpha: f64, parts: (f64, f64, Option<f64>)) -> f64 {
    if alpha.is_infinite() {
        return 1.0;
    }
    stick_coord_from(alpha, parts.0, parts.1, parts.2)
}

/// The `γ`-only parts of the stick coordinate: `α_c2 = γ²·(2/7)`, `ρ α_c2`, and
/// `S(α_max)` (`None` for `α_max = ∞`).
#[inline(always)]
pub fn stick_parts(gamma: f64, alpha_max: f64) -> (f64, f64, Option<f64>) {
    let c2 = gamma * gamma * (2.0 / 7.0);
    let rho_c2 = stick_scale(gamma) * c2;
    let s_max = (!alpha_max.is_infinite()).then(|| {
        let dm = alpha_max - c2;
        dm / (dm + rho_c2)
    });
    (c2, rho_c2, s_max)
}

/// The stick coordinate `S(α)/S(α_max)` (1 at `α = ∞`) from the `γ`-only parts
/// ([`stick_parts`]): the one statement of these operations, branch-free in `α` (a pass over
/// an array of queries is vectorized).
#[inline(always)]
pub fn stick_coord_from(alpha: f64, c2: f64, rho_c2: f64, s_max: Option<f64>) -> f64 {
    let d = alpha - c2;
    let s = d / (d + rho_c2);
    let s = match s_max {
        None => s,
        Some(m) => s / m,
    };
    if alpha.is_infinite() {
        1.0
    } else {
        s
    }
}
