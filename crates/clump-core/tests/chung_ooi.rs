//! Chung & Ooi (2011) impact benchmarks run through the full engine (one-sphere
//! clumps, the step pipeline, walls). Reference values: REFERENCE.md §3.

mod common;
use clump_core::contact::{DampingLaw, Material, NormalLaw, PairProperties};
use clump_core::multi_contact::MultiContact;
use common::*;
use glam::DVec3;

fn elastic(e: f64, mu: f64) -> PairProperties {
    PairProperties {
        restitution: e,
        friction: mu,
        rolling_friction: 0.0,
        ..PairProperties::default()
    }
}

/// Test 1: two identical spheres, R = 0.01 m, ±10 m/s.
fn test1(mat: Material, n_coincident: usize, average: bool) -> (Impact, f64) {
    let r = 0.01;
    let vmax = 10.0;
    // Hertz duration estimate for dt: ~40–55 µs; use 1/1000 of it.
    let mut w = world(
        mat,
        elastic(1.0, 0.0),
        4.0e-8,
        open_domain(1.0),
        DVec3::ZERO,
    );
    if average {
        w.config.multi_contact = MultiContact::Average;
    }
    let t = w
        .add_template(coincident(n_coincident, r, mat.density), 0)
        .unwrap();
    let a = w
        .add_body(&moving(
            t,
            DVec3::new(-r - 1e-5, 0.0, 0.0),
            DVec3::new(vmax, 0.0, 0.0),
            DVec3::ZERO,
        ))
        .unwrap();
    let b = w
        .add_body(&moving(
            t,
            DVec3::new(r + 1e-5, 0.0, 0.0),
            DVec3::new(-vmax, 0.0, 0.0),
            DVec3::ZERO,
        ))
        .unwrap();
    let imp = run_impact(&mut w, a, r, 100_000);
    let ia = w.body_index(a).unwrap();
    let ib = w.body_index(b).unwrap();
    let rebound = 0.5 * (w.bodies().velocity[ib].x - w.bodies().velocity[ia].x);
    (imp, rebound)
}

fn glass() -> Material {
    Material {
        youngs_modulus: 4.8e10,
        poisson_ratio: 0.20,
        density: 2800.0,
    }
}
fn limestone() -> Material {
    Material {
        youngs_modulus: 2.0e10,
        poisson_ratio: 0.25,
        density: 2500.0,
    }
}

#[test]
fn test1_glass_and_limestone() {
    for (mat, dmax, fmax, tc) in [
        (glass(), 274.1e-6, 10.70e3, 40.3e-6),
        (limestone(), 368.3e-6, 7.108e3, 54.2e-6),
    ] {
        let (imp, rebound) = test1(mat, 1, false);
        eprintln!("test1 E={:e}: δmax {:.4e} (ref {dmax:e}), Fmax {:.5e} (ref {fmax:e}), tc {:.4e} (ref {tc:e}), rebound {rebound}", mat.youngs_modulus, imp.max_overlap, imp.max_force, imp.duration);
        assert!(
            rel(imp.max_overlap, dmax) < 0.005,
            "δmax {}",
            imp.max_overlap
        );
        assert!(rel(imp.max_force, fmax) < 0.005, "Fmax {}", imp.max_force);
        assert!(rel(imp.duration, tc) < 0.02, "tc {}", imp.duration);
        assert!(rel(rebound, 10.0) < 1e-3, "rebound {rebound}");
    }
}

/// The same test with clumps of four coincident spheres under `average`:
/// 16 touching sphere pairs, each force divided by 16, must reproduce the
/// single-sphere result.
#[test]
fn test1_four_coincident_spheres_average_matches_single() {
    let (single, rs) = test1(glass(), 1, false);
    let (four, r4) = test1(glass(), 4, true);
    eprintln!("single {single:?} {rs}; four coincident {four:?} {r4}");
    assert!(rel(four.max_overlap, single.max_overlap) < 1e-9);
    assert!(rel(four.max_force, single.max_force) < 1e-9);
    assert_eq!(four.duration, single.duration);
    assert!(rel(r4, rs) < 1e-9);
}

