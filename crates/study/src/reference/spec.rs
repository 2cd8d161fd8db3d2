//! The tests of each suite: bodies, materials, friction and the swept impact conditions, with
//! where every number comes from. Plain data; [`super::eval`] computes them.

use oblique_lookup::rebound::{Body, Elastic, Incident, Pair, State};

use super::measured::{self, Measured};

/// A material of a reference test: elastic constants and density as the suite publishes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Name used in the CSV's `material` column.
    pub name: &'static str,
    /// Young's modulus `E` (Pa); `∞` for a rigid plane.
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`.
    pub poisson_ratio: f64,
    /// Density `ρ` (kg/m³); NaN for a rigid plane.
    pub density: f64,
}

impl Material {
    /// The elastic constants.
    pub fn elastic(&self) -> Elastic {
        Elastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }
}

/// The rigid plane of Chung & Ooi's wall tests and Thornton's: adds no compliance.
pub const RIGID: Material = Material {
    name: "rigid",
    youngs_modulus: f64::INFINITY,
    poisson_ratio: 0.0,
    density: f64::NAN,
};

/// A solid sphere (`I = (2/5) m R²`) of a material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball {
    /// Its material.
    pub material: Material,
    /// Radius `R` (m).
    pub radius: f64,
}

impl Ball {
    /// Mass `(4/3)πR³ρ` (kg), inertia factor `κ = 2/5`.
    pub fn body(&self) -> Body {
        Body {
            mass: 4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3) * self.material.density,
            radius: self.radius,
            kappa: 0.4,
        }
    }
}

/// What sphere 1 hits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A fixed half-space of a material ([`RIGID`] for a rigid plane).
    Wall(Material),
    /// A free sphere.
    Sphere(Ball),
}

/// The limiting contact pressure of Thornton's elastic–perfectly plastic law for a setup
/// (`physics.md`, "Elastic–plastic impacts"), with where it comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YieldPressure {
    /// Limiting contact pressure `p_y` (Pa), > 0.
    pub pascal: f64,
    /// Where the value comes from, in words (the CSV's header lines).
    pub source: &'static str,
}

/// One impact configuration of a test: the bodies, their materials and the friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Label of this configuration in the CSV's `material` column.
    pub label: &'static str,
    /// Sphere 1.
    pub sphere: Ball,
    /// The wall or sphere 2.
    pub target: Target,
    /// Coulomb friction coefficient `μ`.
    pub friction: f64,
    /// The limiting pressure of Thornton's law (`None`: the test's elastic or Kelvin–Voigt
    /// law). With one, each case's `e_n` follows from `p_y` and its normal speed.
    pub yield_pressure: Option<YieldPressure>,
}

impl Setup {
    /// The pair of bodies of the rebound algebra.
    pub fn pair(&self) -> Pair {
        Pair {
            sphere: self.sphere.body(),
            other: match self.target {
                Target::Wall(_) => None,
                Target::Sphere(b) => Some(b.body()),
            },
        }
    }

    /// Elastic constants of sphere 1 and of the target.
    pub fn materials(&self) -> [Elastic; 2] {
        let t = match self.target {
            Target::Wall(m) => m,
            Target::Sphere(b) => b.material,
        };
        [self.sphere.material.elastic(), t.elastic()]
    }

    /// Whether the target is a sphere.
    pub fn sphere_sphere(&self) -> bool {
        matches!(self.target, Target::Sphere(_))
    }

    /// The same bodies with Thornton's law of limiting pressure `p_y`.
    pub fn with_yield(self, yield_pressure: YieldPressure) -> Setup {
        Setup {
            yield_pressure: Some(yield_pressure),
            ..self
        }
    }
}

/// One case of a sweep: the swept value and the incident state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// The swept value, in the unit of the test's `x` column.
    pub x: f64,
    /// Both bodies' motion before the impact (m/s, rad/s; physics.md's convention).
    pub incident: Incident,
}

/// The quantities a suite reports for an oblique test, in the suite's own conventions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Convention {
    /// Chung & Ooi test 4: `e_t` of the centre, `ω'`, the contact-point rebound angle.
    ChungOoiAngle,
    /// Chung & Ooi test 5: normalised recoil angle `V'_st/(μ V'_cn)` and spin `R ω'/(μ V_cn)`
    /// against the normalised incident angle `V_st/(μ V_cn)`.
    ChungOoiNormalised,
    /// Chung & Ooi tests 6 and 8: `β = −V'_st/V_st` against `3.5 μ (1 + e) V_cn/V_st`, and
    /// `tan` of the contact-point recoil angle against that of the incidence.
    ChungOoiSpin,
    /// Chung & Ooi test 7: final tangential centre velocity and spin against the initial spin.
    ChungOoiNoSlip,
    /// MFIX DEM05: the centre's rebound angle `atan(|v'_t|/v'_n)`, `e_t = |v'_t|/|v_t|`, `|ω'|`.
    Mfix,
    /// Seed 000, Fig. 5: `e_t` and `ω'` against the incidence angle, with the seed's slip angle.
    Seed000,
    /// Thornton's normalised velocities `Ψ₁`, `Ψ₂` and spin `Ω₂ = 2Rω'/(μ(1+e)V_n)`.
    Thornton,
}

