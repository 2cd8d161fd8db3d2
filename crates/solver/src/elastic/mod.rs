//! The elastic law (`e_n = 1`, the model of `physics.md`): Hertz normal contact and
//! Cattaneo–Mindlin tangential contact by the MDR, with perfectly elastic springs. Its models
//! ([`models`]) are the Hertz trajectory ([`crate::hertz::NormalTrajectory`]) and the two
//! tangential rows ([`crate::continuum::ContinuumRow`], [`crate::springs::SpringRow`]), which
//! the Kelvin–Voigt law ([`crate::kelvin_voigt`]) builds on and so stay in the crate's root.

pub mod models;

use oblique_physics::regimes;
use serde::Serialize;

use crate::error::PhysicsError;
use crate::hertz::NormalBodies;
use crate::impact::{check_alpha, check_gamma, run_contact, simulate_elastic};
use crate::impact::{Scheme, TangentialBodies};
use crate::law::{BodiesNormal, ContactLaw, Floor, NormalSummary, PARAMETER_KEYS};
use crate::resolution::Resolution;
use crate::zones::Level;

/// The share of the last raw difference `|P_k − P_{k−1}|` below which the Richardson estimate
/// of the elastic law never falls (`refine::extrapolate`); the default of
/// [`crate::refine::refine`].
pub const RAW_FLOOR: f64 = 0.1;

/// The share where the differences do not yet shrink regularly (a sign change or a ratio
/// outside `[3, 5.5]`). At γ = 1.754, α = 1, tol 1e-4, the differences of 32 → 256 steps turn
/// (ratios −6.3, 4.13) and the Richardson value erred by 1.50e-6 = 0.13 |d| (the next ratio,
/// 6.1, is fast), above the 0.1 |d| = 1.15e-6 it stated; 0.2 states 2.3e-6. Measured cost over
/// the 159 points of `ladder -- 150 7 11` at tol 1e-4 to 1e-8: under 2 % more steps.
pub const IRREGULAR_FLOOR: f64 = 0.2;

/// The share where the convergence is steady (three ratios of successive differences within
/// 3.8–4.2): [`RAW_FLOOR`], no less. Over the ladders of 159 random points
/// (`ladder -- 150 7 10`) the 331 steady levels needed at most 0.0042 of the last difference
/// beyond the difference of the Richardson values, but in the stick patch at γ = 2.14,
/// α = 1.30 (the approach to gross slip, `crate::zones`) the ratios 4.01, 4.20 and 4.14 up to
/// 2 048 steps were followed by 4.94, and the Richardson value there erred by 0.080 of the last
/// difference (`levelneed 1e-6` on the grid of `docs/solver.md`): a share of 0.05 stated
/// 6.9e-8 for an error of 1.11e-7.
pub const STEADY_FLOOR: f64 = RAW_FLOOR;

/// The share where the convergence is tight (three ratios of successive differences within
/// 1 % of 4), for every law. Over the ladders of 1 018 points (`ladder -- 400 11 11` and
/// `ladder -- 600 12 11`: the elastic and Kelvin–Voigt laws to 16 384–131 072 steps, against the
/// Richardson value of the two finest levels) the 888 tight levels needed at most 0.0013 of the
/// last difference beyond the difference of the Richardson values, and the 134 tight levels of
/// Thornton's law (`ladder -- 60 1 11 thornton`, `150 2 11 thornton`) at most 0.0047 (γ =
/// 0.3165, α = 0.24, e_n = 0.78, 8 192 steps). The levels that needed the steady share had
/// ratios 2–5 % from 4: 4.01, 4.20, 4.14 before the 0.080 of [`STEADY_FLOOR`], and 4.18, 4.19,
/// 4.07 before Thornton's 0.065 ([`crate::thornton::RAW_FLOOR`]).
pub const TIGHT_FLOOR: f64 = 0.01;

