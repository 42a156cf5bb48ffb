//! The stages of a world split over ranks (see [`crate::partition`]): keep a
//! rank's part of the whole world ([`restrict`]), gather the whole world
//! ([`join`]), rebuild the parts between neighbours ([`migrate`]), refresh
//! ghosts and sum statistics after each step ([`ghosts`]), the walls' heat
//! flows ([`heat`]), keep the world split through an event or gather it
//! ([`split`]), insert bodies into a split world ([`insert`]), take a
//! rank's share of a checkpoint in pieces ([`share`]), reduce outputs'
//! partial results over the ranks ([`reduce`]).

pub(crate) mod cost;
pub(crate) mod ghosts;
pub(crate) mod heat;
pub(crate) mod insert;
pub(crate) mod join;
pub(crate) mod migrate;
pub(crate) mod reduce;
pub(crate) mod restrict;
pub(crate) mod share;
pub(crate) mod split;
pub(crate) mod step_stats;
pub(crate) mod thermo;
pub(crate) mod tree;

use crate::partition::{Comm, Part, PartInfo, Regions, Traffic};
use crate::world::World;

impl World {
    /// Splits this world over the ranks of `comm`: from now on every
    /// [`World::advance`] steps this rank's part only, and hands the whole
    /// world back at its end. Call on every rank with the same world (the
    /// scenario built alike on each).
    ///
    /// Heat runs split too: ghosts carry their owners' temperatures and
    /// the walls' heat flows are summed in one process's order (T-94).
    pub fn partition(&mut self, comm: Box<dyn Comm>) {
        let size = comm.size();
        self.part = Some(Box::new(Part {
            comm,
            regions: Regions::single(&self.config.domain, size),
            local: false,
            owned: Vec::new(),
            order: Vec::new(),
            send: Vec::new(),
            recv: Vec::new(),
            halo: 0.0,
            stay_split: false,
            stop: (false, None),
            traffic: Traffic::default(),
        }));
    }

    /// This rank and the number of ranks, the halo and traffic, when the
    /// world is partitioned.
    pub fn part_info(&self) -> Option<PartInfo> {
        self.part.as_ref().map(|p| PartInfo {
            rank: p.comm.rank(),
            size: p.comm.size(),
            halo: p.halo,
            traffic: p.traffic,
        })
    }

    /// True on the rank that writes files (rank 0, or an unpartitioned world).
    pub fn is_root(&self) -> bool {
        self.part.as_ref().map_or(true, |p| p.comm.rank() == 0)
    }

    /// True on every rank when any rank's `flag` is (a no-op without a partition).
    pub fn any_rank(&mut self, flag: bool) -> bool {
        self.any_ranks([flag])[0]
    }

    /// Each flag or-ed over the ranks, in one reduction.
    pub fn any_ranks<const N: usize>(&mut self, flags: [bool; N]) -> [bool; N] {
        match self.part.as_mut() {
            Some(p) => {
                p.traffic.reductions += 1;
                let t = std::time::Instant::now();
                let mine = flags.map(|f| f as u8);
                let all = p.comm.all_gather(&mine);
                p.traffic.reduce_seconds += t.elapsed().as_secs_f64();
                std::array::from_fn(|k| all.iter().any(|m| m[k] != 0))
            }
            None => flags,
        }
    }
}
