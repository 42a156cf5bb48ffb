//! Characteristic times of contacts, for choosing the time step.
//!
//! - Rayleigh time `T_R = πR√(ρ/G)/(0.1631ν + 0.8766)`: the time a Rayleigh
//!   surface wave takes to cross a sphere; DEM codes commonly use a step of
//!   10–40 % of it.
//! - Hertz contact duration `t_c = 2.9432 δ_max/v` (undamped impact; Johnson,
//!   *Contact Mechanics*, 1985, §11.4), with `δ_max = (15m*v²/(16E*√R*))^{2/5}`.
//!   Resolving a contact with ≥ 50 steps keeps the integration error small.

use super::material::Material;
use super::normal::hertz_max_overlap;

/// Rayleigh time `πR√(ρ/G)/(0.1631ν + 0.8766)`, s, of a sphere of `radius` (m)
/// made of `material` (`G = E/(2(1+ν))`).
pub fn rayleigh_time(material: &Material, radius: f64) -> f64 {
    let g = material.shear_modulus();
    std::f64::consts::PI * radius * (material.density / g).sqrt()
        / (0.1631 * material.poisson_ratio + 0.8766)
}

/// Duration of an undamped Hertz impact, `2.9432 δ_max/v`, s, for effective
/// modulus `e_star` (Pa), radius `r_star` (m), mass `m_star` (kg) and relative
/// normal impact speed `v_normal` (m/s, > 0). Equivalently
/// `2.8683 (m*²/(E*²R* v))^{1/5}`.
pub fn hertz_contact_time(e_star: f64, r_star: f64, m_star: f64, v_normal: f64) -> f64 {
    2.9432 * hertz_max_overlap(e_star, r_star, m_star, v_normal) / v_normal
}
