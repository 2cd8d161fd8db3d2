//! The regions of the plane, the domain of a table, the errors of a query and [`Surface`], the
//! patches of one table with the rule that answers a point.

use super::*;

/// Relative distance from the `γ` of the table of one pair within which a query's `γ` is the
/// pair's ([`Surface::rule_gamma`]): `P` moves by about `|∂P/∂γ|·1e-9 γ`, below 1e-8.
pub const PAIR_GAMMA_TOL: f64 = 1e-9;

/// What a query outside the table's domain does (the full-slip line is answered everywhere).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OutOfDomain {
    /// Refuse it with [`TableError::Query`] naming the field and the domain (the default).
    #[default]
    Error,
    /// Answer at the nearest point of the domain: `γ` clamped to `[gamma_min, gamma_max]`, `α`
    /// to `alpha_max`. An extrapolation by a constant: the caller accepts the error it makes.
    Clamp,
}

/// `Ok` for a query the rule takes: `γ` finite and `> 0`, `α ≥ 0` (`∞` allowed); otherwise
/// the error naming the first that is not (every query path checks with this).
#[inline(always)]
pub fn check_query(gamma: f64, alpha: f64) -> Result<(), TableError> {
    if !(gamma.is_finite() && gamma > 0.0) {
        return Err(bad_gamma(gamma));
    }
    if alpha.is_nan() || alpha < 0.0 {
        return Err(bad_alpha(alpha));
    }
    Ok(())
}

#[cold]
pub fn bad_gamma(gamma: f64) -> TableError {
    TableError::Query {
        name: "gamma",
        value: gamma,
        allowed: "a finite number > 0".into(),
    }
}

/// `α` above a table's `alpha_max` without clamping.
#[cold]
pub fn alpha_outside(alpha_max: f64, alpha: f64) -> TableError {
    TableError::Query {
        name: "alpha",
        value: alpha,
        allowed: format!(
            "<= the table's alpha_max = {alpha_max}; or opt into clamping to answer at alpha_max"
        ),
    }
}

#[cold]
pub fn bad_alpha(alpha: f64) -> TableError {
    TableError::Query {
        name: "alpha",
        value: alpha,
        allowed: ">= 0 (or inf)".into(),
    }
}

/// The three patches of a table, indexed by region (file order: `stick_low`, `partial_high`,
/// `stick_high`; the index is the one of the `checks/patch` dataset).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PatchId {
    /// `γ ≤ 1`, `α_c2 ≤ α ≤ α_max`: a stick patch.
    StickLow,
    /// `γ ≥ 1`, `α_c1 ≤ α ≤ α_c2`: the partial-slip patch (the only one that may be warped).
    PartialHigh,
    /// `γ ≥ 1`, `α_c2 ≤ α ≤ α_max`: a stick patch.
    StickHigh,
}

impl PatchId {
    /// Every patch, in file and index order.
    pub const ALL: [PatchId; 3] = [PatchId::StickLow, PatchId::PartialHigh, PatchId::StickHigh];

    /// Index `0, 1, 2` (the `checks/patch` dataset's value).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The patch's group name in the file.
    pub fn name(self) -> &'static str {
        match self {
            PatchId::StickLow => crate::format::PATCH_STICK_LOW,
            PatchId::PartialHigh => crate::format::PATCH_PARTIAL_HIGH,
            PatchId::StickHigh => crate::format::PATCH_STICK_HIGH,
        }
    }

    /// Region and coordinate of the patch.
    pub fn kind(self) -> PatchKind {
        match self {
            PatchId::PartialHigh => PatchKind::PartialSlip,
            PatchId::StickLow | PatchId::StickHigh => PatchKind::Stick,
        }
    }
}

