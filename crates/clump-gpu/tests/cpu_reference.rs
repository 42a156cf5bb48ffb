//! The device step against the CPU path, its reference: a small bed of
//! tetra clumps and 3-sphere rods falling into a closed box of five plane
//! walls, with jostling initial velocities so that clump-clump and wall
//! contacts form, slide and end within the run. The CPU path's equations
//! are the device's (same laws, same order of operations); the two differ
//! by the summation order of each body's contact loads, so the positions
//! agree to round-off amplified by the contacts: the criterion is
//! 1e-9 of the domain size after a few thousand steps.

mod common;

use clump_core::rotation::RotationScheme;
use clump_core::world::World;
use clump_gpu::bed::{box_bed, periodic_bed};
use clump_gpu::periodic::nearest_image;
use clump_gpu::{DeviceWorld, Gpu};
use common::{compare_at, cpu_apart, max_dev, with_multi};
use glam::DVec3;

/// The bed under `rotation`, `at` steps on both paths; the largest
/// position difference over the checkpoints, relative to the box.
fn compare(rotation: RotationScheme) -> f64 {
    compare_world(box_bed(4, 3, rotation))
}

/// [`compare`] on the bed `cpu`.
fn compare_world(cpu: World) -> f64 {
    compare_keep(cpu).0
}

/// [`compare_world`], also returning the device and the CPU world at the
/// end (step 3000).
fn compare_keep(cpu: World) -> (f64, DeviceWorld, World) {
    compare_at(cpu, &[1, 10, 100, 1000, 2000, 3000], |_| {})
}

/// The criterion: 1e-9 of the domain size after 3000 steps.
fn agrees(rotation: RotationScheme) {
    let worst = compare(rotation);
    assert!(
        worst < 1e-9,
        "{rotation:?}: device and CPU positions differ by {worst:e} of the domain size"
    );
}

#[test]
fn device_step_agrees_with_the_cpu_path_no_squish() {
    agrees(RotationScheme::NoSquish);
}

#[test]
fn device_step_agrees_with_the_cpu_path_richardson_liggghts() {
    agrees(RotationScheme::RichardsonLiggghts);
}

#[test]
fn device_step_agrees_with_the_cpu_path_richardson() {
    agrees(RotationScheme::Richardson);
}

/// Force and torque flags (T-15, dof.rs): every third clump moves only in
/// z and turns only about z, every third but one keeps its x velocity
/// and its L_y; the locked components keep their bits on both paths.
#[test]
fn device_step_agrees_with_the_cpu_path_with_dof_flags() {
    let bed = || {
        clump_gpu::bed::box_bed_dof(4, 3, RotationScheme::NoSquish, |k| match k % 3 {
            0 => ([false, false, true], [false, false, true]),
            1 => ([false, true, true], [true, false, true]),
            _ => ([true; 3], [true; 3]),
        })
    };
    let w = bed();
    let v0: std::collections::HashMap<u64, f64> = (0..w.bodies().len())
        .map(|i| (w.bodies().id[i], w.bodies().velocity[i].x))
        .collect();
    let worst = compare_world(bed());
    assert!(worst < 1e-9, "with DOF flags: {worst:e} of the domain size");
    // the locked components are those of the start, on the device too
    let mut d = DeviceWorld::upload(Gpu::new().unwrap(), &w).unwrap();
    d.run(300).unwrap();
    let mut after = w;
    d.download(&mut after).unwrap();
    let b = after.bodies();
    let locked = (0..b.len()).filter(|&i| !b.force_flag[i][0]).count();
    assert!(locked > 10, "{locked} bodies with v_x locked");
    for i in (0..b.len()).filter(|&i| !b.force_flag[i][0]) {
        let id = b.id[i];
        assert_eq!(
            b.velocity[i].x.to_bits(),
            v0[&id].to_bits(),
            "body {id}: v_x moved"
        );
    }
}

