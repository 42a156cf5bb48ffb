//! Symmetric 3×3 eigen-decomposition (cyclic Jacobi) and a deterministic,
//! right-handed principal frame.

use glam::{DMat3, DVec3};

/// Relative tolerance under which eigenvalues are treated as equal when the
/// principal frame is chosen (see [`principal_frame`]).
pub const DEGENERACY_TOLERANCE: f64 = 1e-9;

/// Eigenvalues (ascending) and unit eigenvectors of a symmetric matrix, by
/// cyclic Jacobi rotations (accurate to a few ulps of the matrix norm).
///
/// Only the symmetric part ½(m + mᵀ) is used. Returns `(values, vectors)`
/// where `vectors[i]` belongs to `values[i]`; eigenvectors are in the same
/// frame as `m` and orthonormal, with no sign convention.
pub fn symmetric_eigen(m: &DMat3) -> (DVec3, [DVec3; 3]) {
    let c = m.to_cols_array_2d(); // c[col][row]
    let mut a = [[0.0f64; 3]; 3];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = 0.5 * (c[j][i] + c[i][j]);
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]; // v[row][col], cols = vectors
    for _sweep in 0..64 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        let diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if off <= 1e-36 * diag || off == 0.0 {
            break;
        }
        for (p, q) in [(0usize, 1usize), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            // Rotation annihilating a[p][q] (Numerical Recipes / Rutishauser).
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let cs = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * cs;
            for row in a.iter_mut() {
                let akp = row[p];
                let akq = row[q];
                row[p] = cs * akp - sn * akq;
                row[q] = sn * akp + cs * akq;
            }
            #[allow(clippy::needless_range_loop)]
            for k in 0..3 {
                let apk = a[p][k];
                let aqk = a[q][k];
                a[p][k] = cs * apk - sn * aqk;
                a[q][k] = sn * apk + cs * aqk;
            }
            for row in v.iter_mut() {
                let vp = row[p];
                let vq = row[q];
                row[p] = cs * vp - sn * vq;
                row[q] = sn * vp + cs * vq;
            }
        }
    }
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]).then(i.cmp(&j)));
    let values = DVec3::new(a[idx[0]][idx[0]], a[idx[1]][idx[1]], a[idx[2]][idx[2]]);
    let vecs = idx.map(|k| DVec3::new(v[0][k], v[1][k], v[2][k]).normalize());
    (values, vecs)
}

/// Flips `v` so that its component of largest magnitude is positive (the
/// first such component on near-ties).
fn canonical_sign(v: DVec3) -> DVec3 {
    let a = v.abs();
    let m = a.max_element();
    let k = (0..3).find(|&k| a[k] >= m * (1.0 - 1e-6)).unwrap_or(0);
    if v[k] < 0.0 {
        -v
    } else {
        v
    }
}

/// Principal frame of a symmetric tensor (e.g. an inertia tensor, kg m²):
/// returns `(moments, axes)`, moments ascending and `axes[i]` the unit axis of
/// `moments[i]`, in the tensor's frame, forming a right-handed orthonormal set
/// (`axes[0] × axes[1] = axes[2]`).
///
/// Deterministic choice of the axes:
/// - a non-degenerate axis is signed so that its largest component is positive
///   (except that the third axis is flipped if needed for right-handedness);
/// - eigenvalues closer than [`DEGENERACY_TOLERANCE`] × max|λ| are treated as
///   one degenerate cluster, whose axes are the coordinate axes projected onto
///   the cluster's eigenspace (taken in order of decreasing projection length,
///   then by index, and Gram–Schmidt orthonormalised). An isotropic tensor thus
///   gets the identity frame, and an axisymmetric one about x gets x, y, z.
pub fn principal_frame(m: &DMat3) -> (DVec3, [DVec3; 3]) {
    let (vals, vecs) = symmetric_eigen(m);
    let scale = vals.abs().max_element();
    if scale == 0.0 || !scale.is_finite() {
        return (vals, [DVec3::X, DVec3::Y, DVec3::Z]);
    }
    let tol = DEGENERACY_TOLERANCE * scale;
    let mut axes = [DVec3::ZERO; 3];
    let mut i = 0;
    while i < 3 {
        let mut j = i + 1;
        while j < 3 && vals[j] - vals[j - 1] <= tol {
            j += 1;
        }
        if j - i == 1 {
            axes[i] = canonical_sign(vecs[i]);
        } else if j - i == 3 {
            axes = [DVec3::X, DVec3::Y, DVec3::Z];
        } else {
            // Projector onto the cluster's eigenspace.
            let proj = |x: DVec3| -> DVec3 { (i..j).map(|k| vecs[k] * vecs[k].dot(x)).sum() };
            let basis = [DVec3::X, DVec3::Y, DVec3::Z];
            let mut cand: Vec<(f64, usize)> =
                (0..3).map(|k| (proj(basis[k]).length(), k)).collect();
            // Decreasing length, ties (within 1e-9) by index.
            cand.sort_by(|p, q| {
                if (p.0 - q.0).abs() <= 1e-9 {
                    p.1.cmp(&q.1)
                } else {
                    q.0.total_cmp(&p.0)
                }
            });
            let mut chosen = i;
            for &(_, k) in &cand {
                if chosen == j {
                    break;
                }
                let mut w = proj(basis[k]);
                for prev in &axes[i..chosen] {
                    w -= *prev * prev.dot(w);
                }
                let len = w.length();
                if len > 1e-6 {
                    axes[chosen] = w / len;
                    chosen += 1;
                }
            }
            // Should not happen; fall back to the raw eigenvectors.
            for (k, axis) in axes.iter_mut().enumerate().take(j).skip(chosen) {
                *axis = vecs[k];
            }
        }
        i = j;
    }
    // Clean rounding noise (components below a few ulps) for exact
    // coordinate axes where the frame is aligned with them.
    for axis in axes.iter_mut() {
        let cleaned = DVec3::select(
            axis.abs().cmplt(DVec3::splat(4.0 * f64::EPSILON)),
            DVec3::ZERO,
            *axis,
        );
        *axis = cleaned.normalize();
    }
    if axes[0].cross(axes[1]).dot(axes[2]) < 0.0 {
        axes[2] = -axes[2];
    }
    (equalize_round_off(vals, scale), axes)
}

