//! The sphere–sphere pair kernel: the rows of the half list, evaluated in
//! batches of touching pairs.
//!
//! Per batch, in order:
//! 1. *detect* ([`RowCtx::evaluate`]): a branch-free pass walks the
//!    candidate pairs of the rows and compacts the touching ones into the
//!    batch (the common non-touching pair costs one distance test; stale
//!    state is cleared only when a pair stops touching). With JKR cohesion
//!    a live contact counts as touching until its gap exceeds the model's
//!    reach `δ_c` (a separate instance of the pass, so the default one is
//!    unchanged);
//! 2. *gather*: each touching pair's inputs (world frame: centre
//!    separation, lever arms from the bodies' centres of mass, body
//!    velocities and angular velocities, radii, body
//!    masses, tangential history) are copied into per-quantity arrays;
//!    the bodies' state comes from their packed record ([`PairBody`]), which
//!    the step derives from the bodies in its first half and never exposes;
//! 3. *law*: the contact geometry and the normal–tangential law
//!    ([`SlidingLaw::evaluate`], the same function the scalar contact law
//!    runs) over those arrays. This loop has no branches and no indirect
//!    access, so the compiler turns it into vector instructions: 8
//!    contacts per instruction with AVX-512 (F, VL, DQ), 4 with AVX2, 2
//!    with the baseline SSE2, the widest the processor has chosen at run
//!    time (`crate::par::simd`); vector and scalar IEEE arithmetic give the
//!    same bits. The loop takes every contact as sticking, which spares
//!    it the Coulomb limit's square root and divisions; the few that slide
//!    are evaluated again with the limit from their stored spring
//!    ([`crate::step::law_lanes::finish_sliding`]). Pairs whose model runs the scalar
//!    composition ([`crate::contact::ContactModel::is_extended`], e.g.
//!    LIGGGHTS' tangential rule) are evaluated again by
//!    [`crate::contact::ContactModel::evaluate`] from their stored history,
//!    overwriting their lanes;
//! 4. *scatter*: rolling couples (for laws that have one), then each pair's
//!    history is stored (and the pair marked live), its `i` side is added
//!    to the row sum of `i`'s body and its `j` side to the column sum of
//!    `j`'s body (or recorded with the pair when `j`'s body is on a seam
//!    between two threads' runs), in pair order. The law loop has already
//!    turned each side's torque into the torque about its body's centre of
//!    mass, so these sums are the bodies' pair loads. Once a body's rows
//!    are done its row sum joins its column sum in [`PairBody::col`] (its
//!    column is complete by then: every pair feeding it lies in an earlier
//!    row).
//!
//! The batch keeps pair order, so every sum is taken in ascending pair order
//! and the results do not depend on the thread count. When the step keeps
//! contact records ([`crate::recorded_contacts`]), the scatter also stores each
//! pair's normal, overlap and forces.

use crate::contact::{ContactHistory, ContactInput};
use crate::neighbor::pairs::{BodyLoad, PairBody};
use crate::neighbor::topo::RowWalk;
use crate::par::prefetch::prefetch;
use crate::par::shared::{at, SharedMut};
use crate::par::simd::{get3, set3, Simd};
use crate::stats::ContactStats;
use crate::step::law_lanes::{finish_sliding, run_law};
use glam::DVec3;
use lanes::Lanes;

mod lanes;

