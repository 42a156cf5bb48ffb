//! Tangential and rolling contact-law tests against values from outside the
//! code: the definitions of the Coulomb and rolling limits, Mindlin's
//! tangential stiffness, and Chung & Ooi (2011) test 5 (see
//! shared/validation/REFERENCE.md §3) as a gross-sliding oblique impact, whose
//! tangential impulse is μ times the normal one by rigid-body impact theory.
//!
//! `ContactModel::evaluate` is called directly (no engine).

mod common;
use clump_core::contact::damping::hertz_gamma;
use clump_core::contact::material::{effective_modulus, effective_shear_modulus};
use clump_core::contact::{ContactHistory, ContactInput, ContactModel, PairProperties, RollingLaw};
use clump_validate::setup::props;
use common::contact::{al_alloy, glass, limestone, sphere_mass, wall};
use common::rel;
use glam::DVec3;

fn unit(v: DVec3) -> DVec3 {
    v.normalize()
}

/// Sliding with a large tangential velocity: |F_t| = μ|F_n| exactly, opposing
/// the slip; the spring stays in the tangent plane; a later stick step holds
/// exactly the limit with the elastic spring alone (e = 1, no dashpot).
#[test]
fn coulomb_limit_and_history() {
    let n = unit(DVec3::new(1.0, 2.0, 2.0));
    let t1 = unit(n.cross(DVec3::Z));
    for e in [1.0, 0.5] {
        let mu = 0.3;
        let model = ContactModel::new(&glass(), &limestone(), &props(e, mu)).unwrap();
        let mut h = ContactHistory::default();
        let c = ContactInput {
            normal: n,
            overlap: 2e-5,
            rel_velocity: 5.0 * t1 - 0.1 * n,
            rel_omega: DVec3::ZERO,
            radius: 0.005,
            radius_sum: f64::INFINITY,
            mass: 0.005,
            dt: 1e-6,
        };
        let out = model.evaluate(&c, &mut h);
        let ft = out.force - out.force.dot(n) * n;
        eprintln!(
            "sliding e={e}: F_n {:.6} N, |F_t| {:.6} N, μF_n {:.6} N, ξ·n {:.1e}, |ξ| {:.3e} m",
            out.normal_force,
            ft.length(),
            mu * out.normal_force,
            h.tangential.dot(n),
            h.tangential.length()
        );
        assert!(out.normal_force > 0.0);
        assert!((out.force.dot(n) - out.normal_force).abs() < 1e-12 * out.normal_force);
        assert!(
            rel(ft.length(), mu * out.normal_force.abs()) < 1e-12,
            "|F_t| = μ|F_n|"
        );
        assert!(
            rel(ft.dot(-t1), ft.length()) < 1e-12,
            "friction opposes slip"
        );
        assert!(
            h.tangential.dot(n).abs() < 1e-14 * h.tangential.length(),
            "ξ in the tangent plane"
        );
        {
            // Step with no relative motion: the elastic spring alone holds the
            // limit (e = 1: the same F_n), or more (e = 0.5: F_n has lost its
            // dashpot part), so the contact is again exactly at the limit.
            let still = ContactInput {
                rel_velocity: DVec3::ZERO,
                ..c
            };
            let out2 = model.evaluate(&still, &mut h);
            let ft2 = out2.force - out2.force.dot(n) * n;
            assert!(
                rel(ft2.length(), mu * out2.normal_force) < 1e-12,
                "truncated spring consistent with the limit"
            );
        }
    }
}

