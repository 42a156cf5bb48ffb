//! A rank's share of a checkpoint in pieces (`crate::state_share`) made
//! its part of the split world without the whole world: the lists are built
//! as a whole restart (`rebuild(w, false)`) and its split (`restrict`)
//! build them, from the build poses on the whole world's grid, whose
//! extent is reduced over the ranks (min, max and integer counts, which no
//! order changes).

use super::restrict::{build_positions, halo, Roles};
use crate::neighbor::grid::Extent;
use crate::neighbor::CellGrid;
use crate::step::kinematics::{
    rebuild_sphere_topology, spheres_at_reference_poses, update_spheres,
};
use crate::step::rebuild::{build_pair_list, build_wall_lists};
use crate::step::StepError;
use crate::world::World;

impl World {
    /// The halo of a rank's part with this world's templates and skin.
    pub(crate) fn share_halo(&self) -> f64 {
        halo(self)
    }

    /// See [`keep_share`].
    pub(crate) fn keep_rank_share(&mut self, order: Vec<(u64, u64)>) -> Result<(), StepError> {
        keep_share(self, order)
    }
}

/// Makes the share this world holds (owned bodies and ghosts of this
/// rank, in the whole world's storage order, `order` their places in it)
/// the rank's part, with its lists built at the build poses.
fn keep_share(w: &mut World, order: Vec<(u64, u64)>) -> Result<(), StepError> {
    let err = |m: String| StepError::Neighbor(format!("partition: {m}"));
    rebuild_sphere_topology(w);
    spheres_at_reference_poses(w);
    w.phase.lists_built();
    let ns = w.spheres.len();
    w.neighbors
        .wall_list
        .live_entries(ns, &mut w.scratch.wall_carry);
    let domain = w.config.domain;
    let mut part = w.part.take().expect("a partitioned world");
    let (me, size) = (part.comm.rank(), part.comm.size());
    part.halo = halo(w);
    let at = build_positions(w);
    let roles = Roles::of(&part.regions, part.halo, me, size, &at);
    // the whole world's sphere extent: each sphere is owned by one rank
    let first = &w.spheres.body_first;
    let owned_spheres = roles
        .owned
        .iter()
        .enumerate()
        .filter(|(_, &o)| o)
        .flat_map(|(b, _)| first[b] as usize..first[b + 1] as usize);
    let mut mine = Extent::empty();
    for s in owned_spheres {
        mine.add(&domain, w.spheres.state[s].position);
    }
    part.traffic.reductions += 1;
    let bytes = postcard::to_stdvec(&mine).map_err(|e| err(format!("encoding: {e}")))?;
    let mut whole = Extent::empty();
    for (r, b) in part.comm.all_gather(&bytes).iter().enumerate() {
        let e: Extent =
            postcard::from_bytes(b).map_err(|e| err(format!("extent from rank {r}: {e}")))?;
        whole.merge(&e);
    }
    if roles.keep.len() != at.len() {
        w.part = Some(part);
        return Err(err(format!(
            "rank {me} read {} bodies that are neither its own nor its ghosts",
            at.len() - roles.keep.len()
        )));
    }
    let min_cell = 2.0 * w.max_radius() + w.skin();
    let grid = CellGrid::from_extent(&domain, &whole, min_cell);
    part.order = order;
    roles.install(&mut part);
    part.local = true;
    w.part = Some(part);
    w.neighbors.grid = grid.map_err(StepError::Neighbor)?;
    build_pair_list(w);
    build_wall_lists(w);
    update_spheres(w);
    w.rebuilds += 1;
    Ok(())
}
