//! Force stage: per-pair contact forces over the rows of the half list
//! (each pair's force is computed once, in batches, by `step::pair_kernel`,
//! with its torques about both bodies' centres of mass; sphere `i`'s side is
//! added to the row sum of its body while its row is evaluated, sphere `j`'s
//! side to the column sum of `j`'s body, or recorded with the pair when
//! that body is on a seam between two threads' runs,
//! `neighbor::pairs::column_sum`; a body's row and column sums meet in
//! `PairBody::col`), then a gather by chunks of bodies in a fixed order:
//! the pair sums and gravity, the sphere–wall contacts of the bodies with
//! wall-list entries (`step::wall_contacts`, their law run as vector
//! lanes), and per body the final kick.
//!
//! Body force and torque (docs/theory.md T-11), world frame:
//! `F = m g + Σ_s F_s`, `M = Σ_s [(x_s − r_cm) × F_s + T_s]`, where `F_s` is
//! the total contact force on sphere `s` and `T_s` the torque of its contacts
//! about the sphere centre, `Σ (x_c − x_s) × f + couples`. This equals
//! `Σ (x_c − r_cm) × f` over the contacts.

use super::body_props::BodyProps;
use super::first_half_lanes::{BodyLanes, LANES};
use super::integrate::{FinalKick, FirstHalf, Held};
use super::pair_kernel::RowCtx;
use super::wall_contacts::{ChunkSums, WallPass, WallScratch};
use crate::multi_contact::{MultiContact, PartnerCounts};
use crate::neighbor::pairs::column_sum;
use crate::par::affinity::{
    body_chunk_cost, for_each_chunk_with, for_each_run, for_each_run_then, several_runs,
    FORCE_LOOP, GATHER_LOOP, PAIR_LOOP,
};
use crate::par::prefetch::prefetch;
use crate::par::shared::{at, SharedMut};
use crate::sphere::SPHERE_ID_BITS;
use crate::stats::{all_finite, BodyTally, ContactStats};
use crate::wall::WallLoad;
use crate::world::World;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Entries of the wall list beyond the current body's whose sphere's state
/// the gather prefetches. On the stone pile (50-sphere stones, 1 700
/// entries a step) 24 beyond the body's last entry took 2 % off the step
/// against 8 from its first, in-process A/B; the tetra bed was unchanged.
const ENTRY_PREFETCH: usize = 24;

/// Bodies whose gather runs before their first halves, in turn: the first
/// halves of a block (kick, drift, rotation, sphere centres, skin check)
/// run as the lanes of one vector loop where the bodies allow
/// (`super::first_half_lanes`), else as independent chains the processor
/// can overlap.
const FIRST_HALF_BLOCK: usize = LANES;

/// Bodies ahead whose column sum ([`crate::neighbor::PairBody::col`]) the
/// gather prefetches.
const BODY_PREFETCH: usize = 4;

/// Computes all contact forces and the total force and torque on every body.
pub fn compute(w: &mut World) {
    // the pair stage reads the bodies' state from its packed copy, which a
    // step's first half writes; here it comes from the bodies as they are
    w.neighbors.pairs.refresh_bodies(&w.bodies);
    pair_forces(w);
    gather(w, false, None);
}

/// Evaluates every candidate sphere pair, row by row: pairs that do not touch
/// get zero force and their history is reset. Writes each body's pair load
/// (row sum plus column sum, `PairBody::col`; the row sum alone for a body on
/// a seam, with each pair's contribution to it in `load_j`), and the pair
/// statistics per chunk of rows.
pub(crate) fn pair_forces(w: &mut World) {
    let nchunks = prepare_pairs(w);
    let chunk = w.body_chunk();
    let stats = SharedMut::new(&mut w.scratch.chunk_pair_stats);
    let ready = SharedMut::new(&mut w.scratch.body_ready);
    let record = w
        .neighbors
        .records
        .recording
        .then(|| SharedMut::new(&mut w.neighbors.records.pair));
    let (rows, _) = row_ctx(
        &w.spheres,
        &w.contact_table,
        &w.config,
        &mut w.neighbors.pairs,
        ready,
        record,
        w.part.as_deref(),
        chunk,
    );
    let balance = &mut w.scratch.balance[PAIR_LOOP];
    // SAFETY: every run is run once, on one thread.
    for_each_run(
        nchunks,
        |c| pair_cost(&rows, c),
        balance,
        |run| unsafe { pair_run(&rows, run, &stats) },
    );
}

