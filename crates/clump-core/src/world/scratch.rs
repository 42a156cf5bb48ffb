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

/// Where a world is within its step: at a step boundary, or with the
/// first half of the current step done (inside a fused stretch of steps,
/// `World::run`; also where such a stretch was interrupted), and how far
/// its neighbour lists and forces are from the current state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum StepPhase {
    /// At a step boundary.
    Boundary(Lists),
    /// The first half of the current step is done (fused into the previous
    /// step's gather).
    FirstHalfDone {
        /// A sphere then moved more than half the skin.
        moved_out: bool,
        /// The bodies' centres, velocities and angular velocities are
        /// current only in the pair stage's packed copy
        /// (`neighbor::PairBody`), not in the body arrays: a fused gather's
        /// first halves store them there alone (one copy fewer to bring
        /// from memory and write back every step);
        /// `World::catch_up_bodies` copies them back.
        bodies_lag: bool,
        lists: Lists,
    },
}

/// How the neighbour lists and forces stand against the current state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Lists {
    /// Bodies were added or removed since the last neighbour build (or
    /// none was made): the next step rebuilds and evaluates the forces.
    Unbuilt,
    /// The lists are current; the forces are not those of the current
    /// settings (a wall or a setting changed): the next step evaluates them.
    ForcesStale,
    /// The lists and the forces of the current state are current.
    Ready,
}

impl Default for StepPhase {
    fn default() -> Self {
        StepPhase::Boundary(Lists::Unbuilt)
    }
}

impl StepPhase {
    fn lists(&self) -> Lists {
        match *self {
            StepPhase::Boundary(l) | StepPhase::FirstHalfDone { lists: l, .. } => l,
        }
    }

    fn set_lists(&mut self, to: Lists) {
        match self {
            StepPhase::Boundary(l) | StepPhase::FirstHalfDone { lists: l, .. } => *l = to,
        }
    }

    /// Bodies were added or removed since the last neighbour build.
    pub(crate) fn topology_dirty(&self) -> bool {
        self.lists() == Lists::Unbuilt
    }

    /// The forces of the current state have been evaluated.
    pub(crate) fn forces_ready(&self) -> bool {
        self.lists() == Lists::Ready
    }

    /// Bodies were added or removed: the lists and forces are stale.
    pub(crate) fn topology_changed(&mut self) {
        self.set_lists(Lists::Unbuilt);
    }

    /// A setting the forces depend on changed.
    pub(crate) fn forces_changed(&mut self) {
        if self.lists() == Lists::Ready {
            self.set_lists(Lists::ForcesStale);
        }
    }

    /// The neighbour lists were built for the current bodies.
    pub(crate) fn lists_built(&mut self) {
        if self.lists() == Lists::Unbuilt {
            self.set_lists(Lists::ForcesStale);
        }
    }

    /// The forces of the current state were evaluated (or restored).
    pub(crate) fn forces_evaluated(&mut self) {
        self.set_lists(Lists::Ready);
    }

    /// Whether the body arrays lag the packed pair records.
    pub(crate) fn bodies_lag(&self) -> bool {
        matches!(
            self,
            StepPhase::FirstHalfDone {
                bodies_lag: true,
                ..
            }
        )
    }

    /// The body arrays are current again.
    pub(crate) fn bodies_caught_up(&mut self) {
        if let StepPhase::FirstHalfDone { bodies_lag, .. } = self {
            *bodies_lag = false;
        }
    }

    /// Whether the first half of the current step is done.
    pub(crate) fn first_half_done(&self) -> bool {
        matches!(self, StepPhase::FirstHalfDone { .. })
    }

    /// Leaves the fused first half, if one is done: the world goes on at
    /// the step's boundary state; returns whether a sphere then moved more
    /// than half the skin, and whether the bodies lag.
    pub(crate) fn take_first_half(&mut self) -> Option<(bool, bool)> {
        match *self {
            StepPhase::FirstHalfDone {
                moved_out,
                bodies_lag,
                lists,
            } => {
                *self = StepPhase::Boundary(lists);
                Some((moved_out, bodies_lag))
            }
            StepPhase::Boundary(_) => None,
        }
    }

    /// The first half of the next step is done (fused into the gather).
    pub(crate) fn first_half_fused(&mut self, moved_out: bool, bodies_lag: bool) {
        *self = StepPhase::FirstHalfDone {
            moved_out,
            bodies_lag,
            lists: self.lists(),
        };
    }
}
