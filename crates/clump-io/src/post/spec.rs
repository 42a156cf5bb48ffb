//! What to coarse-grain: the grid's axes and cells, the kernel and its
//! width, time averaging; from `[output.fields]` or `clump post`'s options.
//! [`FieldSeries`] writes the fields of each frame and their time average.

use super::fields::{coarse_grain, Fields};
use super::frame::Frame;
use super::grid::Grid;
use super::kernel::Kernel;
use crate::atomic::write_atomic;
use clump_core::boundary::Domain;
use std::io;
use std::path::{Path, PathBuf};

/// A coarse-graining request.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FieldSpec {
    /// World axes of the grid (0 = x, 1 = y, 2 = z), 1 to 3, distinct.
    pub axes: Vec<usize>,
    /// Cells along each grid axis.
    pub cells: Vec<usize>,
    /// Lower end along each grid axis, m (default: the domain's).
    pub lo: Option<Vec<f64>>,
    /// Upper end along each grid axis, m (default: the domain's).
    pub hi: Option<Vec<f64>>,
    /// The kernel.
    pub kernel: Kernel,
    /// The kernel's standard deviation, m.
    pub width: f64,
    /// Also write the average over all frames.
    pub average: bool,
}

impl FieldSpec {
    /// The grid in `domain`.
    pub fn grid(&self, domain: &Domain) -> Grid {
        let pick = |v: &Option<Vec<f64>>, d: glam::DVec3| -> Vec<f64> {
            v.clone()
                .unwrap_or_else(|| self.axes.iter().map(|&a| d[a]).collect())
        };
        Grid {
            axes: self.axes.clone(),
            lo: pick(&self.lo, domain.lo),
            hi: pick(&self.hi, domain.hi),
            cells: self.cells.clone(),
            kernel: self.kernel,
            width: self.width,
            domain: *domain,
        }
    }

    /// Why the spec cannot be used in `domain`, if it cannot: the kernel
    /// must be narrower than half the box along a periodic grid axis.
    pub fn check(&self, domain: &Domain) -> Result<(), String> {
        let c = self.kernel.support(self.width);
        for &a in &self.axes {
            if domain.periodic[a] && 2.0 * c >= domain.size()[a] {
                return Err(format!(
                    "the kernel reaches {c} m on each side, more than half the periodic box along {} ({} m): use a smaller width",
                    ["x", "y", "z"][a],
                    domain.size()[a]
                ));
            }
        }
        Ok(())
    }
}

/// Writes `fields_<step>.vti` (and `fields_<step>.csv` for a 1D grid) per
/// frame and, with averaging, `fields_mean.vti` / `.csv` over all frames.
#[derive(Debug, Clone)]
pub struct FieldSeries {
    dir: PathBuf,
    spec: FieldSpec,
    sum: Option<(Grid, Fields, usize)>,
}

impl FieldSeries {
    /// A series writing into `dir`.
    pub fn new(dir: &Path, spec: FieldSpec) -> Self {
        FieldSeries {
            dir: dir.to_path_buf(),
            spec,
            sum: None,
        }
    }

    fn write(&self, grid: &Grid, f: &Fields, label: &str) -> io::Result<()> {
        write_atomic(
            self.dir.join(format!("fields_{label}.vti")),
            super::write::vti(grid, f).as_bytes(),
        )?;
        if grid.axes.len() == 1 {
            write_atomic(
                self.dir.join(format!("fields_{label}.csv")),
                super::write::csv_1d(grid, f).as_bytes(),
            )?;
        }
        Ok(())
    }

    /// Coarse-grains `frame` and writes its fields.
    pub fn add(&mut self, frame: &Frame) -> io::Result<Fields> {
        let grid = self.spec.grid(&frame.domain);
        let f = coarse_grain(frame, &grid);
        self.add_fields(grid, f, frame.step)
    }

    /// The grid of the series in `domain`.
    pub fn grid(&self, domain: &Domain) -> Grid {
        self.spec.grid(domain)
    }

    /// Writes the fields `f` on `grid` of the frame at `step` (made
    /// elsewhere, e.g. summed over ranks) and keeps them for the average.
    pub fn add_fields(&mut self, grid: Grid, f: Fields, step: u64) -> io::Result<Fields> {
        self.write(&grid, &f, &format!("{step:06}"))?;
        if self.spec.average {
            match &mut self.sum {
                Some((_, s, n)) => {
                    s.add_scaled(&f, 1.0);
                    *n += 1;
                }
                None => self.sum = Some((grid, f.clone(), 1)),
            }
        }
        Ok(f)
    }

    /// Writes the time average (when asked for and frames were added).
    pub fn finish(&self) -> io::Result<Option<Fields>> {
        let Some((grid, s, n)) = &self.sum else {
            return Ok(None);
        };
        let mut mean = Fields::zeros(grid.len());
        mean.add_scaled(s, 1.0 / *n as f64);
        self.write(grid, &mean, "mean")?;
        Ok(Some(mean))
    }
}
