//! A patch with its fine index ([`IndexedPatch`]): the rule's steps 5 to 10 on a patch of any
//! number of axes, with the leaf found through a uniform grid instead of the descent from the
//! roots, bit for bit the rule's ([`crate::surface::FineIndex`] says why). The query paths of
//! `oblique-lookup` (single queries, batches) hold one per patch; the arithmetic of the leaf is
//! [`crate::leaf`]'s, the rule's own.

use crate::leaf::{
    cubic_tensor, cubic_tensor3_fast, descend, descend_masked, floor_f64, floor_index,
    floor_index32,
};
use crate::surface::{bound_p, AxisMap, Knots, Patch, PatchKind, Warp};

/// One cell of a patch's tree with its position, for the fine index: `2^depth` and the
/// integer origin per axis in units of the cell's size along it, `tree[cell]`, and the axes it
/// halves if split.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IndexedCell<const D: usize> {
    /// `2^depth` per axis.
    pub scale: [f64; D],
    /// Integer origin per axis (`floor(v·2^depth)` for the points it covers).
    pub origin: [f64; D],
    /// `tree[cell]`: `≥ 0` the first child, `< 0` leaf number `−link − 1`.
    pub link: i32,
    /// The axes a split cell halves ([`Patch::split_mask`]; `2^D − 1` for every axis).
    pub mask: u8,
}

/// A patch of `D` axes (`γ`, `c`, then `e_n` for a table with that axis) with its fine index
/// ([`Patch::fine_index`]) and a copy of its node values.
#[derive(Clone, PartialEq)]
pub struct IndexedPatch<const D: usize> {
    kind: PatchKind,
    /// Per axis, `x = (value − lo)/width` (the `c` axis, `k = 1`, is given as `x`: unused).
    lo: [f64; D],
    width: [f64; D],
    /// Per axis, the map `m` of [`Patch::axis_map`]: `x = (m(value) − lo)/width`.
    map: [AxisMap; D],
    /// Root cells per axis, as floats.
    blocks: [f64; D],
    /// `2^depth` of the index per axis.
    fine: [f64; D],
    /// Index entries per axis.
    shape: [usize; D],
    /// Cell numbers, row-major (γ outer). Invariant (built by [`IndexedPatch::new`]): every
    /// entry is `< cells.len()`.
    index: Vec<u32>,
    /// Every cell of the tree, in the order of the tree.
    cells: Vec<IndexedCell<D>>,
    /// `m`, `m + 1`, `(m + 1)^D`.
    m: f64,
    n1: usize,
    size: usize,
    /// `P` at the nodes, as in [`Patch::p`].
    p: Vec<f64>,
    /// The warp of the coordinate, as in [`Patch::warp`].
    warp: Option<Warp>,
    /// The knots of the coordinate, as in [`Patch::knots`].
    knots: Option<Knots>,
}

impl<const D: usize> std::fmt::Debug for IndexedPatch<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("IndexedPatch")
            .field("kind", &self.kind)
            .field("shape", &self.shape)
            .field("cells", &self.cells.len())
            .finish_non_exhaustive()
    }
}

impl<const D: usize> IndexedPatch<D> {
    /// The fine index of a validated patch of `D` axes with at most `max_entries` entries, or
    /// `None` (another number of axes, a grid too small for the cubic stencil, a tree deeper
    /// than 30).
    pub fn new(patch: &Patch, max_entries: usize) -> Option<IndexedPatch<D>> {
        if patch.dims() as usize != D {
            return None;
        }
        let fine = patch.fine_index_any(max_entries)?;
        let cells = fine
            .cells
            .iter()
            .zip(patch.tree())
            .map(|(c, &link)| IndexedCell {
                scale: std::array::from_fn(|k| c.scale[k]),
                origin: std::array::from_fn(|k| c.origin[k]),
                link,
                mask: c.mask,
            })
            .collect();
        let m = patch.leaf_intervals();
        Some(IndexedPatch {
            kind: patch.kind(),
            lo: std::array::from_fn(|k| patch.axis(k).0),
            width: std::array::from_fn(|k| patch.axis(k).1),
            map: std::array::from_fn(|k| patch.axis_map(k)),
            blocks: std::array::from_fn(|k| patch.axis(k).2 as f64),
            fine: std::array::from_fn(|k| f64::from(1u32 << fine.depth[k])),
            shape: std::array::from_fn(|k| fine.shape[k]),
            index: fine.index,
            cells,
            m: m as f64,
            n1: m + 1,
            size: patch.leaf_size(),
            p: patch.p().to_vec(),
            warp: patch.warp().cloned(),
            knots: patch.knots().cloned(),
        })
    }

