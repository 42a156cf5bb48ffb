//! A rotating drum made of a triangle mesh carries a clump up in rigid-body
//! rotation until it falls back (the avalanche of a single grain), compared
//! with the analytic values: the wall's surface velocity at a contact point
//! is ω × r (r from the rotation centre) and the clump's material point there
//! moves with it, the clump's velocity and angular velocity are those of the
//! drum, it leaves the rigid rotation where the statics of a stuck clump fail
//! (for this cube the uphill contacts unload at 28.7° before friction reaches
//! the Coulomb limit; the 1 % velocity criterion detects it about 0.8° later),
//! and the mesh pose is the prescribed rotation.

mod common;

use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::mesh::primitives::cylinder;
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape};
use common::*;
use glam::{DQuat, DVec3};

const RD: f64 = 0.05; // drum radius, m
const R: f64 = 0.004; // sphere radius, m
const A: f64 = 0.008; // cube edge (sphere centres), m
const MU: f64 = 0.5; // friction
const OMEGA: f64 = 1.0; // drum angular velocity about +y, rad/s
const G: f64 = 9.81;

/// Polar angle of `x` about the drum axis, measured from the lowest point in
/// the direction the drum surface moves there (−x for ω along +y), rad.
fn lift_angle(x: DVec3) -> f64 {
    (-x.x).atan2(-x.z)
}

/// The angle at which a clump stuck to the drum (rotating with it at ω,
/// centre of mass at `rc` from the axis) can no longer be held: it slips
/// (friction at the Coulomb limit μ) or tips (the uphill contacts unload).
///
/// Plane statics in the (x, z) plane: the lower face's sphere pairs touch the
/// drum at the angles θ ± β, β = asin((A/2)/(RD − R)), with radial normal
/// loads N₋, N₊ and tangential friction κ N± (the same ratio κ at both).
/// Newton's law for the centre of mass (centripetal acceleration ω² rc) gives
/// two equations, the moment about the drum axis (normals have none) a third:
/// κ (N₋ + N₊) RD = m g rc sin θ. The clump leaves the rigid rotation at the
/// first θ with κ = μ or N₊ = 0.
fn departure_angle(rc: f64, m: f64) -> f64 {
    let er = |p: f64| glam::DVec2::new(-p.sin(), -p.cos()); // outward radial
    let et = |p: f64| glam::DVec2::new(-p.cos(), p.sin()); // direction of the surface motion
    let beta = (0.5 * A / (RD - R)).asin();
    let mut theta = 0.0f64;
    loop {
        theta += 1e-4;
        assert!(theta < 1.5, "no departure below 86°");
        // N₋ a₋ + N₊ a₊ = rhs with a± = −e_r(θ ± β) + κ e_t(θ ± β)
        let rhs = -m * OMEGA * OMEGA * rc * er(theta) - m * glam::DVec2::new(0.0, -G);
        let mut kappa = 0.0;
        let mut np = 0.0;
        for _ in 0..100 {
            let am = -er(theta - beta) + kappa * et(theta - beta);
            let ap = -er(theta + beta) + kappa * et(theta + beta);
            let det = am.x * ap.y - am.y * ap.x;
            let nm = (rhs.x * ap.y - rhs.y * ap.x) / det;
            np = (am.x * rhs.y - am.y * rhs.x) / det;
            kappa = m * G * rc * theta.sin() / ((nm + np) * RD);
        }
        if kappa >= MU || np <= 0.0 {
            return theta;
        }
    }
}

