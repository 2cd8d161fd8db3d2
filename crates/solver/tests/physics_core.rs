//! Integration tests of the physics core against closed forms and converged runs (its
//! convergence and error estimates: `estimates.rs`).
//!
//! Reference values are closed forms (the full-slip line `P = 1 − 7α`, the `γ = 1` plateau
//! `P = −1`, Hertz's contact time and peak force, momentum conservation, the rigid-body kinematics
//! of a given `P`) or simulations at a much higher resolution than the run under test. Nothing is
//! copied from the program's own output.

use oblique_physics::rebound::{Body, Elastic, Incident, Pair, State};
use oblique_physics::regimes::{self, alpha_c1, alpha_c2, closed_form, linear_limit, Regime};
use oblique_solver::hertz::{HertzClosedForm, NormalBodies};
use oblique_solver::units::{PhysicalImpact, PhysicalOutcome};
use oblique_solver::{Accuracy, Method, PhysicsError, Request, Resolution, Scheme};

const ACC: Scheme = Scheme::Accurate;

fn res(springs: usize, steps: usize) -> Resolution {
    Resolution { springs, steps }
}

/// A resolution of two springs per step (the accurate ladder used one per step since
/// `base_resolution` changed; either converges).
fn res2(steps: usize) -> Resolution {
    res(2 * steps, steps)
}

fn line(alpha: f64) -> f64 {
    1.0 - 7.0 * alpha
}

// ---------------------------------------------------------------------------------------------
// A tiny deterministic RNG (xorshift64) and random physical impacts.
// ---------------------------------------------------------------------------------------------

struct XorShift(u64);

impl XorShift {
    fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.uniform(lo.ln(), hi.ln()).exp()
    }
    fn coin(&mut self) -> bool {
        self.next_u64() & 1 == 0
    }
    fn sign(&mut self) -> f64 {
        if self.coin() {
            1.0
        } else {
            -1.0
        }
    }
}

fn random_material(rng: &mut XorShift) -> Elastic {
    Elastic {
        youngs_modulus: rng.log_uniform(1e6, 1e12),
        poisson_ratio: rng.uniform(-0.9, 0.5),
    }
}

/// A random sphere and its material (drawn in this order: radius, density, κ, material).
fn random_sphere(rng: &mut XorShift) -> (Body, Elastic) {
    let radius = rng.log_uniform(1e-6, 1.0);
    let density = rng.uniform(1000.0, 20000.0);
    let body = Body {
        radius,
        mass: density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3),
        kappa: rng.uniform(0.2, 0.7),
    };
    (body, random_material(rng))
}

fn random_motion(rng: &mut XorShift, radius: f64, v_z: f64, spin: bool) -> State {
    State {
        v_x: rng.sign() * rng.log_uniform(1e-3, 100.0),
        v_z,
        omega: if spin {
            rng.sign() * rng.log_uniform(1e-3, 100.0) / radius
        } else {
            0.0
        },
    }
}

/// Random impact number `i`: even `i` hits a wall, odd `i` a second sphere; spin on every other
/// pair.
fn random_impact(rng: &mut XorShift, i: usize) -> PhysicalImpact {
    let (sphere, material) = random_sphere(rng);
    let spin = i % 4 >= 2;
    let v_z = rng.log_uniform(1e-3, 100.0);
    let motion = random_motion(rng, sphere.radius, v_z, spin);
    let (other, other_material, other_motion) = if i.is_multiple_of(2) {
        (None, random_material(rng), State::default())
    } else {
        let (other, other_material) = random_sphere(rng);
        // Either head-on (moving towards sphere 1) or chased (slower in the same direction).
        let v_z2 = if rng.coin() {
            -rng.log_uniform(1e-3, 100.0)
        } else {
            v_z * rng.uniform(0.0, 0.9)
        };
        let other_motion = random_motion(rng, other.radius, v_z2, spin);
        (Some(other), other_material, other_motion)
    };
    PhysicalImpact {
        pair: Pair { sphere, other },
        materials: [material, other_material],
        incident: Incident {
            sphere: motion,
            other: other_motion,
        },
        friction: rng.uniform(0.01, 2.0),
        law: Default::default(),
    }
}

