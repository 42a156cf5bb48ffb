//! The grid of the coarse-grained fields: one, two or three world axes
//! divided into cells; along the other axes the fields are averaged over
//! the domain's extent (a 1D grid along z gives laterally averaged depth
//! profiles). Along a periodic axis the kernel wraps around.

use super::kernel::Kernel;
use clump_core::boundary::Domain;
use glam::DVec3;

/// A coarse-graining grid with its kernel.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The grid's world axes (0 = x, 1 = y, 2 = z), 1 to 3, distinct.
    pub axes: Vec<usize>,
    /// Lower end along each grid axis, m.
    pub lo: Vec<f64>,
    /// Upper end along each grid axis, m.
    pub hi: Vec<f64>,
    /// Cells along each grid axis.
    pub cells: Vec<usize>,
    /// The kernel.
    pub kernel: Kernel,
    /// The kernel's standard deviation, m.
    pub width: f64,
    /// The domain (periodic axes; extent of the averaged axes).
    pub domain: Domain,
}

impl Grid {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cells.iter().product()
    }

    /// Whether the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Cell size along grid axis `k`, m.
    pub fn spacing(&self, k: usize) -> f64 {
        (self.hi[k] - self.lo[k]) / self.cells[k] as f64
    }

    /// Centre of cell `i` along grid axis `k`, m.
    pub fn centre(&self, k: usize, i: usize) -> f64 {
        self.lo[k] + (i as f64 + 0.5) * self.spacing(k)
    }

    /// The grid cells' volume times the extent of the averaged axes: the
    /// volume a cell's value is averaged over, m³.
    pub fn cell_volume(&self) -> f64 {
        let size = self.domain.size();
        let mut v = 1.0;
        for a in 0..3 {
            v *= match self.axes.iter().position(|&x| x == a) {
                Some(k) => self.spacing(k),
                None => size[a],
            };
        }
        v
    }

    /// The cells a unit deposit at `x` reaches and its density there (the
    /// cell average of the kernel, 1/m³), into `out` (cleared first).
    pub fn weights(&self, x: DVec3, out: &mut Vec<(usize, f64)>) {
        out.clear();
        let c = self.kernel.support(self.width);
        let size = self.domain.size();
        let mut per_axis: [Vec<(usize, f64)>; 3] = Default::default();
        for (k, &a) in self.axes.iter().enumerate() {
            let h = self.spacing(k);
            let images: &[f64] = if self.domain.periodic[a] {
                &[-1.0, 0.0, 1.0]
            } else {
                &[0.0]
            };
            for &im in images {
                let xa = x[a] + im * size[a];
                let first = (((xa - c - self.lo[k]) / h).floor().max(0.0)) as usize;
                let last = (((xa + c - self.lo[k]) / h).floor() + 1.0).min(self.cells[k] as f64);
                if last <= 0.0 {
                    continue;
                }
                for i in first..last as usize {
                    let lo = self.lo[k] + i as f64 * h;
                    let p = self.kernel.cdf(lo + h - xa, self.width)
                        - self.kernel.cdf(lo - xa, self.width);
                    if p > 0.0 {
                        per_axis[k].push((i, p));
                    }
                }
            }
        }
        let norm = 1.0 / self.cell_volume();
        let n = self.axes.len();
        let empty = [(0usize, 1.0f64)];
        let list = |k: usize| -> &[(usize, f64)] {
            if k < n {
                &per_axis[k]
            } else {
                &empty
            }
        };
        let dims = [
            self.cells[0],
            if n > 1 { self.cells[1] } else { 1 },
            if n > 2 { self.cells[2] } else { 1 },
        ];
        for &(i, p) in list(0) {
            for &(j, q) in list(1) {
                for &(l, r) in list(2) {
                    out.push(((i * dims[1] + j) * dims[2] + l, p * q * r * norm));
                }
            }
        }
    }
}
