//! Richardson-extrapolated orientation update (the idea of LAMMPS/LIGGGHTS
//! `MathExtra::richardson`, written from its description).
//!
//! With `L` (world) fixed over the drift, `ω(q) = R I⁻¹ Rᵀ L` depends on the
//! orientation. A first-order update freezes `ω` over the sub-step:
//! `q ← exp(ω(q) h) q` (exact exponential map of the world-frame rotation
//! vector `ω h`). One full step `q_full`, two half steps `q_half2` (with `ω`
//! recomputed from `L` at the intermediate orientation), and the extrapolation
//! `q1 = normalise(2 q_half2 − q_full)` cancels the leading error term, giving
//! a second-order scheme. The full step and the first half step share
//! `ω(q)` and one exponential (see `drift_inv`).
//!
//! Difference from LAMMPS: LAMMPS uses the linearised sub-step
//! `q + ½ h ω ⊗ q` followed by normalisation; we use the exact exponential map,
//! so a rotation about a fixed principal axis (constant `ω`) is reproduced to
//! round-off (test R4), which the linearised form misses by `O((|ω| h)³)` per
//! step.

use glam::{DQuat, DVec3};

use super::body_dynamics::inverse_inertia;
use crate::math::{quat_from_rotation_vector, quat_from_small_rotation_vector};

/// World-frame angular velocity (rad/s) `ω = R I⁻¹ Rᵀ L` at orientation `q`
/// (body → world) from the WORLD-frame angular momentum `l_world` (kg m²/s)
/// and the inverse principal moments `inv_inertia` (body frame, 1/(kg m²)).
#[inline(always)]
fn omega_at(q: DQuat, l_world: DVec3, inv_inertia: DVec3) -> DVec3 {
    q * ((q.conjugate() * l_world) * inv_inertia)
}

/// Torque-free drift over `dt` (s): new body → world orientation from `q`, the
/// constant WORLD-frame angular momentum `l_world` (kg m²/s) and principal
/// moments `inertia` (body frame, kg m²).
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    drift_inv(q, l_world, inverse_inertia(inertia), dt)
}

/// [`drift`] with the inverse principal moments `inv_inertia` (body frame,
/// 1/(kg m²)).
///
/// The full step and the first half step start from the same orientation
/// with the same frozen `ω₀ = ω(q)`, so they share it and one exponential:
/// `exp(ω₀ dt) = exp(ω₀ dt/2)²` (same axis; the square is the double-angle
/// formula). Cost: two `ω` evaluations and two exponential maps.
#[inline(always)]
fn drift_inv(q: DQuat, l_world: DVec3, inv_inertia: DVec3, dt: f64) -> DQuat {
    drift_by(q, l_world, inv_inertia, dt, |v| {
        (quat_from_rotation_vector(v), true)
    })
    .0
}

/// [`drift`] with the inverse principal moments `inv_inertia` (body frame,
/// 1/(kg m²)) and both exponentials by their series alone, with no branch
/// (for the first half's lanes): the orientation, and whether both series
/// hold (half angles below 0.01). Where they do, this is [`drift`]'s
/// result bit for bit; elsewhere the orientation is to be discarded.
#[inline(always)]
pub fn drift_small(q: DQuat, l_world: DVec3, inv_inertia: DVec3, dt: f64) -> (DQuat, bool) {
    drift_by(q, l_world, inv_inertia, dt, quat_from_small_rotation_vector)
}

/// The drift of [`drift_inv`] with the exponential map `exp` (the
/// quaternion of a rotation vector, and whether it holds).
#[inline(always)]
fn drift_by(
    q: DQuat,
    l_world: DVec3,
    inv_inertia: DVec3,
    dt: f64,
    exp: impl Fn(DVec3) -> (DQuat, bool),
) -> (DQuat, bool) {
    let half = 0.5 * dt;
    let w0 = omega_at(q, l_world, inv_inertia);
    let (e_half, held0) = exp(w0 * half);
    let q_full = (e_half * e_half) * q;
    let q_half1 = e_half * q;
    let w1 = omega_at(q_half1, l_world, inv_inertia);
    let (e1, held1) = exp(w1 * half);
    let q_half2 = e1 * q_half1;
    // Both estimates are O(dt²) apart, hence in the same hemisphere.
    ((q_half2 * 2.0 - q_full).normalize(), held0 & held1)
}
