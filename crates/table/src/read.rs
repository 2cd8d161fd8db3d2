//! Loading and validating a table file.

use std::path::Path;

use hdf5::types::VarLenUnicode;

use crate::format::*;
use crate::surface::{
    Axis, AxisMap, Knots, PartialMap, Patch, PatchData, PatchId, PatchKind, Surface, Warp,
};
use crate::TableError;

/// Where a table came from (root attributes).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Provenance {
    /// Schema version of the file.
    pub schema_version: u32,
    /// Engine version that wrote it.
    pub engine_version: String,
    /// Git commit of the engine.
    pub git_commit: String,
    /// The TOML config text.
    pub config: String,
    /// Solver settings.
    pub solver: String,
    /// Creation time (UTC).
    pub created: String,
    /// Build wall time (s).
    pub wall_time_s: f64,
    /// Node solver tolerance.
    pub node_tol: f64,
    /// Solver tolerance of the held-out check points.
    pub check_tol: f64,
    /// Target interpolation error.
    pub target_error: f64,
    /// The contact law of the node values (`kelvin-voigt` for a table with an `e_n` axis;
    /// empty for an elastic table).
    pub law: String,
}

/// One held-out check point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// γ.
    pub gamma: f64,
    /// α.
    pub alpha: f64,
    /// Normal restitution `e_n` (1 for an elastic table).
    pub e_n: f64,
    /// P simulated at the check tolerance (`check_tol`).
    pub p_simulated: f64,
    /// P interpolated from the table.
    pub p_interpolated: f64,
    /// |P_interpolated − P_simulated|.
    pub interpolation_error: f64,
    /// Patch index (0 stick_low, 1 partial_high, 2 stick_high).
    pub patch: i32,
}

/// Everything a table file holds, loaded and validated: the surface of the interpolation
/// rule, the provenance, the held-out checks and the error bound the table states.
#[derive(Debug, Clone, PartialEq)]
pub struct Contents {
    /// The interpolated surface.
    pub surface: Surface,
    /// Provenance attributes.
    pub provenance: Provenance,
    /// Held-out check points.
    pub checks: Vec<Check>,
    /// The stated error bound ([`crate::bound::surface_bound`] of the leaves' predicted errors;
    /// NaN for a file without `leaf_predicted_error`).
    pub error_bound: f64,
}

struct Reader<'a> {
    path: &'a str,
}

