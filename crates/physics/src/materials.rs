//! The built-in material catalogue: elastic constants and density with their source.
//!
//! Values are nominal room-temperature, quasi-static ones. The model is elastic: for the
//! polymers (strongly rate-, temperature- and moisture-dependent, and viscoelastic) treat the
//! result as a first estimate. Scene files name these materials (and may override any value:
//! `youngs_modulus`, `poisson_ratio`, `density`), `sweep gamma` prints γ of a pair of them,
//! and Python reads them as `oblique.materials` (docs/materials.md).

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
}

impl CatalogueMaterial {
    /// The elastic constants.
    pub fn elastic(&self) -> Elastic {
        Elastic {
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
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
    },
    CatalogueMaterial {
        name: "steel",
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
        source: "structural/bearing steel: E = 210 GPa, nu = 0.3 from EN 1993-1-1 (Eurocode 3) \
                 section 3.2.6; density 7850 kg/m^3 from EN 1991-1-1, Annex A",
    },
    CatalogueMaterial {
        name: "aluminium-6061-t6",
        youngs_modulus: 68.9e9,
        poisson_ratio: 0.33,
        density: 2700.0,
        source: "aluminium alloy 6061-T6: E = 68.9 GPa, nu = 0.33, density 2.70 g/cm^3 from \
                 the ASM Aerospace Specification Metals data sheet 'Aluminum 6061-T6; \
                 6061-T651' (MatWeb)",
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
    },
    CatalogueMaterial {
        name: "rigid",
        youngs_modulus: f64::INFINITY,
        poisson_ratio: 0.0,
        density: f64::NAN,
        source: "idealised rigid body (E = infinity): adds no compliance; a wall only",
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
}
