//! The C ABI: the committed header is what cbindgen generates from `src/lib.rs`, and the C
//! example `examples/query.c` compiles against it with the system C compiler (`cc`, or `$CC`),
//! links to the `cdylib` and runs, checking its results against the Rust API.

use std::path::{Path, PathBuf};
use std::process::Command;

use oblique_lookup::{OutOfDomain, Table};

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn table_path() -> PathBuf {
    crate_dir().join("../../tables/quick.h5")
}

#[test]
fn header_is_up_to_date() {
    let dir = crate_dir();
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_crate(&dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = dir.join("include/oblique_lookup.h");
    if std::env::var_os("UPDATE_HEADER").is_some() {
        std::fs::write(&path, &generated).expect("write the header");
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "{} is out of date with src/lib.rs: regenerate it with \
         `UPDATE_HEADER=1 cargo test -p oblique-lookup-capi --test c_abi` and commit it",
        path.display()
    );
    for name in [
        "oblique_table_open",
        "oblique_table_close",
        "oblique_p",
        "oblique_p_batch",
        "oblique_p_e",
        "oblique_table_restitution",
        "oblique_curve_new",
        "oblique_curve_p",
        "oblique_curve_free",
        "oblique_rebound_wall",
        "oblique_rebound_spheres",
        "oblique_prepare_table",
        "oblique_last_error",
        "oblique_version",
        "oblique_abi_version",
        "OBLIQUE_ERR_QUERY",
        "#define OBLIQUE_ABI_VERSION 1",
    ] {
        assert!(generated.contains(name), "header lacks {name}");
    }
}

/// The directory holding `liboblique.so`: the `deps` directory of this test binary
/// (`target/<profile>/deps/c_abi-…`), where `cargo test` builds the library from the sources
/// under test, else the profile directory. The copy in the profile directory is only refreshed
/// by `cargo build`, so a build of other sources left there would otherwise be tested.
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    let profile = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps");
    for dir in [profile.join("deps"), profile.to_path_buf()] {
        if dir.join("liboblique.so").is_file() {
            return dir;
        }
    }
    panic!(
        "liboblique.so not found in {} (crate-type cdylib)",
        profile.display()
    );
}

#[test]
fn c_example_compiles_and_runs() {
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let exe = out_dir.join("query_c");
    let lib = lib_dir();
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "-o"])
        .arg(&exe)
        .arg(crate_dir().join("examples/query.c"))
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg("-L")
        .arg(&lib)
        .args(["-loblique", "-lm"])
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(status.success(), "compiling examples/query.c failed");

    // The library's SONAME is liboblique.so.0 (build.rs), the name the executable asks the
    // loader for: give it that name, in a folder of this test's own.
    let run_dir = out_dir.join("c_abi_lib");
    std::fs::create_dir_all(&run_dir).expect("create the library folder");
    let soname = run_dir.join("liboblique.so.0");
    let _ = std::fs::remove_file(&soname);
    std::os::unix::fs::symlink(lib.join("liboblique.so"), &soname).expect("link liboblique.so.0");
    let out = Command::new(&exe)
        .arg(table_path())
        .env("LD_LIBRARY_PATH", &run_dir)
        .output()
        .expect("run the C example");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "C example failed: {stdout}\n{stderr}");

    // Compare its numbers with the Rust API: `key value` lines.
    let value = |key: &str| -> f64 {
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(key).and_then(|r| r.trim().parse().ok()))
            .unwrap_or_else(|| panic!("no `{key}` line in {stdout}"))
    };
    let t = Table::open(table_path()).unwrap();
    assert_eq!(value("P(1.754,1)"), t.p(1.754, 1.0).unwrap());
    assert_eq!(value("P(2,inf)"), t.p(2.0, f64::INFINITY).unwrap());
    let curve = t.curve(1.754, OutOfDomain::Error).unwrap();
    assert_eq!(value("curve(1.754) P(1)"), curve.p(1.0).unwrap());
    assert!((value("curve(1.754) P(1)") - t.p(1.754, 1.0).unwrap()).abs() <= 1e-14);
    // The impact of examples/query.c: the benchmarks' one with the normal along z.
    let (pair, contact, mut inc) = oblique_lookup::testing::reference_spheres();
    inc.normal = [0.0, 0.0, 1.0];
    let a = t.rebound_3d(&pair, &contact, &inc).unwrap();
    assert_eq!(value("spheres.gamma"), a.gamma);
    assert_eq!(value("spheres.p"), a.rebound.p);
    assert_eq!(value("spheres.v1x"), a.rebound.sphere.velocity[0]);
    assert_eq!(value("spheres.w2y"), a.rebound.other.unwrap().spin[1]);
    assert_eq!(value("spheres.energy_lost"), a.rebound.energy_lost);
    // Table::rebound_3d goes through Prepared: the prepared C call gives the same bits.
    assert_eq!(value("prepared.p"), a.rebound.p);
    assert_eq!(value("prepared.v1x"), a.rebound.sphere.velocity[0]);
    // The error paths the example exercises.
    assert!(stdout.contains("bad gamma: code 4"), "{stdout}");
    assert!(stdout.contains("missing file: code 2"), "{stdout}");
}
