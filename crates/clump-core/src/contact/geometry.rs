//! Contact geometry, one definition for sphere–sphere and sphere–wall
//! contacts (docs/theory.md T-22, T-23): the unit normal towards sphere
//! `i`, the overlap, and the contact point in the middle of the overlap.

use glam::DVec3;

/// The geometry of two spheres whose centres are `d = x_i − x_j` apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpherePair {
    /// Unit normal from `j` to `i`, world frame.
    pub normal: DVec3,
    /// Overlap `δ = r_i + r_j − |d|`, m (negative when apart).
    pub overlap: f64,
    /// Distance from `i`'s centre to the contact point, `r_i − δ/2`, m.
    pub arm_i: f64,
    /// Distance from `j`'s centre to the contact point, `r_j − δ/2`, m.
    pub arm_j: f64,
}

/// Normal, overlap and contact-point distances of spheres of radii `ri`,
/// `rj` at separation `d = x_i − x_j` (m, world frame).
#[inline(always)]
pub fn sphere_pair(d: DVec3, ri: f64, rj: f64) -> SpherePair {
    let dist = d.length();
    let normal = d * (1.0 / dist);
    let overlap = (ri + rj) - dist;
    SpherePair {
        normal,
        overlap,
        arm_i: ri - 0.5 * overlap,
        arm_j: rj - 0.5 * overlap,
    }
}

/// The contact point of a sphere (centre `x`, radius `r`) touching along
/// the unit normal `n` (pointing into the sphere) with overlap `δ`:
/// `x − (r − δ/2) n`, m, world frame. For a sphere pair this is the same
/// point from either side.
#[inline(always)]
pub fn contact_point(x: DVec3, n: DVec3, r: f64, overlap: f64) -> DVec3 {
    x - n * (r - 0.5 * overlap)
}