/// Gross sliding through a whole oblique Hertz impact with strong damping
/// (Chung & Ooi test 5: Al alloy sphere R = 0.1 m onto a rigid wall at
/// 0.2 m/s, 60° from the normal, e = 0.5, μ = 0.3; the tangential dashpot
/// γ_t|v_t| exceeds μF_n for most of the contact): the contact carries
/// |F_t| = μF_n exactly at every step, opposing the slip, so the tangential
/// impulse is μ times the normal impulse. With the old Luding truncation
/// ξ = −(F_t + γ_t v_t)/k_t the stored spring pointed forward and, as k_t
/// grew during loading, the trial force fell below the limit (~10 % less
/// impulse); this test failed there.
#[test]
fn gross_sliding_stays_at_the_coulomb_limit() {
    let (mat, r, e, mu) = (al_alloy(), 0.1, 0.5, 0.3);
    let model = ContactModel::new(&mat, &wall(), &props(e, mu)).unwrap();
    let m = sphere_mass(&mat, r);
    let inertia = 0.4 * m * r * r;
    let th = 60f64.to_radians();
    // World frame: wall z = 0, normal +z; sphere centre at height z.
    let (mut vx, mut vz, mut wy) = (0.2 * th.sin(), -0.2 * th.cos(), 0.0_f64);
    let vz0 = vz;
    let mut z = r;
    let dt = 5e-7;
    let (mut fx, mut fz, mut ty) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut h = ContactHistory::default();
    let (mut jt, mut jn, mut steps, mut dashpot_dominates) = (0.0, 0.0, 0, 0);
    let mut worst: f64 = 0.0;
    loop {
        // velocity Verlet (half kick, drift, force, half kick)
        vx += 0.5 * dt * fx / m;
        vz += 0.5 * dt * fz / m;
        wy += 0.5 * dt * ty / inertia;
        z += dt * vz;
        let overlap = r - z;
        if overlap <= 0.0 {
            break;
        }
        // contact point at −r ẑ from the centre: v_cp = v + ω × (−r ẑ)
        let v_pred = DVec3::new(vx + 0.5 * dt * fx / m, 0.0, vz + 0.5 * dt * fz / m);
        let w_pred = wy + 0.5 * dt * ty / inertia;
        let v_cp = v_pred + DVec3::new(0.0, w_pred, 0.0).cross(DVec3::new(0.0, 0.0, -r));
        let c = ContactInput {
            normal: DVec3::Z,
            overlap,
            rel_velocity: v_cp,
            rel_omega: DVec3::ZERO,
            radius: r,
            radius_sum: f64::INFINITY,
            mass: m,
            dt,
        };
        let out = model.evaluate(&c, &mut h);
        let ft = out.force - out.normal_force * DVec3::Z;
        assert!(v_cp.x > 0.0, "the contact must slide throughout");
        assert!(out.normal_force >= 0.0, "tensile normal force");
        if out.normal_force > 0.0 {
            let err = (ft.length() - mu * out.normal_force).abs() / (mu * out.normal_force);
            worst = worst.max(err);
            assert!(ft.x < 0.0, "friction opposes the slip");
        }
        // How strong the tangential dashpot is compared with the limit.
        let kt = 8.0 * model.effective_shear_modulus() * (r * overlap).sqrt();
        let gamma_t = hertz_gamma(model.damping_ratio(), kt, m);
        if gamma_t * v_cp.x > mu * out.normal_force {
            dashpot_dominates += 1;
        }
        fx = out.force.x;
        fz = out.force.z;
        // torque about the centre of (−r ẑ) × F
        ty = DVec3::new(0.0, 0.0, -r).cross(out.force).y;
        jt += fx.abs() * dt;
        jn += fz * dt;
        steps += 1;
        vx += 0.5 * dt * fx / m;
        vz += 0.5 * dt * fz / m;
        wy += 0.5 * dt * ty / inertia;
    }
    let w_rigid = 2.5 * mu * (1.0 + e) * (-vz0) / r;
    eprintln!(
        "gross sliding: {steps} steps, dashpot > limit in {dashpot_dominates}, worst ||F_t| − μF_n|/μF_n = {worst:.2e}; J_t/(μ J_n) − 1 = {:.2e}; e_out {:.5}; ω' {wy:.5} rad/s (rigid {w_rigid:.5})",
        jt / (mu * jn) - 1.0,
        vz / -vz0
    );
    assert!(steps > 1000);
    assert!(
        dashpot_dominates > steps / 10,
        "the case must have a strong dashpot"
    );
    assert!(
        worst < 1e-12,
        "|F_t| = μF_n at every step (worst {worst:.3e})"
    );
    assert!((jt / (mu * jn) - 1.0).abs() < 1e-10);
    assert!((vz / -vz0 - e).abs() < 1e-3);
    assert!(rel(wy, w_rigid) < 2e-3, "ω' {wy} vs rigid {w_rigid}");
}

