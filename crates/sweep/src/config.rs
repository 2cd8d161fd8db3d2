//! The TOML config of `sweep run`: domain, node placement, solver accuracy, checks, threads,
//! output. Unknown keys are rejected; every error names the key, the value and the allowed range.

use std::path::{Path, PathBuf};

use oblique_table::surface::{AxisMap, PartialMap};
use serde::{Deserialize, Deserializer, Serialize};
use thiserror::Error;

/// `nodes.e_n_coordinate` of a linear `e_n` axis (the default).
pub const E_N_LINEAR: &str = "linear";
/// `nodes.e_n_coordinate` of an axis over `t = (1 − e_n)^{1/4}` ([`AxisMap::QuarterRoot`]).
pub const E_N_QUARTER_ROOT: &str = "quarter-root";

/// A config error: which file, which key, what is wrong.
#[derive(Debug, Error)]
pub enum ConfigError {
    /// The file could not be read.
    #[error("cannot read config {path}: {source}")]
    Read {
        /// Path.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// TOML syntax error, unknown key or wrong type (the message names the key and line).
    #[error("config {path}: {message}")]
    Parse {
        /// Path.
        path: String,
        /// The TOML parser's message.
        message: String,
    },
    /// A value is outside its allowed range.
    #[error("config {path}: `{key}` = {value}: must be {allowed}")]
    Range {
        /// Path.
        path: String,
        /// Dotted key.
        key: &'static str,
        /// The value given.
        value: String,
        /// Allowed range.
        allowed: String,
    },
}

impl ConfigError {
    /// Always true: every variant names the file or key to change.
    pub fn user_can_fix(&self) -> bool {
        true
    }
}

fn alpha_max_de<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum V {
        N(f64),
        S(String),
    }
    match V::deserialize(d)? {
        V::N(x) => Ok(x),
        V::S(s) if matches!(s.trim().to_ascii_lowercase().as_str(), "inf" | "infinity") => {
            Ok(f64::INFINITY)
        }
        V::S(s) => Err(serde::de::Error::custom(format!(
            "alpha_max = \"{s}\": must be a number or \"inf\""
        ))),
    }
}

fn default_alpha_max() -> f64 {
    f64::INFINITY
}

/// `[domain]`: the part of the `(γ, α)` plane the table covers. `α` always starts at 0.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Domain {
    /// Lower end of γ (> 0). With `gamma` (one pair) it is `gamma` and not given.
    #[serde(skip_deserializing)]
    pub gamma_min: f64,
    /// Upper end of γ (> gamma_min, ≤ 64). With `gamma` it is `gamma` and not given.
    #[serde(skip_deserializing)]
    pub gamma_max: f64,
    /// The single γ of one pair of materials (in (0, 64], with `e_n_min` and `e_n_max`, in
    /// place of `gamma_min` and `gamma_max`): the table is then `P(α, e_n)` at that γ.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gamma: Option<f64>,
    /// Upper end of α: a number > α_c2(gamma_max), or "inf" (default) to include no slip.
    #[serde(default = "default_alpha_max", deserialize_with = "alpha_max_de")]
    pub alpha_max: f64,
    /// Lowest normal restitution `e_n` of a table with an `e_n` axis (with `e_n_max`; in
    /// [0.3, 1)): the table is then `P(γ, α, e_n)` of the law `solver.law`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub e_n_min: Option<f64>,
    /// Highest normal restitution `e_n` (with `e_n_min`; in (e_n_min, 1]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub e_n_max: Option<f64>,
    /// `gamma_min` as the file gives it (absent with `gamma`).
    #[serde(default, rename = "gamma_min", skip_serializing)]
    gamma_min_given: Option<f64>,
    /// `gamma_max` as the file gives it (absent with `gamma`).
    #[serde(default, rename = "gamma_max", skip_serializing)]
    gamma_max_given: Option<f64>,
}

impl Domain {
    /// The `e_n` range of a table with an `e_n` axis (`None`: elastic, `e_n = 1`).
    pub fn e_n_range(&self) -> Option<(f64, f64)> {
        Some((self.e_n_min?, self.e_n_max?))
    }

    /// The single γ of the table of one pair (`domain.gamma`), if it is one.
    pub fn pair_gamma(&self) -> Option<f64> {
        self.gamma
    }
}

