//! Contact mobility of a template's surface: how much lighter than the whole
//! body a clump responds at a point of its surface (docs/theory.md T-51).
//!
//! A force `f n` applied at the point `r` (relative to the centre of mass)
//! of a free rigid body of mass `m` and inertia `I` accelerates that point
//! along `n` by `f (1/m + (r×n)ᵀ I⁻¹ (r×n))`. The body therefore acts at that
//! contact like a point mass `m_eff = m/κ` with the **mobility factor**
//! `κ(r, n) = 1 + m (r×n)ᵀ I⁻¹ (r×n) ≥ 1` (1 for a contact whose normal
//! passes through the centre of mass, e.g. any contact of a single sphere).
//! A clump that turns about a sphere far from its centre of mass has `κ`
//! well above 1, so a dashpot scaled with the body's mass damps that contact
//! much more strongly than its damping ratio says.

use super::sphere_grid::SphereGrid;
use super::template::ClumpTemplate;
use glam::DVec3;

/// Outward normals sampled on every sphere (a Fibonacci lattice).
pub const MOBILITY_DIRECTIONS: usize = 192;

/// Above this many spheres the sampled points are not checked for being
/// buried inside other spheres (the all-near-pairs test would dominate
/// `clump check`); `κ` is then an upper bound over the spheres' whole
/// surfaces rather than the union's.
pub const MOBILITY_EXPOSURE_LIMIT: usize = 20_000;

/// `κ = 1 + m Σ_k (r×n)_k²/I_k` (dimensionless) for the contact point `r`
/// (m) and unit normal `n`, both in the principal body frame, of a body of
/// mass `m` (kg) with principal moments `inertia` (kg m²).
pub fn mobility_factor(mass: f64, inertia: DVec3, r: DVec3, n: DVec3) -> f64 {
    let a = r.cross(n);
    1.0 + mass * (a * a / inertia).element_sum()
}

/// The `k`-th of `count` unit vectors spread evenly over the sphere.
fn fibonacci_direction(k: usize, count: usize) -> DVec3 {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let z = 1.0 - (2.0 * k as f64 + 1.0) / count as f64;
    let rho = (1.0 - z * z).max(0.0).sqrt();
    let phi = golden * k as f64;
    DVec3::new(rho * phi.cos(), rho * phi.sin(), z)
}

/// For every sphere of `t`, the largest mobility factor `κ` over the sampled
/// points of its surface that lie on the surface of the union (a contact
/// can only touch those); 0 for a sphere with no such point (buried inside
/// others). The normal at a surface point is the sphere's outward normal.
pub fn sphere_mobility(t: &ClumpTemplate) -> Vec<f64> {
    let spheres = &t.spheres;
    let check_buried = spheres.len() <= MOBILITY_EXPOSURE_LIMIT;
    let grid = check_buried.then(|| SphereGrid::new(spheres));
    let dirs: Vec<DVec3> = (0..MOBILITY_DIRECTIONS)
        .map(|k| fibonacci_direction(k, MOBILITY_DIRECTIONS))
        .collect();
    let mut near = Vec::new();
    spheres
        .iter()
        .enumerate()
        .map(|(i, s)| {
            near.clear();
            if let Some(g) = &grid {
                g.for_each_near(spheres, i, |j| near.push(j));
            }
            let mut worst: f64 = 0.0;
            for &n in &dirs {
                let p = s.center + s.radius * n;
                let buried = near.iter().any(|&j| {
                    let o = &spheres[j];
                    (p - o.center).length() < o.radius * (1.0 - 1e-9)
                });
                if !buried {
                    worst = worst.max(mobility_factor(t.mass, t.principal_inertia, p, n));
                }
            }
            worst
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Sphere;

    /// A single sphere: every contact normal passes through the centre, κ = 1.
    #[test]
    fn sphere_has_unit_mobility() {
        let t =
            ClumpTemplate::from_spheres("s", &[Sphere::new(DVec3::ZERO, 0.01)], 1000.0).unwrap();
        let k = sphere_mobility(&t);
        assert!((k[0] - 1.0).abs() < 1e-12, "{k:?}");
    }

    /// Two equal spheres touching at a point (a dimer of radius R, centres at
    /// ±R): mass 2m₀, I_⊥ = 2(2/5 m₀R² + m₀R²) = 2.8 m₀R². At the end cap
    /// (r = 2R x̂) κ = 1 exactly; the largest κ is where |r×n|²/I is largest:
    /// r = (±R + R nₓ, R n_y, R n_z), |r×n| = R|x̂×n| = R sinθ (the sphere's
    /// own centre offset is along x), so κ_max = 1 + 2m₀R²/(2.8m₀R²) = 1 + 1/1.4
    /// at sinθ = 1 (a point on the sphere's equator, not buried).
    #[test]
    fn dimer_mobility_closed_form() {
        let r = 0.01;
        let t = ClumpTemplate::from_spheres(
            "d",
            &[
                Sphere::new(DVec3::new(-r, 0.0, 0.0), r),
                Sphere::new(DVec3::new(r, 0.0, 0.0), r),
            ],
            1000.0,
        )
        .unwrap();
        let k = sphere_mobility(&t);
        let exact = 1.0 + 1.0 / 1.4;
        for ki in k {
            // sampled directions: the equator is approached within ~1/√N
            assert!(
                ki <= exact * (1.0 + 1e-12) && ki > exact * 0.99,
                "{ki} vs {exact}"
            );
        }
    }
}
