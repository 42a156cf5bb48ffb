// The free-rotation drift of NO_SQUISH (docs/theory.md T-18), of the
// exact Richardson scheme (rotation/richardson.rs) and of the
// spherical top (T-17), as crates/clump-core/src/rotation/no_squish.rs,
// rotation/mod.rs (RotationScheme::drift) and math/quat.rs: the same
// series for the small angles of a DEM step (bit for bit the CPU's), and
// for larger angles an f64 sine and cosine of our own (`sin_cos_f64`):
// SPIR-V's GLSL.std.450 Sin and Cos are 16/32-bit only.

// sin(x)/x and cos(x) from x2 = x^2 (math::quat sinc_series, cos_series)
fn sinc_series(x2: f64) -> f64 {
    return 1.0lf - x2 * (1.0lf / 6.0lf)
        * (1.0lf - x2 * (1.0lf / 20.0lf) * (1.0lf - x2 * (1.0lf / 42.0lf) * (1.0lf - x2 * (1.0lf / 72.0lf))));
}
fn cos_series(x2: f64) -> f64 {
    return 1.0lf - x2 * 0.5lf
        * (1.0lf - x2 * (1.0lf / 12.0lf)
            * (1.0lf - x2 * (1.0lf / 30.0lf) * (1.0lf - x2 * (1.0lf / 56.0lf) * (1.0lf - x2 * (1.0lf / 90.0lf)))));
}

// (sin x, cos x) to about one ulp for |x| < 1e5: Cody-Waite reduction by
// pi/2 (fdlibm's pio2_1, 33 bits, so k pio2_1 is exact, and its tail),
// then Taylor polynomials on |r| <= pi/4 to r^17 and r^16 (truncation
// below 1e-17). Not libm's bits: where the CPU calls libm (half angles
// above 0.02 rad, far beyond a DEM step's), the two differ by round-off.
fn sin_cos_f64(x: f64) -> vec2<f64> {
    let k = round(x * 0.63661977236758134308lf);
    let r = (x - k * 1.57079632673412561417lf) - k * 6.07710050650619224932e-11lf;
    let r2 = r * r;
    var s = 1.0lf / 355687428096000.0lf;
    s = -1.0lf / 1307674368000.0lf + r2 * s;
    s = 1.0lf / 6227020800.0lf + r2 * s;
    s = -1.0lf / 39916800.0lf + r2 * s;
    s = 1.0lf / 362880.0lf + r2 * s;
    s = -1.0lf / 5040.0lf + r2 * s;
    s = 1.0lf / 120.0lf + r2 * s;
    s = -1.0lf / 6.0lf + r2 * s;
    let sn = r + r * r2 * s;
    var c = -1.0lf / 20922789888000.0lf;
    c = 1.0lf / 87178291200.0lf + r2 * c;
    c = -1.0lf / 479001600.0lf + r2 * c;
    c = 1.0lf / 3628800.0lf + r2 * c;
    c = -1.0lf / 40320.0lf + r2 * c;
    c = 1.0lf / 720.0lf + r2 * c;
    c = -1.0lf / 24.0lf + r2 * c;
    c = 0.5lf + r2 * c;
    let cs = 1.0lf - r2 * c;
    let q = i32(k - 4.0lf * floor(k * 0.25lf));
    if (q == 0) { return vec2<f64>(sn, cs); }
    if (q == 1) { return vec2<f64>(cs, -sn); }
    if (q == 2) { return vec2<f64>(-sn, -cs); }
    return vec2<f64>(-cs, sn);
}

// math::sin_cos: the series below 0.02 rad, else sin_cos_f64
fn sin_cos(x: f64) -> vec2<f64> {
    if (abs(x) < 0.02lf) {
        let x2 = x * x;
        return vec2<f64>(x * sinc_series(x2), cos_series(x2));
    }
    return sin_cos_f64(x);
}

