//! A neighbour rebuild of a split world without gathering it: every rank
//! reorganises its own bodies (wrap, lost ones out) and sends each to the
//! ranks that hold it after the build (its new owner and the ranks within
//! the halo), with its wall slots and the histories of its pairs. Only
//! small numbers go to every rank: those that no order changes (the largest
//! displacement for the skin, the bounding boxes of the grids, the lost
//! counts), a sample of at most 256 body positions per rank on which every
//! rank re-balances the regions alike, and each rank's list of
//! destinations. The part then sorts its bodies by the whole world's cell key
//! (on the whole world's grid) and id, which is the whole world's order
//! restricted to them, and builds its lists on the whole world's grid: the
//! result is what a gather, one process's rebuild and a split give, bit for
//! bit (`join` + `restrict`), at the cost of messages between neighbours.

use super::restrict::{halo, Roles};
use crate::body::Bodies;
use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::lost::LostBodies;
use crate::neighbor::grid::Extent;
use crate::neighbor::pairs::{HistoryMap, SlipMap};
use crate::neighbor::sort::CellOrder;
use crate::neighbor::walls::{WallList, WALL_SLOTS};
use crate::neighbor::CellGrid;
use crate::partition::Part;
use crate::sphere::SPHERE_ID_BITS;
use crate::step::kinematics::rebuild_sphere_topology;
use crate::step::kinematics::sphere_position;
use crate::step::rebuild::{build_pair_list, build_wall_lists, references_at_current_poses};
use crate::step::StepError;
use crate::world::World;
use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

/// Bodies moving to a rank, with what travels with them.
#[derive(Serialize, Deserialize, Default)]
struct Moving {
    bodies: Bodies,
    wall_key: Vec<[u32; WALL_SLOTS]>,
    wall_hist: Vec<[ContactHistory; WALL_SLOTS]>,
    pair_history: Vec<((u64, u64), ContactHistory)>,
    /// MDR profiles, as `wall_hist` and `pair_history` (empty when no law
    /// keeps them).
    wall_slip: Vec<[SlipProfile; WALL_SLOTS]>,
    pair_slip: Vec<((u64, u64), SlipProfile)>,
}

/// What every rank contributes to the whole world's numbers.
#[derive(Serialize, Deserialize)]
struct Totals {
    displacement2: f64,
    bodies: Extent,
    spheres: Extent,
    lost: LostBodies,
    /// A sample of the kept owned bodies for the balance: a position (the
    /// first of each run of `stride` bodies in storage order, which is a
    /// spatial order: neighbours) and the run's cost (`super::cost`).
    sample: Vec<(DVec3, u32)>,
}

/// Largest number of sample points a rank sends for the balance.
const SAMPLE: usize = 256;

fn encode<T: Serialize>(v: &T) -> Result<Vec<u8>, StepError> {
    postcard::to_stdvec(v).map_err(|e| StepError::Neighbor(format!("partition: encoding: {e}")))
}

fn decode<'a, T: Deserialize<'a>>(b: &'a [u8], from: usize) -> Result<T, StepError> {
    postcard::from_bytes(b)
        .map_err(|e| StepError::Neighbor(format!("partition: message from rank {from}: {e}")))
}

