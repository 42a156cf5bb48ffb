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

/// Which two spheres a pair joins. `i` has the lower global sphere id, so a
/// pair's orientation never depends on storage order.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairTopo {
    /// Sphere index of the first sphere (lower global id).
    pub i: u32,
    /// Sphere index of the second sphere.
    pub j: u32,
    /// Periodic image shift: the separation is `x_i − x_j + shift·L`.
    pub shift: [i8; 3],
}

/// Result of the last force evaluation of one pair (kept apart from the
/// history so that the kernel touches little memory for non-touching pairs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairState {
    /// Force on sphere `i`, world frame, N (sphere `j` gets the opposite).
    pub force: DVec3,
    /// Torque on body of `i` about its centre of mass, world frame, N m.
    pub torque_i: DVec3,
    /// Torque on body of `j` about its centre of mass, world frame, N m.
    pub torque_j: DVec3,
    /// Elastic energy stored in the contact, J.
    pub energy: f64,
    /// Overlap, m: > 0 touching, 0 not touching, [`HISTORY_ONLY`] when the
    /// pair holds a restored history that the next evaluation must check.
    pub overlap: f64,
}

/// Marker overlap of a pair whose history was restored (checkpoint or
/// rebuild) but which has not been evaluated since.
pub const HISTORY_ONLY: f64 = -1.0;

/// The half pair list with per-sphere incidence, reused between builds.
#[derive(Debug, Clone, Default)]
pub struct PairList {
    /// Pair topology.
    pub topo: Vec<PairTopo>,
    /// Contact history per pair (parallel to `topo`), world frame.
    pub history: Vec<ContactHistory>,
    /// Last evaluation per pair (parallel to `topo`).
    pub state: Vec<PairState>,
    /// Incidence: pairs touching sphere `s` are
    /// `incidence[incidence_start[s]..incidence_start[s+1]]`; each entry is a
    /// pair index with bit 31 set when `s` is the pair's `j`.
    pub incidence: Vec<u32>,
    /// Offsets into `incidence`, one per sphere plus one.
    pub incidence_start: Vec<u32>,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    sphere_cell: Vec<[i64; 3]>,
    counts: Vec<u32>,
    offsets: Vec<usize>,
    cursor: Vec<u32>,
}

/// Bit marking the `j` side in an incidence entry.
pub const SIDE_J: u32 = 1 << 31;

/// Neighbour-cell offsets (all 27).
const STENCIL: [[i64; 3]; 27] = {
    let mut s = [[0i64; 3]; 27];
    let mut n = 0;
    let mut z = -1;
    while z <= 1 {
        let mut y = -1;
        while y <= 1 {
            let mut x = -1;
            while x <= 1 {
                s[n] = [x, y, z];
                n += 1;
                x += 1;
            }
            y += 1;
        }
        z += 1;
    }
    s
};

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

    /// Collects the history of touching pairs keyed by (gid_i, gid_j).
    pub fn save_history(&self, gid: &[u64], out: &mut HistoryMap) {
        out.clear();
        for (t, h) in self.topo.iter().zip(&self.history) {
            if *h != ContactHistory::default() {
                out.insert((gid[t.i as usize], gid[t.j as usize]), *h);
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
        (0..n)
            .into_par_iter()
            .with_min_len(BLOCK)
            .map(|i| ctx.visit(i, |_, _| {}))
            .collect_into_vec(&mut self.counts);

        // 3. offsets
        self.offsets.clear();
        self.offsets.push(0);
        let mut acc = 0usize;
        for &c in &self.counts {
            acc += c as usize;
            self.offsets.push(acc);
        }
        self.topo.clear();
        self.topo.resize(acc, PairTopo::default());

        // 4. fill, block by block, into disjoint ranges (no allocation)
        {
            let out = crate::step::shared::SharedMut::new(&mut self.topo);
            let offsets = &self.offsets;
            (0..n.div_ceil(BLOCK)).into_par_iter().for_each(|blk| {
                let (s0, s1) = (blk * BLOCK, ((blk + 1) * BLOCK).min(n));
                let mut k = offsets[s0];
                for i in s0..s1 {
                    ctx.visit(i, |j, shift| {
                        // SAFETY: sphere i's candidates own the range
                        // offsets[i]..offsets[i + 1]; blocks are disjoint.
                        unsafe {
                            *out.get(k) = PairTopo {
                                i: i as u32,
                                j,
                                shift,
                            };
                        }
                        k += 1;
                    });
                }
            });
        }

        // 5. orient each pair by global id and restore history
        let gid = inp.gid;
        self.state.clear();
        self.state.resize(acc, PairState::default());
        self.history.clear();
        self.history.resize(acc, ContactHistory::default());
        self.topo
            .par_iter_mut()
            .zip(self.history.par_iter_mut().zip(self.state.par_iter_mut()))
            .with_min_len(4096)
            .for_each(|(t, (h, s))| {
                if gid[t.i as usize] > gid[t.j as usize] {
                    std::mem::swap(&mut t.i, &mut t.j);
                    t.shift = [-t.shift[0], -t.shift[1], -t.shift[2]];
                }
                if !history.is_empty() {
                    if let Some(old) = history.get(&(gid[t.i as usize], gid[t.j as usize])) {
                        *h = *old;
                        s.overlap = HISTORY_ONLY;
                    }
                }
            });

        // 6. per-sphere incidence, in pair order (deterministic)
        self.incidence_start.clear();
        self.incidence_start.resize(n + 1, 0);
        for t in &self.topo {
            self.incidence_start[t.i as usize + 1] += 1;
            self.incidence_start[t.j as usize + 1] += 1;
        }
        for s in 0..n {
            self.incidence_start[s + 1] += self.incidence_start[s];
        }
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.incidence_start[..n]);
        self.incidence.clear();
        self.incidence.resize(2 * acc, 0);
        for (p, t) in self.topo.iter().enumerate() {
            let ci = &mut self.cursor[t.i as usize];
            self.incidence[*ci as usize] = p as u32;
            *ci += 1;
            let cj = &mut self.cursor[t.j as usize];
            self.incidence[*cj as usize] = p as u32 | SIDE_J;
            *cj += 1;
        }
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
    /// on another body; returns the count.
    #[inline]
    fn visit(&self, i: usize, mut f: impl FnMut(u32, [i8; 3])) -> u32 {
        let inp = self.inp;
        let xi = inp.position[i];
        let ri = inp.radius[i];
        let bi = inp.body[i];
        let any_periodic = self.domain.periodic.iter().any(|&p| p);
        let mut count = 0;
        for o in STENCIL {
            let Some(nc) = self.grid.neighbor(self.sphere_cell[i], o) else {
                continue;
            };
            let k = self.grid.index(nc);
            for &j in &self.cell_items[self.cell_start[k] as usize..self.cell_start[k + 1] as usize]
            {
                let ju = j as usize;
                if ju <= i || inp.body[ju] == bi {
                    continue;
                }
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
                if d.length_squared() < cut * cut {
                    f(j, shift);
                    count += 1;
                }
            }
        }
        count
    }
}
