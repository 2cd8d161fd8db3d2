//! Tests of the HDF5 table (schema v3) against its specification, `docs/table-format.md`:
//! the file layout (names, types, shapes) as documented, `oblique_lookup::Table` reproducing the
//! held-out checks and the exact full-slip line, atomic writes under SIGKILL, unwritable outputs,
//! thread-count independence, `sweep inspect --json`, and refusal of bad files.
//!
//! Tables are built by the real `sweep` binary from a small inline config (well under a second
//! of solving each) into a scratch directory under `CARGO_TARGET_TMPDIR`.
#![cfg(unix)]

use std::collections::{BTreeSet, HashMap};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::OnceLock;

mod common;
use common::{scratch, subdir};
use std::time::{Duration, Instant};

use hdf5::types::{FloatSize, IntSize, TypeDescriptor, VarLenUnicode};
use oblique_lookup::testing::fork_guard;
use oblique_lookup::Table;
use oblique_table::surface::{alpha_c1, alpha_c2, linear_limit};
use oblique_table::surface::{PatchId, PatchKind, Warp};

/// Small table: all three patches (γ from 0.8 to 1.6), several root cells along γ, leaves at
/// mixed depths, α up to ∞.
const SMALL_CONFIG: &str = r#"# tests/table_format.rs: small table with all three patches
output = "unused.h5"

[domain]
gamma_min = 0.8
gamma_max = 1.6
alpha_max = "inf"

[nodes]
placement = "aligned"
stencil = 4
target_error = 1e-4
leaf_intervals = 8
blocks_per_unit_gamma = 2.0
blocks_coord = 3

[solver]
tol = 2e-5

[checks]
per_patch = 6
seed = 3
"#;

/// A run that takes far longer than the 300 ms after which the atomic-write test kills it.
const SLOW_CONFIG: &str = r#"output = "unused.h5"

[domain]
gamma_min = 0.3
gamma_max = 3.0
alpha_max = "inf"

[nodes]
target_error = 1e-7
max_nodes = 200000

[solver]
tol = 1e-7

[checks]
per_patch = 1
"#;

const GAMMA_MIN: f64 = 0.8;
const GAMMA_MAX: f64 = 1.6;
const CHECKS_PER_PATCH: usize = 6;
const NODE_TOL: f64 = 2e-5;
const TARGET_ERROR: f64 = 1e-4;

/// What a table was built from (the values the layout check expects).
struct Expect {
    gamma_min: f64,
    gamma_max: f64,
    alpha_max: f64,
    config: String,
    /// Built with `nodes.anisotropic`: every patch has the dataset `split`.
    anisotropic: bool,
}

impl Expect {
    fn small() -> Self {
        Expect {
            gamma_min: GAMMA_MIN,
            gamma_max: GAMMA_MAX,
            alpha_max: f64::INFINITY,
            config: SMALL_CONFIG.to_string(),
            anisotropic: false,
        }
    }

    /// SMALL_CONFIG with `nodes.anisotropic = true`: cells halve only the axes they need.
    fn anisotropic() -> Self {
        let config = SMALL_CONFIG.replace(
            "blocks_coord = 3\n",
            "blocks_coord = 3\nanisotropic = true\n",
        );
        assert_ne!(config, SMALL_CONFIG);
        Expect {
            config,
            anisotropic: true,
            ..Expect::small()
        }
    }

    /// SMALL_CONFIG with another domain.
    fn variant(gamma_min: f64, gamma_max: f64, alpha_max: f64) -> Self {
        let am = if alpha_max.is_infinite() {
            "\"inf\"".to_string()
        } else {
            format!("{alpha_max:?}")
        };
        let config = SMALL_CONFIG
            .replace("gamma_min = 0.8", &format!("gamma_min = {gamma_min:?}"))
            .replace("gamma_max = 1.6", &format!("gamma_max = {gamma_max:?}"))
            .replace("alpha_max = \"inf\"", &format!("alpha_max = {am}"));
        Expect {
            gamma_min,
            gamma_max,
            alpha_max,
            config,
            anisotropic: false,
        }
    }

    /// The patches the doc says the domain has.
    fn patches(&self) -> Vec<&'static str> {
        PATCHES
            .iter()
            .map(|x| x.0)
            .filter(|&n| {
                if n == "stick_low" {
                    self.gamma_min < 1.0
                } else {
                    self.gamma_max > 1.0
                }
            })
            .collect()
    }
}

// ---------------------------------------------------------------------------------------------
// What docs/table-format.md says is in the file (checked against the doc text below).

#[derive(Clone, Copy, Debug, PartialEq)]
enum Ty {
    F64,
    I32,
    U8,
    Str,
}

impl Ty {
    fn descriptor(self) -> TypeDescriptor {
        match self {
            Ty::F64 => TypeDescriptor::Float(FloatSize::U8),
            Ty::I32 => TypeDescriptor::Integer(IntSize::U4),
            Ty::U8 => TypeDescriptor::Unsigned(IntSize::U1),
            Ty::Str => TypeDescriptor::VarLenUnicode,
        }
    }
}

/// Root attributes.
const ROOT_ATTRS: &[(&str, Ty)] = &[
    ("format", Ty::Str),
    ("schema_version", Ty::F64),
    ("stencil_points", Ty::F64),
    ("gamma_min", Ty::F64),
    ("gamma_max", Ty::F64),
    ("alpha_max", Ty::F64),
    ("node_tol", Ty::F64),
    ("check_tol", Ty::F64),
    ("target_error", Ty::F64),
    ("engine_version", Ty::Str),
    ("git_commit", Ty::Str),
    ("config", Ty::Str),
    ("solver", Ty::Str),
    ("created", Ty::Str),
    ("wall_time_s", Ty::F64),
];

/// Patches and their `kind`.
const PATCHES: &[(&str, &str)] = &[
    ("stick_low", "stick"),
    ("partial_high", "partial-slip"),
    ("stick_high", "stick"),
];

/// Patch attributes.
const PATCH_ATTRS: &[(&str, Ty)] = &[
    ("kind", Ty::Str),
    ("gamma_lo", Ty::F64),
    ("gamma_hi", Ty::F64),
    ("blocks_gamma", Ty::F64),
    ("blocks_coord", Ty::F64),
    ("leaf_intervals", Ty::F64),
];

/// A leaf's square `(x0, c0, hx, hc)` in patch coordinates and its depth.
type LeafSquare = (f64, f64, f64, f64, i32);

#[derive(Clone, Copy, Debug, PartialEq)]
enum PatchShape {
    /// `[cells]`
    Cells,
    /// `[leaves]`
    Leaves,
    /// `[leaves, m+1, m+1]`
    Nodes,
}

/// Patch datasets.
const PATCH_DATASETS: &[(&str, Ty, PatchShape)] = &[
    ("tree", Ty::I32, PatchShape::Cells),
    ("P", Ty::F64, PatchShape::Nodes),
    ("error_estimate", Ty::F64, PatchShape::Nodes),
    ("gamma", Ty::F64, PatchShape::Nodes),
    ("coord", Ty::F64, PatchShape::Nodes),
    ("alpha", Ty::F64, PatchShape::Nodes),
    ("leaf_depth", Ty::I32, PatchShape::Leaves),
    ("leaf_predicted_error", Ty::F64, PatchShape::Leaves),
];

/// The optional dataset of a patch of a table built with `nodes.anisotropic` (`uint8 [cells]`):
/// the axes each cell halves (bit 2 `γ`, bit 1 `c`; 0 for a leaf).
const SPLIT_DATASET: (&str, Ty) = ("split", Ty::U8);

/// The optional sub-group of `partial_high` (schema 3): the warp of the coordinate.
const WARP_GROUP: &str = "warp";
/// Patches that may have a warp group.
const WARP_PATCHES: &[&str] = &["partial_high"];
/// Attributes of the warp group.
const WARP_ATTRS: &[(&str, Ty)] = &[
    ("start", Ty::F64),
    ("gamma_0", Ty::F64),
    ("gamma_step", Ty::F64),
    ("c_star", Ty::F64),
];
/// Datasets of the warp group (1-D).
const WARP_DATASETS: &[(&str, Ty)] = &[("knot", Ty::F64)];

/// Datasets of the other groups; all of one group share one length (`None`: any, `Some(n)`: n).
const OTHER_DATASETS: &[(&str, Ty, Option<usize>)] = &[
    ("/no_slip/gamma", Ty::F64, None),
    ("/no_slip/P", Ty::F64, None),
    ("/no_slip/error_estimate", Ty::F64, None),
    ("/critical/gamma", Ty::F64, Some(401)),
    ("/critical/alpha_c1", Ty::F64, Some(401)),
    ("/critical/alpha_c2", Ty::F64, Some(401)),
    ("/checks/gamma", Ty::F64, None),
    ("/checks/alpha", Ty::F64, None),
    ("/checks/P_simulated", Ty::F64, None),
    ("/checks/P_interpolated", Ty::F64, None),
    ("/checks/interpolation_error", Ty::F64, None),
    ("/checks/patch", Ty::I32, None),
];

