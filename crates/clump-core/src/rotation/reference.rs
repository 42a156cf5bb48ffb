//! **Reference only, not for production.** The two orientation integrators
//! docs/theory.md T-5 rejects, kept to measure their failure modes in tests:
//!
//! (a) integration of the z-x-z Euler-angle rates (docs/theory.md T-5), singular
//!     at `theta = 0` (and `π`): `phi_dot = (ω_x sinψ + ω_y cosψ)/sinθ`
//!     divides by zero. No guard is applied: the blow-up / NaN is returned as
//!     is;
//! (b) direct integration of the transformation matrix `A` (world → body):
//!     a world-fixed vector seen from the body obeys `ẋ_b = −ω_b × x_b`, so
//!     `dA/dt = −[ω_b]× A` (equivalently `Ṙ = R [ω_b]×` for `R = Aᵀ`). A plain
//!     explicit scheme (Heun) is used without re-orthogonalisation, so `A`
//!     drifts away from orthogonality.
//!
//! Both integrate the torque-free Euler equations for the BODY-frame angular
//! velocity together with the orientation, in one explicit scheme of the
//! stated order.

use glam::{DMat3, DVec3};

use super::body_dynamics::angular_acceleration_body;
use crate::math::skew;

/// z-x-z Euler angles (rad) and BODY-frame angular velocity (rad/s) of a
/// torque-free rigid body. Reference only, not for production.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerAngleState {
    /// First rotation, about world `Z`, rad.
    pub phi: f64,
    /// Second rotation, about `x'`, rad.
    pub theta: f64,
    /// Third rotation, about `z''`, rad.
    pub psi: f64,
    /// Angular velocity, body frame, rad/s.
    pub omega_body: DVec3,
}

/// Euler-angle rates `(phi_dot, theta_dot, psi_dot)` (rad/s) from the
/// BODY-frame angular velocity (docs/theory.md T-5). Singular at `sin θ = 0`:
/// returns infinities / NaN there, unguarded on purpose. `phi` does not enter
/// the rates; it is taken for a uniform `(phi, theta, psi)` signature.
pub fn euler_angle_rates(_phi: f64, theta: f64, psi: f64, omega_body: DVec3) -> DVec3 {
    let (sp, cp) = psi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let phi_dot = (omega_body.x * sp + omega_body.y * cp) / st;
    let theta_dot = omega_body.x * cp - omega_body.y * sp;
    let psi_dot = omega_body.z - phi_dot * ct;
    DVec3::new(phi_dot, theta_dot, psi_dot)
}

/// Time derivative of the combined state (angles, body angular velocity) of a
/// torque-free body with principal moments `inertia` (kg m²).
fn euler_angle_state_rate(s: &EulerAngleState, inertia: DVec3) -> (DVec3, DVec3) {
    (
        euler_angle_rates(s.phi, s.theta, s.psi, s.omega_body),
        angular_acceleration_body(s.omega_body, inertia, DVec3::ZERO),
    )
}

/// `s + h * (d_angles, d_omega)`.
fn euler_angle_state_add(s: &EulerAngleState, h: f64, d: (DVec3, DVec3)) -> EulerAngleState {
    EulerAngleState {
        phi: s.phi + h * d.0.x,
        theta: s.theta + h * d.0.y,
        psi: s.psi + h * d.0.z,
        omega_body: s.omega_body + d.1 * h,
    }
}

/// One classical RK4 step of `dt` seconds of the Euler-angle rates (docs/theory.md T-5)
/// together with the torque-free Euler equations (principal moments
/// `inertia`, kg m²). Reference only, not for production: singular at
/// `theta = 0`.
pub fn euler_angle_rk4_step(s: &mut EulerAngleState, inertia: DVec3, dt: f64) {
    let k1 = euler_angle_state_rate(s, inertia);
    let k2 = euler_angle_state_rate(&euler_angle_state_add(s, 0.5 * dt, k1), inertia);
    let k3 = euler_angle_state_rate(&euler_angle_state_add(s, 0.5 * dt, k2), inertia);
    let k4 = euler_angle_state_rate(&euler_angle_state_add(s, dt, k3), inertia);
    let d = (
        (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0) / 6.0,
        (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1) / 6.0,
    );
    *s = euler_angle_state_add(s, dt, d);
}

/// Transformation matrix `A` (world → body) and BODY-frame angular velocity
/// (rad/s) of a torque-free rigid body. Reference only, not for production.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MatrixAState {
    /// Transformation matrix, world → body (`x_body = A x_world`).
    pub a: DMat3,
    /// Angular velocity, body frame, rad/s.
    pub omega_body: DVec3,
}

/// `dA/dt = −[ω_b]× A` for `A` mapping world → body and `omega_body` the
/// BODY-frame angular velocity (rad/s); units 1/s.
pub fn matrix_a_rate(a: &DMat3, omega_body: DVec3) -> DMat3 {
    -(skew(omega_body) * *a)
}

/// One Heun (explicit trapezoidal RK2) step of `dt` seconds of
/// `dA/dt = −[ω_b]× A` together with the torque-free Euler equations
/// (principal moments `inertia`, kg m²). No re-orthogonalisation.
/// Reference only, not for production.
pub fn matrix_a_heun_step(s: &mut MatrixAState, inertia: DVec3, dt: f64) {
    let da1 = matrix_a_rate(&s.a, s.omega_body);
    let dw1 = angular_acceleration_body(s.omega_body, inertia, DVec3::ZERO);
    let a_pred = s.a + da1 * dt;
    let w_pred = s.omega_body + dw1 * dt;
    let da2 = matrix_a_rate(&a_pred, w_pred);
    let dw2 = angular_acceleration_body(w_pred, inertia, DVec3::ZERO);
    s.a += (da1 + da2) * (0.5 * dt);
    s.omega_body += (dw1 + dw2) * (0.5 * dt);
}

/// Orthogonality defect `‖AᵀA − I‖_F` (Frobenius norm, dimensionless) of a
/// would-be rotation matrix.
pub fn orthogonality_error(a: &DMat3) -> f64 {
    let e = a.transpose() * *a - DMat3::IDENTITY;
    (e.x_axis.length_squared() + e.y_axis.length_squared() + e.z_axis.length_squared()).sqrt()
}