/// Sphere onto a rigid plane at `v` (m/s), returns (impact, rebound speed).
fn wall_impact(mat: Material, props: PairProperties, r: f64, v: f64, dt: f64) -> (Impact, f64) {
    let mut w = world(mat, props, dt, open_domain(10.0), DVec3::ZERO);
    let t = w.add_template(coincident(1, r, mat.density), 0).unwrap();
    let a = w
        .add_body(&moving(
            t,
            DVec3::new(0.0, 0.0, r + 1e-7),
            DVec3::new(0.0, 0.0, -v),
            DVec3::ZERO,
        ))
        .unwrap();
    w.add_wall(plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum))
        .unwrap();
    let imp = run_impact(&mut w, a, r, 1_000_000);
    let ia = w.body_index(a).unwrap();
    (imp, w.bodies().velocity[ia].z)
}

#[test]
fn test2_sphere_on_rigid_wall() {
    let al = Material {
        youngs_modulus: 7.0e10,
        poisson_ratio: 0.30,
        density: 2699.0,
    };
    let mg = Material {
        youngs_modulus: 4.0e10,
        poisson_ratio: 0.35,
        density: 1800.0,
    };
    for (mat, fmax, dmax, tc) in [
        (al, 11.37e3, 49.72e-6, 731.7e-6),
        (mg, 7.233e3, 52.12e-6, 767.1e-6),
    ] {
        let (imp, v) = wall_impact(mat, elastic(1.0, 0.0), 0.10, 0.2, 5e-7);
        eprintln!("test2 E={:e}: Fmax {:.5e} (ref {fmax:e}) δmax {:.5e} (ref {dmax:e}) tc {:.5e} (ref {tc:e}) rebound {v}", mat.youngs_modulus, imp.max_force, imp.max_overlap, imp.duration);
        assert!(rel(imp.max_force, fmax) < 0.005);
        assert!(rel(imp.max_overlap, dmax) < 0.005);
        assert!(rel(imp.duration, tc) < 0.02);
        assert!(rel(v, 0.2) < 1e-3);
    }
}

#[test]
fn test3_restitution_hertz_and_linear() {
    let alumina = Material {
        youngs_modulus: 3.8e11,
        poisson_ratio: 0.23,
        density: 4000.0,
    };
    let cast_iron = Material {
        youngs_modulus: 1.0e11,
        poisson_ratio: 0.25,
        density: 7000.0,
    };
    let r = 2.5e-3;
    let v = 3.9;
    for mat in [alumina, cast_iron] {
        for k in 1..=5 {
            let e = 0.2 * k as f64;
            // Hertz, exact damping
            let p = PairProperties {
                restitution: e,
                friction: 0.0,
                ..PairProperties::default()
            };
            let (_, vo) = wall_impact(mat, p, r, v, 1e-8);
            let e_h = vo / v;
            // linear spring with a comparable stiffness, exact damping
            let m = mat.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
            let kn = 1e7;
            let tc_lin = std::f64::consts::PI * (m / kn).sqrt();
            let pl = PairProperties {
                restitution: e,
                friction: 0.0,
                normal: NormalLaw::Linear {
                    kn,
                    kt: 2.0 / 7.0 * kn,
                },
                ..PairProperties::default()
            };
            let (_, vl) = wall_impact(mat, pl, r, v, tc_lin / 2000.0);
            let e_l = vl / v;
            // LIGGGHTS damping (biased for Hertz) — reported, not asserted
            let pg = PairProperties {
                restitution: e,
                friction: 0.0,
                damping: DampingLaw::Liggghts,
                ..PairProperties::default()
            };
            let (_, vg) = wall_impact(mat, pg, r, v, 1e-8);
            eprintln!("test3 E={:e} e_in {e:.1}: hertz/exact {e_h:.4}  linear/exact {e_l:.4}  hertz/liggghts {:.4}", mat.youngs_modulus, vg / v);
            assert!((e_h - e).abs() < 0.01, "hertz e_out {e_h} for e_in {e}");
            assert!((e_l - e).abs() < 0.01, "linear e_out {e_l} for e_in {e}");
        }
    }
}