/// The whole interpolated surface: the domain, the stencil and the patches. Built only by
/// [`Surface::new`], so every surface is one the rule can evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Lower end of the γ domain.
    gamma_min: f64,
    /// Upper end of the γ domain.
    gamma_max: f64,
    /// Upper end of the α domain (`∞` allowed).
    alpha_max: f64,
    /// Lagrange stencil points per axis.
    stencil: usize,
    /// The patches, indexed by [`PatchId::index`].
    patches: [Option<Patch>; 3],
    /// The `e_n` range `[lo, hi]` of a table with a normal-restitution axis (every patch has
    /// that axis); `None` for an elastic table (`e_n = 1`).
    restitution: Option<(f64, f64)>,
    /// The partial-slip coordinate's map, which also says whether the table answers the
    /// full-slip line ([`PartialMap::has_line`]; [`Surface::with_partial_map`]).
    partial_map: PartialMap,
}

impl Surface {
    /// A surface from its parts, checked: `0 < gamma_min < gamma_max < ∞`, `alpha_max > 0`
    /// (or `∞`), an even stencil in `[2, 8]` that every leaf grid can hold, each patch of the
    /// kind its place says (`patches` indexed by [`PatchId::index`]), `stick_low` present when
    /// `gamma_min < 1`, `partial_high` and `stick_high` when `gamma_max > 1`, a warp only on
    /// `partial_high`. `Err` names the value and the rule.
    pub fn new(
        gamma_min: f64,
        gamma_max: f64,
        alpha_max: f64,
        stencil: usize,
        patches: [Option<Patch>; 3],
    ) -> Result<Surface, String> {
        Surface::with_restitution(gamma_min, gamma_max, alpha_max, stencil, patches, None)
    }

    /// [`Surface::new`] with an `e_n` axis over `restitution = (lo, hi)` (schema 4): every
    /// patch must have that axis ([`Patch::restitution`]) over that range; with `None`, none
    /// may have one.
    pub fn with_restitution(
        gamma_min: f64,
        gamma_max: f64,
        alpha_max: f64,
        stencil: usize,
        patches: [Option<Patch>; 3],
        restitution: Option<(f64, f64)>,
    ) -> Result<Surface, String> {
        if let Some((lo, hi)) = restitution {
            Axis::restitution(lo, hi, 1)?;
        }
        let pair = gamma_min == gamma_max && restitution.is_some();
        if !(gamma_min > 0.0 && (gamma_max > gamma_min || pair) && gamma_max.is_finite()) {
            return Err(format!(
                "gamma domain [{gamma_min}, {gamma_max}] must satisfy 0 < min < max < inf (or \
                 min = max for the table of one pair, which has an e_n axis)"
            ));
        }
        if alpha_max.is_nan() || alpha_max <= 0.0 {
            return Err(format!("alpha_max = {alpha_max} must be > 0 or inf"));
        }
        if !(2..=8).contains(&stencil) || !stencil.is_multiple_of(2) {
            return Err(format!(
                "stencil_points = {stencil}: must be an even integer in [2, 8]"
            ));
        }
        for id in PatchId::ALL {
            let Some(p) = &patches[id.index()] else {
                continue;
            };
            let name = id.name();
            if p.kind() != id.kind() {
                return Err(format!(
                    "patch '{name}' has kind '{}', expected '{}'",
                    p.kind().name(),
                    id.kind().name()
                ));
            }
            if p.leaf_intervals() + 1 < stencil {
                return Err(format!(
                    "patch '{name}': leaf_intervals = {} gives fewer nodes than stencil_points \
                     = {stencil}",
                    p.leaf_intervals()
                ));
            }
            let axis = p.restitution().map(|r| (r.lo(), r.hi()));
            if axis != restitution {
                return Err(format!(
                    "patch '{name}' has the e_n axis {axis:?}, the table {restitution:?}: every \
                     patch must have the table's"
                ));
            }
            let map = p.restitution().map_or(AxisMap::Linear, |r| r.map);
            let first = patches
                .iter()
                .flatten()
                .next()
                .and_then(Patch::restitution)
                .map_or(AxisMap::Linear, |r| r.map);
            if map != first {
                return Err(format!(
                    "patch '{name}' maps e_n as '{}', another patch as '{}': every patch must \
                     map it as the table does",
                    map.name(),
                    first.name()
                ));
            }
            if p.is_pair() != pair || (pair && p.gamma_lo() != gamma_min) {
                return Err(format!(
                    "patch '{name}' has the gamma edges [{}, {}], the table the gamma domain \
                     [{gamma_min}, {gamma_max}]: the table of one pair and its patches hold the \
                     same single gamma, any other table none",
                    p.gamma_lo(),
                    p.gamma_hi()
                ));
            }
            if p.warp().is_some() && id != PatchId::PartialHigh {
                return Err(format!(
                    "patch '{name}' has a warp: only '{}' may have one",
                    PatchId::PartialHigh.name()
                ));
            }
        }
        let [low, partial, high] = &patches;
        if gamma_min < 1.0 && low.is_none() {
            return Err(format!("missing patch '{}'", PatchId::StickLow.name()));
        }
        if gamma_max > 1.0 && (partial.is_none() || high.is_none()) {
            return Err(format!(
                "missing patch '{}' or '{}'",
                PatchId::PartialHigh.name(),
                PatchId::StickHigh.name()
            ));
        }
        Ok(Surface {
            gamma_min,
            gamma_max,
            alpha_max,
            stencil,
            patches,
            restitution,
            partial_map: PartialMap::of_table(restitution.is_some()),
        })
    }

