//! Names of the HDF5 objects of a table (schema v4, v3). `docs/table-format.md` documents each.

/// Newest schema version this crate reads and writes: v4 adds the normal-restitution axis
/// (`e_n`) to v3; v5 adds the map of that axis ([`ATTR_E_N_COORDINATE`]). A table with the
/// axis is written as v4 when the map is linear, as v5 otherwise.
pub const SCHEMA_VERSION: u32 = 5;
/// Schema version of a table with an `e_n` axis mapped linearly: v4, which every reader of v4
/// reads.
pub const E_N_SCHEMA_VERSION: u32 = 4;
/// Root attribute (schema 5, required there; absent before): how the patches map `e_n` to
/// their coordinate, `e_n` (linear) or `(1-e_n)^(1/4)`
/// ([`crate::surface::AxisMap::QuarterRoot`]).
pub const ATTR_E_N_COORDINATE: &str = "e_n_coordinate";
/// Schema version of an elastic table (no `e_n` axis): v3, which every reader of v3 reads.
pub const ELASTIC_SCHEMA_VERSION: u32 = 3;
/// Oldest schema version this crate reads: v2 is v3 without the optional warp.
pub const MIN_SCHEMA_VERSION: u32 = 2;

/// Root attribute: schema version (an integer value stored as float64).
pub const ATTR_SCHEMA: &str = "schema_version";
/// Root attribute: fixed string identifying the file kind.
pub const ATTR_FORMAT: &str = "format";
/// Value of [`ATTR_FORMAT`].
pub const FORMAT_NAME: &str = "oblique-P-table";
/// Root attribute: number of points of the Lagrange stencil per axis (even, ≥ 2).
pub const ATTR_STENCIL: &str = "stencil_points";
/// Root attribute: lower end of the γ domain.
pub const ATTR_GAMMA_MIN: &str = "gamma_min";
/// Root attribute: upper end of the γ domain.
pub const ATTR_GAMMA_MAX: &str = "gamma_max";
/// Root attribute: upper end of the α domain (`inf` for no slip included).
pub const ATTR_ALPHA_MAX: &str = "alpha_max";
/// Root attribute (schema 4): the axes of the table, in order, separated by commas:
/// `gamma,alpha`, `gamma,alpha,e_n`, or [`AXES_PAIR`].
pub const ATTR_AXES: &str = "axes";
/// The axes of the table of one pair of materials (schema 4): `P(α, e_n)` at the single `γ`
/// `gamma_min = gamma_max`; its patches' trees are over `(c, e_n)`.
pub const AXES_PAIR: &str = "alpha,e_n";
/// Root attribute (schema 4, with an `e_n` axis): lowest normal restitution `e_n`.
pub const ATTR_E_N_MIN: &str = E_N.attr_min;
/// Root attribute (schema 4, with an `e_n` axis): highest normal restitution `e_n`.
pub const ATTR_E_N_MAX: &str = E_N.attr_max;
/// Root attribute (schema 4, with an `e_n` axis): the contact law of the node values
/// (`kelvin-voigt` or `thornton`).
pub const ATTR_LAW: &str = "law";
/// The law of a Kelvin–Voigt table (`physics.md`, "Dissipative impacts"): its full-slip line
/// `P = 1 − (7/2)(1 + e_n)α` is exact up to `α_c1(γ, e_n)`.
pub const LAW_KELVIN_VOIGT: &str = "kelvin-voigt";
/// The law of a table of Thornton's elastic–plastic law: `P` has no closed-form full-slip
/// line, so its partial-slip patch covers `0 ≤ α ≤ α_c2` ([`PARTIAL_MAP_SLIP`]).
pub const LAW_THORNTON: &str = "thornton";
/// The values of [`ATTR_LAW`] a reader accepts: the contact laws whose tables this engine
/// builds and answers.
pub const LAWS_E_N: &[&str] = &[LAW_KELVIN_VOIGT, LAW_THORNTON];
/// Patch attribute (schema 4, partial-slip patch with an `e_n` axis): the map from `α` to the
/// patch coordinate, [`PARTIAL_MAP_SQRT_BOTH`] or [`PARTIAL_MAP_SLIP`], the one of the table's
/// law ([`coordinate_of_law`]); readers refuse any other pair.
pub const ATTR_COORDINATE: &str = "coordinate";
/// Value of [`ATTR_COORDINATE`]: `c = 1 − √(1 − √ℓ)` over `α_c1 … α_c2`, `ℓ =
/// ln(α/α_c1)/ln(α_c2/α_c1)` ([`crate::surface::PartialMap::SqrtBoth`]; a Kelvin–Voigt table).
pub const PARTIAL_MAP_SQRT_BOTH: &str = "1-sqrt(1-sqrt(l))";
/// Value of [`ATTR_COORDINATE`]: the patch covers `0 … α_c2`, `c = α/(2α_c1)` up to `α_c1`
/// and `c = 1/2 + (1 − √(1 − √ℓ))/2` above ([`crate::surface::PartialMap::Slip`]; a table of
/// Thornton's law).
pub const PARTIAL_MAP_SLIP: &str = "slip,1-sqrt(1-sqrt(l))";