/// A test whose impacts have a tangential part.
#[derive(Debug, Clone, PartialEq)]
pub struct ObliqueTest {
    /// File stem (`chung_ooi_test4_angle`).
    pub id: &'static str,
    /// Title, as the suite names the test.
    pub title: &'static str,
    /// Where the parameters come from.
    pub source: &'static str,
    /// What of the published test lies outside the elastic model, and what is computed instead.
    pub elastic_note: &'static str,
    /// Name and unit of the swept column (`angle_deg`).
    pub x_name: &'static str,
    /// Axis label of the swept value.
    pub x_label: &'static str,
    /// The configurations (one per material), each with its cases.
    pub setups: Vec<(Setup, Vec<Case>)>,
    /// Quantities and conventions.
    pub convention: Convention,
    /// Measured points to overlay, if the suite publishes some.
    pub measured: Option<&'static Measured>,
    /// Normal restitution of every case: 1 (elastic), or the `e_n < 1` a damped test
    /// publishes, computed with the Kelvin–Voigt law (`physics.md`, "Dissipative impacts").
    /// 1 for an elastic–plastic test, whose setups carry a limiting pressure instead.
    pub e_n: f64,
}

impl ObliqueTest {
    /// Whether the test is elastic–plastic (Thornton's law): its setups carry `p_y`.
    pub fn plastic(&self) -> bool {
        self.setups.iter().any(|(s, _)| s.yield_pressure.is_some())
    }
}

/// A normal-impact test (contact time, peak force, peak overlap).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalTest {
    /// File stem.
    pub id: &'static str,
    /// Title.
    pub title: &'static str,
    /// Where the parameters come from.
    pub source: &'static str,
    /// What lies outside the elastic model.
    pub elastic_note: &'static str,
    /// One configuration per material, each with its approach state.
    pub setups: Vec<(Setup, Incident)>,
}

/// A test of a suite.
#[derive(Debug, Clone, PartialEq)]
pub enum Test {
    /// Normal impact.
    Normal(NormalTest),
    /// Oblique impact or spin.
    Oblique(ObliqueTest),
}

impl Test {
    /// File stem.
    pub fn id(&self) -> &'static str {
        match self {
            Test::Normal(t) => t.id,
            Test::Oblique(t) => t.id,
        }
    }
}

/// The suites.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Suite {
    /// Chung & Ooi (2011), tests 1–8.
    ChungOoi,
    /// MFIX's DEM05: Kharaz, Gorham & Salman (2001), alumina on soda-lime glass.
    MfixDem05,
    /// Thornton, Cummins & Cleary's normalised diagrams, elastic and elastic–plastic.
    Thornton,
    /// Seed 000's Fig. 5: the Gorham–Kharaz alumina sphere on glass with the seed's constants.
    Seed000,
}

impl Suite {
    /// Every suite, in the order `all` runs them.
    pub const ALL: [Suite; 4] = [
        Suite::ChungOoi,
        Suite::MfixDem05,
        Suite::Thornton,
        Suite::Seed000,
    ];

    /// Name on the command line and of the output folder.
    pub fn name(self) -> &'static str {
        match self {
            Suite::ChungOoi => "chung-ooi",
            Suite::MfixDem05 => "mfix-dem05",
            Suite::Thornton => "thornton",
            Suite::Seed000 => "seed000",
        }
    }

    /// Parse a suite name.
    pub fn from_name(name: &str) -> Option<Suite> {
        Suite::ALL.into_iter().find(|s| s.name() == name)
    }

    /// One line on what the suite is.
    pub fn describe(self) -> &'static str {
        match self {
            Suite::ChungOoi => {
                "Chung & Ooi (2011), Granular Matter 13:643-656, tests 1-8 (Kratos, Yade, PySPH)"
            }
            Suite::MfixDem05 => {
                "MFIX DEM05: Kharaz, Gorham & Salman (2001) alumina sphere on soda-lime glass"
            }
            Suite::Thornton => {
                "Thornton, Cummins & Cleary normalised oblique impact, elastic and elastic-plastic (psi_1, psi_2)"
            }
            Suite::Seed000 => {
                "seed 000 (Lyashenko, Willert & Popov), Fig. 5: Gorham-Kharaz alumina on glass"
            }
        }
    }

    /// The suite's tests.
    pub fn tests(self) -> Vec<Test> {
        match self {
            Suite::ChungOoi => chung_ooi(),
            Suite::MfixDem05 => vec![Test::Oblique(mfix_dem05())],
            Suite::Thornton => thornton(),
            Suite::Seed000 => vec![Test::Oblique(seed000())],
        }
    }
}

