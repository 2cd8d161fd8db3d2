//! One patch ([`Patch`]): its root cells and tree, its nodes, the fine index that locates a
//! leaf, and the evaluation inside a leaf.

use super::*;

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
    pub(super) kind: PatchKind,
    /// The axes, in order: `γ`, the coordinate `c` of `α`, and `e_n` (schema 4) if the table
    /// has one; with it the tree is an octree over `(x, c, x_e)` (see [`Axis`]).
    pub(super) axes: Vec<Axis>,
    /// Intervals per axis of every leaf's grid (`m`).
    pub(super) leaf_intervals: usize,
    /// The quadtree, see the type's documentation.
    pub(super) tree: Vec<i32>,
    /// `P` at the nodes, leaf by leaf, `[leaves, m + 1, m + 1]` row-major.
    pub(super) p: Vec<f64>,
    /// Solver error estimate of each node, same layout.
    pub(super) error_estimate: Vec<f64>,
    /// Optional warp of the coordinate (only `partial_high`, schema 3): when present, the
    /// quadtree is over `(x, c')` with `c' =` [`Warp::apply`]`(γ, c)` instead of `(x, c)`.
    pub(super) warp: Option<Warp>,
    /// Optional knots of the coordinate (only `partial_high` of a table over `γ, α, e_n`):
    /// where they apply, the tree is over `(x, c', x_e)` with `c'` from [`KnotLine::apply`].
    pub(super) knots: Option<Knots>,
    /// Which axes each split cell halves (schema 4, optional; see [`check_split`]): bit
    /// `dims − 1 − k` for axis `k` (`γ`, `c`, `e_n`), non-zero exactly for the split cells.
    /// The children of cell `i` are the `2^popcount` cells from `tree[i]`, numbered row-major
    /// over the halved axes in axis order. `None`: every split halves every axis.
    pub(super) split: Option<Vec<u8>>,
}

/// Everything of a patch but its kind and axes ([`Patch::new`]): its tree and the values at
/// its nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchData {
    /// Intervals per axis of every leaf's grid (`m`).
    pub leaf_intervals: usize,
    /// The tree (see [`Patch`]).
    pub tree: Vec<i32>,
    /// Which axes each split cell halves ([`check_split`]; only with an `e_n` axis), or `None`
    /// when every split halves every axis.
    pub split: Option<Vec<u8>>,
    /// `P` at the nodes, leaf by leaf, `[leaves, m + 1, …]` row-major.
    pub p: Vec<f64>,
    /// Solver error estimate of each node, same layout.
    pub error_estimate: Vec<f64>,
    /// The warp of the coordinate, if any (only without an `e_n` axis).
    pub warp: Option<Warp>,
    /// The knots of the coordinate, if any (only with an `e_n` axis, over a range of γ).
    pub knots: Option<Knots>,
}

