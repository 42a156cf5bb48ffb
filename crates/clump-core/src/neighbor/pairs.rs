//! The half list of candidate sphere pairs and their contact state.

use super::grid::CellGrid;
use crate::boundary::Domain;
use crate::contact::ContactHistory;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;

/// Contact histories keyed by (lower, higher) global sphere id.
pub type HistoryMap = HashMap<(u64, u64), ContactHistory, rustc_hash::FxBuildHasher>;

/// Spheres per parallel work block while building the list.
const BLOCK: usize = 512;

/// The partner of one pair in sphere `i`'s row of the half list: sphere `j`
/// (storage index, always greater than `i`), the periodic image shift, and
/// whether the pair holds contact state (8 bytes in all: the pair kernel's
/// detect pass reads only this for the common non-touching pair).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairTopo {
    /// Sphere index of the partner, `j > i` in storage order.
    pub j: u32,
    /// Periodic image shift: the separation is `x_i − x_j + shift·L`.
    pub shift: [i8; 3],
    /// The pair touched at its last evaluation, or its history was restored
    /// (checkpoint or rebuild) and it has not been evaluated since: its
    /// history and `j`-side load may be non-zero and must be cleared when it
    /// is found not touching.
    pub live: bool,
}

/// What a pair contributes to its sphere `j` (the `i` side is summed per
/// sphere while the pairs are evaluated): zero while the pair does not touch.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairLoad {
    /// Force on sphere `j`, world frame, N.
    pub force: DVec3,
    /// Torque on sphere `j` about its own centre, world frame, N m.
    pub torque: DVec3,
}

/// Force and torque on one sphere summed over its pairs (world frame; N and
/// N m about the sphere's centre).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SphereLoad {
    /// Force, world frame, N.
    pub force: DVec3,
    /// Torque about the sphere centre, world frame, N m.
    pub torque: DVec3,
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
    /// Partner of each pair.
    pub topo: Vec<PairTopo>,
    /// Tangential spring of each pair (parallel to `topo`), world frame, m,
    /// oriented from `i` to `j` ([`ContactHistory::tangential`]).
    pub tangential: Vec<DVec3>,
    /// Rolling spring of each pair (parallel to `topo`), world frame, N m,
    /// oriented from `i` to `j` ([`ContactHistory::rolling`]). Kept apart
    /// from the tangential springs: laws without rolling resistance never
    /// touch it, so the pair kernel streams half the history bytes.
    pub rolling: Vec<DVec3>,
    /// What each pair contributes to its sphere `j` (parallel to `topo`),
    /// recorded only for a `j` whose body is on a seam between two threads'
    /// runs (see `load_c`), and zero for a pair that does not touch: the
    /// gather sums such a sphere's column through `col_pair`
    /// ([`column_sum`]).
    pub load_j: Vec<PairLoad>,
    /// Per sphere: the sum of the `j` sides of the pairs in its column, in
    /// ascending pair order, accumulated by the pair kernel as it evaluates
    /// them when all of them lie in the same thread's run as the sphere's
    /// body (always on one thread). The body sum reads it and sets it back
    /// to zero, so it is all zero between steps. (Stored per pair and read
    /// back through the column, the `j` sides cost a 48-byte write per
    /// contact, 11 % of the pair kernel's time at 40 000 spheres, and a
    /// scattered read in the body sums, 12 % of the step.)
    pub load_c: Vec<SphereLoad>,
    /// Per sphere: the sum over the pairs of its own row (its `i` side).
    pub load_i: Vec<SphereLoad>,
    /// Multi-contact scale of each pair's force (`1/n` under `average`,
    /// parallel to `topo`; empty under `sum`).
    pub scale: Vec<f64>,
    /// The pairs of each column slot: the pairs in which sphere `s` is the
    /// `j` are `col_pair[col_start[s]..col_start[s + 1]]`, ascending.
    pub col_pair: Vec<u32>,
    /// Offsets of each sphere's column slots, one per sphere plus one.
    pub col_start: Vec<u32>,
    /// Per body (storage index): the first row (sphere `i`) with a pair in
    /// the column of one of its spheres, or its first sphere when they have
    /// none. Its pair load is complete once the rows from there to its last
    /// sphere's are evaluated.
    pub first_feed: Vec<u32>,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    sphere_cell: Vec<[i64; 3]>,
    counts: Vec<u32>,
    cursor: Vec<u32>,
    /// Scratch of the build: the candidates found by each block of rows.
    block_topo: Vec<Vec<PairTopo>>,
}

