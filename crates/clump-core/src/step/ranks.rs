//! The step's hooks for a world split over ranks ([`crate::partition`]):
//! what the ranks exchange at the stages of [`World::take_step`]. Each is
//! called only for a partitioned world.

use super::partition::{ghosts, migrate, step_stats};
use super::{rebuild, StepError};
use crate::world::World;

impl World {
    /// Before the first half: at an event the world is whole; the rank
    /// keeps its part of it (a restart's rebuild from the build poses, bit
    /// for bit). A whole world with new bodies takes its first half whole,
    /// as one process does, and is split at the rebuild that follows.
    pub(super) fn keep_rank_part(&mut self) -> Result<(), StepError> {
        let local = self.part.as_ref().is_some_and(|p| p.local);
        if local || self.phase.topology_dirty() {
            return Ok(());
        }
        if !self.neighbors.history_pending {
            self.neighbors.pairs.save_history(
                &self.spheres.gid,
                self.contact_table.any_reach(),
                &mut self.neighbors.history_map,
            );
            self.neighbors
                .pairs
                .save_slip(&self.spheres.gid, &mut self.neighbors.slip_map);
        }
        rebuild::rebuild(self, false)?;
        self.rebuilds = self.rebuilds.saturating_sub(1);
        Ok(())
    }

    /// The neighbour rebuild of a rank: its bodies move to their new ranks
    /// (neighbours only), or a whole world (new bodies) is rebuilt whole and
    /// split. The gather then kicks this rank's bodies as they are now.
    pub(super) fn migrate(&mut self) -> Result<(), StepError> {
        if self.part.as_ref().is_some_and(|p| p.local) {
            migrate::rebuild(self)?;
        } else {
            rebuild::rebuild(self, true)?;
        }
        self.props_changed();
        self.refresh_props();
        Ok(())
    }

    /// After the gather: the ghosts take their owners' new state, and the
    /// statistics, wall loads and walls' heat flows are summed over the
    /// ranks.
    pub(super) fn exchange_after_gather(&mut self) -> Result<(), StepError> {
        if self.part.is_none() {
            return Ok(());
        }
        let t = std::time::Instant::now();
        ghosts::refresh(self);
        let t1 = std::time::Instant::now();
        let reduced = step_stats::reduce(self);
        if let Some(p) = self.part.as_mut() {
            p.traffic.ghost_seconds += (t1 - t).as_secs_f64();
            p.traffic.reduce_seconds += t1.elapsed().as_secs_f64();
        }
        reduced.map_err(|e| StepError::Neighbor(format!("partition: {e}")))?;
        if self.heat.is_some() {
            super::partition::heat::reduce(self);
        }
        Ok(())
    }
}
