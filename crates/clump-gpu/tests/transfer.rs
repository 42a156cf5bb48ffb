//! The copies at events, springs included, on the bed of `cpu_reference`
//! (tetra clumps and 3-sphere rods jostling in a box of five planes):
//! - a device run handed to the host and back at step 200 ends with the
//!   bits of a device run that stayed on the device (the hand-over loses
//!   nothing: bodies, forces, pair and wall springs all make the trip);
//! - device → CPU and CPU → device at step 200 end within round-off of a
//!   run that stayed on the CPU: 1e-12 of the box after 400 steps, the
//!   device's own agreement with the CPU path over that many steps
//!   (cpu_reference: about 1e-14 at step 1000; the two differ by the order
//!   of each body's force sums, amplified by the contacts).
//!
//! The hand-over step has pair and wall springs (asserted), so a lost
//! spring would show: dropping them moves the bodies by far more (the
//! last test measures how much).

use clump_core::rotation::RotationScheme;
use clump_core::world::World;
use clump_gpu::bed::box_bed;
use clump_gpu::periodic::nearest_image;
use clump_gpu::{DeviceStepper, DeviceWorld, Gpu};

const HALF: u64 = 200;

fn bed() -> World {
    box_bed(4, 3, RotationScheme::NoSquish)
}

/// Largest position coordinate difference between two worlds' bodies,
/// matched by id, relative to the box size.
fn max_rel(a: &World, b: &World) -> f64 {
    let (ba, bb) = (a.bodies(), b.bodies());
    assert_eq!(ba.len(), bb.len());
    let at: std::collections::HashMap<u64, usize> =
        bb.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let domain = a.config.domain;
    let size = domain.size().max_element();
    let mut worst = 0.0f64;
    for i in 0..ba.len() {
        // the nearest image in a periodic box (the paths wrap at different steps)
        let d = nearest_image(&domain, ba.position[i] - bb.position[at[&ba.id[i]]]);
        worst = worst.max(d.abs().max_element() / size);
    }
    worst
}

fn bits(w: &World) -> Vec<(u64, [u64; 13])> {
    let b = w.bodies();
    let mut out: Vec<_> = (0..b.len())
        .map(|i| {
            let (x, v, l, q) = (
                b.position[i],
                b.velocity[i],
                b.angular_momentum[i],
                b.orientation[i],
            );
            (
                b.id[i],
                [
                    x.x, x.y, x.z, v.x, v.y, v.z, l.x, l.y, l.z, q.x, q.y, q.z, q.w,
                ]
                .map(f64::to_bits),
            )
        })
        .collect();
    out.sort_by_key(|e| e.0);
    out
}

fn on_device(world: &mut World, stepper: &mut DeviceStepper, to: u64) {
    let done = stepper
        .advance(world, to, &mut || false)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(world.step, to);
    assert!(done > 0);
}

/// Springs of the world's state: (pair springs not zero, wall slots in use).
fn springs(w: &mut World) -> (usize, usize) {
    let s = w.save_state().unwrap();
    let walls = s
        .wall_key
        .iter()
        .map(|k| k.iter().filter(|&&k| k != 0).count())
        .sum();
    (s.pair_history.len(), walls)
}

#[test]
fn a_hand_over_at_an_event_keeps_the_device_bits() {
    hand_over_keeps_the_device_bits(bed, springs, HALF, true);
}

/// The same in a periodic box: bodies that wrapped on the device
/// make the trip as they are.
#[test]
fn a_hand_over_in_a_periodic_box_keeps_the_device_bits() {
    hand_over_keeps_the_device_bits(periodic, springs, PERIODIC_HALF, false);
}

/// The hand-over step of the periodic bed: its clumps touch by then
/// (its floor only later, at about step 2000).
const PERIODIC_HALF: u64 = 1000;

fn periodic() -> World {
    clump_gpu::bed::periodic_bed(4, 2, RotationScheme::NoSquish)
}

/// A device run of `bed` handed to the host and back at step `half` of
/// `2 half` ends with the bits of one that stayed on the device; the
/// hand-over carries springs (`carried`: pair and wall springs counted at
/// the hand-over; wall springs required with `need_walls`).
fn hand_over_keeps_the_device_bits(
    bed: fn() -> World,
    carried: fn(&mut World) -> (usize, usize),
    half: u64,
    need_walls: bool,
) {
    let mut stay = bed();
    let mut dev = DeviceStepper::new(Gpu::new().unwrap());
    on_device(&mut stay, &mut dev, 2 * half);

    let mut moved = bed();
    let mut dev = DeviceStepper::new(Gpu::new().unwrap());
    on_device(&mut moved, &mut dev, half);
    let (pairs, walls) = carried(&mut moved);
    eprintln!("at step {half}: {pairs} pair springs, {walls} wall springs");
    assert!(
        pairs > 0 && (walls > 0 || !need_walls),
        "the hand-over must carry springs"
    );
    on_device(&mut moved, &mut dev, 2 * half);
    assert!(
        bits(&stay) == bits(&moved),
        "a download and upload at step {half} changed the device's bits (largest difference {:e} of the box)",
        max_rel(&stay, &moved)
    );
}