/// What the pair-force rows read and write (world frame, SI units).
pub(super) struct RowCtx<'a> {
    /// Time step, s.
    pub dt: f64,
    /// The domain, for periodic image shifts.
    pub domain: crate::boundary::Domain,
    /// Some axis of the domain is periodic.
    pub any_periodic: bool,
    /// Spheres (centres and radii, m; owners; materials).
    pub sp: &'a crate::sphere::Spheres,
    /// Contact models per material pair.
    pub table: &'a crate::contact::ContactTable,
    /// Row offsets of the half list, one per sphere plus one.
    pub row_start: &'a [u32],
    /// Partner, periodic image, live flag and row step of each pair (the
    /// flag is written).
    pub topo: SharedMut<crate::neighbor::PairTopo>,
    /// Multi-contact scale per pair (empty: all 1).
    pub scale: &'a [f64],
    /// Tangential spring per pair, m (written).
    pub tangential: SharedMut<DVec3>,
    /// Rolling spring per pair, N m (written by laws with rolling
    /// resistance only; empty when no law has one).
    pub rolling: SharedMut<DVec3>,
    /// MDR profile per pair ([`crate::contact::mdr`]; written by
    /// `tangential = "mdr"` laws only; empty when no law keeps one).
    pub slip: SharedMut<crate::contact::mdr::SlipProfile>,
    /// `j`-side loads of the pairs whose `j`'s body is on a seam, in pair
    /// order ([`PairList::load_j`]; written; empty on one run).
    ///
    /// [`PairList::load_j`]: crate::neighbor::PairList::load_j
    pub load_j: SharedMut<BodyLoad>,
    /// Per body: centre of mass (m), velocity (m/s), angular velocity
    /// (rad/s), mass (kg), and the column sum, written for the bodies
    /// complete in their thread's run ([`PairBody`]).
    pub body: SharedMut<PairBody>,
    /// First row feeding each body's columns ([`PairList::first_feed`];
    /// empty on one run).
    ///
    /// [`PairList::first_feed`]: crate::neighbor::PairList::first_feed
    pub first_feed: &'a [u32],
    /// Per body: whether its [`PairBody::col`] holds its column sum this step
    /// (written; false: the gather sums it from `load_j`).
    pub body_ready: SharedMut<bool>,
    /// Per pair: the contact's record, when this step keeps them
    /// ([`crate::recorded_contacts`]).
    pub record: Option<SharedMut<crate::contact::record::PairRecord>>,
    /// The vector instructions the law loop may use ([`simd`]).
    pub simd: Simd,
    /// A bed beyond the caches ([`PREFETCH_MIN_SPHERES`]): the detect pass
    /// prefetches further ahead ([`LARGE_AHEAD`]) and also the partner
    /// body's data.
    pub prefetch: bool,
    /// Per body: its pairs count in the statistics (a partitioned world
    /// counts the pairs in the rows of its owned bodies only); `None`: all.
    pub counted: Option<&'a [bool]>,
    /// Bodies per statistics chunk ([`crate::par::affinity::body_chunk`]).
    pub body_chunk: usize,
    /// The exact sums of the counted contacts, when this step makes them.
    pub sums: Option<&'a crate::contact::step_sums::StepSums>,
}

