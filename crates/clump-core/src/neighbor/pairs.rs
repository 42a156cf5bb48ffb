//! The half list of candidate sphere pairs and their contact state.

use super::body_search::{BodySearch, Image};
pub use super::build_input::{BuildInput, HistoryMap, SlipMap};
use super::carry::{reversed, HistoryCarry};
use super::grid::CellGrid;
use super::sort::counting_sort;
use super::topo::{keep_owned_pairs, set_row_steps, PairTopo};
use crate::boundary::Domain;
use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::sphere::Spheres;
use glam::DVec3;
use rayon::prelude::*;

/// Spheres per parallel work block while building the list.
const BLOCK: usize = 512;

/// A force and its torque about a body's centre of mass (world frame; N and
/// N m): what one pair contributes to one of its two bodies, or the sum of
/// such contributions.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BodyLoad {
    /// Force, world frame, N.
    pub force: DVec3,
    /// Torque about the body's centre of mass, world frame, N m.
    pub torque: DVec3,
}

impl BodyLoad {
    /// The sum of two loads on the same body.
    #[inline(always)]
    pub fn add(self, o: BodyLoad) -> BodyLoad {
        BodyLoad {
            force: self.force + o.force,
            torque: self.torque + o.torque,
        }
    }
}

/// What the pair stage reads and writes of one body, packed into two cache
/// lines: the state its contacts read (a copy of the body's, written by the
/// first half step each step and by [`PairList::refresh_bodies`]) and its
/// column sum. Read as the partner of a contact, a body is one or two
/// cache misses instead of five in separate arrays (centre, velocity,
/// angular velocity, mass, column sum).
#[repr(C, align(64))]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PairBody {
    /// Centre of mass, world frame, m.
    pub position: DVec3,
    /// Velocity of the centre of mass, world frame, m/s.
    pub velocity: DVec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
    /// Mass, kg.
    pub mass: f64,
    /// The body's pair load (world frame; torque about its centre of mass),
    /// built by the pair kernel: first the `j` sides of the pairs in the
    /// columns of the body's spheres, summed in ascending pair order as it
    /// evaluates them, when all of them lie in the same thread's run as the
    /// body (always on one thread); then, once the rows of its spheres are
    /// done, their `i` sides (summed in pair order) are added (`row + col`).
    /// For a body on a seam it holds the row sum alone (`column_sum` adds
    /// the rest). The gather reads it and sets it back to zero, so it is zero
    /// between steps.
    pub col: BodyLoad,
}

