//! `sweep gamma`: the dimensionless groups of a pair of materials and bodies (γ, m*/m_t and α per
//! unit μ v_z0/|u0|), and the material catalogue with γ of every pair.

use std::f64::consts::PI;

use crate::failure::{outln, Failure, Result};
use clap::Args;
use serde_json::{json, Value};

use oblique_physics::materials::{self, CatalogueMaterial, CATALOGUE};
use oblique_physics::rebound::{effective_moduli, Body, Elastic, Pair};
use oblique_physics::regimes;

use crate::args::{fmt_num, parse_f64};

/// The inertia factor of a solid sphere, the default of `--kappa`.
const SOLID: f64 = 0.4;

#[derive(Args)]
pub struct GammaArgs {
    /// Sphere 1's material: a catalogue name (`sweep gamma --catalogue`) or your own values,
    /// E=PA,nu=NU[,rho=KG_PER_M3] (e.g. E=200e9,nu=0.3,rho=7800).
    #[arg(long, value_name = "MATERIAL", value_parser = parse_material,
          required_unless_present = "catalogue")]
    sphere: Option<MaterialArg>,
    /// The wall's material, or sphere 2's with --other-radius; default: the sphere's.
    #[arg(long, value_name = "MATERIAL", value_parser = parse_material)]
    other: Option<MaterialArg>,
    /// Sphere 1's radius R_1 (m). Needed for the masses (printed in kg) and R*.
    #[arg(long, value_name = "M", value_parser = parse_length, allow_hyphen_values = true)]
    radius: Option<f64>,
    /// Sphere 1's inertia factor kappa in I = kappa m R^2, in (0, 2/3]: 0.4 solid, 2/3 thin shell.
    #[arg(long, value_name = "K", default_value_t = SOLID, value_parser = parse_kappa,
          allow_hyphen_values = true)]
    kappa: f64,
    /// Sphere 1's mass (kg); default: density x (4/3) pi R^3 for a solid sphere (kappa = 0.4).
    #[arg(long, value_name = "KG", value_parser = parse_mass, allow_hyphen_values = true)]
    mass: Option<f64>,
    /// Sphere 2's radius R_2 (m): the other body is then a free sphere (without it, a wall).
    #[arg(long, value_name = "M", value_parser = parse_length, allow_hyphen_values = true)]
    other_radius: Option<f64>,
    /// Sphere 2's inertia factor, in (0, 2/3] (only with --other-radius).
    #[arg(long, value_name = "K", default_value_t = SOLID, value_parser = parse_kappa,
          allow_hyphen_values = true, requires = "other_radius")]
    other_kappa: f64,
    /// Sphere 2's mass (kg) (only with --other-radius); default as for --mass.
    #[arg(long, value_name = "KG", value_parser = parse_mass, allow_hyphen_values = true,
          requires = "other_radius")]
    other_mass: Option<f64>,
    /// Print the catalogue instead: E, nu, density and gamma of each material, gamma of every
    /// pair, and the sources.
    #[arg(long, conflicts_with_all = ["sphere", "other", "radius", "other_radius", "mass",
          "other_mass"])]
    catalogue: bool,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

/// A material from the command line.
#[derive(Clone, Debug)]
pub struct MaterialArg {
    /// The catalogue name, or the values as given.
    name: String,
    elastic: Elastic,
    /// kg/m³, if known.
    density: Option<f64>,
    /// The catalogue entry, if any.
    entry: Option<&'static CatalogueMaterial>,
}

fn unknown_material(s: &str) -> String {
    format!(
        "unknown material `{s}`: give a catalogue name ({}; `sweep gamma --catalogue` prints \
         their values and sources) or your own values, E=PA,nu=NU[,rho=KG_PER_M3]",
        materials::names()
    )
}

