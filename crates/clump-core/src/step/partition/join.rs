//! Gathering the ranks' owned bodies into the whole world on every rank, in
//! the whole world's storage order, with their contact histories and wall
//! slots: the world then is what one process would hold at this point.

use crate::body::Bodies;
use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::neighbor::pairs::{HistoryMap, SlipMap};
use crate::neighbor::walls::{WallList, WALL_SLOTS};
use crate::sphere::SPHERE_ID_BITS;
use crate::step::kinematics::rebuild_sphere_topology;
use crate::step::kinematics::update_spheres;
use crate::step::StepError;
use crate::world::World;
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// One rank's owned bodies, as sent to every rank.
#[derive(Serialize, Deserialize, Default)]
pub(crate) struct Owned {
    /// Each body's place in the whole world's storage order.
    pub(crate) order: Vec<(u64, u64)>,
    pub(crate) bodies: Bodies,
    pub(crate) reference_pose: Vec<(DVec3, DQuat)>,
    /// Histories of the pairs with at least one owned sphere.
    pub(crate) pair_history: Vec<((u64, u64), ContactHistory)>,
    /// Wall slots per sphere of the owned bodies, in their order.
    pub(crate) wall_key: Vec<[u32; WALL_SLOTS]>,
    pub(crate) wall_hist: Vec<[ContactHistory; WALL_SLOTS]>,
    /// MDR profiles, as `pair_history` and `wall_hist` (empty when no law
    /// keeps them).
    pub(crate) pair_slip: Vec<((u64, u64), SlipProfile)>,
    pub(crate) wall_slip: Vec<[SlipProfile; WALL_SLOTS]>,
}

/// This rank's owned bodies with everything that travels with them.
pub(crate) fn owned(w: &World) -> Owned {
    let part = w.part.as_ref().expect("a partitioned world");
    let mut out = Owned::default();
    let keep: Vec<u32> = (0..w.bodies.len() as u32)
        .filter(|&b| part.owned[b as usize])
        .collect();
    w.bodies.permute_into(&keep, &mut out.bodies);
    let owned_ids: rustc_hash::FxHashSet<u64> = out.bodies.id.iter().copied().collect();
    let (key, hist) = w.neighbors.wall_list.per_sphere(w.spheres.len());
    let wslip = w
        .neighbors
        .wall_list
        .slip_per_sphere(w.spheres.len(), w.contact_table.keeps_slip_profile());
    for &b in &keep {
        let b = b as usize;
        out.order.push(part.order[b]);
        out.reference_pose.push(w.neighbors.reference_pose[b]);
        let s = w.spheres.of_body(b);
        out.wall_key.extend_from_slice(&key[s.clone()]);
        out.wall_hist.extend_from_slice(&hist[s.clone()]);
        if !wslip.is_empty() {
            out.wall_slip.extend_from_slice(&wslip[s]);
        }
    }
    let mut slips = SlipMap::default();
    w.neighbors.pairs.save_slip(&w.spheres.gid, &mut slips);
    out.pair_slip = slips
        .into_iter()
        .filter(|((a, b), _)| {
            owned_ids.contains(&(a >> SPHERE_ID_BITS)) || owned_ids.contains(&(b >> SPHERE_ID_BITS))
        })
        .collect();
    out.pair_slip.sort_by_key(|e| e.0);
    let mut map = HistoryMap::default();
    w.neighbors
        .pairs
        .save_history(&w.spheres.gid, w.contact_table.any_reach(), &mut map);
    out.pair_history = map
        .into_iter()
        .filter(|((a, b), _)| {
            owned_ids.contains(&(a >> SPHERE_ID_BITS)) || owned_ids.contains(&(b >> SPHERE_ID_BITS))
        })
        .collect();
    out
}