/// The half pair list, stored by rows: the candidate partners `j > i` of
/// sphere `i` (storage order, other bodies only) are
/// `topo[row_start[i]..row_start[i + 1]]`. Each pair is oriented by storage
/// index (`i < j`); its history (`tangential`, `rolling`) is stored in that
/// orientation and carried across rebuilds by global sphere ids. Reused
/// between builds.
#[derive(Debug, Clone, Default)]
pub struct PairList {
    /// Row offsets, one per sphere plus one.
    pub row_start: Vec<u32>,
    /// Partner, image, live flag and row step of each pair
    /// ([`super::topo`]).
    pub topo: Vec<PairTopo>,
    /// Tangential spring of each pair (parallel to `topo`), world frame, m,
    /// oriented from `i` to `j` ([`ContactHistory::tangential`]).
    pub tangential: Vec<DVec3>,
    /// Rolling spring of each pair (parallel to `topo`), world frame, N m,
    /// oriented from `i` to `j` ([`ContactHistory::rolling`]). Kept apart
    /// from the tangential springs, and empty unless some law has rolling
    /// resistance or is composed by the scalar path
    /// ([`BuildInput::rolling`], [`PairList::keep_rolling`]): the others
    /// never touch it, so a candidate pair costs 24 bytes less.
    pub rolling: Vec<DVec3>,
    /// MDR profile of each pair (parallel to `topo`, oriented from `i` to
    /// `j`; [`crate::contact::mdr`]), empty unless some law keeps one
    /// ([`BuildInput::slip`], [`PairList::keep_slip`]).
    pub slip: Vec<SlipProfile>,
    /// What each pair contributes to the body of its sphere `j` (parallel
    /// to `topo`; torque about that body's centre of mass), recorded only
    /// when that body is on a seam between two threads' runs (see
    /// `body`), and zero for a pair that does not touch: the gather sums
    /// such a body's column through `col_pair` (`column_sum`). Empty,
    /// like the column lists, until a pair stage runs on several threads
    /// ([`PairList::prepare_seams`]): one run has no seam, and the 48
    /// bytes a pair are most of a candidate's storage.
    pub load_j: Vec<BodyLoad>,
    /// Per body: its state as the contacts read it, and its column sum
    /// ([`PairBody::col`]). (Summed per body rather than per sphere, the
    /// lever arms are applied per contact in the vectorised law, and the
    /// per-sphere sums, 96 bytes a sphere read and written every step, are
    /// gone.)
    pub(crate) body: Vec<PairBody>,
    /// Multi-contact scale of each pair's force (`1/n` under `average`,
    /// parallel to `topo`; empty under `sum`).
    pub scale: Vec<f64>,
    /// The pairs of each body's column: the pairs whose sphere `j` belongs
    /// to body `b` are `col_pair[col_start[b]..col_start[b + 1]]`,
    /// ascending.
    pub col_pair: Vec<u32>,
    /// Offsets of each body's column, one per body plus one.
    pub col_start: Vec<u32>,
    /// Per body (storage index): the first row (sphere `i`) with a pair in
    /// the column of one of its spheres, or its first sphere when they have
    /// none. Its pair load is complete once the rows from there to its last
    /// sphere's are evaluated.
    pub first_feed: Vec<u32>,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    /// Centre and radius of each sphere of `cell_items`, in the same (cell)
    /// order: the scan reads a cell's spheres from one contiguous run.
    cell_xr: Vec<[f64; 4]>,
    cursor: Vec<u32>,
    /// The bodies binned for the search by body pairs, on many-sphere
    /// bodies ([`BodySearch::pays`]).
    by_body: BodySearch,
    /// Tests only: search sphere by sphere on any bodies.
    #[cfg(test)]
    pub(crate) by_sphere: bool,
    /// Scratch of the build: the candidates found by each block of rows
    /// (unused on one thread, where the search writes `topo` directly).
    block_topo: Vec<Vec<PairTopo>>,
    /// Scratch of the search by body pairs: the near bodies of the body
    /// searched, per block of rows.
    block_near: Vec<Vec<u32>>,
    /// The column lists, `first_feed` and `load_j` are built for the
    /// current list ([`PairList::prepare_seams`]).
    seams_ready: bool,
    /// Candidates the last build left out as between two bodies not owned
    /// ([`BuildInput::owned`]).
    pub left_out: usize,
}

/// The column sum of body `b` from the pairs' own records: the `j` sides
/// `load_j` of the pairs in its column, added in ascending pair order from
/// zero, the order in which the pair kernel accumulates
/// [`PairBody::col`]. Either way the body's pair load is
/// `row sum + column`, with the same bits, so the results do not depend
/// on which thread summed it.
///
/// # Safety
/// `load_j` points to the list's `load_j`, complete for these pairs; `b` is
/// a body of the list's last build. Unchecked in release builds.
#[inline(always)]
pub(crate) unsafe fn column_sum(
    load_j: *const BodyLoad,
    col_start: &[u32],
    col_pair: &[u32],
    b: usize,
) -> BodyLoad {
    use crate::par::shared::at;
    let mut l = BodyLoad::default();
    let (c0, c1) = (at(col_start, b) as usize, at(col_start, b + 1) as usize);
    debug_assert!(c0 <= c1);
    for c in c0..c1 {
        l = l.add(*load_j.add(at(col_pair, c) as usize));
    }
    l
}