/// Eigenvalues that agree to within [`EQUAL_MOMENT_TOLERANCE`] of the largest
/// magnitude differ only by the eigen-solver's round-off: a group of them
/// (ascending `vals`) is set to its mean. A body with tetrahedral or cubic
/// symmetry then has exactly equal principal moments (its tensor is a
/// multiple of the identity), and the integrator takes the exact
/// spherical-top rotation for it ([`crate::rotation::RotationScheme::drift`]).
fn equalize_round_off(mut vals: DVec3, scale: f64) -> DVec3 {
    let tol = EQUAL_MOMENT_TOLERANCE * scale;
    let mut i = 0;
    while i < 3 {
        let mut j = i + 1;
        while j < 3 && vals[j] - vals[j - 1] <= tol {
            j += 1;
        }
        if j - i > 1 {
            let mean = (i..j).map(|k| vals[k]).sum::<f64>() / (j - i) as f64;
            for k in i..j {
                vals[k] = mean;
            }
        }
        i = j;
    }
    vals
}

/// Relative spread (of the largest eigenvalue magnitude) below which
/// eigenvalues are taken as equal: a few thousand ulps, far below the error
/// bound of the mass-property quadrature (≥ 1e-12) and far above the
/// round-off of a 3 × 3 symmetric eigen-solve (~1e-15).
pub const EQUAL_MOMENT_TOLERANCE: f64 = 1e-13;

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    #[test]
    fn round_off_spread_is_equalized_but_real_spread_is_kept() {
        // a regular tetrahedron's tensor is isotropic: its computed
        // eigenvalues may differ in the last bits, never more
        let rot = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let r = DMat3::from_quat(rot);
        let m = r * DMat3::from_diagonal(DVec3::splat(2.8479159279069097e-11)) * r.transpose();
        let (v, _) = principal_frame(&m);
        assert_eq!(v.x, v.y);
        assert_eq!(v.y, v.z);
        assert!((v.x / 2.8479159279069097e-11 - 1.0).abs() < 1e-14);
        // a genuine relative difference of 1e-10 is kept
        let m2 = DMat3::from_diagonal(DVec3::new(1.0, 1.0 + 1e-10, 2.0));
        let (v2, _) = principal_frame(&m2);
        assert!(v2.y - v2.x > 0.9e-10, "{v2}");
    }

    #[test]
    fn isotropic_gives_identity() {
        let (v, a) = principal_frame(&(DMat3::IDENTITY * 2.5));
        assert_eq!(v, DVec3::splat(2.5));
        assert_eq!(a, [DVec3::X, DVec3::Y, DVec3::Z]);
    }

    #[test]
    fn rotated_diagonal() {
        let q = DQuat::from_euler(glam::EulerRot::ZXZ, 0.3, 1.1, -0.4);
        let r = DMat3::from_quat(q);
        let d = DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0));
        let m = r * d * r.transpose();
        let (v, a) = principal_frame(&m);
        assert!((v - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-14);
        for (k, ax) in a.iter().enumerate() {
            let mv = m * *ax;
            assert!((mv - v[k] * *ax).length() < 1e-14);
        }
        assert!((a[0].cross(a[1]) - a[2]).length() < 1e-14);
    }
}
