//! The scene file (TOML): bodies, friction and the impact conditions to sweep.
//!
//! See `docs/scenes.md` for every key. Parsing is strict: unknown keys are refused, and every
//! value is checked with an error naming the key and its allowed range.
//!
//! The keys as written are read in `spec/file.rs`, checked in `spec/validate.rs`; this file
//! holds what a valid scene is.

mod file;
mod validate;

use std::path::{Path, PathBuf};

use oblique_lookup::rebound::{Body, Elastic, Incident, Pair, State};
use oblique_solver::Law;

use super::materials::CatalogueMaterial;
use super::SceneError;
use file::SceneFile;
pub use file::Values;
use validate::Validator;

/// Default solver tolerance of `P` (absolute) when the scene gives none.
pub const DEFAULT_TOL: f64 = 1e-6;
/// Most cases one scene may ask for.
pub const MAX_CASES: usize = 100_000;

/// Largest speed a scene may give (m/s): every velocity component of either body, the speed of
/// an `angles` sweep, and the contact-point speed `|ω| R` of a spin. Far above elastic impacts
/// (metals yield at a few m/s), and small enough that every momentum and energy is finite.
pub const MAX_SPEED: f64 = 1e3;
/// Smallest relative normal approach speed of a case (m/s).
pub const MIN_APPROACH_SPEED: f64 = 1e-6;
/// Range of Young's modulus (Pa): soft gels to beyond diamond (1.2e12 Pa); `inf` (rigid) is
/// allowed for a wall.
pub const YOUNGS_MODULUS_RANGE: (f64, f64) = (1e3, 1e13);
/// Range of a radius (m): 1 nm to 1 km.
pub const RADIUS_RANGE: (f64, f64) = (1e-9, 1e3);
/// Range of a density (kg/m³): below aerogels to above osmium (22 590).
pub const DENSITY_RANGE: (f64, f64) = (1.0, 1e5);
/// Range of a mass, given or computed from density and volume (kg).
pub const MASS_RANGE: (f64, f64) = (1e-30, 1e20);

/// A material as resolved for one body.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialUse {
    /// Elastic constants used.
    pub elastic: Elastic,
    /// Catalogue entry the values started from, if any.
    pub catalogue: Option<&'static CatalogueMaterial>,
    /// Which catalogue values the scene overrode (`youngs_modulus`, `poisson_ratio`, `density`).
    pub overridden: Vec<&'static str>,
}

impl MaterialUse {
    /// Short description: `alumina-96`, `alumina-96 (density overridden)` or
    /// `E = 200 GPa, nu = 0.3`.
    pub fn describe(&self) -> String {
        match self.catalogue {
            Some(c) if self.overridden.is_empty() => c.name.to_string(),
            Some(c) => format!("{} ({} overridden)", c.name, self.overridden.join(", ")),
            None => format!(
                "E = {} GPa, nu = {}",
                self.elastic.youngs_modulus / 1e9,
                self.elastic.poisson_ratio
            ),
        }
    }
}

/// What sphere 1 hits.
#[derive(Debug, Clone, PartialEq)]
pub enum SceneTarget {
    /// A fixed flat wall (half-space).
    Wall {
        /// Its material.
        material: MaterialUse,
    },
    /// A free second sphere.
    Sphere {
        /// Mass, radius, κ.
        body: Body,
        /// Its material.
        material: MaterialUse,
        /// Its incident motion (the same for every case).
        motion: State,
    },
}

/// The quantity a scene sweeps (the three oblique-impact benchmark tests of DEM codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CaseKind {
    /// Fixed speed, incidence angle from the normal swept.
    Angles,
    /// Fixed normal speed, tangential speed swept.
    TangentialSpeed,
    /// Fixed normal (and tangential) speed, initial spin swept.
    Spin,
}

impl CaseKind {
    /// Name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            CaseKind::Angles => "angles",
            CaseKind::TangentialSpeed => "tangential-speed",
            CaseKind::Spin => "spin",
        }
    }

    /// Column of the swept quantity in CSV files (also the measured file's first column).
    pub fn x_column(self) -> &'static str {
        match self {
            CaseKind::Angles => "angle_deg",
            CaseKind::TangentialSpeed => "v_x0",
            CaseKind::Spin => "omega0",
        }
    }

    /// Axis label of the swept quantity, with symbol and unit.
    pub fn x_label(self) -> &'static str {
        match self {
            CaseKind::Angles => "incidence angle θ from the normal (°)",
            CaseKind::TangentialSpeed => "incident tangential velocity v_x0 (m/s)",
            CaseKind::Spin => "initial spin ω0 (rad/s)",
        }
    }
}

/// The swept impact conditions of sphere 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Cases {
    /// What is swept.
    pub kind: CaseKind,
    /// The swept values, in scene order (degrees, m/s or rad/s).
    pub values: Vec<f64>,
    /// `angles`: the speed `|v|` (m/s); otherwise the normal speed `v_z0` (m/s).
    pub speed: f64,
    /// Tangential speed `v_x0` (m/s) when not swept.
    pub tangential_speed: f64,
    /// Initial spin `ω0` (rad/s) when not swept.
    pub omega0: f64,
}