fn wall(sphere: Ball, wall: Material, friction: f64, label: &'static str) -> Setup {
    Setup {
        label,
        sphere,
        target: Target::Wall(wall),
        friction,
        yield_pressure: None,
    }
}

fn state(v_x: f64, v_z: f64, omega: f64) -> State {
    State { v_x, v_z, omega }
}

fn on_wall(motion: State) -> Incident {
    Incident {
        sphere: motion,
        other: State::default(),
    }
}

/// `from, from + step, …, to` (inclusive, exact multiples of the step).
fn steps(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|i| from + step * i as f64).collect()
}

/// Angles from the normal at a fixed speed, no spin, on a wall.
fn angle_cases(speed: f64, angles_deg: &[f64]) -> Vec<Case> {
    angles_deg
        .iter()
        .map(|&a| {
            let t = a.to_radians();
            Case {
                x: a,
                incident: on_wall(state(speed * t.sin(), speed * t.cos(), 0.0)),
            }
        })
        .collect()
}

const CO_SOURCE: &str = "Chung & Ooi (2011), Granular Matter 13:643-656; parameters as \
    re-implemented in Kratos DEMApplication (DEM_benchmarks_class.py and its test data) and the \
    Yade benchmark scripts of Angelidakis, Chareyre & Caulk (2023)";

/// Where test 4 elastic–plastic, its law and its limiting pressures come from.
const CO_PLASTIC_SOURCE: &str = "Chung & Ooi (2011), Granular Matter 13:643-656, test 4 \
    (parameters as re-implemented in Kratos DEMApplication and Yade, as the elastic test 4); \
    the law and V_y: Thornton (1997), J. Appl. Mech. 64:383-386; first yield of a Hertz \
    contact at p_0 = 1.60 Y: Johnson (1985), Contact Mechanics, Cambridge University Press, \
    chapter 6; Y = 276 MPa of aluminium 6061-T6: ASM Aerospace Specification Metals data sheet \
    'Aluminum 6061-T6; 6061-T651' (MatWeb)";

/// The catalogue's limiting pressure of aluminium 6061-T6, `1.60 Y` (Pa).
fn aluminium_6061_limiting_pressure() -> f64 {
    oblique_physics::materials::find("aluminium-6061-t6")
        .and_then(|m| m.limiting_pressure())
        .unwrap_or(f64::NAN)
}

// Chung & Ooi's materials (as given by the re-implementations named in CO_SOURCE).
const GLASS: Material = Material {
    name: "glass",
    youngs_modulus: 4.8e10,
    poisson_ratio: 0.20,
    density: 2800.0,
};
const LIMESTONE: Material = Material {
    name: "limestone",
    youngs_modulus: 2.0e10,
    poisson_ratio: 0.25,
    density: 2500.0,
};
/// The aluminium alloy of test 2 (`ν = 0.30`, `ρ = 2699`).
const AL_ALLOY_T2: Material = Material {
    name: "aluminium alloy",
    youngs_modulus: 7.0e10,
    poisson_ratio: 0.30,
    density: 2699.0,
};
/// The aluminium alloy of tests 4, 6–8 (`ν = 0.33`, `ρ = 2700`).
const AL_ALLOY: Material = Material {
    name: "aluminium alloy",
    youngs_modulus: 7.0e10,
    poisson_ratio: 0.33,
    density: 2700.0,
};
const MG_ALLOY: Material = Material {
    name: "magnesium alloy",
    youngs_modulus: 4.0e10,
    poisson_ratio: 0.35,
    density: 1800.0,
};
const AL_OXIDE: Material = Material {
    name: "aluminium oxide",
    youngs_modulus: 3.8e11,
    poisson_ratio: 0.23,
    density: 4000.0,
};
const CAST_IRON: Material = Material {
    name: "cast iron",
    youngs_modulus: 1.0e11,
    poisson_ratio: 0.25,
    density: 7000.0,
};
const STEEL: Material = Material {
    name: "steel",
    youngs_modulus: 2.08e11,
    poisson_ratio: 0.30,
    density: 7850.0,
};
const POLYETHYLENE: Material = Material {
    name: "polyethylene",
    youngs_modulus: 1.0e9,
    poisson_ratio: 0.40,
    density: 1400.0,
};
const NYLON: Material = Material {
    name: "nylon",
    youngs_modulus: 2.5e9,
    poisson_ratio: 0.40,
    density: 1000.0,
};
const COPPER: Material = Material {
    name: "copper",
    youngs_modulus: 1.2e11,
    poisson_ratio: 0.35,
    density: 8900.0,
};

