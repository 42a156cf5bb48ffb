//! Keeping this rank's part of the whole world at a neighbour build: its
//! owned bodies and their ghosts, in the whole world's order, and the lists
//! of who sends whose state after each step.

use crate::neighbor::grid::Extent;
use crate::neighbor::CellGrid;
use crate::partition::Regions;
use crate::step::kinematics::rebuild_sphere_topology;
use crate::step::kinematics::spheres_at_reference_poses;
use crate::step::StepError;
use crate::world::World;
use glam::DVec3;

/// Largest distance from a template's centre of mass to the far side of one
/// of its spheres, over all templates, m.
fn largest_extent(w: &World) -> f64 {
    let t = &w.templates;
    t.offset
        .iter()
        .zip(&t.radius)
        .map(|(o, &r)| o.length() + r)
        .fold(0.0, f64::max)
}

/// The halo of a build: a candidate pair's centres of mass are at most
/// `2 R_max + skin` apart (the pair list keeps spheres within
/// `r_i + r_j + skin`, and each sphere lies within `R_max − r` of its
/// centre); a relative margin of 1e-9 covers the rounding of the distances.
pub(crate) fn halo(w: &World) -> f64 {
    (2.0 * largest_extent(w) + w.skin()) * (1.0 + 1e-9)
}

/// The wrapped build positions of the bodies' centres of mass (world
/// frame, m), on which regions and roles are decided.
pub(crate) fn build_positions(w: &World) -> Vec<DVec3> {
    let domain = &w.config.domain;
    let pose = &w.neighbors.reference_pose;
    pose.iter().map(|&(x, _)| domain.wrap(x)).collect()
}

/// Keeps this rank's part of a whole world whose sphere topology is
/// current and whose spheres are at their reference poses: balances the
/// regions on the bodies' build positions, keeps the owned bodies and the
/// ghosts (in the whole world's order), filters `carry` (per sphere of the whole
/// world, the wall-list entry it continues) alike, places the spheres at
/// their reference poses, and records the ghost lists. Returns the
/// whole world's pair grid, on which the part's pair list is built.
pub(crate) fn restrict(
    w: &mut World,
    min_cell: f64,
    carry: &mut Vec<u32>,
) -> Result<CellGrid, StepError> {
    // the spheres are at their reference poses (the build's)
    let domain = w.config.domain;
    let extent = Extent::of_points(&domain, w.spheres.state.iter().map(|s| s.position));
    let grid = CellGrid::from_extent(&domain, &extent, min_cell).map_err(StepError::Neighbor);
    let Some(mut part) = w.part.take() else {
        return grid;
    };
    let grid = grid?;
    let (me, size) = (part.comm.rank(), part.comm.size());
    let at = build_positions(w);
    let cost = super::cost::body_costs(w);
    part.regions = Regions::balance(&domain, &at, &cost, size);
    let first = &w.spheres.body_first;
    part.halo = halo(w);
    let roles = Roles::of(&part.regions, part.halo, me, size, &at);
    let perm = roles.keep.clone();
    part.order.clear();
    part.order.extend(perm.iter().map(|&b| (b as u64, 0)));
    let kept_carry: Vec<u32> = perm
        .iter()
        .flat_map(|&b| carry[first[b as usize] as usize..first[b as usize + 1] as usize].iter())
        .copied()
        .collect();
    *carry = kept_carry;
    w.bodies.permute_into(&perm, &mut w.scratch.bodies);
    std::mem::swap(&mut w.bodies, &mut w.scratch.bodies);
    let pose: Vec<_> = perm
        .iter()
        .map(|&b| w.neighbors.reference_pose[b as usize])
        .collect();
    w.neighbors.reference_pose = pose;
    rebuild_sphere_topology(w);
    // the part's spheres at the build poses, as a restart places them (the
    // rebuild puts them back at the current poses after the lists)
    spheres_at_reference_poses(w);
    roles.install(&mut part);
    part.local = true;
    w.part = Some(part);
    Ok(grid)
}

/// What each body of a rank's part is to it: kept (owned or ghost), and for
/// the kept ones who sends whose state after each step.
pub(crate) struct Roles {
    /// The bodies kept (indices into the positions given), ascending.
    pub keep: Vec<u32>,
    /// Per kept body: owned here.
    pub owned: Vec<bool>,
    /// Per rank, the kept owned bodies (indices among the kept) it holds as ghosts.
    pub send: Vec<Vec<u32>>,
    /// Per rank, the kept ghosts (indices among the kept) it owns.
    pub recv: Vec<Vec<u32>>,
}

impl Roles {
    /// The roles for rank `me` of bodies at `at` (wrapped build positions of
    /// their centres of mass, in storage order).
    pub fn of(regions: &Regions, halo: f64, me: usize, size: usize, at: &[DVec3]) -> Roles {
        let mut r = Roles {
            keep: Vec::new(),
            owned: Vec::new(),
            send: vec![Vec::new(); size],
            recv: vec![Vec::new(); size],
        };
        let mut near = Vec::new();
        for (b, &x) in at.iter().enumerate() {
            let owner = regions.owner(x);
            regions.near(x, halo, &mut near);
            let local = r.keep.len() as u32;
            if owner == me {
                for &k in near.iter().filter(|&&k| k != me) {
                    r.send[k].push(local);
                }
            } else if near.contains(&me) {
                r.recv[owner].push(local);
            } else {
                continue;
            }
            r.keep.push(b as u32);
            r.owned.push(owner == me);
        }
        r
    }

    /// Stores the owned flags and the ghost lists in the part.
    pub fn install(self, part: &mut crate::partition::Part) {
        let lists = |v: Vec<Vec<u32>>| -> Vec<(usize, Vec<u32>)> {
            v.into_iter()
                .enumerate()
                .filter(|(_, l)| !l.is_empty())
                .collect()
        };
        part.owned = self.owned;
        part.send = lists(self.send);
        part.recv = lists(self.recv);
    }
}
