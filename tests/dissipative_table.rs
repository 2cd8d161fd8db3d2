//! Tables with a normal-restitution axis, end to end through the CLI: `sweep run` builds a
//! small `P(γ, α, e_n)` table (Kelvin–Voigt law, schema 4), `sweep verify` checks its stated
//! bound against direct simulations at random `(γ, α, e_n)`, `sweep query --e-n` answers
//! single points and batches, and every path that cannot answer `e_n < 1` refuses by name.

mod common;
use common::{sweep_ok as ok, sweep_refused as refused};

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

const FULL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/full.h5");

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(args)).expect("JSON")
}

/// The small table (built once per test process, a few seconds on 2 cores).
fn table() -> &'static Path {
    static T: OnceLock<PathBuf> = OnceLock::new();
    T.get_or_init(|| {
        common::build_table(
            "dissipative",
            "kv",
            "[domain]\ngamma_min = 1.3\ngamma_max = 1.6\ne_n_min = 0.7\ne_n_max = 1.0\n\
             [nodes]\ntarget_error = 4e-4\nleaf_intervals = 6\nblocks_coord = 2\n\
             [solver]\ntol = 4e-5\n[checks]\nper_patch = 30\n",
        )
    })
}

fn t() -> &'static str {
    table().to_str().expect("path")
}

#[test]
fn the_table_is_schema_4_with_its_axes_and_law() {
    let text = ok(&["inspect", t(), "--json"]);
    let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(v["schema_version"].as_u64(), Some(4), "{text}");
    let f = hdf5_attrs(table());
    assert!(f.contains("gamma,alpha,e_n"), "{f}");
    assert!(f.contains("kelvin-voigt"), "{f}");
}

/// The root attributes of a table as `h5dump -A` would show them, through the Python reader's
/// h5py (installed by the test command).
fn hdf5_attrs(path: &Path) -> String {
    let out = Command::new("python3")
        .args([
            "-c",
            "import h5py, sys; f = h5py.File(sys.argv[1], 'r'); \
             print({k: str(v) for k, v in f.attrs.items()})",
            path.to_str().expect("path"),
        ])
        .output()
        .expect("python3 with h5py (the test command installs it)");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).to_string()
}

#[test]
fn verify_holds_the_stated_bound_at_random_gamma_alpha_e_n() {
    let text = ok(&[
        "verify",
        t(),
        "--points",
        "60",
        "--seed",
        "3",
        "--quiet",
        "--tol",
        "1e-8",
    ]);
    assert!(text.contains("points above it: 0"), "{text}");
}

/// `nodes.polish_tol` solves again the nodes that hold a leaf's bound up: the same small table
/// with `polish_tol = 4e-6` states at most `target_error + Λ_4³ · 4e-6`, where the unpolished
/// one states more (its node term is up to `Λ_4³ · solver.tol`), the same held-out checks
/// hold, direct simulations stay within the smaller bound, and a polish tolerance not below
/// `solver.tol` is refused by name.
#[test]
fn polished_nodes_lower_the_stated_bound_and_it_holds() {
    const BODY: &str = "[domain]\ngamma_min = 1.3\ngamma_max = 1.6\ne_n_min = 0.7\n\
                        e_n_max = 1.0\n[nodes]\ntarget_error = 4e-4\nleaf_intervals = 6\n\
                        blocks_coord = 2\n[solver]\ntol = 4e-5\n[checks]\nper_patch = 30\n";
    let bound = |path: &Path| -> f64 {
        let v = json(&["inspect", path.to_str().expect("path"), "--json"]);
        v["error_bound"].as_f64().expect("error_bound")
    };
    let limit = 4e-4 + 1.631_1_f64.powi(3) * 4e-6;
    let plain = bound(table());
    assert!(
        plain > limit * 1.05,
        "the unpolished bound {plain:e} is already below {limit:e}"
    );
    let polished = common::build_table(
        "dissipative-polish",
        "kv-polished",
        &BODY.replace(
            "leaf_intervals = 6",
            "leaf_intervals = 6\npolish_tol = 4e-6",
        ),
    );
    let b = bound(&polished);
    assert!(b <= limit, "polished bound {b:e} above {limit:e}");
    let p = polished.to_str().expect("path");
    let text = ok(&[
        "verify", p, "--points", "60", "--seed", "3", "--quiet", "--tol", "1e-8",
    ]);
    assert!(text.contains("points above it: 0"), "{text}");
    let cfg = polished.with_file_name("kv-polish-refused.toml");
    let out = polished.with_file_name("kv-polish-refused.h5");
    let text = format!(
        "output = {:?}\n{}",
        out.display().to_string(),
        BODY.replace(
            "leaf_intervals = 6",
            "leaf_intervals = 6\npolish_tol = 4e-5"
        )
    );
    std::fs::write(&cfg, text).expect("write config");
    refused(&["run", cfg.to_str().expect("path")], &["nodes.polish_tol"]);
}

