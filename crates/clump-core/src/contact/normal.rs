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

/// The stiffness scale `s` of the running law: `√(R*δ)` (Hertz; `R*`, `δ`
/// in m) or 1 (linear). Stiffnesses are `k = k̂ s` and dashpots
/// `γ = ĝ √(s m*)` ([`super::damping::dashpot`]).
#[inline(always)]
pub fn stiffness_scale(hertz: bool, r_star: f64, overlap: f64) -> f64 {
    if hertz {
        (r_star * overlap).sqrt()
    } else {
        1.0
    }
}

/// The law's constants of a normal law: `(hertz, k̂_n, k̂_t, energy factor)`
/// with `k̂_n = (4/3)E*` (Pa) and `k̂_t = 8G*` (Pa) for Hertz–Mindlin, the
/// given `k_n`, `k_t` (N/m) for linear; the normal spring energy is
/// `factor · F_el δ` (2/5 Hertz, 1/2 linear). `E*`, `G*` in Pa.
pub fn stiffness_coefficients(law: NormalLaw, e_star: f64, g_star: f64) -> (bool, f64, f64, f64) {
    match law {
        NormalLaw::Hertz => (true, 4.0 / 3.0 * e_star, 8.0 * g_star, 0.4),
        NormalLaw::Linear { kn, kt } => (false, kn, kt, 0.5),
    }
}

/// Elastic normal force `F_el = k_n δ`, N, for the (secant) stiffness
/// `k_n = k̂_n s` (N/m) and overlap `δ` (m): Hertz `(4/3)E*√(R*δ) δ`.
#[inline(always)]
pub fn elastic_force(kn: f64, overlap: f64) -> f64 {
    kn * overlap
}

/// Energy of the normal spring, `factor · F_el δ`, J.
#[inline(always)]
pub fn spring_energy(factor: f64, f_el: f64, overlap: f64) -> f64 {
    factor * f_el * overlap
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
