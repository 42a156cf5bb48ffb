//! Slabs: a template of many spheres is cut by planes x = const into slabs
//! about four largest radii wide, and each slab is integrated on its own
//! (its cross-sections clipped to the slab, see
//! [`DiscUnion::moments_in_strip`](super::disc_union::DiscUnion::moments_in_strip)).
//!
//! A slice of the whole union visits every sphere it crosses, and the union
//! has a number of slice intervals that grows with the sphere count, so the
//! cost grows about as n^{5/3}–n². A slab holds the few spheres near it:
//! its slices are short and its intervals few, and the total grows about
//! linearly. The cut planes add breakpoints of their own: the top and bottom
//! of each sphere's circle in the plane, and the points where two such
//! circles cross (there the clipped cross-section changes topology).
//!
//! Templates of fewer than [`MIN_SPHERES`] spheres are integrated whole, as
//! one slab without cuts, so their results do not change.

use super::template_sphere::Sphere;

/// Fewest spheres for which a template is cut into slabs.
pub(crate) const MIN_SPHERES: usize = 256;
/// Slab width in largest radii.
const WIDTH_IN_RADII: f64 = 4.0;
/// Most slabs.
const MAX_SLABS: usize = 4096;

/// One slab: `x_lo ≤ x ≤ x_hi` (infinite at the ends).
pub(crate) struct Slab {
    pub x_lo: f64,
    pub x_hi: f64,
    /// The spheres that reach into the slab, in the caller's order.
    pub spheres: Vec<Sphere>,
    /// The same spheres sorted by centre height.
    pub by_height: Vec<Sphere>,
    /// Largest radius among them.
    pub rmax: f64,
}

impl Slab {
    fn new(x_lo: f64, x_hi: f64, spheres: Vec<Sphere>) -> Self {
        let mut by_height = spheres.clone();
        by_height.sort_by(|p, q| p.center.z.total_cmp(&q.center.z));
        let rmax = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
        Slab {
            x_lo,
            x_hi,
            spheres,
            by_height,
            rmax,
        }
    }
}

/// The slabs of a union of `spheres` (one, uncut, for small templates).
pub(crate) fn slabs(spheres: &[Sphere]) -> Vec<Slab> {
    let rmax = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
    let lo = spheres
        .iter()
        .map(|s| s.center.x - s.radius)
        .fold(f64::INFINITY, f64::min);
    let hi = spheres
        .iter()
        .map(|s| s.center.x + s.radius)
        .fold(f64::NEG_INFINITY, f64::max);
    let count = ((hi - lo) / (WIDTH_IN_RADII * rmax)).floor();
    if spheres.len() < MIN_SPHERES || !(count >= 2.0) {
        return vec![Slab::new(
            f64::NEG_INFINITY,
            f64::INFINITY,
            spheres.to_vec(),
        )];
    }
    let count = (count as usize).min(MAX_SLABS);
    let width = (hi - lo) / count as f64;
    (0..count)
        .map(|k| {
            let x_lo = if k == 0 {
                f64::NEG_INFINITY
            } else {
                lo + k as f64 * width
            };
            let x_hi = if k + 1 == count {
                f64::INFINITY
            } else {
                lo + (k + 1) as f64 * width
            };
            let inside = spheres
                .iter()
                .filter(|s| s.center.x - s.radius < x_hi && s.center.x + s.radius > x_lo)
                .copied()
                .collect();
            Slab::new(x_lo, x_hi, inside)
        })
        .collect()
}

/// Heights where the cross-section of the union clipped at the plane x = `x`
/// changes topology on the cut line: the top and bottom of every sphere's
/// circle in the plane, and the crossings of two such circles. Appended to
/// `z`. Nothing for an infinite `x`.
pub(crate) fn cut_events(spheres: &[Sphere], x: f64, z: &mut Vec<f64>) {
    if !x.is_finite() {
        return;
    }
    // circles in the plane: (y, z, ρ), sorted by y for the sweep below
    let mut circles: Vec<(f64, f64, f64)> = spheres
        .iter()
        .filter_map(|s| {
            let d = x - s.center.x;
            (d.abs() < s.radius).then(|| {
                let rho = ((s.radius - d) * (s.radius + d)).sqrt();
                (s.center.y, s.center.z, rho)
            })
        })
        .collect();
    circles.sort_by(|p, q| p.0.total_cmp(&q.0));
    let rho_max = circles.iter().map(|c| c.2).fold(0.0, f64::max);
    for (i, &(yi, zi, ri)) in circles.iter().enumerate() {
        z.push(zi - ri);
        z.push(zi + ri);
        for &(yj, zj, rj) in &circles[i + 1..] {
            if yj - yi >= ri + rho_max {
                break;
            }
            let (dy, dz) = (yj - yi, zj - zi);
            let d2 = dy * dy + dz * dz;
            let sum = ri + rj;
            if d2 >= sum * sum || d2 <= (ri - rj) * (ri - rj) || d2 == 0.0 {
                continue; // apart, or one inside the other: no crossing
            }
            let a = (d2 + ri * ri - rj * rj) / (2.0 * d2);
            let h = (ri * ri / d2 - a * a).max(0.0).sqrt();
            // crossings at (yi, zi) + a (dy, dz) ± h (−dz, dy)
            z.push(zi + a * dz + h * dy);
            z.push(zi + a * dz - h * dy);
        }
    }
}