#[test]
fn query_answers_the_line_exactly_and_the_patches_within_the_bound() {
    // Full slip below alpha_c1(gamma, e_n): 1 - (7/2)(1 + e_n) alpha, exactly.
    let q = json(&[
        "query",
        t(),
        "--gamma",
        "1.4",
        "--alpha",
        "0.05",
        "--e-n",
        "0.8",
        "--json",
    ]);
    assert_eq!(q["P"].as_f64(), Some(1.0 - 3.5 * 1.8 * 0.05));
    assert_eq!(q["error_bound"].as_f64(), Some(0.0));
    // Partial slip, stick and no slip against direct simulations.
    for (g, a, e) in [
        ("1.45", "0.3", "0.75"),
        ("1.35", "0.9", "0.95"),
        ("1.55", "inf", "0.7"),
        ("1.5", "0.25", "1"),
    ] {
        let q = json(&[
            "query",
            t(),
            "--gamma",
            g,
            "--alpha",
            a,
            "--e-n",
            e,
            "--json",
        ]);
        let sim = json(&[
            "impact", "--gamma", g, "--alpha", a, "--e-n", e, "--tol", "1e-8", "--json",
        ]);
        let (p, bound) = (
            q["P"].as_f64().expect("P"),
            q["error_bound"].as_f64().expect("bound"),
        );
        let want = sim["P"].as_f64().expect("P");
        assert!(
            (p - want).abs() <= bound && bound > 0.0,
            "({g}, {a}, {e}): table {p}, simulation {want}, bound {bound}"
        );
    }
    // Without --e-n a table with the axis answers its e_n = 1 slice.
    let q1 = json(&["query", t(), "--gamma", "1.5", "--alpha", "0.25", "--json"]);
    let q2 = json(&[
        "query",
        t(),
        "--gamma",
        "1.5",
        "--alpha",
        "0.25",
        "--e-n",
        "1",
        "--json",
    ]);
    assert_eq!(q1["P"], q2["P"]);
}

#[test]
fn a_batch_with_e_n_gives_the_single_answers() {
    let dir = common::subdir("dissipative-batch");
    let input = dir.join("points.csv");
    std::fs::write(&input, "gamma,alpha,e_n\n1.4,0.3,0.8\n1.5,inf,0.9\n").expect("write");
    let text = ok(&["query", t(), "--batch", input.to_str().expect("path")]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "gamma,alpha,e_n,P,e_t");
    for (line, (g, a, e)) in lines[1..]
        .iter()
        .zip([("1.4", "0.3", "0.8"), ("1.5", "inf", "0.9")])
    {
        let q = json(&[
            "query",
            t(),
            "--gamma",
            g,
            "--alpha",
            a,
            "--e-n",
            e,
            "--json",
        ]);
        let p: f64 = line.split(',').nth(3).expect("P").parse().expect("number");
        assert_eq!(Some(p), q["P"].as_f64(), "{line}");
    }
    // Lines must keep the first line's number of fields.
    std::fs::write(&input, "1.4,0.3,0.8\n1.5,0.3\n").expect("write");
    refused(
        &["query", t(), "--batch", input.to_str().expect("path")],
        &["batch line 2", "gamma,alpha,e_n"],
    );
}

#[test]
fn e_n_outside_a_table_is_refused_by_name() {
    refused(
        &[
            "query",
            t(),
            "--gamma",
            "1.4",
            "--alpha",
            "0.3",
            "--e-n",
            "0.5",
        ],
        &["--e-n", "e_n = 0.5", "[0.7, 1]"],
    );
    refused(
        &[
            "query", FULL, "--gamma", "1.4", "--alpha", "0.3", "--e-n", "0.8",
        ],
        &["--e-n", "elastic"],
    );
}