impl Reader<'_> {
    fn invalid(&self, message: impl Into<String>) -> TableError {
        TableError::Invalid {
            path: self.path.to_string(),
            message: message.into(),
        }
    }

    fn attr_f64(&self, loc: &hdf5::Location, name: &str) -> Result<f64, TableError> {
        loc.attr(name)
            .and_then(|a| a.read_scalar::<f64>())
            .map_err(|_| self.invalid(format!("missing or non-numeric attribute '{name}'")))
    }

    fn attr_str(&self, loc: &hdf5::Location, name: &str) -> Result<String, TableError> {
        loc.attr(name)
            .and_then(|a| a.read_scalar::<VarLenUnicode>())
            .map(|s| s.as_str().to_string())
            .map_err(|_| self.invalid(format!("missing or non-string attribute '{name}'")))
    }

    fn dataset(
        &self,
        group: &hdf5::Group,
        name: &str,
        shape: &[usize],
    ) -> Result<Vec<f64>, TableError> {
        let where_ = format!("{}/{name}", group.name());
        let ds = group
            .dataset(name)
            .map_err(|_| self.invalid(format!("missing dataset '{where_}'")))?;
        if ds.shape() != shape {
            return Err(self.invalid(format!(
                "dataset '{where_}' has shape {:?}, expected {shape:?}",
                ds.shape()
            )));
        }
        ds.read_raw::<f64>()
            .map_err(|e| self.invalid(format!("cannot read dataset '{where_}': {e}")))
    }

    fn finite(&self, what: &str, v: &[f64]) -> Result<(), TableError> {
        match v.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(self.invalid(format!("non-finite value {} in {what}[{i}]", v[i]))),
            None => Ok(()),
        }
    }

    /// A 1-D dataset of any length whose values are `T` (named `type_name` in the error),
    /// in group `g` of `owner` (how the error names the group, e.g. `patch 'stick_high'`).
    fn vector<T: hdf5::H5Type>(
        &self,
        g: &hdf5::Group,
        owner: &str,
        name: &str,
        type_name: &str,
    ) -> Result<Vec<T>, TableError> {
        g.dataset(name)
            .ok()
            .filter(|d| d.ndim() == 1)
            .and_then(|d| d.read_raw::<T>().ok())
            .ok_or_else(|| {
                self.invalid(format!(
                    "{owner}: dataset '{name}' missing or not a 1-D {type_name} array"
                ))
            })
    }

    fn count_attr(&self, g: &hdf5::Group, name: &str, max: usize) -> Result<usize, TableError> {
        let v = self.attr_f64(g, name)?;
        if v.fract() != 0.0 || v < 1.0 || v > max as f64 {
            return Err(self.invalid(format!(
                "patch attribute '{name}' = {v}: must be an integer in [1, {max}]"
            )));
        }
        Ok(v as usize)
    }

    /// The optional warp of patch `name` (group `warp`): only `partial_high` of a schema-3
    /// file may have one; every value is checked against the documented ranges.
    fn warp(&self, g: &hdf5::Group, name: &str, version: u32) -> Result<Option<Warp>, TableError> {
        if !g.link_exists(GROUP_WARP) {
            return Ok(None);
        }
        let where_ = format!("{name}/{GROUP_WARP}");
        if name != PATCH_PARTIAL_HIGH {
            return Err(self.invalid(format!(
                "patch '{name}' has a group '{GROUP_WARP}': only '{PATCH_PARTIAL_HIGH}' may have one"
            )));
        }
        if version < 3 {
            return Err(self.invalid(format!(
                "group '{where_}' in a schema-{version} file: a warp needs schema version 3"
            )));
        }
        let w = g
            .group(GROUP_WARP)
            .map_err(|_| self.invalid(format!("'{where_}' is not a group")))?;
        let attr = |a: &str| {
            self.attr_f64(&w, a).map_err(|_| {
                self.invalid(format!(
                    "'{where_}': missing or non-numeric attribute '{a}'"
                ))
            })
        };
        let (start, gamma_0, gamma_step, c_star) = (
            attr(ATTR_WARP_START)?,
            attr(ATTR_WARP_GAMMA_0)?,
            attr(ATTR_WARP_GAMMA_STEP)?,
            attr(ATTR_WARP_C_STAR)?,
        );
        let knot = self.vector(&w, &format!("'{where_}'"), DS_WARP_KNOT, "float64")?;
        Warp::new(start, gamma_0, gamma_step, c_star, knot)
            .map(Some)
            .map_err(|m| self.invalid(format!("'{where_}': {m}")))
    }

    /// The optional knots of patch `name` (group `knots`): only `partial_high` and
    /// `stick_high` of a schema-4 file over `gamma,alpha,e_n` may have them; every value is checked against the
    /// documented ranges ([`Knots::new`]; the rules against the patch are [`Patch::new`]'s).
    fn knots(
        &self,
        g: &hdf5::Group,
        name: &str,
        e_n_axis: bool,
    ) -> Result<Option<Knots>, TableError> {
        if !g.link_exists(GROUP_KNOTS) {
            return Ok(None);
        }
        let where_ = format!("{name}/{GROUP_KNOTS}");
        if !(name == PATCH_PARTIAL_HIGH || name == PATCH_STICK_HIGH) || !e_n_axis {
            return Err(self.invalid(format!(
                "patch '{name}' has a group '{GROUP_KNOTS}': only '{PATCH_PARTIAL_HIGH}' and \
                 '{PATCH_STICK_HIGH}' of a table over gamma, alpha and e_n may have one"
            )));
        }
        let k = g
            .group(GROUP_KNOTS)
            .map_err(|_| self.invalid(format!("'{where_}' is not a group")))?;
        let attr = |a: &str| {
            self.attr_f64(&k, a).map_err(|_| {
                self.invalid(format!(
                    "'{where_}': missing or non-numeric attribute '{a}'"
                ))
            })
        };
        let owner = format!("'{where_}'");
        let region: Vec<f64> = self.vector(&k, &owner, DS_KNOTS_REGION, "float64")?;
        let region: [f64; 4] = region.try_into().map_err(|v: Vec<f64>| {
            self.invalid(format!(
                "{owner}: dataset '{DS_KNOTS_REGION}' has {} values: expected 4",
                v.len()
            ))
        })?;
        let c_star = self.vector(&k, &owner, DS_KNOTS_C_STAR, "float64")?;
        let grade = self.vector(&k, &owner, DS_KNOTS_GRADE, "uint8")?;
        let ds = k
            .dataset(DS_KNOTS_KNOT)
            .ok()
            .filter(|d| d.ndim() == 3)
            .ok_or_else(|| {
                self.invalid(format!(
                    "{owner}: dataset '{DS_KNOTS_KNOT}' missing or not a 3-D float64 array"
                ))
            })?;
        let shape = ds.shape();
        let knot = ds.read_raw::<f64>().map_err(|e| {
            self.invalid(format!(
                "{owner}: cannot read dataset '{DS_KNOTS_KNOT}': {e}"
            ))
        })?;
        Knots::new(
            attr(ATTR_KNOTS_GAMMA_0)?,
            attr(ATTR_KNOTS_GAMMA_STEP)?,
            attr(ATTR_KNOTS_E_N_0)?,
            attr(ATTR_KNOTS_E_N_STEP)?,
            region,
            c_star,
            grade,
            [shape[0], shape[1], shape[2]],
            knot,
        )
        .map(Some)
        .map_err(|m| self.invalid(format!("{owner}: {m}")))
    }

    #[allow(clippy::too_many_arguments)]
    fn patch(
        &self,
        root: &hdf5::Group,
        name: &str,
        kind: PatchKind,
        stencil: usize,
        version: u32,
        e_range: Option<(f64, f64)>,
        e_map: AxisMap,
        pair: bool,
        law: &str,
    ) -> Result<Option<Patch>, TableError> {
        let Ok(g) = root.group(name) else {
            return Ok(None);
        };
        let stored_kind = self.attr_str(&g, ATTR_KIND)?;
        if stored_kind != kind.name() {
            return Err(self.invalid(format!(
                "patch '{name}' has kind '{stored_kind}', expected '{}'",
                kind.name()
            )));
        }
        let gamma_lo = self.attr_f64(&g, ATTR_GAMMA_LO)?;
        let gamma_hi = self.attr_f64(&g, ATTR_GAMMA_HI)?;
        let ordered = if pair {
            gamma_hi == gamma_lo
        } else {
            gamma_hi > gamma_lo
        };
        if !(gamma_lo.is_finite() && gamma_hi.is_finite() && gamma_lo > 0.0 && ordered) {
            return Err(self.invalid(format!(
                "patch '{name}': gamma edges [{gamma_lo}, {gamma_hi}] must be finite, > 0, {}",
                if pair {
                    "and equal (the table of one pair)"
                } else {
                    "increasing"
                }
            )));
        }
        let bg = self.count_attr(&g, ATTR_BLOCKS_GAMMA, 1 << 16)?;
        let bc = self.count_attr(&g, ATTR_BLOCKS_COORD, 1 << 16)?;
        let m = self.count_attr(&g, ATTR_LEAF_INTERVALS, 1 << 12)?;
        if m + 1 < stencil {
            return Err(self.invalid(format!(
                "patch '{name}': leaf_intervals = {m} gives fewer nodes than stencil_points = {stencil}"
            )));
        }
        let restitution = match e_range {
            Some((lo, hi)) => {
                if kind == PatchKind::PartialSlip {
                    // The coordinate's map is named: a table built with another one is refused,
                    // never read with this one.
                    // The law and its coordinate go together: a table whose coordinate is
                    // not its law's would answer from the wrong place.
                    let map = self.attr_str(&g, ATTR_COORDINATE)?;
                    let known = [PARTIAL_MAP_SQRT_BOTH, PARTIAL_MAP_SLIP];
                    if !known.contains(&map.as_str()) {
                        return Err(self.invalid(format!(
                            "patch '{name}': attribute '{ATTR_COORDINATE}' = '{map}': this reader \
                             understands '{PARTIAL_MAP_SQRT_BOTH}' and '{PARTIAL_MAP_SLIP}'; \
                             rebuild the table with this engine"
                        )));
                    }
                    if coordinate_of_law(law) != Some(map.as_str()) {
                        return Err(self.invalid(format!(
                            "patch '{name}': attribute '{ATTR_COORDINATE}' = '{map}' does not go \
                             with the root attribute '{ATTR_LAW}' = '{law}' (whose coordinate is \
                             '{}'): the file was changed after its build; rebuild it",
                            coordinate_of_law(law).unwrap_or_default()
                        )));
                    }
                }
                let be = self.count_attr(&g, E_N.attr_blocks, 1 << 16)?;
                Some(
                    Axis::extra(&E_N, lo, hi, be)
                        .map_err(|m| self.invalid(format!("patch '{name}': {m}")))?
                        .with_map(e_map),
                )
            }
            None => None,
        };
        let tree = self.vector(&g, &format!("patch '{name}'"), DS_TREE, "int32")?;
        // The tree's axes: (γ, c), (γ, c, e_n), or (c, e_n) in the table of one pair.
        let dims = crate::surface::tree_dims(restitution.is_some(), pair);
        let roots = bg * bc * restitution.map_or(1, |r| r.blocks());
        let fanout = 1 << dims;
        let split: Option<Vec<u8>> = if g.link_exists(DS_SPLIT) {
            let split = self.vector(&g, &format!("patch '{name}'"), DS_SPLIT, "uint8")?;
            crate::surface::check_split(&tree, &split, dims)
                .map_err(|m| self.invalid(format!("patch '{name}': dataset 'split' {m}")))?;
            Some(split)
        } else {
            None
        };
        let leaves = match &split {
            Some(s) => crate::surface::check_tree_split(&tree, roots, &|i| 1 << s[i].count_ones()),
            None => crate::surface::check_tree_of(&tree, roots, fanout),
        }
        .map_err(|m| self.invalid(format!("patch '{name}': dataset 'tree' {m}")))?;
        let mut shape = vec![leaves, m + 1, m + 1];
        if dims == 3 {
            shape.push(m + 1);
        }
        let p = self.dataset(&g, DS_P, &shape)?;
        let err = self.dataset(&g, DS_ERROR, &shape)?;
        self.finite(&format!("{name}/{DS_P}"), &p)?;
        self.finite(&format!("{name}/{DS_ERROR}"), &err)?;
        if let Some(i) = p.iter().position(|x| x.abs() > 1.0 + 1e-6) {
            return Err(self.invalid(format!("patch '{name}': |P| = {} > 1 at node {i}", p[i])));
        }
        let warp = self.warp(&g, name, version)?;
        let knots = self.knots(&g, name, restitution.is_some() && gamma_hi > gamma_lo)?;
        let group = if knots.is_some() {
            GROUP_KNOTS
        } else {
            GROUP_WARP
        };
        // The checks above name the datasets as the file has them; what remains (the warp's
        // rules against the patch) is the model's own check.
        let axes = [Axis::gamma(gamma_lo, gamma_hi, bg), Axis::coord(bc)]
            .into_iter()
            .chain(restitution)
            .collect();
        let patch = Patch::new(
            kind,
            axes,
            PatchData {
                leaf_intervals: m,
                tree,
                split,
                p,
                error_estimate: err,
                warp,
                knots,
            },
        )
        .map_err(|m| self.invalid(format!("'{name}/{group}': {m}")))?;
        // Where the builder simulated each value: the tree and the axis attributes must put
        // every node there, or the file's attributes were changed after the build.
        let gamma = self.dataset(&g, DS_GAMMA, &shape)?;
        let coord = self.dataset(&g, DS_COORD, &shape)?;
        let alpha = self.dataset(&g, DS_ALPHA, &shape)?;
        let e_n = match restitution {
            Some(_) => Some(self.dataset(&g, E_N.name, &shape)?),
            None => None,
        };
        let stored = crate::nodes::StoredNodes {
            gamma: &gamma,
            coord: &coord,
            alpha: &alpha,
            e_n: e_n.as_deref(),
        };
        crate::nodes::check_positions(name, &patch, stored).map_err(|m| self.invalid(m))?;
        Ok(Some(patch))
    }
}