/// The elastic law's floor ([`Floor`]): [`RAW_FLOOR`] where the convergence is regular or
/// steady, [`TIGHT_FLOOR`] where it is tight, [`IRREGULAR_FLOOR`] elsewhere.
pub const FLOOR: Floor = Floor {
    regular: RAW_FLOOR,
    steady: STEADY_FLOOR,
    tight: TIGHT_FLOOR,
    irregular: IRREGULAR_FLOOR,
    scatter: crate::law::ROW_SCATTER,
};

/// The elastic law ([`ContactLaw`]): `e_n = 1`, no parameters.
#[derive(Debug, Clone, Copy, Default)]
pub struct Elastic;

/// The elastic law's parameters: none (`e_n = 1`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Parameters;

impl ContactLaw for Elastic {
    type Parameters = Parameters;

    /// Elastic bodies take no parameters.
    type BodiesParameters = Parameters;

    const FLOOR: Floor = FLOOR;

    fn check_restitution(e_n: f64) -> Result<f64, PhysicsError> {
        if e_n == 1.0 {
            Ok(e_n)
        } else {
            Err(PhysicsError::InvalidParameter {
                name: "e_n",
                value: e_n,
                allowed: "1 for the elastic law (name the kelvin-voigt law for e_n < 1)",
            })
        }
    }

    fn parameters(_e_n: f64) -> Result<Parameters, PhysicsError> {
        Ok(Parameters)
    }

    /// Every scheme (accurate and Euler).
    fn prepare(
        gamma: f64,
        alpha: f64,
        _e_n: f64,
        _scheme: Scheme,
    ) -> Result<(f64, f64, Parameters), PhysicsError> {
        Ok((check_gamma(gamma)?, check_alpha(alpha)?, Parameters))
    }

    /// The full-slip line, the `γ = 1` plateau and `α = 0` ([`regimes::closed_form`]).
    fn closed_form(gamma: f64, alpha: f64, _e_n: f64) -> Option<f64> {
        regimes::closed_form(gamma, alpha)
    }

    /// Hertz normal motion and the row of the scheme ([`simulate_elastic`]).
    fn simulate(
        gamma: f64,
        alpha: f64,
        _parameters: Parameters,
        res: Resolution,
        scheme: Scheme,
    ) -> Result<Level, PhysicsError> {
        simulate_elastic(gamma, alpha, res, scheme)
    }

    /// `τ̂ = 0` (the elastic law is the Kelvin–Voigt law without relaxation).
    fn values(_parameters: &Parameters) -> [f64; PARAMETER_KEYS.len()] {
        [0.0, 0.0]
    }

    fn describe(_parameters: &Parameters) -> Option<String> {
        None
    }

    /// `e_n = 1` at every speed.
    fn of_bodies(
        parameters: Parameters,
        _normal: &BodiesNormal,
    ) -> Result<(Parameters, f64), PhysicsError> {
        Ok((parameters, 1.0))
    }

    /// The Hertz motion of the bodies and the continuum row (`res.springs = 0`) or a row of
    /// `res.springs` springs ([`run_contact`]).
    fn run_bodies<B: TangentialBodies>(
        bodies: &mut B,
        normal: &BodiesNormal,
        _parameters: Parameters,
        res: Resolution,
        (radius, shear_modulus, limit): (f64, f64, f64),
    ) -> Result<NormalSummary, PhysicsError> {
        let normal = NormalBodies {
            inv_mass1: normal.inv_mass1,
            inv_mass2: normal.inv_mass2,
            stiffness: normal.stiffness,
            approach_speed: normal.approach_speed,
        }
        .trajectory(res.steps);
        let shortest_zone = run_contact(bodies, &normal, res.springs, radius, shear_modulus, limit);
        Ok(NormalSummary {
            contact_time: normal.contact_time,
            peak_force: normal.peak_force,
            max_indentation: normal.max_indentation,
            delta_v1: normal.delta_v1,
            delta_v2: normal.delta_v2,
            shortest_zone,
        })
    }
}
