//! The sphere–sphere pair kernel: the rows of the half list, evaluated in
//! batches of touching pairs.
//!
//! Per batch, in order:
//! 1. *detect* ([`RowCtx::evaluate`]): a branch-free pass walks the
//!    candidate pairs of the rows and compacts the touching ones into the
//!    batch (the common non-touching pair costs one distance test; stale
//!    state is cleared only when a pair stops touching);
//! 2. *gather*: each touching pair's inputs (world frame: centre
//!    separation, lever arms from the bodies' centres of mass, body
//!    velocities and angular velocities, radii, body
//!    masses, tangential history) are copied into per-quantity arrays;
//! 3. *law*: the contact geometry and the normal–tangential law
//!    ([`SlidingLaw::evaluate`], the same function the scalar contact law
//!    runs) over those arrays. This loop has no branches and no indirect
//!    access, so the compiler turns it into vector instructions (4 contacts
//!    per instruction with AVX2, chosen at run time; 2 with the baseline
//!    SSE2); vector and scalar IEEE arithmetic give the same bits;
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
//! and the results do not depend on the thread count.

use super::force::BODY_CHUNK;
use crate::par::prefetch::prefetch;
use crate::par::shared::{at, SharedMut};
use crate::par::simd::Simd;
use crate::contact::{ContactInput, SlidingLaw};
use crate::neighbor::pairs::{BodyLoad, PairBody};
use crate::stats::ContactStats;
use glam::DVec3;

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
    /// Row (sphere `i`) of each pair.
    pub row: &'a [u32],
    /// Partner, periodic image and live flag of each pair (the flag is
    /// written).
    pub topo: SharedMut<crate::neighbor::pairs::PairTopo>,
    /// Multi-contact scale per pair (empty: all 1).
    pub scale: &'a [f64],
    /// Tangential spring per pair, m (written).
    pub tangential: SharedMut<DVec3>,
    /// Rolling spring per pair, N m (written by laws with rolling
    /// resistance only).
    pub rolling: SharedMut<DVec3>,
    /// `j`-side loads of the pairs whose `j`'s body is on a seam, in pair
    /// order ([`PairList::load_j`]; written).
    ///
    /// [`PairList::load_j`]: crate::neighbor::PairList::load_j
    pub load_j: SharedMut<BodyLoad>,
    /// Per body: centre of mass (m), velocity (m/s), angular velocity
    /// (rad/s), mass (kg), and the column sum, written for the bodies
    /// complete in their thread's run ([`PairBody`]).
    pub body: SharedMut<PairBody>,
    /// First row feeding each body's columns ([`PairList::first_feed`]).
    ///
    /// [`PairList::first_feed`]: crate::neighbor::PairList::first_feed
    pub first_feed: &'a [u32],
    /// Per body: whether its [`PairBody::col`] holds its column sum this step
    /// (written; false: the gather sums it from `load_j`).
    pub body_ready: SharedMut<bool>,
    /// Per pair: the contact's record, when this step keeps them
    /// ([`crate::contacts`]).
    pub record: Option<SharedMut<crate::contact::record::PairRecord>>,
    /// The vector instructions the law loop may use ([`simd`]).
    pub simd: Simd,
    /// A bed beyond the caches ([`PREFETCH_MIN_SPHERES`]): the detect pass
    /// prefetches further ahead ([`LARGE_AHEAD`]) and also the partner
    /// body's data.
    pub prefetch: bool,
}

