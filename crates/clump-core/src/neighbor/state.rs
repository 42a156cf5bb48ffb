//! The neighbour state of a world: the candidate pair list with its contact
//! store (tangential and rolling springs per pair), the wall list with its
//! contact slots, the cell grid, and what decides the next rebuild.

use super::grid::CellGrid;
use super::pairs::{HistoryMap, PairList, SlipMap};
use super::walls::WallList;
use crate::contact::record::ContactRecords;
use glam::{DQuat, DVec3};

/// Neighbour lists, the contact store and the rebuild bookkeeping.
#[derive(Default)]
pub(crate) struct NeighborState {
    /// Candidate sphere pairs (half list) and their contact state.
    pub pairs: PairList,
    /// The wall Verlet list: the spheres with a wall to test, and their
    /// sphere–wall contact slots.
    pub wall_list: WallList,
    /// Walls (< 64) that have not moved since the wall list was built: only
    /// these may be left out of a sphere's entry (when one starts to move,
    /// the list is built again).
    pub wall_cull: u64,
    /// The skin (m) the last neighbour build chose for the motion (0: none
    /// yet); used unless the configuration fixes the skin.
    pub adapted_skin: f64,
    /// Step of the last neighbour build.
    pub built_step: u64,
    /// Body poses at the last build (centre of mass, orientation; world
    /// frame, m). The spheres' centres at the build, from which the skin
    /// check measures, follow from these (`step::kinematics`); they are not
    /// stored.
    pub reference_pose: Vec<(DVec3, DQuat)>,
    /// Contact histories carried across a rebuild, keyed by sphere ids.
    pub history_map: HistoryMap,
    /// MDR profiles carried with `history_map` ([`crate::contact::mdr`]).
    pub slip_map: SlipMap,
    /// The histories are in `history_map` and the pair list is not built
    /// (a world joined from its ranks, between an event and its next step).
    pub history_pending: bool,
    /// The cell grid of the last build.
    pub grid: CellGrid,
    /// Per-contact records of the last step asked to keep them.
    pub records: ContactRecords,
}
