//! The table of one pair of materials: `domain.gamma` in a config builds `P(α, e_n)` at that
//! single γ (schema 4, axes `alpha,e_n`). `sweep run` builds it, the library answers that γ
//! only (within 1e-9, relative) and within the stated bound of independent simulations, every
//! query path (single, batch, curve, rebound) gives the rule's answer, and bad configs and
//! edited files are refused by name.

mod common;
use common::{sweep_ok as ok, sweep_refused as refused};

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use oblique_lookup::{OutOfDomain, Table};
use oblique_table::surface::PatchId;

/// γ of an alumina-96 sphere on a soda-lime-glass wall (`sweep gamma`).
const GAMMA: f64 = 1.7497858600774299;

const DOMAIN: &str = "[domain]\ngamma = 1.7497858600774299\ne_n_min = 0.6\ne_n_max = 1.0\n";
const REST: &str = "[nodes]\ntarget_error = 1e-4\nleaf_intervals = 6\nblocks_coord = 2\n\
                    [solver]\ntol = 1e-5\n[checks]\nper_patch = 40\n";

/// The small pair table (built once per test process, about a second).
fn table() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| common::build_table("pair", "pair", &format!("{DOMAIN}{REST}")))
}

fn t() -> &'static str {
    table().to_str().expect("path")
}

#[test]
fn the_table_has_the_axes_alpha_e_n_at_one_gamma() {
    let table = Table::open(table()).expect("open");
    let s = table.surface();
    assert_eq!(s.pair_gamma(), Some(GAMMA));
    assert_eq!(s.restitution(), Some((0.6, 1.0)));
    let names: Vec<&str> = s.axes().iter().map(|a| a.name.name()).collect();
    assert_eq!(names, ["alpha", "e_n"]);
    for id in [PatchId::PartialHigh, PatchId::StickHigh] {
        let p = s.patch_by_id(id).expect("patch");
        assert!(p.is_pair());
        assert_eq!(p.dims(), 2);
        assert_eq!(p.leaf_size(), 7 * 7, "one node along gamma");
    }
    assert!(s.patch_by_id(PatchId::StickLow).is_none());
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["inspect", t(), "--json"])).expect("JSON");
    assert_eq!(json["axes"], serde_json::json!(["alpha", "e_n"]), "{json}");
}

/// The answers against direct simulations (the solver, not the table) at random `(α, e_n)`,
/// none above the stated bound, and the full-slip line exactly.
#[test]
fn answers_hold_the_stated_bound_against_simulations() {
    let table = Table::open(table()).expect("open");
    let bound = table.error_bound();
    assert!(bound > 0.0 && bound <= 2e-4, "bound {bound}");
    let mut next = oblique_lookup::testing::uniform(7);
    let mut worst = 0.0f64;
    for i in 0..40 {
        let s = next();
        let alpha = if i == 0 { f64::INFINITY } else { s / (1.0 - s) };
        let e_n = 0.6 + 0.4 * next();
        let p = table.p_e(GAMMA, alpha, e_n).expect("inside");
        let sim = oblique_solver::Request::new(GAMMA, alpha)
            .e_n(e_n)
            .law(oblique_solver::Law::KelvinVoigt)
            .accuracy(oblique_solver::Accuracy::Tolerance(1e-7))
            .solve()
            .expect("simulate");
        worst = worst.max((p - sim.p).abs());
    }
    assert!(worst <= bound, "max error {worst} above the bound {bound}");
    let a1 = oblique_table::surface::alpha_c1_dissipative(GAMMA, 0.8);
    let line = table.p_e(GAMMA, 0.5 * a1, 0.8).expect("line");
    assert_eq!(line, 1.0 - 3.5 * 1.8 * (0.5 * a1));
    // The line is exact at any γ, as in every table.
    assert_eq!(
        table.p_e(3.0, 0.01, 0.8).expect("line"),
        1.0 - 3.5 * 1.8 * 0.01
    );
}