#[test]
fn the_library_answers_inside_the_e_n_range_only() {
    let table = oblique_lookup::Table::open(table()).expect("open");
    assert_eq!(table.restitution(), Some((0.7, 1.0)));
    let p = table.p_e(1.45, 0.3, 0.75).expect("inside");
    assert!(p.abs() <= 1.0);
    assert!(table.p_e(1.45, 0.3, 0.69).is_err());
    assert!(table.p_e(1.45, 0.3, f64::NAN).is_err());
}

/// A 3-D sphere–sphere rebound at `e_n < 1`: the prepared (fast) path and the step-by-step
/// one agree, the normal relative velocity reverses to `e_n` times its value, and the energy
/// lost has its normal part `(m*/2) v_z0² (1 − e_n²)`; an elastic table refuses the contact.
#[test]
fn rebounds_with_e_n_reverse_the_normal_velocity_by_e_n() {
    use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
    use oblique_lookup::{Contact, Prepared, Table};
    let table = Table::open(table()).expect("open");
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: Some(Body {
            mass: 1.1e-3,
            radius: 4e-3,
            kappa: 0.4,
        }),
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let n = [0.0, 0.0, 1.0];
    for (i, e_n) in [0.72, 0.85, 1.0].into_iter().enumerate() {
        let contact = Contact::with_gamma(1.45, 0.3).with_restitution(e_n);
        let inc = Incident3 {
            sphere: Motion3 {
                velocity: [0.4 + 0.1 * i as f64, -0.2, 1.3],
                spin: [30.0, -80.0, 5.0],
            },
            other: Motion3 {
                velocity: [-0.1, 0.3, -0.4],
                spin: [-20.0, 10.0, 0.0],
            },
            normal: n,
        };
        let steps = table.rebound_3d(&pair, &contact, &inc).expect("steps");
        let prepared = Prepared::new(&pair, &contact).expect("prepared");
        let fast = table.rebound_3d_prepared(&prepared, &inc).expect("fast");
        let r = &fast.rebound;
        assert_eq!(fast.rebound.p.to_bits(), steps.rebound.p.to_bits());
        assert_eq!(r.p, table.p_e(1.45, fast.alpha, e_n).expect("P"));
        let v_before = dot(inc.sphere.velocity, n) - dot(inc.other.velocity, n);
        let other = r.other.expect("sphere 2");
        let v_after = dot(r.sphere.velocity, n) - dot(other.velocity, n);
        assert!(
            (v_after + e_n * v_before).abs() <= 1e-14 * v_before,
            "e_n {e_n}: {v_after} vs {}",
            -e_n * v_before
        );
        for (a, b) in [
            (r.energy_lost, steps.rebound.energy_lost),
            (r.normal_impulse, steps.rebound.normal_impulse),
        ] {
            assert!((a - b).abs() <= 1e-13 * b.abs().max(1e-12), "{a} vs {b}");
        }
        let m_star = 1.0 / (1.0 / 2.4e-4 + 1.0 / 1.1e-3);
        let kinetic = |m: f64, v: [f64; 3], w: [f64; 3], radius: f64| {
            0.5 * m * dot(v, v) + 0.5 * 0.4 * m * radius * radius * dot(w, w)
        };
        let before = kinetic(2.4e-4, inc.sphere.velocity, inc.sphere.spin, 2.5e-3)
            + kinetic(1.1e-3, inc.other.velocity, inc.other.spin, 4e-3);
        let after = kinetic(2.4e-4, r.sphere.velocity, r.sphere.spin, 2.5e-3)
            + kinetic(1.1e-3, other.velocity, other.spin, 4e-3);
        assert!(
            (before - after - r.energy_lost).abs() <= 1e-12 * before,
            "energy balance at e_n {e_n}"
        );
        assert!(r.energy_lost >= 0.5 * m_star * v_before * v_before * (1.0 - e_n * e_n) - 1e-15);
    }
    let elastic = Table::open(FULL).expect("full");
    let contact = Contact::with_gamma(1.45, 0.3).with_restitution(0.8);
    let inc = Incident3 {
        sphere: Motion3 {
            velocity: [0.4, 0.0, 1.0],
            spin: [0.0; 3],
        },
        other: Motion3::default(),
        normal: n,
    };
    let e = elastic
        .rebound_3d(&pair, &contact, &inc)
        .map(|_| ())
        .expect_err("elastic table, e_n = 0.8");
    assert!(e.to_string().contains("e_n"), "{e}");
}