impl PairList {
    /// Copies the pairs of this list (built on the spheres `sp`) that hold
    /// state into `carry`: a non-zero history, or with `keep_live` a live
    /// flag (`neighbor::carry`).
    pub(crate) fn save_carry(&self, carry: &mut HistoryCarry, sp: &Spheres, keep_live: bool) {
        // a list not built on these spheres (none built yet) carries nothing
        let n = sp.body_first.last().map_or(0, |&s| s as usize);
        carry.start(&sp.body_first, n);
        let rows = if self.row_start.len() == n + 1 { n } else { 0 };
        let with_rolling = !self.rolling.is_empty();
        let with_slip = !self.slip.is_empty();
        for i in 0..rows {
            for p in self.row(i) {
                if let Some(h) = self.kept_history(p, keep_live) {
                    carry.push(
                        self.topo[p].j,
                        h,
                        with_rolling,
                        with_slip.then(|| self.slip[p]),
                    );
                }
            }
            carry.end_row();
        }
        carry.finish(n);
    }

    /// Copies the bodies' centres, velocities, angular velocities and
    /// masses into `PairList::body` (built for `b`'s bodies), keeping the
    /// column sums.
    pub fn refresh_bodies(&mut self, b: &crate::body::Bodies) {
        for (i, pb) in self.body.iter_mut().enumerate().take(b.len()) {
            pb.position = b.position[i];
            pb.velocity = b.velocity[i];
            pb.angular_velocity = b.angular_velocity[i];
            pb.mass = b.mass[i];
        }
    }

    /// Gives every pair a rolling spring (zero) if the list has none: the
    /// contact table now has a law that keeps one.
    pub fn keep_rolling(&mut self) {
        if self.rolling.len() != self.topo.len() {
            self.rolling.clear();
            self.rolling.resize(self.topo.len(), DVec3::ZERO);
        }
    }

    /// Gives every pair an MDR profile (empty) if the list has none: the
    /// contact table now has a law that keeps one.
    pub fn keep_slip(&mut self) {
        if self.slip.len() != self.topo.len() {
            self.slip.clear();
            self.slip.resize(self.topo.len(), SlipProfile::default());
        }
    }

    /// Collects the MDR profiles of the pairs that hold one, keyed and
    /// oriented as [`Self::save_history`] (nothing when the list keeps no
    /// profiles).
    pub fn save_slip(&self, gid: &[u64], out: &mut SlipMap) {
        out.clear();
        if self.slip.len() != self.topo.len() {
            return;
        }
        for i in 0..self.row_start.len().saturating_sub(1) {
            for p in self.row(i) {
                let sp = &self.slip[p];
                if !sp.is_empty() {
                    let (gi, gj) = (gid[i], gid[self.topo[p].j as usize]);
                    if gi < gj {
                        out.insert((gi, gj), *sp);
                    } else {
                        out.insert((gj, gi), sp.reversed());
                    }
                }
            }
        }
    }

    /// Builds what a pair stage split into several threads' runs needs and
    /// one run does not, once per build: each body's column list
    /// (`col_start`, `col_pair`), the first row feeding it (`first_feed`),
    /// and a zero `j`-side load per pair (`load_j`). `body` is each
    /// sphere's owner, as at the build.
    pub fn prepare_seams(&mut self, body: &[u32]) {
        if self.seams_ready {
            return;
        }
        self.seams_ready = true;
        let acc = self.topo.len();
        self.load_j.clear();
        self.load_j.resize(acc, BodyLoad::default());
        // the pairs whose j belongs to each body, ascending
        let nb = self.body.len();
        let topo = &self.topo;
        counting_sort(
            acc,
            nb,
            |p| body[topo[p].j as usize] as usize,
            &mut self.col_start,
            &mut self.cursor,
            &mut self.col_pair,
        );
        // a body's spheres are contiguous: its first sphere is the first
        // with its owner index
        self.first_feed.clear();
        self.first_feed.resize(nb, u32::MAX);
        for (s, &b) in body.iter().enumerate().rev() {
            self.first_feed[b as usize] = s as u32;
        }
        for i in 0..self.row_start.len().saturating_sub(1) {
            for t in &self.topo[self.row(i)] {
                let b = body[t.j as usize] as usize;
                self.first_feed[b] = self.first_feed[b].min(i as u32);
            }
        }
    }

    /// Number of candidate pairs.
    pub fn len(&self) -> usize {
        self.topo.len()
    }