/// The [`ATTR_COORDINATE`] of the partial-slip patch of a table of the law `law` (a value of
/// [`LAWS_E_N`]); `None` for a law this crate does not know.
pub fn coordinate_of_law(law: &str) -> Option<&'static str> {
    match law {
        LAW_KELVIN_VOIGT => Some(PARTIAL_MAP_SQRT_BOTH),
        LAW_THORNTON => Some(PARTIAL_MAP_SLIP),
        _ => None,
    }
}
/// Patch attribute (schema 4, with an `e_n` axis): number of root cells along `e_n`.
pub const ATTR_BLOCKS_E_N: &str = E_N.attr_blocks;
/// Node dataset (schema 4, with an `e_n` axis; `[leaves, m+1, m+1, m+1]`): `e_n` of every
/// node; also the check dataset of the held-out points' `e_n`, and a no-slip dataset.
pub const DS_E_N: &str = E_N.name;

/// An axis a table may have beyond `γ` and `α` (schema 4): its name, how the file stores its
/// range and layout, and the values it takes. [`EXTRA_AXES`] lists every such axis; the reader,
/// the writer, the node check, the exporter and the bindings take the names from there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExtraAxis {
    /// Name in the `axes` attribute, in queries and messages; also the name of the node
    /// dataset of a patch (`[leaves, m+1, m+1, m+1]`), of the checks' and of a no-slip
    /// dataset.
    pub name: &'static str,
    /// What the axis is, for messages and help (`normal restitution`).
    pub quantity: &'static str,
    /// Root attribute: lowest value of the table's range.
    pub attr_min: &'static str,
    /// Root attribute: highest value of the table's range.
    pub attr_max: &'static str,
    /// Patch attribute: number of root cells along the axis.
    pub attr_blocks: &'static str,
    /// Every range `[lo, hi]` satisfies `bound_lo < lo < hi ≤ bound_hi` (the axis's units).
    pub bound_lo: f64,
    /// See [`ExtraAxis::bound_lo`].
    pub bound_hi: f64,
    /// The value a table without this axis answers (and the only one): `e_n = 1`, elastic.
    pub fixed: f64,
}

impl ExtraAxis {
    /// `Ok` for a range `[lo, hi]` this axis allows; `Err` names the axis and the rule.
    pub fn check_range(&self, lo: f64, hi: f64) -> Result<(), String> {
        if !(lo > self.bound_lo && hi > lo && hi <= self.bound_hi) {
            let n = self.name;
            return Err(format!(
                "{n} range [{lo}, {hi}]: must satisfy {} < {n}_lo < {n}_hi <= {}",
                self.bound_lo, self.bound_hi
            ));
        }
        Ok(())
    }

    /// The axis named `name` in [`EXTRA_AXES`].
    pub fn named(name: &str) -> Option<&'static ExtraAxis> {
        EXTRA_AXES.iter().find(|a| a.name == name)
    }
}

/// The normal-restitution axis `e_n` (dimensionless, `0 < e_n ≤ 1`; `physics.md`, "Dissipative
/// impacts").
pub const E_N: ExtraAxis = ExtraAxis {
    name: "e_n",
    quantity: "normal restitution",
    attr_min: "e_n_min",
    attr_max: "e_n_max",
    attr_blocks: "blocks_e_n",
    bound_lo: 0.0,
    bound_hi: 1.0,
    fixed: 1.0,
};

/// Every axis a table may have beyond `γ` and `α`, in the order of the `axes` attribute and of
/// a query's point: one line per axis.
pub const EXTRA_AXES: &[ExtraAxis] = &[E_N];

/// The value of [`ATTR_AXES`] for a table with the extra axes `extra` (in [`EXTRA_AXES`]
/// order): `gamma,alpha` then their names, or without `gamma` for the table of one pair.
pub fn axes_attr<'a>(extra: impl IntoIterator<Item = &'a ExtraAxis>, pair: bool) -> String {
    let head: &[&str] = if pair {
        &["alpha"]
    } else {
        &["gamma", "alpha"]
    };
    head.iter()
        .copied()
        .chain(extra.into_iter().map(|a| a.name))
        .collect::<Vec<_>>()
        .join(",")
}

