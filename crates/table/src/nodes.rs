//! Where a patch's tree puts its nodes, and the check of the node coordinates a file stores
//! (`gamma`, `coord`, `e_n`, `alpha`; `docs/table-format.md`) against them.
//!
//! The rule reads only the tree, the axis attributes (`gamma_lo`, `gamma_hi`, `blocks_*`,
//! `e_n_min`, `e_n_max`) and `P`; the stored coordinates are where the builder simulated each
//! value. A file whose attributes were edited after the build (an `e_n` range moved, a γ edge
//! shifted) would answer every query with values from other places: the check refuses it.

use crate::format::E_N;
use crate::surface::{AxisMap, Patch};

/// Relative tolerance of a stored coordinate, as a share of its axis's span: far above the
/// rounding of the builder's and this module's arithmetic (a few ulps), far below any
/// displacement that changes an answer by the tables' errors.
pub const POSITION_TOL: f64 = 1e-9;

/// The stored node coordinates of one patch, each in the layout of [`Patch::p`].
#[derive(Debug, Clone, Copy)]
pub struct StoredNodes<'a> {
    /// γ of every node.
    pub gamma: &'a [f64],
    /// Tree coordinate `c` (`c'` in a warped row) of every node.
    pub coord: &'a [f64],
    /// α of every node (`≥ 0`, `∞` allowed).
    pub alpha: &'a [f64],
    /// `e_n` of every node (a patch with an `e_n` axis only).
    pub e_n: Option<&'a [f64]>,
}

/// Check the stored node coordinates of `patch` (named `name` in messages) against the
/// positions its tree and axis attributes give: every node's γ, `c` and `e_n` within
/// [`POSITION_TOL`] of its axis's span, every α a number `≥ 0` (`∞` allowed). `Err` names the
/// first dataset and node that disagree, and what was expected there.
pub fn check_positions(name: &str, patch: &Patch, stored: StoredNodes<'_>) -> Result<(), String> {
    let size = patch.leaf_size();
    let total = patch.p().len();
    let lens = [
        ("gamma", Some(stored.gamma.len())),
        ("coord", Some(stored.coord.len())),
        ("alpha", Some(stored.alpha.len())),
        (E_N.name, stored.e_n.map(<[f64]>::len)),
    ];
    for (ds, len) in lens {
        if let Some(len) = len {
            if len != total {
                return Err(format!(
                    "patch '{name}': dataset '{ds}' has {len} values for {total} nodes"
                ));
            }
        }
    }
    if patch.restitution().is_some() != stored.e_n.is_some() {
        let e = E_N.name;
        return Err(format!(
            "patch '{name}': dataset '{e}' {}",
            if stored.e_n.is_some() {
                format!("present in a patch without an {e} axis")
            } else {
                format!("missing (the patch has an {e} axis)")
            }
        ));
    }
    if let Some(i) = stored.alpha.iter().position(|a| a.is_nan() || *a < 0.0) {
        return Err(format!(
            "patch '{name}': alpha[{i}] = {}: node alphas must be >= 0 (inf allowed)",
            stored.alpha[i]
        ));
    }
    let dims = patch.dims() as usize;
    let m = patch.leaf_intervals();
    let n1 = m + 1;
    // The dataset, value range and root cells of each tree axis: (name, values, lo, span,
    // blocks, map).
    type AxisData<'a> = (&'a str, &'a [f64], f64, f64, f64, AxisMap);
    let axis_data: Vec<AxisData> = (0..dims)
        .map(|k| {
            let (lo, width, blocks) = patch.axis(k);
            let map = patch.axis_map(k);
            let ds = match (patch.is_pair(), k) {
                (false, 0) => ("gamma", stored.gamma),
                (false, 1) | (true, 0) => ("coord", stored.coord),
                _ => (E_N.name, stored.e_n.unwrap_or(&[])),
            };
            (ds.0, ds.1, lo, width, blocks as f64, map)
        })
        .collect();
    let boxes = patch.leaf_boxes();
    for (leaf, (pos, depth)) in boxes.iter().enumerate() {
        // Root cells per unit of the axis coordinate at this leaf's depth, per axis.
        let mut scale = [1.0; 3];
        for (k, &(.., blocks, _)) in axis_data.iter().enumerate() {
            scale[k] = blocks * f64::from(depth[k].min(1000) as i32).exp2();
        }
        for node in 0..size {
            let at = leaf * size + node;
            // Node index along axis k: digit k of `node` in base m + 1, axis 0 outermost.
            let mut rest = node;
            let mut idx = [0usize; 3];
            for k in (0..dims).rev() {
                idx[k] = rest % n1;
                rest /= n1;
            }
            for (k, &(ds, values, lo, span, _, map)) in axis_data.iter().enumerate() {
                let x = (pos[k] + idx[k] as f64 / m as f64) / scale[k];
                // Compared in the axis's mapped values (the values themselves when linear).
                let want = lo + span * x;
                let got = values[at];
                let off = (map.forward(got) - want).abs();
                let want = map.inverse(want);
                if off.is_nan() || off > POSITION_TOL * span.abs() {
                    return Err(format!(
                        "patch '{name}': {ds}[{at}] = {got} where the tree and the axis \
                         attributes put the node at {want} (leaf {leaf}): the attributes do not \
                         describe the stored nodes"
                    ));
                }
            }
            if patch.is_pair() {
                let got = stored.gamma[at];
                if got != patch.gamma_lo() {
                    return Err(format!(
                        "patch '{name}': gamma[{at}] = {got}, the pair's gamma is {}",
                        patch.gamma_lo()
                    ));
                }
            }
        }
    }
    Ok(())
}
