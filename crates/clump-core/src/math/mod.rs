//! Orientation mathematics shared by the whole engine.
//!
//! Conventions (fixed for the crate):
//! - A unit quaternion `q` ([`glam::DQuat`], scalar `w`) maps **body → world**:
//!   `v_world = q * v_body`.
//! - The transformation matrix `A` (docs/theory.md T-2) maps **world → body**:
//!   `x_body = A x_world`, hence `A = R(q)ᵀ` with `R = DMat3::from_quat(q)`.
//! - Euler angles are the classical z-x-z set `(phi, theta, psi)` of
//!   docs/theory.md T-3 (Goldstein's convention), radians.
//!
//! Submodules:
//! - [`euler`]: z-x-z Euler angles ↔ `A` ↔ quaternion.
//! - [`transform`]: quaternion ↔ transformation matrix `A` (docs/theory.md T-2, Shepperd).
//! - [`quat`]: quaternion helpers (exact exponential / logarithm maps, distances).

pub mod euler;
pub mod quat;
pub mod transform;

pub use euler::{euler_to_matrix_a, euler_to_quat, matrix_a_to_euler, quat_to_euler};
pub use quat::{
    quat_distance, quat_from_rotation_vector, quat_from_small_rotation_vector,
    quat_to_rotation_vector, renormalize, renormalize_near_unit, sin_cos, sin_cos_small, skew,
    wrap_angle_2pi,
};
pub use transform::{matrix_a_to_quat, quat_to_matrix_a, rotation_matrix_to_quat};
