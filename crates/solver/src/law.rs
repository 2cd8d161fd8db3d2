//! The dissipation law of an impact, picked by name: `elastic` (`e_n = 1`, the model of
//! `physics.md`) or `kelvin-voigt` (every MDR spring a Kelvin–Voigt element with one relaxation
//! time in the normal and tangential direction, non-adhesive unloading; `physics.md`,
//! "Dissipative impacts"). Within a law, `P` depends on `(γ, α, e_n)` only; across laws it
//! does not, so every answer names its law.
//!
//! What a law is: the [`ContactLaw`] trait (its parameters, closed forms, the floor of its error
//! estimate, its simulation at a resolution, in dimensionless form and for physical bodies),
//! implemented by each law's folder ([`crate::elastic`], [`crate::kelvin_voigt`]). Which laws
//! there are (the [`crate::registry::Law`] names) and which one answers a request:
//! [`crate::registry`]. The range of `e_n` the solver takes, whatever the law:
//! [`MIN_RESTITUTION`], [`check_restitution`]; the one output layout of every law's
//! parameters: [`PARAMETER_KEYS`].

use std::fmt::Debug;

use serde::Serialize;

use crate::error::PhysicsError;
use crate::impact::{Scheme, TangentialBodies};
use crate::resolution::Resolution;
use crate::zones::Level;

/// Smallest normal restitution the solver takes (the Kelvin–Voigt law's range is
/// `[MIN_RESTITUTION, 1]`).
pub const MIN_RESTITUTION: f64 = 0.3;

/// Check a normal restitution: finite, in `[0.3, 1]` (`[MIN_RESTITUTION, 1]`).
pub fn check_restitution(e_n: f64) -> Result<f64, PhysicsError> {
    if (MIN_RESTITUTION..=1.0).contains(&e_n) {
        Ok(e_n)
    } else {
        Err(PhysicsError::InvalidParameter {
            name: "e_n",
            value: e_n,
            allowed: "a number in [0.3, 1] (1: elastic)",
        })
    }
}

/// Refuse a scheme other than the accurate one, for a law solved with it only: `case` says
/// for what (`"for e_n < 1"`), `allowed` what the law takes instead.
pub(crate) fn accurate_only(
    scheme: Scheme,
    case: &'static str,
    allowed: &'static str,
) -> Result<(), PhysicsError> {
    if scheme == Scheme::Accurate {
        Ok(())
    } else {
        Err(PhysicsError::NotForLaw {
            name: "scheme",
            value: scheme.name().to_string(),
            case,
            allowed,
        })
    }
}

/// Refuse a row of springs (`springs > 0`), for a law solved on the continuum row only.
pub(crate) fn continuum_only(
    springs: usize,
    case: &'static str,
    allowed: &'static str,
) -> Result<(), PhysicsError> {
    if springs == 0 {
        Ok(())
    } else {
        Err(PhysicsError::NotForLaw {
            name: "springs",
            value: springs.to_string(),
            case,
            allowed,
        })
    }
}

/// `G* = (2/7) γ²` and the Coulomb limit factor `c = α/G*` of the dimensionless impact (`∞`
/// above [`crate::impact::ALPHA_NO_SLIP`]: no slip).
pub(crate) fn shear_and_limit(gamma: f64, alpha: f64) -> (f64, f64) {
    let shear = 2.0 / 7.0 * gamma * gamma;
    let limit = if alpha > crate::impact::ALPHA_NO_SLIP {
        f64::INFINITY
    } else {
        alpha / shear
    };
    (shear, limit)
}

