//! The pair search by body pairs, for many-sphere clumps.
//!
//! On stones of 50 spheres a sphere's cell stencil holds the spheres of
//! several stones, most of them its own stone's or out of reach (on
//! LIGGGHTS' settled stone pile, 254 spheres in the stencil per sphere for
//! 0.37 candidate pairs), and the per-sphere search spent its time
//! finding the runs of each body in each cell. Here the bodies are binned
//! instead of the spheres, in cells a bounding sphere across
//! ([`BodyBounds`]):
//!
//! 1. per body `a`, the bodies `b > a` of the 27 cells around it whose
//!    bounding spheres come within the skin of `a`'s, ascending;
//! 2. per sphere `i` of `a`, each such `b` whose bounding sphere `i`
//!    reaches, and then each sphere `j` of `b` by the distance test.
//!
//! A body's spheres are contiguous and bodies follow each other in storage
//! order, so every `j` of a body `b > a` is above every `i` of `a`: a row
//! holds its partners in ascending storage order. The list holds every
//! pair of spheres of different bodies within `r_i + r_j + skin`, as the
//! per-sphere search does, and its order does not depend on the grid.

use super::body_bounds::BodyBounds;
use super::build_input::BuildInput;
use super::grid::{CellGrid, Extent};
use super::sort::counting_sort;
use crate::boundary::Domain;
use glam::DVec3;

/// Mean spheres per body from which the search goes by body pairs: on
/// tetrahedra (4 spheres) a body's spheres in a cell are one or two, and
/// the per-sphere search costs less.
const MIN_SPHERES_PER_BODY: usize = 8;

/// The nearest image of one sphere as seen from another, and the cut-off
/// test of a candidate pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Image {
    /// Periodic axes.
    pub periodic: [bool; 3],
    /// Any axis periodic.
    pub any: bool,
    /// Box edges, m.
    pub length: DVec3,
    /// Half the box edges, m.
    pub half: DVec3,
}

impl Image {
    /// The images of `domain`.
    pub(crate) fn of(domain: &Domain) -> Self {
        Image {
            periodic: domain.periodic,
            any: domain.periodic.iter().any(|&p| p),
            length: domain.size(),
            half: 0.5 * domain.size(),
        }
    }

    /// The image shift of sphere `j` (centre `xj`, radius `rj`) seen from
    /// sphere `i` (centre `xi`, radius plus skin `ri`) when the pair is a
    /// candidate, `|x_i − x_j| < r_i + skin + r_j` at the nearest image
    /// (world frame, m).
    #[inline(always)]
    pub(crate) fn candidate(&self, xi: DVec3, ri: f64, xj: DVec3, rj: f64) -> Option<[i8; 3]> {
        let mut d = xi - xj;
        let mut shift = [0i8; 3];
        if self.any {
            // minimum image; the division only runs for pairs that
            // straddle the boundary
            for a in 0..3 {
                if self.periodic[a] && d[a].abs() > self.half[a] {
                    let s = -(d[a] / self.length[a]).round();
                    shift[a] = s as i8;
                    d[a] += s * self.length[a];
                }
            }
        }
        let cut = ri + rj;
        (d.length_squared() < cut * cut).then_some(shift)
    }
}

/// The bodies binned by their bounding spheres' centres. Reused between
/// builds.
#[derive(Debug, Clone, Default)]
pub(crate) struct BodySearch {
    bounds: BodyBounds,
    grid: CellGrid,
    cell_start: Vec<u32>,
    cell_items: Vec<u32>,
    cursor: Vec<u32>,
}

impl BodySearch {
    /// Whether the search goes by body pairs, for bodies owning the spheres
    /// `body_first[b]..body_first[b + 1]` (the last entry is the number of
    /// spheres).
    pub(crate) fn pays(body_first: &[u32]) -> bool {
        let nb = body_first.len().saturating_sub(1);
        let n = body_first.last().map_or(0, |&n| n as usize);
        nb > 0 && n >= MIN_SPHERES_PER_BODY * nb
    }

    /// Bins the bodies of `inp` (at their spheres' centres) for a search
    /// in `domain` with `inp.skin`.
    pub(crate) fn prepare(&mut self, domain: &Domain, inp: &BuildInput) {
        self.bounds.build(inp.state, inp.radius, inp.body_first);
        let nb = inp.body_first.len().saturating_sub(1);
        let centre = |b: usize| self.bounds.get(b).0;
        let extent = Extent::of_points(domain, (0..nb).map(centre));
        // two bounding spheres within the skin of each other have their
        // centres less than a cell apart
        let cell = 2.0 * self.bounds.largest() + inp.skin;
        self.grid = CellGrid::coarse(domain, &extent, cell);
        let grid = &self.grid;
        counting_sort(
            nb,
            grid.len(),
            |b| grid.index(grid.coords(domain.wrap(centre(b)))),
            &mut self.cell_start,
            &mut self.cursor,
            &mut self.cell_items,
        );
    }

