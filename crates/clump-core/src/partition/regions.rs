//! The ranks' regions: recursive coordinate bisection of the domain on the
//! bodies' counted costs (`step/partition/cost.rs`: spheres and candidate
//! pairs), redone at every neighbour build (on a sample of the bodies) and
//! whenever a whole world is split (on all of them).
//!
//! The domain box is cut across its longest side so that the two halves'
//! costs are in proportion to their numbers of ranks, then each half in
//! turn, down to one region per rank. A body belongs to the region that
//! holds its (wrapped) centre of mass; regions are boxes, so a rank's
//! ghosts are the bodies within the halo of its box (periodic images
//! included).

use crate::boundary::Domain;
use glam::DVec3;

#[derive(Debug, Clone)]
enum Node {
    Leaf {
        rank: usize,
    },
    Cut {
        axis: usize,
        at: f64,
        below: usize,
        above: usize,
    },
}

#[derive(Debug, Clone)]
struct Cell {
    node: Node,
    lo: DVec3,
    hi: DVec3,
}

/// The regions of the ranks, as a bisection tree over the domain.
#[derive(Debug, Clone)]
pub struct Regions {
    cells: Vec<Cell>,
    domain: Domain,
}

impl Regions {
    /// Equal cuts of the domain, before any body is known.
    pub fn single(domain: &Domain, size: usize) -> Self {
        Self::balance(domain, &[], &[], size)
    }

    /// Regions for `size` ranks balancing `cost` of bodies at `position`
    /// (wrapped, world frame, m). Deterministic: a function of its inputs.
    pub fn balance(domain: &Domain, position: &[DVec3], cost: &[u32], size: usize) -> Self {
        let mut r = Regions {
            cells: Vec::new(),
            domain: *domain,
        };
        let mut items: Vec<u32> = (0..position.len() as u32).collect();
        r.split(
            domain.lo,
            domain.hi,
            0,
            size.max(1),
            &mut items,
            position,
            cost,
        );
        r
    }

    #[allow(clippy::too_many_arguments)]
    fn split(
        &mut self,
        lo: DVec3,
        hi: DVec3,
        first: usize,
        n: usize,
        items: &mut [u32],
        x: &[DVec3],
        cost: &[u32],
    ) -> usize {
        let me = self.cells.len();
        if n == 1 {
            self.cells.push(Cell {
                node: Node::Leaf { rank: first },
                lo,
                hi,
            });
            return me;
        }
        self.cells.push(Cell {
            node: Node::Leaf { rank: first },
            lo,
            hi,
        });
        let ext = hi - lo;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let n_below = n / 2;
        items.sort_unstable_by(|&a, &b| {
            x[a as usize][axis]
                .total_cmp(&x[b as usize][axis])
                .then(a.cmp(&b))
        });
        let total: u64 = items.iter().map(|&i| cost[i as usize] as u64).sum();
        let target = total * n_below as u64;
        // the first item whose cumulative cost reaches the below share
        let mut acc = 0u64;
        let mut k = items.len();
        for (m, &i) in items.iter().enumerate() {
            if acc * n as u64 >= target {
                k = m;
                break;
            }
            acc += cost[i as usize] as u64;
        }
        let mut at = if items.is_empty() || total == 0 {
            lo[axis] + ext[axis] * n_below as f64 / n as f64
        } else if k == 0 {
            lo[axis]
        } else if k >= items.len() {
            hi[axis]
        } else {
            // halfway between the last body below and the first above
            let a = x[items[k - 1] as usize][axis];
            let b = x[items[k] as usize][axis];
            0.5 * (a + b)
        };
        at = at.clamp(lo[axis], hi[axis]);
        // the bodies strictly below the cut go below (as `owner` decides)
        let split = items.partition_point(|&i| x[i as usize][axis] < at);
        let (below_items, above_items) = items.split_at_mut(split);
        let mut hi_b = hi;
        hi_b[axis] = at;
        let mut lo_a = lo;
        lo_a[axis] = at;
        let below = self.split(lo, hi_b, first, n_below, below_items, x, cost);
        let above = self.split(lo_a, hi, first + n_below, n - n_below, above_items, x, cost);
        self.cells[me].node = Node::Cut {
            axis,
            at,
            below,
            above,
        };
        me
    }

    /// The rank whose region holds `x` (wrapped, world frame).
    pub fn owner(&self, x: DVec3) -> usize {
        let mut c = 0;
        loop {
            match self.cells[c].node {
                Node::Leaf { rank } => return rank,
                Node::Cut {
                    axis,
                    at,
                    below,
                    above,
                } => c = if x[axis] < at { below } else { above },
            }
        }
    }

