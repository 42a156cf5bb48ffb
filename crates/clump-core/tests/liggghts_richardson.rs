//! `RotationScheme::RichardsonLiggghts` against LIGGGHTS itself
//! (LIGGGHTS-PUBLIC 3.8.0, `fix multisphere`): the fixture
//! `tests/fixtures/liggghts/` holds the inputs, the script that ran them
//! and LIGGGHTS' printed body state (`compute multisphere/single`, 15
//! significant digits, every 10 steps).
//!
//! Free rotation of an asymmetric 50-sphere stone (given mass and inertia
//! tensor, no gravity, no contacts): starting from LIGGGHTS' first printed
//! row, Clump's scheme reproduces every later quaternion and angular
//! velocity to the precision LIGGGHTS prints, while Clump's other schemes
//! depart from it by their (different) truncation errors.

mod common;
use clump_core::contact::{DampingLaw, Material, PairProperties};
use clump_core::rotation::{omega_world, RotState, RotationScheme};
use clump_validate::liggghts::{run_bounce, table};
use glam::{DQuat, DVec3};

/// Rows of `free.dat`: time, q (w, x, y, z), ω (world), L (world), I.
fn rows() -> Vec<[f64; 14]> {
    let text = include_str!("fixtures/liggghts/free.dat");
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            v.try_into().unwrap()
        })
        .collect()
}

/// Largest deviation from LIGGGHTS over the run: (quaternion component,
/// relative angular velocity), with `scheme`, dt = 1e-4 s, 10 steps between
/// rows.
fn deviation(scheme: RotationScheme) -> (f64, f64) {
    let rows = rows();
    let r0 = rows[0];
    let inertia = DVec3::new(r0[11], r0[12], r0[13]);
    let mut s = RotState {
        q: DQuat::from_xyzw(r0[2], r0[3], r0[4], r0[1]).normalize(),
        l_world: DVec3::new(r0[8], r0[9], r0[10]),
    };
    let (mut dq, mut dw) = (0.0f64, 0.0f64);
    for r in &rows[1..] {
        for _ in 0..10 {
            scheme.step(&mut s, inertia, &mut |_| DVec3::ZERO, 1e-4);
        }
        let q = DQuat::from_xyzw(r[2], r[3], r[4], r[1]);
        let w = DVec3::new(r[5], r[6], r[7]);
        let e = (s.q - q).length().min((s.q + q).length());
        dq = dq.max(e);
        dw = dw.max((omega_world(s.q, s.l_world, inertia) - w).length() / w.length());
    }
    (dq, dw)
}

#[test]
fn free_rotation_reproduces_liggghts_to_its_printed_precision() {
    assert_eq!(rows().len(), 200);
    let (dq, dw) = deviation(RotationScheme::RichardsonLiggghts);
    eprintln!("richardson_liggghts vs LIGGGHTS over 1990 steps: |dq| {dq:.2e}, |dω|/|ω| {dw:.2e}");
    // 15 printed digits: the start state is rounded at 5e-16 relative
    assert!(dq < 1e-13 && dw < 1e-13, "{dq:e} {dw:e}");
    for scheme in [RotationScheme::Richardson, RotationScheme::NoSquish] {
        let (oq, ow) = deviation(scheme);
        eprintln!("{scheme:?} vs LIGGGHTS: |dq| {oq:.2e}, |dω|/|ω| {ow:.2e}");
        assert!(
            oq > 1e3 * dq.max(1e-15),
            "{scheme:?} does not tell apart: {oq:e}"
        );
    }
}

/// The bounce with `scheme`: largest deviation from LIGGGHTS' rows of
/// (centre of mass in m, velocity in m/s, quaternion, ω relative to |ω|).
fn bounce(scheme: RotationScheme) -> [f64; 4] {
    let rows = table(include_str!("fixtures/liggghts/bounce.dat"));
    let mat = Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    };
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.0,
        damping: DampingLaw::Liggghts,
        tensile: true,
        ..PairProperties::default()
    };
    let spheres = include_str!("fixtures/liggghts/bounce_spheres_step100.txt");
    let states = run_bounce(&rows, spheres, 0.01, mat, props, 1, scheme, 1e-5, 100);
    clump_validate::liggghts::deviation(&rows, &states)
}

#[test]
fn one_bounce_follows_liggghts() {
    let dev = bounce(RotationScheme::RichardsonLiggghts);
    eprintln!("bounce, richardson_liggghts vs LIGGGHTS: |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}", dev[0], dev[1], dev[2], dev[3]);
    let other = bounce(RotationScheme::NoSquish);
    eprintln!("bounce, no_squish vs LIGGGHTS: |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}", other[0], other[1], other[2], other[3]);
    // LIGGGHTS prints 15 digits of x ~ 0.04 m, v ~ 0.5 m/s, q ~ 0.5, ω ~ 10 rad/s
    assert!(
        dev[0] < 1e-13 && dev[1] < 1e-12 && dev[2] < 1e-12 && dev[3] < 1e-12,
        "{dev:?}"
    );
    // a rotation scheme that is not LIGGGHTS' shows at once
    assert!(other[1] > 1e-8 && other[2] > 1e-8, "{other:?}");
    // the rows hold one bounce: vz turns from falling to rising
    let rows = table(include_str!("fixtures/liggghts/bounce.dat"));
    assert!(rows[0][6] < -0.5 && rows.iter().any(|r| r[6] > 0.3));
}