/// What the pair stage needs before its rows are evaluated, on one thread:
/// the `average` scales, the statistics slots and ready flags sized, the
/// seams' column lists (several runs), rolling springs where a law keeps
/// them, and the contact records sized. Returns the number of chunks.
fn prepare_pairs(w: &mut World) -> usize {
    if w.config.multi_contact == MultiContact::Average {
        average_scales(w);
    } else {
        w.neighbors.pairs.scale.clear();
    }
    let nb = w.bodies.len();
    let nchunks = nb.div_ceil(w.body_chunk());
    // each run clears its chunks' slots (pair_run), on its own thread
    w.scratch
        .chunk_pair_stats
        .resize(nchunks, ContactStats::default());
    w.scratch.body_ready.resize(nb, false);
    let pairs = &mut w.neighbors.pairs;
    if several_runs(nchunks) {
        // several runs: the seams' column lists and j-side loads
        pairs.prepare_seams(&w.spheres.body);
    }
    if w.contact_table.keeps_rolling_spring() {
        pairs.keep_rolling();
    }
    if w.contact_table.keeps_slip_profile() {
        pairs.keep_slip();
        w.neighbors.wall_list.keep_slip();
    }
    let records = &mut w.neighbors.records;
    if records.recording {
        records.pair.resize(pairs.topo.len(), Default::default());
    }
    nchunks
}

/// The pair stage's view of the world ([`RowCtx`]), and the pair list
/// seen from the other stages while the rows are evaluated (the fields the
/// rows write are reached through the context only).
#[allow(clippy::too_many_arguments)]
fn row_ctx<'a>(
    sp: &'a crate::sphere::Spheres,
    table: &'a crate::contact::ContactTable,
    config: &crate::world::WorldConfig,
    pairs: &'a mut crate::neighbor::PairList,
    body_ready: SharedMut<bool>,
    record: Option<SharedMut<crate::contact::record::PairRecord>>,
    part: Option<&'a crate::partition::Part>,
    body_chunk: usize,
) -> (RowCtx<'a>, &'a crate::neighbor::PairList) {
    let topo = SharedMut::new(&mut pairs.topo);
    let tangential = SharedMut::new(&mut pairs.tangential);
    let rolling = SharedMut::new(&mut pairs.rolling);
    let slip = SharedMut::new(&mut pairs.slip);
    let load_j = SharedMut::new(&mut pairs.load_j);
    let body = SharedMut::new(&mut pairs.body);
    let pairs = &*pairs;
    let rows = RowCtx {
        dt: config.dt,
        domain: config.domain,
        any_periodic: config.domain.periodic.iter().any(|&p| p),
        sp,
        table,
        row_start: &pairs.row_start,
        topo,
        scale: &pairs.scale,
        tangential,
        rolling,
        slip,
        load_j,
        body,
        first_feed: &pairs.first_feed,
        body_ready,
        record,
        simd: crate::par::simd::simd(),
        prefetch: sp.len() >= super::pair_kernel::PREFETCH_MIN_SPHERES,
        counted: part.map(|p| &p.owned[..]),
        body_chunk,
    };
    (rows, pairs)
}

/// The pair stage's cost estimate of the body chunks `0..c` (the gather's
/// chunks, so that a body's rows never straddle two threads): one unit per
/// sphere and per candidate pair.
fn pair_cost(rows: &RowCtx, c: usize) -> u64 {
    let first = &rows.sp.body_first;
    let nb = first.len().saturating_sub(1);
    let s = first
        .get((c * rows.body_chunk).min(nb))
        .map_or(0, |&s| s as usize);
    rows.row_start.get(s).map_or(0, |&p| p as u64) + s as u64
}