// glam DQuat * DQuat
fn qmul(a: vec4<f64>, b: vec4<f64>) -> vec4<f64> {
    return vec4<f64>(a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                     a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                     a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
                     a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z);
}
// glam DQuat * DVec3 (rotation of a vector)
fn qrot(q: vec4<f64>, v: vec3<f64>) -> vec3<f64> {
    let b = q.xyz;
    let b2 = dot3(b, b);
    return (v * (q.w * q.w - b2) + b * (dot3(v, b) * 2.0lf)) + cross3(b, v) * (q.w * 2.0lf);
}
// glam DQuat::length_squared ((x x + y y) + z z) + w w
fn qdot(q: vec4<f64>) -> f64 {
    return ((q.x * q.x + q.y * q.y) + q.z * q.z) + q.w * q.w;
}
// glam DQuat::normalize: q * (1 / |q|)
fn qnormalize_glam(q: vec4<f64>) -> vec4<f64> {
    return q * (1.0lf / sqrt(qdot(q)));
}
// math::renormalize: one Newton step near unit length, else normalize
fn renormalize(q: vec4<f64>) -> vec4<f64> {
    let n2 = qdot(q);
    if (abs(n2 - 1.0lf) < 1e-8lf) { return q * (0.5lf * (3.0lf - n2)); }
    return qnormalize_glam(q);
}
// math::quat_from_rotation_vector
fn quat_from_rotation_vector(v: vec3<f64>) -> vec4<f64> {
    let h2 = 0.25lf * dot3(v, v);
    if (h2 < 1e-4lf) {
        let s = 0.5lf * sinc_series(h2);
        return vec4<f64>(s * v.x, s * v.y, s * v.z, cos_series(h2));
    }
    let angle = sqrt(dot3(v, v));
    let sc = sin_cos_f64(0.5lf * angle);
    let s = sc.x / angle;
    return vec4<f64>(s * v.x, s * v.y, s * v.z, sc.y);
}

// no_squish::rotate_about_principal_axis about body axis k (0, 1, 2)
fn nsq_rotate(q: ptr<function, vec4<f64>>, lb: ptr<function, vec3<f64>>, inertia: vec3<f64>, k: u32, h: f64) {
    let i_k = inertia[k];
    if (i_k <= 0.0lf) { return; }
    let phi = (*lb)[k] / i_k * h;
    let sc = sin_cos(0.5lf * phi);
    var r = vec4<f64>(0.0lf, 0.0lf, 0.0lf, sc.y);
    r[k] = sc.x;
    *q = qmul(*q, r);
    let s = 2.0lf * sc.x * sc.y;
    let c = sc.y * sc.y - sc.x * sc.x;
    let a = (k + 1u) % 3u;
    let b = (k + 2u) % 3u;
    let la = (*lb)[a];
    let lbb = (*lb)[b];
    (*lb)[a] = c * la + s * lbb;
    (*lb)[b] = -s * la + c * lbb;
}

// RotationScheme::NoSquish.drift: the spherical top's exact turn, else
// the splitting 3(dt/2) 2(dt/2) 1(dt) 2(dt/2) 3(dt/2)
fn no_squish_drift(q0: vec4<f64>, l: vec3<f64>, inertia: vec3<f64>, dt: f64) -> vec4<f64> {
    if (inertia.x == inertia.y && inertia.y == inertia.z && inertia.x > 0.0lf) {
        return renormalize(qmul(quat_from_rotation_vector(l * (dt / inertia.x)), q0));
    }
    let half = 0.5lf * dt;
    var q = q0;
    var lb = qrot(vec4<f64>(-q0.x, -q0.y, -q0.z, q0.w), l);
    nsq_rotate(&q, &lb, inertia, 2u, half);
    nsq_rotate(&q, &lb, inertia, 1u, half);
    nsq_rotate(&q, &lb, inertia, 0u, dt);
    nsq_rotate(&q, &lb, inertia, 1u, half);
    nsq_rotate(&q, &lb, inertia, 2u, half);
    return qnormalize_glam(q);
}

// rotation/richardson.rs omega_at: w = q ((q* L) I^-1), world frame
fn omega_at(q: vec4<f64>, l: vec3<f64>, inv: vec3<f64>) -> vec3<f64> {
    return qrot(q, qrot(vec4<f64>(-q.x, -q.y, -q.z, q.w), l) * inv);
}

// RotationScheme::Richardson.drift (docs/theory.md, rotation/richardson.rs
// drift_by): the spherical top's exact turn, else one full and two half
// exponential sub-steps with w frozen over each, extrapolated to
// normalise(2 q_half2 - q_full); the full step and the first half share
// w(q) and one exponential
fn richardson_drift(q0: vec4<f64>, l: vec3<f64>, inertia: vec3<f64>, inv: vec3<f64>, dt: f64) -> vec4<f64> {
    if (inertia.x == inertia.y && inertia.y == inertia.z && inertia.x > 0.0lf) {
        return renormalize(qmul(quat_from_rotation_vector(l * (dt / inertia.x)), q0));
    }
    let half = 0.5lf * dt;
    let w0 = omega_at(q0, l, inv);
    let e_half = quat_from_rotation_vector(w0 * half);
    let q_full = qmul(qmul(e_half, e_half), q0);
    let q_half1 = qmul(e_half, q0);
    let w1 = omega_at(q_half1, l, inv);
    let e1 = quat_from_rotation_vector(w1 * half);
    let q_half2 = qmul(e1, q_half1);
    return qnormalize_glam(q_half2 * 2.0lf - q_full);
}
