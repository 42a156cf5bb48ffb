//! The gather: per chunk of bodies, in a fixed order, each body's load and
//! the end of its step. The stages of one body, in order (see
//! [`Gather::chunk`]):
//!
//! 1. **pair load**: the sums of its sphere–sphere contacts, which the pair
//!    stage left in `PairBody::col` (or, for a body on the seam between two
//!    threads' runs, summed here from the pairs' j-side loads);
//! 2. **body forces**: gravity, `m g`;
//! 3. **walls**: its sphere–wall contacts (`super::wall_contacts`, their
//!    law run as vector lanes), for the bodies with wall-list entries,
//!    whose loads are therefore made first, in the order of the list;
//! 3b. **coupling**: external loads and the fluid force
//!    ([`super::coupling`]), only in a world with a fluid or external
//!    loads set;
//! 4. **final kick**: the second half kick ([`super::kick::FinalKick`]);
//! 5. **tally**: kinetic energy, mass and the health checks, per chunk;
//! 6. **next first half**: inside a fused stretch of steps, the next step's
//!    first half ([`FirstHalf`]), a block of bodies at a time after their
//!    kicks, while their state is in the cache.
//!
//! Body force and torque (docs/theory.md T-11), world frame:
//! `F = m g + Σ_s F_s`, `M = Σ_s [(x_s − r_cm) × F_s + T_s]`, where `F_s` is
//! the total contact force on sphere `s` and `T_s` the torque of its contacts
//! about the sphere centre, `Σ (x_c − x_s) × f + couples`. This equals
//! `Σ (x_c − r_cm) × f` over the contacts.
//!
//! Wall loads and statistics are summed per chunk, then over the chunks in
//! order (the pair stage's chunks first): the same bits for any thread count.

use super::body_props::BodyProps;
use super::coupling::{CouplingPass, CouplingWrites};
use super::first_half::FirstHalf;
use super::first_half_lanes::{BodyLanes, LANES};
use super::kick::{FinalKick, Held};
use super::pair_kernel::RowCtx;
use super::pair_stage::{pair_cost, pair_forces, pair_run, prepare_pairs, row_ctx};
use super::wall_contacts::{ChunkSums, WallPass, WallScratch};
use crate::neighbor::pairs::column_sum;
use crate::neighbor::{PairBody, PairList};
use crate::par::affinity::{
    body_chunk_cost, for_each_chunk_with, for_each_run_then, Balance, FORCE_LOOP, GATHER_LOOP,
    LOOPS,
};
use crate::par::prefetch::prefetch;
use crate::par::shared::{at, SharedMut};
use crate::sphere::{Spheres, SPHERE_ID_BITS};
use crate::stats::{all_finite, BodyTally, ContactStats};
use crate::wall::WallLoad;
use crate::world::World;
use glam::DVec3;
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

/// Bodies ahead whose column sum ([`PairBody::col`]) the gather prefetches.
const BODY_PREFETCH: usize = 4;

/// On one thread, in a bed beyond the caches ([`RowCtx::prefetch`]): the
/// chunks the pair stage and the gather take in turn
/// (`affinity::for_each_run_then`), so that the gather finds a block's
/// packed records and sphere lines in the core's cache, where its pair
/// stage left them. 8 chunks of tetra bodies (256 bodies, 1 024 spheres)
/// are about 100 KB of what the pair stage reads and writes, well inside
/// a 2 MiB L2. In a bed within the caches the run is one block, as
/// before: the gather finds the records in the cache anyway, and each
/// block ends with a partial batch of the pair kernel.
const ONE_RUN_BLOCK: usize = 8;

/// A body's load: force (N) and torque about its centre of mass (N m),
/// world frame.
type Load = (DVec3, DVec3);

/// Computes all contact forces and the total force and torque on every
/// body, at the current state.
pub(crate) fn compute(w: &mut World) {
    // the pair stage reads the bodies' state from its packed copy, which a
    // step's first half writes; here it comes from the bodies as they are
    w.neighbors.pairs.refresh_bodies(&w.bodies);
    pair_forces(w);
    gather(w, false, None);
}