/// Periodic boxes (T-22, minimum image): the jostling bed periodic in x and y, its
/// clumps crossing the periodic faces and touching across them (both
/// counted on the CPU path and asserted), and the shared tetra lattice bed
/// (`clump_core::testbed`), falling onto its floor.
#[test]
fn device_step_agrees_with_the_cpu_path_in_a_periodic_box() {
    let (crossings, across) = periodic_traffic(periodic_bed(4, 2, RotationScheme::NoSquish));
    eprintln!("periodic bed on the CPU path: {crossings} face crossings, {across} contacts across a face at the checkpoints");
    assert!(
        crossings > 0 && across > 0,
        "the bed must use its periodic faces"
    );
    let worst = compare_world(periodic_bed(4, 2, RotationScheme::NoSquish));
    assert!(worst < 1e-9, "periodic bed: {worst:e} of the domain size");
    let worst = compare_world(clump_core::testbed::tetra_lattice_bed(4, 4, 2, None));
    assert!(
        worst < 1e-9,
        "tetra lattice bed: {worst:e} of the domain size"
    );
}

/// Both device features of the periodic bed and of EPSD rolling
/// resistance at once: the periodic bed with EPSD (mu_r 0.3) on every
/// contact agrees with the CPU path to the criterion, its
/// periodic faces are used, and rolling springs are live at the end.
#[test]
fn device_step_agrees_with_the_cpu_path_in_a_periodic_box_with_epsd_rolling() {
    let bed = || {
        let law = clump_core::contact::PairProperties {
            rolling: clump_core::contact::RollingLaw::Epsd,
            rolling_friction: 0.3,
            ..Default::default()
        };
        clump_gpu::bed::periodic_bed_law(4, 2, RotationScheme::NoSquish, law)
    };
    let (crossings, across) = periodic_traffic(bed());
    eprintln!("periodic EPSD bed on the CPU path: {crossings} face crossings, {across} contacts across a face at the checkpoints");
    assert!(
        crossings > 0 && across > 0,
        "the bed must use its periodic faces"
    );
    let (worst, dev, _) = compare_keep(bed());
    assert!(
        worst < 1e-9,
        "periodic EPSD bed: {worst:e} of the domain size"
    );
    let mut w = bed();
    dev.download_state(&mut w).unwrap();
    let (rolling, _) = live_rolling_springs(&mut w);
    eprintln!("device: {rolling} live pair rolling springs at the end");
    assert!(rolling > 0, "no live pair rolling spring at the end");
}

/// A periodic axis shorter than three cells (here one lattice pitch) is
/// refused at upload, naming the axis, as the CPU path's grid refuses it.
#[test]
fn a_periodic_axis_of_fewer_than_three_cells_is_refused() {
    let w = clump_core::testbed::tetra_lattice_bed(1, 1, 1, None);
    match DeviceWorld::upload(Gpu::new().unwrap(), &w) {
        Err(e) => assert!(
            e.to_string().contains(
                "the periodic axis x of the box is 0.0036 m long, shorter than three cells"
            ),
            "{e}"
        ),
        Ok(_) => panic!("a periodic axis of one cell was accepted"),
    }
}

/// On the CPU path over the checkpoints of [`compare_world`]: how often a
/// body crossed a periodic face (its centre moved by more than half the
/// box between checkpoints along a periodic axis, where it moves a few mm
/// at most), and the touching sphere pairs whose nearest image lies
/// across a face, summed over the checkpoints.
fn periodic_traffic(mut w: World) -> (usize, usize) {
    let domain = w.config.domain;
    let half = 0.5 * domain.size();
    let by_id = |w: &World| -> std::collections::BTreeMap<u64, DVec3> {
        let b = w.bodies();
        b.id.iter()
            .copied()
            .zip(b.position.iter().copied())
            .collect()
    };
    w.prepare().unwrap();
    let (mut crossings, mut across) = (0, 0);
    let mut last = by_id(&w);
    let mut done = 0;
    for &at in &[1u64, 10, 100, 1000, 2000, 3000] {
        w.run(at - done).unwrap();
        done = at;
        let now = by_id(&w);
        crossings += now
            .iter()
            .filter(|(id, x)| {
                let d = (**x - last[id]).abs();
                (0..2).any(|a| domain.periodic[a] && d[a] > half[a])
            })
            .count();
        last = now;
        let s = w.spheres();
        for i in 0..s.len() {
            for j in i + 1..s.len() {
                let d = s.position(i) - s.position(j);
                let near = nearest_image(&domain, d);
                let r = s.radius[i] + s.radius[j];
                if s.body[i] != s.body[j] && near != d && near.length() < r {
                    across += 1;
                }
            }
        }
    }
    (crossings, across)
}

