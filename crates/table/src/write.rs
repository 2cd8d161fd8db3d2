//! The storage layer: writes a built table as HDF5 (schema v3, or v4 with an `e_n` axis;
//! `docs/table-format.md`) through `oblique-output` (a temporary file beside the target, synced,
//! then renamed). Names come from `crate::format`,
//! which owns the format; the lookup crate reads what this writes.

use std::path::Path;

use hdf5::types::VarLenUnicode;
use oblique_physics::regimes::{alpha_c1_dissipative, alpha_c2};

use crate::format::*;
use crate::read::{Check, Provenance};
use crate::surface::{AxisMap, Patch, PatchKind, Surface};
use thiserror::Error;

/// The deflate (zlib) level of every dataset, after the byte-shuffle filter: level 6 writes
/// `tables/full.h5` in 6.7 MB instead of 16.4 MB; level 9 saves 0.2 % more for twice the
/// writing time (`docs/table-format.md`, "Storage").
const DEFLATE_LEVEL: u8 = 6;

/// One patch as built, with the coordinates of every node (same flat layout as `patch.p`).
#[derive(Debug, Clone)]
pub struct BuiltPatch {
    /// Patch name in the file.
    pub name: &'static str,
    /// The patch.
    pub patch: Patch,
    /// γ of every node.
    pub gamma: Vec<f64>,
    /// Patch coordinate `c` of every node.
    pub coord: Vec<f64>,
    /// α of every node (`∞` allowed).
    pub alpha: Vec<f64>,
    /// `e_n` of every node (empty for a patch without an `e_n` axis).
    pub e_n: Vec<f64>,
    /// Predicted interpolation error of every leaf.
    pub leaf_error: Vec<f64>,
    /// Depth of every leaf.
    pub leaf_depth: Vec<u32>,
    /// Distinct nodes (leaves share their edges).
    pub unique_nodes: usize,
    /// Distinct nodes that were simulated (the others are closed forms).
    pub simulated: usize,
}

/// A table as built, what [`write_table`] writes: the surface, the patches with the
/// coordinates of their nodes, the held-out checks.
#[derive(Debug, Clone)]
pub struct Built {
    /// Surface (patches and domain) as the reader loads it.
    pub surface: Surface,
    /// The patches with their node α values, in file order.
    pub patches: Vec<BuiltPatch>,
    /// Held-out checks.
    pub checks: Vec<Check>,
}

/// Errors of writing a table.
#[derive(Debug, Error)]
pub enum StorageError {
    /// HDF5 refused an operation.
    #[error("writing {path}: {message}")]
    Hdf5 {
        /// Output path.
        path: String,
        /// What failed.
        message: String,
    },
    /// A held-out check is off by more than the error bound the table would state: the file
    /// is not written.
    #[error(
        "refusing to write {path}: the held-out check at gamma = {gamma}, alpha = {alpha}, \
         e_n = {e_n} is off by {error:.3e}, more than the error bound the table states, \
         {bound:.3e} (largest leaf prediction + 2.66 x node error estimate, \
         docs/table-format.md); the refinement's prediction does not hold there: lower \
         nodes.target_error or solver.tol"
    )]
    BoundContradicted {
        /// Output path.
        path: String,
        /// The stated bound ([`error_bound`]).
        bound: f64,
        /// The check's measured error.
        error: f64,
        /// γ of the check.
        gamma: f64,
        /// α of the check.
        alpha: f64,
        /// `e_n` of the check (1 in an elastic table).
        e_n: f64,
    },
    /// Filesystem error (directory, rename).
    #[error("writing {path}: {source}")]
    Io {
        /// Output path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Something that is not a regular file is in the way of the output.
    #[error(transparent)]
    Output(#[from] OutputPathError),
}

impl From<oblique_output::OutputError> for StorageError {
    fn from(e: oblique_output::OutputError) -> Self {
        match e {
            oblique_output::OutputError::Path(p) => StorageError::Output(p),
            oblique_output::OutputError::Io { path, source } => StorageError::Io { path, source },
        }
    }
}

impl StorageError {
    /// Whether the caller can fix it: the output path is in the way (not: a failed write, or a
    /// build whose checks contradict its bound).
    pub fn user_can_fix(&self) -> bool {
        matches!(self, StorageError::Output(_))
    }
}

pub use oblique_output::{check_output, check_output_not_input, OutputPathError};

struct W<'a> {
    path: &'a str,
}