/// Chung & Ooi's incidence angles: 5° to 85° in steps of 5°.
fn co_angles() -> Vec<f64> {
    steps(5.0, 85.0, 5.0)
}

/// Spheres of `radius` (m), one per material, approaching a rigid plane head-on at `speed`
/// (m/s): the setups of Chung & Ooi's tests 2 and 3.
fn on_rigid_plane(materials: [Material; 2], radius: f64, speed: f64) -> Vec<(Setup, Incident)> {
    materials
        .into_iter()
        .map(|m| {
            let sphere = Ball {
                material: m,
                radius,
            };
            (
                wall(sphere, RIGID, 0.0, m.name),
                on_wall(state(0.0, speed, 0.0)),
            )
        })
        .collect()
}

fn chung_ooi() -> Vec<Test> {
    let ball = |m: Material, r: f64| Ball {
        material: m,
        radius: r,
    };
    // Test 1: two identical spheres approaching at 10 m/s each.
    let t1 = NormalTest {
        id: "chung_ooi_test1_normal_sphere_sphere",
        title: "Test 1: elastic normal impact of two identical spheres",
        source: CO_SOURCE,
        elastic_note: "elastic as published (e_n = 1)",
        setups: [GLASS, LIMESTONE]
            .into_iter()
            .map(|m| {
                let b = ball(m, 0.010);
                (
                    Setup {
                        label: m.name,
                        sphere: b,
                        target: Target::Sphere(b),
                        friction: 0.35,
                        yield_pressure: None,
                    },
                    Incident {
                        sphere: state(0.0, 10.0, 0.0),
                        other: state(0.0, -10.0, 0.0),
                    },
                )
            })
            .collect(),
    };
    let t2 = NormalTest {
        id: "chung_ooi_test2_normal_sphere_wall",
        title: "Test 2: elastic normal impact of a sphere with a rigid plane",
        source: CO_SOURCE,
        elastic_note: "elastic as published (e_n = 1)",
        setups: on_rigid_plane([AL_ALLOY_T2, MG_ALLOY], 0.10, 0.2),
    };
    let t3 = NormalTest {
        id: "chung_ooi_test3_normal_restitution",
        title: "Test 3: normal impact of a sphere with a rigid plane, different restitution",
        source: CO_SOURCE,
        elastic_note: "the published test sweeps the coefficient of restitution (viscous \
            damping); the elastic model gives its e_n = 1 limit only",
        setups: on_rigid_plane([AL_OXIDE, CAST_IRON], 0.0025, 3.9),
    };
    let t4 = ObliqueTest {
        id: "chung_ooi_test4_angle",
        title: "Test 4: oblique impact on a rigid plane, constant speed 3.9 m/s, varying angle",
        source: CO_SOURCE,
        elastic_note: "the published test uses e_n = 0.98 (viscous damping); this is its \
            elastic limit e_n = 1",
        x_name: "angle_deg",
        x_label: "incidence angle θ from the normal (°)",
        setups: [AL_OXIDE, AL_ALLOY]
            .into_iter()
            .map(|m| {
                (
                    wall(ball(m, 0.0025), RIGID, 0.092, m.name),
                    angle_cases(3.9, &co_angles()),
                )
            })
            .collect(),
        convention: Convention::ChungOoiAngle,
        measured: Some(&measured::KHARAZ_KRATOS),
        e_n: 1.0,
    };
    let t5 = ObliqueTest {
        id: "chung_ooi_test5_tangential_speed",
        title:
            "Test 5: oblique impact on a rigid plane, normal speed 5 m/s, varying tangential speed",
        source: CO_SOURCE,
        elastic_note: "elastic as published (e_n = 1)",
        x_name: "incident_normalised",
        x_label: "normalised incident angle V_st/(μ V_cn)",
        setups: [STEEL, POLYETHYLENE]
            .into_iter()
            .map(|m| {
                let s = wall(ball(m, 1e-5), RIGID, 0.3, m.name);
                let cases = co_angles()
                    .into_iter()
                    .map(|a| {
                        let vt = 5.0 * a.to_radians().tan();
                        Case {
                            x: vt / (0.3 * 5.0),
                            incident: on_wall(state(vt, 5.0, 0.0)),
                        }
                    })
                    .collect();
                (s, cases)
            })
            .collect(),
        convention: Convention::ChungOoiNormalised,
        measured: None,
        e_n: 1.0,
    };
    // Tests 6 and 8: a spinning sphere without tangential centre velocity; the contact point's
    // incidence angle is swept, V_st = V_n tan θ.
    let spin_cases = |r: f64| -> Vec<Case> {
        co_angles()
            .into_iter()
            .map(|a| {
                let vst = 0.2 * a.to_radians().tan();
                Case {
                    x: a,
                    incident: on_wall(state(0.0, 0.2, vst / r)),
                }
            })
            .collect()
    };
    let t6 = ObliqueTest {
        id: "chung_ooi_test6_spin_wall",
        title: "Test 6: impact of a spinning sphere on a rigid plane, normal speed 0.2 m/s",
        source: CO_SOURCE,
        elastic_note: "the published test uses e_n = 0.5 (viscous damping); this is its \
            elastic limit e_n = 1",
        x_name: "angle_deg",
        x_label: "contact-point incidence angle atan(V_st/V_cn) (°)",
        setups: [AL_ALLOY, NYLON]
            .into_iter()
            .map(|m| (wall(ball(m, 0.10), RIGID, 0.4, m.name), spin_cases(0.10)))
            .collect(),
        convention: Convention::ChungOoiSpin,
        measured: None,
        e_n: 1.0,
    };
    let t7 = ObliqueTest {
        id: "chung_ooi_test7_equal_spins",
        title: "Test 7: two identical spheres, normal speed 0.2 m/s each, equal and opposite spins",
        source: CO_SOURCE,
        elastic_note: "the published test uses e_n = 0.5 (viscous damping); this is its \
            elastic limit e_n = 1. The contact points move together (no slip): nothing \
            tangential happens, whatever the friction",
        x_name: "omega0_rad_s",
        x_label: "initial spin ω₀ (rad/s)",
        setups: [AL_ALLOY, COPPER]
            .into_iter()
            .map(|m| {
                let b = ball(m, 0.10);
                let s = Setup {
                    label: m.name,
                    sphere: b,
                    target: Target::Sphere(b),
                    friction: 0.4,
                    yield_pressure: None,
                };
                let cases = co_angles()
                    .into_iter()
                    .map(|a| {
                        let w = 2.0 * a.to_radians().tan();
                        Case {
                            x: w,
                            incident: Incident {
                                sphere: state(0.0, 0.2, w),
                                other: state(0.0, -0.2, -w),
                            },
                        }
                    })
                    .collect();
                (s, cases)
            })
            .collect(),
        convention: Convention::ChungOoiNoSlip,
        measured: None,
        e_n: 1.0,
    };
    let t8 = ObliqueTest {
        id: "chung_ooi_test8_spin_sphere",
        title: "Test 8: a spinning sphere (R = 0.1 m) on a resting sphere of R = 0.5 m, 0.2 m/s",
        source: CO_SOURCE,
        elastic_note: "the published test uses e_n = 0.5 (viscous damping); this is its \
            elastic limit e_n = 1. Sphere 2 is free and of the same material as sphere 1 \
            (re-implementations also run it nearly rigid and immovable, which is test 6)",
        x_name: "angle_deg",
        x_label: "contact-point incidence angle atan(V_st/V_cn) (°)",
        setups: [AL_ALLOY, NYLON]
            .into_iter()
            .map(|m| {
                let s = Setup {
                    label: m.name,
                    sphere: ball(m, 0.10),
                    target: Target::Sphere(ball(m, 0.50)),
                    friction: 0.4,
                    yield_pressure: None,
                };
                (s, spin_cases(0.10))
            })
            .collect(),
        convention: Convention::ChungOoiSpin,
        measured: None,
        e_n: 1.0,
    };
    // Test 4 as published, damped to e_n = 0.98, by the Kelvin–Voigt law.
    let t4_damped = ObliqueTest {
        id: "chung_ooi_test4_angle_damped",
        title: "Test 4 damped (e_n = 0.98, Kelvin-Voigt): rigid plane, 3.9 m/s, varying angle",
        elastic_note: "damped as published, e_n = 0.98 in every case, by the Kelvin-Voigt law \
            (one relaxation time in the normal and tangential springs, physics.md \
            \"Dissipative impacts\"); Chung & Ooi's DEM and its re-implementations damp by \
            other laws (a viscous dashpot giving a constant e_n), which give another P at the \
            same e_n",
        e_n: 0.98,
        ..t4.clone()
    };
    // Test 4 elastic-plastic, by Thornton's law: aluminium oxide at the p_y that gives the
    // published e_n = 0.98 at 3.9 m/s (head-on), the aluminium alloy at 6061-T6's 1.60 Y.
    let t4_plastic = ObliqueTest {
        id: "chung_ooi_test4_angle_plastic",
        title: "Test 4 elastic-plastic (Thornton's law): rigid plane, 3.9 m/s, varying angle",
        source: CO_PLASTIC_SOURCE,
        elastic_note: "elastic-perfectly plastic, Thornton's law (physics.md \"Elastic-plastic \
            impacts\"): Hertz up to the limiting pressure p_y, the pressure capped at p_y \
            beyond; e_n follows from p_y and each case's normal speed 3.9 cos(theta) m/s \
            (Thornton's closed form of V_y/V, 1 at or below the yield speed V_y). Aluminium \
            oxide (brittle, no yield stress): p_y chosen so that Thornton's e_n equals the \
            published 0.98 at 3.9 m/s head-on. Aluminium alloy: p_y = 1.60 Y, Y = 276 MPa of \
            6061-T6 (the catalogue's aluminium-6061-t6), the peak Hertz pressure at first yield",
        setups: t4
            .setups
            .iter()
            .map(|(s, c)| {
                let p_y = if s.sphere.material == AL_OXIDE {
                    YieldPressure {
                        pascal: super::eval::yield_pressure_for_restitution(s, 3.9, 0.98),
                        source: "chosen so that Thornton's e_n equals the published 0.98 at \
                                 3.9 m/s head-on",
                    }
                } else {
                    YieldPressure {
                        pascal: aluminium_6061_limiting_pressure(),
                        source: "1.60 Y, Y = 276 MPa of aluminium 6061-T6",
                    }
                };
                (s.with_yield(p_y), c.clone())
            })
            .collect(),
        ..t4.clone()
    };
    let damped_half = |t: &ObliqueTest, id: &'static str, title: &'static str| ObliqueTest {
        id,
        title,
        elastic_note: "damped as published, e_n = 0.5 in every case, by the Kelvin-Voigt law \
            (one relaxation time in the normal and tangential springs, physics.md \
            \"Dissipative impacts\"); Chung & Ooi's DEM and its re-implementations damp by \
            other laws (a viscous dashpot giving a constant e_n), which give another P at the \
            same e_n",
        e_n: 0.5,
        ..t.clone()
    };
    let t6_damped = damped_half(
        &t6,
        "chung_ooi_test6_spin_wall_damped",
        "Test 6 damped (e_n = 0.5, Kelvin-Voigt): a spinning sphere on a rigid plane, 0.2 m/s",
    );
    let t7_damped = damped_half(
        &t7,
        "chung_ooi_test7_equal_spins_damped",
        "Test 7 damped (e_n = 0.5, Kelvin-Voigt): two identical spheres, equal and opposite spins",
    );
    let t8_damped = damped_half(
        &t8,
        "chung_ooi_test8_spin_sphere_damped",
        "Test 8 damped (e_n = 0.5, Kelvin-Voigt): a spinning sphere on a resting sphere, 0.2 m/s",
    );
    vec![
        Test::Normal(t1),
        Test::Normal(t2),
        Test::Normal(t3),
        Test::Oblique(t4),
        Test::Oblique(t4_damped),
        Test::Oblique(t4_plastic),
        Test::Oblique(t5),
        Test::Oblique(t6),
        Test::Oblique(t6_damped),
        Test::Oblique(t7),
        Test::Oblique(t7_damped),
        Test::Oblique(t8),
        Test::Oblique(t8_damped),
    ]
}

