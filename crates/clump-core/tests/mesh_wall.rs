//! Triangle-mesh walls: one contact per contact patch (shared edges and
//! vertices), concave corners, trajectories identical to analytic planes,
//! history carried across triangles, motion, and the BVH on a large mesh.

mod common;

use clump_core::body::BodyInit;
use clump_core::contact::{Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::wall::mesh::closest::closest_point_triangle;
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape, WallTouch, MAX_TOUCHES_PER_WALL};
use clump_core::world::World;
use common::*;
use glam::{DQuat, DVec3};

fn mesh_wall(mesh: u32) -> Wall {
    Wall {
        name: "mesh".into(),
        shape: WallShape::Mesh {
            mesh,
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
        },
        material: 1,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    }
}

/// Touches of a sphere with a single mesh at the identity pose.
fn touches(m: &TriMesh, x: DVec3, r: f64) -> Vec<WallTouch> {
    let shape = WallShape::Mesh {
        mesh: 0,
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
    };
    let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
    let k = shape.contacts(std::slice::from_ref(m), x, r, 0.0, &mut buf);
    buf[..k].to_vec()
}

/// A flat grid `[x0, x0 + n h] × [y0, y0 + n h]` at height `z`, two triangles
/// per cell, diagonals alternating.
fn grid(x0: f64, y0: f64, z: f64, n: usize, h: f64, bump: impl Fn(f64, f64) -> f64) -> TriMesh {
    let mut v = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (x0 + i as f64 * h, y0 + j as f64 * h);
            v.push(DVec3::new(x, y, z + bump(x, y)));
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut t = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                t.push([a, b, c]);
                t.push([a, c, d]);
            } else {
                t.push([a, b, d]);
                t.push([b, c, d]);
            }
        }
    }
    TriMesh::new(v, t).unwrap()
}

#[test]
fn coplanar_shared_edge_gives_one_contact() {
    // two triangles sharing the diagonal (−1,−1)–(1,1)
    let v = vec![
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
    ];
    let m = TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
    for x in [
        DVec3::new(0.0, 0.0, 0.9),
        DVec3::new(0.3, 0.3, 0.95),
        DVec3::new(0.3, 0.3 + 1e-15, 0.95),
        DVec3::new(-0.5, -0.5, -0.8),
    ] {
        let t = touches(&m, x, 1.0);
        assert_eq!(t.len(), 1, "sphere at {x}: {t:?}");
        let sign = x.z.signum();
        assert!((t[0].normal - DVec3::Z * sign).length() < 1e-12, "{t:?}");
        assert!((t[0].overlap - (1.0 - x.z.abs())).abs() < 1e-12);
    }
    // over the open boundary edge: one edge contact, normal towards the centre
    let t = touches(&m, DVec3::new(1.5, 0.0, 0.0), 0.6);
    assert_eq!(t.len(), 1);
    assert!((t[0].normal - DVec3::X).length() < 1e-12 && (t[0].overlap - 0.1).abs() < 1e-12);
}

#[test]
fn shared_vertex_gives_one_contact() {
    // a flat fan of 8 triangles around the origin, and a pyramid (convex apex)
    for apex in [0.0, 0.5] {
        let mut v = vec![DVec3::new(0.0, 0.0, apex)];
        for k in 0..8 {
            let a = k as f64 * std::f64::consts::TAU / 8.0;
            v.push(DVec3::new(a.cos(), a.sin(), 0.0));
        }
        let t: Vec<[u32; 3]> = (0..8).map(|k| [0, 1 + k, 1 + (k + 1) % 8]).collect();
        let m = TriMesh::new(v, t).unwrap();
        let x = DVec3::new(0.0, 0.0, apex + 0.9);
        let t = touches(&m, x, 1.0);
        assert_eq!(t.len(), 1, "apex {apex}: {t:?}");
        assert!(
            (t[0].normal - DVec3::Z).length() < 1e-12 && (t[0].overlap - 0.1).abs() < 1e-12,
            "{t:?}"
        );
        // slightly off the apex, still in the vertex region of the pyramid
        if apex > 0.0 {
            let x = DVec3::new(0.01, 0.02, apex + 0.9);
            let t = touches(&m, x, 1.0);
            assert_eq!(t.len(), 1, "{t:?}");
            assert!(
                (t[0].normal - x.normalize_or_zero()).length() < 1.0
                    && (t[0].overlap - (1.0 - (x - DVec3::new(0.0, 0.0, apex)).length())).abs()
                        < 1e-12
            );
        }
    }
}

