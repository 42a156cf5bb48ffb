//! Neighbour-list rebuild: wrap periodic centres of mass, drop bodies that
//! left the domain, Morton-sort the bodies, rebuild the sphere topology and
//! the pair list (history carried by global sphere ids).

use super::kinematics::update_spheres;
use super::StepError;
use crate::contact::ContactHistory;
use crate::neighbor::pairs::BuildInput;
use crate::neighbor::{sort, CellGrid};
use crate::sphere::sphere_gid;
use crate::wall::{WallTouch, MAX_TOUCHES_PER_WALL};
use crate::world::{World, WALL_SLOTS};

/// Rebuilds the neighbour list. With `reorganize`, bodies are first wrapped,
/// filtered and re-sorted (this is what a normal rebuild does); without, the
/// list is rebuilt from the stored reference poses only (used on restart so
/// that a resumed run matches an uninterrupted one bit for bit).
pub fn rebuild(w: &mut World, reorganize: bool) -> Result<(), StepError> {
    let min_cell = 2.0 * w.max_radius() + w.skin();
    if reorganize {
        w.pairs.save_history(&w.spheres.gid, &mut w.history_map);
        let domain = w.config.domain;
        let n = w.bodies.len();
        let keep = &mut w.scratch_keep;
        keep.clear();
        keep.resize(n, true);
        for b in 0..n {
            let x = w.bodies.position[b];
            if domain.is_outside(x) {
                keep[b] = false;
            } else {
                w.bodies.position[b] = domain.wrap(x);
            }
        }
        let grid =
            CellGrid::new(&domain, &w.bodies.position, min_cell).map_err(StepError::Neighbor)?;
        sort::morton_order(
            &grid,
            &w.bodies.position,
            &w.bodies.id,
            &w.scratch_keep,
            &mut w.scratch_perm,
            &mut w.scratch_keys,
        );
        w.lost_bodies += (n - w.scratch_perm.len()) as u64;
        // carry wall-contact slots along with their spheres; bodies added
        // since the last build (indices ≥ old count) start with empty slots
        let old_n = w.spheres.body_first.len().saturating_sub(1);
        std::mem::swap(&mut w.wall_key, &mut w.scratch_wall_key);
        std::mem::swap(&mut w.wall_hist, &mut w.scratch_wall_hist);
        w.wall_key.clear();
        w.wall_hist.clear();
        let (old_key, old_hist) = (&w.scratch_wall_key, &w.scratch_wall_hist);
        for &ob in &w.scratch_perm {
            let ob = ob as usize;
            if ob < old_n {
                let r = w.spheres.of_body(ob);
                w.wall_key.extend_from_slice(&old_key[r.clone()]);
                w.wall_hist.extend_from_slice(&old_hist[r]);
            } else {
                let t = w.bodies.template[ob] as usize;
                let ns = (w.template_first[t + 1] - w.template_first[t]) as usize;
                w.wall_key
                    .extend(std::iter::repeat([0; WALL_SLOTS]).take(ns));
                w.wall_hist
                    .extend(std::iter::repeat([ContactHistory::default(); WALL_SLOTS]).take(ns));
            }
        }
        w.bodies
            .permute_into(&w.scratch_perm, &mut w.scratch_bodies);
        std::mem::swap(&mut w.bodies, &mut w.scratch_bodies);
        rebuild_sphere_topology(w);
        update_spheres(w);
        w.reference_pose.clear();
        w.reference_pose.extend(
            w.bodies
                .position
                .iter()
                .zip(&w.bodies.orientation)
                .map(|(&x, &q)| (x, q)),
        );
        w.reference_position.clear();
        w.reference_position.extend(w.spheres.positions());
        w.topology_dirty = false;
    } else {
        // positions at the last build, recomputed from the stored poses
        rebuild_sphere_topology(w);
        let current: Vec<_> = w
            .bodies
            .position
            .iter()
            .zip(&w.bodies.orientation)
            .map(|(&x, &q)| (x, q))
            .collect();
        for (b, &(x, q)) in w.reference_pose.iter().enumerate() {
            w.bodies.position[b] = x;
            w.bodies.orientation[b] = q;
        }
        update_spheres(w);
        w.reference_position.clear();
        w.reference_position.extend(w.spheres.positions());
        for (b, (x, q)) in current.into_iter().enumerate() {
            w.bodies.position[b] = x;
            w.bodies.orientation[b] = q;
        }
        update_spheres(w);
        w.topology_dirty = false;
    }
    w.grid = CellGrid::new(&w.config.domain, &w.reference_position, min_cell)
        .map_err(StepError::Neighbor)?;
    let sp = &w.spheres;
    let inp = BuildInput {
        position: &w.reference_position,
        radius: &sp.radius,
        body: &sp.body,
        gid: &sp.gid,
        skin: w.skin(),
    };
    w.pairs
        .build(&w.grid, &w.config.domain, &inp, &w.history_map);
    w.history_map.clear();
    build_wall_lists(w);
    w.rebuilds += 1;
    Ok(())
}

