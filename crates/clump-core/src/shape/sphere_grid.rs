//! A uniform grid over a template's spheres, so that the pair searches of
//! the mass-property integration (containment, overlapping pairs) cost
//! O(n) for templates of 10⁴–10⁵ spheres instead of O(n²).
//!
//! Cells are cubes of edge 2·r_max (input units): two spheres that overlap,
//! or one inside the other, have centres closer than 2·r_max, so they lie in
//! the same or adjacent cells. The lookup is a binary search in a list
//! sorted by cell, so the candidates of a sphere come in a fixed order
//! (no hashing), and the callers get the same results as an all-pairs loop.

use super::template_sphere::Sphere;
use glam::DVec3;

/// Spheres bucketed by cell.
pub(crate) struct SphereGrid {
    /// Edge of a cell (input units; infinite when the radii are not usable).
    edge: f64,
    /// Lower corner of the bounding box of the centres.
    origin: DVec3,
    /// `(cell, sphere index)`, sorted.
    entries: Vec<([i64; 3], u32)>,
}

impl SphereGrid {
    pub(crate) fn new(spheres: &[Sphere]) -> Self {
        let rmax = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
        let edge = if rmax.is_finite() && rmax > 0.0 {
            2.0 * rmax
        } else {
            f64::INFINITY
        };
        let origin = spheres
            .iter()
            .map(|s| s.center)
            .fold(DVec3::splat(f64::INFINITY), DVec3::min);
        let mut grid = SphereGrid {
            edge,
            origin,
            entries: Vec::with_capacity(spheres.len()),
        };
        for (i, s) in spheres.iter().enumerate() {
            let cell = grid.cell(s.center);
            grid.entries.push((cell, i as u32));
        }
        grid.entries.sort_unstable();
        grid
    }

    fn cell(&self, x: DVec3) -> [i64; 3] {
        // `as` saturates (and maps NaN to 0), so no coordinate can panic here
        let k = ((x - self.origin) / self.edge).floor();
        [k.x as i64, k.y as i64, k.z as i64]
    }

    /// Calls `f(j)` for every sphere `j ≠ i` in the cell of `i` and the 26
    /// around it, in a fixed order (by cell, then index).
    pub(crate) fn for_each_near(&self, spheres: &[Sphere], i: usize, mut f: impl FnMut(usize)) {
        let c = self.cell(spheres[i].center);
        for dx in -1i64..=1 {
            for dy in -1i64..=1 {
                for dz in -1i64..=1 {
                    let key = [
                        c[0].saturating_add(dx),
                        c[1].saturating_add(dy),
                        c[2].saturating_add(dz),
                    ];
                    let start = self.entries.partition_point(|e| e.0 < key);
                    for &(k, j) in &self.entries[start..] {
                        if k != key {
                            break;
                        }
                        if j as usize != i {
                            f(j as usize);
                        }
                    }
                }
            }
        }
    }
}

/// Indices (ascending) of the spheres that contribute to the boundary of the
/// union: a sphere is left out when it lies entirely inside another sphere
/// (within a relative tolerance of a few ulps); of several coincident
/// identical spheres only the first is kept.
///
/// The spheres must be valid (see [`super::template_sphere::validate_spheres`]); frame-independent.
pub fn union_sphere_indices(spheres: &[Sphere]) -> Vec<usize> {
    let n = spheres.len();
    let grid = SphereGrid::new(spheres);
    let mut keep = Vec::with_capacity(n);
    for i in 0..n {
        let si = &spheres[i];
        let mut inside = false;
        // a sphere that contains sphere i has its centre within r_max of
        // i's, so it is among the grid neighbours
        grid.for_each_near(spheres, i, |j| {
            if inside {
                return;
            }
            let sj = &spheres[j];
            let d = (si.center - sj.center).length();
            let tol = 4.0 * f64::EPSILON * (sj.radius + sj.center.abs().max_element());
            // Is sphere i inside sphere j?
            if d + si.radius <= sj.radius + tol {
                // Mutual containment means (numerically) identical spheres:
                // keep the lower index only.
                let tol_i = 4.0 * f64::EPSILON * (si.radius + si.center.abs().max_element());
                let mutual = d + sj.radius <= si.radius + tol_i;
                if !mutual || j < i {
                    inside = true;
                }
            }
        });
        if !inside {
            keep.push(i);
        }
    }
    keep
}
