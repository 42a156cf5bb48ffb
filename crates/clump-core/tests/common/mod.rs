//! Helpers shared by the engine-level tests.
#![allow(dead_code)]
pub mod contact;

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::World;
use glam::{DQuat, DVec3};

/// A world with one particle material (index 0) and a rigid wall material
/// (index 1), the same pair properties everywhere (shared with the
/// validation suite).
pub fn world(
    particle: Material,
    props: PairProperties,
    dt: f64,
    domain: Domain,
    gravity: DVec3,
) -> World {
    clump_validate::setup::world(particle, props, dt, domain, gravity).expect("world")
}

/// A large open domain (no periodic axes).
pub fn open_domain(half: f64) -> Domain {
    Domain {
        lo: DVec3::splat(-half),
        hi: DVec3::splat(half),
        periodic: [false; 3],
    }
}

/// A template of `n` coincident spheres of radius `r` at the origin.
pub fn coincident(n: usize, r: f64, density: f64) -> ClumpTemplate {
    let s: Vec<Sphere> = (0..n)
        .map(|_| Sphere {
            center: DVec3::ZERO,
            radius: r,
        })
        .collect();
    ClumpTemplate::from_spheres("coincident", &s, density).expect("template")
}

/// A body moving at `v` with angular velocity `w` (world).
pub fn moving(template: u32, x: DVec3, v: DVec3, w: DVec3) -> BodyInit {
    BodyInit {
        velocity: v,
        angular_velocity: w,
        ..BodyInit::at_rest(template, x, DQuat::IDENTITY)
    }
}

/// A fixed plane wall of material 1.
pub fn plane(point: DVec3, normal: DVec3, multi: MultiContact) -> Wall {
    Wall {
        name: "plane".into(),
        shape: WallShape::Plane { point, normal },
        material: 1,
        motion: WallMotion::default(),
        multi_contact: multi,
        active: true,
    }
}

/// Records the history of a head-on impact: the largest overlap (m), the
/// largest contact force (N) and the contact duration (s).
#[derive(Debug, Default, Clone, Copy)]
pub struct Impact {
    pub max_overlap: f64,
    pub max_force: f64,
    pub duration: f64,
}

/// Steps `world` until contact has started and ended (or `max_steps`),
/// measuring on body `b` (storage index 0 unless re-sorted; we look up by id).
pub fn run_impact(w: &mut World, body_id: u64, radius: f64, max_steps: usize) -> Impact {
    let mut imp = Impact::default();
    let mut touching_steps = 0usize;
    let mut started = false;
    for _ in 0..max_steps {
        w.step().expect("step");
        let t = w.thermo();
        let contacts = t.pair_contacts + t.wall_contacts;
        if contacts > 0 {
            started = true;
            touching_steps += 1;
            imp.max_overlap = imp.max_overlap.max(t.max_overlap_ratio * radius);
            let b = w.body_index(body_id).unwrap();
            imp.max_force = imp
                .max_force
                .max((w.bodies().force[b] - w.bodies().mass[b] * w.config.gravity).length());
        } else if started {
            break;
        }
    }
    imp.duration = touching_steps as f64 * w.config.dt;
    imp
}

/// Relative difference.
pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Tiny deterministic generator (test-local, independent of the engine).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn quat(&mut self) -> DQuat {
        let (u1, u2, u3) = (self.next(), self.next(), self.next());
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let tau = std::f64::consts::TAU;
        DQuat::from_xyzw(
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        )
        .normalize()
    }

    /// A vector with components uniform in [−a, a).
    pub fn vec(&mut self, a: f64) -> DVec3 {
        DVec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * (2.0 * a)
    }
}
