//! Quaternion ↔ transformation matrix `A` (world → body).
//!
//! docs/theory.md T-2 writes `A` in the Euler parameters `e0..e3`; with `e0` the scalar
//! part, `(e0, e1, e2, e3)` is exactly our body → world quaternion
//! `q = (w, x, y, z)`, and `A` (docs/theory.md T-2) equals `R(q)ᵀ`
//! (verified in `tests/orientation.rs`).

use glam::{DMat3, DQuat, DVec3};

/// Builds a matrix from its three rows.
fn from_rows(r0: DVec3, r1: DVec3, r2: DVec3) -> DMat3 {
    DMat3::from_cols(r0, r1, r2).transpose()
}

/// Element `(i, j)` (row `i`, column `j`) of a matrix.
#[inline]
fn at(m: &DMat3, i: usize, j: usize) -> f64 {
    m.col(j)[i]
}

/// The transformation matrix `A` (docs/theory.md T-2) (world → body: `x_body = A x_world`)
/// of a **unit** body → world quaternion `q = (e0; e1, e2, e3)`, written with
/// the quaternion formula of docs/theory.md T-2:
///
/// ```text
///     | e0²+e1²−e2²−e3²   2(e1e2+e0e3)      2(e1e3−e0e2)    |
/// A = | 2(e1e2−e0e3)      e0²−e1²+e2²−e3²   2(e2e3+e0e1)    |
///     | 2(e1e3+e0e2)      2(e2e3−e0e1)      e0²−e1²−e2²+e3² |
/// ```
///
/// Equals `DMat3::from_quat(q).transpose()` for unit `q`.
pub fn quat_to_matrix_a(q: DQuat) -> DMat3 {
    let (e0, e1, e2, e3) = (q.w, q.x, q.y, q.z);
    let (s0, s1, s2, s3) = (e0 * e0, e1 * e1, e2 * e2, e3 * e3);
    from_rows(
        DVec3::new(
            s0 + s1 - s2 - s3,
            2.0 * (e1 * e2 + e0 * e3),
            2.0 * (e1 * e3 - e0 * e2),
        ),
        DVec3::new(
            2.0 * (e1 * e2 - e0 * e3),
            s0 - s1 + s2 - s3,
            2.0 * (e2 * e3 + e0 * e1),
        ),
        DVec3::new(
            2.0 * (e1 * e3 + e0 * e2),
            2.0 * (e2 * e3 - e0 * e1),
            s0 - s1 - s2 + s3,
        ),
    )
}

/// Unit quaternion of a rotation matrix `r` that maps **body → world**
/// (`v_world = r v_body`), by Shepperd's method: the largest of
/// `4w², 4x², 4y², 4z²` is taken from the diagonal and the other components
/// from off-diagonal sums/differences, so no small pivot is ever divided by.
/// The result is normalised and has `w ≥ 0` (canonical sign). `r` is assumed
/// (close to) orthonormal with determinant +1.
pub fn rotation_matrix_to_quat(r: &DMat3) -> DQuat {
    let (r00, r11, r22) = (at(r, 0, 0), at(r, 1, 1), at(r, 2, 2));
    let trace = r00 + r11 + r22;
    // Candidates for 4w², 4x², 4y², 4z².
    let cand = [
        1.0 + trace,
        1.0 + r00 - r11 - r22,
        1.0 - r00 + r11 - r22,
        1.0 - r00 - r11 + r22,
    ];
    let mut k = 0;
    for i in 1..4 {
        if cand[i] > cand[k] {
            k = i;
        }
    }
    let big = 0.5 * cand[k].max(0.0).sqrt();
    let f = 0.25 / big;
    let d21 = at(r, 2, 1) - at(r, 1, 2);
    let d02 = at(r, 0, 2) - at(r, 2, 0);
    let d10 = at(r, 1, 0) - at(r, 0, 1);
    let s01 = at(r, 0, 1) + at(r, 1, 0);
    let s02 = at(r, 0, 2) + at(r, 2, 0);
    let s12 = at(r, 1, 2) + at(r, 2, 1);
    // (w, x, y, z)
    let (w, x, y, z) = match k {
        0 => (big, d21 * f, d02 * f, d10 * f),
        1 => (d21 * f, big, s01 * f, s02 * f),
        2 => (d02 * f, s01 * f, big, s12 * f),
        _ => (d10 * f, s02 * f, s12 * f, big),
    };
    let q = DQuat::from_xyzw(x, y, z, w).normalize();
    if q.w < 0.0 {
        -q
    } else {
        q
    }
}

/// Unit body → world quaternion of the transformation matrix `A` (docs/theory.md T-2)
/// (world → body), by Shepperd's method on `Aᵀ`; inverse of
/// [`quat_to_matrix_a`] up to the sign of `q` (result has `w ≥ 0`).
pub fn matrix_a_to_quat(a: &DMat3) -> DQuat {
    rotation_matrix_to_quat(&a.transpose())
}
