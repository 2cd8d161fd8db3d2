//! The query path of a table with an `e_n` axis: [`Surface::eval_point`] bit for bit, with
//! a fine index per patch over `(γ, c, e_n)` ([`Patch::fine_index3`]) in place of the
//! octree's descent from its roots, as [`super::Accel`] does for the quadtrees of an elastic
//! table (the module documentation of `fast` says why the bits are the rule's). The
//! arithmetic of the leaf is the rule's own ([`cubic_tensor3`]).

use crate::LookupError;
use oblique_table::surface::{
    bound_p, cubic_tensor3, full_slip_line, partial_coord_e, stick_coord, OutOfDomain, Patch,
    PatchKind, Region, Surface,
};

use super::{floor_index, MAX_INDEX_ENTRIES};

/// One cell of a patch's octree with its position, for the fine index.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cell {
    /// `2^depth`.
    scale: f64,
    /// Integer origin along γ, `c` and `e_n`, in units of the cell's size.
    og: f64,
    oc: f64,
    oe: f64,
    /// `tree[cell]`: `≥ 0` the first child, `< 0` leaf number `−link − 1`.
    link: i32,
}

/// A patch with an `e_n` axis and its fine index.
#[derive(Clone, PartialEq)]
struct FastPatch {
    kind: PatchKind,
    gamma_lo: f64,
    width: f64,
    /// `e_n_min` and `e_n_max − e_n_min` of the axis.
    e_lo: f64,
    e_width: f64,
    /// Root cells along γ, `c`, `e_n`, as floats.
    bg: f64,
    bc: f64,
    be: f64,
    /// `2^D`.
    fine: f64,
    /// Fine cells along γ, `c`, `e_n`.
    rows: usize,
    cols: usize,
    layers: usize,
    /// `rows × cols × layers` cell numbers (γ outer). Invariant (built by [`FastPatch::new`]):
    /// every entry is `< cells.len()`.
    index: Vec<u32>,
    cells: Vec<Cell>,
    /// `m + 1` and `(m + 1)³`.
    n1: usize,
    size: usize,
    /// `P` at the nodes, as in [`Patch::p`].
    p: Vec<f64>,
}

impl std::fmt::Debug for FastPatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FastPatch")
            .field("kind", &self.kind)
            .field("rows", &self.rows)
            .field("cols", &self.cols)
            .field("layers", &self.layers)
            .field("cells", &self.cells.len())
            .finish_non_exhaustive()
    }
}

impl FastPatch {
    /// The fine index of a validated patch with an `e_n` axis, or `None` (no axis, or a grid
    /// too small for the cubic stencil).
    fn new(patch: &Patch, max_entries: usize) -> Option<FastPatch> {
        let axis = *patch.restitution()?;
        let fine = patch.fine_index3(max_entries)?;
        let cells = fine
            .cells
            .iter()
            .zip(patch.tree())
            .map(|(c, &link)| Cell {
                scale: c.scale,
                og: c.og,
                oc: c.oc,
                oe: c.oe,
                link,
            })
            .collect();
        let n1 = patch.leaf_intervals() + 1;
        Some(FastPatch {
            kind: patch.kind(),
            gamma_lo: patch.gamma_lo(),
            width: patch.gamma_hi() - patch.gamma_lo(),
            e_lo: axis.lo(),
            e_width: axis.hi() - axis.lo(),
            bg: patch.blocks_gamma() as f64,
            bc: patch.blocks_coord() as f64,
            be: axis.blocks() as f64,
            fine: f64::from(1u32 << fine.depth),
            rows: fine.rows,
            cols: fine.cols,
            layers: fine.layers,
            index: fine.index,
            cells,
            n1,
            size: n1 * n1 * n1,
            p: patch.p().to_vec(),
        })
    }