    /// The candidate pairs of body `a`'s spheres, row by row, each to
    /// `emit(i, j, shift)` (see the module's doc); `near` is scratch.
    /// [`BodySearch::prepare`] ran for `inp`.
    #[inline]
    pub(crate) fn rows_of(
        &self,
        a: usize,
        inp: &BuildInput,
        domain: &Domain,
        image: &Image,
        near: &mut Vec<u32>,
        mut emit: impl FnMut(usize, u32, [i8; 3]),
    ) {
        self.near_bodies(a, inp.skin, domain, image, near);
        if near.is_empty() {
            return;
        }
        let state = inp.state;
        let first = inp.body_first;
        for i in first[a] as usize..first[a + 1] as usize {
            let (xi, ri) = (state[i].position, state[i].radius + inp.skin);
            for &b in near.iter() {
                let b = b as usize;
                if self
                    .bounds
                    .out_of_reach(b, xi, ri, image.periodic, image.length)
                {
                    continue;
                }
                let j0 = first[b] as usize;
                for (j, sj) in (j0..).zip(&state[j0..first[b + 1] as usize]) {
                    if let Some(shift) = image.candidate(xi, ri, sj.position, sj.radius) {
                        debug_assert!(j > i && inp.body[j] != inp.body[i]);
                        emit(i, j as u32, shift);
                    }
                }
            }
        }
    }

