//! Criterion benches of the hot parts: the neighbour build, the contact
//! kernel, and a whole step on a dense bed of tetrahedral clumps.
//! Run with `cargo bench -p clump-core`.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{
    ContactHistory, ContactInput, ContactModel, DampingLaw, Material, PairProperties,
};
use clump_core::multi_contact::MultiContact;
use clump_core::neighbor::pairs::{BuildInput, HistoryMap};
use clump_core::neighbor::{CellGrid, PairList};
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::wall::{Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, ContactTable, World, WorldConfig};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DQuat, DVec3};

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

fn neighbor_build(c: &mut Criterion) {
    let w = bed(16, 3000);
    let sp = w.spheres();
    let grid = CellGrid::new(&w.config.domain, &sp.position, 2e-3 + 0.5e-3).unwrap();
    let inp = BuildInput {
        position: &sp.position,
        radius: &sp.radius,
        body: &sp.body,
        gid: &sp.gid,
        skin: 0.5e-3,
    };
    let mut list = PairList::default();
    let hist = HistoryMap::default();
    let mut g = c.benchmark_group("neighbor");
    g.throughput(Throughput::Elements(sp.len() as u64));
    g.bench_function("build_16k_spheres", |b| {
        b.iter(|| list.build(&grid, &w.config.domain, &inp, &hist))
    });
    g.finish();
}

fn contact_kernel(c: &mut Criterion) {
    let m = material();
    let model = ContactModel::new(&m, &m, &props()).unwrap();
    let input = ContactInput {
        normal: DVec3::new(0.0, 0.6, 0.8),
        overlap: 2e-6,
        rel_velocity: DVec3::new(0.01, -0.02, 0.003),
        rel_omega: DVec3::new(1.0, 0.0, 0.0),
        radius: 0.5e-3,
        mass: 1.6e-5,
        dt: 1e-5,
    };
    let mut h = ContactHistory::default();
    let mut g = c.benchmark_group("contact");
    g.throughput(Throughput::Elements(1));
    g.bench_function("hertz_mindlin_touching", |b| {
        b.iter(|| std::hint::black_box(model.evaluate(std::hint::black_box(&input), &mut h)))
    });
    g.finish();
}

fn whole_step(c: &mut Criterion) {
    let mut w = bed(12, 5000);
    let n = w.spheres().len() as u64;
    let mut g = c.benchmark_group("step");
    g.throughput(Throughput::Elements(n));
    g.sample_size(20);
    g.bench_function("dense_bed_6912_spheres", |b| b.iter(|| w.step().unwrap()));
    g.finish();
}

criterion_group!(benches, neighbor_build, contact_kernel, whole_step);
criterion_main!(benches);
