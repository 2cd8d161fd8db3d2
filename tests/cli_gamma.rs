//! `sweep gamma`: γ, m*/m_t and α of a pair of materials and bodies against the closed forms of
//! physics.md, the catalogue it prints, its refusals (an unknown material names the catalogue,
//! exit status 2), and the groups given for a general body in the help texts and the README.

use serde_json::Value;

mod common;
use common::sweep;

fn json(args: &[&str]) -> Value {
    let o = sweep(&[args, &["--json"]].concat());
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("one JSON object")
}

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number in {v}"))
}

/// `1/E* = Σ (1 − ν²)/E`, `1/G* = Σ (2 − ν)/(4G)`: `G*/E*`.
fn stiffness_ratio(a: (f64, f64), b: (f64, f64)) -> f64 {
    let c = |(e, nu): (f64, f64)| {
        if e.is_infinite() {
            (0.0, 0.0)
        } else {
            let g = e / (2.0 * (1.0 + nu));
            ((1.0 - nu * nu) / e, (2.0 - nu) / (4.0 * g))
        }
    };
    let (ea, ga) = c(a);
    let (eb, gb) = c(b);
    (ea + eb) / (ga + gb)
}

const ALUMINA: (f64, f64) = (370e9, 0.25);
const GLASS: (f64, f64) = (73e9, 0.217);
const STEEL: (f64, f64) = (210e9, 0.3);
const NYLON: (f64, f64) = (2.9e9, 0.39);

#[test]
fn solid_sphere_on_a_wall_is_the_scene_gamma() {
    let v = json(&[
        "gamma",
        "--sphere",
        "alumina-96",
        "--other",
        "soda-lime-glass",
    ]);
    let want = (3.5 * stiffness_ratio(ALUMINA, GLASS)).sqrt();
    assert!((num(&v, "gamma") - want).abs() < 1e-14, "{v}");
    // The value `sweep scene` prints for seed 000 (tests/scene.rs).
    assert!((num(&v, "gamma") - 1.749_786).abs() < 1e-6);
    assert_eq!(num(&v, "mass_ratio"), 3.5);
    assert_eq!(num(&v, "alpha_per_mu_vz0_over_u0"), 1.0);
    assert!((num(&v, "alpha_c2") - 2.0 * want * want / 7.0).abs() < 1e-14);
    assert_eq!(v["other"]["body"], "wall");
    assert!(v["sphere"]["source"].as_str().unwrap().contains("seed 000"));
    // Without radii, no masses.
    assert!(v["normal_mass"].is_null() && v["effective_radius"].is_null());
}

#[test]
fn a_general_body_follows_the_general_groups() {
    // A hollow sphere on a wall: m*/m_t = (1 + kappa)/kappa.
    let v = json(&[
        "gamma", "--sphere", "nylon", "--other", "steel", "--kappa", "0.5",
    ]);
    assert!((num(&v, "mass_ratio") - 3.0).abs() < 1e-14);
    let want = (3.0 * stiffness_ratio(NYLON, STEEL)).sqrt();
    assert!((num(&v, "gamma") - want).abs() < 1e-14);
    assert!((num(&v, "alpha_per_mu_vz0_over_u0") - 2.0 / 7.0 * 3.0).abs() < 1e-14);

    // Two solid spheres of different sizes: masses from the densities, m*/m_t still 7/2.
    let v = json(&[
        "gamma",
        "--sphere",
        "steel",
        "--other",
        "nylon",
        "--radius",
        "5e-3",
        "--other-radius",
        "0.01",
    ]);
    let m1 = 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * 5e-3f64.powi(3);
    let m2 = 1130.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.01f64.powi(3);
    assert!((num(&v["sphere"], "mass") / m1 - 1.0).abs() < 1e-14);
    assert!((num(&v["other"], "mass") / m2 - 1.0).abs() < 1e-14);
    assert!((num(&v, "normal_mass") / (m1 * m2 / (m1 + m2)) - 1.0).abs() < 1e-14);
    assert!((num(&v, "effective_radius") - 0.01 * 5e-3 / 0.015).abs() < 1e-17);
    assert!((num(&v, "mass_ratio") - 3.5).abs() < 1e-14);
    assert!((num(&v, "gamma") - (3.5 * stiffness_ratio(STEEL, NYLON)).sqrt()).abs() < 1e-14);

    // Different kappas: 1/m_t = sum (1 + 1/kappa)/m, and the masses matter.
    let v = json(&[
        "gamma",
        "--sphere",
        "steel",
        "--other",
        "nylon",
        "--radius",
        "5e-3",
        "--other-radius",
        "0.01",
        "--other-kappa",
        "0.5",
        "--other-mass",
        "2e-3",
    ]);
    let m2 = 2e-3;
    let mt = 1.0 / ((1.0 + 1.0 / 0.4) / m1 + (1.0 + 1.0 / 0.5) / m2);
    let ratio = m1 * m2 / (m1 + m2) / mt;
    assert!((num(&v, "mass_ratio") / ratio - 1.0).abs() < 1e-13, "{v}");
    let want = (ratio * stiffness_ratio(STEEL, NYLON)).sqrt();
    assert!((num(&v, "gamma") / want - 1.0).abs() < 1e-13);
    assert!((num(&v, "alpha_per_mu_vz0_over_u0") / (2.0 / 7.0 * ratio) - 1.0).abs() < 1e-13);

    // Own values, on a rigid wall.
    let v = json(&[
        "gamma",
        "--sphere",
        "E=200e9,nu=0.29,rho=7900",
        "--other",
        "rigid",
    ]);
    let want = (3.5 * stiffness_ratio((200e9, 0.29), (f64::INFINITY, 0.0))).sqrt();
    assert!((num(&v, "gamma") - want).abs() < 1e-14);
    assert_eq!(num(&v["sphere"], "density"), 7900.0);
}