/// Evaluates the rows of the body chunks `run`, one thread's run, as one
/// batch (a batch may span chunks: the statistics go to each pair's own
/// chunk, in pair order).
///
/// # Safety
/// This run owns the rows of its bodies in the half list, their bodies'
/// pair loads and its chunks' statistics slots, no other run's; the column
/// sums it adds to are of bodies complete in it.
unsafe fn pair_run(rows: &RowCtx, run: std::ops::Range<usize>, stats: &SharedMut<ContactStats>) {
    let first = &rows.sp.body_first;
    let nb = first.len().saturating_sub(1);
    for c in run.clone() {
        // SAFETY: the run's chunks' slots are this run's.
        unsafe { *stats.get(c) = ContactStats::default() };
    }
    let b0 = run.start * rows.body_chunk;
    let b1 = (run.end * rows.body_chunk).min(nb);
    if b0 >= b1 {
        return;
    }
    let mut batch = super::pair_kernel::Batch::default();
    rows.evaluate(b0..b1, first[b0] as usize, &mut batch, stats);
}

/// `average` multi-contact: the scale `1/n` of every pair, `n` being the
/// number of touching sphere pairs between the same two bodies. All pairs of
/// bodies `A` and `B` (storage `A < B`) lie in the rows of `A`'s spheres,
/// because a body's spheres are contiguous in storage order.
fn average_scales(w: &mut World) {
    let chunk = w.body_chunk();
    let domain = w.config.domain;
    let any_periodic = domain.periodic.iter().any(|&p| p);
    let sp = &w.spheres;
    let pairs = &mut w.neighbors.pairs;
    pairs.scale.clear();
    pairs.scale.resize(pairs.topo.len(), 1.0);
    let (rows, topo) = (&pairs.row_start, &pairs.topo);
    let scale = SharedMut::new(&mut pairs.scale);
    let nb = w.bodies.len();
    let touching = |i: usize, p: usize| {
        let t = topo[p];
        let j = t.j as usize;
        let mut xj = sp.position(j);
        if any_periodic && t.shift != [0; 3] {
            xj -= domain.shift_vector(t.shift);
        }
        let rsum = sp.radius[i] + sp.radius[j];
        sp.position(i).distance_squared(xj) < rsum * rsum
    };
    (0..nb.div_ceil(chunk))
        .into_par_iter()
        .for_each_init(PartnerCounts::default, |counts, c| {
            for bi in c * chunk..((c + 1) * chunk).min(nb) {
                counts.clear();
                let spheres = sp.of_body(bi);
                for i in spheres.clone() {
                    for p in rows[i] as usize..rows[i + 1] as usize {
                        if touching(i, p) {
                            counts.add(sp.body[topo[p].j as usize] as u64);
                        }
                    }
                }
                for i in spheres {
                    for p in rows[i] as usize..rows[i + 1] as usize {
                        let n = counts.get(sp.body[topo[p].j as usize] as u64).max(1);
                        // SAFETY: the rows of body bi's spheres belong to this chunk only.
                        unsafe { *scale.get(p) = 1.0 / n as f64 };
                    }
                }
            }
        });
}

/// Per body: sum the pair loads of its spheres, evaluate its sphere–wall
/// contacts, add gravity; with `kick`, then apply the body's second half
/// kick ([`FinalKick`]) in the same pass. Bodies are processed in fixed
/// chunks; wall loads and statistics are summed per chunk and then over
/// chunks in order (the pair chunks first).
///
/// With `next` (which implies `kick`), each body then also takes the first
/// half of the next step ([`FirstHalf`]) in the same pass, while its state is
/// in the cache, a block of [`FIRST_HALF_BLOCK`] bodies after their kicks;
/// the result is then whether a sphere moved more than half the skin (else
/// false). A body's first half reads and writes only its own state and
/// spheres, so the blocks change no result.
pub(crate) fn gather(w: &mut World, kick: bool, next: Option<FirstHalf>) -> bool {
    gather_after(w, kick, next, false).0
}

