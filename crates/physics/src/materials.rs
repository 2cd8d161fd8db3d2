//! The built-in material catalogue: elastic constants and density with their source.
//!
//! Values are nominal room-temperature, quasi-static ones. The model is elastic: for the
//! polymers (strongly rate-, temperature- and moisture-dependent, and viscoelastic) treat the
//! result as a first estimate. Scene files name these materials (and may override any value:
//! `youngs_modulus`, `poisson_ratio`, `density`), `sweep gamma` prints γ of a pair of them,
//! and Python reads them as `oblique.materials` (docs/materials.md).
//!
//! The metals also carry a yield stress `Y` from a source, and with it a limiting contact
//! pressure `p_y = 1.60 Y` for Thornton's elastic–perfectly plastic law (`physics.md`,
//! "Elastic–plastic impacts"): the peak Hertz pressure `p_0` at which a Hertz contact first
//! yields ([`FIRST_YIELD_FACTOR`]). The brittle materials (glass, alumina) and the polymers
//! have none.

use crate::rebound::Elastic;

/// One catalogue entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogueMaterial {
    /// Name used in scene files (`material = "..."`).
    pub name: &'static str,
    /// Young's modulus `E` (Pa); `∞` for the rigid body.
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`.
    pub poisson_ratio: f64,
    /// Density `ρ` (kg/m³); NaN for the rigid body (it can only be a wall).
    pub density: f64,
    /// Where the numbers come from.
    pub source: &'static str,
    /// Uniaxial (tensile) yield stress `Y` (Pa) where a source gives one; `None` for brittle
    /// materials and polymers, which Thornton's elastic–perfectly plastic law does not describe.
    pub yield_stress: Option<f64>,
    /// Where the yield stress comes from, or why there is none.
    pub yield_source: &'static str,
}

/// The peak Hertz pressure at first yield over the yield stress, `p_0/Y = 1.60` for `ν ≈ 0.3`
/// (Johnson, *Contact Mechanics*, Cambridge University Press, 1985, chapter 6, "onset of
/// plastic yield": the largest shear stress of a Hertz contact of spheres, `0.31 p_0` at depth
/// `0.48 a` on the axis, reaches the Tresca limit `Y/2`; on the axis the von Mises criterion
/// gives the same). Computed from the Hertz stresses on the axis it is 1.613 at `ν = 0.3` (a
/// test), 1.55 at `ν = 0.25` and 1.67 at `ν = 0.35`.
pub const FIRST_YIELD_FACTOR: f64 = 1.60;

impl CatalogueMaterial {
    /// The elastic constants.
    pub fn elastic(&self) -> Elastic {
        Elastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }

    /// The limiting contact pressure `p_y = 1.60 Y` (Pa) of Thornton's law: the peak Hertz
    /// pressure at first yield ([`FIRST_YIELD_FACTOR`]); `None` without a yield stress.
    pub fn limiting_pressure(&self) -> Option<f64> {
        self.yield_stress.map(|y| FIRST_YIELD_FACTOR * y)
    }
}

/// Every built-in material.
pub const CATALOGUE: &[CatalogueMaterial] = &[
    CatalogueMaterial {
        name: "soda-lime-glass",
        youngs_modulus: 73e9,
        poisson_ratio: 0.217,
        density: 2500.0,
        source: "E = 73 GPa, nu = 0.217: the values seed 000 (Lyashenko, Willert & Popov, \
                 section 4) assumes for the soda-lime glass plate of Gorham & Kharaz, Powder \
                 Technol. 112 (2000) 193-202; density 2500 kg/m^3: EN 572-1 (basic soda-lime \
                 silicate glass), which lists E = 70 GPa and nu = 0.2 as its nominal values",
        yield_stress: None,
        yield_source: "none: brittle (it breaks before it flows)",
    },
    CatalogueMaterial {
        name: "alumina-96",
        youngs_modulus: 370e9,
        poisson_ratio: 0.25,
        density: 3720.0,
        source: "E = 370 GPa, nu = 0.25: seed 000, section 4 ('a material containing 96 % of \
                 Al2O3 at room temperature'), used there for the aluminium-oxide spheres of \
                 Gorham & Kharaz (2000); density 3720 kg/m^3: typical of 96 % alumina (e.g. \
                 CoorsTek AD-96 data, 3.72 g/cm^3), not given by the seed (it changes only \
                 masses and energies, not e_t or omega on a wall)",
        yield_stress: None,
        yield_source: "none: brittle (it breaks before it flows)",
    },
    CatalogueMaterial {
        name: "steel",
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
        source: "structural/bearing steel: E = 210 GPa, nu = 0.3 from EN 1993-1-1 (Eurocode 3) \
                 section 3.2.6; density 7850 kg/m^3 from EN 1991-1-1, Annex A",
        yield_stress: Some(235e6),
        yield_source: "structural steel S235: f_y = 235 MPa (nominal, thickness up to 40 mm), \
                       EN 1993-1-1 (Eurocode 3) table 3.1; S355 yields at 355 MPa, hardened \
                       bearing steels at several times more: give your grade's own",
    },
    CatalogueMaterial {
        name: "aluminium-6061-t6",
        youngs_modulus: 68.9e9,
        poisson_ratio: 0.33,
        density: 2700.0,
        source: "aluminium alloy 6061-T6: E = 68.9 GPa, nu = 0.33, density 2.70 g/cm^3 from \
                 the ASM Aerospace Specification Metals data sheet 'Aluminum 6061-T6; \
                 6061-T651' (MatWeb)",
        yield_stress: Some(276e6),
        yield_source: "tensile yield strength 276 MPa (typical), the same ASM Aerospace \
                       Specification Metals data sheet 'Aluminum 6061-T6; 6061-T651' (MatWeb)",
    },
    CatalogueMaterial {
        name: "nylon",
        youngs_modulus: 2.9e9,
        poisson_ratio: 0.39,
        density: 1130.0,
        source: "polyamide (nylon 6/66), dry as moulded, 20 C: E = 2.9 GPa and density 1130 \
                 kg/m^3 are mid-range of Ashby, 'Materials and the Environment' (2nd ed., \
                 2013), data sheet 'Polyamides (Nylons, PA)' (E 2.62-3.2 GPa, 1120-1140 \
                 kg/m^3); nu = 0.39 from Matmatch 'Polyamide Nylon 6'. Moisture lowers E by up \
                 to 2x (Toray AMILAN technical data: 1.5 GPa for nylon 66 at 2.5 % water)",
        yield_stress: None,
        yield_source: "none: a viscoelastic polymer, not elastic-perfectly plastic",
    },
    CatalogueMaterial {
        name: "polyethylene-hd",
        youngs_modulus: 0.76e9,
        poisson_ratio: 0.45,
        density: 950.0,
        source: "high-density polyethylene: E = 0.76 GPa and density 950 kg/m^3 are mid-range \
                 of Ashby, 'Materials and the Environment' (2nd ed., 2013), data sheet \
                 'Polyethylene (PE)' (E 0.62-0.90 GPa, 939-960 kg/m^3); nu = 0.45 is a \
                 representative value for semicrystalline PE, grade-dependent (check the \
                 grade's data sheet)",
        yield_stress: None,
        yield_source: "none: a viscoelastic polymer, not elastic-perfectly plastic",
    },
    CatalogueMaterial {
        name: "rigid",
        youngs_modulus: f64::INFINITY,
        poisson_ratio: 0.0,
        density: f64::NAN,
        source: "idealised rigid body (E = infinity): adds no compliance; a wall only",
        yield_stress: None,
        yield_source: "none: rigid",
    },
];

/// Look a material up by name (case-insensitive, `_` and `-` interchangeable).
pub fn find(name: &str) -> Option<&'static CatalogueMaterial> {
    let key = name.trim().to_ascii_lowercase().replace('_', "-");
    CATALOGUE.iter().find(|m| m.name == key)
}

/// The catalogue's names, comma-separated (for error messages).
pub fn names() -> String {
    CATALOGUE
        .iter()
        .map(|m| m.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catalogue_is_valid() {
        for m in CATALOGUE {
            m.elastic().validate().unwrap();
            assert!(!m.source.is_empty());
            assert!(m.name == "rigid" || (m.density > 0.0 && m.youngs_modulus.is_finite()));
            assert_eq!(find(m.name).map(|f| f.name), Some(m.name));
        }
        assert_eq!(
            find("Soda_Lime-Glass").map(|m| m.name),
            Some("soda-lime-glass")
        );
        assert!(find("unobtainium").is_none());
    }

    #[test]
    fn limiting_pressures_of_the_metals_only() {
        let p = |n: &str| find(n).and_then(|m| m.limiting_pressure());
        // 1.60 x 276 MPa and 1.60 x 235 MPa, in Pa.
        assert!((p("aluminium-6061-t6").unwrap() - 441.6e6).abs() < 1e-3);
        assert!((p("steel").unwrap() - 376e6).abs() < 1e-3);
        for none in [
            "soda-lime-glass",
            "alumina-96",
            "nylon",
            "polyethylene-hd",
            "rigid",
        ] {
            assert_eq!(p(none), None, "{none}");
        }
        for m in CATALOGUE {
            assert!(!m.yield_source.is_empty());
            // A yield stress in Pa: between 10 MPa and 10 GPa, below E.
            if let Some(y) = m.yield_stress {
                assert!(y > 1e7 && y < 1e10 && y < m.youngs_modulus, "{}", m.name);
            }
        }
    }

    /// `p_0/Y` at first yield from the Hertz stresses on the axis of a contact of spheres
    /// (Johnson 1985, chapter 3): `σ_z/p_0 = −1/(1 + ζ²)`,
    /// `σ_r/p_0 = −(1 + ν)(1 − ζ atan(1/ζ)) + 1/(2(1 + ζ²))`, `ζ = z/a`; yield (Tresca, and von
    /// Mises since `σ_r = σ_θ` there) where `max |σ_z − σ_r| = Y`.
    fn first_yield_factor(nu: f64) -> (f64, f64) {
        let mut best = (0.0, 0.0);
        for i in 1..=20_000 {
            let z = i as f64 * 1e-4;
            let sz = -1.0 / (1.0 + z * z);
            let sr = -(1.0 + nu) * (1.0 - z * (1.0 / z).atan()) + 0.5 / (1.0 + z * z);
            let d = (sz - sr).abs();
            if d > best.0 {
                best = (d, z);
            }
        }
        (1.0 / best.0, best.1)
    }

    #[test]
    fn the_first_yield_factor_is_johnsons() {
        let (factor, depth) = first_yield_factor(0.3);
        // Johnson: 1.60 Y at 0.48 a (his 0.31 p_0 is the shear stress, half the difference).
        assert!((factor - FIRST_YIELD_FACTOR).abs() < 0.015, "{factor}");
        assert!((depth - 0.48).abs() < 0.005, "{depth}");
        assert!((factor - 1.613).abs() < 5e-4, "{factor}");
        assert!((first_yield_factor(0.25).0 - 1.554).abs() < 5e-4);
        assert!((first_yield_factor(0.35).0 - 1.674).abs() < 5e-4);
    }
}
