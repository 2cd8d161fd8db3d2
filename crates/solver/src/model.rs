//! The seams of the impact model, after LAMMPS GRANULAR's split of a contact into sub-models:
//! a normal model (the motion along the common normal), a tangential model (the field of
//! tangential displacements in the contact and the force it exerts) and an integrator (the
//! time scheme). [`crate::impact::run_contact`] composes them; the error-controlled driver
//! ([`crate::refine::refine`], [`crate::Request::solve`]) sits on top.
//!
//! Today's models: Hertz normal contact, elastic (`e_n = 1`), tabulated on the contact's time
//! grid ([`crate::hertz::NormalTrajectory`]); the MDR continuum row
//! ([`crate::continuum::ContinuumRow`], exact in space) and the seed's row of springs
//! ([`crate::springs::SpringRow`]), which the elastic law ([`crate::elastic`]) implements these
//! traits for; the Kelvin–Voigt law's own models ([`crate::kelvin_voigt`]); the accurate scheme
//! ([`VelocityVerlet`]) and the seed's explicit Euler scheme ([`ExplicitEuler`]). A dissipative normal model, another tangential
//! profile or another scheme is one more implementation of a trait, not a change of the loop.

use crate::springs::{StepMotion, StepResult};

/// The tangential degrees of freedom driven by the friction force `F_f` through the springs.
///
/// Implemented once for the dimensionless contact point and once for two bodies in physical
/// units; the time stepping ([`run_contact`]) is shared.
pub trait TangentialBodies {
    /// Relative tangential velocity of the contact points `u` (m/s).
    fn slip_velocity(&self) -> f64;
    /// `du/dt` produced by a friction force `f` (N), from each body's equations of motion.
    fn slip_acceleration(&self, f: f64) -> f64;
    /// Advance every velocity by `h` under the constant friction force `f`.
    fn kick(&mut self, h: f64, f: f64);
}

/// One step of the accurate scheme as the row has taken it, for [`TangentialModel::close_step`].
pub struct StepEnd<'a> {
    /// The motion over the step (its length `h`, start state and slip).
    pub motion: &'a StepMotion,
    /// What the row returned for the step.
    pub step: StepResult,
    /// Effective radius `R*` (m).
    pub radius: f64,
    /// Shear modulus `G*` (Pa).
    pub shear_modulus: f64,
    /// Mean contact radius over the step, `∫ a dt / h` (m).
    pub mean_radius: f64,
    /// Mean displacement at the start of the step (m).
    pub mean0: f64,
    /// Mean displacement at its end for the product rule (m; the separation's value in the
    /// step where the contact vanishes).
    pub end_mean: f64,
    /// The contact's reach at the end of the step (m; ≤ 0 once it has vanished).
    pub reach1: f64,
}

/// The elastic end of a step: the product rule `h G* ā (m₀ + m₁)` for the impulse, the row's
/// integral and mean at the end.
#[inline(always)]
pub fn close_step_elastic<B: TangentialBodies>(bodies: &mut B, end: &StepEnd) -> (f64, f64) {
    let h = end.motion.h;
    bodies.kick(
        h,
        end.shear_modulus * end.mean_radius * (end.mean0 + end.end_mean),
    );
    (2.0 * end.shear_modulus * end.step.integral, end.step.mean)
}

/// The normal motion of one impact on the uniform time grid of the contact: node 0 is first
/// touch, node [`NormalModel::steps`] is separation.
pub trait NormalModel {
    /// Number of grid steps over the contact.
    fn steps(&self) -> usize;
    /// Time step `dt = t_c / steps` (s) of a uniform grid; for a grid of two uniform parts
    /// (an event at the node between them: [`NormalModel::step_length`]) the step of the last
    /// part.
    fn dt(&self) -> f64;
    /// Length of grid step `n` (s): [`NormalModel::dt`] on a uniform grid. A law whose motion
    /// changes its law at an instant (Thornton's switch from loading to unloading) makes that
    /// instant a node, with uniform steps on either side.
    #[inline(always)]
    fn step_length(&self, _n: usize) -> f64 {
        self.dt()
    }
    /// Contact time `t_c` (s).
    fn contact_time(&self) -> f64;
    /// Maximum indentation `d_max` (m).
    fn max_indentation(&self) -> f64;
    /// Indentation `d_n` (m) at node `n`.
    fn indentation(&self, n: usize) -> f64;
    /// Indentation rate `ḋ_n` (m/s) at node `n`.
    fn rate(&self, n: usize) -> f64;
    /// Indentation acceleration `d̈` (m/s²) at indentation `d` (m) and rate `ḋ` (m/s): the
    /// normal force's, `−F_N(d, ḋ) (1/m1 + 1/m2)`. An elastic model ignores `ḋ`.
    fn acceleration(&self, d: f64, rate: f64) -> f64;
    /// Indentation and its rate at time `t ∈ [0, dt]` into step `n`.
    fn within_step(&self, n: usize, t: f64) -> (f64, f64);
    /// The contact's reach (m) at indentation `d` and rate `ḋ`: the springs at profile height
    /// `y = x²/R* <` reach are in contact, and the contact radius is `√(R* reach)`. The
    /// indentation itself for an elastic law (the default); the contact ends where it is 0.
    #[inline(always)]
    fn reach(&self, (d, _rate): (f64, f64)) -> f64 {
        d
    }
    /// The level `D` (m) of the Coulomb limits `±c (D − y)` at indentation `d` and rate `ḋ`:
    /// the indentation itself for an elastic law (the default).
    #[inline(always)]
    fn limit_level(&self, (d, _rate): (f64, f64)) -> f64 {
        d
    }
}