/// The floor of the Richardson estimate as a share of the last raw difference
/// `|P_k − P_{k−1}|`: `regular` where the last two ratios of successive differences are within
/// `[0.75, 1.375] · 2^p` (clean convergence at order `p`), `irregular` elsewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floor {
    /// Share where the convergence is regular.
    pub regular: f64,
    /// Share where it is steady: the last three ratios of successive differences within
    /// `[0.95, 1.05] · 2^p` (`refine::steady`); at most [`Floor::regular`].
    pub steady: f64,
    /// Share where it is tight: the last three ratios within `[0.99, 1.01] · 2^p`
    /// (`refine::tight`); at most [`Floor::steady`]. Such a level is also accepted without the
    /// guard on the level before it (`refine::previous_estimate_agrees`): four doublings at the
    /// order are no plateau.
    pub tight: f64,
    /// Share elsewhere (and while fewer than four values exist).
    pub irregular: f64,
    /// An absolute floor `scatter/N²` at `N` steps: the part of the error that depends on where
    /// events fall inside the steps, which no difference between levels measures (0: none).
    pub scatter: f64,
}

impl Floor {
    /// One share whatever the convergence.
    pub const fn fixed(share: f64) -> Self {
        Floor {
            regular: share,
            steady: share,
            tight: share,
            irregular: share,
            scatter: 0.0,
        }
    }

    /// The same floor without its [`Floor::scatter`] (an impact without slip: no event).
    pub const fn without_scatter(self) -> Self {
        Floor {
            scatter: 0.0,
            ..self
        }
    }
}

/// [`Floor::scatter`] of the continuum row of the elastic and Kelvin–Voigt laws: with the onset
/// of gross slip located inside the steps ([`crate::model::TangentialModel::LOCATES_GROSS_SLIP`]),
/// `P` at `N` steps still scatters around its smooth convergence by up to 0.05/N² (γ 0.5–3,
/// α 0.3–1, `e_n` 0.9–1; `stepscan`); where the smooth part of the error is small (γ = 1.754,
/// α = 1, where `C` is below 0.04) the differences between levels say nothing of it: at tol 1e-8
/// the Richardson value erred by 4.9e-10 at 8192 steps with an estimate of 3.4e-10.
pub const ROW_SCATTER: f64 = 0.1;

/// The keys under which outputs report the laws' parameters, one layout for every law so that
/// answers of different laws share their columns (the JSON of `sweep impact`, the columns of
/// Python's `impact`, the dict of its `simulate`): `tau`, the dimensionless relaxation time
/// `τ̂` (0 for the elastic law, which is the Kelvin–Voigt law at `τ̂ = 0`), and
/// `yield_pressure`, Thornton's dimensionless limiting pressure `p̂_y` (0 for the other laws). A
/// law with other parameters adds its keys here ([`ContactLaw::values`] gives every key a
/// value).
pub const PARAMETER_KEYS: [&str; 2] = ["tau", "yield_pressure"];

/// A contact law: what the solver needs of it to answer a request. Implemented once per law,
/// in the law's folder, by a unit type ([`crate::elastic::Elastic`],
/// [`crate::kelvin_voigt::KelvinVoigt`]) and registered by one line of [`crate::registry`],
/// which picks one by name and `e_n`. Dimensionless units as in [`crate::impact`]
/// (`m* = R* = E* = v_z0 = 1`, `G* = (2/7)γ²`).
pub trait ContactLaw {
    /// The law's dimensionless parameters for one `e_n` (none for the elastic law; the
    /// relaxation time `τ̂` for the Kelvin–Voigt law), as its answers report them.
    type Parameters: Copy + PartialEq + Debug + Serialize;

    /// The law's parameters of physical bodies, in SI units (none for the elastic law; the
    /// relaxation time `τ` (s) for the Kelvin–Voigt law), from which
    /// [`ContactLaw::of_bodies`] finds `e_n` at an impact's speed.
    type BodiesParameters: Copy + PartialEq + Debug;

    /// The floor of the Richardson error estimate as a share of the last raw difference
    /// between levels: the law's estimate policy, set by how regularly it converges.
    const FLOOR: Floor;

    /// Check the normal restitution `e_n` for this law (the elastic law takes 1 only).
    fn check_restitution(e_n: f64) -> Result<f64, PhysicsError>;

    /// The parameters that give a checked `e_n`.
    fn parameters(e_n: f64) -> Result<Self::Parameters, PhysicsError>;

