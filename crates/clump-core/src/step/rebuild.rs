//! Neighbour-list rebuild: wrap periodic centres of mass, drop bodies that
//! left the domain, sort the bodies by cell (`neighbor::sort`), rebuild
//! the sphere topology and the pair list (history carried by global sphere
//! ids).

use super::kinematics::{rebuild_sphere_topology, spheres_at_reference_poses, update_spheres};
use super::StepError;
use crate::neighbor::carry::{old_body_index, NONE};
use crate::neighbor::pairs::BuildInput;
use crate::neighbor::walls::NO_ENTRY;
use crate::neighbor::{sort, CellGrid};
use crate::world::World;

/// Rebuilds the neighbour list. With `reorganize`, bodies are first wrapped,
/// filtered and re-sorted (this is what a normal rebuild does); without, the
/// list is rebuilt from the stored reference poses only (used on restart so
/// that a resumed run matches an uninterrupted one bit for bit).
pub fn rebuild(w: &mut World, reorganize: bool) -> Result<(), StepError> {
    w.scratch.carry.active = false;
    if reorganize {
        adapt_skin(w);
        w.neighbors.built_step = w.step;
    }
    let min_cell = 2.0 * w.max_radius() + w.skin();
    if reorganize {
        // a world joined from its ranks holds its histories in the map; a
        // rank's part is re-sorted once more below (restrict), so its
        // histories go by global id too; otherwise they are carried by
        // storage index (neighbor::carry)
        if !w.neighbors.history_pending {
            let keep_live = w.contact_table.any_reach();
            if w.part.is_some() {
                w.neighbors.pairs.save_history(
                    &w.spheres.gid,
                    keep_live,
                    &mut w.neighbors.history_map,
                );
                w.neighbors
                    .pairs
                    .save_slip(&w.spheres.gid, &mut w.neighbors.slip_map);
            } else {
                w.neighbors
                    .pairs
                    .save_carry(&mut w.scratch.carry, &w.spheres, keep_live);
            }
        }
        let domain = w.config.domain;
        let n = w.bodies.len();
        let keep = &mut w.scratch.keep;
        keep.clear();
        keep.resize(n, true);
        for b in 0..n {
            let x = w.bodies.position[b];
            if let Some(cause) = domain.exit_cause(x) {
                keep[b] = false;
                w.lost.record(cause);
            } else {
                w.bodies.position[b] = domain.wrap(x);
            }
        }
        let grid =
            CellGrid::new(&domain, &w.bodies.position, min_cell).map_err(StepError::Neighbor)?;
        sort::spatial_order(
            &grid,
            &w.bodies.position,
            &w.bodies.id,
            &w.scratch.keep,
            &mut w.scratch.perm,
            &mut w.scratch.keys,
        );
        // each body of the new order in the last build's sphere topology
        old_body_index(
            &w.spheres,
            &w.bodies.id,
            &w.scratch.perm,
            &mut w.scratch.old_body,
        );
        // carry wall-contact slots along with their spheres: per sphere in
        // the new order, the entry of the old wall list it continues; bodies
        // added since the last build start empty
        let carry = &mut w.scratch.wall_carry;
        carry.clear();
        for (&cur, &ob) in w.scratch.perm.iter().zip(&w.scratch.old_body) {
            if ob != NONE {
                w.neighbors
                    .wall_list
                    .append_live_entries(w.spheres.of_body(ob as usize), carry);
            } else {
                let t = w.bodies.template[cur as usize] as usize;
                let ns = (w.templates.first[t + 1] - w.templates.first[t]) as usize;
                carry.extend(std::iter::repeat(NO_ENTRY).take(ns));
            }
        }
        w.bodies
            .permute_into(&w.scratch.perm, &mut w.scratch.bodies);
        std::mem::swap(&mut w.bodies, &mut w.scratch.bodies);
        rebuild_sphere_topology(w);
        if w.scratch.carry.active {
            w.scratch
                .carry
                .map_spheres(&w.scratch.old_body, &w.spheres.body_first);
        }
        references_at_current_poses(w);
    } else {
        // the lists at the positions of the last build, from the stored
        // poses (the spheres go back to the current poses below)
        rebuild_sphere_topology(w);
        spheres_at_reference_poses(w);
        w.phase.lists_built();
        if w.part.is_some() {
            // each sphere continues its own wall slots (filtered below)
            let n = w.spheres.len();
            w.neighbors
                .wall_list
                .live_entries(n, &mut w.scratch.wall_carry);
        }
    }
    // a partitioned world keeps its rank's part here, and builds its lists
    // on the whole world's grid
    let partitioned = w.part.is_some();
    let mut carry = std::mem::take(&mut w.scratch.wall_carry);
    let grid = super::partition::restrict::restrict(w, min_cell, &mut carry);
    w.scratch.wall_carry = carry;
    w.neighbors.grid = grid?;
    build_pair_list(w);
    if reorganize || partitioned {
        build_wall_lists(w);
    } else {
        // the spheres kept their order: each continues its own slots
        refresh_wall_list(w);
    }
    if !reorganize || partitioned {
        // the lists were built at the reference poses, which are not the
        // current ones (a restart, a rank's part)
        update_spheres(w);
    }
    w.rebuilds += 1;
    Ok(())
}

