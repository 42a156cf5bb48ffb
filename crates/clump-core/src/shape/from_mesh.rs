//! Clump templates generated from a closed triangle mesh, and their fidelity.
//!
//! # Method: Euclidean-map sphere placement (CLUMP)
//! Angelidakis, Nadimi & Utili (2021), "CLUMP: A Code Library to generate
//! Universal Multi-sphere Particles", *SoftwareX* 15, 100735 — the
//! `GenerateClump_Euclidean_3D` method:
//! 1. voxelise the interior of the mesh (cubic voxels; `resolution` voxels
//!    along the shortest edge of the bounding box, CLUMP's `div`);
//! 2. compute the Euclidean distance map `D` of the interior;
//! 3. repeat: the voxel of largest `D` is the centre of the next sphere and
//!    `D` there is its radius (the largest sphere inscribed in what is left);
//!    the voxels within `(1 − overlap) r` of its centre are removed from the
//!    particle and `D` is updated (so the next sphere may overlap this one by
//!    at most `overlap · r`); ties go to the voxel farthest from the
//!    centroid, then to the lowest index;
//! 4. until `N` spheres, or the radius falls below `min_radius`, or (with a
//!    `tolerance`) the spheres cover all but that fraction of the interior
//!    voxels.
//!
//! Difference from CLUMP: `D` is the exact distance from each voxel centre
//! to the mesh surface (closest-point queries on the mesh's BVH) rather than
//! the distance between voxel centres (`bwdist`) — no voxel rounding of the
//! radii — and the removed region enters `D` analytically as
//! `|x − c| − (1 − overlap) r`.
//!
//! # Radius refinement (our addition; `refine_iterations = 0` turns it off)
//! All CLUMP spheres are inscribed, so a few dozen of them miss the thin
//! parts of a particle: a 3:2:1 ellipsoid keeps only ~80 % of its volume
//! with 50 spheres. The radii are therefore refined by least squares against
//! points sampled uniformly on the mesh surface: each sample is assigned to
//! the sphere that realises the clump's signed distance there (`argmin_i
//! |p − c_i| − r_i`), and each sphere's radius becomes the mean distance from
//! its centre to its samples (the least-squares radius for fixed centres);
//! repeated until the radii change by less than 1e-6 relative or
//! `refine_iterations` passes. Spheres that own no sample (inner ones) keep
//! their radius. The clump surface then passes through the mesh surface on
//! average instead of lying inside it: for the ellipsoid the volume error
//! drops from −20 % to below 1 % and the mean surface deviation halves.
//!
//! # Fidelity
//! [`fidelity`] compares the union of the spheres (exact mass properties of
//! [`super::mass_properties()`]) with the polyhedron's exact mass properties
//! ([`polyhedron_properties`]: signed tetrahedra, i.e. the divergence
//! theorem): relative volume error, relative errors of the principal moments,
//! angles between corresponding principal axes, and the mean and maximum
//! distance from points sampled uniformly on the mesh surface to the surface
//! of the clump.

use glam::{DMat3, DVec3};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use thiserror::Error;

use super::eigen::principal_frame;
use super::error::ShapeError;
use super::mass_properties::{mass_properties, MassProperties};
use super::template_sphere::Sphere;
use crate::wall::mesh::{MeshError, TriMesh};

/// Options of [`generate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FromMeshOptions {
    /// Largest number of spheres (CLUMP's `N`), ≥ 1.
    pub max_spheres: usize,
    /// Stop placing spheres once they cover all but this fraction of the
    /// interior voxels (the volume deficit of the inscribed spheres, before
    /// the refinement, which usually reduces the error well below it), if given.
    pub tolerance: Option<f64>,
    /// Voxels along the shortest edge of the bounding box (CLUMP's `div`), ≥ 5.
    pub resolution: usize,
    /// Overlap fraction in `[0, 1)` (CLUMP's `overlap`): a new sphere may
    /// penetrate an earlier one of radius `r` by at most `overlap · r`.
    pub overlap: f64,
    /// Stop when the next sphere would be smaller than this radius (m, mesh units).
    pub min_radius: f64,
    /// Passes of the least-squares radius refinement (0: pure CLUMP
    /// placement, all spheres inscribed).
    pub refine_iterations: usize,
}

