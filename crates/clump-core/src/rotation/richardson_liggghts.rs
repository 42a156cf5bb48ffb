//! LIGGGHTS' (and LAMMPS') own Richardson orientation update,
//! `MathExtra::richardson`, step for step, so that a LIGGGHTS user
//! reproduces a `fix multisphere` trajectory to round-off (docs/theory.md T-19).
//!
//! With `dtq = dt/2` and the world angular velocity `ω` from the world
//! angular momentum `L` at the current orientation, each sub-step is the
//! *linearised* quaternion update `q ← normalise(q + dtq·h (0, ω) ⊗ q)` (the
//! time derivative `q̇ = ½ ω ⊗ q`, world ω): a full step `q_full`, two half
//! steps (the second with `ω` recomputed from `L` at the first half step's
//! orientation), and `q1 = normalise(2 q_half − q_full)`. Unlike
//! [`super::richardson`] (exact exponential sub-steps), a rotation at
//! constant ω is not exact: the linearised sub-step errs by `O((|ω| dt)³)`.

use glam::{DQuat, DVec3};

/// LAMMPS `MathExtra::vecquat`: `(0, a) ⊗ b`.
#[inline(always)]
fn vecquat(a: DVec3, b: DQuat) -> DQuat {
    DQuat::from_xyzw(
        b.w * a.x + a.y * b.z - a.z * b.y,
        b.w * a.y + a.z * b.x - a.x * b.z,
        b.w * a.z + a.x * b.y - a.y * b.x,
        -a.x * b.x - a.y * b.y - a.z * b.z,
    )
}

/// LAMMPS `MathExtra::qnormalize`: multiply by `1/√(q·q)`.
#[inline(always)]
fn qnormalize(q: DQuat) -> DQuat {
    let norm = 1.0 / (q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z).sqrt();
    DQuat::from_xyzw(q.x * norm, q.y * norm, q.z * norm, q.w * norm)
}

/// LAMMPS `MathExtra::mq_to_omega`: world `ω = R I⁻¹ Rᵀ L` with `R` from
/// `quat_to_mat`; a zero moment gives a zero body component.
#[inline(always)]
fn mq_to_omega(l: DVec3, q: DQuat, moments: DVec3) -> DVec3 {
    let (w2, i2, j2, k2) = (q.w * q.w, q.x * q.x, q.y * q.y, q.z * q.z);
    let (twoij, twoik, twojk) = (2.0 * q.x * q.y, 2.0 * q.x * q.z, 2.0 * q.y * q.z);
    let (twoiw, twojw, twokw) = (2.0 * q.x * q.w, 2.0 * q.y * q.w, 2.0 * q.z * q.w);
    let r = [
        [w2 + i2 - j2 - k2, twoij - twokw, twojw + twoik],
        [twoij + twokw, w2 - i2 + j2 - k2, twojk - twoiw],
        [twoik - twojw, twojk + twoiw, w2 - i2 - j2 + k2],
    ];
    let mut wb = [0.0; 3];
    let m = [moments.x, moments.y, moments.z];
    for a in 0..3 {
        let t = r[0][a] * l.x + r[1][a] * l.y + r[2][a] * l.z;
        wb[a] = if m[a] == 0.0 { 0.0 } else { t / m[a] };
    }
    DVec3::new(
        r[0][0] * wb[0] + r[0][1] * wb[1] + r[0][2] * wb[2],
        r[1][0] * wb[0] + r[1][1] * wb[1] + r[1][2] * wb[2],
        r[2][0] * wb[0] + r[2][1] * wb[1] + r[2][2] * wb[2],
    )
}

/// Torque-free drift over `dt` (s): LIGGGHTS' `richardson(q, m, w, moments,
/// dtq = dt/2)` from orientation `q` (body → world) under the constant
/// WORLD-frame angular momentum `l_world` (kg m²/s), principal moments
/// `inertia` (body frame, kg m²); the starting `ω` is `mq_to_omega` at `q`
/// (LIGGGHTS' `angmom_to_omega` from `ex, ey, ez`, the same to round-off).
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    drift_omega(q, l_world, inertia, dt).0
}

/// [`drift`], also returning the world angular velocity (rad/s) that
/// `MathExtra::richardson` leaves in its `w` argument: `ω` from `L` at the
/// first half sub-step's orientation. LIGGGHTS' `fix multisphere` moves the
/// spheres with that `ω` until the final half kick recomputes it, so the
/// contact velocities of the step use it (the DEM step does the same).
pub fn drift_omega(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> (DQuat, DVec3) {
    let dtq = 0.5 * dt;
    let w = mq_to_omega(l_world, q, inertia);
    let wq = vecquat(w, q);
    let qfull = qnormalize(q + wq * dtq);
    let qhalf = qnormalize(q + wq * (0.5 * dtq));
    let w = mq_to_omega(l_world, qhalf, inertia);
    let wq = vecquat(w, qhalf);
    let qhalf = qnormalize(qhalf + wq * (0.5 * dtq));
    (qnormalize(qhalf * 2.0 - qfull), w)
}