    /// The same surface with the partial-slip map `map`: [`PartialMap::SqrtEnd`] for an
    /// elastic table, [`PartialMap::SqrtBoth`] (the default with an `e_n` axis) or
    /// [`PartialMap::Slip`] with an `e_n` axis. A [`PartialMap::Slip`] table (Thornton's law)
    /// has no full-slip line: its partial-slip patch answers every `α < α_c2` for `γ ≥ 1`, and
    /// it needs `gamma_min ≥ 1` (the side `γ < 1` of such a law is not designed) and a range
    /// of `γ` (not the table of one pair). `Err` names the rule.
    pub fn with_partial_map(mut self, map: PartialMap) -> Result<Surface, String> {
        let name = |m: PartialMap| m.coordinate().unwrap_or("the elastic map");
        match (map, self.restitution) {
            (PartialMap::SqrtEnd, None) => {}
            (PartialMap::SqrtBoth, Some(_)) => {}
            (PartialMap::Slip, Some(_)) => {
                if self.gamma_min < 1.0 || self.pair_gamma().is_some() {
                    return Err(format!(
                        "the partial-slip coordinate '{}' needs a gamma range with \
                         gamma_min >= 1, not [{}, {}]",
                        name(map),
                        self.gamma_min,
                        self.gamma_max
                    ));
                }
            }
            _ => {
                return Err(format!(
                    "the partial-slip coordinate '{}' is for {}",
                    name(map),
                    if self.restitution.is_some() {
                        "an elastic table, this one has an e_n axis"
                    } else {
                        "a table with an e_n axis, this one is elastic"
                    }
                ))
            }
        }
        self.partial_map = map;
        Ok(self)
    }

    /// The partial-slip coordinate's map ([`Surface::with_partial_map`]).
    #[inline(always)]
    pub fn partial_map(&self) -> PartialMap {
        self.partial_map
    }

    /// Whether the table answers `α ≤ α_c1(γ, e_n)` from the closed-form full-slip line (all
    /// but a table of Thornton's law, [`PartialMap::Slip`]).
    #[inline(always)]
    pub fn has_line(&self) -> bool {
        self.partial_map.has_line()
    }

    /// Where the full-slip line ends at `(γ, e_n)`: [`linear_limit_dissipative`], or `−∞` in
    /// a table without a line ([`Surface::has_line`]; no `α ≥ 0` is on it).
    #[inline(always)]
    pub fn line_end(&self, gamma: f64, e_n: f64) -> f64 {
        if self.has_line() {
            linear_limit_dissipative(gamma, e_n)
        } else {
            f64::NEG_INFINITY
        }
    }

    /// Whether a `γ` in the domain is answered by the patches of `γ ≥ 1` (`partial_high`,
    /// `stick_high`): `γ > 1`, and `γ = 1` too in a table without a line (where the
    /// partial-slip patch holds `P` below `α_c2 = α_c1`).
    #[inline(always)]
    pub fn high(&self, gamma: f64) -> bool {
        gamma > 1.0 || (gamma == 1.0 && !self.has_line())
    }