    /// Region and coordinate.
    pub fn kind(&self) -> PatchKind {
        self.kind
    }

    /// The warp of the coordinate, if any.
    pub fn warp(&self) -> Option<&Warp> {
        self.warp.as_ref()
    }

    /// Index entries per axis (`blocks·2^depth`).
    pub fn shape(&self) -> [usize; D] {
        self.shape
    }

    /// `m`, intervals per axis of every leaf's grid, as a float.
    pub fn m(&self) -> f64 {
        self.m
    }

    /// `m + 1`, nodes per axis of every leaf's grid.
    pub fn n1(&self) -> usize {
        self.n1
    }

    /// `(m + 1)^D`, nodes per leaf.
    pub fn leaf_size(&self) -> usize {
        self.size
    }

    /// `P` at the nodes, leaf by leaf, as in [`Patch::p`].
    pub fn p(&self) -> &[f64] {
        &self.p
    }

    /// Bytes held by the fine index and the cell list (not counting the copy of `P`).
    pub fn index_bytes(&self) -> usize {
        self.index.len() * 4 + self.cells.len() * std::mem::size_of::<IndexedCell<D>>()
    }

    /// Whether 32-bit positions suffice for this patch (always for shipped tables: the fine
    /// index, the node array and the leaf grid are far below 2³¹ entries), and every leaf the
    /// tree names has its whole node grid in `p`, so that the first node of any stencil block
    /// is an integer below `p.len() < 2³¹` (see [`crate::leaf::exact_u32`]).
    pub fn fits_u32(&self) -> bool {
        let small = |n: usize| n < (1 << 31);
        let leaves_end = self
            .cells
            .iter()
            .filter(|c| c.link < 0)
            .map(|c| (-(c.link as i64)) as usize)
            .max()
            .unwrap_or(0);
        small(self.index.len())
            && small(self.p.len())
            && small(self.n1)
            && self.shape.iter().all(|&s| small(s))
            && leaves_end
                .checked_mul(self.size)
                .is_some_and(|e| e <= self.p.len())
    }

    /// Step 6 along axis `k` (not the `c` axis): `v = x·blocks` of `x = (m(value) − lo)/width`
    /// (`m` the axis map), clamped to `[0, blocks]` (as [`crate::leaf::locate`]).
    #[inline(always)]
    pub fn position(&self, k: usize, value: f64) -> f64 {
        let value = self.map[k].forward(value);
        ((value - self.lo[k]) / self.width[k] * self.blocks[k]).clamp(0.0, self.blocks[k])
    }

    /// Step 6 along the `c` axis: `v = c·blocks_coord`, clamped.
    #[inline(always)]
    pub fn position_c(&self, c: f64) -> f64 {
        (c * self.blocks[1]).clamp(0.0, self.blocks[1])
    }

    /// Step 5: the coordinate the tree is over at `γ` with `v_γ =` [`IndexedPatch::position`]
    /// `(0, γ)` ([`Patch::warped`], the same operations).
    #[inline(always)]
    pub fn warped(&self, gamma: f64, vg: f64, c: f64) -> f64 {
        match &self.warp {
            Some(w) if vg >= w.start() => w.apply(gamma, c),
            _ => c,
        }
    }

    /// The fine index entry of the point at `v` (per axis, in units of the root cells).
    #[inline(always)]
    pub fn entry(&self, v: [f64; D]) -> usize {
        let mut e = 0;
        for ((&vk, &s), &fk) in v.iter().zip(&self.shape).zip(&self.fine) {
            e = e * s + floor_index(vk * fk, s - 1);
        }
        e
    }

    /// [`IndexedPatch::entry`] through 32-bit conversions ([`floor_index32`]; for a patch
    /// that [`IndexedPatch::fits_u32`]): the same entry.
    #[inline(always)]
    pub fn entry_u32(&self, v: [f64; D]) -> u32 {
        let mut e = 0;
        for ((&vk, &s), &fk) in v.iter().zip(&self.shape).zip(&self.fine) {
            e = e * s as u32 + floor_index32(vk * fk, s as u32 - 1);
        }
        e
    }