/// Makes the current poses the build's: sphere positions from the poses,
/// and these as the reference poses of the skin check.
pub(crate) fn references_at_current_poses(w: &mut World) {
    update_spheres(w);
    w.neighbors.reference_pose.clear();
    w.neighbors.reference_pose.extend(
        w.bodies
            .position
            .iter()
            .zip(&w.bodies.orientation)
            .map(|(&x, &q)| (x, q)),
    );
    w.phase.lists_built();
}

/// Builds the pair list on `w.neighbors.grid` at the spheres' positions,
/// which are those of the reference poses (the build's), each pair
/// continuing its history from the history map (then emptied).
pub(crate) fn build_pair_list(w: &mut World) {
    let sp = &w.spheres;
    let inp = BuildInput {
        state: &sp.state,
        radius: &sp.radius,
        body: &sp.body,
        body_first: &sp.body_first,
        gid: &sp.gid,
        skin: w.skin(),
        rolling: w.contact_table.keeps_rolling_spring(),
        slip: w
            .contact_table
            .keeps_slip_profile()
            .then_some(&w.neighbors.slip_map),
        // a rank's part: no pairs between two of its ghosts
        owned: w.part.as_ref().filter(|p| p.local).map(|p| &p.owned[..]),
    };
    if w.scratch.carry.active {
        w.neighbors.pairs.build_carried(
            &w.neighbors.grid,
            &w.config.domain,
            &inp,
            &w.scratch.carry,
        );
        w.scratch.carry.active = false;
    } else {
        w.neighbors.pairs.build(
            &w.neighbors.grid,
            &w.config.domain,
            &inp,
            &w.neighbors.history_map,
        );
    }
    w.neighbors.history_map.clear();
    w.neighbors.slip_map.clear();
    w.neighbors.history_pending = false;
    w.neighbors.pairs.refresh_bodies(&w.bodies);
}

/// Chooses the skin of the new lists from the motion since the last build
/// (unless the configuration fixes it): the largest displacement of a
/// sphere from its reference position, over the steps since that build
/// ([`crate::neighbor::skin::adapted_skin`]). Keeps the current skin when
/// the spheres' positions do not match the last build (bodies were added
/// or removed since).
fn adapt_skin(w: &mut World) {
    if w.config.skin.is_some() {
        return;
    }
    if w.phase.topology_dirty()
        || w.neighbors.reference_pose.len() != w.bodies.len()
        || w.step <= w.neighbors.built_step
    {
        return;
    }
    let d2 = largest_displacement2(w, 0..w.bodies.len());
    w.neighbors.adapted_skin = w.adapted_skin(d2.sqrt());
}

