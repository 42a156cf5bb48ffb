//! Mass properties of the union of a template's spheres, and the naive
//! sums (docs/theory.md T-9) for comparison.

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use super::eigen::principal_frame;
use super::error::ShapeError;
use super::template_sphere::{validate_spheres, Sphere};
use super::union_integral::union_integrals;

/// Requested accuracy: results with a larger estimated relative error are
/// rejected with [`ShapeError::NotConverged`].
pub const MAX_RELATIVE_ERROR: f64 = 1e-6;

/// Mass properties of a clump template, all in the template's **input frame**
/// (the frame the spheres were given in), SI units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MassProperties {
    /// Volume of the union of the spheres (overlaps counted once), m³.
    pub volume: f64,
    /// Mass, kg (density × volume unless overridden).
    pub mass: f64,
    /// Centre of mass, m, input frame.
    pub center_of_mass: DVec3,
    /// Inertia tensor about the centre of mass, kg m², input frame (symmetric).
    pub inertia: DMat3,
    /// Principal moments of inertia, kg m², ascending.
    pub principal_moments: DVec3,
    /// Principal axes: **row** `i` is the unit axis of `principal_moments[i]`,
    /// in the input frame; the rows form a right-handed orthonormal set.
    /// Since glam's `DMat3` is column-major, read an axis with
    /// [`MassProperties::principal_axis`] (or `principal_axes.row(i)`), not
    /// with `principal_axes.col(i)`. As a matrix it maps input-frame vectors to
    /// principal-body-frame components: `v_body = principal_axes * v_input`.
    pub principal_axes: DMat3,
    /// Estimated bound on the relative error of the integration (volume and
    /// mass; centre of mass relative to the bounding radius; inertia relative
    /// to its trace), dimensionless. Typically ≤ 1e-10.
    pub relative_error_bound: f64,
    /// Naive volume: sum of the sphere volumes, ignoring overlaps (docs/theory.md
    /// T-9, the naive mass divided by the density), m³.
    pub naive_volume: f64,
    /// Principal moments (ascending) of the naive inertia tensor (docs/theory.md
    /// T-9: sphere inertias plus parallel-axis terms, ignoring overlaps,
    /// about the naive centre of mass), kg m².
    pub naive_principal_moments: DVec3,
}

impl MassProperties {
    /// Principal axis `i` (0, 1, 2; unit vector, input frame), the axis of
    /// `principal_moments[i]`. Panics if `i > 2`.
    pub fn principal_axis(&self, i: usize) -> DVec3 {
        self.principal_axes.row(i)
    }

    /// Replaces mass and inertia by explicit values (kg; kg m² about the
    /// centre of mass, input frame) and recomputes the principal frame from
    /// the given tensor. Volume, centre of mass and the naive values are kept.
    pub fn with_override(mut self, mass: f64, inertia: DMat3) -> Result<Self, ShapeError> {
        if !mass.is_finite() || mass <= 0.0 {
            return Err(ShapeError::InvalidMass { mass });
        }
        validate_inertia(&inertia)?;
        let sym = (inertia + inertia.transpose()) * 0.5;
        let (moments, axes) = principal_frame(&sym);
        self.mass = mass;
        self.inertia = sym;
        self.principal_moments = moments;
        self.principal_axes = rows_to_mat(axes);
        Ok(self)
    }
}

/// Matrix whose rows are the given vectors.
pub(crate) fn rows_to_mat(rows: [DVec3; 3]) -> DMat3 {
    DMat3::from_cols(rows[0], rows[1], rows[2]).transpose()
}