fn parse_material(s: &str) -> Result<MaterialArg, String> {
    if let Some(m) = materials::find(s) {
        return Ok(MaterialArg {
            name: m.name.to_string(),
            elastic: m.elastic(),
            density: Some(m.density).filter(|d| d.is_finite()),
            entry: Some(m),
        });
    }
    if !s.contains('=') {
        return Err(unknown_material(s));
    }
    let (mut e, mut nu, mut rho) = (None, None, None);
    for part in s.split(',') {
        let (key, value) = part.split_once('=').ok_or_else(|| unknown_material(s))?;
        let v = parse_f64(value).map_err(|m| format!("{}: {m}", key.trim()))?;
        let slot = match key.trim().to_ascii_lowercase().as_str() {
            "e" => &mut e,
            "nu" => &mut nu,
            "rho" => &mut rho,
            other => {
                return Err(format!(
                    "unknown key `{other}` in `{s}`: the keys are E (Pa), nu and rho (kg/m^3)"
                ))
            }
        };
        *slot = Some(v);
    }
    let (Some(e), Some(nu)) = (e, nu) else {
        return Err(format!(
            "`{s}` needs both E (Young's modulus, Pa) and nu (Poisson's ratio): \
             E=PA,nu=NU[,rho=KG_PER_M3]"
        ));
    };
    let elastic = Elastic {
        youngs_modulus: e,
        poisson_ratio: nu,
    };
    elastic.validate().map_err(|x| x.to_string())?;
    if let Some(r) = rho {
        if !(r.is_finite() && r > 0.0) {
            return Err(format!(
                "invalid rho = {r}: must be a finite density > 0 (kg/m^3)"
            ));
        }
    }
    Ok(MaterialArg {
        name: s.to_string(),
        elastic,
        density: rho,
        entry: None,
    })
}

fn positive(s: &str, what: &str) -> Result<f64, String> {
    match parse_f64(s) {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("{what} must be a finite number > 0")),
    }
}

fn parse_length(s: &str) -> Result<f64, String> {
    positive(s, "a radius (m)")
}

fn parse_mass(s: &str) -> Result<f64, String> {
    positive(s, "a mass (kg)")
}

fn parse_kappa(s: &str) -> Result<f64, String> {
    match parse_f64(s) {
        Ok(v) if v > 0.0 && v <= 2.0 / 3.0 => Ok(v),
        _ => Err("kappa must be in (0, 2/3] (I = kappa m R^2; 0.4 solid, 2/3 thin shell)".into()),
    }
}

/// One sphere as far as the command line gives it.
struct Sphere<'a> {
    material: &'a MaterialArg,
    radius: Option<f64>,
    kappa: f64,
    /// `--mass`, or the density times the volume of a solid sphere.
    mass: Option<f64>,
}

impl<'a> Sphere<'a> {
    fn new(material: &'a MaterialArg, radius: Option<f64>, kappa: f64, mass: Option<f64>) -> Self {
        let solid = match (radius, material.density) {
            (Some(r), Some(rho)) if kappa == SOLID => Some(rho * 4.0 / 3.0 * PI * r.powi(3)),
            _ => None,
        };
        Sphere {
            material,
            radius,
            kappa,
            mass: mass.or(solid),
        }
    }

    /// The body, with placeholders (1 kg, 1 m) for what is not known; used only where they
    /// cancel.
    fn body(&self) -> Body {
        Body {
            mass: self.mass.unwrap_or(1.0),
            radius: self.radius.unwrap_or(1.0),
            kappa: self.kappa,
        }
    }

    fn json(&self) -> Value {
        json!({
            "material": self.material.name,
            "youngs_modulus": finite_or_inf(self.material.elastic.youngs_modulus),
            "poisson_ratio": self.material.elastic.poisson_ratio,
            "density": self.material.density,
            "radius": self.radius,
            "kappa": self.kappa,
            "mass": self.mass,
            "source": self.material.entry.map(|e| e.source),
        })
    }
}

fn finite_or_inf(v: f64) -> Value {
    crate::args::json_number(v)
}