/// Whether two device runs of `w`, 500 steps each, end with the same bits.
fn bit_reproducible(w: &World) -> bool {
    let run = || {
        let mut d = DeviceWorld::upload(Gpu::new().unwrap(), w).unwrap();
        d.run(500).unwrap();
        d.positions().unwrap()
    };
    let (a, b) = (run(), run());
    a.iter()
        .zip(&b)
        .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits))
}

#[test]
fn device_runs_are_bit_reproducible() {
    let w = box_bed(4, 3, RotationScheme::NoSquish);
    assert!(
        bit_reproducible(&w),
        "two device runs of the same world differ"
    );
}

/// Fixed and driven bodies (dof.rs): every sixth clump is fixed (at rest,
/// never moves), every sixth from the third is driven at a constant
/// velocity and world angular velocity through the bed. Both paths agree
/// to the criterion; on the device a fixed body keeps its bits
/// and a driven one follows the closed form x0 + v t, q = exp(w t) q0; the
/// contacts on them are summed (a torque that gravity cannot give).
#[test]
fn device_step_agrees_with_the_cpu_path_with_fixed_and_driven_bodies() {
    use clump_core::dof::Dof;
    let bed = || {
        clump_gpu::bed::box_bed_with(4, 3, RotationScheme::NoSquish, |k, b| {
            let driven = Dof {
                driven: true,
                ..Dof::default()
            };
            match k % 6 {
                0 => {
                    b.velocity = DVec3::ZERO;
                    b.angular_velocity = DVec3::ZERO;
                    driven.apply(b);
                }
                3 => {
                    b.velocity = DVec3::new(0.03, -0.02, 0.01);
                    driven.apply(b);
                }
                _ => {}
            }
        })
    };
    let w = bed();
    let b0 = w.bodies().clone();
    let (worst, dev, _cpu) = compare_keep(bed());
    assert!(
        worst < 1e-9,
        "fixed and driven: {worst:e} of the domain size"
    );
    // the device's own bits (`download` would renormalise orientations)
    let mut after = w;
    dev.download_state(&mut after).unwrap();
    let b = after.bodies();
    let t = 3000.0 * after.config.dt;
    let at0: std::collections::HashMap<u64, usize> =
        b0.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let (mut fixed, mut driven, mut touched) = (0, 0, 0);
    for i in (0..b.len()).filter(|&i| b.start_step[i] == clump_core::dof::DRIVEN) {
        let j = at0[&b.id[i]];
        if b0.velocity[j] == DVec3::ZERO && b0.angular_velocity[j] == DVec3::ZERO {
            fixed += 1;
            let bits =
                |p: DVec3, q: glam::DQuat| [p.x, p.y, p.z, q.x, q.y, q.z, q.w].map(f64::to_bits);
            assert_eq!(
                bits(b.position[i], b.orientation[i]),
                bits(b0.position[j], b0.orientation[j])
            );
        } else {
            driven += 1;
            let x = b0.position[j] + b0.velocity[j] * t;
            // glam's exponential map: outside the code under test
            let q = glam::DQuat::from_scaled_axis(b0.angular_velocity[j] * t) * b0.orientation[j];
            let dx = (b.position[i] - x).abs().max_element();
            let dq = (b.orientation[i] - q)
                .length()
                .min((b.orientation[i] + q).length());
            eprintln!(
                "driven body {}: |x - (x0 + v t)| = {dx:.2e} m, |q - exp(w t) q0| = {dq:.2e}",
                b.id[i]
            );
            assert!(dx < 1e-13, "driven body {}: {dx:e} m off x0 + v t", b.id[i]);
            assert!(
                dq < 1e-11,
                "driven body {}: {dq:e} off exp(w t) q0",
                b.id[i]
            );
        }
        touched += (b.torque[i] != DVec3::ZERO) as usize;
    }
    assert!(
        fixed >= 8 && driven >= 8,
        "{fixed} fixed, {driven} driven bodies"
    );
    assert!(
        touched > 0,
        "no contact on a fixed or driven body at the end"
    );
}

/// The bed with the rolling law `rolling` (coefficient `mu_r`) on every
/// contact, clump-clump and clump-wall.
fn rolling_bed(rolling: clump_core::contact::RollingLaw, mu_r: f64) -> World {
    let law = clump_core::contact::PairProperties {
        rolling,
        rolling_friction: mu_r,
        ..Default::default()
    };
    clump_gpu::bed::box_bed_law(4, 3, RotationScheme::NoSquish, law, |_, _| {})
}