impl W<'_> {
    fn e(&self, what: &str) -> impl Fn(hdf5::Error) -> StorageError + '_ {
        let what = what.to_string();
        move |err| StorageError::Hdf5 {
            path: self.path.to_string(),
            message: format!("{what}: {err}"),
        }
    }

    fn attr_f64(&self, loc: &hdf5::Location, name: &str, v: f64) -> Result<(), StorageError> {
        loc.new_attr::<f64>()
            .create(name)
            .and_then(|a| a.write_scalar(&v))
            .map_err(self.e(name))
    }

    fn attr_str(&self, loc: &hdf5::Location, name: &str, v: &str) -> Result<(), StorageError> {
        let s: VarLenUnicode = v.parse().map_err(|_| StorageError::Hdf5 {
            path: self.path.to_string(),
            message: format!("attribute {name}: string contains a NUL byte"),
        })?;
        loc.new_attr::<VarLenUnicode>()
            .create(name)
            .and_then(|a| a.write_scalar(&s))
            .map_err(self.e(name))
    }

    fn ds(
        &self,
        g: &hdf5::Group,
        name: &str,
        data: &[f64],
        shape: &[usize],
    ) -> Result<(), StorageError> {
        self.ints(g, name, data, shape)
    }

    fn ints<T: hdf5::H5Type>(
        &self,
        g: &hdf5::Group,
        name: &str,
        data: &[T],
        shape: &[usize],
    ) -> Result<(), StorageError> {
        let arr = ndarray::ArrayView::from_shape(ndarray::IxDyn(shape), data).map_err(|e| {
            StorageError::Hdf5 {
                path: self.path.to_string(),
                message: format!("{name}: {e}"),
            }
        })?;
        // One chunk per dataset, compressed without loss (the byte-shuffle filter, then deflate
        // at level DEFLATE_LEVEL: the stored values are the computed ones, bit for bit), then a
        // Fletcher-32 checksum of the compressed chunk: a corrupted value is an error on read,
        // never a silently wrong number (HDF5 cannot chunk an empty dataset).
        let builder = g.new_dataset_builder().with_data(arr);
        let builder = if shape.iter().all(|&d| d > 0) {
            builder
                .chunk(shape.to_vec())
                .shuffle()
                .deflate(DEFLATE_LEVEL)
                .fletcher32()
        } else {
            builder
        };
        builder.create(name).map(|_| ()).map_err(self.e(name))
    }
}

/// The error bound the table of `built` states: [`crate::bound::surface_bound`] of its
/// leaves' predicted errors (what `Table::error_bound` derives from the written file).
pub fn error_bound(built: &Built) -> f64 {
    let pred = |name: &str| {
        built
            .patches
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.leaf_error.as_slice())
    };
    crate::bound::surface_bound(
        &built.surface,
        [
            pred(PATCH_STICK_LOW),
            pred(PATCH_PARTIAL_HIGH),
            pred(PATCH_STICK_HIGH),
        ],
    )
}

/// Write `built` to `out` atomically: an interrupted write never leaves a partial file at `out`.
/// Refused ([`StorageError::BoundContradicted`], nothing written) when a held-out check exceeds
/// the error bound the table states ([`error_bound`]).
pub fn write_table(out: &Path, built: &Built, prov: &Provenance) -> Result<(), StorageError> {
    let path = out.display().to_string();
    let bound = error_bound(built);
    if let Some(c) = crate::bound::contradicting_check(&built.checks, bound) {
        return Err(StorageError::BoundContradicted {
            path,
            bound,
            error: c.interpolation_error,
            gamma: c.gamma,
            alpha: c.alpha,
            e_n: c.e_n,
        });
    }
    let io = |source| StorageError::Io {
        path: path.clone(),
        source,
    };
    check_output(out)?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    // HDF5 creates the file itself, at the output module's temporary path, and finishes it
    // when its last handle closes (at the end of `write_to`); only then are its bytes final.
    // The seal goes into them before the module syncs the file and renames it over `out`.
    oblique_output::write_via_path(out, |tmp| {
        write_to(tmp, &path, built, prov).and_then(|()| seal(tmp).map_err(io))
    })
}

