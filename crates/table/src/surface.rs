//! The interpolation rule of schema v3 (stated in `docs/table-format.md`).
//!
//! The nonlinear part of the `(γ, α)` plane is covered by up to three patches whose edges lie on
//! the curves where `P` has curvature jumps, so that `P` is smooth inside each patch:
//!
//! | patch          | γ range        | α range          | coordinate `c ∈ [0, 1]`                        |
//! |----------------|----------------|------------------|------------------------------------------------|
//! | `stick_low`    | `γ_min ≤ γ ≤ 1` | `α_c2 … α_max`  | `S(α)/S(α_max)`, `S = r/(r + ρ)`               |
//! | `partial_high` | `1 ≤ γ ≤ γ_max` | `α_c1 … α_c2`   | `1 − √(1 − ℓ)`, `ℓ = ln(α/α_c1)/ln(α_c2/α_c1)` |
//! | `stick_high`   | `1 ≤ γ ≤ γ_max` | `α_c2 … α_max`  | `S(α)/S(α_max)`, `S = r/(r + ρ)`               |
//!
//! with `r = α/α_c2 − 1`, `ρ = 2(1 − γ²)` for `γ < 1` and `ρ = 1` for `γ ≥ 1`, `S(∞) = 1`. Each
//! patch is cut into equal root cells in `(γ, c)`, each refined as a quadtree where `P` needs it
//! (the kink curves inside the partial-slip patch for `γ ≳ 2`); every leaf stores `P` on its own
//! uniform grid. Inside a leaf `P` is the tensor product of 1-D Lagrange polynomials through `k`
//! consecutive nodes of that leaf per axis (`k = stencil_points`). The partial-slip patch may
//! carry a [`Warp`] of its coordinate (schema 3), applied before the leaf is located.

use crate::leaf::{cubic_tensor, descend, descend_masked, lagrange_tensor, MAX_AXES};
use crate::TableError;

pub use crate::leaf::{cubic_weights, floor_index, locate, stencil, stencil4};

pub use oblique_physics::regimes::{
    alpha_c1, alpha_c1_dissipative, alpha_c2, full_slip_line, linear_limit,
    linear_limit_dissipative,
};

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
                let c1 = alpha_c1_dissipative(gamma, e_n);
                let l = (alpha / c1).ln() / (alpha_c2(gamma) / c1).ln();
                map.c_of_l(l)
            }
            PatchKind::Stick => {
                let rho = stick_scale(gamma);
                let squash = |alpha: f64| {
                    let r = alpha / alpha_c2(gamma) - 1.0;
                    // r = ∞ also for finite α near f64::MAX (found by tests/fuzz.rs: NaN).
                    if r.is_infinite() {
                        1.0
                    } else {
                        r / (r + rho)
                    }
                };
                squash(alpha) / squash(alpha_max)
            }
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

    /// `c` of `ℓ` (`ℓ` outside `[0, 1]` by rounding: the ends).
    #[inline(always)]
    pub fn c_of_l(self, l: f64) -> f64 {
        match self {
            PartialMap::SqrtEnd => 1.0 - (1.0 - l).max(0.0).sqrt(),
            PartialMap::SqrtBoth => 1.0 - (1.0 - l.clamp(0.0, 1.0).sqrt()).sqrt(),
        }
    }

    /// `ℓ` of `c` (the inverse of [`PartialMap::c_of_l`]).
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

/// Largest number of entries (4 bytes each) of one patch's fine index: 2¹⁵ = 128 KiB, so that
/// an index stays in the second-level cache next to the nodes. A patch whose deepest leaves
/// would need more gets an index at a smaller depth, from which the quadtree descent continues
/// (`tables/full.h5`: `partial_high` indexed at depth 5 of 9, the others at full depth).
pub const MAX_INDEX_ENTRIES: usize = 1 << 15;

/// Depth `d_k` along each axis `k` (`γ`, `c`, `e_n`) and integer origin of a cell of a
/// patch's tree: `scale_k = 2^d_k`, and the cell covers `[o_k, o_k + 1)` along axis `k` in units
/// of its own size along it (root cells have `scale = 1` and the origin `(a, b, …)` of step 6
/// of the rule; 0 beyond the patch's axes). Without a `split` dataset every `d_k` is the cell's
/// depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellOrigin {
    /// `2^d_k` per axis.
    pub scale: [f64; MAX_AXES],
    /// Origin per axis, `floor(v_k·2^d_k)` for the points it covers.
    pub origin: [f64; MAX_AXES],
    /// The axes the cell halves if it is split ([`Patch::split_mask`]); 0 for a leaf.
    pub mask: u8,
}

/// A uniform grid at depth `depth_k` along each axis `k` of a patch (`blocks_k·2^depth_k`
/// entries), each entry the deepest cell that contains it among those of depth `≤ depth_k`
/// along every axis, and every cell's depths and origin. A query at `v = x·blocks` (step 6 of
/// the rule) reads the entry of `floor(v_k·2^depth_k)`; inside a cell the position is
/// `v_k·scale_k − origin_k`, which equals the rule's repeated `f ← 2f − q` bit for bit
/// (scaling by a power of two and subtracting an integer below the value are exact), and the
/// rule's descent continues from there when the cell is split. Without a `split` dataset
/// every `depth_k` is the same.
#[derive(Debug, Clone, PartialEq)]
pub struct FineIndex {
    /// Depth of the grid per axis (0 beyond the patch's axes).
    pub depth: [u32; MAX_AXES],
    /// Entries per axis (`γ`, `c`, `e_n`; 1 beyond the patch's axes).
    pub shape: [usize; MAX_AXES],
    /// The cell numbers, row-major (γ outer), each `< cells.len()`.
    pub index: Vec<u32>,
    /// Every cell of the tree, in the order of the tree.
    pub cells: Vec<CellOrigin>,
}