/// Rolling resistance (contact/rolling.rs) on the device against the CPU
/// path, to the criterion; the rolling couple matters in this bed
/// (the CPU run without it ends far away) and, for EPSD, rolling springs
/// are live at the end on both paths (pair and wall).
fn rolling_agrees(rolling: clump_core::contact::RollingLaw) {
    let (worst, dev, cpu) = compare_keep(rolling_bed(rolling, 0.3));
    eprintln!("{rolling:?}: worst {worst:.3e} of the box");
    assert!(worst < 1e-9, "{rolling:?}: {worst:e} of the domain size");
    let mut plain = rolling_bed(clump_core::contact::RollingLaw::None, 0.3);
    plain.prepare().unwrap();
    plain.run(cpu.step).unwrap();
    let size = cpu.config.domain.size().max_element();
    let x = dev.positions().unwrap();
    let apart = max_dev(&dev, &x, &plain) / size;
    eprintln!("{rolling:?}: the run without rolling resistance ends {apart:.3e} of the box away");
    assert!(
        apart > 1e-6,
        "rolling resistance changed the run by only {apart:e}"
    );
    if rolling == clump_core::contact::RollingLaw::Epsd {
        let mut w = rolling_bed(rolling, 0.3);
        dev.download_state(&mut w).unwrap();
        let mut cpu = cpu;
        for (name, world) in [("device", &mut w), ("CPU", &mut cpu)] {
            let (pairs, walls) = live_rolling_springs(world);
            eprintln!("{name}: {pairs} pair and {walls} wall rolling springs at the end");
            assert!(pairs > 0 && walls > 0, "{name}: no live rolling spring");
        }
    }
}

/// The rolling springs of `w`'s state that are not zero: (pair, wall).
fn live_rolling_springs(w: &mut World) -> (usize, usize) {
    let s = w.save_state().unwrap();
    let pairs = s
        .pair_history
        .iter()
        .filter(|e| e.1.rolling != DVec3::ZERO)
        .count();
    let walls = s
        .wall_hist
        .iter()
        .flatten()
        .filter(|h| h.rolling != DVec3::ZERO)
        .count();
    (pairs, walls)
}

#[test]
fn device_step_agrees_with_the_cpu_path_with_cdt_rolling() {
    rolling_agrees(clump_core::contact::RollingLaw::Cdt);
}

#[test]
fn device_step_agrees_with_the_cpu_path_with_epsd_rolling() {
    rolling_agrees(clump_core::contact::RollingLaw::Epsd);
}

/// Which of `w`'s walls the clumps touch within `steps` steps of the CPU
/// path (a wall load at some step).
/// Also the most contacts one sphere had at once with one wall.
fn walls_touched(mut w: World, steps: u64) -> (Vec<bool>, usize) {
    let mut touched = vec![false; w.walls.len()];
    let mut most = 0;
    w.prepare().unwrap();
    for _ in 0..steps {
        w.step().unwrap();
        for (t, l) in touched.iter_mut().zip(w.walls.loads()) {
            *t |= l.force != DVec3::ZERO;
        }
        for keys in w.save_state().unwrap().wall_key {
            for k in keys.iter().filter(|&&k| k != 0) {
                let same = keys
                    .iter()
                    .filter(|&&o| o != 0 && (o - 1) >> 16 == (k - 1) >> 16);
                most = most.max(same.count());
            }
        }
    }
    (touched, most)
}

/// Walls of `bed` against the CPU path: to the criterion, every
/// active wall touched along the way (and no inactive one), and the walls handed back at the end where
/// their prescribed motion puts them (`moved(walls, walls at the start,
/// t)` checks them against the closed form of their motion). Returns the
/// most contacts one sphere had at once with one wall.
fn walls_agree(
    bed: impl Fn() -> World,
    moved: impl Fn(&[clump_core::wall::Wall], &[clump_core::wall::Wall], f64),
) -> usize {
    let (touched, most) = walls_touched(bed(), 3000);
    eprintln!("walls touched in 3000 steps: {touched:?}; at most {most} faces of one wall at once");
    let active: Vec<bool> = bed().walls.iter().map(|w| w.active).collect();
    assert_eq!(
        touched, active,
        "every active wall must see contacts, no inactive one"
    );
    let (worst, dev, cpu) = compare_keep(bed());
    eprintln!("walls: worst {worst:.3e} of the box");
    assert!(worst < 1e-9, "walls: {worst:e} of the domain size");
    let mut after = bed();
    dev.download_state(&mut after).unwrap();
    assert_eq!(after.walls.len(), cpu.walls.len());
    for (a, b) in after.walls.iter().zip(cpu.walls.iter()) {
        assert_eq!(a, b, "the device's walls at the end are not the CPU path's");
    }
    moved(&after.walls, &bed().walls, after.time);
    most
}