/// The field of tangential displacements in the contact: advanced over one time step of the
/// normal motion under the Coulomb limit, it returns the mean displacement and the integral
/// that give the friction force.
pub trait TangentialModel {
    /// Whether some part of the contact is at the `+` and at the `−` Coulomb limit.
    fn at_limit(&self) -> (bool, bool);
    /// Whether some part of the contact is stuck (below both limits) after the last step: with
    /// [`TangentialModel::at_limit`], the zone of the slip history the row is in
    /// ([`crate::zones`]). The default, `true`, counts zones by their limits only.
    #[inline(always)]
    fn stuck(&self) -> bool {
        true
    }
    /// Whether the stepper splits a step at the onset of gross slip inside it. There the
    /// friction force joins `±μ F_N` with a kink, and a step that straddles it integrates the
    /// impulse with an error of order `h²` that depends on where in the step the onset falls:
    /// at γ = 2.5, α = 0.9 and at γ = 3, α = 1, `P` at `N` steps scattered by `1.8/N²` rms (up
    /// to `4/N²`) around its smooth convergence, so that the differences between levels
    /// changed sign and the refinement ran one or two levels past the tolerance; split, the
    /// scatter falls to `0.01–0.03/N²`. The stepper locates the onset where the gap of the
    /// mean displacement to its gross-slip value, closing at the previous step's rate, closes
    /// inside the step: the field's limit is `±c (D − y)` ([`NormalModel::limit_level`]) over
    /// the reach `b` ([`NormalModel::reach`]), so that the whole contact at it puts the mean
    /// displacement at `±c (D − b/3)`. `false` (the default): not for a model whose limits
    /// differ.
    const LOCATES_GROSS_SLIP: bool = false;
    /// Advance the field over one step of motion `m` to indentation `d1` with Coulomb limit
    /// `c = μ E*/G*` (`∞` for no slip).
    fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult;
    /// The mean force displacement (m) over the contact at first touch, when the contact radius
    /// is still 0, for slip velocity `ẇ₀` (m/s), approach rate `ḋ₀` (m/s) and Coulomb limit
    /// factor `c`: 0 for an elastic row (the springs enter unloaded); the product rule of the
    /// stepper integrates the first step's force from it.
    #[inline(always)]
    fn touch_mean(&self, _slip_velocity: f64, _rate0: f64, _c: f64) -> f64 {
        0.0
    }
    /// Close a step the row has just taken ([`StepEnd`]): kick `bodies` by the friction impulse
    /// over it and return the friction force (N) and the mean displacement (m) at its end. The
    /// default is the elastic rule ([`close_step_elastic`]); a viscous row solves for the end
    /// velocity implicitly.
    #[inline(always)]
    fn close_step<B: TangentialBodies>(&self, bodies: &mut B, end: &StepEnd) -> (f64, f64) {
        close_step_elastic(bodies, end)
    }
    /// A jump of the field at the start of a grid step: a law whose Coulomb limits change at
    /// an instant (Thornton's switch from loading to unloading, a node of the grid) clips the
    /// field there and returns the new `∫₀^a ũ dx` (m²) and mean displacement (m), with which
    /// the step starts: the friction force jumps with them. `start` and `end` are the normal
    /// states `(d, ḋ)` at the ends of the step, `c` the limit factor. `None` (the default):
    /// the field is continuous.
    #[inline(always)]
    fn jump(&mut self, _start: (f64, f64), _end: (f64, f64), _c: f64) -> Option<StepResult> {
        None
    }
    /// Whether the model reads the end state of the normal motion ([`StepMotion::rate1`],
    /// [`StepMotion::accel1`]); without it the stepper leaves `accel1` at 0.
    const END_STATE: bool = false;
    /// The instant (s, inside the step, away from its ends by 1e-3 of it) at which the field
    /// changes its law everywhere at once, so that the stepper splits the step there; `None`
    /// if there is none. The default is the elastic row's: the part of the contact at a
    /// Coulomb limit sticks again where `ẇ = ±c ḋ` ([`StepMotion::release_times`]).
    #[inline(always)]
    fn release_time(&self, m: &StepMotion, c: f64) -> Option<f64> {
        let h = m.h;
        let (at_plus, at_minus) = self.at_limit();
        let (tp, tm) = m.release_times(c);
        [tp.filter(|_| at_plus), tm.filter(|_| at_minus)]
            .into_iter()
            .flatten()
            .filter(|&t| t > 1e-3 * h && t < (1.0 - 1e-3) * h)
            .reduce(f64::min)
    }
}

