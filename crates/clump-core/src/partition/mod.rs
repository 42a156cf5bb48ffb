//! A world split over several processes (ranks): spatial decomposition with
//! whole ghost clumps, for MPI (the `clump-mpi` crate supplies the
//! communicator; [`ThreadComm`] runs ranks as threads of one process, for
//! tests).
//!
//! Each rank keeps the bodies whose centre of mass lies in its region
//! (*owned*) and, as *ghosts*, every other body whose centre of mass lies
//! within the halo of that region: `h = 2 R_max + skin`, with `R_max` the
//! largest distance from a template's centre of mass to the far side of
//! one of its spheres. A candidate pair needs its spheres within
//! `r_i + r_j + skin` at the last build, so its bodies' centres are within
//! `h`: every pair of an owned body is in the rank's list, and its force
//! and torque are summed there complete. Nothing is set by the user.
//!
//! **Same bits at any rank count.** A rank's bodies are kept in the order
//! the whole world would have (the cell order of `neighbor::sort` on the
//! full set's grid, ties by id), its pair list is built on the whole
//! world's grid, so every row and column of an owned sphere holds the same pairs in the same order as one
//! process would: each owned body's force and torque are the same sums in
//! the same order, hence the same bits. Ghost bodies take the state of
//! their owner after every step (their own force sums are incomplete).
//!
//! **Rebuilds.** When any rank's sphere has moved past half the skin, every
//! rank rebuilds: it wraps its owned bodies, drops the lost ones and sends
//! each body to its new owner and to the ranks within the halo of it, with
//! its wall slots and the histories of its pairs (neighbours only); the
//! whole world's grids come from bounding boxes reduced over the ranks, and
//! the regions are re-balanced on a sample of every rank's bodies (at most
//! 256 positions each). The ranks sort their bodies by the whole world's
//! cell key and id, as one process does.
//!
//! **Events.** At every event of the run loop (output, insertion,
//! checkpoint, stage change) the whole world is gathered on every rank, in
//! one process's order, and the step before it runs whole: the drivers see
//! one process's world, statistics, wall loads and contact records, so
//! insertion, output, checkpoints and steering work unchanged; only rank 0
//! writes files. The regions are re-balanced on every body (recursive
//! coordinate bisection on counted costs, [`regions`]) when the world is
//! split again.
//! The price: each event moves every body to every rank
//! (docs/scaling.md says where that stops scaling).
//!
//! This module holds the part's data and the communicator; the stages that
//! split, gather and rebuild a world are in `step/partition/`.
//!
//! Between events, the statistics of a step (the health check's input) are
//! summed per rank and then exactly over the ranks by a binomial tree
//! (`step/partition/step_stats.rs`): the same on every rank, but not bit
//! for bit one process's (the body states are).

mod comm;
pub mod regions;

pub use comm::{Comm, ThreadComm};
pub use regions::Regions;

/// This rank's part of a world: which of its bodies are its own, where the
/// others come from, and where its own go as ghosts.
pub struct Part {
    /// The communicator.
    pub(crate) comm: Box<dyn Comm>,
    /// The regions of the last balance.
    pub(crate) regions: Regions,
    /// True while the world holds this rank's part only; false while it
    /// holds the whole world (at an event).
    pub(crate) local: bool,
    /// Per local body: owned by this rank.
    pub(crate) owned: Vec<bool>,
    /// Per local body: its place in the whole world's storage order (a key
    /// that sorts as that order: the index in the whole world after a
    /// split of it, the cell key and id after a rebuild of the parts).
    pub(crate) order: Vec<(u64, u64)>,
    /// Per neighbouring rank, the owned bodies (local indices, ascending)
    /// it holds as ghosts.
    pub(crate) send: Vec<(usize, Vec<u32>)>,
    /// Per owning rank, the ghosts (local indices, ascending) it sends.
    pub(crate) recv: Vec<(usize, Vec<u32>)>,
    /// The halo of the last restriction, m.
    pub(crate) halo: f64,
    /// The next event keeps the world split (set by the driver, taken by
    /// `World::advance`).
    pub(crate) stay_split: bool,
    /// This rank's stop request, sent with the statistics of the step
    /// about to be taken (`World::advance`), and the requests of every
    /// rank or-ed, received with them: the stop flags ride on the step's
    /// statistics reduction instead of a collective call of their own.
    pub(crate) stop: (bool, Option<bool>),
    /// Bytes and messages this rank sent (ghost states, gathers).
    pub traffic: Traffic,
}

/// What a rank sent, for the cost model (docs/scaling.md).
#[derive(Debug, Clone, Copy, Default)]
pub struct Traffic {
    /// Ghost-state bytes sent in the steps.
    pub ghost_bytes: u64,
    /// Ghost-state messages sent.
    pub ghost_messages: u64,
    /// Bytes of bodies this rank sent at neighbour rebuilds (migration and
    /// new ghosts).
    pub migrate_bytes: u64,
    /// Messages of those rebuilds.
    pub migrate_messages: u64,
    /// Neighbour rebuilds of the parts.
    pub rebuilds: u64,
    /// Steps of the part (whole steps before events not counted).
    pub steps: u64,
    /// Bytes this rank contributed to gathers of the whole world.
    pub gather_bytes: u64,
    /// Gathers of the whole world (rebuilds and events).
    pub gathers: u64,
    /// Small collective calls (flags, statistics).
    pub reductions: u64,
    /// Sum over steps of the ghost bodies held (halo fraction = this over
    /// the sum of local bodies).
    pub ghost_body_steps: u64,
    /// Sum over steps of the local bodies held.
    pub local_body_steps: u64,
    /// Sum over steps of the candidate sphere pairs in this rank's list
    /// (each evaluated once a step).
    pub pair_steps: u64,
    /// Sum over steps of the candidate pairs between two ghosts that this
    /// rank's builds left out (their owners evaluate them).
    pub ghost_pair_steps: u64,
    /// Seconds in the ghosts' state exchange after each step, waiting for
    /// the neighbours included.
    pub ghost_seconds: f64,
    /// Seconds in the reductions of each step (flags, statistics and wall
    /// loads), waiting for every rank included.
    pub reduce_seconds: f64,
}

/// A summary of a rank's part, for reports.
#[derive(Debug, Clone, Copy)]
pub struct PartInfo {
    /// This rank.
    pub rank: usize,
    /// Number of ranks.
    pub size: usize,
    /// The halo of the last build, m.
    pub halo: f64,
    /// What this rank sent.
    pub traffic: Traffic,
}
