//! Property-based fuzzing of the three places where outside data enters: config
//! parsing, table loading (mutated table files) and queries (arbitrary floats). Nothing may
//! panic; what is accepted must be sane. Bounded for CI (about a minute in all); set
//! `FUZZ_CASES=N` for a longer run, e.g. `FUZZ_CASES=20000 cargo test --release --test fuzz`.

use std::path::PathBuf;
use std::sync::OnceLock;

use oblique_lookup::Table;
use oblique_sweep::Config;
use proptest::prelude::*;
use proptest::test_runner::{Config as PtConfig, TestRunner};

fn cases(default: u32) -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

const GOOD: &str = r#"output = "t.h5"

[domain]
gamma_min = 0.8
gamma_max = 1.6
alpha_max = "inf"

[nodes]
placement = "aligned"
stencil = 4
target_error = 1e-3
leaf_intervals = 8
blocks_per_unit_gamma = 2.0
blocks_coord = 3
max_nodes = 1000

[solver]
tol = 1e-4

[checks]
per_patch = 6
seed = 3
tol = 1e-5

[run]
threads = 0
"#;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn quick_table() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| Table::open(repo().join("tables/quick.h5")).expect("shipped quick table"))
}

/// Replace the value of one `key = value` line of the good config with `value`.
fn with_value(line: usize, value: &str) -> String {
    let lines: Vec<&str> = GOOD.lines().collect();
    let assignments: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].contains(" = "))
        .collect();
    let i = assignments[line % assignments.len()];
    let key = lines[i].split(" = ").next().unwrap_or("");
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    out[i] = format!("{key} = {value}");
    out.join("\n")
}

#[test]
fn config_parsing_never_panics_and_accepts_only_valid_configs() {
    let mut runner = TestRunner::new(PtConfig {
        cases: cases(20_000),
        ..PtConfig::default()
    });
    // Arbitrary text.
    runner
        .run(&".{0,400}", |text| {
            let _ = Config::parse(&text, "fuzz.toml");
            Ok(())
        })
        .expect("arbitrary text");
    // One value of a good config replaced by an arbitrary TOML-ish value.
    let value = prop_oneof![
        any::<f64>().prop_map(|v| format!("{v:e}")),
        any::<i64>().prop_map(|v| v.to_string()),
        Just("\"inf\"".to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        "\"[a-z0-9 ]{0,12}\"",
        Just("[1, 2]".to_string()),
        Just("{}".to_string()),
    ];
    runner
        .run(&(0usize..64, value), |(line, v)| {
            let text = with_value(line, &v);
            if let Ok(cfg) = Config::parse(&text, "fuzz.toml") {
                // Whatever is accepted is within the documented ranges.
                prop_assert!(cfg.domain.gamma_min > 0.0 && cfg.domain.gamma_min.is_finite());
                prop_assert!(cfg.domain.gamma_max > cfg.domain.gamma_min);
                prop_assert!(cfg.solver.tol > 0.0 && cfg.solver.tol.is_finite());
                prop_assert!(cfg.solver.tol <= cfg.nodes.target_error);
                prop_assert!(cfg.check_tol() > 0.0 && cfg.check_tol() <= cfg.solver.tol);
                prop_assert!(!cfg.domain.alpha_max.is_nan());
            }
            Ok(())
        })
        .expect("mutated config");
}

#[test]
fn queries_with_arbitrary_floats_never_panic_and_stay_physical() {
    let t = quick_table();
    let mut runner = TestRunner::new(PtConfig {
        cases: cases(1_000_000),
        ..PtConfig::default()
    });
    let float = prop_oneof![
        any::<f64>(),
        -1.0f64..5.0,
        Just(f64::INFINITY),
        Just(f64::NAN),
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE),
    ];
    runner
        .run(&(float.clone(), float), |(g, a)| {
            match t.p(g, a) {
                Ok(p) => {
                    prop_assert!(p.is_finite(), "P({g}, {a}) = {p}");
                    // Interpolation may overshoot |P| = 1 by its own error, no more.
                    prop_assert!(p.abs() <= 1.0 + 1e-3, "P({g}, {a}) = {p}");
                    // Outside the table's γ range only the exact full-slip line is answered.
                    let s = &t.surface();
                    let inside = g >= s.gamma_min() && g <= s.gamma_max() && a >= 0.0;
                    prop_assert!(
                        inside
                            || (a >= 0.0
                                && a <= oblique_table::surface::linear_limit(g)
                                && p == 1.0 - 7.0 * a),
                        "P({g}, {a}) = {p} outside the table"
                    );
                }
                Err(e) => prop_assert!(!e.to_string().is_empty()),
            }
            Ok(())
        })
        .expect("queries");
}

#[test]
fn mutated_table_files_are_refused_or_read_never_panic() {
    let original = std::fs::read(repo().join("tables/quick.h5")).expect("read quick table");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("fuzz_tables-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create directory");
    let path = dir.join("mutated.h5");
    let n = original.len();
    let mut runner = TestRunner::new(PtConfig {
        cases: cases(2_000),
        ..PtConfig::default()
    });
    let (opened, refused) = (std::cell::Cell::new(0u32), std::cell::Cell::new(0u32));
    runner
        .run(
            &(
                prop::collection::vec((0..n, any::<u8>()), 1..8),
                prop::option::of(0..n),
            ),
            |(flips, cut)| {
                let mut bytes = original.clone();
                for &(i, b) in &flips {
                    bytes[i] = b;
                }
                if let Some(c) = cut {
                    bytes.truncate(c);
                }
                std::fs::write(&path, &bytes).expect("write mutated table");
                match Table::open(&path) {
                    Ok(t) => {
                        opened.set(opened.get() + 1);
                        // A table that opens answers queries without panicking.
                        for &(g, a) in &[(0.6, 0.5), (1.2, 0.2), (2.0, 1.0), (2.4, f64::INFINITY)] {
                            if let Ok(p) = t.p(g, a) {
                                prop_assert!(!p.is_nan() || t.surface().gamma_min().is_nan());
                            }
                        }
                    }
                    Err(e) => {
                        refused.set(refused.get() + 1);
                        prop_assert!(!e.to_string().is_empty());
                    }
                }
                Ok(())
            },
        )
        .expect("mutated tables");
    eprintln!(
        "mutated tables: {} opened, {} refused",
        opened.get(),
        refused.get()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
