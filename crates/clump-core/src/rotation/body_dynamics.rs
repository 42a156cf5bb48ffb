//! Rigid-body rotational kinematics shared by the integrators: angular
//! velocity from angular momentum, Euler's equations, kinetic energy.
//!
//! A zero principal moment is tolerated everywhere: its inverse is taken as
//! zero, so the matching angular-velocity component is zero (never NaN).

use glam::{DMat3, DQuat, DVec3};

/// Component-wise inverse of the principal moments (body frame, 1/(kg m²));
/// a moment that is not strictly positive gives 0.
/// Equal moments (a spherical top) take one division.
#[inline]
pub fn inverse_inertia(inertia: DVec3) -> DVec3 {
    let inv = |i: f64| if i > 0.0 { 1.0 / i } else { 0.0 };
    if inertia.x == inertia.y && inertia.y == inertia.z {
        return DVec3::splat(inv(inertia.x));
    }
    DVec3::new(inv(inertia.x), inv(inertia.y), inv(inertia.z))
}

/// Angular velocity in the BODY frame (rad/s): `ω_b = I⁻¹ (q⁻¹ L)`, from the
/// body → world orientation `q` and the WORLD-frame angular momentum `l_world`
/// (kg m²/s); `inertia` = principal moments (body frame, kg m²).
#[inline]
pub fn omega_body(q: DQuat, l_world: DVec3, inertia: DVec3) -> DVec3 {
    (q.conjugate() * l_world) * inverse_inertia(inertia)
}

/// Angular velocity in the WORLD frame (rad/s): `ω = R I⁻¹ Rᵀ L` with
/// `R = R(q)` (body → world), `l_world` the WORLD-frame angular momentum
/// (kg m²/s) and `inertia` the principal moments (body frame, kg m²).
/// A zero principal moment gives a zero component about that axis.
/// For a spherical top (three equal moments) `ω = L/I`, with no rotation.
#[inline]
pub fn omega_world(q: DQuat, l_world: DVec3, inertia: DVec3) -> DVec3 {
    omega_world_inv(q, l_world, inverse_inertia(inertia))
}

/// [`omega_world`] from the inverse principal moments `inv_inertia` (body
/// frame, 1/(kg m²), see [`inverse_inertia`]).
#[inline(always)]
pub fn omega_world_inv(q: DQuat, l_world: DVec3, inv_inertia: DVec3) -> DVec3 {
    let inv = inv_inertia;
    if inv.x == inv.y && inv.y == inv.z {
        return l_world * inv.x;
    }
    omega_world_rot(&DMat3::from_quat(q), l_world, inv)
}

/// [`omega_world`] from the rotation matrix `rot = R(q)` (body → world,
/// `Aᵀ` of docs/theory.md T-2) and the inverse principal moments `inv_inertia` (body frame,
/// 1/(kg m²), see [`inverse_inertia`]): `ω = R (I⁻¹ ⊙ (Rᵀ L))`, world frame,
/// rad/s. The integration pass builds `R` once per body and reuses it for
/// the body's spheres.
#[inline(always)]
pub fn omega_world_rot(rot: &DMat3, l_world: DVec3, inv_inertia: DVec3) -> DVec3 {
    if inv_inertia.x == inv_inertia.y && inv_inertia.y == inv_inertia.z {
        // spherical top: R (c Rᵀ L) = c L exactly (no round-off of the rotation)
        return l_world * inv_inertia.x;
    }
    omega_world_rot_general(rot, l_world, inv_inertia)
}

/// [`omega_world_rot`] of a body that is not a spherical top, by the
/// general formula `R I⁻¹ Rᵀ L` with no branch.
#[inline(always)]
pub fn omega_world_rot_general(rot: &DMat3, l_world: DVec3, inv_inertia: DVec3) -> DVec3 {
    let l_body = DVec3::new(
        rot.x_axis.dot(l_world),
        rot.y_axis.dot(l_world),
        rot.z_axis.dot(l_world),
    );
    *rot * (l_body * inv_inertia)
}

/// Euler's equations: angular acceleration in the BODY frame (rad/s²),
/// `ω̇_b = I⁻¹ (τ_b − ω_b × I ω_b)`, from the body-frame angular velocity
/// `omega_b` (rad/s), principal moments `inertia` (kg m²) and body-frame torque
/// `torque_b` (N m).
#[inline]
pub fn angular_acceleration_body(omega_b: DVec3, inertia: DVec3, torque_b: DVec3) -> DVec3 {
    (torque_b - omega_b.cross(inertia * omega_b)) * inverse_inertia(inertia)
}

/// Rotational kinetic energy (J): `T = ½ Σ L_b,k² / I_k` from the body → world
/// orientation `q` and the WORLD-frame angular momentum `l_world` (kg m²/s).
#[inline]
pub fn rotational_energy(q: DQuat, l_world: DVec3, inertia: DVec3) -> f64 {
    let l_b = q.conjugate() * l_world;
    0.5 * l_b.dot(l_b * inverse_inertia(inertia))
}