/// [`pair_forces`] and then [`gather`] with the kick, in one parallel call
/// ([`for_each_run_then`]): each thread takes its run of chunks through
/// the pair stage and then through the gather, from its last chunk down;
/// before the first chunk whose bodies the rows of an earlier run feed
/// (`PairList::first_feed`: those rows read the bodies' spheres and
/// packed records, which the gather's first half rewrites, and leave
/// their column loads in `load_j`), it waits for the pair stage of the
/// earlier runs. One cut and one balance for both stages, and one wait
/// for all threads a step instead of two. The same results as the two
/// stages one after the other, for any thread count. Returns the gather's
/// result and the time the calling thread spent in the pair stage (the
/// rest of the call is the gather's).
pub(crate) fn pairs_and_gather(w: &mut World, next: Option<FirstHalf>) -> (bool, Duration) {
    prepare_pairs(w);
    gather_after(w, true, next, true)
}

/// [`gather`]; with `pairs_first`, [`pairs_and_gather`].
fn gather_after(
    w: &mut World,
    kick: bool,
    next: Option<FirstHalf>,
    pairs_first: bool,
) -> (bool, Duration) {
    let chunk = w.body_chunk();
    let World {
        bodies,
        step,
        spheres: sp,
        neighbors,
        walls: wall_set,
        contact_table: table,
        scratch,
        config,
        stats,
        part,
        phase,
        ..
    } = w;
    // a partitioned world counts its owned bodies only in the statistics
    // and wall loads (its ghosts are counted by their owners)
    let owned = part.as_ref().map(|p| &p.owned[..]);
    let crate::neighbor::NeighborState {
        pairs,
        wall_list,
        records: contact_records,
        ..
    } = neighbors;
    let crate::wall::WallSet {
        list: walls,
        meshes,
        loads: wall_loads,
    } = wall_set;
    let crate::world::Scratch {
        body_cost,
        body_ready,
        balance,
        chunk_stats,
        chunk_pair_stats,
        chunk_wall_loads,
        props,
        ..
    } = scratch;
    let nb = bodies.len();
    let nw = walls.len();
    let nchunks = nb.div_ceil(chunk);
    // each chunk clears its own slots, on the thread that gathers it: the
    // threads' slots would otherwise be written here, on the calling
    // thread, and move between the cores' caches twice a step
    chunk_stats.resize(nchunks, ContactStats::default());
    chunk_wall_loads.resize(nchunks * nw, WallLoad::default());
    let dt = config.dt;
    let gravity = config.gravity;
    let any_stale = AtomicBool::new(false);
    let next = next.as_ref();
    // inside a fused stretch the bodies' centres, velocities and angular
    // velocities are current in the packed copy only (StepPhase::bodies_lag)
    let lag = phase.bodies_lag;
    // lagging bodies are kicked here, and a first half fused into this
    // gather keeps them lagging
    #[allow(clippy::unnecessary_map_or)] // `is_none_or` needs Rust 1.82; the MSRV is 1.80
    {
        debug_assert!(!lag || (kick && next.map_or(true, |h| h.lags())));
    }
    let force = SharedMut::new(&mut bodies.force);
    let torque = SharedMut::new(&mut bodies.torque);
    let vel = SharedMut::new(&mut bodies.velocity);
    let angm = SharedMut::new(&mut bodies.angular_momentum);
    let omega = SharedMut::new(&mut bodies.angular_velocity);
    let loads = SharedMut::new(chunk_wall_loads);
    let pos = SharedMut::new(&mut bodies.position);
    // SAFETY: the gather resizes nothing, and writes no orientation (the
    // first half of the next step writes its body's, after its kick).
    let kick = kick.then(|| unsafe { FinalKick::new(dt, *step, config.rotation, props, bodies) });
    // SAFETY: as above; the table was refreshed for these bodies.
    let mass = unsafe { BodyProps::new(props, bodies) };
    let b = &*bodies;
    let pair_body = SharedMut::new(&mut pairs.body);
    let ready = SharedMut::new(body_ready);
    let (rows, pairs) = if pairs_first {
        let record = contact_records
            .recording
            .then(|| SharedMut::new(&mut contact_records.pair));
        let (rows, pairs) = row_ctx(
            sp,
            table,
            config,
            pairs,
            ready,
            record,
            part.as_deref(),
            chunk,
        );
        (Some(rows), pairs)
    } else {
        (None, &*pairs)
    };
    let pair_stats = SharedMut::new(chunk_pair_stats);
    let stats_out = SharedMut::new(chunk_stats);
    // this step keeps its contacts (crate::contacts): each chunk its own list
    let recording = contact_records.recording;
    if recording {
        contact_records.wall.resize_with(nchunks, Vec::new);
        contact_records.wall.truncate(nchunks);
        contact_records.wall.iter_mut().for_each(Vec::clear);
    }
    let wall_pass = WallPass::new(
        sp,
        b,
        lag.then_some(pair_body),
        table,
        walls,
        meshes,
        dt,
        wall_list,
        loads,
        &mut contact_records.wall,
        recording,
    );
    let init = || {
        (
            WallScratch::new(),
            BodyLanes::idle(),
            [Held::default(); FIRST_HALF_BLOCK],
        )
    };
    // per thread: `walls`, the wall touches awaiting their law and the
    // chunk's bodies' loads; `held`, the bodies of a block, from their
    // final kicks to their first half (every slot is written before it is
    // read, so one array per thread, not a zeroed one per chunk)
    let gather_chunk =
        |(walls, lanes, held): &mut (WallScratch, BodyLanes, [Held; FIRST_HALF_BLOCK]),
         c: usize| {
            // SAFETY: chunk c's statistics slot and wall loads are written by
            // chunk c only.
            let stat = unsafe {
                for wi in 0..nw {
                    *loads.get(c * nw + wi) = WallLoad::default();
                }
                stats_out.get(c)
            };
            *stat = ContactStats::default();
            let b0 = c * chunk;
            let b1 = (b0 + chunk).min(nb);
            // the chunk's entries of the wall list, ascending with its bodies
            let (mut e, e_end) = (
                wall_pass.chunk_start[c] as usize,
                wall_pass.chunk_start[c + 1] as usize,
            );
            // the next entry whose sphere is to be prefetched
            let mut e_pf = e;
            // SAFETY: body bi is chunk c's, handled by this chunk only.
            let com_of = |bi: usize| unsafe {
                if lag {
                    (*pair_body.ptr(bi)).position
                } else {
                    pos.read(bi)
                }
            };
            // the load a body has from gravity and the pair stage's sums:
            // force (N) and torque about its centre of mass (N m), world frame
            let pair_load = |bi: usize| {
                // --- sphere–sphere contacts: summed by the pair stage, or
                // here for a body on the seam between two threads' runs
                // SAFETY: body bi is handled by this chunk only; its sum
                // is read and reset for the next step.
                let own = std::mem::take(unsafe { &mut (*pair_body.ptr(bi)).col });
                // SAFETY: the pair stage of this body's run is over.
                let pl = if unsafe { ready.read(bi) } {
                    own
                } else {
                    // SAFETY: the pair list was built for these bodies (a
                    // rebuild precedes every gather after a change), and the
                    // pair stage is over.
                    own.add(unsafe {
                        column_sum(pairs.load_j.as_ptr(), &pairs.col_start, &pairs.col_pair, bi)
                    })
                };
                // SAFETY: bi < nb.
                (unsafe { mass.mass(bi) } * gravity + pl.force, pl.torque)
            };
            let mut sums = ChunkSums { c, b0, stat };
            // --- the bodies with wall entries (in the order of the list, which
            // is theirs): their pair loads, then their wall touches (collected
            // body by body, their law run in batches) added to them
            let mut walled = 0u64;
            while e < e_end {
                // SAFETY: e < e_end ≤ the number of entries.
                let bi = unsafe { at(&sp.body, at(wall_pass.entry_sphere, e) as usize) } as usize;
                // the body's entries: e0..e
                let e0 = e;
                let s_end = sp.of_body(bi).end;
                // SAFETY: e < e_end ≤ the number of entries.
                while e < e_end && (unsafe { at(wall_pass.entry_sphere, e) } as usize) < s_end {
                    e += 1;
                }
                // the spheres of this body's entries and of the next
                // ENTRY_PREFETCH: their state lines, which the pair stage has
                // pushed out of the cache by now in a large bed (read here,
                // they were 10 % of this pass at 40 000 spheres, 16 % at 10⁶
                // when only one entry was prefetched per body, as a body at a
                // wall has up to four); counted from the body's last entry,
                // as a stone lying on a wall has ten or more; within the
                // chunk, as later entries are another thread's
                let pf_end = (e + ENTRY_PREFETCH).min(e_end);
                while e_pf < pf_end {
                    // SAFETY: the entry and its sphere exist (a prefetch
                    // never faults anyway).
                    unsafe {
                        prefetch(
                            sp.state
                                .as_ptr()
                                .add(at(wall_pass.entry_sphere, e_pf) as usize),
                        )
                    };
                    e_pf += 1;
                }
                walls.load[bi - b0] = pair_load(bi);
                walled |= 1 << (bi - b0);
                // SAFETY: the entries e0..e are body bi's, chunk c's.
                unsafe {
                    wall_pass.collect(
                        walls,
                        bi,
                        com_of(bi),
                        e0..e,
                        owned.map_or(true, |o| o[bi]),
                        &mut sums,
                    )
                };
            }
            // SAFETY: the touches are chunk c's.
            unsafe { wall_pass.flush(walls, &mut sums) };
            let stat = sums.stat;
            let mut stale = false;
            // the bodies' statistics, stored in the chunk's slot at its end
            let mut tally = BodyTally::default();
            // --- the final kicks and the first halves, block by block
            for k0 in (b0..b1).step_by(FIRST_HALF_BLOCK) {
                let k1 = (k0 + FIRST_HALF_BLOCK).min(b1);
                for bi in k0..k1 {
                    // the column sum of a body a few ahead (the pair stage
                    // wrote it; 7 % of this pass at 10⁶ spheres, read here)
                    if bi + BODY_PREFETCH < b1 {
                        // SAFETY: a body of this chunk; a prefetch never faults.
                        unsafe {
                            prefetch(std::ptr::addr_of!((*pair_body.ptr(bi + BODY_PREFETCH)).col));
                        }
                    }
                    let (f, m) = if walled >> (bi - b0) & 1 != 0 {
                        walls.load[bi - b0]
                    } else {
                        pair_load(bi)
                    };
                    let com = com_of(bi);
                    // SAFETY: bi < nb.
                    let mass_i = unsafe { mass.mass(bi) };
                    // the body's velocities as local values, kicked, then stored
                    // once: read back from memory right after the kick's
                    // per-component stores, they could not be forwarded (a
                    // stall measured at 6-8 % of this pass)
                    // SAFETY: body bi is handled by this chunk only.
                    let (mut v, mut l, mut om) = unsafe {
                        let l = angm.read(bi);
                        if lag {
                            let pb = pair_body.ptr(bi);
                            ((*pb).velocity, l, (*pb).angular_velocity)
                        } else {
                            (vel.read(bi), l, omega.read(bi))
                        }
                    };
                    // the force and torque are kept for the next step's first
                    // half, unless it takes them now
                    if next.is_none() {
                        // SAFETY: body bi is handled by this chunk only.
                        unsafe {
                            *force.get(bi) = f;
                            *torque.get(bi) = m;
                        }
                    }
                    if let Some(k) = &kick {
                        // SAFETY: bi < nb.
                        unsafe { k.apply(bi, &mut v, &mut l, &mut om, f, m) };
                    }
                    // --- health statistics (folded into this pass: no extra
                    // sweep): the kinetic energy at the end of the step, after
                    // the kick (a force that would fling a body out of the
                    // domain shows here, before the body is removed)
                    let ke = 0.5 * mass_i * v.length_squared() + 0.5 * om.dot(l);
                    if owned.is_some_and(|o| !o[bi]) {
                        // a ghost: its owner counts it
                    } else {
                        tally.add(ke, mass_i, || all_finite(ke, [com, f, m]), || b.id[bi]);
                    }
                    if next.is_some() {
                        held[bi - k0] = Held { v, l, om, f, m };
                    } else if kick.is_some() {
                        // SAFETY: body bi is handled by this chunk only.
                        unsafe {
                            *vel.get(bi) = v;
                            *angm.get(bi) = l;
                            *omega.get(bi) = om;
                            if lag {
                                *pos.get(bi) = com;
                            }
                        }
                    }
                }
                if let Some(h) = next {
                    // SAFETY: bodies k0..k1 (and their spheres) are handled
                    // by this chunk only; it stores their state.
                    stale |= unsafe { h.apply_block(k0, &mut held[..k1 - k0], lanes) };
                }
            }
            tally.store(stat);
            if stale {
                any_stale.store(true, Ordering::Relaxed);
            }
        };
    let gather_cost = body_chunk_cost(body_cost, nb, chunk);
    let pair_time = match &rows {
        None => {
            for_each_chunk_with(
                nchunks,
                gather_cost,
                &mut balance[GATHER_LOOP],
                init,
                gather_chunk,
            );
            Duration::ZERO
        }
        Some(rows) => {
            // a chunk with a body that an earlier run's rows feed (and
            // read): one its own run's rows left not ready
            // SAFETY: the run's pair stage, on this thread, wrote the flags.
            let fed_earlier = |c: usize| {
                (c * chunk..((c + 1) * chunk).min(nb)).any(|b| !unsafe { ready.read(b) })
            };
            for_each_run_then(
                nchunks,
                |c| pair_cost(rows, c),
                gather_cost,
                &mut balance[FORCE_LOOP],
                // SAFETY: every run is run once, on one thread.
                |run| unsafe { pair_run(rows, run, &pair_stats) },
                fed_earlier,
                init,
                gather_chunk,
            )
        }
    };
    let mut total = ContactStats::default();
    for s in chunk_pair_stats.iter() {
        total.merge(s);
    }
    // the pair stage recorded the spheres (storage indices) of each chunk's
    // deepest pair: their bodies' ids (the merge only copies them)
    if total.max_overlap_ratio > 0.0 {
        total.max_overlap_bodies = total
            .max_overlap_bodies
            .map(|x| sp.gid[x as usize] >> SPHERE_ID_BITS);
    }
    for s in chunk_stats.iter() {
        total.merge(s);
    }
    *stats = total;
    // each wall's load summed over the chunks in order, read in the order
    // the chunks' loads are stored
    wall_loads.fill(WallLoad::default());
    for chunk in chunk_wall_loads.chunks_exact(nw.max(1)).take(nchunks) {
        for (l, c) in wall_loads.iter_mut().zip(chunk) {
            l.force += c.force;
            l.torque += c.torque;
        }
    }
    phase.bodies_lag = next.is_some_and(|h| h.lags());
    (any_stale.into_inner(), pair_time)
}

