//! Normal force laws.
//!
//! - **Hertz**: `F_el = (4/3) E* √R* δ^{3/2}`. Secant stiffness
//!   `k_n = F_el/δ = (4/3)E*√(R*δ)`, tangent stiffness
//!   `S_n = dF_el/dδ = 2E*√(R*δ)`, stored energy `(2/5) F_el δ`.
//! - **Linear** (Cundall–Strack): `F_el = k_n δ`, `S_n = k_n`, energy `½ k_n δ²`.
//!
//! In both cases the total normal force on `i` along `+n` is
//! `F_n = F_el − γ_n v_n` with `v_n = v_rel·n` (negative while approaching), see
//! [`super::damping`].

use serde::{Deserialize, Serialize};

/// Normal force law.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalLaw {
    /// Hertz–Mindlin: `F = (4/3)E*√R* δ^{3/2}`, tangential stiffness
    /// `k_t = 8G*√(R*δ)`.
    #[default]
    Hertz,
    /// Linear spring–dashpot (Cundall–Strack) with constant stiffnesses.
    Linear {
        /// Normal stiffness `k_n`, N/m (`> 0`).
        kn: f64,
        /// Tangential stiffness `k_t`, N/m (`≥ 0`; 0 disables tangential forces).
        kt: f64,
    },
}

/// Hertz elastic normal force `(4/3)E*√R* δ^{3/2}`, N, for `E*` in Pa, `R*` and
/// `δ` in m.
pub fn hertz_force(e_star: f64, r_star: f64, overlap: f64) -> f64 {
    4.0 / 3.0 * e_star * (r_star * overlap).sqrt() * overlap
}

/// Hertz tangent normal stiffness `S_n = 2E*√(R*δ)`, N/m.
pub fn hertz_tangent_stiffness(e_star: f64, r_star: f64, overlap: f64) -> f64 {
    2.0 * e_star * (r_star * overlap).sqrt()
}

/// Mindlin tangential stiffness `k_t = 8G*√(R*δ)`, N/m.
pub fn mindlin_tangential_stiffness(g_star: f64, r_star: f64, overlap: f64) -> f64 {
    8.0 * g_star * (r_star * overlap).sqrt()
}

/// Maximum overlap of an undamped Hertz impact,
/// `δ_max = (15 m* v²/(16 E*√R*))^{2/5}`, m, for relative normal speed `v` (m/s).
pub fn hertz_max_overlap(e_star: f64, r_star: f64, m_star: f64, v_normal: f64) -> f64 {
    (15.0 * m_star * v_normal * v_normal / (16.0 * e_star * r_star.sqrt())).powf(0.4)
}

/// Maximum force of an undamped Hertz impact, `(4/3)E*√R* δ_max^{3/2}`, N.
pub fn hertz_max_force(e_star: f64, r_star: f64, m_star: f64, v_normal: f64) -> f64 {
    hertz_force(
        e_star,
        r_star,
        hertz_max_overlap(e_star, r_star, m_star, v_normal),
    )
}
