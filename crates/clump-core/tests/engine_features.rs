//! Engine features checked against closed-form mechanics (not against the
//! code's own output): DOF flags, the added-mass factor, moving and rotating
//! walls, cylinders inside and outside with the recorded wall load, periodic
//! clumps straddling the boundary, a 10× sphere-size ratio in one run,
//! contact history across neighbour-list rebuilds and re-sorting, streamed
//! bodies moving ballistically until their start step, and the rotational
//! energy of a clump in the thermo output.

mod common;
use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World};
use common::*;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

const G: f64 = 9.81;

fn soft() -> Material {
    Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

fn props(e: f64, mu: f64) -> PairProperties {
    PairProperties {
        restitution: e,
        friction: mu,
        ..PairProperties::default()
    }
}

fn sphere_template(r: f64, rho: f64) -> ClumpTemplate {
    coincident(1, r, rho)
}

fn sphere_mass(r: f64, rho: f64) -> f64 {
    rho * 4.0 / 3.0 * PI * r.powi(3)
}

// ------------------------------------------------------------ DOF flags

/// fflag: a frozen world-axis force component leaves that velocity
/// component untouched; the free components follow x = ½ a t² exactly
/// (velocity Verlet is exact for a constant force).
#[test]
fn force_flags_freeze_world_axes() {
    let g = DVec3::new(2.0, 0.0, -G);
    let mut w = world(soft(), props(0.5, 0.5), 1e-4, open_domain(10.0), g);
    let t = w.add_template(sphere_template(0.01, 2500.0), 0).unwrap();
    let id = w
        .add_body(&BodyInit {
            force_flag: [true, true, false],
            ..BodyInit::at_rest(t, DVec3::ZERO, DQuat::IDENTITY)
        })
        .unwrap();
    let n = 1000;
    w.run(n).unwrap();
    let b = w.body_index(id).unwrap();
    let time = n as f64 * 1e-4;
    let (x, v) = (w.bodies().position[b], w.bodies().velocity[b]);
    eprintln!("fflag [1,1,0] under g = {g}: x = {x}, v = {v} at t = {time}");
    assert_eq!(x.z, 0.0);
    assert_eq!(v.z, 0.0);
    assert!(rel(x.x, 0.5 * 2.0 * time * time) < 1e-12);
    assert!(rel(v.x, 2.0 * time) < 1e-12);
    // gravity acts on the true clump mass
    let m = sphere_mass(0.01, 2500.0);
    assert!(rel(w.bodies().mass[b], m) < 1e-12);
    assert!((w.bodies().force[b] - m * g).length() < 1e-12 * m * G);
}

/// A world under gravity with friction `mu` (e = 0.5, dt = 1e-5) holding one
/// sphere template of radius `r`; returns the world, the template and the
/// static Hertz overlap δ of that sphere resting on a rigid floor
/// (m g = (4/3) E* √r δ^{3/2}, E* = E/(1 − ν²)).
fn floor_world(r: f64, mu: f64) -> (World, u32, f64) {
    let mut w = world(
        soft(),
        props(0.5, mu),
        1e-5,
        open_domain(10.0),
        DVec3::new(0.0, 0.0, -G),
    );
    let t = w.add_template(sphere_template(r, 2500.0), 0).unwrap();
    let m = sphere_mass(r, 2500.0);
    let e_star = 1e7 / (1.0 - 0.09);
    let delta = (m * G / (4.0 / 3.0 * e_star * r.sqrt())).powf(2.0 / 3.0);
    (w, t, delta)
}

/// A sphere launched sliding at v0 on a frictional floor (μ = 0.3).
/// Free rotation (tflag on): friction spins it up until it rolls, after
/// t* = 2v0/(7μg), at v = (5/7) v0 and ω = v/R. Rotation frozen (tflag off):
/// it slides at v = v0 − μ g t and never spins. With the added-mass factor
/// f = 1 + CAdd ρ_f/ρ both kicks are divided by f: a = μg/f, α = 5μg/(2fR).
fn slide(torque_flag: [bool; 3], added: AddedMass, time: f64) -> (DVec3, DVec3) {
    let (r, mu, v0) = (0.01, 0.3, 1.0);
    // start at the static Hertz overlap, so the floor load is m g from the start
    let (mut w, t, delta) = floor_world(r, mu);
    w.config.added_mass = added;
    let id = w
        .add_body(&BodyInit {
            velocity: DVec3::new(v0, 0.0, 0.0),
            torque_flag,
            ..BodyInit::at_rest(t, DVec3::new(0.0, 0.0, r - delta), DQuat::IDENTITY)
        })
        .unwrap();
    w.add_wall(plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum))
        .unwrap();
    w.run((time / 1e-5).round() as u64).unwrap();
    let b = w.body_index(id).unwrap();
    (w.bodies().velocity[b], w.bodies().angular_velocity[b])
}

