//! Fixed and driven bodies (`clump_core::dof`) against closed forms: a fixed
//! body never moves and carries the weight of what rests on it; a driven
//! body keeps its prescribed velocity and turns at its prescribed rate, and
//! the torque its contacts exert on it is the Coulomb value `μ m g` times
//! the lever arm.

mod common;
use clump_core::body::BodyInit;
use clump_core::contact::{Material, PairProperties};
use clump_core::dof::Dof;
use common::*;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

const G: f64 = 9.81;
const E: f64 = 1e7;
const NU: f64 = 0.3;
const RHO: f64 = 2500.0;

fn soft() -> Material {
    Material {
        youngs_modulus: E,
        poisson_ratio: NU,
        density: RHO,
    }
}

fn mass(r: f64) -> f64 {
    RHO * 4.0 / 3.0 * PI * r.powi(3)
}

/// Static Hertz overlap of two spheres (radii `r1`, `r2`, the same
/// material) pressed together by `load` (N): `F = (4/3) E* √R* δ^{3/2}`,
/// `E* = E / (2 (1 − ν²))`, `R* = r1 r2 / (r1 + r2)`.
fn hertz_overlap(r1: f64, r2: f64, load: f64) -> f64 {
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let r_star = r1 * r2 / (r1 + r2);
    (load / (4.0 / 3.0 * e_star * r_star.sqrt())).powf(2.0 / 3.0)
}

fn driven(mut init: BodyInit) -> BodyInit {
    Dof {
        driven: true,
        ..Dof::default()
    }
    .apply(&mut init);
    init
}

/// A small sphere (radius r) dropped onto a large fixed sphere (radius R):
/// the fixed body keeps its pose to the bit, and once the small one rests
/// on top the contact force on the fixed body is its weight, −m g ẑ.
#[test]
fn fixed_body_never_moves_and_carries_the_weight() {
    let (big, small) = (0.05, 0.01);
    let g = DVec3::new(0.0, 0.0, -G);
    let props = PairProperties {
        restitution: 0.3,
        friction: 0.5,
        ..PairProperties::default()
    };
    let mut w = world(soft(), props, 1e-5, open_domain(1.0), g);
    let tb = w.add_template(coincident(1, big, RHO), 0).unwrap();
    let ts = w.add_template(coincident(1, small, RHO), 0).unwrap();
    let q0 = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
    let x0 = DVec3::new(0.1, -0.2, 0.05);
    let fixed = w.add_body(&driven(BodyInit::at_rest(tb, x0, q0))).unwrap();
    let top = x0 + DVec3::new(0.0, 0.0, big + small + 0.002);
    let free = w
        .add_body(&BodyInit::at_rest(ts, top, DQuat::IDENTITY))
        .unwrap();
    w.run(30_000).unwrap();
    let b = w.body_index(fixed).unwrap();
    assert_eq!(w.bodies().position[b], x0);
    assert_eq!(w.bodies().orientation[b], q0);
    assert_eq!(w.bodies().velocity[b], DVec3::ZERO);
    assert_eq!(w.bodies().angular_velocity[b], DVec3::ZERO);
    // the body force holds its own weight (gravity acts on every body) plus
    // the contact load
    let contact = w.bodies().force[b] - mass(big) * g;
    let ms = mass(small);
    let s = w.body_index(free).unwrap();
    eprintln!(
        "contact force on the fixed body {contact}, weight of the resting sphere {}; resting v = {}",
        ms * G,
        w.bodies().velocity[s]
    );
    assert!(w.bodies().velocity[s].length() < 1e-6);
    assert!((contact - ms * g).length() < 1e-6 * ms * G);
    // it rests at the static Hertz overlap
    let delta = big + small - (w.bodies().position[s] - x0).length();
    let theory = hertz_overlap(big, small, ms * G);
    eprintln!("overlap {delta:.6e} m, Hertz {theory:.6e} m");
    assert!(rel(delta, theory) < 1e-4);
}