/// The first bytes of the node files (shard parts, checkpoints) that a table build writes; a
/// user who passes one of them as a table is told what it is.
const NODE_FILE_MAGIC: &[u8] = b"OBLQNODE";

/// What an existing path is, in words, for a path that is not a regular file.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

/// An I/O error in words, without the `(os error N)` suffix.
fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => e.to_string(),
    }
}

/// Open, validate and load a table. Errors name the problem: not HDF5 or truncated, not a
/// P table, a newer schema, inconsistent shapes, non-finite values.
pub fn read(path: impl AsRef<Path>) -> Result<Contents, TableError> {
    let path_ref = path.as_ref();
    let path_str = path_ref.display().to_string();
    let r = Reader { path: &path_str };
    let io = |message: String| TableError::Io {
        path: path_str.clone(),
        message,
    };
    let meta = std::fs::metadata(path_ref).map_err(|e| io(io_reason(&e)))?;
    if !meta.is_file() {
        return Err(io(format!(
            "{} (a table is a regular file written by a table build)",
            file_kind(&meta)
        )));
    }
    let bytes = std::fs::read(path_ref).map_err(|e| io(io_reason(&e)))?;
    if bytes.is_empty() {
        return Err(io("empty file (0 bytes), not an HDF5 table".into()));
    }
    if bytes.starts_with(NODE_FILE_MAGIC) {
        return Err(r.invalid(
            "this is a node file (a shard part or a checkpoint of a table build), not a \
             table: merge the shard parts into a table first"
                .to_string(),
        ));
    }
    crate::format::verify_seal(&bytes).map_err(|m| r.invalid(m))?;
    drop(bytes);
    // HDF5 locks the file it opens (`flock`). A lock held by another process (an h5py session
    // writing it, or a child process that inherited a writer's descriptor) must not make a
    // read fail: a table is never written in place (a writer renames a complete file over
    // it), so the read is then retried without the lock. The first attempt keeps HDF5's
    // default, which a file already open in this process through the `hdf5` crate shares
    // (HDF5 refuses a second open of a file with another locking setting).
    let file = hdf5::File::open(path_ref)
        .or_else(|e| {
            if e.to_string().contains("unable to lock file") {
                hdf5::File::with_options()
                    .with_fapl(|p| p.file_locking(false))
                    .open(path_ref)
            } else {
                Err(e)
            }
        })
        .map_err(|e| TableError::Io {
            path: path_str.clone(),
            message: format!("not an HDF5 file, or truncated/corrupted (HDF5: {e})"),
        })?;
    let format = r.attr_str(&file, ATTR_FORMAT).map_err(|_| {
        r.invalid(format!(
            "not a P table (root attribute '{ATTR_FORMAT}' = '{FORMAT_NAME}' missing)"
        ))
    })?;
    if format != FORMAT_NAME {
        return Err(r.invalid(format!(
            "not a P table (format '{format}', expected '{FORMAT_NAME}')"
        )));
    }
    let version_f = r.attr_f64(&file, ATTR_SCHEMA)?;
    if !(MIN_SCHEMA_VERSION..=SCHEMA_VERSION).any(|v| v as f64 == version_f) {
        let version = version_f;
        return Err(r.invalid(format!(
            "schema version {version}, this reader understands {MIN_SCHEMA_VERSION} to \
             {SCHEMA_VERSION}; {}",
            if version_f > SCHEMA_VERSION as f64 {
                "upgrade oblique-lookup to read it"
            } else {
                "rebuild the table with this engine"
            }
        )));
    }
    let version = version_f as u32;
    let stencil_f = r.attr_f64(&file, ATTR_STENCIL)?;
    let stencil = stencil_f as usize;
    if stencil as f64 != stencil_f || !(2..=8).contains(&stencil) || !stencil.is_multiple_of(2) {
        return Err(r.invalid(format!(
            "stencil_points = {stencil_f}: must be an even integer in [2, 8]"
        )));
    }
    let gamma_min = r.attr_f64(&file, ATTR_GAMMA_MIN)?;
    let gamma_max = r.attr_f64(&file, ATTR_GAMMA_MAX)?;
    let alpha_max = r.attr_f64(&file, ATTR_ALPHA_MAX)?;
    if !(gamma_min > 0.0 && gamma_max >= gamma_min && gamma_max.is_finite()) {
        return Err(r.invalid(format!(
            "gamma domain [{gamma_min}, {gamma_max}] must satisfy 0 < min < max < inf (min = \
             max in the table of one pair)"
        )));
    }
    if alpha_max.is_nan() || alpha_max <= 0.0 {
        return Err(r.invalid(format!("alpha_max = {alpha_max} must be > 0 or inf")));
    }
    // Schema 4 names its axes; each extra axis brings its range.
    let mut pair = false;
    // The law of a table with an e_n axis (empty for an elastic one).
    let mut law = String::new();
    let e_range = if version >= 4 {
        let axes = r.attr_str(&file, ATTR_AXES)?;
        let names: Vec<&str> = axes.split(',').collect();
        let (head, extra) = match names.as_slice() {
            ["gamma", "alpha", rest @ ..] => (false, Some(rest)),
            ["alpha", rest @ ..] if !rest.is_empty() => (true, Some(rest)),
            _ => (false, None),
        };
        pair = head;
        let extra: Option<Vec<&ExtraAxis>> =
            extra.and_then(|e| e.iter().map(|n| ExtraAxis::named(n)).collect());
        // The rule answers at most one extra axis (the tree of a patch has at most 3 axes).
        let extra = match extra {
            Some(e) if e.len() <= 1 => e,
            _ => {
                let known: Vec<String> = std::iter::once(axes_attr([], false))
                    .chain(EXTRA_AXES.iter().map(|a| axes_attr([a], false)))
                    .chain(EXTRA_AXES.iter().map(|a| axes_attr([a], true)))
                    .map(|a| format!("'{a}'"))
                    .collect();
                let (last, rest) = known.split_last().expect("at least one");
                return Err(r.invalid(format!(
                    "root attribute '{ATTR_AXES}' = '{axes}': this reader understands {} and \
                     {last}",
                    rest.join(", ")
                )));
            }
        };
        match extra.first() {
            None => None,
            Some(spec) => {
                let (lo, hi) = (
                    r.attr_f64(&file, spec.attr_min)?,
                    r.attr_f64(&file, spec.attr_max)?,
                );
                spec.check_range(lo, hi).map_err(|m| r.invalid(m))?;
                law = r.attr_str(&file, ATTR_LAW)?;
                if !LAWS_E_N.contains(&law.as_str()) {
                    return Err(r.invalid(format!(
                        "root attribute '{ATTR_LAW}' = '{law}': this reader knows the law{} {}; \
                         a table of another law cannot answer this reader's questions",
                        if LAWS_E_N.len() == 1 { "" } else { "s" },
                        LAWS_E_N
                            .iter()
                            .map(|l| format!("'{l}'"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )));
                }
                Some((lo, hi))
            }
        }
    } else {
        None
    };
    if pair != (gamma_min == gamma_max) {
        return Err(r.invalid(format!(
            "gamma domain [{gamma_min}, {gamma_max}] with the axes '{}': the table of one pair \
             ('{AXES_PAIR}') has gamma_min = gamma_max, any other table gamma_min < gamma_max",
            r.attr_str(&file, ATTR_AXES).unwrap_or_default()
        )));
    }
    // Schema 5 names the map of the e_n axis; before it the axis is linear.
    let e_map = if version >= 5 {
        let name = r.attr_str(&file, ATTR_E_N_COORDINATE)?;
        match AxisMap::of_name(&name) {
            Some(map) if e_range.is_some() => map,
            Some(_) => {
                return Err(r.invalid(format!(
                    "root attribute '{ATTR_E_N_COORDINATE}' = '{name}' in a table without an \
                     e_n axis"
                )))
            }
            None => {
                return Err(r.invalid(format!(
                    "root attribute '{ATTR_E_N_COORDINATE}' = '{name}': this reader understands \
                     '{}' and '{}'",
                    AxisMap::Linear.name(),
                    AxisMap::QuarterRoot.name()
                )))
            }
        }
    } else {
        AxisMap::Linear
    };
    let patches = file
        .group(GROUP_PATCHES)
        .map_err(|_| r.invalid(format!("missing group '{GROUP_PATCHES}'")))?;
    let mut read_patches: [Option<Patch>; 3] = [None, None, None];
    for id in PatchId::ALL {
        read_patches[id.index()] = r.patch(
            &patches,
            id.name(),
            id.kind(),
            stencil,
            version,
            e_range,
            e_map,
            pair,
            &law,
        )?;
    }
    let surface = Surface::with_restitution(
        gamma_min,
        gamma_max,
        alpha_max,
        stencil,
        read_patches,
        e_range,
    )
    .map_err(|m| r.invalid(m))?;
    // The law's map (checked against each partial-slip patch's coordinate above).
    let surface = match coordinate_of_law(&law).and_then(PartialMap::of_coordinate) {
        Some(map) if e_range.is_some() => surface
            .with_partial_map(map)
            .map_err(|m| r.invalid(format!("root attribute '{ATTR_LAW}' = '{law}': {m}")))?,
        _ => surface,
    };
    // The predicted error of every leaf, for the stated bound (`None`: not in the file).
    let leaf_predicted = PatchId::ALL.map(|id| {
        let name = id.name();
        match (surface.patch_by_id(id), patches.group(name)) {
            (Some(p), Ok(g)) if g.link_exists(DS_LEAF_ERROR) => {
                let v = r.dataset(&g, DS_LEAF_ERROR, &[p.leaves()])?;
                match v.iter().position(|x| !(x.is_finite() && *x >= 0.0)) {
                    Some(i) => Err(r.invalid(format!(
                        "patch '{name}': {DS_LEAF_ERROR}[{i}] = {}: must be finite and >= 0",
                        v[i]
                    ))),
                    None => Ok(Some(v)),
                }
            }
            _ => Ok(None),
        }
    });
    let [a, b, c] = leaf_predicted;
    let (a, b, c) = (a?, b?, c?);
    let error_bound =
        crate::bound::surface_bound(&surface, [a.as_deref(), b.as_deref(), c.as_deref()]);
    let str_attr = |n: &str| r.attr_str(&file, n).unwrap_or_default();
    let provenance = Provenance {
        schema_version: version,
        engine_version: str_attr(ATTR_ENGINE_VERSION),
        git_commit: str_attr(ATTR_GIT_COMMIT),
        config: str_attr(ATTR_CONFIG),
        solver: str_attr(ATTR_SOLVER),
        created: str_attr(ATTR_CREATED),
        wall_time_s: r.attr_f64(&file, ATTR_WALL_TIME).unwrap_or(f64::NAN),
        node_tol: r.attr_f64(&file, ATTR_NODE_TOL).unwrap_or(f64::NAN),
        check_tol: r.attr_f64(&file, ATTR_CHECK_TOL).unwrap_or(f64::NAN),
        target_error: r.attr_f64(&file, ATTR_TARGET_ERROR).unwrap_or(f64::NAN),
        law: str_attr(ATTR_LAW),
    };
    let checks = match file.group(GROUP_CHECKS) {
        Ok(g) => {
            let n = g
                .dataset(DS_GAMMA)
                .map(|d| d.shape().first().copied().unwrap_or(0))
                .unwrap_or(0);
            let col = |name: &str| r.dataset(&g, name, &[n]);
            let (gm, al) = (col(DS_GAMMA)?, col(DS_ALPHA)?);
            let en = if e_range.is_some() {
                col(E_N.name)?
            } else {
                vec![1.0; n]
            };
            let (ps, pi, er) = (
                col(DS_P_SIMULATED)?,
                col(DS_P_INTERPOLATED)?,
                col(DS_INTERP_ERROR)?,
            );
            let patch = g
                .dataset(DS_PATCH)
                .and_then(|d| d.read_raw::<i32>())
                .map_err(|_| r.invalid(format!("missing dataset '{GROUP_CHECKS}/{DS_PATCH}'")))?;
            if patch.len() != n {
                return Err(r.invalid("checks/patch has the wrong length"));
            }
            (0..n)
                .map(|i| Check {
                    gamma: gm[i],
                    alpha: al[i],
                    e_n: en[i],
                    p_simulated: ps[i],
                    p_interpolated: pi[i],
                    interpolation_error: er[i],
                    patch: patch[i],
                })
                .collect()
        }
        Err(_) => Vec::new(),
    };
    Ok(Contents {
        surface,
        provenance,
        checks,
        error_bound,
    })
}