impl Default for FromMeshOptions {
    /// 50 spheres, no tolerance, resolution 50, overlap 0.6 (CLUMP's
    /// example), no minimum radius, up to 20 refinement passes.
    fn default() -> Self {
        FromMeshOptions {
            max_spheres: 50,
            tolerance: None,
            resolution: 50,
            overlap: 0.6,
            min_radius: 0.0,
            refine_iterations: 20,
        }
    }
}

/// Why a template could not be generated from a mesh.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FromMeshError {
    /// The mesh is not a closed, orientable 2-manifold (or not a mesh).
    #[error("{0}")]
    Mesh(#[from] MeshError),
    /// An option is out of range.
    #[error("invalid option: {0}")]
    Option(String),
    /// The mesh encloses no volume at this resolution.
    #[error("the mesh encloses no voxel at resolution {0}; increase the resolution")]
    NoInterior(usize),
    /// The spheres' mass properties failed.
    #[error("clump mass properties: {0}")]
    Shape(#[from] ShapeError),
}

/// Exact mass properties of a closed polyhedron at unit density, mesh frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolyhedronProperties {
    /// Enclosed volume, m³.
    pub volume: f64,
    /// Centroid, m.
    pub center_of_mass: DVec3,
    /// Inertia tensor about the centroid per unit density, m⁵ (kg m² per kg/m³).
    pub inertia: DMat3,
    /// Principal moments, ascending, m⁵.
    pub principal_moments: DVec3,
    /// Principal axes: row `i` belongs to `principal_moments[i]` (unit, right-handed).
    pub principal_axes: [DVec3; 3],
}

/// Mass properties of the solid bounded by a closed mesh (unit density), by
/// summing signed tetrahedra from a reference point (the divergence theorem):
/// for a triangle `(a, b, c)` relative to the reference, `det = a·(b×c)`,
/// volume `det/6`, first moment `det/24 (a+b+c)`, second moment
/// `∫xxᵀ = det/120 (s sᵀ + a aᵀ + b bᵀ + c cᵀ)` with `s = a+b+c`. The mesh is
/// first oriented outward ([`TriMesh::oriented_outward`]), so the winding of
/// the file does not matter; errors if it is open or non-manifold.
pub fn polyhedron_properties(mesh: &TriMesh) -> Result<PolyhedronProperties, MeshError> {
    let m = mesh.oriented_outward()?;
    let (lo, hi) = m.bounds();
    let o = 0.5 * (lo + hi);
    let mut vol = 0.0;
    let mut first = DVec3::ZERO;
    let mut second = DMat3::ZERO;
    for t in 0..m.triangles().len() {
        let [a, b, c] = m.corners(t as u32).map(|v| v - o);
        let det = a.dot(b.cross(c));
        vol += det / 6.0;
        let s = a + b + c;
        first += s * (det / 24.0);
        let outer = |u: DVec3| DMat3::from_cols(u * u.x, u * u.y, u * u.z);
        second += (outer(s) + outer(a) + outer(b) + outer(c)) * (det / 120.0);
    }
    let com_rel = first / vol;
    let cov = second
        - DMat3::from_cols(
            com_rel * com_rel.x,
            com_rel * com_rel.y,
            com_rel * com_rel.z,
        ) * vol;
    let tr = cov.x_axis.x + cov.y_axis.y + cov.z_axis.z;
    let inertia = DMat3::from_diagonal(DVec3::splat(tr)) - cov;
    let inertia = (inertia + inertia.transpose()) * 0.5;
    let (moments, axes) = principal_frame(&inertia);
    Ok(PolyhedronProperties {
        volume: vol,
        center_of_mass: o + com_rel,
        inertia,
        principal_moments: moments,
        principal_axes: axes,
    })
}

/// How well a set of spheres represents a closed mesh (see the [module docs](self)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fidelity {
    /// The polyhedron's exact properties (unit density).
    pub mesh: PolyhedronProperties,
    /// The clump's exact union properties (unit density), mesh frame.
    pub clump: MassProperties,
    /// `(V_clump − V_mesh)/V_mesh`.
    pub volume_error: f64,
    /// Distance between the centroids divided by `V_mesh^(1/3)`.
    pub centroid_error: f64,
    /// `(I_clump − I_mesh)/I_mesh` for each principal moment (ascending).
    pub moment_errors: DVec3,
    /// Angle between corresponding principal axes, degrees (0..90; axes of
    /// nearly equal moments are ill-defined and may differ a lot).
    pub axis_errors_deg: DVec3,
    /// Mean over surface samples of the distance to the clump surface, m.
    pub mean_surface_deviation: f64,
    /// Largest such distance, m.
    pub max_surface_deviation: f64,
    /// Number of surface samples.
    pub samples: usize,
}

