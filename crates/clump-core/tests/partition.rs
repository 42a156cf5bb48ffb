//! A world split over ranks (threads here, MPI in clump-mpi) gives the same
//! bits as one process: every body's final state, at 1 to 4 ranks, through
//! neighbour rebuilds (bodies migrate between ranks), periodic boundaries
//! and a wall, and through events (the world gathered whole and split
//! again).

use clump_core::partition::ThreadComm;
use clump_core::testbed::{state_bits, tetra_lattice_bed};
use clump_core::world::World;

/// Runs `make()` on `ranks` threads, each advancing `rounds` × `steps`
/// steps (an event between rounds); returns each rank's final whole world's
/// fingerprint and the step count.
fn run_ranks(
    ranks: usize,
    make: fn() -> World,
    steps: u64,
    rounds: usize,
) -> Vec<(Vec<u64>, u64, u64, clump_core::partition::Traffic)> {
    let handles: Vec<_> = ThreadComm::group(ranks)
        .into_iter()
        .map(|comm| {
            std::thread::spawn(move || {
                let mut w = make();
                w.partition(Box::new(comm));
                for _ in 0..rounds {
                    w.run(steps).unwrap();
                }
                let traffic = w.part_info().unwrap().traffic;
                (state_bits(&w), w.step, w.rebuilds, traffic)
            })
        })
        .collect();
    handles.into_iter().map(|h| h.join().unwrap()).collect()
}

fn bed() -> World {
    tetra_lattice_bed(6, 6, 4, None)
}

#[test]
fn a_settling_periodic_bed_has_the_same_bits_on_1_to_4_ranks() {
    let (steps, rounds) = (2500, 4);
    let mut serial = bed();
    serial.run(steps * rounds as u64).unwrap();
    let want = state_bits(&serial);
    assert!(
        serial.rebuilds > 3,
        "too few rebuilds to test migration: {}",
        serial.rebuilds
    );
    assert!(
        serial.stats.pair_contacts > 50,
        "the bed must be in contact: {} contacts",
        serial.stats.pair_contacts
    );
    for ranks in 1..=4 {
        for (rank, (got, step, rebuilds, traffic)) in
            run_ranks(ranks, bed, steps, rounds).into_iter().enumerate()
        {
            assert_eq!(step, serial.step);
            if ranks > 1 {
                // the ranks did share the bed: ghosts were sent every step
                assert!(
                    // every step of the parts (all but the whole steps
                    // before the events) sent ghost states
                    traffic.steps + rounds as u64 >= step
                        && traffic.ghost_messages >= traffic.steps
                        && traffic.ghost_body_steps > 0,
                    "{ranks} ranks, rank {rank}: {traffic:?}"
                );
                assert!(traffic.ghost_body_steps < traffic.local_body_steps);
                // the pairs between two ghosts were left to their owners
                // (a halo two bodies deep holds such pairs every step)
                assert!(
                    traffic.ghost_pair_steps > 0 && traffic.pair_steps > 0,
                    "{ranks} ranks, rank {rank}: {traffic:?}"
                );
                // rebuilds move bodies between neighbours: the whole world
                // is gathered at events only (two per round at most)
                assert!(
                    traffic.gathers <= 2 * rounds as u64 && rebuilds > traffic.gathers,
                    "{ranks} ranks: {} gathers for {rebuilds} rebuilds",
                    traffic.gathers
                );
            }
            assert_eq!(rebuilds, serial.rebuilds, "{ranks} ranks: rebuild count");
            assert!(
                got == want,
                "{ranks} ranks, rank {rank}: body states differ from one process"
            );
        }
    }
}

/// The bed with one body whose motion is restricted (a locked torque
/// axis), thrown over the bed (about 35 mm horizontally before it lands,
/// the periodic bed is 21.6 mm wide) so that it passes from rank to rank: a rank reads its bodies' mass properties and flags from their
/// template's row only while it holds no such body (as owner or ghost),
/// which changes as the body migrates.
fn restricted_bed() -> World {
    let mut w = bed();
    let b = w.bodies().len() - 3;
    let free = w.bodies().force_flag[b];
    w.set_body_dof_at(b, free, [false, true, true]).unwrap();
    let mut x = w.bodies().position[b];
    x.z = 5.4 * clump_core::testbed::LATTICE_PITCH;
    w.set_body_position_at(b, x).unwrap();
    w.set_body_velocity_at(b, clump_core::DVec3::new(1.0, 0.6, 0.0))
        .unwrap();
    w
}

/// A body with restricted motion among free ones gives the same bits on 2
/// and 3 ranks as in one process while it moves from rank to rank.
#[test]
fn restricted_bodies_have_the_same_bits_on_2_and_3_ranks() {
    let (steps, rounds) = (1500, 2);
    let mut serial = restricted_bed();
    serial.run(steps * rounds as u64).unwrap();
    assert!(serial.rebuilds > 3, "{} rebuilds", serial.rebuilds);
    let want = state_bits(&serial);
    for ranks in [2, 3] {
        for (rank, (got, step, _, _)) in run_ranks(ranks, restricted_bed, steps, rounds)
            .into_iter()
            .enumerate()
        {
            assert_eq!(step, serial.step);
            assert!(got == want, "{ranks} ranks, rank {rank}: the bits differ");
        }
    }
}