    /// [`IndexedPatch::entry`] in floating point ([`floor_f64`]; for a patch that
    /// [`IndexedPatch::fits_u32`]): the same entry, as a float.
    #[inline(always)]
    pub fn entry_f64(&self, v: [f64; D]) -> f64 {
        let mut e = 0.0;
        for ((&vk, &s), &fk) in v.iter().zip(&self.shape).zip(&self.fine) {
            e = e * s as f64 + floor_f64(vk * fk, (s - 1) as f64);
        }
        e
    }

    /// The leaf and the position inside it of the point at `v` whose fine index entry is
    /// `entry`: the entry's cell, the position in it (`v·2^d − origin`, exact), then the rule's
    /// descent ([`descend`]), only when the index depth was capped below the deepest leaf.
    #[inline(always)]
    pub fn leaf_from(&self, entry: usize, v: [f64; D]) -> (usize, [f64; D]) {
        let mut cell = self.cells[self.index[entry] as usize];
        let mut f = [0.0; D];
        for (((fk, &vk), &ok), &sk) in f.iter_mut().zip(&v).zip(&cell.origin).zip(&cell.scale) {
            *fk = vk * sk - ok;
        }
        while cell.link >= 0 {
            let child = if u32::from(cell.mask) == (1 << D) - 1 {
                descend(&mut f)
            } else {
                descend_masked(&mut f, cell.mask)
            };
            cell = self.cells[cell.link as usize + child];
        }
        ((-(cell.link as i64) - 1) as usize, f)
    }

    /// Steps 6 to 10 at `v` (per axis, in units of the root cells, after the warp):
    /// [`cubic_tensor`] in the leaf (of three axes through [`cubic_tensor3_fast`],
    /// the same bits), limited to `[−1, 1]`.
    #[inline(always)]
    pub fn at(&self, v: [f64; D]) -> f64 {
        self.at_by(v, |vals, n1, f| {
            if D == 3 {
                cubic_tensor3_fast(vals, n1, std::array::from_fn(|k| f[k]))
            } else {
                cubic_tensor(vals, n1, f)
            }
        })
    }

    /// [`IndexedPatch::at`] with the leaf's tensor product from `tensor(vals, n1, f)`, which
    /// must be [`cubic_tensor`]'s bits (the scalar sum, or [`crate::leaf::cubic_tensor3_avx`]
    /// from code compiled for AVX, where it is inlined).
    #[inline(always)]
    pub fn at_by(&self, v: [f64; D], tensor: impl Fn(&[f64], usize, [f64; D]) -> f64) -> f64 {
        let (leaf, f) = self.leaf_from(self.entry(v), v);
        let vals = &self.p[leaf * self.size..(leaf + 1) * self.size];
        bound_p(tensor(vals, self.n1, f))
    }

    /// [`Patch::interpolate_at`] with `k = 4` at `point`, the value per axis: `γ`, the
    /// unwarped coordinate `c ∈ [0, 1]`, then `e_n` (a table with that axis).
    #[inline(always)]
    pub fn interpolate(&self, point: [f64; D]) -> f64 {
        self.at(self.positions(point))
    }

    /// [`IndexedPatch::interpolate`] with the tensor product of [`IndexedPatch::at_by`].
    #[inline(always)]
    pub fn interpolate_by(
        &self,
        point: [f64; D],
        tensor: impl Fn(&[f64], usize, [f64; D]) -> f64,
    ) -> f64 {
        self.at_by(self.positions(point), tensor)
    }

    /// Steps 5 and 6 at `point` (as [`IndexedPatch::interpolate`] takes it): the position per
    /// axis in units of the root cells, after the warp or the knots ([`Patch::knotted`], the
    /// same operations).
    #[inline(always)]
    pub fn positions(&self, point: [f64; D]) -> [f64; D] {
        let mut v = [0.0; D];
        for k in 2..D {
            v[k] = self.position(k, point[k]);
        }
        v[0] = self.position(0, point[0]);
        let c = match &self.knots {
            Some(k) if D == 3 && k.applies(v[0], v[2], self.blocks[0], self.blocks[2]) => {
                k.line(point[0], point[2]).apply(point[1])
            }
            _ => self.warped(point[0], v[0], point[1]),
        };
        v[1] = self.position_c(c);
        v
    }
}
