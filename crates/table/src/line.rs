//! The rule along one line of a patch: `γ` and `e_n` fixed, the coordinate `c` free
//! ([`PatchLine`], built by [`Patch::line`]).
//!
//! A code that meets one pair of materials at one normal restitution asks for `P` along one
//! line of the table over and over. On that line the descent along `γ` and `e_n` and their
//! stencils (steps 6 to 8 of `docs/table-format.md`) do not depend on `c`, and neither do the
//! rows of a leaf's block along `e_n` (the innermost sums of step 9). [`Patch::line`] follows
//! the rule's descent along every axis but `c` (both halves along `c`), and for every leaf the
//! line crosses stores the `γ` weights and, per `γ` index and `c` node, the row along `e_n`
//! summed as the rule sums it. A query then reads the leaf from a uniform index along `c`
//! (the position inside it is `v·2^d − origin`, exact, as in [`crate::indexed`]), computes the
//! `c` stencil and sums 4 rows of 4 values: the rule's operations in the rule's order for
//! what depends on `c`, the rule's own results for the rest, so the rule's bits
//! ([`Patch::tensor_point`]; tested on every shipped table).

use crate::leaf::{floor_index, stencil4, sum_row, weigh4};
use crate::surface::{bound_p, Patch};

/// Largest number of entries of a line's index along `c` (`2²⁰`, 4 MiB); a line through
/// leaves so deep that its index would need more has no [`PatchLine`].
pub const MAX_LINE_ENTRIES: usize = 1 << 20;

/// One leaf on the line.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Segment {
    /// `2^d` and the integer origin along `c` of the leaf (depth `d` along `c`), in units of
    /// its size: the position inside it is `v·scale − origin` (`v = c·blocks_coord`).
    scale: f64,
    origin: f64,
    /// The `γ` stencil's weights (unused in a patch without a `γ` axis).
    wg: [f64; 4],
    /// Where the leaf's rows start in [`PatchLine::rows`].
    first: usize,
}

/// The rule of one patch along the line `γ = γ₀`, `e_n = e_n₀` ([`Patch::line`]):
/// [`PatchLine::interpolate`] gives [`Patch::interpolate_at`]`(γ₀, c, e_n₀, 4)` bit for bit.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchLine {
    /// Root cells along `c`, as a float.
    blocks: f64,
    /// Index entries per root cell along `c` (`2^D`, `D` the deepest leaf on the line).
    fine: f64,
    /// The last index entry.
    last: usize,
    /// The segment of each index entry.
    index: Vec<u32>,
    segments: Vec<Segment>,
    /// Per segment, `planes × n1` values: for `γ` index `i` of the stencil and `c` node `j`
    /// of the leaf, the row along `e_n` summed with the `e_n` weights (a patch without an
    /// `e_n` axis: the node itself).
    rows: Vec<f64>,
    /// Nodes per axis of a leaf, `m + 1`, and `m`.
    n1: usize,
    m: f64,
    /// 4 (a `γ` stencil), or 1 (the patch of one pair, without a `γ` axis).
    planes: usize,
}

impl Patch {
    /// The rule along `γ = gamma`, `e_n = e_n` (`e_n` ignored in a patch without an `e_n`
    /// axis; `γ` ignored in the patch of one pair) with the cubic stencil, or `None` for a
    /// patch whose leaves have fewer than 4 nodes per axis, a warped or knotted patch, or a line whose
    /// index would exceed [`MAX_LINE_ENTRIES`]. Outside the patch's ranges the coordinates are
    /// clamped as the rule clamps them.
    pub fn line(&self, gamma: f64, e_n: f64) -> Option<PatchLine> {
        let n1 = self.leaf_intervals() + 1;
        if n1 < 4 || self.warp().is_some() || self.knots().is_some() {
            return None;
        }
        let xg = self.x_gamma(gamma);
        match self.restitution() {
            None => self.line_at([xg, 0.0], 1),
            Some(r) if self.is_pair() => self.line_at([0.0, r.x(e_n)], 0),
            Some(r) => self.line_at([xg, 0.0, r.x(e_n)], 1),
        }
    }