/// The wall Verlet list: for every sphere, which of the first 64 walls lie
/// within its radius plus the skin at its reference position. Until the next
/// rebuild a sphere moves less than half the skin, so a wall that has not
/// moved meanwhile and was not near cannot touch it ([`World::wall_cull`]
/// says which walls stayed put). Skipping such walls is exact: it removes
/// only tests that would find no contact.
fn build_wall_lists(w: &mut World) {
    use rayon::prelude::*;
    let skin = w.skin();
    let (walls, meshes) = (&w.walls, &w.meshes);
    let (pos, rad) = (&w.reference_position, &w.spheres.radius);
    w.wall_near.resize(pos.len(), 0);
    w.wall_near
        .par_iter_mut()
        .enumerate()
        .with_min_len(1024)
        .for_each(|(s, near)| {
            let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
            let mut m = 0u64;
            for (wi, wall) in walls.iter().enumerate().take(64) {
                if wall.shape.contacts(meshes, pos[s], rad[s], skin, &mut buf) > 0 {
                    m |= 1 << wi;
                }
            }
            *near = m;
        });
    w.wall_cull = static_walls(walls);
    let sp = &w.spheres;
    w.body_cost.clear();
    w.body_cost.push(0);
    let mut total = 0u64;
    for b in 0..w.bodies.len() {
        for s in sp.of_body(b) {
            total += if w.wall_near[s] != 0 {
                WALL_SPHERE_COST
            } else {
                1
            };
        }
        w.body_cost.push(total);
    }
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

/// Recomputes the per-sphere topology arrays from the bodies (storage order).
pub(crate) fn rebuild_sphere_topology(w: &mut World) {
    let sp = &mut w.spheres;
    sp.body.clear();
    sp.index_in_template.clear();
    sp.gid.clear();
    sp.radius.clear();
    sp.material.clear();
    sp.body_first.clear();
    for (b, (&t, &id)) in w.bodies.template.iter().zip(&w.bodies.id).enumerate() {
        sp.body_first.push(sp.body.len() as u32);
        let (s0, s1) = (
            w.template_first[t as usize],
            w.template_first[t as usize + 1],
        );
        for k in 0..(s1 - s0) {
            sp.body.push(b as u32);
            sp.index_in_template.push(k);
            sp.gid.push(sphere_gid(id, k));
            sp.radius.push(w.template_radius[(s0 + k) as usize]);
            sp.material.push(w.template_material[t as usize]);
        }
    }
    sp.body_first.push(sp.body.len() as u32);
    let n = sp.body.len();
    sp.state.resize(n, Default::default());
    for (s, st) in sp.state.iter_mut().enumerate() {
        st.radius = sp.radius[s];
    }
    sp.single_material = match sp.material.first() {
        Some(&m) if sp.material.iter().all(|&x| x == m) => Some(m),
        _ => None,
    };
    w.wall_key.resize(n, [0; WALL_SLOTS]);
    w.wall_hist
        .resize(n, [ContactHistory::default(); WALL_SLOTS]);
}
