//! A checkpoint of a world split over ranks without gathering it: each rank
//! saves the state of the bodies it owns (with their build poses, wall
//! slots and the histories of the pairs with an owned sphere) as one
//! *piece*; a reader at any rank count keeps its share of them, in one
//! process's storage order, and one process all of them
//! ([`crate::state_share`]).
//!
//! The bodies, build poses, wall slots, pair histories, counters and skin
//! of the state read back are one process's, bit for bit. Its statistics and
//! wall loads are those of the rank's last step: summed per rank, then over
//! the ranks in rank order (the step before such a checkpoint is a rank's
//! step, not a whole one); nothing that follows reads them before the next
//! step recomputes them (the thermo row of that boundary is written before
//! its checkpoint, and a resumed run does not write it again).

use crate::body::Bodies;
use crate::state::WorldState;
use crate::step::StepError;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// One rank's piece of a world's state.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RankPiece {
    /// Per body, its place in the whole world's storage order (a key that
    /// sorts as that order over every rank's pieces of one step).
    pub order: Vec<(u64, u64)>,
    /// The state: the owned bodies and what travels with them, and the
    /// global part (the same on every rank).
    pub state: WorldState,
}

impl WorldState {
    /// The global part of this state (settings, counters, walls, wall
    /// loads, statistics, skin) with no bodies: a split checkpoint's
    /// manifest.
    pub fn into_global(mut self) -> WorldState {
        self.bodies = Bodies::default();
        self.reference_pose = Vec::new();
        self.pair_history = Vec::new();
        self.wall_key = Vec::new();
        self.wall_hist = Vec::new();
        self.pair_slip = Vec::new();
        self.wall_slip = Vec::new();
        self
    }
}

impl World {
    /// This rank's piece of the world's state (the world split over ranks,
    /// at a step boundary): its owned bodies and the global part.
    pub fn save_rank_piece(&mut self) -> Result<RankPiece, StepError> {
        if !self.is_split() {
            return Err(StepError::Neighbor(
                "partition: a rank piece needs a world split over ranks".into(),
            ));
        }
        // as `save_state`: the forces of the state saved (after an insertion)
        self.prepare_split()?;
        let mut o = self.owned_part();
        o.pair_history.sort_by_key(|e| e.0);
        o.pair_slip.sort_by_key(|e| e.0);
        Ok(RankPiece {
            order: o.order,
            state: WorldState {
                bodies: o.bodies,
                reference_pose: o.reference_pose,
                pair_history: o.pair_history,
                wall_key: o.wall_key,
                wall_hist: o.wall_hist,
                pair_slip: o.pair_slip,
                wall_slip: o.wall_slip,
                ..self.global_state()
            },
        })
    }
}
