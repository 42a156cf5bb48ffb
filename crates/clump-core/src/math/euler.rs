//! Classical z-x-z Euler angles `(phi, theta, psi)` (docs/theory.md T-3, Goldstein's
//! convention), radians.
//!
//! The world frame `XYZ` is carried into the body frame `xyz` by a rotation
//! `phi` about `Z`, then `theta` about the new `x'`, then `psi` about the new
//! `z''`. Ranges: `phi, psi ∈ [0, 2π)`, `theta ∈ [0, π]`.
//!
//! The composite transformation matrix (docs/theory.md T-3, world → body) is
//! `A = A_psi A_theta A_phi` with the *passive* elementary rotations
//! `A_phi = [[cφ, sφ, 0], [−sφ, cφ, 0], [0, 0, 1]]`,
//! `A_theta = [[1, 0, 0], [0, cθ, sθ], [0, −sθ, cθ]]`, and `A_psi` like `A_phi`.
//! These are the passive elementary matrices; a text that prints `A_phi` and
//! `A_psi` with the signs of the sines flipped (`[[c, −s], [s, c]]`) describes
//! active rotations and contradicts its own `A_theta` and expanded product;
//! the product above (docs/theory.md T-3) is the definition used here.
//!
//! The body → world quaternion is `q = q_Z(phi) q_x(theta) q_z(psi)`, whose
//! components are exactly the Euler parameters of docs/theory.md T-4
//! `e0 = cos(θ/2) cos((φ+ψ)/2)`, `e1 = sin(θ/2) cos((φ−ψ)/2)`,
//! `e2 = sin(θ/2) sin((φ−ψ)/2)`, `e3 = cos(θ/2) sin((φ+ψ)/2)`; no conjugation
//! is needed under the crate's body → world convention (checked in
//! `tests/orientation.rs`).
//!
//! Gimbal lock: at `theta = 0` only `phi + psi` is defined, at `theta = π`
//! only `phi − psi`. The inverse functions then return `psi = 0` and put the
//! whole defined combination into `phi`.

use glam::{DMat3, DQuat, DVec3};

use super::quat::wrap_angle_2pi;
use super::transform::matrix_a_to_quat;

/// Below this value of `sin(theta/2)` (resp. `cos(theta/2)`) the orientation is
/// treated as exactly gimbal-locked at `theta = 0` (resp. `π`).
const GIMBAL_EPS: f64 = 1e-14;

/// The transformation matrix `A` (docs/theory.md T-2) (docs/theory.md T-3, world → body:
/// `x_body = A x_world`) of the z-x-z Euler angles `(phi, theta, psi)` (rad).
pub fn euler_to_matrix_a(phi: f64, theta: f64, psi: f64) -> DMat3 {
    let (sf, cf) = phi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let rows = [
        DVec3::new(cf * cp - sf * ct * sp, sf * cp + cf * ct * sp, st * sp),
        DVec3::new(-cf * sp - sf * ct * cp, -sf * sp + cf * ct * cp, st * cp),
        DVec3::new(sf * st, -cf * st, ct),
    ];
    DMat3::from_cols(rows[0], rows[1], rows[2]).transpose()
}

/// Body → world unit quaternion of the z-x-z Euler angles (rad), from the
/// Euler-parameter formulas of docs/theory.md T-4 (`e0` = scalar part `w`).
pub fn euler_to_quat(phi: f64, theta: f64, psi: f64) -> DQuat {
    let (sh, ch) = (0.5 * theta).sin_cos();
    let (sp, cp) = (0.5 * (phi + psi)).sin_cos();
    let (sm, cm) = (0.5 * (phi - psi)).sin_cos();
    let e0 = ch * cp;
    let e1 = sh * cm;
    let e2 = sh * sm;
    let e3 = ch * sp;
    DQuat::from_xyzw(e1, e2, e3, e0)
}

/// z-x-z Euler angles `(phi, theta, psi)` (rad) of a unit body → world
/// quaternion, inverting the Euler-parameter formulas of docs/theory.md T-4 with half-angle
/// `atan2`s (well conditioned for every `theta`):
/// `phi + psi = 2 atan2(e3, e0)`, `phi − psi = 2 atan2(e2, e1)`,
/// `theta = 2 atan2(√(e1²+e2²), √(e0²+e3²))`.
///
/// Ranges `phi, psi ∈ [0, 2π)`, `theta ∈ [0, π]`. Gimbal lock
/// (`sin(θ/2) < 1e-14` or `cos(θ/2) < 1e-14` after normalisation): `psi = 0`
/// and `phi` carries `phi + psi` (at `theta = 0`) or `phi − psi` (at
/// `theta = π`). Close to (but not at) gimbal lock, `phi` and `psi`
/// individually lose accuracy as `~ε/sin θ` while the orientation they
/// describe stays accurate to round-off.
pub fn quat_to_euler(q: DQuat) -> (f64, f64, f64) {
    let q = q.normalize();
    let (e0, e1, e2, e3) = (q.w, q.x, q.y, q.z);
    let s = (e1 * e1 + e2 * e2).sqrt(); // |sin(θ/2)|
    let c = (e0 * e0 + e3 * e3).sqrt(); // |cos(θ/2)|
    let theta = 2.0 * s.atan2(c);
    if s < GIMBAL_EPS {
        let sum = 2.0 * e3.atan2(e0);
        return (wrap_angle_2pi(sum), 0.0, 0.0);
    }
    if c < GIMBAL_EPS {
        let diff = 2.0 * e2.atan2(e1);
        return (wrap_angle_2pi(diff), std::f64::consts::PI, 0.0);
    }
    let sum = 2.0 * e3.atan2(e0);
    let diff = 2.0 * e2.atan2(e1);
    let phi = 0.5 * (sum + diff);
    let psi = 0.5 * (sum - diff);
    (wrap_angle_2pi(phi), theta, wrap_angle_2pi(psi))
}

/// z-x-z Euler angles `(phi, theta, psi)` (rad) of the transformation
/// matrix (docs/theory.md T-2) `A` (world → body), via Shepperd's quaternion
/// ([`matrix_a_to_quat`]) and [`quat_to_euler`]; same ranges and gimbal-lock
/// convention (`psi = 0`).
pub fn matrix_a_to_euler(a: &DMat3) -> (f64, f64, f64) {
    quat_to_euler(matrix_a_to_quat(a))
}