impl Cases {
    /// Sphere 1's incident state at swept value `x`.
    pub fn sphere_state(&self, x: f64) -> State {
        match self.kind {
            CaseKind::Angles => {
                let t = x.to_radians();
                State {
                    v_x: self.speed * t.sin(),
                    v_z: self.speed * t.cos(),
                    omega: self.omega0,
                }
            }
            CaseKind::TangentialSpeed => State {
                v_x: x,
                v_z: self.speed,
                omega: self.omega0,
            },
            CaseKind::Spin => State {
                v_x: self.tangential_speed,
                v_z: self.speed,
                omega: x,
            },
        }
    }
}

/// The measured data a scene names.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredRef {
    /// CSV path (resolved against the scene file's folder).
    pub file: PathBuf,
    /// Citation of the data.
    pub source: String,
}

/// How the bodies dissipate in the normal direction (`physics.md`, "Dissipative impacts").
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dissipation {
    /// Elastic bodies: `e_n = 1` (no `e_n`, `relaxation_time` or `yield_pressure` in the scene
    /// file).
    Elastic,
    /// A normal restitution `e_n` (Kelvin–Voigt law; `e_n = 1` is elastic), the same for every
    /// case.
    Restitution(f64),
    /// The relaxation time `τ` (s) of the Kelvin–Voigt law: each case's `e_n` follows from its
    /// impact speed (`oblique_solver::units::PhysicalImpact::restitution`), so it varies along
    /// the sweep.
    RelaxationTime(f64),
    /// The limiting contact pressure `p_y` (Pa) of Thornton's elastic–perfectly plastic law
    /// (`physics.md`, "Elastic–plastic impacts"): each case is elastic (`e_n = 1`) up to the
    /// yield speed `V_y` at which the Hertz peak pressure reaches `p_y`, and above it its `e_n`
    /// is Thornton's closed form of `V_y/v_z0` (`oblique_solver::thornton::restitution`).
    YieldPressure(f64),
}

impl Dissipation {
    /// Whether the scene names a dissipation (`e_n`, `relaxation_time` or `yield_pressure`):
    /// its CSV then has the `e_n` and `law` columns.
    pub fn is_named(self) -> bool {
        !matches!(self, Dissipation::Elastic)
    }

    /// The contact law of a case of normal restitution `e_n`: Thornton's for every case of
    /// a scene with a limiting pressure (its bodies' law, even below the yield speed where the
    /// impact is elastic), otherwise elastic at `e_n = 1` and Kelvin–Voigt below.
    pub fn law(self, e_n: f64) -> Law {
        match self {
            Dissipation::YieldPressure(_) => Law::Thornton,
            _ => Law::for_restitution(e_n),
        }
    }
}

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name (output file stem): `[A-Za-z0-9_.-]+`.
    pub name: String,
    /// Free text.
    pub description: String,
    /// Scene file it was read from (for captions and messages).
    pub path: PathBuf,
    /// Coulomb friction coefficient `μ` (`∞`: no slip).
    pub friction: f64,
    /// Solver tolerance of `P` when simulating (absolute).
    pub tol: f64,
    /// Normal dissipation: elastic, a constant `e_n`, a Kelvin–Voigt relaxation time, or
    /// Thornton's limiting pressure.
    pub dissipation: Dissipation,
    /// Sphere 1: mass, radius, κ.
    pub sphere: Body,
    /// Sphere 1's material.
    pub sphere_material: MaterialUse,
    /// Wall or sphere 2.
    pub target: SceneTarget,
    /// The cases.
    pub cases: Cases,
    /// Measured data, if named.
    pub measured: Option<MeasuredRef>,
}

impl Scene {
    /// The rigid-body data of the pair.
    pub fn pair(&self) -> Pair {
        Pair {
            sphere: self.sphere,
            other: match &self.target {
                SceneTarget::Wall { .. } => None,
                SceneTarget::Sphere { body, .. } => Some(*body),
            },
        }
    }

    /// The target's material.
    pub fn target_material(&self) -> &MaterialUse {
        match &self.target {
            SceneTarget::Wall { material } | SceneTarget::Sphere { material, .. } => material,
        }
    }

    /// The incident state of both bodies at swept value `x`.
    pub fn incident(&self, x: f64) -> Incident {
        Incident {
            sphere: self.cases.sphere_state(x),
            other: match &self.target {
                SceneTarget::Wall { .. } => State::default(),
                SceneTarget::Sphere { motion, .. } => *motion,
            },
        }
    }

    /// Read and validate a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Scene::parse(&text, path)
    }

    /// Parse and validate scene text; `path` names it in messages, gives the default name and
    /// the folder that a measured-data file is relative to.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let shown = path.display().to_string();
        let file: SceneFile = toml::from_str(text).map_err(|e| SceneError::Parse {
            path: shown.clone(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let v = Validator { path: &shown };
        v.build(file, path)
    }
}
