//! A bed that the device path runs whole: for its tests and `clump bench --device gpu`.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{ContactTable, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{builtin, ClumpTemplate};
use clump_core::testbed::{tetra_material, tetra_template};
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};

/// Lattice pitch, m (the tetra bed's, `clump_core::testbed::LATTICE_PITCH`).
const PITCH: f64 = clump_core::testbed::LATTICE_PITCH;

/// `n × n × layers` clumps on a lattice, tetra clumps (`clump_core::testbed`'s
/// template and material) and rods of three spheres (radius 1 mm, spacing
/// 1.1 mm: an asymmetric top) in turn, Clump's default Hertz-Mindlin pair
/// law, in a box
/// `n` pitches wide closed by five static planes, gravity -9.81 m/s² along
/// z, the rotation scheme `rotation`, dt = 1e-5 s; each clump with a
/// deterministic velocity of up to 0.2 m/s and spin of up to 100 rad/s, so
/// that clump-clump and wall contacts form, slide and end within a few
/// thousand steps. Everything in it runs on the device.
pub fn box_bed(n: usize, layers: usize, rotation: RotationScheme) -> World {
    box_bed_dof(n, layers, rotation, |_| ([true; 3], [true; 3]))
}

/// [`box_bed`] with the force and torque flags per world axis of the
/// `k`-th clump (from 1) given by `flags(k)`; a clump's velocity is zero
/// along the axes its force flags lock.
pub fn box_bed_dof(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    flags: impl Fn(u64) -> ([bool; 3], [bool; 3]),
) -> World {
    box_bed_with(n, layers, rotation, |k, b| {
        (b.force_flag, b.torque_flag) = flags(k);
        // a locked axis starts at rest (it would never stop)
        b.velocity = DVec3::select(glam::BVec3::from(b.force_flag), b.velocity, DVec3::ZERO);
    })
}

/// [`box_bed`] with the `k`-th clump (from 1) changed by `each(k, init)`
/// before it is added (its degrees of freedom, its motion).
pub fn box_bed_with(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    each: impl Fn(u64, &mut BodyInit),
) -> World {
    box_bed_law(n, layers, rotation, PairProperties::default(), each)
}

/// [`box_bed_with`] with the pair law `law` for clump-clump and
/// clump-wall contacts (rolling resistance, say).
pub fn box_bed_law(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    law: PairProperties,
    each: impl Fn(u64, &mut BodyInit),
) -> World {
    let walls = box_planes(n as f64 * PITCH, true);
    bed_in(n, layers, rotation, law, walls, |k, b| {
        each(k, b);
        true
    })
}

/// Static planes closing the box `[0, l]² × [0, ∞)`: the floor (with
/// `floor`), then the sides at x = 0, y = 0, x = l, y = l.
fn box_planes(l: f64, floor: bool) -> Vec<(WallShape, WallMotion)> {
    let planes = [
        (DVec3::ZERO, DVec3::Z),
        (DVec3::ZERO, DVec3::X),
        (DVec3::ZERO, DVec3::Y),
        (DVec3::new(l, l, 0.0), -DVec3::X),
        (DVec3::new(l, l, 0.0), -DVec3::Y),
    ];
    planes[!floor as usize..]
        .iter()
        .map(|&(point, normal)| (WallShape::Plane { point, normal }, WallMotion::default()))
        .collect()
}

/// The bed of [`box_bed_law`] in the walls `walls` (shape and motion
/// each) instead of the five planes; the `k`-th clump is changed by
/// `each(k, init)` and left out where it answers false (to make room for
/// a wall). The domain is the five planes' box: the walls must keep the
/// clumps in it.
pub fn bed_in(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    law: PairProperties,
    walls: Vec<(WallShape, WallMotion)>,
    each: impl Fn(u64, &mut BodyInit) -> bool,
) -> World {
    bed_periodic(n, layers, rotation, law, walls, [false; 3], each)
}

/// [`box_bed`] periodic in x and y, with the floor as its only wall: the
/// clumps cross the periodic faces and touch across them.
pub fn periodic_bed(n: usize, layers: usize, rotation: RotationScheme) -> World {
    periodic_bed_law(n, layers, rotation, PairProperties::default())
}

/// [`periodic_bed`] with the pair law `law` for clump-clump and
/// clump-wall contacts (rolling resistance, say).
pub fn periodic_bed_law(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    law: PairProperties,
) -> World {
    let floor = WallShape::Plane {
        point: DVec3::ZERO,
        normal: DVec3::Z,
    };
    bed_periodic(
        n,
        layers,
        rotation,
        law,
        vec![(floor, WallMotion::default())],
        [true, true, false],
        |_, _| true,
    )
}

