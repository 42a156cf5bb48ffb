//! The part of the cross-section the bed occupies along a 1D profile.
//!
//! A 1D grid averages its fields over the whole domain cross-section
//! ([`super::grid`]): its density is the mass per cross-section area and
//! height, which for a heap on a wide floor is a small fraction of the
//! density of the heap itself. Dividing the profile's density by the
//! fraction of the cross-section the bed occupies at each height gives the
//! density where the material lies (the bulk density of the bed, the
//! solid density times the solid fraction).
//!
//! The occupied region: the plane across the profile axis is cut into
//! square columns one mean body diameter wide (volume-equivalent), and in
//! each column the bed spans from the bottom of its lowest body to the top
//! of its highest (each body counted as its volume-equivalent sphere). A
//! heap's slope and a bed that covers only part of the floor are followed
//! column by column. Bodies in flight above the bed stretch their column's
//! span, so average settled frames. The span indicator is smoothed with
//! the fields' kernel along the profile axis, so density and occupancy are
//! compared at the same resolution; in a bed's interior (further than the
//! kernel's support from its top and bottom) the occupancy is exact.

use super::frame::Frame;
use super::grid::Grid;

/// Most columns across a profile: wider columns beyond this.
const MAX_COLUMNS: f64 = 4.0e6;

/// Fraction of the cross-section occupied by the bed in each cell of a 1D
/// `grid` (0 to 1), for one frame. Zero everywhere for a frame without
/// bodies. `grid` must have one axis.
pub fn occupied_fraction(frame: &Frame, grid: &Grid) -> Vec<f64> {
    assert_eq!(grid.axes.len(), 1, "occupancy is defined for 1D grids");
    let mut out = vec![0.0; grid.len()];
    let n = frame.bodies.len();
    if n == 0 {
        return out;
    }
    let a = grid.axes[0];
    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
    let (lo, size) = (grid.domain.lo, grid.domain.size());
    let d_mean = frame
        .bodies
        .iter()
        .map(|x| x.equivalent_diameter())
        .sum::<f64>()
        / n as f64;
    let side = d_mean.max((size[b] * size[c] / MAX_COLUMNS).sqrt());
    let count = |len: f64| ((len / side).ceil() as usize).max(1);
    let (nb, nc) = (count(size[b]), count(size[c]));
    // each column's span along the profile axis, m
    let mut span = vec![(f64::INFINITY, f64::NEG_INFINITY); nb * nc];
    let index = |x: f64, l: f64, m: usize| (((x - l) / side).floor().max(0.0) as usize).min(m - 1);
    for body in &frame.bodies {
        let p = body.position;
        let r = 0.5 * body.equivalent_diameter();
        let s = &mut span[index(p[b], lo[b], nb) * nc + index(p[c], lo[c], nc)];
        s.0 = s.0.min(p[a] - r);
        s.1 = s.1.max(p[a] + r);
    }
    // a column's share of the cross-section along one lateral axis (the
    // last column may be cut by the domain's side)
    let width = |i: usize, len: f64| side.min(len - i as f64 * side).max(0.0) / len;
    for (k, &(bot, top)) in span.iter().enumerate() {
        if bot > top {
            continue;
        }
        let share = width(k / nc, size[b]) * width(k % nc, size[c]);
        for (cell, o) in out.iter_mut().enumerate() {
            *o += share * cell_average(grid, cell, bot, top);
        }
    }
    out
}

/// The cell average of the kernel-smoothed indicator of `[bot, top]`
/// over cell `cell` (three-point Gauss–Legendre, as the fields' deposits
/// are cell averages too).
fn cell_average(grid: &Grid, cell: usize, bot: f64, top: f64) -> f64 {
    const NODES: [(f64, f64); 3] = [
        (-0.774_596_669_241_483_4, 5.0 / 18.0),
        (0.0, 8.0 / 18.0),
        (0.774_596_669_241_483_4, 5.0 / 18.0),
    ];
    let (z0, h) = (grid.centre(0, cell), grid.spacing(0));
    NODES
        .iter()
        .map(|&(t, w)| {
            let z = z0 + 0.5 * h * t;
            w * (grid.kernel.cdf(top - z, grid.width) - grid.kernel.cdf(bot - z, grid.width))
        })
        .sum()
}

/// The time average of [`occupied_fraction`] over the frames added.
#[derive(Debug, Clone, Default)]
pub struct Occupancy {
    sum: Vec<f64>,
    frames: usize,
}

impl Occupancy {
    /// Adds one frame.
    pub fn add(&mut self, frame: &Frame, grid: &Grid) {
        let f = occupied_fraction(frame, grid);
        if self.sum.is_empty() {
            self.sum = vec![0.0; f.len()];
        }
        for (s, x) in self.sum.iter_mut().zip(f) {
            *s += x;
        }
        self.frames += 1;
    }

    /// The mean occupied fraction per cell (empty before any frame).
    pub fn mean(&self) -> Vec<f64> {
        let n = self.frames.max(1) as f64;
        self.sum.iter().map(|s| s / n).collect()
    }
}

/// The density in the bed per cell, kg/m³: the profile's (cross-section
/// averaged) `density` over the mean occupied `fraction`; `None` where
/// the bed occupies less than 2 % of its largest share (above and below
/// the bed, where the ratio is noise).
pub fn density_in_bed(density: &[f64], fraction: &[f64]) -> Vec<Option<f64>> {
    let top = fraction.iter().copied().fold(0.0, f64::max);
    density
        .iter()
        .zip(fraction)
        .map(|(&rho, &f)| (top > 0.0 && f >= 0.02 * top).then(|| rho / f))
        .collect()
}
