//! Clump over MPI. A partitioned world ([`clump_core::partition`]) needs a
//! communicator: this crate's [`MpiComm`] is rsmpi's world communicator
//! (Debian's OpenMPI), behind the `mpi` feature so that the plain build
//! needs no MPI library. `clump run` and `clump resume`, built with
//! `--features mpi`, split the world over the ranks when started by
//! `mpirun -np N` with N > 1 (docs/scaling.md).

#[cfg(feature = "mpi")]
mod comm;

#[cfg(feature = "mpi")]
pub use comm::{Mpi, MpiComm};

/// True when this build can run over MPI.
pub const ENABLED: bool = cfg!(feature = "mpi");