#[test]
fn torque_flags_and_added_mass_against_sliding_and_rolling() {
    let (r, mu, v0) = (0.01, 0.3, 1.0);
    let none = AddedMass::default();
    // free: rolling after t* = 2 v0/(7 μ g) = 0.0971 s
    let (v, om) = slide([true; 3], none, 0.2);
    eprintln!(
        "free sphere at t=0.2: v = {v}, ω = {om} (theory v = {:.5}, ω_y = {:.3})",
        5.0 / 7.0 * v0,
        5.0 / 7.0 * v0 / r
    );
    assert!(rel(v.x, 5.0 / 7.0 * v0) < 5e-3, "{v}");
    assert!(rel(om.y, 5.0 / 7.0 * v0 / r) < 5e-3, "{om}");
    // frozen rotation: pure sliding
    let (v, om) = slide([false; 3], none, 0.2);
    let v_th = v0 - mu * G * 0.2;
    eprintln!("tflag off at t=0.2: v = {v}, ω = {om} (theory v = {v_th:.5}, ω = 0)");
    assert!(rel(v.x, v_th) < 5e-3, "{v}");
    assert_eq!(om, DVec3::ZERO);
    // only the y torque component acts (the friction torque is along y)
    let (v2, om2) = slide([false, true, false], none, 0.2);
    assert!(rel(v2.x, 5.0 / 7.0 * v0) < 5e-3 && rel(om2.y, 5.0 / 7.0 * v0 / r) < 5e-3);
    // added mass, CAdd = 0.5 in water: f = 1 + 0.5·1000/2500 = 1.2
    let added = AddedMass {
        coefficient: 0.5,
        fluid_density: 1000.0,
    };
    let f = 1.2;
    let t = 0.05; // before rolling (t* = 0.1165 s with f)
    let (v, om) = slide([true; 3], added, t);
    let (v_th, om_th) = (v0 - mu * G * t / f, 2.5 * mu * G * t / (f * r));
    eprintln!(
        "added mass f=1.2 at t=0.05: v = {v}, ω = {om} (theory v = {v_th:.5}, ω_y = {om_th:.3})"
    );
    assert!(rel(v.x, v_th) < 5e-3, "{v}");
    assert!(rel(om.y, om_th) < 5e-3, "{om}");
}

/// Added mass in free fall: z = −½ (g/f) t² exactly; the recorded force is
/// still the true weight m g.
#[test]
fn added_mass_free_fall() {
    let mut w = world(
        soft(),
        props(0.5, 0.5),
        1e-4,
        open_domain(10.0),
        DVec3::new(0.0, 0.0, -G),
    );
    w.config.added_mass = AddedMass {
        coefficient: 0.5,
        fluid_density: 1000.0,
    };
    let t = w.add_template(sphere_template(0.01, 2500.0), 0).unwrap();
    let id = w
        .add_body(&BodyInit::at_rest(t, DVec3::ZERO, DQuat::IDENTITY))
        .unwrap();
    w.run(1000).unwrap();
    let b = w.body_index(id).unwrap();
    let z_th = -0.5 * G / 1.2 * 0.1f64.powi(2);
    eprintln!(
        "added-mass free fall: z = {:.9e} (theory {z_th:.9e})",
        w.bodies().position[b].z
    );
    assert!(rel(w.bodies().position[b].z, z_th) < 1e-12);
    assert!(rel(w.bodies().force[b].z, -sphere_mass(0.01, 2500.0) * G) < 1e-12);
}

// ------------------------------------------------------------ walls

/// Runs `w` until body `id` has touched and left the walls; returns the
/// impulse the walls received, Σ F_wall dt (N s, summed over all walls).
fn run_wall_impact(w: &mut World, max_steps: usize) -> DVec3 {
    let mut impulse = DVec3::ZERO;
    let mut started = false;
    for _ in 0..max_steps {
        w.step().unwrap();
        let dt = w.config.dt;
        for l in w.walls.loads() {
            impulse += l.force * dt;
        }
        if w.stats.wall_contacts > 0 {
            started = true;
        } else if started {
            break;
        }
    }
    assert!(started, "no wall contact");
    impulse
}

