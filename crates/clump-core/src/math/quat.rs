//! Quaternion helpers: exact exponential and logarithm maps, sign-insensitive
//! distance, cross-product matrix, angle wrapping.

use glam::{DMat3, DQuat, DVec3};

/// Below this rotation angle (rad) the `sin(x)/x` factors use their Taylor
/// series; the truncation error there is far below `f64` round-off.
const SMALL_ANGLE: f64 = 1e-4;

/// Exact exponential map: the unit quaternion of a rotation by angle `|v|`
/// (rad) about the axis `v/|v|`, i.e. `(cos(|v|/2), sin(|v|/2) v/|v|)`.
///
/// The rotation vector `v` is expressed in whatever frame the caller uses:
/// left-multiplying an orientation (`exp(v) * q`) applies a rotation about a
/// **world**-frame axis; right-multiplying (`q * exp(v)`) applies it about a
/// **body**-frame axis. `v = 0` gives the identity (no division by zero: the
/// factor `sin(|v|/2)/|v|` is evaluated by its series near zero).
pub fn quat_from_rotation_vector(v: DVec3) -> DQuat {
    let (q, small) = quat_from_small_rotation_vector(v);
    if small {
        return q;
    }
    let angle = v.length_squared().sqrt();
    let (sh, ch) = (0.5 * angle).sin_cos();
    let s = sh / angle;
    DQuat::from_xyzw(s * v.x, s * v.y, s * v.z, ch)
}

/// [`quat_from_rotation_vector`] by the series alone, with no branch (so
/// that a loop over several bodies vectorises): the quaternion, and whether
/// the series holds there (half angle below 0.01, the angles of a DEM step).
/// Where it does, this is [`quat_from_rotation_vector`]'s result bit for bit;
/// elsewhere the quaternion is to be discarded.
#[inline(always)]
pub fn quat_from_small_rotation_vector(v: DVec3) -> (DQuat, bool) {
    let h2 = 0.25 * v.length_squared();
    // sin(h)/h and cos(h) by their series in h²: truncation error below
    // 1e-20 for h < 0.01, no square root, no libm call, and v = 0 is exact
    let (s, c) = (0.5 * sinc_series(h2), cos_series(h2));
    (DQuat::from_xyzw(s * v.x, s * v.y, s * v.z, c), h2 < 1e-4)
}

/// Logarithm map, inverse of [`quat_from_rotation_vector`]: the rotation
/// vector (rad, axis times angle) of a unit quaternion, with angle in `[0, π]`
/// (the sign of `q` is irrelevant: `q` and `-q` give the same vector).
pub fn quat_to_rotation_vector(q: DQuat) -> DVec3 {
    let q = if q.w < 0.0 { -q } else { q };
    let v = DVec3::new(q.x, q.y, q.z);
    let s = v.length();
    // angle = 2 atan2(|v|, w), robust for all angles.
    let angle = 2.0 * s.atan2(q.w);
    if s < 1e-300 {
        return 2.0 * v;
    }
    if angle < SMALL_ANGLE {
        // angle / s with s = sin(angle/2): 2 (1 + angle^2/24 + ...)
        let a2 = angle * angle;
        return v * (2.0 * (1.0 + a2 / 24.0));
    }
    v * (angle / s)
}

/// Sign-insensitive distance between two orientations (unit quaternions):
/// `min(|a - b|, |a + b|)` (4-vector Euclidean norm). `q` and `-q` are the same
/// rotation, so this is the natural error measure for orientations.
pub fn quat_distance(a: DQuat, b: DQuat) -> f64 {
    let d1 = (a - b).length();
    let d2 = (a + b).length();
    d1.min(d2)
}

/// Cross-product matrix `[v]×` with `[v]× u = v × u` (same frame as `v`).
pub fn skew(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

/// Wraps an angle (rad) into `[0, 2π)`.
pub fn wrap_angle_2pi(a: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let r = a.rem_euclid(two_pi);
    // rem_euclid can return exactly 2π for tiny negative inputs.
    if r >= two_pi {
        0.0
    } else {
        r
    }
}

/// `sin(x)/x` from `x2 = x²` by its Taylor series to the x⁸ term, for
/// |x| ≤ 0.02 (truncation below 1e-21 relative). Multiplications by
/// reciprocal constants keep divisions out of the step loop.
#[inline(always)]
fn sinc_series(x2: f64) -> f64 {
    1.0 - x2
        * (1.0 / 6.0)
        * (1.0 - x2 * (1.0 / 20.0) * (1.0 - x2 * (1.0 / 42.0) * (1.0 - x2 * (1.0 / 72.0))))
}

/// `cos(x)` from `x2 = x²` by its Taylor series to the x¹⁰ term, for |x| ≤ 0.02.
#[inline(always)]
fn cos_series(x2: f64) -> f64 {
    1.0 - x2
        * 0.5
        * (1.0
            - x2 * (1.0 / 12.0)
                * (1.0 - x2 * (1.0 / 30.0) * (1.0 - x2 * (1.0 / 56.0) * (1.0 - x2 * (1.0 / 90.0)))))
}

/// `(sin x, cos x)` to full double precision, with a polynomial fast path for
/// the small angles of a DEM time step (|x| < 0.02 rad: truncation error
/// below 1e-17 relative) and libm otherwise.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    match sin_cos_small(x) {
        (s, c, true) => (s, c),
        _ => x.sin_cos(),
    }
}

/// [`sin_cos`] by the series alone, with no branch (so that a loop over
/// several bodies vectorises): `(sin x, cos x)`, and whether the series
/// holds there (|x| < 0.02). Where it does, this is [`sin_cos`]'s result
/// bit for bit; elsewhere the values are to be discarded.
#[inline(always)]
pub fn sin_cos_small(x: f64) -> (f64, f64, bool) {
    let x2 = x * x;
    (x * sinc_series(x2), cos_series(x2), x.abs() < 0.02)
}

/// `q/|q|` for a quaternion that is unit up to round-off (the product of
/// two unit quaternions): one Newton step for `1/√(q·q)`,
/// `q (3 − q·q)/2`, exact to `O(ε²)` for `q·q = 1 + ε` (below round-off
/// for `|ε| < 10⁻⁸`), with no square root or division; farther from unit
/// length it falls back to the exact [`DQuat::normalize`].
#[inline(always)]
pub fn renormalize(q: DQuat) -> DQuat {
    match renormalize_near_unit(q) {
        (r, true) => r,
        _ => q.normalize(),
    }
}

/// [`renormalize`]'s Newton step alone, with no branch: the result, and
/// whether `q` is near enough to unit length for it (`|q·q − 1| < 10⁻⁸`);
/// where it is, this is [`renormalize`]'s result bit for bit.
#[inline(always)]
pub fn renormalize_near_unit(q: DQuat) -> (DQuat, bool) {
    let n2 = q.length_squared();
    (q * (0.5 * (3.0 - n2)), (n2 - 1.0).abs() < 1e-8)
}