/// Mindlin stiffness, sign convention, history rotation and elastic energy.
#[test]
fn tangential_spring_and_rotation() {
    let (a, b) = (glass(), limestone());
    let model = ContactModel::new(&a, &b, &props(1.0, 10.0)).unwrap();
    let (r, d, dt): (f64, f64, f64) = (0.005, 1e-5, 1e-7);
    let g_star = effective_shear_modulus(&a, &b);
    let e_star = effective_modulus(&a, &b);
    // G* from the Mindlin formula with shear moduli.
    let g_from_g = 1.0 / ((2.0 - 0.2) / a.shear_modulus() + (2.0 - 0.25) / b.shear_modulus());
    assert!(rel(g_star, g_from_g) < 1e-14);
    assert!(rel(model.effective_shear_modulus(), g_star) < 1e-15);
    let kt = 8.0 * g_star * (r * d).sqrt();
    let n = DVec3::Z;
    let vt = DVec3::new(0.01, -0.02, 0.0);
    let mut h = ContactHistory::default();
    let c = ContactInput {
        normal: n,
        overlap: d,
        rel_velocity: vt,
        rel_omega: DVec3::ZERO,
        radius: r,
        radius_sum: f64::INFINITY,
        mass: 0.01,
        dt,
    };
    let out = model.evaluate(&c, &mut h);
    // Normal force: elastic Hertz, pushes i along +n.
    let f_hertz = 4.0 / 3.0 * e_star * r.sqrt() * d.powf(1.5);
    assert!(rel(out.normal_force, f_hertz) < 1e-14);
    assert!(out.force.z > 0.0);
    let ft_expected = -kt * vt * dt;
    assert!(
        (out.force - DVec3::new(0.0, 0.0, f_hertz) - ft_expected).length()
            < 1e-12 * ft_expected.length()
    );
    let energy = 0.4 * f_hertz * d + 0.5 * kt * (vt * dt).length_squared();
    assert!(rel(out.elastic_energy, energy) < 1e-14);

    // The contact rotates: the stored spring is rotated into the new tangent
    // plane with its length kept.
    let xi0 = DVec3::new(3e-7, -1e-7, 2e-7); // has a normal component
    let n2 = unit(DVec3::new(0.1, 0.0, 1.0));
    let mut h2 = ContactHistory {
        tangential: xi0,
        rolling: DVec3::ZERO,
    };
    let c2 = ContactInput {
        normal: n2,
        rel_velocity: DVec3::ZERO,
        ..c
    };
    let out2 = model.evaluate(&c2, &mut h2);
    eprintln!(
        "rotated spring: ξ·n {:.1e}, |ξ| {:.6e} (was {:.6e})",
        h2.tangential.dot(n2),
        h2.tangential.length(),
        xi0.length()
    );
    assert!(h2.tangential.dot(n2).abs() < 1e-15 * xi0.length());
    assert!(rel(h2.tangential.length(), xi0.length()) < 1e-14);
    let ft2 = out2.force - out2.normal_force * n2;
    assert!((ft2 + kt * h2.tangential).length() < 1e-12 * ft2.length());
}

fn rolling_input(n: DVec3, omega: DVec3) -> ContactInput {
    ContactInput {
        normal: n,
        overlap: 1e-5,
        rel_velocity: DVec3::ZERO,
        rel_omega: omega,
        radius: 0.004,
        radius_sum: f64::INFINITY,
        mass: 0.003,
        dt: 1e-6,
    }
}