/// The largest squared distance (m²) of a sphere of `bodies` from where
/// its body's reference pose puts it (the build's position, computed as
/// the build computed it, so the same bits).
pub(crate) fn largest_displacement2(w: &World, bodies: impl Iterator<Item = usize>) -> f64 {
    let (sp, poses) = (&w.spheres, &w.neighbors.reference_pose);
    let (tf, toff) = (&w.templates.first, &w.templates.offset);
    let mut d2 = 0.0f64;
    for b in bodies {
        let (x0, q0) = poses[b];
        let rot0 = glam::DMat3::from_quat(q0);
        let o0 = tf[w.bodies.template[b] as usize] as usize;
        for (k, s) in sp.of_body(b).enumerate() {
            let x_ref = super::kinematics::sphere_position(x0, &rot0, toff[o0 + k]);
            d2 = d2.max(sp.position(s).distance_squared(x_ref));
        }
    }
    d2
}

/// Builds the wall Verlet list ([`crate::neighbor::walls`]) at the
/// spheres' positions, which are those of the reference poses, each sphere
/// continuing the contact slots of the entry `scratch_wall_carry` names in
/// the previous list, and the per-body cost estimate of the gather. Also called between neighbour
/// builds when a wall starts to move (the list must then hold every
/// sphere); that leaves the forces unchanged, as only walls that cannot
/// touch a sphere are ever left out of its entry.
pub(crate) fn build_wall_lists(w: &mut World) {
    std::mem::swap(&mut w.neighbors.wall_list, &mut w.scratch.wall_list);
    w.neighbors.wall_cull = static_walls(&w.walls);
    let low = if w.walls.len() >= 64 {
        u64::MAX
    } else {
        (1u64 << w.walls.len()) - 1
    };
    let skin = w.skin();
    let sp = &w.spheres;
    w.neighbors.wall_list.build(
        &w.walls,
        &w.walls.meshes,
        &sp.state,
        &sp.radius,
        skin,
        !w.neighbors.wall_cull & low,
        &w.scratch.wall_carry,
        &w.scratch.wall_list,
        &sp.body_first,
        w.body_chunk(),
    );
    w.scratch.body_cost.clear();
    w.scratch.body_cost.push(0);
    let list = &w.neighbors.wall_list.sphere;
    let mut e = 0;
    let mut total = 0u64;
    for b in 0..w.bodies.len() {
        let r = sp.of_body(b);
        total += r.len() as u64;
        while e < list.len() && (list[e] as usize) < r.end {
            total += WALL_SPHERE_COST - 1;
            e += 1;
        }
        w.scratch.body_cost.push(total);
    }
}

/// Builds the wall list again, between neighbour builds, when a wall starts
/// to move: at the reference poses, from which the skin check measures
/// (the spheres go there for the build and back to the current poses).
pub(crate) fn wall_started(w: &mut World) {
    spheres_at_reference_poses(w);
    refresh_wall_list(w);
    update_spheres(w);
}

/// Builds the wall list again for spheres that kept their order, each
/// continuing its own slots (see [`build_wall_lists`]); the spheres are at
/// their reference poses.
pub(crate) fn refresh_wall_list(w: &mut World) {
    let n = w.spheres.len();
    w.neighbors
        .wall_list
        .live_entries(n, &mut w.scratch.wall_carry);
    build_wall_lists(w);
}

/// Gather cost of a sphere with a wall nearby (it is tested against the
/// wall, and often touches it), in units of a sphere without: a rough
/// measured ratio, used only to balance threads.
const WALL_SPHERE_COST: u64 = 8;

/// Bits of the walls (< 64) whose geometry does not move (no translation or
/// rotation; a surface velocity leaves the geometry in place).
pub(crate) fn static_walls(walls: &[crate::wall::Wall]) -> u64 {
    let mut m = 0u64;
    for (wi, wall) in walls.iter().enumerate().take(64) {
        if wall.motion.velocity == glam::DVec3::ZERO
            && wall.motion.angular_velocity == glam::DVec3::ZERO
        {
            m |= 1 << wi;
        }
    }
    m
}