const MFIX_ALUMINA: Material = Material {
    name: "alumina",
    youngs_modulus: 380e9,
    poisson_ratio: 0.23,
    density: 4000.0,
};
const MFIX_GLASS: Material = Material {
    name: "soda-lime glass",
    youngs_modulus: 70e9,
    poisson_ratio: 0.25,
    density: 2500.0,
};

fn mfix_dem05() -> ObliqueTest {
    let mut angles = steps(0.0, 2.5, 0.5);
    angles.extend(steps(5.0, 65.0, 2.5));
    ObliqueTest {
        id: "mfix_dem05_angle",
        title: "DEM05: alumina sphere (d = 5 mm) on soda-lime glass, 3.9 m/s, varying angle",
        source: "MFIX verification case DEM05 after Kharaz, Gorham & Salman (2001), Powder \
            Technol. 120:281-291; parameters from MFIX's tests/dem/DEM05/mfix.dat",
        elastic_note: "elastic as published (DES_EN_WALL_INPUT = 1)",
        x_name: "angle_deg",
        x_label: "incidence angle θ from the normal (°)",
        setups: vec![(
            wall(
                Ball {
                    material: MFIX_ALUMINA,
                    radius: 2.5e-3,
                },
                MFIX_GLASS,
                0.092,
                "alumina on glass",
            ),
            angle_cases(3.9, &angles),
        )],
        convention: Convention::Mfix,
        measured: Some(&measured::KHARAZ_MFIX),
        e_n: 1.0,
    }
}