    /// The bodies `b > a` whose bounding spheres come within `skin` (m) of
    /// `a`'s, ascending, into `near`.
    fn near_bodies(
        &self,
        a: usize,
        skin: f64,
        domain: &Domain,
        image: &Image,
        near: &mut Vec<u32>,
    ) {
        near.clear();
        let grid = &self.grid;
        let c = grid.coords(domain.wrap(self.bounds.get(a).0));
        // a periodic axis of one cell is visited once
        let reach = |ax: usize| -> std::ops::RangeInclusive<i64> {
            if grid.periodic[ax] && grid.dims[ax] == 1 {
                0..=0
            } else {
                -1..=1
            }
        };
        for dz in reach(2) {
            let Some(z) = grid.wrap(c[2] + dz, 2) else {
                continue;
            };
            for dy in reach(1) {
                let Some(y) = grid.wrap(c[1] + dy, 1) else {
                    continue;
                };
                for dx in reach(0) {
                    let Some(x) = grid.wrap(c[0] + dx, 0) else {
                        continue;
                    };
                    let k = grid.index([x, y, z]);
                    let cell = &self.cell_items
                        [self.cell_start[k] as usize..self.cell_start[k + 1] as usize];
                    for &b in cell {
                        if b as usize > a
                            && !self
                                .bounds
                                .apart(a, b as usize, skin, image.periodic, image.length)
                        {
                            near.push(b);
                        }
                    }
                }
            }
        }
        near.sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::neighbor::pairs::{HistoryMap, PairList};
    use crate::sphere::SphereState;
    use rand::{Rng, SeedableRng};

    /// `nb` random stones of `k` spheres (radii 0.4–1 mm, centres within
    /// 2 mm of the body's) with centres of mass anywhere in `domain` and up
    /// to 2 mm beyond it (spheres are unwrapped): centres, radii, owners,
    /// first spheres.
    fn stones(domain: &Domain, nb: usize, k: usize) -> (Vec<DVec3>, Vec<f64>, Vec<u32>, Vec<u32>) {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut position, mut radius, mut body, mut first) =
            (Vec::new(), Vec::new(), Vec::new(), vec![0u32]);
        for b in 0..nb {
            let c = DVec3::new(
                rng.gen_range(domain.lo.x - 0.002..domain.hi.x + 0.002),
                rng.gen_range(domain.lo.y - 0.002..domain.hi.y + 0.002),
                rng.gen_range(domain.lo.z + 0.002..domain.hi.z - 0.002),
            );
            for _ in 0..k {
                let o = DVec3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                );
                position.push(c + 2e-3 * o.normalize_or_zero() * rng.gen_range(0.0..1.0));
                radius.push(rng.gen_range(4e-4..1e-3));
                body.push(b as u32);
            }
            first.push(position.len() as u32);
        }
        (position, radius, body, first)
    }

    /// Every pair `i < j` of spheres of different bodies within
    /// `r_i + r_j + skin` at the nearest periodic image, by brute force, as
    /// rows of (partner, image shift) ascending.
    fn brute_force(
        domain: &Domain,
        position: &[DVec3],
        radius: &[f64],
        body: &[u32],
        skin: f64,
    ) -> Vec<Vec<(u32, [i8; 3])>> {
        let l = domain.size();
        (0..position.len())
            .map(|i| {
                (i + 1..position.len())
                    .filter(|&j| body[i] != body[j])
                    .filter_map(|j| {
                        let mut d = position[i] - position[j];
                        let mut shift = [0i8; 3];
                        for a in 0..3 {
                            if domain.periodic[a] {
                                let s = -(d[a] / l[a]).round();
                                shift[a] = s as i8;
                                d[a] += s * l[a];
                            }
                        }
                        let cut = radius[i] + radius[j] + skin;
                        (d.length_squared() < cut * cut).then_some((j as u32, shift))
                    })
                    .collect()
            })
            .collect()
    }

    /// The rows of a built list.
    fn rows(list: &PairList) -> Vec<Vec<(u32, [i8; 3])>> {
        (0..list.row_start.len() - 1)
            .map(|i| {
                list.row(i)
                    .map(|p| (list.topo[p].j, list.topo[p].shift))
                    .collect()
            })
            .collect()
    }

    /// Builds the list of `nb` stones of 12 spheres in `domain` with the
    /// search by body pairs (on `threads` threads) and, where the sphere
    /// grid allows it, sphere by sphere; checks both against brute force
    /// and returns the number of candidates.
    fn check(domain: Domain, nb: usize, threads: usize) -> usize {
        let skin = 3e-4;
        let (position, radius, body, first) = stones(&domain, nb, 12);
        let gid: Vec<u64> = (0..position.len() as u64).collect();
        assert!(BodySearch::pays(&first));
        let state = SphereState::of(&position, &radius);
        let inp = BuildInput {
            state: &state,
            radius: &radius,
            body: &body,
            body_first: &first,
            gid: &gid,
            skin,
            rolling: false,
            slip: None,
            owned: None,
        };
        let expected = brute_force(&domain, &position, &radius, &body, skin);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let sphere_grid = CellGrid::new(&domain, &position, 2e-3 + skin);
        // the body search reads no sphere grid: any grid will do
        let any_grid = CellGrid::new(&domain, &position, 1e-2).unwrap_or_default();
        let mut by_body = PairList::default();
        pool.install(|| by_body.build(&any_grid, &domain, &inp, &HistoryMap::default()));
        assert!(rows(&by_body) == expected, "the body search's rows differ");
        if let Ok(grid) = sphere_grid {
            let mut by_sphere = PairList::default();
            by_sphere.by_sphere = true;
            pool.install(|| by_sphere.build(&grid, &domain, &inp, &HistoryMap::default()));
            let mut sorted = rows(&by_sphere);
            sorted.iter_mut().for_each(|r| r.sort_unstable());
            assert!(sorted == expected, "the sphere search's candidates differ");
        }
        expected.iter().map(Vec::len).sum()
    }

    /// In a box periodic in x and y, on one thread and on three (blocks of
    /// bodies searched in parallel), the search by body pairs finds exactly
    /// the pairs brute force finds, with their images, each row ascending;
    /// the search sphere by sphere finds the same ones.
    #[test]
    fn the_body_search_finds_every_candidate_in_ascending_rows() {
        let domain = Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(0.02, 0.02, 0.03),
            periodic: [true, true, false],
        };
        for threads in [1, 3] {
            let found = check(domain, 120, threads);
            assert!(found > 200, "too few candidates to test: {found}");
        }
    }

    /// A box periodic in x too thin for three cells of the body grid (one
    /// cell across) or of the sphere grid: the body search still finds
    /// every pair at its nearest image, including pairs across the thin
    /// boundary.
    #[test]
    fn a_thin_periodic_box_is_searched_across() {
        let domain = Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(0.004, 0.03, 0.03),
            periodic: [true, false, false],
        };
        assert!(CellGrid::new(&domain, &[DVec3::ZERO], 2e-3 + 3e-4).is_err());
        let found = check(domain, 60, 1);
        assert!(found > 100, "too few candidates to test: {found}");
    }
}
