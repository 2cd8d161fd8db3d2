//! `|P| ≤ 1` on every read path (step 10 of the rule in `docs/table-format.md`): the rule
//! (`Surface::eval`), the fast path (`Table::p`), the batch path (`Table::p_batch`,
//! `p_batch_par`), per-γ curves (the C ABI: `crates/lookup-capi/tests/energy.rs`), on 1e6 random
//! queries each of the shipped `tables/full.h5` (γ ∈ [0.1, 3.5], α ∈ [0, 20]) with the point
//! where it answered P = −1.000008644, and on a copy of it whose node values are noise next to
//! ±1, so that the tensor product overshoots everywhere (checked) and only the bound keeps
//! `|P| ≤ 1`.

use oblique_lookup::{OutOfDomain, Table};

const FULL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tables/full.h5");

/// Where the table of before the bound answered P = −1.000008644 (simulation: −0.999998276).
const OVERSHOOT: (f64, f64) = (2.829218718427729, 5.60402202817959);

const QUERIES: usize = 1_000_000;

/// `n` queries uniform in γ ∈ [0.1, 3.5], α ∈ [0, 20], after the overshooting point.
fn queries(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut next = oblique_lookup::testing::uniform(seed);
    let mut g = vec![OVERSHOOT.0];
    let mut a = vec![OVERSHOOT.1];
    for _ in 1..n {
        g.push(0.1 + 3.4 * next());
        a.push(20.0 * next());
    }
    (g, a)
}

/// The table with every node value replaced by noise in `[−1, −0.9]` (leaves of even number)
/// or `[0.9, 1]` (odd), with exact ±1 at every third node: its tensor product overshoots ±1.
fn noisy(t: Table) -> Table {
    let mut next = oblique_lookup::testing::uniform(99);
    oblique_lookup::testing::overshooting(t, |_| 0.1 * next())
}

fn assert_bounded(what: &str, g: &[f64], a: &[f64], p: &[f64]) {
    let bad = p.iter().position(|x| x.is_nan() || x.abs() > 1.0);
    if let Some(i) = bad {
        panic!("{what}: P({}, {}) = {} (|P| > 1)", g[i], a[i], p[i]);
    }
}

fn every_rust_path(what: &str, t: &Table) {
    let (g, a) = queries(QUERIES, 0x5EED_0001);
    let rule: Vec<f64> = g
        .iter()
        .zip(&a)
        .map(|(&g, &a)| t.surface().eval(g, a).expect("inside"))
        .collect();
    assert_bounded(&format!("{what}: rule"), &g, &a, &rule);
    let fast: Vec<f64> = g
        .iter()
        .zip(&a)
        .map(|(&g, &a)| t.p(g, a).expect("inside"))
        .collect();
    assert_bounded(&format!("{what}: Table::p"), &g, &a, &fast);
    let mut batch = vec![f64::NAN; g.len()];
    t.p_batch(&g, &a, &mut batch, OutOfDomain::Error)
        .expect("batch");
    assert_bounded(&format!("{what}: p_batch"), &g, &a, &batch);
    let mut par = vec![f64::NAN; g.len()];
    t.p_batch_par(&g, &a, &mut par, OutOfDomain::Error)
        .expect("batch");
    assert_bounded(&format!("{what}: p_batch_par"), &g, &a, &par);
    // The paths keep their bits (the bound is applied the same way on each).
    for i in 0..g.len() {
        assert_eq!(fast[i].to_bits(), rule[i].to_bits(), "({}, {})", g[i], a[i]);
        assert_eq!(
            batch[i].to_bits(),
            rule[i].to_bits(),
            "({}, {})",
            g[i],
            a[i]
        );
        assert_eq!(par[i].to_bits(), rule[i].to_bits(), "({}, {})", g[i], a[i]);
    }
    // Curves: 1000 γ (the overshooting one first) × 1000 α.
    let mut next = oblique_lookup::testing::uniform(0x5EED_0002);
    for k in 0..1000 {
        let gamma = if k == 0 {
            OVERSHOOT.0
        } else {
            0.1 + 3.4 * next()
        };
        let curve = t.curve(gamma, OutOfDomain::Error).expect("curve");
        let alpha: Vec<f64> = (0..1000)
            .map(|j| {
                if k == 0 && j == 0 {
                    OVERSHOOT.1
                } else {
                    20.0 * next()
                }
            })
            .collect();
        let mut out = vec![f64::NAN; alpha.len()];
        curve.p_batch(&alpha, &mut out).expect("curve batch");
        assert_bounded(&format!("{what}: curve"), &vec![gamma; 1000], &alpha, &out);
    }
}

#[test]
fn the_shipped_table_answers_no_p_beyond_one_on_any_path() {
    let t = Table::open(FULL).expect("full.h5");
    let p = t.p(OVERSHOOT.0, OVERSHOOT.1).expect("inside");
    assert!(p >= -1.0, "P = {p} at the point that overshot");
    every_rust_path("full.h5", &t);
}

#[test]
fn the_bound_holds_where_the_tensor_product_overshoots() {
    let t = noisy(Table::open(FULL).expect("full.h5"));
    // The test has teeth: without step 10 the rule overshoots at many of these points.
    let (g, a) = queries(100_000, 0x5EED_0003);
    let over = g
        .iter()
        .zip(&a)
        .filter(|&(&g, &a)| {
            let region = oblique_table::surface::Region::of(g, a);
            let Some(patch) = t.surface().patch(region) else {
                return false;
            };
            let c = patch
                .kind()
                .coord(g, a, t.surface().alpha_max())
                .clamp(0.0, 1.0);
            let c = patch.warped(g, c);
            patch.tensor(g, c, t.surface().stencil()).abs() > 1.0
        })
        .count();
    assert!(over > 1_000, "only {over} overshooting points");
    every_rust_path("noisy copy of full.h5", &t);
}
