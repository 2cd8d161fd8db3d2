//! The simulator: one oblique elastic impact with Coulomb friction by the method of
//! dimensionality reduction (MDR), with error control. Pure: no I/O, no files, no terminal.
//! The closed forms it shares with the table and the lookup are in `oblique-physics`.
//!
//! Symbols follow `physics.md`: `γ = √((7/2) G*/E*)` (generally `γ² = (m*/m_t) G*/E*`),
//! `α = μ v_z0 / |u0|` (generally `α = (2/7)(m*/m_t) μ v_z0/|u0|`), `P = u_after/u_before`.

pub mod continuum;
pub mod elastic;
pub mod error;
pub mod hertz;
pub mod history;
pub mod impact;
pub mod kelvin_voigt;
pub mod law;
pub mod model;
pub mod preset;
pub mod refine;
pub mod registry;
pub mod request;
pub mod resolution;
pub mod springs;
pub mod thornton;
pub mod thornton_mdr;
pub mod units;
pub mod zones;

pub use error::PhysicsError;
pub use impact::{Resolution, Scheme};
pub use law::{ContactLaw, PARAMETER_KEYS};
pub use model::{ExplicitEuler, Integrator, NormalModel, TangentialModel, VelocityVerlet};
pub use preset::Preset;
pub use refine::{Accuracy, Method, NoEstimate, RefineEvent, Solution};
pub use registry::{BodiesLaw, Law, LawParameters};
pub use request::{KeptLevels, Request};
