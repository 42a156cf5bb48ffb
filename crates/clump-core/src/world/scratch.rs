//! The step's working arrays (reused, so that steps and, once warm,
//! rebuilds do not allocate) and where the world is within its step.

use crate::body::Bodies;
use crate::neighbor::carry::HistoryCarry;
use crate::neighbor::walls::WallList;
use crate::par::affinity::Balance;
use crate::stats::ContactStats;
use crate::wall::WallLoad;

/// Working arrays of the step pipeline; never part of the simulated state.
#[derive(Default)]
pub(crate) struct Scratch {
    /// Rebuild: the permutation of the bodies (the storage order of
    /// `neighbor::sort`, lost bodies removed).
    pub perm: Vec<u32>,
    /// Rebuild: which bodies stay.
    pub keep: Vec<bool>,
    /// Rebuild: the permuted bodies.
    pub bodies: Bodies,
    /// Rebuild: the previous wall list.
    pub wall_list: WallList,
    /// Rebuild: per sphere, the entry of the previous wall list whose
    /// contact slots it continues.
    pub wall_carry: Vec<u32>,
    /// Rebuild: per body of the new order, its index in the last build's
    /// sphere topology ([`crate::neighbor::carry::NONE`]: added since).
    pub old_body: Vec<u32>,
    /// Rebuild: the old list's pair histories, for the new list.
    pub carry: HistoryCarry,
    /// Rebuild: sort keys.
    pub keys: Vec<(u64, u64, u32)>,
    /// Gather: statistics per body chunk.
    pub chunk_stats: Vec<ContactStats>,
    /// Pair stage: statistics per body chunk.
    pub chunk_pair_stats: Vec<ContactStats>,
    /// Per body: the pair stage summed its column (`PairBody::col`) this step.
    pub body_ready: Vec<bool>,
    /// Gather: wall loads per body chunk and wall.
    pub chunk_wall_loads: Vec<WallLoad>,
    /// Cumulative per-body cost estimate of the gather (one unit per
    /// sphere, more for a sphere with a wall nearby), `len = bodies + 1`;
    /// built with the wall lists. Splits the per-body loops between threads
    /// (see `par::affinity`).
    pub body_cost: Vec<u64>,
    /// How the first half step, the pair loop, the gather and the two
    /// together share their chunks between threads (learned; never affects
    /// results).
    pub balance: [Balance; crate::par::affinity::LOOPS],
    /// The bodies' mass properties and degrees of freedom as the step
    /// reads them (refreshed at every step boundary where steps begin).
    pub props: super::props::PropsTable,
}

/// Where a world is within its step.
pub(crate) struct StepPhase {
    /// Bodies were added or removed since the last neighbour build.
    pub topology_dirty: bool,
    /// The first half of the current step is done (fused into the previous
    /// step's gather, inside the run loop), with whether a sphere then
    /// moved more than half the skin. None at a step boundary.
    pub first_half_done: Option<bool>,
    /// The forces of the current state have been evaluated.
    pub forces_ready: bool,
    /// The bodies' centres, velocities and angular velocities are current
    /// only in the pair stage's packed copy (`neighbor::PairBody`), not in
    /// the body arrays: set by a fused gather, whose first halves store them
    /// there alone (one copy fewer to bring from memory and write back every
    /// step); `World::catch_up_bodies` copies them back.
    pub bodies_lag: bool,
}

impl Default for StepPhase {
    fn default() -> Self {
        StepPhase {
            topology_dirty: true,
            first_half_done: None,
            forces_ready: false,
            bodies_lag: false,
        }
    }
}