    /// [`Patch::interpolate_at`] with `k = 4` at `(γ, c, e_n)`, `c ∈ [0, 1]`.
    #[inline(always)]
    fn interpolate(&self, gamma: f64, c: f64, e_n: f64) -> f64 {
        // Step 5 of the rule per axis: v = x·blocks, clamped (as `surface::locate`).
        let vg = ((gamma - self.gamma_lo) / self.width * self.bg).clamp(0.0, self.bg);
        let vc = (c * self.bc).clamp(0.0, self.bc);
        let ve = ((e_n - self.e_lo) / self.e_width * self.be).clamp(0.0, self.be);
        let ig = floor_index(vg * self.fine, self.rows - 1);
        let ic = floor_index(vc * self.fine, self.cols - 1);
        let ie = floor_index(ve * self.fine, self.layers - 1);
        let mut cell = self.cells[self.index[(ig * self.cols + ic) * self.layers + ie] as usize];
        let mut f = [
            vg * cell.scale - cell.og,
            vc * cell.scale - cell.oc,
            ve * cell.scale - cell.oe,
        ];
        // The rule's descent, only where the index depth was capped.
        while cell.link >= 0 {
            let mut child = cell.link as usize;
            for (x, weight) in f.iter_mut().zip([4, 2, 1]) {
                *x *= 2.0;
                let q = usize::from(*x >= 1.0);
                *x -= q as f64;
                child += weight * q;
            }
            cell = self.cells[child];
        }
        let leaf = (-(cell.link as i64) - 1) as usize;
        let vals = &self.p[leaf * self.size..(leaf + 1) * self.size];
        bound_p(cubic_tensor3(vals, self.n1, f))
    }
}

/// The acceleration structure of a table with an `e_n` axis: its patches with their fine
/// indexes.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Accel3 {
    alpha_max: f64,
    /// Indexed by `PatchId::index`.
    patches: [Option<FastPatch>; 3],
}

impl Accel3 {
    /// The structure for a surface with an `e_n` axis and the cubic stencil, else `None`.
    pub(crate) fn new(surface: &Surface) -> Option<Accel3> {
        surface.restitution()?;
        if surface.stencil() != 4 {
            return None;
        }
        let mut patches: [Option<FastPatch>; 3] = [None, None, None];
        for (id, p) in surface.patches() {
            patches[id.index()] = Some(FastPatch::new(p, MAX_INDEX_ENTRIES)?);
        }
        Some(Accel3 {
            alpha_max: surface.alpha_max(),
            patches,
        })
    }

    /// Bytes held by the fine indexes and cell lists (not counting the copy of `P`).
    pub(crate) fn index_bytes(&self) -> usize {
        self.patches
            .iter()
            .flatten()
            .map(|p| p.index.len() * 4 + p.cells.len() * std::mem::size_of::<Cell>())
            .sum()
    }

    /// [`Surface::eval_point`], bit for bit.
    #[inline]
    pub(crate) fn eval(
        &self,
        surface: &Surface,
        gamma: f64,
        alpha: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Result<f64, LookupError> {
        if !(gamma.is_finite() && gamma > 0.0) {
            return Err(oblique_table::surface::bad_gamma(gamma));
        }
        if alpha.is_nan() || alpha < 0.0 {
            return Err(oblique_table::surface::bad_alpha(alpha));
        }
        surface.check_e_n(e_n)?;
        let region = Region::of_e(gamma, alpha, e_n);
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        surface.apply_domain_e(region, gamma, alpha, e_n, outside, |r, g, a| {
            self.eval_in(r, g, a, e_n)
        })
    }

    #[inline(always)]
    fn eval_in(&self, region: Region, gamma: f64, alpha: f64, e_n: f64) -> f64 {
        let patch = match region.patch_id() {
            Some(id) => self.patches[id.index()].as_ref(),
            None => None,
        };
        match patch {
            Some(patch) => {
                let c = match patch.kind {
                    PatchKind::PartialSlip => partial_coord_e(gamma, alpha, e_n),
                    PatchKind::Stick => stick_coord(gamma, alpha, self.alpha_max),
                };
                patch.interpolate(gamma, c.clamp(0.0, 1.0), e_n)
            }
            None => -e_n,
        }
    }
}