/// `[nodes]`: how nodes are placed.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Nodes {
    /// Placement: "aligned" (patches bounded by α_c1, α_c2, α_max and γ = 1; the only placement
    /// of schemas v2 and v3).
    #[serde(default = "default_placement")]
    pub placement: String,
    /// Lagrange stencil points per axis: 4 (cubic) or 6 (quintic).
    #[serde(default = "default_stencil")]
    pub stencil: usize,
    /// Target maximum interpolation error of P; a quadtree cell is split into four until the
    /// predicted error of every leaf is below it.
    pub target_error: f64,
    /// Intervals per axis of every leaf's node grid: even, ≥ 2(stencil − 1) so that the half grid
    /// used to measure the error still holds a full stencil.
    #[serde(default = "default_leaf_intervals")]
    pub leaf_intervals: usize,
    /// Root cells per unit of γ along the γ axis of a patch.
    #[serde(default = "default_blocks_gamma")]
    pub blocks_per_unit_gamma: f64,
    /// Root cells along the patch coordinate.
    #[serde(default = "default_blocks_coord")]
    pub blocks_coord: usize,
    /// Root cells along `e_n` (a table with an `e_n` axis; default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blocks_e_n: Option<usize>,
    /// How the `e_n` axis maps to its coordinate: `"linear"` or `"quarter-root"` (`t = (1 −
    /// e_n)^{1/4}`, a table of Thornton's law: its `P` is smooth in `t`, not in `e_n`, next to
    /// `e_n = 1`; written as schema 5). Default: `"quarter-root"` for a Thornton table whose
    /// range reaches `e_n = 1`, `"linear"` otherwise ([`Config::e_n_map`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub e_n_coordinate: Option<String>,
    /// Refuse to place more nodes than this in total.
    #[serde(default = "default_max_nodes")]
    pub max_nodes: usize,
    /// Warp the partial-slip patch's coordinate so that the fold curve F₊ of `P` (γ > 2.904, a jump
    /// of slope) lies on a root-cell boundary, graded below it (schema v3). Traces F₊
    /// first (a few seconds); no effect when the partial-slip patch ends below γ ≈ 2.95.
    #[serde(default)]
    pub fold_warp: bool,
    /// Trace the kink curves of `P` whose leaves the quarter-surplus prediction cannot be trusted
    /// on (the fold F₋ of the partial-slip patch: a curve for γ ≥ 2.40 in an elastic table, a
    /// surface `α_F(γ, e_n)` in a Kelvin–Voigt table, which it needs from γ ≈ 2.37) and measure
    /// every leaf one crosses by direct simulations next to it before accepting it (not for
    /// Thornton's law).
    #[serde(default)]
    pub probe_kinks: bool,
    /// Put the kinks of `P` inside the partial-slip patch of a Thornton table on cell edges
    /// (the knots of the coordinate, `docs/table-format.md`): the end `α_c1` of the line, the
    /// re-slip fold `α_R`, the line `α = 2/7` and the switch fold `α_S`, traced on a grid of
    /// `(γ, e_n)` first (a few seconds), at `c'` = 1/2, 5/8, 3/4 and 7/8, for `e_n` up to
    /// 0.98 (where the folds merge towards `α = 2/7` as `e_n → 1`); and the loading fold `α_L`
    /// of its stick patch at `c'` = 1/2 of that patch where it lies above `α_c2`
    /// ([`crate::knots::loading_fold_knots`]).
    #[serde(default)]
    pub knots: bool,
    /// Tolerance (absolute error of `P`) to which the nodes that hold a leaf's bound up are
    /// solved again after the refinement: every node whose error estimate exceeds it, in a leaf
    /// whose bound `leaf_predicted_error + Λ^d · max error_estimate` exceeds
    /// `target_error + Λ^d · polish_tol` (`Λ^d` = 2.66, or 4.34 with an `e_n` axis). The
    /// stated bound is then at most `target_error + Λ^d · polish_tol` instead of
    /// `target_error + Λ^d · solver.tol`, for a few per cent of the nodes solved again
    /// (`docs/table-format.md`, "The stated error bound"). Below `solver.tol`; unset: no
    /// polishing.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polish_tol: Option<f64>,
    /// Let a split cell of a table without an `e_n` axis halve only the axes that need it
    /// (each axis whose own surplus, a quarter of it as the cell's error along that axis,
    /// exceeds the target, or else the axis with the largest), as the cells of a table with an
    /// `e_n` axis always do; the patches then store which axes each cell halved (`split`,
    /// `docs/table-format.md`). `false`: every split halves both axes (a quadtree).
    #[serde(default)]
    pub anisotropic: bool,
    /// Predict a cell's error from the rate at which its surplus fell from its parent's along
    /// each axis it halved (between 1/16 and 1/4 of the surplus along that axis; the parent's
    /// rate along the others, 1/4 at the roots), summed over the axes, instead of a quarter of
    /// its surplus everywhere (never more than that). Smooth `P` converges faster than the
    /// second order the quarter assumes; the kinks that do not are measured by
    /// `probe_kinks`, which this needs (`docs/table-format.md`, "The stated error bound").
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub observed_rate: bool,
}

fn default_placement() -> String {
    "aligned".into()
}
fn default_stencil() -> usize {
    4
}
fn default_leaf_intervals() -> usize {
    8
}
fn default_blocks_gamma() -> f64 {
    2.0
}
fn default_blocks_coord() -> usize {
    4
}
fn default_max_nodes() -> usize {
    200_000
}

/// `[solver]`: accuracy of every node: `tol`, or a named `preset` (`fast` = 1e-4,
/// `standard` = 1e-6, `reference` = 1e-8; `docs/accuracy.md`), not both.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(try_from = "RawSolver")]
pub struct Solver {
    /// Absolute error tolerance of P at each node (the solver's error estimate ≤ tol).
    pub tol: f64,
    /// The preset `tol` came from, if any.
    pub preset: Option<String>,
    /// The contact law of a table with an `e_n` axis: `kelvin-voigt` (the default there) or
    /// `thornton` (`γ ≥ 1` only); `elastic` (or absent) otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub law: Option<String>,
}

/// `[solver]` as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSolver {
    tol: Option<f64>,
    preset: Option<String>,
    law: Option<String>,
}