// ---------------------------------------------------------------------------------------------
// Helpers

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn write_config(name: &str, text: &str) -> PathBuf {
    let p = scratch().join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// `Command::output` with the child started under [`fork_guard`].
fn output_of(cmd: &mut Command) -> std::io::Result<Output> {
    let child = {
        let _g = fork_guard();
        cmd.stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()?
    };
    child.wait_with_output()
}

fn sweep(args: &[&str]) -> Output {
    output_of(Command::new(env!("CARGO_BIN_EXE_sweep")).args(args)).expect("run the sweep binary")
}

fn spawn_run(config: &Path, out: &Path, threads: usize) -> Child {
    let _g = fork_guard();
    Command::new(env!("CARGO_BIN_EXE_sweep"))
        .arg("run")
        .arg(config)
        .arg("-o")
        .arg(out)
        .args(["--threads", &threads.to_string(), "--quiet"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start sweep run")
}

fn assert_no_panic(out: &Output, what: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("panicked")
            && out.status.code() != Some(101)
            && out.status.code().is_some(),
        "{what}: panicked or died ({:?}): {stderr}",
        out.status
    );
}

/// Build a table with `sweep run CONFIG -o OUT --threads T --quiet`; returns the wall time.
fn build(config: &Path, out: &Path, threads: usize) -> Duration {
    let start = Instant::now();
    let o = output_of(
        Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("run")
            .arg(config)
            .arg("-o")
            .arg(out)
            .args(["--threads", &threads.to_string(), "--quiet"]),
    )
    .expect("run sweep run");
    let wall = start.elapsed();
    assert_no_panic(&o, "sweep run");
    assert!(
        o.status.success(),
        "sweep run {} failed: {}",
        config.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.is_file(), "sweep run did not write {}", out.display());
    wall
}

struct Fixture {
    /// Table of SMALL_CONFIG built with --threads 2.
    table: PathBuf,
    config: PathBuf,
}

fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let config = write_config("small.toml", SMALL_CONFIG);
        let dir = subdir("fixture");
        let table = dir.join("small.h5");
        build(&config, &table, 2);
        // A completed run leaves exactly the table: no temporary or probe file.
        let names = dir_names(&dir);
        assert_eq!(
            names,
            vec!["small.h5".to_string()],
            "files left next to the table"
        );
        Fixture { table, config }
    })
}

fn dir_names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    v.sort();
    v
}

fn open(path: &Path) -> hdf5::File {
    hdf5::File::open(path).unwrap_or_else(|e| panic!("open {}: {e}", path.display()))
}

fn f64s(g: &hdf5::Group, name: &str) -> Vec<f64> {
    g.dataset(name)
        .and_then(|d| d.read_raw::<f64>())
        .unwrap_or_else(|e| panic!("read {}/{name}: {e}", g.name()))
}

fn ints<T: hdf5::H5Type>(g: &hdf5::Group, name: &str) -> Vec<T> {
    g.dataset(name)
        .and_then(|d| d.read_raw::<T>())
        .unwrap_or_else(|e| panic!("read {}/{name}: {e}", g.name()))
}

fn attr_f64(loc: &hdf5::Location, name: &str) -> f64 {
    loc.attr(name)
        .and_then(|a| a.read_scalar::<f64>())
        .unwrap_or_else(|e| panic!("attribute {}@{name}: {e}", loc.name()))
}

fn attr_str(loc: &hdf5::Location, name: &str) -> String {
    loc.attr(name)
        .and_then(|a| a.read_scalar::<VarLenUnicode>())
        .map(|s| s.as_str().to_string())
        .unwrap_or_else(|e| panic!("attribute {}@{name}: {e}", loc.name()))
}

fn count_attr(g: &hdf5::Group, name: &str) -> usize {
    let v = attr_f64(g, name);
    assert!(
        v >= 1.0 && v.fract() == 0.0,
        "{}@{name} = {v}: documented as a float64 with an integer value >= 1",
        g.name()
    );
    v as usize
}

fn set<S: AsRef<str>>(it: impl IntoIterator<Item = S>) -> BTreeSet<String> {
    it.into_iter().map(|s| s.as_ref().to_string()).collect()
}

fn check_attr(loc: &hdf5::Location, name: &str, ty: Ty) {
    let a = loc
        .attr(name)
        .unwrap_or_else(|e| panic!("documented attribute {}@{name} missing: {e}", loc.name()));
    assert!(a.is_scalar(), "{}@{name} is not scalar", loc.name());
    let d = a.dtype().unwrap().to_descriptor().unwrap();
    assert_eq!(
        d,
        ty.descriptor(),
        "{}@{name}: type {d:?}, documented {ty:?}",
        loc.name()
    );
}