/// Seed 000's constants for the Gorham–Kharaz experiment (section 4).
const SEED_ALUMINA: Material = Material {
    name: "alumina-96",
    youngs_modulus: 370e9,
    poisson_ratio: 0.25,
    density: 3720.0,
};
const SEED_GLASS: Material = Material {
    name: "soda-lime glass",
    youngs_modulus: 73e9,
    poisson_ratio: 0.217,
    density: 2500.0,
};

fn seed000() -> ObliqueTest {
    ObliqueTest {
        id: "seed000_kharaz_angle",
        title: "Seed 000, Fig. 5: alumina sphere on soda-lime glass, 3.9 m/s, varying angle",
        source: "Lyashenko, Willert & Popov (seed 000), section 4; E = 370 GPa, nu = 0.25 \
            (alumina), 73 GPa, 0.217 (glass), mu = 0.092, R = 2.5 mm, 3.9 m/s; density 3720 \
            kg/m^3 (96 % alumina; the seed gives none, and it changes no ratio)",
        elastic_note: "elastic as in the seed",
        x_name: "angle_deg",
        x_label: "incidence angle θ from the normal (°)",
        setups: vec![(
            wall(
                Ball {
                    material: SEED_ALUMINA,
                    radius: 2.5e-3,
                },
                SEED_GLASS,
                0.092,
                "alumina on glass",
            ),
            angle_cases(3.9, &steps(1.0, 89.0, 1.0)),
        )],
        convention: Convention::Seed000,
        measured: Some(&measured::KHARAZ_KRATOS),
        e_n: 1.0,
    }
}