/// Run `sweep gamma`.
pub fn run(args: GammaArgs) -> Result<()> {
    if args.catalogue {
        return catalogue(args.json);
    }
    let Some(m1) = &args.sphere else {
        return Err(Failure::usage(
            "give --sphere MATERIAL (or --catalogue)".to_string(),
        ));
    };
    let m2 = args.other.as_ref().unwrap_or(m1);
    let s1 = Sphere::new(m1, args.radius, args.kappa, args.mass);
    let s2 = args
        .other_radius
        .map(|r| Sphere::new(m2, Some(r), args.other_kappa, args.other_mass));
    // m*/m_t depends on the masses only through their ratio, and not at all for one sphere on a
    // wall or for two spheres of the same kappa: (1 + kappa)/kappa.
    let masses_known = s1.mass.is_some() && s2.as_ref().is_none_or(|s| s.mass.is_some());
    if let Some(s2) = &s2 {
        if s2.kappa != s1.kappa && !masses_known {
            return Err(Failure::usage(format!(
                "two spheres of different kappa ({} and {}): m*/m_t depends on their masses; \
                 give --radius and --other-radius with materials that have a density (or \
                 --mass and --other-mass)",
                fmt_num(s1.kappa),
                fmt_num(s2.kappa)
            )));
        }
    }
    let pair = Pair {
        sphere: s1.body(),
        other: s2.as_ref().map(Sphere::body),
    };
    let gamma = pair
        .gamma_from_materials(&m1.elastic, &m2.elastic)
        .map_err(|e| Failure::usage(format!("{e}")))?;
    let (e_star, g_star) = effective_moduli(&m1.elastic, &m2.elastic);
    let ratio = pair.mass_ratio();
    let alpha_per = 2.0 / 7.0 * ratio;
    let (c1, c2) = (regimes::alpha_c1(gamma), regimes::alpha_c2(gamma));
    let radii_known = s1.radius.is_some();
    let normal_mass = masses_known.then(|| pair.normal_mass());
    let tangential_mass = masses_known.then(|| pair.tangential_mass());
    let effective_radius = radii_known.then(|| pair.effective_radius());

    if args.json {
        let out = json!({
            "sphere": s1.json(),
            "other": match &s2 {
                Some(s) => { let mut v = s.json(); v["body"] = json!("sphere"); v }
                None => json!({
                    "body": "wall",
                    "material": m2.name,
                    "youngs_modulus": finite_or_inf(m2.elastic.youngs_modulus),
                    "poisson_ratio": m2.elastic.poisson_ratio,
                    "source": m2.entry.map(|e| e.source),
                }),
            },
            "e_star": e_star,
            "g_star": g_star,
            "mass_ratio": ratio,
            "gamma": gamma,
            "alpha_per_mu_vz0_over_u0": alpha_per,
            "alpha_c1": (gamma > 1.0).then_some(c1),
            "alpha_c2": c2,
            "normal_mass": normal_mass,
            "tangential_mass": tangential_mass,
            "effective_radius": effective_radius,
        });
        outln!("{out}")?;
        return Ok(());
    }

    let describe = |s: &Sphere| {
        let mut parts = Vec::new();
        if let Some(r) = s.radius {
            parts.push(format!("R = {r:.4e} m"));
        }
        if let Some(m) = s.mass {
            parts.push(format!("m = {m:.4e} kg"));
        }
        parts.push(format!("kappa = {}", fmt_num(s.kappa)));
        format!("{} sphere ({})", s.material.name, parts.join(", "))
    };
    let target = match &s2 {
        Some(s) => describe(s),
        None => format!("{} wall", m2.name),
    };
    outln!("{} on a {target}", describe(&s1))?;
    outln!(
        "  E* = {e_star:.4e} Pa, G* = {g_star:.4e} Pa, G*/E* = {:.6}",
        g_star / e_star
    )?;
    let why = match &s2 {
        None => "(1 + kappa)/kappa: one sphere on a wall",
        Some(s) if s.kappa == s1.kappa => "(1 + kappa)/kappa: two spheres of the same kappa",
        Some(_) => "from the masses and kappas",
    };
    outln!("  m*/m_t = {:.6}  ({why})", ratio)?;
    if let (Some(mn), Some(mt)) = (normal_mass, tangential_mass) {
        let r = effective_radius.map_or(String::new(), |r| format!(", R* = {r:.4e} m"));
        outln!("  m* = {mn:.4e} kg, m_t = {mt:.4e} kg{r}")?;
    }
    outln!("  gamma = {gamma}  (gamma^2 = (m*/m_t) G*/E*)")?;
    outln!(
        "  alpha = {:.6} mu v_z0/|u0|  (alpha = (2/7)(m*/m_t) mu v_z0/|u0|)",
        alpha_per
    )?;
    if gamma > 1.0 {
        outln!("  alpha_c1 = {c1:.6} (full slip below), alpha_c2 = {c2:.6} (stick above)")?;
    } else {
        outln!("  alpha_c2 = {c2:.6} (full slip below, stick above)")?;
    }
    Ok(())
}

/// γ of two solid spheres (or a solid sphere and a wall) of the two materials; `None` for two
/// rigid bodies.
fn pair_gamma(a: &CatalogueMaterial, b: &CatalogueMaterial) -> Option<f64> {
    let body = Body {
        mass: 1.0,
        radius: 1.0,
        kappa: SOLID,
    };
    Pair {
        sphere: body,
        other: None,
    }
    .gamma_from_materials(&a.elastic(), &b.elastic())
    .ok()
}

/// Wrap `text` into lines of at most `width` characters, each starting with `indent`.
fn wrap(text: &str, indent: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && indent.len() + line.len() + 1 + word.len() > width {
            lines.push(format!("{indent}{line}"));
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(format!("{indent}{line}"));
    }
    lines
}

