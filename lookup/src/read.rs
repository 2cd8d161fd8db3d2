//! Loading and validating a table file.

use std::path::Path;

use hdf5::types::VarLenUnicode;

use crate::format::*;
use crate::surface::{Patch, PatchKind, Surface};
use crate::LookupError;

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
    /// Target interpolation error.
    pub target_error: f64,
}

/// One held-out check point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// γ.
    pub gamma: f64,
    /// α.
    pub alpha: f64,
    /// P simulated at the node tolerance.
    pub p_simulated: f64,
    /// P interpolated from the table.
    pub p_interpolated: f64,
    /// |P_interpolated − P_simulated|.
    pub interpolation_error: f64,
    /// Patch index (0 stick_low, 1 partial_high, 2 stick_high).
    pub patch: i32,
}

/// A loaded table: the surface, its provenance and its held-out checks. `Send + Sync`; queries
/// touch only memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The interpolated surface.
    pub surface: Surface,
    /// Provenance attributes.
    pub provenance: Provenance,
    /// Held-out check points.
    pub checks: Vec<Check>,
}

struct Reader<'a> {
    path: &'a str,
}

impl Reader<'_> {
    fn invalid(&self, message: impl Into<String>) -> LookupError {
        LookupError::Invalid {
            path: self.path.to_string(),
            message: message.into(),
        }
    }

    fn attr_f64(&self, loc: &hdf5::Location, name: &str) -> Result<f64, LookupError> {
        loc.attr(name)
            .and_then(|a| a.read_scalar::<f64>())
            .map_err(|_| self.invalid(format!("missing or non-numeric attribute '{name}'")))
    }

    fn attr_str(&self, loc: &hdf5::Location, name: &str) -> Result<String, LookupError> {
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
    ) -> Result<Vec<f64>, LookupError> {
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

    fn finite(&self, what: &str, v: &[f64]) -> Result<(), LookupError> {
        match v.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(self.invalid(format!("non-finite value {} in {what}[{i}]", v[i]))),
            None => Ok(()),
        }
    }

    /// A `[blocks_gamma, blocks_coord]` integer dataset of a patch.
    fn block_dataset<T: hdf5::H5Type>(
        &self,
        g: &hdf5::Group,
        patch: &str,
        name: &str,
        shape: [usize; 2],
    ) -> Result<Vec<T>, LookupError> {
        g.dataset(name)
            .ok()
            .filter(|d| d.shape() == shape)
            .and_then(|d| d.read_raw::<T>().ok())
            .ok_or_else(|| {
                self.invalid(format!(
                    "patch '{patch}': dataset '{name}' missing or not [{}, {}]",
                    shape[0], shape[1]
                ))
            })
    }

    fn count_attr(&self, g: &hdf5::Group, name: &str, max: usize) -> Result<usize, LookupError> {
        let v = self.attr_f64(g, name)?;
        if v.fract() != 0.0 || v < 1.0 || v > max as f64 {
            return Err(self.invalid(format!(
                "patch attribute '{name}' = {v}: must be an integer in [1, {max}]"
            )));
        }
        Ok(v as usize)
    }

    fn patch(
        &self,
        root: &hdf5::Group,
        name: &str,
        kind: PatchKind,
        stencil: usize,
    ) -> Result<Option<Patch>, LookupError> {
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
        if !(gamma_lo.is_finite() && gamma_hi.is_finite() && gamma_lo > 0.0 && gamma_hi > gamma_lo)
        {
            return Err(self.invalid(format!(
                "patch '{name}': gamma edges [{gamma_lo}, {gamma_hi}] must be finite, > 0, increasing"
            )));
        }
        let bg = self.count_attr(&g, ATTR_BLOCKS_GAMMA, 1 << 16)?;
        let bc = self.count_attr(&g, ATTR_BLOCKS_COORD, 1 << 16)?;
        let m = self.count_attr(&g, ATTR_BLOCK_INTERVALS, 1 << 12)?;
        if m + 1 < stencil {
            return Err(self.invalid(format!(
                "patch '{name}': block_intervals = {m} gives fewer nodes than stencil_points = {stencil}"
            )));
        }
        let level_raw = self.block_dataset::<i32>(&g, name, DS_LEVEL, [bg, bc])?;
        let offset_raw = self.block_dataset::<i64>(&g, name, DS_OFFSET, [bg, bc])?;
        let mut level = Vec::with_capacity(level_raw.len());
        let mut offset = Vec::with_capacity(level_raw.len());
        let mut total = 0usize;
        for (i, (&l, &o)) in level_raw.iter().zip(&offset_raw).enumerate() {
            if !(0..=12).contains(&l) {
                return Err(
                    self.invalid(format!("patch '{name}': level[{i}] = {l} not in [0, 12]"))
                );
            }
            if o != total as i64 {
                return Err(self.invalid(format!(
                    "patch '{name}': offset[{i}] = {o}, expected {total} (blocks must be stored in order)"
                )));
            }
            level.push(l as u32);
            offset.push(total);
            total += ((m << l) + 1).pow(2);
        }
        let p = self.dataset(&g, DS_P, &[total])?;
        let err = self.dataset(&g, DS_ERROR, &[total])?;
        self.finite(&format!("{name}/{DS_P}"), &p)?;
        self.finite(&format!("{name}/{DS_ERROR}"), &err)?;
        if let Some(i) = p.iter().position(|x| x.abs() > 1.0 + 1e-6) {
            return Err(self.invalid(format!("patch '{name}': |P| = {} > 1 at node {i}", p[i])));
        }
        Ok(Some(Patch {
            kind,
            gamma_lo,
            gamma_hi,
            blocks_gamma: bg,
            blocks_coord: bc,
            block_intervals: m,
            level,
            offset,
            p,
            error_estimate: err,
        }))
    }
}

