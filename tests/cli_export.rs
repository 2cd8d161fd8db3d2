//! `sweep export`: the file it writes is the format crate's export of the table, the C source
//! holds the same bytes, bad arguments are refused with exit status 2, and the exports of the
//! shipped tables keep their bytes.

mod common;
use common::sweep;

use std::path::Path;

use oblique_lookup::{OutOfDomain, Table};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn export_writes_the_format_crates_bytes_and_a_c_source_of_them() {
    let dir = common::subdir("cli_export");
    let table = Path::new(ROOT).join("tables/quick.h5");
    let out = dir.join("q.oblq");
    let r = sweep(&[
        "export",
        table.to_str().expect("path"),
        "-o",
        out.to_str().expect("path"),
        "--gamma",
        "1.2",
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let t = Table::open(&table).expect("table");
    let curve = t.curve(1.2, OutOfDomain::Error).expect("curve");
    let want = oblique_table::export::export(
        t.surface(),
        t.error_bound(),
        true,
        &[curve.export_data().expect("inside")],
    );
    assert_eq!(std::fs::read(&out).expect("export"), want);
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("the table and 1 curve"), "{text}");

    let c = dir.join("q.c");
    let r = sweep(&[
        "export",
        table.to_str().expect("path"),
        "-o",
        c.to_str().expect("path"),
        "--gamma",
        "1.2",
        "--name",
        "quick_table",
    ]);
    assert!(r.status.success());
    let src = std::fs::read_to_string(&c).expect("source");
    assert!(src.contains(&format!("const size_t quick_table_size = {};", want.len())));
    let words: Vec<u64> = src
        .split("0x")
        .skip(1)
        .map(|w| u64::from_str_radix(&w[..16], 16).expect("hex word"))
        .collect();
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    assert_eq!(&bytes[..want.len()], &want[..]);
}

#[test]
fn export_refuses_bad_arguments_with_status_2() {
    let dir = common::subdir("cli_export_bad");
    let table = Path::new(ROOT).join("tables/quick.h5");
    let t = table.to_str().expect("path");
    let o = dir.join("x.oblq");
    let o = o.to_str().expect("path");
    for (args, says) in [
        (vec!["export", t, "-o", o, "--gamma", "9"], "gamma"),
        (vec!["export", t, "-o", o, "--gamma", "nan"], "gamma"),
        (vec!["export", t, "-o", o, "--curves-only"], "--gamma"),
        (
            vec!["export", t, "-o", "/nonexistent-dir/x.oblq"],
            "does not exist",
        ),
        (
            vec!["export", t, "-o", dir.to_str().expect("path")],
            "is a directory",
        ),
        (vec!["export", t, "-o", o, "--name", "9x"], "C identifier"),
        (vec!["export", "/nonexistent.h5", "-o", o], "no such file"),
    ] {
        let r = sweep(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!Path::new(o).exists(), "{args:?} wrote a file");
    }
}

/// `--name` becomes the array of a C source: a name that a C or C++ compiler refuses (a
/// keyword, a name <stddef.h> defines, a reserved one) is refused before anything is written,
/// naming the flag and why.
#[test]
fn export_refuses_c_names_a_compiler_would_refuse() {
    let dir = common::subdir("cli_export_names");
    let table = Path::new(ROOT).join("tables/quick.h5");
    let t = table.to_str().expect("path");
    let o = dir.join("x.c");
    let o = o.to_str().expect("path");
    for (name, says) in [
        ("int", "keyword"),
        ("while", "keyword"),
        ("_Bool", "keyword"),
        ("class", "keyword"),
        ("xor", "keyword"),
        ("size_t", "<stddef.h>"),
        ("__table", "reserved"),
        ("_Table", "reserved"),
        ("a-b", "C identifier"),
        ("", "C identifier"),
    ] {
        let r = sweep(&["export", t, "-o", o, "--name", name]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{name:?}: {err}");
        assert!(
            err.contains("--name") && err.contains(says),
            "{name:?}: {err}"
        );
        assert!(!Path::new(o).exists(), "{name:?} wrote a file");
    }
    // Names that contain a keyword are names like any other.
    for name in ["integer", "int_table", "table_int"] {
        let r = sweep(&["export", t, "-o", o, "--name", name]);
        assert!(
            r.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        let src = std::fs::read_to_string(o).expect("source");
        assert!(src.contains(&format!("const unsigned long long {name}[")));
    }
}

/// The exports of the shipped tables keep their bytes: layout versions 1 (with two curves), 2,
/// 3, 5 and 6, each pinned by its length and 64-bit FNV-1a hash (a later version, or a field
/// of a later version, changes no byte of an export that has no use for it).
#[test]
fn the_exports_of_the_shipped_tables_keep_their_bytes() {
    for (name, gammas, version, len, hash) in [
        (
            "quick",
            &[1.2, 0.5][..],
            1,
            41_360,
            0xa72d_78b9_5346_cfe7u64,
        ),
        ("dissipative-demo", &[], 2, 231_680, 0x4dab_aa27_b9e7_1fc2),
        ("dissipative-pair", &[], 3, 22_584, 0xd5d5_e5ac_6dfd_82d6),
        ("dissipative", &[], 5, 6_093_888, 0x82cf_83bb_1f3c_a66d),
        ("full", &[], 6, 1_584_616, 0xc594_0e27_c219_12dc),
    ] {
        let t = Table::open(Path::new(ROOT).join(format!("tables/{name}.h5"))).expect("table");
        let curves: Vec<_> = gammas
            .iter()
            .map(|&g| {
                let c = t.curve(g, OutOfDomain::Error).expect("curve");
                c.export_data().expect("inside")
            })
            .collect();
        let bytes = oblique_table::export::export(t.surface(), t.error_bound(), true, &curves);
        assert_eq!(
            bytes[8..12],
            u32::to_le_bytes(version),
            "{name}: the version"
        );
        assert_eq!(
            (bytes.len(), oblique_table::format::fnv1a64(&bytes)),
            (len, hash),
            "{name}: the export's bytes changed"
        );
    }
}