fn cylinder(radius: f64, inside: bool, motion: WallMotion) -> Wall {
    Wall {
        name: "cyl".into(),
        shape: WallShape::Cylinder {
            point: DVec3::ZERO,
            axis: DVec3::Z,
            radius,
            inside,
        },
        material: 1,
        motion,
        multi_contact: MultiContact::Sum,
        active: true,
    }
}

/// A sphere hits a cylinder radially, from inside (a drum) and from outside
/// (a pin): it rebounds with e v, and the load recorded on the wall adds up
/// to the momentum the sphere lost (Newton's third law, summed over steps).
#[test]
fn cylinder_inside_and_outside_rebound_and_wall_load() {
    let (r, rc, v) = (0.01, 0.1, 0.5);
    let m = sphere_mass(r, 2500.0);
    for inside in [true, false] {
        for e in [1.0, 0.5] {
            let mut w = world(soft(), props(e, 0.3), 1e-6, open_domain(1.0), DVec3::ZERO);
            let t = w.add_template(sphere_template(r, 2500.0), 0).unwrap();
            let (x0, v0) = if inside {
                (rc - r - 1e-5, v)
            } else {
                (rc + r + 1e-5, -v)
            };
            let id = w
                .add_body(&moving(
                    t,
                    DVec3::new(x0, 0.0, 0.0),
                    DVec3::new(v0, 0.0, 0.0),
                    DVec3::ZERO,
                ))
                .unwrap();
            w.add_wall(cylinder(rc, inside, WallMotion::default()))
                .unwrap();
            let impulse = run_wall_impact(&mut w, 1_000_000);
            let b = w.body_index(id).unwrap();
            let v1 = w.bodies().velocity[b];
            let lost = m * (DVec3::new(v0, 0.0, 0.0) - v1);
            eprintln!("cylinder inside={inside} e={e}: v' = {v1}, wall impulse {impulse} (momentum lost {lost})");
            assert!(((-v1.x / v0) - e).abs() < 0.01, "rebound {v1}");
            assert!(v1.y.abs() < 1e-12 && v1.z.abs() < 1e-12);
            assert!(
                (impulse - lost).length() < 1e-9 * lost.length(),
                "{impulse} vs {lost}"
            );
        }
    }
}

/// A piston (a plane moving at u) hits a sphere at rest: an elastic sphere
/// leaves at 2u, a damped one at (1 + e) u (infinite wall mass).
#[test]
fn moving_plane_launches_sphere_at_one_plus_e_times_u() {
    let (r, u) = (0.01, 0.3);
    for e in [1.0, 0.6] {
        let mut w = world(soft(), props(e, 0.0), 1e-6, open_domain(1.0), DVec3::ZERO);
        let t = w.add_template(sphere_template(r, 2500.0), 0).unwrap();
        let id = w
            .add_body(&BodyInit::at_rest(
                t,
                DVec3::new(0.0, 0.0, r + 1e-5),
                DQuat::IDENTITY,
            ))
            .unwrap();
        let mut p = plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum);
        p.motion.velocity = DVec3::new(0.0, 0.0, u);
        w.add_wall(p).unwrap();
        run_wall_impact(&mut w, 1_000_000);
        let b = w.body_index(id).unwrap();
        let vz = w.bodies().velocity[b].z;
        eprintln!(
            "piston u={u} e={e}: sphere leaves at {vz:.6} (theory {:.6})",
            (1.0 + e) * u
        );
        assert!(rel(vz, (1.0 + e) * u) < 0.01);
    }
}

