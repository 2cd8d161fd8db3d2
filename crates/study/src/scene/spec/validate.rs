//! The checks of a scene file: every value against its allowed range, with an error naming
//! the key, and the resolution of materials, bodies, the target and the cases into a [`Scene`].

use std::f64::consts::PI;
use std::fmt;
use std::path::Path;

use oblique_lookup::rebound::{Body, Elastic, State};

use super::file::{CasesFile, SceneFile, TargetFile, Values, YieldPressureFile};
use super::{
    CaseKind, Cases, Dissipation, MaterialUse, MeasuredRef, Scene, SceneTarget, DEFAULT_TOL,
    DENSITY_RANGE, MASS_RANGE, MAX_SPEED, MIN_APPROACH_SPEED, RADIUS_RANGE, YOUNGS_MODULUS_RANGE,
};
use crate::scene::materials;
use crate::scene::SceneError;

/// The checks of one scene file; `path` names it in every error.
pub(super) struct Validator<'a> {
    pub(super) path: &'a str,
}

/// Body fields shared by `[sphere]` and a `[target]` of kind `sphere`.
struct BodyFields<'a> {
    section: &'static str,
    material: Option<&'a str>,
    youngs_modulus: Option<f64>,
    poisson_ratio: Option<f64>,
    density: Option<f64>,
    mass: Option<f64>,
    radius: f64,
    inner_radius: Option<f64>,
    kappa: Option<f64>,
}

