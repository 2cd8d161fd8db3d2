//! `scripts/install-capi.sh` installs what C and C++ programs need, and they build against the
//! installed tree through pkg-config alone, as a user's would: the script runs once into a
//! scratch PREFIX (its build reuses `target/release` when up to date), then `examples/query.c`
//! is compiled as strict C99 and linked to the shared library, then to the static one, and a
//! C++11 translation unit includes the header. The tools (bash, pkg-config, readelf, gcc or
//! `$CC`, g++ or `$CXX`) are required: a missing one fails the test and names it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use oblique_lookup::Table;

const VERSION: &str = env!("CARGO_PKG_VERSION");
const SONAME: &str = "liboblique.so.0";
const STRICT_C: [&str; 5] = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"];
const STRICT_CXX: [&str; 5] = ["-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic"];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("repository root")
}

fn table_path() -> PathBuf {
    repo().join("tables/quick.h5")
}

fn scratch() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("install-capi")
}

/// Run `cmd`; a program that cannot be started fails with `hint` (how to install it).
fn output(cmd: &mut Command, hint: &str) -> Output {
    let program = cmd.get_program().to_string_lossy().into_owned();
    cmd.output().unwrap_or_else(|e| {
        panic!("cannot run `{program}` ({e}): it is required by this test; {hint}")
    })
}

/// Run `cmd`, which must succeed; its standard output.
fn run(cmd: &mut Command, hint: &str) -> String {
    let shown = format!("{cmd:?}");
    let out = output(cmd, hint);
    assert!(
        out.status.success(),
        "{shown} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

const BINUTILS: &str = "install binutils (Debian: apt-get install binutils)";

/// The installed PREFIX, made once for all the tests of this file.
fn prefix() -> &'static Path {
    static PREFIX: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let made = PREFIX.get_or_init(|| {
        let prefix = scratch().join("prefix");
        let _ = std::fs::remove_dir_all(&prefix);
        let out = Command::new("bash")
            .arg(repo().join("scripts/install-capi.sh"))
            .arg(&prefix)
            .output()
            .map_err(|e| format!("cannot run bash: {e}"))?;
        let stderr = String::from_utf8_lossy(&out.stderr);
        if !out.status.success() {
            return Err(format!(
                "install-capi.sh failed ({}):\n{stderr}",
                out.status
            ));
        }
        eprintln!("{stderr}");
        Ok(prefix)
    });
    match made {
        Ok(p) => p,
        Err(e) => panic!("{e}"),
    }
}

/// `pkg-config ARGS oblique` against the installed tree only: its flags, one per element.
fn pkg_config(args: &[&str]) -> Vec<String> {
    let pc_dir = prefix().join("lib/pkgconfig");
    let out = run(
        Command::new("pkg-config")
            .args(args)
            .arg("oblique")
            .env("PKG_CONFIG_PATH", &pc_dir)
            .env_remove("PKG_CONFIG_SYSROOT_DIR"),
        "install pkg-config (Debian: apt-get install pkg-config)",
    );
    out.split_whitespace().map(str::to_string).collect()
}

fn compiler(var: &str, default: &str) -> String {
    std::env::var(var).unwrap_or_else(|_| default.to_string())
}

/// The `NEEDED` entries of an ELF file.
fn needed(elf: &Path) -> Vec<String> {
    let dynamic = run(Command::new("readelf").arg("-d").arg(elf), BINUTILS);
    dynamic
        .lines()
        .filter(|l| l.contains("(NEEDED)"))
        .filter_map(|l| l.split('[').nth(1)?.split(']').next().map(str::to_string))
        .collect()
}

/// Compile `examples/query.c` as strict C99 with `link` flags into `exe`.
fn compile_query(exe: &Path, link: &[String]) {
    let cc = compiler("CC", "gcc");
    run(
        Command::new(&cc)
            .args(STRICT_C)
            .arg("-O2")
            .arg("-o")
            .arg(exe)
            .arg(repo().join("crates/lookup-capi/examples/query.c"))
            .args(pkg_config(&["--cflags"]))
            .args(link),
        "install a C compiler (Debian: apt-get install gcc) or set CC",
    );
}

/// Run the compiled example on `tables/quick.h5` and check what it prints against the Rust API.
fn check_query_output(exe: &Path, ld_library_path: Option<&Path>) {
    let mut cmd = Command::new(exe);
    cmd.arg(table_path()).env_remove("LD_LIBRARY_PATH");
    if let Some(dir) = ld_library_path {
        cmd.env("LD_LIBRARY_PATH", dir);
    }
    let stdout = run(&mut cmd, "it was just compiled");
    let value = |key: &str| -> f64 {
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(key).and_then(|r| r.trim().parse().ok()))
            .unwrap_or_else(|| panic!("no `{key}` line in:\n{stdout}"))
    };
    let t = Table::open(table_path()).expect("tables/quick.h5");
    assert_eq!(value("P(1.754,1)"), t.p(1.754, 1.0).unwrap(), "{stdout}");
    assert_eq!(
        value("P(2,inf)"),
        t.p(2.0, f64::INFINITY).unwrap(),
        "{stdout}"
    );
    let (pair, contact, mut inc) = oblique_lookup::testing::reference_spheres();
    inc.normal = [0.0, 0.0, 1.0];
    let a = t.rebound_3d(&pair, &contact, &inc).unwrap();
    assert_eq!(value("spheres.p"), a.rebound.p, "{stdout}");
    assert_eq!(
        value("prepared.v1x"),
        a.rebound.sphere.velocity[0],
        "{stdout}"
    );
    for i in 0..3 {
        let p = value(&format!("batch[{i}]"));
        assert!((-1.0..=1.0).contains(&p), "batch[{i}] = {p}: {stdout}");
    }
    assert!(stdout.contains("bad gamma: code 4"), "{stdout}");
    assert!(stdout.contains("missing file: code 2"), "{stdout}");
}

