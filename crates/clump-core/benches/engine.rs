//! Criterion benches of the hot parts: the neighbour build, the contact
//! kernel, and a whole step on a dense bed of tetrahedral clumps.
//! Run with `cargo bench -p clump-core`.

use clump_core::contact::{ContactHistory, ContactInput, ContactModel};
use clump_core::neighbor::pairs::{BuildInput, HistoryMap};
use clump_core::neighbor::{CellGrid, PairList};
use clump_core::testbed::{tetra_contact, tetra_lattice_bed, tetra_material};
use clump_core::world::World;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec3;

/// A cubic bed of `nx³` tetra clumps, allowed to fall for `settle` steps.
fn bed(nx: usize, settle: u64) -> World {
    let mut w = tetra_lattice_bed(nx, nx, nx, Some(0.5e-3));
    w.run(settle).unwrap();
    w
}

fn neighbor_build(c: &mut Criterion) {
    let w = bed(16, 3000);
    let sp = w.spheres();
    let position: Vec<DVec3> = sp.positions().collect();
    let grid = CellGrid::new(&w.config.domain, &position, 2e-3 + 0.5e-3).unwrap();
    let inp = BuildInput {
        state: &sp.state,
        radius: &sp.radius,
        body: &sp.body,
        body_first: &sp.body_first,
        gid: &sp.gid,
        skin: 0.5e-3,
        rolling: false,
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
    let m = tetra_material();
    let model = ContactModel::new(&m, &m, &tetra_contact()).unwrap();
    let input = ContactInput {
        normal: DVec3::new(0.0, 0.6, 0.8),
        overlap: 2e-6,
        rel_velocity: DVec3::new(0.01, -0.02, 0.003),
        rel_omega: DVec3::new(1.0, 0.0, 0.0),
        radius: 0.5e-3,
        radius_sum: f64::INFINITY,
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