/// Regression for the wall Verlet list: a plane that is at rest when the
/// list is built, far from a sphere (so the sphere has no wall to test), and
/// starts to move towards it between two neighbour builds must still hit
/// it, and launch it at (1 + e) u like a piston moving from the start.
#[test]
fn wall_that_starts_moving_between_builds_hits_a_far_sphere() {
    let (r, u, e) = (0.01, 0.3, 0.6);
    let mut w = world(soft(), props(e, 0.0), 1e-6, open_domain(1.0), DVec3::ZERO);
    let t = w.add_template(sphere_template(r, 2500.0), 0).unwrap();
    let id = w
        .add_body(&BodyInit::at_rest(
            t,
            DVec3::new(0.0, 0.0, 3.0 * r),
            DQuat::IDENTITY,
        ))
        .unwrap();
    w.add_wall(plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum))
        .unwrap();
    w.run(10).unwrap();
    let rebuilds = w.rebuilds;
    w.walls[0].motion.velocity = DVec3::new(0.0, 0.0, u);
    // the wall covers the gap of 2r in about 2r/u
    let mut first_contact_rebuilds = None;
    for _ in 0..(4.0 * r / u / w.config.dt) as usize {
        w.step().unwrap();
        if w.stats.wall_contacts > 0 {
            first_contact_rebuilds = Some(w.rebuilds);
            break;
        }
    }
    assert_eq!(
        first_contact_rebuilds,
        Some(rebuilds),
        "the moving wall must touch the sphere, with no neighbour build in between"
    );
    run_wall_impact(&mut w, 1_000_000);
    let vz = w.bodies().velocity[w.body_index(id).unwrap()].z;
    eprintln!(
        "wall started between builds: sphere leaves at {vz:.6} (theory {:.6})",
        (1.0 + e) * u
    );
    assert!(rel(vz, (1.0 + e) * u) < 0.01);
}

/// A floor spinning about its own normal (a turntable; the geometry is
/// invariant, only the surface moves at ω × x). A sphere with frozen rotation
/// resting at distance d from the axis is dragged along the surface velocity
/// (+y at (d, 0)) at a = μ g until it catches up; the floor records the
/// friction load: force −μ m g ŷ and torque about z of −d μ m g.
#[test]
fn rotating_floor_drags_sphere_and_records_torque() {
    let (r, mu, d, omega) = (0.01, 0.3, 0.1, 10.0);
    let m = sphere_mass(r, 2500.0);
    let (mut w, t, delta) = floor_world(r, mu);
    let id = w
        .add_body(&BodyInit {
            torque_flag: [false; 3],
            ..BodyInit::at_rest(t, DVec3::new(d, 0.0, r - delta), DQuat::IDENTITY)
        })
        .unwrap();
    let mut p = plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum);
    p.motion.angular_velocity = DVec3::new(0.0, 0.0, omega);
    w.add_wall(p).unwrap();
    let time: f64 = 0.05;
    let n = (time / 1e-5).round() as u64;
    let mut mean_load = DVec3::ZERO;
    let mut mean_torque = DVec3::ZERO;
    for _ in 0..n {
        w.step().unwrap();
        mean_load += w.walls.loads()[0].force / n as f64;
        mean_torque += w.walls.loads()[0].torque / n as f64;
    }
    let b = w.body_index(id).unwrap();
    let v = w.bodies().velocity[b];
    eprintln!(
        "turntable: v = {v} (theory (0, {:.5}, 0)); mean wall force {mean_load}, torque {mean_torque} (theory F_y {:.4e}, M_z {:.4e})",
        mu * G * time,
        -mu * m * G,
        -d * mu * m * G
    );
    assert!(rel(v.y, mu * G * time) < 0.01, "{v}");
    assert!(v.x.abs() < 0.05 * v.y);
    assert!(rel(mean_load.y, -mu * m * G) < 0.01);
    assert!(rel(mean_load.z, -m * G) < 0.01);
    assert!(rel(mean_torque.z, -d * mu * m * G) < 0.02);
}

// ------------------------------------------------------------ periodic