/// Root attribute: engine version.
pub const ATTR_ENGINE_VERSION: &str = "engine_version";
/// Root attribute: git commit of the engine (or "unknown").
pub const ATTR_GIT_COMMIT: &str = "git_commit";
/// Root attribute: the TOML config text the table was built from.
pub const ATTR_CONFIG: &str = "config";
/// Root attribute: solver settings (scheme, tolerance), human-readable.
pub const ATTR_SOLVER: &str = "solver";
/// Root attribute: node solver tolerance (absolute error of P).
pub const ATTR_NODE_TOL: &str = "node_tol";
/// Root attribute: solver tolerance of the held-out check points (absolute error of P).
pub const ATTR_CHECK_TOL: &str = "check_tol";
/// Root attribute: target interpolation error.
pub const ATTR_TARGET_ERROR: &str = "target_error";
/// Root attribute: creation time (UTC, RFC 3339).
pub const ATTR_CREATED: &str = "created";
/// Root attribute: wall time of the build (s).
pub const ATTR_WALL_TIME: &str = "wall_time_s";

/// Group holding one sub-group per patch.
pub const GROUP_PATCHES: &str = "patches";
/// Patch below γ = 1: α from α_c2 to α_max.
pub const PATCH_STICK_LOW: &str = "stick_low";
/// Patch above γ = 1: α from α_c1 to α_c2 (partial slip).
pub const PATCH_PARTIAL_HIGH: &str = "partial_high";
/// Patch above γ = 1: α from α_c2 to α_max.
pub const PATCH_STICK_HIGH: &str = "stick_high";
/// Patch attribute: "partial-slip" or "stick".
pub const ATTR_KIND: &str = "kind";
/// Patch attribute: lower γ edge.
pub const ATTR_GAMMA_LO: &str = "gamma_lo";
/// Patch attribute: upper γ edge.
pub const ATTR_GAMMA_HI: &str = "gamma_hi";
/// Patch attribute: number of root cells along γ.
pub const ATTR_BLOCKS_GAMMA: &str = "blocks_gamma";
/// Patch attribute: number of root cells along the coordinate.
pub const ATTR_BLOCKS_COORD: &str = "blocks_coord";
/// Patch attribute: intervals per axis of every leaf's node grid (`m`).
pub const ATTR_LEAF_INTERVALS: &str = "leaf_intervals";
/// Patch dataset (int32 `[cells]`): the quadtree; `≥ 0` first child of a split cell, `< 0` leaf
/// number `−value − 1`.
pub const DS_TREE: &str = "tree";
/// Per-cell masks of the axes a split cell halves (schema 4, optional; `uint8`).
pub const DS_SPLIT: &str = "split";
/// Patch dataset (int32 `[leaves]`): depth of every leaf (roots are depth 0).
pub const DS_LEAF_DEPTH: &str = "leaf_depth";
/// Node dataset (`[leaves, m+1, m+1]`): γ of every node.
pub const DS_GAMMA: &str = "gamma";
/// Node dataset (`[leaves, m+1, m+1]`): patch coordinate `c` of every node.
pub const DS_COORD: &str = "coord";
/// Node dataset (`[leaves, m+1, m+1]`): α of every node (`inf` allowed).
pub const DS_ALPHA: &str = "alpha";
/// Node dataset (`[leaves, m+1, m+1]`): P of every node.
pub const DS_P: &str = "P";
/// Node dataset (`[leaves, m+1, m+1]`): solver error estimate of P at every node.
pub const DS_ERROR: &str = "error_estimate";
/// Patch dataset (`[leaves]`): predicted interpolation error of every leaf.
pub const DS_LEAF_ERROR: &str = "leaf_predicted_error";

/// Optional sub-group of `partial_high` (schema 3): the warp of the coordinate
/// ([`crate::surface::Warp`]).
pub const GROUP_WARP: &str = "warp";
/// Warp attribute: γ of the first knot.
pub const ATTR_WARP_GAMMA_0: &str = "gamma_0";
/// Attribute of the warp group: lattice position along γ (root-cell units) where the warp starts.
pub const ATTR_WARP_START: &str = "start";
/// Warp attribute: γ spacing of the knots (`> 0`).
pub const ATTR_WARP_GAMMA_STEP: &str = "gamma_step";
/// Warp attribute: `c'` the knot is sent to, in `(0, 1)`.
pub const ATTR_WARP_C_STAR: &str = "c_star";
/// Warp dataset (float64 `[n]`, `n ≥ 4`): the knot `K` at `γ = gamma_0 + i·gamma_step`, in
/// `(0, 1)`.
pub const DS_WARP_KNOT: &str = "knot";

