//! The elastic law (`e_n = 1`, the model of `physics.md`): Hertz normal contact and
//! Cattaneo–Mindlin tangential contact by the MDR, with perfectly elastic springs. Its models
//! ([`models`]) are the Hertz trajectory ([`crate::hertz::NormalTrajectory`]) and the two
//! tangential rows ([`crate::continuum::ContinuumRow`], [`crate::springs::SpringRow`]), which
//! the Kelvin–Voigt law ([`crate::kelvin_voigt`]) builds on and so stay in the crate's root.

pub mod models;