/// The same oblique, frictional collision of a dimer clump with a sphere,
/// once in the middle of a box periodic in x and once shifted so that the
/// dimer straddles the boundary and the collision happens through the
/// sphere images. The outcomes agree to round-off; the clump's centre of
/// mass is wrapped into the box at every neighbour build.
#[test]
fn periodic_clump_straddling_the_boundary() {
    let run = |shift: f64| {
        let dom = Domain {
            lo: DVec3::new(0.0, -0.05, -0.05),
            hi: DVec3::new(0.1, 0.05, 0.05),
            periodic: [true, false, false],
        };
        let mut w = world(soft(), props(0.7, 0.4), 2e-6, dom, DVec3::ZERO);
        let s = [
            Sphere::new(DVec3::new(-0.004, 0.0, 0.0), 0.005),
            Sphere::new(DVec3::new(0.004, 0.0, 0.0), 0.005),
        ];
        let dimer = w
            .add_template(ClumpTemplate::from_spheres("dimer", &s, 2500.0).unwrap(), 0)
            .unwrap();
        let ball = w.add_template(sphere_template(0.005, 2500.0), 0).unwrap();
        let wrap = |x: f64| (x + shift).rem_euclid(0.1);
        let a = w
            .add_body(&moving(
                dimer,
                DVec3::new(wrap(0.04), 0.0, 0.0),
                DVec3::new(0.5, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 3.0),
            ))
            .unwrap();
        let c = w
            .add_body(&moving(
                ball,
                DVec3::new(wrap(0.0615), 0.004, 0.0),
                DVec3::ZERO,
                DVec3::ZERO,
            ))
            .unwrap();
        let mut contact_steps = 0;
        let mut straddled = false;
        for _ in 0..20_000 {
            let rebuilds = w.rebuilds;
            w.step().unwrap();
            contact_steps += (w.stats.pair_contacts > 0) as u32;
            let ia = w.body_index(a).unwrap();
            let x = w.bodies().position[ia].x;
            // wrapped at every neighbour build (as LAMMPS wraps atoms when
            // it re-neighbours); in between it moves less than half the skin
            if w.rebuilds > rebuilds {
                assert!((0.0..0.1).contains(&x), "centre of mass not wrapped: {x}");
            }
            let h = 0.5 * w.skin();
            assert!(
                x >= -h && x < 0.1 + h,
                "centre of mass {x} beyond half the skin {h}"
            );
            let sp = w.spheres();
            straddled |= sp
                .of_body(ia)
                .any(|k| sp.position(k).x + 0.005 > 0.1 || sp.position(k).x - 0.005 < 0.0);
        }
        let (ia, ic) = (w.body_index(a).unwrap(), w.body_index(c).unwrap());
        (
            w.bodies().velocity[ia],
            w.bodies().angular_velocity[ia],
            w.bodies().velocity[ic],
            w.bodies().angular_velocity[ic],
            contact_steps,
            straddled,
        )
    };
    let mid = run(0.0);
    let edge = run(0.058); // the dimer's front sphere crosses x = 0.1 just before contact
    eprintln!("periodic: middle {mid:?}\n          straddling {edge:?}");
    assert!(
        mid.4 > 100 && edge.4.abs_diff(mid.4) <= 1,
        "contact steps {} {}",
        mid.4,
        edge.4
    );
    assert!(edge.5, "the dimer never straddled the boundary");
    assert!(mid.2.length() > 0.1, "the ball must be hit");
    for (p, q) in [
        (mid.0, edge.0),
        (mid.1, edge.1),
        (mid.2, edge.2),
        (mid.3, edge.3),
    ] {
        assert!(
            (p - q).length() <= 1e-9 * p.length().max(1e-3),
            "{p} vs {q}"
        );
    }
}

// ------------------------------------------------------------ size ratio