impl RowCtx<'_> {
    /// Evaluates the rows of the spheres of `bodies` (see the module docs),
    /// using `batch` as scratch. The thread's run is the spheres `run`
    /// (they hold those of `bodies`; one thread evaluates its run's rows
    /// in one call or in several, in order): a body all of whose column
    /// pairs lie in rows from `run.start` on (`first_feed`) is complete in
    /// the run, and its column sum
    /// is accumulated here (it is marked in `body_ready`); the gather sums
    /// the others' (a body on the seam with an earlier run) from the pairs'
    /// records. Which does the sum never changes the result
    /// ([`crate::neighbor::pairs::column_sum`]).
    ///
    /// # Safety
    /// No other thread touches these rows (their pairs' topology, history
    /// and `load_j`) or these bodies' row sums during the call. The pair
    /// list must be consistent with the spheres (every index in range),
    /// which every rebuild guarantees; indexing is unchecked in this hot
    /// loop (checked in debug builds).
    #[inline(never)]
    pub(super) unsafe fn evaluate(
        &self,
        bodies: std::ops::Range<usize>,
        run: std::ops::Range<usize>,
        batch: &mut Batch,
        stats: &SharedMut<ContactStats>,
    ) {
        // the flags as constants: tested on every candidate pair, they were
        // 1 % of the settled tetra bed's instructions
        let (b, r, s) = (bodies, run, stats);
        match (self.table.any_reach(), self.prefetch, self.any_periodic) {
            (false, false, false) => self.evaluate_rows::<false, false, false>(b, r, batch, s),
            (false, false, true) => self.evaluate_rows::<false, false, true>(b, r, batch, s),
            (false, true, false) => self.evaluate_rows::<false, true, false>(b, r, batch, s),
            (false, true, true) => self.evaluate_rows::<false, true, true>(b, r, batch, s),
            (true, false, false) => self.evaluate_rows::<true, false, false>(b, r, batch, s),
            (true, false, true) => self.evaluate_rows::<true, false, true>(b, r, batch, s),
            (true, true, false) => self.evaluate_rows::<true, true, false>(b, r, batch, s),
            (true, true, true) => self.evaluate_rows::<true, true, true>(b, r, batch, s),
        }
    }

    /// [`Self::evaluate`]; `REACH`: some model keeps a live contact beyond
    /// touching (JKR, [`crate::contact::ContactModel::reach`]), so the
    /// detect pass also keeps a live pair whose gap is within its reach;
    /// `LARGE`: [`RowCtx::prefetch`]; `PERIODIC`: [`RowCtx::any_periodic`].
    #[inline(always)]
    unsafe fn evaluate_rows<const REACH: bool, const LARGE: bool, const PERIODIC: bool>(
        &self,
        bodies: std::ops::Range<usize>,
        run: std::ops::Range<usize>,
        batch: &mut Batch,
        stats: &SharedMut<ContactStats>,
    ) {
        let sp = self.sp;
        let n = sp.len();
        let np = self.topo.len();
        let topo = &self.topo;
        debug_assert!(self.row_start.len() == n + 1 && bodies.end < sp.body_first.len());
        debug_assert!(self.row_start[n] as usize == np);
        let first = &sp.body_first;
        let spheres = at(first, bodies.start) as usize..at(first, bodies.end) as usize;
        debug_assert!(run.start <= spheres.start && spheres.end <= run.end && run.end <= n);
        (batch.run_start, batch.run_end) = (run.start, run.end);
        // one run (one thread) has every body complete in it, and no
        // column lists (`first_feed` is empty)
        let whole = run.start == 0 && run.end == n;
        for b in bodies.clone() {
            *self.body_ready.get(b) = whole || at(self.first_feed, b) as usize >= run.start;
        }
        batch.carry = None;
        // the batch length lives in a register during the detect pass
        let mut len = 0usize;
        let mut n_clear = 0usize;
        // one flat loop over the pairs of the run's rows
        let pairs =
            at(self.row_start, spheres.start) as usize..at(self.row_start, spheres.end) as usize;
        let ahead = if LARGE { LARGE_AHEAD } else { SMALL_AHEAD };
        let mut walk = match pairs.is_empty() {
            false => RowWalk::at(self.row_start, pairs.start, topo.read(pairs.start)),
            true => RowWalk::new(self.row_start),
        };
        for p in pairs {
            let t = topo.read(p);
            let (i, j) = (walk.next(p, t), t.j as usize);
            // the partner a few pairs ahead: its packed state line, the
            // top stall of this loop (it misses the per-core cache even at
            // 8 000 spheres, where the pair stage streams about 1.3 MB, and
            // in a large bed its line comes from memory, as the pair stage
            // is the first to read it in a step); its body index,
            // read half-way (below); and the pair's tangential spring,
            // which the batch gathers once the pair is found touching
            // (read there, it was 7 % of this function at 40 000 spheres)
            if p + ahead < np {
                let partner = topo.read(p + ahead).j as usize;
                prefetch(sp.state.as_ptr().add(partner));
                prefetch(sp.body.as_ptr().add(partner));
                prefetch(self.tangential.as_ptr().add(p + ahead));
            }
            if LARGE && p + PREFETCH_BODY < np {
                // in a bed larger than the caches: the partner body's
                // column sum, angular velocity, mass, centre and velocity
                // of the pair half-way ahead, which the batch gather and
                // scatter read (at 10⁶ spheres the partner body's ω was the
                // top stall, 11 % of this function); its body index was
                // prefetched above (read for the current pair, it missed:
                // 6 % at 40 000 spheres)
                let bj = at(&sp.body, topo.read(p + PREFETCH_BODY).j as usize) as usize;
                let line = self.body.as_ptr().add(bj) as *const u8;
                prefetch(line);
                prefetch(line.add(64));
            }
            let si = self.sphere(i);
            let d = si.position - self.partner_position::<PERIODIC>(j, t.shift);
            let rsum = si.radius + self.sphere(j).radius;
            let mut touching = d.length_squared() < rsum * rsum;
            if REACH && !touching && t.live() {
                // a live contact that may last while apart (JKR)
                let rj = self.sphere(j).radius;
                let reach = self
                    .table
                    .by_index(self.model_index(i, p))
                    .reach(si.radius * rj / (si.radius + rj));
                touching = d.length() < rsum + reach;
            }
            // branch-free compaction: the slot is always written, kept
            // only when touching (len < BATCH here)
            debug_assert!(len < BATCH);
            *batch.pair.get_unchecked_mut(len) = p as u32;
            *batch.row.get_unchecked_mut(len) = i as u32;
            len += touching as usize;
            // pairs that stopped touching are compacted the same way and
            // cleared at the flush: a branch on `!touching && live` here
            // went on `touching` (or on `live`), as good as random in a
            // dense bed, where half the candidates touch
            *batch.clear.get_unchecked_mut(n_clear) = p as u32;
            n_clear += (!touching & t.live()) as usize;
            if len == BATCH || n_clear == BATCH {
                self.clear_pairs(&batch.clear[..n_clear]);
                n_clear = 0;
                batch.len = len;
                self.contacts::<PERIODIC>(batch, stats);
                len = 0;
            }
        }
        self.clear_pairs(&batch.clear[..n_clear]);
        batch.len = len;
        self.contacts::<PERIODIC>(batch, stats);
        if let Some((b, li)) = batch.carry.take() {
            self.finish_row(b, li);
        }
    }

    /// Body `b`'s rows are all evaluated, their `i` sides summing to `li`:
    /// its pair load goes to its [`PairBody::col`], `li + column` when its
    /// column sum is complete there (`body_ready`; all feeding rows come
    /// before its own), else `li` alone (the gather adds the column from the
    /// pairs' records). A body without touching pairs in its rows keeps its
    /// column sum as it is: the same bits as `0 + column`, as a column sum
    /// starts from +0 and so never is −0.
    ///
    /// # Safety
    /// `b` is a body of this thread's run.
    #[inline(always)]
    unsafe fn finish_row(&self, b: usize, li: BodyLoad) {
        let c = &mut *std::ptr::addr_of_mut!((*self.body.ptr(b)).col);
        *c = if *self.body_ready.get(b) {
            li.add(*c)
        } else {
            li
        };
    }

    /// Clears what a contact left on the pairs `ps`, which no longer touch:
    /// the live flag, the springs and the `j`-side load (the last two where
    /// the list keeps them).
    ///
    /// # Safety
    /// As [`Self::evaluate`]: the pairs lie in this thread's rows.
    #[inline(always)]
    unsafe fn clear_pairs(&self, ps: &[u32]) {
        let (rolling, seams) = (self.rolling.len() != 0, self.load_j.len() != 0);
        let slip = self.slip.len() != 0;
        for &p in ps {
            let p = p as usize;
            self.topo.get(p).set_live(false);
            *self.tangential.get(p) = DVec3::ZERO;
            if rolling {
                *self.rolling.get(p) = DVec3::ZERO;
            }
            if slip {
                *self.slip.get(p) = Default::default();
            }
            if seams {
                *self.load_j.get(p) = BodyLoad::default();
            }
        }
    }

    /// Sphere `s`'s packed state.
    ///
    /// # Safety
    /// `s` is a sphere index (unchecked in release builds).
    #[inline(always)]
    unsafe fn sphere(&self, s: usize) -> &crate::sphere::SphereState {
        debug_assert!(s < self.sp.state.len());
        self.sp.state.get_unchecked(s)
    }

    /// Centre of sphere `j` as seen across the periodic image `shift`
    /// (world, m); `PERIODIC`: [`RowCtx::any_periodic`].
    #[inline(always)]
    unsafe fn partner_position<const PERIODIC: bool>(&self, j: usize, shift: [i8; 3]) -> DVec3 {
        let x = self.sphere(j).position;
        if PERIODIC && shift != [0; 3] {
            x - self.domain.shift_vector(shift)
        } else {
            x
        }
    }

    /// Gather, law and scatter (see the module docs) over the touching
    /// pairs of the batch.
    #[inline(always)]
    unsafe fn contacts<const PERIODIC: bool>(
        &self,
        batch: &mut Batch,
        stats: &SharedMut<ContactStats>,
    ) {
        if batch.len == 0 {
            return;
        }
        let len = batch.len.min(BATCH);
        // one material for all spheres (the common case): one model, no
        // per-pair lookup
        let single = self.sp.single_material.map(|m| self.table.index(m, m));
        let first = match single {
            Some(m) => m,
            None => self.model_index(batch.row[0] as usize, batch.pair[0] as usize),
        };
        let uniform = self.load_lanes::<PERIODIC>(batch, len, single, first);
        let l = &mut batch.lanes;
        let table = self.table;
        let law = if uniform {
            Some(*table.by_index(first).sliding_law())
        } else {
            for k in 0..len {
                l.set_law(k, table.by_index(batch.model[k]).sliding_law());
            }
            None
        };
        run_law(l, len, law.as_ref(), self.dt, self.simd);
        // the contacts that slide, with the Coulomb limit, from their
        // stored spring
        let pairs = &batch.pair;
        finish_sliding(l, len, law.as_ref(), self.dt, |k| {
            self.tangential.read(pairs[k] as usize)
        });
        self.scalar_laws(batch, len);
        let l = &mut batch.lanes;
        // The row sum of the current body and the statistics of the current
        // chunk are carried in registers and stored when the body or chunk
        // changes (bodies and chunks ascend in the batch; a body whose rows
        // go on in the next batch is carried over to it). Accumulating in
        // place chained every contact through a store and a reload. Same
        // additions in the same order, so the same bits.
        let single_run = batch.run_start == 0 && batch.run_end == self.sp.len();
        let mut body = batch.body[0][0] as usize;
        let mut li = match batch.carry.take() {
            Some((b, li)) if b == body => li,
            Some((b, li)) => {
                self.finish_row(b, li);
                BodyLoad::default()
            }
            None => BodyLoad::default(),
        };
        let bc = self.body_chunk;
        let mut chunk = body / bc;
        // bodies ascend within a batch: a division only on entering a new
        // chunk, not on every new body
        let mut chunk_end = (chunk + 1) * bc;
        let mut stat = *stats.get(chunk);
        for k in 0..len {
            let p = batch.pair[k] as usize;
            let [bi, bj] = batch.body[k].map(|x| x as usize);
            if bi != body {
                self.finish_row(body, li);
                body = bi;
                li = BodyLoad::default();
                if body >= chunk_end {
                    *stats.get(chunk) = stat;
                    chunk = body / bc;
                    chunk_end = (chunk + 1) * bc;
                    stat = *stats.get(chunk);
                }
            }
            let f = get3(&l.force, k);
            li.force += f;
            li.torque += get3(&l.torque_i, k);
            // the j side: added to the column sum of j's body when that body
            // is complete in this run (then every pair feeding it is
            // evaluated here, in ascending order), else recorded for the
            // gather
            let side = BodyLoad {
                force: -f,
                torque: get3(&l.torque_j, k),
            };
            let j = self.topo.read(p).j as usize;
            // one run (one thread): every body is complete in it
            let direct = single_run
                || (j < batch.run_end && at(self.first_feed, bj) as usize >= batch.run_start);
            if direct {
                // the column sum only (the other fields may be read by the
                // other thread as a partner's state)
                let c = &mut *std::ptr::addr_of_mut!((*self.body.ptr(bj)).col);
                c.force += side.force;
                c.torque += side.torque;
            } else {
                *self.load_j.get(p) = side;
            }
            *self.tangential.get(p) = get3(&l.spring, k);
            if let Some(r) = &self.record {
                *r.get(p) = crate::contact::record::PairRecord {
                    normal: get3(&l.normal, k),
                    overlap: l.overlap[k],
                    force: f,
                    normal_force: l.normal_force[k] * l.scale[k],
                };
            }
            let t = self.topo.get(p);
            if !t.live() {
                t.set_live(true);
            }
            if self.counted.is_some_and(|c| !c[bi]) {
                continue;
            }
            let overlap = l.overlap[k];
            // the statistics of the pair's chunk (a batch may span chunks)
            stat.pair_contacts += 1;
            stat.elastic_energy += l.energy[k] * l.scale[k];
            if let Some(s) = self.sums {
                s.add_elastic(l.energy[k] * l.scale[k]);
            }
            let rmin = l.radius_i[k].min(l.radius_j[k]);
            if overlap > stat.max_overlap_ratio * rmin {
                stat.max_overlap_ratio = overlap / rmin;
                // the two spheres' storage indices: the gather turns them
                // into body ids, once per chunk (looking the ids up here
                // missed the cache in large beds: 7 % of this function)
                let i = batch.row[k] as usize;
                stat.max_overlap_bodies = [i as u64, j as u64];
                stat.max_overlap_wall = 0;
            }
        }
        batch.carry = Some((body, li));
        *stats.get(chunk) = stat;
    }

    /// The gather of the batch's first `len` pairs into the lanes: each
    /// pair's geometry, its bodies' packed state, lever arms, spring,
    /// scale and model (`single`: the one model of a one-material world;
    /// `first`: the first pair's). Returns whether every pair has the
    /// model `first`.
    ///
    /// # Safety
    /// As [`Self::contacts`].
    #[inline(always)]
    unsafe fn load_lanes<const PERIODIC: bool>(
        &self,
        batch: &mut Batch,
        len: usize,
        single: Option<u32>,
        first: u32,
    ) -> bool {
        let l = &mut batch.lanes;
        let mut uniform = true;
        for k in 0..len {
            let p = batch.pair[k] as usize;
            let i = batch.row[k] as usize;
            let t = self.topo.read(p);
            let j = t.j as usize;
            let (si, sj) = (self.sphere(i), self.sphere(j));
            let d = si.position - self.partner_position::<PERIODIC>(j, t.shift);
            let (bi, bj) = (at(&self.sp.body, i) as usize, at(&self.sp.body, j) as usize);
            // the two bodies' packed state: read through raw pointers, as
            // another thread may be writing their column sums
            let (pi, pj) = (self.body.as_ptr().add(bi), self.body.as_ptr().add(bj));
            let (wi, wj) = ((*pi).angular_velocity, (*pj).angular_velocity);
            let h = self.tangential.read(p);
            batch.body[k] = [bi as u32, bj as u32];
            // the lever arms from each body's centre of mass to its sphere
            // (each sphere's own position: the same for any periodic image)
            set3(&mut l.arm_i, k, si.position - (*pi).position);
            set3(&mut l.arm_j, k, sj.position - (*pj).position);
            set3(&mut l.separation, k, d);
            set3(&mut l.velocity_i, k, (*pi).velocity);
            set3(&mut l.velocity_j, k, (*pj).velocity);
            set3(&mut l.omega_i, k, wi);
            set3(&mut l.omega_j, k, wj);
            set3(&mut l.spring, k, h);
            l.radius_i[k] = si.radius;
            l.radius_j[k] = sj.radius;
            l.mass_i[k] = (*pi).mass;
            l.mass_j[k] = (*pj).mass;
            l.scale[k] = if self.scale.is_empty() {
                1.0
            } else {
                at(self.scale, p)
            };
            let m = match single {
                Some(m) => m,
                None => self.model_index(i, p),
            };
            batch.model[k] = m;
            uniform &= m == first;
        }
        uniform
    }

    /// The laws the lanes lack, pair by pair, over their results: pairs
    /// whose law only the scalar composition has, and rolling couples.
    ///
    /// # Safety
    /// As [`Self::contacts`].
    #[inline(always)]
    unsafe fn scalar_laws(&self, batch: &mut Batch, len: usize) {
        let table = self.table;
        let l = &mut batch.lanes;
        if table.any_extended() {
            // pairs whose law only the scalar composition has: evaluated
            // again from their stored history (the lanes ran the vectorised
            // law on them, whose results are overwritten here); their
            // rolling couple comes with it
            for k in 0..len {
                let model = table.by_index(batch.model[k]);
                if model.is_extended() {
                    let p = batch.pair[k] as usize;
                    let mut h = ContactHistory {
                        tangential: self.tangential.read(p),
                        rolling: self.rolling.read(p),
                    };
                    let slip = (self.slip.len() > p).then(|| self.slip.get(p));
                    l.contact_scalar(k, model, &mut h, slip, self.dt);
                    *self.rolling.get(p) = h.rolling;
                }
            }
        }
        if table.any_rolling() {
            for k in 0..len {
                let model = table.by_index(batch.model[k]);
                if !model.has_rolling() || model.is_extended() {
                    continue;
                }
                let p = batch.pair[k] as usize;
                // the rolling laws read the normal, the relative angular
                // velocity, R*, m* and dt (not the sliding velocity)
                let input = ContactInput {
                    normal: get3(&l.normal, k),
                    overlap: l.overlap[k],
                    rel_velocity: DVec3::ZERO,
                    rel_omega: get3(&l.omega_i, k) - get3(&l.omega_j, k),
                    radius: l.r_star[k],
                    radius_sum: l.radius_i[k] + l.radius_j[k],
                    mass: l.m_star[k],
                    dt: self.dt,
                };
                let (couple, e_r) =
                    model.rolling_couple(&input, l.normal_force[k], l.kn[k], self.rolling.get(p));
                let couple = couple * l.scale[k];
                let (ti, tj) = (get3(&l.torque_i, k), get3(&l.torque_j, k));
                set3(&mut l.torque_i, k, ti + couple);
                set3(&mut l.torque_j, k, tj - couple);
                if let Some(e) = e_r {
                    l.energy[k] += e;
                }
            }
        }
    }

    /// Index in the contact table of the model of pair `p` in row `i`.
    #[inline(always)]
    unsafe fn model_index(&self, i: usize, p: usize) -> u32 {
        let j = self.topo.read(p).j as usize;
        self.table
            .index(at(&self.sp.material, i), at(&self.sp.material, j))
    }
}

