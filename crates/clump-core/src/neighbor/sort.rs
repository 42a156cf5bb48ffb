//! Spatial sorting of bodies: slabs across the grid's longest axis.
//!
//! Bodies are stored in the order of the cell of their centre of mass,
//! taken lexicographically with the axis of most cells slowest and the axis
//! of fewest cells fastest (LAMMPS' bin order, with the axes ranked by
//! length). A body's neighbours then lie at most about one slab (one cell
//! layer across the longest axis) away in storage, so the partner data the
//! pair stage reads were touched within the last slab: on a flat
//! 10⁶-sphere bed a slab is a thousand bodies and stays in the per-core
//! cache. A Z-curve (Morton) order keeps most neighbours as close, but the
//! partner across one of its coarse block faces lies up to half the bed
//! away; on the periodic 10⁶-sphere tetra bed that cost 3–5 % of the step
//! (docs/performance.md §5).

use super::grid::CellGrid;
use glam::DVec3;

/// Bits per axis in a key (up to 2²¹ cells per axis).
const AXIS_BITS: u32 = 21;

/// The storage order of a grid's cells: its axes from the one with most
/// cells (slowest) to the one with fewest (fastest); ties go to the higher
/// axis first, so a cube's cells are ordered by z, then y, then x.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellOrder([usize; 3]);

impl CellOrder {
    /// The order of `grid`'s cells.
    pub fn of(grid: &CellGrid) -> Self {
        let mut axes = [2, 1, 0];
        // stable: equal lengths keep the higher axis first
        axes.sort_by(|&a, &b| grid.dims[b].cmp(&grid.dims[a]));
        CellOrder(axes)
    }

    /// The key of cell `c` (grid coordinates): its coordinates along the
    /// ranked axes packed into one integer that sorts as the order.
    pub fn key(&self, c: [i64; 3]) -> u64 {
        let mask = (1u64 << AXIS_BITS) - 1;
        self.0
            .iter()
            .fold(0, |k, &a| (k << AXIS_BITS) | (c[a] as u64 & mask))
    }
}

/// Writes into `perm` the order of bodies (by storage index) sorted by the
/// [`CellOrder`] key of the cell of their (wrapped) centre of mass, ties
/// broken by global id, so the order is deterministic. `keep[b] = false`
/// drops body `b`.
pub fn spatial_order(
    grid: &CellGrid,
    wrapped: &[DVec3],
    ids: &[u64],
    keep: &[bool],
    perm: &mut Vec<u32>,
    keys: &mut Vec<(u64, u64, u32)>,
) {
    let order = CellOrder::of(grid);
    keys.clear();
    for (b, &x) in wrapped.iter().enumerate() {
        if keep[b] {
            keys.push((order.key(grid.coords(x)), ids[b], b as u32));
        }
    }
    keys.sort_unstable();
    perm.clear();
    perm.extend(keys.iter().map(|k| k.2));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(dims: [usize; 3]) -> CellGrid {
        CellGrid {
            dims,
            cell: DVec3::ONE,
            ..Default::default()
        }
    }

    /// Every cell's rank in the order, by cell coordinates.
    fn ranks(g: &CellGrid) -> std::collections::HashMap<[i64; 3], usize> {
        let order = CellOrder::of(g);
        let [nx, ny, nz] = g.dims.map(|d| d as i64);
        let mut cells: Vec<[i64; 3]> = (0..nx)
            .flat_map(|x| (0..ny).flat_map(move |y| (0..nz).map(move |z| [x, y, z])))
            .collect();
        cells.sort_by_key(|&c| order.key(c));
        cells.into_iter().enumerate().map(|(r, c)| (c, r)).collect()
    }

    /// The axes are ranked by cell count, ties to the higher axis.
    #[test]
    fn axes_ranked_by_length() {
        assert_eq!(CellOrder::of(&grid([7, 30, 4])).0, [1, 0, 2]);
        assert_eq!(CellOrder::of(&grid([5, 5, 5])).0, [2, 1, 0]);
        assert_eq!(CellOrder::of(&grid([9, 3, 9])).0, [2, 0, 1]);
    }

    /// A cell's face neighbours lie within one slab (the cells across the
    /// two shorter axes) of it in storage, on a flat grid like a wide bed:
    /// what the pair stage's partner reads rely on. A Z-curve order breaks
    /// this bound by far.
    #[test]
    fn face_neighbours_lie_within_one_slab() {
        let g = grid([48, 40, 6]);
        let slab = 40 * 6;
        let r = ranks(&g);
        let mut widest = 0;
        for (&c, &rc) in &r {
            for a in 0..3 {
                let mut n = c;
                n[a] += 1;
                if let Some(&rn) = r.get(&n) {
                    widest = widest.max(rn.abs_diff(rc));
                }
            }
        }
        assert_eq!(widest, slab, "the farthest face neighbour");
        // the Z-curve's farthest face neighbour, for comparison
        let spread = |v: i64| (0..6).fold(0u64, |k, b| k | (((v as u64 >> b) & 1) << (3 * b)));
        let z = |c: [i64; 3]| spread(c[0]) | spread(c[1]) << 1 | spread(c[2]) << 2;
        let mut zc: Vec<[i64; 3]> = r.keys().copied().collect();
        zc.sort_by_key(|&c| z(c));
        let zr: std::collections::HashMap<_, _> =
            zc.iter().enumerate().map(|(i, &c)| (c, i)).collect();
        let zwide = zr
            .iter()
            .flat_map(|(&c, &rc)| {
                (0..3).filter_map({
                    let zr = &zr;
                    move |a| {
                        let mut n = c;
                        n[a] += 1;
                        zr.get(&n).map(|&rn| rn.abs_diff(rc))
                    }
                })
            })
            .max()
            .unwrap();
        assert!(zwide > 10 * slab, "Z-curve farthest neighbour {zwide}");
    }
}

/// Stable counting sort of items `0..n` into `buckets` buckets by `key`
/// (called twice per item): `start` gets the offsets (`buckets + 1`),
/// `items` the items bucket by bucket, ascending within each; `cursor` is
/// scratch.
pub(crate) fn counting_sort(
    n: usize,
    buckets: usize,
    key: impl Fn(usize) -> usize,
    start: &mut Vec<u32>,
    cursor: &mut Vec<u32>,
    items: &mut Vec<u32>,
) {
    start.clear();
    start.resize(buckets + 1, 0);
    for i in 0..n {
        start[key(i) + 1] += 1;
    }
    for k in 0..buckets {
        start[k + 1] += start[k];
    }
    cursor.clear();
    cursor.extend_from_slice(&start[..buckets]);
    items.clear();
    items.resize(n, 0);
    for i in 0..n {
        let c = &mut cursor[key(i)];
        items[*c as usize] = i as u32;
        *c += 1;
    }
}
