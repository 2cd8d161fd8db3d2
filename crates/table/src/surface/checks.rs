//! Checks of a stored tree: its shape, its split masks, and the axes of a patch.

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
/// cell (bit `dims − 1 − k` for each axis `k` it halves), 0 for a leaf: `dims = 3` over
/// `(γ, c, e_n)`, `dims = 2` over `(c, e_n)` in a patch of one pair or over `(γ, c)` in a
/// patch without an `e_n` axis.
pub fn check_split(tree: &[i32], split: &[u8], dims: u32) -> Result<(), String> {
    if !(2..=3).contains(&dims) {
        return Err(format!(
            "is allowed only in a tree over 2 or 3 axes, not {dims}"
        ));
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