/// Test 7: head-on impact with counter-rotating spins that make the contact
/// surfaces move together: no slip, spins and tangential velocities unchanged.
#[test]
fn test7_no_slip_sign_convention() {
    let al = Material {
        youngs_modulus: 7.0e10,
        poisson_ratio: 0.30,
        density: 2699.0,
    };
    let p = PairProperties {
        restitution: 0.5,
        friction: 0.4,
        ..PairProperties::default()
    };
    let r = 0.1;
    let omega = 10.0;
    let mut w = world(al, p, 5e-7, open_domain(10.0), DVec3::ZERO);
    let t = w.add_template(coincident(1, r, al.density), 0).unwrap();
    let a = w
        .add_body(&moving(
            t,
            DVec3::new(-r - 1e-6, 0.0, 0.0),
            DVec3::new(0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.0, omega),
        ))
        .unwrap();
    let b = w
        .add_body(&moving(
            t,
            DVec3::new(r + 1e-6, 0.0, 0.0),
            DVec3::new(-0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -omega),
        ))
        .unwrap();
    run_impact(&mut w, a, r, 1_000_000);
    let (ia, ib) = (w.body_index(a).unwrap(), w.body_index(b).unwrap());
    let (wa, wb) = (
        w.bodies().angular_velocity[ia],
        w.bodies().angular_velocity[ib],
    );
    eprintln!(
        "test7: ω' = {wa} / {wb}; v' = {} / {}",
        w.bodies().velocity[ia],
        w.bodies().velocity[ib]
    );
    assert!((wa.z - omega).abs() / omega < 1e-6);
    assert!((wb.z + omega).abs() / omega < 1e-6);
    assert!(w.bodies().velocity[ia].y.abs() < 1e-9 && w.bodies().velocity[ib].y.abs() < 1e-9);
    assert!(w.bodies().velocity[ia].x < 0.0, "sphere a rebounds");
}

/// Test 4: oblique impact on a wall on the gross-sliding branch (θ ≥ 35°):
/// v_t' = v_t − μ(1+e)v_n and ω' = −(5/2)μ(1+e)v_n/R.
#[test]
fn test4_oblique_gross_sliding() {
    let alumina = Material {
        youngs_modulus: 3.8e11,
        poisson_ratio: 0.23,
        density: 4000.0,
    };
    let (e, mu, speed, r) = (0.98, 0.092, 3.9, 2.5e-3);
    for deg in [35.0f64, 45.0, 60.0, 80.0] {
        let th = deg.to_radians();
        let (vt, vn) = (speed * th.sin(), speed * th.cos());
        let p = PairProperties {
            restitution: e,
            friction: mu,
            ..PairProperties::default()
        };
        let mut w = world(alumina, p, 1e-8, open_domain(10.0), DVec3::ZERO);
        let t = w
            .add_template(coincident(1, r, alumina.density), 0)
            .unwrap();
        let id = w
            .add_body(&moving(
                t,
                DVec3::new(0.0, 0.0, r + 1e-7),
                DVec3::new(vt, 0.0, -vn),
                DVec3::ZERO,
            ))
            .unwrap();
        w.add_wall(plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum))
            .unwrap();
        run_impact(&mut w, id, r, 1_000_000);
        let b = w.body_index(id).unwrap();
        let v = w.bodies().velocity[b];
        let om = w.bodies().angular_velocity[b];
        let vt_ref = vt - mu * (1.0 + e) * vn;
        // spin about −y for motion along +x on a floor with normal +z (ω' = −(5/2)μ(1+e)v_n/R in the paper's sense)
        let om_ref = 2.5 * mu * (1.0 + e) * vn / r;
        eprintln!(
            "test4 θ={deg}: v_t' {:.5} (ref {vt_ref:.5})  ω' {:.3} (ref {om_ref:.3})  v_n' {:.4}",
            v.x, om.y, v.z
        );
        assert!(rel(v.x, vt_ref) < 0.01, "v_t' {} vs {vt_ref}", v.x);
        assert!(rel(om.y, om_ref) < 0.01, "ω' {} vs {om_ref}", om.y);
        assert!(rel(v.z, e * vn) < 0.01);
    }
}
