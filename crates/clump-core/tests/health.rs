//! The per-step instability check ([`clump_core::health`]): a NaN state, an
//! excessive overlap and a kinetic-energy blow-up are each found at once,
//! with the bodies involved, and a healthy run never trips it.

mod common;

use clump_core::contact::{Material, PairProperties};
use clump_core::health::{HealthLimits, HealthMonitor, InstabilityKind};
use glam::DVec3;

fn rock() -> Material {
    Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

/// Two spheres (r = 1 mm) approaching each other at `speed` (m/s each),
/// 3 mm apart; returns the world and the monitor.
fn pair(speed: f64, dt: f64) -> (clump_core::world::World, HealthMonitor) {
    let mut w = common::world(
        rock(),
        PairProperties::default(),
        dt,
        common::open_domain(0.1),
        DVec3::ZERO,
    );
    w.add_template(common::coincident(1, 1e-3, 2500.0), 0)
        .unwrap();
    for (x, v) in [(-1.5e-3, speed), (1.5e-3, -speed)] {
        let b = common::moving(
            0,
            DVec3::new(x, 0.0, 0.0),
            DVec3::new(v, 0.0, 0.0),
            DVec3::ZERO,
        );
        w.add_body(&b).unwrap();
    }
    let limits = HealthLimits {
        specific_energy_floor: 1.0,
        ..HealthLimits::default()
    };
    (w, HealthMonitor::new(limits))
}

#[test]
fn healthy_collision_never_trips_the_check() {
    let (mut w, mut h) = pair(0.5, 2e-7);
    for _ in 0..20_000 {
        w.step().unwrap();
        h.check(&w).unwrap();
    }
    // they collided and separated
    assert!(w.bodies().velocity[0].x < 0.0);
}

#[test]
fn nan_state_is_found_with_its_body() {
    let (mut w, mut h) = pair(0.5, 2e-7);
    w.step().unwrap();
    h.check(&w).unwrap();
    let mut v = w.bodies().velocity[1];
    v.y = f64::NAN;
    clump_core::testbed::inject_body_velocity(&mut w, 1, v);
    w.step().unwrap();
    let e = h.check(&w).unwrap_err();
    assert_eq!(e.kind, InstabilityKind::NonFinite { body: 2 });
    assert_eq!(e.step, 2);
}

#[test]
fn deep_overlap_and_energy_blow_up_are_found() {
    // far too fast for these soft spheres: the overlap exceeds 15 % of the radius
    let (mut w, mut h) = pair(200.0, 2e-8);
    let e = loop {
        w.step().unwrap();
        if let Err(e) = h.check(&w) {
            break e;
        }
        assert!(w.step < 100_000, "no instability found");
    };
    match e.kind {
        InstabilityKind::Overlap {
            bodies,
            wall,
            ratio,
            ..
        } => {
            assert_eq!(bodies, [1, 2]);
            assert_eq!(wall, None);
            assert!(ratio > 0.15);
        }
        k => panic!("{k:?}"),
    }
    let cause = w.diagnose(&e, None);
    assert!(cause.contains("too soft for the impact speed"), "{cause}");
    // a kick of 1000 m/s: the energy jumps by orders of magnitude
    let (mut w, mut h) = pair(0.5, 2e-7);
    w.step().unwrap();
    h.check(&w).unwrap();
    let mut v = w.bodies().velocity[0];
    v.z = 1000.0;
    w.set_body_velocity_at(0, v).unwrap();
    w.step().unwrap();
    let e = h.check(&w).unwrap_err();
    assert!(
        matches!(e.kind, InstabilityKind::KineticJump { body: 1, .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("kinetic energy jumped"), "{e}");
}

/// A sphere (r = 2 mm) resting on a floor under gravity through a strongly
/// damped contact (restitution 0.1), stepped at `factor` × the damped
/// contact's stability limit dt_c (T-52, at the resting Hertz overlap
/// δ = (3 m g / (4 E* √r))^⅔) under the health check for up to 20 000
/// steps; returns the instability, if any, the vertical net force of the
/// last two steps over the weight, and the final kinetic energy (J).
fn resting_sphere(factor: f64) -> (Option<clump_core::health::Instability>, [f64; 2], f64) {
    let r = 2e-3;
    let mut w = common::world(
        rock(),
        PairProperties {
            restitution: 0.1,
            ..PairProperties::default()
        },
        1.0,
        common::open_domain(0.1),
        DVec3::new(0.0, 0.0, -9.81),
    );
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let e_star = 1e7 / (1.0 - 0.3 * 0.3);
    let delta = (3.0 * m * 9.81 / (4.0 * e_star * r.sqrt())).powf(2.0 / 3.0);
    let model = w.contact_table.get(0, 1);
    let dt_c = clump_core::contact::stability::contact_step_limit(model, r, delta, m, m);
    w.config.dt = factor * dt_c;
    w.add_template(common::coincident(1, r, 2500.0), 0).unwrap();
    w.add_wall(common::plane(
        DVec3::ZERO,
        DVec3::Z,
        clump_core::multi_contact::MultiContact::Sum,
    ))
    .unwrap();
    let at = DVec3::new(0.0, 0.0, r - 0.5 * delta);
    w.add_body(&common::moving(0, at, DVec3::ZERO, DVec3::ZERO))
        .unwrap();
    let mut h = HealthMonitor::new(HealthLimits {
        specific_energy_floor: 1.0,
        ..HealthLimits::default()
    });
    let mut f = [0.0; 2];
    for _ in 0..20_000 {
        w.step().unwrap();
        f = [f[1], w.bodies().force[0].z / (m * 9.81)];
        if let Err(e) = h.check(&w) {
            println!("{factor} dt_c: {e}\n  {}", w.diagnose(&e, None));
            return (Some(e), f, w.thermo().kinetic_translational);
        }
    }
    let ke = w.thermo().kinetic_translational;
    println!("{factor} dt_c: no trip, net force / weight {f:?}, kinetic energy {ke:.3e} J");
    (None, f, ke)
}

/// Just above the damped contact's limit (1.1 dt_c) the resting sphere
/// chatters at period two: the check names it within a few hundred steps,
/// when its net force already flips sign every step at about its weight
/// (the oscillation grows until the contact opens every other step).
/// At the default 0.4 dt_c (and at 0.9 dt_c) it comes to rest untripped.
#[test]
fn period_two_chatter_is_found_and_a_resting_sphere_is_not() {
    let (trip, f, _) = resting_sphere(1.1);
    let trip = trip.expect("the chatter at 1.1 dt_c is found");
    assert!(
        matches!(trip.kind, InstabilityKind::PeriodTwo { .. }),
        "{trip}"
    );
    assert!(trip.step < 1000, "found late: {trip}");
    assert!(
        f[0] * f[1] < 0.0 && f[0].abs().min(f[1].abs()) > 0.5,
        "net force / weight of the last two steps {f:?}"
    );
    for factor in [0.4, 0.9] {
        let (trip, f, ke) = resting_sphere(factor);
        assert!(trip.is_none(), "{factor} dt_c: {trip:?}");
        assert!(ke < 1e-20, "{factor} dt_c: kinetic energy {ke:e} J");
        assert!(
            (f[1] - 0.0).abs() < 1e-6,
            "{factor} dt_c: net force / weight {f:?}"
        );
    }
}