impl RowCtx<'_> {
    /// Evaluates the rows of the spheres of `bodies` (see the module docs),
    /// using `batch` as scratch. The thread's run starts at sphere
    /// `run_start`: a body all of whose column pairs lie in rows from
    /// there on (`first_feed`) is complete in the run, and its column sum
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
        run_start: usize,
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
        debug_assert!(spheres.end <= n);
        (batch.run_start, batch.run_end) = (run_start, spheres.end);
        for b in bodies.clone() {
            *self.body_ready.get(b) = at(self.first_feed, b) as usize >= run_start;
        }
        batch.carry = None;
        // the batch length lives in a register during the detect pass
        let mut len = 0usize;
        let mut n_clear = 0usize;
        // one flat loop over the pairs of the run's rows
        let pairs =
            at(self.row_start, spheres.start) as usize..at(self.row_start, spheres.end) as usize;
        let ahead = if self.prefetch {
            LARGE_AHEAD
        } else {
            SMALL_AHEAD
        };
        for p in pairs {
            let t = topo.read(p);
            let (i, j) = (at(self.row, p) as usize, t.j as usize);
            // the partner a few pairs ahead: its packed state line, the
            // top stall of this loop (it misses the per-core cache even at
            // 8 000 spheres, where the pair stage streams about 1.3 MB, and
            // in a large bed it may lie far away in memory: Morton
            // neighbours across a coarse cell boundary); its body index,
            // read half-way (below); and the pair's tangential spring,
            // which the batch gathers once the pair is found touching
            // (read there, it was 7 % of this function at 40 000 spheres)
            if p + ahead < np {
                let partner = topo.read(p + ahead).j as usize;
                prefetch(sp.state.as_ptr().add(partner));
                prefetch(sp.body.as_ptr().add(partner));
                prefetch(self.tangential.as_ptr().add(p + ahead));
            }
            if self.prefetch && p + PREFETCH_BODY < np {
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
            let d = si.position - self.partner_position(j, t.shift);
            let rsum = si.radius + self.sphere(j).radius;
            let touching = d.length_squared() < rsum * rsum;
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
            n_clear += (!touching & t.live) as usize;
            if len == BATCH || n_clear == BATCH {
                self.clear_pairs(&batch.clear[..n_clear]);
                n_clear = 0;
                batch.len = len;
                self.contacts(batch, stats);
                len = 0;
            }
        }
        self.clear_pairs(&batch.clear[..n_clear]);
        batch.len = len;
        self.contacts(batch, stats);
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
    /// the live flag, the springs and the `j`-side load.
    ///
    /// # Safety
    /// As [`Self::evaluate`]: the pairs lie in this thread's rows.
    #[inline(always)]
    unsafe fn clear_pairs(&self, ps: &[u32]) {
        for &p in ps {
            let p = p as usize;
            self.topo.get(p).live = false;
            *self.tangential.get(p) = DVec3::ZERO;
            *self.rolling.get(p) = DVec3::ZERO;
            *self.load_j.get(p) = BodyLoad::default();
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
    /// (world, m).
    #[inline(always)]
    unsafe fn partner_position(&self, j: usize, shift: [i8; 3]) -> DVec3 {
        let x = self.sphere(j).position;
        if self.any_periodic && shift != [0; 3] {
            x - self.domain.shift_vector(shift)
        } else {
            x
        }
    }

    /// Gather, law and scatter (see the module docs) over the touching
    /// pairs of the batch.
    #[inline(always)]
    unsafe fn contacts(&self, batch: &mut Batch, stats: &SharedMut<ContactStats>) {
        if batch.len == 0 {
            return;
        }
        let len = batch.len.min(BATCH);
        let l = &mut batch.lanes;
        // one material for all spheres (the common case): one model, no
        // per-pair lookup
        let single = self.sp.single_material.map(|m| self.table.index(m, m));
        let first = match single {
            Some(m) => m,
            None => self.model_index(batch.row[0] as usize, batch.pair[0] as usize),
        };
        let mut uniform = true;
        for k in 0..len {
            let p = batch.pair[k] as usize;
            let i = batch.row[k] as usize;
            let t = self.topo.read(p);
            let j = t.j as usize;
            let (si, sj) = (self.sphere(i), self.sphere(j));
            let d = si.position - self.partner_position(j, t.shift);
            let (bi, bj) = (at(&self.sp.body, i) as usize, at(&self.sp.body, j) as usize);
            // the two bodies' packed state: read through raw pointers, as
            // another thread may be writing their column sums
            let (pi, pj) = (self.body.as_ptr().add(bi), self.body.as_ptr().add(bj));
            let (wi, wj) = ((*pi).angular_velocity, (*pj).angular_velocity);
            let h = self.tangential.read(p);
            batch.body[k] = [bi as u32, bj as u32];
            // the lever arms from each body's centre of mass to its sphere
            // (each sphere's own position: the same for any periodic image)
            l.set3(IN_CI, k, si.position - (*pi).position);
            l.set3(IN_CJ, k, sj.position - (*pj).position);
            l.set3(IN_D, k, d);
            l.set3(IN_VI, k, (*pi).velocity);
            l.set3(IN_VJ, k, (*pj).velocity);
            l.set3(IN_WI, k, wi);
            l.set3(IN_WJ, k, wj);
            l.set3(IO_XI, k, h);
            l.v[IN_RI][k] = si.radius;
            l.v[IN_RJ][k] = sj.radius;
            l.v[IN_MI][k] = (*pi).mass;
            l.v[IN_MJ][k] = (*pj).mass;
            l.v[IN_SCALE][k] = if self.scale.is_empty() {
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
        if table.any_rolling() {
            for k in 0..len {
                let model = table.by_index(batch.model[k]);
                if !model.has_rolling() {
                    continue;
                }
                let p = batch.pair[k] as usize;
                // the rolling laws read the normal, the relative angular
                // velocity, R*, m* and dt (not the sliding velocity)
                let input = ContactInput {
                    normal: l.get3(OUT_N, k),
                    overlap: l.v[OUT_OVERLAP][k],
                    rel_velocity: DVec3::ZERO,
                    rel_omega: l.get3(IN_WI, k) - l.get3(IN_WJ, k),
                    radius: l.v[OUT_RSTAR][k],
                    mass: l.v[OUT_MSTAR][k],
                    dt: self.dt,
                };
                let (couple, e_r) = model.rolling_couple(
                    &input,
                    l.v[OUT_FN][k],
                    l.v[OUT_KN][k],
                    self.rolling.get(p),
                );
                let couple = couple * l.v[IN_SCALE][k];
                l.set3(OUT_TI, k, l.get3(OUT_TI, k) + couple);
                l.set3(OUT_TJ, k, l.get3(OUT_TJ, k) - couple);
                if let Some(e) = e_r {
                    l.v[OUT_ENERGY][k] += e;
                }
            }
        }
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
        let mut chunk = body / BODY_CHUNK;
        let mut stat = *stats.get(chunk);
        for k in 0..len {
            let p = batch.pair[k] as usize;
            let [bi, bj] = batch.body[k].map(|x| x as usize);
            if bi != body {
                self.finish_row(body, li);
                body = bi;
                li = BodyLoad::default();
                let c = body / BODY_CHUNK;
                if c != chunk {
                    *stats.get(chunk) = stat;
                    chunk = c;
                    stat = *stats.get(chunk);
                }
            }
            let f = l.get3(OUT_F, k);
            li.force += f;
            li.torque += l.get3(OUT_TI, k);
            // the j side: added to the column sum of j's body when that body
            // is complete in this run (then every pair feeding it is
            // evaluated here, in ascending order), else recorded for the
            // gather
            let side = BodyLoad {
                force: -f,
                torque: l.get3(OUT_TJ, k),
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
            *self.tangential.get(p) = l.get3(IO_XI, k);
            if let Some(r) = &self.record {
                *r.get(p) = crate::contact::record::PairRecord {
                    normal: l.get3(OUT_N, k),
                    overlap: l.v[OUT_OVERLAP][k],
                    force: f,
                    normal_force: l.v[OUT_FN][k] * l.v[IN_SCALE][k],
                };
            }
            let t = self.topo.get(p);
            if !t.live {
                t.live = true;
            }
            let overlap = l.v[OUT_OVERLAP][k];
            // the statistics of the pair's chunk (a batch may span chunks)
            stat.pair_contacts += 1;
            stat.elastic_energy += l.v[OUT_ENERGY][k] * l.v[IN_SCALE][k];
            let rmin = l.v[IN_RI][k].min(l.v[IN_RJ][k]);
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

    /// Index in the contact table of the model of pair `p` in row `i`.
    #[inline(always)]
    unsafe fn model_index(&self, i: usize, p: usize) -> u32 {
        let j = self.topo.read(p).j as usize;
        self.table
            .index(at(&self.sp.material, i), at(&self.sp.material, j))
    }
}

/// Runs [`law_lanes`] over the first `len` lanes, compiled for the vector
/// instructions `simd` (detected on this processor by [`simd`]).
#[inline(always)]
fn run_law(l: &mut Lanes, len: usize, law: Option<&SlidingLaw>, dt: f64, simd: Simd) {
    #[cfg(target_arch = "x86_64")]
    match simd {
        // SAFETY: `simd` was detected on this processor.
        Simd::Avx512 => return unsafe { law_lanes_avx512(l, len, law, dt) },
        Simd::Avx2 => return unsafe { law_lanes_avx2(l, len, law, dt) },
        Simd::Baseline => {}
    }
    let _ = simd;
    law_lanes(l, len, law, dt);
}

/// [`law_lanes`] compiled for AVX-512 (8 doubles per vector).
///
/// # Safety
/// The processor supports AVX-512 F, VL and DQ.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512dq")]
unsafe fn law_lanes_avx512(l: &mut Lanes, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    law_lanes(l, len, law, dt)
}

/// [`law_lanes`] compiled for AVX2 (4 doubles per vector).
///
/// # Safety
/// The processor supports AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn law_lanes_avx2(l: &mut Lanes, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    law_lanes(l, len, law, dt)
}

/// The contact geometry and the law over lanes `0..len`: `law` is the model
/// of every lane, or `None` when the lanes carry their own
/// ([`Lanes::set_law`]).
#[inline(always)]
fn law_lanes(l: &mut Lanes, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    match law {
        Some(law) => {
            for k in 0..len.min(BATCH) {
                l.contact(k, law, dt);
            }
        }
        None => {
            for k in 0..len.min(BATCH) {
                let law = l.law(k);
                l.contact(k, &law, dt);
            }
        }
    }
}

/// How many candidate pairs ahead the detect pass prefetches the partner
/// sphere's state, body index and the pair's spring in a bed whose data fit
/// the caches ([`PREFETCH_MIN_SPHERES`]).
const SMALL_AHEAD: usize = 16;

/// The same beyond the caches, where the line comes from memory (at 10⁶
/// spheres [`SMALL_AHEAD`] left the partner's state the top stall of the
/// detect pass).
const LARGE_AHEAD: usize = 32;

/// How many candidate pairs ahead the detect pass of a large bed prefetches
/// the partner body's packed record (its body index was prefetched
/// [`LARGE_AHEAD`] pairs ahead).
const PREFETCH_BODY: usize = 8;

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
            lanes: Lanes {
                v: [[0.0; BATCH]; NV],
            },
        }
    }
}

// Rows of `Lanes::v` (world frame, SI units). Inputs:
/// `x_i − x_j` (3 rows), m.
const IN_D: usize = 0;
/// Velocity of `i`'s body (3), m/s.
const IN_VI: usize = 3;
/// `ω` of `i`'s body (3), rad/s.
const IN_WI: usize = 6;
/// `ω` of `j`'s body (3), rad/s.
const IN_WJ: usize = 9;
/// Tangential spring `ξ` (3), m: input, and output after the law.
const IO_XI: usize = 12;
/// Radius of `i`, m.
const IN_RI: usize = 15;
/// Radius of `j`, m.
const IN_RJ: usize = 16;
/// Mass of `i`'s body, kg.
const IN_MI: usize = 17;
/// Mass of `j`'s body, kg.
const IN_MJ: usize = 18;
/// Multi-contact scale of the force.
const IN_SCALE: usize = 19;
// Outputs:
/// Force on `i`, scaled (3), N.
const OUT_F: usize = 20;
/// Torque on `i`'s body about its centre of mass (3), N m.
const OUT_TI: usize = 23;
/// Torque on `j`'s body about its centre of mass (3), N m.
const OUT_TJ: usize = 26;
/// Unit normal, `j` → `i` (3).
const OUT_N: usize = 29;
/// Overlap, m.
const OUT_OVERLAP: usize = 32;
/// Elastic energy, unscaled, J.
const OUT_ENERGY: usize = 33;
/// Signed normal force, unscaled, N.
const OUT_FN: usize = 34;
/// Normal stiffness, N/m.
const OUT_KN: usize = 35;
/// `R*`, m.
const OUT_RSTAR: usize = 36;
/// `m*`, kg.
const OUT_MSTAR: usize = 37;
/// Lever arm `x_i − r_cm` of sphere `i` in its body (3), m.
const IN_CI: usize = 38;
/// Lever arm `x_j − r_cm` of sphere `j` in its body (3), m.
const IN_CJ: usize = 41;
/// Velocity of `j`'s body (3), m/s.
const IN_VJ: usize = 44;
// Per-lane law (when the batch mixes models):
const LAW: usize = 47;
/// Number of rows.
const NV: usize = LAW + 8;

/// Per-quantity arrays of a batch (structure of arrays: row `q`, lane `k`).
pub(super) struct Lanes {
    v: [[f64; BATCH]; NV],
}

impl Lanes {
    #[inline(always)]
    fn set3(&mut self, q: usize, k: usize, x: DVec3) {
        self.v[q][k] = x.x;
        self.v[q + 1][k] = x.y;
        self.v[q + 2][k] = x.z;
    }

    #[inline(always)]
    fn get3(&self, q: usize, k: usize) -> DVec3 {
        DVec3::new(self.v[q][k], self.v[q + 1][k], self.v[q + 2][k])
    }

    /// Stores lane `k`'s law.
    #[inline(always)]
    fn set_law(&mut self, k: usize, law: &SlidingLaw) {
        let v = &mut self.v;
        v[LAW][k] = if law.hertz { 1.0 } else { 0.0 };
        v[LAW + 1][k] = law.fn_floor;
        v[LAW + 2][k] = law.kn_coef;
        v[LAW + 3][k] = law.kt_coef;
        v[LAW + 4][k] = law.gn_coef;
        v[LAW + 5][k] = law.gt_coef;
        v[LAW + 6][k] = law.energy_factor;
        v[LAW + 7][k] = law.friction;
    }

    /// Lane `k`'s law, as stored by [`Self::set_law`].
    #[inline(always)]
    fn law(&self, k: usize) -> SlidingLaw {
        let v = &self.v;
        SlidingLaw {
            hertz: v[LAW][k] != 0.0,
            fn_floor: v[LAW + 1][k],
            kn_coef: v[LAW + 2][k],
            kt_coef: v[LAW + 3][k],
            gn_coef: v[LAW + 4][k],
            gt_coef: v[LAW + 5][k],
            energy_factor: v[LAW + 6][k],
            friction: v[LAW + 7][k],
        }
    }

    /// Contact `k`: normal, overlap, contact-point velocities (from the
    /// bodies' velocities and angular velocities), `R*`, `m*`,
    /// the law, and the torques of its force about the two bodies' centres
    /// of mass: the contact point is `x_c = x_i − a_i n = x_j + a_j n`, so
    /// `(x_c − r_cm,i) × f = c_i × f − a_i (n × f)` on `i`'s body and
    /// `(x_c − r_cm,j) × (−f) = −c_j × f − a_j (n × f)` on `j`'s (seed
    /// eq. 4.88), with the lever arms `c = x_s − r_cm`.
    #[inline(always)]
    fn contact(&mut self, k: usize, law: &SlidingLaw, dt: f64) {
        let d = self.get3(IN_D, k);
        let (ri, rj) = (self.v[IN_RI][k], self.v[IN_RJ][k]);
        let rsum = ri + rj;
        let dist = d.length();
        let nrm = d * (1.0 / dist);
        let overlap = rsum - dist;
        let (ai, aj) = (ri - 0.5 * overlap, rj - 0.5 * overlap);
        let (wi, wj) = (self.get3(IN_WI, k), self.get3(IN_WJ, k));
        let (ci, cj) = (self.get3(IN_CI, k), self.get3(IN_CJ, k));
        // contact-point velocities, v + ω × (x_c − r_cm), with
        // x_c − r_cm = c_i − a_i n on i's body and c_j + a_j n on j's
        let vrel = self.get3(IN_VI, k) + wi.cross(ci - nrm * ai)
            - (self.get3(IN_VJ, k) + wj.cross(cj + nrm * aj));
        let (mi, mj) = (self.v[IN_MI][k], self.v[IN_MJ][k]);
        let radius = ri * rj / rsum;
        let mass = mi * mj / (mi + mj);
        let mut xi = self.get3(IO_XI, k);
        let out = law.evaluate(nrm, overlap, vrel, radius, mass, dt, &mut xi);
        let scale = self.v[IN_SCALE][k];
        let f = out.force * scale;
        let g = nrm.cross(f);
        self.set3(IO_XI, k, xi);
        self.set3(OUT_F, k, f);
        self.set3(OUT_TI, k, ci.cross(f) - g * ai);
        self.set3(OUT_TJ, k, -cj.cross(f) - g * aj);
        self.set3(OUT_N, k, nrm);
        let v = &mut self.v;
        v[OUT_OVERLAP][k] = overlap;
        v[OUT_ENERGY][k] = out.energy;
        v[OUT_FN][k] = out.normal_force;
        v[OUT_KN][k] = out.kn;
        v[OUT_RSTAR][k] = radius;
        v[OUT_MSTAR][k] = mass;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::par::simd::simd;
    use crate::contact::{ContactModel, Material, NormalLaw, PairProperties};

    /// Lanes of contacts with overlaps of 0 to 20 % of the radius, sliding
    /// and sticking springs, random velocities; `mixed`: every lane its own
    /// law (Hertz and linear, clamped and tensile).
    fn lanes(seed: u64, laws: &[SlidingLaw], mixed: bool) -> Lanes {
        let mut s = seed;
        let mut u = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut l = Lanes {
            v: [[0.0; BATCH]; NV],
        };
        for k in 0..BATCH {
            fn v3(u: &mut impl FnMut() -> f64, a: f64) -> DVec3 {
                DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * a
            }
            let (ri, rj) = (1e-3 * (0.5 + u()), 1e-3 * (0.5 + u()));
            let n = v3(&mut u, 2.0).normalize();
            let d = n * (ri + rj) * (1.0 - 0.1 * u());
            l.set3(IN_D, k, d);
            l.set3(IN_VI, k, v3(&mut u, 0.2));
            l.set3(IN_VJ, k, v3(&mut u, 0.2));
            l.set3(IN_WI, k, v3(&mut u, 50.0));
            l.set3(IN_WJ, k, v3(&mut u, 50.0));
            l.set3(IN_CI, k, v3(&mut u, 1e-3));
            l.set3(IN_CJ, k, v3(&mut u, 1e-3));
            // springs from far inside the Coulomb cone to far outside
            l.set3(IO_XI, k, {
                let a = 1e-4 * u() * u();
                v3(&mut u, a)
            });
            l.v[IN_RI][k] = ri;
            l.v[IN_RJ][k] = rj;
            l.v[IN_MI][k] = 1e-5 * (0.5 + u());
            l.v[IN_MJ][k] = 1e-5 * (0.5 + u());
            l.v[IN_SCALE][k] = if k % 5 == 0 { 0.5 } else { 1.0 };
            if mixed {
                l.set_law(k, &laws[k % laws.len()]);
            }
        }
        l
    }

    /// The law loop gives the same bits compiled for every vector
    /// instruction set this processor has (the engine picks the widest at
    /// run time; results must not depend on the machine's choice).
    #[test]
    fn law_lanes_same_bits_at_every_simd_level() {
        let mat = Material {
            youngs_modulus: 5e6,
            poisson_ratio: 0.3,
            density: 2500.0,
        };
        let mut laws = vec![];
        for normal in [NormalLaw::Hertz, NormalLaw::Linear { kn: 2e3, kt: 1e3 }] {
            for tensile in [false, true] {
                let p = PairProperties {
                    normal,
                    tensile,
                    ..PairProperties::default()
                };
                laws.push(*ContactModel::new(&mat, &mat, &p).unwrap().sliding_law());
            }
        }
        let mut levels = vec![Simd::Baseline];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                levels.push(Simd::Avx2);
            }
            if simd() == Simd::Avx512 {
                levels.push(Simd::Avx512);
            }
        }
        eprintln!("levels on this processor: {levels:?}");
        for (case, law) in [None, Some(&laws[0]), Some(&laws[3])]
            .into_iter()
            .enumerate()
        {
            for len in [BATCH, 13] {
                let base = lanes(case as u64 + 7, &laws, law.is_none());
                let mut want = base.v;
                {
                    let mut l = Lanes { v: base.v };
                    law_lanes(&mut l, len, law, 1e-5);
                    want.copy_from_slice(&l.v);
                }
                // the loop did something: a stiffness on every evaluated lane,
                // a force on most (a clamped lane separating fast has none)
                assert!((0..len).all(|k| want[OUT_KN][k] > 0.0));
                let pushed = (0..len).filter(|&k| want[OUT_F][k] != 0.0).count();
                assert!(2 * pushed > len, "{pushed} of {len} lanes with a force");
                for &level in &levels {
                    let mut l = Lanes { v: base.v };
                    run_law(&mut l, len, law, 1e-5, level);
                    for q in 0..NV {
                        for k in 0..BATCH {
                            assert_eq!(
                                l.v[q][k].to_bits(),
                                want[q][k].to_bits(),
                                "{level:?}, case {case}, len {len}: row {q} lane {k}"
                            );
                        }
                    }
                }
            }
        }
    }
}