#[test]
fn mesh_drum_carries_a_clump_in_rigid_rotation_until_it_tips_or_slips() {
    let mat = Material {
        // stiff, so that the elastic creep of the contacts under the load
        // that changes as the clump rises (relative rate ≈ 2e-3 (1e7 Pa /
        // E)^(2/3), from the Hertz and Mindlin compliances) stays near 1e-4
        youngs_modulus: 1e9,
        poisson_ratio: 0.3,
        density: 2500.0,
    };
    let props = PairProperties {
        restitution: 0.3,
        friction: MU,
        ..Default::default()
    };
    let dt = 5e-6; // 0.14 Rayleigh times
    let mut w = world(mat, props, dt, open_domain(0.2), DVec3::new(0.0, 0.0, -G));
    // a cube of 8 spheres: flat-bottomed, it cannot roll
    let mut s = Vec::new();
    for i in 0..8 {
        let c = |k: usize| if i >> k & 1 == 1 { 0.5 * A } else { -0.5 * A };
        s.push(Sphere::new(DVec3::new(c(0), c(1), c(2)), R));
    }
    let t = w
        .add_template(ClumpTemplate::from_spheres("cube", &s, 2500.0).unwrap(), 0)
        .unwrap();
    // the drum: 360 facets round (0.5°), axis along mesh z turned to world y
    let (v, tr) = cylinder(RD, 0.04, 360, 0.005);
    let m = w.add_mesh(TriMesh::new(v, tr).unwrap());
    let q0 = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
    let drum = w
        .add_wall(Wall {
            name: "drum".into(),
            shape: WallShape::Mesh {
                mesh: m,
                position: DVec3::ZERO,
                orientation: q0,
            },
            material: 1,
            motion: WallMotion::default(),
            multi_contact: MultiContact::Sum,
            active: true,
        })
        .unwrap();
    // the cube at the bottom, its lower face's spheres just touching
    let z_low = -((RD - R).powi(2) - (0.5 * A).powi(2)).sqrt();
    let id = w
        .add_body(&moving(
            t,
            DVec3::new(0.0, 0.0, z_low + 0.5 * A + 1e-6),
            DVec3::ZERO,
            DVec3::ZERO,
        ))
        .unwrap();
    // settle at rest
    w.run(6000).unwrap();
    let b = w.body_index(id).unwrap();
    assert!(w.bodies().velocity[b].length() < 1e-4);
    // turn the drum
    w.walls[drum].motion.angular_velocity = DVec3::new(0.0, OMEGA, 0.0);
    let omega = w.walls[drum].motion.angular_velocity;
    let c = w.walls[drum].motion.center;
    let rc = (w.bodies().position[b] - c).length(); // COM distance from the axis
    let theta_s = departure_angle(rc, w.bodies().mass[b]);
    let theta0 = lift_angle(w.bodies().position[b]);
    let t_start = w.time;
    let mut checked = 0;
    let mut slip_angle = None;
    while w.time - t_start < 0.7 {
        w.step().unwrap();
        let b = w.body_index(id).unwrap();
        let x = w.bodies().position[b];
        let theta = lift_angle(x);
        let rigid_v = omega.cross(x - c);
        let dv = (w.bodies().velocity[b] - rigid_v).length() / (OMEGA * rc);
        if slip_angle.is_none() && dv > 0.01 && theta > theta0 + 0.1 {
            slip_angle = Some(theta);
        }
        let stick = slip_angle.is_none()
            && theta > theta0 + 5f64.to_radians()
            && theta < theta_s - 3f64.to_radians();
        if stick && w.step % 500 == 0 {
            // rigid-body rotation with the drum
            assert!(dv < 1e-3, "velocity off rigid rotation by {dv} at {theta}");
            let dw = (w.bodies().angular_velocity[b] - omega).length() / OMEGA;
            assert!(dw < 1e-3, "angular velocity off by {dw}");
            // the contact points: the touching spheres projected radially
            // onto the drum surface
            let sp = w.spheres();
            let mut touching = 0;
            for k in sp.of_body(b) {
                let xs = sp.position(k);
                let radial = DVec3::new(xs.x, 0.0, xs.z) - DVec3::new(c.x, 0.0, c.z);
                // (the facets lie up to RD (1 − cos(π/360)) ≈ 2 µm inside the circle)
                if radial.length() + sp.radius[k] < RD - 1e-5 {
                    continue;
                }
                touching += 1;
                let p = DVec3::new(c.x, xs.y, c.z) + radial.normalize() * RD;
                let r = p - c;
                let want = omega.cross(r);
                // the wall's velocity at the contact point is ω × r
                let wall_v = w.walls[drum].surface_velocity_at(p);
                assert!((wall_v - want).length() < 1e-12 * OMEGA * RD);
                // and the clump's material point there moves with it
                let xb = w.bodies().position[b];
                let body_v = w.bodies().velocity[b] + w.bodies().angular_velocity[b].cross(p - xb);
                assert!(
                    (body_v - want).length() < 1e-3 * OMEGA * RD,
                    "contact point velocity {body_v}, ω × r = {want}"
                );
            }
            assert_eq!(touching, 4, "the lower face touches the drum");
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} rigid-rotation checks");
    // the clump was carried up to the angle where the statics of the stuck
    // clump fail, then it left the rigid rotation
    let slip = slip_angle.expect("the clump never left the rigid rotation");
    assert!(
        (slip - theta_s).abs() < 1.5f64.to_radians(),
        "left the rigid rotation at {:.2}°, statics fail at {:.2}° (tolerance: detection delay)",
        slip.to_degrees(),
        theta_s.to_degrees()
    );
    // the mesh pose is the prescribed rotation by ω t about y
    let turned = DQuat::from_rotation_y(OMEGA * (w.time - t_start)) * q0;
    let (_, pos, q) = w.walls[drum].shape.mesh_pose().unwrap();
    assert!(pos.length() < 1e-12);
    assert!(q.dot(turned).abs() > 1.0 - 1e-12, "{q} vs {turned}");
}
