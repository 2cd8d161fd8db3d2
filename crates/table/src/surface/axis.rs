//! The axes of a table and of its patches ([`AxisName`], [`Axis`]) and a point of the domain
//! ([`Point`]).

use crate::format::{ExtraAxis, E_N};

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
    /// An axis of [`crate::format::EXTRA_AXES`], by its name (`e_n`: [`AxisName::RESTITUTION_N`]).
    Extra(&'static str),
}

impl AxisName {
    /// Normal restitution `e_n`.
    pub const RESTITUTION_N: AxisName = AxisName::Extra(E_N.name);

    /// The name stored in the file and used in messages.
    pub fn name(self) -> &'static str {
        match self {
            AxisName::Gamma => "gamma",
            AxisName::Alpha => "alpha",
            AxisName::Extra(name) => name,
        }
    }

    /// The entry of [`crate::format::EXTRA_AXES`] of an extra axis (`None` for `γ` and `α`).
    pub fn extra(self) -> Option<&'static ExtraAxis> {
        match self {
            AxisName::Extra(name) => ExtraAxis::named(name),
            _ => None,
        }
    }
}

/// One axis of a table or of a patch's tree: which quantity, its range and its root cells.
///
/// A patch lists its axes in the order of its tree ([`crate::surface::Patch::axes`]): `γ` from
/// `gamma_lo` to `gamma_hi` (equal in the patch of one pair), the patch coordinate `c` of `α`
/// ([`AxisName::Alpha`] from 0 to 1: `c` is its own coordinate), and `e_n` (schema 4) when the
/// table has one. Each is cut into `blocks` equal root cells; its coordinate is
/// `x = (value − lo)/(hi − lo)` ([`Axis::x`]). With an `e_n` axis a patch is
/// `blocks_gamma × blocks_coord × blocks_e_n` root cells, numbered row-major (`γ` outer,
/// `e_n` inner), each the root of an octree: a split cell's children are the cells
/// `tree[i] + 4·q_γ + 2·q_c + q_e`, and every leaf stores `(m + 1)³` nodes,
/// `p[leaf·(m+1)³ + (i_γ·(m+1) + i_c)·(m+1) + i_e]`.
///
/// The axes of a table ([`crate::surface::Surface::axes`]) are its query's: `γ`, `α` from 0 to
/// `alpha_max` (`hi = ∞` with no slip included) and `e_n`, each with one block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    /// Which quantity.
    pub name: AxisName,
    /// Lowest value.
    pub lo: f64,
    /// Highest value.
    pub hi: f64,
    /// Root cells along the axis.
    pub blocks: usize,
}

impl Axis {
    /// The `γ` axis of a patch over `[lo, hi]` with `blocks` root cells (checked by
    /// [`crate::surface::Patch::new`]).
    pub fn gamma(lo: f64, hi: f64, blocks: usize) -> Axis {
        Axis {
            name: AxisName::Gamma,
            lo,
            hi,
            blocks,
        }
    }

    /// The patch coordinate `c ∈ [0, 1]` of `α`, with `blocks` root cells.
    pub fn coord(blocks: usize) -> Axis {
        Axis {
            name: AxisName::Alpha,
            lo: 0.0,
            hi: 1.0,
            blocks,
        }
    }

    /// The normal-restitution axis from its stored values ([`Axis::extra`] of [`E_N`]):
    /// `0 < lo < hi ≤ 1` and `1 ≤ blocks ≤ 2¹⁶`.
    pub fn restitution(lo: f64, hi: f64, blocks: usize) -> Result<Axis, String> {
        Axis::extra(&E_N, lo, hi, blocks)
    }

    /// The extra axis `spec` from its stored values: a range [`ExtraAxis::check_range`]
    /// allows and `1 ≤ blocks ≤ 2¹⁶`. `Err` names the attribute and the allowed range.
    pub fn extra(spec: &ExtraAxis, lo: f64, hi: f64, blocks: usize) -> Result<Axis, String> {
        spec.check_range(lo, hi)?;
        if !(1..=1 << 16).contains(&blocks) {
            return Err(format!(
                "{} = {blocks}: must be an integer in [1, 65536]",
                spec.attr_blocks
            ));
        }
        Ok(Axis {
            name: AxisName::Extra(spec.name),
            lo,
            hi,
            blocks,
        })
    }

    /// Lowest value.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// Highest value.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// Root cells along the axis.
    pub fn blocks(&self) -> usize {
        self.blocks
    }

    /// The coordinate `x = (value − lo)/(hi − lo)` of `value`.
    #[inline(always)]
    pub fn x(&self, value: f64) -> f64 {
        (value - self.lo) / (self.hi - self.lo)
    }

    /// The value at coordinate `x` (`hi` exactly at `x = 1`).
    pub fn at(&self, x: f64) -> f64 {
        if x >= 1.0 {
            self.hi
        } else {
            self.lo + (self.hi - self.lo) * x
        }
    }
}
