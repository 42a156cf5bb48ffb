//! Uniform cell grid for the neighbour search.

use crate::boundary::Domain;
use glam::DVec3;

/// A uniform grid of cubic-ish cells. Along periodic axes it spans the domain
/// exactly (at least 3 cells); along other axes it spans the bounding box of
/// the spheres.
#[derive(Debug, Clone, Default)]
pub struct CellGrid {
    /// Lower corner, world frame, m.
    pub origin: DVec3,
    /// Cell edge lengths, m.
    pub cell: DVec3,
    /// Cells per axis.
    pub dims: [usize; 3],
    /// Periodic axes.
    pub periodic: [bool; 3],
}

/// The bounding box and number of points a grid is built for (positions
/// wrapped into the periodic box), world frame, m.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Extent {
    /// Lower corner (+∞ when empty).
    pub lo: DVec3,
    /// Upper corner (−∞ when empty).
    pub hi: DVec3,
    /// Number of points.
    pub count: u64,
}

impl Extent {
    /// No points.
    pub fn empty() -> Self {
        Extent {
            lo: DVec3::splat(f64::INFINITY),
            hi: DVec3::splat(f64::NEG_INFINITY),
            count: 0,
        }
    }

    /// Adds one point (wrapped into the periodic box).
    pub fn add(&mut self, domain: &Domain, p: DVec3) {
        let w = domain.wrap(p);
        self.lo = self.lo.min(w);
        self.hi = self.hi.max(w);
        self.count += 1;
    }

    /// The extent of `positions`.
    pub fn of(domain: &Domain, positions: &[DVec3]) -> Self {
        Self::of_points(domain, positions.iter().copied())
    }

    /// [`Extent::of`] for points given one by one.
    pub fn of_points(domain: &Domain, points: impl Iterator<Item = DVec3>) -> Self {
        let mut e = Extent::empty();
        for p in points {
            e.add(domain, p);
        }
        e
    }

    /// The extent of both (min and max are exact: the order of merging
    /// does not matter).
    pub fn merge(&mut self, o: &Extent) {
        self.lo = self.lo.min(o.lo);
        self.hi = self.hi.max(o.hi);
        self.count += o.count;
    }
}

/// Largest number of cells the grid may have per sphere (bounds memory when
/// spheres are sparse in a large box).
const MAX_CELLS_PER_SPHERE: usize = 8;

impl CellGrid {
    /// Builds a grid for spheres at `positions` (world, m) with minimum cell
    /// edge `min_cell` (m). Returns an error message if a periodic axis is
    /// shorter than three cells.
    pub fn new(domain: &Domain, positions: &[DVec3], min_cell: f64) -> Result<Self, String> {
        Self::from_extent(domain, &Extent::of(domain, positions), min_cell)
    }

    /// The grid [`CellGrid::new`] builds for points with extent `e` (the
    /// extent of a whole world assembled from its ranks' parts).
    pub fn from_extent(domain: &Domain, e: &Extent, min_cell: f64) -> Result<Self, String> {
        Self::build(domain, e, min_cell, false)
    }

    /// A grid like [`CellGrid::from_extent`]'s, for a search that visits
    /// a periodic axis of one cell once: a periodic axis shorter than three
    /// cells of `min_cell` is one cell (the body-pair search, whose cells
    /// are a body across).
    pub(crate) fn coarse(domain: &Domain, e: &Extent, min_cell: f64) -> Self {
        Self::build(domain, e, min_cell, true).expect("a coarse grid has no short axis")
    }

    fn build(domain: &Domain, e: &Extent, min_cell: f64, thin_ok: bool) -> Result<Self, String> {
        let (mut lo, mut hi) = (e.lo, e.hi);
        if e.count == 0 {
            lo = domain.lo;
            hi = domain.hi;
        }
        let positions_len = e.count as usize;
        let mut g = CellGrid {
            periodic: domain.periodic,
            ..Default::default()
        };
        let max_cells = (positions_len.max(1) * MAX_CELLS_PER_SPHERE) as f64;
        let mut min_cell = min_cell;
        loop {
            let mut total = 1.0;
            for a in 0..3 {
                if domain.periodic[a] {
                    let l = domain.hi[a] - domain.lo[a];
                    let mut n = (l / min_cell).floor();
                    if n < 3.0 && thin_ok {
                        n = 1.0;
                    } else if n < 3.0 {
                        return Err(format!(
                            "periodic axis {} is {l} m long, shorter than 3 neighbour cells of {min_cell} m \
                             (largest sphere diameter + skin); enlarge the domain",
                            ["x", "y", "z"][a]
                        ));
                    }
                    g.origin[a] = domain.lo[a];
                    g.dims[a] = n as usize;
                    g.cell[a] = l / n;
                } else {
                    let l = (hi[a] - lo[a]).max(0.0);
                    let n = (l / min_cell).floor().max(0.0) + 1.0;
                    g.origin[a] = lo[a];
                    g.dims[a] = n as usize;
                    g.cell[a] = min_cell;
                }
                total *= g.dims[a] as f64;
            }
            if total <= max_cells || g.periodic.iter().all(|&p| p) {
                break;
            }
            min_cell *= 1.5;
        }
        Ok(g)
    }

    /// Integer cell coordinates of a (wrapped) world position.
    #[inline]
    pub fn coords(&self, x: DVec3) -> [i64; 3] {
        let mut c = [0i64; 3];
        for a in 0..3 {
            // truncation, not floor: they differ only on (-1, 0), which the
            // clamp sends to cell 0 either way, and the floor is a library
            // call on the baseline x86-64 target (about 3 % of a stone
            // pile's rebuild)
            let k = ((x[a] - self.origin[a]) / self.cell[a]) as i64;
            c[a] = k.clamp(0, self.dims[a] as i64 - 1);
        }
        c
    }

    /// Linear cell index of integer coordinates (already in range).
    #[inline]
    pub fn index(&self, c: [i64; 3]) -> usize {
        (c[0] as usize) + self.dims[0] * ((c[1] as usize) + self.dims[1] * (c[2] as usize))
    }

    /// Total number of cells.
    pub fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// True when the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Cell coordinate `k` along axis `a`, wrapped if the axis is periodic;
    /// `None` when outside a bounded axis.
    #[inline(always)]
    pub fn wrap(&self, k: i64, a: usize) -> Option<i64> {
        let d = self.dims[a] as i64;
        if self.periodic[a] {
            Some(k.rem_euclid(d))
        } else if k < 0 || k >= d {
            None
        } else {
            Some(k)
        }
    }
}