impl Patch {
    /// A patch from its stored values, checked: the axes `γ`, `c` ([`Axis::coord`]) and
    /// optionally `e_n` ([`Axis::restitution`]) in that order; finite increasing γ edges
    /// `> 0` (equal only in the patch of one pair: an `e_n` axis and one root cell along γ), at
    /// least one root cell per axis, `m ≥ 1`, a valid tree ([`check_tree_of`]: a quadtree, or
    /// an octree with an `e_n` axis; [`check_split`] with `split`), `(m + 1)^dims` finite
    /// node values of `P` (each `|P| ≤ 1 + 1e-6`) and of the error estimate per leaf, and a
    /// valid warp ([`Patch::check_warp`]; a patch with an `e_n` axis has none). `Err` names
    /// the value and the rule.
    pub fn new(kind: PatchKind, axes: Vec<Axis>, data: PatchData) -> Result<Patch, String> {
        let PatchData {
            leaf_intervals,
            tree,
            split,
            p,
            error_estimate,
            warp,
            knots,
        } = data;
        let restitution = match axes.as_slice() {
            [g, c] | [g, c, _] if g.name != AxisName::Gamma || *c != Axis::coord(c.blocks) => {
                return Err("the axes must be gamma, the patch coordinate of alpha and \
                            optionally e_n, in this order"
                    .into())
            }
            [_, _] => None,
            [_, _, e] if e.name.extra().is_some() => e
                .name
                .extra()
                .map(|spec| Axis::extra(spec, e.lo, e.hi, e.blocks).map(|a| a.with_map(e.map)))
                .transpose()?,
            _ => {
                return Err(format!(
                    "{} axes: a patch has gamma, the patch coordinate of alpha and \
                     optionally e_n",
                    axes.len()
                ))
            }
        };
        let (gamma_lo, gamma_hi) = (axes[0].lo, axes[0].hi);
        let (blocks_gamma, blocks_coord) = (axes[0].blocks, axes[1].blocks);
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
        if knots.is_some() && (restitution.is_none() || pair) {
            return Err(
                "only a patch over gamma, its coordinate and e_n (a range of gamma) can \
                        have knots"
                    .into(),
            );
        }
        let dims = tree_dims(restitution.is_some(), pair);
        let roots = axes.iter().map(|a| a.blocks).product();
        let leaves = match &split {
            None => check_tree_of(&tree, roots, 1 << dims),
            Some(split) => {
                check_split(&tree, split, dims).map_err(|m| format!("dataset 'split' {m}"))?;
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
            axes,
            leaf_intervals,
            tree,
            p,
            error_estimate,
            warp,
            knots,
            split,
        };
        patch.check_warp()?;
        patch.check_knots()?;
        Ok(patch)
    }

    /// The same patch with other node values, error estimates, warp and knots, checked as by
    /// [`Patch::new`].
    fn remade(
        &self,
        p: Vec<f64>,
        error_estimate: Vec<f64>,
        warp: Option<Warp>,
        knots: Option<Knots>,
    ) -> Result<Patch, String> {
        Patch::new(
            self.kind,
            self.axes.clone(),
            PatchData {
                leaf_intervals: self.leaf_intervals,
                tree: self.tree.clone(),
                split: self.split.clone(),
                p,
                error_estimate,
                warp,
                knots,
            },
        )
    }

    /// The same patch with other node values of `P` (`f(i, P_i)` at node `i`), checked as by
    /// [`Patch::new`].
    pub fn map_values(&self, f: impl FnMut(usize, f64) -> f64) -> Result<Patch, String> {
        let mut f = f;
        let p = self.p.iter().enumerate().map(|(i, &v)| f(i, v)).collect();
        self.remade(
            p,
            self.error_estimate.clone(),
            self.warp.clone(),
            self.knots.clone(),
        )
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
        self.remade(
            self.p.clone(),
            error_estimate,
            self.warp.clone(),
            self.knots.clone(),
        )
    }

    /// The same patch with another warp (or none), checked as by [`Patch::new`].
    pub fn with_warp(&self, warp: Option<Warp>) -> Result<Patch, String> {
        self.remade(
            self.p.clone(),
            self.error_estimate.clone(),
            warp,
            self.knots.clone(),
        )
    }

    /// The axes, in order: `γ`, the coordinate `c` of `α`, and `e_n` if the patch has one.
    pub fn axes(&self) -> &[Axis] {
        &self.axes
    }

    /// The `e_n` axis, if the patch has one.
    #[inline(always)]
    pub fn restitution(&self) -> Option<&Axis> {
        self.axes.get(2)
    }

    /// The axes of the tree: [`Patch::axes`] without `γ` in the patch of one pair.
    fn tree_axes(&self) -> &[Axis] {
        &self.axes[usize::from(self.is_pair())..]
    }

    /// Number of axes of the tree: 2 (`γ`, `c`), 3 with an `e_n` axis (`γ`, `c`, `e_n`), or 2
    /// in the patch of one pair (`c`, `e_n`; [`Patch::is_pair`]).
    pub fn dims(&self) -> u32 {
        self.tree_axes().len() as u32
    }

    /// Whether this is the patch of one pair of materials: a single `γ` (`gamma_lo =
    /// gamma_hi`, one root cell along γ) with an `e_n` axis, its tree over `(c, e_n)` only. Its
    /// masks, children and nodes are those of a patch over `(γ, c, e_n)` whose cells never
    /// halve `γ` and whose leaves have one node along it.
    #[inline(always)]
    pub fn is_pair(&self) -> bool {
        self.axes[0].lo == self.axes[0].hi
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
        self.restitution().map_or(1, |r| r.blocks)
    }

    /// Root cells of the tree: the product over the axes.
    pub fn roots(&self) -> usize {
        self.axes.iter().map(|a| a.blocks).product()
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
    #[inline(always)]
    pub fn gamma_lo(&self) -> f64 {
        self.axes[0].lo
    }

    /// Upper γ edge.
    #[inline(always)]
    pub fn gamma_hi(&self) -> f64 {
        self.axes[0].hi
    }

    /// Root cells along γ.
    pub fn blocks_gamma(&self) -> usize {
        self.axes[0].blocks
    }

    /// Root cells along `c`.
    pub fn blocks_coord(&self) -> usize {
        self.axes[1].blocks
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
        if self.restitution().is_some() {
            return None;
        }
        self.fine_index_any(max_entries)
    }

    /// The fine index of a patch with an `e_n` axis: [`FineIndex`] over `(γ, c, e_n)`
    /// (`layers` entries along `e_n`), or `None` as [`Patch::fine_index`] (and for a patch
    /// without the axis).
    pub fn fine_index3(&self, max_entries: usize) -> Option<FineIndex> {
        self.restitution()?;
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
        self.axes[0].x(gamma)
    }

    /// Root cells along each of the first `D` axes (`γ`, `c`, `e_n`; 1 beyond the patch's).
    #[inline(always)]
    fn blocks_of<const D: usize>(&self) -> [usize; D] {
        std::array::from_fn(|k| self.axis_blocks(k))
    }

    /// Axis `k` of the patch's tree (0 `γ`, 1 `c`, 2 `e_n`): `(lo, width, blocks)`, its
    /// coordinate `x = (m(value) − lo)/width` with `m` its map ([`Patch::axis_map`],
    /// [`Axis::mapped_span`]; `c` is its own coordinate: `(0, 1)`) and its root cells;
    /// `(0, 1, 1)` beyond the patch's axes.
    /// How axis `k` of the patch's tree maps its values ([`AxisMap::Linear`] but for an `e_n`
    /// axis of a schema-5 table).
    pub fn axis_map(&self, k: usize) -> AxisMap {
        self.tree_axes().get(k).map_or(AxisMap::Linear, |a| a.map)
    }

    /// Root cells along axis `k` of the patch's tree (1 beyond its axes): [`Patch::axis`]'s
    /// third value, without the map's span.
    #[inline(always)]
    pub fn axis_blocks(&self, k: usize) -> usize {
        self.tree_axes().get(k).map_or(1, |a| a.blocks)
    }

    /// [`Patch::axis`]'s values: `(lo, width, blocks)` of axis `k`.
    pub fn axis(&self, k: usize) -> (f64, f64, usize) {
        match self.tree_axes().get(k) {
            Some(a) => {
                let (lo, width) = a.mapped_span();
                (lo, width, a.blocks)
            }
            None => (0.0, 1.0, 1),
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
        match self.restitution() {
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
        w.validate(self.gamma_lo(), self.gamma_hi(), self.blocks_gamma())?;
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

    /// The knots of the coordinate, if any.
    pub fn knots(&self) -> Option<&Knots> {
        self.knots.as_ref()
    }

    /// Check the patch's knots, if any, against the patch: the region inside the root cells
    /// (edges multiples of `2⁻²⁰`), the grid covering the region's γ and `e_n` ranges (within
    /// `1e-12` of the span), and no leaf across an edge of the region (every leaf wholly inside
    /// or wholly outside along each axis). `Err` names the attribute and the allowed range, or
    /// the leaf.
    pub fn check_knots(&self) -> Result<(), String> {
        let (Some(k), Some(r)) = (&self.knots, self.restitution()) else {
            return Ok(());
        };
        let blocks = [self.blocks_gamma() as f64, r.blocks as f64];
        let region = k.region;
        for (axis, (from, to)) in [(region[0], region[1]), (region[2], region[3])]
            .into_iter()
            .enumerate()
        {
            let dyadic = |v: f64| (v * 1048576.0).fract() == 0.0;
            if !(to <= blocks[axis] && dyadic(from) && dyadic(to)) {
                return Err(format!(
                    "attribute 'region' = {region:?}: the {} edges must be multiples of 2^-20 \
                     in [0, {}] (root cells of the patch)",
                    ["gamma", "e_n"][axis],
                    blocks[axis]
                ));
            }
        }
        let at = |axis: usize, v: f64| {
            let (lo, hi) = if axis == 0 {
                (self.gamma_lo(), self.gamma_hi())
            } else if r.map == AxisMap::Linear {
                (r.lo, r.hi)
            } else {
                // The e_n of a root-cell position through the axis map.
                return r.at(v / blocks[axis]);
            };
            lo + (hi - lo) * v / blocks[axis]
        };
        let grids = [
            ("gamma", k.gamma_0, k.gamma_step, k.n_gamma),
            ("e_n", k.e_n_0, k.e_n_step, k.n_e_n),
        ];
        for (axis, (name, first, step, n)) in grids.into_iter().enumerate() {
            let (from, to) = (at(axis, region[2 * axis]), at(axis, region[2 * axis + 1]));
            let end = first + (n - 1) as f64 * step;
            let slack = 1e-12 * to.abs().max(1.0);
            if !(first <= from + slack && end >= to - slack) {
                return Err(format!(
                    "the knot grid along {name} spans [{first}, {end}]: must cover the region's \
                     [{from}, {to}]"
                ));
            }
        }
        for (axis, tree_axis) in [(0usize, 0usize), (1, 2)] {
            let (from, to) = (region[2 * axis], region[2 * axis + 1]);
            for (leaf, (lo, hi)) in self.leaf_spans(tree_axis).into_iter().enumerate() {
                if (lo < from && from < hi) || (lo < to && to < hi) {
                    return Err(format!(
                        "leaf {leaf} spans root cells [{lo}, {hi}] along {} across an edge of \
                         attribute 'region' = {region:?}: no leaf may straddle one",
                        ["gamma", "e_n"][axis]
                    ));
                }
            }
        }
        Ok(())
    }

    /// Each leaf's extent along axis `axis` of the tree (`0` γ, `1` c, `2` `e_n`; a patch over
    /// `γ`, `c`, `e_n`) in root-cell units, `[a/2^d, (a+1)/2^d]` for a leaf halved `d` times
    /// along it at integer position `a` (exact dyadic values), leaf by leaf; the cells' `split`
    /// masks say which axes each halves.
    pub fn leaf_spans(&self, axis: usize) -> Vec<(f64, f64)> {
        let dims = self.dims() as usize;
        let blocks: Vec<usize> = self.tree_axes().iter().map(|a| a.blocks).collect();
        let after: usize = blocks[axis + 1..].iter().product();
        let mut spans = vec![(0.0, 0.0); self.leaves()];
        let mut stack: Vec<(usize, u32, u64)> = (0..self.roots())
            .map(|i| (i, 0, ((i / after) % blocks[axis]) as u64))
            .collect();
        let bit = 1u8 << (dims - 1 - axis);
        while let Some((cell, d, a)) = stack.pop() {
            let t = self.tree[cell];
            if t < 0 {
                let scale = f64::from(d.min(1000) as i32).exp2();
                spans[(-(t as i64) - 1) as usize] = (a as f64 / scale, (a + 1) as f64 / scale);
                continue;
            }
            let mask = self.split_mask(cell);
            let n = 1usize << mask.count_ones();
            if mask & bit == 0 {
                stack.extend((0..n).map(|q| (t as usize + q, d, a)));
            } else {
                let shift = (mask & (bit - 1)).count_ones();
                stack.extend(
                    (0..n).map(|q| (t as usize + q, d + 1, 2 * a + ((q >> shift) & 1) as u64)),
                );
            }
        }
        spans
    }

    /// The knots on the line through `(γ, e_n)` where they apply: the patch has knots and the
    /// clamped root-cell positions of `γ` and `e_n` ([`locate`]'s) are inside their region.
    #[inline]
    pub fn knots_at(&self, gamma: f64, e_n: f64) -> Option<KnotLine> {
        let k = self.knots.as_ref()?;
        let r = self.restitution()?;
        let bg = self.blocks_gamma() as f64;
        let be = r.blocks as f64;
        let vg = (self.x_gamma(gamma) * bg).clamp(0.0, bg);
        let ve = (r.x(e_n) * be).clamp(0.0, be);
        k.applies(vg, ve, bg, be).then(|| k.line(gamma, e_n))
    }

    /// Step 5 of the rule in a patch with an `e_n` axis: `c` itself, or
    /// [`KnotLine::apply`]`(c)` where [`Patch::knots_at`] gives the knots.
    #[inline]
    pub fn knotted(&self, gamma: f64, c: f64, e_n: f64) -> f64 {
        match self.knots_at(gamma, e_n) {
            Some(line) => line.apply(c),
            None => c,
        }
    }

    /// Each leaf's extent along γ in root-cell units, `[a/2^d, (a+1)/2^d]` for a leaf at depth
    /// `d` along γ with integer position `a` (exact dyadic values), leaf by leaf; `[0, 1]` in
    /// the patch of one pair (a single root along γ, never halved).
    pub fn leaf_gamma_spans(&self) -> Vec<(f64, f64)> {
        if self.is_pair() {
            return vec![(0.0, 1.0); self.leaves()];
        }
        self.leaf_boxes()
            .into_iter()
            .map(|(pos, depth)| {
                let scale = f64::from(depth[0].min(1000) as i32).exp2();
                (pos[0] / scale, (pos[0] + 1.0) / scale)
            })
            .collect()
    }

    /// The position of every leaf's box along each axis of the tree (`γ`, `c`, `e_n`; `c`, `e_n`
    /// in the patch of one pair), in root-cell units: leaf `L` spans
    /// `[pos[k], pos[k] + 1] / 2^depth[k]` root cells along axis `k`, the root cell included in
    /// `pos` (`pos = root·2^depth + offset`), following the `split` masks. Exact: dyadic values.
    pub fn leaf_boxes(&self) -> Vec<([f64; 3], [u32; 3])> {
        let dims = self.dims() as usize;
        let blocks: Vec<usize> = (0..dims).map(|k| self.axis_blocks(k)).collect();
        let tree = self.tree();
        let mut boxes = vec![([0.0; 3], [0u32; 3]); self.leaves()];
        let mut stack: Vec<(usize, [f64; 3], [u32; 3])> = (0..self.roots())
            .map(|r| {
                let mut pos = [0.0; 3];
                let mut rest = r;
                for k in (0..dims).rev() {
                    pos[k] = (rest % blocks[k]) as f64;
                    rest /= blocks[k];
                }
                (r, pos, [0; 3])
            })
            .collect();
        while let Some((cell, pos, depth)) = stack.pop() {
            let t = tree[cell];
            if t < 0 {
                boxes[(-(t as i64) - 1) as usize] = (pos, depth);
                continue;
            }
            let mask = self.split_mask(cell);
            let halved: Vec<usize> = (0..dims)
                .filter(|&k| mask >> (dims - 1 - k) & 1 == 1)
                .collect();
            for q in 0..1usize << halved.len() {
                let (mut p, mut d) = (pos, depth);
                for (j, &k) in halved.iter().enumerate() {
                    let bit = (q >> (halved.len() - 1 - j)) & 1;
                    p[k] = 2.0 * p[k] + bit as f64;
                    d[k] += 1;
                }
                stack.push((t as usize + q, p, d));
            }
        }
        boxes
    }

    /// The patch's warp if it applies at `γ`: the patch has one and `v = x·blocks_gamma`
    /// (clamped, as [`locate`] computes it) is at or beyond its `start`.
    #[inline]
    pub fn warp_at(&self, gamma: f64) -> Option<&Warp> {
        let w = self.warp.as_ref()?;
        let xg = self.x_gamma(gamma);
        let bg = self.blocks_gamma() as f64;
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
        match self.restitution() {
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
