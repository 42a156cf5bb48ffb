//! Trajectory rows of a world split over MPI ranks: each rank formats the
//! rows of the tracked bodies it owns (its region's, when the world is
//! whole at the event), sends them to rank 0 only, and rank 0 appends them
//! to the files. A body is owned by one rank, so every file gets one
//! process's row; the world is not gathered.

use super::error::rt;
use super::{RunError, Runner};
use crate::trajectory::TrajectoryWriter;
use clump_core::world::World;

impl Runner {
    /// True when this run's trajectory rows are gathered from the ranks
    /// that own the tracked bodies (a world split over several ranks).
    pub(super) fn trajectory_in_pieces(&self) -> bool {
        self.world.part_info().is_some_and(|p| p.size > 1)
    }
}

/// Writes the tracked bodies' rows at the world's time (a collective call
/// on a partitioned world: every rank makes it; rank 0 writes); one
/// process writes its rows directly.
pub(super) fn write_rows(world: &mut World, tw: &mut TrajectoryWriter) -> Result<(), RunError> {
    let Some(mask) = world.piece_mask() else {
        return tw.write(world).map_err(rt("cannot write trajectories"));
    };
    let rows = tw.rows(world, Some(&mask));
    let bytes = postcard::to_stdvec(&rows)
        .map_err(|e| RunError::Runtime(format!("cannot encode trajectory rows: {e}")))?;
    let Some(all) = world.gather_to_root(bytes) else {
        return Ok(());
    };
    for (rank, b) in all.iter().enumerate() {
        let rows: Vec<(u32, String)> = postcard::from_bytes(b).map_err(|e| {
            RunError::Runtime(format!("rank {rank} sent unreadable trajectory rows: {e}"))
        })?;
        tw.append_rows(&rows)
            .map_err(rt("cannot write trajectories"))?;
    }
    Ok(())
}
