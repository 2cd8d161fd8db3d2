//! The fold F₋ of a table of Thornton's law (`nodes.probe_kinks`): plasticity brings it to lower
//! γ the lower `e_n` (born at γ 1.87 for `e_n` = 0.3), the builder traces it (and the
//! end-of-contact curve E₋) as a surface and measures the cells next to it by direct
//! simulations (and the edges of the `+` strip), and the table holds its stated bound next to
//! it (`sweep verify --near-fold`).
//! A table that reaches F₋ without the key is refused, naming the field.

mod common;
use common::{subdir, sweep, sweep_ok as ok, sweep_refused as refused};

/// γ 2.25–2.35, `e_n` 0.55–0.65: F₋ at α 0.41–0.46 (0.27–0.29 `α_c2`) all across, E₋ below it.
const BODY: &str = "[domain]
gamma_min = 2.25
gamma_max = 2.35
alpha_max = 1.7
e_n_min = 0.55
e_n_max = 0.65

[nodes]
target_error = 2e-4
leaf_intervals = 6
blocks_per_unit_gamma = 10
blocks_coord = 2
probe_kinks = true
max_nodes = 200000

[solver]
law = \"thornton\"
tol = 2e-5

[checks]
per_patch = 30
seed = 1
";

#[test]
fn the_cells_next_to_thornton_fold_minus_are_measured() {
    let dir = subdir("thornton-fold-minus");
    let out = dir.join("f.h5");
    let cfg = dir.join("f.toml");
    let path = |p: &std::path::Path| p.to_str().expect("path").to_string();
    std::fs::write(&cfg, format!("output = {:?}\n{BODY}", path(&out))).expect("config");
    let run = sweep(&["run", &path(&cfg)]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(err.contains("probes next to F-"), "{err}");
    assert!(
        err.lines()
            .any(|l| l.contains("probes next to") && l.contains("E-")),
        "{err}"
    );
    // ... and next to both edges of the `+` strip, which rises through α_c2 into the stick
    // patch here (γ 2.3: 1.08–1.17 α_c2 at e_n 0.55, ending near 0.575).
    for patch in ["partial_high", "stick_high"] {
        assert!(
            err.lines().any(|l| l.contains(patch)
                && l.contains("probes next to")
                && l.contains("F+lo and F+hi")),
            "{patch}: {err}"
        );
    }
    // Next to F₋ (located on the traced surface) the table errs less than it states.
    let v = sweep(&[
        "verify",
        &path(&out),
        "--near-fold",
        "--points",
        "40",
        "--seed",
        "3",
        "--quiet",
    ]);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&v.stdout),
        String::from_utf8_lossy(&v.stderr),
    );
    assert!(v.status.success(), "{stderr}");
    assert!(stderr.contains("of the fold surface F-"), "{stderr}");
    assert!(stdout.contains("points above it: 0"), "{stdout}");
    // And next to F₋ among the seven kinds of --near-folds.
    let folds = ok(&[
        "verify",
        &path(&out),
        "--near-folds",
        "--points",
        "14",
        "--seed",
        "5",
        "--quiet",
    ]);
    assert!(folds.lines().any(|l| l.starts_with("near F- ")), "{folds}");
    // Without the probes the range is refused: F₋ is born at γ 1.948 (less the margin) for
    // e_n_min 0.55.
    let bare = dir.join("bare.toml");
    std::fs::write(
        &bare,
        format!(
            "output = {:?}\n{}",
            path(&dir.join("bare.h5")),
            BODY.replace("probe_kinks = true\n", "")
        ),
    )
    .expect("config");
    refused(
        &["run", &path(&bare)],
        &[
            "domain.gamma_max",
            "e_n_min = 0.55",
            "nodes.probe_kinks = true",
        ],
    );
}