/// Effective quantities computed here from the textbook formulas (not from `groups()`):
/// `(E*, R*, m*, v_z0)`.
fn hertz_inputs(imp: &PhysicalImpact) -> (f64, f64, f64, f64) {
    let s = &imp.pair.sphere;
    let [m1, m2] = &imp.materials;
    let (a, b) = (&imp.incident.sphere, &imp.incident.other);
    let compliance = |m: &Elastic| (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus;
    match &imp.pair.other {
        None => (
            1.0 / (compliance(m1) + compliance(m2)),
            s.radius,
            s.mass,
            a.v_z,
        ),
        Some(o) => (
            1.0 / (compliance(m1) + compliance(m2)),
            s.radius * o.radius / (s.radius + o.radius),
            s.mass * o.mass / (s.mass + o.mass),
            a.v_z - b.v_z,
        ),
    }
}

/// Slip velocity of the contact points, `u = (v1x + R1 ω1) − (v2x − R2 ω2)`, and a scale for
/// rounding (sum of the magnitudes of its terms).
fn slip(imp: &PhysicalImpact, s1: &State, s2: Option<&State>) -> (f64, f64) {
    let r1 = imp.pair.sphere.radius;
    let mut u = s1.v_x + r1 * s1.omega;
    let mut scale = s1.v_x.abs() + (r1 * s1.omega).abs();
    if let (Some(o), Some(m2)) = (&imp.pair.other, s2) {
        u -= m2.v_x - o.radius * m2.omega;
        scale += m2.v_x.abs() + (o.radius * m2.omega).abs();
    }
    (u, scale)
}

fn assert_rel(got: f64, want: f64, scale: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol * scale,
        "{what}: got {got:e}, want {want:e}, |diff| = {:e} > {tol:e} x {scale:e}",
        (got - want).abs()
    );
}

/// Normal restitution (momentum + energy for two spheres) and Hertz's contact time, peak force and
/// maximum indentation.
fn check_normal(imp: &PhysicalImpact, out: &PhysicalOutcome, label: &str) {
    let (e_star, r_star, m_star, v0) = hertz_inputs(imp);
    match (&imp.pair.other, out.other) {
        (None, None) => {
            assert_rel(
                out.sphere.v_z,
                -v0,
                v0,
                1e-8,
                &format!("{label}: rebound v_z"),
            );
        }
        (Some(o), Some(after2)) => {
            let (m1, m2m) = (imp.pair.sphere.mass, o.mass);
            let (v1, v2) = (imp.incident.sphere.v_z, imp.incident.other.v_z);
            let want1 = ((m1 - m2m) * v1 + 2.0 * m2m * v2) / (m1 + m2m);
            let want2 = ((m2m - m1) * v2 + 2.0 * m1 * v1) / (m1 + m2m);
            assert_rel(out.sphere.v_z, want1, v0, 1e-8, &format!("{label}: v_z1"));
            assert_rel(after2.v_z, want2, v0, 1e-8, &format!("{label}: v_z2"));
        }
        _ => panic!("{label}: outcome does not match the target kind"),
    }
    let hertz = HertzClosedForm {
        mass: m_star,
        stiffness: 4.0 / 3.0 * e_star * r_star.sqrt(),
        approach_speed: v0,
    };
    assert_rel(
        out.contact_time,
        hertz.contact_time(),
        hertz.contact_time(),
        1e-4,
        &format!("{label}: contact time"),
    );
    assert_rel(
        out.peak_force,
        hertz.peak_force(),
        hertz.peak_force(),
        1e-4,
        &format!("{label}: peak force"),
    );
    assert_rel(
        out.max_indentation,
        hertz.max_indentation(),
        hertz.max_indentation(),
        1e-4,
        &format!("{label}: max indentation"),
    );
}