/// How many candidate pairs ahead the detect pass prefetches the partner
/// sphere's state, body index and the pair's spring in a bed whose data fit
/// the caches ([`PREFETCH_MIN_SPHERES`]).
const SMALL_AHEAD: usize = 16;

/// The same beyond the caches, where the line comes from memory (at 10⁶
/// spheres [`SMALL_AHEAD`] left the partner's state the top stall of the
/// detect pass). On the 10⁶ bed 64 with [`PREFETCH_BODY`] 24 took the pair
/// stage about 1 ns a sphere-step below 32 with 8 (four alternated rounds;
/// 96 and 128 gave the same as 64).
const LARGE_AHEAD: usize = 64;

/// How many candidate pairs ahead the detect pass of a large bed prefetches
/// the partner body's packed record (its body index was prefetched
/// [`LARGE_AHEAD`] pairs ahead).
const PREFETCH_BODY: usize = 24;

/// Spheres from which the detect pass prefetches the partner body's data
/// (the partner's state line is prefetched at every size): about where the
/// pair stage's data outgrow a typical 1 MiB per-core L2.
/// Measured on settled tetra beds, one thread: at 40 000 spheres
/// prefetching cuts the pair stage from 115 to 96 ns per sphere-step; at
/// 8 000, whose data fit, it costs about 8 % (the extra instructions then
/// buy nothing).
pub(super) const PREFETCH_MIN_SPHERES: usize = 16_384;

