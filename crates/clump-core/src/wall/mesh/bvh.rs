//! A static bounding-volume hierarchy of axis-aligned boxes over the
//! triangles of a mesh (mesh frame).
//!
//! Built top-down by median split of the triangle centroids along the longest
//! axis of the node's centroid box, with at most [`LEAF_SIZE`] triangles per
//! leaf; nodes are stored depth-first (the left child follows its parent).
//! Build is O(n log n), a sphere query O(log n + k). Deterministic: the same
//! mesh always gives the same tree.

use super::closest::aabb_distance2;
use glam::DVec3;

/// Largest number of triangles in a leaf.
pub const LEAF_SIZE: usize = 4;

/// Deepest possible tree for up to 2³² triangles (median splits).
const MAX_DEPTH: usize = 64;

#[derive(Debug, Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: first index into `order`; internal: index of the right child.
    start: u32,
    /// Leaf: number of triangles (≥ 1); internal: 0.
    count: u32,
}

/// Bounding-volume hierarchy over triangles (see the [module docs](self)).
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Bvh {
    /// Builds the tree for triangles with boxes `[lo[i], hi[i]]` (mesh frame, m).
    pub fn build(lo: &[DVec3], hi: &[DVec3]) -> Self {
        let n = lo.len();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * n / LEAF_SIZE + 1),
            order: (0..n as u32).collect(),
        };
        if n == 0 {
            return bvh;
        }
        let centroid: Vec<DVec3> = lo.iter().zip(hi).map(|(a, b)| 0.5 * (*a + *b)).collect();
        bvh.build_node(0, n, lo, hi, &centroid);
        bvh
    }

    fn build_node(
        &mut self,
        s: usize,
        e: usize,
        lo: &[DVec3],
        hi: &[DVec3],
        centroid: &[DVec3],
    ) -> usize {
        let idx = self.nodes.len();
        let (mut blo, mut bhi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let (mut clo, mut chi) = (blo, bhi);
        for &t in &self.order[s..e] {
            let t = t as usize;
            blo = blo.min(lo[t]);
            bhi = bhi.max(hi[t]);
            clo = clo.min(centroid[t]);
            chi = chi.max(centroid[t]);
        }
        self.nodes.push(Node {
            lo: blo,
            hi: bhi,
            start: s as u32,
            count: (e - s) as u32,
        });
        if e - s <= LEAF_SIZE {
            return idx;
        }
        let ext = chi - clo;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let mid = (s + e) / 2;
        self.order[s..e].select_nth_unstable_by(mid - s, |&a, &b| {
            centroid[a as usize][axis]
                .total_cmp(&centroid[b as usize][axis])
                .then(a.cmp(&b))
        });
        self.build_node(s, mid, lo, hi, centroid);
        let right = self.build_node(mid, e, lo, hi, centroid);
        self.nodes[idx].start = right as u32;
        self.nodes[idx].count = 0;
        idx
    }

    /// Bounding box of everything, `(lo, hi)`, or `None` for an empty tree.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.nodes.first().map(|n| (n.lo, n.hi))
    }

    /// Calls `f(triangle)` for every triangle whose box lies within distance
    /// `r` (m) of the point `c` (mesh frame). Triangles come in tree order.
    #[inline]
    pub fn for_each_near(&self, c: DVec3, r: f64, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let r2 = r * r;
        let mut stack = [0u32; MAX_DEPTH];
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let node = &self.nodes[stack[sp] as usize];
            if aabb_distance2(c, node.lo, node.hi) > r2 {
                continue;
            }
            if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    f(t);
                }
            } else {
                let left = stack[sp] + 1;
                stack[sp] = node.start;
                stack[sp + 1] = left;
                sp += 2;
            }
        }
    }

    /// Calls `f(triangle)` for every triangle whose box contains the line
    /// `{(x, y, z) : y = p.y, z = p.z}` when `axis = 0` (and likewise along y
    /// or z for `axis = 1, 2`).
    pub fn for_each_on_line(&self, p: DVec3, axis: usize, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut stack = [0u32; MAX_DEPTH];
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let node = &self.nodes[stack[sp] as usize];
            if p[u] < node.lo[u] || p[u] > node.hi[u] || p[v] < node.lo[v] || p[v] > node.hi[v] {
                continue;
            }
            if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    f(t);
                }
            } else {
                let left = stack[sp] + 1;
                stack[sp] = node.start;
                stack[sp + 1] = left;
                sp += 2;
            }
        }
    }

    /// Nearest-triangle search: visits nodes closest-first and calls
    /// `dist2(triangle) -> f64` (squared distance from the query point) for
    /// candidate triangles; returns the triangle with the smallest value and
    /// that value, or `None` for an empty tree. `c` is the query point (mesh
    /// frame, m), used for pruning.
    pub fn nearest(&self, c: DVec3, mut dist2: impl FnMut(u32) -> f64) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best = (u32::MAX, f64::INFINITY);
        let mut stack = [(0u32, 0.0f64); MAX_DEPTH];
        let mut sp = 1usize;
        stack[0] = (0, aabb_distance2(c, self.nodes[0].lo, self.nodes[0].hi));
        while sp > 0 {
            sp -= 1;
            let (ni, d2) = stack[sp];
            if d2 > best.1 {
                continue;
            }
            let node = &self.nodes[ni as usize];
            if node.count > 0 {
                for &t in &self.order[node.start as usize..(node.start + node.count) as usize] {
                    let d = dist2(t);
                    if d < best.1 || (d == best.1 && t < best.0) {
                        best = (t, d);
                    }
                }
            } else {
                let (l, r) = (ni + 1, node.start);
                let dl = aabb_distance2(c, self.nodes[l as usize].lo, self.nodes[l as usize].hi);
                let dr = aabb_distance2(c, self.nodes[r as usize].lo, self.nodes[r as usize].hi);
                // push the farther child first so that the nearer is visited first
                if dl <= dr {
                    stack[sp] = (r, dr);
                    stack[sp + 1] = (l, dl);
                } else {
                    stack[sp] = (l, dl);
                    stack[sp + 1] = (r, dr);
                }
                sp += 2;
            }
        }
        Some(best)
    }
}