    /// The region of a valid `(γ, α, e_n)` in this table: [`Region::of_e`], or without a
    /// line ([`Surface::has_line`]) [`Region::off_line`].
    #[inline(always)]
    pub fn region_at(&self, gamma: f64, alpha: f64, e_n: f64) -> Region {
        if self.has_line() {
            Region::of_e(gamma, alpha, e_n)
        } else {
            Region::off_line(gamma, alpha, || alpha_c2(gamma))
        }
    }

    /// The same surface with every patch replaced by `f(id, patch)`, checked as by
    /// [`Surface::new`].
    pub fn map_patches(
        &self,
        mut f: impl FnMut(PatchId, &Patch) -> Result<Patch, String>,
    ) -> Result<Surface, String> {
        let mut patches: [Option<Patch>; 3] = [None, None, None];
        for id in PatchId::ALL {
            if let Some(p) = &self.patches[id.index()] {
                patches[id.index()] = Some(f(id, p)?);
            }
        }
        Surface::with_restitution(
            self.gamma_min,
            self.gamma_max,
            self.alpha_max,
            self.stencil,
            patches,
            self.restitution,
        )?
        .with_partial_map(self.partial_map)
    }

    /// The `e_n` range `[lo, hi]` of a table with a normal-restitution axis; `None` for an
    /// elastic table (it answers `e_n = 1` only).
    pub fn restitution(&self) -> Option<(f64, f64)> {
        self.restitution
    }

    /// How the patches map `e_n` to their coordinate ([`AxisMap::Linear`] for an elastic
    /// table): the root attribute `e_n_coordinate` of a schema-5 table.
    pub fn e_n_map(&self) -> AxisMap {
        self.patches
            .iter()
            .flatten()
            .next()
            .and_then(Patch::restitution)
            .map_or(AxisMap::Linear, |r| r.map)
    }

    /// The single `γ` of the table of one pair of materials (axes `α`, `e_n`; `gamma_min =
    /// gamma_max`), `None` for a table over a range of `γ`.
    pub fn pair_gamma(&self) -> Option<f64> {
        (self.gamma_min == self.gamma_max).then_some(self.gamma_min)
    }

    /// `γ` as the rule takes it: in the table of one pair, a `γ` within [`PAIR_GAMMA_TOL`]
    /// (relative) of the pair's is the pair's (`P` moves by far less than the table's error
    /// there); any other `γ` as it is.
    #[inline(always)]
    pub fn rule_gamma(&self, gamma: f64) -> f64 {
        if self.gamma_min == self.gamma_max
            && (gamma - self.gamma_min).abs() <= PAIR_GAMMA_TOL * self.gamma_min
        {
            self.gamma_min
        } else {
            gamma
        }
    }

    /// The table's axes, in order: `γ` over `[gamma_min, gamma_max]`, `α` over
    /// `[0, alpha_max]`, and `e_n` over its range when the table has one.
    pub fn axes(&self) -> Vec<Axis> {
        let mut axes = Vec::with_capacity(3);
        if self.pair_gamma().is_none() {
            axes.push(Axis {
                name: AxisName::Gamma,
                map: AxisMap::Linear,
                lo: self.gamma_min,
                hi: self.gamma_max,
                blocks: 1,
            });
        }
        axes.extend([Axis {
            name: AxisName::Alpha,
            map: AxisMap::Linear,
            lo: 0.0,
            hi: self.alpha_max,
            blocks: 1,
        }]);
        if let Some((lo, hi)) = self.restitution {
            axes.push(Axis {
                name: AxisName::RESTITUTION_N,
                map: self.e_n_map(),
                lo,
                hi,
                blocks: 1,
            });
        }
        axes
    }

    /// Lower end of the γ domain.
    pub fn gamma_min(&self) -> f64 {
        self.gamma_min
    }

