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
use clump_gpu::bed::{box_bed, periodic_bed};
use clump_gpu::periodic::nearest_image;
use clump_gpu::{DeviceWorld, Gpu};
use glam::DVec3;

/// Largest coordinate difference, m, between the device's bodies and the
/// CPU world's, matched by id (the CPU path reorders its bodies), the
/// nearest image along periodic axes (the two paths wrap a body into the
/// box at different steps: the device when it leaves, the CPU path at its
/// next list rebuild).
fn max_dev(dev: &DeviceWorld, x: &[DVec3], cpu: &World) -> f64 {
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

/// The bed under `rotation`, `at` steps on both paths; the largest
/// position difference over the checkpoints, relative to the box.
fn compare(rotation: RotationScheme) -> f64 {
    compare_world(box_bed(4, 3, rotation))
}

/// [`compare`] on the bed `cpu`.
fn compare_world(mut cpu: World) -> f64 {
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
