//! The bodies of an impact: elastic constants of a material, the effective moduli of a pair,
//! and a sphere's mass, radius and inertia factor.

use super::{query, InvalidInput};

/// Elastic constants of an isotropic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    /// Young's modulus `E` (Pa), > 0; `+∞` for a rigid body.
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`, in (−1, 0.5].
    pub poisson_ratio: f64,
}

impl Elastic {
    /// A rigid body (`E = ∞`; it adds no compliance).
    pub const RIGID: Elastic = Elastic {
        youngs_modulus: f64::INFINITY,
        poisson_ratio: 0.0,
    };

    #[inline]
    /// Check `E > 0` (`∞` allowed) and `−1 < ν ≤ 0.5`.
    pub fn validate(&self) -> Result<(), InvalidInput> {
        if self.youngs_modulus.is_nan() || self.youngs_modulus <= 0.0 {
            return Err(query(
                "youngs_modulus",
                self.youngs_modulus,
                "> 0 Pa (inf for a rigid body)",
            ));
        }
        let nu = self.poisson_ratio;
        if !(-1.0..=0.5).contains(&nu) || nu == -1.0 {
            return Err(query("poisson_ratio", nu, "in (-1, 0.5]"));
        }
        Ok(())
    }

    #[inline]
    /// Shear modulus `G = E/(2(1 + ν))` (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }
}

#[inline]
/// Effective moduli of a pair, `(E*, G*)` in Pa:
/// `1/E* = Σ (1 − ν²)/E`, `1/G* = Σ (2 − ν)/(4G)`. A rigid body contributes nothing.
pub fn effective_moduli(a: &Elastic, b: &Elastic) -> (f64, f64) {
    let compliance = |m: &Elastic| {
        if m.youngs_modulus.is_infinite() {
            (0.0, 0.0)
        } else {
            (
                (1.0 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus,
                (2.0 - m.poisson_ratio) / (4.0 * m.shear_modulus()),
            )
        }
    };
    let (ea, ga) = compliance(a);
    let (eb, gb) = compliance(b);
    (1.0 / (ea + eb), 1.0 / (ga + gb))
}

/// Mass, radius and inertia factor of a sphere (rigid-body data only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Mass `m` (kg), > 0.
    pub mass: f64,
    /// Radius `R` (m), > 0.
    pub radius: f64,
    /// Inertia factor `κ` in `I = κ m R²` (2/5 solid, 2/3 thin shell), > 0.
    pub kappa: f64,
}

impl Body {
    #[inline]
    /// Moment of inertia `I = κ m R²` (kg m²).
    pub fn inertia(&self) -> f64 {
        self.kappa * self.mass * self.radius * self.radius
    }

    #[inline]
    pub(super) fn validate(&self, which: &'static [&'static str; 3]) -> Result<(), InvalidInput> {
        let ok = |v: f64| v.is_finite() && v > 0.0;
        if ok(self.mass) && ok(self.radius) && ok(self.kappa) {
            return Ok(());
        }
        self.invalid(which)
    }

    #[cold]
    fn invalid(&self, which: &'static [&'static str; 3]) -> Result<(), InvalidInput> {
        for (name, v) in which.iter().zip([self.mass, self.radius, self.kappa]) {
            if !(v.is_finite() && v > 0.0) {
                return Err(query(name, v, "a finite number > 0"));
            }
        }
        Ok(())
    }
}