    /// Upper end of the γ domain.
    pub fn gamma_max(&self) -> f64 {
        self.gamma_max
    }

    /// Upper end of the α domain (`∞` allowed).
    pub fn alpha_max(&self) -> f64 {
        self.alpha_max
    }

    /// Lagrange stencil points per axis.
    pub fn stencil(&self) -> usize {
        self.stencil
    }

    /// The patch `id`, if the table has it.
    pub fn patch_by_id(&self, id: PatchId) -> Option<&Patch> {
        self.patches[id.index()].as_ref()
    }

    /// The patches the table has, in file order.
    pub fn patches(&self) -> impl Iterator<Item = (PatchId, &Patch)> {
        PatchId::ALL
            .into_iter()
            .filter_map(|id| self.patch_by_id(id).map(|p| (id, p)))
    }
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
    #[inline]
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

    /// [`Region::of`] as a number, branch-free (for passes over arrays that a vector unit
    /// runs): 0 the line, then [`PatchId::index`] + 1 (1 `stick_low`, 2 `partial_high`, 3
    /// `stick_high`).
    #[inline(always)]
    pub fn code_of(gamma: f64, alpha: f64) -> u8 {
        let c2 = alpha_c2(gamma);
        let high = gamma > 1.0;
        // `linear_limit`, the same operations.
        let line = alpha <= if high { alpha_c1(gamma) } else { c2 };
        let patch = 1 + u8::from(high) + u8::from(high & (alpha >= c2));
        if line {
            0
        } else {
            patch
        }
    }

    /// Region of `(γ, α)` at normal restitution `e_n` (assumed valid): the full-slip line ends
    /// at [`linear_limit_dissipative`]; `α_c2` does not move with `e_n`. `e_n = 1` is
    /// [`Region::of`], bit for bit.
    #[inline]
    pub fn of_e(gamma: f64, alpha: f64, e_n: f64) -> Self {
        Region::of_limits(gamma, alpha, linear_limit_dissipative(gamma, e_n), || {
            alpha_c2(gamma)
        })
    }

    /// [`Region::of_e`] from the `γ`-only parts: `line_end` =
    /// [`linear_limit_dissipative`]`(γ, e_n)` and `c2()` = [`alpha_c2`]`(γ)` (for a code that
    /// asks at one `γ` and `e_n` many times).
    #[inline(always)]
    pub fn of_limits(gamma: f64, alpha: f64, line_end: f64, c2: impl Fn() -> f64) -> Self {
        if alpha <= line_end {
            Region::Line
        } else if gamma <= 1.0 {
            Region::StickLow
        } else if alpha < c2() {
            Region::PartialHigh
        } else {
            Region::StickHigh
        }
    }

    /// The region of a valid `(γ, α)` in a table without a full-slip line
    /// ([`Surface::has_line`]; `c2()` = [`alpha_c2`]`(γ)`): `partial_high` for `γ ≥ 1` and
    /// `α < α_c2`, `stick_high` for `γ ≥ 1` above, `stick_low` for `γ < 1` (outside such a
    /// table's domain: refused or clamped). Never [`Region::Line`].
    #[inline(always)]
    pub fn off_line(gamma: f64, alpha: f64, c2: impl Fn() -> f64) -> Self {
        if gamma < 1.0 {
            Region::StickLow
        } else if alpha < c2() {
            Region::PartialHigh
        } else {
            Region::StickHigh
        }
    }