/// Spheres whose radii differ by 10× in one run. (a) A small sphere hits a
/// big one head-on: Hertz theory (REFERENCE.md §3 formulas with R*, m*).
/// (b) A gas of 2 big and ~150 small spheres in a box: at every step the
/// engine's touching-pair count equals a brute-force O(N²) count.
#[test]
fn ten_to_one_size_ratio() {
    let (rs, rb, v) = (0.002, 0.02, 1.0);
    let mat = soft();
    // (a)
    let mut w = world(mat, props(1.0, 0.0), 2e-7, open_domain(1.0), DVec3::ZERO);
    let ts = w.add_template(sphere_template(rs, 2500.0), 0).unwrap();
    let tb = w.add_template(sphere_template(rb, 2500.0), 0).unwrap();
    let small = w
        .add_body(&moving(
            ts,
            DVec3::new(-rs - 1e-6, 0.0, 0.0),
            DVec3::new(v, 0.0, 0.0),
            DVec3::ZERO,
        ))
        .unwrap();
    w.add_body(&BodyInit::at_rest(
        tb,
        DVec3::new(rb + 1e-6, 0.0, 0.0),
        DQuat::IDENTITY,
    ))
    .unwrap();
    let imp = run_impact(&mut w, small, rs, 1_000_000);
    let (ms, mb) = (sphere_mass(rs, 2500.0), sphere_mass(rb, 2500.0));
    let m_star = ms * mb / (ms + mb);
    let r_star = rs * rb / (rs + rb);
    let e_star = 1.0 / (2.0 * (1.0 - 0.09) / 1e7);
    let dmax = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
    let fmax = 4.0 / 3.0 * e_star * r_star.sqrt() * dmax.powf(1.5);
    let tc = 2.9432 * dmax / v;
    eprintln!(
        "10x ratio head-on: δmax {:.5e} (theory {dmax:.5e}), Fmax {:.5e} (theory {fmax:.5e}), t_c {:.4e} (theory {tc:.4e})",
        imp.max_overlap, imp.max_force, imp.duration
    );
    assert!(rel(imp.max_overlap, dmax) < 0.005);
    assert!(rel(imp.max_force, fmax) < 0.005);
    assert!(rel(imp.duration, tc) < 0.02);

    // (b)
    let mut w = world(mat, props(0.9, 0.3), 1e-5, open_domain(1.0), DVec3::ZERO);
    let ts = w.add_template(sphere_template(rs, 2500.0), 0).unwrap();
    let tb = w.add_template(sphere_template(rb, 2500.0), 0).unwrap();
    w.add_wall(Wall {
        name: "box".into(),
        shape: WallShape::Box {
            lo: DVec3::ZERO,
            hi: DVec3::splat(0.1),
            inside: true,
        },
        material: 1,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    })
    .unwrap();
    let bigs = [DVec3::new(0.03, 0.03, 0.05), DVec3::new(0.07, 0.07, 0.05)];
    for c in bigs {
        w.add_body(&BodyInit::at_rest(tb, c, DQuat::IDENTITY))
            .unwrap();
    }
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let mut n_small = 0;
    for i in 0..12 {
        for j in 0..12 {
            for k in 0..3 {
                let x = DVec3::new(
                    0.006 + 0.008 * i as f64,
                    0.006 + 0.008 * j as f64,
                    0.03 + 0.02 * k as f64,
                );
                if bigs.iter().any(|c| (x - *c).length() < rb + rs + 1e-3) {
                    continue;
                }
                let vel = DVec3::new(rnd(), rnd(), rnd()) * 2.0;
                w.add_body(&moving(ts, x, vel, DVec3::ZERO)).unwrap();
                n_small += 1;
            }
        }
    }
    let (mut max_contacts, mut small_big) = (0u64, 0u64);
    let rebuilds0 = w.rebuilds;
    for _ in 0..3000 {
        w.step().unwrap();
        let sp = w.spheres();
        let mut brute = 0u64;
        for i in 0..sp.len() {
            for j in i + 1..sp.len() {
                if sp.body[i] != sp.body[j]
                    && (sp.position(i) - sp.position(j)).length() < sp.radius[i] + sp.radius[j]
                {
                    brute += 1;
                    if sp.radius[i] != sp.radius[j] {
                        small_big += 1;
                    }
                }
            }
        }
        assert_eq!(w.stats.pair_contacts, brute, "step {}", w.step);
        max_contacts = max_contacts.max(brute);
    }
    eprintln!(
        "10x ratio gas: {n_small} small + 2 big spheres, 3000 steps, {} rebuilds, max {max_contacts} contacts, {small_big} small-big contact-steps, lost {}",
        w.rebuilds - rebuilds0,
        w.lost.total()
    );
    assert_eq!(w.lost.total(), 0);
    assert!(small_big > 100, "small spheres must hit the big ones");
    assert!(w.rebuilds - rebuilds0 > 5);
}

// ------------------------------------------------------------ history