/// Momentum conservation (normal and tangential linear momentum; angular momentum of each body
/// about the contact point, which the tangential force cannot change).
fn check_momentum(imp: &PhysicalImpact, out: &PhysicalOutcome, label: &str) {
    let s = &imp.pair.sphere;
    let (m1, r1, i1) = (s.mass, s.radius, s.inertia());
    let (a, b) = (imp.incident.sphere, out.sphere);
    // Body 1 about its contact point: I ω − m R v_x.
    let l1 = |m: &State| i1 * m.omega - m1 * r1 * m.v_x;
    let scale1 = (i1 * a.omega).abs() + (m1 * r1 * a.v_x).abs() + (m1 * r1 * (b.v_x - a.v_x)).abs();
    assert_rel(l1(&b), l1(&a), scale1, 1e-12, &format!("{label}: L1"));
    if let (Some(o), Some(d)) = (&imp.pair.other, out.other) {
        let c = &imp.incident.other;
        let (m2, r2, i2) = (o.mass, o.radius, o.inertia());
        let px = |p: &State, q: &State| m1 * p.v_x + m2 * q.v_x;
        let pz = |p: &State, q: &State| m1 * p.v_z + m2 * q.v_z;
        let jx = (m1 * (b.v_x - a.v_x)).abs();
        let jz = (m1 * (b.v_z - a.v_z)).abs();
        let sx = (m1 * a.v_x).abs() + (m2 * c.v_x).abs() + jx;
        let sz = (m1 * a.v_z).abs() + (m2 * c.v_z).abs() + jz;
        assert_rel(px(&b, &d), px(&a, c), sx, 1e-12, &format!("{label}: p_x"));
        assert_rel(pz(&b, &d), pz(&a, c), sz, 1e-12, &format!("{label}: p_z"));
        // Body 2 about its contact point: I ω + m R v_x.
        let l2 = |m: &State| i2 * m.omega + m2 * r2 * m.v_x;
        let scale2 =
            (i2 * c.omega).abs() + (m2 * r2 * c.v_x).abs() + (m2 * r2 * (d.v_x - c.v_x)).abs();
        assert_rel(l2(&d), l2(c), scale2, 1e-12, &format!("{label}: L2"));
    }
}

// ---------------------------------------------------------------------------------------------
// 1. Full slip: P = 1 − 7α below the linear limit.
// ---------------------------------------------------------------------------------------------

const GAMMAS: [f64; 5] = [0.5, 0.8, 1.2, 1.754, 3.0];

/// The accurate scheme's answer on the full-slip line, extrapolated to infinite resolution.
///
/// In full slip the scheme is not exact: the trapezoid rule on the parabolic Coulomb limit and the
/// time quadrature of the impulse leave a second-order error `C α / N²` with `N` springs = `N`
/// steps, and `C` is the same everywhere on the line (measured: 19.01 at N = 1024 to 19.02 at
/// N = 8192, for γ from 0.5 to 3 and α up to the limit). Richardson's extrapolation of N = 2048
/// and 4096 then lands within about 1e-11 of the limit. Returns the extrapolated `P`, and the
/// ratio of the errors against the line at N and 2N (4 for a second-order error).
fn line_extrapolated(g: f64, a: f64) -> (f64, f64) {
    let n = 2048;
    let p = |n: usize| Request::new(g, a).scheme(ACC).simulate(res(n, n)).unwrap();
    let (coarse, fine) = (p(n), p(2 * n));
    (
        (4.0 * fine - coarse) / 3.0,
        (coarse - line(a)) / (fine - line(a)),
    )
}

