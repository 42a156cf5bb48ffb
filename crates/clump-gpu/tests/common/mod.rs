//! Helpers shared by the device-against-CPU tests (cpu_reference.rs,
//! mesh_reference.rs); each test file uses its own share of them.
#![allow(dead_code)]

use clump_core::world::World;
use clump_gpu::periodic::nearest_image;
use clump_gpu::{DeviceWorld, Gpu};
use glam::DVec3;

/// Largest coordinate difference, m, between the device's bodies and the
/// CPU world's, matched by id (the CPU path reorders its bodies), the
/// nearest image along periodic axes (the two paths wrap a body into the
/// box at different steps: the device when it leaves, the CPU path at its
/// next list rebuild).
pub fn max_dev(dev: &DeviceWorld, x: &[DVec3], cpu: &World) -> f64 {
    let b = cpu.bodies();
    let domain = cpu.config.domain;
    let at: std::collections::HashMap<u64, usize> =
        b.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    dev.ids
        .iter()
        .zip(x)
        .map(|(id, p)| {
            nearest_image(&domain, *p - b.position[at[id]])
                .abs()
                .max_element()
        })
        .fold(0.0, f64::max)
}

/// The bed `cpu` on both paths, compared at the steps `checkpoints`: the
/// largest position difference relative to the box, the device and the
/// CPU world at the end; `each` is called with the CPU world at each.
pub fn compare_at(
    mut cpu: World,
    checkpoints: &[u64],
    mut each: impl FnMut(&World),
) -> (f64, DeviceWorld, World) {
    let rotation = cpu.config.rotation;
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
    for &at in checkpoints {
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
        each(&cpu);
        done = at;
    }
    assert!(
        cpu.stats.pair_contacts > 0,
        "the bed must have contacts for the comparison to mean anything"
    );
    (worst, dev, cpu)
}

/// `w` with `simulation.multi_contact = pairs` and every wall's
/// `multi_contact = walls`.
pub fn with_multi(
    mut w: World,
    pairs: clump_core::multi_contact::MultiContact,
    walls: clump_core::multi_contact::MultiContact,
) -> World {
    w.config.multi_contact = pairs;
    for wall in &mut w.walls {
        wall.multi_contact = walls;
    }
    w
}

/// Largest coordinate difference, m, between two CPU worlds' bodies,
/// matched by id, after `steps` steps of each.
pub fn cpu_apart(mut a: World, mut b: World, steps: u64) -> f64 {
    for w in [&mut a, &mut b] {
        w.prepare().unwrap();
        w.run(steps).unwrap();
    }
    let (ba, bb) = (a.bodies(), b.bodies());
    let at: std::collections::HashMap<u64, usize> =
        bb.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    (0..ba.len())
        .map(|k| {
            (ba.position[k] - bb.position[at[&ba.id[k]]])
                .abs()
                .max_element()
        })
        .fold(0.0, f64::max)
}
