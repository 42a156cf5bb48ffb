//! Criterion benches of the hot parts: the neighbour build, the contact
//! kernel, the micro-slip tangential laws over one oblique impact, and a
//! whole step on a dense bed of tetrahedral clumps.
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
        slip: None,
        owned: None,
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

/// Steps of the oblique impact of [`tangential_laws`].
const IMPACT_STEPS: usize = 400;

/// The cost per contact-step of the micro-slip laws, Thornton–Yin's
/// incremental scheme (`mindlin_deresiewicz`) against the exact MDR model
/// (`mdr`), over one oblique impact replayed from a new contact: the overlap
/// follows a half sine (0 → 2 µm → 0 over 400 steps of 0.1 µs) while the
/// surfaces slide at 0.02 m/s, so that the normal force rises and falls
/// under a tangential load (the MDR profile grows nodes while loading).
fn tangential_laws(c: &mut Criterion) {
    use clump_core::contact::mdr::SlipProfile;
    use clump_core::contact::{PairProperties, TangentialLaw};
    let m = tetra_material();
    let (dt, delta_max, vt) = (1e-7, 2e-6, 0.02);
    let period = IMPACT_STEPS as f64 * dt;
    let inputs: Vec<ContactInput> = (1..IMPACT_STEPS)
        .map(|k| {
            let phase = std::f64::consts::PI * k as f64 * dt / period;
            ContactInput {
                normal: DVec3::Z,
                overlap: delta_max * phase.sin(),
                // i approaches j while the overlap grows
                rel_velocity: DVec3::new(
                    vt,
                    0.0,
                    -delta_max * std::f64::consts::PI / period * phase.cos(),
                ),
                rel_omega: DVec3::ZERO,
                radius: 0.5e-3,
                radius_sum: 2e-3,
                mass: 1.6e-5,
                dt,
            }
        })
        .collect();
    let mut g = c.benchmark_group("tangential");
    g.throughput(Throughput::Elements(inputs.len() as u64));
    for (name, law) in [
        (
            "mindlin_deresiewicz_impact",
            TangentialLaw::MindlinDeresiewicz,
        ),
        ("mdr_impact", TangentialLaw::Mdr),
    ] {
        let props = PairProperties {
            tangential: law,
            ..tetra_contact()
        };
        let model = ContactModel::new(&m, &m, &props).unwrap();
        g.bench_function(name, |b| {
            b.iter(|| {
                let (mut h, mut slip) = (ContactHistory::default(), SlipProfile::default());
                let mut sum = DVec3::ZERO;
                for input in &inputs {
                    let out = if law == TangentialLaw::Mdr {
                        model.evaluate_slip(std::hint::black_box(input), &mut h, &mut slip)
                    } else {
                        model.evaluate(std::hint::black_box(input), &mut h)
                    };
                    sum += out.force;
                }
                sum
            })
        });
    }
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

criterion_group!(
    benches,
    neighbor_build,
    contact_kernel,
    tangential_laws,
    whole_step
);
criterion_main!(benches);