/// Points distributed uniformly by area over the mesh surface (deterministic
/// for a given `seed`), mesh frame.
pub fn surface_samples(mesh: &TriMesh, n: usize, seed: u64) -> Vec<DVec3> {
    let nt = mesh.triangles().len();
    let mut cum = Vec::with_capacity(nt);
    let mut total = 0.0;
    for t in 0..nt {
        let [a, b, c] = mesh.corners(t as u32);
        total += 0.5 * (b - a).cross(c - a).length();
        cum.push(total);
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let u: f64 = rng.gen::<f64>() * total;
            let t = cum.partition_point(|&x| x < u).min(nt - 1);
            let [a, b, c] = mesh.corners(t as u32);
            let (mut r1, mut r2): (f64, f64) = (rng.gen(), rng.gen());
            if r1 + r2 > 1.0 {
                r1 = 1.0 - r1;
                r2 = 1.0 - r2;
            }
            a + (b - a) * r1 + (c - a) * r2
        })
        .collect()
}

/// Fidelity of `spheres` (mesh frame) against the closed `mesh`, with
/// `samples` surface points.
pub fn fidelity(
    mesh: &TriMesh,
    spheres: &[Sphere],
    samples: usize,
) -> Result<Fidelity, FromMeshError> {
    let poly = polyhedron_properties(mesh)?;
    let clump = mass_properties(spheres, 1.0)?;
    let volume_error = (clump.volume - poly.volume) / poly.volume;
    let centroid_error = (clump.center_of_mass - poly.center_of_mass).length() / poly.volume.cbrt();
    let moment_errors = (clump.principal_moments - poly.principal_moments) / poly.principal_moments;
    let mut axis_errors_deg = DVec3::ZERO;
    for k in 0..3 {
        let c = clump
            .principal_axis(k)
            .dot(poly.principal_axes[k])
            .abs()
            .min(1.0);
        axis_errors_deg[k] = c.acos().to_degrees();
    }
    let pts = surface_samples(mesh, samples, 0x5eed);
    let dev: Vec<f64> = pts
        .par_iter()
        .map(|&p| {
            spheres
                .iter()
                .map(|s| (p - s.center).length() - s.radius)
                .fold(f64::INFINITY, f64::min)
                .abs()
        })
        .collect();
    let mean = dev.iter().sum::<f64>() / dev.len().max(1) as f64;
    let max = dev.iter().cloned().fold(0.0, f64::max);
    Ok(Fidelity {
        mesh: poly,
        clump,
        volume_error,
        centroid_error,
        moment_errors,
        axis_errors_deg,
        mean_surface_deviation: mean,
        max_surface_deviation: max,
        samples: pts.len(),
    })
}

