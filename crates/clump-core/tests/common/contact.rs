//! Materials shared by the contact-law tests (contact_laws.rs and
//! contact_friction.rs): the Chung & Ooi (2011) materials (see
//! shared/validation/REFERENCE.md §3) and a rigid wall.
#![allow(dead_code)]

use clump_core::contact::Material;

/// Mass of a sphere of material `m` and radius `r` (m), kg.
pub fn sphere_mass(m: &Material, r: f64) -> f64 {
    clump_validate::setup::sphere_mass(r, m.density)
}

// Chung & Ooi (2011) materials: Young's modulus (Pa), Poisson ratio, density (kg/m³).
pub fn glass() -> Material {
    Material {
        youngs_modulus: 4.8e10,
        poisson_ratio: 0.20,
        density: 2800.0,
    }
}
pub fn limestone() -> Material {
    Material {
        youngs_modulus: 2.0e10,
        poisson_ratio: 0.25,
        density: 2500.0,
    }
}
pub fn al_alloy() -> Material {
    Material {
        youngs_modulus: 7.0e10,
        poisson_ratio: 0.30,
        density: 2699.0,
    }
}
pub fn mg_alloy() -> Material {
    Material {
        youngs_modulus: 4.0e10,
        poisson_ratio: 0.35,
        density: 1800.0,
    }
}
pub fn alumina() -> Material {
    Material {
        youngs_modulus: 3.8e11,
        poisson_ratio: 0.23,
        density: 4000.0,
    }
}
pub fn cast_iron() -> Material {
    Material {
        youngs_modulus: 1.0e11,
        poisson_ratio: 0.25,
        density: 7000.0,
    }
}
/// A rigid wall (infinite Young's modulus).
pub fn wall() -> Material {
    Material {
        youngs_modulus: f64::INFINITY,
        poisson_ratio: 0.3,
        density: 1.0,
    }
}