    /// Check `γ` (> 0), `α` (≥ 0, `∞` for no slip) and the scheme of a request at a checked
    /// `e_n`: the checked `(γ, α)` and the law's parameters.
    fn prepare(
        gamma: f64,
        alpha: f64,
        e_n: f64,
        scheme: Scheme,
    ) -> Result<(f64, f64, Self::Parameters), PhysicsError>;

    /// `P(γ, α, e_n)` where it is exact without simulation (`None` elsewhere); `γ`, `α` checked.
    fn closed_form(gamma: f64, alpha: f64, e_n: f64) -> Option<f64>;

    /// `P` of the dimensionless impact at resolution `res` (no closed form, no estimate), with
    /// the checked `(γ, α)` and parameters of [`ContactLaw::prepare`], and how finely the run
    /// resolved the zones of its slip history ([`Level`]: the refinement accepts a level only
    /// where it did; [`Level::unwatched`] for a law that does not watch them).
    fn simulate(
        gamma: f64,
        alpha: f64,
        parameters: Self::Parameters,
        res: Resolution,
        scheme: Scheme,
    ) -> Result<Level, PhysicsError>;

    /// The values of [`PARAMETER_KEYS`] for `parameters`, in their order (0 for a key that is
    /// not this law's).
    fn values(parameters: &Self::Parameters) -> [f64; PARAMETER_KEYS.len()];

    /// The parameters in words with their units, for a line of text (`None` for a law without
    /// parameters).
    fn describe(parameters: &Self::Parameters) -> Option<String>;

    /// Check the parameters of physical bodies and find, for the bodies' normal constants
    /// `normal` and their approach speed, the dimensionless parameters and `e_n` of the impact
    /// (`e_n` in the law's range; an error names the physical parameter otherwise).
    fn of_bodies(
        parameters: Self::BodiesParameters,
        normal: &BodiesNormal,
    ) -> Result<(Self::Parameters, f64), PhysicsError>;

    /// Run the contact of physical bodies (SI) with checked `parameters` at resolution `res`
    /// with the accurate scheme: the law's normal motion of `normal`, and its tangential row
    /// driving `bodies` with effective radius `R*` (m), shear modulus `G*` (Pa) and Coulomb
    /// limit factor `c = μ E*/G*` (`∞`: no slip), `contact = (R*, G*, c)`.
    fn run_bodies<B: TangentialBodies>(
        bodies: &mut B,
        normal: &BodiesNormal,
        parameters: Self::BodiesParameters,
        res: Resolution,
        contact: (f64, f64, f64),
    ) -> Result<NormalSummary, PhysicsError>;
}

/// The normal constants of two physical bodies, from which a law builds its normal motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodiesNormal {
    /// `1/m1` (1/kg).
    pub inv_mass1: f64,
    /// `1/m2` (1/kg); 0 for a wall.
    pub inv_mass2: f64,
    /// Normal reduced mass `m*` (kg).
    pub normal_mass: f64,
    /// Hertz stiffness `k = (4/3) E* √R*` (N/m^{3/2}).
    pub stiffness: f64,
    /// Effective radius `R*` (m).
    pub radius: f64,
    /// Approach speed `v_z0` at first touch (m/s), > 0.
    pub approach_speed: f64,
}

/// What the outcome of a physical impact needs of the normal motion a law ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalSummary {
    /// Contact time `t_c` (s).
    pub contact_time: f64,
    /// Peak normal force (N).
    pub peak_force: f64,
    /// Maximum indentation `d_max` (m).
    pub max_indentation: f64,
    /// Change of sphere 1's normal velocity over the contact (m/s).
    pub delta_v1: f64,
    /// Change of sphere 2's normal velocity over the contact (m/s; 0 for a wall).
    pub delta_v2: f64,
    /// How finely the run resolved its approach to gross slip ([`Level::shortest_zone`], grid
    /// steps; `∞` for a law that does not watch it).
    pub shortest_zone: f64,
}