/// Spheres (mesh frame) approximating the closed `mesh` by the CLUMP
/// Euclidean-map method (see the [module docs](self)). Errors if the mesh is
/// open or non-manifold (naming the first bad edge), or on bad options.
pub fn generate(mesh: &TriMesh, opt: &FromMeshOptions) -> Result<Vec<Sphere>, FromMeshError> {
    if opt.max_spheres == 0 {
        return Err(FromMeshError::Option(
            "the number of spheres must be at least 1".into(),
        ));
    }
    if opt.resolution < 5 || opt.resolution > 2000 {
        return Err(FromMeshError::Option(format!(
            "resolution must lie in 5..=2000 voxels, found {}",
            opt.resolution
        )));
    }
    if !(0.0..1.0).contains(&opt.overlap) {
        return Err(FromMeshError::Option(format!(
            "overlap must lie in [0, 1), found {}",
            opt.overlap
        )));
    }
    if let Some(t) = opt.tolerance {
        if !(t > 0.0 && t < 1.0) {
            return Err(FromMeshError::Option(format!(
                "tolerance must lie in (0, 1), found {t}"
            )));
        }
    }
    if !(opt.min_radius >= 0.0 && opt.min_radius.is_finite()) {
        return Err(FromMeshError::Option(format!(
            "minimum radius must be finite and >= 0, found {}",
            opt.min_radius
        )));
    }
    mesh.check_closed()?;
    let poly = polyhedron_properties(mesh)?;
    let (lo, hi) = mesh.bounds();
    let ext = hi - lo;
    let h = ext.min_element() / opt.resolution as f64;
    if !(h > 0.0) {
        return Err(FromMeshError::NoInterior(opt.resolution));
    }
    let dims = [
        (ext.x / h).ceil() as usize,
        (ext.y / h).ceil() as usize,
        (ext.z / h).ceil() as usize,
    ];
    let (nx, ny, nz) = (dims[0].max(1), dims[1].max(1), dims[2].max(1));
    // centre the voxel grid on the bounding box
    let origin = 0.5 * (lo + hi) - 0.5 * h * DVec3::new(nx as f64, ny as f64, nz as f64);
    let center = |i: usize, j: usize, k: usize| {
        origin + h * DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5)
    };
    // interior voxels, row by row (parity of the crossings along x)
    let rows: Vec<Vec<DVec3>> = (0..ny * nz)
        .into_par_iter()
        .map(|row| {
            let (j, k) = (row % ny, row / ny);
            let c0 = center(0, j, k);
            let mut xs = Vec::new();
            mesh.line_crossings(c0.y, c0.z, &mut xs);
            let mut out = Vec::new();
            for i in 0..nx {
                let x = c0.x + i as f64 * h;
                if xs.iter().filter(|&&cx| cx > x).count() % 2 == 1 {
                    out.push(center(i, j, k));
                }
            }
            out
        })
        .collect();
    let pts: Vec<DVec3> = rows.into_iter().flatten().collect();
    if pts.is_empty() {
        return Err(FromMeshError::NoInterior(opt.resolution));
    }
    // exact distance from each interior voxel centre to the surface
    let mut dist: Vec<f64> = pts.par_iter().map(|&p| mesh.closest_point(p).2).collect();
    let from_centroid: Vec<f64> = pts
        .iter()
        .map(|&p| (p - poly.center_of_mass).length_squared())
        .collect();
    let mut covered = vec![false; pts.len()];
    let mut n_covered = 0usize;
    let mut spheres = Vec::new();
    let keep = 1.0 - opt.overlap;
    while spheres.len() < opt.max_spheres {
        let mut best = usize::MAX;
        for (i, &d) in dist.iter().enumerate() {
            if best == usize::MAX
                || d > dist[best]
                || (d == dist[best] && from_centroid[i] > from_centroid[best])
            {
                best = i;
            }
        }
        let r = dist[best];
        if !(r > 0.0) || r < opt.min_radius {
            break;
        }
        let c = pts[best];
        spheres.push(Sphere::new(c, r));
        let (r_keep, r2) = (keep * r, r * r);
        for (i, p) in pts.iter().enumerate() {
            let l2 = (*p - c).length_squared();
            if !covered[i] && l2 <= r2 {
                covered[i] = true;
                n_covered += 1;
            }
            let d = l2.sqrt() - r_keep;
            if d < dist[i] {
                dist[i] = d;
            }
        }
        if let Some(tol) = opt.tolerance {
            if 1.0 - n_covered as f64 / pts.len() as f64 <= tol {
                break;
            }
        }
    }
    if opt.refine_iterations > 0 && !spheres.is_empty() {
        let samples = surface_samples(mesh, 20_000.max(200 * spheres.len()), 0x0ddba11);
        refine_radii(&mut spheres, &samples, opt.refine_iterations);
    }
    Ok(spheres)
}

/// Least-squares radius refinement against surface `samples` (see the
/// [module docs](self)); at most `iterations` passes.
pub fn refine_radii(spheres: &mut [Sphere], samples: &[DVec3], iterations: usize) {
    let n = spheres.len();
    for _ in 0..iterations {
        let owner: Vec<(usize, f64)> = samples
            .par_iter()
            .map(|&p| {
                let mut best = (0usize, f64::INFINITY, 0.0);
                for (i, s) in spheres.iter().enumerate() {
                    let l = (p - s.center).length();
                    if l - s.radius < best.1 {
                        best = (i, l - s.radius, l);
                    }
                }
                (best.0, best.2)
            })
            .collect();
        let mut sum = vec![0.0; n];
        let mut cnt = vec![0usize; n];
        for &(i, l) in &owner {
            sum[i] += l;
            cnt[i] += 1;
        }
        let mut change: f64 = 0.0;
        for (i, s) in spheres.iter_mut().enumerate() {
            if cnt[i] > 0 {
                let r = sum[i] / cnt[i] as f64;
                change = change.max((r - s.radius).abs() / s.radius);
                s.radius = r;
            }
        }
        if change < 1e-6 {
            break;
        }
    }
}