/// CDT: magnitude μ_r R* |F_n|, opposing the rolling part of ω_rel; zero
/// (and finite) at ω_rel = 0.
#[test]
fn rolling_cdt() {
    let mu_r = 0.1;
    let p = PairProperties {
        rolling_friction: mu_r,
        rolling: RollingLaw::Cdt,
        ..props(0.5, 0.5)
    };
    let model = ContactModel::new(&glass(), &glass(), &p).unwrap();
    let n = unit(DVec3::new(0.0, 1.0, 1.0));
    let omega = DVec3::new(3.0, 0.0, 0.0) + 7.0 * n; // rolling + twisting
    let c = rolling_input(n, omega);
    let out = model.evaluate(&c, &mut ContactHistory::default());
    let expected = mu_r * c.radius * out.normal_force;
    eprintln!(
        "CDT: |M| {:.6e} N m, μ_r R* F_n {:.6e} N m",
        out.torque.length(),
        expected
    );
    assert!(rel(out.torque.length(), expected) < 1e-12);
    assert!(
        rel(out.torque.dot(-DVec3::X), expected) < 1e-12,
        "opposes rolling, ignores twisting"
    );
    let out0 = model.evaluate(
        &rolling_input(n, DVec3::ZERO),
        &mut ContactHistory::default(),
    );
    assert_eq!(out0.torque, DVec3::ZERO);
    let out_twist = model.evaluate(&rolling_input(n, 5.0 * n), &mut ContactHistory::default());
    assert!(out_twist.torque.length() < 1e-12 * expected);
}

/// EPSD: elastic increments k_r ω Δt with k_r = 2.25 k_n μ_r² R*² (secant k_n),
/// then saturation at μ_r R* |F_n|, the same value as CDT.
#[test]
fn rolling_epsd_saturates_at_cdt_value() {
    let mu_r = 0.1;
    let p = PairProperties {
        rolling_friction: mu_r,
        rolling: RollingLaw::Epsd,
        ..props(0.5, 0.5)
    };
    let model = ContactModel::new(&glass(), &glass(), &p).unwrap();
    let pc = PairProperties {
        rolling: RollingLaw::Cdt,
        ..p
    };
    let cdt = ContactModel::new(&glass(), &glass(), &pc).unwrap();
    let n = DVec3::Z;
    let omega = DVec3::new(0.0, 2.0, 0.0);
    let c = rolling_input(n, omega);
    let mut h = ContactHistory::default();
    let first = model.evaluate(&c, &mut h);
    let kn_secant = 4.0 / 3.0 * model.effective_modulus() * (c.radius * c.overlap).sqrt();
    let kr = 2.25 * kn_secant * mu_r * mu_r * c.radius * c.radius;
    assert!((first.torque - (-kr * omega * c.dt)).length() < 1e-12 * kr * 2.0 * c.dt);
    let mut steps = 1;
    let mut last = first;
    while steps < 1_000_000 {
        last = model.evaluate(&c, &mut h);
        steps += 1;
        if (last.torque - (-kr * omega * c.dt * steps as f64)).length()
            > 1e-9 * last.torque.length()
        {
            break; // saturated
        }
    }
    for _ in 0..10 {
        last = model.evaluate(&c, &mut h);
    }
    let m_cdt = cdt.evaluate(&c, &mut ContactHistory::default()).torque;
    eprintln!(
        "EPSD: k_r {kr:.4e} N m/rad, saturated after {steps} steps at |M| {:.6e} N m; CDT {:.6e} N m",
        last.torque.length(),
        m_cdt.length()
    );
    assert!(rel(last.torque.length(), m_cdt.length()) < 1e-12);
    assert!((last.torque - m_cdt).length() < 1e-12 * m_cdt.length());
    // Reversal unloads elastically.
    let back = model.evaluate(&rolling_input(n, -omega), &mut h);
    assert!(back.torque.length() < m_cdt.length());
}
