//! Insertion into a world split over ranks (threads here, MPI in
//! clump-mpi): a stream and a pack decided on the split world, without
//! gathering it, give one process's bodies, ids and states, bit for bit,
//! on 1 to 4 ranks, through the steps after each insertion (the new
//! bodies' first kick included).

use clump_core::insert::{
    pack, FractionBasis, Mix, MixEntry, Orientation, PackSpec, PackTarget, Region,
    SizeDistribution, StreamInserter, StreamRate, StreamSpec,
};
use clump_core::testbed::{on_thread_ranks, state_bits, tetra_lattice_bed, LATTICE_PITCH};
use clump_core::world::World;
use glam::DVec3;

/// The settling bed of `partition.rs`: 6 × 6 × 4 tetras on a floor,
/// periodic in x and y (21.6 mm square).
fn bed() -> World {
    tetra_lattice_bed(6, 6, 4, None)
}

/// The tetra at 0.8 to 1.1 of its size (scaled templates are added as the
/// bodies are drawn).
fn mix() -> Mix {
    Mix {
        basis: FractionBasis::Number,
        entries: vec![MixEntry {
            template: 0,
            fraction: 1.0,
            size: SizeDistribution::Uniform { min: 0.8, max: 1.1 },
        }],
    }
}

/// A box over the whole periodic cross-section, above the bed, from
/// `z0` to `z1` lattice pitches (m, world frame).
fn layer(z0: f64, z1: f64) -> Region {
    let l = 6.0 * LATTICE_PITCH;
    Region::Box {
        lo: DVec3::new(0.0, 0.0, z0 * LATTICE_PITCH),
        hi: DVec3::new(l, l, z1 * LATTICE_PITCH),
    }
}

/// Runs the bed with a stream (4 000 bodies/s falling at 0.3 m/s) and,
/// at step 800, a pack of 5 bodies, each insertion at an event that keeps
/// the world split when `split`; 1 600 steps in all. Returns the bodies
/// inserted.
fn run_with_insertions(w: &mut World, split: bool) -> u64 {
    let spec = StreamSpec {
        region: layer(4.6, 5.9),
        mix: mix(),
        rate: StreamRate::BodiesPerSecond(4000.0),
        velocity: DVec3::new(0.0, 0.0, -0.3),
        start: 0.0,
        end: None,
        exit_normal: None,
        orientation: Orientation::Random,
        max_attempts_per_body: 20,
        angular_velocity: DVec3::ZERO,
        dof: Vec::new(),
        start_after: None,
        plane: None,
    };
    let mut stream = StreamInserter::new(spec, w, 11).unwrap();
    let packed = PackSpec {
        region: layer(4.6, 5.9),
        target: PackTarget::Count(5),
        mix: mix(),
        velocity: DVec3::new(0.0, 0.0, -0.1),
        orientation: Orientation::Random,
        max_attempts_per_body: 1000,
        angular_velocity: DVec3::ZERO,
        dof: Vec::new(),
        plane: None,
    };
    let (end, dt) = (1600, w.config.dt);
    let mut inserted = 0;
    while w.step < end {
        let next = stream.next_due_step(w.step, dt).min(end);
        let next = if w.step < 800 { next.min(800) } else { next };
        w.keep_split_at_next_event(split);
        w.run(next - w.step).unwrap();
        inserted += stream.insert_due(w).unwrap() as u64;
        if w.step == 800 {
            inserted += pack(w, &packed, 5).unwrap().placed as u64;
        }
        w.settle_inserted();
    }
    inserted
}

#[test]
fn insertion_on_a_split_world_has_one_process_s_bits_on_1_to_4_ranks() {
    let mut serial = bed();
    let n0 = serial.bodies().len() as u64;
    let inserted = run_with_insertions(&mut serial, false);
    let want = state_bits(&serial);
    assert!(inserted > 20, "only {inserted} bodies inserted");
    assert_eq!(serial.bodies().len() as u64, n0 + inserted);
    for ranks in 1..=4 {
        let got = on_thread_ranks(ranks, bed, |w| {
            let inserted = run_with_insertions(w, true);
            let (split, gathers) = (w.is_split(), w.part_info().unwrap().traffic.gathers);
            w.make_whole().unwrap();
            (inserted, split, gathers, state_bits(w), w.rebuilds)
        });
        for (rank, (got_inserted, split, gathers, got, rebuilds)) in got.into_iter().enumerate() {
            assert_eq!(got_inserted, inserted, "{ranks} ranks, rank {rank}");
            if ranks > 1 {
                assert!(
                    split && gathers == 0,
                    "{ranks} ranks: split {split}, {gathers} gathers of the world"
                );
            }
            assert_eq!(rebuilds, serial.rebuilds, "{ranks} ranks: rebuild count");
            assert!(
                got == want,
                "{ranks} ranks, rank {rank}: bodies, ids or states differ from one process"
            );
        }
    }
}