/// The pair's γ within 1e-9 (relative) is the pair's, to the bit; further off is refused
/// naming γ and the pair's value, or answered at the pair's γ when clamping.
#[test]
fn only_the_pairs_gamma_is_answered() {
    let table = Table::open(table()).expect("open");
    let at = table.p_e(GAMMA, 0.5, 0.8).expect("the pair");
    let near = GAMMA * (1.0 + 5e-10);
    assert_eq!(
        table.p_e(near, 0.5, 0.8).expect("near").to_bits(),
        at.to_bits()
    );
    let e = table
        .p_e(GAMMA * (1.0 + 1e-6), 0.5, 0.8)
        .expect_err("another pair");
    let msg = e.to_string();
    assert!(
        msg.contains("gamma") && msg.contains("1.7497858600774299"),
        "{msg}"
    );
    assert!(msg.contains("one pair"), "{msg}");
    let clamped = table
        .p_e_with(1.9, 0.5, 0.8, OutOfDomain::Clamp)
        .expect("clamped");
    assert_eq!(clamped.to_bits(), at.to_bits());
    refused(
        &[
            "query",
            t(),
            "--gamma",
            "1.75",
            "--alpha",
            "0.5",
            "--e-n",
            "0.8",
        ],
        &["gamma", "1.7497858600774299", "one pair"],
    );
    refused(
        &[
            "query",
            t(),
            "--gamma",
            "1.7497858600774299",
            "--alpha",
            "0.5",
            "--e-n",
            "0.5",
        ],
        &["e_n", "0.6"],
    );
}

/// Batches, curves at fixed `e_n` and rebounds (from γ or from the materials) give what
/// `Table::p_e` gives.
#[test]
fn every_query_path_gives_the_rule() {
    use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
    use oblique_lookup::{Contact, Prepared};
    let table = Table::open(table()).expect("open");
    let mut next = oblique_lookup::testing::uniform(11);
    let n = 5000;
    let alpha: Vec<f64> = (0..n)
        .map(|i| {
            if i % 13 == 0 {
                f64::INFINITY
            } else {
                10f64.powf(-2.0 + 3.0 * next())
            }
        })
        .collect();
    let e_n: Vec<f64> = (0..n).map(|_| 0.6 + 0.4 * next()).collect();
    let gamma = vec![GAMMA; n];
    let mut out = vec![0.0; n];
    table
        .p_e_batch(&gamma, &alpha, &e_n, &mut out, OutOfDomain::Error)
        .expect("batch");
    for i in 0..n {
        let one = table.p_e(GAMMA, alpha[i], e_n[i]).expect("single");
        assert_eq!(out[i].to_bits(), one.to_bits(), "batch {i}");
    }
    for e in [0.6, 0.77, 1.0] {
        let curve = table.curve_e(GAMMA, e, OutOfDomain::Error).expect("curve");
        for &a in alpha.iter().take(500) {
            let want = table.p_e(GAMMA, a, e).expect("single");
            let got = curve.p(a).expect("curve");
            assert!(
                (got - want).abs() <= 1e-13,
                "e_n {e}, alpha {a}: {got} vs {want}"
            );
        }
    }
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: None,
    };
    let catalogue = |name: &str| {
        oblique_physics::materials::find(name)
            .expect("catalogue")
            .elastic()
    };
    let from_materials =
        Contact::with_materials(catalogue("alumina-96"), catalogue("soda-lime-glass"), 0.3);
    for contact in [Contact::with_gamma(GAMMA, 0.3), from_materials] {
        let contact = contact.with_restitution(0.8);
        let inc = Incident3 {
            sphere: Motion3 {
                velocity: [0.5, -0.2, 1.3],
                spin: [30.0, -80.0, 5.0],
            },
            other: Motion3::default(),
            normal: [0.0, 0.0, 1.0],
        };
        let steps = table.rebound_3d(&pair, &contact, &inc).expect("rebound");
        let prepared = Prepared::new(&pair, &contact).expect("prepared");
        let fast = table
            .rebound_3d_prepared(&prepared, &inc)
            .expect("prepared");
        assert_eq!(fast.rebound.p.to_bits(), steps.rebound.p.to_bits());
        let want = table.p_e(GAMMA, steps.alpha, 0.8).expect("P");
        assert_eq!(steps.rebound.p.to_bits(), want.to_bits());
    }
}

