//! The axes of a table: the normal-restitution axis of a patch ([`RestitutionAxis`]), a point
//! of the domain ([`Point`]) and the named axes ([`AxisName`], [`Axis`]).

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
    pub(super) lo: f64,
    /// Highest `e_n`.
    pub(super) hi: f64,
    /// Root cells along `e_n`.
    pub(super) blocks: usize,
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
