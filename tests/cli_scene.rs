//! `sweep scene`: the command writes the CSV and the plot of a shipped scene, refuses values
//! outside the documented ranges naming the key (exit 2, nothing written), and refuses a table
//! that cannot answer a case's `e_n`. What a scene evaluates to is checked in
//! `crates/study/tests/scene.rs`.

use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("scene-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn sweep_scene_writes_csv_and_plot() {
    let out = scratch("cli");
    let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args([
            "scene",
            "configs/scenes/alumina_on_rigid_wall.toml",
            "--svg",
            "-o",
        ])
        .arg(&out)
        .current_dir(root())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("gamma = 1.732051"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("alumina_on_rigid_wall.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    let header: Vec<&str> = lines[0].split(',').collect();
    let expected = [
        "angle_deg",
        "v_x",
        "v_z",
        "omega",
        "e_t",
        "rebound_angle_centre_deg",
        "rebound_angle_contact_deg",
        "P",
        "regime",
        "energy_lost_J",
        "e_t_closed_form",
        "e_t_rolling",
    ];
    assert_eq!(&header[..expected.len()], &expected);
    assert_eq!(lines.len(), 18, "header + 17 angles");
    for l in &lines[1..] {
        assert_eq!(l.split(',').count(), header.len());
    }
    let png = std::fs::read(out.join("alumina_on_rigid_wall.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 10_000);
    let svg = std::fs::read_to_string(out.join("alumina_on_rigid_wall.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("configs/scenes/alumina_on_rigid_wall.toml"));

    // A bad scene: non-zero exit, the key in the message.
    let bad = out.join("bad.toml");
    std::fs::write(&bad, "friction = 0.1\n[sphere]\nradius = 1\n").unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(["scene"])
        .arg(&bad)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("target"), "{stderr}");
}

/// Values outside the documented physical ranges are refused by `sweep scene` with the key and
/// the range (exit code 2, nothing written): a speed of 1e200 m/s and E = 1e-300 Pa were
/// accepted with an infinite energy, ω0 = ±1e300 rad/s gave a NaN energy.
#[test]
fn out_of_range_values_are_refused_naming_the_key() {
    let base = r#"friction = 0.1
[sphere]
youngs_modulus = 2e11
poisson_ratio = 0.3
density = 7800
radius = 0.005
[target]
kind = "wall"
material = "steel"
[cases]
kind = "angles"
speed = 1.0
angles_deg = { from = 10, to = 80, count = 8 }
"#;
    let spin = r#"friction = 0.3
[sphere]
material = "nylon"
radius = 0.01
[target]
kind = "wall"
material = "steel"
[cases]
kind = "spin"
normal_speed = 1.0
omega0 = [-300, 300]
"#;
    let cases: &[(&str, &str, &str, &[&str])] = &[
        (
            base,
            "speed = 1.0",
            "speed = 1e200",
            &["cases.speed = 1e200", "[1e-6, 1000] m/s"],
        ),
        (
            base,
            "youngs_modulus = 2e11",
            "youngs_modulus = 1e-300",
            &["sphere.youngs_modulus = 1e-300", "[1e3, 1e13] Pa"],
        ),
        (
            base,
            "youngs_modulus = 2e11",
            "youngs_modulus = 1e20",
            &["sphere.youngs_modulus", "[1e3, 1e13] Pa"],
        ),
        (
            base,
            "radius = 0.005",
            "radius = 1e-300",
            &["sphere.radius", "[1e-9, 1e3] m"],
        ),
        (
            base,
            "density = 7800",
            "density = 1e-300",
            &["sphere.density", "[1e0, 1e5]"],
        ),
        (
            spin,
            "omega0 = [-300, 300]",
            "omega0 = [-1e300, 300]",
            &["cases.omega0 = -1e300", "|omega| * radius <= 1000 m/s"],
        ),
        (
            spin,
            "omega0 = [-300, 300]",
            "omega0 = [-300, 1e300]",
            &["cases.omega0 = 1e300", "1e5 rad/s"],
        ),
        (
            spin,
            "normal_speed = 1.0",
            "normal_speed = 1.0\ntangential_speed = -2e3",
            &["cases.tangential_speed", "1000 m/s"],
        ),
        (
            spin,
            "normal_speed = 1.0",
            "normal_speed = 1e-300",
            &["cases.normal_speed = 1e-300", "[1e-6, 1000] m/s"],
        ),
        (
            base,
            "[target]\nkind = \"wall\"\nmaterial = \"steel\"",
            "[target]\nkind = \"sphere\"\nmaterial = \"steel\"\nradius = 0.01\nv_z = 0.9999999999",
            &[
                "cases.angles_deg",
                "approaches the target at >= 1e-6 m/s",
                "m/s there",
            ],
        ),
    ];
    let dir = scratch("ranges");
    for (text, from, to, want) in cases {
        assert!(text.contains(from), "test case does not apply: {from}");
        let file = dir.join("bad.toml");
        std::fs::write(&file, text.replacen(from, to, 1)).unwrap();
        let out_dir = dir.join("out");
        let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("scene")
            .arg(&file)
            .arg("-o")
            .arg(&out_dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{to}: {stderr}");
        for w in *want {
            assert!(stderr.contains(w), "error for {to:?} lacks {w:?}: {stderr}");
        }
        assert!(stderr.len() < 400, "{stderr}");
        assert!(!out_dir.join("bad.csv").exists(), "{to}: a CSV was written");
    }
}

/// A table that cannot answer a case's e_n is refused (exit 2), naming e_n and the range.
#[test]
fn a_table_without_the_case_e_n_is_refused_naming_e_n_and_the_range() {
    let out = scratch("restitution");
    let text = std::fs::read_to_string(root().join("configs/scenes/steel_on_steel_damped.toml"))
        .unwrap()
        .replace("relaxation_time = 1e-6", "e_n = 0.4");
    let low = out.join("low.toml");
    std::fs::write(&low, &text).unwrap();
    let damped = root().join("configs/scenes/steel_on_steel_damped.toml");
    for (scene_file, table, expect) in [
        (
            &low,
            "tables/dissipative-demo.h5",
            "covers e_n in [0.5, 1] only",
        ),
        (&damped, "tables/quick.h5", "no e_n axis"),
    ] {
        let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("scene")
            .arg(scene_file)
            .args(["--table", table, "-o"])
            .arg(&out)
            .current_dir(root())
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains(expect) && stderr.contains("the case has e_n = "),
            "{stderr}"
        );
        // The first case in sweep order is named, whichever thread met it first.
        assert!(stderr.contains("case angle_deg = 5:"), "{stderr}");
        assert!(!out.join("steel_on_steel_damped.csv").exists());
    }
}

/// Steel shot with Thornton's limiting pressure: `sweep scene` names the law in the summary and
/// in the CSV's `law` column; with `relaxation_time` too it is refused naming both keys
/// (exit 2, nothing written).
#[test]
fn a_yield_pressure_scene_names_thorntons_law_and_two_laws_are_refused() {
    let out = scratch("thornton");
    let text = "name = \"shot\"\nfriction = 0.3\nyield_pressure = 2e9\n\n[sphere]\n\
                material = \"steel\"\nradius = 1e-3\n\n[target]\nkind = \"wall\"\n\
                material = \"steel\"\n\n[cases]\nkind = \"angles\"\nspeed = 1.0\n\
                angles_deg = [10, 50, 85]\n";
    let file = out.join("shot.toml");
    std::fs::write(&file, text).unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .arg("scene")
        .arg(&file)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        stdout.contains("(Thornton's law, limiting pressure 2e9 Pa with each case's impact speed)"),
        "{stdout}"
    );
    let csv = std::fs::read_to_string(out.join("shot.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert!(lines[0].ends_with(",e_n,law"), "{}", lines[0]);
    assert_eq!(lines.len(), 4);
    // 85°: v_z0 = 0.087 m/s, below the yield speed (about 0.24 m/s): elastic, e_n = 1.
    assert!(lines[1..].iter().all(|l| l.ends_with(",thornton")), "{csv}");
    assert!(lines[3].ends_with(",1,thornton"), "{csv}");
    assert!(!lines[1].ends_with(",1,thornton"), "{csv}");

    let both = out.join("both.toml");
    std::fs::write(
        &both,
        text.replace(
            "yield_pressure = 2e9",
            "yield_pressure = 2e9\nrelaxation_time = 1e-6",
        ),
    )
    .unwrap();
    let run = Command::new(env!("CARGO_BIN_EXE_sweep"))
        .arg("scene")
        .arg(&both)
        .arg("-o")
        .arg(out.join("both"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("invalid yield_pressure") && stderr.contains("relaxation_time"),
        "{stderr}"
    );
    assert!(!out.join("both").join("shot.csv").exists());
}

/// `yield_pressure = "catalogue"` takes the lower limiting pressure of the bodies' catalogue
/// materials (1.60 Y): steel on aluminium 6061-T6 runs as `yield_pressure = 3.76e8` (steel's
/// 1.60 x 235 MPa, below aluminium's 441.6 MPa), to the byte; without a catalogue metal, or
/// with another word, it is refused naming the key (exit 2).
#[test]
fn a_catalogue_yield_pressure_is_the_softer_metals() {
    let out = scratch("catalogue_yield");
    let text = "name = \"shot\"\nfriction = 0.3\nyield_pressure = \"catalogue\"\n\n[sphere]\n\
                material = \"steel\"\nradius = 1e-3\n\n[target]\nkind = \"wall\"\n\
                material = \"aluminium-6061-t6\"\n\n[cases]\nkind = \"angles\"\nspeed = 0.2\n\
                angles_deg = [10, 50, 85]\n";
    let run = |name: &str, text: &str| {
        let dir = out.join(name);
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("shot.toml");
        std::fs::write(&file, text).unwrap();
        let r = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("scene")
            .arg(&file)
            .arg("-o")
            .arg(&dir)
            .output()
            .unwrap();
        (r, dir.join("shot.csv"))
    };
    let (a, csv_a) = run("catalogue", text);
    let stdout = String::from_utf8_lossy(&a.stdout);
    assert!(a.status.success(), "{}", String::from_utf8_lossy(&a.stderr));
    assert!(stdout.contains("limiting pressure 3.76e8 Pa"), "{stdout}");
    let (b, csv_b) = run(
        "pascal",
        &text.replace("yield_pressure = \"catalogue\"", "yield_pressure = 3.76e8"),
    );
    assert!(b.status.success(), "{}", String::from_utf8_lossy(&b.stderr));
    let (ca, cb) = (
        std::fs::read_to_string(&csv_a).unwrap(),
        std::fs::read_to_string(&csv_b).unwrap(),
    );
    assert_eq!(ca, cb);
    assert!(ca.lines().skip(1).all(|l| l.ends_with(",thornton")), "{ca}");
    for (name, bad, says) in [
        (
            "glass",
            text.replace("\"steel\"", "\"soda-lime-glass\"")
                .replace("\"aluminium-6061-t6\"", "\"rigid\""),
            "steel, aluminium-6061-t6",
        ),
        (
            "word",
            text.replace("\"catalogue\"", "\"steel\""),
            "or \"catalogue\"",
        ),
    ] {
        let (r, csv) = run(name, &bad);
        let stderr = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("invalid yield_pressure") && stderr.contains(says),
            "{stderr}"
        );
        assert!(!csv.exists());
    }
}