/// The query path (a fine index over `(γ, c, e_n)`) gives the bits of the rule written step
/// by step (`Surface::eval_point`), at random points of the whole domain and beyond it, at the
/// ends of the `e_n` range, on the patch edges, with and without clamping.
#[test]
fn the_indexed_path_gives_the_bits_of_the_rule() {
    use oblique_lookup::{OutOfDomain, Table};
    let table = Table::open(table()).expect("open");
    assert!(
        table.index_bytes() > 0,
        "a table with an e_n axis has its index"
    );
    let s = table.surface();
    let mut next = oblique_lookup::testing::uniform(0x9E37_79B9_7F4A_7C15);
    let mut checked = 0;
    for i in 0..200_000 {
        let gamma = 1.2 + 0.5 * next();
        let alpha = match i % 10 {
            0 => f64::INFINITY,
            1 => oblique_physics::regimes::alpha_c2(gamma),
            _ => 10f64.powf(-2.0 + 3.0 * next()),
        };
        let e_n = match i % 7 {
            0 => 0.7,
            1 => 1.0,
            _ => 0.69 + 0.32 * next(),
        };
        for outside in [OutOfDomain::Error, OutOfDomain::Clamp] {
            let fast = table.p_e_with(gamma, alpha, e_n, outside);
            let rule = s.eval_point(gamma, alpha, e_n, outside);
            match (fast, rule) {
                (Ok(a), Ok(b)) => {
                    assert_eq!(a.to_bits(), b.to_bits(), "({gamma}, {alpha}, {e_n})");
                    checked += 1;
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                (a, b) => panic!("({gamma}, {alpha}, {e_n}): {a:?} vs {b:?}"),
            }
        }
    }
    assert!(checked > 300_000, "{checked} answers compared");
    // Table::p is the e_n = 1 slice.
    for (g, a) in [(1.4, 0.3), (1.55, 2.0), (1.3, f64::INFINITY)] {
        assert_eq!(
            table.p(g, a).expect("inside").to_bits(),
            s.eval_point(g, a, 1.0, OutOfDomain::Error)
                .expect("inside")
                .to_bits()
        );
    }
}

/// A curve at fixed `(γ, e_n)` answers what `Table::p_e` answers (to 1e-14, as the elastic
/// curves do), on the shipped table with an `e_n` axis, also when `γ` is clamped; its `e_n`
/// must be the table's and the prepared rebound's.
#[test]
fn curves_at_fixed_gamma_and_e_n_answer_as_p_e() {
    use oblique_lookup::{OutOfDomain, Table};
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tables/dissipative-demo.h5");
    let table = Table::open(path).expect("demo table");
    let (lo, hi) = table.restitution().expect("an e_n axis");
    let mut worst = 0.0f64;
    let mut count = 0;
    for (gamma, outside) in [
        (1.2, OutOfDomain::Error),
        (1.754, OutOfDomain::Error),
        (1.9999, OutOfDomain::Error),
        (2.3, OutOfDomain::Clamp),
    ] {
        for e_n in [lo, 0.63, 0.8, 0.97, hi] {
            let curve = table.curve_e(gamma, e_n, outside).expect("curve");
            assert_eq!(curve.e_n(), e_n);
            for j in 0..4000 {
                let alpha = if j == 0 {
                    f64::INFINITY
                } else {
                    10f64.powf(-2.5 + 4.0 * j as f64 / 4000.0)
                };
                let want = table.p_e_with(gamma, alpha, e_n, outside).expect("p_e");
                let got = curve.p(alpha).expect("curve p");
                worst = worst.max((got - want).abs());
                count += 1;
            }
        }
    }
    assert!(worst <= 1e-14, "worst {worst:e} over {count} points");
    // Outside the range, and an elastic table, refuse e_n by name.
    let e = table
        .curve_e(1.754, 0.4, OutOfDomain::Error)
        .map(|_| ())
        .expect_err("e_n below the range");
    assert!(e.to_string().contains("e_n"), "{e}");
    let full = Table::open(FULL).expect("full");
    assert!(full.curve_e(1.754, 0.8, OutOfDomain::Error).is_err());
    assert!(full.curve_e(1.754, 1.0, OutOfDomain::Error).is_ok());
    // A prepared pair's rebound through its curve: the curve's e_n must be the contact's.
    use oblique_lookup::rebound::{Body, Incident3, Motion3, Pair};
    use oblique_lookup::{Contact, Prepared};
    let pair = Pair {
        sphere: Body {
            mass: 2.4e-4,
            radius: 2.5e-3,
            kappa: 0.4,
        },
        other: None,
    };
    let contact = Contact::with_gamma(1.754, 0.25).with_restitution(0.8);
    let prepared = Prepared::new(&pair, &contact).expect("prepared");
    let inc = Incident3 {
        sphere: Motion3 {
            velocity: [0.7, 0.1, 1.2],
            spin: [10.0, 40.0, 0.0],
        },
        other: Motion3::default(),
        normal: [0.0, 0.0, 1.0],
    };
    let direct = table.rebound_3d_prepared(&prepared, &inc).expect("direct");
    let curve = table
        .curve_e(1.754, 0.8, OutOfDomain::Error)
        .expect("curve");
    let via = table
        .rebound_3d_curve(&prepared, &curve, &inc)
        .expect("via the curve");
    assert!((via.rebound.p - direct.rebound.p).abs() <= 1e-14);
    let elastic_curve = table.curve(1.754, OutOfDomain::Error).expect("e_n = 1");
    let e = table
        .rebound_3d_curve(&prepared, &elastic_curve, &inc)
        .map(|_| ())
        .expect_err("a curve of e_n = 1 for a contact of e_n = 0.8");
    assert!(e.to_string().contains("e_n = 0.8"), "{e}");
}

/// A copy of the test table named `name` in folder `dir`, changed by the Python (h5py) statement
/// `edit` (with `f` the file open for writing) and sealed again: both the library and the
/// reference reader must refuse it, naming `needle`.
fn edited_copy_is_refused(dir: &str, name: &str, edit: &str, needle: &str) {
    let bad = common::subdir(dir).join(name);
    common::edited_copy(table(), &bad, edit);
    let e = oblique_lookup::Table::open(&bad)
        .map(|_| ())
        .expect_err("an edited table");
    assert!(e.to_string().contains(needle), "{e}");
    let reader = Command::new("python3")
        .args([
            concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/read_table.py"),
            bad.to_str().expect("path"),
            "--gamma",
            "1.4",
            "--alpha",
            "0.3",
            "--e-n",
            "0.8",
        ])
        .output()
        .expect("the reference reader");
    assert!(!reader.status.success());
    assert!(
        String::from_utf8_lossy(&reader.stderr).contains(needle),
        "{}",
        String::from_utf8_lossy(&reader.stderr)
    );
}

/// The partial-slip patch names its coordinate's map: a table whose map is another (an older
/// build's `(2/π) asin(√ℓ)`) is refused by the library and by the reference reader, never read
/// with this map.
#[test]
fn a_table_with_another_partial_slip_map_is_refused() {
    edited_copy_is_refused(
        "dissipative-map",
        "asin.h5",
        "f['patches/partial_high'].attrs['coordinate'] = '(2/pi)asin(sqrt(l))'",
        "'coordinate'",
    );
}

/// The axis attributes must describe the stored nodes and the law must be one the readers
/// know: a table whose `e_n` range or γ edge was changed after the build (it would answer from
/// values simulated elsewhere: −0.32 where the truth is −0.28), whose node coordinates were set
/// to NaN, or whose law is unknown is refused by the library and by the reference reader.
#[test]
fn edited_axes_node_coordinates_and_unknown_laws_are_refused() {
    let moved = "the attributes do not describe the stored nodes";
    let nan_at = |ds: &str| {
        format!(
            "d = f['patches/partial_high/{ds}']; v = d[()]; v[0, 1, 1, 1] = float('nan'); \
             d[...] = v"
        )
    };
    let cases = [
        (
            "e_n_min_low.h5",
            "f.attrs['e_n_min'] = 0.6".to_string(),
            moved,
        ),
        (
            "e_n_min_high.h5",
            "f.attrs['e_n_min'] = 0.8".to_string(),
            moved,
        ),
        ("e_n_max.h5", "f.attrs['e_n_max'] = 0.99".to_string(), moved),
        (
            "gamma_hi.h5",
            "f.attrs['gamma_max'] = 1.65; \
             [f['patches/' + n].attrs.__setitem__('gamma_hi', 1.65) \
              for n in ('partial_high', 'stick_high')]"
                .to_string(),
            moved,
        ),
        ("nan_e_n.h5", nan_at("e_n"), moved),
        ("nan_gamma.h5", nan_at("gamma"), moved),
        ("nan_coord.h5", nan_at("coord"), moved),
        ("nan_alpha.h5", nan_at("alpha"), "node alphas must be >= 0"),
        (
            "maxwell.h5",
            "f.attrs['law'] = 'maxwell'".to_string(),
            "'law' = 'maxwell'",
        ),
    ];
    for (name, edit, needle) in cases {
        edited_copy_is_refused("dissipative-edited", name, &edit, needle);
    }
}

/// Batches (serial and parallel) answer every point with the bits of `Table::p_e`, and name
/// the first refused point's index.
#[test]
fn batches_give_the_single_answers_bit_for_bit() {
    use oblique_lookup::{OutOfDomain, Table};
    let table = Table::open(table()).expect("open");
    let n = 100_000;
    let mut next = oblique_lookup::testing::uniform(0x2545_F491_4F6C_DD1D);
    let gamma: Vec<f64> = (0..n).map(|_| 1.3 + 0.3 * next()).collect();
    let alpha: Vec<f64> = (0..n)
        .map(|i| {
            if i % 11 == 0 {
                f64::INFINITY
            } else {
                10f64.powf(-2.0 + 3.0 * next())
            }
        })
        .collect();
    let e_n: Vec<f64> = (0..n).map(|_| 0.7 + 0.3 * next()).collect();
    let (mut serial, mut parallel) = (vec![0.0; n], vec![0.0; n]);
    table
        .p_e_batch(&gamma, &alpha, &e_n, &mut serial, OutOfDomain::Error)
        .expect("serial");
    table
        .p_e_batch_par(&gamma, &alpha, &e_n, &mut parallel, OutOfDomain::Error)
        .expect("parallel");
    for i in 0..n {
        let one = table.p_e(gamma[i], alpha[i], e_n[i]).expect("single");
        assert_eq!(serial[i].to_bits(), one.to_bits(), "serial {i}");
        assert_eq!(parallel[i].to_bits(), one.to_bits(), "parallel {i}");
    }
    let mut bad = e_n.clone();
    bad[4321] = 0.6;
    bad[70_000] = 0.5;
    let e = table
        .p_e_batch_par(&gamma, &alpha, &bad, &mut parallel, OutOfDomain::Error)
        .expect_err("e_n below the range");
    assert!(e.to_string().contains("query 4321"), "{e}");
}

/// The cells of a table with an `e_n` axis halve only the axes that need it: the built
/// table's patches carry `split` masks and not all of them are 7 (every axis); a mask changed
/// on disk (and the file resealed) is refused by the library and by the reference reader,
/// naming the dataset.
#[test]
fn cells_halve_only_the_axes_that_need_it_and_bad_masks_are_refused() {
    use oblique_table::surface::PatchId;
    let shipped = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tables/dissipative-demo.h5"
    ));
    for path in [table(), shipped] {
        let t = oblique_lookup::Table::open(path).expect("open");
        let p = t
            .surface()
            .patch_by_id(PatchId::PartialHigh)
            .expect("partial slip");
        let split = p.split().expect("a split dataset");
        let halved: Vec<u8> = split.iter().copied().filter(|&s| s != 0).collect();
        assert!(!halved.is_empty(), "{}: a tree with splits", path.display());
        assert!(
            halved.iter().any(|&s| s != 7),
            "{}: some cells halve fewer than 3 axes",
            path.display()
        );
    }
    edited_copy_is_refused(
        "dissipative-split",
        "split.h5",
        "d = f['patches/partial_high/split']; s = d[()]; \
         i = next(i for i, v in enumerate(s) if v != 0); s[i] = 0; d[...] = s",
        "'split'",
    );
}