fn check_dataset(g: &hdf5::Group, name: &str, ty: Ty, shape: &[usize]) {
    let ds = g
        .dataset(name)
        .unwrap_or_else(|e| panic!("documented dataset {}/{name} missing: {e}", g.name()));
    let d = ds.dtype().unwrap().to_descriptor().unwrap();
    assert_eq!(
        d,
        ty.descriptor(),
        "{}/{name}: type {d:?}, documented {ty:?}",
        g.name()
    );
    assert_eq!(ds.shape(), shape, "{}/{name}: shape", g.name());
    // "Integrity": one chunk, byte shuffle, deflate and a Fletcher-32 checksum, in this order
    // (the checksum over the compressed bytes); HDF5 cannot chunk an empty dataset.
    if shape.iter().all(|&d| d > 0) {
        use hdf5::filters::Filter;
        assert_eq!(
            ds.chunk().as_deref(),
            Some(shape),
            "{}/{name}: chunk",
            g.name()
        );
        assert_eq!(
            ds.filters(),
            [Filter::Shuffle, Filter::Deflate(6), Filter::Fletcher32],
            "{}/{name}: filters",
            g.name()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The document

fn doc_text() -> String {
    std::fs::read_to_string(repo().join("docs/table-format.md")).expect("read docs/table-format.md")
}

/// Names in backticks in the first column of every markdown table of the section
/// "What is in the file".
fn doc_table_names(doc: &str) -> BTreeSet<String> {
    let start = doc
        .find("## What is in the file")
        .expect("section 'What is in the file' in docs/table-format.md");
    let rest = &doc[start + 3..];
    let section = &rest[..rest.find("\n## ").unwrap_or(rest.len())];
    let mut names = BTreeSet::new();
    for line in section.lines() {
        let line = line.trim();
        if !line.starts_with('|') || line.starts_with("|---") {
            continue;
        }
        let first = line[1..].split('|').next().unwrap_or("");
        let mut parts = first.split('`');
        parts.next();
        while let (Some(name), Some(_)) = (parts.next(), parts.next()) {
            names.insert(name.to_string());
        }
    }
    names
}

#[test]
fn a_documented_names_match_the_explicit_lists() {
    let doc = doc_text();
    let explicit: BTreeSet<String> = ROOT_ATTRS
        .iter()
        .map(|x| x.0)
        .chain(PATCHES.iter().map(|x| x.0))
        .chain(PATCH_ATTRS.iter().map(|x| x.0))
        .chain(PATCH_DATASETS.iter().map(|x| x.0))
        .chain([SPLIT_DATASET.0])
        .chain(OTHER_DATASETS.iter().map(|x| x.0))
        .chain([WARP_GROUP])
        .chain(WARP_ATTRS.iter().map(|x| x.0))
        .chain(WARP_DATASETS.iter().map(|x| x.0))
        .map(String::from)
        .collect();
    for name in &explicit {
        assert!(
            doc.contains(&format!("`{name}`")),
            "`{name}` is not in docs/table-format.md"
        );
    }
    let parsed = doc_table_names(&doc);
    assert!(parsed.len() > 40, "parsed too few names: {parsed:?}");
    let undocumented: Vec<_> = explicit.difference(&parsed).collect();
    let untested: Vec<_> = parsed.difference(&explicit).collect();
    assert!(
        undocumented.is_empty() && untested.is_empty(),
        "doc tables and test lists differ: not in the doc tables {undocumented:?}, not in the \
         test {untested:?}"
    );
    // The documented types of the integer datasets.
    assert!(doc.contains("| `tree` | dataset | int32 `[cells]`"));
    assert!(doc.contains("| `leaf_depth` | dataset | int32 `[leaves]`"));
    assert!(doc.contains("| `/checks/patch` | int32 `[K]`"));
    assert!(doc.contains("| `warp` | group | optional |"));
    assert!(doc.contains("| `knot` | dataset | float64 `[n]`"));
}

#[test]
fn a_file_has_exactly_the_documented_layout() {
    check_layout(&fixture().table, &Expect::small());
}

/// Everything section "What is in the file" of docs/table-format.md states, for a table built
/// from `ex`.
fn check_layout(path: &Path, ex: &Expect) {
    let f = open(path);
    let (gamma_min, gamma_max, alpha_max) = (ex.gamma_min, ex.gamma_max, ex.alpha_max);

    // Root attributes: all documented ones, with their types, and nothing else.
    for &(name, ty) in ROOT_ATTRS {
        check_attr(&f, name, ty);
    }
    assert_eq!(
        set(f.attr_names().unwrap()),
        set(ROOT_ATTRS.iter().map(|x| x.0)),
        "root attributes differ from the documented ones"
    );
    assert_eq!(attr_str(&f, "format"), "oblique-P-table");
    assert_eq!(attr_f64(&f, "schema_version"), 3.0);
    assert_eq!(attr_f64(&f, "stencil_points"), 4.0);
    assert_eq!(attr_f64(&f, "gamma_min"), gamma_min);
    assert_eq!(attr_f64(&f, "gamma_max"), gamma_max);
    assert_eq!(attr_f64(&f, "alpha_max"), alpha_max);
    assert_eq!(attr_f64(&f, "node_tol"), NODE_TOL);
    assert_eq!(attr_f64(&f, "check_tol"), NODE_TOL / 10.0);
    assert_eq!(attr_f64(&f, "target_error"), TARGET_ERROR);
    assert_eq!(attr_str(&f, "config"), ex.config);
    let wall = attr_f64(&f, "wall_time_s");
    assert!(wall.is_finite() && wall >= 0.0, "wall_time_s = {wall}");
    for s in ["engine_version", "git_commit", "solver"] {
        assert!(!attr_str(&f, s).is_empty(), "{s} is empty");
    }
    let created = attr_str(&f, "created");
    let b = created.as_bytes();
    let rfc3339 = b.len() == 20
        && b.iter().enumerate().all(|(i, &c)| match i {
            4 | 7 => c == b'-',
            10 => c == b'T',
            13 | 16 => c == b':',
            19 => c == b'Z',
            _ => c.is_ascii_digit(),
        });
    assert!(rfc3339, "created = {created:?} is not UTC RFC 3339");

    // Top-level groups: exactly the documented ones (`no_slip` when α_max = ∞).
    let mut groups = vec!["patches", "critical", "checks"];
    if alpha_max.is_infinite() {
        groups.push("no_slip");
    }
    assert_eq!(
        set(f.member_names().unwrap()),
        set(groups),
        "top-level members differ from the documented groups"
    );

    // Patches.
    let patches = f.group("patches").unwrap();
    assert_eq!(
        set(patches.member_names().unwrap()),
        set(ex.patches()),
        "patches of the domain [{gamma_min}, {gamma_max}]"
    );
    let mut stick_c1: Vec<(f64, f64, f64)> = Vec::new(); // (γ, P, error) at c = 1
    for &(pname, kind) in PATCHES.iter().filter(|x| ex.patches().contains(&x.0)) {
        let g = patches.group(pname).unwrap();
        for &(name, ty) in PATCH_ATTRS {
            check_attr(&g, name, ty);
        }
        assert_eq!(
            set(g.attr_names().unwrap()),
            set(PATCH_ATTRS.iter().map(|x| x.0)),
            "{pname}: attributes differ from the documented ones"
        );
        // The optional warp group: only where documented, with exactly the documented names.
        let warp = check_warp(&g, pname);
        let mut members: Vec<&str> = PATCH_DATASETS.iter().map(|x| x.0).collect();
        if warp.is_some() {
            members.push(WARP_GROUP);
        }
        if ex.anisotropic {
            members.push(SPLIT_DATASET.0);
        }
        assert_eq!(
            set(g.member_names().unwrap()),
            set(members),
            "{pname}: datasets differ from the documented ones"
        );
        assert_eq!(attr_str(&g, "kind"), kind, "{pname}: kind");
        let (lo, hi) = (attr_f64(&g, "gamma_lo"), attr_f64(&g, "gamma_hi"));
        let want = if pname == "stick_low" {
            (gamma_min, gamma_max.min(1.0))
        } else {
            (gamma_min.max(1.0), gamma_max)
        };
        assert_eq!((lo, hi), want, "{pname}: gamma edges");
        let bg = count_attr(&g, "blocks_gamma");
        let bc = count_attr(&g, "blocks_coord");
        let m = count_attr(&g, "leaf_intervals");
        let tree: Vec<i32> = ints(&g, "tree");
        // The masks (bit 2 γ, bit 1 c): 3 on every split cell without them.
        let split: Option<Vec<u8>> = ex.anisotropic.then(|| {
            check_dataset(&g, SPLIT_DATASET.0, SPLIT_DATASET.1, &[tree.len()]);
            ints(&g, SPLIT_DATASET.0)
        });
        // Walk the tree as documented: every leaf's box (x0, c0, hx, hc) and depth (the splits
        // above it).
        let mut leaves: Vec<Option<LeafSquare>> = Vec::new();
        let mut stack: Vec<(usize, f64, f64, f64, f64, i32)> = (0..bg * bc)
            .map(|r| {
                let (a, b) = (r / bc, r % bc);
                let (hx, hc) = (1.0 / bg as f64, 1.0 / bc as f64);
                (r, a as f64 * hx, b as f64 * hc, hx, hc, 0)
            })
            .collect();
        let mut visited = vec![false; tree.len()];
        while let Some((cell, x0, c0, hx, hc, d)) = stack.pop() {
            assert!(!visited[cell], "{pname}: cell {cell} reached twice");
            visited[cell] = true;
            let t = tree[cell];
            if t < 0 {
                if let Some(split) = &split {
                    assert_eq!(split[cell], 0, "{pname}: split[{cell}] of a leaf");
                }
                let leaf = (-t - 1) as usize;
                if leaves.len() <= leaf {
                    leaves.resize(leaf + 1, None);
                }
                assert!(leaves[leaf].is_none(), "{pname}: leaf {leaf} twice");
                leaves[leaf] = Some((x0, c0, hx, hc, d));
            } else {
                let t = t as usize;
                let mask = split.as_ref().map_or(3, |s| s[cell]);
                assert!((1..=3).contains(&mask), "{pname}: split[{cell}] = {mask}");
                let (ng, nc) = (usize::from(mask & 2 != 0), usize::from(mask & 1 != 0));
                assert!(
                    t > cell && t + (1 << (ng + nc)) <= tree.len(),
                    "{pname}: cell {cell} -> {t}"
                );
                // Children `t + q`, `q` row-major over the halved axes (γ first).
                let (hx2, hc2) = (hx / (1 + ng) as f64, hc / (1 + nc) as f64);
                for qg in 0..=ng {
                    for qc in 0..=nc {
                        let (x, c) = (x0 + qg as f64 * hx2, c0 + qc as f64 * hc2);
                        stack.push((t + (qg << nc) + qc, x, c, hx2, hc2, d + 1));
                    }
                }
            }
        }
        assert!(visited.iter().all(|&v| v), "{pname}: unreachable cells");
        let leaves: Vec<_> = leaves
            .into_iter()
            .map(|l| l.expect("leaves numbered without gaps"))
            .collect();
        let nl = leaves.len();
        for &(name, ty, shape) in PATCH_DATASETS {
            let shape = match shape {
                PatchShape::Cells => vec![tree.len()],
                PatchShape::Leaves => vec![nl],
                PatchShape::Nodes => vec![nl, m + 1, m + 1],
            };
            check_dataset(&g, name, ty, &shape);
        }
        let depth: Vec<i32> = ints(&g, "leaf_depth");
        for (l, leaf) in leaves.iter().enumerate() {
            assert_eq!(depth[l], leaf.4, "{pname}: leaf_depth[{l}]");
        }
        // Node positions as documented.
        let (gam, coord, alpha) = (f64s(&g, "gamma"), f64s(&g, "coord"), f64s(&g, "alpha"));
        let (p, err) = (f64s(&g, "P"), f64s(&g, "error_estimate"));
        let total = p.len();
        let pk = if kind == "stick" {
            PatchKind::Stick
        } else {
            PatchKind::PartialSlip
        };
        for (l, &(x0, c0, hx, hc, _)) in leaves.iter().enumerate() {
            for i in 0..=m {
                for j in 0..=m {
                    let idx = (l * (m + 1) + i) * (m + 1) + j;
                    let g_doc = lo + (hi - lo) * (x0 + hx * i as f64 / m as f64);
                    let c_doc = c0 + hc * j as f64 / m as f64;
                    assert!(
                        (gam[idx] - g_doc).abs() <= 1e-12,
                        "{pname}: node {idx} (leaf {l}, i {i}, j {j}) gamma {} vs {g_doc}",
                        gam[idx]
                    );
                    assert!(
                        (coord[idx] - c_doc).abs() <= 1e-12,
                        "{pname}: node {idx} coord {} vs {c_doc}",
                        coord[idx]
                    );
                    if pk == PatchKind::Stick && coord[idx] == 1.0 {
                        assert_eq!(alpha[idx], alpha_max, "{pname}: node {idx} at c = 1");
                        stick_c1.push((gam[idx], p[idx], err[idx]));
                    } else if pk == PatchKind::PartialSlip && gam[idx] == 1.0 {
                        // α_c1 = α_c2 at γ = 1: the patch has zero width, c is undefined.
                        assert!(
                            (alpha[idx] - 2.0 / 7.0).abs() <= 1e-15,
                            "{pname}: node {idx} at gamma 1: alpha {}",
                            alpha[idx]
                        );
                    } else {
                        assert!(alpha[idx].is_finite(), "{pname}: node {idx} alpha");
                        let c = pk.coord(gam[idx], alpha[idx], alpha_max);
                        // `coord` stores the warped c' in the leaves at or beyond the warp's
                        // start; compared in c (the grading's square root would amplify the
                        // rounding of α next to the knot).
                        let stored = match &warp {
                            Some(w) if x0 * bg as f64 >= w.start() - 1e-9 => {
                                w.invert(gam[idx], coord[idx])
                            }
                            _ => coord[idx],
                        };
                        // The partial-slip coordinate is compared before its square root,
                        // in ℓ = ln(α/α_c1)/ln(α_c2/α_c1): next to α_c2 (c → 1) the root
                        // turns a rounding of ℓ by ε into one of c by √ε.
                        let (c_cmp, stored_cmp) = if pk == PatchKind::PartialSlip {
                            let map = oblique_table::surface::PartialMap::SqrtEnd;
                            (map.l_of_c(c), map.l_of_c(stored))
                        } else {
                            (c, stored)
                        };
                        assert!(
                            (c_cmp - stored_cmp).abs() <= 1e-9,
                            "{pname}: node {idx}: alpha {} has coordinate {c}, stored {} ({stored} unwarped)",
                            alpha[idx],
                            coord[idx]
                        );
                    }
                    assert!(p[idx].is_finite() && p[idx].abs() <= 1.0 + 1e-9);
                    assert!(
                        err[idx] >= 0.0 && err[idx] <= NODE_TOL,
                        "{pname}: node {idx} error estimate {} > node_tol",
                        err[idx]
                    );
                }
            }
        }
        // Nodes shared by leaves carry identical values.
        let mut seen: HashMap<(u64, u64), f64> = HashMap::new();
        for idx in 0..total {
            let key = (gam[idx].to_bits(), coord[idx].to_bits());
            if let Some(&prev) = seen.get(&key) {
                assert_eq!(
                    prev.to_bits(),
                    p[idx].to_bits(),
                    "{pname}: node {idx} stored twice with different P"
                );
            } else {
                seen.insert(key, p[idx]);
            }
        }
        let lpe = f64s(&g, "leaf_predicted_error");
        assert!(
            lpe.iter()
                .all(|e| e.is_finite() && *e >= 0.0 && *e <= TARGET_ERROR),
            "{pname}: leaf_predicted_error above target_error: {lpe:?}"
        );
    }

    // Other groups: members exactly as documented, shapes, types.
    for group in ["no_slip", "critical", "checks"] {
        let Ok(g) = f.group(group) else {
            continue; // presence is checked above
        };
        let documented: Vec<_> = OTHER_DATASETS
            .iter()
            .filter(|x| x.0.starts_with(&format!("/{group}/")))
            .collect();
        let names = set(documented.iter().map(|x| x.0.rsplit('/').next().unwrap()));
        assert_eq!(
            set(g.member_names().unwrap()),
            names,
            "/{group}: members differ from the documented ones"
        );
        let len = g
            .dataset(documented[0].0.rsplit('/').next().unwrap())
            .unwrap()
            .shape();
        assert_eq!(len.len(), 1, "/{group}: 1-D");
        for &&(path, ty, fixed) in &documented {
            let name = path.rsplit('/').next().unwrap();
            check_dataset(&g, name, ty, &[fixed.unwrap_or(len[0])]);
        }
    }

    // /no_slip: the c = 1 nodes of the stick patches, sorted by γ (one row per γ).
    if alpha_max.is_infinite() {
        stick_c1.sort_by(|x, y| x.0.total_cmp(&y.0));
        stick_c1.dedup_by(|x, y| x.0 == y.0);
        let ns = f.group("no_slip").unwrap();
        let (ng, np, ne) = (
            f64s(&ns, "gamma"),
            f64s(&ns, "P"),
            f64s(&ns, "error_estimate"),
        );
        assert_eq!(ng.len(), stick_c1.len(), "no_slip rows");
        for (i, &(g0, p0, e0)) in stick_c1.iter().enumerate() {
            assert_eq!((ng[i], np[i], ne[i]), (g0, p0, e0), "no_slip row {i}");
        }
        assert!(ng.windows(2).all(|w| w[0] < w[1]), "no_slip/gamma sorted");
        assert_eq!((ng[0], ng[ng.len() - 1]), (gamma_min, gamma_max));
    }

    // /critical: closed forms on 401 points of the γ domain.
    let cr = f.group("critical").unwrap();
    let (cg, c1, c2) = (
        f64s(&cr, "gamma"),
        f64s(&cr, "alpha_c1"),
        f64s(&cr, "alpha_c2"),
    );
    for i in 0..401 {
        let g = gamma_min + (gamma_max - gamma_min) * i as f64 / 400.0;
        assert!((cg[i] - g).abs() <= 1e-14, "critical/gamma[{i}]");
        assert!(
            (c2[i] - alpha_c2(cg[i])).abs() <= 1e-15,
            "critical/alpha_c2[{i}]"
        );
        if cg[i] < 1.0 {
            assert!(
                c1[i].is_nan(),
                "critical/alpha_c1[{i}] must be NaN below γ = 1"
            );
        } else {
            assert!(
                (c1[i] - alpha_c1(cg[i])).abs() <= 1e-15,
                "critical/alpha_c1[{i}]"
            );
        }
    }

    // /checks: per_patch points per patch, consistent columns.
    let ch = f.group("checks").unwrap();
    let (g, a) = (f64s(&ch, "gamma"), f64s(&ch, "alpha"));
    let (ps, pi, e) = (
        f64s(&ch, "P_simulated"),
        f64s(&ch, "P_interpolated"),
        f64s(&ch, "interpolation_error"),
    );
    let patch: Vec<i32> = ints(&ch, "patch");
    let npatches = ex.patches().len();
    assert_eq!(g.len(), npatches * CHECKS_PER_PATCH, "checks count");
    for i in 0..g.len() {
        assert!(
            g[i] >= gamma_min && g[i] <= gamma_max,
            "check {i} gamma {}",
            g[i]
        );
        assert!(
            a[i] > linear_limit(g[i]) && a[i].is_finite(),
            "check {i} alpha {}",
            a[i]
        );
        assert_eq!(
            e[i],
            (pi[i] - ps[i]).abs(),
            "check {i}: interpolation_error"
        );
        let want = if g[i] <= 1.0 {
            0
        } else if a[i] < alpha_c2(g[i]) {
            1
        } else {
            2
        };
        assert_eq!(
            patch[i], want,
            "check {i}: patch index vs the rule's step 3"
        );
    }
    for name in ex.patches() {
        let want = PATCHES.iter().position(|x| x.0 == name).unwrap() as i32;
        assert!(patch.contains(&want), "no check in patch {name} ({want})");
    }
}

/// The warp group of patch `pname` as documented (`None` when absent): only in the documented
/// patches, exactly the documented attributes and datasets with their types, valid values.
fn check_warp(g: &hdf5::Group, pname: &str) -> Option<Warp> {
    if !g.link_exists(WARP_GROUP) {
        return None;
    }
    assert!(
        WARP_PATCHES.contains(&pname),
        "{pname} has a warp group: documented only for {WARP_PATCHES:?}"
    );
    let w = g.group(WARP_GROUP).expect("warp is a group");
    for &(name, ty) in WARP_ATTRS {
        check_attr(&w, name, ty);
    }
    assert_eq!(
        set(w.attr_names().unwrap()),
        set(WARP_ATTRS.iter().map(|x| x.0)),
        "{pname}/warp: attributes differ from the documented ones"
    );
    assert_eq!(
        set(w.member_names().unwrap()),
        set(WARP_DATASETS.iter().map(|x| x.0)),
        "{pname}/warp: datasets differ from the documented ones"
    );
    let knot = f64s(&w, "knot");
    for &(name, ty) in WARP_DATASETS {
        check_dataset(&w, name, ty, &[knot.len()]);
    }
    let warp = Warp::new(
        attr_f64(&w, "start"),
        attr_f64(&w, "gamma_0"),
        attr_f64(&w, "gamma_step"),
        attr_f64(&w, "c_star"),
        knot,
    )
    .unwrap_or_else(|e| panic!("{pname}/warp: {e}"));
    let (lo, hi) = (attr_f64(g, "gamma_lo"), attr_f64(g, "gamma_hi"));
    let bg = count_attr(g, "blocks_gamma") as f64;
    let end = warp.gamma_0() + (warp.knot().len() - 1) as f64 * warp.gamma_step();
    assert!(warp.gamma_step() > 0.0 && warp.c_star() > 0.0 && warp.c_star() < 1.0);
    assert!(warp.knot().len() >= 4 && warp.knot().iter().all(|&k| k > 0.0 && k < 1.0));
    assert!(
        warp.start() > 0.0 && warp.start() < bg && (warp.start() * 1048576.0).fract() == 0.0,
        "{pname}/warp: start {}",
        warp.start()
    );
    let first = lo + (hi - lo) * warp.start() / bg;
    assert!(
        warp.gamma_0() <= first + 1e-12 * hi && end >= hi - 1e-12 * hi,
        "{pname}/warp: grid"
    );
    Some(warp)
}

// ---------------------------------------------------------------------------------------------
// Other domains: a finite α_max (no `/no_slip`), a domain starting at γ = 1 (no `stick_low`) and
// one ending at γ = 1 (no high patches); and the small table built with `nodes.anisotropic`
// (every patch with the dataset `split`, its tree walked through the masks).

#[test]
fn a_domain_variants_follow_the_documented_layout() {
    let dir = subdir("variants");
    for (i, ex) in [
        Expect::variant(0.8, 1.6, 3.0),
        Expect::variant(1.0, 1.5, f64::INFINITY),
        Expect::variant(0.6, 1.0, f64::INFINITY),
        Expect::anisotropic(),
    ]
    .iter()
    .enumerate()
    {
        let config = write_config(&format!("variant{i}.toml"), &ex.config);
        let out = dir.join(format!("variant{i}.h5"));
        build(&config, &out, 2);
        check_layout(&out, ex);
        if ex.anisotropic {
            // Some cell halves one axis only, so the walk above followed the masks.
            let f = open(&out);
            let one_axis = ex
                .patches()
                .iter()
                .flat_map(|p| ints::<u8>(&f.group(&format!("patches/{p}")).unwrap(), "split"))
                .filter(|&m| m == 1 || m == 2)
                .count();
            assert!(one_axis > 0, "variant {i}: no cell halves one axis only");
        }

        let t = Table::open(&out).expect("open the table");
        for c in t.checks() {
            let p = t.p(c.gamma, c.alpha).unwrap();
            assert!(
                (p - c.p_interpolated).abs() <= 1e-12,
                "variant {i}: check ({}, {}): {p} vs {}",
                c.gamma,
                c.alpha,
                c.p_interpolated
            );
        }
        let mid = 0.5 * (ex.gamma_min + ex.gamma_max);
        let inf = t.p(mid, f64::INFINITY);
        assert_eq!(
            inf.is_ok(),
            ex.alpha_max.is_infinite(),
            "variant {i}: alpha = inf: {inf:?}"
        );
        if ex.alpha_max.is_finite() {
            assert!(
                t.p(mid, ex.alpha_max).is_ok(),
                "variant {i}: alpha = alpha_max"
            );
            assert!(
                t.p(mid, ex.alpha_max * 1.01).is_err(),
                "variant {i}: above alpha_max"
            );
        }
        if ex.gamma_min == 1.0 {
            // Step 3: γ = 1 selects the absent `stick_low`, where P = −1.
            assert_eq!(t.p(1.0, 0.5).unwrap(), -1.0, "variant {i}: gamma 1");
        }
        // Full slip outside the domain stays exact.
        assert_eq!(t.p(5.0, 0.1).unwrap(), 1.0 - 7.0 * 0.1);
    }
}

// ---------------------------------------------------------------------------------------------
// (b) the lookup crate

#[test]
fn b_lookup_reproduces_checks_and_full_slip_line() {
    let fx = fixture();
    let t = Table::open(&fx.table).expect("open the table");
    let f = open(&fx.table);
    let ch = f.group("checks").unwrap();
    let (g, a, pi) = (
        f64s(&ch, "gamma"),
        f64s(&ch, "alpha"),
        f64s(&ch, "P_interpolated"),
    );
    assert_eq!(t.checks().len(), g.len());
    let mut worst = 0.0_f64;
    for i in 0..g.len() {
        let p = t.p(g[i], a[i]).expect("check point inside the domain");
        let d = (p - pi[i]).abs();
        worst = worst.max(d);
        assert!(
            d <= 1e-12,
            "check {i} (gamma {}, alpha {}): lookup {p}, stored P_interpolated {}",
            g[i],
            a[i],
            pi[i]
        );
        assert_eq!(t.checks()[i].p_interpolated.to_bits(), pi[i].to_bits());
    }
    eprintln!(
        "lookup vs stored P_interpolated: max |diff| {worst:e} over {} checks",
        g.len()
    );

    // Full-slip line: exact for every γ > 0, inside the domain or not.
    for gamma in [
        0.05,
        0.3,
        0.72,
        0.8,
        0.95,
        1.0,
        1.0 + 1e-12,
        1.2,
        1.6,
        2.0,
        10.0,
        300.0,
    ] {
        let lin = linear_limit(gamma);
        assert!(lin > 0.0);
        for alpha in [
            0.0,
            0.25 * lin,
            0.5 * lin,
            lin * (1.0 - 1e-12),
            lin,
            f64::MIN_POSITIVE,
        ] {
            let p = t.p(gamma, alpha).unwrap_or_else(|e| {
                panic!("full slip at gamma {gamma}, alpha {alpha} refused: {e}")
            });
            assert_eq!(
                p.to_bits(),
                (1.0 - 7.0 * alpha).to_bits(),
                "full slip at gamma {gamma}, alpha {alpha}: {p}"
            );
        }
        let outside = !(GAMMA_MIN..=GAMMA_MAX).contains(&gamma);
        let above = t.p(gamma, lin * 1.5 + 1e-9);
        assert_eq!(
            above.is_err(),
            outside,
            "gamma {gamma} above the line: {above:?}"
        );
        let inf = t.p(gamma, f64::INFINITY);
        assert_eq!(inf.is_err(), outside, "gamma {gamma}, alpha inf: {inf:?}");
    }

    // α = ∞ at the stored no-slip nodes reproduces the node values.
    let ns = f.group("no_slip").unwrap();
    let (ng, np) = (f64s(&ns, "gamma"), f64s(&ns, "P"));
    for (&gamma, &p0) in ng.iter().zip(&np) {
        let p = t.p(gamma, f64::INFINITY).unwrap();
        assert!(
            (p - p0).abs() <= 1e-10,
            "P(gamma {gamma}, inf) = {p}, no_slip node {p0}"
        );
    }

    // Invalid queries are errors, not panics or NaN.
    for (gamma, alpha) in [
        (f64::NAN, 0.5),
        (0.0, 0.5),
        (-1.0, 0.5),
        (f64::INFINITY, 0.5),
        (1.2, f64::NAN),
        (1.2, -0.1),
    ] {
        assert!(t.p(gamma, alpha).is_err(), "({gamma}, {alpha}) accepted");
    }
}

// ---------------------------------------------------------------------------------------------
// (c) atomic write, unwritable output

fn kill9(child: &mut Child) -> std::process::ExitStatus {
    let st = output_of(Command::new("kill").args(["-9", &child.id().to_string()]))
        .expect("run kill")
        .status;
    if !st.success() {
        // The process may have exited just before; reap it below either way.
        let _ = child.kill();
    }
    child.wait().expect("wait for sweep run")
}

#[test]
fn c_sigkill_leaves_the_old_table_untouched() {
    let fx = fixture();
    let slow = write_config("slow.toml", SLOW_CONFIG);
    let dir = subdir("atomic");
    let out = dir.join("t.h5");
    std::fs::copy(&fx.table, &out).unwrap();
    let before = std::fs::read(&out).unwrap();

    let mut child = spawn_run(&slow, &out, 2);
    std::thread::sleep(Duration::from_millis(300));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the slow run ended within 300 ms; the test needs it still running"
    );
    let status = kill9(&mut child);
    assert_eq!(
        status.signal(),
        Some(9),
        "sweep run was not killed: {status:?}"
    );

    let after = std::fs::read(&out).unwrap();
    assert!(
        after == before,
        "the table at the output path changed after SIGKILL ({} -> {} bytes)",
        before.len(),
        after.len()
    );
    // At most the checkpoint of the killed run (for `--resume`, tests/resume_shard.rs) appears
    // (none if the kill came during the pre-flight probe, before the checkpoint is created),
    // and its lock file (`t.h5.lock`, released by the kill; the next run takes it over).
    let names: Vec<String> = dir_names(&dir)
        .into_iter()
        .filter(|n| n != "t.h5.lock")
        .collect();
    assert!(
        names == ["t.h5"] || names == ["t.h5", "t.h5.ckpt"],
        "files appeared next to the output: {names:?}"
    );
    Table::open(&out).expect("old table still opens");
}

/// Kill runs the moment the writer's temporary file appears next to the output, i.e. while the
/// table is being written: the output path must still hold the previous bytes (or, if the
/// rename already happened, a complete valid table). Timing decides where exactly each kill
/// lands; every attempt must pass.
#[test]
fn c_sigkill_during_the_write_leaves_old_or_complete_table() {
    let fx = fixture();
    let dir = subdir("atomic_write");
    let out = dir.join("t.h5");
    std::fs::copy(&fx.table, &out).unwrap();
    let checks = Table::open(&fx.table).unwrap().checks().to_vec();
    let (mut mid_write, mut finished, mut replaced) = (0, 0, 0);
    for attempt in 0..4 {
        let before = std::fs::read(&out).unwrap();
        let existing: BTreeSet<String> = dir_names(&dir).into_iter().collect();
        let mut child = spawn_run(&fx.config, &out, 2);
        let start = Instant::now();
        let status = loop {
            if let Some(st) = child.try_wait().unwrap() {
                break st;
            }
            let appeared = dir_names(&dir).into_iter().any(|n| {
                !existing.contains(&n)
                    && !n.starts_with(".sweep-probe-")
                    && !n.ends_with(".ckpt")
                    && !n.ends_with(".lock")
            });
            if appeared {
                break kill9(&mut child);
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "attempt {attempt}: run neither wrote nor finished in 60 s"
            );
            std::thread::sleep(Duration::from_micros(200));
        };
        if status.signal() == Some(9) {
            mid_write += 1;
        } else {
            assert!(
                status.success(),
                "attempt {attempt}: sweep run failed: {status:?}"
            );
            finished += 1;
        }
        let after = std::fs::read(&out).unwrap();
        if after != before {
            replaced += 1;
            let table = Table::open(&out).unwrap_or_else(|e| {
                panic!(
                    "attempt {attempt} ({status:?}): the output path holds neither the old \
                     table nor a valid new one: {e}"
                )
            });
            assert_eq!(
                table.checks(),
                checks,
                "a replaced table differs in its checks"
            );
        }
        // Besides the table, only the writer's hidden temporary files (left by SIGKILL), the
        // killed run's lock file and its checkpoint, removed here so that the next attempt
        // starts afresh.
        for name in dir_names(&dir) {
            assert!(
                name == "t.h5"
                    || name.starts_with(".t.h5.tmp-")
                    || name == "t.h5.ckpt"
                    || name == "t.h5.lock",
                "unexpected file {name} next to the output"
            );
        }
        let _ = std::fs::remove_file(dir.join("t.h5.ckpt"));
    }
    eprintln!(
        "kill during write: {mid_write} killed with the temporary file present, {finished} \
         finished first, {replaced} replaced the table"
    );
}

#[test]
fn c_unwritable_output_fails_early_naming_the_path() {
    let slow = write_config("slow_unwritable.toml", SLOW_CONFIG);
    let dir = subdir("unwritable");
    let cases = [
        PathBuf::from("/proc/nope/t.h5"),
        dir.clone(), // a directory, not a file
    ];
    for out in cases {
        let start = Instant::now();
        let g = fork_guard();
        let mut child = Command::new(env!("CARGO_BIN_EXE_sweep"))
            .arg("run")
            .arg(&slow)
            .arg("-o")
            .arg(&out)
            .args(["--quiet", "--threads", "1"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(g);
        // The slow config would solve for minutes: the error must come before any solving.
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > Duration::from_secs(10) {
                kill9(&mut child);
                panic!("sweep run -o {} did not fail early", out.display());
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let o = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_no_panic(&o, "sweep run to an unwritable path");
        assert!(
            !o.status.success(),
            "-o {}: exit status {:?}",
            out.display(),
            o.status
        );
        assert!(
            stderr.contains(&out.display().to_string()),
            "message does not name {}: {stderr}",
            out.display()
        );
    }
    assert!(
        dir_names(&dir).is_empty(),
        "files left in {}",
        dir.display()
    );
}

// ---------------------------------------------------------------------------------------------
// (d) thread-count independence

#[test]
fn d_tables_do_not_depend_on_thread_count() {
    let fx = fixture(); // built with --threads 2
    let dir = subdir("threads");
    let one = dir.join("t1.h5");
    build(&fx.config, &one, 1);
    let (f1, f2) = (open(&one), open(&fx.table));
    let (p1, p2) = (f1.group("patches").unwrap(), f2.group("patches").unwrap());
    assert_eq!(
        set(p1.member_names().unwrap()),
        set(p2.member_names().unwrap())
    );
    let bits = |v: Vec<f64>| v.into_iter().map(f64::to_bits).collect::<Vec<u64>>();
    for (pname, _) in PATCHES {
        let (g1, g2) = (p1.group(pname).unwrap(), p2.group(pname).unwrap());
        assert_eq!(
            ints::<i32>(&g1, "tree"),
            ints::<i32>(&g2, "tree"),
            "{pname}: quadtrees differ between --threads 1 and 2"
        );
        assert!(
            bits(f64s(&g1, "P")) == bits(f64s(&g2, "P")),
            "{pname}: P differs between --threads 1 and 2"
        );
        for name in ["error_estimate", "leaf_predicted_error", "alpha"] {
            assert!(
                bits(f64s(&g1, name)) == bits(f64s(&g2, name)),
                "{pname}/{name} differs between --threads 1 and 2"
            );
        }
    }
    let (c1, c2) = (f1.group("checks").unwrap(), f2.group("checks").unwrap());
    for name in ["P_simulated", "P_interpolated"] {
        assert!(
            bits(f64s(&c1, name)) == bits(f64s(&c2, name)),
            "checks/{name} differs between --threads 1 and 2"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// (e) sweep inspect

#[test]
fn e_inspect_json_reports_the_files_node_counts() {
    let fx = fixture();
    let path = fx.table.to_str().unwrap();
    let o = sweep(&["inspect", path, "--json"]);
    assert_no_panic(&o, "sweep inspect --json");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("inspect --json is JSON");
    let f = open(&fx.table);
    let patches = f.group("patches").unwrap();
    let mut total = 0u64;
    let listed = v["patches"].as_array().expect("patches array");
    assert_eq!(listed.len(), 3);
    for entry in listed {
        let name = entry["name"].as_str().unwrap();
        let g = patches.group(name).unwrap();
        let n = g.dataset("P").unwrap().size() as u64;
        total += n;
        assert_eq!(entry["nodes"].as_u64(), Some(n), "{name}: nodes");
        assert_eq!(entry["kind"].as_str().unwrap(), attr_str(&g, "kind"));
        for key in ["blocks_gamma", "blocks_coord", "leaf_intervals"] {
            assert_eq!(
                entry[key].as_u64(),
                Some(count_attr(&g, key) as u64),
                "{name}: {key}"
            );
        }
        let depth: Vec<i32> = ints(&g, "leaf_depth");
        assert_eq!(entry["leaves"].as_u64(), Some(depth.len() as u64));
        assert_eq!(
            entry["depth_min"].as_i64(),
            depth.iter().min().map(|&x| x as i64)
        );
        assert_eq!(
            entry["depth_max"].as_i64(),
            depth.iter().max().map(|&x| x as i64)
        );
        assert_eq!(entry["gamma_lo"].as_f64(), Some(attr_f64(&g, "gamma_lo")));
        assert_eq!(entry["gamma_hi"].as_f64(), Some(attr_f64(&g, "gamma_hi")));
    }
    assert_eq!(v["nodes"].as_u64(), Some(total), "total nodes");
    let ch = f.group("checks").unwrap();
    let err = f64s(&ch, "interpolation_error");
    assert_eq!(v["checks"]["count"].as_u64(), Some(err.len() as u64));
    assert_eq!(
        v["checks"]["max_interpolation_error"].as_f64(),
        Some(err.iter().copied().fold(0.0, f64::max))
    );
    // The stated bound: largest leaf prediction + Λ₄² × the leaf's largest node estimate.
    let factor = oblique_table::bound::node_error_factor(4);
    let mut bound = 0.0_f64;
    for name in ["stick_low", "partial_high", "stick_high"] {
        let g = patches.group(name).unwrap();
        let pred = f64s(&g, "leaf_predicted_error");
        let est = f64s(&g, "error_estimate");
        let per_leaf = est.len() / pred.len();
        for (l, p) in pred.iter().enumerate() {
            let worst = est[l * per_leaf..(l + 1) * per_leaf]
                .iter()
                .copied()
                .fold(0.0, f64::max);
            bound = bound.max(p + factor * worst);
        }
    }
    let stated = v["error_bound"].as_f64().expect("error_bound");
    assert!(
        (stated - bound).abs() <= 1e-15 * bound,
        "{stated} vs {bound}"
    );
    assert_eq!(Table::open(&fx.table).unwrap().error_bound(), stated);
    assert!(err.iter().all(|&e| e <= stated), "a check above the bound");
    assert_eq!(v["schema_version"].as_u64(), Some(3));
    assert_eq!(v["stencil_points"].as_u64(), Some(4));
    assert_eq!(v["alpha_max"].as_str(), Some("inf"));
    assert_eq!(v["gamma_min"].as_f64(), Some(GAMMA_MIN));
    assert_eq!(v["gamma_max"].as_f64(), Some(GAMMA_MAX));
    assert_eq!(v["provenance"]["config"].as_str(), Some(SMALL_CONFIG));

    // The text summary names every patch with its node count.
    let o = sweep(&["inspect", path]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    for entry in listed {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(entry["name"].as_str().unwrap()))
            .unwrap_or_else(|| panic!("no line for {} in {text}", entry["name"]));
        assert!(
            line.contains(&format!("{} nodes", entry["nodes"])),
            "{line}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// (f) bad files

/// `Table::open` fails with a message containing one of `needles`; `sweep inspect` exits
/// non-zero without panicking and says the same.
fn refused(path: &Path, needles: &[&str]) {
    let e = Table::open(path)
        .map(|_| ())
        .expect_err(&format!("{} was accepted", path.display()));
    let msg = e.to_string();
    let lower = msg.to_lowercase();
    assert!(
        needles.iter().any(|n| lower.contains(n)),
        "{}: message {msg:?} mentions none of {needles:?}",
        path.display()
    );
    let o = sweep(&["inspect", path.to_str().unwrap()]);
    assert_no_panic(&o, "sweep inspect on a bad file");
    assert!(
        !o.status.success(),
        "sweep inspect accepted {}",
        path.display()
    );
    let stderr = String::from_utf8_lossy(&o.stderr).to_lowercase();
    assert!(
        needles.iter().any(|n| stderr.contains(n)),
        "sweep inspect {}: {stderr}",
        path.display()
    );
    let o = sweep(&["inspect", path.to_str().unwrap(), "--json"]);
    assert_no_panic(&o, "sweep inspect --json on a bad file");
    assert!(!o.status.success());
}

#[test]
fn f_bad_files_are_refused_with_clear_messages() {
    let fx = fixture();
    let dir = subdir("bad");
    let bytes = std::fs::read(&fx.table).unwrap();
    let not_hdf5 = ["truncated", "not an hdf5"];

    let truncated = dir.join("truncated.h5");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    refused(&truncated, &not_hdf5);

    // One flipped byte anywhere after the user block: the seal catches it before HDF5 reads.
    for (k, at) in [bytes.len() / 3, bytes.len() - 100].into_iter().enumerate() {
        let flipped = dir.join(format!("flipped{k}.h5"));
        let mut b = bytes.clone();
        b[at] ^= 0x10;
        std::fs::write(&flipped, b).unwrap();
        refused(&flipped, &["damaged"]);
    }

    let random = dir.join("random.h5");
    let mut x = 0x2545_F491_4F6C_DD1Du64;
    let noise: Vec<u8> = (0..65536)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 32) as u8
        })
        .collect();
    std::fs::write(&random, noise).unwrap();
    refused(&random, &not_hdf5);

    let empty = dir.join("empty.h5");
    std::fs::write(&empty, b"").unwrap();
    refused(&empty, &not_hdf5);

    refused(&dir.join("missing.h5"), &["no such file"]);

    let no_format = dir.join("no_format.h5");
    {
        let _g = fork_guard();
        let f = hdf5::File::create(&no_format).unwrap();
        f.new_attr::<f64>()
            .create("schema_version")
            .unwrap()
            .write_scalar(&1.0)
            .unwrap();
        f.create_group("patches").unwrap();
    }
    refused(&no_format, &["not a p table"]);

    let wrong_format = dir.join("wrong_format.h5");
    std::fs::copy(&fx.table, &wrong_format).unwrap();
    {
        let _g = fork_guard();
        let f = hdf5::File::open_rw(&wrong_format).unwrap();
        let s: VarLenUnicode = "something-else".parse().unwrap();
        f.attr("format").unwrap().write_scalar(&s).unwrap();
    }
    // Edited on purpose: seal it again so the reader gets to the check under test.
    oblique_table::write::seal(&wrong_format).unwrap();
    refused(&wrong_format, &["not a p table"]);

    for (name, version) in [("schema1.h5", 1.0), ("schema6.h5", 6.0)] {
        let other = dir.join(name);
        std::fs::copy(&fx.table, &other).unwrap();
        {
            let _g = fork_guard();
            let f = hdf5::File::open_rw(&other).unwrap();
            f.attr("schema_version")
                .unwrap()
                .write_scalar(&version)
                .unwrap();
        }
        // Edited on purpose: seal it again so the reader gets to the check under test.
        oblique_table::write::seal(&other).unwrap();
        refused(&other, &["schema version"]);
    }

    // A quadtree whose cell points back to itself (a cycle) or outside the array.
    for (name, value) in [("tree_cycle.h5", 0), ("tree_out_of_range.h5", 1 << 30)] {
        let bad = dir.join(name);
        std::fs::copy(&fx.table, &bad).unwrap();
        {
            let _g = fork_guard();
            let f = hdf5::File::open_rw(&bad).unwrap();
            let g = f.group("patches/partial_high").unwrap();
            let d = g.dataset("tree").unwrap();
            let mut tree: Vec<i32> = d.read_raw().unwrap();
            tree[0] = value;
            d.write_raw(&tree).unwrap();
        }
        // Edited on purpose: seal it again so the reader gets to the check under test.
        oblique_table::write::seal(&bad).unwrap();
        refused(&bad, &["tree"]);
    }
}

// ---------------------------------------------------------------------------------------------
// (g) the optional warp (schema 3) through the writer

/// The fixture table as the writer's input (`Built`), read back from its file, with a warp on
/// `partial_high`: the node α values are moved so that the stored `coord` is the warped c' of
/// each node, as the sweep lays them out.
fn built_with_warp(path: &Path, warp: &Warp) -> oblique_sweep::Built {
    let t = Table::open(path).expect("open the fixture");
    let f = open(path);
    let patches = f.group("patches").unwrap();
    let surface = t
        .surface()
        .map_patches(|id, p| match id {
            PatchId::PartialHigh => p.with_warp(Some(warp.clone())),
            _ => Ok(p.clone()),
        })
        .expect("a valid warp");
    let mut built_patches = Vec::new();
    for (id, patch) in surface.patches() {
        let name = id.name();
        let g = patches.group(name).unwrap();
        let (gamma, coord) = (f64s(&g, "gamma"), f64s(&g, "coord"));
        let alpha = if patch.warp().is_some() {
            // Nodes of the leaves at or beyond the warp's start sit at c' = coord.
            let spans = patch.leaf_gamma_spans();
            let per_leaf = (patch.leaf_intervals() + 1).pow(2);
            gamma
                .iter()
                .zip(&coord)
                .enumerate()
                .map(|(i, (&gm, &c))| {
                    let warped = spans[i / per_leaf].0 >= warp.start();
                    if gm == 1.0 {
                        2.0 / 7.0
                    } else if !warped {
                        patch.kind().alpha(gm, c, surface.alpha_max())
                    } else {
                        patch
                            .kind()
                            .alpha(gm, warp.invert(gm, c), surface.alpha_max())
                    }
                })
                .collect()
        } else {
            f64s(&g, "alpha")
        };
        let leaf_depth: Vec<i32> = ints(&g, "leaf_depth");
        built_patches.push(oblique_sweep::BuiltPatch {
            name,
            patch: patch.clone(),
            gamma,
            coord,
            alpha,
            e_n: Vec::new(),
            leaf_error: f64s(&g, "leaf_predicted_error"),
            leaf_depth: leaf_depth.iter().map(|&d| d as u32).collect(),
            unique_nodes: 0,
            simulated: 0,
        });
    }
    oblique_sweep::Built {
        surface,
        patches: built_patches,
        checks: t.checks().to_vec(),
    }
}

#[test]
fn g_a_table_with_a_warp_round_trips_through_the_writer() {
    let fx = fixture();
    // partial_high of the fixture spans γ ∈ [1, 1.6] in two root rows: the warp applies from
    // the second (γ = 1.3).
    let warp = Warp::new(1.0, 1.2, 0.1, 0.5, vec![0.45, 0.5, 0.6, 0.55, 0.4]).expect("valid");
    let built = built_with_warp(&fx.table, &warp);
    let prov = Table::open(&fx.table).unwrap().provenance().clone();
    let out = subdir("warp").join("warp.h5");
    {
        let _g = fork_guard();
        oblique_table::write::write_table(&out, &built, &prov).expect("write the table");
    }
    // The file: the documented layout, with the warp group where documented.
    check_layout(&out, &Expect::small());
    let f = open(&out);
    let w = f
        .group("patches/partial_high/warp")
        .expect("the warp group");
    assert_eq!(attr_f64(&w, "c_star"), 0.5);
    assert_eq!(f64s(&w, "knot"), warp.knot());
    for other in ["stick_low", "stick_high"] {
        assert!(!f
            .group(&format!("patches/{other}"))
            .unwrap()
            .link_exists("warp"));
    }
    drop(f);
    // Read back: the same surface, and the same bits at random queries as the in-memory one.
    let t = Table::open(&out).expect("open the warped table");
    assert_eq!(t.provenance().schema_version, 3);
    // `sweep inspect` reports the warp: where it starts (row 1 of [1, 1.6] = γ 1.3) and c*.
    let o = sweep(&["inspect", out.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("fold edge: from gamma 1.3 (root row 1) the fold F+ lies on c' = 0.5"),
        "{text}"
    );
    let o = sweep(&["inspect", out.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("inspect --json");
    let w = &v["patches"][1]["warp"];
    assert_eq!(v["patches"][1]["name"].as_str(), Some("partial_high"));
    assert_eq!(
        (w["start"].as_f64(), w["knots"].as_u64()),
        (Some(1.0), Some(5))
    );
    assert!(v["patches"][0]["warp"].is_null() && v["patches"][2]["warp"].is_null());
    assert_eq!(t.surface(), &built.surface, "surface after write -> read");
    let mut next = oblique_lookup::testing::uniform(0x0123_4567_89AB_CDEF_u64);
    let plain = Table::open(&fx.table).unwrap();
    let mut changed = 0;
    for i in 0..4000 {
        let g = GAMMA_MIN + (GAMMA_MAX - GAMMA_MIN) * next();
        let a = if i % 2 == 0 && g > 1.0 {
            alpha_c1(g) + (alpha_c2(g) - alpha_c1(g)) * next()
        } else {
            10f64.powf(-2.0 + 3.0 * next())
        };
        let p = t.p(g, a).expect("inside");
        let mem = built.surface.eval(g, a).expect("inside");
        assert_eq!(p.to_bits(), mem.to_bits(), "({g}, {a})");
        changed += usize::from(p != plain.p(g, a).unwrap());
    }
    assert!(changed > 100, "the warp changed only {changed} answers");

    // The writer refuses a warp the readers would refuse, and leaves no file.
    let bad_dir = subdir("warp_bad");
    // The error of writing the fixture with `change` made to its warped table, to `file`.
    let refused = |file: &str, change: &dyn Fn(&mut oblique_sweep::Built)| {
        let mut bad = built_with_warp(&fx.table, &warp);
        change(&mut bad);
        let e = {
            let _g = fork_guard();
            oblique_table::write::write_table(&bad_dir.join(file), &bad, &prov)
        };
        e.expect_err(file).to_string()
    };
    // A warp the readers would refuse cannot be built: the model refuses it, naming the value
    // (so the writer, which takes only models, never sees one).
    let knots = vec![0.45, 0.5, 0.6, 0.55, 0.4];
    let e = Warp::new(1.0, 1.2, 0.1, 1.5, knots.clone()).expect_err("c_star 1.5");
    assert!(e.contains("c_star"), "{e}");
    let partial = built
        .surface
        .patch_by_id(PatchId::PartialHigh)
        .expect("partial_high");
    let early = Warp::new(0.3, 1.2, 0.1, 0.5, knots).expect("valid on its own");
    let e = partial.with_warp(Some(early)).expect_err("start 0.3");
    assert!(e.contains("'start' = 0.3"), "{e}");
    let e = built
        .surface
        .map_patches(|id, p| match id {
            PatchId::StickHigh => p.with_warp(Some(warp.clone())),
            _ => Ok(p.clone()),
        })
        .expect_err("a warp on stick_high");
    assert!(e.contains("only 'partial_high'"), "{e}");
    // The writer refuses a warp on another patch than partial_high in its input too.
    let e = refused("stick.h5", &|bad| {
        let stick = bad.patches.iter_mut().find(|b| b.name == "stick_high");
        let stick = stick.expect("stick_high");
        stick.patch = stick
            .patch
            .with_warp(Some(warp.clone()))
            .expect("a patch on its own");
    });
    assert!(e.contains("only 'partial_high'"), "{e}");
    assert!(dir_names(&bad_dir).is_empty(), "{:?}", dir_names(&bad_dir));
}

/// `sweep run` (the writer) refuses a table whose held-out checks exceed the bound it states,
/// writing nothing; and `sweep verify` exits 1 on a table that does not hold its bound.
#[test]
fn h_a_table_is_not_written_or_verified_against_a_bound_it_breaks() {
    let fx = fixture();
    let warp = Warp::new(1.0, 1.2, 0.1, 0.5, vec![0.45, 0.5, 0.6, 0.55, 0.4]).expect("valid");
    let mut built = built_with_warp(&fx.table, &warp);
    let prov = Table::open(&fx.table).unwrap().provenance().clone();
    let bound = oblique_table::write::error_bound(&built);
    assert_eq!(bound, Table::open(&fx.table).unwrap().error_bound());
    let dir = subdir("bound");
    let out = dir.join("contradicted.h5");
    built.checks[3].interpolation_error = 1.5 * bound;
    let e = {
        let _g = fork_guard();
        oblique_table::write::write_table(&out, &built, &prov).expect_err("a check above the bound")
    };
    let msg = e.to_string();
    assert!(
        matches!(
            e,
            oblique_table::write::StorageError::BoundContradicted { .. }
        ),
        "{msg}"
    );
    assert!(
        msg.contains("refusing to write") && msg.contains("error bound the table states"),
        "{msg}"
    );
    // The check's point, e_n included.
    let c = built.checks[3];
    assert!(
        msg.contains(&format!(
            "gamma = {}, alpha = {}, e_n = {}",
            c.gamma, c.alpha, c.e_n
        )),
        "{msg}"
    );
    assert!(!out.exists(), "nothing written");
    assert_eq!(dir_names(&dir), Vec::<String>::new(), "no temporary left");
    // A table whose stated bound is 0 (no predicted or node error): written without checks,
    // `sweep verify` finds points above it and exits 1.
    built.checks.clear();
    for p in &mut built.patches {
        p.leaf_error.iter_mut().for_each(|e| *e = 0.0);
        p.patch = p.patch.map_error_estimate(|_, _| 0.0).expect("zero errors");
    }
    built.surface = built
        .surface
        .map_patches(|_, p| p.map_error_estimate(|_, _| 0.0))
        .expect("zero errors");
    let zero = dir.join("zero.h5");
    {
        let _g = fork_guard();
        oblique_table::write::write_table(&zero, &built, &prov).expect("no checks to contradict");
    }
    assert_eq!(Table::open(&zero).unwrap().error_bound(), 0.0);
    let o = sweep(&[
        "verify",
        zero.to_str().unwrap(),
        "--points",
        "20",
        "--quiet",
    ]);
    assert_no_panic(&o, "sweep verify");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("exceed the table's stated error bound"),
        "{err}"
    );
}