fn write_to(tmp: &Path, path: &str, built: &Built, prov: &Provenance) -> Result<(), StorageError> {
    let w = W { path };
    // File format of HDF5 1.10: every metadata block carries a checksum, so a damaged file is
    // refused by the library instead of being misread.
    // A user block for the seal (`crate::format::seal_of`), written after the file is
    // closed.
    let file = hdf5::File::with_options()
        // No HDF5 file lock: `tmp` is this process's own file, and a lock on it would pass to
        // any child process started while it is open, which then keeps it after the rename.
        .with_fapl(|p| p.libver_v110().file_locking(false))
        .with_fcpl(|p| p.userblock(USERBLOCK as u64))
        .create(tmp)
        .map_err(w.e("create file"))?;
    let s = &built.surface;
    let e_range = s.restitution();
    w.attr_str(&file, ATTR_FORMAT, FORMAT_NAME)?;
    let e_map = s.e_n_map();
    let version = match e_range {
        Some(_) if e_map != AxisMap::Linear => SCHEMA_VERSION,
        Some(_) => E_N_SCHEMA_VERSION,
        None => ELASTIC_SCHEMA_VERSION,
    };
    w.attr_f64(&file, ATTR_SCHEMA, version as f64)?;
    if version >= 5 {
        w.attr_str(&file, ATTR_E_N_COORDINATE, e_map.name())?;
    }
    if let Some((lo, hi)) = e_range {
        let axes = axes_attr([&E_N], s.pair_gamma().is_some());
        w.attr_str(&file, ATTR_AXES, &axes)?;
        w.attr_f64(&file, E_N.attr_min, lo)?;
        w.attr_f64(&file, E_N.attr_max, hi)?;
        // Never write a law and a partial-slip coordinate that the readers refuse together.
        let coordinate = s.partial_map().coordinate();
        if coordinate_of_law(&prov.law) != coordinate {
            return Err(StorageError::Hdf5 {
                path: path.to_string(),
                message: format!(
                    "the law '{}' does not go with the partial-slip coordinate '{}'",
                    prov.law,
                    coordinate.unwrap_or_default()
                ),
            });
        }
        w.attr_str(&file, ATTR_LAW, &prov.law)?;
    }
    w.attr_f64(&file, ATTR_STENCIL, s.stencil() as f64)?;
    w.attr_f64(&file, ATTR_GAMMA_MIN, s.gamma_min())?;
    w.attr_f64(&file, ATTR_GAMMA_MAX, s.gamma_max())?;
    w.attr_f64(&file, ATTR_ALPHA_MAX, s.alpha_max())?;
    w.attr_str(&file, ATTR_ENGINE_VERSION, &prov.engine_version)?;
    w.attr_str(&file, ATTR_GIT_COMMIT, &prov.git_commit)?;
    w.attr_str(&file, ATTR_CONFIG, &prov.config)?;
    w.attr_str(&file, ATTR_SOLVER, &prov.solver)?;
    w.attr_str(&file, ATTR_CREATED, &prov.created)?;
    w.attr_f64(&file, ATTR_WALL_TIME, prov.wall_time_s)?;
    w.attr_f64(&file, ATTR_NODE_TOL, prov.node_tol)?;
    w.attr_f64(&file, ATTR_CHECK_TOL, prov.check_tol)?;
    w.attr_f64(&file, ATTR_TARGET_ERROR, prov.target_error)?;

    let patches = file.create_group(GROUP_PATCHES).map_err(w.e("patches"))?;
    for bp in &built.patches {
        let p = &bp.patch;
        let g = patches.create_group(bp.name).map_err(w.e(bp.name))?;
        w.attr_str(&g, ATTR_KIND, p.kind().name())?;
        w.attr_f64(&g, ATTR_GAMMA_LO, p.gamma_lo())?;
        w.attr_f64(&g, ATTR_GAMMA_HI, p.gamma_hi())?;
        w.attr_f64(&g, ATTR_BLOCKS_GAMMA, p.blocks_gamma() as f64)?;
        w.attr_f64(&g, ATTR_BLOCKS_COORD, p.blocks_coord() as f64)?;
        w.attr_f64(&g, ATTR_LEAF_INTERVALS, p.leaf_intervals() as f64)?;
        if let Some(r) = p.restitution() {
            w.attr_f64(&g, E_N.attr_blocks, r.blocks() as f64)?;
            if let (PatchKind::PartialSlip, Some(coordinate)) =
                (p.kind(), s.partial_map().coordinate())
            {
                w.attr_str(&g, ATTR_COORDINATE, coordinate)?;
            }
        }
        let leaves = [bp.leaf_error.len()];
        w.ints(&g, DS_TREE, p.tree(), &[p.tree().len()])?;
        if let Some(split) = p.split() {
            w.ints(&g, DS_SPLIT, split, &[split.len()])?;
        }
        let depth: Vec<i32> = bp.leaf_depth.iter().map(|&d| d as i32).collect();
        w.ints(&g, DS_LEAF_DEPTH, &depth, &leaves)?;
        w.ds(&g, DS_LEAF_ERROR, &bp.leaf_error, &leaves)?;
        let mut n = vec![leaves[0], p.leaf_intervals() + 1, p.leaf_intervals() + 1];
        if p.dims() == 3 {
            n.push(p.leaf_intervals() + 1);
        }
        w.ds(&g, DS_GAMMA, &bp.gamma, &n)?;
        w.ds(&g, DS_COORD, &bp.coord, &n)?;
        w.ds(&g, DS_ALPHA, &bp.alpha, &n)?;
        if p.restitution().is_some() {
            w.ds(&g, E_N.name, &bp.e_n, &n)?;
        }
        w.ds(&g, DS_P, p.p(), &n)?;
        w.ds(&g, DS_ERROR, p.error_estimate(), &n)?;
        // The optional warp of the coordinate (schema 3; only `partial_high` has one).
        if let Some(warp) = &p.warp() {
            // Never write a warp the readers refuse.
            let refuse = |m: String| StorageError::Hdf5 {
                path: path.to_string(),
                message: format!("patch '{}': {GROUP_WARP}: {m}", bp.name),
            };
            if bp.name != PATCH_PARTIAL_HIGH {
                return Err(refuse(format!("only '{PATCH_PARTIAL_HIGH}' may have one")));
            }
            p.check_warp().map_err(refuse)?;
            let wg = g
                .create_group(GROUP_WARP)
                .map_err(w.e(&format!("{}/{GROUP_WARP}", bp.name)))?;
            w.attr_f64(&wg, ATTR_WARP_START, warp.start())?;
            w.attr_f64(&wg, ATTR_WARP_GAMMA_0, warp.gamma_0())?;
            w.attr_f64(&wg, ATTR_WARP_GAMMA_STEP, warp.gamma_step())?;
            w.attr_f64(&wg, ATTR_WARP_C_STAR, warp.c_star())?;
            w.ds(&wg, DS_WARP_KNOT, warp.knot(), &[warp.knot().len()])?;
        }
        // The optional knots of the coordinate (schema 4; only `partial_high` and `stick_high`
        // have them).
        if let Some(k) = p.knots() {
            let refuse = |m: String| StorageError::Hdf5 {
                path: path.to_string(),
                message: format!("patch '{}': {GROUP_KNOTS}: {m}", bp.name),
            };
            if bp.name != PATCH_PARTIAL_HIGH && bp.name != PATCH_STICK_HIGH {
                return Err(refuse(format!(
                    "only '{PATCH_PARTIAL_HIGH}' and '{PATCH_STICK_HIGH}' may have them"
                )));
            }
            p.check_knots().map_err(refuse)?;
            let kg = g
                .create_group(GROUP_KNOTS)
                .map_err(w.e(&format!("{}/{GROUP_KNOTS}", bp.name)))?;
            w.attr_f64(&kg, ATTR_KNOTS_GAMMA_0, k.gamma_0())?;
            w.attr_f64(&kg, ATTR_KNOTS_GAMMA_STEP, k.gamma_step())?;
            w.attr_f64(&kg, ATTR_KNOTS_E_N_0, k.e_n_0())?;
            w.attr_f64(&kg, ATTR_KNOTS_E_N_STEP, k.e_n_step())?;
            w.ds(&kg, DS_KNOTS_REGION, &k.region(), &[4])?;
            w.ds(&kg, DS_KNOTS_C_STAR, k.c_star(), &[k.c_star().len()])?;
            w.ints(&kg, DS_KNOTS_GRADE, &k.grade_values(), &[k.c_star().len()])?;
            w.ds(&kg, DS_KNOTS_KNOT, k.values(), &k.shape())?;
        }
    }

    // No-slip limit: the nodes at c = 1 of the stick patches (when α_max = ∞), by γ (and by
    // e_n within a γ, with an e_n axis).
    if s.alpha_max().is_infinite() {
        let e_at = |b: &BuiltPatch, i: usize| b.e_n.get(i).copied().unwrap_or(1.0);
        let mut rows: Vec<(f64, f64, f64, f64)> = built
            .patches
            .iter()
            .filter(|b| b.patch.kind() == PatchKind::Stick)
            .flat_map(|b| {
                (0..b.coord.len())
                    .filter(|&i| b.coord[i] == 1.0)
                    .map(move |i| {
                        (
                            b.gamma[i],
                            e_at(b, i),
                            b.patch.p()[i],
                            b.patch.error_estimate()[i],
                        )
                    })
            })
            .collect();
        rows.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.total_cmp(&y.1)));
        rows.dedup_by(|x, y| x.0 == y.0 && x.1 == y.1);
        let g = file.create_group(GROUP_NO_SLIP).map_err(w.e("no_slip"))?;
        let col = |f: fn(&(f64, f64, f64, f64)) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
        w.ds(&g, DS_GAMMA, &col(|r| r.0), &[rows.len()])?;
        if e_range.is_some() {
            w.ds(&g, E_N.name, &col(|r| r.1), &[rows.len()])?;
        }
        w.ds(&g, DS_P, &col(|r| r.2), &[rows.len()])?;
        w.ds(&g, DS_ERROR, &col(|r| r.3), &[rows.len()])?;
    }

    // Critical curves sampled on 401 points of the γ domain (α_c1 is NaN below γ = 1, where it
    // marks nothing); with an e_n axis α_c1 on 5 rows of e_n from e_n_min to e_n_max.
    let n = 401;
    let gamma: Vec<f64> = (0..n)
        .map(|i| s.gamma_min() + (s.gamma_max() - s.gamma_min()) * i as f64 / (n - 1) as f64)
        .collect();
    let c1_at = |e: f64| {
        gamma
            .iter()
            .map(move |&g| {
                if g >= 1.0 {
                    alpha_c1_dissipative(g, e)
                } else {
                    f64::NAN
                }
            })
            .collect::<Vec<f64>>()
    };
    let c2: Vec<f64> = gamma.iter().map(|&g| alpha_c2(g)).collect();
    let g = file.create_group(GROUP_CRITICAL).map_err(w.e("critical"))?;
    w.ds(&g, DS_GAMMA, &gamma, &[n])?;
    match e_range {
        None => w.ds(&g, DS_ALPHA_C1, &c1_at(1.0), &[n])?,
        Some((lo, hi)) => {
            let rows = 5;
            let e: Vec<f64> = (0..rows)
                .map(|i| lo + (hi - lo) * i as f64 / (rows - 1) as f64)
                .collect();
            let c1: Vec<f64> = e.iter().flat_map(|&e| c1_at(e)).collect();
            w.ds(&g, E_N.name, &e, &[rows])?;
            w.ds(&g, DS_ALPHA_C1, &c1, &[rows, n])?;
        }
    }
    w.ds(&g, DS_ALPHA_C2, &c2, &[n])?;

    let ch = &built.checks;
    let g = file.create_group(GROUP_CHECKS).map_err(w.e("checks"))?;
    let col = |f: fn(&Check) -> f64| ch.iter().map(f).collect::<Vec<f64>>();
    w.ds(&g, DS_GAMMA, &col(|c| c.gamma), &[ch.len()])?;
    w.ds(&g, DS_ALPHA, &col(|c| c.alpha), &[ch.len()])?;
    if e_range.is_some() {
        w.ds(&g, E_N.name, &col(|c| c.e_n), &[ch.len()])?;
    }
    w.ds(&g, DS_P_SIMULATED, &col(|c| c.p_simulated), &[ch.len()])?;
    w.ds(
        &g,
        DS_P_INTERPOLATED,
        &col(|c| c.p_interpolated),
        &[ch.len()],
    )?;
    w.ds(
        &g,
        DS_INTERP_ERROR,
        &col(|c| c.interpolation_error),
        &[ch.len()],
    )?;
    let patch: Vec<i32> = ch.iter().map(|c| c.patch).collect();
    w.ints(&g, DS_PATCH, &patch, &[ch.len()])?;
    file.flush().map_err(w.e("flush"))?;
    Ok(())
}

/// Write the seal (`crate::format::seal_of`) into the user block of the table file at
/// `path`, and sync it to disk. Also for tools that edit a table on purpose (the schema tests).
pub fn seal(path: &Path) -> std::io::Result<()> {
    use std::io::{Seek, SeekFrom, Write};
    let bytes = std::fs::read(path)?;
    let mut f = std::fs::OpenOptions::new().write(true).open(path)?;
    f.seek(SeekFrom::Start(0))?;
    f.write_all(&seal_of(&bytes))?;
    f.sync_all()
}