/// The gather after the pair stage: per body the stages of [`Gather::chunk`]
/// (the final kick only with `kick`). With `next` (which implies `kick`),
/// each body also takes the first half of the next step ([`FirstHalf`]);
/// the result is then whether a sphere moved more than half the skin
/// (else false). A body's first half reads and writes only its own state
/// and spheres, so the blocks change no result.
pub(crate) fn gather(w: &mut World, kick: bool, next: Option<FirstHalf>) -> bool {
    gather_after(w, kick, next, false).0
}

/// The pair stage and then [`gather`] with the kick, in one parallel call
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

/// [`gather`]; with `pairs_first`, [`pairs_and_gather`]: the world's sets
/// taken apart into what the chunks read and write ([`Gather`]), the
/// chunks run, their sums reduced in order.
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
        fluid,
        ..
    } = w;
    let crate::neighbor::NeighborState {
        pairs,
        wall_list,
        records,
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
    let (nb, nw) = (bodies.len(), walls.len());
    let nchunks = nb.div_ceil(chunk);
    // each chunk clears its own slots, on the thread that gathers it: the
    // threads' slots would otherwise be written here, on the calling
    // thread, and move between the cores' caches twice a step
    chunk_stats.resize(nchunks, ContactStats::default());
    chunk_wall_loads.resize(nchunks * nw, WallLoad::default());
    let recording = records.start_wall_chunks(nchunks);
    // exact sums of the step's contacts, when a driver asked for them
    let sums_step = *step + 1;
    let sums = (records.sums.begin(sums_step, nw) && pairs_first).then_some(&records.sums);
    // inside a fused stretch the bodies' centres, velocities and angular
    // velocities are current in the packed copy only (StepPhase::bodies_lag);
    // lagging bodies are kicked here, and a first half fused into this
    // gather keeps them lagging
    let lag = phase.bodies_lag();
    debug_assert!(!lag || (kick && next.as_ref().map_or(true, FirstHalf::lags)));
    let pair_body = SharedMut::new(&mut pairs.body);
    let ready = SharedMut::new(body_ready);
    let (rows, pairs) = if pairs_first {
        let record = recording.then(|| SharedMut::new(&mut records.pair));
        let (rows, pairs) = row_ctx(
            sp,
            table,
            config,
            pairs,
            ready,
            record,
            part.as_deref(),
            chunk,
            sums,
        );
        (Some(rows), pairs)
    } else {
        (None, &*pairs)
    };
    let loads = SharedMut::new(chunk_wall_loads);
    let stats_out = SharedMut::new(chunk_stats);
    let ends_step = kick;
    let coupling_writes = CouplingWrites::new(fluid.is_some(), &mut bodies.coupling, nb);
    // SAFETY: the gather resizes nothing, and writes no orientation (the
    // first half of the next step writes its body's, after its kick).
    let kick =
        kick.then(|| unsafe { FinalKick::new(config.dt, *step, config.rotation, props, bodies) });
    let g = Gather {
        chunk,
        nb,
        nw,
        gravity: config.gravity,
        lag,
        owned: part.as_ref().map(|p| &p.owned[..]),
        sp,
        pairs,
        pair_body,
        ready,
        // SAFETY: as above; the table was refreshed for these bodies.
        mass: unsafe { BodyProps::new(props, bodies) },
        kick,
        next: next.as_ref(),
        pos: SharedMut::new(&mut bodies.position),
        vel: SharedMut::new(&mut bodies.velocity),
        angm: SharedMut::new(&mut bodies.angular_momentum),
        omega: SharedMut::new(&mut bodies.angular_velocity),
        force: SharedMut::new(&mut bodies.force),
        torque: SharedMut::new(&mut bodies.torque),
        stats_out,
        loads,
        ids: &bodies.id,
        coupling: CouplingPass::new(
            fluid.as_ref(),
            &bodies.coupling,
            coupling_writes,
            &bodies.template,
            config.gravity,
            config.dt,
            ends_step,
        ),
        wall_pass: WallPass::new(
            sp,
            bodies,
            lag.then_some(pair_body),
            table,
            walls,
            meshes,
            config.dt,
            wall_list,
            loads,
            &mut records.wall,
            recording,
            sums,
        ),
    };
    let gather_cost = body_chunk_cost(body_cost, nb, chunk);
    let pair_stats = SharedMut::new(chunk_pair_stats);
    let (any_stale, pair_time) =
        run_chunks(&g, rows.as_ref(), nchunks, gather_cost, balance, pair_stats);
    *stats = total_stats(chunk_pair_stats, chunk_stats, sp);
    if sums.is_some() {
        records.sums.end(sums_step);
    }
    sum_wall_loads(wall_loads, chunk_wall_loads, nchunks);
    if !next.as_ref().is_some_and(FirstHalf::lags) {
        phase.bodies_caught_up();
    }
    (any_stale, pair_time)
}

