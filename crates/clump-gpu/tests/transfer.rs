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
    hand_over_keeps_bits(bed, HALF, true);
}

/// The same in a periodic box: bodies that wrapped on the device
/// make the trip as they are.
#[test]
fn a_hand_over_in_a_periodic_box_keeps_the_device_bits() {
    hand_over_keeps_bits(periodic, PERIODIC_HALF, false);
}

/// The hand-over step of the periodic bed: its clumps touch by then
/// (its floor only later, at about step 2000).
const PERIODIC_HALF: u64 = 1000;

fn periodic() -> World {
    clump_gpu::bed::periodic_bed(4, 2, RotationScheme::NoSquish)
}

/// `bed` handed over at step `half` of `2 half`, with pair springs (and
/// wall springs with `need_walls`) at the hand-over.
fn hand_over_keeps_bits(bed: fn() -> World, half: u64, need_walls: bool) {
    let mut stay = bed();
    let mut dev = DeviceStepper::new(Gpu::new().unwrap());
    on_device(&mut stay, &mut dev, 2 * half);

    let mut moved = bed();
    let mut dev = DeviceStepper::new(Gpu::new().unwrap());
    on_device(&mut moved, &mut dev, half);
    let (pairs, walls) = springs(&mut moved);
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
    across_devices(bed, HALF, true);
}

#[test]
fn device_to_cpu_and_cpu_to_device_agree_in_a_periodic_box() {
    across_devices(periodic, PERIODIC_HALF, false);
}

fn across_devices(bed: fn() -> World, half: u64, need_walls: bool) {
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