/// The round-off bound of a coordinate of size `x` (m) that 3000 steps
/// each moved by one rounded addition: 3000 ε |x|.
fn rounding(x: f64) -> f64 {
    3000.0 * f64::EPSILON * x.abs()
}

/// The point (plane, cylinder) or lower corner (box) of a wall, m.
fn wall_point(w: &clump_core::wall::Wall) -> DVec3 {
    use clump_core::wall::WallShape;
    match w.shape {
        WallShape::Plane { point, .. } | WallShape::Cylinder { point, .. } => point,
        WallShape::Box { lo, .. } => lo,
        WallShape::Mesh { position, .. } => position,
    }
}

/// Every wall at the end where its velocity takes it from the start,
/// x0 + v t, to round-off.
fn at_closed_form(walls: &[clump_core::wall::Wall], start: &[clump_core::wall::Wall], t: f64) {
    for (w, w0) in walls.iter().zip(start) {
        let (x, x0) = (wall_point(w), wall_point(w0));
        let off = (x - (x0 + w0.motion.velocity * t)).abs().max_element();
        eprintln!("wall {}: {off:.2e} m from x0 + v t", w.name);
        assert!(
            off <= rounding(x.abs().max_element()),
            "wall {}: {off:e} m from x0 + v t",
            w.name
        );
    }
}

/// A drum and a pin (cylinders seen from inside and from outside, both
/// turning about their axes, the pin moving down into the bed) on a
/// rising floor (`bed::drum_bed`).
#[test]
fn device_step_agrees_with_the_cpu_path_with_cylinder_and_moving_walls() {
    walls_agree(clump_gpu::bed::drum_bed, |walls, start, t| {
        at_closed_form(walls, start, t);
        let axis = match walls[2].shape {
            clump_core::wall::WallShape::Cylinder { axis, .. } => axis,
            _ => unreachable!(),
        };
        assert!(
            (axis - DVec3::X).length() < 1e-14,
            "the pin's axis turned: {axis}"
        );
    });
}

/// A moving, turning container (a box seen from inside) with a conveyor
/// post (a box seen from outside) in it (`bed::container_bed`); some
/// sphere touches two of the container's faces at once.
#[test]
fn device_step_agrees_with_the_cpu_path_with_box_walls() {
    let most = walls_agree(clump_gpu::bed::container_bed, at_closed_form);
    assert!(
        most >= 2,
        "no sphere touched two faces of the container at once"
    );
}

/// `average` multi-contact (T-34, multi_contact.rs) on the device against
/// the CPU path, to the criterion: between clumps and with the
/// five planes of the box bed, and with the container bed's box walls
/// (a body's touches with the faces of one box counted together). Each
/// switch changes the CPU run (so bodies did touch a body or a wall at
/// several spheres at once, and the counts matter).
#[test]
fn device_step_agrees_with_the_cpu_path_with_average_contacts() {
    use clump_core::multi_contact::MultiContact::{Average, Sum};
    let bed = |p, w| with_multi(box_bed(4, 3, RotationScheme::NoSquish), p, w);
    let size = box_bed(4, 3, RotationScheme::NoSquish)
        .config
        .domain
        .size()
        .max_element();
    let pairs_matter = cpu_apart(bed(Average, Average), bed(Sum, Average), 3000) / size;
    let walls_matter = cpu_apart(bed(Average, Average), bed(Average, Sum), 3000) / size;
    eprintln!(
        "average against sum on the CPU path after 3000 steps: pairs {pairs_matter:.3e}, walls {walls_matter:.3e} of the box"
    );
    assert!(
        pairs_matter > 1e-6 && walls_matter > 1e-6,
        "average changed the CPU run by only {pairs_matter:e} (pairs), {walls_matter:e} (walls)"
    );
    let worst = compare_world(bed(Average, Average));
    eprintln!("average, box bed: worst {worst:.3e} of the box");
    assert!(
        worst < 1e-9,
        "average, box bed: {worst:e} of the domain size"
    );
    let container = || with_multi(clump_gpu::bed::container_bed(), Average, Average);
    let box_matter = cpu_apart(
        container(),
        with_multi(clump_gpu::bed::container_bed(), Average, Sum),
        3000,
    ) / size;
    eprintln!("average box walls against sum on the CPU path: {box_matter:.3e} of the box");
    assert!(
        box_matter > 1e-6,
        "average box walls changed the run by only {box_matter:e}"
    );
    let worst = compare_world(container());
    eprintln!("average, container bed: worst {worst:.3e} of the box");
    assert!(
        worst < 1e-9,
        "average, container bed: {worst:e} of the domain size"
    );
}