/// The Poisson ratios of Thornton's family of diagrams (a sphere on a rigid plane).
pub const THORNTON_POISSON: [f64; 6] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5];

/// `Ψ₁` values of the Thornton diagrams: 0.05 to 12.
fn psi1_values() -> Vec<f64> {
    let mut v = steps(0.25, 12.0, 0.25);
    v.insert(0, 0.05);
    v
}

fn thornton() -> Vec<Test> {
    const MU: f64 = 0.1;
    const VN: f64 = 5.0;
    let setup = |m: Material| {
        wall(
            Ball {
                material: m,
                radius: 0.025,
            },
            RIGID,
            MU,
            m.name,
        )
    };
    // Ψ₁ = 2 V_t/(μ (1 + e) V_n) with e = 1: V_t = Ψ₁ μ V_n.
    let cases = || -> Vec<Case> {
        psi1_values()
            .into_iter()
            .map(|p| Case {
                x: p,
                incident: on_wall(state(p * MU * VN, VN, 0.0)),
            })
            .collect()
    };
    let names = [
        "nu = 0.0", "nu = 0.1", "nu = 0.2", "nu = 0.3", "nu = 0.4", "nu = 0.5",
    ];
    let family = THORNTON_POISSON
        .iter()
        .zip(names)
        .map(|(&nu, name)| {
            (
                setup(Material {
                    name,
                    youngs_modulus: 7.0e10,
                    poisson_ratio: nu,
                    density: 2650.0,
                }),
                cases(),
            )
        })
        .collect();
    let elastic = ObliqueTest {
        id: "thornton_psi",
        title:
            "Thornton's normalised oblique impact: sphere on a rigid plane, V_n = 5 m/s, μ = 0.1",
        source: "Thornton, Cummins & Cleary (2011), Powder Technol. 210:189-197, and (2013) \
            Powder Technol. 233:30-46; Psi = 2 V_t/(mu (1 + e) V_n); R = 25 mm, E = 70 GPa, \
            rho = 2650 kg/m^3, mu = 0.1, V_n = 5 m/s as in Kratos DEMApplication's Thornton \
            benchmarks; Poisson's ratio swept (it sets gamma)",
        elastic_note: "the elastic case e = 1 (the papers also damp the normal contact)",
        x_name: "psi1",
        x_label: "Ψ₁ = 2V_t/(μ(1+e)V_n)",
        setups: family,
        convention: Convention::Thornton,
        measured: None,
        e_n: 1.0,
    };
    // The ν = 0.3 bodies with the catalogue's limiting pressure of aluminium 6061-T6 (E = 68.9
    // GPa, near the bodies' 70 GPa): Ψ₁ = 2 V_t/(μ (1 + e) V_n) with the setup's e. One setup
    // and Ψ₁ in steps of 0.5 keep the suite fast (Thornton's law in stick takes 0.3–2 s a
    // point at e ≈ 0.3).
    let p_y = YieldPressure {
        pascal: aluminium_6061_limiting_pressure(),
        source: "1.60 Y, Y = 276 MPa of aluminium 6061-T6",
    };
    let plastic_setups = elastic
        .setups
        .iter()
        .filter(|(s, _)| s.sphere.material.poisson_ratio == PLASTIC_POISSON)
        .map(|(s, _)| {
            let s = s.with_yield(p_y);
            let e = super::eval::thornton_restitution(&s, p_y.pascal, VN);
            let cases = steps(0.5, 12.0, 0.5)
                .into_iter()
                .map(|p| Case {
                    x: p,
                    incident: on_wall(state(0.5 * p * MU * (1.0 + e) * VN, VN, 0.0)),
                })
                .collect();
            (s, cases)
        })
        .collect();
    let plastic = ObliqueTest {
        id: "thornton_psi_plastic",
        title: "Thornton's normalised oblique impact, elastic-plastic: V_n = 5 m/s, μ = 0.1",
        source: THORNTON_PLASTIC_SOURCE,
        elastic_note: "elastic-perfectly plastic, Thornton's law (physics.md \"Elastic-plastic \
            impacts\"), p_y = 1.60 Y with Y = 276 MPa of aluminium 6061-T6 (the catalogue's \
            aluminium-6061-t6), the peak Hertz pressure at first yield; e_n is Thornton's \
            closed form of V_y/V_n, the same for every case of a setup, and enters \
            Psi = 2 V_t/(mu (1 + e) V_n); nu = 0.3 only (at nu = 0.4 and 0.5 the e_n at 5 m/s \
            is below 0.3, outside the law's range)",
        x_label: "Ψ₁ = 2V_t/(μ(1+e)V_n)",
        setups: plastic_setups,
        ..elastic.clone()
    };
    vec![Test::Oblique(elastic), Test::Oblique(plastic)]
}

