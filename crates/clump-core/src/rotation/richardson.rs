//! Richardson-extrapolated orientation update (the idea of LAMMPS/LIGGGHTS
//! `MathExtra::richardson`, written from its description).
//!
//! With `L` (world) fixed over the drift, `ω(q) = R I⁻¹ Rᵀ L` depends on the
//! orientation. A first-order update freezes `ω` over the sub-step:
//! `q ← exp(ω(q) h) q` (exact exponential map of the world-frame rotation
//! vector `ω h`). One full step `q_full`, two half steps `q_half2` (with `ω`
//! recomputed from `L` at the intermediate orientation), and the extrapolation
//! `q1 = normalise(2 q_half2 − q_full)` cancels the leading error term, giving
//! a second-order scheme.
//!
//! Difference from LAMMPS: LAMMPS uses the linearised sub-step
//! `q + ½ h ω ⊗ q` followed by normalisation; we use the exact exponential map,
//! so a rotation about a fixed principal axis (constant `ω`) is reproduced to
//! round-off (test R4), which the linearised form misses by `O((|ω| h)³)` per
//! step.

use glam::{DQuat, DVec3};

use super::body_dynamics::inverse_inertia;
use crate::math::quat_from_rotation_vector;

/// One first-order sub-step: rotate `q` (body → world) by the world-frame
/// angular velocity computed from `l_world` at `q`, frozen over `h` seconds;
/// `inv_inertia` = inverse principal moments (body frame, 1/(kg m²)). The
/// result is unit to round-off; [`drift`] normalises once at the end.
#[inline(always)]
fn frozen_omega_step(q: DQuat, l_world: DVec3, inv_inertia: DVec3, h: f64) -> DQuat {
    let w = q * ((q.conjugate() * l_world) * inv_inertia);
    quat_from_rotation_vector(w * h) * q
}

/// Torque-free drift over `dt` (s): new body → world orientation from `q`, the
/// constant WORLD-frame angular momentum `l_world` (kg m²/s) and principal
/// moments `inertia` (body frame, kg m²).
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    let inv = inverse_inertia(inertia);
    let q_full = frozen_omega_step(q, l_world, inv, dt);
    let q_half1 = frozen_omega_step(q, l_world, inv, 0.5 * dt);
    let q_half2 = frozen_omega_step(q_half1, l_world, inv, 0.5 * dt);
    // Both estimates are O(dt²) apart, hence in the same hemisphere.
    (q_half2 * 2.0 - q_full).normalize()
}
