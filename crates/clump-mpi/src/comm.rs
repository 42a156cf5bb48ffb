//! The MPI communicator of a partitioned world.

use clump_core::partition::Comm;
use mpi::datatype::PartitionMut;
use mpi::environment::Universe;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use mpi::Threading;

/// MPI, initialised for the process; finalised when dropped.
pub struct Mpi {
    universe: Universe,
}

impl Mpi {
    /// Initialises MPI (once per process). The engine calls MPI from one
    /// thread at a time, but not always the thread that initialised it (a
    /// run goes on inside its thread pool): hence `Serialized`.
    pub fn init() -> Option<Mpi> {
        let (universe, _level) = mpi::initialize_with_threading(Threading::Serialized)?;
        Some(Mpi { universe })
    }

    /// This rank.
    pub fn rank(&self) -> usize {
        self.universe.world().rank() as usize
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        self.universe.world().size() as usize
    }

    /// A communicator over every rank, for [`clump_core::world::World::partition`].
    pub fn comm(&self) -> MpiComm {
        MpiComm {
            world: self.universe.world(),
        }
    }

    /// Stops every rank (after a rank's failure, which it has reported).
    pub fn abort(&self, code: i32) -> ! {
        self.universe.world().abort(code)
    }
}

/// rsmpi's world communicator.
pub struct MpiComm {
    world: SimpleCommunicator,
}

// SAFETY: MPI is initialised with `Threading::Serialized`, and a partitioned
// world makes its calls from one thread at a time (the thread that steps
// it; the calls that communicate take `&mut self`).
unsafe impl Send for MpiComm {}
// SAFETY: as above; shared references only read the rank and the size.
unsafe impl Sync for MpiComm {}

impl Comm for MpiComm {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn all_gather(&mut self, mine: &[u8]) -> Vec<Vec<u8>> {
        let n = self.world.size() as usize;
        let len = mine.len() as i32;
        let mut counts = vec![0i32; n];
        self.world.all_gather_into(&len, &mut counts[..]);
        let displs: Vec<i32> = counts
            .iter()
            .scan(0i32, |acc, &c| {
                let d = *acc;
                *acc += c;
                Some(d)
            })
            .collect();
        let total: i32 = counts.iter().sum();
        if total == 0 {
            // nothing to gather (every rank knows it): an empty receive
            // buffer's dangling address would read as MPI_IN_PLACE
            return vec![Vec::new(); n];
        }
        let mut buf = vec![0u8; total as usize];
        {
            let mut part = PartitionMut::new(&mut buf[..], &counts[..], &displs[..]);
            self.world.all_gather_varcount_into(mine, &mut part);
        }
        (0..n)
            .map(|r| buf[displs[r] as usize..(displs[r] + counts[r]) as usize].to_vec())
            .collect()
    }

    fn exchange(&mut self, sends: &[(usize, Vec<u8>)], from: &[usize]) -> Vec<Vec<u8>> {
        let world = &self.world;
        mpi::request::scope(|scope| {
            let pending: Vec<_> = sends
                .iter()
                .map(|(r, bytes)| {
                    world
                        .process_at_rank(*r as i32)
                        .immediate_send(scope, &bytes[..])
                })
                .collect();
            let got: Vec<Vec<u8>> = from
                .iter()
                .map(|&r| world.process_at_rank(r as i32).receive_vec::<u8>().0)
                .collect();
            for p in pending {
                p.wait();
            }
            got
        })
    }
}
