//! Elastic materials and the mixing rules of Hertz–Mindlin theory.
//!
//! - `E* = [(1−ν₁²)/E₁ + (1−ν₂²)/E₂]⁻¹`
//! - `G* = [2(2−ν₁)(1+ν₁)/E₁ + 2(2−ν₂)(1+ν₂)/E₂]⁻¹`
//! - `R* = R₁R₂/(R₁+R₂)`, `m* = m₁m₂/(m₁+m₂)`
//!
//! A rigid wall has `E = ∞`: its compliance terms vanish, so against a wall
//! `E* = E/(1−ν²)` and `G* = E/(2(2−ν)(1+ν))` of the sphere's material.

use super::ContactError;
use serde::{Deserialize, Serialize};

/// Elastic material. A rigid wall uses `youngs_modulus = f64::INFINITY` (then
/// `(1−ν²)/E = 0`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus `E`, Pa (`> 0`; `f64::INFINITY` for a rigid wall).
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`, dimensionless, in `(−1, 0.5)`.
    pub poisson_ratio: f64,
    /// Density `ρ`, kg/m³ (`> 0`; not used by the contact law itself, and
    /// irrelevant for a rigid wall, where any value `≥ 0` is accepted).
    pub density: f64,
}

impl Material {
    /// A rigid material (`E = ∞`, `ν = 0`, `ρ = 0`) for walls.
    pub const fn rigid() -> Self {
        Material {
            youngs_modulus: f64::INFINITY,
            poisson_ratio: 0.0,
            density: 0.0,
        }
    }

    /// Whether the material is rigid (`E = ∞`).
    pub fn is_rigid(&self) -> bool {
        self.youngs_modulus == f64::INFINITY
    }

    /// Shear modulus `G = E/(2(1+ν))`, Pa.
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Normal compliance term `(1−ν²)/E`, 1/Pa (zero for a rigid material).
    pub fn normal_compliance(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus
    }

    /// Tangential compliance term `2(2−ν)(1+ν)/E = (2−ν)/G`, 1/Pa (zero for a
    /// rigid material).
    pub fn tangential_compliance(&self) -> f64 {
        2.0 * (2.0 - self.poisson_ratio) * (1.0 + self.poisson_ratio) / self.youngs_modulus
    }

    /// Checks the ranges: `E > 0` (∞ allowed), `ν ∈ (−1, 0.5)`, `ρ > 0`
    /// (`ρ ≥ 0` for a rigid material). `which` names the material in the error.
    pub fn validate(&self, which: &'static str) -> Result<(), ContactError> {
        let err = |what: String| Err(ContactError::Material { which, what });
        let (e, nu, rho) = (self.youngs_modulus, self.poisson_ratio, self.density);
        if e.is_nan() || e <= 0.0 {
            return err(format!(
                "Young's modulus must be > 0 Pa (or infinite for a rigid wall), got {e}"
            ));
        }
        if !(nu > -1.0 && nu < 0.5) {
            return err(format!("Poisson's ratio must lie in (-1, 0.5), got {nu}"));
        }
        if self.is_rigid() {
            if rho.is_nan() || rho < 0.0 {
                return err(format!("density must be >= 0 kg/m^3, got {rho}"));
            }
        } else if rho.is_nan() || rho <= 0.0 {
            return err(format!("density must be > 0 kg/m^3, got {rho}"));
        }
        Ok(())
    }
}

/// Effective Young's modulus `E* = [(1−ν₁²)/E₁ + (1−ν₂²)/E₂]⁻¹`, Pa
/// (infinite if both materials are rigid).
pub fn effective_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / (a.normal_compliance() + b.normal_compliance())
}

/// Effective shear modulus `G* = [2(2−ν₁)(1+ν₁)/E₁ + 2(2−ν₂)(1+ν₂)/E₂]⁻¹`, Pa
/// (infinite if both materials are rigid).
pub fn effective_shear_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / (a.tangential_compliance() + b.tangential_compliance())
}

/// Effective radius `R* = R₁R₂/(R₁+R₂)`, m. Pass `f64::INFINITY` for a plane
/// to get `R* = R₁`.
pub fn effective_radius(r1: f64, r2: f64) -> f64 {
    if r2 == f64::INFINITY {
        r1
    } else if r1 == f64::INFINITY {
        r2
    } else {
        r1 * r2 / (r1 + r2)
    }
}

/// Effective mass `m* = m₁m₂/(m₁+m₂)`, kg. Pass `f64::INFINITY` for a wall (or
/// any immovable body) to get `m* = m₁`.
pub fn effective_mass(m1: f64, m2: f64) -> f64 {
    if m2 == f64::INFINITY {
        m1
    } else if m1 == f64::INFINITY {
        m2
    } else {
        m1 * m2 / (m1 + m2)
    }
}