    /// [`Patch::line`] at coordinates `x` of `D` axes, `ca` the axis of `c` (`x[ca]` unused).
    fn line_at<const D: usize>(&self, x: [f64; D], ca: usize) -> Option<PatchLine> {
        let blocks = self.axis(ca).2;
        let leaves = self.line_leaves(x, ca);
        let depth = leaves.iter().map(|l| l.2).max()?;
        let entries = blocks
            .checked_shl(depth)
            .filter(|&n| n > 0 && n <= MAX_LINE_ENTRIES && depth < 52)?;
        let n1 = self.leaf_intervals() + 1;
        let m = (n1 - 1) as f64;
        let planes = if D == 3 || ca == 1 { 4 } else { 1 };
        let size = self.leaf_size();
        let mut index = vec![u32::MAX; entries];
        let mut segments = Vec::with_capacity(leaves.len());
        let mut rows = Vec::with_capacity(leaves.len() * planes * n1);
        for (leaf, f, d, origin) in leaves {
            let vals = &self.p()[leaf * size..(leaf + 1) * size];
            // The stencils along γ and e_n (the rule's: `stencil4` at `f·m`).
            let stencil = |k: usize| stencil4(f[k] * m, n1);
            let (sg, wg) = if ca == 1 { stencil(0) } else { (0, [0.0; 4]) };
            let first = rows.len();
            for i in 0..planes {
                for j in 0..n1 {
                    rows.push(match D {
                        // (γ, c, e_n): the row along e_n at γ node sg + i, c node j.
                        3 => {
                            let (se, we) = stencil(2);
                            sum_row(&vals[((sg + i) * n1 + j) * n1 + se..][..4], &we)
                        }
                        // (c, e_n) of one pair: the row along e_n at c node j.
                        _ if ca == 0 => {
                            let (se, we) = stencil(1);
                            sum_row(&vals[j * n1 + se..][..4], &we)
                        }
                        // (γ, c) of an elastic patch: the node.
                        _ => vals[(sg + i) * n1 + j],
                    });
                }
            }
            let span = 1usize << (depth - d);
            let start = usize::try_from(origin).ok()?.checked_mul(span)?;
            let k = u32::try_from(segments.len()).ok()?;
            index.get_mut(start..start.checked_add(span)?)?.fill(k);
            segments.push(Segment {
                scale: f64::from(d as i32).exp2(),
                origin: origin as f64,
                wg,
                first,
            });
        }
        // The tree's leaves tile the line: every entry has its leaf.
        if index.contains(&u32::MAX) {
            return None;
        }
        Some(PatchLine {
            blocks: blocks as f64,
            fine: f64::from(depth as i32).exp2(),
            last: entries - 1,
            index,
            segments,
            rows,
            n1,
            m,
            planes,
        })
    }
}

impl PatchLine {
    /// [`Patch::interpolate_at`]`(γ₀, c, e_n₀, 4)` of the line's patch, bit for bit: `P`
    /// (dimensionless, in `[−1, 1]`) at the patch coordinate `c ∈ [0, 1]` (clamped as the
    /// rule clamps it).
    #[inline(always)]
    pub fn interpolate(&self, c: f64) -> f64 {
        // Steps 6 and 7: the rule's position along c, the leaf from the index, the position
        // inside it.
        let v = (c * self.blocks).clamp(0.0, self.blocks);
        let s = &self.segments[self.index[floor_index(v * self.fine, self.last)] as usize];
        let fc = v * s.scale - s.origin;
        // Steps 8 and 9: the c stencil over the stored rows, then the planes over γ.
        let (sc, wc) = stencil4(fc * self.m, self.n1);
        let rows = &self.rows[s.first + sc..];
        let plane = |i: usize| {
            let r = &rows[i * self.n1..][..4];
            weigh4(&wc, [r[0], r[1], r[2], r[3]])
        };
        let p = if self.planes == 1 {
            plane(0)
        } else {
            weigh4(&s.wg, [plane(0), plane(1), plane(2), plane(3)])
        };
        bound_p(p)
    }

    /// Bytes held by the line's index, leaves and rows.
    pub fn bytes(&self) -> usize {
        self.index.len() * 4
            + self.segments.len() * std::mem::size_of::<Segment>()
            + self.rows.len() * 8
    }
}