/// Replaces this rank's part by the whole world, gathered from every rank:
/// bodies in the whole world's storage order, their build poses, wall
/// slots, the pair histories in the history map (no pair list is built:
/// the next build or restriction makes one), spheres and reference
/// positions recomputed. Statistics, wall loads, counters and settings are
/// already the same on every rank.
pub(crate) fn join(w: &mut World) -> Result<(), StepError> {
    let mine = postcard::to_stdvec(&owned(w))
        .map_err(|e| StepError::Neighbor(format!("partition: cannot encode bodies: {e}")))?;
    let part = w.part.as_mut().expect("a partitioned world");
    part.traffic.gather_bytes += mine.len() as u64;
    part.traffic.gathers += 1;
    let all = part.comm.all_gather(&mine);
    let mut parts = Vec::with_capacity(all.len());
    for (r, bytes) in all.iter().enumerate() {
        parts.push(postcard::from_bytes::<Owned>(bytes).map_err(|e| {
            StepError::Neighbor(format!("partition: bodies from rank {r} unreadable: {e}"))
        })?);
    }
    // every body once, by its place in the whole world
    let mut order: Vec<((u64, u64), usize, usize)> = Vec::new();
    for (r, p) in parts.iter().enumerate() {
        order.extend(p.order.iter().enumerate().map(|(k, &g)| (g, r, k)));
    }
    order.sort_unstable();
    let mut all_bodies = Bodies::default();
    let mut base = Vec::with_capacity(parts.len());
    let mut sphere_first: Vec<Vec<usize>> = Vec::with_capacity(parts.len());
    for p in &parts {
        base.push(all_bodies.len());
        all_bodies.append(&p.bodies);
        let mut first = vec![0usize];
        for &t in &p.bodies.template {
            let t = t as usize;
            let n = (w.templates.first[t + 1] - w.templates.first[t]) as usize;
            first.push(first.last().unwrap() + n);
        }
        sphere_first.push(first);
    }
    let perm: Vec<u32> = order
        .iter()
        .map(|&(_, r, k)| (base[r] + k) as u32)
        .collect();
    all_bodies.permute_into(&perm, &mut w.bodies);
    w.neighbors.reference_pose.clear();
    let (mut key, mut hist, mut wslip) = (Vec::new(), Vec::new(), Vec::new());
    for &(_, r, k) in &order {
        let p = &parts[r];
        w.neighbors.reference_pose.push(p.reference_pose[k]);
        let s = sphere_first[r][k]..sphere_first[r][k + 1];
        key.extend_from_slice(&p.wall_key[s.clone()]);
        hist.extend_from_slice(&p.wall_hist[s.clone()]);
        if p.wall_slip.len() == p.wall_key.len() && !p.wall_slip.is_empty() {
            wslip.extend_from_slice(&p.wall_slip[s]);
        }
    }
    let map = &mut w.neighbors.history_map;
    map.clear();
    w.neighbors.slip_map.clear();
    for p in parts {
        map.extend(p.pair_history);
        w.neighbors.slip_map.extend(p.pair_slip);
    }
    w.neighbors.history_pending = true;
    w.neighbors.wall_list = WallList::from_per_sphere(&key, &hist);
    if wslip.len() == key.len() {
        w.neighbors.wall_list.set_slip_per_sphere(&wslip);
    }
    w.neighbors.records.step = None;
    rebuild_sphere_topology(w);
    update_spheres(w);
    w.neighbors.pairs.refresh_bodies(&w.bodies);
    let part = w.part.as_mut().expect("a partitioned world");
    part.local = false;
    part.owned.clear();
    part.order.clear();
    part.send.clear();
    part.recv.clear();
    Ok(())
}

/// One step of the whole world on every rank, as one process takes it (the
/// step before an event: its statistics, wall loads and contact records are
/// then one process's). The world is gathered first if it is
/// split, and stays whole.
pub(crate) fn whole_step(w: &mut World) -> Result<(), StepError> {
    if w.part.as_ref().is_some_and(|p| p.local) {
        join(w)?;
    }
    // the whole world's bodies, not this rank's
    w.props_changed();
    let part = w.part.take();
    let result = (|| {
        if w.neighbors.history_pending {
            // the whole world's pair list, from the build poses
            crate::step::rebuild::rebuild(w, false)?;
            w.rebuilds = w.rebuilds.saturating_sub(1);
        }
        w.take_step(false)
    })();
    w.part = part;
    result
}
