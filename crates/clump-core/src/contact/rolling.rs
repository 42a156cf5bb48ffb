//! Rolling resistance: a couple on `i` (and its opposite on `j`) opposing the
//! relative rolling of the two surfaces.
//!
//! Both models use the **rolling** part of the relative angular velocity,
//! `ω_r = ω_rel − (ω_rel·n) n` (rad/s, world), i.e. `rel_omega` projected onto
//! the tangent plane: the twisting (torsion) component about the normal is not
//! resisted. (LIGGGHTS' `rolling_friction cdt` likewise removes the normal
//! component.) The limiting couple is `M_max = μ_r R* F_n` (N m) with `F_n` the
//! total normal force after the tensile clamp (`≥ 0`; `|F_n|` for a pair with
//! `tensile = true`), the same normal force as the Coulomb limit.
//!
//! - **CDT** (constant directional torque, Zhou et al. 1999):
//!   `M = −μ_r R* F_n ω̂_r`; zero when `|ω_r| ≤ 10⁻¹² rad/s` (no NaN). Being
//!   discontinuous at `ω_r = 0`, it can chatter at rest.
//! - **EPSD** (elastic–plastic spring–dashpot; Iwashita & Oda 1998, Ai, Chen,
//!   Rotter & Ooi 2011, Powder Technol. 206:269, model type C): an incremental
//!   spring `M_r ← M_r − k_r ω_r Δt` (stored in [`super::ContactHistory::rolling`],
//!   rotated into the current tangent plane like the tangential spring), with
//!   `k_r = 2.25 k_n μ_r² R*²`, `k_n` the **secant** normal stiffness `F_el/δ`
//!   (Hertz: `(4/3)E*√(R*δ)`, as in LIGGGHTS' `epsd`; linear: `k_n`), limited
//!   to `|M_r| ≤ M_max` (full mobilisation: the spring is scaled back). The
//!   optional viscous part `M_d = −C_r ω_r`, `C_r = η_r · 2√(I_r k_r)`, with
//!   `I_r = (7/5) m* R*²` (the sphere–wall value of Ai et al.'s equivalent
//!   moment of inertia), acts only while the spring is not fully mobilised.
//!   `η_r = 0` by default (see [`super::ContactModel::with_rolling_damping`]).

use super::tangential::rotate_into_plane;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Rolling-resistance law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RollingLaw {
    /// No rolling resistance (default).
    #[default]
    None,
    /// Constant directional torque `−μ_r R* F_n ω̂_r`.
    Cdt,
    /// Elastic–plastic spring–dashpot (history spring limited to `μ_r R* F_n`).
    Epsd,
}

/// Below this rolling speed (rad/s) the CDT couple is zero.
pub const CDT_OMEGA_EPS: f64 = 1e-12;

/// Rolling part of the relative angular velocity, `ω − (ω·n)n`, rad/s, world.
#[inline(always)]
pub fn rolling_omega(rel_omega: DVec3, n: DVec3) -> DVec3 {
    rel_omega - rel_omega.dot(n) * n
}

/// CDT couple on `i`, N m, world: `−m_max ω̂_r` (zero if `|ω_r| ≤ 10⁻¹²`).
/// `omega_r` is the rolling angular velocity (rad/s, world), `m_max = μ_r R* F_n`
/// (N m, `≥ 0`).
#[inline(always)]
pub fn cdt(omega_r: DVec3, m_max: f64) -> DVec3 {
    let w2 = omega_r.length_squared();
    if w2 > CDT_OMEGA_EPS * CDT_OMEGA_EPS {
        omega_r * (-m_max / w2.sqrt())
    } else {
        DVec3::ZERO
    }
}

/// EPSD couple on `i`, N m, world, updating the spring `m_r` (N m, world) in
/// place. `n` unit normal; `omega_r` rolling angular velocity (rad/s); `dt` (s);
/// `kr` rolling stiffness (N m/rad); `cr` viscous coefficient (N m s/rad);
/// `m_max = μ_r R* F_n` (N m, `≥ 0`). Returns the couple and the spring energy
/// `½|M_r|²/k_r` (J, 0 if `k_r = 0`).
#[inline(always)]
pub fn epsd(
    m_r: &mut DVec3,
    n: DVec3,
    omega_r: DVec3,
    dt: f64,
    kr: f64,
    cr: f64,
    m_max: f64,
) -> (DVec3, f64) {
    let mut m = rotate_into_plane(*m_r, n) - kr * dt * omega_r;
    let m2 = m.length_squared();
    let torque = if m2 >= m_max * m_max {
        // Fully mobilised: plastic rolling, no dashpot.
        m = if m2 > 0.0 {
            m * (m_max / m2.sqrt())
        } else {
            DVec3::ZERO
        };
        m
    } else {
        m - cr * omega_r
    };
    *m_r = m;
    let energy = if kr > 0.0 {
        0.5 * m.length_squared() / kr
    } else {
        0.0
    };
    (torque, energy)
}
