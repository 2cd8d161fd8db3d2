//! The closed-form physics of an oblique elastic impact with Coulomb friction, shared by the
//! simulator (`oblique-solver`), the table format (`oblique-table`) and the lookup
//! (`oblique-lookup`): the critical values of the friction group, the friction regimes and the
//! exact parts of `P(γ, α)` ([`regimes`]); bodies, materials and the rebound algebra from `P`
//! to the post-impact state ([`rebound`]); the material catalogue with its sources
//! ([`materials`]). Pure: no I/O.
//!
//! Symbols follow `physics.md`: `γ = √((7/2) G*/E*)` (generally `γ² = (m*/m_t) G*/E*`),
//! `α = μ v_z0 / |u0|` (generally `α = (2/7)(m*/m_t) μ v_z0/|u0|`), `P = u_after/u_before`,
//! `α_c1 = 2γ²/(7(2γ² − 1))`, `α_c2 = 2γ²/7`.

pub mod materials;
pub mod rebound;
pub mod regimes;
pub mod sample;
pub mod vec3;

pub use rebound::{effective_moduli, Body, Elastic, InvalidInput, Pair};
pub use regimes::{alpha_c1, alpha_c2, linear_limit, Regime};