    /// Appends to `out` every rank whose region is within `halo` of `x`
    /// (periodic images included), in ascending order, without repeats.
    pub fn near(&self, x: DVec3, halo: f64, out: &mut Vec<usize>) {
        out.clear();
        self.visit(0, x, halo * halo, out);
        out.sort_unstable();
        out.dedup();
    }

    fn visit(&self, c: usize, x: DVec3, h2: f64, out: &mut Vec<usize>) {
        let cell = &self.cells[c];
        if self.distance2(x, cell.lo, cell.hi) > h2 {
            return;
        }
        match cell.node {
            Node::Leaf { rank } => out.push(rank),
            Node::Cut { below, above, .. } => {
                self.visit(below, x, h2, out);
                self.visit(above, x, h2, out);
            }
        }
    }

    /// Squared distance from `x` to the box, the nearest periodic image
    /// along periodic axes.
    fn distance2(&self, x: DVec3, lo: DVec3, hi: DVec3) -> f64 {
        let l = self.domain.size();
        let mut d2 = 0.0;
        for a in 0..3 {
            let gap = |v: f64| (lo[a] - v).max(v - hi[a]).max(0.0);
            let mut d = gap(x[a]);
            if self.domain.periodic[a] {
                d = d.min(gap(x[a] - l[a])).min(gap(x[a] + l[a]));
            }
            d2 += d * d;
        }
        d2
    }

    /// True when the box `[lo, hi]` (world frame, m) comes within `halo`
    /// of the region of `rank` (periodic images included).
    pub fn box_near_region(&self, lo: DVec3, hi: DVec3, halo: f64, rank: usize) -> bool {
        let Some((rlo, rhi)) = self.region(rank) else {
            return false;
        };
        let l = self.domain.size();
        let mut d2 = 0.0;
        for a in 0..3 {
            let gap = |s: f64| (rlo[a] - (hi[a] + s)).max((lo[a] + s) - rhi[a]).max(0.0);
            let mut d = gap(0.0);
            if self.domain.periodic[a] {
                d = d.min(gap(-l[a])).min(gap(l[a]));
            }
            d2 += d * d;
        }
        d2 <= halo * halo
    }

    /// The region box of `rank` (world frame, m).
    pub fn region(&self, rank: usize) -> Option<(DVec3, DVec3)> {
        self.cells.iter().find_map(|c| match c.node {
            Node::Leaf { rank: r } if r == rank => Some((c.lo, c.hi)),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn domain(periodic: [bool; 3]) -> Domain {
        Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(4.0, 2.0, 1.0),
            periodic,
        }
    }

    #[test]
    fn costs_are_shared_in_proportion_to_ranks() {
        let d = domain([false; 3]);
        let x: Vec<DVec3> = (0..300)
            .map(|i| DVec3::new((i as f64 * 0.37) % 4.0, (i as f64 * 0.11) % 2.0, 0.5))
            .collect();
        let cost = vec![1u32; x.len()];
        for size in 1..=5 {
            let r = Regions::balance(&d, &x, &cost, size);
            let mut count = vec![0usize; size];
            for &p in &x {
                count[r.owner(p)] += 1;
            }
            let (lo, hi) = (*count.iter().min().unwrap(), *count.iter().max().unwrap());
            assert!(hi - lo <= 2, "{size} ranks: counts {count:?}");
            // each body's owner is among the ranks near it
            let mut near = Vec::new();
            for &p in &x {
                r.near(p, 0.0, &mut near);
                assert!(near.contains(&r.owner(p)));
            }
        }
    }

    #[test]
    fn a_periodic_halo_reaches_across_the_boundary() {
        let d = domain([true, false, false]);
        let r = Regions::single(&d, 2);
        // two halves along x: [0, 2) and [2, 4)
        assert_eq!(r.owner(DVec3::new(0.1, 1.0, 0.5)), 0);
        assert_eq!(r.owner(DVec3::new(3.9, 1.0, 0.5)), 1);
        let mut near = Vec::new();
        r.near(DVec3::new(3.9, 1.0, 0.5), 0.2, &mut near);
        assert_eq!(near, vec![0, 1], "the image at x = -0.1 is near rank 0");
        let r = Regions::single(&domain([false; 3]), 2);
        r.near(DVec3::new(3.9, 1.0, 0.5), 0.2, &mut near);
        assert_eq!(near, vec![1]);
    }
}