    /// True when there are no candidate pairs.
    pub fn is_empty(&self) -> bool {
        self.topo.is_empty()
    }

    /// Pair indices of sphere `i`'s row.
    #[inline(always)]
    pub fn row(&self, i: usize) -> std::ops::Range<usize> {
        self.row_start[i] as usize..self.row_start[i + 1] as usize
    }

    /// The history of pair `p` (oriented from its `i` to its `j`) when a
    /// rebuild carries it over: it has a spring, or an MDR profile (a
    /// touching contact whose tangential force is exactly zero), or with
    /// `keep_live` it is live (a JKR contact lives on while apart, with or
    /// without a spring).
    #[inline]
    pub(crate) fn kept_history(&self, p: usize, keep_live: bool) -> Option<ContactHistory> {
        let h = ContactHistory {
            tangential: self.tangential[p],
            rolling: self.rolling.get(p).copied().unwrap_or_default(),
        };
        let profile = self.slip.get(p).is_some_and(|s| !s.is_empty());
        (h != ContactHistory::default() || profile || (keep_live && self.topo[p].live()))
            .then_some(h)
    }

    /// Collects the history of touching pairs keyed by (lower, higher) global
    /// sphere id and oriented from the lower to the higher id: the pairs
    /// with a spring, and with `keep_live` every live pair (a JKR contact
    /// lives on while apart, with or without a spring).
    pub fn save_history(&self, gid: &[u64], keep_live: bool, out: &mut HistoryMap) {
        out.clear();
        for i in 0..self.row_start.len().saturating_sub(1) {
            for p in self.row(i) {
                if let Some(h) = self.kept_history(p, keep_live) {
                    let (gi, gj) = (gid[i], gid[self.topo[p].j as usize]);
                    if gi < gj {
                        out.insert((gi, gj), h);
                    } else {
                        out.insert((gj, gi), reversed(h));
                    }
                }
            }
        }
    }

    /// Rebuilds the list for spheres `inp` on `grid`, keeping the history of
    /// pairs found in `history` (keyed by global sphere ids, lower first).
    pub fn build(
        &mut self,
        grid: &CellGrid,
        domain: &Domain,
        inp: &BuildInput,
        history: &HistoryMap,
    ) {
        self.build_from(grid, domain, inp, Carried::ById(history))
    }

    /// [`PairList::build`], keeping the history of pairs found in `carry`
    /// (the list before a re-sort, by storage index).
    pub(crate) fn build_carried(
        &mut self,
        grid: &CellGrid,
        domain: &Domain,
        inp: &BuildInput,
        carry: &HistoryCarry,
    ) {
        self.build_from(grid, domain, inp, Carried::ByIndex(carry))
    }

    fn build_from(&mut self, grid: &CellGrid, domain: &Domain, inp: &BuildInput, history: Carried) {
        let n = inp.state.len();
        let by_body = BodySearch::pays(inp.body_first);
        #[cfg(test)]
        let by_body = by_body && !self.by_sphere;
        let image = Image::of(domain);

        // 1. the candidates of each sphere (j > i, other body): one search
        // per sphere (or per body, on many-sphere bodies). On
        // several threads, block by block: each block's candidates go to
        // its own scratch list (kept from build to build, so no allocation
        // once they are large enough), then are concatenated in block order
        // (searching twice, to count and then to fill, cost twice as
        // much). On one thread the scratch copy would only add 8 bytes a
        // pair to the peak memory.
        // each row's count goes to row_start[i + 1], summed into the
        // offsets below
        self.row_start.clear();
        self.row_start.resize(n + 1, 0);
        if by_body {
            self.by_body.prepare(domain, inp);
            self.search_by_body(inp, domain, &image);
        } else {
            self.search_by_sphere(grid, domain, inp, image);
        }
        self.left_out = match inp.owned {
            Some(owned) => {
                keep_owned_pairs(&mut self.row_start[1..], &mut self.topo, inp.body, owned)
            }
            None => 0,
        };

        // 2. row offsets, and the rows in order
        for i in 0..n {
            self.row_start[i + 1] += self.row_start[i];
        }
        let acc = self.row_start[n] as usize;
        debug_assert_eq!(self.topo.len(), acc);
        set_row_steps(&self.row_start, &mut self.topo);

        // 3. the histories of the pairs that persist
        self.restore(inp, history);
    }