fn catalogue(as_json: bool) -> Result<()> {
    if as_json {
        let list: Vec<Value> = CATALOGUE
            .iter()
            .map(|m| {
                json!({
                    "name": m.name,
                    "youngs_modulus": finite_or_inf(m.youngs_modulus),
                    "poisson_ratio": m.poisson_ratio,
                    "density": Some(m.density).filter(|d| d.is_finite()),
                    "gamma_same_material": pair_gamma(m, m),
                    "gamma": CATALOGUE.iter().map(|o| pair_gamma(m, o)).collect::<Vec<_>>(),
                    "source": m.source,
                    "yield_stress": m.yield_stress,
                    "limiting_pressure": m.limiting_pressure(),
                    "yield_source": m.yield_source,
                })
            })
            .collect();
        outln!(
            "{}",
            json!({
                "kappa": SOLID,
                "materials": list,
                "note": "gamma[j]: with the j-th material (solid spheres; sphere-wall and \
                         sphere-sphere alike, any radii); null for two rigid bodies. \
                         yield_stress Y and limiting_pressure p_y = 1.60 Y (Pa) of Thornton's \
                         elastic-perfectly plastic law: null where none",
            })
        )?;
        return Ok(());
    }
    let width = CATALOGUE.iter().map(|m| m.name.len()).max().unwrap_or(0);
    outln!(
        "{:w$}  {:>8}  {:>6}  {:>11}  {:>8}  {:>7}  {:>9}",
        "material",
        "E (GPa)",
        "nu",
        "rho (kg/m3)",
        "gamma",
        "Y (MPa)",
        "p_y (MPa)",
        w = width + 3
    )?;
    for (i, m) in CATALOGUE.iter().enumerate() {
        let rho = if m.density.is_finite() {
            format!("{}", m.density)
        } else {
            "-".into()
        };
        let gamma = pair_gamma(m, m).map_or("-".into(), |g| format!("{g:.6}"));
        let mpa = |v: Option<f64>| v.map_or("-".into(), |v| fmt_num(v / 1e6));
        outln!(
            "{:>2} {:width$}  {:>8}  {:>6}  {:>11}  {:>8}  {:>7}  {:>9}",
            i + 1,
            m.name,
            fmt_num(m.youngs_modulus / 1e9),
            fmt_num(m.poisson_ratio),
            rho,
            gamma,
            mpa(m.yield_stress),
            mpa(m.limiting_pressure())
        )?;
    }
    outln!()?;
    for l in wrap(
        "Y: yield stress; p_y = 1.60 Y: the limiting contact pressure of Thornton's \
         elastic-perfectly plastic law (the peak Hertz pressure at first yield, Johnson 1985, \
         Contact Mechanics, chapter 6); scenes take it with yield_pressure = \"catalogue\". \
         None for brittle materials and polymers.",
        "",
        96,
    ) {
        outln!("{l}")?;
    }
    outln!()?;
    for l in wrap(
        "gamma: a solid sphere (kappa = 0.4) of the material on a wall of it, on a rigid wall or \
         on a solid sphere of it of any radius: all the same, sqrt(7 (1 - nu)/(2 - nu)). Below: \
         gamma of a solid sphere of the row's material on a wall or a solid sphere (any radii) \
         of the column's material, gamma^2 = (7/2) G*/E* (symmetric). For another kappa, equal \
         for both spheres, multiply by sqrt(2 (1 + kappa)/(7 kappa)); for different kappas: \
         sweep gamma --sphere A --other B --radius R1 --other-radius R2 --kappa K1 \
         --other-kappa K2.",
        "",
        96,
    ) {
        outln!("{l}")?;
    }
    outln!()?;
    let mut head = format!("{:w$}", "", w = width + 3);
    for j in 1..=CATALOGUE.len() {
        head.push_str(&format!("  {j:>8}"));
    }
    outln!("{}", head.trim_end())?;
    for (i, a) in CATALOGUE.iter().enumerate() {
        let mut line = format!("{:>2} {:width$}", i + 1, a.name);
        for b in CATALOGUE {
            let g = pair_gamma(a, b).map_or("-".into(), |g| format!("{g:.6}"));
            line.push_str(&format!("  {g:>8}"));
        }
        outln!("{line}")?;
    }
    outln!()?;
    outln!("sources:")?;
    for m in CATALOGUE {
        let lines = wrap(&format!("{}: {}", m.name, m.source), "    ", 96);
        for (k, l) in lines.iter().enumerate() {
            outln!("{}", if k == 0 { &l[2..] } else { l })?;
        }
    }
    outln!()?;
    outln!("yield stress:")?;
    for m in CATALOGUE {
        let lines = wrap(&format!("{}: {}", m.name, m.yield_source), "    ", 96);
        for (k, l) in lines.iter().enumerate() {
            outln!("{}", if k == 0 { &l[2..] } else { l })?;
        }
    }
    Ok(())
}