#[test]
fn device_to_cpu_and_cpu_to_device_agree_with_the_cpu_path() {
    both_ways_agree(bed, HALF, true);
}

#[test]
fn device_to_cpu_and_cpu_to_device_agree_in_a_periodic_box() {
    both_ways_agree(periodic, PERIODIC_HALF, false);
}

/// Device → CPU and CPU → device at step `half` of `bed` end within 1e-12
/// of the box of a run that stayed on the CPU path after `2 half` steps;
/// the hand-over carries pair springs (and wall springs with `need_walls`).
fn both_ways_agree(bed: fn() -> World, half: u64, need_walls: bool) {
    let mut cpu = bed();
    cpu.prepare().unwrap();
    cpu.run(2 * half).unwrap();

    // device, then the CPU path (a GPU checkpoint resumed on the CPU)
    let mut a = bed();
    on_device(&mut a, &mut DeviceStepper::new(Gpu::new().unwrap()), half);
    a.run(half).unwrap();
    // the CPU path, then the device (a CPU checkpoint resumed on the GPU)
    let mut b = bed();
    b.prepare().unwrap();
    b.run(half).unwrap();
    let (pairs, walls) = springs(&mut b);
    assert!(
        pairs > 0 && (walls > 0 || !need_walls),
        "the hand-over must carry springs"
    );
    on_device(
        &mut b,
        &mut DeviceStepper::new(Gpu::new().unwrap()),
        2 * half,
    );

    let (da, db) = (max_rel(&a, &cpu), max_rel(&b, &cpu));
    eprintln!(
        "after {} steps: gpu→cpu {da:.3e}, cpu→gpu {db:.3e} of the box",
        2 * half
    );
    assert!(da < 1e-12 && db < 1e-12, "gpu→cpu {da:e}, cpu→gpu {db:e}");
}

/// What the springs are worth here: the same hand-over with the springs
/// dropped (the upload of `DeviceWorld::upload`, which starts them at
/// zero) ends far from the CPU path, so the tolerance above would catch
/// a lost spring.
#[test]
fn dropping_the_springs_at_the_hand_over_shows() {
    let mut cpu = bed();
    cpu.prepare().unwrap();
    cpu.run(2 * HALF).unwrap();
    let mut b = bed();
    b.prepare().unwrap();
    b.run(HALF).unwrap();
    let mut dev = DeviceWorld::upload(Gpu::new().unwrap(), &b).unwrap();
    dev.run(HALF).unwrap();
    dev.download(&mut b).unwrap();
    let d = max_rel(&b, &cpu);
    eprintln!(
        "springs dropped at step {HALF}: {d:.3e} of the box after {} steps",
        2 * HALF
    );
    assert!(
        d > 1e-9,
        "dropping the springs changed the run by only {d:e}"
    );
}

/// The bed with EPSD rolling resistance (the rolling springs make the
/// trip too).
fn epsd_bed() -> World {
    let law = clump_core::contact::PairProperties {
        rolling: clump_core::contact::RollingLaw::Epsd,
        rolling_friction: 0.3,
        ..Default::default()
    };
    clump_gpu::bed::box_bed_law(4, 3, RotationScheme::NoSquish, law, |_, _| {})
}

/// Rolling springs of the world's state: (pair, wall) springs not zero.
fn rolling_springs(w: &mut World) -> (usize, usize) {
    let s = w.save_state().unwrap();
    let live = |h: &clump_core::contact::ContactHistory| h.rolling != glam::DVec3::ZERO;
    (
        s.pair_history.iter().filter(|e| live(&e.1)).count(),
        s.wall_hist.iter().flatten().filter(|h| live(h)).count(),
    )
}