/// Runs the gather's chunks, each once: the gather alone, or with `rows`
/// each thread's run of chunks through the pair stage and then the gather
/// ([`pairs_and_gather`]). Returns whether a sphere moved more than half
/// the skin in a fused first half, and the time the calling thread spent
/// in the pair stage.
fn run_chunks(
    g: &Gather,
    rows: Option<&RowCtx>,
    nchunks: usize,
    gather_cost: impl Fn(usize) -> u64 + Sync,
    balance: &mut [Balance; LOOPS],
    pair_stats: SharedMut<ContactStats>,
) -> (bool, Duration) {
    let (chunk, nb, ready) = (g.chunk, g.nb, g.ready);
    let any_stale = AtomicBool::new(false);
    // SAFETY: every chunk is gathered once, on one thread.
    let gather_chunk = |s: &mut ChunkScratch, c: usize| {
        if unsafe { g.chunk(s, c) } {
            any_stale.store(true, Ordering::Relaxed);
        }
    };
    let pair_time = match rows {
        None => {
            let balance = &mut balance[GATHER_LOOP];
            for_each_chunk_with(
                nchunks,
                gather_cost,
                balance,
                ChunkScratch::new,
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
            let block = if rows.prefetch {
                ONE_RUN_BLOCK
            } else {
                nchunks
            };
            for_each_run_then(
                nchunks,
                |c| pair_cost(rows, c),
                gather_cost,
                &mut balance[FORCE_LOOP],
                block,
                // SAFETY: every run is run once, on one thread.
                |run, part| unsafe { pair_run(rows, run, part, &pair_stats) },
                fed_earlier,
                ChunkScratch::new,
                gather_chunk,
            )
        }
    };
    (any_stale.into_inner(), pair_time)
}

/// The step's statistics: the pair stage's chunks, then the gather's, in
/// order.
fn total_stats(pair: &[ContactStats], gather: &[ContactStats], sp: &Spheres) -> ContactStats {
    let mut total = ContactStats::default();
    for s in pair {
        total.merge(s);
    }
    // the pair stage recorded the spheres (storage indices) of each chunk's
    // deepest pair: their bodies' ids (the merge only copies them)
    if total.max_overlap_ratio > 0.0 {
        total.max_overlap_bodies = total
            .max_overlap_bodies
            .map(|x| sp.gid[x as usize] >> SPHERE_ID_BITS);
    }
    for s in gather {
        total.merge(s);
    }
    total
}

/// Each wall's load summed over the chunks in order, read in the order the
/// chunks' loads are stored.
fn sum_wall_loads(wall_loads: &mut [WallLoad], chunks: &[WallLoad], nchunks: usize) {
    wall_loads.fill(WallLoad::default());
    for chunk in chunks.chunks_exact(wall_loads.len().max(1)).take(nchunks) {
        for (l, c) in wall_loads.iter_mut().zip(chunk) {
            l.force += c.force;
            l.torque += c.torque;
        }
    }
}

/// Per thread: the wall touches awaiting their law and the chunk's bodies'
/// loads; the first-half lanes; the bodies of a block, from their final
/// kicks to their first half (every slot is written before it is read, so
/// one array per thread, not a zeroed one per chunk).
struct ChunkScratch {
    walls: WallScratch,
    lanes: BodyLanes,
    held: [Held; FIRST_HALF_BLOCK],
}

impl ChunkScratch {
    fn new() -> Self {
        ChunkScratch {
            walls: WallScratch::new(),
            lanes: BodyLanes::idle(),
            held: [Held::default(); FIRST_HALF_BLOCK],
        }
    }
}

/// What the gather's chunks read and write: pointers into the world's
/// body, pair and statistics arrays, each body's entries written by the
/// one chunk that holds the body.
struct Gather<'a> {
    /// Bodies per chunk.
    chunk: usize,
    nb: usize,
    nw: usize,
    /// m/s², world frame.
    gravity: DVec3,
    /// The centres, velocities and angular velocities are current in the
    /// packed pair records only (`StepPhase::bodies_lag`).
    lag: bool,
    /// A partitioned world's own bodies: its ghosts take their owners'
    /// state after the step (`partition::ghosts::refresh`), so the gather
    /// skips them, and their owners count them in the statistics and wall
    /// loads.
    owned: Option<&'a [bool]>,
    sp: &'a Spheres,
    pairs: &'a PairList,
    pair_body: SharedMut<PairBody>,
    /// Per body: the pair stage of its run summed its column.
    ready: SharedMut<bool>,
    mass: BodyProps,
    kick: Option<FinalKick>,
    next: Option<&'a FirstHalf>,
    pos: SharedMut<DVec3>,
    vel: SharedMut<DVec3>,
    angm: SharedMut<DVec3>,
    omega: SharedMut<DVec3>,
    force: SharedMut<DVec3>,
    torque: SharedMut<DVec3>,
    /// Per chunk: its statistics.
    stats_out: SharedMut<ContactStats>,
    /// Per chunk and wall: the chunk's load on the wall.
    loads: SharedMut<WallLoad>,
    ids: &'a [u64],
    /// The coupling stage, where a fluid or external loads are set.
    coupling: Option<CouplingPass<'a>>,
    wall_pass: WallPass<'a>,
}