#[test]
fn script_has_help_and_rejects_bad_arguments() {
    let script = repo().join("scripts/install-capi.sh");
    let help = run(
        Command::new("bash").arg(&script).arg("--help"),
        "install bash",
    );
    assert!(help.contains("usage: scripts/install-capi.sh"), "{help}");
    assert!(help.contains("pkg-config"), "{help}");
    for args in [&[][..], &["--bogus"][..], &["a", "b"][..]] {
        let out = output(Command::new("bash").arg(&script).args(args), "install bash");
        assert_eq!(
            out.status.code(),
            Some(2),
            "install-capi.sh {args:?}: {out:?}"
        );
    }
}

#[test]
fn installed_tree_is_complete() {
    let prefix = prefix();
    let lib = prefix.join("lib");
    let real = format!("liboblique.so.{VERSION}");
    // The shared library and its two links, as ldconfig and the linker expect them.
    let link = |name: &str| {
        std::fs::read_link(lib.join(name))
            .unwrap_or_else(|e| panic!("lib/{name} is not a symbolic link: {e}"))
    };
    assert_eq!(link("liboblique.so"), Path::new(SONAME));
    assert_eq!(link(SONAME), Path::new(&real));
    let so = lib.join(&real);
    assert!(so.is_file(), "lib/{real} missing");
    let dynamic = run(Command::new("readelf").arg("-d").arg(&so), BINUTILS);
    assert!(
        dynamic.contains(&format!("Library soname: [{SONAME}]")),
        "lib/{real} has no SONAME {SONAME}:\n{dynamic}"
    );
    // Stripped: neither debug information nor a static symbol table; exports only the C ABI.
    let sections = run(Command::new("readelf").arg("-S").arg(&so), BINUTILS);
    for section in [".debug_info", ".symtab"] {
        assert!(
            !sections.contains(section),
            "lib/{real} not stripped: has {section}"
        );
    }
    let symbols = run(Command::new("readelf").arg("--dyn-syms").arg(&so), BINUTILS);
    for name in [
        "oblique_version",
        "oblique_abi_version",
        "oblique_p",
        "oblique_table_open",
    ] {
        assert!(
            symbols.lines().any(|l| l.ends_with(&format!(" {name}"))),
            "lib/{real} does not export {name}"
        );
    }
    let unstripped = repo().join("target/release/liboblique.so");
    if let (Ok(small), Ok(big)) = (so.metadata(), unstripped.metadata()) {
        eprintln!(
            "lib/{real}: {} bytes (target/release/liboblique.so: {} bytes)",
            small.len(),
            big.len()
        );
    }
    let archive = std::fs::read(lib.join("liboblique.a")).expect("lib/liboblique.a");
    assert!(
        archive.starts_with(b"!<arch>\n"),
        "lib/liboblique.a is not an archive"
    );
    let header = std::fs::read_to_string(prefix.join("include/oblique_lookup.h"))
        .expect("include/oblique_lookup.h");
    let source =
        std::fs::read_to_string(repo().join("crates/lookup-capi/include/oblique_lookup.h"))
            .expect("the committed header");
    assert!(
        header == source,
        "include/oblique_lookup.h differs from the committed header"
    );
    // pkg-config: the version, the flags, and what a static link needs.
    assert_eq!(pkg_config(&["--modversion"]), [VERSION]);
    let include = format!("-I{}", prefix.join("include").display());
    assert_eq!(pkg_config(&["--cflags"]), [include]);
    let libdir = format!("-L{}", lib.display());
    assert_eq!(pkg_config(&["--libs"]), [libdir.as_str(), "-loblique"]);
    let static_libs = pkg_config(&["--static", "--libs"]);
    for flag in ["-loblique", "-lhdf5", "-lpthread", "-lm", "-ldl", "-lc"] {
        assert!(
            static_libs.iter().any(|f| f == flag),
            "pkg-config --static --libs lacks {flag}: {static_libs:?}"
        );
    }
}