#[cfg(test)]
mod tests {
    use crate::testbed::tetra_lattice_bed;

    /// Regression for the pair stage's body sums: on two threads, the bodies
    /// on the seam between the runs are summed by the gather and the others
    /// by the pair stage (both paths run), and every body's force and torque
    /// are bit for bit those of one thread, where the pair stage sums all.
    #[test]
    fn seam_bodies_are_summed_by_the_gather_with_the_same_bits() {
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut w = tetra_lattice_bed(8, 8, 4, None);
                w.run(3000).unwrap();
                let ready = w.scratch.body_ready.clone();
                let forces: Vec<u64> = (0..w.bodies.len())
                    .flat_map(|i| {
                        let (f, m) = (w.bodies.force[i], w.bodies.torque[i]);
                        [f.x, f.y, f.z, m.x, m.y, m.z].map(f64::to_bits)
                    })
                    .collect();
                (ready, forces, w.stats.pair_contacts)
            })
        };
        let (ready1, f1, contacts) = run(1);
        let (ready2, f2, _) = run(2);
        assert!(contacts > 100, "too few contacts to test: {contacts}");
        assert!(
            ready1.iter().all(|&r| r),
            "one thread: the pair stage sums every body"
        );
        let seam = ready2.iter().filter(|&&r| !r).count();
        assert!(
            seam > 0 && seam < ready2.len(),
            "two threads: {seam} of {} bodies on the seam",
            ready2.len()
        );
        assert!(f1 == f2, "body forces differ between 1 and 2 threads");
    }
}
