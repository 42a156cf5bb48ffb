//! Profiling driver: a bed of tetra clumps, settled, then stepped.
//! `cargo run --release -p clump-core --example profile_bed -- NX SETTLE STEPS`

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{DampingLaw, Material, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, ContactTable, World, WorldConfig};
use glam::{DQuat, DVec3};
use std::time::Instant;

fn material() -> Material {
    Material {
        youngs_modulus: 5e6,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

fn props() -> PairProperties {
    PairProperties {
        restitution: 0.5,
        friction: 0.5,
        damping: DampingLaw::Liggghts,
        ..PairProperties::default()
    }
}

/// A box of tetra clumps on a jittered lattice, allowed to fall for `settle` steps.
fn bed(nx: usize, settle: u64) -> World {
    let m = material();
    let mats = vec![m];
    let table = ContactTable::new(&mats, |_, _| props()).unwrap();
    let l = nx as f64 * 3.6e-3;
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::new(0.0, 0.0, -0.001),
            hi: DVec3::new(l, l, 1.0),
            periodic: [true, true, false],
        },
        gravity: DVec3::new(0.0, 0.0, -9.81),
        dt: 1e-5,
        rotation: Default::default(),
        added_mass: AddedMass::default(),
        skin: Some(0.5e-3),
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    let h = 1.2e-3 / (2.0 * 2f64.sqrt());
    let s: Vec<Sphere> = [[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]]
        .iter()
        .map(|c| Sphere {
            center: DVec3::from_array(*c) * h,
            radius: 1e-3,
        })
        .collect();
    let t = w
        .add_template(
            ClumpTemplate::from_spheres("tetra", &s, m.density).unwrap(),
            0,
        )
        .unwrap();
    w.add_wall(Wall {
        name: "floor".into(),
        shape: WallShape::Plane {
            point: DVec3::ZERO,
            normal: DVec3::Z,
        },
        material: 0,
        motion: WallMotion::default(),
        multi_contact: MultiContact::Sum,
        active: true,
    })
    .unwrap();
    let mut k = 0u64;
    for z in 0..nx {
        for y in 0..nx {
            for x in 0..nx {
                k += 1;
                let q = DQuat::from_euler(
                    glam::EulerRot::ZXZ,
                    k as f64 * 0.7,
                    k as f64 * 1.3,
                    k as f64 * 0.4,
                );
                let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.6) * 3.6e-3;
                w.add_body(&BodyInit::at_rest(t, p, q)).unwrap();
            }
        }
    }
    w.run(settle).unwrap();
    w
}

#[inline(never)]
fn profiled(w: &mut World, steps: u64) {
    w.run(steps).unwrap();
}

fn main() {
    let a: Vec<u64> = std::env::args()
        .skip(1)
        .map(|x| x.parse().unwrap())
        .collect();
    let (nx, settle, steps) = (
        a.first().copied().unwrap_or(12),
        a.get(1).copied().unwrap_or(20000),
        a.get(2).copied().unwrap_or(2000),
    );
    let mut w = bed(nx as usize, settle);
    let r0 = w.rebuilds;
    println!("SETTLED");
    use std::io::Write;
    std::io::stdout().flush().unwrap();
    if std::env::var_os("PROFILE_WAIT").is_some() {
        std::thread::sleep(std::time::Duration::from_secs(3));
    }
    let t = Instant::now();
    profiled(&mut w, steps);
    let s = t.elapsed().as_secs_f64();
    let th = w.thermo();
    println!("{} spheres, {} steps in {s:.3} s: {:.3} M sphere-steps/s; rebuilds {}; contacts {}+{}; KE {:.3e}", w.spheres().len(), steps, w.spheres().len() as f64 * steps as f64 / s / 1e6, w.rebuilds - r0, th.pair_contacts, th.wall_contacts, th.kinetic_translational);
}
