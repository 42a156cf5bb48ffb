//! NO_SQUISH free-rotor integrator (Miller, Eleftheriou, Pattnaik, Ndirango,
//! Newns & Martyna, J. Chem. Phys. 116, 8649 (2002)), written from the paper's
//! idea.
//!
//! The free-rotor Hamiltonian `T = Σ_k L_b,k² / (2 I_k)` is split into the
//! three terms `T_k`. The flow of `T_k` alone is exact and simple: a rotation
//! of the body about its principal axis `k` at the constant rate
//! `L_b,k / I_k` (the body-frame momentum rotates the opposite way so that the
//! world-frame `L` stays fixed). The symmetric composition
//! `T3(dt/2) T2(dt/2) T1(dt) T2(dt/2) T3(dt/2)` is symplectic,
//! time-reversible and second order: `L_world` is kept exactly, and the energy
//! error stays bounded (no secular drift).

use glam::{DQuat, DVec3};

use crate::math::quat_from_rotation_vector;

/// Exact flow of `T_k` over `h` seconds: rotate the body about its principal
/// axis `k` (body frame) by the angle `L_b,k h / I_k`. A zero moment `I_k`
/// leaves `q` unchanged.
fn rotate_about_principal_axis(
    q: DQuat,
    l_world: DVec3,
    inertia: DVec3,
    k: usize,
    h: f64,
) -> DQuat {
    let i_k = inertia[k];
    if i_k <= 0.0 {
        return q;
    }
    let l_body = q.conjugate() * l_world;
    let mut rot = DVec3::ZERO;
    rot[k] = l_body[k] / i_k * h;
    // Body-frame rotation: right multiplication.
    q * quat_from_rotation_vector(rot)
}

/// Torque-free drift over `dt` (s): new body → world orientation from `q`, the
/// constant WORLD-frame angular momentum `l_world` (kg m²/s) and principal
/// moments `inertia` (body frame, kg m²). Time-reversible:
/// `drift(drift(q, L, I, dt), L, I, −dt) = q` to round-off.
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    let half = 0.5 * dt;
    let mut q = q;
    for (k, h) in [(2, half), (1, half), (0, dt), (1, half), (2, half)] {
        q = rotate_about_principal_axis(q, l_world, inertia, k, h);
    }
    q.normalize()
}