    /// The candidates of each sphere by its cell stencil ([`Search`]) on
    /// `grid`, into `topo` with each row's count at `row_start[i + 1]`.
    fn search_by_sphere(
        &mut self,
        grid: &CellGrid,
        domain: &Domain,
        inp: &BuildInput,
        image: Image,
    ) {
        let n = inp.state.len();
        // bin spheres into cells (counting sort; each sphere's cell is
        // computed where it is needed, here twice and once in the search,
        // rather than kept per sphere)
        let cell = |x: DVec3| grid.index(grid.coords(domain.wrap(x)));
        counting_sort(
            n,
            grid.len(),
            |s| cell(inp.state[s].position),
            &mut self.cell_start,
            &mut self.cursor,
            &mut self.cell_items,
        );
        self.cell_xr.clear();
        self.cell_xr.extend(self.cell_items.iter().map(|&s| {
            let (x, r) = (inp.state[s as usize].position, inp.radius[s as usize]);
            [x.x, x.y, x.z, r]
        }));
        let ctx = Search {
            grid,
            domain,
            inp,
            cell_start: &self.cell_start,
            cell_items: &self.cell_items,
            cell_xr: &self.cell_xr,
            image,
        };
        let nblocks = n.div_ceil(BLOCK);
        let serial = rayon::current_num_threads() == 1 || nblocks <= 1;
        if serial {
            // the same searches in the same order, straight into the list
            self.topo.clear();
            for i in 0..n {
                self.row_start[i + 1] =
                    ctx.visit(i, |j, shift| self.topo.push(PairTopo::new(j, shift)));
            }
        } else {
            if self.block_topo.len() < nblocks {
                self.block_topo.resize_with(nblocks, Vec::new);
            }
            let counts = crate::par::shared::SharedMut::new(&mut self.row_start[1..]);
            self.block_topo[..nblocks]
                .par_iter_mut()
                .enumerate()
                .for_each(|(blk, out)| {
                    out.clear();
                    for i in blk * BLOCK..((blk + 1) * BLOCK).min(n) {
                        let c = ctx.visit(i, |j, shift| out.push(PairTopo::new(j, shift)));
                        // SAFETY: sphere i belongs to this block only.
                        unsafe { *counts.get(i) = c };
                    }
                });
            concat_blocks(&mut self.topo, &self.block_topo[..nblocks]);
        }
    }

    /// The candidates of each sphere by body pairs ([`BodySearch`]), into
    /// `topo` with each row's count at `row_start[i + 1]`; the bodies are
    /// binned.
    fn search_by_body(&mut self, inp: &BuildInput, domain: &Domain, image: &Image) {
        let nb = inp.body_first.len() - 1;
        let n = inp.state.len();
        // blocks of bodies of about BLOCK spheres
        let per_block = (BLOCK * nb / n.max(1)).max(1);
        let nblocks = nb.div_ceil(per_block);
        if self.block_near.len() < nblocks.max(1) {
            self.block_near.resize_with(nblocks.max(1), Vec::new);
        }
        let search = &self.by_body;
        if rayon::current_num_threads() == 1 || nblocks <= 1 {
            self.topo.clear();
            let (topo, rows) = (&mut self.topo, &mut self.row_start);
            for a in 0..nb {
                search.rows_of(a, inp, domain, image, &mut self.block_near[0], |i, j, s| {
                    topo.push(PairTopo::new(j, s));
                    rows[i + 1] += 1;
                });
            }
            return;
        }
        if self.block_topo.len() < nblocks {
            self.block_topo.resize_with(nblocks, Vec::new);
        }
        let counts = crate::par::shared::SharedMut::new(&mut self.row_start[1..]);
        self.block_topo[..nblocks]
            .par_iter_mut()
            .zip(&mut self.block_near[..nblocks])
            .enumerate()
            .for_each(|(blk, (out, near))| {
                out.clear();
                for a in blk * per_block..((blk + 1) * per_block).min(nb) {
                    search.rows_of(a, inp, domain, image, near, |i, j, s| {
                        out.push(PairTopo::new(j, s));
                        // SAFETY: the rows of body a's spheres belong to
                        // this block only.
                        unsafe { *counts.get(i) += 1 };
                    });
                }
            });
        concat_blocks(&mut self.topo, &self.block_topo[..nblocks]);
    }

