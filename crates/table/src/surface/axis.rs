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
    /// How a value maps to the axis coordinate ([`AxisMap::Linear`] but for the `e_n` axis of
    /// a table that names another, [`AxisMap::QuarterRoot`]).
    pub map: AxisMap,
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
            map: AxisMap::Linear,
            lo,
            hi,
            blocks,
        }
    }

    /// The patch coordinate `c ∈ [0, 1]` of `α`, with `blocks` root cells.
    pub fn coord(blocks: usize) -> Axis {
        Axis {
            name: AxisName::Alpha,
            map: AxisMap::Linear,
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
            map: AxisMap::Linear,
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

    /// The same axis with the map `map` from its values to its coordinate.
    pub fn with_map(self, map: AxisMap) -> Axis {
        Axis { map, ..self }
    }

    /// The ends of the axis in mapped values, `(m(lo), m(hi) − m(lo))` ([`AxisMap::forward`]):
    /// the coordinate is `x = (m(value) − m(lo))/(m(hi) − m(lo))`. `(lo, hi − lo)` for a linear
    /// axis.
    #[inline(always)]
    pub fn mapped_span(&self) -> (f64, f64) {
        let lo = self.map.forward(self.lo);
        (lo, self.map.forward(self.hi) - lo)
    }

    /// The coordinate `x = (m(value) − m(lo))/(m(hi) − m(lo))` of `value`
    /// ([`AxisMap::forward`]; `(value − lo)/(hi − lo)` on a linear axis).
    #[inline(always)]
    pub fn x(&self, value: f64) -> f64 {
        match self.map {
            AxisMap::Linear => (value - self.lo) / (self.hi - self.lo),
            map => {
                let (lo, width) = self.mapped_span();
                (map.forward(value) - lo) / width
            }
        }
    }

    /// The value at coordinate `x` (`lo` exactly at `x ≤ 0`, `hi` exactly at `x ≥ 1`).
    pub fn at(&self, x: f64) -> f64 {
        if x >= 1.0 {
            self.hi
        } else if x <= 0.0 {
            self.lo
        } else {
            match self.map {
                AxisMap::Linear => self.lo + (self.hi - self.lo) * x,
                map => {
                    let (lo, width) = self.mapped_span();
                    map.inverse(lo + width * x).clamp(self.lo, self.hi)
                }
            }
        }
    }
}

/// How the values of an axis map to its coordinate.
///
/// Thornton's law takes `e_n` from the yield velocity ratio `V_y/V` (`physics.md`,
/// "Elastic–plastic impacts"); near `e_n = 1` the plastic radius at the deepest indentation
/// grows like `(1 − e_n)^{1/4}`, and `P` goes like `P(1) − a(1 − e_n) + b(1 − e_n)^{5/4}`:
/// smooth in `t = (1 − e_n)^{1/4}`, not in `e_n` (its second derivative is unbounded at 1).
/// A table of that law over a range that reaches `e_n = 1` is built over `t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AxisMap {
    /// `x = (value − lo)/(hi − lo)`.
    #[default]
    Linear,
    /// `m(e) = −(1 − e)^{1/4}` (as `−√√(1 − e)`, correctly rounded square roots in every
    /// reader), for an axis inside `(−∞, 1]`: `x = (m(e) − m(lo))/(m(hi) − m(lo))`.
    QuarterRoot,
}

impl AxisMap {
    /// The stored name of the map (the root attribute `e_n_coordinate` of a schema-5 table).
    pub fn name(self) -> &'static str {
        match self {
            AxisMap::Linear => "e_n",
            AxisMap::QuarterRoot => "(1-e_n)^(1/4)",
        }
    }

    /// The map of a stored name, `None` for a name this reader does not know.
    pub fn of_name(name: &str) -> Option<AxisMap> {
        [AxisMap::Linear, AxisMap::QuarterRoot]
            .into_iter()
            .find(|m| m.name() == name)
    }

    /// The mapped value `m(value)`.
    #[inline(always)]
    pub fn forward(self, value: f64) -> f64 {
        match self {
            AxisMap::Linear => value,
            AxisMap::QuarterRoot => -(1.0 - value).sqrt().sqrt(),
        }
    }

    /// The value of a mapped value `w` (the inverse of [`AxisMap::forward`], to rounding).
    #[inline(always)]
    pub fn inverse(self, w: f64) -> f64 {
        match self {
            AxisMap::Linear => w,
            AxisMap::QuarterRoot => {
                let t2 = w * w;
                1.0 - t2 * t2
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_axis_keeps_its_expressions() {
        let a = Axis::extra(&E_N, 0.3, 0.95, 2).unwrap();
        assert_eq!(a.map, AxisMap::Linear);
        for &e in &[0.3, 0.41, 0.5, 0.77, 0.95] {
            assert_eq!(a.x(e), (e - 0.3) / (0.95 - 0.3));
        }
        for &x in &[0.0, 0.125, 0.5, 0.9] {
            assert_eq!(a.at(x), 0.3 + (0.95 - 0.3) * x);
        }
        assert_eq!(a.mapped_span(), (0.3, 0.95 - 0.3));
    }

    #[test]
    fn the_quarter_root_map_is_monotone_exact_at_its_ends_and_inverts() {
        let a = Axis::extra(&E_N, 0.3, 1.0, 4)
            .unwrap()
            .with_map(AxisMap::QuarterRoot);
        assert_eq!((a.x(0.3), a.x(1.0)), (0.0, 1.0));
        assert_eq!((a.at(0.0), a.at(1.0)), (0.3, 1.0));
        // x(e) = 1 − ((1 − e)/0.7)^{1/4}: the coordinate of t = (1 − e)^{1/4}.
        let mut last = -1.0;
        for i in 0..=1000 {
            let e = 0.3 + 0.7 * i as f64 / 1000.0;
            let x = a.x(e);
            let want = 1.0 - ((1.0 - e) / 0.7).powf(0.25);
            assert!((x - want).abs() < 1e-14, "x({e}) = {x}, want {want}");
            assert!(x > last, "x must increase: x({e}) = {x} after {last}");
            last = x;
            // Back to e_n within rounding.
            assert!((a.at(x) - e).abs() < 1e-14, "at(x({e})) = {}", a.at(x));
        }
        // Next to e_n = 1 the coordinate spreads the axis: the last 1e-4 of e_n holds a tenth.
        assert!(a.x(1.0 - 1e-4) < 0.9);
        assert_eq!(
            AxisMap::of_name(AxisMap::QuarterRoot.name()),
            Some(AxisMap::QuarterRoot)
        );
        assert_eq!(AxisMap::of_name("e_n"), Some(AxisMap::Linear));
        assert_eq!(AxisMap::of_name("sqrt(1-e_n)"), None);
    }
}