/// [`bed_in`] with the domain's periodic axes `periodic`.
pub fn bed_periodic(
    n: usize,
    layers: usize,
    rotation: RotationScheme,
    law: PairProperties,
    walls: Vec<(WallShape, WallMotion)>,
    periodic: [bool; 3],
    each: impl Fn(u64, &mut BodyInit) -> bool,
) -> World {
    let mats = vec![tetra_material()];
    let table = ContactTable::new(&mats, |_, _| law).expect("a valid test bed");
    let l = n as f64 * PITCH;
    let h = (layers as f64 + 2.0) * PITCH;
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(l, l, h),
            periodic,
        },
        gravity: DVec3::new(0.0, 0.0, -9.81),
        dt: 1e-5,
        rotation,
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let rod = ClumpTemplate::from_spheres(
        "rod",
        &builtin::rod(3, 1e-3, 1.1e-3),
        tetra_material().density,
    )
    .expect("a valid test bed");
    let templates = [
        w.add_template(tetra_template(), 0)
            .expect("a valid test bed"),
        w.add_template(rod, 0).expect("a valid test bed"),
    ];
    for (k, (shape, motion)) in walls.into_iter().enumerate() {
        w.add_wall(Wall {
            name: format!("wall{k}"),
            shape,
            material: 0,
            motion,
            multi_contact: MultiContact::Sum,
            active: true,
        })
        .expect("a valid test bed");
    }
    let mut k = 0u64;
    for z in 0..layers {
        for y in 0..n {
            for x in 0..n {
                k += 1;
                let kf = k as f64;
                let q = DQuat::from_euler(glam::EulerRot::ZXZ, kf * 0.7, kf * 1.3, kf * 0.4);
                let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.6) * PITCH;
                let mut b = BodyInit::at_rest(templates[k as usize % 2], p, q);
                b.velocity = 0.2 * DVec3::new((kf * 1.7).sin(), (kf * 2.3).sin(), (kf * 3.1).sin());
                b.angular_velocity =
                    100.0 * DVec3::new((kf * 0.9).cos(), (kf * 1.1).cos(), (kf * 1.9).cos());
                if each(k, &mut b) {
                    w.add_body(&b).expect("a valid test bed");
                }
            }
        }
    }
    w
}

/// A drum (a cylinder seen from inside, along z through the middle of a
/// 6 × 6 pitch box, radius 3 pitches, turning at 20 rad/s about its axis)
/// on a floor rising at 0.01 m/s, with a pin (a cylinder seen from
/// outside, along x, radius 0.25 pitch, turning at 30 rad/s about its
/// axis) coming down at 0.1 m/s from 3.6 pitches into the bed; three
/// layers of clumps within 2 pitches of the drum's axis. Walls 0 (floor),
/// 1 (drum), 2 (pin).
pub fn drum_bed() -> World {
    let c = DVec3::new(3.0 * PITCH, 3.0 * PITCH, 0.0);
    let pin = DVec3::new(0.0, 3.0 * PITCH, 3.6 * PITCH);
    let walls = vec![
        (
            WallShape::Plane {
                point: DVec3::ZERO,
                normal: DVec3::Z,
            },
            WallMotion {
                velocity: DVec3::new(0.0, 0.0, 0.01),
                ..Default::default()
            },
        ),
        (
            WallShape::Cylinder {
                point: c,
                axis: DVec3::Z,
                radius: 3.0 * PITCH,
                inside: true,
            },
            WallMotion {
                angular_velocity: DVec3::new(0.0, 0.0, 20.0),
                center: c,
                ..Default::default()
            },
        ),
        turning_pin(pin),
    ];
    let law = PairProperties::default();
    bed_in(6, 3, RotationScheme::NoSquish, law, walls, |_, b| {
        (b.position - c).truncate().length() < 2.0 * PITCH
    })
}