    /// Restores the history of the pairs of a new list that persist, from
    /// `history`, and sizes the per-pair and per-body state.
    fn restore(&mut self, inp: &BuildInput, history: Carried) {
        let n = inp.state.len();
        let acc = self.topo.len();
        // the history of pairs that persist (stored from the lower to the
        // higher global id; pairs here run from i to j > i)
        let gid = inp.gid;
        self.tangential.clear();
        self.tangential.resize(acc, DVec3::ZERO);
        self.rolling.clear();
        if inp.rolling {
            self.rolling.resize(acc, DVec3::ZERO);
        }
        self.slip.clear();
        if inp.slip.is_some() {
            self.slip.resize(acc, SlipProfile::default());
        }
        self.load_j.clear();
        self.col_pair.clear();
        self.seams_ready = false;
        self.scale.clear();
        let any = match history {
            Carried::ById(map) => !map.is_empty(),
            Carried::ByIndex(carry) => !carry.is_empty(),
        };
        if any {
            let tan = crate::par::shared::SharedMut::new(&mut self.tangential);
            let rol = crate::par::shared::SharedMut::new(&mut self.rolling);
            let slp = crate::par::shared::SharedMut::new(&mut self.slip);
            let slip_map = inp.slip;
            let topo = crate::par::shared::SharedMut::new(&mut self.topo);
            let rows = &self.row_start;
            (0..n).into_par_iter().with_min_len(BLOCK).for_each(|i| {
                for p in rows[i] as usize..rows[i + 1] as usize {
                    // SAFETY: pair p belongs to row i only.
                    let t = unsafe { topo.get(p) };
                    let (gi, gj) = (gid[i], gid[t.j as usize]);
                    let old = match history {
                        Carried::ById(map) => {
                            if gi < gj {
                                map.get(&(gi, gj)).copied()
                            } else {
                                map.get(&(gj, gi)).map(|h| reversed(*h))
                            }
                        }
                        Carried::ByIndex(carry) => carry.get(i, t.j as usize),
                    };
                    if let Some(h) = old {
                        t.set_live(true);
                        // SAFETY: pair p belongs to row i only.
                        unsafe {
                            *tan.get(p) = h.tangential;
                            if rol.len() > p {
                                *rol.get(p) = h.rolling;
                            }
                        }
                    }
                    if slp.len() > p {
                        let sp = match (history, slip_map) {
                            (Carried::ByIndex(carry), _) => carry.get_slip(i, t.j as usize),
                            (Carried::ById(_), Some(m)) if gi < gj => m.get(&(gi, gj)).copied(),
                            (Carried::ById(_), Some(m)) => m.get(&(gj, gi)).map(|x| x.reversed()),
                            _ => None,
                        };
                        if let Some(sp) = sp {
                            // SAFETY: pair p belongs to row i only.
                            unsafe { *slp.get(p) = sp };
                        }
                    }
                }
            });
        }

        // the bodies' packed state (the column lists wait for a pair stage
        // on several threads: prepare_seams)
        let nb = inp.body.last().map_or(0, |&b| b as usize + 1);
        self.body.clear();
        self.body.resize(nb, PairBody::default());
    }
}

/// `topo` from the blocks' candidates, in block order.
fn concat_blocks(topo: &mut Vec<PairTopo>, blocks: &[Vec<PairTopo>]) {
    topo.clear();
    for b in blocks {
        topo.extend_from_slice(b);
    }
}