/// Rebuilds the neighbour lists of this rank's part (see the module docs).
pub(crate) fn rebuild(w: &mut World) -> Result<(), StepError> {
    let mut part = w.part.take().expect("a partitioned world");
    let (me, size) = (part.comm.rank(), part.comm.size());
    // 1. + 2. the whole world's numbers, the regions, the skin, the losses
    let (whole, keep) = reduce_totals(w, &mut part)?;
    apply_totals(w, &whole);
    // 3. each kept body to its new owner and the ranks within the halo
    part.halo = halo(w);
    let arrived = migrate_bodies(w, &mut part, &keep)?;
    // 4. the part in the whole world's order
    let (sphere_grid, sorted) = order_arrived(w, &whole, arrived)?;
    // 5. who owns what, and who sends whose state
    let roles = Roles::of(&part.regions, part.halo, me, size, &w.bodies.position);
    if roles.keep.len() != w.bodies.len() {
        return Err(StepError::Neighbor(format!(
            "partition: rank {me} received {} bodies it does not hold",
            w.bodies.len() - roles.keep.len()
        )));
    }
    part.order = sorted.iter().map(|e| e.0).collect();
    roles.install(&mut part);
    part.local = true;
    part.traffic.rebuilds += 1;
    w.part = Some(part);
    // 6. the lists, as one process's rebuild makes them (without the pairs
    // of two ghosts)
    rebuild_sphere_topology(w);
    references_at_current_poses(w);
    w.neighbors.grid = sphere_grid;
    build_pair_list(w);
    let ns = w.spheres.len();
    w.neighbors
        .wall_list
        .live_entries(ns, &mut w.scratch.wall_carry);
    build_wall_lists(w);
    w.rebuilds += 1;
    Ok(())
}

/// Step 1: this rank's share of the whole world's numbers (largest
/// displacement, extents, lost bodies, a sample of the bodies' places and
/// costs), reduced over the ranks; the regions re-balanced on the sample
/// (the same on every rank). Returns the whole world's numbers and the
/// owned bodies kept (wrapped into the domain).
fn reduce_totals(w: &mut World, part: &mut Part) -> Result<(Totals, Vec<usize>), StepError> {
    let domain = w.config.domain;
    let n = w.bodies.len();
    let d2 = crate::step::rebuild::largest_displacement2(w, (0..n).filter(|&b| part.owned[b]));
    let mut totals = Totals {
        displacement2: d2,
        bodies: Extent::empty(),
        spheres: Extent::empty(),
        lost: LostBodies::default(),
        sample: Vec::new(),
    };
    let mut keep = Vec::new();
    for b in (0..n).filter(|&b| part.owned[b]) {
        let x = w.bodies.position[b];
        totals.bodies.add(&domain, x);
        if let Some(cause) = domain.exit_cause(x) {
            totals.lost.record(cause);
            continue;
        }
        let x = domain.wrap(x);
        w.bodies.position[b] = x;
        let t = w.bodies.template[b] as usize;
        let rot = DMat3::from_quat(w.bodies.orientation[b]);
        let (f0, f1) = (w.templates.first[t], w.templates.first[t + 1]);
        for k in f0..f1 {
            totals.spheres.add(
                &domain,
                sphere_position(x, &rot, w.templates.offset[k as usize]),
            );
        }
        keep.push(b);
    }
    let stride = keep.len().div_ceil(SAMPLE).max(1);
    let cost = super::cost::body_costs(w);
    for run in keep.chunks(stride) {
        let c: u32 = run.iter().map(|&b| cost[b]).sum();
        totals.sample.push((w.bodies.position[run[0]], c));
    }
    part.traffic.reductions += 1;
    let all = part.comm.all_gather(&encode(&totals)?);
    let mut whole = Totals {
        displacement2: 0.0,
        bodies: Extent::empty(),
        spheres: Extent::empty(),
        lost: LostBodies::default(),
        sample: Vec::new(),
    };
    for (r, bytes) in all.iter().enumerate() {
        let t: Totals = decode(bytes, r)?;
        whole.displacement2 = whole.displacement2.max(t.displacement2);
        whole.bodies.merge(&t.bodies);
        whole.spheres.merge(&t.spheres);
        let l = &mut whole.lost;
        for (a, b) in l.through_side.iter_mut().zip(t.lost.through_side) {
            *a += b;
        }
        l.not_finite += t.lost.not_finite;
        l.removed += t.lost.removed;
        whole.sample.extend(t.sample);
    }
    // the regions re-balanced on the sample (the same on every rank)
    let (at, cost): (Vec<DVec3>, Vec<u32>) = whole.sample.iter().copied().unzip();
    part.regions = crate::partition::Regions::balance(&domain, &at, &cost, part.comm.size());
    Ok((whole, keep))
}