/// A time scheme: how the equations of the bodies and of the tangential field are advanced,
/// with what the error-controlled driver needs to know of it: its order, its ladder of
/// resolutions, the memory it holds and the error of its first level.
pub trait Integrator {
    /// The scheme's name as the CLI and the tables print it.
    const NAME: &'static str;
    /// Order of convergence in the time step.
    const ORDER: i32;
    /// Whether the refinement extrapolates its values (Richardson) rather than reporting the
    /// finest one.
    const RICHARDSON: bool;
    /// The base level of the refinement for a `γ` whose tangential frequency asks for `scale`
    /// times the steps of `γ ≤ 1` (a power of two).
    fn base_resolution(scale: f64) -> crate::resolution::Resolution;
    /// The first level the refinement runs, from its base.
    fn ladder_start(base: crate::resolution::Resolution) -> crate::resolution::Resolution;
    /// Memory (bytes) the scheme holds of the normal motion at `res`.
    fn normal_memory(res: crate::resolution::Resolution) -> f64;
    /// Predicted raw error (difference between the first two levels) at `γ` with base `base`.
    fn base_error(gamma: f64, base: crate::resolution::Resolution) -> f64;
    /// Refuse a resolution the scheme cannot run.
    fn check(
        res: crate::resolution::Resolution,
    ) -> Result<crate::resolution::Resolution, crate::PhysicsError> {
        Ok(res)
    }
    /// `P` of the dimensionless impact of one solid sphere (`m* = R* = E* = v_z0 = 1`,
    /// `u0 = 1`) at resolution `res`, with `G* = shear = (2/7)γ²` and Coulomb limit
    /// `c = limit` (`∞` for no slip). `res` is valid for the scheme.
    /// The run's zones are watched where the scheme can ([`crate::zones::Level`]).
    fn dimensionless_p(
        shear: f64,
        limit: f64,
        res: crate::resolution::Resolution,
    ) -> crate::zones::Level;
}

/// The accurate scheme: velocity Verlet for the bodies, product integration of the friction
/// impulse, exact release instants, graded steps before separation (`docs/solver.md`).
#[derive(Debug, Clone, Copy, Default)]
pub struct VelocityVerlet;

/// The seed paper's explicit Euler scheme (first order), kept for comparison: it integrates its
/// own normal motion on a row of springs at the midpoints.
#[derive(Debug, Clone, Copy, Default)]
pub struct ExplicitEuler;

