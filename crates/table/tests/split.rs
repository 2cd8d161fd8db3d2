//! Trees whose cells halve only some axes (the `split` dataset of a patch with an `e_n` axis):
//! the masks are checked, the rule descends them, and the fine index finds the same leaves.

use oblique_table::indexed::IndexedPatch;
use oblique_table::surface::{check_split, Axis, Patch, PatchData, PatchKind};

const M: usize = 6;

/// A polynomial of degree 3 per axis in the patch's coordinates `(x_γ, c, x_e)`: the cubic
/// stencil reproduces it exactly on any leaf, so every answer is known.
fn poly(x: [f64; 3]) -> f64 {
    let [g, c, e] = x;
    0.1 + 0.2 * g - 0.15 * c * c * c + 0.1 * e * e + 0.05 * g * c * e - 0.08 * g * g * g * e
}

/// A stick patch over γ ∈ [1.5, 2.5], e_n ∈ [0.5, 1], one root cell, with the tree
/// `tree`/`split`; the leaves' boxes (in the patch's coordinates) in leaf order.
fn patch(tree: Vec<i32>, split: Vec<u8>, boxes: &[[(f64, f64); 3]]) -> Result<Patch, String> {
    let n1 = M + 1;
    let mut p = Vec::new();
    for b in boxes {
        for i in 0..n1 {
            for j in 0..n1 {
                for l in 0..n1 {
                    let at = |(lo, hi): (f64, f64), k: usize| lo + (hi - lo) * k as f64 / M as f64;
                    p.push(poly([at(b[0], i), at(b[1], j), at(b[2], l)]));
                }
            }
        }
    }
    let err = vec![0.0; p.len()];
    Patch::new(
        PatchKind::Stick,
        vec![
            Axis::gamma(1.5, 2.5, 1),
            Axis::coord(1),
            Axis::restitution(0.5, 1.0, 1)?,
        ],
        PatchData {
            leaf_intervals: M,
            tree,
            split: Some(split),
            p,
            error_estimate: err,
            warp: None,
            knots: None,
        },
    )
}

/// Root halved along `c` (mask 2): two leaves; its upper half halved along γ and `e_n`
/// (mask 5): four leaves, `2·q_γ + q_e`.
fn two_level() -> Patch {
    let tree = vec![1, -1, 3, -2, -3, -4, -5];
    let split = vec![2, 0, 5, 0, 0, 0, 0];
    let (lo, hi) = ((0.0, 0.5), (0.5, 1.0));
    let all = (0.0, 1.0);
    let boxes = [
        [all, lo, all],
        [lo, hi, lo],
        [lo, hi, hi],
        [hi, hi, lo],
        [hi, hi, hi],
    ];
    patch(tree, split, &boxes).expect("a valid patch")
}

#[test]
fn the_rule_descends_the_halved_axes_only() {
    let patch = two_level();
    assert_eq!(patch.leaf_depths(), vec![1, 2, 2, 2, 2]);
    let indexed = IndexedPatch::<3>::new(&patch, 1 << 15).expect("an index");
    let mut s = 0x2545_F491_4F6C_DD1Du64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20_000 {
        let x = [next(), next(), next()];
        let (gamma, e_n) = (1.5 + x[0], 0.5 + 0.5 * x[2]);
        let rule = patch.interpolate_at(gamma, x[1], e_n, 4);
        assert!(
            (rule - poly(x)).abs() < 1e-13,
            "{x:?}: {rule} vs {}",
            poly(x)
        );
        let fast = indexed.interpolate([gamma, x[1], e_n]);
        assert_eq!(fast.to_bits(), rule.to_bits(), "{x:?}");
        // The line through the point (`Patch::line`) gives the same bits.
        let line = patch.line(gamma, e_n).expect("a line");
        assert_eq!(line.interpolate(x[1]).to_bits(), rule.to_bits(), "{x:?}");
    }
    // The line γ = 1.7 crosses one halving of c.
    assert_eq!(patch.line_depth(1.7, 0.8), 1);
}

#[test]
fn the_index_depth_per_axis_stays_within_its_budget() {
    let patch = two_level();
    // 8 entries at most: the deepest axes are given up first; the descent finds the rest.
    let indexed = IndexedPatch::<3>::new(&patch, 8).expect("an index");
    assert!(
        indexed.shape().iter().product::<usize>() <= 8,
        "{:?}",
        indexed.shape()
    );
    for x in [[0.1, 0.7, 0.9], [0.9, 0.6, 0.2], [0.3, 0.2, 0.4]] {
        let (gamma, e_n) = (1.5 + x[0], 0.5 + 0.5 * x[2]);
        assert_eq!(
            indexed.interpolate([gamma, x[1], e_n]).to_bits(),
            patch.interpolate_at(gamma, x[1], e_n, 4).to_bits()
        );
    }
}

#[test]
fn bad_masks_are_refused_naming_the_dataset() {
    let tree = vec![1, -1, 3, -2, -3, -4, -5];
    for (split, needle) in [
        (vec![2, 0, 5, 0, 0, 0], "6 masks"),    // one short
        (vec![0, 0, 5, 0, 0, 0, 0], "[0] = 0"), // a split cell without axes
        (vec![2, 1, 5, 0, 0, 0, 0], "[1] = 1"), // a mask on a leaf
        (vec![8, 0, 5, 0, 0, 0, 0], "[0] = 8"), // no such axis
        (vec![7, 0, 5, 0, 0, 0, 0], "children of its split cells"), // 8 children, 6 cells after
    ] {
        let e = check_split(&tree, &split, 3)
            .err()
            .or_else(|| two_level_with(&tree, split.clone()).err())
            .unwrap_or_else(|| panic!("{split:?} accepted"));
        assert!(e.contains(needle), "{split:?}: {e}");
    }
    assert!(check_split(&[-1], &[0], 4)
        .expect_err("4 axes")
        .contains("2 or 3 axes"));
    // A tree over two axes ((c, e_n) of one pair, or (γ, c) without an e_n axis): masks 1 to 3.
    assert!(check_split(&[1, -1, -2], &[1, 0, 0], 2).is_ok());
    assert!(check_split(&[1, -1, -2], &[4, 0, 0], 2)
        .expect_err("a gamma bit in a pair patch")
        .contains("[0] = 4"));
}

fn two_level_with(tree: &[i32], split: Vec<u8>) -> Result<Patch, String> {
    let all = (0.0, 1.0);
    patch(tree.to_vec(), split, &[[all, all, all]; 5])
}