impl TryFrom<RawSolver> for Solver {
    type Error = String;

    fn try_from(raw: RawSolver) -> Result<Self, String> {
        if let Some(law) = &raw.law {
            oblique_solver::Law::from_name(law).map_err(|e| format!("solver.law: {e}"))?;
        }
        let law = raw.law;
        match (raw.tol, raw.preset) {
            (Some(tol), None) => Ok(Solver {
                tol,
                preset: None,
                law,
            }),
            (None, Some(name)) => {
                let p = oblique_solver::Preset::from_name(&name)
                    .map_err(|e| format!("solver.preset: {e}"))?;
                Ok(Solver {
                    tol: p.tolerance(),
                    preset: Some(p.name().to_string()),
                    law,
                })
            }
            (Some(_), Some(_)) => Err("give solver.tol or solver.preset, not both".to_string()),
            (None, None) => Err(
                "solver.tol (absolute error of P, e.g. 1e-6) or solver.preset \
                 (fast, standard or reference) is required"
                    .to_string(),
            ),
        }
    }
}

/// `[checks]`: held-out points, simulated but not used for interpolation.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Checks {
    /// Random check points per patch, 1 to 100000.
    #[serde(default = "default_checks")]
    pub per_patch: usize,
    /// Held-out points next to the critical curves (0 to 100000, default 0), in addition to
    /// the random ones: `α = α_k (1 ± r)` with `α_k` alternately `α_c1(γ, e_n)` and `α_c2(γ)`
    /// and `r` log-uniform in `[1e-4, 0.1]` ([`crate::near_curve_points`]), where `P` has its
    /// kinks and a random sample rarely lands.
    #[serde(default)]
    pub near_curves: usize,
    /// Seed of the deterministic generator that places them.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Solver tolerance of the check points (absolute error of P); default `solver.tol / 10`
    /// (loosened up to `solver.tol` where the pre-flight finds that out of reach), so that the
    /// measured interpolation error is that of the table, not of the check.
    #[serde(default)]
    pub tol: Option<f64>,
}

fn default_checks() -> usize {
    100
}
fn default_seed() -> u64 {
    1
}

impl Default for Checks {
    fn default() -> Self {
        Self {
            per_patch: default_checks(),
            near_curves: 0,
            seed: default_seed(),
            tol: None,
        }
    }
}

/// `[run]`: execution.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Run {
    /// Worker threads (0 = one per core).
    #[serde(default)]
    pub threads: usize,
}

/// A whole config file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// Output table path (relative to the working directory).
    pub output: PathBuf,
    /// Domain.
    pub domain: Domain,
    /// Node placement.
    pub nodes: Nodes,
    /// Node accuracy.
    pub solver: Solver,
    /// Held-out checks.
    #[serde(default)]
    pub checks: Checks,
    /// Execution.
    #[serde(default)]
    pub run: Run,
    /// The default of `checks.tol` as the pre-flight found it reachable
    /// (`crate::Preflight::check_tol`); not a key of the file.
    #[serde(skip)]
    pub derived_check_tol: Option<f64>,
}