/// Optional sub-group of `partial_high` and of `stick_high` (schema 4, a table over `γ, α, e_n`):
/// the knots of the patch's coordinate ([`crate::surface::Knots`]).
pub const GROUP_KNOTS: &str = "knots";
/// Knots attributes: the grid's origins and steps along γ and `e_n`.
pub const ATTR_KNOTS_GAMMA_0: &str = "gamma_0";
/// See [`ATTR_KNOTS_GAMMA_0`].
pub const ATTR_KNOTS_GAMMA_STEP: &str = "gamma_step";
/// See [`ATTR_KNOTS_GAMMA_0`].
pub const ATTR_KNOTS_E_N_0: &str = "e_n_0";
/// See [`ATTR_KNOTS_GAMMA_0`].
pub const ATTR_KNOTS_E_N_STEP: &str = "e_n_step";
/// Knots dataset (float64 `[4]`): the box of root cells where the knots apply.
pub const DS_KNOTS_REGION: &str = "region";
/// Knots dataset (float64 `[k]`): where each knot is sent.
pub const DS_KNOTS_C_STAR: &str = "c_star";
/// Knots dataset (uint8 `[k]`): the grading next to each knot.
pub const DS_KNOTS_GRADE: &str = "grade";
/// Knots dataset (float64 `[k, n_γ, n_e]`): the knot values on the grid.
pub const DS_KNOTS_KNOT: &str = "knot";

/// Group with the no-slip limit `P(γ, ∞)`: datasets `gamma`, `P`, `error_estimate`.
pub const GROUP_NO_SLIP: &str = "no_slip";
/// Group with the critical curves: datasets `gamma`, `alpha_c1`, `alpha_c2`.
pub const GROUP_CRITICAL: &str = "critical";
/// Dataset name of α_c1 samples.
pub const DS_ALPHA_C1: &str = "alpha_c1";
/// Dataset name of α_c2 samples.
pub const DS_ALPHA_C2: &str = "alpha_c2";

/// Group with the held-out check points.
pub const GROUP_CHECKS: &str = "checks";
/// Check dataset: simulated P.
pub const DS_P_SIMULATED: &str = "P_simulated";
/// Check dataset: P interpolated from the table.
pub const DS_P_INTERPOLATED: &str = "P_interpolated";
/// Check dataset: |P_interpolated − P_simulated|.
pub const DS_INTERP_ERROR: &str = "interpolation_error";
/// Check dataset: patch index (0 stick_low, 1 partial_high, 2 stick_high).
pub const DS_PATCH: &str = "patch";

/// Size (bytes) of the HDF5 user block at the start of a table: HDF5 ignores it, and the writer
/// puts the table's seal there.
pub const USERBLOCK: usize = 512;

/// First bytes of the seal.
pub const SEAL_MAGIC: &[u8; 8] = b"OBLQSEAL";

/// FNV-1a (64 bit) of a byte string: the seal's digest.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The seal of a table file's bytes: `SEAL_MAGIC`, then the file length and the FNV-1a 64 of
/// every byte after the user block, both as little-endian u64 (24 bytes at offset 0).
pub fn seal_of(file: &[u8]) -> [u8; 24] {
    let mut s = [0u8; 24];
    s[..8].copy_from_slice(SEAL_MAGIC);
    s[8..16].copy_from_slice(&(file.len() as u64).to_le_bytes());
    let digest = fnv1a64(file.get(USERBLOCK..).unwrap_or(&[]));
    s[16..].copy_from_slice(&digest.to_le_bytes());
    s
}

/// Check the seal of a table file before HDF5 parses it: the HDF5 library is not robust
/// against damaged files (it can crash on them), so a sealed file whose bytes changed after it
/// was written is refused here. A file without a seal (written by other software) is left to
/// HDF5 and the format checks. `Err` holds the message.
pub fn verify_seal(file: &[u8]) -> Result<(), String> {
    if file.len() < USERBLOCK || &file[..8] != SEAL_MAGIC {
        return Ok(());
    }
    if file[..24] != seal_of(file) {
        return Err(
            "damaged: its checksum does not match its contents (the file was truncated, \
             corrupted or modified after it was written); rebuild it with `sweep run` or copy it \
             again"
                .into(),
        );
    }
    Ok(())
}