impl Gather<'_> {
    /// Chunk `c`: its bodies through the stages, in order; true when one
    /// of their spheres moved more than half the skin in the next first
    /// half.
    ///
    /// # Safety
    /// Chunk `c` is gathered once, on one thread, after the pair stage of
    /// its bodies (and of the bodies its rows feed) is over.
    #[inline(always)]
    unsafe fn chunk(&self, s: &mut ChunkScratch, c: usize) -> bool {
        let b0 = c * self.chunk;
        let b1 = (b0 + self.chunk).min(self.nb);
        let mut sums = self.open_chunk(c, b0);
        let walled = self.walls(&mut s.walls, &mut sums);
        let mut tally = BodyTally::default();
        let mut stale = false;
        for k0 in (b0..b1).step_by(FIRST_HALF_BLOCK) {
            let k1 = (k0 + FIRST_HALF_BLOCK).min(b1);
            for bi in k0..k1 {
                if bi + BODY_PREFETCH < b1 {
                    self.prefetch_pair_load(bi + BODY_PREFETCH);
                }
                if self.ghost(bi) {
                    self.skip_ghost(bi);
                    continue;
                }
                let load = if walled >> (bi - b0) & 1 != 0 {
                    s.walls.load[bi - b0]
                } else {
                    self.body_forces(bi, self.pair_load(bi))
                };
                let load = self.couple(bi, load);
                let com = self.centre(bi);
                let kicked = self.final_kick(bi, load);
                self.tally(&mut tally, bi, com, &kicked);
                self.keep(bi, com, kicked, &mut s.held[bi - k0]);
            }
            stale |= self.next_first_half(k0, &mut s.held[..k1 - k0], &mut s.lanes);
        }
        tally.store(sums.stat);
        stale
    }

    /// Chunk `c`'s sums, cleared: its statistics and its loads on the walls.
    ///
    /// # Safety
    /// Chunk `c`'s slots are written by chunk `c` only.
    #[inline(always)]
    unsafe fn open_chunk(&self, c: usize, b0: usize) -> ChunkSums<'_> {
        for wi in 0..self.nw {
            *self.loads.get(c * self.nw + wi) = WallLoad::default();
        }
        let stat = self.stats_out.get(c);
        *stat = ContactStats::default();
        ChunkSums { c, b0, stat }
    }

    /// Body `bi` is a ghost of a partitioned world.
    ///
    /// # Safety
    /// `bi` is a body index.
    #[inline(always)]
    unsafe fn ghost(&self, bi: usize) -> bool {
        self.owned.is_some_and(|o| !*o.get_unchecked(bi))
    }

    /// A ghost's turn: no load, walls, kick or tally (its owner's state
    /// replaces it after the step, and its pair load here lacks the pairs
    /// with other ghosts); only its pair load is set back to zero for the
    /// next step. A split world's steps are never fused, so no first half
    /// follows here.
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline(always)]
    unsafe fn skip_ghost(&self, bi: usize) {
        debug_assert!(self.next.is_none());
        (*self.pair_body.ptr(bi)).col = Default::default();
    }

    /// Body `bi`'s centre of mass, m, world frame.
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline(always)]
    unsafe fn centre(&self, bi: usize) -> DVec3 {
        if self.lag {
            (*self.pair_body.ptr(bi)).position
        } else {
            self.pos.read(bi)
        }
    }

    /// Stage 1, pair load: the sum of body `bi`'s sphere–sphere contacts,
    /// read and reset for the next step; for a body on the seam between
    /// two threads' runs, its row sum plus the column loads of its pairs.
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's; the pair stage of its run is over.
    #[inline(always)]
    unsafe fn pair_load(&self, bi: usize) -> crate::neighbor::BodyLoad {
        let own = std::mem::take(&mut (*self.pair_body.ptr(bi)).col);
        if self.ready.read(bi) {
            own
        } else {
            // the pair list was built for these bodies (a rebuild precedes
            // every gather after a change)
            let p = self.pairs;
            own.add(column_sum(p.load_j.as_ptr(), &p.col_start, &p.col_pair, bi))
        }
    }

    /// Stage 2, body forces: gravity added to body `bi`'s pair load.
    ///
    /// # Safety
    /// `bi` is a body index.
    #[inline(always)]
    unsafe fn body_forces(&self, bi: usize, pair: crate::neighbor::BodyLoad) -> Load {
        (self.mass.mass(bi) * self.gravity + pair.force, pair.torque)
    }

    /// Stage 3b, coupling: body `bi`'s external and fluid loads added to
    /// its `load`, where the world has them ([`CouplingPass`]).
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline(always)]
    unsafe fn couple(&self, bi: usize, load: Load) -> Load {
        match &self.coupling {
            None => load,
            Some(c) => {
                let v = if self.lag {
                    (*self.pair_body.ptr(bi)).velocity
                } else {
                    self.vel.read(bi)
                };
                let x = self.pos.read(bi);
                c.apply(bi, load, v, x, self.mass.mass(bi) * self.mass.factor(bi))
            }
        }
    }

    /// Prefetches body `bi`'s pair load (the pair stage wrote it; 7 % of
    /// this pass at 10⁶ spheres, read when its turn comes).
    #[inline(always)]
    fn prefetch_pair_load(&self, bi: usize) {
        // SAFETY: a body of this chunk; a prefetch never faults.
        unsafe { prefetch(std::ptr::addr_of!((*self.pair_body.ptr(bi)).col)) };
    }

    /// Stage 3, walls: the bodies of the chunk with wall-list entries, in
    /// the list's order (which is theirs): their pair loads and body
    /// forces, then their wall touches (collected body by body, their law
    /// run in batches) added to them, into `ws.load`. Returns the bodies
    /// done, as bits from the chunk's first.
    ///
    /// # Safety
    /// As [`Gather::chunk`], for the chunk of `sums`.
    #[inline(always)]
    unsafe fn walls(&self, ws: &mut WallScratch, sums: &mut ChunkSums) -> u64 {
        let (wp, sp, b0) = (&self.wall_pass, self.sp, sums.b0);
        let (mut e, e_end) = (
            wp.chunk_start[sums.c] as usize,
            wp.chunk_start[sums.c + 1] as usize,
        );
        // the next entry whose sphere is to be prefetched
        let mut e_pf = e;
        let mut walled = 0u64;
        while e < e_end {
            let bi = at(&sp.body, at(wp.entry_sphere, e) as usize) as usize;
            // the body's entries: e0..e
            let e0 = e;
            let s_end = sp.of_body(bi).end;
            while e < e_end && (at(wp.entry_sphere, e) as usize) < s_end {
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
                prefetch(sp.state.as_ptr().add(at(wp.entry_sphere, e_pf) as usize));
                e_pf += 1;
            }
            if self.ghost(bi) {
                // its owner meets the walls
                continue;
            }
            ws.load[bi - b0] = self.body_forces(bi, self.pair_load(bi));
            walled |= 1 << (bi - b0);
            wp.collect(ws, bi, self.centre(bi), e0..e, sums);
        }
        wp.flush(ws, sums);
        walled
    }

    /// Stage 4, final kick: body `bi`'s velocity, angular momentum and
    /// angular velocity, kicked by its `load` when the gather kicks; its
    /// load is kept for the next step's first half, unless that is fused
    /// here (then it is held with the state).
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline(always)]
    unsafe fn final_kick(&self, bi: usize, (f, m): Load) -> Held {
        // the velocities as local values, kicked, then stored once: read
        // back from memory right after the kick's per-component stores,
        // they could not be forwarded (a stall measured at 6-8 % of this
        // pass)
        let l = self.angm.read(bi);
        let (mut v, mut l, mut om) = if self.lag {
            let pb = self.pair_body.ptr(bi);
            ((*pb).velocity, l, (*pb).angular_velocity)
        } else {
            (self.vel.read(bi), l, self.omega.read(bi))
        };
        if self.next.is_none() {
            *self.force.get(bi) = f;
            *self.torque.get(bi) = m;
        }
        if let Some(k) = &self.kick {
            k.apply(bi, &mut v, &mut l, &mut om, f, m);
        }
        Held { v, l, om, f, m }
    }

    /// Stage 5, tally: body `bi`'s kinetic energy at the end of the step,
    /// after the kick (a force that would fling a body out of the domain
    /// shows here, before the body is removed), its mass, and whether its
    /// state is finite (a ghost never comes here: its owner counts it).
    ///
    /// # Safety
    /// `bi` is a body index.
    #[inline(always)]
    unsafe fn tally(&self, tally: &mut BodyTally, bi: usize, com: DVec3, h: &Held) {
        let mass = self.mass.mass(bi);
        let ke = 0.5 * mass * h.v.length_squared() + 0.5 * h.om.dot(h.l);
        tally.add(
            ke,
            mass,
            || all_finite(ke, [com, h.f, h.m]),
            || self.ids[bi],
        );
    }

    /// Body `bi`'s kicked state: held in `slot` for the next first half
    /// when that is fused here, else stored (the centre too, where it
    /// lagged in the packed copy).
    ///
    /// # Safety
    /// Body `bi` is the calling chunk's.
    #[inline(always)]
    unsafe fn keep(&self, bi: usize, com: DVec3, h: Held, slot: &mut Held) {
        if self.next.is_some() {
            *slot = h;
        } else if self.kick.is_some() {
            *self.vel.get(bi) = h.v;
            *self.angm.get(bi) = h.l;
            *self.omega.get(bi) = h.om;
            if self.lag {
                *self.pos.get(bi) = com;
            }
        }
    }

    /// Stage 6, next first half: the bodies `k0..k0 + held.len()`, held
    /// after their kicks, take the next step's first half when it is fused
    /// here; true when one of their spheres moved more than half the skin.
    ///
    /// # Safety
    /// The bodies (and their spheres) are the calling chunk's.
    #[inline(always)]
    unsafe fn next_first_half(&self, k0: usize, held: &mut [Held], lanes: &mut BodyLanes) -> bool {
        match self.next {
            Some(h) => h.apply_block(k0, held, lanes),
            None => false,
        }
    }
}