/// A driven body keeps its prescribed velocity and rate: after n steps its
/// centre is at x0 + v n dt and it has turned by n |ω| dt about ω.
#[test]
fn driven_body_follows_its_prescribed_motion() {
    let mut w = world(
        soft(),
        PairProperties::default(),
        1e-4,
        open_domain(10.0),
        DVec3::new(0.0, 0.0, -G),
    );
    let t = w.add_template(asymmetric(), 0).unwrap();
    let (v, om) = (DVec3::new(0.3, -0.1, 0.2), DVec3::new(1.0, -2.0, 0.5));
    let q0 = DQuat::from_axis_angle(DVec3::Y, 0.3);
    let id = w
        .add_body(&driven(BodyInit {
            orientation: q0,
            ..moving(t, DVec3::ZERO, v, om)
        }))
        .unwrap();
    let n = 20_000u64;
    w.run(n).unwrap();
    let b = w.body_index(id).unwrap();
    let time = n as f64 * 1e-4;
    let x = w.bodies().position[b];
    let angle = om.length() * time;
    let exact = DQuat::from_axis_angle(om.normalize(), angle) * q0;
    let dq = (w.bodies().orientation[b] * exact.conjugate()).normalize();
    let err_angle = 2.0 * dq.xyz().length();
    eprintln!(
        "driven: x = {x} (exact {}), orientation error {err_angle:.2e} rad after {angle:.1} rad",
        v * time
    );
    assert!((x - v * time).length() < 1e-12 * (v * time).length());
    assert!(err_angle < 1e-11);
    assert_eq!(w.bodies().velocity[b], v);
    assert_eq!(w.bodies().angular_velocity[b], om);
    // angular momentum consistent with ω: L = R I Rᵀ ω
    let q = w.bodies().orientation[b];
    let l = q * (w.bodies().inertia[b] * (q.conjugate() * om));
    assert!((w.bodies().angular_momentum[b] - l).length() < 1e-12 * l.length());
}

/// A large sphere (radius R) driven to turn about the horizontal x axis at
/// ω, under a small sphere pinned above its centre (force flags [0, 0, 1],
/// no rotation) that rests on it with its weight m g. The surface slides
/// under the small sphere at ω R, so Coulomb friction μ m g drags it along
/// −y, and the torque the contacts exert on the driven body about its
/// centre is −μ m g (R − δ/2) x̂ (the contact point lies half the overlap δ
/// inside the large sphere's surface); the motor must supply its negative.
#[test]
fn driven_body_torque_is_the_coulomb_drag() {
    let (big, small, mu, omega) = (0.05, 0.01, 0.3, 2.0);
    let g = DVec3::new(0.0, 0.0, -G);
    let props = PairProperties {
        restitution: 0.3,
        friction: mu,
        ..PairProperties::default()
    };
    let mut w = world(soft(), props, 1e-5, open_domain(1.0), g);
    let tb = w.add_template(coincident(1, big, RHO), 0).unwrap();
    let ts = w.add_template(coincident(1, small, RHO), 0).unwrap();
    let ms = mass(small);
    let delta = hertz_overlap(big, small, ms * G);
    let motor = w
        .add_body(&driven(moving(
            tb,
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::new(omega, 0.0, 0.0),
        )))
        .unwrap();
    let pinned = w
        .add_body(&BodyInit {
            force_flag: [false, false, true],
            torque_flag: [false; 3],
            ..BodyInit::at_rest(
                ts,
                DVec3::new(0.0, 0.0, big + small - delta),
                DQuat::IDENTITY,
            )
        })
        .unwrap();
    w.run(20_000).unwrap();
    let b = w.body_index(motor).unwrap();
    let s = w.body_index(pinned).unwrap();
    let contact_force = w.bodies().force[b] - mass(big) * g;
    let torque = w.bodies().torque[b];
    let theory = -mu * ms * G * (big - 0.5 * delta);
    eprintln!(
        "driven sphere: contact force {contact_force}, torque {torque} (theory x: {theory:.6e}); pinned sphere v = {}",
        w.bodies().velocity[s]
    );
    // pinned: still in x, y; at rest vertically
    assert_eq!(w.bodies().position[s].x, 0.0);
    assert_eq!(w.bodies().position[s].y, 0.0);
    assert!(w.bodies().velocity[s].z.abs() < 1e-7);
    assert!(rel(torque.x, theory) < 1e-6);
    assert!(torque.y.abs() < 1e-9 * theory.abs() && torque.z.abs() < 1e-9 * theory.abs());
    // the drag on the driven body points along the surface motion's
    // opposite on the small sphere: +y on the driven body
    assert!(rel(contact_force.y, mu * ms * G) < 1e-6);
    assert!(rel(contact_force.z, -ms * G) < 1e-6);
    // power the motor supplies = heat of sliding friction: −M·ω = μ m g ω (R − δ/2)
    assert!(
        rel(
            -torque.dot(DVec3::new(omega, 0.0, 0.0)),
            mu * ms * G * omega * (big - 0.5 * delta)
        ) < 1e-6
    );
}

/// An asymmetric three-sphere clump (distinct principal moments).
fn asymmetric() -> clump_core::shape::ClumpTemplate {
    use clump_core::shape::{ClumpTemplate, Sphere};
    let s = [
        Sphere {
            center: DVec3::new(0.0, 0.0, 0.0),
            radius: 0.01,
        },
        Sphere {
            center: DVec3::new(0.012, 0.0, 0.0),
            radius: 0.008,
        },
        Sphere {
            center: DVec3::new(0.0, 0.009, 0.002),
            radius: 0.006,
        },
    ];
    ClumpTemplate::from_spheres("asym", &s, RHO).unwrap()
}