/// One patch: `blocks_gamma × blocks_coord` equal root cells in `(γ, c)`, each the root of a
/// quadtree. A cell is either split into four children of half its size or is a leaf; every leaf
/// carries a uniform grid of `(m + 1) × (m + 1)` nodes (`m = leaf_intervals`) over its own square,
/// so the node spacing halves with each depth, only where `P` needs it.
///
/// `tree[i]` describes cell `i`. Cells `0 .. blocks_gamma·blocks_coord` are the roots, row-major
/// (`γ` outer). `tree[i] ≥ 0`: the cell is split and its children are the cells
/// `tree[i] + 2·q_γ + q_c`, where `q_γ, q_c ∈ {0, 1}` select the upper half along γ and `c`.
/// `tree[i] < 0`: the cell is leaf number `−tree[i] − 1`, whose nodes are
/// `p[leaf·(m+1)² + i_γ·(m+1) + i_c]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// Region and coordinate.
    kind: PatchKind,
    /// Lower γ edge.
    gamma_lo: f64,
    /// Upper γ edge.
    gamma_hi: f64,
    /// Root cells along γ.
    blocks_gamma: usize,
    /// Root cells along `c`.
    blocks_coord: usize,
    /// Intervals per axis of every leaf's grid (`m`).
    leaf_intervals: usize,
    /// The quadtree, see the type's documentation.
    tree: Vec<i32>,
    /// `P` at the nodes, leaf by leaf, `[leaves, m + 1, m + 1]` row-major.
    p: Vec<f64>,
    /// Solver error estimate of each node, same layout.
    error_estimate: Vec<f64>,
    /// Optional warp of the coordinate (only `partial_high`, schema 3): when present, the
    /// quadtree is over `(x, c')` with `c' =` [`Warp::apply`]`(γ, c)` instead of `(x, c)`.
    warp: Option<Warp>,
    /// The third axis, normal restitution `e_n` (schema 4), if the table has one: the tree is
    /// then an octree over `(x, c, x_e)` (see [`RestitutionAxis`]).
    restitution: Option<RestitutionAxis>,
    /// Which axes each split cell halves (schema 4, optional; see [`check_split`]): bit
    /// `dims − 1 − k` for axis `k` (`γ`, `c`, `e_n`), non-zero exactly for the split cells.
    /// The children of cell `i` are the `2^popcount` cells from `tree[i]`, numbered row-major
    /// over the halved axes in axis order. `None`: every split halves every axis.
    split: Option<Vec<u8>>,
}

/// The normal-restitution axis of a patch (schema 4): `e_n` from `lo` to `hi`, cut into
/// `blocks` equal root cells; the patch's third coordinate is `x_e = (e_n − lo)/(hi − lo)`.
///
/// With it a patch is `blocks_gamma × blocks_coord × blocks` root cells, numbered row-major
/// (`γ` outer, `e_n` inner), each the root of an octree: a split cell's children are the cells
/// `tree[i] + 4·q_γ + 2·q_c + q_e`, and every leaf stores `(m + 1)³` nodes,
/// `p[leaf·(m+1)³ + (i_γ·(m+1) + i_c)·(m+1) + i_e]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestitutionAxis {
    /// Lowest `e_n`.
    lo: f64,
    /// Highest `e_n`.
    hi: f64,
    /// Root cells along `e_n`.
    blocks: usize,
}

impl RestitutionAxis {
    /// The axis from its stored values: `0 < lo < hi ≤ 1` and `1 ≤ blocks ≤ 2¹⁶`. `Err` names
    /// the attribute and the allowed range.
    pub fn new(lo: f64, hi: f64, blocks: usize) -> Result<RestitutionAxis, String> {
        if !(lo > 0.0 && hi > lo && hi <= 1.0) {
            return Err(format!(
                "e_n range [{lo}, {hi}]: must satisfy 0 < e_n_lo < e_n_hi <= 1"
            ));
        }
        if !(1..=1 << 16).contains(&blocks) {
            return Err(format!(
                "blocks_e_n = {blocks}: must be an integer in [1, 65536]"
            ));
        }
        Ok(RestitutionAxis { lo, hi, blocks })
    }

    /// Lowest `e_n`.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// Highest `e_n`.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// Root cells along `e_n`.
    pub fn blocks(&self) -> usize {
        self.blocks
    }

    /// The coordinate `x_e = (e_n − lo)/(hi − lo)` of `e_n`.
    #[inline(always)]
    pub fn x(&self, e_n: f64) -> f64 {
        (e_n - self.lo) / (self.hi - self.lo)
    }

    /// `e_n` at coordinate `x` (`hi` exactly at `x = 1`).
    pub fn e_n(&self, x: f64) -> f64 {
        if x >= 1.0 {
            self.hi
        } else {
            self.lo + (self.hi - self.lo) * x
        }
    }
}

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
    start: f64,
    /// γ of `knot[0]`.
    gamma_0: f64,
    /// γ spacing of the knots (`> 0`).
    gamma_step: f64,
    /// Where the knot is sent: `c' = c_star` at `c = K(γ)`, in `(0, 1)`.
    c_star: f64,
    /// `K` at `γ = gamma_0 + i·gamma_step`, every value in `(0, 1)`, at least 4 values.
    knot: Vec<f64>,
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

/// Step 10 of the rule: the interpolated `P` limited to `[−1, 1]` (`|P| ≤ 1`: a rebound never
/// gains energy). Every read path applies it to the tensor product, so that near `P = −1` (where
/// the interpolant can overshoot by up to the table's error) no path answers `|P| > 1`; a NaN
/// stays NaN.
#[inline(always)]
pub fn bound_p(p: f64) -> f64 {
    p.clamp(-1.0, 1.0)
}

/// Axes of a patch's tree: 3 (`γ`, `c`, `e_n`) with an `e_n` axis over a range of `γ`, else 2
/// (`γ`, `c` without the axis; `c`, `e_n` in the patch of one pair, [`Patch::is_pair`]).
pub fn tree_dims(has_e_n: bool, pair: bool) -> u32 {
    if has_e_n && !pair {
        3
    } else {
        2
    }
}

/// Check that `tree` is a valid quadtree over `roots` root cells whose leaves are numbered
/// `0..leaves` each exactly once; returns the number of leaves. `Err` says what is wrong with
/// the dataset `tree`.
pub fn check_tree(tree: &[i32], roots: usize) -> Result<usize, String> {
    check_tree_of(tree, roots, 4)
}

/// [`check_tree`] for a tree whose split cells have `fanout` children (4 for a quadtree, 8
/// for the octree of a patch with an `e_n` axis).
pub fn check_tree_of(tree: &[i32], roots: usize, fanout: usize) -> Result<usize, String> {
    if tree.len() < roots || !(tree.len() - roots).is_multiple_of(fanout) {
        return Err(format!(
            "has {} cells: expected {roots} roots plus groups of {fanout} children",
            tree.len()
        ));
    }
    check_tree_split(tree, roots, &|_| fanout)
}

/// [`check_tree_of`] with the number of children of each split cell given by `fanout(cell)`
/// (a tree whose cells halve different sets of axes, [`check_split`]).
pub fn check_tree_split(
    tree: &[i32],
    roots: usize,
    fanout: &dyn Fn(usize) -> usize,
) -> Result<usize, String> {
    if tree.len() < roots {
        return Err(format!(
            "has {} cells: expected at least {roots} roots",
            tree.len()
        ));
    }
    let children: usize = (0..tree.len()).filter(|&i| tree[i] >= 0).map(fanout).sum();
    if tree.len() - roots != children {
        return Err(format!(
            "has {} cells: expected {roots} roots plus the {children} children of its split \
             cells",
            tree.len()
        ));
    }
    let mut referenced = vec![false; tree.len()];
    let mut leaves = Vec::new();
    for (i, &t) in tree.iter().enumerate() {
        if t < 0 {
            leaves.push((-(t as i64) - 1) as usize);
            continue;
        }
        let (first, fanout) = (t as usize, fanout(i));
        // Children come after their parent (no cycles) and after the roots.
        if first <= i || first < roots || first + fanout > tree.len() {
            return Err(format!("cell {i} points to children at {t}: out of range"));
        }
        for r in &mut referenced[first..first + fanout] {
            if *r {
                return Err(format!(
                    "cell {i}: children at {t} shared with another cell"
                ));
            }
            *r = true;
        }
    }
    if let Some(i) = (roots..tree.len()).find(|&i| !referenced[i]) {
        return Err(format!("cell {i} is not reachable from a root"));
    }
    leaves.sort_unstable();
    if leaves.iter().enumerate().any(|(k, &l)| k != l) {
        return Err("does not number its leaves 0, 1, 2, ... exactly once".into());
    }
    Ok(leaves.len())
}