#[test]
fn convex_ridge_gives_one_contact() {
    // a roof: two faces meeting at the ridge y = 0, z = 0.2, sloping down
    let v = vec![
        DVec3::new(-1.0, 0.0, 0.2),
        DVec3::new(1.0, 0.0, 0.2),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(-1.0, -1.0, 0.0),
    ];
    let m = TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3], [1, 0, 5], [1, 5, 4]]).unwrap();
    // above the ridge: one edge contact, straight up
    let t = touches(&m, DVec3::new(0.1, 0.0, 1.1), 1.0);
    assert_eq!(t.len(), 1, "{t:?}");
    assert!((t[0].normal - DVec3::Z).length() < 1e-12 && (t[0].overlap - 0.1).abs() < 1e-12);
    // over the +y face near the ridge: one face contact (the edge of the other face is not a contact)
    let n = DVec3::new(0.0, 0.2, 1.0).normalize();
    let foot = DVec3::new(0.0, 0.1, 0.18);
    let x = foot + n * 0.95;
    let t = touches(&m, x, 1.0);
    assert_eq!(t.len(), 1, "{t:?}");
    assert!(
        (t[0].normal - n).length() < 1e-12 && (t[0].overlap - 0.05).abs() < 1e-12,
        "{t:?}"
    );
    // sweeping across the ridge: always exactly one contact, normal and overlap continuous
    let mut prev: Option<WallTouch> = None;
    for i in 0..=400 {
        let y = -0.5 + i as f64 * 0.0025;
        let t = touches(&m, DVec3::new(0.0, y, 1.05), 1.0);
        assert_eq!(t.len(), 1, "y = {y}: {t:?}");
        if let Some(p) = prev {
            assert!(
                (t[0].normal - p.normal).length() < 0.02 && (t[0].overlap - p.overlap).abs() < 0.01,
                "jump at y = {y}"
            );
        }
        prev = Some(t[0]);
    }
}

