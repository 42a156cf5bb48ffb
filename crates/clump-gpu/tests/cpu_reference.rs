//! The device step against the CPU path, its reference: a small bed of
//! tetra clumps and 3-sphere rods falling into a closed box of five plane
//! walls, with jostling initial velocities so that clump-clump and wall
//! contacts form, slide and end within the run. The CPU path's equations
//! are the device's (same laws, same order of operations); the two differ
//! by the summation order of each body's contact loads, so the positions
//! agree to round-off amplified by the contacts: the criterion is
//! 1e-9 of the domain size after a few thousand steps.

use clump_core::rotation::RotationScheme;
use clump_core::world::World;
use clump_gpu::bed::box_bed;
use clump_gpu::{DeviceWorld, Gpu};
use glam::DVec3;

/// Largest coordinate difference, m, between the device's bodies and the
/// CPU world's, matched by id (the CPU path reorders its bodies).
fn max_dev(dev: &DeviceWorld, x: &[DVec3], cpu: &World) -> f64 {
    let b = cpu.bodies();
    let at: std::collections::HashMap<u64, usize> =
        b.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    dev.ids
        .iter()
        .zip(x)
        .map(|(id, p)| (*p - b.position[at[id]]).abs().max_element())
        .fold(0.0, f64::max)
}

/// The bed under `rotation`, `at` steps on both paths; the largest
/// position difference over the checkpoints, relative to the box.
fn compare(rotation: RotationScheme) -> f64 {
    let mut cpu = box_bed(4, 3, rotation);
    let size = cpu.config.domain.size().max_element();
    let mut dev = DeviceWorld::upload(Gpu::new().unwrap(), &cpu).unwrap_or_else(|e| panic!("{e}"));
    eprintln!(
        "{rotation:?}: adapter {}, {} spheres",
        dev.gpu.describe(),
        dev.spheres()
    );
    cpu.prepare().unwrap();
    let mut done = 0;
    let mut worst = 0.0f64;
    for &at in &[1u64, 10, 100, 1000, 2000, 3000] {
        let t0 = std::time::Instant::now();
        dev.run(at - done).unwrap_or_else(|e| panic!("{e}"));
        let gpu_x = dev.positions().unwrap();
        let secs = t0.elapsed().as_secs_f64();
        cpu.run(at - done).unwrap();
        let dev_rel = max_dev(&dev, &gpu_x, &cpu) / size;
        eprintln!(
            "step {at}: max |x_gpu - x_cpu| / L = {dev_rel:.3e}; contacts on the CPU {}; device table builds {}, {:.0} sphere-steps/s",
            format!("{} pair, {} wall", cpu.stats.pair_contacts, cpu.stats.wall_contacts),
            dev.builds,
            (dev.spheres() as f64 * (at - done) as f64) / secs
        );
        worst = worst.max(dev_rel);
        done = at;
    }
    assert!(
        cpu.stats.pair_contacts > 0,
        "the bed must have contacts for the comparison to mean anything"
    );
    worst
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

#[test]
fn device_runs_are_bit_reproducible() {
    let w = box_bed(4, 3, RotationScheme::NoSquish);
    let run = || {
        let mut d = DeviceWorld::upload(Gpu::new().unwrap(), &w).unwrap();
        d.run(500).unwrap();
        d.positions().unwrap()
    };
    let (a, b) = (run(), run());
    let same = a
        .iter()
        .zip(&b)
        .all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits));
    assert!(same, "two device runs of the same world differ");
}
