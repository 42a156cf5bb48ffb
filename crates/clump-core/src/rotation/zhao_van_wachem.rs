//! Zhao & van Wachem (2013) quaternion integrator (Acta Mech. 224, 3091–3109),
//! as published by Zhao & van Wachem (2013; docs/theory.md T-20), with two slips of a common transcription corrected to the
//! paper's algorithm:
//! - quarter-point velocity `ω_b¼ = ω_b0 + ¼ ω̇_b0 Δt` and half-point velocity
//!   `ω_b½ = ω_b0 + ½ ω̇_b0 Δt` (the transcription swaps the ¼ and ½);
//! - the midpoint torque is rotated into the body frame with the predicted
//!   `q_½` (the transcription writes `q_0`).
//!
//! Step: `q_½ = exp(ω_¼ Δt/2) q_0` with `ω_¼ = q_0 ω_b¼` (world);
//! `ω̇_b½` from Euler's equations at `q_½`; `q_1 = exp(ω_½ Δt) q_0` with
//! `ω_½ = q_½ ω_b½`; `ω_b1 = ω_b0 + ω̇_b½ Δt`. The rotations use the exact
//! exponential map (`(cos(|ω|h/2), sin(|ω|h/2) ω̂)`, guarded at `ω = 0`), so
//! `|q| = 1` to round-off without renormalisation.

use glam::{DQuat, DVec3};

use super::body_dynamics::{angular_acceleration_body, inverse_inertia};
use super::RotState;
use crate::math::quat_from_rotation_vector;

/// Core update: from orientation `q0` (body → world) and BODY-frame angular
/// velocity `omega_b0` (rad/s), with WORLD-frame torque callback `torque`
/// (N m) and principal moments `inertia` (kg m²), returns `(q1, ω_b1)` after
/// `dt` seconds.
fn advance(
    q0: DQuat,
    omega_b0: DVec3,
    inertia: DVec3,
    torque: &mut dyn FnMut(DQuat) -> DVec3,
    dt: f64,
) -> (DQuat, DVec3) {
    let tau_b0 = q0.conjugate() * torque(q0);
    let alpha_b0 = angular_acceleration_body(omega_b0, inertia, tau_b0);
    let omega_b_quarter = omega_b0 + alpha_b0 * (0.25 * dt);
    let omega_b_half = omega_b0 + alpha_b0 * (0.5 * dt);
    let omega_quarter = q0 * omega_b_quarter;
    let q_half = quat_from_rotation_vector(omega_quarter * (0.5 * dt)) * q0;

    let tau_b_half = q_half.conjugate() * torque(q_half);
    let alpha_b_half = angular_acceleration_body(omega_b_half, inertia, tau_b_half);
    let omega_half = q_half * omega_b_half;
    let q1 = quat_from_rotation_vector(omega_half * dt) * q0;
    let omega_b1 = omega_b0 + alpha_b_half * dt;
    (q1, omega_b1)
}

/// One full step of `dt` seconds with the WORLD-frame torque callback
/// `torque(q)` (N m); updates `state.q` (body → world) and `state.l_world`
/// (kg m²/s, world frame). `inertia` = principal moments (body frame, kg m²).
pub fn step(state: &mut RotState, inertia: DVec3, torque: &mut dyn FnMut(DQuat) -> DVec3, dt: f64) {
    let omega_b0 = (state.q.conjugate() * state.l_world) * inverse_inertia(inertia);
    let (q1, omega_b1) = advance(state.q, omega_b0, inertia, torque, dt);
    state.q = q1;
    state.l_world = q1 * (inertia * omega_b1);
}

/// Torque-free drift over `dt` (s): the ZvW update with zero torque, keeping
/// the WORLD-frame angular momentum `l_world` (kg m²/s) unchanged; returns the
/// new body → world orientation. `inertia` = principal moments (kg m²).
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    let omega_b0 = (q.conjugate() * l_world) * inverse_inertia(inertia);
    advance(q, omega_b0, inertia, &mut |_| DVec3::ZERO, dt).0
}
