//! A world split over ranks at an event: whether it is split, keeping it
//! split through an event whose boundary work needs only each rank's part
//! (a checkpoint in pieces, `crate::state_pieces`), gathering it whole,
//! and a gather of small values for the driver.

use super::join;
use crate::step::StepError;
use crate::world::World;

impl World {
    /// True while this world holds a rank's part only (between events of a
    /// world split over ranks, and at events that keep it split).
    pub fn is_split(&self) -> bool {
        self.part.as_ref().is_some_and(|p| p.local)
    }

    /// Asks the next [`World::advance`] of a world split over ranks to end
    /// its event with the world still split (no gather of the whole world,
    /// and the step before the event a rank's step): for an event whose
    /// boundary work needs only each rank's part, such as a checkpoint
    /// written in pieces ([`World::save_rank_piece`]). Taken by that call;
    /// without a partition, nothing.
    pub fn keep_split_at_next_event(&mut self, on: bool) {
        if let Some(p) = self.part.as_mut() {
            p.stay_split = on;
        }
    }

    /// Gathers the whole world on every rank when it is split (the run's
    /// end, before files that hold every body); otherwise nothing.
    pub fn make_whole(&mut self) -> Result<(), StepError> {
        if self.is_split() {
            join::join(self)?;
        }
        Ok(())
    }

    /// Every rank's `mine`, in rank order, on every rank (a collective
    /// call: every rank makes it); `[mine]` without a partition.
    pub fn gather_from_ranks(&mut self, mine: &[u8]) -> Vec<Vec<u8>> {
        match self.part.as_mut() {
            Some(p) => {
                p.traffic.reductions += 1;
                p.comm.all_gather(mine)
            }
            None => vec![mine.to_vec()],
        }
    }

    /// Per body of this world, whether this rank writes it to a frame in
    /// pieces (one piece per rank, every body in exactly one): its owned
    /// bodies while the world is split; while it is whole, the bodies
    /// whose wrapped centre of mass lies in this rank's region of the last
    /// balance (the same function of the same bits on every rank). `None`
    /// without a partition.
    pub fn piece_mask(&self) -> Option<Vec<bool>> {
        let p = self.part.as_ref()?;
        if p.local {
            return Some(p.owned.clone());
        }
        let (me, d) = (p.comm.rank(), &self.config.domain);
        Some(
            self.bodies
                .position
                .iter()
                .map(|&x| p.regions.owner(d.wrap(x)) == me)
                .collect(),
        )
    }

    /// Every rank's `mine` on rank 0, in rank order (a collective call,
    /// point to point: the other ranks receive nothing); `None` on the
    /// other ranks; `[mine]` without a partition.
    pub fn gather_to_root(&mut self, mine: Vec<u8>) -> Option<Vec<Vec<u8>>> {
        let Some(p) = self.part.as_mut() else {
            return Some(vec![mine]);
        };
        p.traffic.reductions += 1;
        let (me, n) = (p.comm.rank(), p.comm.size());
        if me == 0 {
            let from: Vec<usize> = (1..n).collect();
            let mut all = vec![mine];
            all.extend(p.comm.exchange(&[], &from));
            Some(all)
        } else {
            p.comm.exchange(&[(0, mine)], &[]);
            None
        }
    }

    /// This rank's owned bodies with everything that travels with them.
    pub(crate) fn owned_part(&self) -> join::Owned {
        join::owned(self)
    }
}
