//! Reference solution of Maw, Barber & Fawcett (1976), "The oblique impact
//! of elastic spheres", Wear 38, 101–114: an elastic sphere strikes a rigid
//! half-space obliquely; Hertz normal contact, Cattaneo–Mindlin tangential
//! tractions with local Coulomb friction and the full stick/micro-slip/slip
//! history over the contact circle, normal and tangential problems
//! uncoupled. Independent of the engine: MBF discretise the contact circle
//! into annuli; this module solves the same problem by the method of
//! dimensionality reduction (Popov & Heß 2015, "Method of Dimensionality
//! Reduction in Contact Mechanics and Friction", Springer, ch. 5 and 8),
//! which maps the axisymmetric Cattaneo–Mindlin problem with arbitrary
//! normal and tangential loading histories exactly onto a row of
//! independent springs:
//!
//! ```text
//! profile     g(x) = x²/R                      (sphere of radius R; κ = 2)
//! normal      u_z(x) = d − g(x),   F_n = E* ∫ max(u_z, 0) dx
//! tangential  each spring follows the contact point, u_x += Δu, and
//!             slips where |G̃ u_x| > μ E* u_z: u_x = ±μ E* u_z / G̃;
//!             a spring out of contact has u_x = 0;  F_t = −G̃ ∫ u_x dx
//! E* = E/(1 − ν²),  G̃ = 4G/(2 − ν)  (rigid half-space)
//! ```
//!
//! (`E*∫(d − x²/R)dx` over `|x| ≤ a = √(Rd)` is Hertz's `(4/3)E*√R d^{3/2}`,
//! and `2aG̃` Mindlin's `8aG/(2 − ν)`.) The rigid-body motion is integrated
//! by leapfrog: `m v̇_x = F_t`, `I ω̇_y = −R F_t`, `m v̇_z = F_n`, the contact
//! point slips at `v_x − Rω_y`. The normal force uses Hertz's closed form;
//! the spring row resolves the tangential tractions.

/// An MBF impact: the sphere (radius `r` m, density `rho` kg/m³, Young's
/// modulus `e_mod` Pa, Poisson ratio `nu`) with velocity `(vx, vz)` (m/s,
/// `vz < 0` towards the plane z = 0) and spin `wy` (rad/s) about y; friction
/// coefficient `mu`. `springs`: springs over the half-row `0 ≤ x ≤ 1.2 a_max`;
/// `steps`: time steps over the Hertz contact duration. Returns the rebound
/// `(vx', vz', wy')`.
#[allow(clippy::too_many_arguments)]
pub fn impact(
    e_mod: f64,
    nu: f64,
    rho: f64,
    r: f64,
    mu: f64,
    v: (f64, f64),
    wy: f64,
    springs: usize,
    steps: usize,
) -> (f64, f64, f64) {
    let e_star = e_mod / (1.0 - nu * nu);
    let g_mod = e_mod / (2.0 * (1.0 + nu));
    let g_t = 4.0 * g_mod / (2.0 - nu);
    let m = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) * rho;
    let inertia = 0.4 * m * r * r;
    let kh = 4.0 / 3.0 * e_star * r.sqrt();
    let vn = -v.1;
    let d_max = (15.0 * m * vn * vn / (16.0 * e_star * r.sqrt())).powf(0.4);
    let t_c = 2.9432 * d_max / vn;
    let dt = t_c / steps as f64;
    let a_max = (r * d_max).sqrt();
    let dx = 1.2 * a_max / springs as f64;
    let xs: Vec<f64> = (0..springs).map(|i| (i as f64 + 0.5) * dx).collect();
    let mut u = vec![0.0; springs];
    // state: overlap d (m), velocities; starts at first touch
    let (mut d, mut vz, mut vx, mut w) = (0.0f64, v.1, v.0, wy);
    let (mut fn_, mut ft) = (0.0, 0.0);
    for _ in 0..(4 * steps) {
        // half kick
        vz += 0.5 * dt * fn_ / m;
        vx += 0.5 * dt * ft / m;
        w += -0.5 * dt * r * ft / inertia;
        // drift
        d -= vz * dt;
        let du = (vx - r * w) * dt;
        // forces at the new position
        fn_ = if d > 0.0 { kh * d.powf(1.5) } else { 0.0 };
        let mut sum = 0.0;
        for (ui, &x) in u.iter_mut().zip(&xs) {
            let uz = d - x * x / r;
            if uz <= 0.0 {
                *ui = 0.0;
                continue;
            }
            let lim = mu * e_star * uz / g_t;
            *ui = (*ui + du).clamp(-lim, lim);
            sum += *ui;
        }
        ft = -g_t * 2.0 * sum * dx;
        vz += 0.5 * dt * fn_ / m;
        vx += 0.5 * dt * ft / m;
        w += -0.5 * dt * r * ft / inertia;
        if d < 0.0 && vz > 0.0 {
            break;
        }
    }
    (vx, vz, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Far on the gross-sliding branch the spring row reproduces the rigid
    /// impulse `μ(1+e)m v_n` (e = 1): v_t' = v_t − 2μ v_n.
    #[test]
    fn gross_sliding_limit() {
        let (vx, vz, w) = impact(
            3.8e11,
            0.23,
            4000.0,
            2.5e-3,
            0.092,
            (3.0, -1.0),
            0.0,
            400,
            4000,
        );
        assert!((vz - 1.0).abs() < 1e-3, "{vz}");
        assert!((vx - (3.0 - 2.0 * 0.092)).abs() < 2e-3, "{vx}");
        assert!(
            (w - 2.5 * 2.0 * 0.092 / 2.5e-3).abs() < 2e-3 * 2.5 / 2.5e-3,
            "{w}"
        );
    }

    /// Small incidence (stick throughout would reverse the contact-point
    /// velocity): the tangential impulse stays below the rigid rolling limit.
    #[test]
    fn converges_with_the_discretisation() {
        let th = 10f64.to_radians();
        let v = (3.9 * th.sin(), -3.9 * th.cos());
        let a = impact(3.8e11, 0.23, 4000.0, 2.5e-3, 0.092, v, 0.0, 500, 5000);
        let b = impact(3.8e11, 0.23, 4000.0, 2.5e-3, 0.092, v, 0.0, 1000, 10000);
        assert!((a.0 - b.0).abs() < 1e-3 * v.0, "{a:?} {b:?}");
    }
}