/// Step 2: the skin, as one process adapts it, and the lost bodies.
fn apply_totals(w: &mut World, whole: &Totals) {
    // bodies added since the last build keep the skin, as in one process
    let added = w.phase.topology_dirty();
    if w.config.skin.is_none() && w.step > w.neighbors.built_step && !added {
        w.neighbors.adapted_skin = w.adapted_skin(whole.displacement2.sqrt());
    }
    w.neighbors.built_step = w.step;
    let l = &mut w.lost;
    for (a, b) in l.through_side.iter_mut().zip(whole.lost.through_side) {
        *a += b;
    }
    l.not_finite += whole.lost.not_finite;
    l.removed += whole.lost.removed;
}

/// Step 3: each kept body, with its wall slots and pair histories, to its
/// new owner and the ranks within the halo; returns what arrived here
/// (this rank's own share first).
fn migrate_bodies(
    w: &mut World,
    part: &mut Part,
    keep: &[usize],
) -> Result<Vec<Moving>, StepError> {
    let (me, size) = (part.comm.rank(), part.comm.size());
    part.halo = halo(w);
    let mut history = HistoryMap::default();
    w.neighbors
        .pairs
        .save_history(&w.spheres.gid, w.contact_table.any_reach(), &mut history);
    let mut slips = SlipMap::default();
    w.neighbors.pairs.save_slip(&w.spheres.gid, &mut slips);
    let mut slip_by_body: rustc_hash::FxHashMap<u64, Vec<((u64, u64), SlipProfile)>> =
        Default::default();
    for (&(a, b), &p) in &slips {
        let (ba, bb) = (a >> SPHERE_ID_BITS, b >> SPHERE_ID_BITS);
        slip_by_body.entry(ba).or_default().push(((a, b), p));
        if bb != ba {
            slip_by_body.entry(bb).or_default().push(((a, b), p));
        }
    }
    let mut by_body: rustc_hash::FxHashMap<u64, Vec<((u64, u64), ContactHistory)>> =
        Default::default();
    for (&(a, b), &h) in &history {
        let (ba, bb) = (a >> SPHERE_ID_BITS, b >> SPHERE_ID_BITS);
        by_body.entry(ba).or_default().push(((a, b), h));
        if bb != ba {
            by_body.entry(bb).or_default().push(((a, b), h));
        }
    }
    let (wall_key, wall_hist) = w.neighbors.wall_list.per_sphere(w.spheres.len());
    let wall_slip = w
        .neighbors
        .wall_list
        .slip_per_sphere(w.spheres.len(), w.contact_table.keeps_slip_profile());
    let mut out: Vec<Moving> = (0..size).map(|_| Moving::default()).collect();
    let mut near = Vec::new();
    let mut one = Bodies::default();
    for &b in keep {
        let x = w.bodies.position[b];
        part.regions.near(x, part.halo, &mut near);
        near.push(part.regions.owner(x));
        near.sort_unstable();
        near.dedup();
        w.bodies.permute_into(&[b as u32], &mut one);
        let s = w.spheres.of_body(b);
        let hist = by_body.get(&w.bodies.id[b]);
        let slip = slip_by_body.get(&w.bodies.id[b]);
        for &r in &near {
            let m = &mut out[r];
            m.bodies.append(&one);
            m.wall_key.extend_from_slice(&wall_key[s.clone()]);
            m.wall_hist.extend_from_slice(&wall_hist[s.clone()]);
            if !wall_slip.is_empty() {
                m.wall_slip.extend_from_slice(&wall_slip[s.clone()]);
            }
            if let Some(h) = hist {
                m.pair_history.extend_from_slice(h);
            }
            if let Some(p) = slip {
                m.pair_slip.extend_from_slice(p);
            }
        }
    }
    // who sends to whom: each rank's destinations, to every rank (the
    // regions moved, so neighbours are not known beforehand)
    let dest: Vec<u32> = (0..size)
        .filter(|&r| r != me && !out[r].bodies.is_empty())
        .map(|r| r as u32)
        .collect();
    part.traffic.reductions += 1;
    let lists = part.comm.all_gather(&encode(&dest)?);
    let mut sources = Vec::new();
    for (r, bytes) in lists.iter().enumerate() {
        let d: Vec<u32> = decode(bytes, r)?;
        if d.contains(&(me as u32)) {
            sources.push(r);
        }
    }
    let mut sends = Vec::with_capacity(dest.len());
    for &r in &dest {
        let bytes = encode(&out[r as usize])?;
        part.traffic.migrate_bytes += bytes.len() as u64;
        part.traffic.migrate_messages += 1;
        sends.push((r as usize, bytes));
    }
    let got = part.comm.exchange(&sends, &sources);
    let mut arrived = vec![std::mem::take(&mut out[me])];
    for (bytes, &r) in got.iter().zip(&sources) {
        arrived.push(decode(bytes, r)?);
    }
    Ok(arrived)
}