/// Pair force (N) and torque (N m, about the centre of mass `com`) on the
/// body whose spheres are `spheres`, world frame: per sphere, its row sum
/// plus its column sum (`column(s)`, the `j` sides of the pairs in its
/// column added in ascending pair order, starting from zero),
/// `F = Σ f_s`, `M = Σ (x_s − com) × f_s + t_s`. The one summation both the
/// pair kernel (bodies complete in its thread's run, whose column sums it
/// accumulated as it went, `PairList::load_c`) and the gather (the others,
/// from the pairs' own records, [`column_sum`]) use, so either gives the
/// same bits and the results do not depend on the thread count.
///
/// # Safety
/// `load_i` points to the list's row sums; the spheres are of the list's
/// last build, their loads are complete and nothing writes them during the
/// call. Unchecked in release builds (hot loop), checked in debug builds.
#[inline(always)]
pub(crate) unsafe fn body_load(
    load_i: *const SphereLoad,
    column: impl Fn(usize) -> SphereLoad,
    state: &[crate::sphere::SphereState],
    spheres: std::ops::Range<usize>,
    com: DVec3,
) -> SphereLoad {
    use crate::step::shared::at;
    let mut total = SphereLoad::default();
    for s in spheres {
        let (row, col) = (*load_i.add(s), column(s));
        let f = row.force + col.force;
        let x = at(state, s).position;
        total.force += f;
        total.torque += (x - com).cross(f) + (row.torque + col.torque);
    }
    total
}

/// The column sum of sphere `s` from the pairs' own records: the `j` sides
/// `load_j` of the pairs in its column, added in ascending pair order from
/// zero (the order in which the pair kernel accumulates `load_c`).
///
/// # Safety
/// `load_j` points to the list's `load_j`, complete for these pairs; `s` is
/// a sphere of the list's last build. Unchecked in release builds.
#[inline(always)]
pub(crate) unsafe fn column_sum(
    load_j: *const PairLoad,
    col_start: &[u32],
    col_pair: &[u32],
    s: usize,
) -> SphereLoad {
    use crate::step::shared::at;
    let mut l = SphereLoad::default();
    let (c0, c1) = (at(col_start, s) as usize, at(col_start, s + 1) as usize);
    debug_assert!(c0 <= c1);
    for c in c0..c1 {
        let pl = &*load_j.add(at(col_pair, c) as usize);
        l.force += pl.force;
        l.torque += pl.torque;
    }
    l
}

/// Inputs describing the spheres for a build.
pub struct BuildInput<'a> {
    /// Sphere centres at the build, world frame, m.
    pub position: &'a [DVec3],
    /// Radii, m.
    pub radius: &'a [f64],
    /// Owner body (storage index).
    pub body: &'a [u32],
    /// Global sphere ids.
    pub gid: &'a [u64],
    /// Verlet skin, m.
    pub skin: f64,
}

impl PairList {
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

