//! Insertion into a world split over ranks, without gathering it: the
//! spheres a candidate is checked against come from the ranks that own
//! them, near the insertion region only; every rank then draws the same
//! candidates from the same stream and accepts the same ones (the free-space
//! test is a set query, so the order of the gathered spheres changes no
//! answer); every rank counts every new body's id, and only the rank whose
//! region holds a new body's centre of mass keeps it. The next
//! [`World::advance`] then rebuilds the parts (the new bodies migrate to
//! their owners and the halo ranks' ghosts) and evaluates the forces of the
//! new state on each part (`World::prepare_split`), as one process's
//! `World::prepare` does on the whole world: the first kick of the new
//! bodies is one process's, bit for bit.

use crate::step::kinematics::{rebuild_sphere_topology, update_spheres};
use crate::step::StepError;
use crate::world::World;
use glam::DVec3;

/// f64 values per gathered sphere: centre (world frame, m) and radius (m).
const SPHERE_LEN: usize = 4;

impl World {
    /// Every rank's owned spheres (world-frame centre, radius; m) for which
    /// `near` holds, on every rank (a collective call), from the bodies'
    /// poses as one process's insertion computes them. Without a split
    /// world: this world's spheres for which `near` holds.
    pub(crate) fn spheres_near(&mut self, near: impl Fn(DVec3) -> bool) -> Vec<(DVec3, f64)> {
        let b = &self.bodies;
        let owned = self.part.as_ref().filter(|p| p.local).map(|p| &p.owned);
        let mut mine = Vec::new();
        for i in 0..b.len() {
            if owned.is_some_and(|o| !o[i]) {
                continue;
            }
            let t = &self.templates[b.template[i] as usize];
            let (x, q) = (b.position[i], b.orientation[i]);
            for s in &t.spheres {
                let c = x + q * s.center;
                if near(c) {
                    mine.push((c, s.radius));
                }
            }
        }
        if owned.is_none() {
            return mine;
        }
        let mut bytes = Vec::with_capacity(mine.len() * SPHERE_LEN * 8);
        for (c, r) in &mine {
            for x in [c.x, c.y, c.z, *r] {
                bytes.extend_from_slice(&x.to_le_bytes());
            }
        }
        let p = self.part.as_mut().expect("a split world");
        p.traffic.reductions += 1;
        let all = p.comm.all_gather(&bytes);
        let mut out = Vec::new();
        for m in &all {
            for s in m.chunks_exact(SPHERE_LEN * 8) {
                let f = |k: usize| f64::from_le_bytes(s[8 * k..8 * k + 8].try_into().expect("8"));
                out.push((DVec3::new(f(0), f(1), f(2)), f(3)));
            }
        }
        out
    }

    /// Whether this rank keeps a body added at `x` (world frame, m) with
    /// id `id` while the world is split: the rank whose region holds its
    /// wrapped centre of mass keeps it as owned (it has a place after every
    /// body of the last build, in id order). True without a split world.
    pub(crate) fn keeps_new_body(&mut self, x: DVec3, id: u64) -> bool {
        let domain = self.config.domain;
        let Some(p) = self.part.as_mut().filter(|p| p.local) else {
            return true;
        };
        if p.regions.owner(domain.wrap(x)) != p.comm.rank() {
            return false;
        }
        p.owned.push(true);
        p.order.push((u64::MAX, id));
        true
    }

    /// After bodies were added to a split world: the part's spheres follow
    /// its bodies (the new ones appended), at their poses, with their build
    /// poses, so that a
    /// checkpoint piece, a gather or a frame sees them before the next
    /// [`World::advance`] places them on their ranks. Nothing on a whole
    /// world, whose next step rebuilds it as one process does.
    pub fn settle_inserted(&mut self) {
        if self.is_split() && self.spheres.body_first.len() != self.bodies.len() + 1 {
            rebuild_sphere_topology(self);
            update_spheres(self);
            // the new bodies' build poses are where they start
            let b = &self.bodies;
            let from = self.neighbors.reference_pose.len();
            self.neighbors
                .reference_pose
                .extend((from..b.len()).map(|i| (b.position[i], b.orientation[i])));
        }
    }
}

impl World {
    /// The forces of the current state of a split world whose bodies or
    /// settings changed at the last boundary (`World::prepare` of one
    /// process, on the parts; a collective call), unless they are current.
    pub(crate) fn prepare_split(&mut self) -> Result<(), StepError> {
        if self.phase.forces_ready() {
            return Ok(());
        }
        prepare_parts(self)
    }
}

/// The parts rebuilt (every body to its owner and the ranks within the
/// halo, as a neighbour rebuild of the ranks does), each part's forces
/// evaluated, the ghosts given their owners' forces and the statistics
/// summed over the ranks.
fn prepare_parts(w: &mut World) -> Result<(), StepError> {
    w.settle_inserted();
    w.props_changed();
    w.refresh_props();
    super::migrate::rebuild(w)?;
    w.props_changed();
    w.refresh_props();
    crate::step::gather::compute(w);
    super::ghosts::refresh(w);
    super::step_stats::reduce(w).map_err(|e| StepError::Neighbor(format!("partition: {e}")))?;
    w.phase.forces_evaluated();
    Ok(())
}