    /// The patch that answers in this region (`None` on the line).
    pub fn patch_id(self) -> Option<PatchId> {
        match self {
            Region::Line => None,
            Region::StickLow => Some(PatchId::StickLow),
            Region::PartialHigh => Some(PatchId::PartialHigh),
            Region::StickHigh => Some(PatchId::StickHigh),
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
        self.patch_by_id(region.patch_id()?)
    }

    /// `P(γ, α)` by the documented rule, refusing `γ` outside `[gamma_min, gamma_max]` (except
    /// on the full-slip line) and `α > alpha_max`; the same as
    /// [`Surface::eval_with`]`(γ, α, OutOfDomain::Error)`.
    #[inline]
    pub fn eval(&self, gamma: f64, alpha: f64) -> Result<f64, TableError> {
        self.eval_with(gamma, alpha, OutOfDomain::Error)
    }

    /// `P(γ, α)` by the documented rule (dimensionless, `−1 ≤ P ≤ 1`) of an elastic impact:
    /// [`Surface::eval_point`] at `e_n = 1` (an error for a table whose `e_n` range does not
    /// reach 1). `γ` must be finite and `> 0`, `α ≥ 0` (`α = ∞` is the no-slip limit). The
    /// full-slip line `P = 1 − 7α` is exact and answered for any `γ > 0`. Elsewhere a point
    /// outside the table's domain (`γ ∉ [gamma_min, gamma_max]` or `α > alpha_max`) is an
    /// error with [`OutOfDomain::Error`]; with [`OutOfDomain::Clamp`] it is answered at the
    /// nearest point of the domain, `P(clamp(γ), min(α, alpha_max))`.
    ///
    /// Touches only memory and does not allocate unless it returns an error.
    #[inline]
    pub fn eval_with(
        &self,
        gamma: f64,
        alpha: f64,
        outside: OutOfDomain,
    ) -> Result<f64, TableError> {
        self.eval_point(gamma, alpha, 1.0, outside)
    }

    /// `P(γ, α, e_n)` by the documented rule: [`Surface::eval_with`] at normal restitution
    /// `e_n`. `e_n` must be 1 for an elastic table and inside the table's `e_n` range
    /// otherwise (with either [`OutOfDomain`]: clamping applies to `γ` and `α` only, never to
    /// `e_n`). The full-slip line is `P = 1 − (7/2)(1 + e_n)α` up to
    /// `α_c1(γ, e_n)` (`physics.md`).
    #[inline]
    pub fn eval_point(
        &self,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, TableError> {
        let gamma = self.rule_gamma(gamma);
        let region = self.region_of(gamma, alpha, e_n)?;
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        self.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n)
        })
    }

    /// Steps 1 to 3 of the rule for a query at normal restitution `e_n`: the checks of the
    /// query ([`check_query`], [`Surface::check_e_n`]) and its region ([`Region::of_e`]). The
    /// rule ([`Surface::eval_point`]) and the indexed query path of a table with an `e_n`
    /// axis begin with it; on [`Region::Line`] both answer the full-slip line, elsewhere both
    /// go through [`Surface::apply_domain_e`].
    #[inline(always)]
    pub fn region_of(&self, gamma: f64, alpha: f64, e_n: f64) -> Result<Region, TableError> {
        check_query(gamma, alpha)?;
        self.check_e_n(e_n)?;
        Ok(self.region_at(gamma, alpha, e_n))
    }

    /// `Ok` when the table answers at normal restitution `e_n`: exactly 1 for an elastic
    /// table, inside `[lo, hi]` for a table with an `e_n` axis; otherwise the query error
    /// naming `e_n` and the allowed values.
    #[inline(always)]
    pub fn check_e_n(&self, e_n: f64) -> Result<(), TableError> {
        match self.restitution {
            None if e_n == 1.0 => Ok(()),
            Some((lo, hi)) if e_n >= lo && e_n <= hi => Ok(()),
            r => Err(e_n_outside(r, e_n)),
        }
    }

    /// The domain policy of [`Surface::eval_with`] for a valid query above the full-slip line
    /// (in `region`, not [`Region::Line`]): inside the table's domain `eval_in(region, γ, α)`;
    /// outside it the error for [`OutOfDomain::Error`], or for [`OutOfDomain::Clamp`] the value
    /// at `(clamp(γ), min(α, alpha_max))` (exactly `1 − 7α` if that point is on the line).
    ///
    /// The one place of this policy: the rule ([`Surface::eval_with`]) and the fast path
    /// (`fast::Accel`, with its own evaluator of a known non-line region) both go through it.
    #[inline(always)]
    pub fn apply_domain(
        &self,
        region: Region,
        gamma: f64,
        alpha: f64,
        outside: OutOfDomain,
        eval_in: impl Fn(Region, f64, f64) -> f64,
    ) -> Result<f64, TableError> {
        self.apply_domain_e(region, gamma, alpha, 1.0, outside, eval_in)
    }

    /// [`Surface::apply_domain`] at normal restitution `e_n` (checked by the caller): the
    /// clamped point's region and line are those of `e_n`.
    #[inline(always)]
    pub fn apply_domain_e(
        &self,
        region: Region,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
        eval_in: impl Fn(Region, f64, f64) -> f64,
    ) -> Result<f64, TableError> {
        let inside = gamma >= self.gamma_min && gamma <= self.gamma_max;
        if inside && alpha <= self.alpha_max {
            return Ok(eval_in(region, gamma, alpha));
        }
        match outside {
            OutOfDomain::Error if !inside => Err(self.gamma_outside(gamma)),
            OutOfDomain::Error => Err(self.alpha_outside(alpha)),
            OutOfDomain::Clamp => {
                let g = gamma.clamp(self.gamma_min, self.gamma_max);
                let a = alpha.min(self.alpha_max);
                match self.region_at(g, a, e_n) {
                    Region::Line => Ok(full_slip_line(a, e_n)),
                    r => Ok(eval_in(r, g, a)),
                }
            }
        }
    }

    #[cold]
    pub fn gamma_outside(&self, gamma: f64) -> TableError {
        if let Some(g) = self.pair_gamma() {
            return TableError::Query {
                name: "gamma",
                value: gamma,
                allowed: format!(
                    "{g} (within a relative {PAIR_GAMMA_TOL:e}): this table holds one pair of \
                     materials (or alpha <= alpha_lin(gamma)); for other pairs use a table over \
                     a range of gamma"
                ),
            };
        }
        TableError::Query {
            name: "gamma",
            value: gamma,
            allowed: format!(
                "in the table's domain [{}, {}] (or alpha <= alpha_lin(gamma)); \
                 or opt into clamping to answer at the nearest gamma of the table",
                self.gamma_min, self.gamma_max
            ),
        }
    }

    #[cold]
    pub fn alpha_outside(&self, alpha: f64) -> TableError {
        alpha_outside(self.alpha_max, alpha)
    }

    /// Evaluate in a known non-line region at `e_n` (no checks: `γ` inside the table's range,
    /// `α ≤ alpha_max`, `e_n` one the table answers). The patch coordinate is
    /// [`PatchKind::coord_at`]'s, from the `γ`-only parts.
    #[inline]
    pub fn eval_in(&self, region: Region, gamma: f64, alpha: f64, e_n: f64) -> f64 {
        match self.patch(region) {
            Some(patch) if patch.restitution().is_none() => {
                let c = match patch.kind {
                    PatchKind::PartialSlip => partial_coord(gamma, alpha),
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                let c = patch.warped(gamma, c.clamp(0.0, 1.0));
                patch.interpolate(gamma, c, self.stencil)
            }
            Some(patch) => {
                let c = match patch.kind {
                    PatchKind::PartialSlip => {
                        partial_coord_map(self.partial_map, gamma, alpha, e_n)
                    }
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                let c = patch.knotted(gamma, c.clamp(0.0, 1.0), e_n);
                patch.interpolate_at(gamma, c, e_n, self.stencil)
            }
            // A domain that touches γ = 1 only from one side: at γ = 1 exactly the contact
            // sticks at once and P = −e_n on the nonlinear part (α ≥ 2/7).
            None => -e_n,
        }
    }
}

/// `e_n` that a table with the `e_n` range `range` (`None`: elastic) does not answer.
#[cold]
pub fn e_n_outside(range: Option<(f64, f64)>, e_n: f64) -> TableError {
    TableError::Query {
        name: "e_n",
        value: e_n,
        allowed: match range {
            None => "1: this table is elastic (it has no e_n axis); for e_n < 1 use a table \
                     built with an e_n range"
                .into(),
            Some((lo, hi)) => format!("in the table's e_n range [{lo}, {hi}]"),
        },
    }
}