impl Validator<'_> {
    fn invalid(
        &self,
        key: impl Into<String>,
        value: impl fmt::Display,
        allowed: &str,
    ) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_string(),
            key: key.into(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    /// [`Self::invalid`] for a number, shown in exponent notation when very large or small (not
    /// as hundreds of digits).
    fn invalid_num(&self, key: impl Into<String>, v: f64, allowed: &str) -> SceneError {
        self.invalid(key, crate::scene::format::num(v), allowed)
    }

    /// `v` in `[lo, hi]` (unit `unit`), else an error naming the key and the range.
    fn in_range(
        &self,
        key: String,
        v: f64,
        (lo, hi): (f64, f64),
        unit: &str,
    ) -> Result<f64, SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(v)
        } else {
            Err(self.invalid_num(key, v, &format!("a number > 0 in [{lo:e}, {hi:e}] {unit}")))
        }
    }

    /// `|v| ≤ MAX_SPEED`.
    fn speed(&self, key: impl Into<String>, v: f64) -> Result<f64, SceneError> {
        if v.abs() <= MAX_SPEED {
            Ok(v)
        } else {
            Err(self.invalid_num(
                key,
                v,
                &format!("a finite speed with |v| <= {MAX_SPEED} m/s"),
            ))
        }
    }

    /// `|ω| radius ≤ MAX_SPEED`: the contact-point speed of the spin.
    fn spin(&self, key: impl Into<String>, omega: f64, radius: f64) -> Result<f64, SceneError> {
        if omega.abs() * radius <= MAX_SPEED {
            Ok(omega)
        } else {
            Err(self.invalid_num(
                key,
                omega,
                &format!(
                    "a finite spin with |omega| * radius <= {MAX_SPEED} m/s (|omega| <= {:e} \
                     rad/s for radius {radius:e} m)",
                    MAX_SPEED / radius
                ),
            ))
        }
    }

    pub(super) fn build(&self, f: SceneFile, path: &Path) -> Result<Scene, SceneError> {
        let name = match f.name {
            Some(n) => n,
            None => path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "scene".into()),
        };
        let name_ok = !name.is_empty()
            && name.len() <= 100
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
            && !name.starts_with('.');
        if !name_ok {
            return Err(self.invalid(
                "name",
                format!("{name:?}"),
                "1-100 characters from A-Z a-z 0-9 _ - . (not starting with '.'); it names the \
                 output files",
            ));
        }
        if f.friction.is_nan() || f.friction < 0.0 {
            return Err(self.invalid_num("friction", f.friction, ">= 0 (inf for no slip)"));
        }
        let tol = f.tol.unwrap_or(DEFAULT_TOL);
        if !(1e-10..=1e-2).contains(&tol) {
            return Err(self.invalid_num("tol", tol, "in [1e-10, 1e-2] (absolute error of P)"));
        }
        let s = &f.sphere;
        let (sphere, sphere_material) = self.body(&BodyFields {
            section: "sphere",
            material: s.material.as_deref(),
            youngs_modulus: s.youngs_modulus,
            poisson_ratio: s.poisson_ratio,
            density: s.density,
            mass: s.mass,
            radius: s.radius,
            inner_radius: s.inner_radius,
            kappa: s.kappa,
        })?;
        if sphere_material.elastic.youngs_modulus.is_infinite() {
            return Err(self.invalid(
                "sphere.youngs_modulus",
                "inf",
                "finite: the sphere must be elastic (a rigid target is allowed)",
            ));
        }
        let target = self.target(&f.target)?;
        let yield_pressure = match &f.yield_pressure {
            None => None,
            Some(YieldPressureFile::Pascal(p)) => Some(*p),
            Some(YieldPressureFile::Named(word)) => {
                Some(self.catalogue_yield_pressure(word, &sphere_material, &target)?)
            }
        };
        let dissipation = self.dissipation(f.e_n, f.relaxation_time, yield_pressure)?;
        let cases = self.cases(&f.cases)?;
        self.case_ranges(&cases, sphere.radius)?;
        let measured = match f.measured {
            None => None,
            Some(m) => {
                if m.source.trim().is_empty() {
                    return Err(self.invalid(
                        "measured.source",
                        "\"\"",
                        "a citation of the measured data (who measured it, where published)",
                    ));
                }
                let dir = path.parent().unwrap_or(Path::new(""));
                Some(MeasuredRef {
                    file: dir.join(m.file),
                    source: m.source,
                })
            }
        };
        let scene = Scene {
            name,
            description: f.description.unwrap_or_default(),
            path: path.to_path_buf(),
            friction: f.friction,
            tol,
            dissipation,
            sphere,
            sphere_material,
            target,
            cases,
            measured,
        };
        // Every case must approach.
        let pair = scene.pair();
        for &x in &scene.cases.values {
            let inc = scene.incident(x);
            let v = pair.approach_speed(&inc);
            if v.is_nan() || v < MIN_APPROACH_SPEED {
                return Err(self.invalid_num(
                    format!("cases.{}", x_key(scene.cases.kind)),
                    x,
                    &format!(
                        "values for which sphere 1 approaches the target at >= \
                         {MIN_APPROACH_SPEED:e} m/s: the relative normal speed is {} m/s there \
                         (target.v_z must be < sphere 1's v_z)",
                        crate::scene::format::num(v)
                    ),
                ));
            }
        }
        Ok(scene)
    }

    /// `yield_pressure = "catalogue"`: the lower limiting pressure of the two bodies' catalogue
    /// materials that have one (the softer body flows first; `CatalogueMaterial::
    /// limiting_pressure`, 1.60 times the yield stress), refused where neither has one.
    fn catalogue_yield_pressure(
        &self,
        word: &str,
        sphere: &MaterialUse,
        target: &SceneTarget,
    ) -> Result<f64, SceneError> {
        if word != "catalogue" {
            return Err(self.invalid(
                "yield_pressure",
                format!("{word:?}"),
                "a finite pressure > 0 (Pa), or \"catalogue\" for the limiting pressure of the \
                 bodies' catalogue materials",
            ));
        }
        let target = match target {
            SceneTarget::Wall { material } | SceneTarget::Sphere { material, .. } => material,
        };
        [sphere, target]
            .iter()
            .filter_map(|m| m.catalogue.and_then(|c| c.limiting_pressure()))
            .min_by(f64::total_cmp)
            .ok_or_else(|| {
                self.invalid(
                    "yield_pressure",
                    "\"catalogue\"",
                    &format!(
                        "a catalogue material with a limiting pressure for one of the bodies \
                         (those with a yield stress: {}), or p_y in Pa",
                        materials::CATALOGUE
                            .iter()
                            .filter(|m| m.yield_stress.is_some())
                            .map(|m| m.name)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
    }

    fn dissipation(
        &self,
        e_n: Option<f64>,
        relaxation_time: Option<f64>,
        yield_pressure: Option<f64>,
    ) -> Result<Dissipation, SceneError> {
        let Some(p) = yield_pressure else {
            return self.kelvin_voigt(e_n, relaxation_time);
        };
        let other = match (e_n, relaxation_time) {
            (Some(_), _) => Some("e_n"),
            (None, Some(_)) => Some("relaxation_time"),
            (None, None) => None,
        };
        if let Some(other) = other {
            return Err(self.invalid(
                "yield_pressure",
                format!("(given with {other})"),
                &format!(
                    "either yield_pressure (Pa, Thornton's elastic-plastic bodies) or {other} \
                     (Kelvin-Voigt bodies), not both"
                ),
            ));
        }
        if p.is_finite() && p > 0.0 {
            Ok(Dissipation::YieldPressure(p))
        } else {
            Err(self.invalid_num(
                "yield_pressure",
                p,
                "a finite pressure > 0 (Pa): the limiting contact pressure of Thornton's law",
            ))
        }
    }

    /// The dissipation of Kelvin–Voigt bodies: a constant `e_n` or a relaxation time.
    fn kelvin_voigt(
        &self,
        e_n: Option<f64>,
        relaxation_time: Option<f64>,
    ) -> Result<Dissipation, SceneError> {
        let lo = oblique_solver::law::MIN_RESTITUTION;
        let in_range = |e: f64| oblique_solver::law::check_restitution(e).is_ok();
        match (e_n, relaxation_time) {
            (Some(_), Some(_)) => Err(self.invalid(
                "relaxation_time",
                "(given with e_n)",
                "either e_n (constant) or relaxation_time (s; e_n then follows from each case's \
                 impact speed), not both",
            )),
            (Some(e), None) if in_range(e) => Ok(Dissipation::Restitution(e)),
            (Some(e), None) => Err(self.invalid_num(
                "e_n",
                e,
                &format!("in [{lo}, 1] (normal restitution of the Kelvin-Voigt law; 1: elastic)"),
            )),
            (None, Some(t)) if (0.0..=1.0).contains(&t) => Ok(Dissipation::RelaxationTime(t)),
            (None, Some(t)) => Err(self.invalid_num(
                "relaxation_time",
                t,
                "a finite number in [0, 1] (s): the Kelvin-Voigt relaxation time (0: elastic)",
            )),
            (None, None) => Ok(Dissipation::Elastic),
        }
    }

    fn material(&self, b: &BodyFields) -> Result<(MaterialUse, Option<f64>), SceneError> {
        let sec = b.section;
        let catalogue = match b.material {
            None => None,
            Some(name) => Some(materials::find(name).ok_or_else(|| {
                self.invalid(
                    format!("{sec}.material"),
                    format!("{name:?}"),
                    &format!("one of the catalogue's materials: {}", materials::names()),
                )
            })?),
        };
        let mut overridden = Vec::new();
        let mut pick = |key: &'static str, given: Option<f64>, cat: Option<f64>| match (given, cat)
        {
            (Some(v), Some(_)) => {
                overridden.push(key);
                Some(v)
            }
            (Some(v), None) => Some(v),
            (None, c) => c,
        };
        let e = pick(
            "youngs_modulus",
            b.youngs_modulus,
            catalogue.map(|c| c.youngs_modulus),
        );
        let nu = pick(
            "poisson_ratio",
            b.poisson_ratio,
            catalogue.map(|c| c.poisson_ratio),
        );
        let density = pick(
            "density",
            b.density,
            catalogue.map(|c| c.density).filter(|d| d.is_finite()),
        );
        let (Some(e), Some(nu)) = (e, nu) else {
            return Err(self.invalid(
                format!("{sec}.material"),
                "(none)",
                "a catalogue name, or both youngs_modulus (Pa) and poisson_ratio",
            ));
        };
        let (e_lo, e_hi) = YOUNGS_MODULUS_RANGE;
        if !(e == f64::INFINITY || (e_lo..=e_hi).contains(&e)) {
            return Err(self.invalid_num(
                format!("{sec}.youngs_modulus"),
                e,
                &format!("in [{e_lo:e}, {e_hi:e}] Pa (inf for a rigid wall)"),
            ));
        }
        if !(-1.0..=0.5).contains(&nu) || nu == -1.0 {
            return Err(self.invalid_num(format!("{sec}.poisson_ratio"), nu, "in (-1, 0.5]"));
        }
        Ok((
            MaterialUse {
                elastic: Elastic {
                    youngs_modulus: e,
                    poisson_ratio: nu,
                },
                catalogue,
                overridden,
            },
            density,
        ))
    }

    fn body(&self, b: &BodyFields) -> Result<(Body, MaterialUse), SceneError> {
        let sec = b.section;
        let (material, density) = self.material(b)?;
        let radius = self.in_range(format!("{sec}.radius"), b.radius, RADIUS_RANGE, "m")?;
        let inner = match b.inner_radius {
            None => 0.0,
            Some(r) if r >= 0.0 && r < radius => r,
            Some(r) => {
                return Err(self.invalid_num(
                    format!("{sec}.inner_radius"),
                    r,
                    "in [0, radius) (m): the cavity of a hollow sphere",
                ))
            }
        };
        let kappa = match (b.kappa, b.inner_radius) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(
                    format!("{sec}.kappa"),
                    "(given with inner_radius)",
                    "either kappa or inner_radius, not both (inner_radius implies kappa)",
                ))
            }
            (Some(k), None) => {
                if !(0.0..=2.0 / 3.0).contains(&k) || k == 0.0 {
                    return Err(self.invalid_num(
                        format!("{sec}.kappa"),
                        k,
                        "in (0, 2/3] (I = kappa m R^2; 0.4 solid, 2/3 thin shell)",
                    ));
                }
                k
            }
            (None, _) => {
                let q = inner / radius;
                0.4 * (1.0 - q.powi(5)) / (1.0 - q.powi(3))
            }
        };
        let volume = 4.0 / 3.0 * PI * (radius.powi(3) - inner.powi(3));
        let mass = match (b.mass, b.density) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(
                    format!("{sec}.mass"),
                    "(given with density)",
                    "either mass (kg) or density (kg/m^3), not both",
                ))
            }
            (Some(m), None) => self.in_range(format!("{sec}.mass"), m, MASS_RANGE, "kg")?,
            (None, _) => match density {
                Some(d) => {
                    self.in_range(format!("{sec}.density"), d, DENSITY_RANGE, "kg/m^3")? * volume
                }
                None => {
                    return Err(self.invalid(
                        format!("{sec}.density"),
                        "(none)",
                        "a density (kg/m^3) or a mass (kg): the material gives none",
                    ))
                }
            },
        };
        let (m_lo, m_hi) = MASS_RANGE;
        if !(m_lo..=m_hi).contains(&mass) {
            return Err(self.invalid_num(
                format!("{sec}.mass"),
                mass,
                &format!(
                    "in [{m_lo:e}, {m_hi:e}] kg (here computed from the density and the volume)"
                ),
            ));
        }
        Ok((
            Body {
                mass,
                radius,
                kappa,
            },
            material,
        ))
    }

    fn target(&self, t: &TargetFile) -> Result<SceneTarget, SceneError> {
        match t.kind.as_str() {
            "wall" => {
                let extra = [
                    ("density", t.density.is_some()),
                    ("mass", t.mass.is_some()),
                    ("radius", t.radius.is_some()),
                    ("inner_radius", t.inner_radius.is_some()),
                    ("kappa", t.kappa.is_some()),
                    ("v_x", t.v_x.is_some()),
                    ("v_z", t.v_z.is_some()),
                    ("omega", t.omega.is_some()),
                ];
                if let Some((k, _)) = extra.iter().find(|(_, given)| *given) {
                    return Err(self.invalid(
                        format!("target.{k}"),
                        "(given)",
                        "absent for kind = \"wall\" (a fixed half-space has only material, \
                         youngs_modulus, poisson_ratio)",
                    ));
                }
                let (material, _) = self.material(&BodyFields {
                    section: "target",
                    material: t.material.as_deref(),
                    youngs_modulus: t.youngs_modulus,
                    poisson_ratio: t.poisson_ratio,
                    density: None,
                    mass: None,
                    radius: 1.0,
                    inner_radius: None,
                    kappa: None,
                })?;
                Ok(SceneTarget::Wall { material })
            }
            "sphere" => {
                let Some(radius) = t.radius else {
                    return Err(self.invalid(
                        "target.radius",
                        "(none)",
                        "a finite number > 0 (m), required for kind = \"sphere\"",
                    ));
                };
                let (body, material) = self.body(&BodyFields {
                    section: "target",
                    material: t.material.as_deref(),
                    youngs_modulus: t.youngs_modulus,
                    poisson_ratio: t.poisson_ratio,
                    density: t.density,
                    mass: t.mass,
                    radius,
                    inner_radius: t.inner_radius,
                    kappa: t.kappa,
                })?;
                if material.elastic.youngs_modulus.is_infinite() {
                    return Err(self.invalid(
                        "target.youngs_modulus",
                        "inf",
                        "finite for kind = \"sphere\" (a rigid body can only be a wall)",
                    ));
                }
                let mut motion = State::default();
                for (key, given, slot) in [
                    ("target.v_x", t.v_x, &mut motion.v_x),
                    ("target.v_z", t.v_z, &mut motion.v_z),
                    ("target.omega", t.omega, &mut motion.omega),
                ] {
                    let v = given.unwrap_or(0.0);
                    *slot = if key == "target.omega" {
                        self.spin(key, v, body.radius)?
                    } else {
                        self.speed(key, v)?
                    };
                }
                Ok(SceneTarget::Sphere {
                    body,
                    material,
                    motion,
                })
            }
            other => Err(self.invalid(
                "target.kind",
                format!("{other:?}"),
                "\"wall\" or \"sphere\"",
            )),
        }
    }

    /// The speeds and spins of the cases within [`MAX_SPEED`] (`radius`: sphere 1's).
    fn case_ranges(&self, c: &Cases, radius: f64) -> Result<(), SceneError> {
        let speed_key = match c.kind {
            CaseKind::Angles => "cases.speed",
            _ => "cases.normal_speed",
        };
        if !(MIN_APPROACH_SPEED..=MAX_SPEED).contains(&c.speed) {
            return Err(self.invalid_num(
                speed_key,
                c.speed,
                &format!("in [{MIN_APPROACH_SPEED:e}, {MAX_SPEED}] m/s"),
            ));
        }
        self.speed("cases.tangential_speed", c.tangential_speed)?;
        self.spin("cases.omega0", c.omega0, radius)?;
        for &x in &c.values {
            match c.kind {
                CaseKind::Angles => {}
                CaseKind::TangentialSpeed => {
                    self.speed("cases.tangential_speed", x)?;
                }
                CaseKind::Spin => {
                    self.spin("cases.omega0", x, radius)?;
                }
            }
        }
        Ok(())
    }

    fn single(&self, key: &str, v: &Option<Values>) -> Result<f64, SceneError> {
        match v {
            None => Ok(0.0),
            Some(Values(list)) if list.len() == 1 && list[0].is_finite() => Ok(list[0]),
            Some(Values(list)) => Err(self.invalid(
                format!("cases.{key}"),
                format!("{list:?}"),
                "one finite number here (it is swept only by its own kind of cases)",
            )),
        }
    }

    fn cases(&self, c: &CasesFile) -> Result<Cases, SceneError> {
        let forbid = |key: &str, given: bool, kind: &str| {
            if given {
                Err(self.invalid(
                    format!("cases.{key}"),
                    "(given)",
                    &format!("absent for kind = \"{kind}\""),
                ))
            } else {
                Ok(())
            }
        };
        let require = |key: &str, v: Option<f64>, kind: &str| match v {
            Some(v) if v.is_finite() && v > 0.0 => Ok(v),
            Some(v) => {
                Err(self.invalid_num(format!("cases.{key}"), v, "a finite number > 0 (m/s)"))
            }
            None => Err(self.invalid(
                format!("cases.{key}"),
                "(none)",
                &format!("a finite number > 0 (m/s), required for kind = \"{kind}\""),
            )),
        };
        let list = |key: &str, v: &Option<Values>, kind: &str, range: (f64, f64), what: &str| {
            let Some(Values(list)) = v else {
                return Err(self.invalid(
                    format!("cases.{key}"),
                    "(none)",
                    &format!(
                        "required for kind = \"{kind}\": a list or {{ from, to, count }} of {what}"
                    ),
                ));
            };
            if let Some(bad) = list
                .iter()
                .find(|x| !(x.is_finite() && **x > range.0 && **x < range.1))
            {
                return Err(self.invalid_num(format!("cases.{key}"), *bad, what));
            }
            Ok(list.clone())
        };
        let kind = c.kind.as_str();
        match kind {
            "angles" => {
                forbid("normal_speed", c.normal_speed.is_some(), kind)?;
                forbid("tangential_speed", c.tangential_speed.is_some(), kind)?;
                Ok(Cases {
                    kind: CaseKind::Angles,
                    speed: require("speed", c.speed, kind)?,
                    values: list(
                        "angles_deg",
                        &c.angles_deg,
                        kind,
                        (-90.0, 90.0),
                        "angles in (-90, 90) degrees from the normal",
                    )?,
                    tangential_speed: 0.0,
                    omega0: self.single("omega0", &c.omega0)?,
                })
            }
            "tangential-speed" => {
                forbid("speed", c.speed.is_some(), kind)?;
                forbid("angles_deg", c.angles_deg.is_some(), kind)?;
                Ok(Cases {
                    kind: CaseKind::TangentialSpeed,
                    speed: require("normal_speed", c.normal_speed, kind)?,
                    values: list(
                        "tangential_speed",
                        &c.tangential_speed,
                        kind,
                        (f64::NEG_INFINITY, f64::INFINITY),
                        "finite tangential speeds (m/s)",
                    )?,
                    tangential_speed: 0.0,
                    omega0: self.single("omega0", &c.omega0)?,
                })
            }
            "spin" => {
                forbid("speed", c.speed.is_some(), kind)?;
                forbid("angles_deg", c.angles_deg.is_some(), kind)?;
                Ok(Cases {
                    kind: CaseKind::Spin,
                    speed: require("normal_speed", c.normal_speed, kind)?,
                    values: list(
                        "omega0",
                        &c.omega0,
                        kind,
                        (f64::NEG_INFINITY, f64::INFINITY),
                        "finite initial spins (rad/s)",
                    )?,
                    tangential_speed: self.single("tangential_speed", &c.tangential_speed)?,
                    omega0: 0.0,
                })
            }
            other => Err(self.invalid(
                "cases.kind",
                format!("{other:?}"),
                "\"angles\", \"tangential-speed\" or \"spin\"",
            )),
        }
    }
}

fn x_key(kind: CaseKind) -> &'static str {
    match kind {
        CaseKind::Angles => "angles_deg",
        CaseKind::TangentialSpeed => "tangential_speed",
        CaseKind::Spin => "omega0",
    }
}