/// Static friction held by the tangential history spring, on a sphere pair
/// and on an inclined wall, survives a neighbour-list rebuild that also
/// re-sorts the bodies (a new body is added far away, at the grid's low
/// corner, first in storage order, so storage indices change). Sphere B
/// rests on a fixed sphere A, 10° off the top, and sphere D on a 10° incline, both with frozen rotation
/// and μ = 0.9 (> tan 10°): if the history were lost at the rebuild they
/// would start to slide. The run with the rebuild matches a run without it.
#[test]
fn contact_history_survives_rebuild_and_resort() {
    let run = |add_body: bool| {
        let mut w = world(
            soft(),
            props(0.3, 0.9),
            2e-5,
            open_domain(2.0),
            DVec3::new(0.0, 0.0, -G),
        );
        let r = 0.01;
        let t = w.add_template(sphere_template(r, 2500.0), 0).unwrap();
        let frozen = |x: DVec3| BodyInit {
            force_flag: [false; 3],
            torque_flag: [false; 3],
            ..BodyInit::at_rest(t, x, DQuat::IDENTITY)
        };
        let a = w.add_body(&frozen(DVec3::ZERO)).unwrap();
        let tilt = 10f64.to_radians();
        let dir = DVec3::new(tilt.sin(), 0.0, tilt.cos());
        let b = w
            .add_body(&BodyInit {
                torque_flag: [false; 3],
                ..BodyInit::at_rest(t, dir * (2.0 * r - 1e-5), DQuat::IDENTITY)
            })
            .unwrap();
        // the incline leans the other way, so that the far corner where the
        // extra body goes lies above it
        let p0 = DVec3::new(0.5, 0.0, -1.5);
        let n2 = DVec3::new(-tilt.sin(), 0.0, tilt.cos());
        w.add_wall(plane(p0, n2, MultiContact::Sum)).unwrap();
        let d = w
            .add_body(&BodyInit {
                torque_flag: [false; 3],
                ..BodyInit::at_rest(t, p0 + n2 * (r - 1e-6), DQuat::IDENTITY)
            })
            .unwrap();
        w.run(3000).unwrap(); // settle
        let tangent = DVec3::new(tilt.cos(), 0.0, -tilt.sin());
        let tangent2 = DVec3::new(tilt.cos(), 0.0, tilt.sin());
        let at = |w: &World, id| w.bodies().position[w.body_index(id).unwrap()];
        let (xb, xd) = (at(&w, b), at(&w, d));
        let before = (w.body_index(a), w.body_index(b), w.body_index(d));
        let rebuilds = w.rebuilds;
        if add_body {
            let far = DVec3::new(-1.9, -1.9, -1.4);
            assert!(
                (far - p0).dot(n2) > 0.1,
                "the extra body must lie above the incline"
            );
            w.add_body(&frozen(far)).unwrap();
        }
        w.run(10_000).unwrap();
        let after = (w.body_index(a), w.body_index(b), w.body_index(d));
        let slide_b = (at(&w, b) - xb).dot(tangent).abs();
        let slide_d = (at(&w, d) - xd).dot(tangent2).abs();
        (
            at(&w, b),
            at(&w, d),
            slide_b,
            slide_d,
            w.rebuilds - rebuilds,
            before != after,
        )
    };
    let plain = run(false);
    let rebuilt = run(true);
    eprintln!(
        "history: without rebuild slide B {:.2e} m, D {:.2e} m; with rebuild+resort ({} rebuilds, indices changed: {}) slide B {:.2e} m, D {:.2e} m",
        plain.2, plain.3, rebuilt.4, rebuilt.5, rebuilt.2, rebuilt.3
    );
    assert_eq!(plain.4, 0, "the control run must not rebuild");
    assert!(rebuilt.4 >= 1 && rebuilt.5, "no rebuild / re-sort happened");
    for s in [plain.2, plain.3, rebuilt.2, rebuilt.3] {
        assert!(s < 1e-7, "sphere slid by {s} m");
    }
    assert!((plain.0 - rebuilt.0).length() < 1e-12 && (plain.1 - rebuilt.1).length() < 1e-12);
}

// ------------------------------------------------------------ start step

/// A body before its start step moves at its velocity, ignoring gravity and
/// contacts (LIGGGHTS' `has_stream … start_step` branch), and then falls.
#[test]
fn body_moves_ballistically_until_its_start_step() {
    let dt = 1e-4;
    let mut w = world(
        soft(),
        props(0.5, 0.5),
        dt,
        open_domain(10.0),
        DVec3::new(0.0, 0.0, -G),
    );
    let t = w.add_template(coincident(2, 0.01, 2500.0), 0).unwrap();
    let v = DVec3::new(0.3, 0.0, -2.0);
    let x0 = DVec3::new(0.0, 0.0, 1.0);
    let om = DVec3::new(0.0, 5.0, 0.0);
    // it starts half inside a wall (spheres live below z = 1), which it
    // leaves after 50 steps: no push from it before the start step
    w.add_wall(plane(
        DVec3::new(0.0, 0.0, 1.0),
        -DVec3::Z,
        MultiContact::Sum,
    ))
    .unwrap();
    let id = w
        .add_body(&BodyInit {
            velocity: v,
            angular_velocity: om,
            start_step: 500,
            ..BodyInit::at_rest(t, x0, DQuat::IDENTITY)
        })
        .unwrap();
    for n in 1..=500u64 {
        w.step().unwrap();
        let b = w.body_index(id).unwrap();
        let x = x0 + v * (n as f64 * dt);
        assert!((w.bodies().position[b] - x).length() < 1e-12, "step {n}");
        assert_eq!(w.bodies().velocity[b], v);
        assert_eq!(w.bodies().orientation[b], DQuat::IDENTITY);
    }
    // from its start step on, gravity acts
    w.run(10).unwrap();
    let b = w.body_index(id).unwrap();
    eprintln!(
        "start step 500: 10 steps after it v = {}",
        w.bodies().velocity[b]
    );
    assert!((w.bodies().velocity[b].z - (v.z - G * 10.0 * dt)).abs() < 1e-12);
}

