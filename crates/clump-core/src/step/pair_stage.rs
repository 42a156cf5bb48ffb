//! The pair stage: the contact forces of every candidate sphere pair of
//! two bodies, over the rows of the half list (each pair's force is
//! computed once, in batches, by `super::pair_kernel`, with its torques
//! about both bodies' centres of mass). Sphere `i`'s side is added to the
//! row sum of its body while its row is evaluated, sphere `j`'s side to the
//! column sum of `j`'s body, or recorded with the pair when that body is on
//! a seam between two threads' runs (`neighbor::pairs::column_sum`); a
//! body's row and column sums meet in `PairBody::col`, which the gather
//! reads (`super::gather`).

use super::pair_kernel::RowCtx;
use crate::multi_contact::{MultiContact, PartnerCounts};
use crate::par::affinity::{for_each_run, several_runs, PAIR_LOOP};
use crate::par::shared::SharedMut;
use crate::stats::ContactStats;
use crate::world::World;
use rayon::prelude::*;

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
        None,
    );
    let balance = &mut w.scratch.balance[PAIR_LOOP];
    // SAFETY: every run is run once, on one thread.
    for_each_run(
        nchunks,
        |c| pair_cost(&rows, c),
        balance,
        |run| unsafe { pair_run(&rows, run.clone(), run, &stats) },
    );
}

/// What the pair stage needs before its rows are evaluated, on one thread:
/// the `average` scales, the statistics slots and ready flags sized, the
/// seams' column lists (several runs), rolling springs where a law keeps
/// them, and the contact records sized. Returns the number of chunks.
pub(super) fn prepare_pairs(w: &mut World) -> usize {
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
pub(super) fn row_ctx<'a>(
    sp: &'a crate::sphere::Spheres,
    table: &'a crate::contact::ContactTable,
    config: &crate::world::WorldConfig,
    pairs: &'a mut crate::neighbor::PairList,
    body_ready: SharedMut<bool>,
    record: Option<SharedMut<crate::contact::record::PairRecord>>,
    part: Option<&'a crate::partition::Part>,
    body_chunk: usize,
    sums: Option<&'a crate::contact::step_sums::StepSums>,
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
        sums,
    };
    (rows, pairs)
}

/// The pair stage's cost estimate of the body chunks `0..c` (the gather's
/// chunks, so that a body's rows never straddle two threads): one unit per
/// sphere and per candidate pair.
pub(super) fn pair_cost(rows: &RowCtx, c: usize) -> u64 {
    let first = &rows.sp.body_first;
    let nb = first.len().saturating_sub(1);
    let s = first
        .get((c * rows.body_chunk).min(nb))
        .map_or(0, |&s| s as usize);
    rows.row_start.get(s).map_or(0, |&p| p as u64) + s as u64
}

/// Evaluates the rows of the body chunks `part` of the chunks `run`, one
/// thread's run, as one batch (a batch may span chunks: the statistics go
/// to each pair's own chunk, in pair order). A run's parts are evaluated
/// in order, on its thread; the results are those of the whole run at
/// once (the same pairs in the same order).
///
/// # Safety
/// This run owns the rows of its bodies in the half list, their bodies'
/// pair loads and its chunks' statistics slots, no other run's; the column
/// sums it adds to are of bodies complete in it. The parts of `run` before
/// `part` have been evaluated.
pub(super) unsafe fn pair_run(
    rows: &RowCtx,
    run: std::ops::Range<usize>,
    part: std::ops::Range<usize>,
    stats: &SharedMut<ContactStats>,
) {
    let first = &rows.sp.body_first;
    let nb = first.len().saturating_sub(1);
    for c in part.clone() {
        // SAFETY: the run's chunks' slots are this run's.
        unsafe { *stats.get(c) = ContactStats::default() };
    }
    let b0 = part.start * rows.body_chunk;
    let b1 = (part.end * rows.body_chunk).min(nb);
    if b0 >= b1 {
        return;
    }
    let run = first[run.start * rows.body_chunk] as usize
        ..first[(run.end * rows.body_chunk).min(nb)] as usize;
    // the thread's batch, kept between steps: every slot is written before
    // it is read, and a new zeroed batch (30 KB) cost 0.6 % of the settled
    // tetra bed's instructions
    BATCH.with(|batch| rows.evaluate(b0..b1, run.clone(), &mut batch.borrow_mut(), stats));
}

thread_local! {
    /// Each thread's scratch for [`pair_run`] (no destructor, so no
    /// allocation on first use).
    static BATCH: std::cell::RefCell<super::pair_kernel::Batch> =
        std::cell::RefCell::new(super::pair_kernel::Batch::default());
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