/// A container (a box seen from inside, 4 × 4 × 5 pitches: six faces, a
/// clump in a corner touches several) moving along x at 0.03 m/s and
/// turning at 5 rad/s about z (a surface velocity: a box only
/// translates), with a post (a box seen from outside, 0.4 × 0.4 × 1.2
/// pitches) in its middle whose surface moves at 0.05 m/s along y like a
/// conveyor; three layers of clumps, less those of the two lower layers
/// around the post. Walls 0 (container), 1 (post), 2 (an inactive plane
/// through the bed, a gate removed: it must touch nothing).
pub fn container_bed() -> World {
    let (l, h) = (4.0 * PITCH, 5.0 * PITCH);
    let mid = DVec3::new(2.0 * PITCH, 2.0 * PITCH, 0.0);
    let walls = vec![
        (
            WallShape::Box {
                lo: DVec3::ZERO,
                hi: DVec3::new(l, l, h),
                inside: true,
            },
            WallMotion {
                velocity: DVec3::new(0.03, 0.0, 0.0),
                angular_velocity: DVec3::new(0.0, 0.0, 5.0),
                center: mid,
                ..Default::default()
            },
        ),
        conveyor_post(mid),
        (
            WallShape::Plane {
                point: DVec3::new(0.0, 0.0, 1.5 * PITCH),
                normal: DVec3::Z,
            },
            WallMotion::default(),
        ),
    ];
    let law = PairProperties::default();
    let mut w = bed_in(4, 3, RotationScheme::NoSquish, law, walls, |_, b| {
        let d = (b.position - mid).truncate().abs();
        !(d.max_element() < PITCH && b.position.z < 2.0 * PITCH)
    });
    w.walls[2].active = false;
    w
}

/// The mesh walls `meshes` (a mesh, its pose and its motion each) added
/// to `w` after its other walls, static material 0, in order.
fn add_meshes(w: &mut World, meshes: Vec<(TriMesh, DVec3, DQuat, WallMotion)>) {
    for (mesh, position, orientation, motion) in meshes {
        let k = w.walls.len();
        let mesh = w.add_mesh(mesh);
        w.add_wall(Wall {
            name: format!("wall{k}"),
            shape: WallShape::Mesh {
                mesh,
                position,
                orientation,
            },
            material: 0,
            motion,
            multi_contact: MultiContact::Sum,
            active: true,
        })
        .expect("a valid test bed");
    }
}

/// A static mesh floor and post in a 4 × 4 pitch box: the floor an
/// inverted eight-facet cone one pitch deep (a hopper bottom: its seams
/// are concave, its apex a vertex) over the whole box, merge angle
/// `merge` rad; the post a 1 × 1 × 3 pitch cuboid mesh turned by 30°
/// about z in the middle (convex edges and corners). The box's side
/// planes (walls 0-3) close it; walls 4 (floor) and 5 (post). Three
/// layers of clumps, raised by a pitch and thrown down at 0.3 m/s, less
/// those in the post.
pub fn mesh_floor_bed(merge: f64) -> World {
    use clump_core::wall::mesh::primitives::{cuboid, revolve};
    let l = 4.0 * PITCH;
    let mid = DVec3::new(0.5 * l, 0.5 * l, 0.0);
    let walls = box_planes(l, false);
    let post = |p: DVec3| (p - mid).truncate().length() < 1.3 * PITCH;
    let mut w = bed_in(
        4,
        3,
        RotationScheme::NoSquish,
        PairProperties::default(),
        walls,
        |_, b| {
            b.position.z += PITCH;
            b.velocity.z -= 0.3;
            !post(b.position)
        },
    );
    let (v, t) = revolve(&[(0.0, 0.0), (0.75 * l, PITCH)], 8, 0.0);
    let mut floor = TriMesh::new(v, t).expect("a valid test bed");
    floor.merge_angle = merge;
    let (v, t) = cuboid(
        DVec3::new(-0.5, -0.5, 0.0) * PITCH,
        DVec3::new(0.5, 0.5, 3.0) * PITCH,
    );
    let mut post = TriMesh::new(v, t).expect("a valid test bed");
    post.merge_angle = merge;
    let turn = DQuat::from_rotation_z(std::f64::consts::PI / 6.0);
    add_meshes(
        &mut w,
        vec![
            (floor, mid, DQuat::IDENTITY, WallMotion::default()),
            (post, mid, turn, WallMotion::default()),
        ],
    );
    w
}