#[test]
fn full_slip_line_is_exact_below_the_linear_limit() {
    for &g in &GAMMAS {
        let limit = linear_limit(g);
        let expected_limit = if g > 1.0 { alpha_c1(g) } else { alpha_c2(g) };
        assert_eq!(limit, expected_limit, "linear limit at gamma = {g}");
        for &frac in &[0.25, 0.6] {
            let a = frac * limit;
            let (p, ratio) = line_extrapolated(g, a);
            assert!(
                (p - line(a)).abs() < 1e-9 && (ratio - 4.0).abs() < 0.01,
                "gamma = {g}, alpha = {a}: P (extrapolated) = {p}, 1 - 7 alpha = {}, diff {:e}, \
                 error ratio N/2N {ratio}",
                line(a),
                p - line(a)
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. γ = 1: P = −1 for α ≥ 2/7.
// ---------------------------------------------------------------------------------------------

#[test]
fn gamma_one_plateau_is_minus_one() {
    for &a in &[2.0 / 7.0, 0.3, 0.5, 1.0, 10.0, f64::INFINITY] {
        let s = Request::new(1.0, a)
            .accuracy(Accuracy::Tolerance(1e-6))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap();
        assert_eq!(s.method, Method::Simulated);
        assert!(s.error_estimate <= 1e-6);
        assert!(
            (s.p + 1.0).abs() <= s.error_estimate,
            "gamma = 1, alpha = {a}: P + 1 = {:e} exceeds the error estimate {:e} \
             ({} springs x {} steps)",
            s.p + 1.0,
            s.error_estimate,
            s.resolution.springs,
            s.resolution.steps
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Normal restitution and Hertz.
// ---------------------------------------------------------------------------------------------

fn steel(radius: f64) -> (Body, Elastic) {
    let body = Body {
        radius,
        mass: 7800.0 * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3),
        kappa: 0.4,
    };
    let material = Elastic {
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
    };
    (body, material)
}

fn glass(radius: f64) -> (Body, Elastic) {
    let body = Body {
        radius,
        mass: 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3),
        kappa: 0.4,
    };
    let material = Elastic {
        youngs_modulus: 63e9,
        poisson_ratio: 0.22,
    };
    (body, material)
}

#[test]
fn normal_restitution_and_hertz_closed_forms() {
    let aluminium = Elastic {
        youngs_modulus: 70e9,
        poisson_ratio: 0.33,
    };
    let mut cases = vec![
        PhysicalImpact::sphere_on_wall(
            steel(0.01),
            aluminium,
            State {
                v_x: 0.7,
                v_z: 2.0,
                omega: 0.0,
            },
            0.2,
        ),
        PhysicalImpact::sphere_on_sphere(
            glass(0.02),
            State {
                v_x: -0.4,
                v_z: 1.5,
                omega: 10.0,
            },
            steel(0.005),
            State {
                v_x: 0.3,
                v_z: -0.5,
                omega: -30.0,
            },
            0.3,
        ),
    ];
    let mut rng = XorShift(0x2545_F491_4F6C_DD1D);
    cases.extend((0..6).map(|i| random_impact(&mut rng, i)));
    for (i, imp) in cases.iter().enumerate() {
        let out = imp.simulate(res2(1024)).unwrap();
        let label = format!("case {i} ({:?})", imp.pair.other);
        check_normal(imp, &out, &label);
        check_momentum(imp, &out, &label);
    }
}

#[test]
fn normal_trajectory_matches_hertz_for_any_mass_ratio() {
    // (1/m1, 1/m2, k, v0): wall, equal masses, very unequal masses.
    for &(i1, i2, k, v0) in &[
        (1.0, 0.0, 4.0 / 3.0, 1.0),
        (2.0, 2.0, 3.0, 0.25),
        (1e-3, 50.0, 7e4, 30.0),
    ] {
        let tr = NormalBodies {
            inv_mass1: i1,
            inv_mass2: i2,
            stiffness: k,
            approach_speed: v0,
        }
        .trajectory(1024);
        let cf = HertzClosedForm {
            mass: 1.0 / (i1 + i2),
            stiffness: k,
            approach_speed: v0,
        };
        let what = format!("1/m1 = {i1}, 1/m2 = {i2}");
        assert_rel(
            tr.contact_time,
            cf.contact_time(),
            cf.contact_time(),
            1e-4,
            &what,
        );
        assert_rel(tr.peak_force, cf.peak_force(), cf.peak_force(), 1e-4, &what);
        assert_rel(
            tr.max_indentation,
            cf.max_indentation(),
            cf.max_indentation(),
            1e-4,
            &what,
        );
        // Elastic: the relative normal velocity reverses; momentum m1 Δv1 + m2 Δv2 = 0.
        let m1 = 1.0 / i1;
        let dv_rel = tr.delta_v1 - tr.delta_v2;
        assert_rel(dv_rel, -2.0 * v0, v0, 1e-8, &what);
        assert_rel(tr.delta_v1, -2.0 * v0 * i1 / (i1 + i2), v0, 1e-8, &what);
        if i2 > 0.0 {
            let m2 = 1.0 / i2;
            // Relative to the momentum in the system (body 1 carries v0 at first touch).
            let p_scale = m1 * v0 + m1 * tr.delta_v1.abs();
            assert_rel(
                m1 * tr.delta_v1 + m2 * tr.delta_v2,
                0.0,
                p_scale,
                1e-12,
                &what,
            );
        } else {
            assert_eq!(tr.delta_v2, 0.0);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Departure from the straight line.
// ---------------------------------------------------------------------------------------------

#[test]
fn line_holds_just_below_the_limit_and_departs_above() {
    for &g in &GAMMAS {
        let limit = linear_limit(g);
        let below = 0.999 * limit;
        assert_eq!(Regime::of(g, below), Regime::FullSlip);
        assert_eq!(closed_form(g, below), Some(line(below)));
        let (p, ratio) = line_extrapolated(g, below);
        assert!(
            (p - line(below)).abs() < 1e-9 && (ratio - 4.0).abs() < 0.01,
            "gamma = {g}, alpha = 0.999 limit = {below}: P (extrapolated) - (1 - 7 alpha) = {:e}, \
             error ratio N/2N {ratio}",
            p - line(below)
        );

        let above = 1.2 * limit;
        assert_ne!(Regime::of(g, above), Regime::FullSlip);
        assert_eq!(closed_form(g, above), None);
        let s = Request::new(g, above)
            .accuracy(Accuracy::Tolerance(1e-6))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap();
        let dev = (s.p - line(above)).abs();
        assert!(
            dev > 1e-3 && dev > 100.0 * s.error_estimate,
            "gamma = {g}, alpha = 1.2 limit = {above}: |P - (1 - 7 alpha)| = {dev:e}, \
             error estimate {:e}",
            s.error_estimate
        );
    }
}

/// One-sided second differences of `P(α)` around `ac` with spacing `d`: `(left, right)`.
fn one_sided_curvatures(g: f64, ac: f64, d: f64) -> (f64, f64) {
    let p: Vec<f64> = (-2..=2)
        .map(|k| {
            Request::new(g, ac + f64::from(k) * d)
                .scheme(ACC)
                .simulate(res2(2048))
                .unwrap()
        })
        .collect();
    (
        (p[0] - 2.0 * p[1] + p[2]) / (d * d),
        (p[2] - 2.0 * p[3] + p[4]) / (d * d),
    )
}

/// For γ = 0.8 (< 1) α_c1 = 0.653 lies above α_c2 = 0.183, i.e. beyond the end of the line:
/// the line does not hold there, and `P(α)` has no kink there (the difference of the one-sided
/// curvatures vanishes like the spacing), whereas at α_c2 the curvature jumps from 0 (line side)
/// to a large value.
#[test]
fn gamma_08_nothing_happens_at_alpha_c1_but_line_ends_at_alpha_c2() {
    let g = 0.8;
    let (c1, c2) = (alpha_c1(g), alpha_c2(g));
    assert!(c1 > c2);
    assert_eq!(linear_limit(g), c2);

    let p_c1 = Request::new(g, c1)
        .scheme(ACC)
        .simulate(res2(2048))
        .unwrap();
    assert!(
        (p_c1 - line(c1)).abs() > 0.1,
        "P(alpha_c1) = {p_c1} should be far off the line (alpha_c1 > alpha_c2)"
    );
    let jumps: Vec<f64> = [0.04, 0.02, 0.01]
        .iter()
        .map(|&d| {
            let (l, r) = one_sided_curvatures(g, c1, d);
            r - l
        })
        .collect();
    // A curvature jump Δ would give r − l → Δ; a smooth P gives r − l = O(d).
    assert!(
        jumps[1].abs() < 0.6 * jumps[0].abs() && jumps[2].abs() < 0.6 * jumps[1].abs(),
        "curvature jump at alpha_c1(0.8) does not vanish with the spacing: {jumps:?}"
    );
    assert!(jumps[2].abs() < 0.1, "{jumps:?}");

    for &d in &[0.04, 0.02, 0.01] {
        let (l, r) = one_sided_curvatures(g, c2, d);
        assert!(
            l.abs() < 1e-2,
            "line side of alpha_c2 must be straight: {l}"
        );
        assert!(
            r > 50.0,
            "curvature above alpha_c2 must be large: {r} (d = {d})"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 5. Universality: physical units reduce to (γ, α).
// ---------------------------------------------------------------------------------------------

#[test]
fn universality_of_random_physical_impacts() {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    let fixed = res2(256);
    let (mut walls, mut pairs) = (0, 0);
    for i in 0..24 {
        let imp = random_impact(&mut rng, i);
        let groups = imp.groups().unwrap();
        if groups.slip_velocity == 0.0 {
            continue;
        }
        match imp.pair.other {
            None => walls += 1,
            Some(_) => pairs += 1,
        }
        let label = format!(
            "case {i} (gamma = {}, alpha = {:e}, {:?})",
            groups.gamma, groups.alpha, imp
        );

        // Same resolution: the physical run and the dimensionless run agree far below the error.
        let out = imp.simulate(fixed).unwrap();
        let p_phys = out.p.expect("u0 != 0");
        let p_dimless = Request::new(groups.gamma, groups.alpha)
            .scheme(ACC)
            .simulate(fixed)
            .unwrap();
        let fixed_est = Request::new(groups.gamma, groups.alpha)
            .accuracy(Accuracy::Fixed(fixed))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap()
            .error_estimate;
        let diff = (p_phys - p_dimless).abs();
        assert!(
            diff <= 1e-9 && diff <= fixed_est,
            "{label}: physical P = {p_phys}, dimensionless P = {p_dimless}, diff {diff:e}, \
             estimate {fixed_est:e}"
        );
        // P is the restitution of the reported slip velocities.
        let (u0, s0) = slip(&imp, &imp.incident.sphere, imp_other_motion(&imp).as_ref());
        let (u1, s1) = slip(&imp, &out.sphere, out.other.as_ref());
        assert_rel(u0, groups.slip_velocity, s0, 1e-14, &format!("{label}: u0"));
        assert_rel(p_phys * u0, u1, s0.max(s1), 1e-12, &format!("{label}: u1"));
        check_normal(&imp, &out, &label);
        check_momentum(&imp, &out, &label);

        // With refinement: the physical solve and the dimensionless solve agree within estimates.
        let phys = imp.solve(1e-6).unwrap();
        let dimless = Request::new(groups.gamma, groups.alpha)
            .accuracy(Accuracy::Tolerance(1e-6))
            .scheme(ACC)
            .forced(true)
            .solve()
            .unwrap();
        let bound = phys.error_estimate + dimless.error_estimate;
        let diff = (phys.p.unwrap() - dimless.p).abs();
        assert!(
            phys.error_estimate <= 1e-6 && diff <= bound,
            "{label}: solve: physical {:?} +/- {:e}, dimensionless {} +/- {:e}",
            phys.p,
            phys.error_estimate,
            dimless.p,
            dimless.error_estimate
        );
    }
    assert!(walls >= 10 && pairs >= 10, "{walls} walls, {pairs} pairs");
}

fn imp_other_motion(imp: &PhysicalImpact) -> Option<State> {
    imp.pair.other.map(|_| imp.incident.other)
}

/// The rigid-body consequences of a given P for one sphere on a wall (physics.md): with
/// `u0 = v_x0 + R ω0`, `v_x = v̄_x + P u0 κ/(1+κ)` and `ω = ω̄ + P u0/(R (1+κ))`, where
/// `(v̄_x, ω̄)` is the rolling motion (`u = 0`) with the same angular momentum about the contact
/// point; and `ΔE = (m_t/2) u0² (P² − 1)` with `m_t = m κ/(1+κ)`.
#[test]
fn rigid_body_kinematics_of_p_on_a_wall() {
    let wall = Elastic {
        youngs_modulus: 70e9,
        poisson_ratio: 0.33,
    };
    for &(kappa, omega0) in &[(0.4, 0.0), (0.4, 25.0), (2.0 / 3.0, -40.0)] {
        let (mut s, steel_material) = steel(0.01);
        s.kappa = kappa;
        let (m, r) = (s.mass, s.radius);
        let i = s.inertia();
        let v_x0 = 0.8;
        let imp = PhysicalImpact::sphere_on_wall(
            (s, steel_material),
            wall,
            State {
                v_x: v_x0,
                v_z: 1.0,
                omega: omega0,
            },
            0.25,
        );
        let out = imp.simulate(res2(512)).unwrap();
        let p = out.p.unwrap();
        let u0 = v_x0 + r * omega0;
        // Rolling solution (u = 0) with the same angular momentum about the contact point.
        let l = i * omega0 - m * r * v_x0;
        let v_roll = -l / (m * r + i / r);
        let w_roll = -v_roll / r;
        let v_x = v_roll + p * u0 * kappa / (1.0 + kappa);
        let w = w_roll + p * u0 / (r * (1.0 + kappa));
        let what = format!("kappa = {kappa}, omega0 = {omega0}");
        assert_rel(
            out.sphere.v_x,
            v_x,
            v_x0.abs() + (r * omega0).abs(),
            1e-12,
            &what,
        );
        assert_rel(
            out.sphere.omega * r,
            w * r,
            v_x0.abs() + (r * omega0).abs(),
            1e-12,
            &what,
        );
        if kappa == 0.4 && omega0 == 0.0 {
            // Solid sphere without spin: e_t = (2P + 5)/7, ω = 5 v_x0 (P − 1)/(7R).
            assert_rel(
                out.sphere.v_x / v_x0,
                regimes::tangential_restitution(p),
                1.0,
                1e-12,
                &what,
            );
            let w7 = 5.0 * v_x0 * (p - 1.0) / (7.0 * r);
            assert_rel(out.sphere.omega, w7, (v_x0 / r).abs(), 1e-12, &what);
        }
        // Tangential kinetic energy: ΔE = (m_t/2) u0² (P² − 1), m_t = m κ/(1+κ).
        let e = |mo: &State| 0.5 * m * mo.v_x * mo.v_x + 0.5 * i * mo.omega * mo.omega;
        let m_t = m * kappa / (1.0 + kappa);
        let de = e(&out.sphere) - e(&imp.incident.sphere);
        assert_rel(
            de,
            0.5 * m_t * u0 * u0 * (p * p - 1.0),
            e(&imp.incident.sphere),
            1e-12,
            &what,
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 6. u0 = 0 and mirror symmetry.
// ---------------------------------------------------------------------------------------------

fn u0_zero_cases() -> Vec<PhysicalImpact> {
    let mut s1 = steel(0.5);
    s1.0.mass = 3.0;
    let mut s2 = glass(0.25);
    s2.0.mass = 0.75;
    vec![
        PhysicalImpact::sphere_on_wall(
            s1,
            glass(1.0).1,
            // u = 1 + 0.5 (−2) = 0 exactly.
            State {
                v_x: 1.0,
                v_z: 2.0,
                omega: -2.0,
            },
            0.4,
        ),
        PhysicalImpact::sphere_on_sphere(
            s1,
            State {
                v_x: 1.0,
                v_z: 2.0,
                omega: -2.0,
            },
            // Sphere 2's contact point moves at v_x − R ω = 0.25 − 0.25 = 0 as well.
            s2,
            State {
                v_x: 0.25,
                v_z: -1.0,
                omega: 1.0,
            },
            0.4,
        ),
    ]
}

#[test]
fn pure_normal_impact_leaves_tangential_motion_unchanged() {
    for imp in u0_zero_cases() {
        let g = imp.groups().unwrap();
        assert_eq!(g.slip_velocity, 0.0);
        for out in [imp.simulate(res2(512)).unwrap(), imp.solve(1e-6).unwrap()] {
            assert_eq!(out.p, None);
            assert_eq!(out.error_estimate, 0.0);
            assert_rel(out.sphere.v_x, imp.incident.sphere.v_x, 1.0, 1e-12, "v_x");
            assert_rel(
                out.sphere.omega,
                imp.incident.sphere.omega,
                2.0,
                1e-12,
                "omega",
            );
            if let (Some(_), Some(o)) = (&imp.pair.other, out.other) {
                let m = &imp.incident.other;
                assert_rel(o.v_x, m.v_x, m.v_x.abs(), 1e-12, "v_x2");
                assert_rel(o.omega, m.omega, m.omega.abs(), 1e-12, "omega2");
            }
            check_normal(&imp, &out, "u0 = 0");
        }
    }
}

fn mirror(m: &State) -> State {
    State {
        v_x: -m.v_x,
        v_z: m.v_z,
        omega: -m.omega,
    }
}

#[test]
fn negative_slip_mirrors_positive_slip() {
    let mut rng = XorShift(0xD1B5_4A32_D192_ED03);
    for i in 0..8 {
        let imp = random_impact(&mut rng, i);
        let mirrored = PhysicalImpact {
            incident: Incident {
                sphere: mirror(&imp.incident.sphere),
                other: match imp.pair.other {
                    None => imp.incident.other,
                    Some(_) => mirror(&imp.incident.other),
                },
            },
            ..imp
        };
        let (a, b) = (
            imp.simulate(res2(256)).unwrap(),
            mirrored.simulate(res2(256)).unwrap(),
        );
        let (ga, gb) = (imp.groups().unwrap(), mirrored.groups().unwrap());
        assert_eq!(gb.slip_velocity, -ga.slip_velocity);
        assert_eq!(gb.alpha, ga.alpha);
        let what = format!("case {i}");
        let pa = a.p.unwrap();
        assert_rel(b.p.unwrap(), pa, pa.abs().max(1e-3), 1e-12, &what);
        let (_, scale) = slip(&imp, &imp.incident.sphere, imp_other_motion(&imp).as_ref());
        let check = |x: &State, y: &State, r: f64| {
            assert_rel(y.v_x, -x.v_x, scale, 1e-12, &what);
            assert_rel(y.omega * r, -x.omega * r, scale, 1e-12, &what);
            assert_rel(y.v_z, x.v_z, x.v_z.abs(), 1e-12, &what);
        };
        check(&a.sphere, &b.sphere, imp.pair.sphere.radius);
        if let (Some(o), Some(x), Some(y)) = (&imp.pair.other, a.other, b.other) {
            check(&x, &y, o.radius);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 7. Input validation.
// ---------------------------------------------------------------------------------------------

fn invalid_name<T: std::fmt::Debug>(r: Result<T, PhysicsError>) -> &'static str {
    match r {
        Err(PhysicsError::InvalidParameter { name, .. }) => name,
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

/// The field named by a physical input refused by the rebound algebra's check.
fn invalid_input_name<T: std::fmt::Debug>(r: Result<T, PhysicsError>) -> &'static str {
    match r {
        Err(PhysicsError::Input(e)) => e.name,
        other => panic!("expected Input, got {other:?}"),
    }
}

#[test]
fn invalid_parameters_are_rejected_with_their_name() {
    let ok = res2(64);
    for g in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            invalid_name(Request::new(g, 0.5).scheme(ACC).simulate(ok)),
            "gamma",
            "gamma = {g}"
        );
        assert_eq!(
            invalid_name(
                Request::new(g, 0.5)
                    .accuracy(Accuracy::Tolerance(1e-6))
                    .scheme(ACC)
                    .solve()
            ),
            "gamma"
        );
    }
    for a in [-0.1, -1e-300, f64::NAN, f64::NEG_INFINITY] {
        assert_eq!(
            invalid_name(Request::new(1.754, a).scheme(ACC).simulate(ok)),
            "alpha",
            "alpha = {a}"
        );
        assert_eq!(
            invalid_name(
                Request::new(1.754, a)
                    .accuracy(Accuracy::Tolerance(1e-6))
                    .scheme(ACC)
                    .solve()
            ),
            "alpha"
        );
    }
    // springs = 0 is the continuum row of the accurate scheme; Euler needs real springs.
    assert_eq!(
        invalid_name(
            Request::new(1.754, 1.0)
                .scheme(Scheme::Euler)
                .simulate(res(0, 64))
        ),
        "springs"
    );
    for scheme in [Scheme::Accurate, Scheme::Euler] {
        assert_eq!(
            invalid_name(Request::new(1.754, 1.0).scheme(scheme).simulate(res(1, 64))),
            "springs"
        );
        assert_eq!(
            invalid_name(Request::new(1.754, 1.0).scheme(scheme).simulate(res(64, 0))),
            "steps"
        );
    }
    assert_eq!(
        invalid_name(
            Request::new(1.754, 1.0)
                .accuracy(Accuracy::Fixed(res(1, 64)))
                .scheme(ACC)
                .forced(true)
                .solve()
        ),
        "springs"
    );
    for tol in [0.0, -1e-6, f64::NAN, f64::INFINITY] {
        // α = 1 at γ = 1.754 has no closed form: the tolerance is used.
        assert_eq!(
            invalid_name(
                Request::new(1.754, 1.0)
                    .accuracy(Accuracy::Tolerance(tol))
                    .scheme(ACC)
                    .solve()
            ),
            "tol",
            "tol = {tol}"
        );
    }
    // Physical inputs.
    let base = PhysicalImpact::sphere_on_wall(
        steel(0.01),
        glass(1.0).1,
        State {
            v_x: 0.5,
            v_z: 1.0,
            omega: 0.0,
        },
        0.3,
    );
    let mut bad = base;
    bad.pair.sphere.radius = 0.0;
    assert_eq!(invalid_input_name(bad.groups()), "radius");
    let mut bad = base;
    bad.friction = f64::NAN;
    assert_eq!(invalid_input_name(bad.simulate(ok)), "friction");
    let mut bad = base;
    bad.incident.sphere.v_z = -1.0;
    assert_eq!(invalid_input_name(bad.solve(1e-6)), "v_z");
    let mut bad = base;
    bad.materials[0].poisson_ratio = 0.7;
    assert_eq!(invalid_input_name(bad.groups()), "poisson_ratio");
    assert_eq!(invalid_name(base.solve(0.0)), "tol");
    assert_eq!(invalid_name(base.simulate(res(1, 64))), "springs");
}

/// An invalid accuracy request is invalid whatever (γ, α) is: a closed-form answer must not
/// make `tol = 0` or `springs = 0` acceptable.
#[test]
fn invalid_accuracy_is_rejected_in_the_closed_form_region_too() {
    let (g, a) = (1.754, 0.1); // on the full-slip line: closed form
    assert!(closed_form(g, a).is_some());
    for tol in [0.0, -1e-6, f64::NAN] {
        assert_eq!(
            invalid_name(
                Request::new(g, a)
                    .accuracy(Accuracy::Tolerance(tol))
                    .scheme(ACC)
                    .solve()
            ),
            "tol",
            "tol = {tol}"
        );
    }
    assert_eq!(
        invalid_name(
            Request::new(g, a)
                .accuracy(Accuracy::Fixed(res(1, 64)))
                .scheme(ACC)
                .solve()
        ),
        "springs"
    );
}
