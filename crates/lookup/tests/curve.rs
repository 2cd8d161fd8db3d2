//! `Table::curve`: `P(α)` at a fixed γ agrees with the rule (`Table::p_with`) everywhere on the
//! line, and refuses what the rule refuses.

use oblique_lookup::{LookupError, OutOfDomain, Table};
use oblique_table::surface::{alpha_c2, linear_limit};
use oblique_table::surface::{PatchId, PatchKind, Surface};

/// The neighbouring floats of a positive finite `x` (`f64::next_up` is newer than the MSRV).
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

fn down(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

fn table(name: &str) -> Table {
    Table::open(format!(
        "{}/../../tables/{name}",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect(name)
}

/// α values along the line γ: log-spread, ∞, the region edges and their neighbours, and the
/// α of every node position of a fine uniform grid in each patch's coordinate (leaf edges).
fn alphas(t: &Table, gamma: f64) -> Vec<f64> {
    let s = &t.surface();
    let mut out: Vec<f64> = (0..400)
        .map(|i| 10f64.powf(-3.0 + 6.0 * i as f64 / 399.0))
        .collect();
    out.push(f64::INFINITY);
    for edge in [linear_limit(gamma), alpha_c2(gamma)] {
        out.extend([edge, up(edge), down(edge), edge * 1.001, edge / 1.001]);
    }
    let kinds: &[PatchKind] = if gamma > 1.0 {
        &[PatchKind::PartialSlip, PatchKind::Stick]
    } else {
        &[PatchKind::Stick]
    };
    for &kind in kinds {
        for j in 0..=2048 {
            out.push(kind.alpha(gamma, j as f64 / 2048.0, s.alpha_max()));
        }
    }
    out.retain(|a| *a <= s.alpha_max());
    out
}

fn gammas(t: &Table) -> Vec<f64> {
    let s = &t.surface();
    let mut g = vec![
        s.gamma_min(),
        s.gamma_max(),
        0.5 * (s.gamma_min() + s.gamma_max()),
    ];
    if s.gamma_min() <= 1.0 && 1.0 <= s.gamma_max() {
        g.extend([1.0, up(1.0), down(1.0)]);
    }
    // Root and leaf edges along γ (every 1/64 of each patch's root cells) and points between.
    for p in s.patches().map(|(_, p)| p) {
        let steps = p.blocks_gamma() * 64;
        for i in 0..=steps {
            g.push(p.gamma_lo() + (p.gamma_hi() - p.gamma_lo()) * i as f64 / steps as f64);
        }
        for i in 0..13 {
            g.push(p.gamma_lo() + (p.gamma_hi() - p.gamma_lo()) * (i as f64 + 0.37) / 13.0);
        }
    }
    g.retain(|x| *x >= s.gamma_min() && *x <= s.gamma_max());
    g
}

#[test]
fn the_curve_answers_what_the_rule_answers() {
    for name in ["quick.h5", "isotropic.h5", "full.h5"] {
        let t = table(name);
        let mut worst = 0.0_f64;
        let mut count = 0;
        for gamma in gammas(&t) {
            let curve = t.curve(gamma, OutOfDomain::Error).expect("curve");
            assert_eq!(curve.gamma(), gamma);
            for alpha in alphas(&t, gamma) {
                let want = t.p(gamma, alpha).expect("rule");
                let got = curve.p(alpha).expect("curve");
                let d = (got - want).abs();
                assert!(
                    d <= 1e-14,
                    "{name}: gamma {gamma}, alpha {alpha}: curve {got} rule {want} ({d:e})"
                );
                worst = worst.max(d);
                count += 1;
            }
        }
        eprintln!("{name}: {count} points, max |curve - rule| = {worst:e}");
    }
}

#[test]
fn the_curve_refuses_what_the_rule_refuses() {
    let t = table("quick.h5");
    let s = &t.surface();
    for bad in [
        f64::NAN,
        -1.0,
        0.0,
        f64::INFINITY,
        s.gamma_max() * 1.01,
        s.gamma_min() * 0.99,
    ] {
        let err = t.curve(bad, OutOfDomain::Error).expect_err("refused");
        assert!(
            matches!(err, LookupError::Query { name: "gamma", .. }),
            "{err}"
        );
    }
    // Clamping: the curve sits at the domain's edge and answers what the rule answers there.
    let clamped = t
        .curve(s.gamma_max() * 2.0, OutOfDomain::Clamp)
        .expect("clamped");
    assert_eq!(clamped.gamma(), s.gamma_max());
    let edge = t.curve(s.gamma_max(), OutOfDomain::Error).expect("edge");
    assert_eq!(clamped.p(1.0).unwrap(), edge.p(1.0).unwrap());
    assert_eq!(clamped.requested_gamma(), s.gamma_max() * 2.0);
    // Outside the domain on either side, with clamping: the rule's line test at the requested
    // γ first, then the value at the clamped γ.
    for gamma in [s.gamma_min() * 0.6, s.gamma_max() * 1.4] {
        let curve = t.curve(gamma, OutOfDomain::Clamp).expect("clamped");
        for alpha in alphas(&t, gamma)
            .into_iter()
            .chain(alphas(&t, curve.gamma()))
        {
            let want = t.p_with(gamma, alpha, OutOfDomain::Clamp).expect("rule");
            let got = curve.p(alpha).expect("curve");
            assert!(
                (got - want).abs() <= 1e-14,
                "gamma {gamma} alpha {alpha}: {got} {want}"
            );
        }
    }
    // Along a line a non-cubic stencil is not a cubic: such a table has no curves.
    let quick = table("quick.h5");
    let s = quick.surface();
    let patches = PatchId::ALL.map(|id| s.patch_by_id(id).cloned());
    let six_points = Surface::new(s.gamma_min(), s.gamma_max(), s.alpha_max(), 6, patches)
        .expect("a 6-point stencil fits the leaf grids of quick.h5");
    let six = Table::from_parts(
        six_points,
        quick.provenance().clone(),
        quick.checks().to_vec(),
        quick.error_bound(),
    );
    let err = six.curve(1.754, OutOfDomain::Error).expect_err("stencil 6");
    assert!(
        matches!(
            err,
            LookupError::Query {
                name: "table stencil_points",
                ..
            }
        ),
        "{err}"
    );
    let curve = t.curve(1.754, OutOfDomain::Error).expect("curve");
    for bad in [f64::NAN, -1e-300, -1.0, f64::NEG_INFINITY] {
        let err = curve.p(bad).expect_err("refused");
        assert!(
            matches!(err, LookupError::Query { name: "alpha", .. }),
            "{err}"
        );
    }
    let mut out = vec![0.0; 3];
    let err = curve.p_batch(&[0.1, 1.0], &mut out).expect_err("lengths");
    assert!(
        matches!(
            err,
            LookupError::Length {
                name: "out",
                len: 3,
                expected: 2
            }
        ),
        "{err}"
    );
    let err = curve
        .p_batch(&[0.1, f64::NAN, 1.0], &mut out)
        .expect_err("NaN");
    assert!(matches!(err, LookupError::Batch { index: 1, .. }), "{err}");
    curve
        .p_batch(&[0.1, 1.0, f64::INFINITY], &mut out)
        .expect("batch");
    for (o, a) in out.iter().zip([0.1, 1.0, f64::INFINITY]) {
        assert_eq!(*o, curve.p(a).unwrap());
    }
}