    /// Collects the history of touching pairs keyed by (lower, higher) global
    /// sphere id and oriented from the lower to the higher id.
    pub fn save_history(&self, gid: &[u64], out: &mut HistoryMap) {
        out.clear();
        for i in 0..self.row_start.len().saturating_sub(1) {
            for p in self.row(i) {
                let h = ContactHistory {
                    tangential: self.tangential[p],
                    rolling: self.rolling[p],
                };
                if h != ContactHistory::default() {
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
        let n = inp.position.len();
        // 1. bin spheres into cells (counting sort)
        self.sphere_cell.clear();
        self.sphere_cell
            .extend(inp.position.iter().map(|&x| grid.coords(domain.wrap(x))));
        let ncell = grid.len();
        self.cell_start.clear();
        self.cell_start.resize(ncell + 1, 0);
        for c in &self.sphere_cell {
            self.cell_start[grid.index(*c) + 1] += 1;
        }
        for k in 0..ncell {
            self.cell_start[k + 1] += self.cell_start[k];
        }
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.cell_start[..ncell]);
        self.cell_items.clear();
        self.cell_items.resize(n, 0);
        for (s, c) in self.sphere_cell.iter().enumerate() {
            let k = grid.index(*c);
            self.cell_items[self.cursor[k] as usize] = s as u32;
            self.cursor[k] += 1;
        }

        // 2. count candidates per sphere (j > i, other body)
        let ctx = Search {
            grid,
            domain,
            inp,
            cell_start: &self.cell_start,
            cell_items: &self.cell_items,
            sphere_cell: &self.sphere_cell,
            length: domain.size(),
            half: 0.5 * domain.size(),
        };
        // one search per sphere, block by block: each block's candidates go
        // to its own scratch list (kept from build to build, so no
        // allocation once they are large enough), then are concatenated in
        // block order (searching twice, to count and then to fill, cost
        // twice as much)
        let nblocks = n.div_ceil(BLOCK);
        if self.block_topo.len() < nblocks {
            self.block_topo.resize_with(nblocks, Vec::new);
        }
        self.counts.clear();
        self.counts.resize(n, 0);
        {
            let counts = crate::step::shared::SharedMut::new(&mut self.counts);
            self.block_topo[..nblocks]
                .par_iter_mut()
                .enumerate()
                .for_each(|(blk, out)| {
                    out.clear();
                    for i in blk * BLOCK..((blk + 1) * BLOCK).min(n) {
                        let c = ctx.visit(i, |j, shift| {
                            out.push(PairTopo {
                                j,
                                shift,
                                live: false,
                            })
                        });
                        // SAFETY: sphere i belongs to this block only.
                        unsafe { *counts.get(i) = c };
                    }
                });
        }

        // 3. row offsets, and the rows in order
        self.row_start.clear();
        self.row_start.push(0);
        let mut acc = 0u32;
        for &c in &self.counts {
            acc += c;
            self.row_start.push(acc);
        }
        let acc = acc as usize;
        self.topo.clear();
        for b in &self.block_topo[..nblocks] {
            self.topo.extend_from_slice(b);
        }
        debug_assert_eq!(self.topo.len(), acc);

        // 5. restore the history of pairs that persist (stored from the lower
        //    to the higher global id; pairs here run from i to j > i)
        let gid = inp.gid;
        self.tangential.clear();
        self.tangential.resize(acc, DVec3::ZERO);
        self.rolling.clear();
        self.rolling.resize(acc, DVec3::ZERO);
        self.load_j.clear();
        self.load_j.resize(acc, PairLoad::default());
        self.load_i.clear();
        self.load_i.resize(n, SphereLoad::default());
        self.load_c.clear();
        self.load_c.resize(n, SphereLoad::default());
        self.scale.clear();
        if !history.is_empty() {
            let tan = crate::step::shared::SharedMut::new(&mut self.tangential);
            let rol = crate::step::shared::SharedMut::new(&mut self.rolling);
            let topo = crate::step::shared::SharedMut::new(&mut self.topo);
            let rows = &self.row_start;
            (0..n).into_par_iter().with_min_len(BLOCK).for_each(|i| {
                for p in rows[i] as usize..rows[i + 1] as usize {
                    // SAFETY: pair p belongs to row i only.
                    let t = unsafe { topo.get(p) };
                    let (gi, gj) = (gid[i], gid[t.j as usize]);
                    let old = if gi < gj {
                        history.get(&(gi, gj)).copied()
                    } else {
                        history.get(&(gj, gi)).map(|h| reversed(*h))
                    };
                    if let Some(h) = old {
                        t.live = true;
                        // SAFETY: pair p belongs to row i only.
                        unsafe {
                            *tan.get(p) = h.tangential;
                            *rol.get(p) = h.rolling;
                        }
                    }
                }
            });
        }

        // 6. per-sphere column lists (pairs where the sphere is j), ascending
        self.col_start.clear();
        self.col_start.resize(n + 1, 0);
        for t in &self.topo {
            self.col_start[t.j as usize + 1] += 1;
        }
        for s in 0..n {
            self.col_start[s + 1] += self.col_start[s];
        }
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.col_start[..n]);
        self.col_pair.clear();
        self.col_pair.resize(acc, 0);
        for (p, t) in self.topo.iter().enumerate() {
            let c = &mut self.cursor[t.j as usize];
            self.col_pair[*c as usize] = p as u32;
            *c += 1;
        }
        // a body's spheres are contiguous: its first sphere is the first
        // with its owner index
        let nb = inp.body.last().map_or(0, |&b| b as usize + 1);
        self.first_feed.clear();
        self.first_feed.resize(nb, u32::MAX);
        for (s, &b) in inp.body.iter().enumerate().rev() {
            self.first_feed[b as usize] = s as u32;
        }
        for i in 0..n {
            for p in self.row(i) {
                let b = inp.body[self.topo[p].j as usize] as usize;
                self.first_feed[b] = self.first_feed[b].min(i as u32);
            }
        }
    }
}

/// The history of a pair seen from the other side (`j` to `i`): both springs
/// are relative quantities of `i` with respect to `j`, so they change sign.
#[inline]
fn reversed(h: ContactHistory) -> ContactHistory {
    ContactHistory {
        tangential: -h.tangential,
        rolling: -h.rolling,
    }
}

struct Search<'a> {
    grid: &'a CellGrid,
    domain: &'a Domain,
    inp: &'a BuildInput<'a>,
    cell_start: &'a [u32],
    cell_items: &'a [u32],
    sphere_cell: &'a [[i64; 3]],
    length: DVec3,
    half: DVec3,
}

