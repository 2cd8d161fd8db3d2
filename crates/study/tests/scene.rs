//! Scenes (`oblique_study::scene`): the shipped scene files, agreement of the simulated slice
//! with table lookup and with a direct physical-units simulation, conservation laws of
//! sphere–sphere scenes, the measured-data overlay (on synthetic data), clear errors for bad
//! scene files, the CSV fields at the corners of the allowed ranges and dissipative scenes.
//! `sweep scene` itself is checked in the root package's `tests/cli_scene.rs`.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

use oblique_lookup::rebound::{Incident, Pair, State};
use oblique_lookup::Table;
use oblique_physics::regimes::Regime;
use oblique_solver::units::PhysicalImpact;
use oblique_study::scene::{
    self, evaluate, Dissipation, PSource, RowMethod, Scene, SceneError, SceneTarget,
};

/// The repository root, where the shipped scenes and tables are.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn shipped(name: &str) -> Scene {
    Scene::load(root().join("configs/scenes").join(format!("{name}.toml"))).expect("shipped scene")
}

fn scratch(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("scene-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const SHIPPED: [&str; 7] = [
    "seed000_alumina_on_glass",
    "alumina_on_rigid_wall",
    "steel_on_steel",
    "sphere_sphere_mixed",
    "nylon_spin_on_steel",
    "steel_on_steel_damped",
    "steel_on_steel_plastic",
];

#[test]
fn every_shipped_scene_loads() {
    for name in SHIPPED {
        let s = shipped(name);
        assert_eq!(s.name, name);
        assert!(!s.cases.values.is_empty());
    }
    let s = shipped("sphere_sphere_mixed");
    assert!(matches!(s.target, SceneTarget::Sphere { .. }));
    assert!(s.sphere.radius != s.pair().other.unwrap().radius);
    // The catalogue's limiting pressure of steel, 1.60 x 235 MPa (Pa).
    let s = shipped("steel_on_steel_plastic");
    assert_eq!(
        s.dissipation,
        oblique_study::scene::Dissipation::YieldPressure(1.60 * 235e6)
    );
}

#[test]
fn seed_000_gamma_from_the_materials() {
    let s = shipped("seed000_alumina_on_glass");
    let ev = evaluate(&s, PSource::Simulate).unwrap();
    // The seed quotes γ ≈ 1.754 (from a rounded G*); its material values give 1.7498.
    assert!((ev.gamma - 1.754).abs() < 5e-3, "gamma = {}", ev.gamma);
    assert!((ev.gamma - 1.749_786).abs() < 1e-6, "gamma = {}", ev.gamma);
    assert!((ev.e_star / 6.42e10 - 1.0).abs() < 1e-3);
    assert_eq!(s.cases.speed, 3.9);
    assert_eq!(s.friction, 0.092);
    assert_eq!(s.sphere.radius, 2.5e-3);
    // ω0 = 0 on a wall: the seed's formulas (32), (33) with α = μ v_z0/v_x0.
    for r in ev.rows.iter().filter(|r| r.p.is_finite()) {
        let t = r.x.to_radians();
        assert!((r.alpha - 0.092 / t.tan()).abs() < 1e-12 * r.alpha);
        assert!((r.model.e_t - (2.0 * r.p + 5.0) / 7.0).abs() < 1e-12);
        let omega = 5.0 * 3.9 * t.sin() * (r.p - 1.0) / (7.0 * 2.5e-3);
        assert!((r.model.sphere.omega - omega).abs() < 1e-9 * omega.abs());
        // Where the contact slips throughout, the seed's approximation (35) is exact.
        if r.regime == Some(Regime::FullSlip) {
            let cf = r.closed_form.unwrap();
            assert!((cf.e_t - r.model.e_t).abs() < 1e-12);
            assert_eq!(
                r.method,
                RowMethod::ClosedForm,
                "closed forms are never simulated"
            );
        }
        let approx = 1.0 - 0.092 * 2.0 / t.tan();
        assert!((r.closed_form.unwrap().e_t - approx).abs() < 1e-12);
        assert!((r.rolling.e_t - 5.0 / 7.0).abs() < 1e-14);
    }
}

#[test]
fn seventeen_angle_seed_000_scene_without_table() {
    let path = root().join("configs/scenes/seed000_alumina_on_glass.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let re = text
        .lines()
        .map(|l| {
            if l.starts_with("angles_deg") {
                "angles_deg = { from = 5, to = 85, count = 17 }"
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let s = Scene::parse(&re, &path).unwrap();
    assert_eq!(s.cases.values.len(), 17);
    let start = Instant::now();
    let ev = evaluate(&s, PSource::Simulate).unwrap();
    let wall = start.elapsed().as_secs_f64();
    println!(
        "17-angle seed-000 scene without a table: {wall:.3} s ({} simulated, {} closed form)",
        ev.count(RowMethod::Simulated),
        ev.count(RowMethod::ClosedForm)
    );
    assert_eq!(ev.rows.len(), 17);
    assert!(ev
        .rows
        .iter()
        .all(|r| r.p.is_finite() && r.model.e_t.is_finite()));
    assert!(ev.max_p_error() <= s.tol);
    assert!(ev.count(RowMethod::ClosedForm) > 0 && ev.count(RowMethod::Simulated) > 0);
}

/// The table to compare with: the shipped `tables/full.h5`.
fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| Table::open(root().join("tables/full.h5")).expect("open tables/full.h5"))
}

#[test]
fn simulated_slice_agrees_with_table_lookup_within_its_certified_error() {
    let t = table();
    let certified = t.error_bound();
    println!("table certified error (max(held-out max, target) + node tol): {certified}");
    for name in SHIPPED {
        let s = shipped(name);
        if s.dissipation.is_named() {
            // An elastic table answers e_n = 1 only (the damped scene's table test is
            // constant_e_n_from_a_table_agrees_with_simulation_and_e_n_1_is_elastic).
            continue;
        }
        let sim = evaluate(&s, PSource::Simulate).unwrap();
        let tab = evaluate(&s, PSource::Table(t)).unwrap();
        assert_eq!(sim.rows.len(), tab.rows.len());
        let mut worst: f64 = 0.0;
        for (a, b) in sim.rows.iter().zip(&tab.rows) {
            assert_eq!(a.x, b.x);
            if a.method == RowMethod::NormalImpact {
                assert_eq!(b.method, RowMethod::NormalImpact);
                continue;
            }
            let bound = a.p_error + b.p_error + 1e-13;
            let d = (a.p - b.p).abs();
            worst = worst.max(d / bound);
            assert!(
                d <= bound,
                "{name} at x = {}: simulated P = {} (+/- {:.1e}), table P = {} (+/- {:.1e})",
                a.x,
                a.p,
                a.p_error,
                b.p,
                b.p_error
            );
            if a.method == RowMethod::ClosedForm {
                assert_eq!(b.method, RowMethod::ClosedForm);
                assert_eq!(a.p, b.p);
            }
        }
        println!("{name}: worst |P_sim - P_table| / bound = {worst:.3}");
    }
}

#[test]
fn scene_cases_agree_with_a_direct_physical_units_simulation() {
    for name in [
        "seed000_alumina_on_glass",
        "sphere_sphere_mixed",
        "nylon_spin_on_steel",
    ] {
        let s = shipped(name);
        let ev = evaluate(&s, PSource::Simulate).unwrap();
        // A few cases per scene, spread over the regimes.
        let n = ev.rows.len();
        for r in [
            &ev.rows[1],
            &ev.rows[n / 4],
            &ev.rows[n / 2],
            &ev.rows[3 * n / 4],
        ] {
            if r.method == RowMethod::NormalImpact {
                continue;
            }
            let (other, other_material, other_motion) = match &s.target {
                SceneTarget::Wall { material: m } => (None, m.elastic, State::default()),
                SceneTarget::Sphere {
                    body, material: m, ..
                } => (Some(*body), m.elastic, r.incident.other),
            };
            let imp = PhysicalImpact {
                pair: Pair {
                    sphere: s.sphere,
                    other,
                },
                materials: [s.sphere_material.elastic, other_material],
                incident: Incident {
                    sphere: r.incident.sphere,
                    other: other_motion,
                },
                friction: s.friction,
                law: Default::default(),
            };
            let phys = imp.solve(1e-6).unwrap();
            let g = phys.groups;
            assert!(
                (g.gamma - ev.gamma).abs() < 1e-9 * ev.gamma,
                "{name}: gamma"
            );
            assert!((g.alpha - r.alpha).abs() < 1e-9 * r.alpha, "{name}: alpha");
            let err = phys.error_estimate + r.p_error + 1e-12;
            let p = phys.p.unwrap();
            assert!(
                (p - r.p).abs() <= err,
                "{name} x = {}: P scene {} vs physical {p} (err {err:.1e})",
                r.x,
                r.p
            );
            let dj = ev.tangential_mass * err * g.slip_velocity.abs();
            let b = s.sphere;
            let v = r.incident.sphere.v_z.abs() + g.slip_velocity.abs();
            assert!((phys.sphere.v_x - r.model.sphere.v_x).abs() <= dj / b.mass + 1e-9 * v);
            assert!((phys.sphere.v_z - r.model.sphere.v_z).abs() <= 1e-8 * v);
            assert!(
                (phys.sphere.omega - r.model.sphere.omega).abs()
                    <= dj * b.radius / b.inertia() + 1e-9 * v / b.radius,
                "{name} x = {}: omega {} vs {}",
                r.x,
                phys.sphere.omega,
                r.model.sphere.omega
            );
            if let (Some(o), Some(mo), Some(ob)) = (phys.other, r.model.other, s.pair().other) {
                assert!((o.v_x - mo.v_x).abs() <= dj / ob.mass + 1e-9 * v);
                assert!((o.v_z - mo.v_z).abs() <= 1e-8 * v);
                assert!(
                    (o.omega - mo.omega).abs()
                        <= dj * ob.radius / ob.inertia() + 1e-9 * v / ob.radius
                );
            }
        }
    }
}

#[test]
fn sphere_sphere_conserves_momentum_and_angular_momentum_about_the_contact() {
    let base = root().join("configs/scenes/sphere_sphere_mixed.toml");
    let text = std::fs::read_to_string(&base).unwrap();
    // The shipped scene (target at rest) and a variant with a moving, spinning target.
    let moving = text.replace(
        "# v_x, v_z, omega of the target default to 0 (at rest)",
        "v_x = -0.3\nv_z = -0.7\nomega = 150.0",
    );
    assert_ne!(moving, text);
    for t in [&text, &moving] {
        let s = Scene::parse(t, &base).unwrap();
        let ev = evaluate(&s, PSource::Simulate).unwrap();
        let b1 = s.sphere;
        let b2 = s.pair().other.unwrap();
        for r in &ev.rows {
            let (a0, c0) = (r.incident.sphere, r.incident.other);
            let (a1, c1) = (r.model.sphere, r.model.other.unwrap());
            let px = |a: f64, c: f64| b1.mass * a + b2.mass * c;
            let rel = |x: f64, y: f64, scale: f64| (x - y).abs() / scale;
            let p_scale =
                b1.mass * a0.v_x.abs().max(a0.v_z.abs()) + b2.mass * c0.v_x.abs().max(c0.v_z.abs());
            assert!(rel(px(a0.v_x, c0.v_x), px(a1.v_x, c1.v_x), p_scale) < 1e-12);
            assert!(rel(px(a0.v_z, c0.v_z), px(a1.v_z, c1.v_z), p_scale) < 1e-12);
            // About the contact point: centres at z = −R1 and z = +R2 (L_y = Σ z m v_x + I ω).
            let l = |a: &oblique_lookup::rebound::State, c: &oblique_lookup::rebound::State| {
                -b1.radius * b1.mass * a.v_x
                    + b1.inertia() * a.omega
                    + b2.radius * b2.mass * c.v_x
                    + b2.inertia() * c.omega
            };
            let l_scale = b1.radius * p_scale
                + b1.inertia() * a0.omega.abs()
                + b2.inertia() * c0.omega.abs()
                + b2.radius * p_scale;
            assert!(rel(l(&a0, &c0), l(&a1, &c1), l_scale) < 1e-12);
            // Elastic normal motion; energy balance with the reported friction loss.
            assert!(((a1.v_z - c1.v_z) + (a0.v_z - c0.v_z)).abs() < 1e-12 * a0.v_z.abs());
            let ke = |a: &oblique_lookup::rebound::State, c: &oblique_lookup::rebound::State| {
                0.5 * b1.mass * (a.v_x * a.v_x + a.v_z * a.v_z)
                    + 0.5 * b1.inertia() * a.omega * a.omega
                    + 0.5 * b2.mass * (c.v_x * c.v_x + c.v_z * c.v_z)
                    + 0.5 * b2.inertia() * c.omega * c.omega
            };
            let (k0, k1) = (ke(&a0, &c0), ke(&a1, &c1));
            assert!((k0 - k1 - r.model.energy_lost).abs() < 1e-10 * k0);
            assert!(r.model.energy_lost >= 0.0);
        }
    }
}

#[test]
fn measured_data_overlay_reports_the_rms_difference() {
    // SYNTHETIC data, made here from the model itself plus known offsets: it tests the
    // bookkeeping (matching, extra points, RMS), it is not a measurement.
    let dir = scratch("measured");
    let scene_path = dir.join("synthetic.toml");
    let base = r#"name = "synthetic"
friction = 0.092
[sphere]
material = "alumina-96"
radius = 2.5e-3
[target]
kind = "wall"
material = "soda-lime-glass"
[cases]
kind = "angles"
speed = 3.9
angles_deg = [10, 20, 30, 40]
"#;
    let plain = Scene::parse(base, &scene_path).unwrap();
    let ev0 = evaluate(&plain, PSource::Simulate).unwrap();
    // Model at an angle outside the scene's list, for the extra point.
    let extra = Scene::parse(&base.replace("[10, 20, 30, 40]", "[25]"), &scene_path).unwrap();
    let ev25 = evaluate(&extra, PSource::Simulate).unwrap();
    let mut csv = String::from("# SYNTHETIC test data (model + known offsets), not measured\n");
    csv.push_str("angle_deg,e_t,omega\n");
    for r in &ev0.rows[..3] {
        csv.push_str(&format!(
            "{},{},{}\n",
            r.x,
            r.model.e_t + 0.01,
            r.model.sphere.omega - 2.0
        ));
    }
    let r25 = &ev25.rows[0];
    csv.push_str(&format!("25,{},\n", r25.model.e_t - 0.01));
    std::fs::write(dir.join("synthetic.csv"), csv).unwrap();
    let with =
        format!("{base}[measured]\nfile = \"synthetic.csv\"\nsource = \"synthetic test data\"\n");
    std::fs::write(&scene_path, &with).unwrap();
    let s = Scene::load(&scene_path).unwrap();
    let ev = evaluate(&s, PSource::Simulate).unwrap();
    assert_eq!(ev.rows.len(), 5, "4 scene angles + 1 measured-only angle");
    assert_eq!(ev.rows.iter().filter(|r| !r.in_scene).count(), 1);
    let xs: Vec<f64> = ev.rows.iter().map(|r| r.x).collect();
    assert_eq!(xs, vec![10.0, 20.0, 25.0, 30.0, 40.0]);
    let rms = ev.rms.unwrap();
    let (e_rms, e_n) = rms.e_t.unwrap();
    let (w_rms, w_n) = rms.omega.unwrap();
    assert_eq!((e_n, w_n), (4, 3));
    assert!((e_rms - 0.01).abs() < 1e-9, "e_t rms {e_rms}");
    assert!((w_rms - 2.0).abs() < 1e-6, "omega rms {w_rms}");
    let lines = scene::csv::lines(&ev, false);
    assert!(lines[0].ends_with("e_t_measured,omega_measured"));
    assert_eq!(lines.len(), 6);
    // A measured file with a bad column is refused with the line number.
    std::fs::write(dir.join("synthetic.csv"), "angle_deg,e_t,spin\n10,0.7,1\n").unwrap();
    let err = evaluate(&s, PSource::Simulate).unwrap_err().to_string();
    assert!(err.contains("spin") && err.contains("line 1"), "{err}");
}

#[test]
fn bad_scene_files_give_errors_naming_the_key() {
    let good = r#"friction = 0.1
[sphere]
material = "steel"
radius = 0.005
[target]
kind = "wall"
material = "steel"
[cases]
kind = "angles"
speed = 1.0
angles_deg = { from = 10, to = 80, count = 8 }
"#;
    let p = Path::new("bad.toml");
    Scene::parse(good, p).expect("the base scene is valid");
    let cases: &[(&str, &str, &[&str])] = &[
        ("radius = 0.005", "radiuss = 0.005", &["radiuss"]),
        (
            "radius = 0.005",
            "radius = -0.005",
            &["sphere.radius", "> 0"],
        ),
        (
            "material = \"steel\"\nradius",
            "material = \"steel\"\npoisson_ratio = 0.7\nradius",
            &["sphere.poisson_ratio", "(-1, 0.5]"],
        ),
        (
            "material = \"steel\"\nradius",
            "material = \"unobtainium\"\nradius",
            &["sphere.material", "soda-lime-glass"],
        ),
        ("count = 8", "count = 0", &["count", "[2, 100000]"]),
        (
            "{ from = 10, to = 80, count = 8 }",
            "[10, 95]",
            &["cases.angles_deg", "(-90, 90)"],
        ),
        ("friction = 0.1", "friction = -0.1", &["friction", ">= 0"]),
        ("friction = 0.1", "", &["friction"]),
        (
            "kind = \"wall\"",
            "kind = \"floor\"",
            &["target.kind", "\"wall\" or \"sphere\""],
        ),
        (
            "kind = \"wall\"",
            "kind = \"wall\"\nradius = 1.0",
            &["target.radius", "wall"],
        ),
        (
            "material = \"steel\"\nradius",
            "material = \"steel\"\nmass = 0.1\ndensity = 7000\nradius",
            &["sphere.mass", "not both"],
        ),
        (
            "material = \"steel\"\nradius",
            "material = \"steel\"\nkappa = 0.9\nradius",
            &["sphere.kappa", "(0, 2/3]"],
        ),
        (
            "friction = 0.1",
            "friction = 0.1\ntol = 1",
            &["tol", "[1e-10, 1e-2]"],
        ),
        (
            "kind = \"angles\"",
            "kind = \"angle\"",
            &["cases.kind", "tangential-speed"],
        ),
        ("speed = 1.0", "speed = 0", &["cases.speed", "> 0"]),
        (
            "speed = 1.0",
            "speed = 1.0\nnormal_speed = 1.0",
            &["cases.normal_speed", "angles"],
        ),
        (
            "friction = 0.1",
            "friction = 0.1\nname = \"../escape\"",
            &["name", "A-Z"],
        ),
    ];
    for (from, to, want) in cases {
        assert!(good.contains(from), "test case does not apply: {from}");
        let text = good.replacen(from, to, 1);
        let err = Scene::parse(&text, p)
            .expect_err(&format!("{to:?} should be refused"))
            .to_string();
        for w in *want {
            assert!(err.contains(w), "error for {to:?} lacks {w:?}: {err}");
        }
        assert!(err.contains("bad.toml"), "error names the file: {err}");
    }
    // Sphere–sphere: a target moving away faster than sphere 1 approaches.
    let away = good.replacen(
        "kind = \"wall\"\nmaterial = \"steel\"",
        "kind = \"sphere\"\nmaterial = \"steel\"\nradius = 0.01\nv_z = 5.0",
        1,
    );
    let err = Scene::parse(&away, p).unwrap_err().to_string();
    assert!(
        err.contains("cases.angles_deg") && err.contains("approach"),
        "{err}"
    );
    // A missing file.
    let err = Scene::load("no/such/scene.toml").unwrap_err().to_string();
    assert!(err.contains("no/such/scene.toml"), "{err}");
}

/// The CSV of a scene at the corners of the allowed ranges: every field a finite number, except
/// the documented empty fields (`e_t` columns where the incident relative `v_x0` is 0, `P` of a
/// pure normal impact, the closed form where α = ∞) and `alpha` = `inf` for no slip. Every case
/// of a spin sweep without tangential speed has an empty `e_t` (it was `NaN`).
#[test]
fn csv_fields_are_finite_or_documented_empty_at_the_range_corners() {
    let template = r#"friction = FRICTION
tol = 1e-3
[sphere]
youngs_modulus = E1
poisson_ratio = 0.3
density = RHO
radius = R
[target]
kind = "wall"
youngs_modulus = E2
poisson_ratio = 0.2
[cases]
kind = "spin"
normal_speed = VZ
tangential_speed = VX
omega0 = [-W, 0, W]
"#;
    let mut checked = 0;
    for (e1, e2) in [("1e3", "1e13"), ("1e13", "inf"), ("1e3", "1e3")] {
        for (rho, r) in [("1", "1e-9"), ("1e5", "1e3")] {
            for (vz, vx) in [("1e3", "0"), ("1e-6", "1e3"), ("1", "-1e-3")] {
                for friction in ["0.3", "inf"] {
                    let radius: f64 = r.parse().unwrap();
                    let w = format!("{:e}", 0.999e3 / radius);
                    let text = template
                        .replace("FRICTION", friction)
                        .replace("E1", e1)
                        .replace("E2", e2)
                        .replace("RHO", rho)
                        .replace("radius = R", &format!("radius = {r}"))
                        .replace("VZ", vz)
                        .replace("VX", vx)
                        .replace("[-W, 0, W]", &format!("[-{w}, 0, {w}]"));
                    let what = format!("E {e1}/{e2}, rho {rho}, R {r}, v {vz}/{vx}, mu {friction}");
                    let s = Scene::parse(&text, Path::new("corner.toml"))
                        .unwrap_or_else(|e| panic!("{what}: {e}"));
                    let ev =
                        evaluate(&s, PSource::Simulate).unwrap_or_else(|e| panic!("{what}: {e}"));
                    let lines = scene::csv::lines(&ev, false);
                    let header: Vec<&str> = lines[0].split(',').collect();
                    for (line, row) in lines[1..].iter().zip(&ev.rows) {
                        let rel_vx0 = row.incident.sphere.v_x;
                        for (col, cell) in header.iter().zip(line.split(',')) {
                            let ctx = format!("{what}: {col} = {cell:?} in {line}");
                            match *col {
                                "regime" | "method" => continue,
                                _ if cell.is_empty() => {
                                    let documented = match *col {
                                        "e_t" | "e_t_rolling" => rel_vx0 == 0.0,
                                        "e_t_closed_form" => {
                                            rel_vx0 == 0.0 || row.alpha.is_infinite()
                                        }
                                        "omega_closed_form" => row.alpha.is_infinite(),
                                        "P" => row.method == RowMethod::NormalImpact,
                                        _ => false,
                                    };
                                    assert!(documented, "undocumented empty field: {ctx}");
                                }
                                "alpha" if cell == "inf" => {
                                    assert!(
                                        friction == "inf" || row.method == RowMethod::NormalImpact,
                                        "{ctx}"
                                    )
                                }
                                _ => {
                                    let v: f64 = cell.parse().unwrap_or_else(|_| panic!("{ctx}"));
                                    assert!(v.is_finite(), "{ctx}");
                                }
                            }
                        }
                        if rel_vx0 == 0.0 {
                            assert!(line.split(',').nth(4) == Some(""), "{what}: {line}");
                        }
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 2 * 3 * 2 * 3);
    // The shipped spin scene: e_t empty in every row, never NaN anywhere.
    let ev = evaluate(&shipped("nylon_spin_on_steel"), PSource::Simulate).unwrap();
    let lines = scene::csv::lines(&ev, false);
    assert!(!lines.iter().any(|l| l.contains("NaN")), "{lines:?}");
    assert!(lines[1..].iter().all(|l| l.split(',').nth(4) == Some("")));
}

/// A scene with a Kelvin–Voigt relaxation time: each case's `e_n` is the one of a direct
/// physical-units simulation at that case's speed (so it varies along an `angles` sweep), and
/// its `P` and rebound agree with that simulation.
#[test]
fn relaxation_time_gives_each_case_its_e_n_and_p_of_a_physical_simulation() {
    let s = shipped("steel_on_steel_damped");
    assert_eq!(s.dissipation, Dissipation::RelaxationTime(1e-6));
    let ev = evaluate(&s, PSource::Simulate).unwrap();
    let (lo, hi) = ev.e_n_range().unwrap();
    assert!(lo > 0.85 && hi < 0.9 && hi - lo > 0.03, "e_n {lo} .. {hi}");
    // e_n grows with the angle: the normal speed v_z0 = |v| cos θ falls.
    assert!(ev.rows.windows(2).all(|w| w[1].e_n > w[0].e_n));
    let n = ev.rows.len();
    for r in [&ev.rows[1], &ev.rows[n / 2], &ev.rows[n - 2]] {
        let SceneTarget::Wall { material } = &s.target else {
            unreachable!()
        };
        let imp = PhysicalImpact::sphere_on_wall(
            (s.sphere, s.sphere_material.elastic),
            material.elastic,
            r.incident.sphere,
            s.friction,
        )
        .with_relaxation_time(1e-6);
        let phys = imp.solve(1e-6).unwrap();
        assert!(
            (phys.e_n - r.e_n).abs() < 1e-6,
            "e_n {} vs {}",
            phys.e_n,
            r.e_n
        );
        let err = phys.error_estimate + r.p_error + 1e-6;
        let p = phys.p.unwrap();
        assert!((p - r.p).abs() <= err, "x = {}: P {} vs {p}", r.x, r.p);
        let v = r.incident.sphere.v_z;
        assert!(
            (phys.sphere.v_z - r.model.sphere.v_z).abs() <= 1e-5 * v,
            "v_z {} vs {}",
            phys.sphere.v_z,
            r.model.sphere.v_z
        );
        assert!((r.model.sphere.v_z + r.e_n * v).abs() < 1e-12 * v);
    }
    // The full-slip cases are the exact line P = 1 − (7/2)(1 + e_n)α, not simulated.
    let full: Vec<_> = ev
        .rows
        .iter()
        .filter(|r| r.regime == Some(Regime::FullSlip))
        .collect();
    assert!(!full.is_empty());
    for r in full {
        assert_eq!(r.method, RowMethod::ClosedForm);
        assert!((r.p - (1.0 - 3.5 * (1.0 + r.e_n) * r.alpha)).abs() < 1e-12);
    }
}

/// A constant `e_n`: the table with an e_n axis agrees with the simulated slice within its
/// stated bound; `e_n = 1` is the elastic scene's answer.
#[test]
fn constant_e_n_from_a_table_agrees_with_simulation_and_e_n_1_is_elastic() {
    let text = std::fs::read_to_string(root().join("configs/scenes/steel_on_steel_damped.toml"))
        .unwrap()
        .replace("relaxation_time = 1e-6", "e_n = 0.7");
    let s = Scene::parse(&text, Path::new("damped.toml")).unwrap();
    assert_eq!(s.dissipation, Dissipation::Restitution(0.7));
    let table = Table::open(root().join("tables/dissipative-demo.h5")).unwrap();
    let sim = evaluate(&s, PSource::Simulate).unwrap();
    let tab = evaluate(&s, PSource::Table(&table)).unwrap();
    assert_eq!(tab.count(RowMethod::Simulated), 0);
    assert!(tab.count(RowMethod::Table) > 0);
    for (a, b) in sim.rows.iter().zip(&tab.rows) {
        assert_eq!((a.e_n, b.e_n), (0.7, 0.7));
        assert!(
            (a.p - b.p).abs() <= table.error_bound() + a.p_error,
            "x = {}: simulated {} table {}",
            a.x,
            a.p,
            b.p
        );
    }
    let lines = scene::csv::lines(&tab, false);
    assert!(lines[0].ends_with(",omega_rolling,e_n,law"), "{}", lines[0]);
    assert!(lines[1].ends_with(",0.7,kelvin-voigt"), "{}", lines[1]);

    // e_n = 1 named: the elastic scene's P, with the e_n and law columns.
    let one = Scene::parse(&text.replace("e_n = 0.7", "e_n = 1"), Path::new("one.toml")).unwrap();
    let elastic = Scene::parse(&text.replace("e_n = 0.7", ""), Path::new("el.toml")).unwrap();
    let (a, b) = (
        evaluate(&one, PSource::Simulate).unwrap(),
        evaluate(&elastic, PSource::Simulate).unwrap(),
    );
    for (r1, r2) in a.rows.iter().zip(&b.rows) {
        assert_eq!(r1.p.to_bits(), r2.p.to_bits());
        assert_eq!(r1.model, r2.model);
    }
    assert!(scene::csv::lines(&a, false)[1].ends_with(",1,elastic"));
    assert!(!scene::csv::lines(&b, false)[0].contains("e_n"));
}

/// A table that cannot answer a case's e_n is refused as the user's to fix
/// ([`SceneError::Restitution`]); bad `e_n` and `relaxation_time` keys are refused naming the
/// key. (`sweep scene` with such a table: `tests/cli_scene.rs`.)
#[test]
fn a_table_without_the_case_e_n_is_the_users_to_fix_and_bad_dissipation_keys_name_the_key() {
    let out = scratch("restitution-keys");
    let text = std::fs::read_to_string(root().join("configs/scenes/steel_on_steel_damped.toml"))
        .unwrap()
        .replace("relaxation_time = 1e-6", "e_n = 0.4");
    let low = out.join("low.toml");
    std::fs::write(&low, &text).unwrap();
    let s = Scene::load(&low).unwrap();
    let t = Table::open(root().join("tables/dissipative-demo.h5")).unwrap();
    let e = evaluate(&s, PSource::Table(&t)).unwrap_err();
    assert!(matches!(e, SceneError::Restitution { .. }) && e.user_can_fix());

    // Bad keys: out of range, both given.
    for (edit, key) in [
        ("e_n = 1.5", "e_n"),
        ("e_n = 0.1", "e_n"),
        ("relaxation_time = -1", "relaxation_time"),
        ("e_n = 0.9\nrelaxation_time = 1e-6", "relaxation_time"),
        ("relaxation_time = 1e-3", "relaxation_time"),
    ] {
        let text = text.replace("e_n = 0.4", edit);
        let e = match Scene::parse(&text, Path::new("bad.toml")) {
            Err(e) => e,
            // A relaxation time too long for the impact speed fails when evaluated.
            Ok(s) => evaluate(&s, PSource::Simulate).unwrap_err(),
        };
        assert!(e.to_string().contains(key), "{edit}: {e}");
    }
}

/// Steel shot (R = 1 mm) on a steel plate at 1 m/s with Thornton's limiting pressure 2 GPa
/// (`physics.md`, "Elastic–plastic impacts"): the yield speed is about 0.24 m/s, so the steep
/// cases yield and the grazing ones (v_z0 = 0.17 and 0.09 m/s) stay elastic.
const SHOT: &str = r#"
name = "shot"
friction = 0.3
yield_pressure = 2e9

[sphere]
material = "steel"
radius = 1e-3

[target]
kind = "wall"
material = "steel"

[cases]
kind = "angles"
speed = 1.0
angles_deg = [10, 30, 50, 70, 80, 85]
"#;

/// `V_y` (m/s) of the scene's bodies at limiting pressure `p_y` (Pa), written out from
/// `physics.md`: `½ m* V_y² = (2/5) k d_y^{5/2}`, `k = (4/3) E* √R*`, `d_y = R* (π p_y/(2E*))²`.
fn yield_speed(ev: &scene::Evaluation, p_y: f64) -> f64 {
    let (e, r) = (ev.e_star, ev.effective_radius);
    let d_y = r * (std::f64::consts::PI * p_y / (2.0 * e)).powi(2);
    let k = 4.0 / 3.0 * e * r.sqrt();
    (2.0 * 0.4 * k * d_y.powf(2.5) / ev.normal_mass).sqrt()
}

/// A scene with `yield_pressure`: Thornton bodies. Below the yield speed a case is the elastic
/// scene's, bit for bit, with `e_n = 1`; above it `e_n` is Thornton's closed form of `V_y/v_z0`
/// and `P` that of a direct physical-units simulation of Thornton bodies. The CSV names the
/// law, and a Kelvin–Voigt table is refused for the yielding cases.
#[test]
fn yield_pressure_gives_thornton_bodies_that_yield_above_the_yield_speed() {
    use oblique_solver::thornton::{self, BodiesParameters};
    use oblique_solver::{BodiesLaw, Law};
    let p_y = 2e9;
    let s = Scene::parse(SHOT, Path::new("shot.toml")).unwrap();
    assert_eq!(s.dissipation, Dissipation::YieldPressure(p_y));
    let ev = evaluate(&s, PSource::Simulate).unwrap();
    let elastic = Scene::parse(
        &SHOT.replace("yield_pressure = 2e9", ""),
        Path::new("e.toml"),
    )
    .unwrap();
    let el = evaluate(&elastic, PSource::Simulate).unwrap();
    let v_y = yield_speed(&ev, p_y);
    assert!((0.2..0.3).contains(&v_y), "V_y = {v_y}");
    let (mut yielded, mut stayed) = (0, 0);
    for (r, e) in ev.rows.iter().zip(&el.rows) {
        assert_eq!(r.law, Law::Thornton);
        let v = r.incident.sphere.v_z;
        if v <= v_y {
            stayed += 1;
            assert_eq!(r.e_n, 1.0, "x = {}", r.x);
            assert_eq!(r.p.to_bits(), e.p.to_bits(), "x = {}", r.x);
            assert_eq!(r.model, e.model, "x = {}", r.x);
            continue;
        }
        yielded += 1;
        let want = thornton::restitution(v_y / v);
        assert!(
            (r.e_n - want).abs() <= 1e-12 * want,
            "e_n {} vs {want}",
            r.e_n
        );
        assert!(r.e_n < 1.0 && r.e_n > 0.75, "x = {}: e_n {}", r.x, r.e_n);
        assert!((r.model.sphere.v_z + r.e_n * v).abs() < 1e-12 * v);
        assert_eq!(r.method, RowMethod::Simulated);
        let phys = PhysicalImpact::sphere_on_wall(
            (s.sphere, s.sphere_material.elastic),
            s.target_material().elastic,
            r.incident.sphere,
            s.friction,
        )
        .with_law(BodiesLaw::Thornton(BodiesParameters {
            yield_pressure: p_y,
        }))
        .solve(1e-6)
        .unwrap();
        assert_eq!(phys.law.name(), "thornton");
        assert!(
            (phys.e_n - r.e_n).abs() < 1e-12,
            "{} vs {}",
            phys.e_n,
            r.e_n
        );
        let p = phys.p.unwrap();
        let err = phys.error_estimate + r.p_error + 1e-9;
        assert!((p - r.p).abs() <= err, "x = {}: P {} vs {p}", r.x, r.p);
        // Plastic flow changes P beyond the solver's accuracy.
        assert!(
            (r.p - e.p).abs() > 1e-3,
            "x = {}: {} vs elastic {}",
            r.x,
            r.p,
            e.p
        );
    }
    assert_eq!((yielded, stayed), (4, 2));
    // e_n falls as the normal speed grows (the steeper the impact).
    assert!(ev.rows.windows(2).all(|w| w[1].e_n >= w[0].e_n));
    let lines = scene::csv::lines(&ev, false);
    assert!(lines[0].ends_with(",e_n,law"), "{}", lines[0]);
    assert!(
        lines[1..].iter().all(|l| l.ends_with(",thornton")),
        "{lines:?}"
    );

    // A table of the Kelvin–Voigt law answers another P at the same e_n: refused.
    let t = Table::open(root().join("tables/dissipative-demo.h5")).unwrap();
    let e = evaluate(&s, PSource::Table(&t)).unwrap_err();
    assert!(matches!(e, SceneError::Restitution { .. }) && e.user_can_fix());
    assert!(
        e.to_string().contains("kelvin-voigt law")
            && e.to_string().contains("thornton law")
            && e.to_string().contains("case angle_deg = 10:"),
        "{e}"
    );
}

/// Bad limiting pressures are refused naming `yield_pressure`; with `e_n` or
/// `relaxation_time`, naming both keys; one whose `e_n` would fall below 0.3 when evaluated.
#[test]
fn bad_yield_pressures_and_two_laws_are_refused_naming_the_keys() {
    for (edit, keys) in [
        ("yield_pressure = 0", &["yield_pressure", "> 0 (Pa)"][..]),
        ("yield_pressure = -2e9", &["yield_pressure", "> 0 (Pa)"]),
        ("yield_pressure = nan", &["yield_pressure", "> 0 (Pa)"]),
        ("yield_pressure = inf", &["yield_pressure", "> 0 (Pa)"]),
        (
            "yield_pressure = 2e9\ne_n = 0.9",
            &["yield_pressure", "e_n"],
        ),
        (
            "yield_pressure = 2e9\nrelaxation_time = 1e-6",
            &["yield_pressure", "relaxation_time"],
        ),
        // Far below the Hertz pressure of a 1 m/s impact: e_n < 0.3.
        ("yield_pressure = 1e7", &["yield_pressure", "0.3"]),
    ] {
        let text = SHOT.replace("yield_pressure = 2e9", edit);
        let e = match Scene::parse(&text, Path::new("bad.toml")) {
            Err(e) => e,
            Ok(s) => evaluate(&s, PSource::Simulate).unwrap_err(),
        };
        for key in keys {
            assert!(e.to_string().contains(key), "{edit}: {e}");
        }
    }
}
