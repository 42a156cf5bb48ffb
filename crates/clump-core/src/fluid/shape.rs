//! The surface area of a union of spheres, for the sphericity (T-65).

use crate::shape::Sphere;

/// Points per sphere of the Fibonacci lattice: the exposed fraction of a
/// sphere is found to about 1/N.
const POINTS: usize = 8192;

/// Area of the boundary of the union of `spheres`, m²: per sphere its
/// area times the fraction of a Fibonacci lattice of points on it that
/// lies inside no other sphere. A sphere inside another, or a second copy
/// of one, counts once.
pub fn union_area(spheres: &[Sphere]) -> f64 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut area = 0.0;
    for (i, s) in spheres.iter().enumerate() {
        let mut exposed = 0usize;
        for k in 0..POINTS {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / POINTS as f64;
            let rho = (1.0 - z * z).sqrt();
            let a = golden * k as f64;
            let p = s.center + s.radius * glam::DVec3::new(rho * a.cos(), rho * a.sin(), z);
            let covered = spheres.iter().enumerate().any(|(j, o)| {
                let d2 = (p - o.center).length_squared();
                // an identical sphere earlier in the list owns the surface
                j != i && (d2 < o.radius * o.radius || (j < i && o == s))
            });
            if !covered {
                exposed += 1;
            }
        }
        area += 4.0 * std::f64::consts::PI * s.radius * s.radius * exposed as f64 / POINTS as f64;
    }
    area
}