impl Config {
    /// Parse and validate config text (`path` is used in messages).
    pub fn parse(text: &str, path: &str) -> Result<Self, ConfigError> {
        // toml's report spans several lines (the line of the file, a caret under the error):
        // kept as it is.
        let mut cfg: Config = toml::from_str(text).map_err(|e| ConfigError::Parse {
            path: path.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
        cfg.validate_pair(path)?;
        cfg.validate(path)?;
        Ok(cfg)
    }

    /// Read, parse and validate a config file.
    pub fn load(path: &Path) -> Result<(Self, String), ConfigError> {
        let p = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Read {
            path: p.clone(),
            source,
        })?;
        Ok((Self::parse(&text, &p)?, text))
    }

    /// Solver tolerance of the held-out checks: `checks.tol`; when it is not set, the value the
    /// pre-flight chose ([`Config::derived_check_tol`]), else `solver.tol / 10` (at least 1e-10).
    pub fn check_tol(&self) -> f64 {
        self.checks
            .tol
            .or(self.derived_check_tol)
            .unwrap_or((self.solver.tol / 10.0).max(1e-10))
    }

    /// The contact law of the node values: `solver.law`, else Kelvin–Voigt for a table with
    /// an `e_n` range and elastic without.
    pub fn law(&self) -> oblique_solver::Law {
        match &self.solver.law {
            Some(name) => {
                oblique_solver::Law::from_name(name).unwrap_or(oblique_solver::Law::Elastic)
            }
            None if self.domain.e_n_range().is_some() => oblique_solver::Law::KelvinVoigt,
            None => oblique_solver::Law::Elastic,
        }
    }

    /// The partial-slip coordinate's map of the table ([`PartialMap`]): the elastic one
    /// without an `e_n` range, [`PartialMap::Slip`] for Thornton's law (no closed-form
    /// full-slip line), [`PartialMap::SqrtBoth`] for Kelvin–Voigt.
    pub fn partial_map(&self) -> PartialMap {
        match (self.domain.e_n_range(), self.law()) {
            (None, _) => PartialMap::SqrtEnd,
            (Some(_), oblique_solver::Law::Thornton) => PartialMap::Slip,
            (Some(_), _) => PartialMap::SqrtBoth,
        }
    }

    /// Root cells along `e_n` (`nodes.blocks_e_n`, default 1).
    pub fn blocks_e_n(&self) -> usize {
        self.nodes.blocks_e_n.unwrap_or(1)
    }

    /// The map of the `e_n` axis (`nodes.e_n_coordinate`, checked by validation). By default
    /// [`AxisMap::QuarterRoot`] for a table of Thornton's law whose range reaches `e_n = 1`,
    /// where its `P` is smooth in `(1 − e_n)^{1/4}` and not in `e_n`; linear otherwise.
    pub fn e_n_map(&self) -> AxisMap {
        match self.nodes.e_n_coordinate.as_deref() {
            Some(E_N_QUARTER_ROOT) => AxisMap::QuarterRoot,
            Some(_) => AxisMap::Linear,
            None => match self.domain.e_n_range() {
                Some((_, hi)) if hi == 1.0 && self.law() == oblique_solver::Law::Thornton => {
                    AxisMap::QuarterRoot
                }
                _ => AxisMap::Linear,
            },
        }
    }

    /// `domain.gamma` (one pair) in place of `gamma_min` and `gamma_max`, which it then sets;
    /// without it both are required.
    fn validate_pair(&mut self, path: &str) -> Result<(), ConfigError> {
        let err = |key: &'static str, value: String, allowed: String| ConfigError::Range {
            path: path.to_string(),
            key,
            value,
            allowed,
        };
        let d = &mut self.domain;
        let given = [
            ("domain.gamma_min", d.gamma_min_given),
            ("domain.gamma_max", d.gamma_max_given),
        ];
        let Some(g) = d.gamma else {
            for (key, v) in given {
                if v.is_none() {
                    return Err(err(
                        key,
                        "missing".into(),
                        "a number: gamma_min and gamma_max give the range of gamma (or \
                         domain.gamma alone, the gamma of one pair of materials)"
                            .into(),
                    ));
                }
            }
            d.gamma_min = d.gamma_min_given.unwrap_or(f64::NAN);
            d.gamma_max = d.gamma_max_given.unwrap_or(f64::NAN);
            return Ok(());
        };
        for (key, v) in given {
            if let Some(v) = v {
                return Err(err(
                    key,
                    v.to_string(),
                    "absent with domain.gamma (the table of one pair has a single gamma)".into(),
                ));
            }
        }
        if !(g.is_finite() && g > 0.0 && g <= 64.0) {
            return Err(err("domain.gamma", g.to_string(), "in (0, 64]".into()));
        }
        if d.e_n_range().is_none() {
            return Err(err(
                "domain.gamma",
                g.to_string(),
                "with domain.e_n_min and e_n_max: the table of one pair is P(alpha, e_n); for an \
                 elastic pair read P(alpha) from a table over a range of gamma"
                    .into(),
            ));
        }
        (d.gamma_min, d.gamma_max) = (g, g);
        Ok(())
    }