/// Two device runs of an `average` bed give the same bits (integer counts,
/// no atomics).
#[test]
fn average_device_runs_are_bit_reproducible() {
    use clump_core::multi_contact::MultiContact::Average;
    let w = with_multi(box_bed(4, 3, RotationScheme::NoSquish), Average, Average);
    assert!(
        bit_reproducible(&w),
        "two average device runs of the same world differ"
    );
}

/// Cylinder and box walls inside a box periodic in x and y
/// (`bed::periodic_walls_bed`: a turning pin through both periodic x
/// faces coming down into the bed, a conveyor post), against the CPU path
/// as `walls_agree` does.
#[test]
fn device_step_agrees_with_the_cpu_path_with_walls_in_a_periodic_box() {
    walls_agree(clump_gpu::bed::periodic_walls_bed, at_closed_form);
}

/// Bodies leaving a box periodic in x and y through its open floor (no
/// wall: the jostling periodic bed falls out through z_lo): the device
/// removes the same bodies as the CPU path, with the same counts per side,
/// and the bodies left agree to the criterion. Both remove a body
/// at a list build, which with the same skin (fixed here: the CPU path
/// adapts its own otherwise) comes at the same steps.
#[test]
fn bodies_leave_a_periodic_box_as_on_the_cpu_path() {
    let bed = || {
        let law = clump_core::contact::PairProperties::default();
        let mut w = clump_gpu::bed::bed_periodic(
            4,
            2,
            RotationScheme::NoSquish,
            law,
            vec![],
            [true, true, false],
            |_, _| true,
        );
        w.config.skin = Some(0.2e-3);
        w
    };
    let mut cpu = bed();
    let all: Vec<u64> = cpu.bodies().id.clone();
    let size = cpu.config.domain.size().max_element();
    let mut dev = DeviceWorld::upload(Gpu::new().unwrap(), &cpu).unwrap();
    cpu.prepare().unwrap();
    let mut seen = 0;
    for &at in &[1000u64, 2000, 3000] {
        cpu.run(at - cpu.step).unwrap();
        dev.run(at - dev.step).unwrap();
        let cpu_ids: Vec<u64> = all
            .iter()
            .copied()
            .filter(|id| !cpu.bodies().id.contains(id))
            .collect();
        let sides = cpu.lost.through_side;
        let mut after = bed();
        dev.download(&mut after).unwrap_or_else(|e| panic!("{e}"));
        let dev_ids: Vec<u64> = all
            .iter()
            .copied()
            .filter(|id| !after.bodies().id.contains(id))
            .collect();
        eprintln!(
            "step {at}: lost per side on the CPU path {sides:?}, on the device {:?}; {} bodies left",
            after.lost.through_side,
            after.bodies().len()
        );
        assert_eq!(dev_ids, cpu_ids, "step {at}: the device lost other bodies");
        assert_eq!(
            after.lost.through_side, sides,
            "step {at}: other counts per side"
        );
        // the bodies left, matched by id
        let b = cpu.bodies();
        let at_id: std::collections::HashMap<u64, usize> =
            b.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
        let a = after.bodies();
        let worst = (0..a.len())
            .map(|k| {
                let d = a.position[k] - b.position[at_id[&a.id[k]]];
                nearest_image(&cpu.config.domain, d).abs().max_element() / size
            })
            .fold(0.0, f64::max);
        eprintln!("step {at}: bodies left within {worst:.3e} of the box");
        assert!(worst < 1e-9, "step {at}: {worst:e} of the domain size");
        seen = dev_ids.len();
    }
    assert!(
        seen > 0 && seen < all.len(),
        "{seen} of {} bodies lost: the test needs some",
        all.len()
    );
}
