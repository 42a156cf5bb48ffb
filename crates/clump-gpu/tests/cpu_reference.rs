//! The device step against the CPU path, its reference: a small bed of
//! tetra clumps (4 spheres each) falling into a closed box of five plane
//! walls, with jostling initial velocities so that clump-clump and wall
//! contacts form, slide and end within the run. The CPU path's equations
//! are the device's (same laws, same order of operations); the two differ
//! by the summation order of each body's contact loads, so the positions
//! agree to round-off amplified by the contacts: the criterion is
//! 1e-9 of the domain size after a few thousand steps.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{ContactTable, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::testbed::{tetra_material, tetra_template};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, World, WorldConfig};
use clump_gpu::{DeviceWorld, Gpu};
use glam::{DQuat, DVec3};

const PITCH: f64 = 3.6e-3;

/// `n × n × layers` tetra clumps in a box `n` pitches wide, each with a
/// deterministic velocity of up to 0.2 m/s and spin of up to 100 rad/s.
fn bed(n: usize, layers: usize) -> World {
    let mats = vec![tetra_material()];
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let l = n as f64 * PITCH;
    let h = (layers as f64 + 2.0) * PITCH;
    let config = WorldConfig {
        domain: Domain { lo: DVec3::ZERO, hi: DVec3::new(l, l, h), periodic: [false; 3] },
        gravity: DVec3::new(0.0, 0.0, -9.81),
        dt: 1e-5,
        rotation: RotationScheme::RichardsonLiggghts,
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let t = w.add_template(tetra_template(), 0).unwrap();
    let planes = [
        (DVec3::ZERO, DVec3::Z),
        (DVec3::ZERO, DVec3::X),
        (DVec3::ZERO, DVec3::Y),
        (DVec3::new(l, l, 0.0), -DVec3::X),
        (DVec3::new(l, l, 0.0), -DVec3::Y),
    ];
    for (k, (point, normal)) in planes.into_iter().enumerate() {
        w.add_wall(Wall {
            name: format!("wall{k}"),
            shape: WallShape::Plane { point, normal },
            material: 0,
            motion: WallMotion::default(),
            multi_contact: MultiContact::Sum,
            active: true,
        })
        .unwrap();
    }
    let mut k = 0u64;
    for z in 0..layers {
        for y in 0..n {
            for x in 0..n {
                k += 1;
                let kf = k as f64;
                let q = DQuat::from_euler(glam::EulerRot::ZXZ, kf * 0.7, kf * 1.3, kf * 0.4);
                let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.6) * PITCH;
                let mut b = BodyInit::at_rest(t, p, q);
                b.velocity = 0.2 * DVec3::new((kf * 1.7).sin(), (kf * 2.3).sin(), (kf * 3.1).sin());
                b.angular_velocity = 100.0 * DVec3::new((kf * 0.9).cos(), (kf * 1.1).cos(), (kf * 1.9).cos());
                w.add_body(&b).unwrap();
            }
        }
    }
    w
}

/// Largest coordinate difference, m, between the device's bodies and the
/// CPU world's, matched by id (the CPU path reorders its bodies).
fn max_dev(dev: &DeviceWorld, x: &[DVec3], cpu: &World) -> f64 {
    let b = cpu.bodies();
    let at: std::collections::HashMap<u64, usize> = b.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    dev.ids.iter().zip(x).map(|(id, p)| (*p - b.position[at[id]]).abs().max_element()).fold(0.0, f64::max)
}

#[test]
fn device_step_agrees_with_the_cpu_path() {
    let mut cpu = bed(4, 3);
    let size = cpu.config.domain.size().max_element();
    let mut dev = DeviceWorld::upload(Gpu::new().unwrap(), &cpu).unwrap_or_else(|e| panic!("{e}"));
    eprintln!("adapter: {}, {} spheres", dev.gpu.describe(), dev.spheres());
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
            "step {at}: max |x_gpu - x_cpu| / L = {dev_rel:.3e}; contacts on the CPU {}; device {:.0} sphere-steps/s",
            format!("{} pair, {} wall", cpu.stats.pair_contacts, cpu.stats.wall_contacts),
            (dev.spheres() as f64 * (at - done) as f64) / secs
        );
        worst = worst.max(dev_rel);
        done = at;
    }
    assert!(cpu.stats.pair_contacts > 0, "the bed must have contacts for the comparison to mean anything");
    assert!(worst < 1e-9, "device and CPU positions differ by {worst:e} of the domain size");
}

#[test]
fn device_runs_are_bit_reproducible() {
    let w = bed(4, 3);
    let run = || {
        let mut d = DeviceWorld::upload(Gpu::new().unwrap(), &w).unwrap();
        d.run(500).unwrap();
        d.positions().unwrap()
    };
    let (a, b) = (run(), run());
    let same = a.iter().zip(&b).all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits));
    assert!(same, "two device runs of the same world differ");
}