    fn validate(&self, path: &str) -> Result<(), ConfigError> {
        let err = |key: &'static str, value: String, allowed: String| ConfigError::Range {
            path: path.to_string(),
            key,
            value,
            allowed,
        };
        let d = &self.domain;
        if !(d.gamma_min.is_finite() && d.gamma_min > 0.0) {
            return Err(err(
                "domain.gamma_min",
                d.gamma_min.to_string(),
                "a finite number > 0".into(),
            ));
        }
        let pair = d.gamma.is_some();
        if !(d.gamma_max.is_finite() && (d.gamma_max > d.gamma_min || pair) && d.gamma_max <= 64.0)
        {
            return Err(err(
                "domain.gamma_max",
                d.gamma_max.to_string(),
                format!("in (gamma_min = {}, 64]", d.gamma_min),
            ));
        }
        let c2 = 2.0 * d.gamma_max * d.gamma_max / 7.0;
        if d.alpha_max.is_nan() || d.alpha_max <= c2 {
            return Err(err(
                "domain.alpha_max",
                d.alpha_max.to_string(),
                format!("\"inf\" or a number > alpha_c2(gamma_max) = {c2}"),
            ));
        }
        match (d.e_n_min, d.e_n_max) {
            (None, None) => {}
            (Some(lo), Some(hi)) => {
                // The solver's range of e_n, less its elastic end.
                let min = oblique_solver::law::MIN_RESTITUTION;
                if !(oblique_solver::law::check_restitution(lo).is_ok() && lo < 1.0) {
                    return Err(err(
                        "domain.e_n_min",
                        lo.to_string(),
                        format!("in [{min}, 1)"),
                    ));
                }
                if !(hi > lo && hi <= 1.0) {
                    return Err(err(
                        "domain.e_n_max",
                        hi.to_string(),
                        format!("in (e_n_min = {lo}, 1]"),
                    ));
                }
            }
            (lo, _) => {
                let (key, other) = if lo.is_none() {
                    ("domain.e_n_min", "e_n_max")
                } else {
                    ("domain.e_n_max", "e_n_min")
                };
                return Err(err(
                    key,
                    "missing".into(),
                    format!("given with {other}: both or neither (an elastic table)"),
                ));
            }
        }
        let law = self.law();
        if law == oblique_solver::Law::Elastic && d.e_n_range().is_some() {
            return Err(err(
                "solver.law",
                "\"elastic\"".into(),
                "\"kelvin-voigt\" (or absent) for a table with an e_n range".into(),
            ));
        }
        if law != oblique_solver::Law::Elastic && d.e_n_range().is_none() {
            return Err(err(
                "solver.law",
                format!("\"{}\"", law.name()),
                "\"elastic\" (or absent) without domain.e_n_min and e_n_max".into(),
            ));
        }
        // The laws whose tables the format holds (oblique_table::format::LAWS_E_N).
        if d.e_n_range().is_some() && !oblique_table::format::LAWS_E_N.contains(&law.name()) {
            return Err(err(
                "solver.law",
                format!("\"{}\"", law.name()),
                format!(
                    "{} for a table with an e_n range",
                    oblique_table::format::LAWS_E_N
                        .iter()
                        .map(|l| format!("\"{l}\""))
                        .collect::<Vec<_>>()
                        .join(" or ")
                ),
            ));
        }
        if law == oblique_solver::Law::Thornton {
            // Its table has no closed-form full-slip line: the partial-slip patch covers
            // 0 <= alpha <= alpha_c2 for gamma >= 1 (PartialMap::Slip); the side gamma < 1 and
            // the table of one pair are not designed for it yet.
            if pair {
                return Err(err(
                    "domain.gamma",
                    d.gamma_min.to_string(),
                    "absent for the thornton law: give domain.gamma_min and gamma_max (the \
                     table of one pair is not built for this law yet)"
                        .into(),
                ));
            }
            if d.gamma_min < 1.0 {
                return Err(err(
                    "domain.gamma_min",
                    d.gamma_min.to_string(),
                    format!(
                        "in [1, gamma_max = {}) for the thornton law (its table below gamma = 1 \
                         is not designed yet)",
                        d.gamma_max
                    ),
                ));
            }
            // alpha_c1 is the root-cell boundary c = 1/2 of the partial-slip patch.
            if !self.nodes.blocks_coord.is_multiple_of(2) {
                return Err(err(
                    "nodes.blocks_coord",
                    self.nodes.blocks_coord.to_string(),
                    "an even number in [2, 1024] for the thornton law (alpha_c1 is the root-cell \
                     boundary c = 1/2)"
                        .into(),
                ));
            }
        }
        let n = &self.nodes;
        if let Some(b) = n.blocks_e_n {
            if d.e_n_range().is_none() || !(1..=64).contains(&b) {
                return Err(err(
                    "nodes.blocks_e_n",
                    b.to_string(),
                    "in [1, 64], with domain.e_n_min and e_n_max".into(),
                ));
            }
        }
        if let Some(map) = &n.e_n_coordinate {
            let known = [E_N_LINEAR, E_N_QUARTER_ROOT].contains(&map.as_str());
            if !known || d.e_n_range().is_none() {
                return Err(err(
                    "nodes.e_n_coordinate",
                    format!("\"{map}\""),
                    format!(
                        "\"{E_N_LINEAR}\" or \"{E_N_QUARTER_ROOT}\" (solver.law = \"thornton\"), \
                         with domain.e_n_min and e_n_max"
                    ),
                ));
            }
            if map == E_N_QUARTER_ROOT && law != oblique_solver::Law::Thornton {
                return Err(err(
                    "nodes.e_n_coordinate",
                    format!("\"{map}\""),
                    format!(
                        "\"{E_N_LINEAR}\" for the law '{}' (\"{E_N_QUARTER_ROOT}\" is for \
                         solver.law = \"thornton\")",
                        law.name()
                    ),
                ));
            }
        }
        if d.e_n_range().is_some() && n.fold_warp {
            return Err(err(
                "nodes.fold_warp",
                "true".into(),
                "false for a table with an e_n range".into(),
            ));
        }
        let knotted_law = matches!(
            law,
            oblique_solver::Law::Thornton | oblique_solver::Law::KelvinVoigt
        );
        if n.knots && (!knotted_law || pair || d.e_n_range().is_none()) {
            return Err(err(
                "nodes.knots",
                "true".into(),
                "false unless the table has an e_n range over a range of gamma, of the \
                 thornton or kelvin-voigt law (the knots follow the kinks of those laws)"
                    .into(),
            ));
        }
        if d.e_n_range().is_some() && n.probe_kinks && !crate::kink::probes_implemented(law) {
            return Err(err(
                "nodes.probe_kinks",
                "true".into(),
                format!(
                    "false for a table of the {} law: no kink of its surface is traced for the \
                     probes yet (nodes.probe_kinks traces the fold F- and the end-of-contact \
                     curve E- of the elastic and kelvin-voigt laws)",
                    law.name()
                ),
            ));
        }
        if n.observed_rate && !n.probe_kinks {
            return Err(err(
                "nodes.observed_rate",
                "true".into(),
                "false unless nodes.probe_kinks = true (a leaf that a kink of P crosses converges \
                 at second order whatever its surplus fell by, and must be measured next to it)"
                    .into(),
            ));
        }
        if let Some((lo, hi)) = d.e_n_range() {
            // Next to the fold curve F₋ the leaves' predictions miss how P leaves its smooth
            // continuation (docs/accuracy.md, "Tables with an e_n axis"): a table that reaches
            // it must measure those leaves (nodes.probe_kinks) or put F₋ on a cell edge
            // (nodes.knots, the Kelvin–Voigt law over a range of γ), else its bound would not
            // hold. Damping moves F₋'s birth to larger γ, plasticity to smaller γ.
            let thornton = law == oblique_solver::Law::Thornton;
            let free = if thornton {
                oblique_solver::history::fold_minus_free_below_thornton(lo)
            } else {
                oblique_solver::history::fold_minus_free_below(hi)
            };
            let aligned = n.knots && law == oblique_solver::Law::KelvinVoigt && !pair;
            if d.gamma_max >= free && !n.probe_kinks && !aligned {
                let field = if pair {
                    "domain.gamma"
                } else {
                    "domain.gamma_max"
                };
                let why = if thornton {
                    format!(
                        "< {free} with e_n_min = {lo} and nodes.probe_kinks false: from there on \
                         P has the fold F- (under the thornton law born at gamma 1.87 for e_n = \
                         0.3, later for higher e_n, 2.37 for e_n = 1), next to which a table \
                         does not hold its stated bound unless it measures the leaves there; set \
                         nodes.probe_kinks = true (its leaves are then measured next to F-), or \
                         lower it or raise e_n_min"
                    )
                } else {
                    // An e_n range: the Kelvin–Voigt law.
                    format!(
                        "< {free} with e_n_max = {hi}, nodes.probe_kinks and nodes.knots false: \
                         from there on P has the fold curve F- (born at gamma 2.37 for e_n = 1, \
                         later for lower e_n, none up to 3.6 for e_n <= 0.8), next to which a \
                         table with an e_n range does not hold its stated bound unless it \
                         measures the leaves there; set nodes.probe_kinks = true (its leaves are \
                         then measured next to F-) or, over a range of gamma, nodes.knots = true \
                         (F- on a cell edge), or lower it or e_n_max"
                    )
                };
                return Err(err(field, d.gamma_max.to_string(), why));
            }
        }
        if n.placement != "aligned" {
            return Err(err(
                "nodes.placement",
                format!("\"{}\"", n.placement),
                "\"aligned\"".into(),
            ));
        }
        if n.stencil != 4 && n.stencil != 6 {
            return Err(err("nodes.stencil", n.stencil.to_string(), "4 or 6".into()));
        }
        if !(n.target_error.is_finite() && n.target_error > 0.0 && n.target_error < 0.1) {
            return Err(err(
                "nodes.target_error",
                n.target_error.to_string(),
                "in (0, 0.1)".into(),
            ));
        }
        let min_leaf = 2 * (n.stencil - 1);
        if n.leaf_intervals < min_leaf
            || n.leaf_intervals > 64
            || !n.leaf_intervals.is_multiple_of(2)
        {
            return Err(err(
                "nodes.leaf_intervals",
                n.leaf_intervals.to_string(),
                format!("an even number in [2(stencil - 1) = {min_leaf}, 64]"),
            ));
        }
        if !(n.blocks_per_unit_gamma.is_finite()
            && n.blocks_per_unit_gamma >= 0.1
            && n.blocks_per_unit_gamma <= 1024.0)
        {
            return Err(err(
                "nodes.blocks_per_unit_gamma",
                n.blocks_per_unit_gamma.to_string(),
                "in [0.1, 1024]".into(),
            ));
        }
        if n.blocks_coord == 0 || n.blocks_coord > 1024 {
            return Err(err(
                "nodes.blocks_coord",
                n.blocks_coord.to_string(),
                "in [1, 1024]".into(),
            ));
        }
        if n.max_nodes < 100 {
            return Err(err(
                "nodes.max_nodes",
                n.max_nodes.to_string(),
                ">= 100".into(),
            ));
        }
        let s = &self.solver;
        if !(s.tol.is_finite() && s.tol >= 1e-10 && s.tol < 0.01) {
            return Err(err(
                "solver.tol",
                s.tol.to_string(),
                "in [1e-10, 0.01)".into(),
            ));
        }
        if s.tol > n.target_error {
            return Err(err(
                "solver.tol",
                s.tol.to_string(),
                format!("<= nodes.target_error = {} (nodes must be more accurate than the interpolation)", n.target_error),
            ));
        }
        if let Some(t) = n.polish_tol {
            if !(t.is_finite() && t >= 1e-10 && t < s.tol) {
                return Err(err(
                    "nodes.polish_tol",
                    t.to_string(),
                    format!(
                        "in [1e-10, solver.tol = {}) (the nodes are solved again more accurately)",
                        s.tol
                    ),
                ));
            }
        }
        if let Some(t) = self.checks.tol {
            if !(t.is_finite() && t >= 1e-10 && t <= s.tol) {
                return Err(err(
                    "checks.tol",
                    t.to_string(),
                    format!("in [1e-10, solver.tol = {}]", s.tol),
                ));
            }
        }
        // The held-out checks are what a table's stated error rests on: at least one per patch.
        if self.checks.per_patch == 0 || self.checks.per_patch > 100_000 {
            return Err(err(
                "checks.per_patch",
                self.checks.per_patch.to_string(),
                "in [1, 100000] (the held-out checks measure the table's error)".into(),
            ));
        }
        if self.checks.near_curves > 100_000 {
            return Err(err(
                "checks.near_curves",
                self.checks.near_curves.to_string(),
                "in [0, 100000]".into(),
            ));
        }
        if self.run.threads > 1024 {
            return Err(err(
                "run.threads",
                self.run.threads.to_string(),
                "in [0, 1024] (0 = one per core)".into(),
            ));
        }
        if self.output.as_os_str().is_empty() {
            return Err(err("output", "\"\"".into(), "a file path".into()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
output = "t.h5"
[domain]
gamma_min = 0.1
gamma_max = 3.5
alpha_max = "inf"
[nodes]
target_error = 1e-5
[solver]
tol = 1e-6
"#;

    #[test]
    fn parses_good_config_with_defaults() {
        let c = Config::parse(GOOD, "x.toml").expect("valid");
        assert!(c.domain.alpha_max.is_infinite());
        assert_eq!(c.nodes.stencil, 4);
        assert_eq!(c.run.threads, 0);
    }

    #[test]
    fn rejects_unknown_key_naming_it() {
        let bad = GOOD.replace("tol = 1e-6", "tol = 1e-6\ntolerance = 2");
        let e = Config::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(e.contains("tolerance"), "{e}");
    }

    #[test]
    fn rejects_out_of_range_naming_key_and_range() {
        let bad = GOOD.replace("gamma_min = 0.1", "gamma_min = -1");
        let e = Config::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(e.contains("domain.gamma_min") && e.contains("> 0"), "{e}");
        let bad = GOOD.replace("gamma_max = 3.5", "gamma_max = 0.05");
        let e = Config::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(e.contains("domain.gamma_max"), "{e}");
        let bad = GOOD.replace("tol = 1e-6", "tol = nan");
        let e = Config::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(e.contains("solver.tol"), "{e}");
        let bad = GOOD.replace("alpha_max = \"inf\"", "alpha_max = 0.5");
        let e = Config::parse(&bad, "x.toml").unwrap_err().to_string();
        assert!(e.contains("domain.alpha_max"), "{e}");
    }

    #[test]
    fn solver_preset_sets_the_tolerance_and_excludes_tol() {
        let fast = GOOD
            .replace("tol = 1e-6", "preset = \"fast\"")
            .replace("target_error = 1e-5", "target_error = 1e-3");
        let c = Config::parse(&fast, "x.toml").expect("preset fast");
        assert_eq!(
            (c.solver.tol, c.solver.preset.as_deref()),
            (1e-4, Some("fast"))
        );
        let c = Config::parse(
            &GOOD.replace("tol = 1e-6", "preset = \"standard\""),
            "x.toml",
        )
        .expect("preset standard");
        assert_eq!(c.solver.tol, 1e-6);
        for (text, needle) in [
            ("preset = \"quick\"", "solver.preset"),
            ("tol = 1e-6\npreset = \"fast\"", "not both"),
            ("", "is required"),
        ] {
            let e = Config::parse(&GOOD.replace("tol = 1e-6", text), "x.toml")
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }

    #[test]
    fn a_thornton_range_stops_below_its_fold_f_minus_unless_probed() {
        let with = |gamma: &str, e_n: &str, probe: bool| {
            let text = GOOD
                .replace("gamma_min = 0.1\ngamma_max = 3.5", gamma)
                .replace(
                    "alpha_max = \"inf\"",
                    &format!("alpha_max = \"inf\"\n{e_n}"),
                )
                .replace("tol = 1e-6", "tol = 1e-6\nlaw = \"thornton\"")
                .replace(
                    "target_error = 1e-5",
                    &format!("target_error = 1e-5\nprobe_kinks = {probe}"),
                );
            Config::parse(&text, "x.toml").map_err(|e| e.to_string())
        };
        // Plasticity brings F₋ to lower γ the lower e_n: born at γ 1.873 for e_n 0.3, 2.165
        // for 0.8 (less the margin 0.02 of the search).
        let low = "e_n_min = 0.3\ne_n_max = 1.0";
        assert!(with("gamma_min = 1.0\ngamma_max = 1.85", low, false).is_ok());
        let e = with("gamma_min = 1.0\ngamma_max = 1.9", low, false).unwrap_err();
        assert!(
            e.contains("domain.gamma_max")
                && e.contains("< 1.8529")
                && e.contains("e_n_min = 0.3")
                && e.contains("set nodes.probe_kinks = true"),
            "{e}"
        );
        let high = "e_n_min = 0.8\ne_n_max = 1.0";
        assert!(with("gamma_min = 1.0\ngamma_max = 2.1", high, false).is_ok());
        assert!(with("gamma_min = 1.0\ngamma_max = 2.2", high, false).is_err());
        // With its leaves measured next to F₋ the range is taken.
        assert!(with("gamma_min = 1.0\ngamma_max = 2.6", low, true).is_ok());
    }

    #[test]
    fn an_e_n_range_stops_below_the_fold_curve_f_minus_unless_probed() {
        let with = |gamma: &str, e_n: &str| {
            let text = GOOD
                .replace("gamma_min = 0.1\ngamma_max = 3.5", gamma)
                .replace(
                    "alpha_max = \"inf\"",
                    &format!("alpha_max = \"inf\"\n{e_n}"),
                )
                .replace("tol = 1e-6", "tol = 1e-6\nlaw = \"kelvin-voigt\"");
            Config::parse(&text, "x.toml").map_err(|e| e.to_string())
        };
        let near_one = "e_n_min = 0.5\ne_n_max = 1.0";
        assert!(with("gamma_min = 1.0\ngamma_max = 2.3", near_one).is_ok());
        // F₋ is born at γ ≈ 2.37 for e_n = 1.
        let e = with("gamma_min = 1.0\ngamma_max = 2.6", near_one).unwrap_err();
        assert!(
            e.contains("domain.gamma_max") && e.contains("< 2.3666") && e.contains("F-"),
            "{e}"
        );
        // For e_n <= 0.8 none up to γ = 3.6; at 0.95 from γ ≈ 2.55.
        assert!(with(
            "gamma_min = 1.0\ngamma_max = 2.6",
            "e_n_min = 0.3\ne_n_max = 0.8"
        )
        .is_ok());
        assert!(with(
            "gamma_min = 1.0\ngamma_max = 2.5",
            "e_n_min = 0.3\ne_n_max = 0.95"
        )
        .is_ok());
        assert!(with(
            "gamma_min = 1.0\ngamma_max = 2.6",
            "e_n_min = 0.3\ne_n_max = 0.95"
        )
        .is_err());
        // The table of one pair names its single gamma.
        let e = with("gamma = 2.5", near_one).unwrap_err();
        assert!(e.contains("`domain.gamma` = 2.5"), "{e}");
        assert!(!e.contains("domain.gamma_max"), "{e}");
        assert!(e.contains("set nodes.probe_kinks = true"), "{e}");
        // With its leaves measured next to F₋ the range is taken.
        let probed = |gamma: &str| {
            with(gamma, near_one).or_else(|_| {
                let text = GOOD
                    .replace("gamma_min = 0.1\ngamma_max = 3.5", gamma)
                    .replace(
                        "alpha_max = \"inf\"",
                        &format!("alpha_max = \"inf\"\n{near_one}"),
                    )
                    .replace(
                        "target_error = 1e-5",
                        "target_error = 1e-5\nprobe_kinks = true",
                    );
                Config::parse(&text, "x.toml").map_err(|e| e.to_string())
            })
        };
        assert!(probed("gamma_min = 1.0\ngamma_max = 2.6").is_ok());
        assert!(probed("gamma = 2.5").is_ok());
        // With F₋ on a cell edge (the knots) too, over a range of γ; not for one pair.
        let knotted = |gamma: &str| {
            let text = GOOD
                .replace("gamma_min = 0.1\ngamma_max = 3.5", gamma)
                .replace(
                    "alpha_max = \"inf\"",
                    &format!("alpha_max = \"inf\"\n{near_one}"),
                )
                .replace("target_error = 1e-5", "target_error = 1e-5\nknots = true")
                .replace("tol = 1e-6", "tol = 1e-6\nlaw = \"kelvin-voigt\"");
            Config::parse(&text, "x.toml").map_err(|e| e.to_string())
        };
        assert!(knotted("gamma_min = 1.0\ngamma_max = 2.6").is_ok());
        assert!(knotted("gamma = 2.5").is_err());
    }

    #[test]
    fn kink_probes_are_taken_for_every_law_of_a_table() {
        let probe = GOOD.replace(
            "target_error = 1e-5",
            "target_error = 1e-5\nprobe_kinks = true",
        );
        assert!(
            Config::parse(&probe, "x.toml")
                .expect("elastic")
                .nodes
                .probe_kinks
        );
        let dissipative = probe
            .replace(
                "gamma_min = 0.1\ngamma_max = 3.5",
                "gamma_min = 1.0\ngamma_max = 2.6",
            )
            .replace(
                "alpha_max = \"inf\"",
                "alpha_max = \"inf\"\ne_n_min = 0.5\ne_n_max = 1.0",
            );
        // The Kelvin–Voigt law (the default with an e_n range): F₋ is traced as a surface.
        let c = Config::parse(&dissipative, "x.toml").expect("kelvin-voigt");
        assert_eq!(c.law(), oblique_solver::Law::KelvinVoigt);
        // Thornton's law: its F₋ is traced as a surface too, whatever γ.
        for g in ["2.6", "2.0"] {
            let thornton = dissipative
                .replace("gamma_max = 2.6", &format!("gamma_max = {g}"))
                .replace("tol = 1e-6", "tol = 1e-6\nlaw = \"thornton\"");
            let c = Config::parse(&thornton, "x.toml").expect("thornton");
            assert!(c.nodes.probe_kinks && crate::kink::probes_implemented(c.law()));
        }
    }

    #[test]
    fn the_observed_rate_needs_the_probes() {
        let with = |keys: &str| {
            let text = GOOD.replace(
                "target_error = 1e-5",
                &format!("target_error = 1e-5\n{keys}"),
            );
            Config::parse(&text, "x.toml").map_err(|e| e.to_string())
        };
        let e = with("observed_rate = true").unwrap_err();
        assert!(
            e.contains("nodes.observed_rate") && e.contains("nodes.probe_kinks = true"),
            "{e}"
        );
        let cfg = with("observed_rate = true\nprobe_kinks = true").unwrap();
        assert!(cfg.nodes.observed_rate);
        assert!(!with("").unwrap().nodes.observed_rate);
    }
}
