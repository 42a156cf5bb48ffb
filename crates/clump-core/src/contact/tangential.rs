//! Tangential force: incremental history spring, dashpot and Coulomb limit.
//!
//! Per evaluation, with `n` the current unit normal and
//! `v_t = v_rel − (v_rel·n) n` the tangential relative velocity of the contact
//! points (m/s, world):
//! 1. **Rotate** the stored spring `ξ` (m, world) into the current tangent
//!    plane: remove its normal component and rescale it to its old length
//!    ([`rotate_into_plane`]); this follows the rotation of the contact without
//!    creating or destroying spring energy.
//! 2. **Increment**: `ξ ← ξ + v_t Δt`.
//! 3. **Trial force** on `i`: `F_t = −k_t ξ − γ_t v_t`, where `k_t` is
//!    `8G*√(R*δ)` (Hertz–Mindlin, evaluated at the current overlap) or the
//!    constant linear `k_t`, and `γ_t` is the tangential dashpot of
//!    [`super::damping`].
//! 4. **Coulomb limit** on the total tangential force: if `|F_t| > μ|F_n|`, then
//!    `F_t ← μ|F_n| F_t/|F_t|` and the spring is truncated so that the elastic
//!    part alone is consistent with the limited force,
//!    `ξ = −(F_t + γ_t v_t)/k_t` (Luding 2008, "Cohesive, frictional powders:
//!    contact models for tension", Granular Matter 10:235). Hence a contact in
//!    sustained sliding carries exactly `|F_t| = μ|F_n|`. (LIGGGHTS instead
//!    compares the elastic part alone with the limit and switches the dashpot
//!    off while sliding; both agree when `γ_t = 0`.)
//!
//! `|F_n|` is the magnitude of the total (elastic + damping) normal force.
//! With `k_t = 0` (a linear law with `kt = 0`) there is no tangential force and
//! the spring stays zero.

use glam::DVec3;

/// Rotates `v` (world) into the plane normal to the unit vector `n`: removes
/// its normal component and rescales the rest to the original length `|v|`.
/// If `v` is (almost) parallel to `n` (in-plane part below 10⁻⁶ of its length),
/// the result is zero. Same units as `v`.
#[inline(always)]
pub fn rotate_into_plane(v: DVec3, n: DVec3) -> DVec3 {
    let l0 = v.length_squared();
    let p = v - v.dot(n) * n;
    let lp = p.length_squared();
    let scale = if lp > 1e-12 * l0 {
        (l0 / lp).sqrt()
    } else {
        0.0
    };
    p * scale
}

/// Tangential force on `i` (N, world) from the history spring, updating the
/// spring `xi` (m, world) in place as described in the module docs.
///
/// - `n`: unit normal (world); `v_t`: tangential relative velocity (m/s, world,
///   already in the tangent plane); `dt`: time step (s);
/// - `kt`: tangential stiffness (N/m); `inv_kt`: `1/kt`, or 0 when `kt = 0`;
/// - `gamma_t`: tangential dashpot coefficient (kg/s);
/// - `f_max`: Coulomb limit `μ|F_n|` (N).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn history_spring(
    xi: &mut DVec3,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    kt: f64,
    inv_kt: f64,
    gamma_t: f64,
    f_max: f64,
) -> DVec3 {
    let s = rotate_into_plane(*xi, n) + v_t * dt;
    let f = -kt * s - gamma_t * v_t;
    let f2 = f.length_squared();
    if f2 > f_max * f_max {
        let fl = f * (f_max / f2.sqrt());
        *xi = -(fl + gamma_t * v_t) * inv_kt;
        fl
    } else {
        // kt = 0 ⇒ inv_kt = 0 and f = 0: keep the spring at zero.
        *xi = if inv_kt > 0.0 { s } else { DVec3::ZERO };
        f
    }
}