/// A mesh drum (a closed 36-facet cylinder, radius 3 pitches, 5 pitches
/// long, along z, its bottom cap the floor) turning at 20 rad/s about its
/// axis in a 6 × 6 pitch box, and a mesh bar (a 3 × 0.5 × 0.5 pitch
/// cuboid along x) coming down from 3 pitches at 0.15 m/s while it
/// turns at 10 rad/s about its own y axis; three layers of clumps within
/// 2 pitches of the drum's axis, thrown down at 0.3 m/s. Walls 0 (drum),
/// 1 (bar).
pub fn mesh_drum_bed() -> World {
    use clump_core::wall::mesh::primitives::{cuboid, cylinder};
    let c = DVec3::new(3.0 * PITCH, 3.0 * PITCH, 0.0);
    let mut w = bed_in(
        6,
        3,
        RotationScheme::NoSquish,
        PairProperties::default(),
        vec![],
        |_, b| {
            b.velocity.z -= 0.3;
            (b.position - c).truncate().length() < 2.0 * PITCH
        },
    );
    let (v, t) = cylinder(3.0 * PITCH, 5.0 * PITCH, 36, 0.0);
    let drum = TriMesh::new(v, t).expect("a valid test bed");
    let (v, t) = cuboid(
        DVec3::new(-1.5, -0.25, -0.25) * PITCH,
        DVec3::new(1.5, 0.25, 0.25) * PITCH,
    );
    let bar = TriMesh::new(v, t).expect("a valid test bed");
    let bar_at = c + DVec3::new(0.0, 0.0, 3.0 * PITCH);
    add_meshes(
        &mut w,
        vec![
            (
                drum,
                c + DVec3::new(0.0, 0.0, 2.5 * PITCH),
                DQuat::IDENTITY,
                WallMotion {
                    angular_velocity: DVec3::new(0.0, 0.0, 20.0),
                    center: c,
                    ..Default::default()
                },
            ),
            (
                bar,
                bar_at,
                DQuat::IDENTITY,
                WallMotion {
                    velocity: DVec3::new(0.0, 0.0, -0.15),
                    angular_velocity: DVec3::new(0.0, 10.0, 0.0),
                    center: bar_at,
                    ..Default::default()
                },
            ),
        ],
    );
    w
}

/// The bed of [`periodic_bed`] (periodic in x and y, 4 × 4 pitches, three
/// layers) with walls inside the periodic box: the floor, a pin (a
/// cylinder seen from outside, along x through both periodic x faces,
/// radius 0.25 pitch, turning at 30 rad/s about its axis) coming down at
/// 0.1 m/s from 3.6 pitches into the bed, and a post (a box seen from
/// outside, 0.4 × 0.4 × 1.2 pitches, its surface moving at 0.05 m/s along
/// y) in the middle, less the clumps of the two lower layers around it.
/// Walls 0 (floor), 1 (pin), 2 (post).
pub fn periodic_walls_bed() -> World {
    let mid = DVec3::new(2.0 * PITCH, 2.0 * PITCH, 0.0);
    let pin = DVec3::new(0.0, 2.0 * PITCH, 3.6 * PITCH);
    let floor = WallShape::Plane {
        point: DVec3::ZERO,
        normal: DVec3::Z,
    };
    let walls = vec![
        (floor, WallMotion::default()),
        turning_pin(pin),
        conveyor_post(mid),
    ];
    let law = PairProperties::default();
    let periodic = [true, true, false];
    bed_periodic(
        4,
        3,
        RotationScheme::NoSquish,
        law,
        walls,
        periodic,
        |_, b| {
            let d = (b.position - mid).truncate().abs();
            !(d.max_element() < PITCH && b.position.z < 2.0 * PITCH)
        },
    )
}

/// A pin through `pin` (a cylinder seen from outside, along x, radius
/// 0.25 pitch) turning at 30 rad/s about its axis and coming down at
/// 0.1 m/s.
fn turning_pin(pin: DVec3) -> (WallShape, WallMotion) {
    (
        WallShape::Cylinder {
            point: pin,
            axis: DVec3::X,
            radius: 0.25 * PITCH,
            inside: false,
        },
        WallMotion {
            velocity: DVec3::new(0.0, 0.0, -0.1),
            angular_velocity: DVec3::new(30.0, 0.0, 0.0),
            center: pin,
            ..Default::default()
        },
    )
}

/// A post standing on the floor at `mid` (a box seen from outside, 0.4 ×
/// 0.4 × 1.2 pitches) whose surface moves at 0.05 m/s along y like a
/// conveyor.
fn conveyor_post(mid: DVec3) -> (WallShape, WallMotion) {
    (
        WallShape::Box {
            lo: mid - DVec3::new(0.2 * PITCH, 0.2 * PITCH, 0.0),
            hi: mid + DVec3::new(0.2 * PITCH, 0.2 * PITCH, 1.2 * PITCH),
            inside: false,
        },
        WallMotion {
            surface_velocity: DVec3::new(0.0, 0.05, 0.0),
            ..Default::default()
        },
    )
}