/// Step 4: the part in the whole world's order (cell key on the whole
/// world's grid, then id): the bodies, their wall slots and the carried
/// histories stored in the world. Returns the sphere grid and the sort keys.
#[allow(clippy::type_complexity)]
fn order_arrived(
    w: &mut World,
    whole: &Totals,
    arrived: Vec<Moving>,
) -> Result<(CellGrid, Vec<((u64, u64), u32)>), StepError> {
    let domain = w.config.domain;
    let min_cell = 2.0 * w.max_radius() + w.skin();
    let body_grid =
        CellGrid::from_extent(&domain, &whole.bodies, min_cell).map_err(StepError::Neighbor)?;
    let sphere_grid =
        CellGrid::from_extent(&domain, &whole.spheres, min_cell).map_err(StepError::Neighbor)?;
    let mut all_bodies = Bodies::default();
    let (mut key, mut hist) = (Vec::new(), Vec::new());
    let mut wslip = Vec::new();
    let map = &mut w.neighbors.history_map;
    map.clear();
    w.neighbors.slip_map.clear();
    for m in arrived {
        all_bodies.append(&m.bodies);
        key.extend(m.wall_key);
        hist.extend(m.wall_hist);
        map.extend(m.pair_history);
        wslip.extend(m.wall_slip);
        w.neighbors.slip_map.extend(m.pair_slip);
    }
    let mut first = vec![0usize];
    for &t in &all_bodies.template {
        let t = t as usize;
        let ns = (w.templates.first[t + 1] - w.templates.first[t]) as usize;
        first.push(first.last().copied().unwrap_or(0) + ns);
    }
    let order = CellOrder::of(&body_grid);
    let mut sorted: Vec<((u64, u64), u32)> = (0..all_bodies.len())
        .map(|b| {
            let k = order.key(body_grid.coords(all_bodies.position[b]));
            ((k, all_bodies.id[b]), b as u32)
        })
        .collect();
    sorted.sort_unstable();
    let perm: Vec<u32> = sorted.iter().map(|e| e.1).collect();
    all_bodies.permute_into(&perm, &mut w.bodies);
    let (mut k2, mut h2) = (
        Vec::with_capacity(key.len()),
        Vec::with_capacity(hist.len()),
    );
    let mut s2 = Vec::with_capacity(wslip.len());
    for &b in &perm {
        let s = first[b as usize]..first[b as usize + 1];
        k2.extend_from_slice(&key[s.clone()]);
        h2.extend_from_slice(&hist[s.clone()]);
        if wslip.len() == key.len() {
            s2.extend_from_slice(&wslip[s]);
        }
    }

    w.neighbors.wall_list = WallList::from_per_sphere(&k2, &h2);
    w.neighbors.wall_list.set_slip_per_sphere(&s2);
    Ok((sphere_grid, sorted))
}