/// The bed with the exact micro-slip law (`tangential = "mdr"`): its
/// contact profiles travel with the bodies between ranks and through
/// the events, so the ranks repeat one process's bits.
fn mdr_bed() -> World {
    use clump_core::contact::{ContactTable, PairProperties, TangentialLaw};
    let mut w = bed();
    w.contact_table = ContactTable::new(&w.materials, |_, _| PairProperties {
        tangential: TangentialLaw::Mdr,
        ..clump_core::testbed::tetra_contact()
    })
    .unwrap();
    w
}

#[test]
fn mdr_profiles_have_the_same_bits_on_2_and_3_ranks() {
    let (steps, rounds) = (2500, 2);
    let mut serial = mdr_bed();
    serial.run(steps * rounds as u64).unwrap();
    let want = state_bits(&serial);
    assert!(
        serial.rebuilds > 3 && serial.stats.pair_contacts > 20,
        "{} rebuilds, {} contacts",
        serial.rebuilds,
        serial.stats.pair_contacts
    );
    for ranks in [2, 3] {
        for (rank, (got, step, _, _)) in run_ranks(ranks, mdr_bed, steps, rounds)
            .into_iter()
            .enumerate()
        {
            assert_eq!(step, serial.step);
            assert!(
                got == want,
                "{ranks} ranks, rank {rank}: body states differ from one process"
            );
        }
    }
}

/// The bed with heat: a floor at 400 K under bodies at 300 K, conducting
/// through every contact while it settles.
fn heat_bed() -> World {
    let mut w = bed();
    clump_core::testbed::heat_on(&mut w, 5.0, 1.0, 400.0, 300.0, 0.0);
    w
}

/// The temperatures (by id) and the walls' heat of a world, as bits.
fn heat_bits(w: &World) -> (Vec<(u64, u64)>, Vec<u64>) {
    let b = w.bodies();
    let mut t: Vec<(u64, u64)> =
        b.id.iter()
            .zip(&b.temperature)
            .map(|(&i, &t)| (i, t.to_bits()))
            .collect();
    t.sort();
    let h = w.heat.as_ref().unwrap();
    (t, h.wall_heat.iter().map(|x| x.to_bits()).collect())
}

/// Heat on ranks (T-94): ghosts carry their owners' temperatures and the
/// floor's heat flows are summed in one process's order, so the
/// temperatures and the floor's heat have one process's bits on 2 and 3
/// ranks, as do the body states.
#[test]
fn heat_has_the_same_bits_on_2_and_3_ranks() {
    let (steps, rounds) = (2000, 2);
    let mut serial = heat_bed();
    serial.run(steps * rounds as u64).unwrap();
    let want = (state_bits(&serial), heat_bits(&serial));
    let hottest = serial.thermo().heat.unwrap().max_temperature;
    assert!(
        serial.rebuilds > 3 && hottest > 300.1,
        "{} rebuilds, hottest body {hottest} K",
        serial.rebuilds
    );
    for ranks in [2, 3] {
        let handles: Vec<_> = ThreadComm::group(ranks)
            .into_iter()
            .map(|comm| {
                std::thread::spawn(move || {
                    let mut w = heat_bed();
                    w.partition(Box::new(comm));
                    for _ in 0..rounds {
                        w.run(steps).unwrap();
                    }
                    (state_bits(&w), heat_bits(&w))
                })
            })
            .collect();
        for (rank, h) in handles.into_iter().enumerate() {
            let got = h.join().unwrap();
            assert!(
                got.0 == want.0,
                "{ranks} ranks, rank {rank}: body states differ"
            );
            assert!(
                got.1 .0 == want.1 .0,
                "{ranks} ranks, rank {rank}: temperatures differ"
            );
            assert_eq!(
                got.1 .1, want.1 .1,
                "{ranks} ranks, rank {rank}: floor heat"
            );
        }
    }
}

/// The thermo row of a world kept split through its events
/// (`World::thermo_of_ranks`: exact sums reduced over the ranks, T-73) is
/// one process's, bit for bit, on 2 to 5 ranks (5: a binomial tree with a
/// rank that has no partner at the top level). The row's energies,
/// contact count and floor load must be live.
#[test]
fn thermo_rows_of_a_split_world_are_one_process_s_on_2_to_5_ranks() {
    /// Three rows 700 steps apart, each at an event (kept split on ranks).
    fn rows(w: &mut World, split: bool) -> Vec<String> {
        (0..3)
            .map(|_| {
                w.request_exact_sums(Some(w.step + 700));
                w.keep_split_at_next_event(split);
                w.run(700).unwrap();
                format!("{:?}", w.thermo_of_ranks().unwrap())
            })
            .collect()
    }
    let mut serial = bed();
    let want = rows(&mut serial, false);
    let last = serial.thermo();
    assert!(last.pair_contacts > 50 && last.elastic > 0.0 && last.kinetic_translational > 0.0);
    assert!(
        last.wall_loads.iter().any(|l| l.force.length() > 0.0),
        "{last:?}"
    );
    for ranks in 2..=5 {
        let handles: Vec<_> = ThreadComm::group(ranks)
            .into_iter()
            .map(|comm| {
                std::thread::spawn(move || {
                    let mut w = bed();
                    w.partition(Box::new(comm));
                    let got = rows(&mut w, true);
                    (got, w.is_split(), w.part_info().unwrap().traffic.gathers)
                })
            })
            .collect();
        for (rank, h) in handles.into_iter().enumerate() {
            let (got, split, gathers) = h.join().unwrap();
            assert!(
                split && gathers == 0,
                "{ranks} ranks: split {split}, {gathers} gathers"
            );
            assert_eq!(got, want, "{ranks} ranks, rank {rank}");
        }
    }
}