impl Table {
    /// Open, validate and load a table. Errors name the problem: not HDF5 or truncated, not a
    /// P table, a newer schema, inconsistent shapes, non-finite values.
    pub fn open(path: impl AsRef<Path>) -> Result<Table, LookupError> {
        let path_ref = path.as_ref();
        let path_str = path_ref.display().to_string();
        let r = Reader { path: &path_str };
        if !path_ref.is_file() {
            return Err(LookupError::Io {
                path: path_str.clone(),
                message: "no such file".into(),
            });
        }
        let file = hdf5::File::open(path_ref).map_err(|_| LookupError::Io {
            path: path_str.clone(),
            message: "not an HDF5 file, or truncated/corrupted".into(),
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
        let version = r.attr_f64(&file, ATTR_SCHEMA)?;
        if version != SCHEMA_VERSION as f64 {
            return Err(r.invalid(format!(
                "schema version {version}, this reader understands {SCHEMA_VERSION}; \
                 {}",
                if version > SCHEMA_VERSION as f64 {
                    "upgrade oblique-lookup to read it"
                } else {
                    "rebuild the table with `sweep run`"
                }
            )));
        }
        let stencil_f = r.attr_f64(&file, ATTR_STENCIL)?;
        let stencil = stencil_f as usize;
        if stencil as f64 != stencil_f || !(2..=8).contains(&stencil) || stencil % 2 != 0 {
            return Err(r.invalid(format!(
                "stencil_points = {stencil_f}: must be an even integer in [2, 8]"
            )));
        }
        let gamma_min = r.attr_f64(&file, ATTR_GAMMA_MIN)?;
        let gamma_max = r.attr_f64(&file, ATTR_GAMMA_MAX)?;
        let alpha_max = r.attr_f64(&file, ATTR_ALPHA_MAX)?;
        if !(gamma_min > 0.0 && gamma_max > gamma_min && gamma_max.is_finite()) {
            return Err(r.invalid(format!(
                "gamma domain [{gamma_min}, {gamma_max}] must satisfy 0 < min < max < inf"
            )));
        }
        if alpha_max.is_nan() || alpha_max <= 0.0 {
            return Err(r.invalid(format!("alpha_max = {alpha_max} must be > 0 or inf")));
        }
        let patches = file
            .group(GROUP_PATCHES)
            .map_err(|_| r.invalid(format!("missing group '{GROUP_PATCHES}'")))?;
        let surface = Surface {
            gamma_min,
            gamma_max,
            alpha_max,
            stencil,
            stick_low: r.patch(&patches, PATCH_STICK_LOW, PatchKind::Stick, stencil)?,
            partial_high: r.patch(
                &patches,
                PATCH_PARTIAL_HIGH,
                PatchKind::PartialSlip,
                stencil,
            )?,
            stick_high: r.patch(&patches, PATCH_STICK_HIGH, PatchKind::Stick, stencil)?,
        };
        if gamma_min < 1.0 && surface.stick_low.is_none() {
            return Err(r.invalid(format!("missing patch '{PATCH_STICK_LOW}'")));
        }
        if gamma_max > 1.0 && (surface.partial_high.is_none() || surface.stick_high.is_none()) {
            return Err(r.invalid(format!(
                "missing patch '{PATCH_PARTIAL_HIGH}' or '{PATCH_STICK_HIGH}'"
            )));
        }
        let str_attr = |n: &str| r.attr_str(&file, n).unwrap_or_default();
        let provenance = Provenance {
            schema_version: SCHEMA_VERSION,
            engine_version: str_attr(ATTR_ENGINE_VERSION),
            git_commit: str_attr(ATTR_GIT_COMMIT),
            config: str_attr(ATTR_CONFIG),
            solver: str_attr(ATTR_SOLVER),
            created: str_attr(ATTR_CREATED),
            wall_time_s: r.attr_f64(&file, ATTR_WALL_TIME).unwrap_or(f64::NAN),
            node_tol: r.attr_f64(&file, ATTR_NODE_TOL).unwrap_or(f64::NAN),
            target_error: r.attr_f64(&file, ATTR_TARGET_ERROR).unwrap_or(f64::NAN),
        };
        let checks = match file.group(GROUP_CHECKS) {
            Ok(g) => {
                let n = g
                    .dataset(DS_GAMMA)
                    .map(|d| d.shape().first().copied().unwrap_or(0))
                    .unwrap_or(0);
                let col = |name: &str| r.dataset(&g, name, &[n]);
                let (gm, al) = (col(DS_GAMMA)?, col(DS_ALPHA)?);
                let (ps, pi, er) = (
                    col(DS_P_SIMULATED)?,
                    col(DS_P_INTERPOLATED)?,
                    col(DS_INTERP_ERROR)?,
                );
                let patch = g
                    .dataset(DS_PATCH)
                    .and_then(|d| d.read_raw::<i32>())
                    .map_err(|_| {
                        r.invalid(format!("missing dataset '{GROUP_CHECKS}/{DS_PATCH}'"))
                    })?;
                if patch.len() != n {
                    return Err(r.invalid("checks/patch has the wrong length"));
                }
                (0..n)
                    .map(|i| Check {
                        gamma: gm[i],
                        alpha: al[i],
                        p_simulated: ps[i],
                        p_interpolated: pi[i],
                        interpolation_error: er[i],
                        patch: patch[i],
                    })
                    .collect()
            }
            Err(_) => Vec::new(),
        };
        Ok(Table {
            surface,
            provenance,
            checks,
        })
    }

    /// `P(γ, α)`; see [`Surface::eval`].
    pub fn p(&self, gamma: f64, alpha: f64) -> Result<f64, LookupError> {
        self.surface.eval(gamma, alpha)
    }
}