impl Search<'_> {
    /// Calls `f(j, shift)` for every candidate partner `j > i` of sphere `i`
    /// on another body, in stencil order (cells by z, then y, then x; each
    /// cell's spheres in storage order); returns the count.
    ///
    /// The three cells of a stencil row along x are contiguous in the cell
    /// list, so a row is one slice of spheres unless it wraps around a
    /// periodic x boundary (then cell by cell, in the same order). Each
    /// sphere is tested without an early exit: `j ≤ i`, same body and out
    /// of range are folded into one rarely true condition (skipping `j ≤ i`
    /// first was a branch on a coin toss, 40 % of the build).
    #[inline]
    fn visit(&self, i: usize, mut f: impl FnMut(u32, [i8; 3])) -> u32 {
        let grid = self.grid;
        let c = self.sphere_cell[i];
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
        let xi = inp.position[i];
        let ri = inp.radius[i];
        let bi = inp.body[i];
        let any_periodic = self.domain.periodic.iter().any(|&p| p);
        let items = &self.cell_items[self.cell_start[k0] as usize..self.cell_start[k1] as usize];
        for &j in items {
            let ju = j as usize;
            let mut d = xi - inp.position[ju];
            let mut shift = [0i8; 3];
            if any_periodic {
                // minimum image; the division only runs for pairs that
                // straddle the boundary
                for a in 0..3 {
                    if self.domain.periodic[a] && d[a].abs() > self.half[a] {
                        let s = -(d[a] / self.length[a]).round();
                        shift[a] = s as i8;
                        d[a] += s * self.length[a];
                    }
                }
            }
            let cut = ri + inp.radius[ju] + inp.skin;
            let hit = (ju > i) & (inp.body[ju] != bi) & (d.length_squared() < cut * cut);
            if hit {
                f(j, shift);
                *count += 1;
            }
        }
    }
}