/// The grid accessors of [`NormalModel`] for a trajectory tabulated in the fields
/// `indentation`, `rate`, `dt`, `contact_time` and `max_indentation` (the Hertz and the
/// Kelvin–Voigt trajectories).
macro_rules! grid_accessors {
    () => {
        #[inline(always)]
        fn steps(&self) -> usize {
            self.indentation.len() - 1
        }
        #[inline(always)]
        fn dt(&self) -> f64 {
            self.dt
        }
        #[inline(always)]
        fn contact_time(&self) -> f64 {
            self.contact_time
        }
        #[inline(always)]
        fn max_indentation(&self) -> f64 {
            self.max_indentation
        }
        #[inline(always)]
        fn indentation(&self, n: usize) -> f64 {
            self.indentation[n]
        }
        #[inline(always)]
        fn rate(&self, n: usize) -> f64 {
            self.rate[n]
        }
    };
}
pub(crate) use grid_accessors;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::continuum::ContinuumRow;
    use crate::impact::{
        dimensionless_normal, run_contact_with, simulate_elastic, ContactPoint, Resolution, Scheme,
    };
    use crate::springs::SpringRow;

    /// A tangential model that never holds a displacement: no friction force at all.
    struct Frictionless;

    impl TangentialModel for Frictionless {
        fn at_limit(&self) -> (bool, bool) {
            (false, false)
        }
        fn step_accurate(&mut self, _: &StepMotion, _: f64, _: f64) -> StepResult {
            StepResult {
                integral: 0.0,
                mean: 0.0,
            }
        }
    }

    /// `P` of the dimensionless impact at γ, α through the generic loop with tangential model
    /// `row`.
    fn p_with<T: TangentialModel>(gamma: f64, alpha: f64, steps: usize, row: T) -> f64 {
        let shear = 2.0 / 7.0 * gamma * gamma;
        let normal = dimensionless_normal(steps);
        let mut cp = ContactPoint { u: 1.0 };
        run_contact_with(&mut cp, &*normal, row, 1.0, shear, alpha / shear);
        cp.u
    }

    #[test]
    fn the_composed_models_are_the_accurate_scheme_to_the_bit() {
        for (g, a) in [(0.5, 2.0), (1.754, 1.0), (3.2, 1.3)] {
            let continuum = simulate_elastic(
                g,
                a,
                Resolution {
                    springs: 0,
                    steps: 512,
                },
                Scheme::Accurate,
            );
            let row = ContinuumRow::new(1.0);
            assert_eq!(
                p_with(g, a, 512, row).to_bits(),
                continuum.unwrap().p.to_bits()
            );
            let res = Resolution {
                springs: 64,
                steps: 256,
            };
            let springs = simulate_elastic(g, a, res, Scheme::Accurate).unwrap().p;
            let a_max = dimensionless_normal(256).max_indentation.sqrt();
            let row = SpringRow::nodes(a_max, 64, 1.0);
            assert_eq!(p_with(g, a, 256, row).to_bits(), springs.to_bits());
        }
    }

    /// `P` of the dimensionless impact on `normal` started with the slip velocity `u0 = ±1`
    /// (`P = u/u0`).
    fn p_signed<N: NormalModel, T: TangentialModel>(
        u0: f64,
        normal: &N,
        (gamma, alpha): (f64, f64),
        row: T,
    ) -> f64 {
        let shear = 2.0 / 7.0 * gamma * gamma;
        let mut cp = ContactPoint { u: u0 };
        run_contact_with(&mut cp, normal, row, 1.0, shear, alpha / shear);
        cp.u / u0
    }

    /// The elastic and Kelvin–Voigt rows are the same under `u → −u`, to the bit: the two
    /// Coulomb limits are treated alike (the release corrections, the clipping, the onset of
    /// gross slip). Thornton's row has its own test (`thornton::tests`).
    #[test]
    fn the_rows_are_the_same_for_a_mirrored_slip() {
        let tau = crate::kelvin_voigt::tau_fit(0.8);
        let elastic = dimensionless_normal(512);
        let viscous = crate::kelvin_voigt::dimensionless_normal(512, tau);
        for case in [(0.5, 1.0), (1.754, 0.3), (3.0, 1.5), (3.4, 0.6), (2.1, 4.4)] {
            let continuum = |u0| p_signed(u0, &*elastic, case, ContinuumRow::new(1.0));
            assert_eq!(
                continuum(1.0).to_bits(),
                continuum(-1.0).to_bits(),
                "{case:?}"
            );
            let kv = |u0| {
                let row = crate::kelvin_voigt::row::ViscoelasticRow::new(1.0, tau);
                p_signed(u0, &*viscous, case, row)
            };
            assert_eq!(kv(1.0).to_bits(), kv(-1.0).to_bits(), "{case:?}");
        }
    }

    #[test]
    fn a_new_tangential_model_plugs_into_the_loop() {
        // Without friction the contact point keeps its tangential velocity: P = 1 exactly,
        // whatever γ and α (the normal motion alone exerts no tangential impulse).
        for (g, a) in [(0.5, 2.0), (1.754, 1.0), (3.2, f64::INFINITY)] {
            assert_eq!(p_with(g, a, 256, Frictionless), 1.0);
        }
        // With the MDR row the same loop loses tangential velocity: P < 1.
        assert!(p_with(1.754, 1.0, 256, ContinuumRow::new(1.0)) < 0.5);
    }

    #[test]
    fn the_schemes_name_their_integrators() {
        // The names the command line, configs and provenance strings use, and the orders the
        // Richardson estimate divides by (2^order − 1).
        let named = |s: Scheme| (s.name(), s.order());
        assert_eq!(named(Scheme::Accurate), ("accurate", 2));
        assert_eq!(named(Scheme::Euler), ("euler", 1));
        assert_eq!(
            (VelocityVerlet::NAME, VelocityVerlet::ORDER),
            named(Scheme::Accurate)
        );
        assert_eq!(
            (ExplicitEuler::NAME, ExplicitEuler::ORDER),
            named(Scheme::Euler)
        );
    }
}
