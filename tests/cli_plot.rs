//! `sweep plot`: the command writes valid PNG and SVG files (the same sheets the library
//! builds), draws the restitution figure only when asked, and fails cleanly on bad input. What
//! the figures hold is checked in `crates/study/tests/figures.rs`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use oblique_lookup::Table;
use oblique_study::figures::{self, FigureKind, Source};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn quick() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| Table::open(root().join("tables/quick.h5")).expect("shipped table quick.h5"))
}

fn src() -> Source {
    Source {
        table: "tables/full.h5".into(),
        command: "sweep plot tables/full.h5 -o out".into(),
    }
}

fn scratch(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("plot-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn sweep(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("run sweep")
}

fn assert_png(path: &Path, size: (u32, u32)) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((w, h), size, "{}", path.display());
    assert_eq!(&bytes[bytes.len() - 8..bytes.len() - 4], b"IEND");
}

#[test]
fn sweep_plot_writes_every_figure_as_png() {
    let out = scratch("png");
    let out_s = out.to_str().unwrap();
    let run = sweep(&["plot", "tables/quick.h5", "-o", out_s]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let sizes = [
        (FigureKind::Surface, (1200, 860)),
        (FigureKind::Slices, (1200, 1250)),
        (FigureKind::Regimes, (1200, 800)),
        (FigureKind::Quality, (1200, 860)),
    ];
    for (kind, size) in sizes {
        let path = out.join(format!("{}.png", kind.stem()));
        assert_png(&path, size);
        assert!(stdout.contains(&format!("{}.png", kind.stem())), "{stdout}");
        // The figure is the same sheet the library builds (its size is part of the data).
        let sheet = figures::build(
            kind,
            quick(),
            &src(),
            &figures::default_gammas(quick()),
            &figures::default_alphas(quick()),
            &[],
        )
        .unwrap();
        assert_eq!(sheet.size, size);
    }
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 4);
}

#[test]
fn sweep_plot_writes_selected_figures_as_svg() {
    let out = scratch("svg");
    let run = sweep(&[
        "plot",
        "tables/quick.h5",
        "-o",
        out.to_str().unwrap(),
        "--format",
        "svg",
        "--figure",
        "surface",
        "--figure",
        "slices",
        "--gammas",
        "1.2,2",
        "--alphas",
        "0.5,inf",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, vec!["p_slices.svg", "p_surface.svg"]);
    for n in &names {
        let text = std::fs::read_to_string(out.join(n)).unwrap();
        assert!(text.starts_with("<svg"), "{n}");
        assert!(text.trim_end().ends_with("</svg>"), "{n}");
        assert!(text.contains("tables/quick.h5"), "{n}: provenance caption");
    }
    let slices = std::fs::read_to_string(out.join("p_slices.svg")).unwrap();
    for label in ["γ = 1.2", "γ = 2", "α = 0.5", "α = ∞ (no slip)", "fit (29)"] {
        assert!(slices.contains(label), "legend entry {label}");
    }
    assert!(slices.contains("--gammas 1.2,2 --alphas 0.5,inf"));
}

fn assert_clean_failure(run: &Output, code: i32, needle: &str) {
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(code), "{stderr}");
    assert!(stderr.contains(needle), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn sweep_plot_fails_cleanly_on_bad_input() {
    let out = scratch("bad");
    let o = out.to_str().unwrap();
    // Missing table.
    let run = sweep(&["plot", "no/such/table.h5", "-o", o]);
    assert_clean_failure(&run, 2, "no such file");
    assert_eq!(String::from_utf8_lossy(&run.stderr).lines().count(), 1);
    // Not a table.
    let junk = out.join("junk.h5");
    std::fs::write(&junk, b"not hdf5").unwrap();
    let run = sweep(&["plot", junk.to_str().unwrap(), "-o", o]);
    assert_clean_failure(&run, 2, "not an HDF5 file");
    // Output folder below a file: the user's to fix.
    let run = sweep(&[
        "plot",
        "tables/quick.h5",
        "-o",
        junk.join("sub").to_str().unwrap(),
    ]);
    assert_clean_failure(&run, 2, "junk.h5 exists and is not a folder");
    // Usage errors exit with 2, before anything is written.
    let run = sweep(&["plot", "tables/quick.h5", "-o", o, "--format", "jpg"]);
    assert_clean_failure(&run, 2, "jpg");
    let run = sweep(&["plot", "tables/quick.h5", "-o", o, "--gammas", "9"]);
    assert_clean_failure(&run, 2, "--gammas");
    let run = sweep(&["plot", "tables/quick.h5", "-o", o, "--alphas", "x"]);
    assert_clean_failure(&run, 2, "not a number");
    let written = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .map(|e| e.file_name() != "junk.h5")
                .unwrap_or(true)
        })
        .count();
    assert_eq!(written, 0);
}

#[test]
fn sweep_plot_help_teaches() {
    let run = sweep(&["plot", "--help"]);
    assert!(run.status.success());
    let help = String::from_utf8_lossy(&run.stdout);
    for needle in [
        "Examples:",
        "sweep plot tables/full.h5",
        "p_surface",
        "check_errors",
        "--gammas",
        "--format",
    ] {
        assert!(help.contains(needle), "help lacks {needle}:\n{help}");
    }
}

#[test]
fn sweep_plot_draws_the_restitution_figure_only_when_asked_and_refuses_an_elastic_table() {
    let out = scratch("restitution");
    let o = out.to_str().unwrap();
    let run = sweep(&[
        "plot",
        "tables/dissipative-demo.h5",
        "--figure",
        "restitution",
        "--e-n",
        "0.6,1",
        "--gammas",
        "1.75",
        "-o",
        o,
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("p_restitution.png"), "{stdout}");
    let png = std::fs::read(out.join("p_restitution.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 10_000);
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
    for (args, needle) in [
        (
            vec![
                "plot",
                "tables/quick.h5",
                "--figure",
                "restitution",
                "-o",
                o,
            ],
            "invalid --figure: restitution needs a table with an e_n axis",
        ),
        (
            vec![
                "plot",
                "tables/dissipative-demo.h5",
                "--figure",
                "restitution",
                "--e-n",
                "0.4",
                "-o",
                o,
            ],
            "invalid --e-n: 0.4 is not an e_n in the table's range [0.5, 1]",
        ),
    ] {
        let run = sweep(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(needle), "{stderr}");
    }
}