#[test]
fn c_example_links_to_the_shared_library() {
    let lib = prefix().join("lib");
    let exe = scratch().join("query_shared");
    compile_query(&exe, &pkg_config(&["--libs"]));
    let needs = needed(&exe);
    assert!(
        needs.iter().any(|n| n == SONAME),
        "the example does not need {SONAME}: {needs:?}"
    );
    check_query_output(&exe, Some(&lib));
}

#[test]
fn c_example_links_to_the_static_library() {
    let exe = scratch().join("query_static");
    // `-loblique` would pick liboblique.so, which is next to liboblique.a: name the archive.
    let mut flags = pkg_config(&["--static", "--libs"]);
    let at = flags.iter().position(|f| f == "-loblique");
    let at = at.unwrap_or_else(|| panic!("no -loblique in {flags:?}"));
    flags[at] = "-l:liboblique.a".to_string();
    compile_query(&exe, &flags);
    let needs = needed(&exe);
    assert!(
        !needs.iter().any(|n| n.starts_with("liboblique")),
        "the statically linked example still needs the shared library: {needs:?}"
    );
    check_query_output(&exe, None);
}

#[test]
fn header_compiles_as_cxx11() {
    let lib = prefix().join("lib");
    let dir = scratch();
    let source = dir.join("version.cpp");
    std::fs::write(
        &source,
        r#"#include <cstdio>
#include <cstring>

#include "oblique_lookup.h"

static_assert(OBLIQUE_ABI_VERSION == 1, "ABI version of the header");

int main(int argc, char **argv) {
    if (argc != 2) return 2;
    if (oblique_abi_version() != OBLIQUE_ABI_VERSION) return 3;
    ObliqueTable *table = nullptr;
    if (oblique_table_open(argv[1], &table) != OBLIQUE_OK) return 4;
    double p = 0.0;
    int rc = oblique_p(table, 1.754, 1.0, 0, &p);
    oblique_table_close(table);
    if (rc != OBLIQUE_OK) return 5;
    std::printf("oblique %s abi %d p %.17g\n", oblique_version(), oblique_abi_version(), p);
    return std::strlen(oblique_last_error()) == 0 ? 0 : 6;
}
"#,
    )
    .expect("write the C++ source");
    let exe = dir.join("version_cxx");
    let cxx = compiler("CXX", "g++");
    run(
        Command::new(&cxx)
            .args(STRICT_CXX)
            .arg("-o")
            .arg(&exe)
            .arg(&source)
            .args(pkg_config(&["--cflags", "--libs"])),
        "install a C++ compiler (Debian: apt-get install g++) or set CXX",
    );
    let stdout = run(
        Command::new(&exe)
            .arg(table_path())
            .env("LD_LIBRARY_PATH", &lib),
        "it was just compiled",
    );
    let expected = format!("oblique {VERSION} abi 1 p ");
    let printed = stdout.trim().strip_prefix(&expected);
    let printed = printed.unwrap_or_else(|| panic!("expected `{expected}…`, got `{stdout}`"));
    let p = Table::open(table_path()).unwrap().p(1.754, 1.0).unwrap();
    assert_eq!(printed.parse::<f64>().ok(), Some(p), "{stdout}");
}