#[test]
fn concave_corner_gives_one_contact_per_face() {
    // floor z = 0 (x ≥ 0) meeting a wall x = 0 (z ≥ 0)
    let v = vec![
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, -1.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let m = TriMesh::new(v, vec![[0, 1, 2], [0, 2, 3], [0, 3, 5], [0, 5, 4]]).unwrap();
    let t = touches(&m, DVec3::new(0.09, 0.0, 0.095), 0.1);
    assert_eq!(t.len(), 2, "{t:?}");
    let (mut nz, mut nx) = (false, false);
    for c in &t {
        if (c.normal - DVec3::Z).length() < 1e-12 {
            nz = true;
            assert!((c.overlap - 0.005).abs() < 1e-12);
        }
        if (c.normal - DVec3::X).length() < 1e-12 {
            nx = true;
            assert!((c.overlap - 0.01).abs() < 1e-12);
        }
    }
    assert!(nz && nx, "{t:?}");
    // a box corner from inside: three faces
    let cube = cube_mesh(0.5);
    let t = touches(&cube, DVec3::splat(-0.45), 0.1);
    assert_eq!(t.len(), 3, "{t:?}");
}

/// A closed axis-aligned cube `[-h, h]³`, 12 triangles.
fn cube_mesh(h: f64) -> TriMesh {
    let (v, t) = clump_core::wall::mesh::primitives::cuboid(DVec3::splat(-h), DVec3::splat(h));
    TriMesh::new(v, t).unwrap()
}

fn material() -> Material {
    Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

fn sphere_world(walls: impl FnOnce(&mut World)) -> (World, u64) {
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.4,
        ..Default::default()
    };
    let mut w = world(
        material(),
        props,
        5e-6,
        open_domain(1.0),
        DVec3::new(0.0, 0.0, -9.81),
    );
    let t = w.add_template(coincident(1, 0.01, 2500.0), 0).unwrap();
    walls(&mut w);
    let id = w
        .add_body(&moving(
            t,
            DVec3::new(0.0013, -0.0211, 0.0099),
            DVec3::new(0.35, 0.12, -0.05),
            DVec3::new(3.0, -20.0, 5.0),
        ))
        .unwrap();
    (w, id)
}

fn rel_vec(a: DVec3, b: DVec3, scale: f64) -> f64 {
    (a - b).length() / scale
}

#[test]
fn rolling_on_triangulated_floor_matches_analytic_plane() {
    let (mut a, ida) = sphere_world(|w| {
        w.add_wall(plane(DVec3::ZERO, DVec3::Z, MultiContact::Sum))
            .unwrap();
    });
    let (mut b, idb) = sphere_world(|w| {
        // 3 mm cells (the sphere radius is 10 mm): the contact crosses many
        // edges and passes near vertices
        let m = w.add_mesh(grid(-0.06, -0.06, 0.0, 40, 0.003, |_, _| 0.0));
        w.add_wall(mesh_wall(m)).unwrap();
    });
    let mut contacts = 0u64;
    for step in 0..30_000 {
        a.step().unwrap();
        b.step().unwrap();
        assert_eq!(a.stats.wall_contacts, b.stats.wall_contacts, "step {step}");
        contacts += a.stats.wall_contacts;
        if step % 500 == 499 {
            let (ia, ib) = (a.body_index(ida).unwrap(), b.body_index(idb).unwrap());
            let (pa, pb) = (a.bodies().position[ia], b.bodies().position[ib]);
            assert!(
                rel_vec(pa, pb, pa.length()) < 1e-9,
                "step {step}: {pa} vs {pb}"
            );
            let (va, vb) = (a.bodies().velocity[ia], b.bodies().velocity[ib]);
            assert!(
                rel_vec(va, vb, va.length()) < 1e-9,
                "step {step}: {va} vs {vb}"
            );
            let (wa, wb) = (
                a.bodies().angular_velocity[ia],
                b.bodies().angular_velocity[ib],
            );
            assert!(
                rel_vec(wa, wb, wa.length()) < 1e-9,
                "step {step}: {wa} vs {wb}"
            );
            let (fa, fb) = (a.walls.loads()[0].force, b.walls.loads()[0].force);
            assert!(
                rel_vec(fa, fb, fa.length().max(1e-3)) < 1e-9,
                "step {step}: wall force {fa} vs {fb}"
            );
            let (ta, tb) = (a.walls.loads()[0].torque, b.walls.loads()[0].torque);
            assert!(
                rel_vec(ta, tb, ta.length().max(1e-6)) < 1e-9,
                "step {step}: wall torque {ta} vs {tb}"
            );
        }
    }
    // it touched most of the time and travelled over many triangles
    assert!(contacts > 25_000, "{contacts}");
    let p = b.bodies().position[b.body_index(idb).unwrap()];
    assert!(p.x > 0.03, "{p}");
}

#[test]
fn history_carries_across_triangles() {
    // a non-rotating sphere dragged at constant horizontal velocity over a
    // finely triangulated floor: sliding friction must stay at μ|F_n| on every
    // step (a history reset at an edge would drop it to k_t v Δt ≪ μ|F_n|)
    for kink in [0.0, 1.0] {
        let mu = 0.4;
        // no dashpots (e = 1), so that the tangential force is the spring's alone
        let props = PairProperties {
            restitution: 1.0,
            friction: mu,
            ..Default::default()
        };
        let mut w = world(
            material(),
            props,
            5e-6,
            open_domain(1.0),
            DVec3::new(0.0, 0.0, -9.81),
        );
        let t = w.add_template(coincident(1, 0.01, 2500.0), 0).unwrap();
        // 1 mm cells, with a gentle convex fold along x = −6 mm (kink
        // degrees) so that the normal also rotates through an edge contact
        let slope = (kink as f64).to_radians().tan();
        let m = w.add_mesh(grid(-0.015, -0.015, 0.0, 30, 0.001, |x, _| {
            -slope * (x + 0.006).max(0.0)
        }));
        w.add_wall(mesh_wall(m)).unwrap();
        let body = BodyInit {
            force_flag: [false, false, true],
            torque_flag: [false; 3],
            velocity: DVec3::new(0.2, 0.05, 0.0),
            ..BodyInit::at_rest(t, DVec3::new(-0.0101, -0.0037, 0.00998), DQuat::IDENTITY)
        };
        let id = w.add_body(&body).unwrap();
        let mass = w.bodies().mass[0];
        let mut worst: f64 = f64::INFINITY;
        for step in 0..8000 {
            w.step().unwrap();
            assert_eq!(w.stats.wall_contacts, 1, "step {step}");
            if step < 1000 {
                continue; // build-up and settling
            }
            let b = w.body_index(id).unwrap();
            let f_contact = w.bodies().force[b] - mass * w.config.gravity;
            let x = w.bodies().position[b];
            let n = (x - w.walls.meshes()[0].closest_point(x).1).normalize();
            let fn_ = f_contact.dot(n);
            let ft = (f_contact - fn_ * n).length();
            worst = worst.min(ft / (mu * fn_.abs()));
        }
        assert!(
            worst > 0.999,
            "kink {kink}: tangential force dropped to {worst} of the Coulomb limit"
        );
        let x = w.bodies().position[0];
        assert!(x.x > -0.004, "{x}");
    }
}

#[test]
fn moving_and_rotated_mesh_matches_analytic_plane() {
    // a floor tilted by 20° about y and translating: contacts equal those of
    // the equivalent analytic plane
    let q = DQuat::from_rotation_y(20f64.to_radians());
    let m = grid(-1.0, -1.0, 0.0, 10, 0.2, |_, _| 0.0);
    let meshes = vec![m];
    let mut wm = mesh_wall(0);
    wm.shape = WallShape::Mesh {
        mesh: 0,
        position: DVec3::new(0.1, 0.0, 0.0),
        orientation: q,
    };
    wm.motion = WallMotion {
        velocity: DVec3::new(0.0, 0.0, 0.3),
        angular_velocity: DVec3::new(0.0, 0.5, 0.0),
        center: DVec3::new(0.1, 0.0, 0.0),
        ..Default::default()
    };
    let mut wp = plane(DVec3::new(0.1, 0.0, 0.0), q * DVec3::Z, MultiContact::Sum);
    wp.motion = wm.motion;
    for step in 0..100 {
        let WallShape::Plane { point, normal } = wp.shape else {
            unreachable!()
        };
        let (e1, e2) = normal.any_orthonormal_pair();
        let x = point
            + normal * (0.15 + 0.01 * (step as f64 * 0.3).cos())
            + e1 * (0.3 * (step as f64 * 0.1).sin())
            + e2 * (0.01 * step as f64);
        let mut bm = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
        let mut bp = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
        let km = wm.shape.contacts(&meshes, x, 0.2, 0.0, &mut bm);
        let kp = wp.shape.contacts(&meshes, x, 0.2, 0.0, &mut bp);
        assert_eq!(km, kp, "step {step}");
        for k in 0..km {
            assert!((bm[k].normal - bp[k].normal).length() < 1e-12);
            assert!((bm[k].overlap - bp[k].overlap).abs() < 1e-12);
        }
        wm.advance(1e-3);
        wp.advance(1e-3);
    }
    // the VTK accessor puts the vertices at the pose
    let (verts, tris) = wm.shape.mesh_at_pose(&meshes).unwrap();
    assert_eq!(verts.len(), meshes[0].vertices().len());
    assert_eq!(tris.len(), meshes[0].triangles().len());
    let (_, p, o) = wm.shape.mesh_pose().unwrap();
    assert!((verts[7] - (p + o * meshes[0].vertices()[7])).length() < 1e-15);
    if let WallShape::Plane { point, normal } = wp.shape {
        for v in &verts {
            assert!((*v - point).dot(normal).abs() < 1e-12);
        }
    }
}

#[test]
fn bvh_on_a_large_mesh() {
    // a bumpy 224 × 224 height field: 100 352 triangles
    let n = 224;
    let m = grid(-1.0, -1.0, 0.0, n, 2.0 / n as f64, |x, y| {
        0.05 * (7.0 * x).sin() * (5.0 * y).cos()
    });
    assert!(m.triangles().len() > 100_000);
    let t0 = std::time::Instant::now();
    let mut rng = 0x2545F4914F6CDD1Du64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    let queries = 100_000;
    let mut found = 0usize;
    let r = 0.01;
    for q in 0..queries {
        let x = DVec3::new(next() * 2.0 - 1.0, next() * 2.0 - 1.0, next() * 0.14 - 0.07);
        let t = touches(&m, x, r);
        found += t.len();
        // check every 500th query against brute force (distance to the surface)
        if q % 500 == 0 {
            let dmin = m
                .triangles()
                .iter()
                .enumerate()
                .map(|(i, _)| {
                    let [a, b, c] = m.corners(i as u32);
                    (x - closest_point_triangle(x, a, b, c).0).length()
                })
                .fold(f64::INFINITY, f64::min);
            if dmin < r - 1e-12 {
                assert!(
                    !t.is_empty(),
                    "query {q} missed a contact at distance {dmin}"
                );
                assert!((t[0].overlap - (r - dmin)).abs() < 1e-12);
            } else if dmin > r + 1e-12 {
                assert!(t.is_empty());
            }
        }
    }
    let dt = t0.elapsed();
    eprintln!(
        "{queries} sphere queries on {} triangles: {:.3} s ({} contacts)",
        m.triangles().len(),
        dt.as_secs_f64(),
        found
    );
    assert!(found > 0);
}