/// Check a `split` dataset against its tree: one mask per cell, 1 to `2^dims − 1` for a split
/// cell (bit `dims − 1 − k` for each axis `k` it halves), 0 for a leaf; only in a patch with
/// an `e_n` axis: `dims = 3` over `(γ, c, e_n)`, or `dims = 2` over `(c, e_n)` in a patch of
/// one pair (`has_e_n`; an elastic patch, `dims = 2` without the axis, has none).
pub fn check_split(tree: &[i32], split: &[u8], dims: u32, has_e_n: bool) -> Result<(), String> {
    if !has_e_n || !(2..=3).contains(&dims) {
        return Err("is allowed only in a patch with an e_n axis".into());
    }
    if split.len() != tree.len() {
        return Err(format!(
            "has {} masks: expected one per cell of 'tree' ({})",
            split.len(),
            tree.len()
        ));
    }
    for (i, (&t, &s)) in tree.iter().zip(split).enumerate() {
        if (t >= 0) != (s != 0) || u32::from(s) >= 1 << dims {
            return Err(format!(
                "[{i}] = {s}: must be 1 to {} for a split cell, 0 for a leaf",
                (1 << dims) - 1
            ));
        }
    }
    Ok(())
}

impl Patch {
    /// A patch of an elastic table from its stored values: [`Patch::with_restitution`]
    /// without an `e_n` axis.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        kind: PatchKind,
        gamma_lo: f64,
        gamma_hi: f64,
        blocks_gamma: usize,
        blocks_coord: usize,
        leaf_intervals: usize,
        tree: Vec<i32>,
        p: Vec<f64>,
        error_estimate: Vec<f64>,
        warp: Option<Warp>,
    ) -> Result<Patch, String> {
        Patch::with_restitution(
            kind,
            gamma_lo,
            gamma_hi,
            blocks_gamma,
            blocks_coord,
            leaf_intervals,
            tree,
            p,
            error_estimate,
            warp,
            None,
        )
    }

    /// A patch from its stored values, checked: finite increasing γ edges `> 0`, at least one
    /// root cell per axis, `m ≥ 1`, a valid tree ([`check_tree_of`]: a quadtree, or an octree
    /// with an `e_n` axis), `(m + 1)^dims` finite node values of `P` (each `|P| ≤ 1 + 1e-6`)
    /// and of the error estimate per leaf, and a valid warp ([`Patch::check_warp`]; a patch
    /// with an `e_n` axis has none). `Err` names the value and the rule.
    #[allow(clippy::too_many_arguments)]
    pub fn with_restitution(
        kind: PatchKind,
        gamma_lo: f64,
        gamma_hi: f64,
        blocks_gamma: usize,
        blocks_coord: usize,
        leaf_intervals: usize,
        tree: Vec<i32>,
        p: Vec<f64>,
        error_estimate: Vec<f64>,
        warp: Option<Warp>,
        restitution: Option<RestitutionAxis>,
    ) -> Result<Patch, String> {
        Patch::with_split(
            kind,
            gamma_lo,
            gamma_hi,
            blocks_gamma,
            blocks_coord,
            leaf_intervals,
            tree,
            p,
            error_estimate,
            warp,
            restitution,
            None,
        )
    }

    /// [`Patch::with_restitution`] with the axes each split cell halves (`split`, checked by
    /// [`check_split`]; only with an `e_n` axis), or `None` when every split halves every axis.
    #[allow(clippy::too_many_arguments)]
    pub fn with_split(
        kind: PatchKind,
        gamma_lo: f64,
        gamma_hi: f64,
        blocks_gamma: usize,
        blocks_coord: usize,
        leaf_intervals: usize,
        tree: Vec<i32>,
        p: Vec<f64>,
        error_estimate: Vec<f64>,
        warp: Option<Warp>,
        restitution: Option<RestitutionAxis>,
        split: Option<Vec<u8>>,
    ) -> Result<Patch, String> {
        if !(gamma_lo.is_finite() && gamma_hi.is_finite() && gamma_lo > 0.0 && gamma_hi >= gamma_lo)
        {
            return Err(format!(
                "gamma edges [{gamma_lo}, {gamma_hi}] must be finite, > 0, increasing (or \
                 equal, for the patch of one pair)"
            ));
        }
        let pair = gamma_hi == gamma_lo;
        if pair && (restitution.is_none() || blocks_gamma != 1) {
            return Err(format!(
                "gamma edges [{gamma_lo}, {gamma_hi}] are equal: only the patch of one pair (an \
                 e_n axis, blocks_gamma = 1) holds a single gamma; blocks_gamma = {blocks_gamma}, \
                 e_n axis: {}",
                if restitution.is_some() { "yes" } else { "no" }
            ));
        }
        if blocks_gamma == 0 || blocks_coord == 0 || leaf_intervals == 0 {
            return Err(format!(
                "blocks_gamma = {blocks_gamma}, blocks_coord = {blocks_coord}, \
                 leaf_intervals = {leaf_intervals}: each must be >= 1"
            ));
        }
        if restitution.is_some() && warp.is_some() {
            return Err("a patch with an e_n axis cannot have a warp".into());
        }
        let dims = tree_dims(restitution.is_some(), pair);
        let roots = blocks_gamma * blocks_coord * restitution.map_or(1, |r| r.blocks);
        let leaves = match &split {
            None => check_tree_of(&tree, roots, 1 << dims),
            Some(split) => {
                check_split(&tree, split, dims, restitution.is_some())
                    .map_err(|m| format!("dataset 'split' {m}"))?;
                check_tree_split(&tree, roots, &|i| 1 << split[i].count_ones())
            }
        }
        .map_err(|m| format!("dataset 'tree' {m}"))?;
        let size = leaves * (leaf_intervals + 1).pow(dims);
        for (name, v) in [("P", &p), ("error_estimate", &error_estimate)] {
            if v.len() != size {
                let n1 = leaf_intervals + 1;
                let grid = vec![n1.to_string(); dims as usize].join(" x ");
                return Err(format!(
                    "dataset '{name}' has {} values: expected {size} ({leaves} leaves of \
                     {grid} nodes)",
                    v.len(),
                ));
            }
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(format!("dataset '{name}'[{i}] = {}: must be finite", v[i]));
            }
        }
        if let Some(i) = p.iter().position(|x| x.abs() > 1.0 + 1e-6) {
            return Err(format!("|P| = {} > 1 at node {i}", p[i]));
        }
        let patch = Patch {
            kind,
            gamma_lo,
            gamma_hi,
            blocks_gamma,
            blocks_coord,
            leaf_intervals,
            tree,
            p,
            error_estimate,
            warp,
            restitution,
            split,
        };
        patch.check_warp()?;
        Ok(patch)
    }

    /// The same patch with other node values and error estimates, checked as by
    /// [`Patch::with_restitution`].
    fn remade(
        &self,
        p: Vec<f64>,
        error_estimate: Vec<f64>,
        warp: Option<Warp>,
    ) -> Result<Patch, String> {
        Patch::with_split(
            self.kind,
            self.gamma_lo,
            self.gamma_hi,
            self.blocks_gamma,
            self.blocks_coord,
            self.leaf_intervals,
            self.tree.clone(),
            p,
            error_estimate,
            warp,
            self.restitution,
            self.split.clone(),
        )
    }

    /// The same patch with other node values of `P` (`f(i, P_i)` at node `i`), checked as by
    /// [`Patch::new`].
    pub fn map_values(&self, f: impl FnMut(usize, f64) -> f64) -> Result<Patch, String> {
        let mut f = f;
        let p = self.p.iter().enumerate().map(|(i, &v)| f(i, v)).collect();
        self.remade(p, self.error_estimate.clone(), self.warp.clone())
    }

    /// The same patch with other error estimates (`f(i, e_i)` at node `i`), checked as by
    /// [`Patch::new`].
    pub fn map_error_estimate(
        &self,
        mut f: impl FnMut(usize, f64) -> f64,
    ) -> Result<Patch, String> {
        let error_estimate = self
            .error_estimate
            .iter()
            .enumerate()
            .map(|(i, &v)| f(i, v))
            .collect();
        self.remade(self.p.clone(), error_estimate, self.warp.clone())
    }

    /// The same patch with another warp (or none), checked as by [`Patch::new`].
    pub fn with_warp(&self, warp: Option<Warp>) -> Result<Patch, String> {
        self.remade(self.p.clone(), self.error_estimate.clone(), warp)
    }

    /// The `e_n` axis, if the patch has one.
    pub fn restitution(&self) -> Option<&RestitutionAxis> {
        self.restitution.as_ref()
    }

    /// Number of axes of the tree: 2 (`γ`, `c`), 3 with an `e_n` axis (`γ`, `c`, `e_n`), or 2
    /// in the patch of one pair (`c`, `e_n`; [`Patch::is_pair`]).
    pub fn dims(&self) -> u32 {
        tree_dims(self.restitution.is_some(), self.is_pair())
    }

    /// Whether this is the patch of one pair of materials: a single `γ` (`gamma_lo =
    /// gamma_hi`, one root cell along γ) with an `e_n` axis, its tree over `(c, e_n)` only. Its
    /// masks, children and nodes are those of a patch over `(γ, c, e_n)` whose cells never
    /// halve `γ` and whose leaves have one node along it.
    #[inline(always)]
    pub fn is_pair(&self) -> bool {
        self.gamma_lo == self.gamma_hi
    }

    /// The partial-slip coordinate's map: [`PartialMap::SqrtBoth`] with an `e_n` axis,
    /// [`PartialMap::SqrtEnd`] without.
    pub fn partial_map(&self) -> PartialMap {
        PartialMap::of_table(self.restitution.is_some())
    }

    /// Children of a split cell that halves every axis: `2^dims`.
    pub fn fanout(&self) -> usize {
        1 << self.dims()
    }

    /// The axes split cell `cell` halves: bit `dims − 1 − k` for axis `k` (every axis,
    /// `2^dims − 1`, without a `split` dataset).
    #[inline(always)]
    pub fn split_mask(&self, cell: usize) -> u8 {
        match &self.split {
            None => ((1u32 << self.dims()) - 1) as u8,
            Some(s) => s[cell],
        }
    }

    /// The masks of a tree whose cells halve different axes ([`check_split`]), if it is one.
    pub fn split(&self) -> Option<&[u8]> {
        self.split.as_deref()
    }

    /// Children of split cell `cell`: `2^k` for the `k` axes it halves.
    #[inline]
    pub fn fanout_of(&self, cell: usize) -> usize {
        1 << self.split_mask(cell).count_ones()
    }

    /// Root cells along `e_n` (1 without an `e_n` axis).
    pub fn blocks_e_n(&self) -> usize {
        self.restitution.map_or(1, |r| r.blocks)
    }

    /// Root cells of the tree.
    pub fn roots(&self) -> usize {
        self.blocks_gamma * self.blocks_coord * self.blocks_e_n()
    }

    /// Nodes per leaf, `(m + 1)^dims`.
    pub fn leaf_size(&self) -> usize {
        (self.leaf_intervals + 1).pow(self.dims())
    }

    /// Region and coordinate.
    pub fn kind(&self) -> PatchKind {
        self.kind
    }

    /// Lower γ edge.
    pub fn gamma_lo(&self) -> f64 {
        self.gamma_lo
    }

    /// Upper γ edge.
    pub fn gamma_hi(&self) -> f64 {
        self.gamma_hi
    }

    /// Root cells along γ.
    pub fn blocks_gamma(&self) -> usize {
        self.blocks_gamma
    }

    /// Root cells along `c`.
    pub fn blocks_coord(&self) -> usize {
        self.blocks_coord
    }

    /// Intervals per axis of every leaf's grid (`m`).
    pub fn leaf_intervals(&self) -> usize {
        self.leaf_intervals
    }

    /// The quadtree (see the type's documentation).
    pub fn tree(&self) -> &[i32] {
        &self.tree
    }

    /// `P` at the nodes, leaf by leaf, `[leaves, m + 1, m + 1]` row-major.
    pub fn p(&self) -> &[f64] {
        &self.p
    }

    /// Solver error estimate of each node, same layout as [`Patch::p`].
    pub fn error_estimate(&self) -> &[f64] {
        &self.error_estimate
    }

    /// The warp of the coordinate, if any.
    pub fn warp(&self) -> Option<&Warp> {
        self.warp.as_ref()
    }

    /// Number of leaves.
    pub fn leaves(&self) -> usize {
        self.p.len() / self.leaf_size()
    }

    /// The fine index of this patch ([`FineIndex`]) with at most `max_entries` entries, or
    /// `None` for a grid too small for the cubic stencil (`m < 3`), a tree deeper than 30, or
    /// a patch with an `e_n` axis (see [`Patch::fine_index3`]).
    pub fn fine_index(&self, max_entries: usize) -> Option<FineIndex> {
        if self.restitution.is_some() {
            return None;
        }
        self.fine_index_any(max_entries)
    }

    /// The fine index of a patch with an `e_n` axis: [`FineIndex`] over `(γ, c, e_n)`
    /// (`layers` entries along `e_n`), or `None` as [`Patch::fine_index`] (and for a patch
    /// without the axis).
    pub fn fine_index3(&self, max_entries: usize) -> Option<FineIndex> {
        self.restitution?;
        self.fine_index_any(max_entries)
    }

    /// [`Patch::fine_index`] over the patch's axes.
    pub(crate) fn fine_index_any(&self, max_entries: usize) -> Option<FineIndex> {
        // The patch of one pair is answered by the descent (its axes are `c`, `e_n`, which the
        // indexed paths of `(γ, c)` and `(γ, c, e_n)` do not take).
        if self.is_pair() {
            return None;
        }
        let dims = self.dims() as usize;
        let blocks = self.blocks_of::<MAX_AXES>();
        let (roots, n) = (self.roots(), self.tree.len());
        if self.leaf_intervals < 3 || roots == 0 || n < roots || n > u32::MAX as usize {
            return None;
        }
        // Depths and integer origin of every cell (children come after their parents).
        let mut depth = vec![[0u32; MAX_AXES]; n];
        let mut origin = vec![[0usize; MAX_AXES]; n];
        for (r, o) in origin.iter_mut().take(roots).enumerate() {
            let mut rest = r;
            for k in (0..dims).rev() {
                (o[k], rest) = (rest % blocks[k], rest / blocks[k]);
            }
        }
        let mut cells = Vec::with_capacity(n);
        let mut max_depth = [0u32; MAX_AXES];
        for i in 0..n {
            let t = self.tree[i];
            let mask = if t >= 0 { self.split_mask(i) } else { 0 };
            cells.push(CellOrigin {
                scale: depth[i].map(|d| f64::from(1u32 << d.min(31))),
                origin: origin[i].map(|a| a as f64),
                mask,
            });
            for k in 0..dims {
                max_depth[k] = max_depth[k].max(depth[i][k]);
            }
            if t >= 0 {
                let (first, fanout) = (t as usize, self.fanout_of(i));
                if first <= i || first + fanout > n || depth[i].iter().any(|&d| d >= 30) {
                    return None;
                }
                let halved: Vec<usize> = (0..dims)
                    .filter(|&k| mask >> (dims - 1 - k) & 1 == 1)
                    .collect();
                for q in 0..fanout {
                    // Child `q`, row-major over the halved axes: `2·q_γ + q_c`,
                    // `4·q_γ + 2·q_c + q_e` when every axis is halved.
                    let (mut o, mut d) = (origin[i], depth[i]);
                    for (j, &k) in halved.iter().enumerate() {
                        o[k] = 2 * o[k] + ((q >> (halved.len() - 1 - j)) & 1);
                        d[k] += 1;
                    }
                    depth[first + q] = d;
                    origin[first + q] = o;
                }
            }
        }
        // The deepest index within the budget: every axis together without a `split`
        // dataset; with one, the deepest axis first.
        let mut d = max_depth;
        let entries = |d: &[u32; MAX_AXES]| (0..dims).fold(roots as u128, |e, k| e << d[k]);
        while entries(&d) > max_entries as u128 && d.iter().any(|&x| x > 0) {
            if self.split.is_none() {
                for x in d.iter_mut().take(dims) {
                    *x -= 1;
                }
            } else {
                let k = (0..dims).max_by_key(|&k| (d[k], dims - k)).unwrap_or(0);
                d[k] -= 1;
            }
        }
        let shape: [usize; MAX_AXES] =
            std::array::from_fn(|k| if k < dims { blocks[k] << d[k] } else { 1 });
        let mut index = vec![u32::MAX; shape.iter().product()];
        let last = dims - 1;
        for i in 0..n {
            // Cells no deeper than the index along every axis cover their part of it (a box of
            // k_a entries along axis a); deeper cells are reached by the descent. Parents come
            // first, so a later (deeper) cell overwrites its ancestor's entries.
            if (0..dims).any(|k| depth[i][k] > d[k]) {
                continue;
            }
            let k: [usize; MAX_AXES] = std::array::from_fn(|a| {
                if a < dims {
                    1usize << (d[a] - depth[i][a])
                } else {
                    1
                }
            });
            let inner: usize = k[..last].iter().product();
            for t in 0..inner {
                let (mut at, mut rest) = (0, t);
                let mut along = [0usize; MAX_AXES];
                for a in (0..last).rev() {
                    (along[a], rest) = (origin[i][a] * k[a] + rest % k[a], rest / k[a]);
                }
                for a in 0..last {
                    at = at * shape[a] + along[a];
                }
                at = at * shape[last] + origin[i][last] * k[last];
                index[at..at + k[last]].fill(i as u32);
            }
        }
        if index.iter().any(|&e| e as usize >= n) {
            return None;
        }
        Some(FineIndex {
            depth: d,
            shape,
            index,
            cells,
        })
    }

    /// Depth of every leaf (roots have depth 0), in leaf order.
    pub fn leaf_depths(&self) -> Vec<u32> {
        let mut depth = vec![0u32; self.leaves()];
        let mut stack: Vec<(usize, u32)> = (0..self.roots()).map(|i| (i, 0)).collect();
        while let Some((cell, d)) = stack.pop() {
            let t = self.tree[cell];
            if t < 0 {
                depth[(-(t as i64) - 1) as usize] = d;
            } else {
                stack.extend((0..self.fanout_of(cell)).map(|q| (t as usize + q, d + 1)));
            }
        }
        depth
    }

    /// The leaf containing `(γ, c)` and the position inside it, both components in `[0, 1]`
    /// (a patch without an `e_n` axis): [`Patch::find_leaf_at`].
    #[inline]
    pub fn find_leaf(&self, gamma: f64, c: f64) -> (usize, f64, f64) {
        let (leaf, [fg, fc]) = self.find_leaf_at([self.x_gamma(gamma), c]);
        (leaf, fg, fc)
    }

    /// `x = (γ − gamma_lo)/(gamma_hi − gamma_lo)`, the patch's coordinate along γ.
    #[inline(always)]
    pub fn x_gamma(&self, gamma: f64) -> f64 {
        (gamma - self.gamma_lo) / (self.gamma_hi - self.gamma_lo)
    }

    /// Root cells along each of the first `D` axes (`γ`, `c`, `e_n`; 1 beyond the patch's).
    #[inline(always)]
    fn blocks_of<const D: usize>(&self) -> [usize; D] {
        std::array::from_fn(|k| self.axis(k).2)
    }

    /// Axis `k` of the patch's tree (0 `γ`, 1 `c`, 2 `e_n`): `(lo, width, blocks)`, its
    /// coordinate `x = (value − lo)/width` (`c` is its own coordinate: `(0, 1)`) and its root
    /// cells; `(0, 1, 1)` beyond the patch's axes.
    pub fn axis(&self, k: usize) -> (f64, f64, usize) {
        if let (true, Some(r)) = (self.is_pair(), &self.restitution) {
            // The patch of one pair: `(c, e_n)`.
            return match k {
                0 => (0.0, 1.0, self.blocks_coord),
                1 => (r.lo, r.hi - r.lo, r.blocks),
                _ => (0.0, 1.0, 1),
            };
        }
        match (k, &self.restitution) {
            (0, _) => (
                self.gamma_lo,
                self.gamma_hi - self.gamma_lo,
                self.blocks_gamma,
            ),
            (1, _) => (0.0, 1.0, self.blocks_coord),
            (2, Some(r)) => (r.lo, r.hi - r.lo, r.blocks),
            _ => (0.0, 1.0, 1),
        }
    }

    /// Steps 6 and 7 of the rule in a patch of `D` axes ([`Patch::dims`]): the leaf that
    /// contains the point at coordinates `x` (`x_γ`, `c`, `x_e`, each in `[0, 1]`) and the
    /// position inside it, each component in `[0, 1]`. The root cell per axis
    /// ([`locate`]), numbered row-major, then the descent ([`descend`]).
    #[inline]
    pub fn find_leaf_at<const D: usize>(&self, x: [f64; D]) -> (usize, [f64; D]) {
        let blocks = self.blocks_of::<D>();
        let mut f = [0.0; D];
        let mut cell = 0;
        for ((fk, &xk), &bk) in f.iter_mut().zip(&x).zip(&blocks) {
            let (a, frac) = locate(xk, bk);
            cell = cell * bk + a;
            *fk = frac;
        }
        loop {
            let t = self.tree[cell];
            if t < 0 {
                return ((-(t as i64) - 1) as usize, f);
            }
            cell = t as usize
                + match &self.split {
                    None => descend(&mut f),
                    Some(s) => descend_masked(&mut f, s[cell]),
                };
        }
    }

    /// Depth along `c` (the number of halvings of `c`) of the deepest leaf crossed by the line
    /// `γ = gamma` (at `e_n` for a patch with an `e_n` axis, ignored without), following the
    /// rule's descent along every axis but `c` (which does not depend on `c`) and both halves
    /// along `c`.
    pub fn line_depth(&self, gamma: f64, e_n: f64) -> u32 {
        let xg = self.x_gamma(gamma);
        match &self.restitution {
            None => self.line_depth_at([xg, 0.0], 1),
            Some(r) if self.is_pair() => self.line_depth_at([0.0, r.x(e_n)], 0),
            Some(r) => self.line_depth_at([xg, 0.0, r.x(e_n)], 1),
        }
    }

    /// [`Patch::line_depth`] at coordinates `x` of `D` axes (`x[ca]`, along `c`, unused; `ca`
    /// the axis of `c`).
    fn line_depth_at<const D: usize>(&self, x: [f64; D], ca: usize) -> u32 {
        self.line_leaves(x, ca)
            .iter()
            .map(|&(_, _, d, _)| d)
            .max()
            .unwrap_or(0)
    }

    /// The leaves crossed by the line through the coordinates `x` of `D` axes along `c` (axis
    /// `ca`; `x[ca]` unused), by the rule's descent along every other axis and both halves
    /// along `c`: per leaf its number, the positions inside it along the other axes (those of
    /// the rule; `f[ca]` is 0), its depth `d` along `c` and its integer origin along `c` in
    /// units of its size (`[origin, origin + 1)·2^−d` root cells).
    pub(crate) fn line_leaves<const D: usize>(
        &self,
        x: [f64; D],
        ca: usize,
    ) -> Vec<(usize, [f64; D], u32, u64)> {
        let blocks = self.blocks_of::<D>();
        let (mut root, mut f) = ([0usize; D], [0.0; D]);
        for k in (0..D).filter(|&k| k != ca) {
            (root[k], f[k]) = locate(x[k], blocks[k]);
        }
        let mut stack = Vec::new();
        for b in 0..blocks[ca] {
            root[ca] = b;
            let cell = root
                .iter()
                .zip(&blocks)
                .fold(0, |cell, (&a, &bk)| cell * bk + a);
            stack.push((cell, f, 0, b as u64));
        }
        let c_bit = 1u8 << (D - 1 - ca);
        let mut leaves = Vec::new();
        while let Some((cell, f, d, origin)) = stack.pop() {
            let t = self.tree[cell];
            if t < 0 {
                leaves.push(((-(t as i64) - 1) as usize, f, d, origin));
                continue;
            }
            // f[ca] = 0 stays 0: the lower half along c; the upper one next to it, which is
            // `2^(number of halved axes after c)` further on. A cell that does not halve `c`
            // has one child on the line and adds no depth along `c`.
            let (mut f, mask) = (f, self.split_mask(cell));
            let child = t as usize + descend_masked(&mut f, mask);
            if mask & c_bit == 0 {
                stack.push((child, f, d, origin));
            } else {
                let upper_c = 1usize << (mask & (c_bit - 1)).count_ones();
                stack.push((child, f, d + 1, 2 * origin));
                stack.push((child + upper_c, f, d + 1, 2 * origin + 1));
            }
        }
        leaves
    }

    /// Check the patch's warp, if any: [`Warp::validate`], and no leaf straddles its `start`
    /// (every leaf lies wholly before or wholly at/after it). `Err` names the attribute and
    /// the allowed range, or the leaf.
    pub fn check_warp(&self) -> Result<(), String> {
        let Some(w) = &self.warp else {
            return Ok(());
        };
        w.validate(self.gamma_lo, self.gamma_hi, self.blocks_gamma)?;
        for (leaf, (lo, hi)) in self.leaf_gamma_spans().into_iter().enumerate() {
            if lo < w.start && w.start < hi {
                return Err(format!(
                    "leaf {leaf} spans root rows [{lo}, {hi}] across attribute 'start' = {}: \
                     no leaf may straddle it",
                    w.start
                ));
            }
        }
        Ok(())
    }

    /// Each leaf's extent along γ in root-cell units, `[a/2^d, (a+1)/2^d]` for a leaf at depth
    /// `d` with integer position `a` (exact dyadic values), leaf by leaf.
    pub fn leaf_gamma_spans(&self) -> Vec<(f64, f64)> {
        let mut spans = vec![(0.0, 0.0); self.leaves()];
        let per_row = self.blocks_coord * self.blocks_e_n();
        let mut stack: Vec<(usize, u32, u64)> = (0..self.roots())
            .map(|i| (i, 0, (i / per_row) as u64))
            .collect();
        let fanout = self.fanout();
        while let Some((cell, d, a)) = stack.pop() {
            let t = self.tree[cell];
            if t < 0 {
                let scale = f64::from(d.min(1000) as i32).exp2();
                spans[(-(t as i64) - 1) as usize] = (a as f64 / scale, (a + 1) as f64 / scale);
            } else {
                // The child's upper half along γ: `q_γ`, the first bit of `q`.
                stack.extend(
                    (0..fanout).map(|q| (t as usize + q, d + 1, 2 * a + (q / (fanout / 2)) as u64)),
                );
            }
        }
        spans
    }

    /// The patch's warp if it applies at `γ`: the patch has one and `v = x·blocks_gamma`
    /// (clamped, as [`locate`] computes it) is at or beyond its `start`.
    #[inline]
    pub fn warp_at(&self, gamma: f64) -> Option<&Warp> {
        let w = self.warp.as_ref()?;
        let xg = self.x_gamma(gamma);
        let bg = self.blocks_gamma as f64;
        ((xg * bg).clamp(0.0, bg) >= w.start).then_some(w)
    }

    /// Step 5 of the rule: the coordinate the quadtree is over at `(γ, c)` — `c` itself, or
    /// [`Warp::apply`]`(γ, c)` where [`Patch::warp_at`] gives the warp.
    #[inline]
    pub fn warped(&self, gamma: f64, c: f64) -> f64 {
        match self.warp_at(gamma) {
            Some(w) => w.apply(gamma, c),
            None => c,
        }
    }

    /// `P` at `(γ, c)` by steps 6 to 10 of the rule: [`Patch::tensor`] limited to `[−1, 1]`
    /// ([`bound_p`]).
    #[inline]
    pub fn interpolate(&self, gamma: f64, c: f64, k: usize) -> f64 {
        bound_p(self.tensor(gamma, c, k))
    }

    /// The tensor product of steps 6 to 9 at `(γ, c)` with a `k`-point stencil per axis, before
    /// the bound of step 10 (a polynomial inside each interval of the leaf's grid).
    #[inline]
    pub fn tensor(&self, gamma: f64, c: f64, k: usize) -> f64 {
        self.tensor_at([self.x_gamma(gamma), c], k)
    }

    /// Steps 6 to 9 in a patch of `D` axes at coordinates `x` (`x_γ`, `c`, `x_e`): the leaf
    /// ([`Patch::find_leaf_at`]) and its tensor product with a `k`-point stencil per axis
    /// ([`cubic_tensor`] for `k = 4`, else [`lagrange_tensor`]), before the bound of step 10.
    #[inline]
    pub fn tensor_at<const D: usize>(&self, x: [f64; D], k: usize) -> f64 {
        let (leaf, f) = self.find_leaf_at(x);
        let n1 = self.leaf_intervals + 1;
        let size = self.leaf_size();
        let vals = &self.p[leaf * size..(leaf + 1) * size];
        if k == 4 && n1 >= 4 {
            cubic_tensor(vals, n1, f)
        } else {
            lagrange_tensor(vals, n1, f, k)
        }
    }

    /// The tensor product of the rule at `(γ, c, e_n)` over every axis of the patch (`e_n`
    /// ignored without an `e_n` axis) with a `k`-point stencil per axis, before the bound of
    /// step 10.
    #[inline]
    pub fn tensor_point(&self, gamma: f64, c: f64, e_n: f64, k: usize) -> f64 {
        let xg = self.x_gamma(gamma);
        match &self.restitution {
            None => self.tensor_at([xg, c], k),
            Some(r) if self.is_pair() => self.tensor_at([c, r.x(e_n)], k),
            Some(r) => self.tensor_at([xg, c, r.x(e_n)], k),
        }
    }

    /// `P` at `(γ, c, e_n)` (`e_n` ignored without an `e_n` axis): [`Patch::tensor_point`]
    /// limited to `[−1, 1]` ([`bound_p`]).
    #[inline]
    pub fn interpolate_at(&self, gamma: f64, c: f64, e_n: f64, k: usize) -> f64 {
        bound_p(self.tensor_point(gamma, c, e_n, k))
    }
}

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
            RestitutionAxis::new(lo, hi, 1)?;
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
        })
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
        )
    }

    /// The `e_n` range `[lo, hi]` of a table with a normal-restitution axis; `None` for an
    /// elastic table (it answers `e_n = 1` only).
    pub fn restitution(&self) -> Option<(f64, f64)> {
        self.restitution
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
                lo: self.gamma_min,
                hi: self.gamma_max,
            });
        }
        axes.extend([Axis {
            name: AxisName::Alpha,
            lo: 0.0,
            hi: self.alpha_max,
        }]);
        if let Some((lo, hi)) = self.restitution {
            axes.push(Axis {
                name: AxisName::RestitutionN,
                lo,
                hi,
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
        check_query(gamma, alpha)?;
        self.check_e_n(e_n)?;
        let region = Region::of_e(gamma, alpha, e_n);
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        self.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n)
        })
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
                match Region::of_e(g, a, e_n) {
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
    /// `α ≤ alpha_max`, `e_n` one the table answers). The patch coordinate is computed with
    /// fewer divisions than [`PatchKind::coord_at`] (same value up to rounding).
    #[inline]
    pub fn eval_in(&self, region: Region, gamma: f64, alpha: f64, e_n: f64) -> f64 {
        match self.patch(region) {
            Some(patch) if patch.restitution.is_none() => {
                let c = match patch.kind {
                    PatchKind::PartialSlip => partial_coord(gamma, alpha),
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                let c = patch.warped(gamma, c.clamp(0.0, 1.0));
                patch.interpolate(gamma, c, self.stencil)
            }
            Some(patch) => {
                let c = match patch.kind {
                    PatchKind::PartialSlip => partial_coord_e(gamma, alpha, e_n),
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                patch.interpolate_at(gamma, c.clamp(0.0, 1.0), e_n, self.stencil)
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

/// A point of a table's domain: `(γ, α, e_n)`, dimensionless (`physics.md`); `e_n = 1` is
/// an elastic impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// `γ = √((7/2) G*/E*)`.
    pub gamma: f64,
    /// `α = μ v_z0/|u0|` (`∞`: no slip).
    pub alpha: f64,
    /// Normal restitution `e_n`.
    pub e_n: f64,
}

impl Point {
    /// `(γ, α, e_n)`.
    pub fn new(gamma: f64, alpha: f64, e_n: f64) -> Point {
        Point { gamma, alpha, e_n }
    }

    /// `(γ, α)` of an elastic impact (`e_n = 1`).
    pub fn elastic(gamma: f64, alpha: f64) -> Point {
        Point::new(gamma, alpha, 1.0)
    }
}

/// The name of an axis of a table (schema 4 lists them in this order).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisName {
    /// `γ = √((7/2) G*/E*)`.
    Gamma,
    /// `α = μ v_z0/|u0|`.
    Alpha,
    /// Normal restitution `e_n`.
    RestitutionN,
}

impl AxisName {
    /// The name stored in the file and used in messages.
    pub fn name(self) -> &'static str {
        match self {
            AxisName::Gamma => "gamma",
            AxisName::Alpha => "alpha",
            AxisName::RestitutionN => "e_n",
        }
    }
}

/// One axis of a table: its name and range (`hi = ∞` for `α` with no slip included).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    /// Which quantity.
    pub name: AxisName,
    /// Lowest value.
    pub lo: f64,
    /// Highest value.
    pub hi: f64,
}

/// [`PatchKind::coord_at`] of the partial-slip patch of a table with an `e_n` axis
/// ([`PartialMap::SqrtBoth`]) at normal restitution `e_n`: [`partial_coord_from`] with
/// [`partial_ratio_e`].
#[inline(always)]
pub fn partial_coord_e(gamma: f64, alpha: f64, e_n: f64) -> f64 {
    let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
    partial_coord_from(PartialMap::SqrtBoth, alpha, ratio, two_g2, ratio.ln())
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
/// statement of these operations (the rule, the query paths, the curves).
#[inline(always)]
pub fn partial_coord_from(
    map: PartialMap,
    alpha: f64,
    ratio: f64,
    two_g2: f64,
    ln_ratio: f64,
) -> f64 {
    map.c_of_l(partial_arg(alpha, ratio, two_g2).ln() / ln_ratio)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn warp() -> Warp {
        Warp {
            start: 1.0,
            gamma_0: 2.9,
            gamma_step: 0.05,
            c_star: 0.5,
            knot: (0..13)
                .map(|i| 0.35 + 0.2 * (i as f64 * 0.4).sin() * (i as f64 / 12.0))
                .collect(),
        }
    }

    #[test]
    fn the_knot_rule_reproduces_the_knot_values_at_the_grid_points() {
        let w = warp();
        for (i, &k) in w.knot.iter().enumerate() {
            let g = w.gamma_0 + i as f64 * w.gamma_step;
            assert!((w.knot_at(g) - k).abs() <= 1e-14, "knot {i}");
        }
        // Clamped outside the grid.
        assert_eq!(w.knot_at(1.0), w.knot[0]);
        assert_eq!(w.knot_at(100.0), w.knot[w.knot.len() - 1]);
        // Between grid points: a cubic reproduces a cubic exactly.
        let cubic =
            |g: f64| 0.3 + 0.1 * (g - 3.0) - 0.2 * (g - 3.0).powi(2) + 0.3 * (g - 3.0).powi(3);
        let wc = Warp {
            knot: (0..13).map(|i| cubic(2.9 + 0.05 * i as f64)).collect(),
            ..warp()
        };
        for j in 0..=96 {
            let g = 2.9 + 0.6 * j as f64 / 96.0;
            assert!((wc.knot_at(g) - cubic(g)).abs() <= 1e-13, "gamma {g}");
        }
    }

    #[test]
    fn apply_sends_the_knot_to_c_star_and_invert_undoes_it() {
        let w = warp();
        for j in 0..=200 {
            let g = 2.5 + 1.0 * j as f64 / 200.0;
            let k = w.knot_at(g);
            assert_eq!(w.apply(g, k), w.c_star, "gamma {g}");
            assert_eq!(w.apply(g, 0.0), 0.0);
            assert!((w.apply(g, 1.0) - 1.0).abs() <= 1e-15);
            assert_eq!(w.apply(g, 0.3).to_bits(), w.apply_with(k, 0.3).to_bits());
            let mut prev = -1.0;
            for i in 0..=100 {
                let c = i as f64 / 100.0;
                let cp = w.apply(g, c);
                assert!(cp > prev && (0.0..=1.0).contains(&cp), "monotone in [0, 1]");
                prev = cp;
                assert!(
                    (w.invert(g, cp) - c).abs() <= 1e-15,
                    "invert(apply) at {g}, {c}"
                );
                // The square root of the grading amplifies rounding next to the knot
                // (c' − c* ∝ √(K − c)): 1e-16/(2·0.02) at the nearest grid point.
                assert!(
                    (w.apply(g, w.invert(g, c)) - c).abs() <= 1e-13,
                    "apply(invert) at {g}, {c}"
                );
            }
        }
    }

    #[test]
    fn the_grading_makes_the_fold_singularity_a_cubic() {
        // Below the fold P ≈ smooth + C(α_F − α)^{3/2}; in c' the power is (1 − c'/c*)³ times
        // K^{3/2}, a polynomial: a cubic through four points of it reproduces it.
        let w = warp();
        let g = 3.13;
        let k = w.knot_at(g);
        let f = |c_prime: f64| (k - w.invert(g, c_prime)).max(0.0).powf(1.5);
        let nodes = [0.1, 0.2, 0.3, 0.4];
        let vals = nodes.map(f);
        for i in 0..=50 {
            let x = 0.1 + 0.3 * i as f64 / 50.0;
            let lagrange: f64 = (0..4)
                .map(|j| {
                    let mut l = vals[j];
                    for m in (0..4).filter(|&m| m != j) {
                        l *= (x - nodes[m]) / (nodes[j] - nodes[m]);
                    }
                    l
                })
                .sum();
            assert!((lagrange - f(x)).abs() <= 1e-14, "c' = {x}");
        }
        // Linear in c the same power is not: the cubic through four c-points misses it.
        let fc = |c: f64| (k - c).max(0.0).powf(1.5);
        let cn = nodes.map(|x| k * x / w.c_star);
        let mid = 0.5 * (cn[2] + cn[3]);
        let lag: f64 = (0..4)
            .map(|j| {
                let mut l = fc(cn[j]);
                for m in (0..4).filter(|&m| m != j) {
                    l *= (mid - cn[m]) / (cn[j] - cn[m]);
                }
                l
            })
            .sum();
        assert!((lag - fc(mid)).abs() > 1e-6, "{}", (lag - fc(mid)).abs());
    }

    #[test]
    fn the_warp_applies_from_its_start_row_on() {
        let patch = Patch {
            kind: PatchKind::PartialSlip,
            gamma_lo: 1.0,
            gamma_hi: 3.5,
            blocks_gamma: 5,
            blocks_coord: 4,
            leaf_intervals: 8,
            tree: (0..20).map(|i| -(i + 1)).collect(),
            p: vec![0.0; 20 * 81],
            error_estimate: vec![0.0; 20 * 81],
            warp: Some(Warp {
                start: 3.8125,
                gamma_0: 2.90625,
                gamma_step: 0.01,
                c_star: 0.5,
                knot: vec![0.6; 61],
            }),
            restitution: None,
            split: None,
        };
        // γ(start) = 2.90625: unwarped below, warped from it on.
        let w = patch.warp.as_ref().expect("warp");
        assert_eq!(patch.warped(2.9, 0.3).to_bits(), 0.3f64.to_bits());
        assert_eq!(patch.warped(2.90625, 0.3), w.apply(2.90625, 0.3));
        assert_eq!(patch.warped(3.2, 0.3), w.apply(3.2, 0.3));
        assert_ne!(patch.warped(3.2, 0.3), 0.3);
        // Leaves at depth 0 straddle a start inside a root row: refused, naming 'start'.
        let e = patch.check_warp().expect_err("root leaves straddle 3.8125");
        assert!(e.contains("'start' = 3.8125"), "{e}");
        // At a root boundary it is valid.
        let mut ok = patch.clone();
        if let Some(w) = ok.warp.as_mut() {
            w.start = 4.0;
            w.gamma_0 = 3.0;
        }
        assert_eq!(ok.check_warp(), Ok(()));
        // A knot grid that starts after γ(start) is refused.
        let mut late = ok.clone();
        if let Some(w) = late.warp.as_mut() {
            w.gamma_0 = 3.05;
        }
        assert!(late
            .check_warp()
            .expect_err("late grid")
            .contains("gamma_0"));
    }
}
