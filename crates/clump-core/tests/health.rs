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