/// Checks an explicit inertia tensor (kg m²): finite, symmetric (1e-9
/// relative), positive definite, and satisfying the triangle inequality of
/// principal moments (I1 + I2 ≥ I3, 1e-9 relative).
pub fn validate_inertia(m: &DMat3) -> Result<(), ShapeError> {
    if !m.is_finite() {
        return Err(ShapeError::InvalidInertia {
            reason: "entries must be finite".into(),
        });
    }
    let scale = m.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let asym = (*m - m.transpose())
        .to_cols_array()
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    if asym > 1e-9 * scale {
        return Err(ShapeError::InvalidInertia {
            reason: format!("tensor must be symmetric (largest asymmetry {asym:e} kg m²)"),
        });
    }
    let (vals, _) = principal_frame(&((*m + m.transpose()) * 0.5));
    if vals.x <= 0.0 {
        return Err(ShapeError::InvalidInertia {
            reason: format!("principal moments must be > 0, found {vals:?} kg m²"),
        });
    }
    if vals.x + vals.y < vals.z * (1.0 - 1e-9) {
        return Err(ShapeError::InvalidInertia {
            reason: format!(
                "principal moments {vals:?} kg m² violate the triangle inequality I1 + I2 ≥ I3"
            ),
        });
    }
    Ok(())
}

/// Naive sums (docs/theory.md T-9), ignoring overlaps: returns
/// `(volume m³, centre of mass m, inertia tensor about that centre kg m²)`,
/// input frame. Every sphere counts in full, duplicates included.
pub fn naive_mass_properties(spheres: &[Sphere], density: f64) -> (f64, DVec3, DMat3) {
    let vol: f64 = spheres.iter().map(Sphere::volume).sum();
    let com = spheres.iter().map(|s| s.volume() * s.center).sum::<DVec3>() / vol;
    let mut inertia = DMat3::ZERO;
    for s in spheres {
        let m = density * s.volume();
        let d = s.center - com;
        let own = DMat3::from_diagonal(DVec3::splat(0.4 * m * s.radius * s.radius));
        let shift = DMat3::from_diagonal(DVec3::splat(d.length_squared()))
            - DMat3::from_cols(d * d.x, d * d.y, d * d.z);
        inertia += own + shift * m;
    }
    (vol, com, inertia)
}

/// Mass properties of the union of `spheres` (m, input frame) at uniform
/// `density` (kg/m³); overlaps, duplicates and contained spheres are counted
/// once. Exact up to an adaptive quadrature accurate to ~1e-10 relative
/// (reported in [`MassProperties::relative_error_bound`]); deterministic.
///
/// Errors: empty list, non-finite or non-positive radius, non-finite centre,
/// density not finite and > 0, results that overflow (coordinates beyond
/// about 1e150 m), or (pathological inputs) no convergence.
pub fn mass_properties(spheres: &[Sphere], density: f64) -> Result<MassProperties, ShapeError> {
    validate_spheres(spheres)?;
    if !density.is_finite() || density <= 0.0 {
        return Err(ShapeError::InvalidDensity { density });
    }
    let u = union_integrals(spheres);
    if u.relative_error_bound.is_nan() || u.relative_error_bound > MAX_RELATIVE_ERROR {
        return Err(ShapeError::NotConverged {
            relative_error_bound: u.relative_error_bound,
        });
    }
    let c = u.second_moment;
    let trace = c.x_axis.x + c.y_axis.y + c.z_axis.z;
    let inertia = (DMat3::from_diagonal(DVec3::splat(trace)) - c) * density;
    let (moments, axes) = principal_frame(&inertia);
    let bad = |what: String| ShapeError::NotFinite {
        what,
        extent: spheres
            .iter()
            .map(|s| s.center.length() + s.radius)
            .fold(0.0, f64::max),
    };
    if !(u.volume.is_finite() && u.volume > 0.0) {
        return Err(bad(format!("volume {:e} m³", u.volume)));
    }
    if !u.centroid.is_finite() {
        return Err(bad(format!("centre of mass {} m", u.centroid)));
    }
    if !(inertia.is_finite() && moments.is_finite() && moments.x > 0.0) {
        return Err(bad(format!("principal moments {moments} kg m²")));
    }
    let (naive_volume, _, naive_inertia) = naive_mass_properties(spheres, density);
    let (naive_moments, _) = principal_frame(&naive_inertia);
    Ok(MassProperties {
        volume: u.volume,
        mass: density * u.volume,
        center_of_mass: u.centroid,
        inertia,
        principal_moments: moments,
        principal_axes: rows_to_mat(axes),
        relative_error_bound: u.relative_error_bound,
        naive_volume,
        naive_principal_moments: naive_moments,
    })
}