/// Touching pairs per batch (stack arrays; no allocation).
pub(super) const BATCH: usize = 64;

/// Touching pairs found by the detect pass: pair index and row (sphere `i`)
/// of the first `len` slots; the slot at `len` is scratch for the
/// branch-free compaction (`len < BATCH` between flushes). The gathered
/// inputs and the law's outputs live in `lanes`.
pub(super) struct Batch {
    pair: [u32; BATCH],
    /// The spheres of the thread's run: `run_start..run_end`.
    run_start: usize,
    run_end: usize,
    /// Pairs that stopped touching, to clear at the next flush (the slot
    /// at the count is scratch, like `pair`'s).
    clear: [u32; BATCH],
    row: [u32; BATCH],
    /// Bodies of the pair's spheres `i` and `j`.
    body: [[u32; 2]; BATCH],
    model: [u32; BATCH],
    len: usize,
    /// The body of the last row evaluated and its row sum so far, when its
    /// rows may go on in the next batch.
    carry: Option<(usize, BodyLoad)>,
    lanes: Lanes,
}

impl Default for Batch {
    fn default() -> Self {
        Batch {
            pair: [0; BATCH],
            run_start: 0,
            run_end: 0,
            clear: [0; BATCH],
            row: [0; BATCH],
            body: [[0; 2]; BATCH],
            model: [0; BATCH],
            len: 0,
            carry: None,
            lanes: Lanes::zeroed(),
        }
    }
}