/// Where a build finds the histories of the pairs that persist.
#[derive(Clone, Copy)]
enum Carried<'a> {
    /// Keyed by global sphere ids, lower first (a checkpoint, a world
    /// joined from its ranks).
    ById(&'a HistoryMap),
    /// The list before a re-sort, by storage index.
    ByIndex(&'a HistoryCarry),
}

struct Search<'a> {
    grid: &'a CellGrid,
    domain: &'a Domain,
    inp: &'a BuildInput<'a>,
    cell_start: &'a [u32],
    cell_items: &'a [u32],
    cell_xr: &'a [[f64; 4]],
    image: Image,
}

impl Search<'_> {
    /// Calls `f(j, shift)` for every candidate partner `j > i` of sphere `i`
    /// on another body, in stencil order (cells by z, then y, then x; each
    /// cell's spheres in storage order); returns the count.
    ///
    /// The three cells of a stencil row along x are contiguous in the cell
    /// list, so a row is one range of cells unless it wraps around a
    /// periodic x boundary (then cell by cell, in the same order). Each
    /// cell drops its spheres up to the end of `i`'s body at once
    /// ([`Search::scan`]); the rest get the distance test without an early
    /// exit.
    #[inline]
    fn visit(&self, i: usize, mut f: impl FnMut(u32, [i8; 3])) -> u32 {
        let grid = self.grid;
        let c = grid.coords(self.domain.wrap(self.inp.state[i].position));
        let mut count = 0;
        for dz in -1..=1i64 {
            let Some(z) = grid.wrap(c[2] + dz, 2) else {
                continue;
            };
            for dy in -1..=1i64 {
                let Some(y) = grid.wrap(c[1] + dy, 1) else {
                    continue;
                };
                let nx = grid.dims[0] as i64;
                let (x0, x1) = (c[0] - 1, c[0] + 1);
                if !grid.periodic[0] || (x0 >= 0 && x1 < nx) {
                    let k0 = grid.index([x0.max(0), y, z]);
                    let k1 = grid.index([x1.min(nx - 1), y, z]);
                    self.scan(i, k0, k1 + 1, &mut f, &mut count);
                } else {
                    for dx in -1..=1i64 {
                        if let Some(x) = grid.wrap(c[0] + dx, 0) {
                            let k = grid.index([x, y, z]);
                            self.scan(i, k, k + 1, &mut f, &mut count);
                        }
                    }
                }
            }
        }
        count
    }

    /// The candidates of `i` among the spheres of cells `k0..k1`.
    ///
    /// A cell's spheres are in ascending storage order, and a body's
    /// spheres are contiguous, so the partners `j > i` on other bodies are
    /// the cell's spheres from the first one past the end of `i`'s body: a
    /// cell wholly before it is passed over, one wholly after it taken
    /// whole, any other cut there by a binary search; only the rest get the
    /// distance test.
    #[inline(always)]
    fn scan(
        &self,
        i: usize,
        k0: usize,
        k1: usize,
        f: &mut impl FnMut(u32, [i8; 3]),
        count: &mut u32,
    ) {
        let inp = self.inp;
        let xi = inp.state[i].position;
        let ri = inp.radius[i] + inp.skin;
        let first = inp.body_first[inp.body[i] as usize + 1].max(i as u32 + 1);
        for k in k0..k1 {
            let (c0, c1) = (self.cell_start[k] as usize, self.cell_start[k + 1] as usize);
            // a cell wholly before `first` (or empty) is passed over, and one
            // wholly after it taken whole, without the binary search
            if c0 == c1 || self.cell_items[c1 - 1] < first {
                continue;
            }
            let c0 = if self.cell_items[c0] >= first {
                c0
            } else {
                c0 + self.cell_items[c0..c1].partition_point(|&j| j < first)
            };
            for (&j, xr) in self.cell_items[c0..c1].iter().zip(&self.cell_xr[c0..c1]) {
                let xj = DVec3::new(xr[0], xr[1], xr[2]);
                if let Some(shift) = self.image.candidate(xi, ri, xj, xr[3]) {
                    debug_assert!(j as usize > i && inp.body[j as usize] != inp.body[i]);
                    f(j, shift);
                    *count += 1;
                }
            }
        }
    }
}