// ------------------------------------------------------------ thermo

/// Rotational kinetic energy of a clump: two unit-ish overlapping spheres
/// (REFERENCE.md §2 closed forms for I_axis and I_trans) spinning about an
/// arbitrary axis at an arbitrary orientation: T = ½(I_axis ω_∥² + I_trans ω_⊥²).
#[test]
fn thermo_rotational_energy_of_a_clump() {
    let (a, rho) = (0.25f64, 3.0);
    let mut w = world(
        soft(),
        props(0.5, 0.5),
        1e-4,
        open_domain(10.0),
        DVec3::ZERO,
    );
    let s = [
        Sphere::new(DVec3::new(-a, 0.0, 0.0), 1.0),
        Sphere::new(DVec3::new(a, 0.0, 0.0), 1.0),
    ];
    let t = w
        .add_template(ClumpTemplate::from_spheres("pair", &s, rho).unwrap(), 0)
        .unwrap();
    let q = DQuat::from_axis_angle(DVec3::new(0.3, -1.0, 0.4).normalize(), 1.1);
    let om = DVec3::new(0.7, -0.2, 1.3);
    w.add_body(&BodyInit {
        angular_velocity: om,
        ..BodyInit::at_rest(t, DVec3::ZERO, q)
    })
    .unwrap();
    w.prepare().unwrap();
    let i_axis = rho * PI * (8.0 / 15.0 + a - 2.0 / 3.0 * a.powi(3) + a.powi(5) / 5.0);
    let i_trans =
        rho * PI * (8.0 / 15.0 + 1.5 * a + 4.0 / 3.0 * a * a + a.powi(3) / 3.0 + a.powi(5) / 30.0);
    // the template's long axis (smallest moment) is its body x axis
    let axis = q * DVec3::X;
    let w_par = om.dot(axis);
    let w_perp2 = om.length_squared() - w_par * w_par;
    let expect = 0.5 * (i_axis * w_par * w_par + i_trans * w_perp2);
    let got = w.thermo().kinetic_rotational;
    eprintln!("thermo rotational KE {got:.12e}, closed form {expect:.12e}");
    assert!(rel(got, expect) < 1e-9);
}

// ------------------------------------------------------------ lost bodies

/// Bodies leaving the domain are counted by the side their centre crossed,
/// a body removed by a driver by its own cause; a periodic axis loses none.
/// Ballistic flight without gravity: a body at speed v from the centre of a
/// box of half-width h leaves after h / v, so after 1.5 h / v every body sent
/// towards a non-periodic side is gone.
#[test]
fn lost_bodies_are_counted_by_cause() {
    let h = 0.1;
    let mut d = open_domain(h);
    d.periodic = [false, true, false];
    let mut w = world(soft(), props(0.5, 0.5), 1e-4, d, DVec3::ZERO);
    let t = w.add_template(sphere_template(0.005, 2500.0), 0).unwrap();
    let v = 2.0;
    let sends = [
        (DVec3::new(0.0, 0.0, -v), 0.0),
        (DVec3::new(0.0, 0.0, -v), 0.03),
        (DVec3::new(v, 0.0, 0.0), 0.0),
        (DVec3::new(0.0, v, 0.0), 0.0), // periodic y: wraps, never lost
    ];
    for (k, &(vel, dx)) in sends.iter().enumerate() {
        let x = DVec3::new(dx, 0.03 * k as f64 - 0.05, 0.0);
        w.add_body(&moving(t, x, vel, DVec3::ZERO)).unwrap();
    }
    let kept = w
        .add_body(&moving(
            t,
            DVec3::new(0.05, 0.05, 0.05),
            DVec3::ZERO,
            DVec3::ZERO,
        ))
        .unwrap();
    w.remove_body(kept).unwrap();
    let steps = (1.5 * h / v / 1e-4).ceil() as u64;
    w.run(steps).unwrap();
    let l = w.lost;
    eprintln!("after {steps} steps: {:?}", l.by_cause());
    assert_eq!(l.through_side, [0, 1, 0, 0, 2, 0]);
    assert_eq!(l.removed, 1);
    assert_eq!(l.not_finite, 0);
    assert_eq!(l.total(), 4);
    assert_eq!(w.bodies().len(), 1);
}