/// Poisson's ratio of the elastic–plastic Thornton setup.
const PLASTIC_POISSON: f64 = 0.3;

const THORNTON_PLASTIC_SOURCE: &str = "Thornton, Cummins & Cleary (2011), Powder Technol. \
    210:189-197, and (2013) Powder Technol. 233:30-46 (Psi); bodies as the elastic thornton_psi \
    (Kratos DEMApplication's Thornton benchmarks); the law and V_y: Thornton (1997), J. Appl. \
    Mech. 64:383-386; first yield of a Hertz contact at p_0 = 1.60 Y: Johnson (1985), Contact \
    Mechanics, Cambridge University Press, chapter 6; Y = 276 MPa of aluminium 6061-T6: ASM \
    Aerospace Specification Metals data sheet 'Aluminum 6061-T6; 6061-T651' (MatWeb)";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweeps_hit_their_published_values() {
        assert_eq!(co_angles().len(), 17);
        assert_eq!(co_angles()[16], 85.0);
        let m = mfix_dem05();
        assert_eq!(m.setups[0].1.len(), 31);
        assert_eq!(m.setups[0].1[30].x, 65.0);
        for suite in Suite::ALL {
            assert_eq!(Suite::from_name(suite.name()), Some(suite));
            assert!(!suite.tests().is_empty());
        }
        // Thornton: Ψ₁ = 2 V_t / (μ (1 + e) V_n) with e = 1.
        let Test::Oblique(t) = &thornton()[0] else {
            panic!("oblique")
        };
        let c = t.setups[0].1[5];
        let psi1 = c.incident.sphere.v_x / (0.1 * c.incident.sphere.v_z);
        assert!((psi1 - c.x).abs() < 1e-12);
    }
}
