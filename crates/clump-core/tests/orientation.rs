//! Orientation conventions: z-x-z Euler angles, the transformation
//! matrix (docs/theory.md T-2) `A` (world → body), quaternions (body → world), and their round trips.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use approx::assert_abs_diff_eq;
use clump_core::math::{
    euler_to_matrix_a, euler_to_quat, matrix_a_to_euler, matrix_a_to_quat, quat_distance,
    quat_from_rotation_vector, quat_to_euler, quat_to_matrix_a, quat_to_rotation_vector,
    rotation_matrix_to_quat,
};
use clump_core::rotation::reference::euler_angle_rates;
use glam::{DMat3, DQuat, DVec3};
use proptest::prelude::*;

fn mat_diff(a: &DMat3, b: &DMat3) -> f64 {
    let d = *a - *b;
    d.x_axis
        .abs()
        .max_element()
        .max(d.y_axis.abs().max_element())
        .max(d.z_axis.abs().max_element())
}

fn rows(r: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols_array_2d(&r).transpose()
}

/// Angle difference modulo 2π, in [0, π].
fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

#[test]
fn matrix_a_hand_derived_value() {
    // phi = 90° about Z, then theta = 90° about x'. By hand: x' = Y, y' = -X,
    // z' = Z; then x'' = Y, y'' = Z, z'' = X. So the body axes are
    // (x, y, z) = (Y, Z, X) and x_b = (y_s, z_s, x_s).
    let a = euler_to_matrix_a(FRAC_PI_2, FRAC_PI_2, 0.0);
    let expected = rows([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
    assert!(mat_diff(&a, &expected) < 1e-15, "{a:?}");
    let q = euler_to_quat(FRAC_PI_2, FRAC_PI_2, 0.0);
    // Body axes in world: body x -> Y, body y -> Z, body z -> X.
    assert!((q * DVec3::X - DVec3::Y).length() < 1e-15);
    assert!((q * DVec3::Y - DVec3::Z).length() < 1e-15);
    assert!((q * DVec3::Z - DVec3::X).length() < 1e-15);
    assert!(mat_diff(&quat_to_matrix_a(q), &expected) < 1e-15);
}

#[test]
fn elementary_rotations_match_active_quaternions() {
    for &ang in &[0.3, -1.2, 2.9] {
        let qz = euler_to_quat(ang, 0.0, 0.0);
        assert!(quat_distance(qz, DQuat::from_rotation_z(ang)) < 1e-15);
        let qx = euler_to_quat(0.0, ang.abs(), 0.0);
        assert!(quat_distance(qx, DQuat::from_rotation_x(ang.abs())) < 1e-15);
        let qpsi = euler_to_quat(0.0, 0.0, ang);
        assert!(quat_distance(qpsi, DQuat::from_rotation_z(ang)) < 1e-15);
    }
    // Composite: q = q_Z(phi) q_x(theta) q_z(psi) (body -> world).
    let (phi, theta, psi) = (0.7, 1.1, -2.3);
    let q =
        DQuat::from_rotation_z(phi) * DQuat::from_rotation_x(theta) * DQuat::from_rotation_z(psi);
    assert!(quat_distance(q, euler_to_quat(phi, theta, psi)) < 1e-15);
}

#[test]
fn seed_quaternion_formulas_consistent_with_eq_4_3_and_body_to_world() {
    // The Euler parameters e0..e3 (docs/theory.md T-4) fed into the quaternion form of T-2
    // of A reproduce eq. 4.3, and A = R(q)^T: no conjugation needed.
    let angles = [
        (0.1, 0.2, 0.3),
        (5.0, 2.0, 1.0),
        (3.0, 3.1, 6.2),
        (1.0, 0.0, 2.0),
        (1.0, PI, 2.0),
    ];
    for &(phi, theta, psi) in &angles {
        let a = euler_to_matrix_a(phi, theta, psi);
        let q = euler_to_quat(phi, theta, psi);
        assert!(mat_diff(&quat_to_matrix_a(q), &a) < 1e-15);
        assert!(mat_diff(&DMat3::from_quat(q).transpose(), &a) < 1e-15);
        let v = DVec3::new(0.3, -1.7, 2.2);
        assert!((a * v - q.conjugate() * v).length() < 1e-14);
        assert!((a.transpose() * v - q * v).length() < 1e-14);
        assert_abs_diff_eq!(q.length(), 1.0, epsilon = 1e-15);
        assert_abs_diff_eq!(a.determinant(), 1.0, epsilon = 1e-14);
    }
}

#[test]
fn shepperd_handles_half_turns_and_all_pivots() {
    let axes = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::new(1.0, 1.0, 0.0).normalize(),
        DVec3::new(-1.0, 2.0, 3.0).normalize(),
    ];
    for axis in axes {
        for &ang in &[0.0, 1e-9, 0.5, 2.0, PI - 1e-9, PI] {
            let q = DQuat::from_axis_angle(axis, ang);
            let back = matrix_a_to_quat(&quat_to_matrix_a(q));
            assert!(
                quat_distance(q, back) < 1e-14,
                "axis {axis} ang {ang}: {back:?}"
            );
            assert!(back.w >= 0.0);
            let back2 = rotation_matrix_to_quat(&DMat3::from_quat(q));
            assert!(quat_distance(q, back2) < 1e-14);
        }
    }
}

#[test]
fn gimbal_lock_near_and_at_theta_zero_and_pi() {
    let (phi, psi) = (1.3, 0.4);
    for &theta in &[0.0, 1e-8, PI - 1e-8, PI] {
        let a = euler_to_matrix_a(phi, theta, psi);
        let q = euler_to_quat(phi, theta, psi);
        for (f, t, p) in [matrix_a_to_euler(&a), quat_to_euler(q)] {
            assert!(f.is_finite() && t.is_finite() && p.is_finite());
            assert!((0.0..=PI).contains(&t));
            // The orientation is reproduced to round-off.
            assert!(
                mat_diff(&euler_to_matrix_a(f, t, p), &a) < 1e-14,
                "theta {theta}"
            );
            assert!(quat_distance(euler_to_quat(f, t, p), q) < 1e-14);
            assert!(angle_diff(t, theta) < 1e-12);
            if theta < 1.0 {
                assert!(angle_diff(f + p, phi + psi) < 1e-12);
            } else {
                assert!(angle_diff(f - p, phi - psi) < 1e-12);
            }
            if theta == 0.0 || theta == PI {
                assert_eq!(p, 0.0, "psi = 0 convention at exact gimbal lock");
            }
        }
    }
}

#[test]
fn euler_angle_rates_match_quaternion_kinematics() {
    // q_dot = 1/2 q (0, w_body): finite difference of euler_to_quat along the
    // rates of eq. 4.8 must agree (checks eq. 4.7/4.8 against our convention).
    let (phi, theta, psi) = (0.4, 1.0, 2.5);
    let w = DVec3::new(0.3, -0.8, 1.1);
    let r = euler_angle_rates(phi, theta, psi, w);
    let h = 1e-6;
    let qp = euler_to_quat(phi + h * r.x, theta + h * r.y, psi + h * r.z);
    let qm = euler_to_quat(phi - h * r.x, theta - h * r.y, psi - h * r.z);
    let qdot_fd = (qp - qm) * (0.5 / h);
    let q = euler_to_quat(phi, theta, psi);
    let qdot = q * DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * 0.5;
    assert!((qdot_fd - qdot).length() < 1e-9, "{qdot_fd:?} vs {qdot:?}");
}

#[test]
fn rotation_vector_exp_log() {
    assert_eq!(quat_from_rotation_vector(DVec3::ZERO), DQuat::IDENTITY);
    assert_eq!(quat_to_rotation_vector(DQuat::IDENTITY), DVec3::ZERO);
    for v in [
        DVec3::new(1e-12, 0.0, 0.0),
        DVec3::new(3e-5, -2e-5, 1e-5),
        DVec3::new(0.3, -1.2, 0.7),
        DVec3::new(0.0, 0.0, 3.0),
    ] {
        let q = quat_from_rotation_vector(v);
        let expect = DQuat::from_axis_angle(v.normalize(), v.length());
        assert!(quat_distance(q, expect) < 1e-15, "{v}");
        assert_abs_diff_eq!(q.length(), 1.0, epsilon = 1e-15);
        assert!((quat_to_rotation_vector(q) - v).length() < 1e-14 * v.length().max(1.0));
    }
}

fn arb_angles() -> impl Strategy<Value = (f64, f64, f64)> {
    (0.0..TAU, 0.0..PI, 0.0..TAU)
}

proptest! {
    #[test]
    fn euler_quat_matrix_round_trips((phi, theta, psi) in arb_angles()) {
        let a = euler_to_matrix_a(phi, theta, psi);
        let q = euler_to_quat(phi, theta, psi);
        prop_assert!(mat_diff(&quat_to_matrix_a(q), &a) < 1e-14);
        // quat <-> A
        prop_assert!(quat_distance(matrix_a_to_quat(&a), q) < 1e-14);
        // Euler <-> quat, Euler <-> A (angles themselves away from gimbal lock)
        for (f, t, p) in [quat_to_euler(q), matrix_a_to_euler(&a)] {
            prop_assert!(mat_diff(&euler_to_matrix_a(f, t, p), &a) < 1e-13);
            let st = theta.sin();
            if st > 1e-3 {
                let tol = 1e-13 / st;
                prop_assert!(angle_diff(f, phi) < tol, "phi {} vs {}", f, phi);
                prop_assert!((t - theta).abs() < 1e-12, "theta {} vs {}", t, theta);
                prop_assert!(angle_diff(p, psi) < tol, "psi {} vs {}", p, psi);
            }
        }
    }

    #[test]
    fn random_quaternion_round_trips(x in -1.0..1.0f64, y in -1.0..1.0f64, z in -1.0..1.0f64, w in -1.0..1.0f64) {
        let q = DQuat::from_xyzw(x, y, z, w);
        prop_assume!(q.length() > 1e-3);
        let q = q.normalize();
        let (f, t, p) = quat_to_euler(q);
        prop_assert!(quat_distance(euler_to_quat(f, t, p), q) < 1e-13);
        prop_assert!(quat_distance(matrix_a_to_quat(&quat_to_matrix_a(q)), q) < 1e-14);
        let v = quat_to_rotation_vector(q);
        prop_assert!(quat_distance(quat_from_rotation_vector(v), q) < 1e-14);
    }
}
