//! The point API ([`Table::axes`], [`Table::p_at`], [`Table::curve_at`], columns named by their
//! axis) answers the same bits as the named functions (`p`, `p_e`, `curve`, `curve_e`) on every
//! shipped table, and a point of the wrong length is an error naming the table's axes.

use oblique_lookup::columns::{Column, ColumnError, PointColumns};
use oblique_lookup::{LookupError, OutOfDomain, Table};

fn open(name: &str) -> Table {
    let path = format!("{}/../../tables/{name}", env!("CARGO_MANIFEST_DIR"));
    Table::open(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A deterministic generator of numbers in `[0, 1)`.
fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Points `(γ, α, e_n)` over the table's domain (γ a little beyond it, α log-uniform in
/// `[1e-3, 10]` and some `∞`, `e_n` in its range or 1).
fn points(t: &Table, n: usize, seed: u64) -> Vec<[f64; 3]> {
    let s = t.surface();
    let (g0, g1) = (s.gamma_min(), s.gamma_max());
    let (e0, e1) = t.restitution().unwrap_or((1.0, 1.0));
    let mut r = rng(seed);
    (0..n)
        .map(|i| {
            let g = g0 + (g1 - g0) * (1.1 * r() - 0.05);
            let a = if i % 17 == 0 {
                f64::INFINITY
            } else {
                10f64.powf(-3.0 + 4.0 * r())
            };
            [g, a, e0 + (e1 - e0) * r()]
        })
        .collect()
}

fn same(a: &Result<f64, LookupError>, b: &Result<f64, LookupError>) -> bool {
    match (a, b) {
        (Ok(x), Ok(y)) => x.to_bits() == y.to_bits(),
        (Err(x), Err(y)) => x.to_string() == y.to_string(),
        _ => false,
    }
}

#[test]
fn p_at_equals_the_named_functions_bit_for_bit() {
    for name in ["default.h5", "full.h5", "quick.h5", "dissipative-pair.h5"] {
        let t = open(name);
        let has_e = t.restitution().is_some();
        assert_eq!(
            t.axes(),
            if has_e {
                vec!["gamma", "alpha", "e_n"]
            } else {
                vec!["gamma", "alpha"]
            },
            "{name}"
        );
        for outside in [OutOfDomain::Error, OutOfDomain::Clamp] {
            for [g, a, e] in points(&t, 4000, 7) {
                let (at, named) = if has_e {
                    (
                        t.p_at_with(&[g, a, e], outside),
                        t.p_e_with(g, a, e, outside),
                    )
                } else {
                    (t.p_at_with(&[g, a], outside), t.p_with(g, a, outside))
                };
                assert!(
                    same(&at, &named),
                    "{name} ({g}, {a}, {e}): {at:?} {named:?}"
                );
            }
        }
        // Curves: `curve_at` with the extra axes as a slice.
        for [g, _, e] in points(&t, 20, 11) {
            let extra: &[f64] = if has_e { &[e] } else { &[] };
            let c = t.curve_at(g, extra, OutOfDomain::Clamp);
            let d = if has_e {
                t.curve_e(g, e, OutOfDomain::Clamp)
            } else {
                t.curve(g, OutOfDomain::Clamp)
            };
            match (c, d) {
                (Ok(c), Ok(d)) => {
                    for [_, a, _] in points(&t, 50, 3) {
                        assert!(same(&c.p(a), &d.p(a)), "{name} curve at {g}, {a}");
                    }
                }
                (Err(c), Err(d)) => assert_eq!(c.to_string(), d.to_string()),
                (c, d) => panic!("{name}: {c:?} {d:?}"),
            }
        }
    }
}

#[test]
fn a_point_of_the_wrong_length_names_the_axes() {
    let t = open("default.h5");
    for point in [&[1.2][..], &[1.2, 0.3], &[1.2, 0.3, 0.8, 1.0]] {
        let e = t.p_at(point).expect_err("wrong length");
        assert!(matches!(e, LookupError::Point { .. }), "{e:?}");
        let m = e.to_string();
        assert!(
            m.contains("gamma, alpha, e_n") && m.contains("has 3 values"),
            "{m}"
        );
    }
    let t = open("full.h5");
    let m = t.p_at(&[1.2, 0.3, 1.0]).expect_err("3 values").to_string();
    assert!(m.contains("2 values (gamma, alpha), not 3"), "{m}");
    assert!(t.p_at(&[f64::NAN, 0.3]).is_err());
    let m = t
        .curve_at(1.2, &[0.9], OutOfDomain::Error)
        .expect_err("e_n")
        .to_string();
    assert!(m.contains("(gamma)"), "{m}");
}

#[test]
fn columns_named_by_their_axis_answer_as_the_e_n_column() {
    let t = open("default.h5");
    let pts = points(&t, 5000, 5);
    let g: Vec<f64> = pts.iter().map(|p| p[0]).collect();
    let a: Vec<f64> = pts.iter().map(|p| p[1]).collect();
    let e: Vec<f64> = pts.iter().map(|p| p[2]).collect();
    let (gc, ac, ec) = (
        Column::scalar("gamma", &g),
        Column::scalar("alpha", &a),
        Column::scalar("e_n", &e),
    );
    let mut x = vec![0.0; g.len()];
    let mut y = vec![0.0; g.len()];
    let by_axes = PointColumns::with_axes(gc, ac, &[ec]).expect("columns");
    let named = PointColumns::new(gc, ac, Some(ec)).expect("columns");
    t.p_columns(&by_axes, &mut x, OutOfDomain::Clamp)
        .expect("answers");
    t.p_columns(&named, &mut y, OutOfDomain::Clamp)
        .expect("answers");
    assert!(x.iter().zip(&y).all(|(x, y)| x.to_bits() == y.to_bits()));
    let bad = PointColumns::with_axes(gc, ac, &[Column::scalar("e_t", &e)]);
    assert!(
        matches!(bad, Err(ColumnError::Axis { name: "e_t", .. })),
        "{bad:?}"
    );
    let twice = PointColumns::with_axes(gc, ac, &[ec, ec]);
    assert!(matches!(twice, Err(ColumnError::Axis { .. })), "{twice:?}");
}
