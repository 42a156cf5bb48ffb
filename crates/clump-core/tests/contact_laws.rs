//! Normal contact-law and damping tests against values from outside the code:
//! Chung & Ooi (2011) benchmarks 1–3 (see shared/validation/REFERENCE.md §3),
//! closed-form Hertz theory, the restitution the damping laws are defined by,
//! hand-computed time scales, and the rejection of invalid properties.
//!
//! Impacts are integrated with a small velocity-Verlet loop calling
//! `ContactModel::evaluate` directly (no engine).

mod common;
use clump_core::contact::damping::{
    clamped_beta, clamped_restitution, exact_hertz_beta, exact_hertz_beta_numeric,
    hertz_restitution, log_beta, restitution_numeric,
};
use clump_core::contact::time_scale::{hertz_contact_time, rayleigh_time};
use clump_core::contact::{
    ContactError, ContactHistory, ContactInput, ContactModel, DampingLaw, Material, NormalLaw,
    PairProperties, RollingLaw,
};
use clump_validate::setup::props;
use common::contact::{
    al_alloy, alumina, cast_iron, glass, limestone, mg_alloy, sphere_mass, wall,
};
use common::rel;
use glam::DVec3;
use std::f64::consts::PI;

#[derive(Debug)]
struct Impact {
    /// Maximum overlap, m.
    max_overlap: f64,
    /// Maximum normal force, N.
    max_force: f64,
    /// Contact duration, s.
    duration: f64,
    /// Normal restitution (rebound speed / impact speed).
    restitution: f64,
    /// Largest |kinetic + elastic − initial kinetic| / initial kinetic.
    energy_drift: f64,
    /// Smallest normal force during the contact, N (negative: tensile).
    min_force: f64,
}