/// EPSD's rolling springs through the hand-over: device → host → device
/// keeps the device's bits; device → CPU and CPU → device end within
/// 1e-12 of the box of the CPU run, and with the rolling springs zeroed at
/// the hand-over far from it (so a lost rolling spring would show).
#[test]
fn epsd_rolling_springs_make_the_trip() {
    hand_over_keeps_the_device_bits(epsd_bed, rolling_springs, HALF, true);

    let mut cpu = epsd_bed();
    cpu.prepare().unwrap();
    cpu.run(2 * HALF).unwrap();
    let at_half = || {
        let mut b = epsd_bed();
        b.prepare().unwrap();
        b.run(HALF).unwrap();
        b
    };
    let mut b = at_half();
    on_device(
        &mut b,
        &mut DeviceStepper::new(Gpu::new().unwrap()),
        2 * HALF,
    );
    let mut lost = at_half();
    let mut s = lost.save_state().unwrap();
    s.pair_history
        .iter_mut()
        .for_each(|e| e.1.rolling = glam::DVec3::ZERO);
    s.wall_hist
        .iter_mut()
        .flatten()
        .for_each(|h| h.rolling = glam::DVec3::ZERO);
    lost.restore_state(s).unwrap();
    on_device(
        &mut lost,
        &mut DeviceStepper::new(Gpu::new().unwrap()),
        2 * HALF,
    );
    let mut a = epsd_bed();
    on_device(&mut a, &mut DeviceStepper::new(Gpu::new().unwrap()), HALF);
    a.run(HALF).unwrap();
    let (da, d, d_lost) = (max_rel(&a, &cpu), max_rel(&b, &cpu), max_rel(&lost, &cpu));
    eprintln!(
        "EPSD after {} steps: gpu→cpu {da:.3e}, cpu→gpu {d:.3e} of the box; rolling springs dropped: {d_lost:.3e}",
        2 * HALF
    );
    assert!(
        da < 1e-12 && d < 1e-12,
        "EPSD gpu→cpu {da:e}, cpu→gpu {d:e} of the box"
    );
    assert!(
        d_lost > 1e-9,
        "dropping the rolling springs changed the run by only {d_lost:e}"
    );
}

/// Moving walls and a box's faces through the hand-over (`bed::container_bed`:
/// a moving, turning container, six face slots per sphere, and a conveyor
/// post): the device's bits kept, both directions within round-off of the
/// CPU path, the walls handed back where the CPU path has them.
#[test]
fn moving_box_walls_make_the_trip() {
    hand_over_keeps_the_device_bits(clump_gpu::bed::container_bed, springs, HALF, true);
    both_ways_agree(clump_gpu::bed::container_bed, HALF, true);
    let mut cpu = clump_gpu::bed::container_bed();
    cpu.prepare().unwrap();
    cpu.run(HALF).unwrap();
    let mut dev = clump_gpu::bed::container_bed();
    on_device(&mut dev, &mut DeviceStepper::new(Gpu::new().unwrap()), HALF);
    assert!(
        dev.walls.iter().zip(cpu.walls.iter()).all(|(a, b)| a == b),
        "the walls handed back are not the CPU path's"
    );
}

/// The hand-over step of the mesh drum bed: its clumps touch the drum's
/// floor cap by then.
const MESH_HALF: u64 = 500;

/// Mesh wall slots of the world's state: (slots in use, those with a
/// spring), which must both be non-zero at the hand-over.
fn mesh_springs(w: &mut World) -> (usize, usize) {
    let s = w.save_state().unwrap();
    let keys = s.wall_key.iter().flatten().filter(|&&k| k != 0).count();
    let live = s
        .wall_hist
        .iter()
        .flatten()
        .filter(|h| h.tangential != glam::DVec3::ZERO)
        .count();
    (keys, live)
}

/// Mesh walls through the hand-over (`bed::mesh_drum_bed`: a turning mesh
/// drum and a moving mesh bar, every wall a mesh): the device's bits kept
/// with mesh contacts live, both directions within 1e-12 of the CPU path,
/// the walls' poses handed back as the CPU path has them. A mesh slot's
/// key holds its contact's normal, by which the next step finds it: with
/// the keys' normals replaced at the hand-over (code 0, straight down),
/// the springs are lost to the next step and the run ends far from the
/// CPU path's.
#[test]
fn mesh_walls_make_the_trip() {
    let bed = clump_gpu::bed::mesh_drum_bed;
    hand_over_keeps_the_device_bits(bed, mesh_springs, MESH_HALF, true);
    both_ways_agree(bed, MESH_HALF, true);
    let mut cpu = bed();
    cpu.prepare().unwrap();
    cpu.run(MESH_HALF).unwrap();
    let mut dev = bed();
    let mut stepper = DeviceStepper::new(Gpu::new().unwrap());
    on_device(&mut dev, &mut stepper, MESH_HALF);
    assert!(
        dev.walls.iter().zip(cpu.walls.iter()).all(|(a, b)| a == b),
        "the mesh walls handed back are not the CPU path's"
    );
    cpu.run(MESH_HALF).unwrap();
    let mut s = dev.save_state().unwrap();
    s.wall_key
        .iter_mut()
        .flatten()
        .filter(|k| **k != 0)
        .for_each(|k| *k = ((*k - 1) & 0xFFFF_0000) + 1);
    dev.restore_state(s).unwrap();
    on_device(&mut dev, &mut stepper, 2 * MESH_HALF);
    let d = max_rel(&dev, &cpu);
    eprintln!(
        "mesh slot normals lost at step {MESH_HALF}: {d:.3e} of the box after {} steps",
        2 * MESH_HALF
    );
    assert!(
        d > 1e-9,
        "losing the mesh slots' normals changed the run by only {d:e}"
    );
}