#[test]
fn catalogue_gamma_of_one_material_depends_on_nu_only() {
    let v = json(&["gamma", "--catalogue"]);
    let list = v["materials"].as_array().unwrap();
    assert!(list.len() >= 7);
    let names: Vec<&str> = list.iter().map(|m| m["name"].as_str().unwrap()).collect();
    let rigid = names.iter().position(|&n| n == "rigid").unwrap();
    for (i, m) in list.iter().enumerate() {
        assert!(!m["source"].as_str().unwrap().is_empty());
        if m["name"] == "rigid" {
            assert!(m["density"].is_null() && m["gamma_same_material"].is_null());
            continue;
        }
        let nu = num(m, "poisson_ratio");
        let g = num(m, "gamma_same_material");
        assert!(
            (g - (7.0 * (1.0 - nu) / (2.0 - nu)).sqrt()).abs() < 1e-14,
            "{m}"
        );
        // The same on a rigid wall, and the pair table is symmetric.
        assert!((m["gamma"][rigid].as_f64().unwrap() - g).abs() < 1e-14);
        for (j, o) in list.iter().enumerate() {
            assert_eq!(m["gamma"][j], o["gamma"][i]);
        }
        // Each entry agrees with the pair command.
        let p = json(&["gamma", "--sphere", names[i], "--other", "steel"]);
        let j = names.iter().position(|&n| n == "steel").unwrap();
        assert_eq!(m["gamma"][j].as_f64().unwrap(), num(&p, "gamma"));
    }
    // Yield stress and limiting pressure p_y = 1.60 Y (Pa) of the metals only.
    for m in list {
        let (y, p) = (&m["yield_stress"], &m["limiting_pressure"]);
        assert!(!m["yield_source"].as_str().unwrap().is_empty());
        match m["name"].as_str().unwrap() {
            "steel" => assert_eq!((y.as_f64(), p.as_f64()), (Some(235e6), Some(1.60 * 235e6))),
            "aluminium-6061-t6" => {
                assert_eq!((y.as_f64(), p.as_f64()), (Some(276e6), Some(1.60 * 276e6)))
            }
            _ => assert!(y.is_null() && p.is_null(), "{m}"),
        }
    }
    // The text form lists every material and its source.
    let o = sweep(&["gamma", "--catalogue"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    for n in &names {
        assert!(
            text.contains(&format!("{n}: ")),
            "no source for {n}:\n{text}"
        );
    }
    let yields = text
        .split("yield stress:\n")
        .nth(1)
        .expect("yield stress section");
    for n in &names {
        assert!(yields.contains(&format!("  {n}: ")), "{yields}");
    }
    assert!(text.contains("  Y (MPa)  p_y (MPa)") && text.contains("      276      441.6"));
}

#[test]
fn unknown_material_names_the_catalogue() {
    for args in [
        &["gamma", "--sphere", "glass"][..],
        &["gamma", "--sphere", "steel", "--other", "unobtainium"],
    ] {
        let o = sweep(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        for name in ["soda-lime-glass", "alumina-96", "steel", "nylon", "rigid"] {
            assert!(err.contains(name), "{args:?}: {err}");
        }
        assert!(err.contains("E=PA,nu=NU"), "{err}");
    }
    for (args, says) in [
        (&["gamma", "--sphere", "E=1e9"][..], "needs both E"),
        (&["gamma", "--sphere", "E=1e9,nu=0.7"], "poisson_ratio"),
        (&["gamma", "--sphere", "E=1e9,nu=0.3,k=2"], "unknown key"),
        (&["gamma", "--sphere", "rigid"], "two rigid bodies"),
        (&["gamma", "--sphere", "steel", "--kappa", "0.9"], "kappa"),
        (
            &["gamma", "--sphere", "steel", "--other-radius", "-1"],
            "radius",
        ),
        (
            &[
                "gamma",
                "--sphere",
                "steel",
                "--other-radius",
                "0.01",
                "--other-kappa",
                "0.5",
            ],
            "different kappa",
        ),
        (&["gamma"], "--sphere"),
    ] {
        let o = sweep(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// γ and α are stated for a general pair of bodies, not only for a solid sphere on a wall.
#[test]
fn help_and_readme_give_the_groups_for_a_general_body() {
    let help = |args: &[&str]| String::from_utf8(sweep(args).stdout).unwrap();
    for args in [
        &["--help"][..],
        &["gamma", "--help"],
        &["impact", "--help"],
        &["query", "--help"],
    ] {
        let h = help(args);
        assert!(
            h.contains("sqrt((m*/m_t) G*/E*)") || h.contains("gamma^2 = (m*/m_t) G*/E*"),
            "sweep {args:?}:\n{h}"
        );
        assert!(
            h.contains("(2/7)(m*/m_t) mu v_z0/|u0|"),
            "sweep {args:?}:\n{h}"
        );
    }
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    assert!(
        readme.contains("√((m*/m_t) G*/E*)"),
        "README: gamma of a general body"
    );
    assert!(
        readme.contains("(2/7)(m*/m_t) μ v_z0/"),
        "README: alpha of a general body"
    );
    assert!(
        readme.contains("sweep gamma"),
        "README: the command that prints gamma"
    );
}