/// Head-on impact along x. Body `i` (mass `mi`, radius `ri`) starts touching
/// body `j` (mass `mj`, radius `rj`; `mj = ∞`, `rj = ∞` for a rigid plane at
/// x = 0) and approaches it at relative speed `v` (split so the total momentum
/// is zero). Velocity Verlet; the contact force uses the predicted full-step
/// velocity.
fn head_on(model: &ContactModel, mi: f64, ri: f64, mj: f64, rj: f64, v: f64, dt: f64) -> Impact {
    let wall = mj.is_infinite();
    let (r_star, m_star) = if wall {
        (ri, mi)
    } else {
        (ri * rj / (ri + rj), mi * mj / (mi + mj))
    };
    let rsum = if wall { ri } else { ri + rj };
    // i on the +x side of j.
    let (mut xi, mut xj) = (rsum, 0.0_f64);
    let (mut vi, mut vj) = if wall {
        (-v, 0.0)
    } else {
        (-v * mj / (mi + mj), v * mi / (mi + mj))
    };
    let ke0 = 0.5 * mi * vi * vi + if wall { 0.0 } else { 0.5 * mj * vj * vj };
    let (mut ai, mut aj) = (0.0_f64, 0.0_f64);
    let mut h = ContactHistory::default();
    let (mut max_overlap, mut max_force, mut drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut min_force = f64::INFINITY;
    let mut t = 0.0;
    let mut prev_overlap = 0.0;
    for _ in 0..100_000_000u64 {
        vi += 0.5 * dt * ai;
        vj += 0.5 * dt * aj;
        xi += dt * vi;
        xj += dt * vj;
        t += dt;
        let overlap = rsum - (xi - xj);
        if overlap <= 0.0 {
            // End of contact inside this step: interpolate the time.
            let duration = t - dt + dt * prev_overlap / (prev_overlap - overlap);
            // The force is zero from here on: the velocities are final
            // (the half-kick with the last force was already applied).
            let vrel_out = vi - vj;
            return Impact {
                max_overlap,
                max_force,
                duration,
                restitution: vrel_out / v,
                energy_drift: drift,
                min_force,
            };
        }
        let input = ContactInput {
            normal: DVec3::X,
            overlap,
            rel_velocity: DVec3::new((vi + 0.5 * dt * ai) - (vj + 0.5 * dt * aj), 0.0, 0.0),
            rel_omega: DVec3::ZERO,
            radius: r_star,
            radius_sum: f64::INFINITY,
            mass: m_star,
            dt,
        };
        let out = model.evaluate(&input, &mut h);
        let f = out.force.x;
        ai = f / mi;
        aj = if wall { 0.0 } else { -f / mj };
        vi += 0.5 * dt * ai;
        vj += 0.5 * dt * aj;
        max_overlap = max_overlap.max(overlap);
        max_force = max_force.max(out.normal_force);
        min_force = min_force.min(out.normal_force);
        let ke = 0.5 * mi * vi * vi + if wall { 0.0 } else { 0.5 * mj * vj * vj };
        drift = drift.max((ke + out.elastic_energy - ke0).abs() / ke0);
        prev_overlap = overlap;
    }
    panic!("contact did not end");
}

fn sphere_pair_impact(mat: Material, p: &PairProperties, r: f64, v_rel: f64, steps: f64) -> Impact {
    let model = ContactModel::new(&mat, &mat, p).unwrap();
    let m = sphere_mass(&mat, r);
    let tc = hertz_contact_time(model.effective_modulus(), r / 2.0, m / 2.0, v_rel);
    head_on(&model, m, r, m, r, v_rel, tc / steps)
}

fn wall_impact(mat: Material, p: &PairProperties, r: f64, v: f64, steps: f64) -> Impact {
    let model = ContactModel::new(&mat, &wall(), p).unwrap();
    let m = sphere_mass(&mat, r);
    let tc = model.contact_time(r, m, v);
    head_on(&model, m, r, f64::INFINITY, f64::INFINITY, v, tc / steps)
}

/// Chung & Ooi test 1: two identical spheres, R = 0.01 m, ±10 m/s, elastic.
#[test]
fn chung_ooi_test1_sphere_sphere() {
    for (name, mat, dmax, fmax, tc) in [
        ("glass", glass(), 274.1e-6, 10.70e3, 40.3e-6),
        ("limestone", limestone(), 368.3e-6, 7.108e3, 54.2e-6),
    ] {
        let imp = sphere_pair_impact(mat, &props(1.0, 0.0), 0.01, 20.0, 1000.0);
        eprintln!(
            "test1 {name}: δmax {:.2} µm (ref {:.1}), Fmax {:.4} kN (ref {}), tc {:.2} µs (ref {}), e {:.6}, energy drift {:.1e}",
            imp.max_overlap * 1e6,
            dmax * 1e6,
            imp.max_force / 1e3,
            fmax / 1e3,
            imp.duration * 1e6,
            tc * 1e6,
            imp.restitution,
            imp.energy_drift
        );
        assert!(rel(imp.max_overlap, dmax) < 0.005, "δmax");
        assert!(rel(imp.max_force, fmax) < 0.005, "Fmax");
        assert!(rel(imp.duration, tc) < 0.02, "t_c");
        assert!((imp.restitution - 1.0).abs() < 1e-4, "elastic rebound");
        assert!(
            imp.energy_drift < 1e-4,
            "energy conservation with the reported elastic energy"
        );
    }
}

/// Chung & Ooi test 2: sphere R = 0.1 m onto a rigid wall at 0.2 m/s, elastic.
#[test]
fn chung_ooi_test2_sphere_wall() {
    for (name, mat, fmax, dmax, tc) in [
        ("Al alloy", al_alloy(), 11.37e3, 49.72e-6, 731.7e-6),
        ("Mg alloy", mg_alloy(), 7.233e3, 52.12e-6, 767.1e-6),
    ] {
        let imp = wall_impact(mat, &props(1.0, 0.0), 0.10, 0.2, 1000.0);
        eprintln!(
            "test2 {name}: Fmax {:.4} kN (ref {}), δmax {:.3} µm (ref {}), tc {:.2} µs (ref {}), e {:.6}",
            imp.max_force / 1e3,
            fmax / 1e3,
            imp.max_overlap * 1e6,
            dmax * 1e6,
            imp.duration * 1e6,
            tc * 1e6,
            imp.restitution
        );
        assert!(rel(imp.max_overlap, dmax) < 0.005, "δmax");
        assert!(rel(imp.max_force, fmax) < 0.005, "Fmax");
        assert!(rel(imp.duration, tc) < 0.02, "t_c");
        assert!((imp.restitution - 1.0).abs() < 1e-4, "elastic rebound");
    }
}

/// Chung & Ooi test 3: restitution out vs in, R = 2.5 mm, 3.9 m/s onto a rigid
/// wall: exact damping for both laws, clamped (default) and tensile; the
/// LIGGGHTS formula exact when tensile and biased upwards under the clamp.
#[test]
fn chung_ooi_test3_restitution() {
    let (r, v) = (2.5e-3, 3.9);
    for (name, mat) in [("alumina", alumina()), ("cast iron", cast_iron())] {
        let m = sphere_mass(&mat, r);
        let e_star = ContactModel::new(&mat, &wall(), &props(1.0, 0.0))
            .unwrap()
            .effective_modulus();
        let tc_hertz = hertz_contact_time(e_star, r, m, v);
        // Linear spring with the same undamped contact time π√(m/kn).
        let kn = m * (PI / tc_hertz).powi(2);
        let linear = NormalLaw::Linear {
            kn,
            kt: 2.0 / 7.0 * kn,
        };
        for k in 1..=5 {
            let e = 0.2 * k as f64;
            let run = |normal: NormalLaw, damping: DampingLaw, tensile: bool| {
                let p = PairProperties {
                    normal,
                    damping,
                    tensile,
                    ..props(e, 0.0)
                };
                wall_impact(mat, &p, r, v, 1000.0).restitution
            };
            let hertz = run(NormalLaw::Hertz, DampingLaw::Exact, false);
            let lin = run(linear, DampingLaw::Exact, false);
            let hertz_t = run(NormalLaw::Hertz, DampingLaw::Exact, true);
            let lin_t = run(linear, DampingLaw::Exact, true);
            let lig_t = run(NormalLaw::Hertz, DampingLaw::Liggghts, true);
            let lig = run(NormalLaw::Hertz, DampingLaw::Liggghts, false);
            let lig_lin = run(linear, DampingLaw::Liggghts, false);
            // What the closed form predicts for LIGGGHTS' β under the clamp.
            let lig_pred = clamped_restitution(log_beta(e));
            eprintln!(
                "test3 {name} e_in {e:.1}: exact clamped hertz {hertz:.5} linear {lin:.5}; exact tensile hertz {hertz_t:.5} linear {lin_t:.5}; liggghts tensile {lig_t:.5}, clamped hertz {lig:.5} linear {lig_lin:.5} (closed form {lig_pred:.5})"
            );
            for (what, got) in [
                ("hertz exact", hertz),
                ("linear exact", lin),
                ("hertz exact tensile", hertz_t),
                ("linear exact tensile", lin_t),
                ("hertz liggghts tensile", lig_t),
            ] {
                assert!((got - e).abs() < 1e-3, "{what}: e_out {got} for e_in {e}");
            }
            // Under the clamp the tensile (decelerating) dashpot force at the
            // end of the rebound is gone, so LIGGGHTS' β dissipates less:
            // e_out > e_in, the same for both laws (phase-plane mapping).
            assert!((lig - lig_pred).abs() < 1e-3 && (lig_lin - lig_pred).abs() < 1e-3);
            if e < 1.0 {
                assert!(lig > e + 0.005, "clamping biases LIGGGHTS' e upwards");
            }
        }
    }
}

/// The clamped exact damping reproduces the input restitution to ~10⁻⁴ or
/// better for both laws over e ∈ [0.01, 1] (single contact, small dt), and
/// the normal force is never tensile.
#[test]
fn clamped_restitution_is_exact() {
    let (mat, r, v) = (alumina(), 2.5e-3, 3.9);
    let kn = 1e7;
    let mut worst: f64 = 0.0;
    for e in [0.01, 0.05, 0.1, 0.135, 0.2, 0.35, 0.5, 0.7, 0.9, 0.99, 1.0] {
        for normal in [
            NormalLaw::Hertz,
            NormalLaw::Linear {
                kn,
                kt: 2.0 / 7.0 * kn,
            },
        ] {
            let p = PairProperties {
                normal,
                ..props(e, 0.3)
            };
            let model = ContactModel::new(&mat, &wall(), &p).unwrap();
            assert!(model.clamps_normal_force());
            assert_eq!(model.damping_ratio(), clamped_beta(e));
            let imp = wall_impact(mat, &p, r, v, 5000.0);
            let err = (imp.restitution - e).abs();
            eprintln!(
                "clamped {normal:?} e_in {e}: β = {:.6}, e_out {:.6} (err {err:.1e}), min F_n {:.3e} N",
                model.damping_ratio(),
                imp.restitution,
                imp.min_force
            );
            assert!(
                imp.min_force >= 0.0,
                "tensile normal force {}",
                imp.min_force
            );
            assert!(err < 2e-4, "{normal:?} e {e}: e_out {}", imp.restitution);
            worst = worst.max(err);
        }
    }
    eprintln!("clamped restitution: worst |e_out − e_in| = {worst:.2e}");
}

/// `tensile = true` keeps the unclamped law: the dashpot pulls before
/// separation (F_n < 0), the restitution is still exact with the log formula
/// (both laws), and the Coulomb limit uses |F_n| there.
#[test]
fn tensile_option_keeps_the_unclamped_law() {
    let (mat, r, v) = (alumina(), 2.5e-3, 3.9);
    for normal in [NormalLaw::Hertz, NormalLaw::Linear { kn: 1e7, kt: 2e6 }] {
        for e in [0.2, 0.5, 0.8] {
            let p = PairProperties {
                normal,
                tensile: true,
                ..props(e, 0.3)
            };
            let model = ContactModel::new(&mat, &wall(), &p).unwrap();
            assert!(!model.clamps_normal_force());
            assert_eq!(model.damping_ratio(), log_beta(e));
            let imp = wall_impact(mat, &p, r, v, 5000.0);
            eprintln!(
                "tensile {normal:?} e_in {e}: e_out {:.6}, min F_n {:.3e} N (max {:.3e})",
                imp.restitution, imp.min_force, imp.max_force
            );
            assert!(imp.min_force < -1e-3 * imp.max_force, "no tensile phase");
            assert!((imp.restitution - e).abs() < 2e-4);
        }
    }
    // A receding contact with a strong dashpot: tensile F_n, and the
    // sliding friction is μ|F_n| (as LIGGGHTS).
    let p = PairProperties {
        tensile: true,
        ..props(0.1, 0.3)
    };
    let model = ContactModel::new(&glass(), &wall(), &p).unwrap();
    let c = ContactInput {
        normal: DVec3::Z,
        overlap: 1e-7,
        rel_velocity: DVec3::new(2.0, 0.0, 1.0),
        rel_omega: DVec3::ZERO,
        radius: 0.005,
        radius_sum: f64::INFINITY,
        mass: 0.005,
        dt: 1e-7,
    };
    let out = model.evaluate(&c, &mut ContactHistory::default());
    let ft = out.force - out.normal_force * DVec3::Z;
    assert!(out.normal_force < 0.0);
    assert!(rel(ft.length(), 0.3 * out.normal_force.abs()) < 1e-12);
    // The same contact clamped: no normal force, no friction.
    let clamped = ContactModel::new(&glass(), &wall(), &props(0.1, 0.3)).unwrap();
    let mut h = ContactHistory::default();
    let out = clamped.evaluate(&c, &mut h);
    assert_eq!(out.normal_force, 0.0);
    assert_eq!(out.force, DVec3::ZERO);
    assert_eq!(h.tangential, DVec3::ZERO);
}

/// With the δ^{1/4} dashpot and exact β', e does not depend on impact speed.
#[test]
fn hertz_exact_restitution_independent_of_velocity() {
    for e in [0.3, 0.5, 0.9] {
        let slow = wall_impact(alumina(), &props(e, 0.0), 2.5e-3, 0.5, 1000.0);
        let fast = wall_impact(alumina(), &props(e, 0.0), 2.5e-3, 5.0, 1000.0);
        eprintln!(
            "velocity independence e_in {e}: 0.5 m/s → {:.5}, 5 m/s → {:.5}",
            slow.restitution, fast.restitution
        );
        assert!((slow.restitution - e).abs() < 0.01 && (fast.restitution - e).abs() < 0.01);
        assert!((slow.restitution - fast.restitution).abs() < 0.002);
    }
}

/// e = 0: no rebound (the overlap decays without separation within a long
/// window), both laws; the normal force stays finite.
#[test]
fn zero_restitution_does_not_rebound() {
    for normal in [NormalLaw::Hertz, NormalLaw::Linear { kn: 1e6, kt: 0.0 }] {
        let p = PairProperties {
            normal,
            ..props(0.0, 0.0)
        };
        let model = ContactModel::new(&glass(), &wall(), &p).unwrap();
        let (m, r, v) = (0.01, 0.005, 1.0);
        let tc =
            model
                .contact_time(r, m, v)
                .min(hertz_contact_time(model.effective_modulus(), r, m, v));
        let dt = tc.min(PI * (m / 1e6f64).sqrt()) / 1000.0;
        let (mut x, mut vx, mut a) = (0.0_f64, -v, 0.0_f64); // x = −overlap
        let mut h = ContactHistory::default();
        let mut separated = false;
        for _ in 0..200_000 {
            vx += 0.5 * dt * a;
            x += dt * vx;
            if x >= 0.0 {
                separated = true;
                break;
            }
            let c = ContactInput {
                normal: DVec3::X,
                overlap: -x,
                rel_velocity: DVec3::new(vx + 0.5 * dt * a, 0.0, 0.0),
                rel_omega: DVec3::ZERO,
                radius: r,
                radius_sum: f64::INFINITY,
                mass: m,
                dt,
            };
            let out = model.evaluate(&c, &mut h);
            assert!(out.force.is_finite());
            a = out.force.x / m;
            vx += 0.5 * dt * a;
        }
        eprintln!("e = 0 ({normal:?}): β = {}, separated: {separated}, final overlap {:.3e}, velocity {:.3e}", model.damping_ratio(), -x, vx);
        assert!(!separated || vx.abs() < 1e-3 * v);
        // No finite clamped dashpot stops the rebound, so exact damping with
        // e = 0 uses critical damping without the clamp.
        assert!(!model.clamps_normal_force());
        assert_eq!(model.damping_ratio(), -1.0);
    }
}

/// Linear law: force kn δ, damping −2β√(m kn) v_n, kt = 0 gives no friction.
#[test]
fn linear_law_values() {
    let (kn, kt, e, m) = (2e5, 5e4, 0.5, 0.02);
    let p = PairProperties {
        normal: NormalLaw::Linear { kn, kt },
        ..props(e, 0.4)
    };
    let c = ContactInput {
        normal: DVec3::Y,
        overlap: 1e-4,
        rel_velocity: DVec3::new(0.0, -0.3, 0.0),
        rel_omega: DVec3::ZERO,
        radius: 0.01,
        radius_sum: f64::INFINITY,
        mass: m,
        dt: 1e-6,
    };
    // Clamped (default): β from exp(−2ζA(ζ)) = e; tensile: the log formula.
    for (tensile, beta) in [
        (false, clamped_beta(e)),
        (true, e.ln() / (e.ln().powi(2) + PI * PI).sqrt()),
    ] {
        let pt = PairProperties { tensile, ..p };
        let model = ContactModel::new(&glass(), &glass(), &pt).unwrap();
        assert_eq!(model.damping_ratio(), beta);
        let out = model.evaluate(&c, &mut ContactHistory::default());
        let expected = kn * 1e-4 - 2.0 * beta * (m * kn).sqrt() * 0.3;
        assert!(rel(out.normal_force, expected) < 1e-14);
        assert!(rel(out.elastic_energy, 0.5 * kn * 1e-8) < 1e-14);
    }
    let p0 = PairProperties {
        normal: NormalLaw::Linear { kn, kt: 0.0 },
        ..props(e, 0.4)
    };
    let m0 = ContactModel::new(&glass(), &glass(), &p0).unwrap();
    let mut h = ContactHistory::default();
    let out0 = m0.evaluate(
        &ContactInput {
            rel_velocity: DVec3::new(1.0, -0.3, 0.0),
            ..c
        },
        &mut h,
    );
    assert_eq!(out0.force.x, 0.0);
    assert_eq!(h.tangential, DVec3::ZERO);
    assert!(out0.force.is_finite());
}
/// Time scales against hand-computed values.
#[test]
fn time_scales() {
    // Rayleigh time, glass, R = 1 cm: G = E/(2(1+ν)) = 2e10 Pa.
    let tr = rayleigh_time(&glass(), 0.01);
    let expected = PI * 0.01 * (2800.0f64 / 2.0e10).sqrt() / (0.1631 * 0.2 + 0.8766);
    assert!(rel(tr, expected) < 1e-14);
    // Hertz contact time, test 1 glass: 40.3 µs.
    let m = sphere_mass(&glass(), 0.01);
    let tc = hertz_contact_time(2.5e10, 0.005, m / 2.0, 20.0);
    eprintln!(
        "Rayleigh time glass R=1cm {:.4e} s; Hertz t_c test 1 glass {:.4e} s",
        tr, tc
    );
    assert!(rel(tc, 40.3e-6) < 0.005);
}

#[test]
fn validation_errors() {
    let ok = props(0.5, 0.5);
    let bad_e = ContactModel::new(&glass(), &glass(), &props(1.5, 0.5)).unwrap_err();
    assert!(matches!(bad_e, ContactError::Property(_)));
    eprintln!("{bad_e}");
    assert!(ContactModel::new(&glass(), &glass(), &props(-0.1, 0.5)).is_err());
    assert!(ContactModel::new(&glass(), &glass(), &props(f64::NAN, 0.5)).is_err());
    assert!(ContactModel::new(&glass(), &glass(), &props(0.5, -1.0)).is_err());
    let bad_nu = Material {
        poisson_ratio: 0.5,
        ..glass()
    };
    let err = ContactModel::new(&bad_nu, &glass(), &ok).unwrap_err();
    eprintln!("{err}");
    assert!(matches!(err, ContactError::Material { which: "a", .. }));
    assert!(ContactModel::new(
        &glass(),
        &Material {
            youngs_modulus: 0.0,
            ..glass()
        },
        &ok
    )
    .is_err());
    assert!(ContactModel::new(
        &glass(),
        &Material {
            density: 0.0,
            ..glass()
        },
        &ok
    )
    .is_err());
    assert!(ContactModel::new(&wall(), &wall(), &ok).is_err());
    let lin_bad = PairProperties {
        normal: NormalLaw::Linear { kn: 0.0, kt: 1.0 },
        ..ok
    };
    assert!(ContactModel::new(&glass(), &glass(), &lin_bad).is_err());
    assert!(ContactModel::new(&glass(), &Material::rigid(), &ok).is_ok());
    assert!(ContactModel::new(&glass(), &glass(), &ok)
        .unwrap()
        .with_rolling_damping(-1.0)
        .is_err());
}

/// The closed-form exact Hertz β agrees with a numerical root search on the
/// non-dimensional impact ODE (the brief's bisection approach).
#[test]
fn exact_beta_closed_form_vs_numeric() {
    let t0 = std::time::Instant::now();
    for e in [0.05, 0.2, 0.4, 0.6, 0.8, 0.95] {
        let closed = exact_hertz_beta(e);
        let numeric = exact_hertz_beta_numeric(e);
        eprintln!(
            "e {e}: β closed form {closed:.9}, numeric {numeric:.9}, e(β) from ODE {:.7}",
            hertz_restitution(closed)
        );
        assert!((closed - numeric).abs() < 1e-5);
        // Clamped (the default): closed form against the RK4 solution.
        let bc = clamped_beta(e);
        for hertz in [true, false] {
            assert!((restitution_numeric(hertz, bc, true) - e).abs() < 1e-5);
        }
    }
    eprintln!(
        "numeric solve: {:.2} ms per e",
        t0.elapsed().as_secs_f64() * 1e3 / 6.0
    );
    let t1 = std::time::Instant::now();
    for k in 0..=20 {
        let _ = ContactModel::new(&glass(), &limestone(), &props(0.05 * k as f64, 0.5)).unwrap();
    }
    let per = t1.elapsed().as_secs_f64() / 21.0;
    eprintln!("ContactModel::new: {:.2} µs", per * 1e6);
}

#[test]
fn serde_defaults() {
    let p = PairProperties::default();
    assert_eq!(
        (p.restitution, p.friction, p.rolling_friction),
        (0.5, 0.5, 0.0)
    );
    assert_eq!(p.normal, NormalLaw::Hertz);
    assert_eq!(p.damping, DampingLaw::Exact);
    assert_eq!(p.rolling, RollingLaw::None);
}