/// `Table::prepare` (C: `oblique_prepare_table`) refuses at once a pair whose `γ` is not the
/// table's (its rebounds would be refused above the full-slip line); with clamping it
/// prepares, and its rebounds answer at the pair's `γ`.
#[test]
fn prepare_refuses_a_pair_of_another_gamma() {
    use oblique_lookup::rebound::{Body, Pair};
    use oblique_lookup::Contact;
    let table = oblique_lookup::Table::open(table()).expect("open");
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: None,
    };
    let near = Contact::with_gamma(GAMMA * (1.0 + 5e-10), 0.3).with_restitution(0.8);
    table
        .prepare(&pair, &near)
        .expect("within the pair's tolerance");
    for off in [GAMMA * (1.0 + 1e-6), 1.2, 2.5] {
        let contact = Contact::with_gamma(off, 0.3).with_restitution(0.8);
        let e = table.prepare(&pair, &contact).expect_err("another gamma");
        assert!(
            matches!(e, oblique_lookup::LookupError::Query { name: "gamma", .. }),
            "{e}"
        );
        assert!(e.to_string().contains("one pair"), "{e}");
        let clamped = Contact {
            outside: OutOfDomain::Clamp,
            ..contact
        };
        table.prepare(&pair, &clamped).expect("clamped");
    }
}

/// `domain.gamma` replaces `gamma_min` and `gamma_max` and needs an `e_n` range; each
/// mistake is refused naming the key.
#[test]
fn bad_pair_configs_are_refused_by_key() {
    let dir = common::subdir("pair-configs");
    let cases = [
        (
            "[domain]\ngamma = 1.75\ngamma_min = 1.7\ne_n_min = 0.6\ne_n_max = 1.0\n",
            &["domain.gamma_min", "absent with domain.gamma"][..],
        ),
        (
            "[domain]\ngamma = 1.75\n",
            &["domain.gamma", "e_n_min and e_n_max"][..],
        ),
        (
            "[domain]\ngamma = -1\ne_n_min = 0.6\ne_n_max = 1.0\n",
            &["domain.gamma", "(0, 64]"][..],
        ),
        (
            "[domain]\ngamma_max = 2\n",
            &["domain.gamma_min", "missing", "domain.gamma alone"][..],
        ),
    ];
    for (i, (domain, needles)) in cases.into_iter().enumerate() {
        let cfg = dir.join(format!("bad{i}.toml"));
        std::fs::write(&cfg, format!("output = \"x.h5\"\n{domain}{REST}")).expect("write");
        refused(&["run", cfg.to_str().expect("path")], needles);
    }
}

/// A pair table whose axes attribute says it spans a range of γ (and the reverse: a range
/// table that says it is one pair) is refused by name, never read with the wrong axes.
#[test]
fn a_pair_table_with_the_wrong_axes_is_refused() {
    let dir = common::subdir("pair-edited");
    for (name, edit) in [
        ("axes.h5", "f.attrs['axes'] = 'gamma,alpha,e_n'"),
        ("edges.h5", "f.attrs['gamma_max'] = 1.76"),
    ] {
        let bad = dir.join(name);
        common::edited_copy(table(), &bad, edit);
        let e = Table::open(&bad).map(|_| ()).expect_err("an edited table");
        assert!(e.to_string().contains("gamma"), "{name}: {e}");
    }
}
